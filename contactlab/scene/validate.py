"""Validation of a raw scene mapping, before any computation.

:func:`validate` walks the whole scene and collects every problem as a ``(key path, value,
allowed)`` triple; only at the end does it raise one :class:`~contactlab.errors.SceneError` whose
``issues`` hold them all. Unknown keys are errors with a did-you-mean (difflib). Quantities are
converted to SI floats (:mod:`.units`). The result is the *normalised* scene: the same nesting,
SI floats, only the keys the user gave (defaults are applied by the planner and the runner, so a
normalised scene round-trips unchanged).

Profiles and materials are looked up by name through :func:`profile_class` /
:func:`material_class`: the single place to swap in ``contactlab.registry`` once it lands.
"""
from __future__ import annotations

import difflib
import inspect
import math
import re
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np

from ..errors import ContactlabError, ParameterError, SceneError, UnknownNameError
from ..loadpath.base import canonical_unit
from .units import DIMENSION_OF_SI_UNIT, parse_quantity, unit_factor

__all__ = ["validate", "profile_class", "material_class", "make_profile", "make_material",
           "SECTIONS", "SERIES", "FIELDS", "EFFECTS", "METHODS", "CONTROLS", "SEGMENTS",
           "MAX_STEPS", "read_table", "resolve_file", "WEAR_KEYS", "FRETTING_MAP_KEYS",
           "CRITERIA", "MAX_MAP_POINTS", "fretting_segment", "axis_values"]

Issue = tuple[str, Any, str]

#: top-level tables of a scene
SECTIONS = ("scene", "profile", "materials", "interface", "load_path", "outputs", "solver",
            "wear", "fretting_map")
#: per-step series a run can write -> the effect that produces it
SERIES = {"time": "normal", "depth": "normal", "force": "normal", "radius": "normal",
          "stiffness": "normal", "peak_pressure": "normal", "twist": "torsion",
          "torque": "torsion", "stick_radius": None, "dissipated_energy": "slip",
          "displacement": "tangential", "tangential_force": "tangential"}
#: field outputs (at the final step, over radius) -> the effect that produces it
FIELDS = {"pressure": "normal", "surface_displacement": "normal", "shear": "torsion"}
#: effects in dependency order
EFFECTS = ("normal", "adhesion", "viscoelastic", "tangential", "torsion", "slip")
METHODS = ("no-slip", "exact", "mdr")
#: load-path control -> (axis, dimension)
CONTROLS = {"depth": ("normal", "length"), "force": ("normal", "force"),
            "displacement": ("shift", "length"), "tangential_force": ("shift", "force"),
            "twist": ("twist", "angle"), "torque": ("twist", "torque")}
#: segment kind -> {option: (dimension or "int"/"count", required)}
SEGMENTS: dict[str, dict[str, tuple[str, bool]]] = {
    "ramp": {"steps": ("int", True), "duration": ("time", False)},
    "hold": {"steps": ("int", True), "duration": ("time", False)},
    "sinusoid": {"cycles": ("count", True), "steps_per_cycle": ("int", False),
                 "period": ("time", False)},
    "table": {"file": ("path", False), "time": ("array", False)},
    "repeat": {"times": ("int", True), "last": ("int", False)},
}
#: a scene may not ask for more load steps than this (fuzzed scenes must stay cheap)
MAX_STEPS = 200_000
#: most field points
MAX_FIELD_POINTS = 100_000
#: keys of a [wear] table -> (dimension or kind, required)
WEAR_KEYS = {"wear_coefficient": ("wear_coefficient", True), "cycles": ("count", True),
             "checkpoints": ("checkpoints", False), "method": ("method", False),
             "n_grid": ("int", False), "jump_rtol": ("dimensionless", False),
             "max_radius": ("length", False)}
#: keys of a [fretting_map] table
FRETTING_MAP_KEYS = ("force", "twist_amplitude", "displacement_amplitude", "method", "criterion",
                     "threshold")
#: torsional gross-slip criteria of a fretting map (docs/fretting.md, section 2)
CRITERIA = ("energy_ratio", "stick_ratio", "torque_ratio")
#: most points of a scene's fretting map (force x amplitude)
MAX_MAP_POINTS = 250_000
#: most cycles of a scene's wear run, and most checkpoints
MAX_WEAR_CYCLES = 1e12
MAX_CHECKPOINTS = 1000

# ---- name lookup (swap in contactlab.registry here) ---------------------------------------------
# Extra keys some built-ins accept besides their constructor arguments: key -> dimension/kind.
_PROFILE_ALTERNATES: dict[str, dict[str, str]] = {
    "cone": {"half_angle": "angle"},
    "tabulated": {"file": "path", "r": "array", "f": "array", "interpolation": "choice",
                  "r_unit": "unit:length", "f_unit": "unit:length", "smoothing": "smoothing",
                  "noise": "length", "admissible": "admissible", "axis": "axis"},
    "polynomial": {"terms": "terms"},
}
_MATERIAL_ALTERNATES: dict[str, dict[str, str]] = {"elastic": {"G": "pressure"}}


def _registry_table(kind: str) -> dict[str, type]:
    """Every type registered for ``kind`` (built-ins and entry-point plugins) by name."""
    from ..registry import registry
    return {name: registry.get(kind, name) for name in registry.available(kind)}


def _profile_table() -> dict[str, type]:
    return _registry_table("profile")


def _material_table() -> dict[str, type]:
    return _registry_table("material")


