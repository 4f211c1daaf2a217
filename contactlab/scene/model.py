"""The :class:`Scene`: profile, materials, interface, load path and requested outputs.

A scene is built from a TOML file, a TOML string, a plain mapping or Python objects, is validated
once at construction (every problem reported together, see :mod:`.validate`) and converts back to
a mapping or TOML (round trip: ``Scene.from_dict(s.to_dict()) == s``). It computes nothing until
:meth:`Scene.run`; :meth:`Scene.plan` says what a run will compute and why.
"""
from __future__ import annotations

import copy
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from ..errors import SceneError, UnknownNameError
from ..loadpath import Hold, LoadPath, Ramp, Sinusoid
from . import toml_io
from .validate import CONTROLS, read_table, resolve_file, validate

__all__ = ["Scene", "History", "build_load_path", "leaf_segments"]

#: steps per cycle of a sinusoid segment that does not say
DEFAULT_STEPS_PER_CYCLE = 100


@dataclass(frozen=True)
class History:
    """The load path sampled at its steps.

    Attributes
    ----------
    time : ndarray
        Time of each step, s (step 0 is the unloaded start unless a table says otherwise).
    controls : dict
        Axis (``"normal"``, ``"tangential"``, ``"torsion"``: the groups of
        :data:`contactlab.loadpath.base.GROUPS`) -> ``(control name, values)``; e.g.
        ``{"normal": ("force", array), "torsion": ("twist", array)}``. Axes the path never
        drives are absent.
    segment : ndarray of int
        Index of the load-path segment each step belongs to (-1 for the start).
    """

    time: np.ndarray
    controls: dict[str, tuple[str, np.ndarray]]
    segment: np.ndarray

    @property
    def n_steps(self) -> int:
        return int(self.time.size)

    def kind(self, axis: str) -> str | None:
        """Control name driving ``axis`` or None."""
        _check_axis(axis)
        return self.controls[axis][0] if axis in self.controls else None

    def values(self, axis: str) -> np.ndarray:
        """Per-step values of ``axis`` (zeros when the path does not drive it)."""
        _check_axis(axis)
        return self.controls[axis][1] if axis in self.controls else np.zeros(self.time.shape)


#: the axes of a history: the load path's groups
AXES = ("normal", "tangential", "torsion")


def _check_axis(axis: str) -> None:
    """An unknown axis would read as "not driven" (zeros): refuse it instead."""
    if axis not in AXES:
        raise UnknownNameError(f"axis={axis!r} is unknown: the axes of a load history are "
                               f"{AXES}.")


def _table_columns(body: Mapping[str, Any], base_dir: Path | None) -> dict[str, Any]:
    if "file" in body:
        return read_table(resolve_file(body["file"], base_dir))
    return dict(body)


def build_load_path(segments: Sequence[Mapping[str, Any]], base_dir: Path | None) -> LoadPath:
    """The typed :class:`~contactlab.LoadPath` of validated scene segments.

    A scene path starts from the unloaded state at time 0: unless the path is a measured table
    alone (whose first row is the start), it opens with a one-row
    :class:`~contactlab.loadpath.Table` holding every control at 0, so step 0 of the scene is
    that start. A ``table`` among other segments is one segment like the rest (its times are
    offsets from its first row, which follows the previous segment's last step); ``repeat =
    { times = N, last = k }`` runs the ``k`` segments before it (default 1) ``N`` times in all.
    """
    if len(segments) == 1 and "table" in segments[0]:
        cols = _table_columns(segments[0]["table"], base_dir)
        n = len(next(iter(cols.values())))
        return LoadPath.from_arrays(time=cols.get("time", np.arange(n, dtype=float)),
                                    **{k: v for k, v in cols.items() if k in CONTROLS})
    tables = {i: _table_columns(seg["table"], base_dir) for i, seg in enumerate(segments)
              if "table" in seg}
    controls = {k for seg in segments for k in next(iter(seg.values())) if k in CONTROLS}
    controls |= {k for cols in tables.values() for k in cols if k in CONTROLS}
    path = LoadPath.from_arrays(time=[0.0], **{k: [0.0] for k in sorted(controls)})
    for i, seg in enumerate(segments):
        kind, body = next(iter(seg.items()))
        targets = tuple((k, v) for k, v in body.items() if k in CONTROLS)
        if kind == "ramp":
            path = path.then(Ramp(targets, body["steps"], body.get("duration")))
        elif kind == "hold":
            path = path.then(Hold(body["steps"], body.get("duration")))
        elif kind == "table":
            cols = tables[i]
            path = path + LoadPath.from_arrays(
                time=cols.get("time"),
                **{k: v for k, v in cols.items() if k in CONTROLS})
        elif kind == "repeat":
            path = path.repeat(body["times"], last=body.get("last", 1))
        else:
            path = path.then(Sinusoid(targets, body["cycles"],
                                      body.get("steps_per_cycle", DEFAULT_STEPS_PER_CYCLE),
                                      body.get("period")))
    return path


