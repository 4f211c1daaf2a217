"""What accuracy costs for one scene: every numeric knob over a ladder, error against wall time.

:func:`scene_cost` (``Scene.cost()``, ``contactlab cost SCENE``) runs the user's own scene once
per rung of a ladder of each numeric knob that applies to it, the other knobs at the scene's own
setting:

``rtol``
    Relative tolerance of quadratures and root solves (every scene).
``n_springs``
    Cells of the MDR foundation (scenes whose plan runs the MDR springs or the viscoelastic
    history).
``n_rings``
    Rings of the exact torsion solver (scenes whose plan runs it: a twist under a varying normal
    load); it does not read ``n_springs``. A scene with ``solver.torque_rtol`` ladders around the
    rings that accuracy chooses (each rung sets ``n_rings`` in its place).
``steps``
    Refinement factor of every load-path segment's ``steps`` (``steps_per_cycle`` for a
    sinusoid), durations and periods held (foundation and viscoelastic scenes; a measured table
    path cannot be refined). Closed-form routes are exact at every step, so there it is no knob.
``interpolation``
    ``"linear"`` against ``"cubic"`` for a tabulated profile (the difference of the two
    interpolants of the same table estimates the linear one's interpolation error).
``n_grid``
    Intervals of the worn-profile grid of a ``[wear]`` table (1/4, 1/2 and 1 times the scene's
    value: the scene's own grid is the reference, since a finer wear grid costs 4-8 times more
    per doubling).
``jump_rtol``
    Local error of one wear step (cycle jump) of a ``[wear]`` table.

A knob that no rung moves beyond rounding (every rung's error at most :data:`INERT_FLOOR`) is
not read by the scene's route (``rtol`` of a closed-form scene): it is reported in
``CostReport.inert``, gets no recommended setting and no share of the target.

The error of a rung is ``max over outputs of max|s - s_ref| / max|s_ref|``, every series and
field of the scene's outputs compared with the same knob's tightest rung (the last of its ladder,
the reference; a coarser ``steps`` rung is compared at its own steps, which the reference also
samples). A wear run is compared at its checkpoints (every series of the run, and the wear
depth interpolated onto the reference's grid), since its steps adapt to each setting. The wall
time is the best of up to three runs.

Choosing. With ``k`` knobs, a rung meets the target when its error is at most ``target / (2k)``:
the errors of independent knobs add to first order (so ``k`` shares of the budget), and a ladder
whose consecutive rungs improve the error at least twofold has a reference at most half as wrong
as any coarser rung, so a rung's true error is at most twice its difference to the reference.
The recommended setting is, per knob, the loosest (cheapest) rung below the reference that meets
it; when none does, the reference, flagged as not certified.
"""
from __future__ import annotations

import copy
import time
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any, cast

import numpy as np

from ..errors import ParameterError, UnknownNameError
from ..numeric.quadrature import DEFAULT_RTOL

if TYPE_CHECKING:  # pragma: no cover
    from .model import Scene

__all__ = ["CostReport", "Rung", "scene_cost", "knobs_of", "default_ladders", "with_setting",
           "output_error", "KNOBS"]

#: every knob :func:`scene_cost` knows, in report order
KNOBS = ("rtol", "n_springs", "n_rings", "steps", "interpolation", "n_grid", "jump_rtol")
#: default rtol ladder (loosest first; the last is the reference)
RTOL_LADDER = (1e-4, 1e-6, 1e-8, 1e-10, 1e-12)
#: n_springs ladder as multiples of the scene's value (the last is the reference)
SPRING_FACTORS = (0.125, 0.25, 0.5, 1.0, 2.0, 4.0)
#: n_rings ladder as multiples of the scene's value: the ring solver's cost per step grows about
#: as the square of the rings (hip cup, 271 steps: 3.1 s at 200 rings, 17 s at 400, 78 s at
#: 800), so the reference is twice the scene's value
RING_FACTORS = (0.25, 0.5, 1.0, 2.0)
#: steps ladder: refinement factors of every segment (the last is the reference)
STEP_FACTORS = (0.25, 0.5, 1.0, 2.0, 4.0)
#: n_grid ladder (wear) as multiples of the scene's value, the scene's own grid the reference: a
#: twice finer wear grid costs 4-8 times as much (more cells and more, stiffer steps; a 10^6-cycle
#: hip taper at n_grid 800, jump_rtol 1e-6 took 10 min on the shared VM), so a ladder asks which
#: coarser grids keep to the target; give a finer rung in ``ladders=`` to check the scene's own
GRID_FACTORS = (0.25, 0.5, 1.0)
#: jump_rtol ladder (wear; loosest first, the last is the reference, 1e-4 the default)
JUMP_LADDER = (1e-2, 1e-3, 1e-4)
#: wear series left out of the comparison: once the slip annulus carries no load (the partial-slip
#: limiting state) the contact radius is the edge of a load-free, touching annulus whose gap is
#: zero to rounding, so any setting moves it by whole cells; the scar radius is the well-posed one
WEAR_NOT_COMPARED = ("radius",)
#: the share of the target one knob may use is target / (SAFETY * number of knobs)
SAFETY = 2.0
#: a knob none of whose rungs differs from its reference by more than this (relative) changes
#: nothing beyond rounding: its route does not read it (measured: rtol of closed-form scenes 0
#: to 1.3e-15; the smallest real effect among the examples, rtol of the tabulated hip cup,
#: 5e-12)
INERT_FLOOR = 1e-13
#: runs shorter than this are repeated (up to three times) and the best time kept, s
_REPEAT_BELOW = 0.05


