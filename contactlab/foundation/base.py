"""Abstract :class:`Foundation`: the 1D MDR foundation discretised into cells (springs).

To implement a subclass
-----------------------
1. Required: ``_build(self)`` (precompute per-cell constants from ``self.boundaries``) and
   ``new_state(self)`` (fresh state arrays for one solver run).
2. To run load paths (an entry of ``contactlab.effects.path.METHODS``): :meth:`run` (the time
   loop, returning :class:`PathArrays`), :meth:`check_path` (the options and the memory budget),
   ``ESTIMATED`` and :meth:`coarser` (the error estimate); :meth:`for_path` and :meth:`writes`
   when the defaults do not fit (see :class:`~contactlab.foundation.Winkler` and
   :class:`~contactlab.foundation.rings.Rings`).
3. Free: :meth:`for_path` (spacing from the path's maximum contact radius), :attr:`positions`,
   :attr:`widths`, :attr:`built` (which spring families exist), :func:`run_path` (checks, the
   normal problem of every step, ``for_path``, ``run``).

A foundation object is immutable geometry plus material constants; spring *state* arrays belong
to a solver run (``new_state()``), so one foundation can serve several runs. A run takes the
profile, moduli, friction and tolerance, never a ``Contact``.
"""
from __future__ import annotations

from abc import ABC, abstractmethod
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..errors import (ContactlabError, OutsideTheoryError, ParameterError, UnknownNameError,
                      failed_part_way)
from ..numeric.prefix import solved_prefix
from ..params import as_float_array
from ..physics import normal as _normal

__all__ = ["Foundation", "DEFAULT_N_SPRINGS", "SPACINGS", "SERIES", "NORMAL_SERIES", "PathArrays",
           "cell_boundaries", "families_needed", "path_normal_states", "iter_path_normal_states",
           "path_normal_series", "series_block", "PathNormal", "run_path"]

#: default number of springs (cells) over the path's maximum contact radius. The error is second
#: order in 1/N (only the cell holding a stick–slip boundary is lumped); with the edge-refined
#: spacing 2000 cells reproduce the Cattaneo–Mindlin/Mindlin–Deresiewicz loops of Hertz and cone
#: contacts to 2e-7 and 3.4e-7 of the loop amplitude and the MDR torsion loop to 6e-7, a factor
#: 3 below the 1e-6 target (1000 cells: 4e-7, 9.7e-7, 2.8e-6); see
#: benchmarks/foundation_accuracy.py. The time loop costs O(log N) per step while the normal load
#: is held and O(N) per step while it changes.
DEFAULT_N_SPRINGS = 2000
#: available spacings: "uniform" (equal cells) and "edge" (cells shrinking quadratically towards
#: the maximum contact radius, where the stick–slip boundary starts)
SPACINGS = ("uniform", "edge")
FAMILIES = ("normal", "tangential", "torsion")
#: per-step series of a foundation run (:class:`PathArrays`, :class:`contactlab.PathResult`)
SERIES = ("time", "depth", "force", "radius", "displacement", "tangential_force", "twist",
          "torque", "stick_radius", "dissipated_energy", "gross_sliding")
#: the series of the normal problem, solved for every step before a run
NORMAL_SERIES = ("time", "depth", "force", "radius")
#: steps of a leaf's normal solve at a time (bounded solver temporaries on long paths)
SOLVE_CHUNK = 1 << 16


@dataclass(eq=False)
class PathArrays:
    """The arrays of a foundation run along a load path (:meth:`Foundation.run`).

    A failed run raises its error with the arrays of the steps before it as ``err.partial``
    (``done`` steps complete; ``time``: the time of the failing step where the series do not
    hold it).

    Attributes
    ----------
    series : dict of ndarray
        Per-step series (:data:`SERIES`), SI units.
    snapshots : dict
        ``{step: {name: value}}`` states at the requested steps.
    meta : dict
        What the run built and how (discretisation, counts, energies).
    done : int
        Steps complete.
    time : float or None
    """

    series: dict
    snapshots: dict = field(default_factory=dict)
    meta: dict = field(default_factory=dict)
    done: int = 0
    time: float | None = None


