"""Adhesive (JKR) normal contact through the MDR: the Heß rule [Heß11; H1; PH] (theory §4).

The outermost springs of the 1D foundation detach when their elongation reaches the critical
value ``Δl(a) = sqrt(2π a Δγ / E*)``, so on the equilibrium curve

* ``d(a) = g(a) - Δl(a)``,
* ``F(a) = 2E* (a d(a) - ∫_0^a g dx) = F_nonadh(a) - sqrt(8π a³ E* Δγ)``,
* ``p(r)`` is the non-adhesive pressure plus the tensile edge term ``(E*/π)(d - g(a))/sqrt(a²-r²)``.

Everything about stability follows from one dimensionless function of the contact radius,

    φ(a) = a g'(a) / Δl(a):   dF/da = 2E* Δl (φ - 3/2),   dd/da = (Δl / a)(φ - 1/2).

An equilibrium is stable under force control where ``φ > 3/2`` and under displacement control
(fixed grips) where ``φ > 1/2``. The pull-off radii are the crossings ``φ = 3/2`` (force control,
minimum of ``F(a)``) and ``φ = 1/2`` (displacement control, minimum of ``d(a)``). The incremental
stiffness along the equilibrium curve is ``dF/dd = 2E* a (φ - 3/2)/(φ - 1/2)``.

Branch structure (found once per contact, :func:`branches`): ``φ`` is scanned on a logarithmic
grid of radii; the *stable branch* is the one connected to large contacts, i.e. it starts at the
largest upward crossing of ``φ = 3/2`` (force) or ``φ = 1/2`` (displacement). Below it lies the
*unstable branch*, down to the next crossing (or to ``a → 0``). A punch wall (flat punch) pins the
contact radius at the wall radius ``b``: there ``F = 2E*(b d - ∫_0^b g)`` and the contact holds
while ``d >= g(b) - Δl(b)`` (Kendall [K71]). A flat central part (truncated profiles) gives
``φ = 0`` inside it, so both pull-offs sit at its rim when ``g`` rises steeply there.

Profiles whose ``g`` grows no faster than ``sqrt(x)`` at large ``x`` (power laws with
``n <= 1/2``) have no stable branch at large radii and no interior minimum of ``F(a)``:
depth- and force-controlled states and pull-off raise
:class:`~contactlab.errors.OutsideTheoryError` (``radius=`` still works).

Pure kernels: profile, moduli and arrays in, arrays out. The drivers that build
:class:`~contactlab.effects.adhesion.AdhesiveNormalState` objects live in
:mod:`contactlab.effects.adhesion`.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import cast

import numpy as np

from ..errors import ConvergenceError, OutsideTheoryError, ParameterError
from ..numeric.roots import bracketed_root

__all__ = ["edge_elongation", "depth_of_radius", "force_of_radius", "g_prime", "phi",
           "Branches", "branches", "solve_depth", "solve_force", "check_branch", "BRANCHES"]

#: accepted values of ``branch=``
BRANCHES = ("stable", "unstable")

#: grid points per decade in the branch scan, and the scanned range below the upper bracket
_PER_DECADE = 24
_DECADES = 12


# ---------------------------------------------------------------------------- kernels
def edge_elongation(E_star: float, dgamma: float, a: np.ndarray) -> np.ndarray:
    """Critical spring elongation ``Δl(a) = sqrt(2π a Δγ/E*)``, m [Heß11]."""
    return np.sqrt(2.0 * np.pi * np.asarray(a, float) * dgamma / E_star)


def depth_of_radius(profile, E_star: float, dgamma: float, a: np.ndarray) -> np.ndarray:
    """JKR depth ``d(a) = g(a) - Δl(a)``, m (``d(0) = 0``)."""
    a = np.asarray(a, float)
    return np.where(a > 0, profile._g(a), 0.0) - edge_elongation(E_star, dgamma, a)


def force_of_radius(profile, E_star: float, dgamma: float, a: np.ndarray,
                    d: np.ndarray | None = None) -> np.ndarray:
    """``F = 2E*(a d - ∫_0^a g)``, N; ``d`` defaults to the JKR depth ``d(a)``."""
    a = np.asarray(a, float)
    if d is None:
        d = depth_of_radius(profile, E_star, dgamma, a)
    g_int = np.where(a > 0, profile._g_integral(a), 0.0)
    return np.where(a > 0, 2.0 * E_star * (a * d - g_int), 0.0)


def g_prime(profile, x: np.ndarray) -> np.ndarray:
    """``g'(x)`` for ``x > 0``: closed form, power terms, term sums, else 4th-order differences."""
    x = np.asarray(x, float)
    if profile._has("_g_prime_closed_form"):
        return profile._g_prime_closed_form(x)
    terms = profile.power_terms()
    if terms is not None:
        from ..symbolic.transform import kappa
        return sum(kappa(n) * c * n * x ** (n - 1.0) for c, n in terms) * np.ones_like(x)
    if profile.has("terms"):
        return cast(np.ndarray, sum(g_prime(t, x) for t in profile.terms))
    # central differences (error ~ h⁴ g⁽⁵⁾ + eps g/h ≈ 1e-12 relative for smooth g), with the
    # step shrunk so that the stencil never crosses a slope jump, flat rim or wall of the profile
    # (there g' jumps; the one-sided value on x's own side is the one wanted).
    h = 1e-4 * x
    ends = [c for c in (profile.wall_radius, profile.max_radius) if 0 < c < np.inf]
    cuts = [c for c in (*profile.breakpoints, profile.flat_radius) if 0 < c < np.inf] + ends
    for c in cuts:
        dist = np.abs(x - c)
        h = np.where(dist > 0, np.minimum(h, 0.45 * dist), h)
    h = np.maximum(h, 1e-9 * x)
    backward = np.zeros(x.shape, bool)
    forward = np.zeros(x.shape, bool)
    for c in cuts:
        near = np.abs(x - c) <= 2 * h
        below = (x < c) | (c in ends)          # never evaluate beyond a wall / the domain
        backward |= near & below
        forward |= near & ~below
    forward &= ~backward
    with np.errstate(invalid="ignore"):
        val = (-profile._g(x + 2 * h) + 8 * profile._g(x + h)
               - 8 * profile._g(np.maximum(x - h, 0.0)) + profile._g(np.maximum(x - 2 * h, 0.0))
               ) / (12 * h) if not np.any(backward | forward) else np.zeros(x.shape)
        mid = ~(backward | forward)
        if np.any(backward | forward):
            xm, hm = x[mid], h[mid]
            val[mid] = (-profile._g(xm + 2 * hm) + 8 * profile._g(xm + hm)
                        - 8 * profile._g(np.maximum(xm - hm, 0.0))
                        + profile._g(np.maximum(xm - 2 * hm, 0.0))) / (12 * hm)
        if np.any(backward):
            xb, hb = x[backward], h[backward]
            val[backward] = (3 * profile._g(xb) - 4 * profile._g(np.maximum(xb - hb, 0.0))
                             + profile._g(np.maximum(xb - 2 * hb, 0.0))) / (2 * hb)
        if np.any(forward):
            xf, hf = x[forward], h[forward]
            val[forward] = (-3 * profile._g(xf) + 4 * profile._g(xf + hf)
                            - profile._g(xf + 2 * hf)) / (2 * hf)
    return val


