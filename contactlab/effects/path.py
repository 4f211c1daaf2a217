"""Load paths through a discretised foundation: the driver behind :meth:`Contact.simulate` and
its result :class:`PathResult`.

The driver validates the call, picks the foundation of the method (:data:`METHODS`, resolved by
:func:`resolve_path_method`, which the scene planner calls too), runs it
(:func:`contactlab.foundation.base.run_path`: the normal problem of every step, then the
foundation's own time loop) and wraps its arrays in a :class:`PathResult`. The time loops live
with their foundations: the MDR springs in :mod:`contactlab.foundation.winkler_path`, the exact
ring solver in :mod:`contactlab.foundation.rings`.
"""
from __future__ import annotations

import warnings
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..citations import Cited
from ..errors import (ContactlabError, EffectNotPlannedError, NotSupportedError, ParameterError,
                      UnknownNameError, ValidityWarning, failed_part_way)
from ..foundation.base import (SERIES, SPACINGS, PathArrays, path_normal_states, run_path)
from ..foundation.base import Foundation
from ..foundation.rings import Rings
from ..foundation.winkler import Winkler
from ..foundation.winkler_path import memory as _spring_memory
from ..loadpath import LoadPath
from ..loadpath.base import UNITS
from ..params import check_flag, name_list, step_indices
from ..physics import fretting as _fr
from ..physics.torsion import MDR_VALID_STICK_RATIO
from ..physics.torsion_validity import affordable_states
from ._protocol import Result, reporting

__all__ = ["PathResult", "simulate", "SERIES", "PROGRESS_THRESHOLD", "compile_normal",
           "simulate_memory", "METHODS", "PATH_METHODS", "resolve_path_method", "METHOD_ARGUMENTS",
           "partial_path_failure", "mdr_path_validity", "warn_mdr_path", "force_variation",
           "MDR_PATH_STICK_RATIOS", "MDR_PATH_HELD_FORCE"]

#: the foundation of each method of :func:`simulate` (``method=``): a
#: :class:`~contactlab.foundation.Foundation` subclass whose ``for_path`` and ``run`` take the load
#: path (its options: the method's :data:`METHOD_ARGUMENTS`)
METHODS: dict[str, type[Foundation]] = {"mdr": Winkler, "exact": Rings}
#: torsion models of :func:`simulate` (``method=``)
PATH_METHODS = tuple(sorted(METHODS))
#: arguments of :func:`simulate` that only one method reads (its discretisation)
METHOD_ARGUMENTS = {"mdr": ("n_springs", "spacing", "strategy"),
                    "exact": ("n_rings", "torque_rtol")}


def simulate_memory(n_steps: int, n_springs: int, n_snapshots: int = 0) -> float:
    """Estimated peak memory of :func:`simulate` on the MDR springs, bytes (checked against the
    memory budget before anything is allocated; see :func:`contactlab.set_memory_budget`)."""
    return _spring_memory(n_steps, n_springs, n_snapshots)


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

    def stress(self, a: Any, b: Any, c: Any = None, *, step: int, body: int = 1,
               part: str = "total") -> Any:
        """Subsurface stress field at snapshot ``step``, Pa.

        The normal part is the exact field of the step's normal state; the frictional parts are
        the fields of the step's own surface tractions (``snapshots[step]["shear_torsion"]``:
        a superposition of twisted flat punches; ``snapshots[step]["shear_tangential"]``: a
        superposition of punch-type shear tractions along ``+x``), as exact as those tractions
        (:mod:`contactlab.effects.stress_path`). ``part="friction"`` gives the frictional parts
        alone.

        Parameters
        ----------
        a, b, c : array_like
            Points, m: ``(r, z)`` (radius and depth) for a path without shift, or
            ``(x, y, z)`` (``x`` along the shift, ``z >= 0`` the depth) for any path (needed
            for a path with a shift).
        step : int
            A step with a snapshot (negative: counted from the end).
        body : int
            1 or 2 (the body's Poisson ratio; body 2 receives the opposite tractions).
        part : str
            ``"total"`` or ``"friction"``.

        Returns
        -------
        StressField or CartesianStressField
            Cylindrical components at ``(r, z)`` as :meth:`TorsionState.stress`, or Cartesian
            components at ``(x, y, z)`` as :meth:`TangentialState.stress` (``meta["step"]``,
            ``meta["error_estimate"]``).

        Raises
        ------
        EffectNotPlannedError
            ``step`` has no snapshot.
        NotSupportedError
            A shift whose traction sticks at the contact edge with friction on a profile that
            rises to a wall (below the slip limit there), where it is singular; a plain flat
            punch is covered (its traction keeps the punch's shape at every step). Without
            friction the tractions are rebuilt from the path's series instead (rigid punches;
            :mod:`contactlab.effects.stress_path_noslip`).
        """
        from .stress_path import path_stress
        return path_stress(self, a, b, c, step=step, body=body, part=part)

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
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            ex = simulate(contact, path, outputs=tuple(series), method="exact",
                          n_rings=PATH_CHECK_RINGS)
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