def series_block(n: int, keys: list) -> dict[str, np.ndarray]:
    """Float series of ``n`` steps for ``keys``, the rows of one ``(len(keys), n)`` block.

    Each row must be written at every step before it is read (the normal series by the solve,
    a run's by its time loop). One allocation instead of one per series: the operating system
    backs a long block by whole huge pages (a 10^6-step gait run: ~3 300 page faults instead of
    ~7 200, ~9 ns per step less of system time on a 2-core VM), and the rows are the returned
    series only, so that a series computed but not asked for is freed on return.
    """
    if not keys:
        return {}
    block = np.empty((len(keys), n))
    return dict(zip(keys, block))


@dataclass(eq=False)
class PathNormal:
    """The normal problem of every step of a load path (:func:`path_normal_series`).

    Attributes
    ----------
    series : dict of ndarray
        ``time`` (s), ``depth`` (m), ``force`` (N), ``radius`` (m) per step, and the rows
        allocated for the run (written by it).
    leaves : list of dict
        Per leaf segment: ``depth`` and ``radius``, views of the series.
    """

    series: dict
    leaves: list

    @property
    def max_radius(self) -> float:
        """The largest contact radius of the path, m."""
        return float(np.max(self.series["radius"], initial=0.0))


def path_normal_series(profile: Any, E_star: float, path: Any, rtol: float,
                       rows: Any = ()) -> PathNormal:
    """The normal series of every step of ``path`` (:data:`NORMAL_SERIES`) and each leaf's
    normal state.

    The states go straight into the series, one leaf at a time (no second copy of the path's
    normal arrays); ``rows`` are the series allocated as rows of one block
    (:func:`series_block`): the normal ones among them are filled here, the others left for the
    run to write at every step.

    Returns
    -------
    PathNormal

    Raises
    ------
    ContactlabError
        The normal solve of a step failed: ``err.partial`` is the :class:`PathArrays` of the
        normal series of the steps before it (``done``, ``time`` of the failing step).
    """
    n_total = path.n_steps
    res = series_block(n_total, list(rows))
    for k in NORMAL_SERIES:
        if k not in res:        # read by the run, not returned: its own array
            res[k] = np.empty(n_total)
    t0 = 0.0
    i0 = 0
    leaves = []
    try:
        for seg in iter_path_normal_states(profile, E_star, path, rtol, chunk=SOLVE_CHUNK,
                                           out=res):
            n = seg["depth"].size      # depth, force, radius: written into res by the solve
            res["time"][i0:i0 + n] = t0 + seg["dt"]
            del seg
            leaves.append({k: res[k][i0:i0 + n] for k in ("depth", "radius")})
            t0 = float(res["time"][i0 + n - 1]) if n else t0
            i0 += n
    except ContactlabError as err:
        pre = err.partial if isinstance(err.partial, dict) else None
        done = i0 + (pre["depth"].size if pre is not None else 0)
        if pre is not None:
            res["time"][i0:done] = t0 + pre["dt"]
            for name in ("depth", "force", "radius"):
                res[name][i0:done] = pre[name]
        err.partial = PathArrays({name: res[name] for name in NORMAL_SERIES}, done=done,
                                 time=t0 + (err.failed_at or {}).get("dt", 0.0))
        raise
    return PathNormal(res, leaves)


