"""What a sweep evaluates at one point, and how a result becomes one table row.

A *study* is any picklable callable of keyword arguments (one per grid name). A scene becomes one
through :class:`SceneStudy`, which writes each point's values into the scene by key path, runs it
and summarises the series. :func:`evaluate` runs a study at one point and records its outputs, or
its error, and the warnings it raised; :func:`run_batch` does it for a batch of points. These are
the functions workers run: they hold no state between calls.
"""
from __future__ import annotations

import copy
import hashlib
import itertools
import math
import time
import warnings
from collections.abc import Callable, Mapping
from operator import itemgetter
from pathlib import Path
from types import FunctionType
from typing import Any

import numpy as np

from ..errors import ParameterError, SceneError
from .keypath import set_key_path

__all__ = ["SceneStudy", "as_study", "scalars", "evaluate", "run_batch", "run_calls", "study_id",
           "Points", "Records"]


class SceneStudy:
    """A scene as a sweep study: grid names are key paths into the scene.

    Calling it with ``**{"interface.friction": 0.3}`` writes 0.3 into a copy of the scene's
    tables, validates and runs the scene and returns :func:`scalars` of the result: for each
    series (except ``time``) its final value ``name`` and its extremes ``name_min``,
    ``name_max``. Only the scene's plain tables are stored, so the study pickles.

    Parameters
    ----------
    scene : Scene, mapping or path
        A :class:`~contactlab.scene.Scene`, its tables or a TOML file.
    base_dir : path, optional
        Directory of the scene's relative CSV files (taken from the Scene or file by default).
    allow_outside : bool, optional
        Let relative file names in the scene leave its folder (as ``contactlab run
        --allow-outside``); default: the Scene's own setting, False for files and tables.

    Examples
    --------
    >>> study = SceneStudy("examples/steel_ball_twist.toml")   # doctest: +SKIP
    >>> study(**{"interface.friction": 0.3})["torque"]          # doctest: +SKIP
    """

    def __init__(self, scene: Any, base_dir: str | Path | None = None, *,
                 allow_outside: bool | None = None) -> None:
        from ..scene import Scene
        if allow_outside is not None and not isinstance(allow_outside, (bool, np.bool_)):
            raise ParameterError(f"allow_outside={allow_outside!r} is invalid: give True, False "
                                 "or None (the scene's own setting).")
        outside = bool(allow_outside)
        if isinstance(scene, (str, Path)):
            scene = Scene.from_toml(scene, allow_outside=outside)
        elif isinstance(scene, Mapping):
            scene = Scene(scene, base_dir, allow_outside=outside)
        elif not isinstance(scene, Scene):
            raise ParameterError(f"study={scene!r} is invalid: give a Scene, a scene file, its "
                                 "tables or a picklable function of keyword arguments.")
        elif allow_outside is not None and outside != scene.allow_outside:
            scene = Scene(scene.to_dict(), scene.base_dir, allow_outside=outside)
        self.allow_outside = scene.allow_outside
        self.data = scene.to_dict()
        bd = base_dir if base_dir is not None else scene.base_dir
        self.base_dir = str(Path(bd).resolve()) if bd is not None else None

    def scene(self, **values: Any) -> Any:
        """The scene with ``values`` (key path -> value) written in; validated."""
        from ..scene import Scene
        data = copy.deepcopy(self.data)
        for key, value in values.items():
            set_key_path(data, key, value)
        return Scene(data, self.base_dir, allow_outside=self.allow_outside)

    def __call__(self, **values: Any) -> dict[str, Any]:
        return scalars(self.scene(**values).run())

    def check(self, point: Mapping[str, Any]) -> None:
        """Fail early on grid keys that can never fit the scene (not on invalid values).

        Raises
        ------
        ParameterError
            A key path that does not fit the scene's structure or names a key the scene does not
            have (with the validator's did-you-mean).
        """
        try:
            self.scene(**point)
        except SceneError as err:
            for path, _value, allowed in err.issues:
                if path in point and str(allowed).startswith("a key from"):
                    raise ParameterError(f"grid key {path!r} is not a scene key: expected "
                                         f"{allowed}") from err

    def __repr__(self) -> str:
        title = self.data.get("scene", {}).get("title") or self.data["profile"]["type"]
        return f"SceneStudy({title!r})"


