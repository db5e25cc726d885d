"""The numpy peer of bench_rainflow: ASTM E1049 5.4.4 rainflow of the same series, written the usual
way for numpy (turning points vectorized, the stack loop in Python), timed best of 3.

    bench_rainflow N /tmp/series.f64      # writes the series
    python3 bench/rainflow_numpy.py /tmp/series.f64
"""
import sys
import time

import numpy as np


def turning_points(x):
    d = np.diff(x)
    keep = d != 0
    x = np.concatenate(([x[0]], x[1:][keep]))
    d = np.diff(x)
    rev = np.nonzero(d[1:] * d[:-1] < 0)[0] + 1
    return np.concatenate(([x[0]], x[rev], [x[-1]])) if len(x) > 1 else x


def rainflow(x):
    count, damage = 0.0, 0.0
    s = []
    for p in turning_points(x).tolist():
        s.append(p)
        while len(s) >= 3:
            X, Y = abs(s[-1] - s[-2]), abs(s[-2] - s[-3])
            if X < Y:
                break
            if len(s) == 3:
                count += 0.5
                damage += 0.5 * Y ** 3
                del s[0]
            else:
                count += 1.0
                damage += Y ** 3
                del s[-3:-1]
    for a, b in zip(s, s[1:]):
        count += 0.5
        damage += 0.5 * abs(b - a) ** 3
    return count, damage


x = np.fromfile(sys.argv[1], dtype=np.float64)
best, cpu = 1e30, 1e30
for _ in range(3):
    t0, c0 = time.perf_counter(), time.process_time()
    c, d = rainflow(x)
    best, cpu = min(best, time.perf_counter() - t0), min(cpu, time.process_time() - c0)
print(f"turning points {len(x)}\ncycles {c:.1f}\nsum n*range^3 {d:.10g}\n"
      f"numpy + Python loop: {best:.3f} s wall, {cpu:.3f} s CPU")
