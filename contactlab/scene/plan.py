"""Effect planning: which physics a scene calls for, which implementation answers it, and why.

:func:`make_plan` is pure: it reads the validated scene and its sampled load path and returns a
:class:`Plan` whose rows are ``(effect, implementation, reason)``. Rules:

* Elastic normal contact is path-independent, so a normal-only path is answered by
  ``contact.normal`` over all steps at once (closed form / exact transform), never by the
  foundation.
* A twist (shift) applied at constant normal load is answered exactly: monotone by
  ``contact.torsion`` (``contact.tangential``), any other twist (shift) history by
  ``contact.twist_history`` (``contact.shift_history``, exact Masing rule).
* A normal load that changes while the contact is twisted or shifted, a force/torque-controlled
  oscillation, or a viscoelastic body needs the MDR foundation with memory: ``contact.simulate``.
* No torsion or tangential machinery unless the path drives it or the outputs ask for it;
  no slip machinery without a friction coefficient.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, cast

import numpy as np

from ..errors import SceneError
from .validate import EFFECTS, SERIES, axis_values, fretting_segment

if TYPE_CHECKING:  # pragma: no cover
    from .model import Scene

__all__ = ["Effect", "Plan", "make_plan", "deliverable_series"]

_NORMAL_SERIES = ("time", "depth", "force", "radius")


@dataclass(frozen=True)
class Effect:
    """One row of a plan: an effect, the implementation that computes it, and why."""

    effect: str
    implementation: str
    reason: str

    def to_dict(self) -> dict[str, str]:
        return {"effect": self.effect, "implementation": self.implementation,
                "reason": self.reason}


@dataclass(frozen=True)
class Plan:
    """What a run of a scene computes.

    Attributes
    ----------
    effects : tuple of Effect
        Active effects in dependency order (normal, adhesion, viscoelastic, tangential, torsion,
        slip), each with implementation and reason.
    route : {"closed_form", "foundation", "viscoelastic"}
        Closed forms / exact histories, the MDR foundation simulation with frictional memory, or
        the viscoelastic MDR history.
    calls : tuple of str
        The ``Contact`` methods the run will call, in order (``"normal"``, ``"torsion"``,
        ``"twist_history"``, ``"tangential"``, ``"shift_history"``, ``"simulate"``).
    series, fields : tuple of str
        Output series (per step) and fields (over radius, at the final step).
    outputs : tuple of Effect
        How each field is computed (rows ``field:<name>``).
    method : str or None
        Torsion/tangential model: ``"no-slip"``, ``"exact"`` or ``"mdr"``.
    n_steps : int
        Load steps (including the start).
    """

    effects: tuple[Effect, ...]
    route: str
    calls: tuple[str, ...]
    series: tuple[str, ...]
    fields: tuple[str, ...] = ()
    outputs: tuple[Effect, ...] = ()
    method: str | None = None
    n_steps: int = 0
    details: dict[str, Any] = field(default_factory=dict, compare=False, repr=False)

    @property
    def names(self) -> tuple[str, ...]:
        """Names of the active effects."""
        return tuple(e.effect for e in self.effects)

    def __contains__(self, name: object) -> bool:
        return name in self.names

    def __getitem__(self, name: str) -> Effect:
        for e in self.effects:
            if e.effect == name:
                return e
        raise KeyError(f"effect {name!r} is not in the plan (active: {list(self.names)})")

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready form (``contactlab plan --json``)."""
        return {"route": self.route, "calls": list(self.calls), "method": self.method,
                "n_steps": self.n_steps, "effects": [e.to_dict() for e in self.effects],
                "series": list(self.series), "fields": list(self.fields),
                "outputs": [e.to_dict() for e in self.outputs]}

    def __str__(self) -> str:
        rows = [(e.effect, e.implementation, e.reason) for e in self.effects + self.outputs]
        w1 = max(len("effect"), *(len(r[0]) for r in rows))
        w2 = max(len("implementation"), *(len(r[1]) for r in rows))
        lines = [f"plan: {self.route.replace('_', ' ')} route, {self.n_steps} load steps, "
                 f"calls {', '.join(self.calls)}",
                 f"  {'effect':<{w1}}  {'implementation':<{w2}}  reason",
                 f"  {'-' * w1}  {'-' * w2}  {'-' * 6}"]
        lines += [f"  {a:<{w1}}  {b:<{w2}}  {c}" for a, b, c in rows]
        lines.append(f"  series: {', '.join(self.series)}")
        return "\n".join(lines)


