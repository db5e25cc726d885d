"""Bounds of what a model may hold, from Python (issue 28): values no double can carry are located
InputErrors — NaN and infinity in a dict, a dict nested deeper than a model file may be, a
subnormal inertia, a heat capacity whose temperature leaves the doubles (a SolverError naming the
brake) — never a bare ValueError, a RecursionError or `inf` in the results."""
import copy
import math

import pytest

import machdyn

BASE = {
    "bodies": {"I1": {"type": "rotational", "inertia": 1.0}},
    "links": {"c1": {"type": "spring", "between": ["I1", "ground"], "stiffness": 100.0}},
    "simulation": {"t_end": 0.01},
}


def with_inertia(value):
    d = copy.deepcopy(BASE)
    d["bodies"] = {"I1": {"type": "rotational", "inertia": value}}
    return d


@pytest.mark.parametrize("value", [math.nan, math.inf, -math.inf])
def test_non_finite_floats_are_located_input_errors(value):
    with pytest.raises(machdyn.InputError) as e:
        machdyn.from_dict(with_inertia(value), source="my-dict")
    (where, line, column, message), = e.value.diagnostics
    assert where == "my-dict bodies.I1.inertia"
    assert (line, column) == (0, 0)
    assert "not a finite number" in message
    assert str(e.value) == f"my-dict bodies.I1.inertia: error: {message}"
    # In a list too, with the item's index.
    d = with_inertia(1.0)
    d["links"]["c1"]["between"] = ["I1", value]
    with pytest.raises(machdyn.InputError) as e:
        machdyn.from_dict(d)
    assert e.value.diagnostics[0][0] == "<dict> links.c1.between[1]"


def test_a_dict_deeper_than_a_model_file_is_an_input_error():
    deep = inner = {}
    for _ in range(5000):
        inner["x"] = {}
        inner = inner["x"]
    with pytest.raises(machdyn.InputError) as e:
        machdyn.from_dict({"bodies": deep})
    where = e.value.diagnostics[0][0]
    assert where.startswith("<dict> bodies.x.x")
    assert f"more than {machdyn._machdyn.spec_max_depth} levels" in e.value.diagnostics[0][3]
    # A dict that contains itself is as deep as that.
    loop = {"bodies": {}}
    loop["bodies"]["self"] = loop
    with pytest.raises(machdyn.InputError):
        machdyn.from_dict(loop)
    # Within the limit the dict reaches the reader (and is refused there as a model, not by depth).
    shallow = inner = {}
    for _ in range(machdyn._machdyn.spec_max_depth - 2):
        inner["x"] = {}
        inner = inner["x"]
    with pytest.raises(machdyn.InputError) as e:
        machdyn.from_dict({"bodies": shallow})
    assert "the limit of a model file" not in str(e.value)


def test_a_subnormal_inertia_is_out_of_range():
    with pytest.raises(machdyn.InputError) as e:
        machdyn.from_dict(with_inertia(5e-324))
    assert "out of range" in str(e.value)
    with pytest.raises(machdyn.InputError):
        machdyn.loads("bodies:\n  I1: {type: rotational, inertia: 5e-324}\n")
    assert machdyn.from_dict(with_inertia(1e-300)).bodies


def test_a_temperature_beyond_the_doubles_names_the_brake():
    # 1 kg m^2 at 10 rad/s braked by 10 N m: 17.98 J of heat make T = Q / (1e-307 J/K) overflow at
    # t = 0.1997 s (tests/analysis/failure_names_test.cpp derives it).
    m = machdyn.from_dict({
        "bodies": {"I1": {"type": "rotational", "inertia": 1.0, "velocity": 10.0}},
        "brakes": {"B": {"body": "I1", "holding": 10.0, "braking": 10.0, "time": 0.0,
                         "thermal": {"heat_capacity": 1e-307, "ambient": "20 degC"}}},
        "simulation": {"t_end": 2.0},
    })
    with pytest.raises(machdyn.SolverError) as e:
        machdyn.simulate(m)
    assert e.value.element == "B"
    assert 0.1997 <= e.value.time < 1.0


def test_without_a_simulation_section_the_defaults_and_overrides_hold():
    d = {k: copy.deepcopy(v) for k, v in BASE.items() if k != "simulation"}
    m = machdyn.from_dict(d, set={"simulation.t_end": 2.0})
    r = machdyn.simulate(m)
    assert len(r.t) == 1001
    assert r.t[-1] == 2.0