@dataclass(frozen=True)
class Rung:
    """One run of the scene with one knob changed.

    Attributes
    ----------
    knob : str
    value : float, int or str
        The knob's setting (``steps``: the refinement factor).
    label : str
        Human form of the setting (``steps``: the factor and the total load steps).
    seconds : float
        Wall time of the run, s (best of up to three).
    error : float or None
        Relative difference to the knob's reference rung (None for the reference itself).
    default, reference, chosen : bool
        The scene's own setting; the tightest rung; the recommended setting.
    """

    knob: str
    value: Any
    label: str
    seconds: float
    error: float | None
    default: bool = False
    reference: bool = False
    chosen: bool = False

    def to_dict(self) -> dict[str, Any]:
        return {"knob": self.knob, "value": self.value, "label": self.label,
                "seconds": self.seconds, "error": self.error, "default": self.default,
                "reference": self.reference, "chosen": self.chosen}


@dataclass(frozen=True)
class CostReport:
    """Result of :func:`scene_cost`.

    Attributes
    ----------
    title : str
    target : float
        Relative error the recommended setting must meet.
    rungs : tuple of Rung
        Every run, knob by knob, loosest first.
    choice : dict
        Knob -> recommended value.
    certified : dict
        Knob -> whether a rung below the reference met its share of the target.
    budget : float
        The error each knob's rung had to meet (``target / (2 k)``, ``k`` knobs that change the
        results).
    inert : dict
        Knob -> largest rung error, for knobs laddered but changing nothing beyond rounding
        (:data:`INERT_FLOOR`): the scene's route does not read them; they have no rungs here
        and no recommended setting.
    """

    title: str
    target: float
    rungs: tuple[Rung, ...]
    choice: dict[str, Any]
    certified: dict[str, bool]
    budget: float
    defaults: dict[str, Any] = field(default_factory=dict)
    inert: dict[str, float] = field(default_factory=dict)

    @property
    def knobs(self) -> tuple[str, ...]:
        return tuple(k for k in KNOBS if any(r.knob == k for r in self.rungs))

    @property
    def solver(self) -> dict[str, Any]:
        """The recommended setting as scene entries: ``{"solver": {...}, "steps": factor, ...}``."""
        return dict(self.choice)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready form (``contactlab cost --json``)."""
        return {"title": self.title, "target": self.target, "budget_per_knob": self.budget,
                "knobs": list(self.knobs), "defaults": self.defaults, "choice": self.choice,
                "certified": self.certified, "inert": self.inert,
                "rungs": [r.to_dict() for r in self.rungs]}

    def __str__(self) -> str:
        lines = [f"cost of accuracy: {self.title} (target {self.target:.3g}, each of "
                 f"{len(self.knobs)} knob(s) must reach {self.budget:.3g})",
                 f"  {'knob':<14} {'setting':<22} {'time [s]':>10} {'error':>10}  mark",
                 f"  {'-' * 14} {'-' * 22} {'-' * 10} {'-' * 10}  {'-' * 4}"]
        for r in self.rungs:
            err = "reference" if r.error is None else f"{r.error:10.3g}"
            marks = [m for m, on in (("default", r.default), ("chosen", r.chosen)) if on]
            lines.append(f"  {r.knob:<14} {r.label:<22} {r.seconds:10.4f} {err:>10}  "
                         + ", ".join(marks))
        lines.append("recommended: " + (", ".join(
            f"{k} = {_fmt(self.choice[k])}" + ("" if self.certified[k] else
                                                " (reference: target not certified)")
            for k in self.knobs) or "nothing to set"))
        for k, e in self.inert.items():
            lines.append(f"not read: {k} (no rung changes the results by more than "
                         f"{INERT_FLOOR:g}; largest {e:.2g}): this scene's route does not use it")
        return "\n".join(lines)

    def plot(self, path: str | Path | None = None, *, ax: Any = None) -> Any:
        """Error against wall time per knob, the default and chosen rungs marked.

        Parameters
        ----------
        path : str or Path, optional
            Write the figure there (PNG, PDF, ... by suffix) and close it; returns the path.
        ax : matplotlib Axes, optional
            Draw into these axes (default: a new styled figure); returned when ``path`` is None.

        Raises
        ------
        ImportError
            matplotlib is not installed (extra ``plot``).
        """
        try:
            import matplotlib.pyplot as plt
        except ImportError as err:
            raise ImportError("plotting needs matplotlib: pip install 'contactlab[plot]'") from err
        from .. import plotting as pl
        floor = self.budget * 1e-6
        with pl.style():
            if ax is None:
                fig, ax = pl.subplots(figsize=(6.4, 4.4))
            else:
                fig = ax.figure
            for knob in self.knobs:
                rs = [r for r in self.rungs if r.knob == knob and r.error is not None]
                if not rs:
                    continue
                t = [r.seconds for r in rs]
                e = [max(cast(float, r.error), floor) for r in rs]   # not None: rs
                line, = ax.loglog(t, e, "o-", label=knob)
                for r, ti, ei in zip(rs, t, e):
                    if r.default:
                        ax.plot(ti, ei, "o", ms=12, mfc="none", mec=line.get_color())
                    if r.chosen:
                        ax.plot(ti, ei, "*", ms=14, color=line.get_color())
                    ax.annotate(_fmt(r.value), (ti, ei), fontsize=7, xytext=(3, 3),
                                textcoords="offset points")
            ax.axhline(self.target, color="k", ls="--", lw=0.8, label="target")
            ax.axhline(self.budget, color="k", ls=":", lw=0.8, label="per-knob share")
            ax.set_xlabel("wall time [s]")
            ax.set_ylabel(f"relative error (floor {floor:.0e})")
            ax.set_title(f"{self.title}\nring: default, star: cheapest meeting the target",
                         fontsize=9)
            ax.legend(fontsize=8)
        if path is None:
            return ax
        import io

        from .run import atomic_write
        path = Path(path)
        buf = io.BytesIO()                 # written whole through a rename: never through a link
        pl.save(fig, buf, format=path.suffix.lstrip(".") or "png")
        plt.close(fig)
        return atomic_write(path, buf.getvalue())


def _fmt(v: Any) -> str:
    return f"{v:g}" if isinstance(v, float) else str(v)


# ---- which knobs, which ladders ----------------------------------------------------------------
def knobs_of(scene: "Scene") -> tuple[str, ...]:
    """The numeric knobs that change the results of ``scene`` (see the module docstring)."""
    plan = scene.plan()
    route = plan.route
    out = ["rtol"]
    if route in ("foundation", "viscoelastic"):
        # the exact ring solver (twist under a varying load) reads rings, not springs
        exact = route == "foundation" and plan.details.get("exact_torsion_path", False)
        out.append("n_rings" if exact else "n_springs")
        if not any("table" in seg for seg in scene.to_dict()["load_path"]):
            out.append("steps")
    data = scene.to_dict()
    if data["profile"]["type"] == "tabulated":
        out.append("interpolation")
    if "wear" in data:
        out += ["n_grid", "jump_rtol"]
    return tuple(out)


def _defaults(scene: "Scene") -> dict[str, Any]:
    from ..effects.viscoelastic import DEFAULT_N_SPRINGS as VISCO_N
    from ..effects.wear import DEFAULT_GRID, DEFAULT_JUMP_RTOL
    from ..foundation import DEFAULT_N_SPRINGS
    from ..foundation.rings import DEFAULT_N_RINGS, rings_for_rtol
    data = scene.to_dict()
    wear = data.get("wear", {})
    sol = data.get("solver", {})
    # the scene's rings: its n_rings, or those its torque_rtol chooses
    rings = (rings_for_rtol(float(sol["torque_rtol"])) if "torque_rtol" in sol
             else DEFAULT_N_RINGS)
    n_def = VISCO_N if scene.plan().route == "viscoelastic" else DEFAULT_N_SPRINGS
    return {"rtol": float(sol.get("rtol", DEFAULT_RTOL)),
            "n_springs": int(sol.get("n_springs", n_def)),
            "n_rings": int(sol.get("n_rings", rings)), "steps": 1.0,
            "interpolation": data["profile"].get("interpolation", "linear"),
            "n_grid": int(wear.get("n_grid", DEFAULT_GRID)),
            "jump_rtol": float(wear.get("jump_rtol", DEFAULT_JUMP_RTOL))}


def default_ladders(scene: "Scene") -> dict[str, list[Any]]:
    """Default ladder of every knob of ``scene``, loosest first, the reference last; the scene's
    own setting is always a rung."""
    dflt = _defaults(scene)
    out: dict[str, list[Any]] = {}
    for knob in knobs_of(scene):
        if knob == "rtol":
            vals = sorted(set(RTOL_LADDER) | {dflt["rtol"]}, reverse=True)
        elif knob in ("n_springs", "n_rings"):
            n0 = dflt[knob]
            factors = SPRING_FACTORS if knob == "n_springs" else RING_FACTORS
            vals = sorted({max(2, round(n0 * f)) for f in factors})      # int * float
        elif knob == "steps":
            vals = [f for f in STEP_FACTORS if _refined(scene.to_dict(), f) is not None]
        elif knob == "n_grid":
            from ..effects.wear import MIN_GRID
            vals = sorted({max(MIN_GRID, round(dflt["n_grid"] * f)) for f in GRID_FACTORS})
        elif knob == "jump_rtol":
            vals = sorted(set(JUMP_LADDER) | {dflt["jump_rtol"]}, reverse=True)
        else:
            vals = ["linear", "cubic"]
        out[knob] = vals
    return out


def _refined(data: dict[str, Any], factor: float) -> dict[str, Any] | None:
    """``data`` with every segment's steps (steps per cycle) times ``factor``, times held; None
    when a count would not be a whole number, a sinusoid would get fewer than 4 steps per cycle,
    or the path would exceed the scenes' step limit."""
    from .validate import MAX_STEPS
    data = copy.deepcopy(data)
    total = 0
    for seg in data["load_path"]:
        kind, body = next(iter(seg.items()))
        if kind in ("ramp", "hold"):
            n = body["steps"] * factor
            if n < 1 or abs(n - round(n)) > 1e-9:
                return None
            body.setdefault("duration", float(body["steps"]))
            body["steps"] = int(round(n))      # noqa: RUF046 - n may be a numpy scalar
            total += body["steps"]
        elif kind == "sinusoid":
            from .model import DEFAULT_STEPS_PER_CYCLE
            spc = body.get("steps_per_cycle", DEFAULT_STEPS_PER_CYCLE)
            n = spc * factor
            if n < 4 or abs(n - round(n)) > 1e-9:
                return None
            body.setdefault("period", float(spc))
            body["steps_per_cycle"] = int(round(n))    # noqa: RUF046 - as above
            total += int(round(body["cycles"] * body["steps_per_cycle"]))  # noqa: RUF046
        else:
            return None
    return data if total <= MAX_STEPS else None


