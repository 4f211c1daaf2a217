"""Adhesive (JKR) normal contact through the MDR: the Heß rule [Heß11; H1; PH] (physics.md §4).

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

The driver functions take a :class:`~contactlab.Contact` and return
:class:`~contactlab.adhesion.AdhesiveNormalState` objects; the kernels are pure.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from ..errors import ConvergenceError, OutsideTheoryError, ParameterError
from ..numeric.roots import bracketed_root
from ..params import as_float_array

__all__ = ["edge_elongation", "depth_of_radius", "force_of_radius", "g_prime", "phi",
           "Branches", "branches", "adhesive_normal", "pull_off", "adhesion_cycle",
           "BRANCHES"]

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
    if hasattr(profile, "terms") and isinstance(profile.terms, tuple):
        return sum(g_prime(t, x) for t in profile.terms)
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


def branches(contact) -> Branches:
    """Scan ``φ(a)`` and locate both pull-off radii (cached on the contact)."""
    cached = contact.__dict__.get("_jkr_branches")
    if cached is not None:
        return cached
    prof = contact.profile
    E = contact.moduli.normal
    w = contact.work_of_adhesion
    terms = prof.power_terms()
    if terms is not None and max(n for _, n in terms) <= 0.5:
        raise OutsideTheoryError(
            f"profile {prof!r} grows like r**n with n <= 1/2: adhesion outgrows elasticity at large "
            "contact radii, F(a) has no interior minimum and there is no stable JKR branch "
            "(physics.md §4). Only normal(radius=...) is defined for this adhesive contact.")
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
            "faster than sqrt(a) (physics.md §4).")
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
    out = Branches(a_f, a_d, a_f_low, a_d_low, wall, pin_f, pin_d)
    contact.__dict__["_jkr_branches"] = out
    return out


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


def _check_branch(branch: str) -> None:
    if branch not in BRANCHES:
        raise ParameterError(f"branch={branch!r} is invalid: choose one of {BRANCHES}.")


def _solve_depth(contact, d: np.ndarray, branch: str) -> tuple[np.ndarray, np.ndarray]:
    """Contact radius for depths ``d`` on the chosen branch (0 where detached)."""
    prof, E, w = contact.profile, contact.moduli.normal, contact.work_of_adhesion
    br = branches(contact)
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


def _solve_force(contact, F: np.ndarray, branch: str
                 ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(radius, depth, pinned) for forces ``F`` on the chosen branch."""
    prof, E, w = contact.profile, contact.moduli.normal, contact.work_of_adhesion
    br = branches(contact)
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


# ---------------------------------------------------------------------------- drivers
def _state(contact, d: np.ndarray, a: np.ndarray, pinned: np.ndarray, control: str,
           branch: str, F: np.ndarray | None = None):
    from ..adhesion import AdhesiveNormalState
    prof, E, w = contact.profile, contact.moduli.normal, contact.work_of_adhesion
    if F is None:
        F = force_of_radius(prof, E, w, a, d)
    F = np.where(a > 0, F, 0.0)
    if np.any(a > 0):
        prof._check_monotone_upto(float(np.max(a)), float(np.max(np.where(a > 0, d, -np.inf))))
    # stiffness dF/dd along the equilibrium curve; 2E*b when pinned at a wall, 0 when detached
    with np.errstate(invalid="ignore", divide="ignore"):
        ph = np.where(a > 0, phi(prof, E, w, np.where(a > 0, a, 1.0)), 0.0)
        k = 2 * E * a * (ph - 1.5) / (ph - 0.5)
    k = np.where(pinned, 2 * E * a, np.where(a > 0, k, 0.0))
    k = np.where(np.isnan(k), 2 * E * a, k)     # φ = ∞ (slope jump at a flat rim)
    k = np.where(np.abs(ph - 0.5) < 1e-9, np.inf, k)   # at the fixed-grip pull-off
    br = contact.__dict__.get("_jkr_branches")
    meta = {"routes": {"g": prof.g_route}, "rtol": contact.rtol, "control": control,
            "branch": branch, "work_of_adhesion": w}
    if br is not None:
        meta["stable_under_force"] = (a >= br.a_force * (1 - 1e-9)) & (a > 0)
        meta["stable_under_displacement"] = (a >= br.a_disp * (1 - 1e-9)) & (a > 0)
    return AdhesiveNormalState(contact, np.asarray(d, float), np.asarray(a, float),
                               np.asarray(F, float), meta, np.asarray(k, float))


