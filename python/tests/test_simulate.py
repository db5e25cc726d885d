"""machdyn.simulate: closed forms, and equality with the CLI to the last bit."""
import json
import math
import threading

import numpy as np
import pytest

import machdyn
from conftest import cli_json, example, run_cli

# Two inertias joined by one undamped spring, a constant torque M on I1 from rest. With
# ω² = c (I1 + I2)/(I1 I2), the relative coordinate δ = φ1 − φ2 obeys δ'' + ω² δ = M/I1, so
#   F(t) = c δ = M I2/(I1 + I2) · (1 − cos ω t):  peak 2 M I2/(I1 + I2) at t = π/ω.
I1, I2, C, M = 0.8, 0.45, 2.4e4, 450.0
OMEGA = math.sqrt(C * (I1 + I2) / (I1 * I2))
TWO_MASS = {
    "name": "two-mass",
    "bodies": {"I1": {"type": "rotational", "inertia": I1}, "I2": {"type": "rotational", "inertia": I2}},
    "links": {"c1": {"type": "spring", "between": ["I1", "I2"], "stiffness": C}},
    "loads": {"M": {"type": "constant", "body": "I1", "value": M}},
    "simulation": {"t_end": 0.1, "dt_out": 1e-4, "rtol": 1e-11, "atol": 1e-13, "integrator": "dopri5"},
}


def test_two_mass_link_load_follows_the_closed_form():
    r = machdyn.simulate(machdyn.from_dict(TWO_MASS))
    exact = M * I2 / (I1 + I2) * (1 - np.cos(OMEGA * r.t))
    np.testing.assert_allclose(r["c1.load"], exact, rtol=0, atol=1e-6 * M)
    s = r.summary["links"]["c1"]
    assert s["max"] == pytest.approx(2 * M * I2 / (I1 + I2), rel=1e-9)
    assert s["t_max"] == pytest.approx(math.pi / OMEGA, rel=1e-8)


def test_two_mass_modes_follow_the_closed_form():
    modes = machdyn.modes(machdyn.from_dict(TWO_MASS))
    assert modes.rigid_body_modes == 1
    assert modes.omega == pytest.approx([OMEGA], rel=1e-12)
    # Mass-normalized: φᵀ M φ = 1.
    phi = modes.shapes[:, 0]
    assert phi @ np.diag([I1, I2]) @ phi == pytest.approx(1.0, rel=1e-12)


def test_set_override_changes_the_closed_form():
    m = machdyn.from_dict(TWO_MASS, set={"c1.stiffness": "9.6e4 N*m/rad"})  # 4 c: twice ω
    r = machdyn.simulate(m)
    assert r.summary["links"]["c1"]["t_max"] == pytest.approx(math.pi / (2 * OMEGA), rel=1e-8)
    assert m.links[0]["stiffness"] == 9.6e4


def test_hoist_equals_the_cli_to_the_last_bit(tmp):
    path = example("hoist-3mass.yaml")
    run_cli("simulate", path, "-o", tmp, "--quiet")
    r = machdyn.simulate(machdyn.load(path))
    cli = json.load(open(tmp / "summary.json"))
    py = r.summary
    # Wall time is measured, not computed: everything else is equal.
    for s in (cli, py):
        s["solver"].pop("wall_time_s")
    assert py == cli
    assert r.to_csv() == (tmp / "timeseries.csv").read_text()
    # The arrays hold the same doubles as the CSV's 17 digits.
    header, *rows = (tmp / "timeseries.csv").read_text().splitlines()
    table = np.array([[float(x) for x in row.split(",")] for row in rows])
    assert header.split(",") == r.columns
    for k, name in enumerate(r.columns):
        assert np.array_equal(r[name], table[:, k]), name


@pytest.mark.parametrize("name", ["travel-start.yaml", "crank-slider.yaml", "crank-slider-brake.yaml",
                                  "rolling-wheel-1.yaml", "walking-drive.yaml", "chain-20.yaml"])