def leaf_segments(segments: Sequence[Mapping[str, Any]]) -> list[tuple[int, int, int]]:
    """Scene segment of each leaf of the built path, in order (repeats expanded, the unloaded
    start left out, so :attr:`History.segment` indexes this list): ``(segment index,
    repetition, times)``, repetition 0-based, ``times`` 1 unless a ``repeat`` runs it again.

    >>> leaf_segments([{"ramp": {}}, {"table": {}}, {"repeat": {"times": 3}}, {"hold": {}}])
    [(0, 0, 1), (1, 0, 3), (1, 1, 3), (1, 2, 3), (3, 0, 1)]
    """
    groups: list[list[tuple[int, int, int]]] = []
    for i, seg in enumerate(segments):
        if "repeat" in seg:
            k = min(int(seg["repeat"].get("last", 1)), len(groups))
            times = int(seg["repeat"]["times"])
            block = [leaf for g in groups[len(groups) - k:] for leaf in g]
            groups[len(groups) - k:] = [[(j, r, times) for r in range(times)
                                         for j, _, _ in block]]
        else:
            groups.append([(i, 0, 1)])
    return [leaf for g in groups for leaf in g]


def _history(path: LoadPath, opens_with_start: bool) -> History:
    """Scene view of ``path.sample()``: controls by axis, scene segment index per step (leaf 0
    is the unloaded start, segment -1, when ``opens_with_start``)."""
    smp = path.sample(start_time=float(path.segments[0].time[0]))
    controls = {CONTROLS[k][0]: (k, v) for k, v in smp.values.items()}
    return History(smp.time, controls, smp.leaf - int(opens_with_start))