#: per-step series each route's run fills (the closed-form route: every series, the rules of
#: :func:`make_plan` pick the call that fills it); checked before any computation
_ROUTE_SERIES = {"viscoelastic": ("time", "depth", "force", "radius")}


def deliverable_series(route: str, axis: str | None = None) -> tuple[str, ...]:
    """Series a run on ``route`` (``"closed_form"``, ``"foundation"``, ``"viscoelastic"``) can
    fill, for a path driving ``axis`` (``"torsion"``, ``"tangential"`` or None): requested series
    outside it are rejected when the scene is planned, not after the run."""
    if route == "foundation":
        from ..effects.path import SERIES as PATH_SERIES   # what contact.simulate returns
        other = {"torsion": ("tangential",), "tangential": ("torsion",)}.get(axis or "", ())
        return tuple(s for s in SERIES if s in PATH_SERIES and SERIES[s] not in other)
    return _ROUTE_SERIES.get(route, tuple(SERIES))


def _route_label(route: str, exact_path: bool, calls: list[str]) -> str:
    """The route in words, with the calls that run it (for messages)."""
    if route == "viscoelastic":
        return "viscoelastic route (contact.viscoelastic_history)"
    if route == "foundation":
        return ("foundation route (contact.simulate(method='exact'), exact ring solver)"
                if exact_path else "foundation route (contact.simulate, MDR springs)")
    return "closed-form route (" + ", ".join(f"contact.{c}" for c in calls) + ")"


def _monotone(v: np.ndarray) -> bool:
    d = np.diff(v)
    return bool(np.all(d >= 0) or np.all(d <= 0))


def _fmt(v: float) -> str:
    return f"{v:.6g}"


#: outputs.method of a twisted scene on the foundation route -> method of contact.simulate
_SIMULATE_METHOD: dict[Any, str] = {"exact": "exact", "mdr": "mdr", "no-slip": "mdr"}