def with_setting(scene: "Scene", knob: str, value: Any) -> "Scene":
    """A copy of ``scene`` with one knob set (``steps``: a refinement factor)."""
    from .model import Scene
    data = scene.to_dict()
    if knob == "rtol":
        data.setdefault("solver", {})["rtol"] = float(value)
    elif knob in ("n_springs", "n_rings"):
        data.setdefault("solver", {})[knob] = int(value)
        if knob == "n_rings":          # a rung's rings replace those torque_rtol would choose
            data["solver"].pop("torque_rtol", None)
    elif knob == "steps":
        refined = _refined(data, float(value))
        if refined is None:
            raise ParameterError(f"steps={value!r} is invalid for this scene: every segment's "
                                 "steps (steps_per_cycle) times it must be a whole number "
                                 "(>= 4 per cycle) within the step limit.")
        data = refined
    elif knob == "interpolation":
        data["profile"]["interpolation"] = str(value)
    elif knob in ("n_grid", "jump_rtol") and "wear" in data:
        data["wear"][knob] = int(value) if knob == "n_grid" else float(value)
    else:
        raise UnknownNameError(f"knob={knob!r} is invalid: allowed are {KNOBS} (n_grid and "
                               "jump_rtol for a scene with a [wear] table).")
    return Scene.from_dict(data, scene.base_dir)


