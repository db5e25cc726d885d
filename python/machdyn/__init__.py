"""machdyn: dynamics of machine drives (cranes, hoists, travel drives, crank machines, non-circular
gears) from Python.

A thin layer over the C++ library, calling the same functions as the ``machdyn`` command line, so
results are equal to the CLI's to the last bit::

    import machdyn
    m = machdyn.load("examples/hoist-3mass.yaml", set={"c1.stiffness": "3e4 N*m/rad"})
    r = machdyn.simulate(m)
    r.t, r["c1.load"]          # numpy arrays: s, N*m
    r.summary                  # the dict of summary.json
    r.to_pandas(); r.plot()
    machdyn.modes(m).frequencies_hz
    machdyn.sweep(m, vary={"c1.stiffness": "1e4:5e4:5"}, threads=2)   # a pandas DataFrame

Every quantity is SI (rad, m, s, kg, N, N*m); column and key names carry the unit. Bad input raises
:class:`InputError` (every problem, with file:line:col); a numerical failure :class:`SolverError`
(the element and the time). Runs release the GIL and may run in several threads at once.
"""
from __future__ import annotations

import json as _json
import math as _math
import os as _os
import tempfile as _tempfile
from typing import Iterable, Mapping

from . import _machdyn
from ._result import Modes, Result, _Model

__version__ = _machdyn.__version__
__all__ = ["load", "loads", "from_dict", "simulate", "modes", "energy", "crane", "gears", "sweep", "report", "rainflow", "duty",
           "InputError", "SolverError", "Model", "Result", "Modes"]

Model = _Model

#: Bad input (a model file, a string, an override). ``e.diagnostics`` lists every problem as
#: ``(file, line, column, message)`` tuples (line and column 0 when the place is not in a file);
#: ``str(e)`` has one ``file:line:col: error: message`` line each. A subclass of ValueError.
InputError = _machdyn.InputError
#: A numerical failure during a run: ``e.element`` (body, link or load name) and ``e.time`` (s).
#: A subclass of RuntimeError.
SolverError = _machdyn.SolverError


def _sets(set_: Mapping[str, object] | Iterable[str] | None) -> list[str]:
    """``{"c1.stiffness": "3e4 N*m/rad"}`` or ``["c1.stiffness=3e4"]`` → the CLI's ``--set`` strings."""
    if set_ is None:
        return []
    if isinstance(set_, Mapping):
        out = []
        for k, v in set_.items():
            if not isinstance(k, str):
                raise TypeError(f"set: keys are NAME.FIELD strings, not {type(k).__name__}")
            out.append(f"{k}={_value_text(v)}")
        return out
    if isinstance(set_, str):
        return [set_]
    return [str(s) for s in set_]


def _value_text(v: object) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, float):
        return repr(v)  # shortest text that reads back to the same double
    if isinstance(v, (list, tuple, dict)):
        return _json.dumps(v)  # YAML reads JSON: tables like [[0, 0], [1, 5]]
    return str(v)


def load(path: str | _os.PathLike, set: Mapping[str, object] | Iterable[str] | None = None,
         case: str | None = None) -> Model:
    """Reads and compiles a model file (YAML, docs/model-files.md), as ``machdyn simulate PATH``.

    path: the model file.
    set:  overrides ``{"NAME.FIELD": value}`` (a value may carry its unit: ``"3e4 N*m/rad"``; a
          number is taken in SI) or a list of ``"NAME.FIELD=VALUE"`` strings, as ``--set``.
    case: a load case of the file's ``cases:`` (as ``--case NAME``), applied before ``set``.
    Raises InputError with every problem of the file and the overrides.
    """
    return _Model(_machdyn.load_file(_os.fspath(path), _sets(set), case or ""))