@reporting(lambda res, notes, contact, path=None, *a, **k: res._assess(notes, contact, path))
def simulate(contact, path: LoadPath, *, outputs: Any = None, n_springs: int | None = None,
             spacing: str | None = None, snapshots: Any = None, progress: bool = False,
             approximate: bool = False, strategy: str | None = None,
             error_estimate: bool = False, method: str | None = None,
             n_rings: int | None = None, torque_rtol: float | None = None) -> PathResult:
    """Run ``path`` through the foundation of ``method`` (:data:`METHODS`).

    Parameters
    ----------
    contact : Contact
        Non-adhesive; ``friction=None`` means no slip.
    path : LoadPath
    outputs : iterable of str, optional
        Per-step series to keep (default all of :data:`SERIES`).
    n_springs : int, optional
        ``"mdr"``: cells over the path's largest contact radius (default
        :data:`~contactlab.foundation.DEFAULT_N_SPRINGS`).
    spacing : {"edge", "uniform"}
        ``"mdr"``: cell spacing (edge-refined by default).
    snapshots : iterable of int, optional
        Steps (0-based; negative counts from the end) at which the states are stored.
    progress : bool
        Show a tqdm progress bar for paths of at least :data:`PROGRESS_THRESHOLD` steps
        (library use is quiet by default).
    approximate : bool
        Allow combined shift and twist, run as independent spring families (warns).
    strategy : {"segments", "steps"}, optional
        ``"mdr"``: numerical route of the time loop, same results up to rounding.
        ``"segments"`` (default) advances runs of steps with a held normal load and a monotone
        control in closed form (sorted slip thresholds, ``O(log N)`` per step); ``"steps"``
        updates every spring at every step.
    error_estimate : bool
        See below.
    method : {"exact", "mdr"}, optional
        The torsion model of a path with twist or torque (default
        :data:`DEFAULT_TORSION_METHOD`; :func:`resolve_path_method`): ``"exact"`` (exact normal
        solution per step, exact half-space torsion on ``n_rings`` rings with Coulomb friction
        and memory, :class:`contactlab.foundation.rings.Rings`) or ``"mdr"`` (the MDR spring
        foundation :class:`contactlab.foundation.Winkler`, exact only while the slip annulus is
        narrow). Paths without twist always run through the MDR foundation (``"mdr"``).
    n_rings : int, optional
        ``"exact"``: rings over the path's largest contact radius (default
        :data:`contactlab.foundation.rings.DEFAULT_N_RINGS`).
    torque_rtol : float, optional
        ``"exact"``: the accuracy asked of the torque instead of a ring count: the rings are
        chosen from the measured error law of the ring solver
        (:func:`contactlab.foundation.rings.rings_for_rtol`) so that the largest torque error
        of the path stays below ``torque_rtol`` times its largest full-sliding torque
        ``2π μ ∫ p r² dr``; in ``[1e-5, 0.1]``, not together with ``n_rings``.

    Returns
    -------
    PathResult

    Notes
    -----
    The discretisation arguments belong to one method (:data:`METHOD_ARGUMENTS`): ``n_springs``,
    ``spacing`` and ``strategy`` to ``"mdr"``, ``n_rings`` and ``torque_rtol`` to ``"exact"``; given
    to the other method they raise :class:`~contactlab.errors.ParameterError` instead of being ignored.

    ``error_estimate=True`` runs the path a second time with half the springs (rings) and
    stores, in ``result.meta["error_estimates"]``, ``max|s_N - s_{N/2}| / max|s_N|`` for each
    series the foundation estimates (its ``ESTIMATED``: springs: tangential force, torque,
    stick radius, dissipated energy; rings: torque, twist, stick radius, dissipated energy).
    The spring error falls as 1/N², so this difference is about three times the error of the
    N-spring run; the ring error at least as ``N^-1``: a conservative estimate that costs about
    half a run more (issue 7; honesty tested in tests/unit/effects/test_path_error_estimate.py).

    A step that fails (a normal solve, a spring or ring step) raises its error with its type,
    the message naming the step (index, time, path segment); ``err.partial`` is the
    :class:`PathResult` of the steps before it (``meta["status"] == "partial"``; only the normal
    series when the normal solve failed, before the time loop) and ``err.failed_at`` the place.

    Raises
    ------
    OutsideTheoryError
        Combined shift and twist without ``approximate=True``.
    NotSupportedError
        Adhesive contacts; ``method="exact"`` on a path with a shift.

    Warns
    -----
    ValidityWarning
        A twisted path beyond the validity of the MDR torsion springs (:func:`warn_mdr_path`).
    """
    approximate = check_flag("approximate", approximate)
    error_estimate = check_flag("error_estimate", error_estimate)
    progress = check_flag("progress", progress)
    if spacing is not None and spacing not in SPACINGS:
        raise UnknownNameError(f"spacing={spacing!r} is invalid: allowed are {SPACINGS}.")
    if outputs is not None:
        outputs = name_list("outputs", outputs, SERIES)
    method = resolve_path_method(path, method, approximate)
    given = {"n_springs": n_springs, "spacing": spacing, "strategy": strategy,
             "n_rings": n_rings, "torque_rtol": torque_rtol}
    _check_method_arguments(method, **given)
    options = {name: given[name] for name in METHOD_ARGUMENTS[method]}
    options["approximate"] = approximate
    fnd = METHODS[method]
    res = _run(fnd, method, contact, path, outputs, snapshots, progress, options)
    if error_estimate:
        coarse_options = fnd.coarser(options, res.meta)
        if coarse_options is not None:
            half = _run(fnd, method, contact, path, outputs, None, False, coarse_options,
                        warn=False)
            est = {}
            for name in fnd.ESTIMATED:
                if name in res.data:
                    full, coarse = np.asarray(res.data[name]), np.asarray(half.data[name])
                    scale = float(np.max(np.abs(full), initial=0.0))
                    est[name] = (float(np.max(np.abs(full - coarse), initial=0.0)) / scale
                                 if scale else 0.0)
            res.meta["error_estimates"] = est
    return res