def make_plan(scene: "Scene") -> Plan:
    """Plan the effects of a validated scene (pure: computes no physics).

    Raises
    ------
    SceneError
        Conflicting effects or outputs that no planned effect produces.
    """
    h = scene.history()
    outs = scene.outputs
    friction = scene.friction
    wa = scene.work_of_adhesion or 0.0
    requested = list(outs.get("effects", []))
    series_req = outs.get("series")
    fields = tuple(outs.get("fields", ()))
    issues: list[tuple[str, Any, str]] = []

    n_kind = h.kind("normal")
    normal = h.values("normal")
    tw_kind, sh_kind = h.kind("torsion"), h.kind("tangential")
    twist_on = tw_kind is not None and bool(np.any(h.values("torsion") != 0))
    shift_on = sh_kind is not None and bool(np.any(h.values("tangential") != 0))
    s_req = list(series_req or [])
    want_torsion = ("torsion" in requested or any(SERIES[s] == "torsion" for s in s_req)
                    or "shear" in fields)
    want_tangential = "tangential" in requested or any(SERIES[s] == "tangential" for s in s_req)
    torsion = twist_on or want_torsion
    tangential = shift_on or want_tangential
    visco = scene.is_viscoelastic
    adhesive = wa > 0
    if torsion and tangential:
        issues.append(("load_path", "twist and shift", "twist or shift, not both: combined "
                       "torsion and tangential loading is outside the decoupled theory"))
    if adhesive and visco:
        issues.append(("interface.work_of_adhesion", wa, "0 with a viscoelastic body: adhesive "
                       "viscoelastic contact is not covered by the theory"))
    if visco and (torsion or tangential):
        issues.append(("load_path", "twist/shift", "normal loading only with a viscoelastic body "
                       "(viscoelastic torsion and tangential contact are not covered)"))
    method = outs.get("method") or ("exact" if friction is not None else "no-slip")
    if friction is None:
        method = "no-slip"
    slip = (torsion or tangential) and method != "no-slip"
    if "slip" in requested and not (torsion or tangential):
        issues.append(("outputs.effects", "slip", "'slip' with a twist or shift in the load path"))
    pending = []      # output issues that name the route (known below)
    if "stick_radius" in s_req and not (torsion or tangential):
        pending.append(("outputs.series", "stick_radius", "'stick_radius' with a twist or shift "
                        "in the load path (or 'torsion' in outputs.effects)"))
    if "dissipated_energy" in s_req and not slip:
        pending.append(("outputs.series", "dissipated_energy", "'dissipated_energy' with partial "
                        "slip (a twist or shift and interface.friction)"))

    axis = "torsion" if torsion else "tangential" if tangential else None
    drive_kind = tw_kind if axis == "torsion" else sh_kind if axis == "tangential" else None
    drive = h.values(axis) if axis else None
    coupled_at = None
    start = 0
    if drive is not None and np.any(drive != 0):
        i0 = int(np.argmax(drive != 0))
        start = max(i0 - 1, 0)
        varying = normal[start:] != normal[start]
        if np.any(varying):
            coupled_at = start + int(np.argmax(varying))
    monotone = drive is None or _monotone(drive[start:])
    force_controlled_history = (drive_kind in ("torque", "tangential_force") and not monotone
                                and method != "no-slip")
    foundation = visco or coupled_at is not None or force_controlled_history
    route = "viscoelastic" if visco else "foundation" if foundation else "closed_form"
    if adhesive and not visco and (foundation or shift_on or (twist_on and method != "no-slip")):
        why = ("the foundation route (contact.simulate) covers non-adhesive contacts only"
               if foundation else "a tangential shift of adhesive bodies is outside the "
               "implemented theory" if shift_on else "torsion with slip of adhesive bodies is "
               "outside the implemented theory (without interface.friction it runs, no slip)")
        issues.append(("interface.work_of_adhesion", wa, f"0 for this load path: {why}"))

    # the model of contact.simulate: the resolver simulate itself calls (one owner of the
    # route). outputs.method of a twisted path with friction in simulate's terms ("no-slip" has
    # no foundation implementation: the MDR springs); without it, without friction (no slip
    # whatever the method) and for a shift: simulate's default
    path_method = None
    if foundation and not visco and not (torsion and tangential):
        from ..effects.path import resolve_path_method
        asked = (_SIMULATE_METHOD.get(outs.get("method")) if torsion and friction is not None
                 else None)
        path_method = resolve_path_method(scene.load_path, asked)
    exact_path = path_method == "exact"

    rows: dict[str, Effect] = {}
    calls: list[str] = []
    n = h.n_steps
    if visco:
        rows["normal"] = Effect("normal", "contact.viscoelastic_history (MDR foundation)",
                                "viscoelastic body: the response depends on the load history in "
                                "time, no elastic closed form")
        calls.append("viscoelastic_history")
    elif foundation:
        if coupled_at is not None:
            from .model import leaf_segments
            owners = leaf_segments(scene.to_dict()["load_path"])
            leaf = int(h.segment[coupled_at])
            seg = owners[leaf][0] if 0 <= leaf < len(owners) else leaf
            why = (f"normal load varies while {'twisted' if axis == 'torsion' else 'shifted'} "
                   f"(step {coupled_at}, load_path[{seg}]): no closed form, foundation with memory")
        else:
            why = (f"{drive_kind}-controlled non-monotone history: no closed-form history API, "
                   "foundation with memory")
        rows["normal"] = Effect("normal", "contact.simulate (MDR foundation)", why)
        calls.append("simulate")
    else:
        what = "JKR equilibrium branch" if adhesive else "elastic normal contact"
        rows["normal"] = Effect("normal", f"contact.normal({n_kind}=<{n} steps>), vectorised",
                                f"{what} is path-independent: closed form exists, no foundation")
        calls.append("normal")
    if adhesive:
        rows["adhesion"] = Effect("adhesion", "JKR through the MDR (Heß rule)"
                                  + (" in contact.normal" if not foundation else " in the foundation"),
                                  f"interface.work_of_adhesion = {_fmt(wa)} J/m^2")
    if visco:
        names = [type(m).__name__ for m in scene.materials if getattr(m, "is_viscoelastic", False)]
        rows["viscoelastic"] = Effect("viscoelastic", "rheological elements of the material's "
                                      "type, parameters scaled by 4 dx [H3]",
                                      f"body material {', '.join(names)} is viscoelastic")

    impl_call = None
    if torsion or tangential:
        eff = "torsion" if torsion else "tangential"
        ctrl = drive_kind or ("twist" if torsion else "displacement")
        reasons = []
        if (twist_on if torsion else shift_on):
            reasons.append(f"path has {ctrl}")
        if eff in requested:
            reasons.append("requested in outputs.effects")
        implied = [s for s in s_req if SERIES[s] == eff]
        if torsion and "shear" in fields:
            implied.append("shear")
        if implied:
            reasons.append(f"outputs ask for {', '.join(implied)}")
        if not (twist_on if torsion else shift_on):
            reasons.append(f"the path has no {ctrl}: zero {'torque' if torsion else 'force'}")
        mono_api, hist_api = (("torsion", "twist_history") if torsion
                              else ("tangential", "shift_history"))
        if not (twist_on if torsion else shift_on) and not foundation:
            impl = ("no call: zero twist gives zero torque, stick radius = contact radius" if torsion
                    else "no call: zero shift gives zero force, stick radius = contact radius")
        elif foundation:
            impl = "contact.simulate (MDR " + ("torsional" if torsion else "tangential") + " springs)"
            if exact_path and friction is not None:
                impl = "contact.simulate(method='exact') (exact ring solver)"
                reasons.append("the normal load changes while twisted: exact pressure per step, "
                               "the half-space's torsional influence on rings, Coulomb friction "
                               "with memory (the default of contact.simulate for twisted paths; "
                               "the MDR springs err by up to 24 % of the sliding torque on such "
                               "paths, benchmarks/results/torsion_rings_map.csv)")
            elif exact_path:
                impl = "contact.simulate(method='exact') (exact ring solver)"
                reasons.append("the normal load changes while twisted, no friction limit: rigid "
                               "punches at the contact radii, exact (the default of "
                               "contact.simulate for twisted paths)")
            elif torsion and method == "no-slip" and friction is not None:
                reasons.append(f"method {method!r} has no foundation implementation: the MDR "
                               "spring model is used")
        elif method == "no-slip":
            impl_call = mono_api
            impl = f"contact.{mono_api}(method='no-slip')" if torsion else f"contact.{mono_api}()"
            reasons.append("no slip: the response is linear, any history is exact")
        elif monotone and "dissipated_energy" not in s_req:
            impl_call = mono_api
            impl = f"contact.{mono_api}(method={method!r})" if torsion else f"contact.{mono_api}()"
            reasons.append(f"monotone {ctrl} at constant normal load: exact closed form, "
                           "no foundation")
        else:
            impl_call = hist_api
            impl = f"contact.{hist_api}(method={method!r})" if torsion else f"contact.{hist_api}()"
            reasons.append((f"non-monotone {ctrl}" if not monotone else "dissipated energy asked")
                           + " at constant normal load: exact Masing history, no foundation")
        rows[eff] = Effect(eff, impl, "; ".join(reasons))
        if impl_call:
            calls.append(impl_call)
    label = _route_label(route, exact_path, calls)
    avail = deliverable_series(route, axis)
    issues += [(p, v, f"{a}; this scene runs the {label}") for p, v, a in pending]
    for name in s_req:
        if name not in avail and name not in {v for _, v, _ in pending}:
            hint = {"peak_pressure": "; the pressure at the final step: outputs.fields = "
                                     "['pressure']",
                    "stiffness": "; per-step stiffness: the same normal load path without "
                                 "twist or shift (closed-form route)"}.get(name, "")
            issues.append(("outputs.series", name, f"a series the {label} delivers "
                           f"({', '.join(avail)}){hint}"))
    if slip:
        assert friction is not None     # slip needs a friction coefficient (method above)
        if exact_path:
            rows["slip"] = Effect("slip", "exact Coulomb friction per ring with memory (ring solver)",
                                  f"interface.friction = {_fmt(friction)}; foundation route")
        elif foundation:
            model = ("MDR torsional springs, Coulomb per spring (narrow-slip model)" if torsion else
                     "MDR tangential springs, Coulomb per spring (exact Cattaneo-Mindlin)")
            if torsion:
                method = "mdr"
            rows["slip"] = Effect("slip", model, f"interface.friction = {_fmt(friction)}; "
                                  "foundation route")
        else:
            model = {"exact": "exact partial slip (Jäger superposition)" if torsion else
                     "Cattaneo-Mindlin partial slip (exact)",
                     "mdr": "MDR narrow-slip approximation (springs, mu* = 2 mu)"}.get(method, method)
            rows["slip"] = Effect("slip", model, f"interface.friction = {_fmt(friction)}"
                                  + (" and outputs.method = " + repr(method) if "method" in outs else ""))

    extra = _fretting_rows(scene, h, issues)
    for name, (row, _det) in extra.items():
        rows[name] = row
        calls.append(name)

    # fields
    out_rows = []
    for f in fields:
        if f in ("pressure", "surface_displacement"):
            if visco:
                issues.append(("outputs.fields", f, f"a field the {label} delivers (none: "
                               "no fields for viscoelastic scenes)"))
                continue
            if foundation:
                out_rows.append(Effect(f"field:{f}", "contact.normal at the final depth",
                                       "the normal problem is decoupled: exact at any step"))
                if "normal" not in calls:
                    calls.append("normal")
            else:
                out_rows.append(Effect(f"field:{f}", "NormalState at the final step",
                                       "requested in outputs.fields"))
        else:  # shear
            if not torsion or foundation or impl_call != "torsion":
                have = "none" if visco else "pressure, surface_displacement"
                issues.append(("outputs.fields", f, f"a field the {label} delivers ({have}): "
                               "'shear' needs a monotone twist at constant normal load (the "
                               "exact torsion state at the final step)"))
                continue
            out_rows.append(Effect("field:shear", "TorsionState.shear at the final step",
                                   "requested in outputs.fields"))
    if issues:
        from .validate import _summary
        raise SceneError(_summary(issues), issues)

    if series_req:
        series = tuple(series_req)
    else:
        default_series = list(_NORMAL_SERIES)
        if torsion:
            default_series += ["twist", "torque", "stick_radius"]
        if tangential:
            default_series += ["displacement", "tangential_force", "stick_radius"]
        if slip and (foundation or impl_call in ("twist_history", "shift_history")):
            default_series.append("dissipated_energy")
        series = tuple(default_series)
    ordered = tuple(rows[e] for e in EFFECTS + FRETTING_EFFECTS if e in rows)
    return Plan(ordered, route, tuple(calls), series, fields, tuple(out_rows),
                method if (torsion or tangential) else None, n,
                {"axis": axis, "start": start, "monotone": monotone, "coupled_at": coupled_at,
                 "exact_torsion_path": exact_path, "path_method": path_method,
                 **{name: det for name, (_, det) in extra.items()}})