def loads(text: str, set: Mapping[str, object] | Iterable[str] | None = None, case: str | None = None,
          source: str = "<string>") -> Model:
    """Compiles a model from YAML text; ``source`` names it in error messages. See :func:`load`."""
    if not isinstance(text, str):
        raise TypeError(f"loads: expected the YAML text as str, not {type(text).__name__}")
    return _Model(_machdyn.load_text(text, source, _sets(set), case or ""))


def from_dict(spec: Mapping, set: Mapping[str, object] | Iterable[str] | None = None, case: str | None = None,
              source: str = "<dict>") -> Model:
    """Compiles a model from a dict with the layout of a model file (``{"bodies": {...}, ...}``).
    Values may be numbers (SI) or strings with units. See :func:`load`."""
    if not isinstance(spec, Mapping):
        raise TypeError(f"from_dict: expected a dict, not {type(spec).__name__}")
    _check_dict(spec, source)
    # JSON is YAML: the dict goes through the same reader as a file.
    return loads(_json.dumps(spec, indent=1, allow_nan=False), set=set, case=case, source=source)


def _input_error(where: str, message: str) -> InputError:
    """An InputError as the C++ core raises it: one diagnostic at ``where`` (no line in a file)."""
    e = InputError(f"{where}: error: {message}")
    e.diagnostics = [(where, 0, 0, message)]
    return e


def _check_dict(spec: Mapping, source: str) -> None:
    """What the JSON text of a dict cannot carry, as located InputErrors (``<dict> bodies.I1.inertia``):
    NaN and infinity (JSON has no such numbers), and nesting deeper than the model reader's limit
    (``_machdyn.spec_max_depth``; a deep or self-containing dict would otherwise exhaust Python's
    recursion). Walked without recursion."""
    limit = _machdyn.spec_max_depth
    todo = [(spec, "", 1)]
    while todo:
        node, path, depth = todo.pop()
        where = f"{source} {path}" if path else source
        if depth > limit:
            raise _input_error(where, f"nested more than {limit} levels deep (the limit of a model file)")
        if isinstance(node, Mapping):
            todo.extend((v, f"{path}.{k}" if path else str(k), depth + 1) for k, v in node.items())
        elif isinstance(node, (list, tuple)):
            todo.extend((v, f"{path}[{i}]", depth + 1) for i, v in enumerate(node))
        elif isinstance(node, float) and not _math.isfinite(node):
            raise _input_error(where, f"{node!r} is not a finite number")


def simulate(model: Model, case: str | None = None, outputs: list[str] | None = None, check: bool = False) -> Result:
    """Simulates the model with its ``simulation:`` settings, as ``machdyn simulate`` does.

    case: run this load case of the model's file instead (as ``--case NAME``).
    outputs: extra column groups, as ``--outputs``: ``"deflection"``, ``"acceleration"``,
             ``"power"``, ``"heat"`` or ``"all"`` (docs/model-files.md, "Outputs").
    Returns a :class:`Result`: ``r.t`` (s), ``r["c1.load"]`` (N*m or N), every series as a numpy
    array, ``r.summary`` (the summary.json dict), ``r.events`` (mode events of an event-driven run).
    check: audit the run against the documented laws, as ``--check`` (docs/hybrid.md, "The
           invariant audit"); a violation raises SolverError naming the invariant, the element,
           the time and the values. Also on with the environment variable MACHDYN_CHECK=1.
    Raises SolverError (element, time) on a numerical failure. The GIL is released during the run.
    """
    m = model.with_case(case) if case else model
    return Result(_machdyn.simulate(m._core, list(outputs or []), bool(check)), m)


