#!/usr/bin/python3
"""The runs of bench/run-sweep.sh's travel start-up sweep done with scipy: mu_d (adhesion.mu_k) from
MUA to MUB in NMU steps (slowest) times P from PA to PB in NP steps (N), each run the event model of
bench/travel_start_scipy.py (solve_ivp RK45 with terminal events, restarting with the new modes) over
2 s at machdyn's tolerances rtol 1e-10, atol 1e-12 (no output grid: only the events and the peak
link force, less than machdyn records). Prints runs/s. MAX_RUNS limits the runs done to every k-th
run of the design (scipy is slow; the rate is what counts).
Usage: /usr/bin/python3 scipy_travel_sweep.py MUA MUB NMU PA PB NP [MAX_RUNS]   (python3-scipy)"""
import os
import sys
import time

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from travel_start_scipy import run  # noqa: E402  (the one scipy model of the start-up)


def main():
    mua, mub, nmu, pa, pb, npp = (float(sys.argv[1]), float(sys.argv[2]), int(sys.argv[3]), float(sys.argv[4]),
                                  float(sys.argv[5]), int(sys.argv[6]))
    runs = [(mu, p) for mu in np.linspace(mua, mub, nmu) for p in np.linspace(pa, pb, npp)]
    if len(sys.argv) > 7:  # every k-th run: a sample across the whole design, not its first corner
        n = int(sys.argv[7])
        runs = runs[::max(1, len(runs) // n)][:n]
    kw = dict(method="RK45", rtol=1e-10, atol=1e-12)
    a = time.perf_counter()
    for mu, p in runs:
        run(kw, P=p, mu_d=mu)
    dt = time.perf_counter() - a
    print(f"scipy         {len(runs):6d} runs {dt:9.3f} s {len(runs) / dt:10.1f} runs/s")


if __name__ == "__main__":
    main()