# ---- running and comparing ----------------------------------------------------------------------
def _timed_run(scene: "Scene") -> tuple[Any, float]:
    t0 = time.perf_counter()
    res = scene.run()
    best = time.perf_counter() - t0
    for _ in range(2):
        if best >= _REPEAT_BELOW:
            break
        t0 = time.perf_counter()
        scene.run()
        best = min(best, time.perf_counter() - t0)
    return res, best


def _step_map(coarse: "Scene", fine: "Scene") -> np.ndarray:
    """Index into the fine scene's steps of each coarse step (same segments, the fine one a
    whole-number refinement of the coarse one)."""
    sc, sf = coarse.history().segment, fine.history().segment
    idx = np.zeros(sc.size, int)
    for s in np.unique(sc):
        ic, jf = np.flatnonzero(sc == s), np.flatnonzero(sf == s)
        if s < 0:
            idx[ic] = jf[:ic.size]
            continue
        ratio = jf.size // ic.size
        if ratio * ic.size != jf.size:
            raise ParameterError(f"load_path[{s}] has {ic.size} and {jf.size} steps: not a "
                                 "whole-number refinement.")
        idx[ic] = jf[ratio * np.arange(1, ic.size + 1) - 1]
    return idx


def output_error(result: Any, reference: Any, index: np.ndarray | None = None) -> float:
    """``max over outputs of max|s - s_ref| / max|s_ref|`` of two scene results (series at the
    reference's steps ``index``, fields point by point); ``time`` is not compared."""
    worst = 0.0
    pairs = [(k, v, reference.series[k] if index is None else reference.series[k][index])
             for k, v in result.series.items() if k != "time"]
    pairs += [(k, v, reference.fields[k]) for k, v in result.fields.items()]
    pairs += _wear_pairs(getattr(result, "wear", None), getattr(reference, "wear", None))
    for _, v, ref in pairs:
        v, ref = np.asarray(v, float), np.asarray(ref, float)
        diff = float(np.max(np.abs(v - ref), initial=0.0))
        scale = float(np.max(np.abs(ref), initial=0.0))
        err = diff / scale if scale > 0 else (0.0 if diff == 0 else float("inf"))
        worst = max(worst, err)
    return worst


