#!/usr/bin/env python3
"""Benchmark (not a test): the crank-slider of examples/crank-slider.yaml, 100 revolutions, with
scipy's solve_ivp RK45 (Dormand-Prince 5(4), the same method) at rtol 1e-10, atol 1e-12."""
import math, time
import numpy as np
from scipy.integrate import solve_ivp

r, l, m_rod, m_p, J_c, M = 0.04, 0.16, 1.2, 1.6, 0.08, 24.66
a = l / 3; J_rod = m_rod * a * (l - a)
tx = np.array([0, 20, 40, 180, 240, 290, 320, 335, 360.0]); tF = np.array([6000, 2500, 0, 0, 600, 2000, 4500, 6000, 6000.0])

def rhs(t, y):
    phi, w = y
    lam = r / l; s = math.sin(phi); c = math.cos(phi)
    u = lam * s; cp = math.sqrt(1 - u * u); dpsi = lam * c / cp
    ddpsi = -lam * s / cp + lam**3 * s * c * c / cp**3
    gx1 = -r * s - a * u * dpsi; gx2 = -r * c - a * (lam * c * dpsi + u * ddpsi)
    bx1 = -r * s - l * u * dpsi; bx2 = -r * c - l * (lam * c * dpsi + u * ddpsi)
    gy1 = r * c * (1 - a / l); gy2 = -r * s * (1 - a / l)
    I = J_c + m_rod * (gx1**2 + gy1**2) + J_rod * dpsi**2 + m_p * bx1**2
    dI = 2 * m_rod * (gx1 * gx2 + gy1 * gy2) + 2 * J_rod * dpsi * ddpsi + 2 * m_p * bx1 * bx2
    F = float(np.interp(math.degrees(phi) % 360.0, tx, tF))
    return [w, (M + F * (-bx1) - 0.5 * dI * w * w) / I]

t_end = 100 * 2 * math.pi / 150.0
best = 1e300
for _ in range(2):
    t0 = time.perf_counter()
    sol = solve_ivp(rhs, (0, t_end), [0.0, 150.0], method="RK45", rtol=1e-10, atol=1e-12)
    best = min(best, time.perf_counter() - t0)
print(f"{'scipy RK45':<22} {best*1e3:10.3f} ms {sol.t.size-1:8d} steps {sol.nfev:8d} f-evals  "
      f"phi_end {sol.y[0,-1]:.12g}  omega_end {sol.y[1,-1]:.12g}")
