"""Scalar normal solves: one depth or one force, in plain floats (the fast path of ``normal()``).

The array kernels of :mod:`contactlab.physics.normal` pay numpy's per-call overhead a few dozen
times per solve (masks, broadcasting, 0-d arrays), which dominates a single call on a closed-form
profile. Here the profile's closed forms are looked up **once per profile** and bound into plain
float functions (:func:`forms_of`), so a scalar solve is a few float operations:

* a single power term ``f = c r**n``: ``g = κ c a**n``, ``∫g = κ c a**(n+1)/(n+1)`` and both
  inverses in closed form, no iteration;
* other closed-form profiles (sphere, polynomial, truncated paraboloid): the contact radius by
  :func:`contactlab.numeric.roots.scalar_root`, Newton on the closed-form derivative where the
  profile has one (``g'``; for the force ``d(a g - ∫g)/da = a g'``), Chandrupatla otherwise.

* a flat punch: the contact radius is the wall's; ``g`` and ``∫g`` there are evaluated once;
* sums and scaled profiles: composed from their terms' (base's) scalar forms.

Profiles without a closed-form (or symbolic) ``g``, rising before a wall, summed with a punch, or
with a ring-contact check (tables) are not handled here (:func:`forms_of` returns ``None``): their
callers use the array kernels. The results agree with the array route to the same tolerance
(the same formulas, the same bracket tolerance :func:`contactlab.profiles.base.root_rtol`); they
need not be bit-identical to it, but every call of this route is deterministic. Cones,
paraboloids and flat punches are: both routes perform the same operations (the same square or
cube root of the same operands, :mod:`contactlab.numeric.powers`; a paraboloid's own ``x²/R``
and ``sqrt(R d)``). Elsewhere a root solve (Newton here, Chandrupatla on arrays) or a
non-whole power (the C library's ``pow`` against numpy's) may move the last bits (measured
<= 2.1e-15 relative; docs/robustness.md).
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cache
from typing import TYPE_CHECKING, cast
from collections.abc import Callable

import numpy as np

from ..errors import ConvergenceError, OutsideTheoryError
from ..numeric.powers import root_of_ratio_float, times_power_float
from ..numeric.quadrature import LOOSE_RTOL, common_nodes, min_level_for, upto_rows
from ..numeric.roots import _chandrupatla, scalar_root, shrink_bracket_scalar
from ..profiles.base import ROUNDING, Profile, force_ftol, quadrature_root_rtol, root_rtol
from ..profiles.radius_bounds import first_step_one, upper_radius_one

if TYPE_CHECKING:
    from ..profiles.compound import Scaled, Sum

_TINY = float(np.finfo(float).tiny)

__all__ = ["ScalarForms", "forms_of", "solve_depth", "solve_force", "force_rel_error",
           "quadrature_scalar_ok", "solve_depth_quadrature", "solve_force_quadrature",
           "quadrature_force_rel_error"]

_CACHE_KEY = "_scalar_normal_forms"


@dataclass(frozen=True)
class ScalarForms:
    """Plain-float closed forms of one profile (see :func:`forms_of`).

    ``g``, ``g_integral``: ``g(a)`` and ``∫_0^a g`` (m, m²); ``g_inverse``: contact radius of a
    depth or ``None``; ``radius_of_reduced_force``: contact radius of ``F/(2E*)`` or ``None``;
    ``g_prime``: ``g'(a)`` or ``None``; ``lo``: the flat radius (g = 0 below it); ``limit``: the
    largest admissible contact radius; ``start``: the first upper bracket; ``wall``: the punch
    wall radius (``inf`` without); ``validity``: the profile's ``validity_radius``; ``route``: its
    ``g_route`` (reported in the result's meta); ``force_constants``: ``E* -> (K, c)`` of a
    paraboloid (:meth:`~contactlab.profiles.Paraboloid._hertz_force_constants`: ``F = K a³``,
    the force of a radius and depth ``(a·d)·c``) or ``None``.
    """

    g: Callable[[float], float]
    g_integral: Callable[[float], float]
    g_inverse: Callable[[float], float] | None
    radius_of_reduced_force: Callable[[float], float] | None
    g_prime: Callable[[float], float] | None
    lo: float
    limit: float
    start: float
    wall: float = math.inf
    validity: float = math.inf
    route: str = ""
    radius_depth_of_reduced_force: Callable[[float], tuple[float, float]] | None = None
    force_constants: Callable[[float], tuple[float, float]] | None = None


def _on_scalar(fn: Callable[[np.ndarray], np.ndarray]) -> Callable[[float], float]:
    def call(x: float) -> float:
        return float(fn(np.array(x)))
    return call


def _at_wall(fn: Callable[[float], float], wall: float) -> Callable[[float], float]:
    """``fn`` with its value at the wall radius computed once (a punch's contact radius is the
    wall's for every load, so that is the only argument the fast path passes)."""
    at_wall = fn(wall)

    def call(x: float) -> float:
        return at_wall if x == wall else fn(x)
    return call


def _sum_forms(profile: Sum) -> ScalarForms | None:
    """A sum of profiles: g, ∫g and g' are sums of the terms' scalar forms (the MDR transform is
    linear in the profile); ``None`` when a term has no scalar forms or a wall."""
    parts = [forms_of(t) for t in profile.terms]
    if any(f is None or math.isfinite(f.wall) for f in parts):
        return None
    forms = cast("list[ScalarForms]", parts)   # none is None past the test above
    gs = tuple(f.g for f in forms)
    gis = tuple(f.g_integral for f in forms)
    gps = tuple(f.g_prime for f in forms)
    # read by g_prime only, which is used only when no term lacks g'
    gps_all = cast("tuple[Callable[[float], float], ...]", gps)

    def g(a: float) -> float:
        return sum(f(a) for f in gs)

    def g_int(a: float) -> float:
        return sum(f(a) for f in gis)

    def g_prime(a: float) -> float:
        return sum(f(a) for f in gps_all)
    return ScalarForms(g=g, g_integral=g_int, g_inverse=None, radius_of_reduced_force=None,
                       g_prime=None if None in gps else g_prime,
                       lo=float(profile.flat_radius), limit=float(profile.max_radius),
                       start=float(profile._initial_bracket()))


def _scaled_forms(profile: Scaled) -> ScalarForms | None:
    """``k f``: g, ∫g, g' scale by k; the inverses take the depth or reduced force over k."""
    base = forms_of(profile.base)
    if base is None:
        return None
    k = float(profile.factor)
    inv_k = 1.0 / k
    bg, bgi, bgp, binv, brf = (base.g, base.g_integral, base.g_prime, base.g_inverse,
                               base.radius_of_reduced_force)
    return ScalarForms(
        g=lambda a: k * bg(a), g_integral=lambda a: k * bgi(a),
        g_inverse=None if binv is None else (lambda d: binv(d * inv_k)),
        radius_of_reduced_force=None if brf is None else (lambda fr: brf(fr * inv_k)),
        g_prime=None if bgp is None else (lambda a: k * bgp(a)),
        lo=base.lo, limit=float(profile.max_radius), start=base.start, wall=base.wall)


def _build(profile: Profile) -> ScalarForms | None:
    if profile.g_route not in ("closed_form", "symbolic") or profile._has("_check_monotone_upto"):
        return None
    from ..profiles.compound import Scaled, Sum
    if type(profile) is Sum:
        return _sum_forms(profile)
    if type(profile) is Scaled and profile.power_terms() is None:
        return _scaled_forms(profile)
    if profile.has("terms"):
        return None
    lo = float(profile.flat_radius)
    wall = float(profile.wall_radius)
    if math.isfinite(wall):
        if lo < wall:
            return None             # a profile rising before its wall: the array route
        # a flat punch: the contact radius is the wall's for every load
        g_int = _at_wall(_on_scalar(lambda a: profile._g_integral_with_error(a)[0]), wall)
        return ScalarForms(g=_at_wall(_on_scalar(profile._g), wall), g_integral=g_int,
                           g_inverse=None, radius_of_reduced_force=None, g_prime=None, lo=lo,
                           limit=float(profile.max_radius), start=wall, wall=wall)
    limit = float(profile.max_radius)
    start = float(profile._initial_bracket())
    terms = profile.power_terms()
    if terms is not None and len(terms) == 1 and lo == 0.0:
        c, n = (float(v) for v in terms[0])
        kc = profile._power_kappa(n) * c
        inv_n, n1 = 1.0 / n, n + 1.0
        # a profile's own float forms (the operations of its array closed forms: a paraboloid's
        # x²/R and sqrt(R d), bit-identical to the array route) replace the generic κ c x^n
        own = profile._scalar_closed_forms() if profile._has("_scalar_closed_forms") else {}
        return ScalarForms(
            g=own.get("g", lambda a: times_power_float(kc, a, n)),
            g_integral=lambda a: times_power_float(kc, a, n1, whole=True) / n1,
            g_inverse=own.get("g_inverse", lambda d: ((d / kc) ** inv_n
                                                      if _TINY <= d / kc < math.inf
                                                      else root_of_ratio_float(d, kc, n))),
            # F/(2E*) = a g(a) - ∫g = κ c n a**(n+1)/(n+1); the array route's operations
            radius_of_reduced_force=lambda fr: root_of_ratio_float(fr * n1, kc * n, n1),
            g_prime=lambda a: times_power_float(n * kc, a, n - 1.0),
            lo=lo, limit=limit, start=start,
            force_constants=getattr(profile, "_hertz_force_constants", None))
    own = profile._scalar_closed_forms() if profile._has("_scalar_closed_forms") else {}
    g = _on_scalar(profile._g) if not profile._has("_g_closed_form") else _on_scalar(
        profile._g_closed_form)
    g_int = _on_scalar(lambda a: profile._g_integral_with_error(a)[0])
    g_inv = (_on_scalar(profile._g_inverse_closed_form)
             if profile._has("_g_inverse_closed_form") else None)
    g_prime = (_on_scalar(profile._g_prime_closed_form)
               if profile._has("_g_prime_closed_form") else None)
    if terms is not None and lo == 0.0:
        kn = [(profile._power_kappa(float(n)) * float(c), float(n)) for c, n in terms]

        def g(a: float) -> float:
            return sum(times_power_float(k, a, n) for k, n in kn)

        def g_int(a: float) -> float:
            return sum(times_power_float(k, a, n + 1.0, whole=True) / (n + 1.0) for k, n in kn)

        def g_prime(a: float) -> float:
            return sum(times_power_float(n * k, a, n - 1.0) for k, n in kn)
    g, g_int = own.get("g", g), own.get("g_integral", g_int)
    g_inv, g_prime = own.get("g_inverse", g_inv), own.get("g_prime", g_prime)
    return ScalarForms(g=g, g_integral=g_int, g_inverse=g_inv, radius_of_reduced_force=None,
                       g_prime=g_prime, lo=lo, limit=limit, start=start,
                       radius_depth_of_reduced_force=own.get("radius_depth_of_reduced_force"))


def _with_validity(profile: Profile, forms: ScalarForms | None) -> ScalarForms | None:
    if forms is None:
        return None
    from dataclasses import replace
    return replace(forms, validity=float(getattr(profile, "validity_radius", math.inf)),
                   route=profile.g_route)


def forms_of(profile: Profile) -> ScalarForms | None:
    """The scalar forms of ``profile``, built on first use and kept on the profile.

    ``None`` when the profile has no scalar route (numeric g, a profile rising before its wall, a
    sum with a punch term, a table).
    The forms are a pure function of the (immutable) profile, so keeping them changes no result.
    """
    forms = profile.__dict__.get(_CACHE_KEY, False)
    if forms is False:
        forms = _with_validity(profile, _build(profile))
        profile.__dict__[_CACHE_KEY] = forms
    return forms


def _too_deep(what: str, value: float, limit: float, profile: Profile) -> OutsideTheoryError:
    return OutsideTheoryError(
        f"{what}={value!r} {'m' if what == 'depth' else 'N'} needs a contact radius >= "
        f"max_radius={limit!r} m of {profile!r}; reduce the {what}.")


def _upper(forms: ScalarForms, h: Callable[[float], float], target: float, what: str,
           value: float, profile: Profile) -> tuple[float, float, float]:
    """Bracket ``[lo, hi]`` with ``h(lo) <= target <= h(hi)``, grown by 4x from ``forms.start``."""
    lo, hi = forms.lo, forms.start
    finite = math.isfinite(forms.limit)
    cap = forms.limit * (1 - 1e-15) if finite else math.inf
    for _ in range(400):
        hi_c = min(hi, cap)
        h_hi = h(hi_c)
        if h_hi >= target:
            # a root far below the first bracket (forces of 1e-100 N): tightened from above
            return shrink_bracket_scalar(h, target, lo, hi_c, h_hi)
        if hi_c >= cap:
            raise _too_deep(what, value, forms.limit, profile)
        lo, hi = hi_c, 4.0 * hi
    raise _too_deep(what, value, forms.limit, profile)  # pragma: no cover - 4**400 overflows


def solve_depth(profile: Profile, forms: ScalarForms, d: float, rtol: float) -> float:
    """Contact radius (m) of one non-adhesive depth ``d > 0`` (m)."""
    if math.isfinite(forms.wall):
        return forms.wall
    if forms.g_inverse is not None:
        a = forms.g_inverse(d)
    else:
        lo, hi, g_hi = _upper(forms, forms.g, d, "depth", d, profile)
        a = scalar_root(forms.g, d, lo, hi, rtol=root_rtol(rtol), fprime=forms.g_prime,
                        f_hi=g_hi, what="contact radius")
    if a >= forms.limit:
        raise _too_deep("depth", d, forms.limit, profile)
    return a


def solve_force(profile: Profile, forms: ScalarForms, E_star: float, F: float, rtol: float
                ) -> tuple[float, float]:
    """Contact radius and depth (m) of one non-adhesive force ``F > 0`` (N)."""
    fr = F / (2.0 * E_star)
    if math.isfinite(forms.wall):       # flat punch: F = 2E*(b d - ∫_0^b g)
        b = forms.wall
        return b, (fr + forms.g_integral(b)) / b
    if forms.radius_depth_of_reduced_force is not None:
        a, d = forms.radius_depth_of_reduced_force(fr)
        if a >= forms.limit:
            raise _too_deep("force", F, forms.limit, profile)
        return a, d
    if forms.force_constants is not None:   # a paraboloid: F = K a³ (the array route's)
        a = root_of_ratio_float(F, forms.force_constants(E_star)[0], 3.0)
    elif forms.radius_of_reduced_force is not None:
        a = forms.radius_of_reduced_force(fr)
    else:
        g, G, gp = forms.g, forms.g_integral, forms.g_prime

        def h(x: float) -> float:          # F/(2E*) as a function of the contact radius
            return x * g(x) - G(x)

        lo, hi, h_hi = _upper(forms, h, fr, "force", F, profile)
        dh = None if gp is None else (lambda x: x * gp(x))
        a = scalar_root(h, fr, lo, hi, rtol=root_rtol(rtol), fprime=dh, f_hi=h_hi,
                        what="contact radius")
    if a >= forms.limit:
        raise _too_deep("force", F, forms.limit, profile)
    return a, forms.g(a)


def hertz_force_rel_error(forms: ScalarForms, E_star: float, a: float, d: float, F: float,
                          c: float) -> float:
    """:func:`force_rel_error` of a paraboloid's force-controlled state, whose force ``F`` is
    the request: the rounding of ``a d - ∫g`` and of ``∫g`` (``∫g`` computed here: only the
    estimate reads it) and the residual ``|(a·d)·c - F|`` of the state's radius and depth
    (:meth:`~contactlab.profiles.Paraboloid._hertz_force_constants`)."""
    if not F > 0:
        return 0.0
    ad = a * d
    g_int = forms.g_integral(a)
    err = 2.0 * E_star * (ROUNDING * (abs(ad) + abs(g_int)) + ROUNDING * abs(g_int))
    err += abs(ad * c - F)
    return float(err / F)


def force_rel_error(E_star: float, a: float, d: float, g_int: float, F: float,
                    requested: float | None) -> float:
    """Relative error estimate of the force, as :func:`contactlab.physics.normal.solve` gives it.

    Closed-form routes: rounding of ``a d - ∫g`` and of ``∫g``; under force control plus the
    residual against the requested force.
    """
    if not F > 0:
        return 0.0
    err = 2.0 * E_star * (ROUNDING * (abs(a * d) + abs(g_int)) + ROUNDING * abs(g_int))
    if requested is not None and requested > 0:
        err += abs(F - requested)
    return float(err / F)


# ----------------------------------------------------------------------------- quadrature route
_QUAD_KEY = "_scalar_quadrature_ok"
#: radii of the bracket's growth on f evaluated per call of f (4**8: a factor 65536)
_LADDER = 8
#: the Profile methods the array route of a depth runs on a quadrature profile: a subclass that
#: overrides one of them keeps the array route
_QUAD_METHODS = ("_radius_of_depth", "_solve_radius", "_g", "_g_route_eval", "_g_quadrature",
                 "_theta_quadrature", "_theta_segments", "_theta_whole", "_quadrature_floor",
                 "_g_integral", "_g_integral_with_error", "_g_integral_quadrature",
                 "_initial_bracket")
_HALF_PI = float(np.full(1, 0.5 * np.pi)[0])      # θ's upper end as _theta_quadrature sets it


def _theta_values(profile: Profile, x: float, cos2: bool) -> np.ndarray:
    """The θ integrands of g (and, with ``cos2``, of ∫g as a second row) at one ``x`` on the
    first levels' nodes over ``[0, π/2]``: the operations of :meth:`Profile._g_quadrature`'s
    and :meth:`Profile._g_integral_quadrature`'s weights (f' evaluated once)."""
    sin_th, cos2_th = _theta_trig()
    fx = np.asarray(profile._slope_any(np.array([[x]]) * sin_th), dtype=float)
    if cos2:
        fx = np.concatenate([fx, fx * cos2_th])
    return fx


@cache
def _theta_trig() -> tuple[np.ndarray, np.ndarray]:
    """``sin θ`` and ``cos²θ`` on :func:`common_nodes` over ``[0, π/2]`` (numpy's, as the
    weights compute them at every call; kept read-only)."""
    th = common_nodes(0.0, _HALF_PI)
    sin_th, cos2_th = np.sin(th), np.cos(th) ** 2
    sin_th.flags.writeable = False
    cos2_th.flags.writeable = False
    return sin_th, cos2_th


def _level1_one(profile: Profile, x: float, rtol: float, cos2: bool) -> tuple[float, float] | None:
    """``(value, error)`` of :meth:`Profile._theta_quadrature` at one ``x > 0`` over the whole
    θ range at a loose ``rtol`` when the first levels reach it (the same operations as on a
    batch of one: the same bits), or None (the caller takes the array route)."""
    fx = _theta_values(profile, x, cos2)
    rows = upto_rows(fx, 0.0, _HALF_PI)
    if rows is None:
        return None
    return _first_converged_one(*rows[-1], rtol)


def _first_converged_one(values: list[float], errors: list[float], rtol: float
                         ) -> tuple[float, float] | None:
    """:func:`~contactlab.numeric.quadrature.first_converged` of one integral in floats (the
    same comparisons): ``(value, error)`` at the first level that stops, or None."""
    for k in range(min_level_for(rtol), len(values) + 1):
        v, e = values[k - 1], errors[k - 1]
        if e <= rtol * abs(v):
            return v, e
    return None


def _g_and_integral_one(profile: Profile, x: float, rtol: float, lean: bool
                        ) -> tuple[float, float, float]:
    """``(g(x), ∫_0^x g, its error)`` at one radius on a quadrature profile (the same bits as
    ``profile._g`` and ``profile._g_integral_with_error``): at a loose rtol both θ integrals in
    one pass, f' evaluated once for both (the ∫g integrand is that f' times cos²θ)."""
    if lean and x > 0:
        rows = upto_rows(_theta_values(profile, x, True), 0.0, _HALF_PI)
        if rows is not None:
            g = _first_converged_one(*rows[0], rtol)
            gi = _first_converged_one(*rows[1], rtol)
            if g is not None and gi is not None:
                x2 = x * x
                return g[0] * x, gi[0] * x2, gi[1] * x2
    return (g_one(profile, x, rtol, lean), *g_integral_one(profile, x, rtol, lean))


def _lean(profile: Profile, rtol: float) -> bool:
    """Whether :func:`_level1_one` applies (a loose rtol, θ never split)."""
    return rtol >= LOOSE_RTOL and profile._theta_whole()


def g_one(profile: Profile, x: float, rtol: float, lean: bool) -> float:
    """``profile._g`` at one radius ``x`` (m) on a quadrature profile (the same bits)."""
    if x == 0.0:
        return 0.0          # (Profile._theta_quadrature skips x = 0: its value 0 times x)
    if lean and x > 0:
        ve = _level1_one(profile, x, rtol, False)
        if ve is not None:
            return ve[0] * x
    return float(profile._g(np.array([x]), rtol)[0])


def g_integral_one(profile: Profile, a: float, rtol: float, lean: bool) -> tuple[float, float]:
    """``profile._g_integral_with_error`` at one radius ``a`` (m) on a quadrature profile."""
    if lean and a > 0:
        ve = _level1_one(profile, a, rtol, True)
        if ve is not None:
            a2 = a * a
            return ve[0] * a2, ve[1] * a2
    gi, gi_err = profile._g_integral_with_error(np.array([a]), rtol)
    return float(gi[0]), float(gi_err[0])


def quadrature_scalar_ok(profile: Profile) -> bool:
    """Whether one depth on ``profile`` may take :func:`solve_depth_quadrature` (kept on the
    profile): g by quadrature, no wall, no ring-contact check, no closed-form inverse, and the
    base class's solve (no override of the methods it runs)."""
    ok = profile.__dict__.get(_QUAD_KEY)
    if ok is None:
        cls = type(profile)
        ok = (profile.g_route == "quadrature" and not profile.has("terms")
              and not profile.has("reduced_force_solver")
              and not profile.has("reduced_force_state")
              and not math.isfinite(float(profile.wall_radius))
              and not profile._has("_check_monotone_upto")
              and not profile._has("_g_inverse_closed_form")
              and all(getattr(cls, m) is getattr(Profile, m) for m in _QUAD_METHODS))
        profile.__dict__[_QUAD_KEY] = ok
    return bool(ok)


def _times4(hi: float) -> float:
    """``4 hi``, raising FloatingPointError where it overflows (as the array route's bracket
    growth does under numpy's ``over="raise"``)."""
    out = hi * 4.0
    if out == math.inf and hi < math.inf:
        raise FloatingPointError("overflow growing the bracket")
    return out


def _bracket_one(fun: Callable[[float], float], target: float, lo: float, hi: float,
                 limit: float) -> tuple[float, float, float, float, float] | None:
    """The array route's bracket for one element in floats: ``hi`` grown ×4 (capped just below
    ``limit``) until ``fun(hi) >= target``, then shrunk from above; returns ``(lo, hi,
    fun(hi), fun(lo) - target, fun(hi) - target)``, or ``None`` where the array route would
    decline (no bracket below ``limit``, a non-finite end, no sign change)."""
    finite = math.isfinite(limit)
    cap = limit * (1 - 1e-15)
    for _ in range(400):
        hi_c = min(hi, cap) if finite else hi
        f_hi = fun(hi_c)
        if not f_hi < target:
            lo, hi, f_hi = shrink_bracket_scalar(fun, target, lo, hi_c, f_hi)
            break
        if finite and hi >= cap:
            return None
        lo, hi = hi_c, _times4(hi)
    else:
        return None
    f1, f2 = fun(lo) - target, f_hi - target
    if not (math.isfinite(f1) and math.isfinite(f2)):
        return None
    if math.isinf(f1 * f2):
        # bracketed_root's sign test f1 f2 > 0 overflows on the array route (over="raise")
        raise FloatingPointError("overflow in the bracket's sign test")
    if f1 * f2 > 0:
        return None
    return lo, hi, f_hi, f1, f2


def solve_depth_quadrature(profile: Profile, d: float, rtol: float) -> float | None:
    """Contact radius (m) of one depth ``d > 0`` on a quadrature profile, or ``None`` (the
    array route then runs, and raises where this one would).

    The steps of :meth:`Profile._solve_radius` and :func:`~contactlab.numeric.roots.
    bracketed_root` for one element in plain floats (the bracket grown on f, then on g, shrunk
    from above, then Chandrupatla's iteration), with each g a one-element array through the same
    quadrature: the same radius, bit for bit, as the array route, without its per-iteration
    array bookkeeping (which costs more than one g at a loose ``rtol``).
    """
    lean = _lean(profile, rtol)

    def g(x: float) -> float:
        return g_one(profile, x, rtol, lean)

    limit = float(profile.max_radius)
    finite = math.isfinite(limit)
    lo = float(profile.flat_radius)
    hi = float(profile._initial_bracket())
    if profile._has("_height"):
        # the array route's growth of the bracket on f, its radii taken _LADDER at a time in one
        # call of f (f is elementwise: the same values)
        cap = limit * (1 - 1e-15) if finite else math.inf
        f_prev = -math.inf
        growing = True
        if rtol >= LOOSE_RTOL:
            # the array route's bracket from the lower bound of g on f (the same function)
            hb = upper_radius_one(profile, d, hi, cap, "depth")
            if math.isfinite(hb):
                hi, growing = hb, False
        for _ in range(200 // _LADDER if growing else 0):
            his = [hi]
            for _ in range(_LADDER - 1):
                his.append(his[-1] * 4.0)
            hcs = [min(h, cap) for h in his]
            with np.errstate(over="ignore", invalid="ignore"):
                fs = profile._height(np.array(hcs))
            for hc, f_hc in zip(hcs, fs.tolist()):
                if not ((f_hc < d) and (hc < cap) and (f_hc > f_prev)):
                    growing = False
                    break
                f_prev = f_hc
                hi = _times4(hi)
            if not growing:
                break
    got = _bracket_one(g, d, lo, hi, limit)
    if got is None:
        return None
    lo, hi, g_hi, f1, f2 = got
    if f2 == 0:             # (bracketed_root's order: the upper end wins a double zero)
        a = hi
    elif f1 == 0:
        a = lo
    else:
        try:
            step0, ftol, tol = 0.5, 0.0, quadrature_root_rtol(rtol)
            if rtol >= LOOSE_RTOL and profile._has("_height"):
                # the array route's first point (the same function on one element) and stop
                step0, ftol = first_step_one(
                    profile, d, lo, hi, g_hi, float(profile._initial_bracket()),
                    limit * (1 - 1e-15) if finite else math.inf, "depth"), tol
            a = _chandrupatla(g, d, lo, hi, f1, f2, tol, 200, "contact radius", step0, ftol)
        except ConvergenceError:
            return None
    if finite and a >= limit:
        return None
    return a


def solve_force_quadrature(profile: Profile, E_star: float, F: float, rtol: float
                           ) -> tuple[float, float, float, float] | None:
    """Contact radius and depth (m) of one force ``F > 0`` (N) on a quadrature profile, with
    ``∫_0^a g`` (m²) and its error estimate there (those of the root's own force evaluation,
    the bits of :func:`g_integral_one`), or ``None`` (the array route then runs, and raises
    where this one would).

    The steps of the bracketed branch of :func:`contactlab.physics.normal.radius_depth_of_force`
    for one element in plain floats, the force ``2E*(a g(a) - ∫g)`` of each radius through the
    same quadratures (one pass for both at a loose rtol): the array route's radius and depth,
    bit for bit.
    """
    lean = _lean(profile, rtol)
    two_e = 2.0 * E_star

    # g, ∫g and its error at the radii evaluated (the depth and ∫g at the root)
    seen: dict[float, tuple[float, float, float]] = {}

    def force(x: float) -> float:
        if x == 0.0:
            return 0.0      # (the array route's 2E*(0 g(0) - ∫_0^0 g): g(0) = ∫_0^0 g = 0)
        g, gi, _ = seen[x] = _g_and_integral_one(profile, x, rtol, lean)
        out = two_e * (x * g - gi)
        if not math.isfinite(out) and math.isfinite(g) and math.isfinite(gi):
            # an overflow, which raises on the array route (numpy's over="raise" there)
            raise FloatingPointError("overflow in the force of a contact radius")
        return out

    limit = float(profile.max_radius)
    finite = math.isfinite(limit)
    lo = float(profile.flat_radius)
    hi = float(profile._initial_bracket())
    if rtol >= LOOSE_RTOL and profile._has("_height"):
        # the array route's first bracket from the lower bound of the force on f
        hb = upper_radius_one(profile, F / (2 * E_star), hi,
                              limit * (1 - 1e-15) if finite else math.inf, "force")
        if math.isfinite(hb):
            hi = hb
    got = _bracket_one(force, F, lo, hi, limit)
    if got is None:
        return None
    lo, hi, F_hi, f1, f2 = got
    if f2 == 0:             # (bracketed_root's order: the upper end wins a double zero)
        a = hi
    elif f1 == 0:
        a = lo
    else:
        try:
            step0, ftol = 0.5, 0.0
            if rtol >= LOOSE_RTOL and profile._has("_height"):
                # the array route's first point (the same function on one element) and stop
                step0, ftol = first_step_one(
                    profile, F / (2 * E_star), lo, hi, F_hi / (2 * E_star),
                    float(profile._initial_bracket()),
                    limit * (1 - 1e-15) if finite else math.inf, "force"), force_ftol(rtol)
            a = _chandrupatla(force, F, lo, hi, f1, f2, root_rtol(rtol), 200, "contact radius",
                              step0, ftol)
        except ConvergenceError:
            return None
    if not a > 0 or (finite and a >= limit):
        return None
    parts = seen.get(a)     # (g and ∫g of the force's pass: the same bits as each alone)
    if parts is None:
        return a, g_one(profile, a, rtol, lean), *g_integral_one(profile, a, rtol, lean)
    return a, *parts


def quadrature_force_rel_error(E_star: float, a: float, d: float, g_int: float,
                               g_int_err: float, F: float, requested: float | None = None
                               ) -> float:
    """Relative force error of one depth or force on the quadrature route, the operations of
    :func:`contactlab.physics.normal._force_rel_error` in floats (the same bits)."""
    if not a > 0:
        return 0.0
    F_err = ((abs(a * d) + abs(g_int)) * ROUNDING + abs(g_int_err)) * (2.0 * E_star)
    if requested is not None:
        F_err = F_err + (abs(F - requested) if requested > 0 else 0.0)
    return float(F_err / F) if F > 0 else 0.0