def phi(profile, E_star: float, dgamma: float, a: np.ndarray) -> np.ndarray:
    """Stability function ``φ(a) = a g'(a)/Δl(a)`` (dimensionless; see the module notes)."""
    a = np.asarray(a, float)
    return a * g_prime(profile, a) / edge_elongation(E_star, dgamma, a)


# ---------------------------------------------------------------------------- branch structure
@dataclass(frozen=True)
class Branches:
    """Pull-off radii and branch limits of one adhesive contact, m.

    Attributes
    ----------
    a_force : float
        Force-controlled pull-off radius (start of the force-stable branch; minimum of F(a)).
    a_disp : float
        Displacement-controlled pull-off radius (start of the grip-stable branch; minimum of d(a)).
    a_force_low, a_disp_low : float
        Lower ends of the unstable branches below ``a_force`` / ``a_disp`` (0 when they reach
        ``a → 0``).
    wall : float
        Punch wall radius (``inf`` without a wall); radii never exceed it.
    pinned_force, pinned_disp : bool
        The pull-off sits at the wall (flat punch: Kendall).
    """

    a_force: float
    a_disp: float
    a_force_low: float
    a_disp_low: float
    wall: float
    pinned_force: bool
    pinned_disp: bool


def _limit(profile) -> float:
    return min(profile.wall_radius, profile.max_radius)