def modes(model: Model, topology: str | None = None) -> Modes:
    """Natural frequencies and mass-normalized mode shapes (K φ = ω² M φ), as ``machdyn modes``.

    topology: the mode of each gap, contact and brake, as ``machdyn modes --topology``
              (e.g. ``"c=closed, adhesion=stuck, W=slip+"``; docs/modes.md). Default: every
              topology the model can be in, listed in ``summary["topologies"]``.
    Returns :class:`Modes`: ``omega`` (rad/s), ``frequencies_hz`` (Hz), ``shapes`` (bodies × modes,
    mass-normalized) of the named (or the first listed: the initial state's) topology, named by
    ``Modes.topology``; ``summary`` (the dict of ``machdyn modes --json``: each topology's
    frequencies, shapes and damped modes); ``Modes.select(...)`` gives another topology's.
    Raises InputError for an unknown element or mode word (the message lists the element's words).
    """
    text, omega, shapes = _machdyn.modes(model._core, "" if topology is None else str(topology))
    return Modes(_json.loads(text), omega, shapes, model)


def energy(model: Model, to: str | float | None = None, points: int = 201, delta: float | None = None,
           mean_speed: str | float | None = None) -> dict:
    """Energy integral ω(q) of a 1-DOF machine (one body, no links), as ``machdyn energy --json``.

    to:         end of the scan in the sweep coordinate (β for the rolling wheel, q otherwise), rad;
                a string may carry a unit ("720 deg"). Default: one period or 2π.
    points:     rows of the ω(q) table (3 … 1e6).
    delta:      target coefficient of speed fluctuation (ωmax − ωmin)/ωmean: adds ``steady``
                (steady running and the flywheel inertia, kg*m^2, that brings δ to it).
    mean_speed: mean speed for ``delta``, rad/s (default: the body's initial speed).
    Returns the JSON dict; ``table`` holds the columns q (rad), omega (rad/s), I (kg*m^2).
    Raises InputError for a model without such an integral (time-dependent loads, links).
    """
    if not 3 <= int(points) <= 1_000_000:
        raise ValueError("points: expected 3 … 1000000")
    if delta is not None and not delta > 0:
        raise ValueError("delta: expected a positive number")
    return _json.loads(_machdyn.energy(model._core, "" if to is None else _value_text(to), int(points),
                                       float(delta or 0.0), "" if mean_speed is None else _value_text(mean_speed)))


def crane(model: Model, drive_classes=None) -> dict:
    """The crane dynamic factors of a model with a ``crane:`` section, as ``machdyn crane --json``
    (docs/crane-factors.md): ``{"model": NAME, "rows": [{"factor", "case", "simulated",
    "standard_lo", "standard_hi", "clause", "margin", "note", "extreme", "t_extreme_s", "reference",
    "vh_m_s", "xi_b", "stroke", "contact_speed", "t_contact_s", "warning"}, ...]}`` (``"load_case"``
    for a model loaded with a case), NaN as None.
    ``drive_classes``: "all" or a list such as ``["HD1", "HD4"]`` gives one φ2 row per hoist drive
    class (as ``--drive-classes``). Raises InputError for a model without ``crane:`` or a case it
    cannot build, ValueError for an unknown drive class.
    """
    classes = []
    if drive_classes == "all":
        classes = [1, 2, 3, 4, 5]
    elif drive_classes is not None:
        for hd in drive_classes:
            if not (isinstance(hd, str) and len(hd) == 3 and hd[:2] == "HD" and hd[2] in "12345"):
                raise ValueError(f"drive class {hd!r}: expected 'all' or HD1 ... HD5")
            classes.append(int(hd[2]))
    return _json.loads(_machdyn.crane(model._core, classes))


def gears(spec: str | _os.PathLike, set: Mapping[str, object] | Iterable[str] | None = None) -> dict:
    """Synthesizes a non-circular gear pair from a gear spec file, as ``machdyn gears --json``.

    set: overrides ``{"FIELD": value}`` (e.g. ``{"L": "150 mm"}``).
    Returns the JSON dict: ``u``, ``sectors`` [{i, phi, dphi, rH, theta, dtheta, r}] (rad, mm), ...
    The paper's Table 1 as text is under the key ``"text"``.
    """
    text, table = _machdyn.gears(_os.fspath(spec), _sets(set))
    out = _json.loads(text)
    out["text"] = table
    return out