def as_study(study: Any, allow_outside: bool | None = None) -> Callable[..., Any]:
    """A scene (file, tables, Scene) becomes a :class:`SceneStudy`; a callable stays itself.

    ``allow_outside`` (scene studies only) lets the scene's relative file names leave its folder.
    """
    if isinstance(study, SceneStudy):
        if allow_outside is not None and bool(allow_outside) != study.allow_outside:
            raise ParameterError(f"allow_outside={allow_outside!r} disagrees with the "
                                 f"SceneStudy's allow_outside={study.allow_outside!r}: set it "
                                 "when building the SceneStudy.")
        return study
    if callable(study) and not isinstance(study, type):
        if allow_outside is not None:
            raise ParameterError(f"allow_outside={allow_outside!r} applies to scene studies "
                                 "(files a scene refers to); a study function reads its own "
                                 "files.")
        return study
    return SceneStudy(study, allow_outside=allow_outside)


def study_id(study: Any) -> str:
    """A stable name of a study, to tell whether a store belongs to it."""
    if isinstance(study, SceneStudy):
        text = (repr(sorted(study.data.items(), key=lambda kv: kv[0])) + str(study.base_dir)
                + ("|outside" if study.allow_outside else ""))
        return "scene:" + hashlib.sha256(text.encode()).hexdigest()[:16]
    mod = getattr(study, "__module__", None) or type(study).__module__
    name = getattr(study, "__qualname__", None) or type(study).__qualname__
    return f"{mod}.{name}"


def _number(value: Any, key: str) -> float | str:
    if value is None:
        return math.nan
    if isinstance(value, str):
        return value
    if isinstance(value, (bool, int, float, np.number, np.bool_)):
        return float(value)
    raise ParameterError(f"study output {key!r}={value!r} is invalid: outputs must be numbers, "
                         f"strings or arrays of numbers (got {type(value).__name__}).")


def scalars(result: Any) -> dict[str, float | str]:
    """The table row of a study result: named scalars.

    A mapping's numbers and strings are kept (numbers as float); an array ``x`` of more than one
    value becomes ``x`` (its final value), ``x_min`` and ``x_max``. A scene result gives its
    series (without ``time``) that way; another result object the numeric entries of its
    ``to_dict()``.

    Raises
    ------
    ParameterError
        An output that is neither a number, a string nor an array of numbers; a result that is
        neither a mapping nor a contactlab result.

    Examples
    --------
    >>> scalars({"torque": [0.0, 2.0, 1.0], "mu": 0.2})
    {'torque': 1.0, 'torque_min': 0.0, 'torque_max': 2.0, 'mu': 0.2}
    """
    strict = True
    if type(result) is dict or isinstance(result, Mapping):
        items = dict(result)
    elif isinstance(getattr(result, "series", None), Mapping):         # a scene result
        items = {k: v for k, v in result.series.items() if k != "time"}
    elif callable(getattr(result, "to_dict", None)):
        items, strict = result.to_dict(), False
    else:
        raise ParameterError(f"study result of type {type(result).__name__} is invalid: return "
                             "a dict of numbers or a contactlab result.")
    out: dict[str, float | str] = {}
    for key, value in items.items():
        if type(value) is float and type(key) is str:         # the usual case, fast
            out[key] = value
            continue
        key = str(key)
        if isinstance(value, (list, tuple, np.ndarray)):
            try:
                arr = np.asarray(value, dtype=float).ravel()
            except (TypeError, ValueError):
                if strict:
                    raise ParameterError(f"study output {key!r} is not an array of numbers.") from None
                continue
            if arr.size == 1:
                out[key] = float(arr[0])
            elif arr.size > 1:
                out[key] = float(arr[-1])
                out[key + "_min"] = float(arr.min())
                out[key + "_max"] = float(arr.max())
            continue
        try:
            out[key] = _number(value, key)
        except ParameterError:
            if strict:
                raise
    return out


