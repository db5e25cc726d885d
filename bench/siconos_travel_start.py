#!/usr/bin/python3
"""Travel-drive start-up (paper 001, examples/travel-start.yaml) in Siconos, 2 s of simulated time.

Usage: siconos_travel_start.py [--model FILE] [--h H ...] [--theta T] [--machdyn BIN] [--repeat N]
  defaults: the example model, h = 1e-4 and 1e-5, theta = 0.5, one run per h.
  --machdyn BIN also runs `BIN simulate MODEL --json` and prints its events and peak beside ours.

Formulation (Siconos 4.4, time stepping, no event location):

  state x = [x1, xk, x2, v1, vk, v2]  (positions and velocities of m1, mk, m2)
  FirstOrderLinearTIDS   x' = A x + b + r     A: x_i' = v_i,  b: P/m1 on v1'  (the drive force)
  EulerMoreauOSI(theta)  theta-method on x' = A x + b + r, r = B lambda taken implicitly at t_k+1
  Relay (one-step problem) solves all interactions of a step together:
    w = M lambda + q,  -w in N_[lb,ub](lambda)
  Interactions (FirstOrderLinearTIR: y = C x + D lambda + e, r = B lambda), each with its law:
    gap+   the link c on its positive flank: lambda = contact force >= 0,
           y = (Delta - gap_start) - (x1 - xk) + lambda / c >= 0, complementary (ComplementarityConditionNSL).
           The compliance D = 1/c turns the rigid unilateral contact into a spring that only
           pushes once the gap is taken up: lambda = c * max(0, delta - delta+), exact at every step.
    gap-   the same on the negative flank (delta <= -gap_start pushes mk back onto m1).
    adhesion  wheel-rail friction, y = v2 - vk (minus the sliding speed u = vk - v2),
           lambda = friction force on m2 (-lambda on mk), RelayNSL bounds [-F, F]:
           stuck (u = 0) while |lambda| < F, else lambda = F sign(u).
    W      resistance of m2 to the ground, y = v2, lambda = force on m2, RelayNSL [-W, W].

  mu_s != mu_d: a Siconos RelayNSL has a single bound, so the bound of the adhesion relay is reset
  before every step from the state of the previous step (stick/slip switching between steps):
    F = F_sc = dG mu_s  while the contact is stuck (lambda strictly inside its bounds), and in the
                        step where a sliding speed is about to cross zero (linear extrapolation of
                        the last two steps): sticking again is decided against the static limit;
    F = F_d  = dG mu_d  while it slips.
  The step in which the contact breaks away is therefore computed with F_sc throughout, the first
  one after it with F_d: an O(h) error per transition, which is what the h-study below measures.
"""
import argparse, json, os, subprocess, sys, tempfile, time
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
DEFAULT_MODEL = os.path.join(HERE, "..", "examples", "travel-start.yaml")


# ---- model ----------------------------------------------------------------------------------------
UNITS = {"kg": 1.0, "N/m": 1.0, "N": 1.0, "kN": 1e3, "m": 1.0, "mm": 1e-3, "s": 1.0, "ms": 1e-3}


def qty(v):
    """'4 mm' -> 0.004, '2.0e6 N/m' -> 2e6, 1500 -> 1500 (only the units the example uses)."""
    if isinstance(v, (int, float)):
        return float(v)
    num, _, unit = str(v).strip().partition(" ")
    return float(num) * UNITS[unit.strip() or "N"]


def load_model(path):
    """The travel start-up parameters from the model file (python3-yaml). Without yaml: the values
    of examples/travel-start.yaml, hard-coded."""
    try:
        import yaml
    except ImportError:
        print("(python3-yaml missing: using the values of examples/travel-start.yaml)")
        return dict(m1=3000.0, mk=300.0, m2=10000.0, c=2.0e6, Delta=0.004, gap_start=0.0,
                    Fs=50e3 * 0.18, Fd=50e3 * 0.11, W=1500.0, P=6800.0, t_end=2.0)
    d = yaml.safe_load(open(path))
    b, link, con, load = d["bodies"], d["links"]["c"], d["contacts"], d["loads"]["P"]
    adh, res = con["adhesion"], con["W"]
    assert link["between"] == ["m1", "mk"] and adh["between"] == ["mk", "m2"]
    assert res["between"] == ["m2", "ground"] and load["body"] == "m1" and load["type"] == "constant"
    assert qty(res["static"]) == qty(res["kinetic"]), "W: one friction level only"
    N = qty(adh["normal_force"])
    return dict(m1=qty(b["m1"]["mass"]), mk=qty(b["mk"]["mass"]), m2=qty(b["m2"]["mass"]),
                c=qty(link["stiffness"]), Delta=qty(link["gap"]),
                gap_start=qty(link.get("gap_start", 0.0)),
                Fs=N * float(adh["mu_s"]), Fd=N * float(adh["mu_k"]), W=qty(res["static"]),
                P=qty(load["value"]), t_end=qty(d["simulation"]["t_end"]))