class Scene:
    """A whole contact study: bodies, interface, load path and requested outputs.

    Parameters
    ----------
    data : mapping
        The scene as nested tables (see ``examples/*.toml``): ``profile``, ``materials``
        (``body1``, ``body2``), ``interface`` (``friction``, ``work_of_adhesion``), ``load_path``
        (list of segments ``ramp``/``hold``/``sinusoid``/``table``), ``outputs`` (``series``,
        ``fields``, ``field_points``, ``method``, ``effects``), ``solver`` (``rtol``,
        ``n_springs`` of the MDR springs, ``n_rings`` of the exact ring solver), ``scene``
        (``title``, ``description``). Quantities are SI numbers or strings with a unit
        (``"10 um"``).
    base_dir : path, optional
        Directory that relative CSV file names refer to (the scene file's directory).

    Raises
    ------
    SceneError
        Every validation problem at once, in ``err.issues`` as (key path, value, allowed).

    Examples
    --------
    >>> s = Scene({"profile": {"type": "paraboloid", "R": "10 mm"},
    ...            "materials": {"body1": {"type": "elastic", "E": "210 GPa", "nu": 0.3},
    ...                          "body2": {"type": "elastic", "E": "210 GPa", "nu": 0.3}},
    ...            "load_path": [{"ramp": {"force": "100 N", "steps": 4}}]})
    >>> s.to_dict()["profile"]
    {'type': 'paraboloid', 'R': 0.01}
    >>> [e.effect for e in s.plan().effects]
    ['normal']
    """

    def __init__(self, data: Mapping[str, Any], base_dir: str | Path | None = None, *,
                 allow_outside: bool = False) -> None:
        self.base_dir = Path(base_dir) if base_dir is not None else None
        self.allow_outside = bool(allow_outside)
        self._data, self._objects = validate(data, self.base_dir, allow_outside=self.allow_outside)
        self._load_path: LoadPath | None = None
        self._history: History | None = None
        self._plan = None
        self._contact: Any = None
        self._plan = self.plan()   # plan-level issues (conflicts) are validation errors too

    # ---- construction ---------------------------------------------------------------------------
    @classmethod
    def from_dict(cls, data: Mapping[str, Any], base_dir: str | Path | None = None) -> "Scene":
        """Scene from a mapping (as :func:`tomllib.loads` returns it)."""
        return cls(data, base_dir)

    @classmethod
    def from_toml(cls, path: str | Path, *, allow_outside: bool = False) -> "Scene":
        """Scene from a TOML file; relative CSV names are relative to the file's directory and
        must stay inside it unless ``allow_outside`` (absolute names are always used as given)."""
        path = Path(path)
        return cls(toml_io.load(path), base_dir=path.parent, allow_outside=allow_outside)

    @classmethod
    def loads(cls, text: str, base_dir: str | Path | None = None) -> "Scene":
        """Scene from TOML text."""
        return cls(toml_io.loads(text), base_dir)

    @classmethod
    def from_objects(cls, profile: Any, materials: tuple[Any, Any], load_path: Any,
                     *, friction: float | None = None, work_of_adhesion: float | None = None,
                     outputs: Mapping[str, Any] | None = None,
                     solver: Mapping[str, Any] | None = None, title: str | None = None) -> "Scene":
        """Scene from contactlab objects (profile, two materials) and a load path.

        ``load_path`` is a :class:`~contactlab.LoadPath` (ramp, hold, sinusoid without ``mean``,
        repeat, from_arrays) or a list of segment tables as in a scene file, e.g.
        ``[{"ramp": {"force": 100.0, "steps": 50}}, {"sinusoid": {"twist": 1e-3, "cycles": 2}}]``.
        """
        if hasattr(load_path, "leaves"):
            load_path = _segments_of_loadpath(load_path)
        data: dict[str, Any] = {
            "profile": _object_table(profile, "profile"),
            "materials": {"body1": _object_table(materials[0], "materials.body1"),
                          "body2": _object_table(materials[1], "materials.body2")},
            "load_path": [dict(s) for s in load_path],
        }
        itf = {k: v for k, v in (("friction", friction), ("work_of_adhesion", work_of_adhesion))
               if v is not None}
        if itf:
            data["interface"] = itf
        if outputs:
            data["outputs"] = dict(outputs)
        if solver:
            data["solver"] = dict(solver)
        if title:
            data["scene"] = {"title": title}
        return cls(data)

    # ---- back to data ---------------------------------------------------------------------------
    def to_dict(self) -> dict[str, Any]:
        """The normalised scene (SI floats) as a plain mapping; ``Scene.from_dict`` reads it."""
        return copy.deepcopy(self._data)

    def to_toml(self) -> str:
        """The normalised scene as TOML text."""
        return toml_io.dumps(self.to_dict())

    def save(self, path: str | Path) -> None:
        """Write :meth:`to_toml` to ``path``."""
        Path(path).write_text(self.to_toml())

    def __eq__(self, other: object) -> bool:
        return isinstance(other, Scene) and self._data == other._data

    def __hash__(self) -> int:
        return hash(self.to_toml())

    def __repr__(self) -> str:
        title = self._data.get("scene", {}).get("title")
        prof = self._data["profile"]["type"]
        return f"Scene({title or prof!r}, {len(self._data['load_path'])} segments)"

    # ---- views ----------------------------------------------------------------------------------
    @property
    def title(self) -> str:
        return self._data.get("scene", {}).get("title", self._data["profile"]["type"])

    @property
    def profile(self) -> Any:
        """The profile object."""
        return self._objects["profile"]

    @property
    def materials(self) -> tuple[Any, Any]:
        """The two body materials."""
        return self._objects["body1"], self._objects["body2"]

    @property
    def friction(self) -> float | None:
        return self._data.get("interface", {}).get("friction")

    @property
    def work_of_adhesion(self) -> float | None:
        return self._data.get("interface", {}).get("work_of_adhesion")

    @property
    def outputs(self) -> dict[str, Any]:
        return dict(self._data.get("outputs", {}))

    @property
    def solver(self) -> dict[str, Any]:
        return dict(self._data.get("solver", {}))

    @property
    def is_viscoelastic(self) -> bool:
        return any(getattr(m, "is_viscoelastic", False) for m in self.materials)

    @property
    def load_path(self) -> LoadPath:
        """The typed load path, opening with the unloaded start (see :func:`build_load_path`)."""
        if self._load_path is None:
            self._load_path = build_load_path(self._data["load_path"], self.base_dir)
        return self._load_path

    def history(self) -> History:
        """The load path sampled at its steps (cached)."""
        if self._history is None:
            opens_with_start = "table" not in self._data["load_path"][0]
            self._history = _history(self.load_path, opens_with_start)
        return self._history

    def contact(self) -> Any:
        """The :class:`~contactlab.Contact` of this scene (built on first use)."""
        if self._contact is None:
            from ..contact import Contact
            self._contact = Contact(self.profile, materials=self.materials, friction=self.friction,
                                    work_of_adhesion=self.work_of_adhesion or None,
                                    rtol=self.solver.get("rtol"))
        return self._contact

    # ---- planning and running -------------------------------------------------------------------
    def plan(self) -> Any:
        """The effect plan: which physics, which implementation, and why (pure, cached)."""
        if self._plan is None:
            from .plan import make_plan
            self._plan = make_plan(self)
        return self._plan

    def run(self) -> Any:
        """Compute what the plan calls for; returns a :class:`~contactlab.scene.run.SceneResult`."""
        from .run import run_scene
        return run_scene(self)

    def cost(self, target: float = 1e-6, **kwargs: Any) -> Any:
        """What accuracy costs for this scene: each numeric knob over a ladder, error against
        wall time, and the cheapest setting meeting ``target``; see
        :func:`contactlab.scene.cost.scene_cost` (keyword arguments go there)."""
        from .cost import scene_cost
        return scene_cost(self, target=target, **kwargs)


