"""The Python side of models, results and modes: numpy arrays, pandas, matplotlib, Jupyter display."""
from __future__ import annotations

import html as _html
import json as _json

import numpy as np


# Unit suffixes of the output columns (model.hpp unit_suffix: "N*m" → "N_m", "/" → "_").
_UNIT_SUFFIXES = {"s", "rad", "m", "rad_s", "m_s", "rad_s2", "m_s2", "N", "N_m", "kg", "kg_m2", "J", "W", "1"}


def _table_html(header: list[str], rows: list[list[str]], caption: str = "") -> str:
    h = "".join(f"<th>{_html.escape(c)}</th>" for c in header)
    body = "".join("<tr>" + "".join(f"<td>{_html.escape(str(c))}</td>" for c in r) + "</tr>" for r in rows)
    cap = f"<caption>{_html.escape(caption)}</caption>" if caption else ""
    return f"<table>{cap}<thead><tr>{h}</tr></thead><tbody>{body}</tbody></table>"


def _g(x, digits: int = 6) -> str:
    return "–" if x is None else f"{x:.{digits}g}"


class _Model:
    """A compiled model (immutable). Inspect it with ``bodies``, ``links``, ``loads``, ``contacts``
    (lists of dicts, SI values with the unit in the key) and ``simulation`` (the run settings).
    Made by :func:`machdyn.load`, :func:`machdyn.loads` or :func:`machdyn.from_dict`."""

    __slots__ = ("_core",)

    def __init__(self, core):
        self._core = core

    name = property(lambda self: self._core.name, doc="the model's name (with ' [case]' for a load case)")
    description = property(lambda self: self._core.description)
    source = property(lambda self: self._core.source, doc="the file it was read from, or '<string>'")
    case = property(lambda self: self._core.case or None, doc="the load case applied, or None")
    cases = property(lambda self: self._core.cases, doc="the load cases of the file's 'cases:'")
    sets = property(lambda self: self._core.sets, doc="the overrides applied, as 'NAME.FIELD=VALUE'")
    dof = property(lambda self: self._core.dof, doc="degrees of freedom (one per body)")
    is_hybrid = property(lambda self: self._core.is_hybrid,
                         doc="True when the model runs event-driven (a gap, a friction contact or a brake)")
    bodies = property(lambda self: self._core.bodies,
                      doc="bodies: name, type, inertia_kg_m2 or mass_kg, position, velocity (SI)")
    links = property(lambda self: self._core.links,
                     doc="links: name, type, between (a, b), ratio, stiffness (N*m/rad or N/m), damping, gap")
    loads = property(lambda self: self._core.loads, doc="loads: name, type, body, value (N*m or N)")
    drives = property(lambda self: self._core.drives, doc="drives with states: name, type (dc-motor, speed-drive), body, states")
    contacts = property(lambda self: self._core.contacts, doc="friction contacts and brakes")
    simulation = property(lambda self: self._core.simulation,
                          doc="run settings: t_end_s, dt_out_s, rtol, atol, integrator, max_steps")

    def with_case(self, case: str) -> "_Model":
        """The same file and overrides with load case ``case`` applied (as ``--case``)."""
        return _Model(self._core.with_case(case))

    def with_set(self, set) -> "_Model":
        """The model with more overrides (``{"NAME.FIELD": value}``) applied after the present ones."""
        from . import _sets
        return _Model(self._core.with_sets(_sets(set)))

    def __repr__(self) -> str:
        return (f"<machdyn.Model {self.name!r} from {self.source!r}: {len(self.bodies)} bodies, "
                f"{len(self.links)} links, {len(self.loads)} loads>")

    def _repr_html_(self) -> str:
        rows = [[b["name"], b["type"], _g(b.get("inertia_kg_m2", b.get("mass_kg"))),
                 "kg*m^2" if b["type"] == "rotational" else "kg"] for b in self.bodies]
        links = [[l["name"], f"{l['between'][0]} → {l['between'][1]}", _g(l["stiffness"]), _g(l["damping"]),
                  _g(l["ratio"])] for l in self.links]
        return (f"<b>{_html.escape(self.name)}</b> <small>({_html.escape(self.source)})</small>"
                + _table_html(["body", "type", "inertia / mass", "unit"], rows)
                + _table_html(["link", "between", "stiffness", "damping", "ratio"], links))


