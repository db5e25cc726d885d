#!/usr/bin/python3
"""Travel start-up (paper 001), 2 s, with scipy solve_ivp and terminal events, restarting at each
event with the new modes (the same mode logic as bench_travel_start.cpp's hand-written loop).
Usage: travel_start_scipy.py [rtol atol]   (default: scipy's own defaults rtol=1e-3, atol=1e-6)"""
import sys, time
import numpy as np
from scipy.integrate import solve_ivp

m1, mk, m2, c, Delta, P = 3000.0, 300.0, 10000.0, 2.0e6, 0.004, 6800.0
Fsc, Fd, W = 50e3 * 0.18, 50e3 * 0.11, 1500.0

def forces(y, md):
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

def run(kw):
    t, y, md = 0.0, np.zeros(6), [0, 0, 0]
    events, Fmax, nfev = 0, 0.0, 0
    while t < 2.0:
        def rhs(_, y):
            _, a1, ak, a2, _, _ = forces(y, md)
            return [y[3], y[4], y[5], a1, ak, a2]
        def g0(_, y): return forces(y, md)[0] if md[0] else Delta - (y[0] - y[1])
        def g1(_, y): return y[4] - y[5] if md[1] else Fsc - forces(y, md)[4]
        def g2(_, y): return y[5] if md[2] else W - forces(y, md)[5]
        evs = [g0, g1, g2]
        for g in evs:
            g.terminal, g.direction = True, -1
        sol = solve_ivp(rhs, (t, 2.0), y, events=evs, **kw)
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
            if md[1]:
                md[1] = 0
                y[4] = y[5] = (mk * y[4] + m2 * y[5]) / (mk + m2)
                if forces(y, md)[4] > Fsc:
                    md[1] = 1
            else:
                md[1] = 1
        else:
            if md[2]:
                md[2], y[5] = 0, 0.0
            else:
                md[2] = 1
    return events, Fmax, nfev, t

kw = {}
if len(sys.argv) > 2:
    kw = dict(rtol=float(sys.argv[1]), atol=float(sys.argv[2]))
kw["method"] = "RK45"
t0 = time.perf_counter()
ev, Fmax, nfev, t_last = run(kw)
dt = time.perf_counter() - t0
print(f"scipy solve_ivp RK45 {kw}: {dt*1e3:.1f} ms, {ev} events, {nfev} f-evals, F_max {Fmax:.6g} N, last event at t = {t_last:.4g} s")