def branches(profile, E_star: float, dgamma: float) -> Branches:
    """Scan ``φ(a)`` and locate both pull-off radii of one adhesive contact.

    Parameters
    ----------
    profile : Profile
    E_star : float
        Effective modulus, Pa.
    dgamma : float
        Work of adhesion Δγ, J/m² (> 0).
    """
    prof = profile
    E = E_star
    w = dgamma
    terms = prof.power_terms()
    if terms is not None and max(n for _, n in terms) <= 0.5:
        raise OutsideTheoryError(
            f"profile {prof!r} grows like r**n with n <= 1/2: adhesion outgrows elasticity at large "
            "contact radii, F(a) has no interior minimum and there is no stable JKR branch "
            "(theory §4). Only normal(radius=...) is defined for this adhesive contact.")
    wall = prof.wall_radius
    limit = _limit(prof)
    top = limit * (1 - 1e-12) if np.isfinite(limit) else np.inf

    def f_phi(a: np.ndarray) -> np.ndarray:
        with np.errstate(invalid="ignore", divide="ignore"):
            v = phi(prof, E, w, a)
        return np.where(np.isnan(v), np.inf, v)

    # 1. an upper radius where both branches are stable (φ > 3/2), or the wall / domain limit
    s = prof._initial_bracket()
    s = min(s, top)
    capped = False
    for _ in range(80):
        if f_phi(np.array(s)) > 1.5:
            break
        if s >= top:
            capped = True
            break
        s = min(4.0 * s, top)
    else:
        raise OutsideTheoryError(
            f"no stable adhesive branch found for {prof!r} up to a = {s:.3g} m: g(a) grows no "
            "faster than sqrt(a) (theory §4).")
    if capped and not np.isfinite(wall):
        raise OutsideTheoryError(
            f"the stable adhesive branch of {prof!r} lies beyond its max_radius={prof.max_radius!r} m "
            f"(work_of_adhesion={w!r} J/m² is too large for this profile).")
    # 2. log grid below s
    grid = s * np.logspace(-_DECADES, 0.0, _DECADES * _PER_DECADE + 1)
    # resolve narrow features next to slope jumps and flat rims (φ jumps there)
    cuts = [c for c in (*prof.breakpoints, prof.flat_radius) if 0 < c < s]
    extra = [c * (1 + e) for c in cuts for e in (-1e-9, 1e-9, 1e-6, 1e-4, 1e-3, 3e-3, 1e-2, 3e-2)]
    grid = np.unique(np.concatenate([grid, [x for x in extra if grid[0] < x < s]]))
    vals = f_phi(grid)

    def crossing(level: float) -> tuple[float, float, bool]:
        below = np.flatnonzero(vals <= level)
        if capped and vals[-1] <= level:
            # pinned at the wall: the lower end is the next upward crossing below it
            up = np.flatnonzero(vals > level)
            low = float(grid[up[-1]]) if up.size else 0.0
            return float(wall if np.isfinite(wall) else s), low, True
        if below.size == 0:
            return 0.0, 0.0, False
        i = int(below[-1])
        lo, hi = grid[i], grid[i + 1]
        root = float(bracketed_root(lambda x, idx: f_phi(x), level, lo, hi, rtol=1e-14,
                                    what="pull-off contact radius")[()])
        # a crossing at a slope jump / flat rim is a jump of φ: the answer is the rim itself
        for c in cuts:
            if abs(root - c) <= 1e-9 * c:
                root = c
        above = np.flatnonzero(vals[: i + 1] > level)
        low = float(grid[above[-1]]) if above.size else 0.0
        if above.size:
            j = int(above[-1])
            low = float(bracketed_root(lambda x, idx: f_phi(x), level, grid[j], grid[j + 1],
                                       rtol=1e-14, what="unstable-branch end")[()])
        return root, low, False

    a_f, a_f_low, pin_f = crossing(1.5)
    a_d, a_d_low, pin_d = crossing(0.5)
    return Branches(a_f, a_d, a_f_low, a_d_low, wall, pin_f, pin_d)


# ---------------------------------------------------------------------------- solves on a branch
def _expand_upper(func, target: np.ndarray, start: float, top: float) -> np.ndarray:
    """Upper brackets ``hi >= start`` with ``func(hi) >= target`` (expanding by 4), capped at top."""
    hi = np.full(target.shape, max(start, 1e-300) * 2.0 if start > 0 else 1e-9)
    hi = np.minimum(hi, top)
    for _ in range(400):
        short = func(hi) < target
        if not np.any(short):
            return hi
        if np.any(short & (hi >= top)):
            return np.where(short, top, hi)
        hi = np.where(short, np.minimum(hi * 4.0, top), hi)
    raise ConvergenceError("could not bracket the adhesive contact radius (expansion failed).")


def _solve_increasing(func, target: np.ndarray, lo: float, top: float, what: str
                      ) -> tuple[np.ndarray, np.ndarray]:
    """Solve increasing ``func(a) = target`` on ``[lo, top]``; returns (a, pinned-at-top mask)."""
    a = np.empty(target.shape)
    hi = _expand_upper(func, target, lo, top)
    pinned = func(hi) < target
    if np.any(pinned & ~np.isfinite(top)):
        raise ConvergenceError(f"could not bracket the {what}.")
    a[pinned] = top
    free = ~pinned
    if np.any(free):
        a[free] = bracketed_root(lambda x, idx: func(x), target[free],
                                 np.full(int(free.sum()), lo), hi[free], rtol=1e-15, what=what)
    return a, pinned


