"""modes, energy, gears, report: the CLI's JSON, and an independent check of each."""
import math

import numpy as np
import pytest

import machdyn
from conftest import cli_json, example


def test_modes_equal_the_cli():
    path = example("hoist-3mass.yaml")
    modes = machdyn.modes(machdyn.load(path))
    assert modes.summary == cli_json("modes", path, "--json")
    assert np.array_equal(modes.omega, modes.summary["frequencies_rad_s"])
    assert modes.bodies == ["I1", "I2", "I3"]


def test_modes_solve_the_eigenproblem():
    # K φ = ω² M φ for every mode, with M and K assembled here from the model's own numbers.
    m = machdyn.load(example("hoist-3mass.yaml"))
    I = np.array([b["inertia_kg_m2"] for b in m.bodies])
    c1, c2 = (l["stiffness"] for l in m.links)
    K = np.array([[c1, -c1, 0], [-c1, c1 + c2, -c2], [0, -c2, c2]])
    modes = machdyn.modes(m)
    for k, w in enumerate(modes.omega):
        phi = modes.shapes[:, k]
        np.testing.assert_allclose(K @ phi, w**2 * I * phi, rtol=0, atol=1e-9 * w**2 * np.abs(I * phi).max())
    assert modes.rigid_body_modes == 1 and len(modes.omega) == 2


def test_energy_equals_the_cli_and_the_simulation():
    path = example("crank-slider.yaml")
    m = machdyn.load(path)
    e = machdyn.energy(m)
    assert e == cli_json("energy", path, "--json")
    # A second algorithm: the simulation's ω at the same crank angles (ODE integration against the
    # energy integral's quadrature). q rises monotonically, so ω(q) interpolates on the output grid.
    r = machdyn.simulate(m)
    q, w = r["crank.position"], r["crank.velocity"]
    table_q, table_w = np.array(e["table"]["q"]), np.array(e["table"]["omega"])
    inside = (table_q >= q[0]) & (table_q <= q[-1])
    assert inside.sum() > 50
    np.testing.assert_allclose(np.interp(table_q[inside], q, w), table_w[inside], rtol=1e-4)


def test_gears_equal_the_cli_and_the_law():
    path = example("walking-drive-gears.yaml")
    g = machdyn.gears(path)
    text = g.pop("text")
    assert g == cli_json("gears", path, "--json")
    assert "sector" in text.lower()
    # Paper 003: k = 3b/(a − b + c) with a = 60 mm, b = 100 mm, c = 360 mm.
    assert g["k"] == pytest.approx(3 * 100 / (60 - 100 + 360), rel=1e-12)
    g2 = machdyn.gears(path, set={"L": "150 mm"})
    assert g2 != g


def test_report_is_one_html_file(tmp):
    out = machdyn.report(machdyn.load(example("hoist-3mass.yaml")), tmp / "r" / "report.html")
    html = open(out, encoding="utf-8").read()
    assert html.startswith("<!DOCTYPE html>") or html.lower().startswith("<!doctype html>")
    assert "Three-mass hoist" in html and "uPlot" in html
    assert [p.name for p in (tmp / "r").iterdir()] == ["report.html"]


def test_model_inspection():
    m = machdyn.load(example("travel-start.yaml"))
    assert [b["name"] for b in m.bodies] == ["m1", "mk", "m2"]
    assert m.bodies[0]["mass_kg"] == 3000
    assert m.links[0]["gap"] == pytest.approx(0.004)
    assert {c["name"] for c in m.contacts} == {"adhesion", "W"}
    assert m.is_hybrid and m.simulation["t_end_s"] == 2
    assert "travel" in repr(m).lower() and "<table>" in m._repr_html_()


