"""Abstract :class:`Foundation`: the 1D MDR foundation discretised into cells (springs).

To implement a subclass
-----------------------
1. Required: ``_build(self)`` (precompute per-cell constants from ``self.boundaries``),
   ``new_state(self)`` (fresh spring state arrays for one solver run), ``set_normal(...)``,
   ``step(...)`` and ``solve(...)`` (see :class:`~contactlab.foundation.Winkler`).
2. Optional: nothing else.
3. Free: :meth:`for_path` (spacing from the path's maximum contact radius), :attr:`positions`,
   :attr:`widths`, :attr:`built` (which spring families exist).

A foundation object is immutable geometry plus material constants; spring *state* arrays belong
to a solver run (``new_state()``), so one foundation can serve several runs.
"""
from __future__ import annotations

from abc import ABC, abstractmethod
from typing import Any

import numpy as np

from ..errors import (ContactlabError, OutsideTheoryError, ParameterError, UnknownNameError,
                      failed_part_way)
from ..numeric.prefix import solved_prefix
from ..params import as_float_array
from ..physics import normal as _normal

__all__ = ["Foundation", "DEFAULT_N_SPRINGS", "SPACINGS", "cell_boundaries", "families_needed",
           "path_normal_states", "iter_path_normal_states"]

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

    @classmethod
    def for_path(cls, profile: Any, path: Any, *, moduli: Any, friction: float | None = None,
                 n_springs: int | None = None, spacing: str = "edge", rtol: float = 1e-10,
                 approximate: bool = False) -> "Foundation":
        """Build the foundation a load path needs.

        The cells cover the largest contact radius the path reaches (a normal-only pass over the
        path, exact because non-adhesive normal contact is path independent); only the spring
        families the path controls are built (no torsional springs without twist/torque).
        ``moduli`` (E*, G*, G_t) is needed besides the profile because a force-controlled path
        reaches its radius through E*. Called on :class:`Foundation` it builds a
        :class:`~contactlab.foundation.Winkler`.

        Examples
        --------
        >>> import contactlab as cl
        >>> from contactlab.foundation import Foundation
        >>> c = cl.Contact(cl.profiles.Paraboloid(R=0.01), materials=(cl.Elastic(E=210e9, nu=0.3),
        ...                cl.Rigid()), friction=0.3)
        >>> f = Foundation.for_path(c.profile, cl.LoadPath().ramp(force=10.0, steps=5),
        ...                         moduli=c.moduli, friction=0.3, n_springs=100)
        >>> f.built
        ['normal']
        """
        from .winkler import Winkler
        impl = Winkler if cls is Foundation else cls
        needs = families_needed(path, approximate=approximate)
        normal = path_normal_states(profile, moduli.normal, path, rtol)
        radius = max(float(np.max(seg["radius"], initial=0.0)) for seg in normal)
        return impl(profile, moduli, friction, radius, n_springs=n_springs, spacing=spacing,
                    needs=needs, rtol=rtol)

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
