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
import math
import time
import warnings
from collections.abc import Callable, Mapping
from pathlib import Path
from typing import Any

import numpy as np

from ..errors import ParameterError, SceneError
from .keypath import set_key_path

__all__ = ["SceneStudy", "as_study", "scalars", "evaluate", "run_batch", "study_id"]


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
            for path, value, allowed in err.issues:
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
    if isinstance(result, Mapping):
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
        key = str(key)
        if isinstance(value, (list, tuple, np.ndarray)):
            try:
                arr = np.asarray(value, dtype=float).ravel()
            except (TypeError, ValueError):
                if strict:
                    raise ParameterError(f"study output {key!r} is not an array of numbers.")
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
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")   # every point records its own warnings, whatever ran before
        try:
            outputs, error, message = scalars(study(**point)), None, None
        except Exception as err:          # noqa: BLE001 - recorded per point by design
            outputs, error, message = {}, type(err).__name__, str(err)
    seen: list[str] = []
    for w in caught:
        text = f"{w.category.__name__}: {w.message}"
        if text not in seen:
            seen.append(text)
    return {"point": int(index), "outputs": outputs, "error": error, "message": message,
            "warnings": "\n".join(seen) or None, "seconds": time.perf_counter() - t0}


def run_batch(study: Callable[..., Any],
              batch: list[tuple[int, Mapping[str, Any]]]) -> list[dict[str, Any]]:
    """:func:`evaluate` each ``(index, point)`` of ``batch``, in order."""
    return [evaluate(study, i, p) for i, p in batch]