def closed_forms(p):
    """Stages 1-3 exactly (docs/hybrid.md, /work/shared/docs/seed-notes.md section 001)."""
    m1, mk, m2, c, D, P, W, Fs = (p[k] for k in ("m1", "mk", "m2", "c", "Delta", "P", "W", "Fs"))
    D -= p["gap_start"]
    t1 = np.sqrt(2 * m1 * D / P)
    w2 = np.sqrt(c / m1)
    t2 = (np.arctan(np.sqrt(P / (2 * c * D))) - np.arcsin((P - W) / np.sqrt(P * (2 * c * D + P)))) / w2
    # stage 3: m1 against (mk + m2) on the spring, from F = W with v1 and v2 = vk = 0, until the
    # contact force (m2 F + mk W)/(mk + m2) reaches F_sc, i.e. F = F_slip
    F_slip = (Fs * (mk + m2) - mk * W) / m2
    mr = mk + m2
    v1 = np.sqrt((2 * P * (D * c + W) - W ** 2) / (c * m1))
    # relative coordinate s = x1 - xk - D (spring deflection): s'' = (P - F)/m1 - (F - W)/mr, F = c s
    w3 = np.sqrt(c / m1 + c / mr)
    s_eq = (P / m1 + W / mr) / (c / m1 + c / mr)
    s0 = W / c - s_eq
    # s(t) = s_eq + s0 cos w3 t + (v1/w3) sin w3 t = s_eq + A cos(w3 t - phi); c s rises to F_slip
    A, phi = np.hypot(s0, v1 / w3), np.arctan2(v1 / w3, s0)
    t3 = (phi - np.arccos((F_slip / c - s_eq) / A)) / w3
    return dict(t1=t1, t12=t1 + t2, t123=t1 + t2 + t3, F_slip=F_slip)