def _lookup(kind: str, name: str, table: dict[str, type]) -> type:
    if name in table:
        return table[name]
    close = difflib.get_close_matches(name, list(table), n=3, cutoff=0.6)
    hint = f" Did you mean {' or '.join(repr(c) for c in close)}?" if close else ""
    raise UnknownNameError(f"{kind} type={name!r} is unknown: available are "
                           f"{sorted(table)}.{hint}")


def profile_class(name: str) -> type:
    """Profile class registered under ``name`` in the plugin registry (built-ins and plugins)."""
    return _lookup("profile", name, _profile_table())


def material_class(name: str) -> type:
    """Material class registered under ``name`` in the plugin registry."""
    return _lookup("material", name, _material_table())


def resolve_file(value: str | Path, base_dir: Path | None, allow_outside: bool = True) -> Path:
    """The path a scene's file reference names.

    A relative name is taken relative to ``base_dir`` (the scene's folder) and, unless
    ``allow_outside``, must stay inside it after resolving ``..`` and symbolic links; an absolute
    name is the user's explicit choice and is used as given.

    Raises
    ------
    ParameterError
        A relative name that leaves the scene's folder (``../../etc/passwd``, or a link to
        outside) while ``allow_outside`` is False. The message never shows file contents.
    """
    p = Path(value)
    if p.is_absolute() or base_dir is None:
        return p
    full = Path(base_dir) / p
    if not allow_outside:
        root = Path(base_dir).resolve()
        if not full.resolve().is_relative_to(root):
            raise ParameterError(
                f"file {str(value)!r} resolves outside the scene's folder {str(root)!r}: scene "
                "files may only refer to files in their folder or below (give an absolute "
                "path, or run with --allow-outside, to read it anyway).")
    return full


def make_profile(type_: str, params: Mapping[str, Any], base_dir: Path | None = None) -> Any:
    """Build a profile from its scene table (SI values): the one constructor call for scenes."""
    cls = profile_class(type_)
    p = dict(params)
    if type_ == "cone" and "half_angle" in p:
        return cls.from_half_angle(p["half_angle"])
    if type_ == "tabulated" and "file" in p:
        path = resolve_file(p["file"], base_dir)
        return cls.from_csv(path, quote_contents=False,    # never show the file in a message
                            **{k: v for k, v in p.items() if k != "file"})
    if type_ == "polynomial":
        return cls([tuple(t) for t in p["terms"]])
    return cls(**p)


_make_profile = make_profile   # the name the scene issue asked for


def make_material(type_: str, params: Mapping[str, Any]) -> Any:
    """Build a material from its scene table (SI values)."""
    cls = material_class(type_)
    p = dict(params)
    if type_ == "elastic" and "G" in p:
        return cls.from_shear_modulus(p["G"], p.get("nu"))
    return cls(**p)


def _spec(cls: type, alternates: dict[str, str]) -> tuple[dict[str, str], set[str]]:
    """Accepted keys of a class's scene table -> dimension, and the required ones."""
    units = {p.name: p.unit for p in getattr(cls, "params", ())}
    sig = inspect.signature(cls.__init__)
    keys: dict[str, str] = {}
    required: set[str] = set()
    for name, par in list(sig.parameters.items())[1:]:
        if par.kind in (par.VAR_POSITIONAL, par.VAR_KEYWORD):
            continue
        unit = units.get(name, "1")
        keys[name] = DIMENSION_OF_SI_UNIT.get(canonical_unit(unit), "number")
        if par.default is inspect.Parameter.empty:
            required.add(name)
    keys.update(alternates)
    return keys, required


# ---- the checker ---------------------------------------------------------------------------------
class _Checker:
    def __init__(self, base_dir: Path | None, allow_outside: bool = False) -> None:
        self.allow_outside = allow_outside
        self.issues: list[Issue] = []
        self.base_dir = base_dir
        self.file_steps: dict[str, int] = {}     # load_path[i] -> rows of its CSV history

    def add(self, path: str, value: Any, allowed: str) -> None:
        self.issues.append((path, value, allowed))

    def table(self, path: str, value: Any) -> dict | None:
        if not isinstance(value, Mapping):
            self.add(path, value, "a table (mapping of keys to values)")
            return None
        bad = [k for k in value if not isinstance(k, str)]
        for k in bad:
            self.add(f"{path}.{k!r}", k, "string keys")
        return {k: v for k, v in value.items() if isinstance(k, str)}

    def unknown_keys(self, path: str, table: Mapping, allowed: Any) -> None:
        allowed = list(allowed)
        for k in table:
            if k not in allowed:
                close = difflib.get_close_matches(k, allowed, n=1, cutoff=0.6)
                hint = f"; did you mean {close[0]!r}?" if close else ""
                self.add(_join(path, k), table[k], f"a key from {sorted(allowed)}{hint}")

    def quantity(self, path: str, value: Any, dim: str, domain: str = "real") -> float | None:
        try:
            v = parse_quantity(value, dim, path)
        except SceneError as err:
            self.issues.extend(err.issues)
            return None
        ok = {"real": True, "positive": v > 0, "nonnegative": v >= 0}[domain]
        if not ok:
            self.add(path, value, {"positive": "> 0", "nonnegative": ">= 0"}[domain])
            return None
        return v

    def integer(self, path: str, value: Any, low: int, high: int) -> int | None:
        if isinstance(value, bool) or not isinstance(value, int):
            if isinstance(value, float) and value.is_integer() and low <= value <= high:
                return int(value)
            self.add(path, value, f"an integer {low}..{high}")
            return None
        if not low <= value <= high:
            self.add(path, value, f"an integer {low}..{high}")
            return None
        return value

    def choice(self, path: str, value: Any, allowed: Any) -> Any:
        allowed = list(allowed)
        if not isinstance(value, str) or value not in allowed:
            close = (difflib.get_close_matches(value, allowed, n=1, cutoff=0.6)
                     if isinstance(value, str) else [])
            hint = f"; did you mean {close[0]!r}?" if close else ""
            self.add(path, value, f"one of {allowed}{hint}")
            return None
        return value

    def string_list(self, path: str, value: Any, allowed: Any) -> list[str] | None:
        if not isinstance(value, list):
            self.add(path, value, f"a list of names from {sorted(allowed)}")
            return None
        out = []
        for i, v in enumerate(value):
            c = self.choice(f"{path}[{i}]", v, allowed)
            if c is not None:
                if c in out:
                    self.add(f"{path}[{i}]", v, "each name once")
                else:
                    out.append(c)
        return out

    def array(self, path: str, value: Any, dim: str) -> list[float] | None:
        if not isinstance(value, list) or len(value) == 0:
            self.add(path, value, "a non-empty list of numbers")
            return None
        out = []
        for i, v in enumerate(value):
            q = self.quantity(f"{path}[{i}]", v, dim)
            if q is None:
                return None
            out.append(q)
        return out

    def file(self, path: str, value: Any) -> str | None:
        if not isinstance(value, str) or not value:
            self.add(path, value, "a file name (relative to the scene file)")
            return None
        try:
            p = resolve_file(value, self.base_dir, self.allow_outside)
        except ParameterError:
            self.add(path, value, "a file inside the scene's folder (an absolute path or "
                     "--allow-outside reads files elsewhere)")
            return None
        if not p.is_file():
            self.add(path, value, f"an existing file (looked for {str(p)!r})")
            return None
        return value