def _segments_of_loadpath(path: Any) -> list[dict[str, Any]]:
    """Scene segment tables of a :class:`~contactlab.LoadPath` (issue 4), leaf by leaf."""
    out: list[dict[str, Any]] = []
    for i, seg in enumerate(path.leaves()):
        kind = type(seg).__name__.lower()
        if kind == "ramp":
            out.append({"ramp": {**{k: float(v) for k, v in seg.targets}, "steps": int(seg.steps),
                                 "duration": float(seg.duration)}})
        elif kind == "hold":
            out.append({"hold": {"steps": int(seg.steps), "duration": float(seg.duration)}})
        elif kind == "sinusoid" and getattr(seg, "mean", None) is None:
            out.append({"sinusoid": {**{k: float(v) for k, v in seg.amplitudes},
                                     "cycles": int(seg.cycles),
                                     "steps_per_cycle": int(seg.steps_per_cycle),
                                     "period": float(seg.period)}})
        elif kind == "table":
            out.append({"table": {"time": [float(t) for t in seg.time],
                                  **{k: [float(x) for x in v] for k, v in seg.columns}}})
        else:
            raise SceneError(f"load_path segment {i} ({seg!r}) has no scene form: scenes "
                             "sinusoids oscillate around the current value (no mean=).",
                             [(f"load_path[{i}]", repr(seg), "ramp, hold, sinusoid without "
                               "mean, repeat, from_arrays")])
    return out


def _object_table(obj: Any, path: str) -> dict[str, Any]:
    name = getattr(type(obj), "name", "")
    if not name or name in ("sum", "scaled"):
        raise SceneError(f"{path}={obj!r} cannot be written to a scene: only named built-in or "
                         "registered types can.", [(path, repr(obj), "a named profile/material")])
    if name == "polynomial":
        return {"type": name, "terms": [[float(c), float(n)] for c, n in obj.terms]}
    if name == "tabulated":
        out_t = {"type": name, "r": [float(v) for v in obj.r], "f": [float(v) for v in obj.f],
                 "interpolation": obj.interpolation}
        if obj.axis != "even":
            out_t["axis"] = obj.axis
        return out_t
    out: dict[str, Any] = {"type": name}
    for p in getattr(type(obj), "params", ()):
        v = getattr(obj, p.name)
        if isinstance(v, (int, float, np.floating)):
            v = float(v)
        elif isinstance(v, (tuple, list, np.ndarray)):
            v = [float(x) for x in v]
        out[p.name] = v
    return out