# ---- Siconos model and run -----------------------------------------------------------------------
def simulate(p, h, theta):
    import siconos.kernel as sk
    m1, mk, m2, c = p["m1"], p["mk"], p["m2"], p["c"]
    dplus, dminus = p["Delta"] - p["gap_start"], -p["gap_start"]   # flanks in delta = x1 - xk
    t_end = p["t_end"]

    # the three masses as one first-order linear time-invariant system (x' = A x + b + r)
    A = np.zeros((6, 6))
    A[0:3, 3:6] = np.eye(3)
    b = np.zeros(6)
    b[3] = p["P"] / m1                       # drive force P on m1
    body = sk.FirstOrderLinearTIDS(np.zeros(6), A, b)

    def relation(C, B, D=None, e=None):
        """y = C x + D lambda + e, r = B lambda (FirstOrderLinearTIR)."""
        rel = sk.FirstOrderLinearTIR(np.atleast_2d(C), np.array(B, float).reshape(6, 1))
        if D is not None:
            rel.setDPtr(np.array([[D]]))
        if e is not None:
            rel.setePtr(np.array([e]))
        return rel

    # gap+: contact force lambda >= 0 pushes mk forward and m1 back, y = delta+ - delta + lambda/c
    gap_pos = sk.Interaction(sk.ComplementarityConditionNSL(1),
                             relation([-1, 1, 0, 0, 0, 0], [0, 0, 0, -1 / m1, 1 / mk, 0], 1 / c, dplus))
    # gap-: contact force lambda >= 0 pushes m1 forward and mk back, y = delta - delta- + lambda/c
    gap_neg = sk.Interaction(sk.ComplementarityConditionNSL(1),
                             relation([1, -1, 0, 0, 0, 0], [0, 0, 0, 1 / m1, -1 / mk, 0], 1 / c, -dminus))
    # adhesion: 1-D Coulomb friction as a relay on y = v2 - vk, lambda = force on m2
    adh_law = sk.RelayNSL(1, -p["Fs"], p["Fs"])
    adhesion = sk.Interaction(adh_law, relation([0, 0, 0, 0, -1, 1], [0, 0, 0, 0, -1 / mk, 1 / m2]))
    # W: resistance of m2 to the ground as a relay on y = v2, lambda = force on m2
    resist = sk.Interaction(sk.RelayNSL(1, -p["W"], p["W"]),
                            relation([0, 0, 0, 0, 0, 1], [0, 0, 0, 0, 0, 1 / m2]))

    nsds = sk.NonSmoothDynamicalSystem(0.0, t_end)
    nsds.insertDynamicalSystem(body)
    for inter in (gap_pos, gap_neg, adhesion, resist):
        nsds.link(inter, body)

    td = sk.TimeDiscretisation(0.0, h)
    osi = sk.EulerMoreauOSI(theta)           # theta-method, nonsmooth input implicit at t_k+1
    osnspb = sk.Relay()                      # mixed relay / complementarity problem of each step
    sim = sk.TimeStepping(nsds, td, osi, osnspb)

    # per-step records
    n = int(round(t_end / h))
    T = np.empty(n); F = np.empty(n); U = np.empty(n); V2 = np.empty(n); LA = np.empty(n)
    stuck = True                              # adhesion starts stuck
    u_prev = u_prev2 = 0.0
    k = 0
    t_solve = 0.0
    c0, t0 = time.process_time(), time.perf_counter()
    while sim.hasNextEvent() and k < n:
        # stick/slip switching of the adhesion's single relay bound (see the module docstring)
        approaching = (not stuck) and u_prev * (2 * u_prev - u_prev2) <= 0.0
        bound = p["Fs"] if (stuck or approaching) else p["Fd"]
        adh_law.setLb(-bound)
        adh_law.setUb(bound)

        ts = time.perf_counter()
        sim.computeOneStep()
        t_solve += time.perf_counter() - ts

        x = body.x()
        la = adhesion.lambda_(0)[0]
        T[k] = sim.nextTime()
        F[k] = gap_pos.lambda_(0)[0] - gap_neg.lambda_(0)[0]   # link force
        U[k] = x[4] - x[5]                                     # sliding speed u = vk - v2
        V2[k] = x[5]
        LA[k] = la
        stuck = abs(la) < bound * (1.0 - 1e-9)                 # lambda inside the bounds: stuck
        u_prev2, u_prev = u_prev, U[k]
        sim.nextStep()
        k += 1
    wall, cpu = time.perf_counter() - t0, time.process_time() - c0
    return dict(T=T[:k], F=F[:k], U=U[:k], V2=V2[:k], LA=LA[:k], steps=k, wall=wall, cpu=cpu,
                t_solve=t_solve, solver=osnspb.numericsSolverOptions().solverId)


def simulate_counting_warnings(p, h, theta):
    """simulate() with the C-level stdout captured: Siconos prints a warning for every step whose
    Relay problem the numerics solver did not solve to its tolerance; count them."""
    sys.stdout.flush()
    saved = os.dup(1)
    with tempfile.TemporaryFile(mode="w+") as log:
        os.dup2(log.fileno(), 1)
        try:
            r = simulate(p, h, theta)
        finally:
            sys.stdout.flush()
            os.dup2(saved, 1)
            os.close(saved)
        log.seek(0)
        r["relay_failures"] = log.read().count("Problem in Relay resolution")
    return r


def events(r, p):
    """Event times as the end of the first step in the new mode (resolution h)."""
    T, F, U, V2, LA = r["T"], r["F"], r["U"], r["V2"], r["LA"]
    out = {}
    closed = F > 0.0
    out["gap_events"] = int(np.count_nonzero(closed[1:] != closed[:-1])) + int(closed[0])
    out["t1"] = T[np.argmax(closed)] if closed.any() else None
    moving = V2 > 1e-12
    out["t12"] = T[np.argmax(moving)] if moving.any() else None
    # adhesion slipping: |lambda| at a bound and a nonzero sliding speed
    slip = (np.abs(U) > 1e-12) & (np.abs(LA) >= p["Fd"] * (1 - 1e-9))
    starts = np.flatnonzero(slip[1:] & ~slip[:-1]) + 1
    if slip[0]:
        starts = np.r_[0, starts]
    out["slips"] = len(starts)
    out["slip_times"] = T[starts]
    out["t123"] = T[starts[0]] if len(starts) else None
    sgn = np.sign(U[np.abs(U) > 1e-12])
    out["reversals"] = int(np.count_nonzero(sgn[1:] != sgn[:-1]))
    i = int(np.argmax(F))
    out["Fmax"], out["t_Fmax"] = F[i], T[i]
    # peak link force of the last slip phase
    if len(starts):
        out["F_last"] = F[starts[-1]:].max()
    return out