def _vary_text(v: object) -> str:
    if isinstance(v, str):
        return v
    if isinstance(v, Iterable):
        return ",".join(_value_text(x) for x in v)
    raise TypeError(f"vary: a value is a SPEC string ('a:b:n', 'a:b:n:log', 'a:b') or a list, not {type(v).__name__}")


def sweep(model: Model, vary: Mapping[str, object], method: str = "grid", samples: int = 0, seed: int = 1,
          cases: Iterable[str] | str | None = None, all_cases: bool = False, threads: int | None = None,
          out: str | _os.PathLike | None = None, resume: bool = False):
    """A parameter study, as ``machdyn sweep``: the same runs, the same table, the same threads.

    vary:      ``{"NAME.FIELD": SPEC}``; SPEC is ``"a:b:n"`` (linear), ``"a:b:n:log"``, ``"a:b"``
               (random, lhs) or a list of values; values may carry units (``"2 mm:8 mm:4"``). A grid
               varies the first key slowest.
    method:    "grid" (full factorial), "lhs" (Latin hypercube) or "random", with ``samples``, ``seed``.
    cases:     load cases to run every point for (the table gets a ``case`` column); ``all_cases``:
               every case of the file.
    threads:   worker threads, 1 … 1024 (default: all cores).
    out:       folder for sweep.csv and sweep.journal (default: a temporary folder, removed after).
    resume:    continue an interrupted sweep from the journal in ``out`` (Ctrl-C stops a sweep:
               the finished runs stay in the journal and KeyboardInterrupt is raised).
    Returns a pandas DataFrame of the table (run, varied fields in SI, summary columns, status,
    message). A failing run is a row with status ``error``; bad input raises InputError before any run.
    """
    import pandas as pd  # only sweeps need pandas

    if not isinstance(vary, Mapping) or not vary:
        raise ValueError("vary: give at least one {'NAME.FIELD': SPEC}")
    if method not in ("grid", "lhs", "random"):
        raise ValueError(f"method: expected grid, lhs or random, not {method!r}")
    case_list = [cases] if isinstance(cases, str) else list(cases or [])
    if all_cases:
        if case_list:
            raise ValueError("give either cases or all_cases")
        case_list = model.cases
        if not case_list:
            raise ValueError("all_cases: the model file has no 'cases:'")
    if threads is not None and not 1 <= threads <= 1024:
        raise ValueError("threads: expected 1 … 1024")
    args = ([f"{k}={_vary_text(v)}" for k, v in vary.items()], method, int(samples), int(seed), case_list)
    tmp = None
    if out is None:
        tmp = _tempfile.TemporaryDirectory(prefix="machdyn-sweep-")
        out = tmp.name
    try:
        info = _machdyn.sweep(model._core, *args, _os.fspath(out), int(threads or 0), bool(resume))
        df = pd.read_csv(info["table_path"], keep_default_na=False, na_values=["nan", ""],
                         float_precision="round_trip")  # the 17 digits back to the same doubles
    finally:
        if tmp is not None:
            tmp.cleanup()
    df.attrs.update({k: v for k, v in info.items() if k != "table_path" or tmp is None})
    return df


def rainflow(series, gate: float = 0.0, residue: str = "half", frame: bool = True):
    """Rainflow cycles of a load history (ASTM E1049-85, 5.4.4; docs/duty.md), as the library counts.

    ``series``: any one-dimensional array-like of finite numbers (a numpy array, a list, a column of
    :meth:`Result.__getitem__`). ``gate``: the hysteresis gate as a fraction of the largest range
    (max − min of the series), in [0, 1): reversals of at most that size are dropped before counting.
    ``residue``: ``"half"`` (each residue range is half a cycle) or ``"repeat"`` (the residue closed by
    repeating the history; all cycles whole). Returns a pandas DataFrame with the columns ``range``,
    ``mean``, ``count`` (1 or 0.5), ``from``, ``to`` in the order counted, or with ``frame=False`` a dict
    of numpy arrays under the same keys. Bad input raises ValueError.
    """
    import numpy as np

    if residue not in ("half", "repeat"):
        raise ValueError(f"rainflow: residue is 'half' or 'repeat', not {residue!r}")
    x = np.asarray(series, dtype=float)
    if x.ndim != 1:
        raise ValueError(f"rainflow: the series must be one-dimensional, not of shape {x.shape}")
    d = _machdyn.rainflow(np.ascontiguousarray(x), float(gate), residue == "repeat")
    if not frame:
        return d
    import pandas as pd

    return pd.DataFrame({k: d[k] for k in ("range", "mean", "count", "from", "to")})


