"""Error paths: InputError with every diagnostic (file:line:col), SolverError with element and time,
and no crash of the interpreter on bad input."""
import math
import subprocess
import sys

import pytest

import machdyn
from conftest import example, run_cli

BAD = """\
name: bad
bodies:
  I1: {type: rotational, inertia: -1 kg*m^2}
  I2: {type: rotational, inertia: 2 m}
links:
  c1: {type: spring, between: [I1, nowhere], stiffness: 1e4 N*m/rad}
"""


def test_every_problem_is_listed_with_its_place(tmp):
    path = tmp / "bad.yaml"
    path.write_text(BAD)
    with pytest.raises(machdyn.InputError) as e:
        machdyn.load(path)
    diags = e.value.diagnostics
    assert len(diags) >= 3
    files, lines = {d[0] for d in diags}, {d[1] for d in diags}
    assert files == {str(path)}
    assert {3, 4, 6} <= lines
    assert all(d[2] > 0 for d in diags)
    # The same lines as the CLI prints, which exits 2.
    cli = run_cli("simulate", path, "-o", tmp / "out", check=False)
    assert cli.returncode == 2
    assert str(e.value).splitlines() == cli.stderr.splitlines()
    assert isinstance(e.value, ValueError)


def test_string_sources_are_named():
    with pytest.raises(machdyn.InputError) as e:
        machdyn.loads(BAD, source="my-model")
    assert all(d[0] == "my-model" for d in e.value.diagnostics)


def test_missing_file_and_bad_yaml():
    with pytest.raises(machdyn.InputError):
        machdyn.load("/nonexistent/model.yaml")
    with pytest.raises(machdyn.InputError) as e:
        machdyn.loads("bodies: {I1: [unclosed")
    assert e.value.diagnostics[0][1] >= 1


def test_bad_overrides_and_cases():
    path = example("hoist-3mass.yaml")
    with pytest.raises(machdyn.InputError) as e:
        machdyn.load(path, set={"nothing.stiffness": 1})
    assert "--set" in e.value.diagnostics[0][0]
    with pytest.raises(machdyn.InputError):
        machdyn.load(path, set={"c1.stiffness": "3 kg"})  # wrong unit
    with pytest.raises(machdyn.InputError):
        machdyn.load(path, case="no-such-case")
    with pytest.raises(TypeError):
        machdyn.load(path, set={1: 2})
    with pytest.raises(TypeError):
        machdyn.loads(b"bytes")
    with pytest.raises(TypeError):
        machdyn.from_dict(["not", "a", "dict"])


def test_solver_error_names_element_and_time():
    m = machdyn.load(example("hoist-3mass.yaml"), set={"simulation.max_steps": 20, "simulation.integrator": "dopri5"})
    with pytest.raises(machdyn.SolverError) as e:
        machdyn.simulate(m)
    assert isinstance(e.value, RuntimeError)
    assert isinstance(e.value.element, str)
    assert 0 <= e.value.time < 0.5 and math.isfinite(e.value.time)


ODD = ["", "- a\n- b", "bodies: 3", "name: x\nbodies: {}\n", "\x00\x01",
       "bodies: {I1: {type: rotational, inertia: 1e400}}", "{" * 2000, "[" * 100000,
       "a: &x [*x]", "description: &x [*x]"]


@pytest.mark.parametrize("text", ODD)
def test_odd_input_raises_input_error_not_a_crash(text):
    # In a child interpreter, so that a crash is a failed test and not the end of the test run.
    code = ("import sys, machdyn\n"
            "try:\n    machdyn.loads(sys.stdin.read())\nexcept machdyn.InputError as e:\n"
            "    assert e.diagnostics, 'no diagnostics'\n    sys.exit(0)\n"
            "sys.exit('no InputError')\n")
    p = subprocess.run([sys.executable, "-c", code], input=text, capture_output=True, text=True, timeout=60)
    assert p.returncode == 0, p.stderr[-2000:]


def test_bad_arguments_raise_python_errors():
    m = machdyn.load(example("hoist-3mass.yaml"))
    with pytest.raises(ValueError):
        machdyn.sweep(m, vary={})
    with pytest.raises(ValueError):
        machdyn.sweep(m, vary={"c1.stiffness": "1e4:2e4:2"}, method="nope")
    with pytest.raises(machdyn.InputError):
        machdyn.sweep(m, vary={"c1.stiffness": "1e4:2e4"})  # a grid needs n
    with pytest.raises(machdyn.InputError):
        machdyn.energy(m)  # three bodies and links: no energy integral
    with pytest.raises(ValueError):
        machdyn.energy(m, points=1)
    for threads in (0, 10**6):
        with pytest.raises(ValueError):
            machdyn.sweep(m, vary={"c1.stiffness": "1e4:2e4:2"}, threads=threads)
    with pytest.raises(machdyn.InputError):
        machdyn.sweep(m, vary={"c1.stiffness": "1:2:1000000000"})
    with pytest.raises(machdyn.InputError):
        machdyn.energy(machdyn.load(example("crank-slider.yaml")), to="abc")
    with pytest.raises(machdyn.InputError):
        machdyn.gears("/nonexistent/gears.yaml")
    r = machdyn.simulate(m)
    with pytest.raises(IndexError):
        r._core.column(10**6)


@pytest.mark.parametrize("kind", ["device", "fifo", "folder", "huge"])
def test_model_files_that_are_devices_fifos_or_huge_raise_input_error(tmp, kind):
    """Not a MemoryError (/dev/zero read to the end) nor a hang (a FIFO without a writer): an
    InputError naming the file and why."""
    import os
    if kind == "device":
        path, says = "/dev/zero", "is a character device"
    elif kind == "fifo":
        path, says = str(tmp / "m.yaml"), "is a FIFO"
        os.mkfifo(path)
    elif kind == "folder":
        path, says = str(tmp), "is a folder"
    else:
        path, says = str(tmp / "big.yaml"), "more than the limit of 16 MiB"
        with open(path, "wb") as f:
            f.truncate(16 * 2**20 + 1)  # sparse
    with pytest.raises(machdyn.InputError) as e:
        machdyn.load(path)
    assert e.value.diagnostics[0][0] == path
    assert says in str(e.value)


def test_report_never_replaces_the_model_file(tmp):
    """report(m, PATH) where PATH is the model file, or a link to it, raises InputError and leaves
    the model as it was."""
    import os
    text = open(example("hoist-3mass.yaml"), encoding="utf-8").read()
    path = tmp / "model.yaml"
    path.write_text(text, encoding="utf-8")
    os.symlink(path, tmp / "link.html")
    m = machdyn.load(path)
    for target, says in ((path, "it is the input file"), (tmp / "link.html", "it is a symbolic link")):
        with pytest.raises(machdyn.InputError) as e:
            machdyn.report(m, target)
        assert says in str(e.value)
        assert path.read_text(encoding="utf-8") == text
