// Reading scale (issue 15 "Scale"): time to read (YAML → spec) and compile a free chain of N bodies
// and N − 1 spring-dampers, for N = 10^3, 10^4, 10^5; linear time shows as a constant µs per body.
// Then the memory of a 10^6-point load table (a 20 MB file): peak resident set after reading and
// compiling it. Usage: bench_read_scale [table] (`table` runs only the table, in a fresh process,
// so its peak RSS is its own).
#include <chrono>
#include <cstdio>
#include <cstring>
#include <string>
#include <sys/resource.h>
#include <fmt/format.h>

#include "machdyn/io/yaml_reader.hpp"
#include "machdyn/model/compile.hpp"

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

double peak_rss_mb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_maxrss) / 1024.0;
}

std::string chain(int n) {
  std::string t = "bodies:\n";
  for (int k = 0; k < n; ++k) t += fmt::format("  m{}: {{type: translational, mass: 1 kg}}\n", k);
  t += "links:\n";
  for (int k = 1; k < n; ++k)
    t += fmt::format("  c{}: {{type: spring-damper, between: [m{}, m{}], stiffness: 1 kN/m, damping: 1 N*s/m}}\n", k,
                     k - 1, k);
  return t + "simulation: {t_end: 1 s, dt_out: 0.1 s}\n";
}

}  // namespace

int main(int argc, char** argv) {
  using machdyn::compile_model;
  using machdyn::parse_yaml_string;
  if (argc > 1 && std::strcmp(argv[1], "table") == 0) {
    std::string t = "bodies:\n  I: {inertia: 1}\nloads:\n  M: {type: table, body: I, points: [";
    const int n = 1'000'000;
    for (int k = 0; k < n; ++k) t += fmt::format("{}[{:.6f}, {:.3f}]", k ? ", " : "", k * 1e-3, 100.0 + k % 7);
    t += "]}\nsimulation: {t_end: 1 s}\n";
    const double before = peak_rss_mb();
    const auto t0 = std::chrono::steady_clock::now();
    const auto m = compile_model(parse_yaml_string(t, "table.yaml"), "table.yaml");
    std::printf("table: %d points, %.1f MB of text: read+compile %.2f s, peak RSS %.0f MB (%.0f MB before reading; "
                "%zu values kept)\n", n, static_cast<double>(t.size()) / 1e6, seconds_since(t0), peak_rss_mb(), before,
                m.loads[0].signal.times().size());
    return 0;
  }
  std::printf("%10s %10s %12s %12s %14s\n", "bodies", "text MB", "read s", "compile s", "us per body");
  for (int n : {1'000, 10'000, 100'000}) {
    const std::string text = chain(n);
    auto t0 = std::chrono::steady_clock::now();
    const machdyn::SpecNode root = parse_yaml_string(text, "chain.yaml");
    const double read = seconds_since(t0);
    t0 = std::chrono::steady_clock::now();
    const auto m = compile_model(root, "chain.yaml");
    const double comp = seconds_since(t0);
    std::printf("%10d %10.1f %12.3f %12.3f %14.2f\n", m.dof(), static_cast<double>(text.size()) / 1e6, read, comp,
                (read + comp) / n * 1e6);
  }
  return 0;
}