def run_path(cls: Any, profile: Any, moduli: Any, friction: float | None, path: Any,
             rtol: float, *, outputs: Any = SERIES, snapshots: Any = (), progress: Any = None,
             on_normal: Any = None, **options: Any) -> PathArrays:
    """Run ``path`` through the foundation class ``cls``: its checks
    (:meth:`Foundation.check_path`), the normal problem of every step
    (:func:`path_normal_series`), the foundation the path needs (:meth:`Foundation.for_path`)
    and its time loop (:meth:`Foundation.run`).

    Parameters
    ----------
    cls : type
        A :class:`Foundation` subclass (``contactlab.effects.path.METHODS``).
    profile, moduli, friction, rtol
        The contact's parts (``friction=None``: no slip limit).
    path : LoadPath
    outputs : tuple of str
        The series the caller keeps (:data:`SERIES`).
    snapshots : set of int
        Steps (valid indices) whose state is stored.
    progress : callable, optional
        ``progress(n)`` after ``n`` more steps.
    on_normal : callable, optional
        ``on_normal(max_radius)`` once the normal problem is solved, before the time loop.
    **options
        The discretisation of ``cls`` (see its :meth:`~Foundation.check_path`).

    Raises
    ------
    ContactlabError
        A failed step: ``err.partial`` is the :class:`PathArrays` of the steps before it.
    """
    outputs = tuple(outputs)
    options = cls.check_path(path, snapshots, **options)
    writes = cls.writes(path, outputs, **options)
    normal = path_normal_series(profile, moduli.normal, path, rtol,
                                [k for k in SERIES if k in outputs and (k in NORMAL_SERIES
                                                                         or k in writes)])
    if on_normal is not None:
        on_normal(normal.max_radius)
    fnd = cls.for_path(profile, moduli, friction, path, normal=normal, rtol=rtol, **options)
    return fnd.run(path.leaves(), normal, outputs, snapshots, progress=progress)


def cell_boundaries(radius: float, n_springs: int, spacing: str) -> np.ndarray:
    """Cell boundaries ``0 = b_0 < ... < b_N = radius``, m.

    ``"uniform"``: ``b_j = radius j/N``. ``"edge"``: ``b_j = radius (1 - (1 - j/N)²)``; the cell at
    distance ``s`` from the edge has width ``~2 sqrt(s radius)/N``, so the error of the one cell
    that holds a stick–slip boundary is a fixed fraction ``~1/(4N²)`` of the local force.
    """
    s = np.linspace(0.0, 1.0, n_springs + 1)
    if spacing == "uniform":
        b = radius * s
    else:
        b = radius * (1.0 - (1.0 - s) ** 2)
    b[-1] = radius
    return b


def families_needed(path: Any, *, approximate: bool = False) -> tuple[str, ...]:
    """Spring families a path needs besides the normal springs.

    Raises
    ------
    OutsideTheoryError
        The path drives both a tangential shift and a twist, without ``approximate=True``.
    """
    groups = path.groups
    needs = tuple(g for g in ("tangential", "torsion") if g in groups)
    if len(needs) == 2 and not approximate:
        raise OutsideTheoryError(
            "the path drives both a tangential shift (displacement/tangential_force) and a twist "
            "(twist/torque): combined shift and twist is outside the MDR theory (the slip "
            "conditions couple). Pass approximate=True to run the two as independent spring "
            "families, each with the full friction limit (an explicit approximation).")
    return needs


def path_normal_states(profile: Any, E_star: float, path: Any, rtol: float
                       ) -> list[dict[str, np.ndarray]]:
    """Normal state of every step of a load path, per leaf segment.

    Exact and vectorised per segment: non-adhesive normal contact is path independent, so each
    step is the normal solution of its depth or force (:func:`contactlab.physics.normal.solve`);
    a segment that controls neither holds the last state.

    Returns
    -------
    list of dict
        Per leaf: ``dt`` (s), ``depth`` (m), ``radius`` (m), ``force`` (N), one value per step.
    """
    return list(iter_path_normal_states(profile, E_star, path, rtol))