def _join(path: str, key: str) -> str:
    return f"{path}.{key}" if path else key


# ---- sections --------------------------------------------------------------------------------------
def _typed_object(ck: _Checker, path: str, raw: Any, kind: str) -> dict | None:
    tab = ck.table(path, raw)
    if tab is None:
        return None
    if "type" not in tab:
        ck.add(f"{path}.type", None, f"a {kind} type name (required)")
        return None
    type_ = tab["type"]
    table = _profile_table() if kind == "profile" else _material_table()
    if not isinstance(type_, str) or type_ not in table:
        ck.choice(f"{path}.type", type_, sorted(table))
        return None
    cls = table[type_]
    alternates = (_PROFILE_ALTERNATES if kind == "profile" else _MATERIAL_ALTERNATES).get(type_, {})
    keys, required = _spec(cls, alternates)
    params = {k: v for k, v in tab.items() if k != "type"}
    ck.unknown_keys(path, params, list(keys) + ["type"])
    out: dict[str, Any] = {"type": type_}
    n_before = len(ck.issues)
    for k, v in params.items():
        if k not in keys:
            continue
        dim = keys[k]
        kp = f"{path}.{k}"
        if dim == "path":
            val = ck.file(kp, v)
        elif dim == "array":
            val = ck.array(kp, v, "length")
        elif dim == "choice":
            val = ck.choice(kp, v, ("linear", "cubic"))
        elif dim.startswith("unit:"):          # a unit name for the columns of a CSV file
            try:
                unit_factor(v, dim[5:], kp)
                val = v
            except SceneError as err:
                ck.issues.extend(err.issues)
                val = None
        elif dim == "smoothing":
            val = (v if v == "auto" else
                   ck.quantity(kp, v, "dimensionless", "nonnegative") if not isinstance(v, str)
                   else ck.choice(kp, v, ("auto",)))
        elif dim == "admissible":
            val = ck.choice(kp, v, ("nearest",))
        elif dim == "axis":
            val = ck.choice(kp, v, ("even", "free"))
        elif dim == "terms":
            val = _terms(ck, kp, v)
        elif isinstance(v, list):    # sequence parameters (e.g. Prony-series moduli)
            val = ck.array(kp, v, dim if dim != "number" else "dimensionless")
        else:
            val = ck.quantity(kp, v, dim)
        if val is not None:
            out[k] = val
    # required keys, with the built-in alternatives
    alt_groups = {("cone", "slope"): "half_angle", ("elastic", "E"): "G"}
    for k in sorted(required):
        alt = alt_groups.get((type_, k))
        if type_ == "tabulated" and k in ("r", "f"):
            continue
        if k not in params and not (alt and alt in params):
            ck.add(f"{path}.{k}", None, f"required for type {type_!r}"
                   + (f" (or give {alt!r})" if alt else ""))
    for (t, k), alt in alt_groups.items():
        if t == type_ and k in params and alt in params:
            ck.add(f"{path}.{alt}", params[alt], f"either {k!r} or {alt!r}, not both")
    if type_ == "tabulated":
        has_file, has_rf = "file" in params, ("r" in params or "f" in params)
        if has_file == has_rf:
            ck.add(f"{path}.file", params.get("file"),
                   "either file = 'table.csv' or both r = [...] and f = [...]")
        elif has_rf and not ("r" in params and "f" in params):
            ck.add(f"{path}.{'f' if 'r' in params else 'r'}", None, "r and f together")
    if len(ck.issues) > n_before:
        return None
    try:
        obj = (make_profile(type_, {k: v for k, v in out.items() if k != "type"}, ck.base_dir)
               if kind == "profile" else
               make_material(type_, {k: v for k, v in out.items() if k != "type"}))
    except (ContactlabError, ValueError, TypeError) as err:
        msg = _first_line(err)
        m = re.match(r"^([A-Za-z_]\w*)=.*? is invalid: (.*)$", msg)
        if m and m.group(1) in params:
            ck.add(f"{path}.{m.group(1)}", params[m.group(1)], m.group(2))
        else:
            ck.add(path, dict(tab), msg)
        return None
    return {"out": out, "obj": obj}