class Points:
    """A batch of grid points as sent to a worker: point indices and one column per name.

    One object with a few lists inside, not a list of per-point dicts: it pickles in one go and a
    task scheduler (Dask walks the arguments of every task looking for futures) sees one opaque
    argument instead of thousands of nested containers.
    """

    __slots__ = ("columns", "index", "names")

    def __init__(self, index: list[int], names: tuple[str, ...], columns: list[list[Any]]) -> None:
        self.index = index
        self.names = names
        self.columns = columns

    @classmethod
    def of(cls, points: Any, indices: list[int], names: tuple[str, ...]) -> Points:
        """The points ``points[i]`` (mappings) for ``i`` in ``indices``."""
        return cls(list(indices), tuple(names),
                   [[points[i][k] for i in indices] for k in names])

    @classmethod
    def take(cls, grid: Any, indices: list[int]) -> Points:
        """The points of ``grid`` (a :class:`~contactlab.sweeps.grid.Grid`) at ``indices``,
        which must be increasing (a run of consecutive points is sliced, not gathered)."""
        if not indices:
            return cls([], grid.names, [[] for _ in grid.names])
        a, b = indices[0], indices[-1] + 1
        if b - a == len(indices):              # increasing and this long: consecutive
            columns = [c[a:b] for c in grid.columns]
        else:
            columns = [[c[i] for i in indices] for c in grid.columns]
        return cls(list(indices), grid.names, columns)

    def __len__(self) -> int:
        return len(self.index)

    def __iter__(self) -> Any:
        names = self.names
        for i, values in zip(self.index, zip(*self.columns) if self.columns
                             else [()] * len(self.index)):
            yield i, dict(zip(names, values))

    def __getstate__(self) -> tuple[Any, ...]:
        return _pack_index(self.index), self.names, [_pack(c) for c in self.columns]

    def __setstate__(self, state: tuple[Any, ...]) -> None:
        index, self.names, columns = state
        self.index = _unpack_index(index)
        self.columns = [_unpack(c, len(self.index)) for c in columns]


class Records:
    """Outcomes of points, one column per field (what a batch sends back).

    ``point``, ``error``, ``message``, ``warnings`` are lists with one entry per point;
    ``outputs`` maps each output name (in the order the points first returned them) to a list
    with the point's value, or None where that point did not return the name (a failed point
    returns none; outputs are never None themselves: :func:`scalars` turns None into NaN).
    """

    __slots__ = ("error", "message", "outputs", "point", "warnings")

    def __init__(self) -> None:
        self.point: list[int] = []
        self.outputs: dict[str, list[Any]] = {}
        self.error: list[str | None] = []
        self.message: list[str | None] = []
        self.warnings: list[str | None] = []

    def __len__(self) -> int:
        return len(self.point)

    def append(self, index: int, outputs: Mapping[str, Any], error: str | None,
               message: str | None, warned: str | None) -> None:
        """Add one point's outcome."""
        cols = self.outputs
        if outputs.keys() == cols.keys():            # the usual case: the same names again
            for key, value in outputs.items():
                cols[key].append(value)
        else:
            n = len(self.point)
            for key, value in outputs.items():
                col = cols.get(key)
                if col is None:
                    cols[key] = col = [None] * n
                col.append(value)
            n += 1
            for col in cols.values():
                if len(col) < n:
                    col.append(None)
        self.point.append(int(index))
        self.error.append(error)
        self.message.append(message)
        self.warnings.append(warned)

    def extend(self, other: Records) -> None:
        """Append every point of ``other``."""
        n, m = len(self), len(other)
        for key, col in other.outputs.items():
            mine = self.outputs.get(key)
            if mine is None:
                self.outputs[key] = mine = [None] * n
            mine.extend(col)
        for col in self.outputs.values():
            if len(col) < n + m:
                col.extend([None] * m)
        self.point.extend(other.point)
        self.error.extend(other.error)
        self.message.extend(other.message)
        self.warnings.extend(other.warnings)

    def rows(self) -> list[dict[str, Any]]:
        """One dict per point: ``point``, ``outputs`` (the names it returned), ``error``,
        ``message``, ``warnings``."""
        names = list(self.outputs)
        out = []
        for j, i in enumerate(self.point):
            outs = {k: self.outputs[k][j] for k in names if self.outputs[k][j] is not None}
            out.append({"point": i, "outputs": outs, "error": self.error[j],
                        "message": self.message[j], "warnings": self.warnings[j]})
        return out

    @classmethod
    def from_rows(cls, rows: Any) -> Records:
        """The inverse of :meth:`rows`."""
        rec = cls()
        for r in rows:
            rec.append(r["point"], r["outputs"], r["error"], r["message"], r["warnings"])
        return rec

    def rename(self, name: Callable[[str], str]) -> None:
        """Rename every output column through ``name``."""
        self.outputs = {name(k): v for k, v in self.outputs.items()}

    def __getstate__(self) -> tuple[Any, ...]:
        return (_pack_index(self.point), {k: _pack(v) for k, v in self.outputs.items()},
                _pack(self.error), _pack(self.message), _pack(self.warnings))

    def __setstate__(self, state: tuple[Any, ...]) -> None:
        point, outputs, error, message, warned = state
        self.point = _unpack_index(point)
        n = len(self.point)
        self.outputs = {k: _unpack(v, n) for k, v in outputs.items()}
        self.error, self.message = _unpack(error, n), _unpack(message, n)
        self.warnings = _unpack(warned, n)