def adhesive_normal(contact, *, depth: Any = None, force: Any = None, radius: Any = None,
                    branch: str = "stable"):
    """JKR normal contact through the MDR (Heß rule) for given depth, force or contact radius.

    Parameters
    ----------
    contact : Contact
        With ``work_of_adhesion > 0``.
    depth : float or array_like, optional
        Indentation depth ``d``, m (may be negative). Depths below the displacement-controlled
        pull-off depth give the detached state (radius 0, force 0).
    force : float or array_like, optional
        Normal force, N (negative = tensile). Forces below the force-controlled pull-off force
        raise :class:`~contactlab.errors.OutsideTheoryError` (no equilibrium exists).
    radius : float or array_like, optional
        Contact radius ``a``, m (direct; every ``a > 0`` is an equilibrium, stable or not).
    branch : {"stable", "unstable"}
        For ``depth=``/``force=``: ``"stable"`` (default) is the equilibrium stable under that
        control, the solution with the largest radius; ``"unstable"`` the smaller-radius solution
        that exists between the pull-off point and ``a → 0`` (a ``ParameterError`` names the
        reachable range otherwise).

    Returns
    -------
    AdhesiveNormalState
        ``meta["stable_under_force"]`` and ``meta["stable_under_displacement"]`` flag each state.

    Notes
    -----
    ``d(a) = g(a) - sqrt(2π a Δγ/E*)`` and ``F(a) = 2E*(a d - ∫_0^a g)`` [Heß11; physics.md §4].
    The state returned for a depth between the pull-off depth and 0 is the one reached on
    retraction; on approach the bodies stay apart until ``d = 0`` (see
    :meth:`Contact.adhesion_cycle`).
    """
    _check_branch(branch)
    given = {k: v for k, v in (("depth", depth), ("force", force), ("radius", radius))
             if v is not None}
    if len(given) != 1:
        raise ParameterError(f"normal() needs exactly one of depth=, force=, radius=; got "
                             f"{sorted(given) or 'none'}.")
    key, value = next(iter(given.items()))
    arr = as_float_array(key, value)
    prof, E, w = contact.profile, contact.moduli.normal, contact.work_of_adhesion
    if key == "radius":
        if np.any(arr < 0):
            raise ParameterError(f"radius contains {arr[arr < 0].ravel()[0]!r}: contact radii "
                                 "must be >= 0 m.")
        lim = _limit(prof)
        if np.any(arr > prof.wall_radius) or np.any(arr >= prof.max_radius):
            raise OutsideTheoryError(f"radius={np.max(arr)!r} m is invalid: it must stay below "
                                     f"{lim!r} m for {prof!r}.")
        a = arr.copy()
        d = depth_of_radius(prof, E, w, a)
        prof._check_monotone_upto(float(np.max(a, initial=0.0)), float(np.max(d, initial=0.0)))
        try:
            branches(contact)
        except OutsideTheoryError:
            pass
        return _state(contact, d, a, np.zeros(a.shape, bool), "radius", "n/a")
    if key == "depth":
        a, pinned = _solve_depth(contact, arr, branch)
        d = arr.copy()
        F = None
        if np.any(pinned):
            F = force_of_radius(prof, E, w, a, d)
        return _state(contact, d, a, pinned, "depth", branch, F)
    a, d, pinned = _solve_force(contact, arr, branch)
    return _state(contact, d, a, pinned, "force", branch, np.where(a > 0, arr, 0.0))