class Result:
    """The result of :func:`machdyn.simulate`.

    ``r.t``: output times, s. ``r[name]``: a series as a read-only numpy array (a view of the C++
    result, no copy); ``name`` is a column name (``"c1.load_N_m"``) or the same without its unit
    (``"c1.load"``). ``r.columns``: every column name. ``r.summary``: the dict of summary.json
    (link peaks, their times, static loads, dynamic factors, solver statistics). ``r.brakes``: each
    brake's stops, one by one (stopping time, travel, energy, peak power, temperature rise). ``r.events``: the
    mode events of an event-driven run (t_s, kind, element, from, to).
    """

    def __init__(self, core, model: _Model):
        self._core = core
        self.model = model
        self.columns: list[str] = list(core.column_names)
        self._summary = None

    @property
    def t(self) -> np.ndarray:
        """Output times, s."""
        return self._core.column(0)

    def _index(self, name: str) -> int:
        if name in self.columns:
            return self.columns.index(name)
        hits = [k for k, c in enumerate(self.columns) if c.startswith(name + "_")]
        if len(hits) == 1:
            return hits[0]
        if len(hits) > 1:
            # "crank.M" against "crank.M_rod_N_m": keep the column whose rest is only a unit.
            exact = [k for k in hits if self.columns[k][len(name) + 1:] in _UNIT_SUFFIXES]
            if len(exact) == 1:
                return exact[0]
            raise KeyError(f"{name!r} is ambiguous: {[self.columns[k] for k in hits]}")
        raise KeyError(f"no series {name!r}; the columns are {self.columns}")

    def __getitem__(self, name: str) -> np.ndarray:
        return self._core.column(self._index(name))

    def __contains__(self, name: str) -> bool:
        try:
            self._index(name)
            return True
        except KeyError:
            return False

    def keys(self) -> list[str]:
        return list(self.columns)

    @property
    def summary(self) -> dict:
        """The dict of summary.json (``machdyn simulate --json``)."""
        if self._summary is None:
            self._summary = _json.loads(self._core.summary_json())
        return self._summary

    @property
    def events(self) -> list[dict]:
        """Mode events (gap closed/opened, stick, slip, reversal) in time order; empty for a smooth run."""
        return self._core.events

    @property
    def brakes(self) -> dict:
        """Each brake's stops in this run (summary.json ``brakes``): per brake ``stops``, a list with one
        dict per stop (the brake applied, sliding, until its body is at rest or it is lifted):
        ``applied_at_s``, ``ended_at_s``, ``end`` (stuck, released, t_end), ``stopping_time_s``,
        ``travel`` ({body: {value, unit}}: the braked body and every translational body joined to it,
        the load), ``energy_J``, ``peak_power_W`` and, with a thermal model, ``temperature_rise_K``;
        and the run's ``energy_J``, ``peak_power_W``, ``temperature_max_degC`` and
        ``temperature_end_degC``; empty without brakes (docs/model-files.md, Brakes)."""
        return dict(self.summary.get("brakes", {}))

    @property
    def warnings(self) -> list[str]:
        """What the run decided on its own (an end stop's accumulating bounces ended at rest), one sentence each."""
        return list(self.summary.get("warnings", []))

    def to_csv(self) -> str:
        """The time series as the CLI's timeseries.csv (17 significant digits)."""
        return self._core.timeseries_csv()

    def to_pandas(self):
        """The time series as a pandas DataFrame, one column per series (``t_s`` first)."""
        import pandas as pd
        return pd.DataFrame({c: self._core.column(k) for k, c in enumerate(self.columns)})

    def plot(self, ax=None, links: list[str] | None = None):
        """Draws the link loads against time with matplotlib, the quasi-static load at each peak
        marked. Returns the Axes. ``links``: the links drawn (default: all); a name the model does
        not have raises InputError at ``links=`` listing the model's links."""
        names = self.model._core.chosen_links(list(links or []))  # before matplotlib: a typo draws nothing
        import matplotlib.pyplot as plt
        if ax is None:
            _, ax = plt.subplots(figsize=(8, 4))
        s = self.summary["links"]
        for name in names:
            line, = ax.plot(self.t, self[name + ".load"], label=f"{name} [{s[name]['unit']}]")
            ax.plot([s[name]["t_max"]], [s[name]["static"]], "o", mfc="none", color=line.get_color())
        ax.set_xlabel("t [s]")
        ax.set_ylabel("link load")
        ax.set_title(self.model.name)
        ax.grid(True, alpha=0.3)
        ax.legend()
        return ax

    def __repr__(self) -> str:
        s = self.summary
        lines = [f"<machdyn.Result {self.model.name!r}: {len(self.t)} points, t = 0 … {self.t[-1]:g} s>"]
        for name, l in s["links"].items():
            lines.append(f"  {name}: max {l['max']:.6g} at {l['t_max']:.4g} s, min {l['min']:.6g}, "
                         f"dyn.factor {_g(l['dynamic_factor'], 4)} [{l['unit']}]")
        return "\n".join(lines)

    def _repr_html_(self) -> str:
        s = self.summary
        rows = [[n, _g(l["max"]), _g(l["t_max"]), _g(l["min"]), _g(l["static"]), _g(l["dynamic_factor"], 4), l["unit"]]
                for n, l in s["links"].items()]
        solver = s.get("solver", {})
        cap = (f"{self.model.name}: {solver.get('method', '')}, {solver.get('steps', '')} steps"
               + (f", {sum(e['kind'] != 'initial' for e in self.events)} events" if self.events else ""))
        return _table_html(["link", "max", "t_max [s]", "min", "static", "dyn. factor", "unit"], rows, cap)


