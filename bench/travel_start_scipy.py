#!/usr/bin/python3
"""Travel start-up (paper 001), 2 s, with scipy solve_ivp and terminal events, restarting at each
event with the new modes (the same mode logic as bench_travel_start.cpp's hand-written loop).
The values are those of examples/travel-start.yaml. bench/scipy_travel_sweep.py imports run().
Usage: travel_start_scipy.py [rtol atol]   (default: scipy's own defaults rtol=1e-3, atol=1e-6)"""
import sys
import time

import numpy as np
from scipy.integrate import solve_ivp

m1, mk, m2, c, Delta = 3000.0, 300.0, 10000.0, 2.0e6, 0.004
dG, mu_s, W = 50e3, 0.18, 1500.0
Fsc = dG * mu_s
T_END = 2.0


def run(kw, P=6800.0, mu_d=0.11):
    """One start-up; returns (events, slips, F_max, f-evals, time of the last event)."""
    Fd = dG * mu_d

    def forces(y, md):  # link force, accelerations of m1, mk, m2, adhesion force, resistance force
        gap, adh, res = md
        F = c * (y[0] - y[1] - Delta) if gap else 0.0
        a1 = (P - F) / m1
        if adh == 0 and res == 0:
            return F, a1, 0.0, 0.0, F, F
        if adh == 0:
            acc = (F - W) / (mk + m2)
            return F, a1, acc, acc, F - mk * acc, W
        ak = (F - Fd) / mk
        if res == 0:
            return F, a1, ak, 0.0, Fd, Fd
        return F, a1, ak, (Fd - W) / m2, Fd, W

    t, y, md = 0.0, np.zeros(6), [0, 0, 0]  # modes: gap closed, adhesion slipping, m2 sliding
    events, slips, Fmax, nfev, last = 0, 0, 0.0, 0, -1
    while t < T_END:
        def rhs(_, y):
            _, a1, ak, a2, _, _ = forces(y, md)
            return [y[3], y[4], y[5], a1, ak, a2]

        def g0(_, y): return forces(y, md)[0] if md[0] else Delta - (y[0] - y[1])
        def g1(_, y): return y[4] - y[5] if md[1] else Fsc - forces(y, md)[4]
        def g2(_, y): return y[5] if md[2] else W - forces(y, md)[5]
        evs = [g0, g1, g2]
        for g in evs:
            g.terminal, g.direction = True, -1
        sol = solve_ivp(rhs, (t, T_END), y, events=evs, **kw)
        nfev += sol.nfev
        if md[0]:
            Fmax = max(Fmax, float(np.max(c * (sol.y[0] - sol.y[1] - Delta))))
        if sol.status != 1:
            break
        k = [i for i in range(3) if len(sol.t_events[i])][0]
        t, y = sol.t_events[k][0], sol.y_events[k][0].copy()
        if t <= sol.t[0] and events > 0 and k == last:  # no progress: an event at the restart point
            break
        last = k
        events += 1
        if k == 0:
            md[0] ^= 1
        elif k == 1:
            if md[1]:  # re-stick if the locked pair can hold
                md[1] = 0
                y[4] = y[5] = (mk * y[4] + m2 * y[5]) / (mk + m2)
                if forces(y, md)[4] > Fsc:
                    md[1] = 1
                    slips += 1
            else:
                md[1] = 1
                slips += 1
        else:
            if md[2]:
                md[2], y[5] = 0, 0.0
            else:
                md[2] = 1
    return events, slips, Fmax, nfev, t


def main():
    kw = {}
    if len(sys.argv) > 2:
        kw = dict(rtol=float(sys.argv[1]), atol=float(sys.argv[2]))
    kw["method"] = "RK45"
    t0 = time.perf_counter()
    ev, _, Fmax, nfev, t_last = run(kw)
    dt = time.perf_counter() - t0
    print(f"scipy solve_ivp RK45 {kw}: {dt*1e3:.1f} ms, {ev} events, {nfev} f-evals, F_max {Fmax:.6g} N, "
          f"last event at t = {t_last:.4g} s")


if __name__ == "__main__":
    main()