def duty(model: str | _os.PathLike, duty: str | _os.PathLike,
         set: Mapping[str, object] | Iterable[str] | None = None):
    """A duty run as ``machdyn duty MODEL DUTY`` runs it (docs/duty.md): every operation (a load case
    of the model file with its repetitions) simulated once, its link loads rainflow-counted over the
    located turning points, the counts merged over the duty.

    Returns ``(links, cycles)``: two pandas DataFrames — per link the figures of duty.json (``cycles``,
    ``largest_range``, ``equivalent_range``, ``k``, ``nu``, ``s``, ``damage`` with an S–N curve, the load
    spectrum factor ``k_m`` with ``p_max``, ``spectrum_class`` L1–L4, ``mechanism_group`` M1–M8 and EN 13001's
    ``stress_history_class`` S0–S9 of ``s``; the
    duty's running hours and class of utilization in ``links.attrs["duty"]``), and
    every merged cycle (``link, range, mean, count, from, to``, the rows of duty_cycles.csv). Bad input
    raises :class:`InputError` with the file's line and column.
    """
    import io

    import pandas as pd

    text, csv = _machdyn.duty(_os.fspath(model), _os.fspath(duty), _sets(set))
    summary = _json.loads(text)
    links = pd.DataFrame(summary["links"]).set_index("link")
    links.attrs["duty"] = {k: v for k, v in summary.items() if k != "links"}
    return links, pd.read_csv(io.StringIO(csv), float_precision="round_trip")


def report(model: Model, path: str | _os.PathLike, case: str | None = None, links: list[str] | None = None,
           frf_input: str | None = None, frf_outputs: list[str] | None = None,
           frf_band_hz: tuple[float, float] | None = None) -> str:
    """Simulates, computes the modes and writes the self-contained HTML report to ``path``, as
    ``machdyn report`` (the same pipeline, so the same sections, the frequency response included).
    Returns the path. Written through a temporary file, so a failed run leaves no partial file; a
    path that is the model file (also through a link) or not a regular file raises InputError. The
    file's mode follows the umask, as every file the CLI writes.

    links:       the links whose loads are drawn (default: all, in panels by unit and size), as ``--links``.
    frf_input:   the frequency response's input, a load or a body (default: the drive), as ``--frf-input``.
    frf_outputs: its outputs, ``LINK.load``, ``BODY.position`` or ``BODY.speed`` (default: every link load).
    frf_band_hz: its band ``(lo, hi)`` in Hz (default: 0.1 × the lowest mode to 2 × the highest
                 resonance the outputs show), as ``--frf-band LO:HI``.
    """
    m = model.with_case(case) if case else model
    command = f"machdyn.report({_os.path.basename(m.source)!r}" + (f", case={case!r}" if case else "") + ")"
    path = _os.fspath(path)
    lo, hi = (0.0, 0.0) if frf_band_hz is None else (float(frf_band_hz[0]), float(frf_band_hz[1]))
    html = _machdyn.report_html(m._core, command, frf_input or "", list(frf_outputs or []), lo, hi, list(links or []))
    # Through a temporary file and a rename, never over the model file or a device (InputError).
    _machdyn.write_result_file(path, html)
    return path