# ---- compact pickles of columns: what a worker sends and receives -------------------------------
# A column of Python floats travels as one float64 array (8 bytes a value, one buffer) and comes
# back as the same Python floats (``tolist`` is exact); a column of Nones as None; a run of
# consecutive indices as its bounds. Anything else travels as the list it is.
_FLOATS, _NONES = "f8", "none"


def _pack(col: list[Any]) -> Any:
    if col.count(None) == len(col):
        return (_NONES,)
    if set(map(type, col)) == {float}:
        return (_FLOATS, np.array(col, dtype=np.float64))
    return col


def _unpack(packed: Any, n: int) -> list[Any]:
    if type(packed) is tuple:
        return packed[1].tolist() if packed[0] == _FLOATS else [None] * n
    return packed


def _pack_index(index: list[int]) -> Any:
    if index and index[-1] - index[0] == len(index) - 1 and index == list(
            range(index[0], index[-1] + 1)):
        return (index[0], index[-1] + 1)
    return index


def _unpack_index(packed: Any) -> list[int]:
    return list(range(*packed)) if type(packed) is tuple else packed


def evaluate(study: Callable[..., Any], index: int, point: Mapping[str, Any]) -> dict[str, Any]:
    """Run ``study(**point)`` and record the outcome.

    Returns
    -------
    dict
        ``point`` (the index), ``outputs`` (dict of scalars, empty on failure), ``error`` (the
        exception's class name or None), ``message``, ``warnings`` (``"Class: text"`` of each
        distinct warning raised, joined by newlines, or None) and ``seconds`` (compute time).
        Any :class:`Exception` is recorded; KeyboardInterrupt and SystemExit pass.
    """
    t0 = time.perf_counter()
    row = run_batch(study, [(index, point)]).rows()[0]
    row["seconds"] = time.perf_counter() - t0
    return row


_FAILED = object()       # run_batch's result of a point that raised
#: run_batch converts the results of this many points at a time (bounds the memory they hold)
CONVERT_EVERY = 4096


def _leading(study: Any, names: tuple[str, ...]) -> list[int] | None:
    """Where ``names`` sit among the leading parameters of a plain Python function.

    Returns the order in which to pass the grid columns positionally (``study(*values)`` binds
    exactly as ``study(**point)`` does, at half the cost of building and unpacking a dict), or
    None when the study is not such a function (a scene, a callable object, a function taking
    ``**kwargs`` or position-only parameters).
    """
    code = getattr(study, "__code__", None)
    if type(study) is not FunctionType or code is None or code.co_posonlyargcount \
            or len(names) > code.co_argcount:
        return None
    lead = code.co_varnames[:len(names)]
    if set(lead) != set(names):
        return None
    return [names.index(v) for v in lead]


def _calls(study: Any, batch: Any) -> tuple[list[int], Any, bool]:
    """The indices of a batch, an iterator over the arguments of each point's call, and
    whether they are positional (tuples) or keyword (dicts)."""
    if type(batch) is Points:
        order = _leading(study, batch.names)
        if order is not None:
            return batch.index, zip(*[batch.columns[k] for k in order]), True
        return batch.index, map(dict, map(zip, itertools.repeat(batch.names),
                                          zip(*batch.columns))), False
    pairs = list(batch)
    return [i for i, _ in pairs], iter([p for _, p in pairs]), False


def _warning_text(caught: list[Any]) -> str:
    seen: list[str] = []
    for w in caught:
        text = f"{w.category.__name__}: {w.message}"
        if text not in seen:
            seen.append(text)
    return "\n".join(seen)


