// Rainflow counting (analysis/rainflow.hpp) of a long load history on one core:
//   bench_rainflow [N] [SERIES_OUT]
// N turning points (default 10^7): x_k = ±(0.05 + u_k), u_k uniform on [0, 1) (seed 1), the sign
// alternating, so every sample is a reversal (the gate is 0). Times, best of 5: the streaming
// counter with a sink that sums Σ n Δ³ (what a damage sum reads; no storage), and rainflow()
// returning every cycle in a vector. SERIES_OUT: writes the series (binary float64) for
// bench/rainflow_numpy.py. Prints the counts, so the two peers can be compared.
#include <chrono>
#include <ctime>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <random>
#include <vector>

#include "machdyn/analysis/rainflow.hpp"

int main(int argc, char** argv) {
  const long n = argc > 1 ? std::atol(argv[1]) : 10'000'000L;
  std::vector<double> x(static_cast<std::size_t>(n));
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (long k = 0; k < n; ++k) x[static_cast<std::size_t>(k)] = (k % 2 ? -1.0 : 1.0) * (0.05 + u(rng));
  if (argc > 2) {
    std::ofstream out(argv[2], std::ios::binary);
    out.write(reinterpret_cast<const char*>(x.data()), static_cast<std::streamsize>(x.size() * sizeof(double)));
  }
  using clock = std::chrono::steady_clock;
  // Wall time and this process's CPU time (std::clock): on a shared machine the CPU time is the
  // one-core figure.
  double best_stream = 1e30, best_vector = 1e30, cpu_stream = 1e30, cpu_vector = 1e30, cycles = 0, damage = 0;
  std::size_t held = 0, stored = 0;
  for (int rep = 0; rep < 5; ++rep) {
    double c = 0, d = 0;
    const std::clock_t c0 = std::clock();
    auto t0 = clock::now();
    machdyn::RainflowCounter counter([&](const machdyn::RainflowCycle& y) {
      const double r = y.range();
      c += y.count, d += y.count * r * r * r;
    });
    for (const double v : x) counter.add(v);
    counter.finish();
    auto t1 = clock::now();
    const std::clock_t c1 = std::clock();
    const auto all = machdyn::rainflow(x);
    auto t2 = clock::now();
    const std::clock_t c2 = std::clock();
    cpu_stream = std::min(cpu_stream, static_cast<double>(c1 - c0) / CLOCKS_PER_SEC);
    cpu_vector = std::min(cpu_vector, static_cast<double>(c2 - c1) / CLOCKS_PER_SEC);
    best_stream = std::min(best_stream, std::chrono::duration<double>(t1 - t0).count());
    best_vector = std::min(best_vector, std::chrono::duration<double>(t2 - t1).count());
    cycles = c, damage = d, held = counter.max_held(), stored = all.size();
  }
  std::printf("turning points %ld\ncycles %.1f (%zu records)\nsum n*range^3 %.10g\nmax held %zu\n", n, cycles, stored,
              damage, held);
  std::printf("streaming counter: %.3f s wall, %.3f s CPU (%.1f ns per point)\n", best_stream, cpu_stream,
              cpu_stream / static_cast<double>(n) * 1e9);
  std::printf("rainflow() into a vector: %.3f s wall, %.3f s CPU\n", best_vector, cpu_vector);
  return 0;
}
