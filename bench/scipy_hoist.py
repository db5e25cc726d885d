#!/usr/bin/env python3
"""The three-mass hoist of examples/hoist-3mass.yaml for 10 s with scipy's solve_ivp (RK45 =
Dormand–Prince, rtol 1e-8, atol 1e-10, the same 1 ms output grid). Prints wall time and steps.
Run with Debian's /usr/bin/python3 (python3-scipy)."""
import sys
import time

import numpy as np
from scipy.integrate import solve_ivp

I1, I2, I3 = 0.80, 0.45, 0.25
c1, c2 = 2.4e4, 9.0e3
Msp, MB = 450.0, 270.0


def f(t, y):
    M12 = c1 * (y[0] - y[2])
    M23 = c2 * (y[2] - y[4])
    return [y[1], (Msp - M12) / I1, y[3], (M12 - M23 - MB) / I2, y[5], M23 / I3]


def main():
    T = 10.0
    t_eval = np.linspace(0.0, T, 10001)
    y0 = [MB / c1, 0, 0, 0, 0, 0]
    times = []
    for _ in range(int(sys.argv[1]) if len(sys.argv) > 1 else 3):
        a = time.perf_counter()
        sol = solve_ivp(f, (0.0, T), y0, method="RK45", rtol=1e-8, atol=1e-10, t_eval=t_eval)
        times.append(time.perf_counter() - a)
    M12 = c1 * (sol.y[0] - sol.y[2])
    steps = (sol.nfev - 2) // 6
    print(f"hoist scipy    {sorted(times)[len(times) // 2]:.6f} s  steps ~{steps}  max M12 {M12.max():.9g} (on the grid)")


if __name__ == "__main__":
    main()