def _convert(results: list[Any], errors: dict[int, tuple[str, str]], base: int,
             into: Records) -> None:
    """Append the outputs of ``results`` (raw study results of points ``base``, ``base + 1``,
    ... of a batch; :data:`_FAILED` for a point that raised) to ``into.outputs``, as
    :func:`scalars` makes them; an output that does not convert is an error of its point.

    The usual case (every result a dict of floats under the same names) goes column by column;
    anything else point by point, in order.
    """
    cols = into.outputs
    n = len(results)
    first = results[0] if n else None
    if type(first) is dict and first and set(map(type, results)) == {dict} \
            and set(map(len, results)) == {len(first)} and (not cols or cols.keys() == first.keys()):
        try:
            new = {k: list(map(itemgetter(k), results)) for k in first}
        except KeyError:                      # another name somewhere
            new = None
        if new is not None and all(type(k) is str and set(map(type, c)) == {float}
                                   for k, c in new.items()):
            for k, c in new.items():
                col = cols.get(k)
                if col is None:
                    cols[k] = c
                else:
                    col.extend(c)
            return
    done = len(into.point) - n                # points of this batch converted before these
    for j, result in enumerate(results):
        outputs: Mapping[str, Any] = {}
        if result is not _FAILED:
            try:
                outputs = scalars(result)
            except Exception as err:          # noqa: BLE001 - an invalid output
                errors[base + j] = (type(err).__name__, str(err))
        m = done + j
        for key, value in outputs.items():
            col = cols.get(key)
            if col is None:
                cols[key] = col = [None] * m
            col.append(value)
        for col in cols.values():
            if len(col) <= m:
                col.append(None)


def run_batch(study: Callable[..., Any], batch: Any, out: Records | None = None) -> Records:
    """Run ``study`` at each ``(index, point)`` of ``batch`` (a :class:`Points` or a list of
    pairs), in order, and record each outcome as :func:`evaluate` describes.

    Every point records its own warnings, whatever ran before: warnings are caught under the
    ``"always"`` filter (set once per batch and set again if a study changed the filters), and
    each point keeps the distinct ones it raised.

    The loop does the least per point (the call, its warnings, its error if any); the results
    are turned into columns :data:`CONVERT_EVERY` points at a time, in one go when they are
    dicts of floats under the same names (the sweep's own cost per point is measured in
    ``benchmarks/sweep_scaling.py``).

    Parameters
    ----------
    out : Records, optional
        Receives the outcomes, also of the points finished before an exception such as
        KeyboardInterrupt stopped the batch (a caller in this process keeps them); default a
        new one.
    """
    part = Records()
    errors: dict[int, tuple[str, str]] = {}
    warned: dict[int, str] = {}
    results: list[Any] = []
    keep = results.append
    base = 0                                  # points converted so far
    index, calls, positional = _calls(study, batch)
    mod = warnings
    try:
        with mod.catch_warnings(record=True) as caught:
            mod.simplefilter("always")
            top = mod.filters[0]
            while True:
                for args in itertools.islice(calls, CONVERT_EVERY):
                    wf = mod.filters
                    if not wf or wf[0] is not top:
                        mod.simplefilter("always")
                        top = mod.filters[0]
                    try:
                        keep(study(*args) if positional else study(**args))
                    except Exception as err:      # noqa: BLE001 - recorded per point by design
                        errors[base + len(results)] = (type(err).__name__, str(err))
                        keep(_FAILED)
                    if caught:
                        warned[base + len(results) - 1] = _warning_text(caught)
                        del caught[:]
                if len(results) < CONVERT_EVERY:
                    break
                part.point = index[:base + len(results)]
                _convert(results, errors, base, part)
                base += len(results)
                results.clear()
    finally:
        n = base + len(results)
        part.point = index[:n]
        _convert(results, errors, base, part)
        if type(batch) is not Points:
            part.point = [int(i) for i in part.point]
        part.error = [None] * n
        part.message = [None] * n
        part.warnings = [None] * n
        for j, (error, message) in errors.items():
            if j < n:
                part.error[j], part.message[j] = error, message
        for j, text in warned.items():
            if j < n:
                part.warnings[j] = text
        if out is None:
            out = part
        elif len(out):
            out.extend(part)
        else:
            for name in Records.__slots__:
                setattr(out, name, getattr(part, name))
    return out


def run_calls(fn: Callable[..., Any], batch: Any, out: Records | None = None) -> Records:
    """``fn(**point)`` for each ``(index, point)`` of ``batch``, its return value kept as it is
    (output ``"value"``): the runner of :func:`~contactlab.sweeps.run.run_tasks`, whose tasks
    return arrays. An exception is not recorded: it ends the batch and reaches the caller."""
    rec = Records() if out is None else out
    for index, point in batch:
        value = fn(**point)
        rec.append(index, {"value": value}, None, None, None)
    return rec