def iter_path_normal_states(profile: Any, E_star: float, path: Any, rtol: float,
                            chunk: int | None = None, out: dict | None = None):
    """:func:`path_normal_states` one leaf at a time (a caller that copies each leaf into its own
    series holds one leaf's arrays, not the whole path's); ``chunk``: leaves longer than this
    many steps are solved a chunk of steps at a time (bounded solver temporaries; the same
    result for the same ``chunk``). ``out``: arrays ``"depth"``, ``"radius"``, ``"force"`` of
    the path's length; the states are then written into them and each leaf's ``depth``,
    ``radius``, ``force`` are views of them (no per-leaf arrays and copies: ~3 fresh 8 MB
    arrays per 10^6 steps)."""
    cur = dict.fromkeys(("depth", "force", "displacement", "tangential_force", "twist",
                         "torque"), 0.0)
    last = (np.zeros(1), np.zeros(1), np.zeros(1))
    i0 = 0
    for li, leaf in enumerate(path.leaves()):
        # the normal controls only (the time loop computes the others), read only here
        dt, vals = leaf.values_of(cur, ("depth", "force"))
        n = leaf.n_steps
        if "depth" in vals or "force" in vals:
            kind = "depth" if "depth" in vals else "force"
            x = as_float_array(kind, vals[kind])
            if kind == "force" and np.any(x < 0):
                bad = x[x < 0][0]
                raise ParameterError(f"force={bad!r} N is invalid: it is below the adhesion limit "
                                     "0 N of this non-adhesive contact (use force >= 0, or a "
                                     "negative depth to separate the bodies).")
            c0 = 0
            try:
                if out is None and (chunk is None or x.size <= chunk):
                    d, a, F, _ = _normal.solve(profile, E_star, kind, x, rtol,
                                               error_estimate=False)
                else:   # long leaf: solve a chunk at a time (bounded solver temporaries)
                    x = x.reshape(-1)
                    d, a, F = ((np.empty(x.size), np.empty(x.size), np.empty(x.size))
                               if out is None else _views(out, i0, n))
                    per = x.size if chunk is None else chunk
                    for c0 in range(0, x.size, per):
                        sl = slice(c0, c0 + per)
                        d[sl], a[sl], F[sl] = (np.asarray(v, float).reshape(-1) for v in
                                               _normal.solve(profile, E_star, kind, x[sl], rtol,
                                                             error_estimate=False)[:3])
            except ContactlabError as err:
                raise _normal_failure(err, profile, E_star, kind, x, rtol, c0, chunk, dt,
                                      None if c0 == 0 else (d, a, F), i0, li) from None
            del x
        elif out is None:
            d, a, F = (np.full(n, v[-1]) for v in last)
        else:
            d, a, F = _views(out, i0, n)
            for dst, v in zip((d, a, F), last):
                dst.fill(v[-1])
        del vals
        d, a, F = (np.asarray(v, float).reshape(n) for v in (d, a, F))
        last = (d[-1:].copy(), a[-1:].copy(), F[-1:].copy())  # not views: a leaf is freed
        cur["depth"], cur["force"] = float(d[-1]), float(F[-1])
        i0 += n
        yield {"dt": dt, "depth": d, "radius": a, "force": F}


def _views(out: dict, i0: int, n: int) -> tuple:
    """Steps ``i0 .. i0 + n - 1`` of the caller's depth, radius and force arrays."""
    return tuple(out[k][i0:i0 + n] for k in ("depth", "radius", "force"))


