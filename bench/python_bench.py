#!/usr/bin/env python3
"""The Python module's cost (issue 13), with Debian's /usr/bin/python3:

1. Call overhead on the hoist: ``machdyn.simulate(m)`` timed in Python against the same simulate()
   timed in C++ inside the same process (machdyn._machdyn._time_simulate), interleaved, medians.
   The goal: overhead < 50 µs. Also what reading a series and the summary dict cost.
2. Sweep throughput: ``machdyn.sweep`` against ``machdyn sweep`` (the CLI process) on the same runs
   and threads; the tables are compared byte for byte.
3. Against scipy: the 10 s hoist of bench/scipy_hoist.py (solve_ivp RK45, same tolerances).

Usage: PYTHONPATH=BUILD/python /usr/bin/python3 bench/python_bench.py BUILD [REPEATS]
Not a test: the numbers depend on the machine (docs/benchmarks.md, section "Python module").
"""
import os
import statistics
import subprocess
import sys
import tempfile
import time

import machdyn
from machdyn import _machdyn

HERE = os.path.dirname(os.path.abspath(__file__))
EXAMPLES = os.path.join(HERE, "..", "examples")


def overhead(name, model, repeats):
    # Warm up (allocator, caches), then interleave C++-timed and Python-timed calls.
    for _ in range(3):
        machdyn.simulate(model)
    cpp, py = [], []
    for _ in range(repeats):
        cpp.append(_machdyn._time_simulate(model._core, 1))
        a = time.perf_counter()
        r = machdyn.simulate(model)
        py.append(time.perf_counter() - a)
        r = None
    c, p = statistics.median(cpp), statistics.median(py)
    # Paired differences: each Python call against the C++ call just before it.
    d = statistics.median(b - a for a, b in zip(cpp, py))
    print(f"{name:<34} C++ {c * 1e6:10.1f} µs   Python {p * 1e6:10.1f} µs   overhead (median of pairs) "
          f"{d * 1e6:7.1f} µs   ({repeats} pairs)")
    r = machdyn.simulate(model)
    col = r.columns[-1]
    n = 2000
    a = time.perf_counter()
    for _ in range(n):
        r[col]
    t_col = (time.perf_counter() - a) / n
    a = time.perf_counter()
    for _ in range(200):
        r._summary = None
        r.summary
    t_sum = (time.perf_counter() - a) / 200
    print(f"{'':<34} r[{col!r}] {t_col * 1e6:.2f} µs (a view, no copy); r.summary {t_sum * 1e6:.1f} µs (JSON → dict)")


def sweep(build, model_path, vary, threads, repeats):
    cli = os.path.join(build, "apps", "machdyn", "machdyn")
    m = machdyn.load(model_path)
    with tempfile.TemporaryDirectory() as tmp:
        best_cli = best_py = 1e300
        for k in range(repeats):
            out_c, out_p = os.path.join(tmp, f"c{k}"), os.path.join(tmp, f"p{k}")
            args = [cli, "sweep", model_path, "--jobs", str(threads), "-o", out_c]
            for f, s in vary.items():
                args += ["--vary", f"{f}={s}"]
            a = time.perf_counter()
            subprocess.run(args, check=True, capture_output=True)
            best_cli = min(best_cli, time.perf_counter() - a)
            a = time.perf_counter()
            df = machdyn.sweep(m, vary=vary, threads=threads, out=out_p)
            best_py = min(best_py, time.perf_counter() - a)
            same = open(os.path.join(out_c, "sweep.csv"), "rb").read() == open(os.path.join(out_p, "sweep.csv"), "rb").read()
        n = len(df)
        print(f"sweep {os.path.basename(model_path)} {n} runs, {threads} thread(s): CLI {n / best_cli:8.1f} runs/s "
              f"({best_cli:.3f} s with process start)   machdyn.sweep {n / best_py:8.1f} runs/s ({best_py:.3f} s, "
              f"DataFrame included)   tables identical: {same}   (best of {repeats})")


def main():
    build = sys.argv[1] if len(sys.argv) > 1 else "build/release"
    repeats = int(sys.argv[2]) if len(sys.argv) > 2 else 200
    hoist = os.path.join(EXAMPLES, "hoist-3mass.yaml")
    print(f"== Python module: /usr/bin/python3 {sys.version.split()[0]}, {os.cpu_count()} cores, "
          f"load average {os.getloadavg()[0]:.2f}")
    overhead("hoist-3mass.yaml (0.5 s)", machdyn.load(hoist), repeats)
    ten = machdyn.load(hoist, set={"simulation.t_end": 10, "simulation.rtol": 1e-8, "simulation.atol": 1e-10,
                                   "simulation.dt_out": 1e-3, "simulation.integrator": "dopri5"})
    overhead("hoist 10 s, rtol 1e-8 (bench_hoist)", ten, max(20, repeats // 10))
    sweep(build, hoist, {"c1.stiffness": "1e4:5e4:20", "I3.inertia": "0.2:0.4:10"}, 2, 3)
    sweep(build, os.path.join(EXAMPLES, "travel-start.yaml"),
          {"adhesion.mu_k": "0.09:0.13:40", "P.value": "6000:7000:25"}, 2, 3)
    print("== the 10 s hoist: machdyn.simulate against scipy solve_ivp (bench/scipy_hoist.py)")
    times = []
    for _ in range(15):
        a = time.perf_counter()
        machdyn.simulate(ten)
        times.append(time.perf_counter() - a)
    print(f"hoist machdyn.simulate  {statistics.median(times):.6f} s (median of 15)")
    subprocess.run([sys.executable, os.path.join(HERE, "scipy_hoist.py"), "3"], check=False)


if __name__ == "__main__":
    main()