class Modes:
    """Natural frequencies and mode shapes (:func:`machdyn.modes`).

    ``omega``: elastic natural frequencies, rad/s, ascending. ``frequencies_hz``: the same in Hz.
    ``shapes``: bodies × modes, mass-normalized (φᵀ M φ = 1). ``bodies``: the row names.
    ``rigid_body_modes``: how many (ω = 0). ``summary``: the dict of ``machdyn modes --json``.
    ``kinds``: per mode ``"pendulum"``, ``"rope stretch"`` or ``"drive line"`` (a model with a
    spatial rope: by the loads' share of the mode's kinetic energy, docs/sway.md "Pendulum modes";
    every mode ``"drive line"`` without one); ``pendulum_modes``: the indices of the pendulum modes.
    ``topology``: the topology (mode of every gap, contact, brake and stop) these arrays belong to —
    without a ``topology`` argument the first listed, the initial state's (a load resting on the
    floor has no rope mode there). ``topologies``: the labels of every topology in ``summary``;
    ``select(name)`` gives the modes of another: an index into ``topologies``, or a topology text
    as :func:`machdyn.modes` takes it (``"floor=open"`` for the hanging load).
    """

    def __init__(self, summary: dict, omega: np.ndarray, shapes: np.ndarray, model=None):
        self.summary = summary
        self.omega = np.asarray(omega)
        self.frequencies_hz = self.omega / (2 * np.pi)
        self.shapes = np.asarray(shapes)
        self.bodies: list[str] = list(summary["bodies"])
        self.rigid_body_modes: int = summary["rigid_body_modes"]
        self.topology: str = summary.get("topology", "")
        self.topologies: list[str] = [t["topology"] for t in summary.get("topologies", [])]
        self.kinds: list[str] = list(summary.get("kinds", ["drive line"] * len(self.omega)))
        self.pendulum_modes: list[int] = [k for k, kind in enumerate(self.kinds) if kind == "pendulum"]
        self._model = model

    def select(self, topology: int | str) -> "Modes":
        """The modes of another topology: an index into ``topologies`` or a topology text
        (``"floor=open, rope=closed"``, docs/modes.md), as ``machdyn.modes(model, topology=...)``."""
        if self._model is None:
            raise ValueError("select: these modes were not made by machdyn.modes(model)")
        from . import modes as _modes
        if isinstance(topology, int):
            if not 0 <= topology < len(self.topologies):
                raise IndexError(f"select: topology index {topology} of {len(self.topologies)}")
            topology = self.topologies[topology]
        return _modes(self._model, topology)

    def to_pandas(self):
        """One row per mode: frequency_rad_s, frequency_hz and the amplitude of every body."""
        import pandas as pd
        return pd.DataFrame(self.summary["shapes"])

    def __repr__(self) -> str:
        more = f"; {len(self.topologies)} topologies, select() another" if len(self.topologies) > 1 else ""
        where = f" of topology '{self.topology}'" if self.topology else ""
        return (f"<machdyn.Modes{where}: {len(self.omega)} elastic, "
                f"f = {np.array2string(self.frequencies_hz, precision=4)} Hz{more}>")

    def _repr_html_(self) -> str:
        named = "kinds" in self.summary  # a swinging load's model: each mode's kind
        rows = [[k + 1, _g(w, 8), _g(w / (2 * np.pi), 8)] + ([self.kinds[k]] if named else []) +
                [f"{self.shapes[i, k]:+.4f}" for i in range(len(self.bodies))]
                for k, w in enumerate(self.omega)]
        where = f"topology {self.topology}; " if self.topology else ""
        return _table_html(["mode", "ω [rad/s]", "f [Hz]"] + (["kind"] if named else []) + self.bodies, rows,
                           f"{where}{self.rigid_body_modes} rigid-body mode(s)")