def _terms(ck: _Checker, path: str, value: Any) -> list | None:
    if not isinstance(value, list) or not value:
        ck.add(path, value, "a non-empty list of [c, n] pairs")
        return None
    out = []
    for i, t in enumerate(value):
        if not isinstance(t, list) or len(t) != 2:
            ck.add(f"{path}[{i}]", t, "a [c, n] pair of plain numbers (SI)")
            return None
        c = ck.quantity(f"{path}[{i}][0]", t[0], "number", "positive")
        n = ck.quantity(f"{path}[{i}][1]", t[1], "number", "positive")
        if c is None or n is None:
            return None
        out.append([c, n])
    return out


def _first_line(err: BaseException) -> str:
    return str(err).splitlines()[0] if str(err) else type(err).__name__


def read_table(path: Path) -> dict[str, np.ndarray]:
    """Read a load-history CSV: a header row of column names with optional units in the grammar
    of scene files (``time [ms],force [kN],twist [deg]``), then numbers; returns SI columns.

    The reader of :func:`contactlab.loadpath.io.read_history` (same units, delimiters and
    byte-order marks), never quoting the file: columns of unknown names are returned as read,
    for the validator to report."""
    from ..loadpath.io import DIMENSIONS
    from ..numeric.tables import read_columns
    names, cols = read_columns(path, dimension=lambda n: DIMENSIONS.get(n, "ignore"),
                               quote=False, known_names=tuple(DIMENSIONS))
    if any(n.startswith("column ") for n in names):
        # (the header is not echoed: a mistaken file name must not print another file's lines)
        raise ValueError("the header row must name the columns (time, force, depth, ...)")
    n_rows = max((len(v) for v in cols.values()), default=0)
    if n_rows > MAX_STEPS:
        raise ValueError(f"{n_rows} rows exceed the limit of {MAX_STEPS} steps")
    return cols


def _segment(ck: _Checker, path: str, raw: Any, axes: dict[str, tuple[str, str]]) -> dict | None:
    tab = ck.table(path, raw)
    if tab is None:
        return None
    kinds = [k for k in tab if k in SEGMENTS]
    if len(kinds) != 1 or len(tab) != 1:
        extra = [k for k in tab if k not in SEGMENTS]
        ck.unknown_keys(path, {k: None for k in extra}, SEGMENTS)
        if len(kinds) != 1:
            ck.add(path, dict(tab), f"exactly one segment kind from {sorted(SEGMENTS)}")
        return None
    kind = kinds[0]
    sp = f"{path}.{kind}"
    body = ck.table(sp, tab[kind])
    if body is None:
        return None
    opts = SEGMENTS[kind]
    allowed_keys = list(opts) + (list(CONTROLS) if kind not in ("hold", "repeat") else [])
    ck.unknown_keys(sp, body, allowed_keys)
    out: dict[str, Any] = {}
    n_before = len(ck.issues)
    for k, (dim, req) in opts.items():
        if k not in body:
            if req:
                ck.add(f"{sp}.{k}", None, f"required for a {kind} segment")
            continue
        v = body[k]
        if dim == "int":
            low = 4 if k == "steps_per_cycle" else 1
            val = ck.integer(f"{sp}.{k}", v, low, MAX_STEPS)
        elif dim == "count":
            val = ck.quantity(f"{sp}.{k}", v, "dimensionless", "positive")
        elif dim == "path":
            val = ck.file(f"{sp}.{k}", v)
        elif dim == "array":
            val = ck.array(f"{sp}.{k}", v, "time")
        else:
            val = ck.quantity(f"{sp}.{k}", v, dim, "positive")
        if val is not None:
            out[k] = val
    controls = [k for k in body if k in CONTROLS]
    if kind in ("ramp", "sinusoid") and not controls:
        ck.add(sp, dict(body), f"at least one control from {sorted(CONTROLS)}")
    for k in controls:
        axis, dim = CONTROLS[k]
        if kind == "table":
            val = ck.array(f"{sp}.{k}", body[k], dim)
        else:
            val = ck.quantity(f"{sp}.{k}", body[k], dim)
        if val is not None:
            out[k] = val
    if kind == "table":
        if ("file" in body) == bool(controls):
            ck.add(sp, dict(body), "either file = 'history.csv' or inline columns "
                   "(time = [...] optional, plus controls such as force = [...])")
        elif "file" in out:
            p = resolve_file(out["file"], ck.base_dir)     # contained: ck.file checked it
            try:
                cols = read_table(p)
            except (OSError, ValueError) as err:
                ck.add(f"{sp}.file", body["file"], f"a readable CSV history ({_first_line(err)})")
                cols = None
            if cols is not None:
                ck.file_steps[path] = max((len(v) for v in cols.values()), default=0)
                for name in cols:
                    if name != "time" and name not in CONTROLS:
                        ck.unknown_keys(f"{sp}.file[columns]", {name: None},
                                        ["time", *CONTROLS])
                controls = [k for k in cols if k in CONTROLS]
                if not controls:
                    ck.add(f"{sp}.file", body["file"], f"a column from {sorted(CONTROLS)}")
                for k, col in cols.items():
                    if not np.all(np.isfinite(col)):
                        ck.add(f"{sp}.file[{k}]", "non-finite", "finite numbers")
        else:
            lens = {k: len(out[k]) for k in out if k in CONTROLS or k == "time"}
            if len(set(lens.values())) > 1:
                ck.add(sp, lens, "columns of equal length")
        if "time" in out and len(ck.issues) == n_before:
            t = np.asarray(out["time"])
            if np.any(np.diff(t) <= 0):
                ck.add(f"{sp}.time", out["time"], "strictly increasing times")
    for k in controls:
        axis = CONTROLS[k][0]
        if axis in axes and axes[axis][0] != k:
            ck.add(f"{sp}.{k}", body.get(k, "(column)"),
                   f"the same control as {axes[axis][1]} ({axes[axis][0]!r}): one control per "
                   f"axis in a load path")
        else:
            axes.setdefault(axis, (k, f"{sp}.{k}"))
    if len(ck.issues) > n_before:
        return None
    return {kind: out}


