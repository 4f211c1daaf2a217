"""Validation of a raw scene mapping, before any computation.

:func:`validate` walks the whole scene and collects every problem as a ``(key path, value,
allowed)`` triple; only at the end does it raise one :class:`~contactlab.errors.SceneError` whose
``issues`` hold them all. Unknown keys are errors with a did-you-mean (difflib). Quantities are
converted to SI floats (:mod:`.units`). The result is the *normalised* scene: the same nesting,
SI floats, only the keys the user gave (defaults are applied by the planner and the runner, so a
normalised scene round-trips unchanged).

What each table may hold is data (:mod:`.schema`): [scene], [interface], [solver], [outputs],
the load-path segments, [wear] and [fretting_map] are tables of :class:`~.schema.Key`, and a
profile's or material's keys are its constructor's parameters, with the units of its
:class:`~contactlab.params.Param` specifications, plus what the class declares in ``scene_keys``
and ``scene_one_of`` (``Tabulated``: a CSV file, or the r and f columns). The checker
(:mod:`.check`) applies them; this module holds the rules that tie keys together.

Profiles and materials are looked up by name in the plugin registry (:func:`profile_class`,
:func:`material_class`).
"""
from __future__ import annotations

import difflib
import inspect
import re
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np

from ..errors import ContactlabError, SceneError, UnknownNameError
from ..params import QUANTITY_UNITS
from .check import Checker, first_line, resolve_file, short, summary
from .fretting_tables import axis_values, check_fretting_map, check_wear, fretting_segment
from .schema import (CONTROLS, CRITERIA, EFFECTS, FIELDS, FRETTING_MAP_KEYS, INTERFACE_KEYS,
                     MAX_MAP_POINTS, MAX_STEPS, METHODS, OUTPUT_KEYS, SCENE_KEYS, SECTIONS,
                     SEGMENTS, SERIES, SOLVER_KEYS, WEAR_KEYS, Key, dimension_of, key_from_text)

__all__ = ["validate", "profile_class", "material_class", "make_profile", "make_material",
           "object_keys", "SECTIONS", "SERIES", "FIELDS", "EFFECTS", "METHODS", "CONTROLS",
           "SEGMENTS", "MAX_STEPS", "read_table", "resolve_file", "WEAR_KEYS",
           "FRETTING_MAP_KEYS", "CRITERIA", "MAX_MAP_POINTS", "fretting_segment", "axis_values"]

# names other modules read from here (their home is .check)
_summary, _short = summary, short


# ---- name lookup ---------------------------------------------------------------------------------
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



def make_profile(type_: str, params: Mapping[str, Any], base_dir: Path | None = None) -> Any:
    """Build a profile from its scene table (SI values): the one constructor call for scenes."""
    cls: Any = profile_class(type_)
    p = dict(params)
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
    cls: Any = material_class(type_)
    p = dict(params)
    if type_ == "elastic" and "G" in p:
        return cls.from_shear_modulus(p["G"], p.get("nu"))
    return cls(**p)


def object_keys(cls: Any) -> tuple[dict[str, Key], set[str], tuple[tuple[str, ...], ...]]:
    """The keys of a profile's or material's scene table, the required ones, and the groups of
    which it gives exactly one.

    The keys are the constructor's parameters: a quantity in the unit of the class's
    :class:`~contactlab.params.Param` of that name (else of
    :data:`contactlab.params.QUANTITY_UNITS`, else dimensionless), plus the class's
    ``scene_keys`` (``{key: "kind[:dimension[:domain]][|names]"}``, see
    :func:`.schema.key_from_text`), which also override. ``scene_one_of`` lists alternative key
    groups (``(("slope",), ("half_angle",))``). Domains are left to the constructor, whose
    message names the rule.
    """
    units = {p.name: p.unit for p in getattr(cls, "params", ())}
    sig = inspect.signature(cls.__init__)
    keys: dict[str, Key] = {}
    required: set[str] = set()
    for name, par in list(sig.parameters.items())[1:]:
        if par.kind in (par.VAR_POSITIONAL, par.VAR_KEYWORD):
            continue
        unit = units.get(name, QUANTITY_UNITS.get(name, "1"))
        keys[name] = Key("quantity", dimension_of(unit))
        if par.default is inspect.Parameter.empty:
            required.add(name)
    keys.update({k: key_from_text(text) for k, text in getattr(cls, "scene_keys", {}).items()})
    return keys, required, tuple(getattr(cls, "scene_one_of", ()))


# ---- profiles and materials ----------------------------------------------------------------------
def _object_value(ck: Checker, path: str, value: Any, key: Key) -> Any:
    if key.kind == "terms":
        return _terms(ck, path, value)
    if key.kind == "quantity" and isinstance(value, list):    # sequences (Prony-series moduli)
        return ck.array(path, value, "dimensionless" if key.dimension == "number"
                        else key.dimension)
    return ck.key(path, value, key)


def _required(ck: Checker, path: str, type_: str, params: Mapping[str, Any],
              required: set[str], groups: tuple[tuple[str, ...], ...]) -> None:
    """Required keys, and exactly one of the alternative key groups, complete."""
    missing = {k: f"required for type {type_!r}"
               for k in required - {k for g in groups for k in g} if k not in params}
    given = [g for g in groups if any(k in params for k in g)]
    if groups and not given:
        missing[groups[0][0]] = (f"required for type {type_!r}: give "
                                 + " or ".join(" and ".join(repr(k) for k in g) for g in groups))
    for k in sorted(missing):
        ck.add(f"{path}.{k}", None, missing[k])
    if len(given) > 1:
        k = given[1][0]
        ck.add(f"{path}.{k}", params[k], "either " + " or ".join(
            " and ".join(repr(k) for k in g) for g in given) + ", not both")
    elif given:
        for k in given[0]:
            if k not in params:
                ck.add(f"{path}.{k}", None, f"{' and '.join(given[0])} together")


