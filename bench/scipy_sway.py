#!/usr/bin/python3
"""The sway sweep of bench/run-sway.sh solved with scipy: the model of bench/sway-sweep.yaml written
from docs/sway.md and docs/model-files.md (Drives: the speed drive) — not from machdyn's code.

  carriage  the drive line and the trolley, one body while the wheels stick (M = m_d + M_t; machdyn's
            table shows no slip for these runs), at x_c: M x_c'' = F_d − F u_x
  drive     PI: e = v_ref(t) − x_c', F_d = K_p e + x_I, x_I' = (K_p/T_i) e (|F_d| stays below the limit:
            checked)
  load      (x, z), m: m x'' = F u_x, m z'' = F u_z − m g
  rope      suspension point p = (x_c, h), h = L0 + m g/c; l = |p − r|, u = (p − r)/l, e = l − L0,
            e' = u·(p' − r'), F = c e + d e' (c = n E A/L0; taut throughout: checked)
  sway      θ = atan2(x − x_c, h − z); the residual sway is max |θ| on the 10 ms grid from 14 s on
  reference a ramp s(t) 0 → v over T_a, shaped for 12 m (docs/sway.md, ω² = g/12 m, τ = π/ω, ζ = 0):
            none s(t); zv ½ s(t) + ½ s(t − τ); zvd ¼ s(t) + ½ s(t − τ) + ¼ s(t − 2τ); two-step two
            ramps 0 → v/2 over T_a/2 from 0 and from τ

Usage: /usr/bin/python3 scipy_sway.py LA LB NL TA TB NT [MAX_RUNS] [--rtol R]
  the grid rope.length LA:LB:NL (slowest) × ramp end TA:TB:NT, each shaper (none, zv, zvd, two-step);
  MAX_RUNS runs of each shaper's grid, drawn with a fixed seed. Prints the runs/s and one line per run:
  `shaper length T_a residual_sway_rad`, for bench/run-sway.sh to compare with machdyn's."""
import math
import sys
import time

import numpy as np
from scipy.integrate import solve_ivp

G = 9.80665
M_C, M_L = 1500.0 + 8000.0, 40000.0
EA, FALLS, D = 1.2e8, 4, 20e3
KP, TI, LIMIT = 4e5, 0.5, 60e3
V, T_END, T_R, DT = 0.63, 20.0, 14.0, 0.01
W_SHAPER = math.sqrt(G / 12.0)


def ramp(t, ta):
    return V * min(max(t / ta, 0.0), 1.0)


SHAPERS = ("none", "zv", "zvd", "two-step")


def run(length, ta, shaper, rtol=1e-8, atol=1e-10):
    c = FALLS * EA / length
    h = length + M_L * G / c
    half = math.pi / W_SHAPER

    def vref(t):
        if shaper == "zv":
            return 0.5 * ramp(t, ta) + 0.5 * ramp(t - half, ta)
        if shaper == "zvd":
            return 0.25 * ramp(t, ta) + 0.5 * ramp(t - half, ta) + 0.25 * ramp(t - 2 * half, ta)
        if shaper == "two-step":
            return 0.5 * ramp(t, 0.5 * ta) + 0.5 * ramp(t - half, 0.5 * ta)
        return ramp(t, ta)

    def rhs(t, y):
        xc, vc, xi, x, z, vx, vz = y
        wx, wz = xc - x, h - z
        l = math.hypot(wx, wz)
        ux, uz = wx / l, wz / l
        F = c * (l - length) + D * (ux * (vc - vx) - uz * vz)
        e = vref(t) - vc
        Fd = KP * e + xi
        return [vc, (Fd - F * ux) / M_C, KP / TI * e, vx, vz, F * ux / M_L, F * uz / M_L - G]

    grid = np.arange(0.0, T_END + DT / 2, DT)
    sol = solve_ivp(rhs, (0.0, T_END), [0.0] * 7, method="RK45", rtol=rtol, atol=atol, t_eval=grid)
    xc, vc, xi, x, z = sol.y[0], sol.y[1], sol.y[2], sol.y[3], sol.y[4]
    theta = np.arctan2(x - xc, h - z)
    # The assumptions above, checked on the grid: the rope taut, the drive below its limit.
    l = np.hypot(xc - x, h - z)
    assert np.all(l > length), "the rope went slack"
    assert np.all(np.abs(KP * (np.array([vref(t) for t in grid]) - vc) + xi) < LIMIT), "the drive limited"
    return float(np.max(np.abs(theta[grid >= T_R - 1e-9]))), sol.nfev


def main():
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    rtol = 1e-8
    if "--rtol" in sys.argv:
        rtol = float(sys.argv[sys.argv.index("--rtol") + 1])
        args.remove(sys.argv[sys.argv.index("--rtol") + 1])
    la, lb, nl, ta, tb, nt = (float(args[0]), float(args[1]), int(args[2]), float(args[3]), float(args[4]), int(args[5]))
    grid = [(lv, tv) for lv in np.linspace(la, lb, nl) for tv in np.linspace(ta, tb, nt)]
    runs = []
    for case in SHAPERS:
        pts = grid
        if len(args) > 6:  # a sample across the case's grid (fixed seed: the same runs every time)
            n = min(int(args[6]), len(grid))
            pts = [grid[i] for i in sorted(np.random.default_rng(1).choice(len(grid), n, replace=False))]
        runs += [(case, lv, tv) for lv, tv in pts]
    out, nfev = [], 0
    a, cpu = time.perf_counter(), time.process_time()
    for case, lv, tv in runs:
        res, nf = run(lv, tv, case, rtol=rtol, atol=rtol * 1e-2)
        out.append((case, lv, tv, res))
        nfev += nf
    dt, cpu = time.perf_counter() - a, time.process_time() - cpu
    print(f"scipy         {len(runs):6d} runs {dt:9.3f} s {len(runs) / dt:10.2f} runs/s   CPU {cpu:8.3f} s "
          f"{len(runs) / cpu:8.2f} runs/CPU-s  (rtol {rtol:g}, {nfev / len(runs):.0f} evaluations per run)")
    for case, lv, tv, res in out:
        print(f"run {case} {lv!r} {tv!r} {res!r}")


if __name__ == "__main__":
    main()