def pull_off(contact, control: str = "force"):
    """State at detachment: minimum of ``F(a)`` (force control) or of ``d(a)`` (fixed grips).

    Parameters
    ----------
    contact : Contact
        With ``work_of_adhesion > 0``.
    control : {"force", "displacement"}
        Loading device. Force control: the contact follows the stable branch while the tensile
        force grows and jumps off at the minimum of ``F(a)`` (``dF/da = 0``). Displacement control:
        it follows the branch further, to the minimum of ``d(a)`` (``dd/da = 0``).

    Returns
    -------
    AdhesiveNormalState
        ``.force``, ``.radius``, ``.depth`` at detachment.

    Raises
    ------
    OutsideTheoryError
        No interior minimum (power laws with ``n <= 1/2``, physics.md §4).

    Warns
    -----
    ValidityWarning
        When ``φ`` crosses the critical value more than once (e.g. a flat punch with a gently
        rounded edge): the returned state ends the stable branch connected to large contacts, but
        the contact may then jump onto a lower stable branch rather than separate.
    """
    controls = ("force", "displacement")
    if control not in controls:
        raise ParameterError(f"control={control!r} is invalid: choose one of {controls}.")
    br = branches(contact)
    prof, E, w = contact.profile, contact.moduli.normal, contact.work_of_adhesion
    a_c = br.a_force if control == "force" else br.a_disp
    if a_c <= 0:
        raise OutsideTheoryError(
            f"{control}-controlled pull-off of {prof!r}: the stable branch reaches a -> 0 without "
            "an interior minimum, so the contact carries no tensile force at detachment.")
    low = br.a_force_low if control == "force" else br.a_disp_low
    if low > 0:
        import warnings
        from ..errors import ValidityWarning
        warnings.warn(
            f"{control}-controlled pull-off of {prof!r}: the stability function crosses its "
            f"critical value more than once, so another stable branch exists below "
            f"a = {low:.6g} m. The state returned ends the stable branch connected to large "
            "contacts; the contact may jump onto the lower branch instead of separating.",
            ValidityWarning, stacklevel=3)
    a = np.array(a_c)
    d = depth_of_radius(prof, E, w, a)
    pinned = np.array(br.pinned_force if control == "force" else br.pinned_disp)
    return _state(contact, d, a, pinned, f"pull_off:{control}", "stable")


def adhesion_cycle(contact, *, depth: Any = None, force: Any = None):
    """Walk an approach/retraction history with JKR jump-in and jump-off (hysteresis).

    Parameters
    ----------
    depth, force : array_like (1D), exactly one
        The load history, m or N.

    Returns
    -------
    AdhesionCycle
        Per-step ``depth``, ``force``, ``radius``, ``in_contact`` and the step indices of the
        jumps.

    Notes
    -----
    Rules (quasi-static, short-range adhesion):

    * Out of contact the bodies stay apart (zero force) until the surfaces touch: under depth
      control at ``d >= 0``, under force control at ``F >= 0``. They then jump onto the stable
      branch (JKR jump-in: for a paraboloid under fixed grips ``a³ = 2πΔγR²/E*`` at ``d = 0``).
    * In contact the state follows the stable branch; there is no other memory.
    * Contact is lost below the pull-off depth (depth control, ``dd/da = 0``) or the pull-off
      force (force control, ``dF/da = 0``); the bodies jump apart.
    """
    given = {k: v for k, v in (("depth", depth), ("force", force)) if v is not None}
    if len(given) != 1:
        raise ParameterError("adhesion_cycle() needs exactly one of depth=, force=; got "
                             f"{sorted(given) or 'none'}.")
    key, value = next(iter(given.items()))
    arr = as_float_array(key, value)
    if arr.ndim != 1 or arr.size == 0:
        raise ParameterError(f"{key} must be a non-empty 1D history; got shape {arr.shape}.")
    br = branches(contact)
    prof, E, w = contact.profile, contact.moduli.normal, contact.work_of_adhesion
    if key == "depth":
        a_c = br.a_disp
        lim = float(depth_of_radius(prof, E, w, np.array(a_c)))
    else:
        a_c = br.a_force
        lim = float(force_of_radius(prof, E, w, np.array(a_c)))
    # contact flag: a scan with memory (jump-in at >= 0, jump-off below the pull-off value)
    in_contact = np.zeros(arr.shape, bool)
    state = False
    for i, v in enumerate(arr):          # scalar bookkeeping only; the solves are vectorised
        state = (v >= lim) if state else (v >= 0.0)
        in_contact[i] = state
    radius = np.zeros(arr.shape)
    depth_out = arr.copy() if key == "depth" else np.zeros(arr.shape)
    force_out = np.zeros(arr.shape) if key == "depth" else np.where(in_contact, arr, 0.0)
    if np.any(in_contact):
        s = adhesive_normal(contact, **{key: arr[in_contact]})
        radius[in_contact] = s._radius
        depth_out[in_contact] = s._depth
        force_out[in_contact] = s._force
    if key == "force":
        # out of contact under force control the gap is undefined; report the touching depth 0
        depth_out[~in_contact] = 0.0
    jumps = np.flatnonzero(np.diff(in_contact.astype(int)) != 0) + 1
    from ..adhesion import AdhesionCycle
    return AdhesionCycle(control=key, depth=depth_out, force=force_out, radius=radius,
                         in_contact=in_contact, jumps=jumps, pull_off_value=lim)
