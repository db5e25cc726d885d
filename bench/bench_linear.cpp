// Linear analysis benchmark (issue 12): full undamped modal analysis of a 1000-mass chain, damped
// modes of 100- and 300-mass chains, and the frequency response of a 100-mass chain at 1000
// frequencies. Writes the matrices and results to DIR so bench/linear_scipy.py times scipy on the
// very same matrices and compares the answers.
//   bench_linear DIR [REPEATS]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>

#include <fmt/format.h>

#include "machdyn/analysis/frequency_response.hpp"
#include "machdyn/analysis/modal.hpp"
#include "machdyn/elements/linearize.hpp"
#include "machdyn/io/model_file.hpp"

using namespace machdyn;
namespace fs = std::filesystem;

namespace {

/// A free chain of n masses (1 + 0.5 sin i kg) on spring–dampers (1e6 (1 + 0.3 cos i) N/m, 50 N·s/m),
/// a force F on the first mass.
Model chain(int n, const fs::path& dir) {
  std::string s = fmt::format("name: chain {}\nbodies:\n", n);
  for (int i = 0; i < n; ++i) s += fmt::format("  b{}: {{type: translational, mass: {:.17g} kg}}\n", i, 1.0 + 0.5 * std::sin(i));
  s += "links:\n";
  for (int i = 0; i + 1 < n; ++i)
    s += fmt::format("  l{}: {{type: spring-damper, between: [b{}, b{}], stiffness: {:.17g} N/m, damping: 50 N*s/m}}\n", i, i,
                     i + 1, 1e6 * (1.0 + 0.3 * std::cos(i)));
  s += "loads:\n  F: {type: constant, body: b0, value: 1 N}\n";
  const fs::path p = dir / fmt::format("chain{}.yaml", n);
  std::ofstream(p) << s;
  return load_model(p.string());
}

template <class F>
double best_of(int repeats, F&& f) {
  double best = 1e300;
  for (int r = 0; r < repeats; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    f();
    best = std::min(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  return best;
}

void write_matrices(const LinearModel& lin, const fs::path& stem) {
  std::ofstream m(stem.string() + "_M.txt"), k(stem.string() + "_K.txt"), d(stem.string() + "_D.txt");
  m.precision(17), k.precision(17), d.precision(17);
  for (int i = 0; i < lin.n; ++i) m << lin.M(i) << '\n';
  const Eigen::MatrixXd K(lin.stiffness()), D(lin.damping());
  for (int i = 0; i < lin.n; ++i) {
    for (int j = 0; j < lin.n; ++j) k << (j ? " " : "") << K(i, j), d << (j ? " " : "") << D(i, j);
    k << '\n', d << '\n';
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::cerr << "usage: bench_linear DIR [REPEATS]\n";
    return 2;
  }
  const fs::path dir = argv[1];
  const int repeats = argc > 2 ? std::stoi(argv[2]) : 5;
  fs::create_directories(dir);

  // 1000-mass chain: undamped modes (all 999 frequencies and shapes).
  const Model big = chain(1000, dir);
  LinearModel lin_big;
  const double t_lin = best_of(repeats, [&] { lin_big = linearize(big, initial_topology(big)); });
  UndampedModes um;
  const double t_modes = best_of(repeats, [&] { um = undamped_modes(lin_big); });
  write_matrices(lin_big, dir / "chain1000");
  {
    std::ofstream f(dir / "chain1000_omega.txt");
    f.precision(17);
    for (double w : um.omega) f << w << '\n';
  }
  fmt::print("chain 1000: linearize {:.3f} ms, undamped modes (999 frequencies + shapes) {:.1f} ms\n", t_lin * 1e3,
             t_modes * 1e3);

  // Damped (state-space) modes.
  for (int n : {100, 300}) {
    const Model m = chain(n, dir);
    const LinearModel lin = linearize(m, initial_topology(m));
    DampedModes dm;
    const double t = best_of(std::max(1, repeats / (n > 100 ? 5 : 1)), [&] { dm = damped_modes(lin); });
    write_matrices(lin, dir / fmt::format("chain{}", n));
    std::ofstream f(dir / fmt::format("chain{}_damped.txt", n));
    f.precision(17);
    for (const auto& d : dm.modes) f << d.lambda.real() << ' ' << d.lambda.imag() << '\n';
    fmt::print("chain {}: damped modes ({}x{} state space) {:.1f} ms\n", n, 2 * n, 2 * n, t * 1e3);
  }

  // FRF of the 100-mass chain at 1000 frequencies: force on b0 → load of the last link.
  const Model small = chain(100, dir);
  const Topology topo = initial_topology(small);
  const LinearModel lin = linearize(small, topo);
  const Location at{"bench", 0, 0};
  const LinearSignal in = linear_input(small, "F", at);
  const std::vector<LinearSignal> out{linear_output(small, topo, "l98.load", at)};
  const Eigen::VectorXd w = frequency_grid(10.0, 5000.0, 1000, true);
  FrequencyResponse r;
  const double t_frf = best_of(repeats, [&] { r = frequency_response(lin, in, out, w); });
  {
    std::ofstream f(dir / "chain100_frf.txt");
    f.precision(17);
    for (Eigen::Index i = 0; i < w.size(); ++i) f << w(i) << ' ' << r.H(i, 0).real() << ' ' << r.H(i, 0).imag() << '\n';
    std::ofstream c(dir / "chain100_out.txt");
    c.precision(17);
    for (int i = 0; i < lin.n; ++i) c << out[0].q(i) << ' ' << out[0].v(i) << '\n';
  }
  fmt::print("chain 100: frequency response at 1000 frequencies {:.1f} ms\n", t_frf * 1e3);
  return 0;
}