def test_modes_per_topology_equal_the_cli_and_paper_001():
    # Rolling without slip (adhesion stuck, W sliding, gap closed): m1 against mk + m2,
    # ω3 = √(c/m1 + c/(mk + m2)) (paper 001).
    path = example("travel-start.yaml")
    m = machdyn.load(path)
    modes = machdyn.modes(m, topology="c=closed, W=slip+")
    assert modes.summary == cli_json("modes", path, "--json", "--topology", "c=closed, W=slip+")
    c, m1, mk, m2 = 2.0e6, 3000.0, 300.0, 10000.0
    assert modes.omega[0] == pytest.approx(math.sqrt(c / m1 + c / (mk + m2)), rel=1e-10)
    assert modes.rigid_body_modes == 1
    assert len(machdyn.modes(m).summary["topologies"]) == 8
    with pytest.raises(machdyn.InputError, match="'shut' is not a mode"):
        machdyn.modes(m, topology="c=shut")


def test_crane_drive_classes_equal_the_cli():
    path = example("crane/main-hoist-inverter.yaml")
    t = machdyn.crane(machdyn.load(path), drive_classes=["HD1", "HD4"])
    assert t == cli_json("crane", path, "--json", "--drive-classes", "HD1,HD4", "-o",
                         str(__import__("tempfile").mkdtemp()))
    assert [r["case"].split(",")[1].strip()[:7] for r in t["rows"] if r["factor"] == "phi2"] == ["HC2/HD1", "HC2/HD4"]
    with pytest.raises(ValueError, match="HD9"):
        machdyn.crane(machdyn.load(path), drive_classes=["HD9"])


def test_crane_equals_the_cli_and_the_closed_form():
    path = example("crane/trolley-buffers.yaml")
    t = machdyn.crane(machdyn.load(path))
    assert t == cli_json("crane", path, "--json", "-o", str(__import__("tempfile").mkdtemp()))
    # φ7's rigid reference: the whole group (400 + 3000 + 2000 kg) at 0.63 m/s into c = 2e5 N/m,
    # F = v sqrt(c M); the row's note carries it.
    row = t["rows"][0]
    assert row["factor"] == "phi7" and row["standard_lo"] == 1.25
    assert f"rigid-body force {0.63 * math.sqrt(2e5 * 5400):.6g} N" in row["note"]


def test_crane_release_during_a_run_equals_the_cli():
    # The φ3 case of the grab example releases 4 t at 1.2 s while hoisting; the release is a field of
    # the model's crane section, so an override moves it (the row's case says when), and the Python
    # table equals the CLI's.
    path = example("crane/grab-release.yaml")
    t = machdyn.crane(machdyn.load(path))
    assert t == cli_json("crane", path, "--json", "-o", str(__import__("tempfile").mkdtemp()))
    phi3 = [r for r in t["rows"] if r["factor"] == "phi3"][0]
    assert "at t = 1.2 s while hoisting" in phi3["case"]
    moved = machdyn.crane(machdyn.load(
        path, set={"crane.release": "{mass: 4 t, kind: rapid, time: 1.5 s, while: hoisting}"}))
    assert "at t = 1.5 s while hoisting" in [r for r in moved["rows"] if r["factor"] == "phi3"][0]["case"]
    # The model's own run: the release in the events, its kinetic energy in the books.
    r = machdyn.simulate(machdyn.load(path))
    assert any(e["kind"] == "release" and e["t"] == 1.2 for e in r.summary["events"])
    assert r.summary["energy"]["released_kinetic_J"] > 0


def test_moved_elements_show_the_users_bodies():
    # An ideal gear slaves the gearbox to the motor (rho = 1/4): compile moves the shaft's first end
    # and the load onto the motor (ratio 2/rho = 8, value 40 rho = 10); the model lists them as written.
    m = machdyn.loads("""
bodies: {motor: {inertia: 2}, gearbox: {inertia: 1}, drum: {inertia: 5}}
links:
  g: {type: ideal-gear, between: [motor, gearbox], ratio: 4}
  shaft: {type: spring, between: [gearbox, drum], ratio: 2, stiffness: 1e4}
loads: {M: {type: constant, body: gearbox, value: 40}}
""")
    assert [b["name"] for b in m.bodies] == ["motor", "drum"]
    shaft = next(l for l in m.links if l["name"] == "shaft")
    assert shaft["between"] == ("gearbox", "drum")
    assert shaft["ratio"] == pytest.approx(2.0, rel=1e-15)
    assert m.loads[0]["body"] == "gearbox"
    assert m.loads[0]["value"] == pytest.approx(40.0, rel=1e-15)