def _total_steps(segs: list, file_steps: Sequence[int] = ()) -> int:
    """Steps of the whole load path: every segment kind, repeats expanded, and the rows of CSV
    histories (``file_steps[i]``: rows of segment ``i``'s file, read during validation)."""
    counts: list[int] = []
    for i, seg in enumerate(segs):
        if "repeat" in seg:
            k = min(seg["repeat"].get("last", 1), len(counts))
            counts[-k:] = [seg["repeat"]["times"] * sum(counts[-k:])] if k else []
        else:
            counts.append(_segment_steps(seg) or (file_steps[i] if i < len(file_steps) else 0))
    return sum(counts)


def _check_repeats(ck: _Checker, segs: list) -> None:
    """``repeat = { times = N, last = k }`` repeats the ``k`` segments before it (default 1)."""
    for i, seg in enumerate(segs):
        if "repeat" in seg:
            last = seg["repeat"].get("last", 1)
            prior = [s for s in segs[:i] if "repeat" not in s]
            if i == 0 or last > i or any("repeat" in s for s in segs[i - last:i]):
                ck.add(f"load_path[{i}].repeat.last", last,
                       f"1 <= last <= {i} segments before it, none of them a repeat"
                       if prior else "a segment to repeat before the repeat")


def _segment_steps(seg: dict) -> int:
    kind, body = next(iter(seg.items()))
    if kind in ("ramp", "hold"):
        return int(body["steps"])
    if kind == "sinusoid":
        return max(1, int(round(body["cycles"] * body.get("steps_per_cycle", 100))))
    if kind == "repeat" or "file" in body:
        return 0  # repeats and CSV histories: counted by _total_steps
    return max((len(v) for k, v in body.items() if k in CONTROLS or k == "time"), default=0)


