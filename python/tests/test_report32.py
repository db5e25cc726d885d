"""Issue 32, item 14: the modes' topology named and selectable, the topology words of end stops,
and machdyn.report() as the CLI's report (same pipeline: the frequency response section, the same
options) writing a file whose mode follows the umask."""
import math
import os
import stat

import pytest

import machdyn
from conftest import example, run_cli

HANGING = """
gravity: 9.81 m/s^2
bodies:
  drum: {inertia: 40 kg*m^2}
  hook: {type: translational, mass: 4 t, vertical: up}
links:
  rope: {type: rope, between: [drum, hook], ratio: 4 rad/m, stiffness: 4e6 N/m}
loads:
  M: {type: constant, body: drum, value: 0 N*m}
stops:
  floor: {body: hook, min: 0 m}
simulation: {t_end: 0.1 s}
"""


def test_modes_name_their_topology_and_offer_the_hanging_one(tmp):
    path = tmp / "hanging.yaml"
    path.write_text(HANGING)
    m = machdyn.load(path)
    modes = machdyn.modes(m)
    # The initial state: the hook on the floor, the rope slack — named, not silent.
    assert modes.topology and modes.topology in repr(modes)
    assert modes.topology == modes.topologies[0] and len(modes.topologies) > 1
    hanging = modes.select("floor=open, rope=closed")
    # The hanging load: drum J on the rope to the hook m, ω² = c (1/(J i²) + 1/m) (J reduced to the hook).
    c, J, i, mh = 4e6, 40.0, 4.0, 4000.0
    assert hanging.omega[-1] == pytest.approx(math.sqrt(c * (1 / (J * i * i) + 1 / mh)), rel=1e-10)
    assert "floor=released" in hanging.topology
    # An index into the listed topologies gives that one's arrays (the first: these).
    assert modes.select(0).omega.tolist() == modes.omega.tolist()
    last = modes.select(len(modes.topologies) - 1)
    assert last.topology == modes.topologies[-1]
    with pytest.raises(IndexError):
        modes.select(len(modes.topologies))


def test_stop_words_open_and_closed_and_a_listing_error(tmp):
    path = tmp / "hanging.yaml"
    path.write_text(HANGING)
    m = machdyn.load(path)
    assert machdyn.modes(m, topology="floor=open").topology == machdyn.modes(m, topology="floor=released").topology
    with pytest.raises(machdyn.InputError, match=r"closed \(at the stop\), open \(off it\)"):
        machdyn.modes(m, topology="floor=lifted")


def test_report_has_the_cli_sections_and_follows_the_umask(tmp):
    path = example("hoist-3mass.yaml")
    old = os.umask(0o002)
    try:
        out = machdyn.report(machdyn.load(path), tmp / "py.html")
    finally:
        os.umask(old)
    assert stat.S_IMODE(os.stat(out).st_mode) == 0o664
    py = open(out, encoding="utf-8").read()
    cli_out = tmp / "cli.html"
    run_cli("report", path, "--quiet", "-o", cli_out)
    cli = open(cli_out, encoding="utf-8").read()
    # The frequency response section (its figures) is in both, from the same input.
    for page in (py, cli):
        assert "frequency response |H| from" in page
    assert py.count('data-figure="') == cli.count('data-figure="')


def test_report_options_as_the_cli(tmp):
    m = machdyn.load(example("hoist-3mass.yaml"))
    out = machdyn.report(m, tmp / "o.html", links=["c2"], frf_input="I1", frf_outputs=["c2.load"],
                         frf_band_hz=(1, 200))
    html = open(out, encoding="utf-8").read()
    assert "link loads (c2)" in html and "from I1" in html
    with pytest.raises(machdyn.InputError, match="frf_input"):
        machdyn.report(m, tmp / "bad.html", frf_input="nothing")
    assert not (tmp / "bad.html").exists()


def test_links_errors_name_the_python_argument(tmp):
    # Issue 32 item 5: a link the model does not have is an error at `links=` in Python (plot and
    # report), at `--links` on the command line — the same message (io/figures.hpp chosen_links).
    import matplotlib
    matplotlib.use("Agg")
    path = example("hoist-3mass.yaml")
    m = machdyn.load(path)
    r = machdyn.simulate(m)
    with pytest.raises(machdyn.InputError) as e:
        r.plot(links=["c2", "nothing"])
    assert "links=" in str(e.value) and "--links" not in str(e.value)
    assert "no link 'nothing'; the model's links: c1, c2" in str(e.value)
    with pytest.raises(machdyn.InputError) as e:
        machdyn.report(m, tmp / "bad.html", links=["nothing"])
    assert "links=" in str(e.value) and "--links" not in str(e.value)
    assert not (tmp / "bad.html").exists()
    cli = run_cli("report", path, "--quiet", "-o", tmp / "cli.html", "--links", "nothing", check=False)
    assert cli.returncode == 2 and "--links" in cli.stderr and "no link 'nothing'; the model's links: c1, c2" in cli.stderr
    # A known name draws that link only (its load and its static marker).
    assert len(r.plot(links=["c2"]).get_lines()) == 2