def check_branch(branch: str) -> None:
    """Raise :class:`ParameterError` unless ``branch`` is one of :data:`BRANCHES`."""
    if branch not in BRANCHES:
        raise ParameterError(f"branch={branch!r} is invalid: choose one of {BRANCHES}.")


def solve_depth(profile, E_star: float, dgamma: float, br: Branches, d: np.ndarray, branch: str
                ) -> tuple[np.ndarray, np.ndarray]:
    """Contact radius (m) and pinned-at-the-wall mask for depths ``d`` on the chosen branch
    (radius 0 where detached); ``br`` from :func:`branches`."""
    prof, E, w = profile, E_star, dgamma
    dfun = lambda a: depth_of_radius(prof, E, w, a)  # noqa: E731
    a = np.zeros(d.shape)
    pinned = np.zeros(d.shape, bool)
    if branch == "stable":
        d_c = float(dfun(np.array(br.a_disp)))
        on = d >= d_c
        if br.pinned_disp:
            a[on] = br.a_disp
            pinned[on] = True
        elif np.any(on):
            top = br.wall if np.isfinite(br.wall) else _limit(prof) * (1 - 1e-12)
            a[on], pinned[on] = _solve_increasing(dfun, d[on], br.a_disp, top, "contact radius")
        return a, pinned
    lo, hi = br.a_disp_low, br.a_disp
    d_lo, d_hi = float(dfun(np.array(lo))), float(dfun(np.array(hi)))
    bad = (d > d_lo) | (d < d_hi)
    if np.any(bad) or hi <= lo:
        val = d[bad].ravel()[0] if np.any(bad) else d.ravel()[0]
        raise ParameterError(
            f"depth={val!r} m is invalid for branch='unstable': the unstable JKR branch exists "
            f"only for {d_hi:.6g} <= depth <= {d_lo:.6g} m (radii {lo:.6g} to {hi:.6g} m).")
    a[...] = bracketed_root(lambda x, idx: dfun(x), d.ravel(), np.full(d.size, lo),
                            np.full(d.size, hi), rtol=1e-15, what="contact radius").reshape(d.shape)
    return a, pinned


def solve_force(profile, E_star: float, dgamma: float, br: Branches, F: np.ndarray, branch: str
                ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(radius m, depth m, pinned mask) for forces ``F`` (N) on the chosen branch."""
    prof, E, w = profile, E_star, dgamma
    ffun = lambda a: force_of_radius(prof, E, w, a)  # noqa: E731
    a = np.zeros(F.shape)
    pinned = np.zeros(F.shape, bool)
    if branch == "stable":
        F_c = float(ffun(np.array(br.a_force)))
        if np.any(F < F_c):
            raise OutsideTheoryError(
                f"force={np.min(F)!r} N is below the pull-off force {F_c:.6g} N of this adhesive "
                "contact: no equilibrium exists, the bodies separate (see contact.pull_off()).")
        if br.pinned_force:
            a[...] = br.a_force
            pinned[...] = True
        else:
            top = br.wall if np.isfinite(br.wall) else _limit(prof) * (1 - 1e-12)
            a, pinned = _solve_increasing(ffun, F, br.a_force, top, "contact radius")
    else:
        lo, hi = br.a_force_low, br.a_force
        F_lo, F_hi = float(ffun(np.array(lo))), float(ffun(np.array(hi)))
        bad = (F > F_lo) | (F < F_hi)
        if np.any(bad) or hi <= lo:
            val = F[bad].ravel()[0] if np.any(bad) else F.ravel()[0]
            raise ParameterError(
                f"force={val!r} N is invalid for branch='unstable': the force-unstable JKR branch "
                f"exists only for {F_hi:.6g} <= force <= {F_lo:.6g} N.")
        a[...] = bracketed_root(lambda x, idx: ffun(x), F.ravel(), np.full(F.size, lo),
                                np.full(F.size, hi), rtol=1e-15,
                                what="contact radius").reshape(F.shape)
    d = depth_of_radius(prof, E, w, a)
    if np.any(pinned):
        # pinned at the wall: F = 2E*(b d - ∫_0^b g) gives the depth
        ap = a[pinned]
        d[pinned] = (F[pinned] / (2 * E) + prof._g_integral(ap)) / ap
    return a, d, pinned
