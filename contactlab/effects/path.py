"""Load paths through the MDR foundation: the driver behind :meth:`Contact.simulate` and its
result :class:`PathResult`.

The normal problem (non-adhesive) is path independent: it is solved first for every step,
vectorised per segment, with the exact closed-form/bracketed normal solver of the contact. Then one
loop over time steps advances the tangential and torsional Jenkins elements of the
:class:`~contactlab.foundation.Winkler` foundation; every operation inside it is vectorised over
the springs. Displacement/twist-controlled steps are explicit; force/torque-controlled steps are
solved exactly (the element sum is piecewise linear and monotone in the increment); a target at or
beyond full sliding gives gross sliding (flagged, not an error).
"""
from __future__ import annotations

import warnings
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..citations import Cited, sources_for
from ..errors import (ContactlabError, EffectNotPlannedError, NotSupportedError, ParameterError,
                      UnknownNameError, ValidityWarning, failed_part_way)
from ..foundation import DEFAULT_N_SPRINGS, Winkler
from ..foundation.base import (SPACINGS, families_needed, iter_path_normal_states,
                               path_normal_states)
from ..loadpath import LoadPath
from ..loadpath.base import UNITS
from ..params import check_count, check_flag, check_memory, name_list, step_indices
from ..physics import fretting as _fr
from ..physics.torsion import MDR_VALID_STICK_RATIO
from ..physics.torsion_validity import affordable_states
from ._protocol import Result, reporting

__all__ = ["PathResult", "simulate", "SERIES", "PROGRESS_THRESHOLD", "compile_normal",
           "simulate_memory", "PATH_METHODS", "resolve_path_method", "METHOD_ARGUMENTS",
           "partial_path_failure", "mdr_path_validity", "warn_mdr_path", "force_variation",
           "MDR_PATH_STICK_RATIOS", "MDR_PATH_HELD_FORCE"]

#: float64 values held per step and per spring at the peak of a run (tracemalloc, rounded up:
#: 42 per step for a sinusoid, 35 per spring, 8 per spring and stored snapshot)
_PER_STEP, _PER_SPRING, _PER_SNAPSHOT_SPRING = 48, 48, 8


def simulate_memory(n_steps: int, n_springs: int, n_snapshots: int = 0) -> float:
    """Estimated peak memory of :func:`simulate`, bytes (checked against the memory budget
    before anything is allocated; see :func:`contactlab.set_memory_budget`)."""
    return 8.0 * (_PER_STEP * float(n_steps) + _PER_SPRING * float(n_springs)
                  + _PER_SNAPSHOT_SPRING * float(n_springs) * n_snapshots)

#: per-step series of a PathResult
SERIES = ("time", "depth", "force", "radius", "displacement", "tangential_force", "twist",
          "torque", "stick_radius", "dissipated_energy", "gross_sliding")
_SERIES_UNITS = dict(UNITS, radius="m", stick_radius="m", dissipated_energy="J",
                     gross_sliding="1")
#: rings of the coarse exact check of an MDR torsion path under a changing normal force
PATH_CHECK_RINGS = 64
#: longest path (steps) whose MDR torsion run gets the coarse exact check
PATH_CHECK_STEPS = 2000
#: model error reported for longer such paths: the largest MDR energy error measured on
#: varying-load paths (benchmarks/torsion_rings.py --map: up to 68 %), not a bound
PATH_MEASURED_ERROR = 0.68
#: paths with at least this many steps show a progress bar when ``progress=True``
PROGRESS_THRESHOLD = 1000
def compile_normal(contact, path: LoadPath) -> list[dict[str, np.ndarray]]:
    """Normal state of every step of ``path``, per leaf segment (exact; see
    :func:`contactlab.foundation.base.path_normal_states`)."""
    return path_normal_states(contact.profile, contact.moduli.normal, path, contact.rtol)


#: steps converted to plain floats at a time by the step-by-step loop (bounded temporaries)
_CHUNK = 4096
#: steps per window of the fused compiled runs (edge data a window at a time; larger than
#: ``_CHUNK``: each window costs ~60 numpy calls, ~25 ns per step at 4096 steps)
_FUSED_WINDOW = 1 << 15
#: steps of a leaf's normal solve at a time (bounded solver temporaries on long paths)
_SOLVE_CHUNK = 1 << 16
#: steps per window of the direction-reversal search (bounded temporaries)
_TURN_WINDOW = 1 << 16
#: shortest run of steps advanced in closed form (shorter runs: step by step, which is cheaper)
_MIN_BLOCK = 8


