#pragma once
// Helpers shared by the tests: temporary model files and running the CLI as a user would.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "machdyn/analysis/simulate.hpp"

namespace machdyn::test {

/// A fresh empty folder under the system temp dir, removed at exit of the test process.
std::filesystem::path temp_dir();

/// Writes `text` to temp_dir()/name and returns the path.
std::string write_temp(const std::string& name, const std::string& text);

struct CliResult {
  int exit_code = -1;
  std::string out, err;
};

/// Runs the machdyn binary with `args` (shell words, already quoted as needed) in `cwd`.
CliResult run_cli(const std::string& args, const std::filesystem::path& cwd = temp_dir());

/// Path of a shipped example.
std::string example(const std::string& name);

/// The whole content of a file ("" if it cannot be read).
std::string slurp(const std::filesystem::path& p);

/// The lines of a text, without their line ends.
std::vector<std::string> lines_of(const std::string& text);

/// Whether the library finds gnuplot (the figure tests skip, saying so, without it).
bool have_gnuplot();

/// A body `crank` under `bodies:` (a crank-slider: r = 40 mm, l = 160 mm, rod 1.2 kg, piston 1.6 kg,
/// crank 0.08 kg·m²), for tests to append their own fields to.
extern const char* const kCrankSliderBody;

/// Index of the output column called `name`; records a test failure if there is none.
std::size_t column(const SimulationResult& r, const std::string& name);

/// The output column called `name`; records a test failure and gives an empty series if there is none.
const std::vector<double>& series(const SimulationResult& r, const std::string& name);

/// The value of column `name` in the output row at time t (within `tol` s); a test failure and NaN
/// if no row is there.
double at(const SimulationResult& r, const std::string& name, double t, double tol = 1e-9);

/// The largest |column `name` − f(t)| over all output rows (∞ without rows).
template <class F>
double max_error(const SimulationResult& r, const std::string& name, F f) {
  const auto& ts = series(r, "t_s");
  const auto& v = series(r, name);
  double e = 0.0;
  for (std::size_t i = 0; i < ts.size() && i < v.size(); ++i) e = std::max(e, std::abs(v[i] - f(ts[i])));
  return ts.empty() ? INFINITY : e;
}

/// The first t in (a, b] where f(t) > 0, given f(a) ≤ 0: a scan in steps of 1e-4 and a bisection to
/// 1e-15 of the bracket it finds (for reference solutions' switching instants); b if f stays ≤ 0.
double first_positive(const std::function<double(double)>& f, double a, double b);

/// x in a short scientific notation ("1.23e-09"), for the measured errors tests record.
std::string sci(double x);

/// The model compiled from YAML text as if read from a file called `file` (errors name it).
Model model_text(const std::string& yaml, const std::string& file = "test.yaml");

/// The compile errors of YAML text (InputError's message, each problem at file:line:col), or "" if
/// it compiles.
std::string compile_errors(const std::string& yaml, const std::string& file = "test.yaml");

/// Load l's law M at (t, q, v) of the body it acts on (Load::at on that body alone; a load on one body).
inline double load_at(const Load& l, double t, double q, double v) {
  std::vector<double> qs(static_cast<size_t>(l.body) + 1, 0.0), vs(qs);
  qs.back() = q, vs.back() = v;
  return l.ratio * l.at(t, qs.data(), vs.data());
}
/// ∂M/∂q and ∂M/∂v of load_at() (the Jacobian's entries ρ² ∂M of Load::slopes_at).
inline void load_slopes(const Load& l, double t, double q, double v, double* dMdq, double* dMdv) {
  std::vector<double> qs(static_cast<size_t>(l.body) + 1, 0.0), vs(qs);
  qs.back() = q, vs.back() = v;
  l.slopes_at(t, qs.data(), vs.data(), dMdq, dMdv);
  *dMdq *= l.ratio * l.ratio, *dMdv *= l.ratio * l.ratio;
}

/// The name suffix of a test parameterized over the integrators: "dopri5" or "bdf"
/// (INSTANTIATE_TEST_SUITE_P(..., ::testing::Values(...), test::IntegratorName{})).
struct IntegratorName {
  template <class Info>
  std::string operator()(const Info& p) const {
    return p.param == IntegratorChoice::bdf ? "bdf" : "dopri5";
  }
};

}  // namespace machdyn::test
