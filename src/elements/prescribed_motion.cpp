#include "machdyn/elements/prescribed_motion.hpp"

namespace machdyn {

PrescribedMotionLaw PrescribedMotionLaw::of(const Model& m, int i) {
  const Body& b = m.bodies[static_cast<size_t>(i)];
  PrescribedMotionLaw k{i, b.motion, &b.motion_signal, b.inertia};
  if (b.motion == MotionKind::speed) k.speed_scale = b.motion_signal.magnitude_bound(0.0, m.simulation.t_end);
  return k;
}

void PrescribedMotionLaw::add_linear(const std::string& name, LinearModel& lin) const {
  lin.G.push_back({{body, 1.0}});
  lin.constraint_names.push_back(name);
}

}  // namespace machdyn