def test_every_kind_of_model_equals_the_cli(tmp, name):
    # Smooth and event-driven runs, machines with variable inertia, a stepwise gear drive, a chain.
    run_cli("simulate", example(name), "-o", tmp, "--quiet")
    r = machdyn.simulate(machdyn.load(example(name)))
    cli = json.load(open(tmp / "summary.json"))
    for s in (cli, r.summary):
        s["solver"].pop("wall_time_s")
    assert r.summary == cli
    assert r.to_csv() == (tmp / "timeseries.csv").read_text()


def test_set_and_case_equal_the_cli(tmp):
    path = example("hoist-modes.yaml")
    m = machdyn.load(path)
    case = m.cases[1]
    run_cli("simulate", path, "-o", tmp, "--quiet", "--case", case, "--set", "c1.stiffness=3e4 N*m/rad")
    r = machdyn.simulate(machdyn.load(path, set={"c1.stiffness": "3e4 N*m/rad"}), case=case)
    cli = json.load(open(tmp / case / "summary.json"))  # a case writes to OUT/CASE (README, output folders)
    for s in (cli, r.summary):
        s["solver"].pop("wall_time_s")
    assert r.summary == cli
    assert r.model.case == case


def test_loads_of_the_file_text_equals_load():
    path = example("hoist-3mass.yaml")
    a = machdyn.simulate(machdyn.load(path))
    b = machdyn.simulate(machdyn.loads(open(path).read()))
    assert np.array_equal(a["c1.load"], b["c1.load"])


def test_arrays_are_read_only_views_that_outlive_the_result():
    r = machdyn.simulate(machdyn.from_dict(TWO_MASS))
    x = r["c1.load"]
    with pytest.raises(ValueError):
        x[0] = 1.0
    del r
    assert x.shape == (1001,) and math.isfinite(float(x.sum()))


def test_pandas_and_column_names():
    r = machdyn.simulate(machdyn.from_dict(TWO_MASS))
    df = r.to_pandas()
    assert list(df.columns) == r.columns
    assert np.array_equal(df["t_s"].to_numpy(), r.t)
    assert "c1.load" in r and "c1.load_N_m" in r and "nothing" not in r
    with pytest.raises(KeyError):
        r["nothing"]


def test_travel_start_gap_closes_when_the_closed_form_says():
    # Stage 1 of paper 001: m1 alone under P takes up the gap Δ: Δ = P t²/(2 m1).
    r = machdyn.simulate(machdyn.load(example("travel-start.yaml")))
    first = next(e for e in r.events if e["kind"] != "initial")
    assert first["kind"] == "gap_closed" and first["element"] == "c"
    assert first["t_s"] == pytest.approx(math.sqrt(2 * 0.004 * 3000 / 6800), rel=1e-9)
    assert len(r.events) > 5  # the self-oscillation: slip and stick again


def test_travel_start_equals_the_cli(tmp):
    path = example("travel-start.yaml")
    cli = cli_json("simulate", path, "-o", tmp, "--quiet", "--json")
    r = machdyn.simulate(machdyn.load(path))
    for s in (cli, r.summary):
        s["solver"].pop("wall_time_s")
    assert r.summary == cli


