#!/usr/bin/env python3
"""The runs of bench/run-sweep.sh's default sweep of examples/hoist-3mass.yaml done with scipy:
c1 from C1A to C1B in N1 steps (slowest) times I3 from I3A to I3B in N3 steps, each run solve_ivp
RK45 (Dormand-Prince, as machdyn's dopri5) over the model's t_end 0.5 s with its rtol 1e-10,
atol 1e-12 and 0.5 ms output grid, then the peak link loads on the grid. Prints runs/s.
Usage: python3 scipy_sweep.py C1A C1B N1 I3A I3B N3 [MAX_RUNS]
Run with Debian's /usr/bin/python3 (python3-scipy)."""
import sys
import time

import numpy as np
from scipy.integrate import solve_ivp

I1, I2 = 0.80, 0.45
c2 = 9.0e3
Msp, MB = 450.0, 270.0


def run(c1, I3):
    def f(t, y):
        M12 = c1 * (y[0] - y[2])
        M23 = c2 * (y[2] - y[4])
        return [y[1], (Msp - M12) / I1, y[3], (M12 - M23 - MB) / I2, y[5], M23 / I3]

    T = 0.5
    t_eval = np.linspace(0.0, T, 1001)
    y0 = [0.01125, 0, 0, 0, 0, 0]
    sol = solve_ivp(f, (0.0, T), y0, method="RK45", rtol=1e-10, atol=1e-12, t_eval=t_eval)
    M12 = c1 * (sol.y[0] - sol.y[2])
    M23 = c2 * (sol.y[2] - sol.y[4])
    return M12.max(), M12.min(), M23.max(), M23.min()


def main():
    c1a, c1b, n1, i3a, i3b, n3 = (float(sys.argv[1]), float(sys.argv[2]), int(sys.argv[3]), float(sys.argv[4]),
                                  float(sys.argv[5]), int(sys.argv[6]))
    max_runs = int(sys.argv[7]) if len(sys.argv) > 7 else n1 * n3
    runs = [(c1, i3) for c1 in np.linspace(c1a, c1b, n1) for i3 in np.linspace(i3a, i3b, n3)][:max_runs]
    a = time.perf_counter()
    for c1, i3 in runs:
        run(c1, i3)
    dt = time.perf_counter() - a
    print(f"scipy         {len(runs):6d} runs {dt:9.3f} s {len(runs) / dt:10.1f} runs/s")


if __name__ == "__main__":
    main()