def validate(raw: Any, base_dir: str | Path | None = None, *,
             allow_outside: bool = False) -> tuple[dict, dict]:
    """Validate a raw scene mapping and normalise it to SI.

    Parameters
    ----------
    raw : mapping
        The scene as parsed from TOML (or built in Python).
    base_dir : path, optional
        Directory that relative file names (tabulated profiles, CSV histories) refer to.
    allow_outside : bool
        Let relative file names leave ``base_dir`` (``..``, links); default False.

    Returns
    -------
    data : dict
        The normalised scene (SI floats; only the keys given).
    objects : dict
        ``profile``, ``body1``, ``body2`` built objects.

    Raises
    ------
    SceneError
        With ``issues`` listing every problem found (key path, value, allowed).
    """
    ck = _Checker(Path(base_dir) if base_dir is not None else None, allow_outside)
    top = ck.table("", raw)
    if top is None:
        raise SceneError("scene is invalid: expected a table of sections", ck.issues)
    ck.unknown_keys("", top, SECTIONS)
    data: dict[str, Any] = {}
    objects: dict[str, Any] = {}

    if "scene" in top:
        meta = ck.table("scene", top["scene"])
        if meta is not None:
            ck.unknown_keys("scene", meta, ("title", "description"))
            for k in ("title", "description"):
                if k in meta and not isinstance(meta[k], str):
                    ck.add(f"scene.{k}", meta[k], "a string")
            data["scene"] = {k: meta[k] for k in ("title", "description")
                             if isinstance(meta.get(k), str)}

    if "profile" not in top:
        ck.add("profile", None, "a [profile] table with type = one of "
               f"{sorted(_profile_table())} (required)")
    else:
        got = _typed_object(ck, "profile", top["profile"], "profile")
        if got:
            data["profile"], objects["profile"] = got["out"], got["obj"]

    if "materials" not in top:
        ck.add("materials", None, "a [materials] table with body1 and body2 (required)")
    else:
        mats = ck.table("materials", top["materials"])
        if mats is not None:
            ck.unknown_keys("materials", mats, ("body1", "body2"))
            data["materials"] = {}
            for body in ("body1", "body2"):
                if body not in mats:
                    ck.add(f"materials.{body}", None, "a material table, e.g. { type = 'elastic', "
                           "E = '210 GPa', nu = 0.3 } or { type = 'rigid' } (required)")
                    continue
                got = _typed_object(ck, f"materials.{body}", mats[body], "material")
                if got:
                    data["materials"][body], objects[body] = got["out"], got["obj"]

    if "interface" in top:
        itf = ck.table("interface", top["interface"])
        if itf is not None:
            ck.unknown_keys("interface", itf, ("friction", "work_of_adhesion"))
            data["interface"] = {}
            if "friction" in itf:
                v = ck.quantity("interface.friction", itf["friction"], "dimensionless", "positive")
                if v is not None:
                    data["interface"]["friction"] = v
            if "work_of_adhesion" in itf:
                v = ck.quantity("interface.work_of_adhesion", itf["work_of_adhesion"],
                                "energy_per_area", "nonnegative")
                if v is not None:
                    data["interface"]["work_of_adhesion"] = v

    if "load_path" not in top:
        ck.add("load_path", None, "a list of segments ([[load_path]] tables), e.g. "
               "ramp = { force = '100 N', steps = 50 } (required)")
    else:
        lp = top["load_path"]
        if not isinstance(lp, list) or not lp:
            ck.add("load_path", lp, "a non-empty list of segments ([[load_path]] tables)")
        else:
            axes: dict[str, tuple[str, str]] = {}
            segs = [_segment(ck, f"load_path[{i}]", s, axes) for i, s in enumerate(lp)]
            if all(s is not None for s in segs):
                data["load_path"] = segs
                n = _total_steps(segs, [ck.file_steps.get(f"load_path[{i}]", 0)
                                        for i in range(len(segs))])
                if n > MAX_STEPS:
                    ck.add("load_path", f"{n} steps", f"at most {MAX_STEPS} steps in total")
                if "normal" not in axes:
                    ck.add("load_path", [next(iter(s)) for s in segs],
                           "a normal control (force or depth) in at least one segment")
                _check_repeats(ck, segs)

    if "outputs" in top:
        outs = ck.table("outputs", top["outputs"])
        if outs is not None:
            ck.unknown_keys("outputs", outs, ("series", "fields", "field_points", "method",
                                              "effects"))
            o: dict[str, Any] = {}
            if "series" in outs:
                v = ck.string_list("outputs.series", outs["series"], SERIES)
                if v is not None:
                    o["series"] = v
            if "fields" in outs:
                v = ck.string_list("outputs.fields", outs["fields"], FIELDS)
                if v is not None:
                    o["fields"] = v
            if "field_points" in outs:
                v = ck.integer("outputs.field_points", outs["field_points"], 2, MAX_FIELD_POINTS)
                if v is not None:
                    o["field_points"] = v
            if "method" in outs:
                v = ck.choice("outputs.method", outs["method"], METHODS)
                if v is not None:
                    o["method"] = v
            if "effects" in outs:
                v = ck.string_list("outputs.effects", outs["effects"], EFFECTS)
                if v is not None:
                    o["effects"] = v
            data["outputs"] = o

    if "solver" in top:
        sol = ck.table("solver", top["solver"])
        if sol is not None:
            ck.unknown_keys("solver", sol, ("rtol", "n_springs"))
            s: dict[str, Any] = {}
            if "rtol" in sol:
                v = ck.quantity("solver.rtol", sol["rtol"], "dimensionless", "positive")
                if v is not None and v >= 0.1:
                    ck.add("solver.rtol", sol["rtol"], "0 < rtol < 0.1")
                elif v is not None:
                    s["rtol"] = v
            if "n_springs" in sol:
                v = ck.integer("solver.n_springs", sol["n_springs"], 2, 10_000_000)
                if v is not None:
                    s["n_springs"] = v
            data["solver"] = s

    if "wear" in top:
        w = _wear(ck, top["wear"], data, objects)
        if w is not None:
            data["wear"] = w
    if "fretting_map" in top:
        m = _fretting_map(ck, top["fretting_map"], data, objects)
        if m is not None:
            data["fretting_map"] = m

    # cross-section rules
    itf = data.get("interface", {})
    outs = data.get("outputs", {})
    if outs.get("method") in ("exact", "mdr") and "friction" not in itf:
        ck.add("outputs.method", outs["method"], "'no-slip' without interface.friction (the "
               "exact and mdr methods model partial slip and need a friction coefficient)")
    eff = outs.get("effects", [])
    if "slip" in eff and "friction" not in itf:
        ck.add("outputs.effects", "slip", "'slip' only with interface.friction")
    if "adhesion" in eff and not itf.get("work_of_adhesion"):
        ck.add("outputs.effects", "adhesion", "'adhesion' only with interface.work_of_adhesion > 0")
    if "dissipated_energy" in outs.get("series", []) and "friction" not in itf:
        ck.add("outputs.series", "dissipated_energy", "'dissipated_energy' only with "
               "interface.friction (no friction, no dissipation)")
    if ("materials" in data and "body1" in objects and "body2" in objects
            and not any(getattr(objects[b], "is_viscoelastic", False) for b in ("body1", "body2"))):
        try:
            objects["body1"].pair(objects["body2"])
        except (ContactlabError, ValueError) as err:
            ck.add("materials", f"({data['materials']['body1']['type']}, "
                   f"{data['materials']['body2']['type']})", _first_line(err))
    visco = [b for b in ("body1", "body2") if getattr(objects.get(b), "is_viscoelastic", False)]
    if visco:
        other = objects.get("body2" if visco[0] == "body1" else "body1")
        if len(visco) == 2 or (other is not None and getattr(type(other), "name", "") != "rigid"):
            ck.add("materials", f"({data['materials']['body1']['type']}, "
                   f"{data['materials']['body2']['type']})",
                   "a viscoelastic body against a rigid one (the viscoelastic MDR rules cover a "
                   "rigid indenter on a viscoelastic half-space)")
    if "viscoelastic" in eff and not any(getattr(objects.get(b), "is_viscoelastic", False)
                                         for b in ("body1", "body2")):
        ck.add("outputs.effects", "viscoelastic", "'viscoelastic' only with a viscoelastic body")

    if ck.issues:
        raise SceneError(_summary(ck.issues), ck.issues)
    return data, objects


