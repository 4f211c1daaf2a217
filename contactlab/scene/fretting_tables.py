"""The [wear] and [fretting_map] tables of a scene: their keys (:mod:`.schema`) and the rules that
tie them to the rest of the scene (a fretting segment in the load path, friction, elastic bodies).
"""
from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np

from .check import Checker
from .schema import (AXIS_KEYS, CONTROLS, FRETTING_MAP_KEYS, FRETTING_MAP_TABLE, MAX_CHECKPOINTS,
                     MAX_MAP_POINTS, WEAR_KEYS, Key)

__all__ = ["check_wear", "check_fretting_map", "fretting_segment", "axis_values"]


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


def axis_values(spec: Any) -> np.ndarray:
    """The values of a validated map axis (list, or range table)."""
    if isinstance(spec, Mapping):
        lo, hi, n = spec["from"], spec["to"], int(spec["points"])
        return (np.geomspace(lo, hi, n) if spec.get("spacing") == "log"
                else np.linspace(lo, hi, n))
    return np.asarray(spec, float)


def _fretting_needs(ck: Checker, path: str, data: dict, objects: dict) -> None:
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


def _checkpoints(ck: Checker, path: str, v: Any, key: Key) -> Any:
    """``checkpoints``: a count, or a list of cycle numbers > 0."""
    if not isinstance(v, list):
        return ck.integer(path, v, 1, MAX_CHECKPOINTS)
    val = ck.array(path, v, "dimensionless")
    if val is not None and any(x <= 0 for x in val):
        ck.add(path, v, "cycle numbers > 0")
        return None
    if val is not None and len(val) > MAX_CHECKPOINTS:
        ck.add(path, f"{len(val)} checkpoints", f"at most {MAX_CHECKPOINTS}")
        return None
    return val


def check_wear(ck: Checker, raw: Any, data: dict, objects: dict) -> dict | None:
    """The normalised [wear] table, or None after recording its issues."""
    tab = ck.table("wear", raw)
    if tab is None:
        return None
    ck.unknown_keys("wear", tab, WEAR_KEYS)
    n_before = len(ck.issues)
    out = ck.keys("wear", tab, WEAR_KEYS, {"checkpoints": _checkpoints})
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


def _axis(ck: Checker, path: str, v: Any, key: Key) -> list[float] | dict | None:
    """A map axis: a list of quantities or a range table {from, to, points, spacing}."""
    dim, domain = key.dimension, key.domain
    if isinstance(v, list):
        vals = ck.array(path, v, dim)
        if vals is not None and any(x < 0 or (domain == "positive" and x == 0) for x in vals):
            ck.add(path, v, "values > 0" if domain == "positive" else "values >= 0")
            return None
        return vals
    tab = ck.table(path, v)
    if tab is None:
        return None
    ck.unknown_keys(path, tab, AXIS_KEYS)
    n_before = len(ck.issues)
    for k in ("from", "to", "points"):
        if k not in tab:
            ck.add(f"{path}.{k}", None, "required in a range table { from = ..., to = ..., "
                   "points = N, spacing = 'log' or 'linear' }")
    lo = ck.quantity(f"{path}.from", tab["from"], dim, "nonnegative") if "from" in tab else None
    hi = ck.quantity(f"{path}.to", tab["to"], dim, "positive") if "to" in tab else None
    n = ck.key(f"{path}.points", tab["points"], AXIS_KEYS["points"]) if "points" in tab else None
    spacing = (ck.key(f"{path}.spacing", tab["spacing"], AXIS_KEYS["spacing"])
               if "spacing" in tab else "linear")
    if lo is not None and hi is not None and lo > hi:
        ck.add(f"{path}.to", tab["to"], f">= from ({tab['from']!r})")
    if lo == 0 and (spacing == "log" or domain == "positive"):
        ck.add(f"{path}.from", tab["from"], "> 0" + (" with spacing = 'log'"
                                                     if spacing == "log" else ""))
    if len(ck.issues) > n_before or None in (lo, hi, n, spacing):
        return None
    return {"from": lo, "to": hi, "points": n, "spacing": spacing}


def check_fretting_map(ck: Checker, raw: Any, data: dict, objects: dict) -> dict | None:
    """The normalised [fretting_map] table, or None after recording its issues."""
    tab = ck.table("fretting_map", raw)
    if tab is None:
        return None
    ck.unknown_keys("fretting_map", tab, FRETTING_MAP_KEYS)
    n_before = len(ck.issues)
    custom = {"axis": _axis}
    out = ck.keys("fretting_map", tab, {"force": FRETTING_MAP_TABLE["force"]}, custom)
    amps = [k for k in ("twist_amplitude", "displacement_amplitude") if k in tab]
    if len(amps) != 1:
        ck.add("fretting_map", amps or None, "exactly one of twist_amplitude (torsional "
               "fretting) or displacement_amplitude (tangential fretting)")
    out |= ck.keys("fretting_map", tab, {k: v for k, v in FRETTING_MAP_TABLE.items()
                                         if k != "force"}, custom)
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