def machdyn_summary(binary, model):
    js = json.loads(subprocess.run([binary, "simulate", model, "--json", "-o",
                                    os.path.join("/tmp", f"machdyn-siconos-bench-{os.getpid()}")],
                                   check=True, capture_output=True, text=True).stdout)
    ev = js["events"]
    first = lambda kind, el: next((e["t"] for e in ev if e["kind"] == kind and e["element"] == el), None)
    peaks = js["links"]["c"]["slip_phase_peaks"]
    adh = [q for q in peaks if q["contact"] == "adhesion"]
    tmax = next(q["t_max"] for q in peaks if q["max"] == js["links"]["c"]["max"])
    return dict(t1=first("gap_closed", "c"), t12=first("slip", "W"), t123=first("slip", "adhesion"),
                slips=js["contacts"]["adhesion"]["slips"], Fmax=js["links"]["c"]["max"], t_Fmax=tmax,
                F_last=adh[-1]["max"] if adh else None, wall=js["solver"]["wall_time_s"],
                steps=js["solver"]["steps"],
                gap_events=sum(1 for e in ev if e["element"] == "c" and e["kind"] != "initial"),
                slip_times=np.array([e["t"] for e in ev if e["kind"] == "slip" and e["element"] == "adhesion"]))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--model", default=DEFAULT_MODEL)
    ap.add_argument("--h", type=float, nargs="+", default=[1e-4, 1e-5])
    ap.add_argument("--theta", type=float, default=0.5)
    ap.add_argument("--machdyn", help="machdyn binary for the comparison columns")
    ap.add_argument("--repeat", type=int, default=1, help="runs per h, best wall time reported")
    a = ap.parse_args()

    p = load_model(a.model)
    cf = closed_forms(p)
    md = machdyn_summary(a.machdyn, a.model) if a.machdyn else None
    print(f"== Siconos travel start-up ({os.path.basename(a.model)}), "
          f"{p['t_end']:g} s, EulerMoreauOSI theta = {a.theta}, Relay (Lemke)")
    print(f"   closed forms: t1 = {cf['t1']:.9f} s, t1+t2 = {cf['t12']:.9f} s, "
          f"t1+t2+t3 = {cf['t123']:.9f} s, F_slip = {cf['F_slip']:.1f} N")
    rows = []
    for h in a.h:
        best = None
        for _ in range(a.repeat):
            r = simulate_counting_warnings(p, h, a.theta)
            if best is None or r["wall"] < best["wall"]:
                best = r
        e = events(best, p)
        rows.append((f"siconos h={h:g}", best, e))
        print(f"siconos h={h:g}: {best['wall']*1e3:.0f} ms wall, {best['cpu']*1e3:.0f} ms CPU "
              f"({best['t_solve']*1e3:.0f} ms wall in computeOneStep), "
              f"{best['steps']} steps, t1 {e['t1']:.6f} s, t1+t2 {e['t12']:.6f} s, "
              f"first slip {e['t123']:.6f} s, slips {e['slips']}, reversals of u {e['reversals']}, "
              f"gap events {e['gap_events']}, F_max {e['Fmax']:.1f} N at {e['t_Fmax']:.5f} s, "
              f"last slip peak {e.get('F_last', float('nan')):.1f} N, "
              f"steps with a Relay solver warning {best['relay_failures']}")
        if md is not None:
            n = min(len(md["slip_times"]), len(e["slip_times"]))
            dev = np.max(np.abs(md["slip_times"][:n] - e["slip_times"][:n])) if n else float("nan")
            print(f"   vs machdyn: t1 {e['t1'] - md['t1']:+.2e} s, t1+t2 {e['t12'] - md['t12']:+.2e} s, "
                  f"first slip {e['t123'] - md['t123']:+.2e} s, max |slip time diff| (first {n}) {dev:.2e} s, "
                  f"F_max {e['Fmax'] - md['Fmax']:+.1f} N ({(e['Fmax'] / md['Fmax'] - 1) * 100:+.2f} %)")
    if md is not None:
        print(f"machdyn (dopri5 + events): {md['wall']*1e3:.2f} ms, {md['steps']} steps, t1 {md['t1']:.9f} s, "
              f"t1+t2 {md['t12']:.9f} s, first slip {md['t123']:.9f} s, slips {md['slips']}, "
              f"gap events {md['gap_events']}, F_max {md['Fmax']:.1f} N at {md['t_Fmax']:.5f} s, "
              f"last slip peak {md['F_last']:.1f} N")


if __name__ == "__main__":
    sys.exit(main())