#: how an error message names the call of each method
_CALL = {"mdr": "simulate()", "exact": "simulate(method='exact')"}


def _run(fnd: Any, method: str, contact, path: LoadPath, outputs: Any, snapshots: Any,
         progress: bool, options: dict, warn: bool = True) -> PathResult:
    """One run of ``path`` on the foundation class ``fnd``
    (:func:`contactlab.foundation.base.run_path`) as a :class:`PathResult`; ``warn``: emit the
    :class:`ValidityWarning` of :func:`warn_mdr_path` (off for the coarser run of an error
    estimate); ``options``: the discretisation of ``fnd`` (its ``check_path``)."""
    if not isinstance(path, LoadPath):
        raise ParameterError(f"path={path!r} is invalid: expected a contactlab.LoadPath.")
    if contact.is_adhesive:
        raise NotSupportedError(f"{_CALL[method]} supports non-adhesive contacts only "
                                "(work_of_adhesion=None).")
    outputs = SERIES if outputs is None else tuple(outputs)
    n_total = path.n_steps
    if n_total == 0:
        raise ParameterError("path has no steps: add a segment, e.g. "
                             "LoadPath().ramp(force=1.0, steps=10).")
    snaps = step_indices("snapshots", snapshots, n_total)
    from .normal import warn_outside_validity

    def on_normal(a_max: float) -> None:
        warn_outside_validity(contact.profile, a_max, stacklevel=6)

    bar = _progress(n_total, progress)
    try:
        out = run_path(fnd, contact.profile, contact.moduli, contact.friction, path,
                       contact.rtol, outputs=outputs, snapshots=snaps,
                       progress=None if bar is None else bar.update, on_normal=on_normal,
                       **options)
    except ContactlabError as err:
        part = err.partial
        if not isinstance(part, PathArrays):
            raise
        outs = [o for o in outputs if o in part.series]
        raise partial_path_failure(err, path, part.series, outs, part.done,
                                   part.meta or {"method": method},
                                   _with_pressure(contact, part.snapshots), time=part.time
                                   ) from None
    finally:
        if bar is not None:
            bar.close()
    res = out.series
    if (warn and method == "mdr" and "torsion" in out.meta["built"]
            and contact.friction is not None):
        warn_mdr_path(contact, res["twist"], res["radius"], res["depth"], res["force"],
                      energy="dissipated_energy" in outputs, stacklevel=4)
    result = PathResult({k: res[k] for k in outputs}, _with_pressure(contact, out.snapshots),
                        out.meta)
    object.__setattr__(result, "_contact", contact)     # for stress(); not a result field
    return result


def _with_pressure(contact, snapshots: dict) -> dict:
    """The snapshots, each at cell midpoints ``x`` without a pressure given the exact 3D
    pressure of the step's normal state there (0 out of contact), Pa."""
    for snap in snapshots.values():
        if "x" in snap and "pressure" not in snap:
            x, d, a = snap["x"], snap["depth"], snap["radius"]
            snap["pressure"] = (np.asarray(contact.normal(depth=d).pressure(x), float) if a > 0
                                else np.zeros(x.size))
    return snapshots


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