#: effects planned from the [wear] and [fretting_map] tables (after the path's effects)
FRETTING_EFFECTS = ("wear", "fretting_map")

_SLIP_MODEL = {("torsion", "exact"): "3D slip from Jäger's exact partial-slip solution",
               ("torsion", "mdr"): "3D slip from the MDR springs' twist distribution (the fast "
                                   "approximation; warns beyond its validity)",
               ("tangential", None): "3D slip as the Abel transform of the MDR spring slip "
                                     "(exact Cattaneo-Mindlin)"}


def _fretting_method(table: dict, outs: dict, mode: str) -> str | None:
    if mode == "tangential":
        return None
    m = table.get("method") or outs.get("method")
    return m if m in ("exact", "mdr") else "exact"


def _fretting_rows(scene: "Scene", h: Any, issues: list) -> dict[str, tuple[Effect, dict[str, Any]]]:
    """Plan rows (and run details) for the [wear] and [fretting_map] tables."""
    data = scene.to_dict()
    outs = scene.outputs
    out: dict[str, tuple[Effect, dict[str, Any]]] = {}
    if "wear" in data:
        w = data["wear"]
        i, ctrl, amp = cast("tuple[int, str, float]",
                            fretting_segment(data["load_path"]))   # validated: exists
        from .model import leaf_segments     # History.segment counts leaves (repeats expanded)
        leaves = [j for j, (seg, rep, _) in enumerate(leaf_segments(data["load_path"]))
                  if seg == i and rep == 0]
        steps = np.flatnonzero(np.isin(h.segment, leaves[:1]))
        force = float(h.values("normal")[steps[0]]) if steps.size else 0.0
        if force <= 0:
            issues.append((f"load_path[{i}]", f"normal force {force:g} N", "a positive normal "
                           "force during the fretting segment for [wear]"))
        else:
            mode = "torsion" if ctrl == "twist" else "tangential"
            key = "twist_amplitude" if mode == "torsion" else "displacement_amplitude"
            unit = "rad" if mode == "torsion" else "m"
            method = _fretting_method(w, outs, mode)
            kw: dict[str, Any] = {"force": force, key: amp,
                                  "wear_coefficient": w["wear_coefficient"],
                                  "cycles": w["cycles"], "method": method}
            for k in ("checkpoints", "n_grid", "jump_rtol", "max_radius", "integrator"):
                if k in w:
                    kw[k] = w[k]
            impl = (f"contact.wear(force={_fmt(force)} N, {key}={_fmt(amp)} {unit}, "
                    f"wear_coefficient={_fmt(w['wear_coefficient'])} 1/Pa, "
                    f"cycles={_fmt(w['cycles'])}"
                    + (f", method={method!r}" if method else "")
                    + (f", integrator={w['integrator']!r}" if "integrator" in w else "") + ")")
            jumps = ("Rosenbrock-W (implicit) cycle jumps, local error <= "
                     f"{_fmt(w.get('jump_rtol', 1e-4))} x largest wear depth"
                     if w.get("integrator") == "implicit" else
                     f"Heun cycle jumping, local error <= {_fmt(w.get('jump_rtol', 1e-4))} x depth")
            why = (f"[wear] table; fretting condition of load_path[{i}] ({ctrl} sinusoid of "
                   f"amplitude {_fmt(amp)} {unit} at constant force {_fmt(force)} N); Archard "
                   f"wear with the {_SLIP_MODEL[(mode, method)]}; {jumps}")
            out["wear"] = (Effect("wear", impl, why), {"kwargs": kw, "segment": i, "mode": mode})
    if "fretting_map" in data:
        m = data["fretting_map"]
        key = "twist_amplitude" if "twist_amplitude" in m else "displacement_amplitude"
        mode = "torsion" if key == "twist_amplitude" else "tangential"
        forces, amps = axis_values(m["force"]), axis_values(m[key])
        method = _fretting_method(m, outs, mode)
        kw = {"force": forces, key: amps}
        if method:
            kw["method"] = method
        for k in ("criterion", "threshold"):
            if k in m:
                kw[k] = m[k]
        if mode == "torsion":
            crit = m.get("criterion", "energy_ratio")
            thr = m.get("threshold", {"energy_ratio": 0.2, "stick_ratio": 0.1,
                                      "torque_ratio": 0.95}[crit])
            why = (f"[fretting_map] table; torsional gross slip declared by {crit} "
                   f"(threshold {_fmt(thr)}): a smooth profile keeps a stick zone at any twist")
        else:
            why = ("[fretting_map] table; gross slip exact where the whole contact slides "
                   "(delta_t = mu E* d / G*)")
        impl = (f"contact.fretting_map(force=<{forces.size} values>, {key}=<{amps.size} values>"
                + (f", method={method!r}" if method else "") + "), vectorised")
        out["fretting_map"] = (Effect("fretting_map", impl, why), {"kwargs": kw, "mode": mode})
    return out