# ---- fretting: [wear] and [fretting_map] -----------------------------------------------------------
def fretting_segment(segments: Sequence[Mapping[str, Any]]) -> tuple[int, str, float] | None:
    """The fretting condition of a load path: the last sinusoid that oscillates a twist or a
    displacement, as ``(segment index, control, amplitude)``, or None."""
    for i in range(len(segments) - 1, -1, -1):
        kind, body = next(iter(segments[i].items()))
        if kind == "sinusoid":
            for k in ("twist", "displacement"):
                if k in body:
                    return i, k, abs(float(body[k]))
    return None


def _fretting_needs(ck: _Checker, path: str, data: dict, objects: dict) -> None:
    """What wear and fretting maps need from the rest of the scene: friction, no adhesion,
    elastic bodies."""
    itf = data.get("interface", {})
    if "friction" not in itf and not any(i[0] == "interface.friction" for i in ck.issues):
        ck.add("interface.friction", None, f"a friction coefficient (required by [{path}]: "
               "fretting is frictional slip)")
    if itf.get("work_of_adhesion"):
        ck.add("interface.work_of_adhesion", itf["work_of_adhesion"], f"0 with [{path}] "
               "(fretting of adhesive contacts is outside the implemented theory)")
    if any(getattr(objects.get(b), "is_viscoelastic", False) for b in ("body1", "body2")):
        ck.add(path, "viscoelastic body", "elastic bodies (fretting and wear are elastic theory)")


def _wear(ck: _Checker, raw: Any, data: dict, objects: dict) -> dict | None:
    tab = ck.table("wear", raw)
    if tab is None:
        return None
    ck.unknown_keys("wear", tab, WEAR_KEYS)
    n_before = len(ck.issues)
    out: dict[str, Any] = {}
    for k, (dim, req) in WEAR_KEYS.items():
        kp = f"wear.{k}"
        if k not in tab:
            if req:
                ck.add(kp, None, {"wear_coefficient": "Archard's coefficient k = K/H, e.g. "
                                  "'1e-6 mm^3/(N*m)' or '1e-15 1/Pa' (required)",
                                  "cycles": "the number of fretting cycles, e.g. 1e6 "
                                  "(required)"}[k])
            continue
        v = tab[k]
        if k == "wear_coefficient":
            val = ck.quantity(kp, v, dim, "nonnegative")
        elif k == "cycles":
            val = ck.quantity(kp, v, "dimensionless", "positive")
            if val is not None and val > MAX_WEAR_CYCLES:
                ck.add(kp, v, f"at most {MAX_WEAR_CYCLES:g} cycles")
                val = None
        elif k == "checkpoints":
            if isinstance(v, list):
                val = ck.array(kp, v, "dimensionless")
                if val is not None and any(x <= 0 for x in val):
                    ck.add(kp, v, "cycle numbers > 0")
                    val = None
                elif val is not None and len(val) > MAX_CHECKPOINTS:
                    ck.add(kp, f"{len(val)} checkpoints", f"at most {MAX_CHECKPOINTS}")
                    val = None
            else:
                val = ck.integer(kp, v, 1, MAX_CHECKPOINTS)
        elif k == "method":
            val = ck.choice(kp, v, ("exact", "mdr"))
        elif k == "n_grid":
            val = ck.integer(kp, v, 16, 20_000)
        elif k == "jump_rtol":
            val = ck.quantity(kp, v, "dimensionless", "positive")
            if val is not None and val >= 0.1:
                ck.add(kp, v, "0 < jump_rtol < 0.1")
                val = None
        else:
            val = ck.quantity(kp, v, dim, "positive")
        if val is not None:
            out[k] = val
    cyc, pts = out.get("cycles"), out.get("checkpoints")
    if isinstance(pts, list) and cyc is not None and max(pts) > cyc:
        ck.add("wear.checkpoints", tab["checkpoints"], f"cycle numbers <= wear.cycles = {cyc:g}")
    _fretting_needs(ck, "wear", data, objects)
    prof = objects.get("profile")
    if prof is not None and math.isfinite(getattr(prof, "wall_radius", math.inf)):
        ck.add("profile.type", data["profile"]["type"], "a profile without a wall for [wear] (a "
               "flat punch cannot be worn into a table; use truncated_paraboloid)")
    segs = data.get("load_path")
    if segs is not None:
        got = fretting_segment(segs)
        if got is None:
            ck.add("wear", "no fretting segment", "a load path with a sinusoid of twist or "
                   "displacement (the fretting amplitude) after the normal force is applied, "
                   "e.g. [[load_path]] sinusoid = { twist = '2 mrad', cycles = 1 }")
        else:
            i, ctrl, amp = got
            body = segs[i]["sinusoid"]
            moving = [k for k in body if k in CONTROLS and CONTROLS[k][0] == "normal"]
            if moving:
                ck.add(f"load_path[{i}].sinusoid.{moving[0]}", body[moving[0]], "no normal "
                       "oscillation in the fretting segment: [wear] runs at constant normal force")
            if amp == 0:
                ck.add(f"load_path[{i}].sinusoid.{ctrl}", body[ctrl], "a non-zero fretting "
                       "amplitude for [wear]")
            normal = {k for s in segs for k in next(iter(s.values()))
                      if k in CONTROLS and CONTROLS[k][0] == "normal"}
            if "depth" in normal:
                ck.add("load_path", "depth", "a force-controlled normal load for [wear] (wear "
                       "runs at constant normal force; give force = ... instead of depth)")
    return out if len(ck.issues) == n_before else None


