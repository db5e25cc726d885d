#!/usr/bin/python3
"""The runs of bench/run-sweep.sh's travel start-up sweep done with scipy: mu_d (adhesion.mu_k) from
MUA to MUB in NMU steps (slowest) times P from PA to PB in NP steps (N), each run the event model of
bench/travel_start_scipy.py (solve_ivp RK45 with terminal events, restarting with the new modes) over
2 s at machdyn's tolerances rtol 1e-10, atol 1e-12 (no output grid: only the events and the peak
link force, less than machdyn records). Prints runs/s. MAX_RUNS limits the runs done to every k-th
run of the design (scipy is slow; the rate is what counts).
Usage: /usr/bin/python3 scipy_travel_sweep.py MUA MUB NMU PA PB NP [MAX_RUNS]   (python3-scipy)"""
import sys
import time

import numpy as np
from scipy.integrate import solve_ivp

m1, mk, m2, c, Delta = 3000.0, 300.0, 10000.0, 2.0e6, 0.004
dG, mu_s, W = 50e3, 0.18, 1500.0
Fsc = dG * mu_s
T_END = 2.0


def run(mu_d, P, kw):
    Fd = dG * mu_d

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

    t, y, md = 0.0, np.zeros(6), [0, 0, 0]
    events, slips, Fmax, last = 0, 0, 0.0, -1
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
        sol = solve_ivp(rhs, (t, T_END), y, events=evs, t_eval=None, **kw)
        if md[0]:
            Fmax = max(Fmax, float(np.max(c * (sol.y[0] - sol.y[1] - Delta))))
        if sol.status != 1:
            break
        k = [i for i in range(3) if len(sol.t_events[i])][0]
        t, y = sol.t_events[k][0], sol.y_events[k][0].copy()
        if t <= sol.t[0] and events > 0 and k == last:
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
                    slips += 1
            else:
                md[1] = 1
                slips += 1
        else:
            if md[2]:
                md[2], y[5] = 0, 0.0
            else:
                md[2] = 1
    return events, slips, Fmax


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
        run(mu, p, kw)
    dt = time.perf_counter() - a
    print(f"scipy         {len(runs):6d} runs {dt:9.3f} s {len(runs) / dt:10.1f} runs/s")


if __name__ == "__main__":
    main()