def _typed_object(ck: Checker, path: str, raw: Any, kind: str) -> dict | None:
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
    keys, required, groups = object_keys(table[type_])
    params = {k: v for k, v in tab.items() if k != "type"}
    ck.unknown_keys(path, params, [*keys, "type"])
    out: dict[str, Any] = {"type": type_}
    n_before = len(ck.issues)
    for k, v in params.items():
        if k in keys:
            val = _object_value(ck, f"{path}.{k}", v, keys[k])
            if val is not None:
                out[k] = val
    _required(ck, path, type_, params, required, groups)
    if len(ck.issues) > n_before:
        return None
    try:
        obj = (make_profile(type_, {k: v for k, v in out.items() if k != "type"}, ck.base_dir)
               if kind == "profile" else
               make_material(type_, {k: v for k, v in out.items() if k != "type"}))
    except (ContactlabError, ValueError, TypeError) as err:
        msg = first_line(err)
        m = re.match(r"^([A-Za-z_]\w*)=.*? is invalid: (.*)$", msg)
        if m and m.group(1) in params:
            ck.add(f"{path}.{m.group(1)}", params[m.group(1)], m.group(2))
        else:
            ck.add(path, dict(tab), msg)
        return None
    return {"out": out, "obj": obj}


def _terms(ck: Checker, path: str, value: Any) -> list | None:
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


def _segment(ck: Checker, path: str, raw: Any, axes: dict[str, tuple[str, str]]) -> dict | None:
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
    n_before = len(ck.issues)
    out: dict[str, Any] = ck.keys(sp, body, opts)
    controls = [k for k in body if k in CONTROLS]
    if kind in ("ramp", "sinusoid") and not controls:
        ck.add(sp, dict(body), f"at least one control from {sorted(CONTROLS)}")
    for k in controls:
        val: Any
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
                ck.add(f"{sp}.file", body["file"], f"a readable CSV history ({first_line(err)})")
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


def _check_repeats(ck: Checker, segs: list) -> None:
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
        return max(1, round(body["cycles"] * body.get("steps_per_cycle", 100)))
    if kind == "repeat" or "file" in body:
        return 0  # repeats and CSV histories: counted by _total_steps
    return max((len(v) for k, v in body.items() if k in CONTROLS or k == "time"), default=0)



def _plain_section(ck: Checker, top: Mapping[str, Any], data: dict, section: str,
                   keys: Mapping[str, Key]) -> None:
    """A section whose keys are independent of each other: checked against its key table."""
    if section in top:
        tab = ck.table(section, top[section])
        if tab is not None:
            ck.unknown_keys(section, tab, keys)
            data[section] = ck.keys(section, tab, keys)


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
    ck = Checker(Path(base_dir) if base_dir is not None else None, allow_outside)
    top = ck.table("", raw)
    if top is None:
        raise SceneError("scene is invalid: expected a table of sections", ck.issues)
    ck.unknown_keys("", top, SECTIONS)
    data: dict[str, Any] = {}
    objects: dict[str, Any] = {}

    if "scene" in top:
        meta = ck.table("scene", top["scene"])
        if meta is not None:
            ck.unknown_keys("scene", meta, SCENE_KEYS)
            data["scene"] = ck.keys("scene", meta, SCENE_KEYS)

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

    _plain_section(ck, top, data, "interface", INTERFACE_KEYS)

    if "load_path" not in top:
        ck.add("load_path", None, "a list of segments ([[load_path]] tables), e.g. "
               "ramp = { force = '100 N', steps = 50 } (required)")
    else:
        lp = top["load_path"]
        if not isinstance(lp, list) or not lp:
            ck.add("load_path", lp, "a non-empty list of segments ([[load_path]] tables)")
        else:
            axes: dict[str, tuple[str, str]] = {}
            segs: list[Any] = [_segment(ck, f"load_path[{i}]", s, axes) for i, s in enumerate(lp)]
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

    _plain_section(ck, top, data, "outputs", OUTPUT_KEYS)
    _plain_section(ck, top, data, "solver", SOLVER_KEYS)
    if "wear" in top:
        w = check_wear(ck, top["wear"], data, objects)
        if w is not None:
            data["wear"] = w
    if "fretting_map" in top:
        m = check_fretting_map(ck, top["fretting_map"], data, objects)
        if m is not None:
            data["fretting_map"] = m

    # cross-section rules
    itf = data.get("interface", {})
    outs = data.get("outputs", {})
    if outs.get("method") in ("exact", "mdr") and "friction" not in itf:
        ck.add("outputs.method", outs["method"], "'no-slip' without interface.friction (the "
               "exact and mdr methods model partial slip and need a friction coefficient)")
    sol = data.get("solver", {})
    if "n_rings" in sol and "torque_rtol" in sol:
        # Contact.simulate refuses both (the accuracy chooses the rings)
        ck.add("solver.torque_rtol", sol["torque_rtol"],
               f"solver.n_rings or solver.torque_rtol, not both (n_rings = {sol['n_rings']} was "
               "given; torque_rtol chooses the rings of the exact ring solver itself)")
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
                   f"{data['materials']['body2']['type']})", first_line(err))
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
        raise SceneError(summary(ck.issues), ck.issues)
    return data, objects