def _wear_pairs(w: Any, ref: Any) -> list[tuple[str, np.ndarray, np.ndarray]]:
    """Wear series at the checkpoints of both runs and the wear depth at the checkpoints on the
    reference's grid (linear interpolation: the worn profile is piecewise linear)."""
    if w is None or ref is None:
        return []
    at = lambda res: np.searchsorted(res.cycles, res.checkpoints)      # noqa: E731
    i, j = at(w), at(ref)
    out = [(f"wear.{k}", v[i], getattr(ref, k)[j]) for k, v in w.to_dict().items()
           if k not in WEAR_NOT_COMPARED]
    # the worn profile in the volume norm: ∫2πr|h - h_ref| dr against ∫2πr h_ref dr per
    # checkpoint (pointwise, the step at the stick edge of a partial-slip scar moves by cells)
    depth = np.array([np.interp(ref.r, w.r, h, right=0.0) for h in w.wear_depth])
    weight = 2 * np.pi * ref.r * np.gradient(ref.r)
    vol_ref = ref.wear_depth @ weight
    out.append(("wear.wear_depth", vol_ref + np.abs(depth - ref.wear_depth) @ weight, vol_ref))
    return out


def scene_cost(scene: "Scene", *, target: float = 1e-6,
               ladders: Mapping[str, Sequence[Any]] | None = None,
               knobs: Sequence[str] | None = None) -> CostReport:
    """Run ``scene`` over a ladder of each numeric knob; error against wall time per rung.

    Parameters
    ----------
    scene : Scene
    target : float
        Relative error the recommended setting must meet (``0 < target < 1``).
    ladders : mapping, optional
        Knob -> values, loosest first, the reference last (``steps``: refinement factors,
        ``interpolation``: ``"linear"``, ``"cubic"``); the default is :func:`default_ladders`.
        The scene's own setting is added when missing; ``steps`` factors that cannot refine the
        path (a segment's count would not be whole) are left out.
    knobs : sequence of str, optional
        Only these knobs (default: every knob of the scene, :func:`knobs_of`).

    Returns
    -------
    CostReport
        ``print(report)`` for the table, ``report.choice`` for the recommended setting,
        ``report.plot(path)`` for error against time.

    Raises
    ------
    ParameterError
        ``target`` outside ``(0, 1)``, a ladder with fewer than two values or an inapplicable
        rung.
    UnknownNameError
        A knob that does not apply to this scene.

    Examples
    --------
    >>> from contactlab.scene import Scene
    >>> s = Scene.from_toml("examples/hip_joint_torsion.toml")        # doctest: +SKIP
    >>> print(s.cost(target=1e-4))                                     # doctest: +SKIP
    """
    if isinstance(target, bool) or not isinstance(target, (int, float)) \
            or not 0 < float(target) < 1:
        raise ParameterError(f"target={target!r} is invalid: the relative error target must "
                             "satisfy 0 < target < 1, e.g. 1e-6.")
    applicable = knobs_of(scene)
    knobs = applicable if knobs is None else tuple(knobs)
    for k in knobs:
        if k not in applicable:
            raise UnknownNameError(f"knob {k!r} does not apply to this scene: its knobs are "
                                   f"{applicable}.")
    dflt = _defaults(scene)
    lad = default_ladders(scene)
    for k, vals in (ladders or {}).items():
        if k not in knobs:
            raise UnknownNameError(f"ladders has {k!r}: the knobs run here are {knobs}.")
        vals = list(vals)
        if k == "steps":   # factors that cannot refine this path are left out
            vals = [f for f in vals if _refined(scene.to_dict(), float(f)) is not None]
        if len(vals) < 2:
            raise ParameterError(f"ladders[{k!r}]={vals!r} is invalid: give at least two values "
                                 "(loosest first, the reference last).")
        lad[k] = vals
    scene.run()   # warm-up, untimed: first-call costs (imports, compiled kernels) are no rung's
    runs: dict[str, list[list[Any]]] = {}
    for knob in knobs:
        vals = _ordered(knob, [*lad[knob], dflt[knob]])
        ref_val = vals[-1]
        ref_scene = with_setting(scene, knob, ref_val)
        ref_res, ref_t = _timed_run(ref_scene)
        rows = []
        for v in vals[:-1]:
            sc = with_setting(scene, knob, v)
            res, t = _timed_run(sc)
            idx = _step_map(sc, ref_scene) if knob == "steps" else None
            rows.append([v, t, output_error(res, ref_res, idx), sc])
        rows.append([ref_val, ref_t, None, ref_scene])
        runs[knob] = rows
    # a knob no rung moves beyond rounding is not read by this route: no share of the target
    inert = {k: max(r[2] for r in rows[:-1]) for k, rows in runs.items()
             if all(r[2] <= INERT_FLOOR for r in rows[:-1])}
    live = [k for k in knobs if k not in inert]
    budget = float(target) / (SAFETY * max(len(live), 1))
    rungs: list[Rung] = []
    choice: dict[str, Any] = {}
    certified: dict[str, bool] = {}
    for knob in live:
        rows = runs[knob]
        ref_val = rows[-1][0]
        ok = [r for r in rows[:-1] if r[2] <= budget]
        pick = ok[0][0] if ok else ref_val
        choice[knob] = pick
        certified[knob] = bool(ok)
        for v, t, e, sc in rows:
            rungs.append(Rung(knob, v, _label(knob, v, sc), t, e, default=v == dflt[knob],
                              reference=e is None, chosen=v == pick))
    return CostReport(scene.title, float(target), tuple(rungs), choice, certified, budget,
                      {k: dflt[k] for k in live}, inert)


def _ordered(knob: str, vals: list[Any]) -> list[Any]:
    """Distinct values, loosest first (the reference, the tightest, last)."""
    if knob == "interpolation":
        return [v for v in ("linear", "cubic") if v in vals]
    return sorted(set(vals), reverse=knob in ("rtol", "jump_rtol"))


def _label(knob: str, value: Any, scene: "Scene") -> str:
    if knob == "steps":
        return f"x{value:g} ({scene.history().n_steps} steps)"
    return _fmt(value)

