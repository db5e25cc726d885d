"""The swinging load's summary in Python (docs/sway.md, "Summary values"): r.summary["sway"] against
the linear pendulum's closed form, equal to the CLI's summary.json; a model without a spatial rope has
none."""
import json
import math

import pytest

import machdyn
from conftest import run_cli

G = 9.80665

# A trolley accelerated at a for T_a, then coasting, carries a load m on a rope of hanging length ℓ
# (ω² = g/ℓ): the relative swing ξ = −(a/ω²)(1 − cos ωt) up to T_a leaves the amplitude
# (2a/ω²)|sin(ω T_a/2)| (also the largest swing, since 1 − cos x ≤ 2|sin(x/2)|), so the largest and
# the residual sway are (2a/g)|sin(ω T_a/2)|, the largest horizontal force m g times it, the rigid
# force m a and the horizontal dynamic factor 2|sin(ω T_a/2)|.
M_LOAD, L0, EA, A, TA = 1000.0, 10.0, 1e9, 0.02, 2.0
MOVE = {
    "name": "trolley move",
    "bodies": {
        "trolley": {"type": "translational", "mass": 5000,
                    "motion": {"acceleration": {"type": "table", "points": [[0, A], [TA, A], [TA, 0], [100, 0]]}}},
        "load": {"type": "point-mass", "mass": M_LOAD, "axes": ["x", "z"]},
    },
    "links": {"rope": {"type": "spatial-rope", "load": "load", "trolley": "trolley", "length": L0, "EA": EA,
                       "sway_after": TA}},
    "simulation": {"t_end": 12.0, "dt_out": 1e-3, "rtol": 1e-10, "atol": 1e-12, "integrator": "dopri5"},
}


def test_sway_summary_of_a_move_follows_the_closed_form():
    r = machdyn.simulate(machdyn.from_dict(MOVE))
    ell = L0 + M_LOAD * G / (EA / L0)
    w = math.sqrt(G / ell)
    theta = 2 * A / G * abs(math.sin(w * TA / 2))
    s = r.summary["sway"]["rope"]
    assert s["max_sway_rad"] == pytest.approx(theta, rel=1e-3)
    assert s["residual_after_s"] == TA
    assert s["residual_sway_rad"] == pytest.approx(theta, rel=1e-3)
    assert s["max_horizontal_force_N"] == pytest.approx(M_LOAD * G * theta, rel=1e-3)
    assert s["rigid_force_N"] == pytest.approx(M_LOAD * A, rel=1e-6)
    assert s["horizontal_dynamic_factor"] == pytest.approx(2 * abs(math.sin(w * TA / 2)), abs=1e-3)
    assert r["rope.sway_x_rad"].shape == r.t.shape


def test_sway_summary_equals_the_cli(tmp):
    path = tmp / "move.yaml"  # JSON is YAML
    path.write_text(json.dumps(MOVE))
    run_cli("simulate", path, "-o", tmp / "out", "--quiet")
    cli = json.load(open(tmp / "out" / "summary.json"))
    py = machdyn.simulate(machdyn.load(str(path))).summary
    assert py["sway"] == cli["sway"]


def test_a_model_without_a_spatial_rope_has_no_sway():
    model = {"bodies": {"a": {"inertia": 1.0}}, "loads": {"M": {"type": "constant", "body": "a", "value": 1.0}},
             "simulation": {"t_end": 0.1, "dt_out": 0.01}}
    assert "sway" not in machdyn.simulate(machdyn.from_dict(model)).summary


def test_modes_name_the_pendulum_and_the_stretch_mode():
    """A load m on a free trolley M: one pendulum mode at ω² = (g/ℓ)(1 + m/M) (ℓ = L0 + m g/c the
    hanging length, c = EA/L0), one rope-stretch mode at c/m, the kinds equal to the CLI's
    `modes --json`; a model without a spatial rope has drive-line modes only (docs/sway.md,
    "Pendulum modes")."""
    free = dict(MOVE, bodies={"trolley": {"type": "translational", "mass": 5000},
                              "load": {"type": "point-mass", "mass": M_LOAD, "axes": ["x", "z"]}})
    md = machdyn.modes(machdyn.from_dict(free))
    c = EA / L0
    ell = L0 + M_LOAD * G / c
    assert md.kinds == ["pendulum", "rope stretch"]
    assert md.pendulum_modes == [0]
    assert md.omega[0] ** 2 == pytest.approx(G / ell * (1 + M_LOAD / 5000), rel=1e-9)
    assert md.omega[1] ** 2 == pytest.approx(c / M_LOAD, rel=1e-9)
    shares = md.summary["shapes"][0]["energy_shares"]
    assert shares["sway"] == pytest.approx(5000 / (5000 + M_LOAD), rel=1e-6)
    assert "pendulum" in md._repr_html_()
    chain = machdyn.from_dict({"name": "two masses", "bodies": {"a": {"type": "translational", "mass": 1},
                                                                 "b": {"type": "translational", "mass": 1}},
                               "links": {"s": {"type": "spring", "between": ["a", "b"], "stiffness": 100}}})
    plain = machdyn.modes(chain)
    assert plain.kinds == ["drive line"] and plain.pendulum_modes == []
    assert "kinds" not in plain.summary