def _normal_failure(err, profile, E_star, kind, x, rtol, c0, chunk, dt, done, i0, leaf):
    """The normal solve of a leaf failed (in the chunk starting at ``c0``): find the first
    failing step by bisection over prefixes of that chunk and attach the leaf's solved prefix
    (``dt``, ``depth``, ``radius``, ``force``) as ``err.partial``, the step as ``err.failed_at``."""
    x = np.asarray(x, float).reshape(-1)
    n = x.size - c0 if chunk is None else min(chunk, x.size - c0)

    def solve(m):
        return [np.asarray(v, float).reshape(-1)
                for v in _normal.solve(profile, E_star, kind, x[c0:c0 + m], rtol,
                                       error_estimate=False)[:3]]

    m, got = solved_prefix(solve, n)
    cols = [np.concatenate((done[j][:c0] if done is not None else np.zeros(0),
                            got[j] if got is not None else np.zeros(0))) for j in range(3)]
    k = c0 + m
    dts = np.broadcast_to(np.asarray(dt, float), x.shape)
    pre = {"dt": dts[:k].copy(), "depth": cols[0], "radius": cols[1], "force": cols[2]}
    return failed_part_way(err, f"the normal solve failed at step {i0 + k} ({kind} "
                           f"{x[k]:.6g})", pre, step=i0 + k, leaf=leaf, dt=float(dts[k]))