@dataclass(frozen=True, eq=False)
class PathResult(Result, Cited):
    """Per-step result of :meth:`Contact.simulate`.

    Attributes
    ----------
    time, depth, force, radius, displacement, tangential_force, twist, torque, stick_radius,
    dissipated_energy : ndarray
        Per-step series in SI units (s, m, N, m, m, N, rad, N·m, m, J). ``stick_radius`` is the
        outer radius of the central stick zone of the tangential springs (of the torsional
        springs for a path without shift); ``dissipated_energy`` is cumulative.
    gross_sliding : ndarray of bool
        Steps where a force/torque target reached full sliding.
    snapshots : dict
        ``{step: {"x", "depth", "radius", "normal", "tangential", "torsion", "pressure",
        "shear_tangential", "shear_torsion"}}``: spring states per cell (N, N·m) and the 3D
        pressure and tractions (Pa) at the cell midpoints ``x``, at the requested steps. The
        tractions are the MDR inverse of the spring line loads (piecewise-linear between cells).
    meta : dict
        ``built`` (spring families built), ``n_springs``, ``spacing``, ``foundation``,
        ``approximate``, ``notes`` (warnings raised), ``model_errors`` and
        ``model_error_basis`` (runs on the MDR torsion springs, see :meth:`_assess`).
    model_error : float
        Largest relative model error of the torsion outputs of a run on the MDR torsion springs
        (0.0 for exact routes: the ring solver, normal and tangential springs).
    """

    data: dict
    snapshots: dict = field(default_factory=dict)
    meta: dict = field(default_factory=dict)

    units = _SERIES_UNITS

    def __getattr__(self, name: str) -> Any:
        if name in SERIES:
            data = object.__getattribute__(self, "data")
            if name not in data:
                raise EffectNotPlannedError(f"{name!r} was not requested: add it to outputs= "
                                            f"(requested: {sorted(data)}).")
            return data[name]
        raise AttributeError(name)

    def __len__(self) -> int:
        return int(next(iter(self.data.values())).size)

    def to_dict(self) -> dict[str, np.ndarray]:
        """Copies of the per-step series, keyed by name."""
        return {k: np.array(v) for k, v in self.data.items()}

    def _assess(self, notes: list, contact: Any, path: Any) -> list[str]:
        """Where the model error of a run on the MDR torsion springs comes from, into ``meta``
        (``model_error_basis``; ``model_errors`` per torsion output, computed on first access
        of :attr:`model_error`). The run's validity warnings (:func:`warn_mdr_path`) judge it
        at run time, at the thresholds of the same measurements; nothing more is raised here.
        Exact routes (the ring solver; normal and tangential springs, exact in the MDR) carry
        no model error.

        - Normal force held while twisted (relative range at most :data:`MDR_PATH_HELD_FORCE`):
          the measured MDR-vs-exact maps (:mod:`contactlab.physics.model_error`) at the exact
          stick ratio of the path's largest twist at the contact radius where the slip annulus
          is widest (:func:`mdr_path_validity`).
        - Changing normal force: a coarse exact check, the same path on the exact ring solver
          with :data:`PATH_CHECK_RINGS` rings (paths of at most :data:`PATH_CHECK_STEPS` steps;
          ~2 ms per step on first access); longer paths report the largest error measured on
          varying-load paths, :data:`PATH_MEASURED_ERROR` (not a bound).
        - Shift and twist together (``approximate=True``): no bound (``inf``).
        """
        from functools import partial
        meta, data = self.meta, self.data
        built = meta.get("built", ())
        wanted = tuple(q for q in ("torque", "dissipated_energy") if q in data)
        if (meta.get("method") == "exact" or "torsion" not in built or contact.friction is None
                or not wanted or meta.get("status") == "partial"):
            return []
        if "tangential" in built:
            meta["model_errors"] = {q: float("inf") for q in wanted}
            meta["model_error_basis"] = ("combined shift and twist run as independent spring "
                                         "families (outside the MDR theory): no error bound is "
                                         "known")
        elif not all(k in data for k in ("twist", "radius", "depth", "force")):
            meta["model_errors"] = {q: float("inf") for q in wanted}
            meta["model_error_basis"] = ("not estimated, no bound known: the series twist, "
                                         "radius, depth and force are needed (add them to "
                                         "outputs=)")
        elif force_variation(data["twist"], data["radius"], data["force"]) <= MDR_PATH_HELD_FORCE:
            from .torsion import MDR_MAP_BASIS
            self._defer_model_errors(partial(PathResult._held_force_errors, contact, wanted,
                                             *(data[k] for k in ("twist", "radius", "depth"))))
            meta["model_error_basis"] = MDR_MAP_BASIS + " (normal force held while twisted)"
        elif path is not None and path.n_steps <= PATH_CHECK_STEPS:
            self._defer_model_errors(partial(PathResult._checked_errors, contact, path,
                                             {q: data[q] for q in wanted}))
            meta["model_error_basis"] = (
                f"coarse exact check: the same path on the exact ring solver with "
                f"{PATH_CHECK_RINGS} rings (torque: largest difference over the steps relative "
                "to the largest exact torque; energy: final dissipated energy)")
        else:
            meta["model_errors"] = {q: PATH_MEASURED_ERROR for q in wanted}
            meta["model_error_basis"] = (f"path longer than {PATH_CHECK_STEPS} steps, not "
                                         "checked: the largest MDR error measured on "
                                         "varying-load paths (energy per twist cycle, "
                                         "benchmarks/torsion_rings.py --map), not a bound")
        return []

    @staticmethod
    def _held_force_errors(contact: Any, wanted: tuple, twist: np.ndarray, radius: np.ndarray,
                           depth: np.ndarray) -> dict[str, float]:
        """Model errors of an MDR torsion run at a held normal force, from the measured maps."""
        from .torsion import mdr_map_errors
        tw, a, d = (np.asarray(v, float) for v in (twist, radius, depth))
        _, big, _, a_lim = mdr_path_validity(contact, tw, a, d, "torque")
        i = int(np.argmax(a == a_lim))
        prof = contact.profile
        g = float(prof._g(np.array([a_lim]))[0]) if a_lim > 0 else 0.0
        if np.isfinite(prof.wall_radius) and a_lim >= prof.wall_radius:
            g = min(g, float(d[i]))
        m = mdr_map_errors(contact, np.array([big]), np.array([a_lim]), np.array([d[i]]),
                           np.array([g]), ("torque", "energy"))
        return {q: float(m["energy" if q == "dissipated_energy" else q][0]) for q in wanted}

    @staticmethod
    def _checked_errors(contact: Any, path: Any, series: dict) -> dict[str, float]:
        """Model errors of an MDR torsion run against the exact ring solver at
        :data:`PATH_CHECK_RINGS` rings (the coarse exact check)."""
        from .torsion_path import simulate_exact
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            ex = simulate_exact(contact, path, outputs=tuple(series), n_rings=PATH_CHECK_RINGS)
        errs = {}
        for q, got in series.items():
            ref, got = np.asarray(ex.data[q], float), np.asarray(got, float)
            if q == "torque":
                scale = float(np.max(np.abs(ref), initial=0.0))
                diff = float(np.max(np.abs(got - ref), initial=0.0))
            else:
                scale, diff = abs(float(ref[-1])), abs(float(got[-1] - ref[-1]))
            errs[q] = diff / scale if scale > 0 else 0.0
        return errs

    def plot(self, quantities: Any = None, *, x: str = "time", ax: Any = None,
             units: str = "si"):
        """Plot series against ``x`` (needs matplotlib); returns the axes.

        ``quantities`` defaults to every driven series (force, tangential force, torque).
        ``units="engineering"`` labels µm, mN·m, mrad, µJ instead of SI (see
        :mod:`contactlab.plotting`). A loop (``x="twist"`` against torque, ``x="displacement"``
        against tangential force) gets the loop tick format.
        """
        from .. import plotting as pl
        pl.check_units(units)
        pl.pyplot()
        if quantities is None:
            quantities = [q for q in ("force", "tangential_force", "torque") if q in self.data
                          and np.any(self.data[q] != 0)] or ["force"]
        quantities = [quantities] if isinstance(quantities, str) else list(quantities)
        with pl.style():
            if ax is None:
                _, axes = pl.subplots(len(quantities), 1, squeeze=False, sharex=True,
                                      figsize=(6.0, 1.2 + 1.8 * len(quantities)))
                axes = axes[:, 0]
            else:
                axes = np.atleast_1d(ax)
            xu = _SERIES_UNITS.get(x, "")
            for q, a in zip(quantities, axes):
                qu = _SERIES_UNITS.get(q, "")
                a.plot(pl.scaled(getattr(self, x), xu, units), pl.scaled(getattr(self, q), qu, units))
                a.set_ylabel(pl.axis_label(q.replace("_", " "), qu, units))
                if x != "time" and x != "step":
                    pl.loop_axes(a)
            axes[-1].set_xlabel(pl.axis_label(x.replace("_", " "), xu, units))
        return axes


def _progress(total: int, progress: bool):
    if not progress or total < PROGRESS_THRESHOLD:
        return None
    try:
        from tqdm import tqdm
    except ImportError as err:
        raise ImportError("progress=True needs tqdm: pip install tqdm "
                          "(or pip install 'contactlab[progress]')") from err
    return tqdm(total=total, unit="step", desc="simulate")


#: series whose discretisation error ``error_estimate=True`` reports (the normal ones are exact
#: at any N, the cells integrating their springs exactly)
_ESTIMATED = ("tangential_force", "torque", "stick_radius", "dissipated_energy")


