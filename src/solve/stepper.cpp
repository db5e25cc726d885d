#include "machdyn/solve/stepper.hpp"

#include "cvode_bdf.hpp"
#include "dopri5.hpp"

namespace machdyn {

std::unique_ptr<Stepper> make_stepper(Method method, OdeSystem& system, const StepperOptions& options) {
  if (method == Method::bdf) return std::make_unique<CvodeBdf>(system, options);
  return make_dopri5(system, options);
}

}  // namespace machdyn
