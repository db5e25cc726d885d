"""machdyn.rainflow on numpy arrays: the ASTM E1049 example's published counts, a sine's closed form,
and bad input; machdyn.duty equal to `machdyn duty`."""
import json

import numpy as np
import pandas as pd
import pytest

import machdyn
from conftest import run_cli


def test_astm_example_counts():
    # ASTM E1049-85 Table 4: range 3: 0.5, 4: 1.5, 6: 0.5, 8: 1.0, 9: 0.5.
    df = machdyn.rainflow(np.array([-2, 1, -3, 5, -1, 3, -4, 4, -2], dtype=float))
    assert list(df.columns) == ["range", "mean", "count", "from", "to"]
    by_range = df.groupby("range")["count"].sum().to_dict()
    assert by_range == {3.0: 0.5, 4.0: 1.5, 6.0: 0.5, 8.0: 1.0, 9.0: 0.5}


def test_sine_closed_form_and_any_array_like():
    # A sine of N periods from 0: N cycles of 2A when the residue is closed by repetition.
    n, a = 12, 2.0
    x = a * np.sin(np.linspace(0.0, 2 * np.pi * n, 400 * n + 1))
    d = machdyn.rainflow(x, residue="repeat", frame=False)
    assert np.isclose(d["count"][np.isclose(d["range"], 2 * a)].sum(), n)
    assert d["count"].sum() == n
    # A list and a float32 strided view count alike (converted to float64).
    assert machdyn.rainflow(list(x)).equals(machdyn.rainflow(x))
    y = np.repeat(x.astype(np.float32), 2)[::2]
    assert len(machdyn.rainflow(y)) == len(machdyn.rainflow(x.astype(np.float32).astype(float)))


def test_gate_drops_small_reversals():
    x = np.array([0.0, 5, 4.5, 6, -3, -2.8, 2])  # gate 0.1 · 9 = 0.9 drops the 0.5 and 0.2 dips
    assert machdyn.rainflow(x, gate=0.1).equals(machdyn.rainflow(np.array([0.0, 6, -3, 2])))


def test_bad_input():
    with pytest.raises(ValueError):
        machdyn.rainflow(np.array([1.0, np.nan]))
    with pytest.raises(ValueError):
        machdyn.rainflow(np.zeros((2, 2)))
    with pytest.raises(ValueError):
        machdyn.rainflow(np.array([1.0, 2.0]), gate=1.0)
    with pytest.raises(ValueError):
        machdyn.rainflow(np.array([1.0, 2.0]), residue="close")
    assert len(machdyn.rainflow(np.array([]))) == 0


DUTY_MODEL = """
bodies:
  A: {type: translational, mass: 1 kg}
  B: {type: translational, mass: 1.5 kg, velocity: 0.5 m/s}
links:
  ab: {type: spring-damper, between: [A, B], stiffness: 1e4 N/m, damping: 2 N*s/m}
simulation: {t_end: 0.3 s, rtol: 1e-10, atol: 1e-12}
cases:
  fast: {bodies: {B: {velocity: 0.5 m/s}}}
  slow: {bodies: {B: {velocity: 0.2 m/s}}}
"""


def test_duty_equals_the_cli(tmp_path):
    # machdyn.duty gives duty.json's figures and duty_cycles.csv's rows of `machdyn duty`, to the bit.
    model = tmp_path / "m.yaml"
    model.write_text(DUTY_MODEL)
    duty = tmp_path / "d.yaml"
    duty.write_text("operations:\n  lift: {case: fast, repeat: 3}\n  lower: {case: slow, repeat: 2}\n"
                    "sn_curve: {m: 3, delta_ref: 100, n_ref: 1e6}\n")
    links, cycles = machdyn.duty(model, duty)
    run_cli("duty", model, duty, "-o", tmp_path / "out")
    j = json.loads((tmp_path / "out" / "duty.json").read_text())
    assert list(links.index) == ["ab"]
    for key in ("cycles", "largest_range", "equivalent_range", "s", "damage", "k_m", "p_max", "spectrum_class",
                "stress_history_class",
                "mechanism_group"):
        assert links.loc["ab", key] == j["links"][0][key]
    assert links.attrs["duty"]["running_hours"] == j["running_hours"]
    assert links.attrs["duty"]["utilization_class"] == j["utilization_class"] == "T0"
    csv = pd.read_csv(tmp_path / "out" / "duty_cycles.csv", float_precision="round_trip")
    assert csv.equals(cycles)
    # A bad duty: located.
    bad = tmp_path / "bad.yaml"
    bad.write_text("operations:\n  lift: {case: heavy, repeat: 1}\n")
    with pytest.raises(machdyn.InputError) as e:
        machdyn.duty(model, bad)
    assert "bad.yaml:2:" in str(e.value)