def _axis(ck: _Checker, path: str, v: Any, dim: str, domain: str) -> list[float] | None:
    """A map axis: a list of quantities or a range table {from, to, points, spacing}."""
    if isinstance(v, list):
        vals = ck.array(path, v, dim)
        if vals is not None and any(x < 0 or (domain == "positive" and x == 0) for x in vals):
            ck.add(path, v, "values > 0" if domain == "positive" else "values >= 0")
            return None
        return vals
    tab = ck.table(path, v)
    if tab is None:
        return None
    keys = ("from", "to", "points", "spacing")
    ck.unknown_keys(path, tab, keys)
    n_before = len(ck.issues)
    for k in ("from", "to", "points"):
        if k not in tab:
            ck.add(f"{path}.{k}", None, "required in a range table { from = ..., to = ..., "
                   "points = N, spacing = 'log' or 'linear' }")
    lo = ck.quantity(f"{path}.from", tab["from"], dim, "nonnegative") if "from" in tab else None
    hi = ck.quantity(f"{path}.to", tab["to"], dim, "positive") if "to" in tab else None
    n = ck.integer(f"{path}.points", tab["points"], 1, 10_000) if "points" in tab else None
    spacing = (ck.choice(f"{path}.spacing", tab["spacing"], ("linear", "log"))
               if "spacing" in tab else "linear")
    if lo is not None and hi is not None and lo > hi:
        ck.add(f"{path}.to", tab["to"], f">= from ({tab['from']!r})")
    if lo == 0 and (spacing == "log" or domain == "positive"):
        ck.add(f"{path}.from", tab["from"], "> 0" + (" with spacing = 'log'"
                                                     if spacing == "log" else ""))
    if len(ck.issues) > n_before or None in (lo, hi, n, spacing):
        return None
    return {"from": lo, "to": hi, "points": n, "spacing": spacing}  # type: ignore[return-value]


def axis_values(spec: Any) -> np.ndarray:
    """The values of a validated map axis (list, or range table)."""
    if isinstance(spec, Mapping):
        lo, hi, n = spec["from"], spec["to"], int(spec["points"])
        return (np.geomspace(lo, hi, n) if spec.get("spacing") == "log"
                else np.linspace(lo, hi, n))
    return np.asarray(spec, float)


def _fretting_map(ck: _Checker, raw: Any, data: dict, objects: dict) -> dict | None:
    tab = ck.table("fretting_map", raw)
    if tab is None:
        return None
    ck.unknown_keys("fretting_map", tab, FRETTING_MAP_KEYS)
    n_before = len(ck.issues)
    out: dict[str, Any] = {}
    if "force" not in tab:
        ck.add("fretting_map.force", None, "the normal forces, a list ['10 N', '100 N'] or a "
               "range { from = '10 N', to = '1 kN', points = 8, spacing = 'log' } (required)")
    else:
        v = _axis(ck, "fretting_map.force", tab["force"], "force", "positive")
        if v is not None:
            out["force"] = v
    amps = [k for k in ("twist_amplitude", "displacement_amplitude") if k in tab]
    if len(amps) != 1:
        ck.add("fretting_map", amps or None, "exactly one of twist_amplitude (torsional "
               "fretting) or displacement_amplitude (tangential fretting)")
    for k in amps:
        v = _axis(ck, f"fretting_map.{k}", tab[k],
                  "angle" if k == "twist_amplitude" else "length", "nonnegative")
        if v is not None:
            out[k] = v
    if "method" in tab:
        v = ck.choice("fretting_map.method", tab["method"], ("exact", "mdr"))
        if v is not None:
            out["method"] = v
    if "criterion" in tab:
        v = ck.choice("fretting_map.criterion", tab["criterion"], CRITERIA)
        if v is not None:
            out["criterion"] = v
    if "threshold" in tab:
        v = ck.quantity("fretting_map.threshold", tab["threshold"], "dimensionless", "positive")
        if v is not None and v >= 1:
            ck.add("fretting_map.threshold", tab["threshold"], "0 < threshold < 1")
        elif v is not None:
            out["threshold"] = v
    if amps == ["displacement_amplitude"] and ("criterion" in tab or "threshold" in tab):
        ck.add("fretting_map.criterion", tab.get("criterion", tab.get("threshold")),
               "no criterion for a tangential map (gross slip is exact: the whole contact "
               "slides at delta_t = mu E* d / G*)")
    if len(ck.issues) == n_before and len(amps) == 1:
        n = axis_values(out["force"]).size * axis_values(out[amps[0]]).size
        if n > MAX_MAP_POINTS:
            ck.add("fretting_map", f"{n} points", f"at most {MAX_MAP_POINTS} points "
                   "(force x amplitude); run larger maps through contactlab.sweep")
    _fretting_needs(ck, "fretting_map", data, objects)
    return out if len(ck.issues) == n_before else None


def _summary(issues: list[Issue]) -> str:
    lines = [f"scene is invalid ({len(issues)} problem{'s' if len(issues) > 1 else ''}):"]
    for path, value, allowed in issues:
        lines.append(f"  {path or '<scene>'} = {_short(value)}: expected {allowed}")
    return "\n".join(lines)


def _short(value: Any) -> str:
    s = repr(value)
    return s if len(s) <= 80 else s[:77] + "..."


def is_finite_number(v: Any) -> bool:
    return isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v)