def test_threads_give_the_serial_results():
    m = machdyn.load(example("travel-start.yaml"))
    serial = machdyn.simulate(m)["c.load"].copy()
    out = [None] * 4
    def run(k):
        out[k] = machdyn.simulate(m)["c.load"]
    threads = [threading.Thread(target=run, args=(k,)) for k in range(4)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    for x in out:
        assert np.array_equal(x, serial)


def test_the_gil_is_released_during_a_run():
    # With the GIL held for the whole run, this thread could not tick between the run's start and
    # end; released, it ticks all along (the longest pause is far below the run's duration).
    import time
    # The undamped hoist oscillates for ever: ~0.5 ms of CPU per simulated second.
    m = machdyn.load(example("hoist-3mass.yaml"), set={"simulation.t_end": "600 s", "simulation.dt_out": "1 s"})
    done = threading.Event()
    span = {}
    def run():
        span["start"] = time.perf_counter()
        machdyn.simulate(m)
        span["end"] = time.perf_counter()
        done.set()
    ticks = []
    worker = threading.Thread(target=run)
    worker.start()
    while not done.is_set():
        ticks.append(time.perf_counter())
        time.sleep(0.001)
    worker.join()
    duration = span["end"] - span["start"]
    inside = [t for t in ticks if span["start"] <= t <= span["end"]]
    gaps = np.diff([span["start"], *inside, span["end"]])
    assert duration > 0.05, "the run is too short to tell"
    assert gaps.max() < 0.5 * duration, (gaps.max(), duration)


def test_rich_display_and_plot():
    import matplotlib
    matplotlib.use("Agg")
    r = machdyn.simulate(machdyn.load(example("hoist-3mass.yaml")))
    html = r._repr_html_()
    assert "<table>" in html and "c1" in html and "c2" in html
    ax = r.plot()
    assert len(ax.get_lines()) == 4  # two loads and their static markers
    assert "Three-mass hoist" in repr(r) and "c1: max" in repr(r)


def test_help_documents_every_function_with_units():
    for f in (machdyn.load, machdyn.loads, machdyn.from_dict, machdyn.simulate, machdyn.modes, machdyn.energy,
              machdyn.gears, machdyn.sweep, machdyn.report, machdyn.Result, machdyn.Modes):
        assert f.__doc__ and len(f.__doc__) > 80, f
    assert "(s)" in machdyn.simulate.__doc__ and "N*m" in machdyn.simulate.__doc__
    assert "rad/s" in machdyn.modes.__doc__ and "Hz" in machdyn.modes.__doc__
    assert "kg*m^2" in machdyn.energy.__doc__ and "rad" in machdyn.energy.__doc__
    assert "mm" in machdyn.gears.__doc__


def test_speed_drive_case_equals_the_cli(tmp):
    # A model with a drive's own states (speed drive: integral and lagged torque) through the module.
    path = example("drives.yaml")
    run_cli("simulate", path, "-o", tmp, "--quiet", "--case", "inverter")
    m = machdyn.load(path)
    r = machdyn.simulate(m, case="inverter")
    cli = json.load(open(tmp / "inverter" / "summary.json"))
    for s in (cli, r.summary):
        s["solver"].pop("wall_time_s")
    assert r.summary == cli
    assert r.to_csv() == (tmp / "inverter" / "timeseries.csv").read_text()
    assert "drive.torque_N_m" in r.columns
    assert [(d["name"], d["type"], d["body"], d["states"]) for d in m.with_case("inverter").drives] == \
        [("drive", "speed-drive", "I1", 2)]


def test_extra_outputs_equal_the_cli(tmp):
    """--outputs all: the same columns and doubles as the CLI's timeseries.csv (no logic in Python)."""
    path = example("crank-slider-brake.yaml")
    run_cli("simulate", path, "-o", tmp, "--quiet", "--outputs", "all")
    r = machdyn.simulate(machdyn.load(path), outputs=["all"])
    assert r.to_csv() == (tmp / "timeseries.csv").read_text()
    assert any(c.endswith(".heat_J") for c in r.columns)
    assert any(c.endswith(".acceleration_rad_s2") for c in r.columns)
    df = r.to_pandas()
    assert list(df.columns) == r.columns
    with pytest.raises(machdyn.InputError):
        machdyn.simulate(machdyn.load(path), outputs=["temperature"])


# A block (1 kg, F_s = 10 N, F_k = 6 N) pushed by P = 20 t N: it breaks away at t* = F_s/20 = 0.5 s.
BLOCK = {
    "name": "block",
    "bodies": {"a": {"type": "translational", "mass": 1.0}},
    "contacts": {"k": {"between": ["a", "ground"], "static": 10.0, "kinetic": 6.0}},
    "loads": {"P": {"type": "ramp", "body": "a", "value": 20.0, "end": 1.0}},
    "simulation": {"t_end": 1.0, "dt_out": 0.01, "rtol": 1e-10, "atol": 1e-12},
}


def test_check_true_audits_the_run_and_changes_no_number(monkeypatch, tmp):
    # check=True runs the invariant audit (docs/hybrid.md); the suite's MACHDYN_CHECK would turn it on
    # for check=False too, so it is cleared here to compare on with off.
    monkeypatch.delenv("MACHDYN_CHECK", raising=False)
    model = machdyn.from_dict(BLOCK)
    off = machdyn.simulate(model)
    on = machdyn.simulate(model, check=True)
    assert on.columns == off.columns
    for name in off.columns:
        np.testing.assert_array_equal(on[name], off[name])
    slips = [e for e in on.events if e["element"] == "k" and e["kind"] == "slip"]
    assert slips and slips[0]["t_s"] == pytest.approx(0.5, abs=1e-9)
    # The CLI's --check gives the same summary.
    checked = cli_json("simulate", "--check", "--json", "-q", "-o", tmp / "on", example("travel-start.yaml"))
    plain = cli_json("simulate", "--json", "-q", "-o", tmp / "off", example("travel-start.yaml"))
    assert checked["links"] == plain["links"] and checked["events"] == plain["events"]


# A ball dropped from h = 1 m onto a floor with restitution e = 0.5: the flights 2 v_k / g shrink by
# e and sum to the rest time t1 (1 + e)/(1 − e), t1 = √(2h/g). The bounces accumulate there (Zeno):
# the ball rests on the floor and the run says so in r.warnings (and summary.json "warnings").
def test_bouncing_ball_rests_at_the_accumulation_point_with_a_warning():
    m = machdyn.from_dict({
        "bodies": {"ball": {"type": "translational", "mass": 2, "position": 1}},
        "stops": {"floor": {"body": "ball", "min": 0, "restitution": 0.5}},
        "loads": {"G": {"type": "constant", "body": "ball", "value": -19.62}},
        "simulation": {"t_end": 2, "dt_out": 0.01, "rtol": 1e-11, "atol": 1e-12, "integrator": "dopri5"},
    })
    r = machdyn.simulate(m)
    t1 = math.sqrt(2 / 9.81)
    rest = [e for e in r.events if e["kind"] == "stick"]
    assert len(rest) == 1 and abs(rest[0]["t_s"] - 3 * t1) < 1e-9
    assert len(r.warnings) == 1 and "accumulate" in r.warnings[0]
    assert r.warnings == r.summary["warnings"]


# A flywheel I = 2 kg m^2 at 100 rad/s stopped by a brake of constant braking torque 50 N m applied at
# 0.1005 s: by hand it stops after w0 I / M = 4 s, turning w0^2 I / (2 M) = 200 rad, the brake taking
# 1/2 I w0^2 = 10 kJ at a peak power of M w0 = 5 kW; its adiabatic disc (1 kJ/K) ends 10 K warmer.
def test_brake_stop_in_the_result_follows_the_hand_calculation():
    model = {
        "name": "brake stop",
        "bodies": {"wheel": {"type": "rotational", "inertia": 2.0, "velocity": 100.0}},
        "brakes": {"disc": {"body": "wheel", "holding": "60 N*m", "braking": "50 N*m", "time": "0.1005 s",
                            "thermal": {"heat_capacity": "1 kJ/K", "ambient": "20 degC"}}},
        "simulation": {"t_end": 5.0, "dt_out": 1e-3, "rtol": 1e-11, "atol": 1e-13},
    }
    r = machdyn.simulate(machdyn.from_dict(model))
    assert r.brakes["disc"] == r.summary["brakes"]["disc"]
    assert len(r.brakes["disc"]["stops"]) == 1
    b = r.brakes["disc"]["stops"][0]
    assert b["end"] == "stuck"
    assert b["stopping_time_s"] == pytest.approx(4.0, rel=1e-8)
    assert b["travel"]["wheel"]["value"] == pytest.approx(200.0, rel=1e-8)
    assert b["energy_J"] == pytest.approx(1e4, rel=1e-8)
    assert b["peak_power_W"] == pytest.approx(5e3, rel=1e-8)
    assert b["temperature_end_degC"] == pytest.approx(30.0, abs=1e-6)
    assert b["temperature_rise_K"] == pytest.approx(10.0, abs=1e-6)
    assert r.brakes["disc"]["temperature_end_degC"] == pytest.approx(30.0, abs=1e-6)