class Foundation(ABC):
    """A 1D MDR foundation over ``0 <= x <= radius`` (both sides ±x are lumped in each cell).

    Parameters
    ----------
    profile : Profile
    moduli : EffectiveModuli
        ``.normal`` E*, ``.tangential`` G*, ``.torsional`` G_t (Pa).
    friction : float or None
        Coulomb μ; ``None`` means no slip.
    radius : float
        Largest contact radius the foundation must cover, m.
    n_springs : int, optional
        Number of cells (default :data:`DEFAULT_N_SPRINGS`).
    spacing : {"edge", "uniform"}
    needs : iterable of {"tangential", "torsion"}
        Spring families to build besides the normal springs.
    rtol : float
        Tolerance of profile quadratures.
    """

    def __init__(self, profile: Any, moduli: Any, friction: float | None, radius: float, *,
                 n_springs: int | None = None, spacing: str = "edge", needs: Any = (),
                 rtol: float = 1e-10) -> None:
        n = DEFAULT_N_SPRINGS if n_springs is None else n_springs
        if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 1:
            raise ParameterError(f"n_springs={n_springs!r} is invalid: it must be an integer >= 1.")
        if spacing not in SPACINGS:
            raise UnknownNameError(f"spacing={spacing!r} is invalid: allowed are {SPACINGS}.")
        if not (np.isfinite(radius) and radius > 0):
            raise ParameterError(f"radius={radius!r} m is invalid: the foundation needs a finite "
                                 "maximum contact radius > 0 (does the path load the contact?).")
        needs = tuple(sorted(set(needs)))
        for fam in needs:
            if fam not in FAMILIES[1:]:
                raise UnknownNameError(f"needs contains {fam!r}: allowed are {FAMILIES[1:]}.")
        self.profile = profile
        self.moduli = moduli
        self.friction = friction
        self.radius = float(radius)
        self.n_springs = int(n)
        self.spacing = spacing
        self.needs = needs
        self.rtol = rtol
        self.boundaries = cell_boundaries(self.radius, self.n_springs, spacing)
        self._build()

    #: series whose discretisation error an error estimate reports (:meth:`coarser`)
    ESTIMATED: tuple[str, ...] = ()

    @classmethod
    def check_path(cls, path: Any, snapshots: Any = (), *, n_springs: int | None = None,
                   spacing: str = "edge", approximate: bool = False) -> dict[str, Any]:
        """Check the discretisation options of a run along ``path`` (and its memory, before
        anything is allocated); returns them completed with their defaults.

        Raises
        ------
        ParameterError, UnknownNameError, OutsideTheoryError, MemoryBudgetError
        """
        from ..params import check_count
        n = DEFAULT_N_SPRINGS if n_springs is None else check_count("n_springs", n_springs)
        if spacing not in SPACINGS:
            raise UnknownNameError(f"spacing={spacing!r} is invalid: allowed are {SPACINGS}.")
        families_needed(path, approximate=approximate)
        return {"n_springs": n, "spacing": spacing, "approximate": approximate}

    @classmethod
    def writes(cls, path: Any, outputs: Any, **options: Any) -> tuple[str, ...]:
        """The series a run along ``path`` writes at every step (allocated without a zero fill,
        as rows of one block with the normal series)."""
        return ()

    @classmethod
    def coarser(cls, options: dict, meta: dict) -> dict | None:
        """The options of the coarser run an error estimate compares with (``None``: none)."""
        return None

    @classmethod
    def for_path(cls, profile: Any, moduli: Any, friction: float | None, path: Any, *,
                 normal: PathNormal | None = None, n_springs: int | None = None,
                 spacing: str = "edge", rtol: float = 1e-10, approximate: bool = False,
                 **options: Any) -> "Foundation":
        """Build the foundation a load path needs.

        The cells cover the largest contact radius the path reaches (a normal-only pass over the
        path, exact because non-adhesive normal contact is path independent; ``normal``: that
        pass done already, :func:`path_normal_series`); only the spring families the path
        controls are built (no torsional springs without twist/torque). ``moduli`` (E*, G*,
        G_t) is needed besides the profile because a force-controlled path reaches its radius
        through E*. Called on :class:`Foundation` it builds a
        :class:`~contactlab.foundation.Winkler`. ``options``: those of the subclass
        (:meth:`check_path`).

        Examples
        --------
        >>> import contactlab as cl
        >>> from contactlab.foundation import Foundation
        >>> c = cl.Contact(cl.profiles.Paraboloid(R=0.01), materials=(cl.Elastic(E=210e9, nu=0.3),
        ...                cl.Rigid()), friction=0.3)
        >>> f = Foundation.for_path(c.profile, c.moduli, 0.3,
        ...                         cl.LoadPath().ramp(force=10.0, steps=5), n_springs=100)
        >>> f.built
        ['normal']
        """
        if cls is Foundation:
            from .winkler import Winkler
            return Winkler.for_path(profile, moduli, friction, path, normal=normal,
                                    n_springs=n_springs, spacing=spacing, rtol=rtol,
                                    approximate=approximate, **options)
        needs = families_needed(path, approximate=approximate)
        if normal is None:
            normal = path_normal_series(profile, moduli.normal, path, rtol)
        return cls(profile, moduli, friction, normal.max_radius, n_springs=n_springs,
                   spacing=spacing, needs=needs, rtol=rtol, **options)

    def run(self, leaves: Any, normal: PathNormal, outputs: Any, snapshots: Any,
            progress: Any = None) -> PathArrays:
        """Run the load path's steps (its leaf segments ``leaves``, their normal problem
        ``normal``) through the foundation: the per-step series (``outputs`` at least), the
        states at the steps ``snapshots`` and the meta data. ``progress(n)`` is called after
        ``n`` more steps.

        Raises
        ------
        ContactlabError
            A failed step, with ``err.partial`` the :class:`PathArrays` of the steps before it.
        NotSupportedError
            A foundation without a time loop.
        """
        from ..errors import NotSupportedError
        raise NotSupportedError(f"{type(self).__name__} has no time loop along a load path.")

    @property
    def built(self) -> list[str]:
        """Spring families that exist: always ``"normal"``, plus the path's needs."""
        return ["normal", *self.needs]

    @property
    def positions(self) -> np.ndarray:
        """Cell midpoints, m."""
        b = self.boundaries
        return 0.5 * (b[1:] + b[:-1])

    @property
    def widths(self) -> np.ndarray:
        """Cell widths Δx, m."""
        return np.diff(self.boundaries)

    @abstractmethod
    def _build(self) -> None:
        """Precompute per-cell constants."""

    @abstractmethod
    def new_state(self) -> Any:
        """Fresh spring state for one run."""

    def __repr__(self) -> str:
        return (f"{type(self).__name__}(radius={self.radius!r}, n_springs={self.n_springs}, "
                f"spacing={self.spacing!r}, built={self.built})")