@reporting(lambda res, notes, contact, path=None, *a, **k: res._assess(notes, contact, path))
def simulate(contact, path: LoadPath, *, outputs: Any = None, n_springs: int | None = None,
             spacing: str | None = None, snapshots: Any = None, progress: bool = False,
             approximate: bool = False, strategy: str | None = None,
             error_estimate: bool = False, method: str | None = None,
             n_rings: int | None = None) -> PathResult:
    """Run ``path`` through the MDR foundation; see :func:`_simulate` for the parameters.

    ``method`` picks the torsion model of a path with twist or torque (default
    :data:`DEFAULT_TORSION_METHOD`): ``"exact"`` (exact normal solution per step, exact
    half-space torsion on ``n_rings`` rings with Coulomb friction and memory,
    :func:`contactlab.effects.torsion_path.simulate_exact`) or
    ``"mdr"`` (the MDR spring foundation, exact only while the slip annulus is narrow). Paths
    without twist always run through the MDR foundation (``"mdr"``). The discretisation
    arguments belong to one method (:data:`METHOD_ARGUMENTS`): ``n_springs``, ``spacing`` and
    ``strategy`` to ``"mdr"``, ``n_rings`` to ``"exact"``; given to the other method they raise
    :class:`~contactlab.errors.ParameterError` instead of being ignored.

    ``error_estimate=True`` runs the path a second time with half the springs and stores, in
    ``result.meta["error_estimates"]``, ``max|s_N - s_{N/2}| / max|s_N|`` for each estimated series
    (tangential force, torque, stick radius, dissipated energy). The spring error falls as 1/N²,
    so this difference is about three times the error of the N-spring run: a conservative
    estimate that costs about half a run more (issue 7; honesty tested in
    tests/unit/effects/test_path_error_estimate.py).

    A step that fails (a normal solve, a spring or ring step) raises its error with its type,
    the message naming the step (index, time, path segment); ``err.partial`` is the
    :class:`PathResult` of the steps before it (``meta["status"] == "partial"``; only the normal
    series when the normal solve failed, before the time loop) and ``err.failed_at`` the place.
    """
    approximate = check_flag("approximate", approximate)
    error_estimate = check_flag("error_estimate", error_estimate)
    progress = check_flag("progress", progress)
    if spacing is not None and spacing not in SPACINGS:
        raise UnknownNameError(f"spacing={spacing!r} is invalid: allowed are {SPACINGS}.")
    if outputs is not None:
        outputs = name_list("outputs", outputs, SERIES)
    method = resolve_path_method(path, method, approximate)
    _check_method_arguments(method, n_springs=n_springs, spacing=spacing, strategy=strategy,
                            n_rings=n_rings)
    spacing = "edge" if spacing is None else spacing
    if method == "exact":
        from .torsion_path import simulate_exact
        return simulate_exact(contact, path, outputs=outputs, n_rings=n_rings,
                              snapshots=snapshots, error_estimate=error_estimate,
                              progress=progress)
    res = _simulate(contact, path, outputs=outputs, n_springs=n_springs, spacing=spacing,
                    snapshots=snapshots, progress=progress, approximate=approximate,
                    strategy=strategy)
    if error_estimate and res.meta.get("n_springs"):
        half = _simulate(contact, path, outputs=outputs, n_springs=max(2, res.meta["n_springs"] // 2),
                         spacing=spacing, progress=False, approximate=approximate,
                         strategy=strategy, warn=False)
        est = {}
        for name in _ESTIMATED:
            if name in res.data:
                full, coarse = np.asarray(res.data[name]), np.asarray(half.data[name])
                scale = float(np.max(np.abs(full), initial=0.0))
                est[name] = float(np.max(np.abs(full - coarse), initial=0.0)) / scale if scale else 0.0
        res.meta["error_estimates"] = est
    return res


#: torsion models of :func:`simulate` (``method=``)
PATH_METHODS = ("exact", "mdr")
#: arguments of :func:`simulate` that only one method reads (its discretisation)
METHOD_ARGUMENTS = {"mdr": ("n_springs", "spacing", "strategy"), "exact": ("n_rings",)}


def _check_method_arguments(method: str, **given: Any) -> None:
    """:class:`ParameterError` for an argument of the other method's discretisation: it would be
    ignored silently (``n_springs`` on a twisted path, which runs the ring solver by default)."""
    for other, names in METHOD_ARGUMENTS.items():
        if other == method:
            continue
        for name in names:
            if given.get(name) is not None:
                hint = ("pass method='mdr' to run the MDR spring foundation, or n_rings= to set "
                        "the ring solver's resolution" if other == "mdr" else
                        "it sets the ring solver's resolution (method='exact', paths with twist "
                        "or torque and no shift)")
                raise ParameterError(
                    f"{name}={given[name]!r} applies to method={other!r} only, but this path "
                    f"runs method={method!r}"
                    + (" (the default for a path with twist or torque)" if method == "exact"
                       else "") + f": {hint}.")
#: model of a path with twist/torque and no shift when ``method=None``
DEFAULT_TORSION_METHOD = "exact"


def resolve_path_method(path: LoadPath, method: str | None, approximate: bool = False) -> str:
    """The torsion model a path runs with: :data:`DEFAULT_TORSION_METHOD` for a path with
    twist/torque and no shift, else ``"mdr"``."""
    if method is not None and method not in PATH_METHODS:
        raise UnknownNameError(f"method={method!r} is invalid: allowed are {PATH_METHODS}.")
    groups = getattr(path, "groups", ())
    torsion_only = "torsion" in groups and "tangential" not in groups
    if method is None:
        return DEFAULT_TORSION_METHOD if torsion_only and not approximate else "mdr"
    if method == "exact" and not torsion_only:
        raise NotSupportedError("method='exact' solves paths with twist or torque and no shift; "
                                "this path has " + (" and ".join(sorted(groups)) or "no twist")
                                + ": use method='mdr'.")
    return method


def _simulate(contact, path: LoadPath, *, outputs: Any = None, n_springs: int | None = None,
              spacing: str = "edge", snapshots: Any = None, progress: bool = False,
              approximate: bool = False, strategy: str | None = None,
              warn: bool = True) -> PathResult:
    """Run ``path`` through the MDR foundation of ``contact``.

    Parameters
    ----------
    contact : Contact
        Non-adhesive; ``friction=None`` means no slip.
    path : LoadPath
    outputs : iterable of str, optional
        Per-step series to keep (default all of :data:`SERIES`).
    n_springs : int, optional
        Cells over the path's largest contact radius (default
        :data:`~contactlab.foundation.DEFAULT_N_SPRINGS`).
    spacing : {"edge", "uniform"}
        Cell spacing (edge-refined by default).
    snapshots : iterable of int, optional
        Steps (0-based; negative counts from the end) at which spring states are stored.
    progress : bool
        Show a tqdm progress bar for paths of at least :data:`PROGRESS_THRESHOLD` steps
        (library use is quiet by default).
    approximate : bool
        Allow combined shift and twist, run as independent spring families (warns).
    strategy : {"segments", "steps"}, optional
        Numerical route of the time loop, same results up to rounding. ``"segments"`` (default)
        advances runs of steps with a held normal load and a monotone control in closed form
        (sorted slip thresholds, ``O(log N)`` per step); ``"steps"`` updates every spring at
        every step.
    warn : bool
        Emit the :class:`ValidityWarning` of :func:`warn_mdr_path` (off for the half-spring run
        of the error estimate).

    Returns
    -------
    PathResult

    Raises
    ------
    OutsideTheoryError
        Combined shift and twist without ``approximate=True``.
    NotSupportedError
        Adhesive contacts.

    Warns
    -----
    ValidityWarning
        A twisted path beyond the validity of the MDR torsion springs (:func:`warn_mdr_path`).
    """
    if not isinstance(path, LoadPath):
        raise ParameterError(f"path={path!r} is invalid: expected a contactlab.LoadPath.")
    if contact.is_adhesive:
        raise NotSupportedError("simulate() supports non-adhesive contacts only "
                                "(work_of_adhesion=None).")
    strategy = "segments" if strategy is None else strategy
    if strategy not in ("segments", "steps"):
        raise UnknownNameError(f"strategy={strategy!r} is invalid: allowed are "
                               "('segments', 'steps').")
    needs = families_needed(path, approximate=approximate)
    if len(needs) == 2:
        warnings.warn("combined shift and twist is run as two independent spring families "
                      "(approximate=True): outside the MDR theory, the slip limits do not "
                      "interact.", ValidityWarning, stacklevel=3)
    if outputs is None:
        outputs = SERIES
    outputs = tuple(outputs)
    for o in outputs:
        if o not in SERIES:
            raise UnknownNameError(f"outputs contains {o!r}: allowed are {SERIES}.")
    n_total = path.n_steps
    if n_total == 0:
        raise ParameterError("path has no steps: add a segment, e.g. "
                             "LoadPath().ramp(force=1.0, steps=10).")
    n_springs = DEFAULT_N_SPRINGS if n_springs is None else check_count("n_springs", n_springs)
    step_indices("snapshots", snapshots, n_total)             # a list of valid step indices
    snapshots = [] if snapshots is None else list(snapshots)
    check_memory("simulate()", simulate_memory(n_total, n_springs, len(snapshots)),
                 f"{n_total} steps, {n_springs} springs, {len(snapshots)} snapshots")
    snaps = step_indices("snapshots", snapshots, n_total)
    # the normal series are written at every step (or the call raises before reading them):
    # no zero fill (a 10^6-step series re-used from the heap is memset by np.zeros, ~2 ms each)
    res = _series_block(n_total, [k for k in SERIES if k in outputs and (
        k in _NORMAL or (needs and k in _run_writes(needs, outputs)))])
    for k in _NORMAL:
        if k not in res:        # read by the time loop, not returned: its own array
            res[k] = np.empty(n_total)
    # the normal states go straight into the series, one leaf at a time; the time loop reads
    # them back as views (no second copy of the path's normal arrays)
    t0 = 0.0
    i0 = 0
    normal = []
    try:
        for seg in iter_path_normal_states(contact.profile, contact.moduli.normal, path,
                                           contact.rtol, chunk=_SOLVE_CHUNK, out=res):
            n = seg["depth"].size      # depth, force, radius: written into res by the solve
            res["time"][i0:i0 + n] = t0 + seg["dt"]
            del seg
            normal.append({k: res[k][i0:i0 + n] for k in ("depth", "radius")})
            t0 = float(res["time"][i0 + n - 1]) if n else t0
            i0 += n
    except ContactlabError as err:
        pre = err.partial if isinstance(err.partial, dict) else None
        k = i0 + (pre["depth"].size if pre is not None else 0)
        if pre is not None:
            res["time"][i0:k] = t0 + pre["dt"]
            for name in ("depth", "force", "radius"):
                res[name][i0:k] = pre[name]
        # the time loop had not started: the partial result holds the normal series only
        raise partial_path_failure(err, path, res, [o for o in outputs if o in _NORMAL], k,
                                   {"method": "mdr"},
                                   time=t0 + (err.failed_at or {}).get("dt", 0.0)) from None
    a_max = float(np.max(res["radius"], initial=0.0))
    from .normal import warn_outside_validity
    warn_outside_validity(contact.profile, a_max, stacklevel=4)
    meta = {"built": ["normal", *needs], "n_springs": None, "spacing": spacing,
            "approximate": bool(approximate), "foundation": None,
            "citations": sources_for("normal", "foundation",
                                     *(("tangential",) if "tangential" in needs else ()),
                                     *(("foundation:torsion",) if "torsion" in needs else ()))}
    snapshot_data: dict[int, dict] = {}
    runs = a_max > 0 and bool(needs)
    for k in SERIES:
        if k not in res:
            res[k] = (np.empty(n_total) if runs and k in _run_writes(needs, outputs) else
                      np.zeros(n_total, bool if k == "gross_sliding" else float))
    if not runs:
        # nothing but the (exact) normal problem: no tangential/torsional springs are built
        res["stick_radius"][:] = res["radius"]
        if needs:
            _no_contact_controls(path, needs)
        fnd = None
        if snaps and a_max > 0:
            fnd = Winkler(contact.profile, contact.moduli, contact.friction, a_max,
                          n_springs=n_springs, spacing=spacing, needs=(), rtol=contact.rtol)
            meta.update(n_springs=fnd.n_springs, foundation=repr(fnd))
        for s in sorted(snaps):
            snapshot_data[s] = _snapshot(contact, fnd, None, res, s)
        return PathResult({k: res[k] for k in outputs}, snapshot_data, meta)
    track: dict[str, Any] = {"done": 0}
    try:
        fnd = Winkler(contact.profile, contact.moduli, contact.friction, a_max,
                      n_springs=n_springs, spacing=spacing, needs=needs, rtol=contact.rtol)
        meta.update(n_springs=fnd.n_springs, foundation=repr(fnd))
        _run(contact, fnd, path, normal, res, snaps, snapshot_data, "stick_radius" in outputs,
             progress, strategy, track)
    except ContactlabError as err:
        snaps_done = {s: v for s, v in snapshot_data.items() if s < track["done"]}
        raise partial_path_failure(err, path, res, outputs, track["done"], meta,
                                   snaps_done) from None
    if warn and "torsion" in needs and contact.friction is not None:
        warn_mdr_path(contact, res["twist"], res["radius"], res["depth"], res["force"],
                      energy="dissipated_energy" in outputs, stacklevel=4)
    return PathResult({k: res[k] for k in outputs}, snapshot_data, meta)


_NORMAL = ("time", "depth", "force", "radius")
#: the series of each spring family, written at every step by the time loop (:func:`_run`)
_FAMILY_SERIES = {"tangential": ("displacement", "tangential_force"),
                  "torsion": ("twist", "torque")}


def _series_block(n: int, keys: list) -> dict[str, np.ndarray]:
    """Float series of ``n`` steps for ``keys``, the rows of one ``(len(keys), n)`` block.

    Each row is written at every step before it is read (the normal series by the solve, the
    spring families' by the time loop, which runs whenever a family is loaded or the call
    raises). One allocation instead of one per series: the operating system backs a long block
    by whole huge pages (a 10^6-step gait run: ~3 300 page faults instead of ~7 200, ~9 ns per
    step less of system time on a 2-core VM), and the rows are the returned series only, so
    that a series computed but not asked for is freed on return as before.
    """
    if not keys:
        return {}
    block = np.empty((len(keys), n))
    return dict(zip(keys, block))


def _run_writes(needs: tuple, outputs: tuple) -> tuple:
    """The series :func:`_run` writes at every step (each step's fused, closed-form or
    step-by-step route): those need no zero fill. The others (a family the path does not
    load, ``gross_sliding`` which steps OR into) start from zeros."""
    out = ["dissipated_energy"]
    if "stick_radius" in outputs:      # the loop skips the stick search otherwise
        out.append("stick_radius")
    for fam in needs:
        out += _FAMILY_SERIES[fam]
    return tuple(out)


def partial_path_failure(err: ContactlabError, path: LoadPath, res: dict, outputs: Any, k: int,
                         meta: dict, snapshots: dict | None = None,
                         time: float | None = None) -> ContactlabError:
    """``err`` from step ``k`` of ``path`` (steps ``0 .. k-1`` complete in ``res``), named by
    step, time (``res["time"][k]`` unless given) and segment, with the :class:`PathResult` of
    those steps as ``err.partial`` (``meta["status"] == "partial"``)."""
    n = path.n_steps
    leaves = list(path.leaves())
    ends = np.cumsum([lf.n_steps for lf in leaves])
    leaf = min(int(np.searchsorted(ends, k, side="right")), ends.size - 1)
    kind = type(leaves[leaf]).__name__.lower()
    t = float(time) if time is not None else float(res["time"][k]) if k < n else float("nan")
    where = (f"step {k} of {n} failed (t = {t:.6g} s, path segment {leaf}, {kind}; "
             + (f"steps 0-{k - 1} computed, in err.partial)" if k else "no step computed)"))
    info = {"step": k, "n_steps": n, "time": t, "segment": leaf}
    part = PathResult({o: np.array(res[o][:k]) for o in outputs}, dict(snapshots or {}),
                      {**meta, "status": "partial", "failed_at": info})
    failed_part_way(err, where, part, **info)
    part.meta["error"] = f"{type(err).__name__}: {err}"
    return err


#: contact radii (spread over the path's range by value, the smallest and largest included) at
#: which :func:`warn_mdr_path` evaluates the MDR validity twist; the smallest of these limits is
#: used (fewer on tables too large for the exact slip function:
#: :func:`contactlab.physics.torsion_validity.affordable_states`)
_VALIDITY_RADII = 33

#: the quantities :func:`mdr_path_validity` judges and the exact stick ratio ``c/a`` at constant
#: load below which the MDR model errs by more than 1 % on each (torque: the criterion of
#: ``contact.torsion(method="mdr")``; energy per twist cycle: the fretting error map's)
MDR_PATH_STICK_RATIOS: dict[str, float] = {"torque": MDR_VALID_STICK_RATIO,
                                           "energy": _fr.MDR_VALID_STICK_RATIOS["energy"]}

#: largest relative range of the normal force, ``(max F − min F)/max F`` over the twisted steps,
#: at which :func:`warn_mdr_path` still judges the MDR dissipated energy by the constant-load
#: criterion. Measured by ``benchmarks/torsion_rings.py --map`` (Hertz and cone, 180 steps, exact
#: ring solver at 400 rings): at constant force and at ±0.1 % (range 2e-3) the constant-load
#: criterion separated the MDR energy per twist cycle exactly (at most 0.65 % off inside it, at
#: least 1.16 % beyond it); with the force changing by ±0.3 % to ±40 % (sinusoid, gait) the
#: MDR energy was off by more than 1 % on 49 of 52 paths (up to 68 %), also within the torque
#: limit (the error grows as the twist shrinks against the load change: the moving contact edge
#: dominates the dissipation)
MDR_PATH_HELD_FORCE = 2e-3


#: long paths: the radii binned by :func:`_validity_states` are those of about this many steps
#: (evenly strided; the smallest and the largest radius are always kept)
_VALIDITY_SAMPLE = 1 << 14


def _twisted(twist: np.ndarray, radius: np.ndarray) -> int:
    """Index of the first step at which the twist differs from the twist at first contact."""
    a = np.asarray(radius, float)
    return int(np.argmax(np.asarray(twist, float) != (float(twist[0]) if a[0] > 0 else 0.0)))


def force_variation(twist: np.ndarray, radius: np.ndarray, force: np.ndarray) -> float:
    """Relative range of the normal force while the path is twisted,
    ``(max F − min F)/max |F|`` from the step before the twist first changes (0 at constant normal
    force while twisted, and without force)."""
    return _force_variation(np.asarray(force, float), _twisted(twist, radius))


def _force_variation(force: np.ndarray, j: int) -> float:
    """:func:`force_variation` with the first twisted step ``j`` known (two passes over the
    force: max and min; ``max |F| = max(|max F|, |min F|)``)."""
    f = force[max(j - 1, 0):]
    if f.size == 0:
        return 0.0
    hi, lo = float(np.max(f)), float(np.min(f))
    top = max(abs(hi), abs(lo))
    return (hi - lo) / top if top > 0 else 0.0


def _validity_states(a: np.ndarray, depth: np.ndarray, j0: int, held: np.ndarray | None,
                     count: int) -> tuple[np.ndarray, np.ndarray]:
    """Up to ``count`` normal states (radius, depth) spread over the range of the contact radii
    of steps ``j0 ...`` (``held``: those steps' indices where not all are in contact), in
    O(steps): the radii (of every step, or of every ``steps // _VALIDITY_SAMPLE``-th on long
    paths) are binned by value into ``count`` equal bins and each bin is represented by its
    first such step; the smallest and the largest radius (their first steps) are always among
    them."""
    ah = a[j0:] if held is None else a[held]
    dh = depth[j0:] if held is None else depth[held]
    i_lo, i_hi = int(np.argmin(ah)), int(np.argmax(ah))
    lo, hi = float(ah[i_lo]), float(ah[i_hi])
    if hi == lo:
        return ah[i_lo:i_lo + 1].copy(), dh[i_lo:i_lo + 1].copy()
    k = max(count, 2) - 1
    stride = max(1, ah.size // _VALIDITY_SAMPLE)
    b = ((ah[::stride] - lo) / (hi - lo) * k).astype(np.intp)
    np.minimum(b, k, out=b)
    first = np.full(k + 1, -1, np.intp)
    # repeated indices: the last assignment wins, so assigning in reverse keeps the first step
    first[b[::-1]] = np.arange(b.size - 1, -1, -1) * stride
    first[0], first[k] = i_lo, i_hi
    first = np.unique(first[first >= 0])
    return ah[first], dh[first]


def mdr_path_validity(contact, twist: np.ndarray, radius: np.ndarray, depth: np.ndarray,
                      quantity: str = "torque") -> tuple[float, float, float, float]:
    """How far a twisted path leaves the constant-load validity of the MDR torsion springs.

    The constant-load criterion of ``quantity`` (the exact twist at which the stick radius falls
    to :data:`MDR_PATH_STICK_RATIOS` ``[quantity]`` times the contact radius; for ``"torque"`` the
    criterion of ``contact.torsion(method="mdr")``,
    :func:`contactlab.effects.torsion.mdr_validity_twist`) evaluated at the contact radius where it
    is smallest among the radii while the path is twisted (for Hertz the smallest of them; up to
    :data:`_VALIDITY_RADII` radii spread over their range, found in O(steps)),
    compared with the path's largest twist measured from the twist at first contact. A profile
    with a wall (flat punch) has the energy limit 0: its MDR energy errs by more than 1 % as soon
    as anything slips.

    Parameters
    ----------
    contact : Contact
    twist, radius, depth : ndarray
        Per-step twist (rad), contact radius (m) and depth (m) of the path.
    quantity : {"torque", "energy"}

    Returns
    -------
    ratio : float
        Largest ``|twist|`` over the validity twist (1 at the limit; 0 without contact or twist,
        ``inf`` for a zero limit).
    twist, limit : float
        That twist and the validity twist, rad.
    radius : float
        The contact radius of the limit, m.
    """
    if quantity not in MDR_PATH_STICK_RATIOS:
        raise UnknownNameError(f"quantity={quantity!r} is invalid: allowed are "
                               f"{tuple(MDR_PATH_STICK_RATIOS)}.")
    return _path_validity(contact, np.asarray(twist, float), np.asarray(radius, float),
                          np.asarray(depth, float), quantity, None)


def _path_validity(contact, tw: np.ndarray, a: np.ndarray, depth: np.ndarray, quantity: str,
                   j: int | None) -> tuple[float, float, float, float]:
    """:func:`mdr_path_validity` (``j``: the first twisted step if known) in a few passes over
    the steps (a gait of 10^6 steps: a few ms)."""
    if a.size == 0:
        return 0.0, 0.0, float("inf"), 0.0
    i0 = 0 if a[0] > 0 else int(np.argmax(a > 0))
    if not a[i0] > 0:
        return 0.0, 0.0, float("inf"), 0.0
    ref = float(tw[i0 - 1]) if i0 else 0.0
    # every step in contact from the first contact on (a gait): no masks
    all_live = bool(a[i0 + int(np.argmin(a[i0:]))] > 0)
    live_tw = tw[i0:] if all_live else tw[a > 0]
    # max |twist - ref| (rounding is monotone: the same value as over every step)
    big = max(float(np.max(live_tw)) - ref, ref - float(np.min(live_tw)))
    if not big > 0:
        return 0.0, 0.0, float("inf"), 0.0
    # the limit over the contact radii while twisted (from the step before the twist first
    # changes: a force ramp before the twist does not count)
    j0 = max((_twisted(tw, a) if j is None else j) - 1, 0)
    held = None if all_live and j0 >= i0 else np.flatnonzero(a[j0:] > 0) + j0
    ra, rd = _validity_states(a, depth, j0, held,
                              affordable_states(contact.profile, float(np.max(a)),
                                                _VALIDITY_RADII))
    prof = contact.profile
    g_a = prof._g(ra)
    if np.isfinite(prof.wall_radius):
        g_a = np.where(ra >= prof.wall_radius, np.minimum(g_a, rd), g_a)
    if quantity == "torque":
        from .torsion import mdr_validity_twist
        lim = mdr_validity_twist(contact, ra, rd, g_a)
    else:
        lim = _fr.mdr_validity_twists(prof, contact.moduli.normal, contact.moduli.torsional,
                                      contact.friction, ra, rd, g_a, (quantity,),
                                      contact.rtol)[quantity]
    k = int(np.argmin(lim))
    ratio = big / float(lim[k]) if lim[k] > 0 else float("inf")
    return ratio, big, float(lim[k]), float(ra[k])


def warn_mdr_path(contact, twist: np.ndarray, radius: np.ndarray, depth: np.ndarray,
                  force: np.ndarray, *, energy: bool = True, stacklevel: int = 2) -> None:
    """:class:`ValidityWarning` when a twisted path run on the MDR springs leaves their validity
    for its torque or (``energy=True``, when the dissipated energy is an output) its dissipated
    energy; the message states both judgements.

    - Torque: :func:`mdr_path_validity` above 1, at constant or changing normal load (at constant
      load the criterion of ``contact.torsion(method="mdr")`` and ``twist_history``).
    - Energy: at a normal force held while twisted (relative range at most
      :data:`MDR_PATH_HELD_FORCE`) :func:`mdr_path_validity` with ``quantity="energy"`` above 1
      (the constant-load criterion of the fretting functions); with a changing normal load
      whenever the path is twisted (the MDR energy was off by more than 1 % on nearly every such
      path measured, also at the smallest twists).

    Grounded by ``benchmarks/torsion_rings.py --map`` (Hertz and cone, constant, sinusoidal and
    gait-like normal force, 180 steps, against the exact ring solver at 400 rings): the MDR torque
    erred by at most 0.8 % of the path's largest sliding torque up to the torque limit, by
    0.5-2.1 % at 1.06-1.7 times it, 9-12 % at 4.5-6.4 times it and 21-24 % at 12-17 times it.
    The MDR energy dissipated per twist cycle followed the constant-load energy criterion at a
    held force (at most 0.65 % off inside it, at least 1.16 % beyond it); with the force changing
    by ±0.3 % to ±40 % it was off by more than 1 % on 49 of 52 paths (up to 68 %), also well
    within the torque limit.

    Parameters
    ----------
    contact : Contact
    twist, radius, depth, force : ndarray
        Per-step twist (rad), contact radius (m), depth (m) and normal force (N) of the run.
    energy : bool
        Judge the dissipated energy too (``False`` when it is not an output).
    stacklevel : int
        Passed to :func:`warnings.warn`.
    """
    twist, radius, depth = (np.asarray(v, float) for v in (twist, radius, depth))
    j = _twisted(twist, radius)
    if j == 0 and float(twist[0]) == 0.0:
        return          # never twisted
    ratio, big, lim, a = _path_validity(contact, twist, radius, depth, "torque", j)
    torque_bad = ratio > 1.0
    parts = [f"torque: twist {big:.4g} rad is {ratio:.3g} times {lim:.4g} rad, the twist at "
             f"which the exact stick radius falls below c/a={MDR_VALID_STICK_RATIO} at the contact "
             f"radius {a:.4g} m (" + ("outside" if torque_bad else "within") + " the torque "
             "limit; measured MDR torque errors of the largest sliding torque: up to 0.8 % within "
             "it, 0.5-2.1 % at 1.06-1.7 times it, 9-12 % at 4.5-6.4 times it, 21-24 % at 12-17 "
             "times it)"]
    energy_bad = False
    if energy:
        var = _force_variation(np.asarray(force, float), j)
        if var <= MDR_PATH_HELD_FORCE:
            e_ratio, _, e_lim, _ = _path_validity(contact, twist, radius, depth, "energy", j)
            energy_bad = e_ratio > 1.0
            parts.append("dissipated energy: " + ("outside" if energy_bad else "within")
                         + f", the twist is {e_ratio:.3g} times {e_lim:.4g} rad, the twist at "
                         "which the exact stick radius falls below c/a="
                         f"{MDR_PATH_STICK_RATIOS['energy']} (beyond it the MDR energy per twist "
                         "cycle errs by more than 1 %)")
        else:
            energy_bad = big > 0.0
            parts.append(f"dissipated energy: outside, the normal force changes by "
                         f"{100 * var:.3g} % while twisted (measured: the MDR energy per twist "
                         "cycle off by more than 1 % on 49 of 52 paths with the force changing "
                         "by ±0.3 % to ±40 %, up to 68 %, also within the torque limit)")
    if torque_bad or energy_bad:
        warnings.warn("MDR torsion springs outside their validity on this path. "
                      + "; ".join(parts) + ". Use method='exact'.",
                      ValidityWarning, stacklevel=stacklevel)


def _no_contact_controls(path, needs):
    """A shift/twist on a contact that never touches: only zero targets are meaningful."""
    raise ParameterError("the path prescribes " + " and ".join(needs) + " but the normal load "
                         "never brings the bodies into contact (contact radius 0 at every step).")


def _snapshot(contact, fnd, st, res, i) -> dict:
    d, a = float(res["depth"][i]), float(res["radius"][i])
    snap = {"depth": d, "radius": a}
    if fnd is not None:
        x = fnd.positions
        snap["x"] = x.copy()
        S = np.maximum(d * fnd.w - fnd.dG, 0.0)
        S[fnd.bl >= a] = 0.0
        if st is not None:
            from ..foundation.winkler import snapshot_shear
            S = st.S.copy()
            snap["tangential"] = None if st.tangential is None else st.tangential.copy()
            snap["torsion"] = None if st.torsion is None else st.torsion.copy()
            snap.update(snapshot_shear(fnd, st, x))
        snap["normal"] = 2.0 * contact.moduli.normal * S
        snap["pressure"] = (np.asarray(contact.normal(depth=d).pressure(x), float) if a > 0
                            else np.zeros(x.size))
    return snap


def _turns(v0: float, v: np.ndarray) -> np.ndarray:
    """Indices j where the increment v[j] - v[j-1] reverses the direction of the last non-zero
    increment (v[-1] := v0): the starts of new monotone runs (a window of steps at a time:
    bounded temporaries)."""
    out = [np.zeros(0, np.int64)]
    last, prev = 0.0, v0
    for c0 in range(0, v.size, _TURN_WINDOW):
        w = v[c0:c0 + _TURN_WINDOW]
        sg = np.sign(np.diff(w, prepend=prev))
        prev = w[-1]
        nnz = np.count_nonzero(sg)
        if nnz == 0:
            continue
        if nnz == sg.size:  # every step moves (a gait): no index gather
            s = sg
            flips = np.flatnonzero(s[1:] != s[:-1]) + 1
            first = 0
        else:
            nz = np.flatnonzero(sg)
            s = sg[nz]
            flips = nz[1:][s[1:] != s[:-1]]
            first = int(nz[0])
        if last != 0.0 and s[0] != last:
            flips = np.concatenate(([first], flips))
        out.append(flips + c0)
        last = s[-1]
    return np.concatenate(out)


def _run_edges(flags: np.ndarray) -> np.ndarray:
    """Starts and ends (one past) of the runs of True in ``flags``."""
    f = flags.view(np.int8)
    return np.flatnonzero(np.diff(f, prepend=np.int8(0), append=np.int8(0)))


def _next(sorted_idx: np.ndarray, j: int, default: int) -> int:
    k = int(np.searchsorted(sorted_idx, j, side="right"))
    return int(sorted_idx[k]) if k < sorted_idx.size else default


def _set_keff(ch: dict, weight: np.ndarray) -> None:
    """Stiffness of the elements for this step: full stiffness times the contact weight."""
    np.multiply(ch["K"], weight, out=ch["Keff"])
    # 1/K_eff where in contact; elsewhere the slip is 0 and any finite value will do
    np.divide(ch["invK"], weight, out=ch["iKeff"], where=weight > 0)


def _fused_step(fnd: Winkler, chans: list) -> Any:
    """The compiled fused step (numba backend) for one spring family with friction, else None;
    its arguments per family: the limit's cell integrals and friction factor."""
    from ..foundation._compiled import fused_step
    if len(chans) != 1 or fnd.friction is None:
        return None
    kernel = fused_step()
    if kernel is None:
        return None
    tor = chans[0]["L"] == "L_tor"
    chans[0]["fused"] = ((fnd.X1, fnd.dH, fnd._c_tor) if tor else (fnd.w, fnd.dG, fnd._c_tan))
    return kernel


def _fused_run(kernel, fnd, st, ch, i0, d, a, k, S_edge, T_edge, target, state, out_W,
               out_stick):
    """Steps ``i0 ...`` (each with a new depth, a prescribed displacement/twist) in one compiled
    call (the same element arithmetic as ``set_normal`` + stiffness weighting + ``jenkins`` + sum
    + stick radius per step), then the normal state and slip limits of the last step."""
    from ..foundation import _compiled
    X1, dH, c = ch["fused"]
    n = d.size
    sl = slice(i0, i0 + n)
    stick = out_stick[sl] if out_stick is not None else np.empty(n)
    W = out_W[sl]
    sgn, lo = kernel(d, a, k, S_edge, T_edge, target, st.depth, st.k, ch["x"], ch["release"], c,
                     fnd.w, fnd.dG, X1, dH, ch["K"], ch["invK"], ch["iKeff"], st.S, ch["m"],
                     fnd.bl, state["W"], ch["out_frc"][sl], W, stick, out_stick is not None,
                     _compiled.FUSED_BLOCK, _compiled.FUSED_BLOCK_FROM)
    ch["iKeff"][:lo] = ch["invK"][:lo]   # the bulk of the last step (weight 1)
    # the normal state and slip limits of the last step (what set_normal computes), written
    # into the run's arrays: no full-length temporaries (10^6 springs: 4 fresh 8 MB arrays)
    dl, kl = float(d[-1]), int(k[-1])
    S = st.S   # read by the kernel at the first step only
    np.multiply(fnd.w, dl, out=S)
    S -= fnd.dG
    S[kl + 1:] = 0.0
    S[kl] = S_edge[-1]
    name = ch["L"]
    L, nL = getattr(st, name), getattr(st, "n" + name)
    if name == "L_tor":
        np.multiply(X1, dl, out=L)
        L -= dH
        L[kl + 1:] = 0.0
        L[kl] = T_edge[-1]
        L *= c
    else:
        np.multiply(S, c, out=L)
    np.negative(L, out=nL)
    st.depth, st.radius, st.k = dl, float(a[-1]), kl
    state.update(first=False, keff_is_frac=False, W=float(W[-1]))
    if sgn != 0.0:
        ch["dir"] = sgn
    ch["release"] = False
    ch["x"] = float(target[-1])
    dst = ch["out_pos"][sl]
    if dst.ctypes.data != target.ctypes.data or dst.strides != target.strides:
        dst[...] = target      # (the time loop passes the series' own view: nothing to copy)


def _run(contact, fnd: Winkler, path, normal, res, snaps, snapshot_data, want_stick, progress,
         strategy="segments", track=None):
    """Time loop. ``strategy="segments"``: runs of steps with a held normal load and a monotone
    control are advanced in closed form (:func:`~contactlab.foundation.winkler.monotone_block`),
    other steps one by one; ``"steps"``: every step one by one (same results up to rounding)."""
    from ..foundation.winkler import monotone_block
    st = fnd.new_state()
    n = fnd.n_springs
    chans = []
    if st.tangential is not None:
        chans.append({"m": st.tangential, "K": fnd.K_tan, "invK": fnd.invK_tan, "L": "L_tan",
                      "pos": "displacement", "frc": "tangential_force"})
    if st.torsion is not None:
        chans.append({"m": st.torsion, "K": fnd.K_tor, "invK": fnd.invK_tor, "L": "L_tor",
                      "pos": "twist", "frc": "torque"})
    for ch in chans:
        ch.update(Keff=np.zeros(n), iKeff=np.zeros(n), ctrl=ch["pos"], x=0.0, dir=1.0,
                  release=False)
        ch["out_pos"], ch["out_frc"] = res[ch["pos"]], res[ch["frc"]]
    stick_ch = chans[0] if chans else None
    loop_controls = tuple(q for ch in chans for q in (ch["pos"], ch["frc"]))
    tmp = np.empty(n)
    cur = dict.fromkeys(("depth", "force", "displacement", "tangential_force", "twist",
                         "torque"), 0.0)
    out_W, out_stick, out_gross = res["dissipated_energy"], res["stick_radius"], res["gross_sliding"]
    bar = _progress(res["time"].size, progress)
    snap_idx = np.array(sorted(snaps), int)
    state = track if track is not None else {}      # "done": steps complete (partial results)
    state.update(W=0.0, first=True, keff_is_frac=False, done=0)
    fused = _fused_step(fnd, chans)

    def step(i, d, a, k_edge, S_edge, T_edge, targets):
        W = state["W"]
        if state["first"] or d != st.depth or a != st.radius:
            state["first"] = False
            release = d < st.depth  # slip limits only shrink when the depth decreases
            weight = fnd.set_normal(st, d, a, k_edge, S_edge, T_edge)
            state["keff_is_frac"] = weight is None
            if weight is None:
                weight = fnd.fraction(a)
            for ch in chans:
                _set_keff(ch, weight)
                # springs beyond their new limit slide back to it (a prescribed displacement
                # step does this in the same clip as its increment)
                if release and ch["ctrl"] != ch["pos"]:
                    W += fnd.jenkins(ch["m"], ch["Keff"], ch["iKeff"], getattr(st, ch["L"]),
                                     getattr(st, "n" + ch["L"]), 0.0, tmp)
                elif release:
                    ch["release"] = True
        elif not state["keff_is_frac"]:
            frac = fnd.fraction(a)
            for ch in chans:
                _set_keff(ch, frac)
            state["keff_is_frac"] = True
        for ch, target in zip(chans, targets):
            m = ch["m"]
            L = getattr(st, ch["L"])
            if ch["ctrl"] == ch["pos"]:
                inc = target - ch["x"]
            else:
                inc, gross = fnd.solve(m, ch["Keff"], L, target)
                out_gross[i] |= gross
            if inc != 0.0 or ch["release"]:
                if inc != 0.0:
                    ch["dir"] = 1.0 if inc > 0 else -1.0
                W += fnd.jenkins(m, ch["Keff"], ch["iKeff"], L, getattr(st, "n" + ch["L"]), inc,
                                 tmp)
                ch["x"] += inc
                ch["release"] = False
            if ch["ctrl"] == ch["pos"]:
                ch["x"] = float(target)  # no round-off drift of a prescribed position
            ch["out_pos"][i] = ch["x"]
            ch["out_frc"][i] = m.sum()
        out_W[i] = W
        state["W"] = W
        if want_stick:
            out_stick[i] = (fnd.stick_radius(stick_ch["m"], getattr(st, stick_ch["L"]), fnd.bl, a)
                            if stick_ch is not None else a)
        state["done"] = i + 1

    def block(i0, i1, values):
        if not state["keff_is_frac"]:
            frac = fnd.fraction(st.radius)
            for ch in chans:
                _set_keff(ch, frac)
            state["keff_is_frac"] = True
        sl = slice(i0, i1)
        Wblock = np.zeros(i1 - i0)
        for ch, v in zip(chans, values):
            m = ch["m"]
            L = getattr(st, ch["L"])
            ref = ch["x"] if ch["ctrl"] == ch["pos"] else float(m.sum())
            nzv = v[v != ref]
            sgn = ch["dir"] if nzv.size == 0 else (1.0 if nzv[0] > ref else -1.0)
            ch["dir"] = sgn
            want = want_stick and ch is stick_ch
            if ch["ctrl"] == ch["pos"]:
                out = monotone_block(m, ch["Keff"], L, fnd.bl, st.radius, sgn, du=sgn * (v - ref),
                                     want_stick=want)
                ch["out_pos"][sl] = v
                ch["x"] = float(v[-1])
            else:
                out = monotone_block(m, ch["Keff"], L, fnd.bl, st.radius, sgn, target=v,
                                     want_stick=want)
                ch["out_pos"][sl] = ch["x"] + sgn * out["x"]
                ch["x"] = float(ch["out_pos"][i1 - 1])
                out_gross[sl] |= out["gross"]
            ch["out_frc"][sl] = out["force"]
            Wblock += out["dissipation"]
            if want:
                out_stick[sl] = out["stick"]
        out_W[sl] = state["W"] + Wblock
        state["W"] += float(Wblock[-1])
        if want_stick and stick_ch is None:
            out_stick[sl] = st.radius
        state["done"] = i1

    base = 0
    for leaf, nrm in zip(path.leaves(), normal):
        if base:
            cur["depth"], cur["force"] = float(res["depth"][base - 1]), float(res["force"][base - 1])
        # the spring families' controls only (the normal solve read the others)
        _, vals = leaf.values_of(cur, loop_controls, time=False)
        nsteps = leaf.n_steps
        d_arr, a_arr = nrm["depth"], nrm["radius"]
        d0, a0 = st.depth, st.radius
        changed = np.empty(nsteps, bool)
        changed[0] = d_arr[0] != d0 or a_arr[0] != a0 or state["first"]
        np.not_equal(d_arr[1:], d_arr[:-1], out=changed[1:])
        changed[1:] |= a_arr[1:] != a_arr[:-1]
        breaks = [np.array([0, nsteps])]
        vs = []
        for ch in chans:
            pos, frc = ch["pos"], ch["frc"]
            if pos in vals or frc in vals:
                ch["ctrl"] = pos if pos in vals else frc
                v = vals[ch["ctrl"]]
                if ch["ctrl"] == pos:   # a prescribed position is its own series: the loop
                    # reads the targets from it (writeable, unlike a table's own columns,
                    # which the compiled run would take as another argument type)
                    out = ch["out_pos"][base:base + nsteps]
                    out[:] = v
                    v = out
            else:
                v = np.full(nsteps, cur[ch["ctrl"]])
            vs.append(v)
            breaks.append(_turns(cur[ch["ctrl"]], v))
        del vals
        # runs of steps whose normal state changes are run step by step: their ends are breaks
        all_changed = bool(changed.all())   # e.g. a gait: no run edges, no gather
        breaks += [np.array([0, nsteps]) if all_changed else _run_edges(changed),
                   snap_idx - base + 1]
        brk = np.unique(np.concatenate(breaks))
        del breaks
        brk = brk[(brk >= 0) & (brk <= nsteps)].tolist()
        fusing = fused is not None and chans[0]["ctrl"] == chans[0]["pos"]
        tor_edge = bool(chans) and chans[0]["L"] == "L_tor"

        def edges(c0, c1):
            """Edge cell data of steps c0..c1-1, computed where the normal state changes
            (zeros elsewhere: step() does not read them there)."""
            if all_changed or changed[c0:c1].all():    # no gather and scatter
                edc = fnd.edge_data(d_arr[c0:c1], a_arr[c0:c1])
                return edc["k"], edc["S"], edc.get("T")
            ci = np.flatnonzero(changed[c0:c1])
            ek, eS = np.zeros(c1 - c0, np.int64), np.zeros(c1 - c0)
            eT = np.zeros(c1 - c0) if "torsion" in fnd.needs else None
            if ci.size:
                edc = fnd.edge_data(d_arr[c0:c1][ci], a_arr[c0:c1][ci])
                ek[ci], eS[ci] = edc["k"], edc["S"]
                if eT is not None:
                    eT[ci] = edc["T"]
            return ek, eS, eT

        def one_by_one(j0, j1):
            for c0 in range(j0, j1, _CHUNK):   # plain floats, converted a chunk at a time
                c1 = min(c0 + _CHUNK, j1)
                dl, al = d_arr[c0:c1].tolist(), a_arr[c0:c1].tolist()
                ek, eS, eT = edges(c0, c1)
                ek, eS = ek.tolist(), eS.tolist()
                eT = eT.tolist() if eT is not None else [None] * (c1 - c0)
                vl = [v[c0:c1].tolist() for v in vs]
                for o in range(c1 - c0):
                    step(base + c0 + o, dl[o], al[o], ek[o], eS[o], eT[o], [v[o] for v in vl])

        def steps(j0, j1):
            if not fusing:
                one_by_one(j0, j1)
                return
            for c0 in range(j0, j1, _FUSED_WINDOW):   # edge data a window at a time
                c1 = min(c0 + _FUSED_WINDOW, j1)
                prev = d_arr[c0 - 1] if c0 > 0 else d0
                # steps whose depth equals the one before (run step by step)
                same = np.flatnonzero(d_arr[c0 + 1:c1] == d_arr[c0:c1 - 1])
                same += 1
                if d_arr[c0] == prev:
                    same = np.concatenate(([0], same))
                ek, eS, eT = edges(c0, c1)
                eT = eT if tor_edge else eS
                j = 0
                while j < c1 - c0:   # runs of steps with a new depth each: one compiled call
                    r = _next(same, j - 1, c1 - c0)
                    if r > j:
                        _fused_run(fused, fnd, st, chans[0], base + c0 + j, d_arr[c0 + j:c0 + r],
                                   a_arr[c0 + j:c0 + r], ek[j:r], eS[j:r], eT[j:r],
                                   vs[0][c0 + j:c0 + r], state, out_W,
                                   out_stick if want_stick else None)
                        state["done"] = base + c0 + r
                        j = r
                    else:
                        one_by_one(c0 + j, c0 + j + 1)
                        j += 1

        pending = None   # first step of a stretch of step-by-step intervals not yet run
        for j0, j1 in zip(brk[:-1], brk[1:]):
            if strategy == "segments" and j1 - j0 >= _MIN_BLOCK and not changed[j0]:
                if pending is not None:
                    steps(pending, j0)
                    pending = None
                block(base + j0, base + j1, [v[j0:j1] for v in vs])
            elif pending is None:
                pending = j0
            if base + j1 - 1 in snaps:
                if pending is not None:
                    steps(pending, j1)
                    pending = None
                snapshot_data[base + j1 - 1] = _snapshot(contact, fnd, st, res, base + j1 - 1)
        if pending is not None:
            steps(pending, nsteps)
        base += nsteps
        for ch in chans:
            cur[ch["pos"]], cur[ch["frc"]] = ch["out_pos"][base - 1], ch["out_frc"][base - 1]
        if bar is not None:
            bar.update(nsteps)
    if bar is not None:
        bar.close()
