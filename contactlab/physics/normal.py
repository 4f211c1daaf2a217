"""Normal contact through the MDR [S eqs. 1-20; H1; Sn65] (theory §3).

With the 1D foundation ``Δk = E* Δx`` and spring compression ``d - g(x)`` for ``|x| <= a``:

* ``F = 2E* (a d - ∫_0^a g dx)``, stiffness ``dF/dd = 2E* a``;
* ``p(r) = (E*/π) [S(r, a) + (d - g(a))/sqrt(a²-r²)]`` with the pressure shape
  ``S(r, a) = ∫_r^a g'(x)/sqrt(x²-r²) dx``;
* ``u_z(r) = (2d/π) asin(min(1, a/r)) - A(r, a)`` with ``A = (2/π) ∫_0^{min(r,a)} g/sqrt(r²-x²) dx``
  (``A = f(r)`` inside the contact, so ``u_z = d - f`` there).

Numeric routes: with a closed-form ``g'`` (hook ``_g_prime_closed_form``) ``S = ∫_0^U g'(r cosh u) du``;
otherwise S is evaluated by parts so only g is needed:
``S = (g(a)-g(r))/sqrt(a²-r²) + ∫_0^{U} (g(r cosh u) - g(r)) cosh u /(r sinh² u) du``,
``U = arccosh(a/r)``, with splits at the profile's breakpoints.
"""
from __future__ import annotations

import sys
from typing import Any, cast

import numpy as np

from ..errors import ConvergenceError, OutsideTheoryError
from ..numeric.powers import root_of_ratio
from ..numeric.quadrature import LOOSE_RTOL, tanh_sinh
from ..numeric.roots import bracketed_root, shrink_bracket
from ..profiles.base import ROUNDING, force_ftol, root_rtol
from ..profiles.power_law import Paraboloid
from ..profiles.radius_bounds import first_step_from_f, upper_radius_from_f
from . import normal_fused as _fused

__all__ = ["force", "pressure_shape", "abel_g", "pressure", "pressure_from_shape", "displacement",
           "elastic_energy", "g_squared_integral", "force_of_radius", "radius_depth_of_force", "solve"]


_U_MIN = 1e-4


def force(E_star: float, a: np.ndarray, d: np.ndarray, g_integral: np.ndarray) -> np.ndarray:
    """``F = 2E* (a d - ∫_0^a g)`` [S eq. 8], N."""
    return 2.0 * E_star * (a * d - g_integral)


def pressure_shape(profile, r: np.ndarray, a: np.ndarray, rtol: float, *,
                   table_rules: bool = True) -> tuple[np.ndarray, np.ndarray]:
    """``S(r, a) = ∫_r^a g'(x)/sqrt(x²-r²) dx`` (0 for ``r >= a``); returns (value, error estimate).

    Tables (``"node_table"``) take the per-segment rules of
    :mod:`contactlab.physics.table_pressure` (``table_rules=False``: the profile's own route,
    which those rules fall back on where they cannot resolve a radius)."""
    r, a = np.broadcast_arrays(np.asarray(r, float), np.asarray(a, float))
    if profile._has("_pressure_shape_closed_form"):
        return profile._pressure_shape_closed_form(r, a), np.zeros(r.shape)
    if table_rules and profile.has("node_table"):
        from .table_pressure import pressure_shape as table_shape
        res = table_shape(profile, r, a, rtol)
        if res is not None:
            return res
    if profile.has("semi_analytic_pressure_shape"):   # with an error estimate, or None: decline
        res = profile._pressure_shape_semi_analytic(r, a, rtol)
        if res is not None:
            return res
    if profile.has("terms"):       # Sum: the MDR is linear, each term takes its own route
        parts = [pressure_shape(t, r, a, rtol) for t in profile.terms]
        # (at least two terms: the sums are arrays)
        return (cast(np.ndarray, sum(p[0] for p in parts)),
                cast(np.ndarray, sum(p[1] for p in parts)))
    out = np.zeros(r.shape)
    err = np.zeros(r.shape)
    inside = r < a
    if not np.any(inside):
        return out, err
    rr, aa = r[inside], a[inside]
    g_a = profile._g(aa, rtol)
    g_r = profile._g(rr, rtol)
    val = np.zeros(rr.shape)
    er = np.zeros(rr.shape)
    axis = rr == 0
    # r > 0: by-parts form in u = arccosh(x/r), split at the breakpoints
    pos = ~axis
    if np.any(pos):
        rp, ap, grp = rr[pos], aa[pos], g_r[pos]
        cuts = sorted({b for b in (*profile.breakpoints, profile.flat_radius) if b > 0})
        U = np.arccosh(ap / rp)
        us = [np.clip(np.arccosh(np.maximum(b / rp, 1.0)), 0.0, U) for b in cuts]
        edges = np.stack([np.zeros_like(rp), *us, U])
        # exact x-limits of each segment: x is clipped into them, so rounding of arccosh/cosh
        # never moves a node across a breakpoint (where g' may be singular or jump)
        x_edges = np.stack([rp] + [np.clip(np.full_like(rp, b), rp, ap) for b in cuts] + [ap])
        lo, hi = edges[:-1], edges[1:]
        x_lo = x_edges[:-1].ravel()
        x_hi = x_edges[1:].ravel()
        rr_b = np.broadcast_to(rp, lo.shape).ravel()
        gr_b = np.broadcast_to(grp, lo.shape).ravel()
        # g varies on the scale u ~ sqrt(2(r - b)/r) just beyond a slope jump at b < r: the
        # small-u cut-off (see integrand) must stay well below that scale
        gap = np.full(rp.shape, np.inf)
        for b in cuts:
            gap = np.where(rp > b, np.minimum(gap, (rp - b) / rp), gap)
        u_min = np.broadcast_to(np.minimum(_U_MIN, 1e-2 * np.sqrt(2 * gap)), lo.shape).ravel()

        def node_x(u: np.ndarray, idx: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
            x = np.clip(rr_b[idx][:, None] * np.cosh(u), x_lo[idx][:, None], x_hi[idx][:, None])
            interior = (x > x_lo[idx][:, None]) & (x < x_hi[idx][:, None])
            return x, interior

        def integrand(u: np.ndarray, idx: np.ndarray) -> np.ndarray:
            rv = rr_b[idx][:, None]
            # Below u = 1e-4 the integrand is g'(r)/2 + O(u²); evaluating it there would divide
            # rounding noise of g(x) - g(r) by u², so the value at 1e-4 is used instead (the
            # neglected variation is ~1e-8 relative over an interval of length 1e-4).
            u = np.maximum(u, u_min[idx][:, None])
            x, interior = node_x(u, idx)
            sh = np.sinh(u)
            val = (profile._g(x, rtol) - gr_b[idx][:, None]) * (x / rv) / (rv * sh * sh)
            return np.where(interior | np.isfinite(val), val, 0.0)

        tail = (g_a[pos] - grp) / np.sqrt((ap - rp) * (ap + rp))
        # Each segment is judged against the magnitude of the whole S (~ g(a)/a), not its own
        # value: a segment that is exactly 0 (flat part) must not demand relative accuracy.
        # The g(x) - g(r) difference carries rounding noise ~ eps g(a)/r: tolerate it absolutely.
        scale = g_a[pos] / ap
        noise = 64 * np.finfo(float).eps * g_a[pos] / rp
        if profile._has("_g_prime_closed_form") and not cuts:
            # (with breakpoints the by-parts form is kept: g is bounded at a slope jump where g'
            # is singular, so node rounding near the breakpoint does not matter)
            def integrand(u: np.ndarray, idx: np.ndarray) -> np.ndarray:
                x, interior = node_x(u, idx)
                with np.errstate(divide="ignore", invalid="ignore"):
                    val = profile._g_prime_closed_form(x)
                # a node rounded onto a singular breakpoint carries no information: drop it
                return np.where(interior | np.isfinite(val), val, 0.0)
            tail = np.zeros_like(tail)
            noise = 0.0
        atol = np.broadcast_to(rtol * (np.abs(tail) + scale) + noise, lo.shape)
        quad = tanh_sinh(integrand, lo.ravel(), hi.ravel(), rtol=rtol, atol=atol.ravel())
        val[pos] = tail + quad.value.reshape(lo.shape).sum(axis=0)
        er[pos] = quad.error.reshape(lo.shape).sum(axis=0)
    if np.any(axis):
        # S(0, a) = g(a)/a + ∫_0^a g(x)/x² dx  (g(0) = 0), split at the breakpoints
        a0 = aa[axis]
        cuts = sorted({b for b in (*profile.breakpoints, profile.flat_radius) if b > 0})
        edges = np.stack([np.zeros_like(a0)] + [np.clip(np.full_like(a0, b), 0, a0) for b in cuts]
                         + [a0])
        lo0, hi0 = edges[:-1], edges[1:]

        def integrand0(x: np.ndarray, idx: np.ndarray) -> np.ndarray:
            return profile._g(x, rtol) / (x * x)

        scale0 = np.broadcast_to(rtol * g_a[axis] / a0, lo0.shape).ravel()
        res0 = tanh_sinh(integrand0, lo0.ravel(), hi0.ravel(), rtol=rtol, atol=scale0,
                         raise_on_failure=False)
        v0 = g_a[axis] / a0 + res0.value.reshape(lo0.shape).sum(axis=0)
        e0 = res0.error.reshape(lo0.shape).sum(axis=0)
        unconverged = e0 > 10 * rtol * np.abs(v0)
        if np.any(unconverged):
            # g(x)/x not vanishing at the axis (cone-like tip, n <= 1): p(0) is infinite
            tiny = a0[unconverged]
            h1 = profile._g(1e-12 * tiny, rtol) / (1e-12 * tiny)
            h2 = profile._g(1e-6 * tiny, rtol) / (1e-6 * tiny)
            divergent = (h1 > 0) & (h1 >= 0.5 * h2)
            if not np.all(divergent):
                raise ConvergenceError(
                    f"pressure at r=0 did not converge (estimate {v0[unconverged][0]:.6g}, error "
                    f"{e0[unconverged][0]:.3g}); loosen rtol.")
            v0[unconverged] = np.inf
            e0[unconverged] = 0.0
        val[axis] = v0
        er[axis] = e0
    out[inside] = val
    err[inside] = er
    return out, err


def abel_g(profile, r: np.ndarray, a: np.ndarray, rtol: float) -> tuple[np.ndarray, np.ndarray]:
    """``A(r, a) = (2/π) ∫_0^{asin(min(1,a/r))} g(r sinθ) dθ``; returns (value, error estimate)."""
    r, a = np.broadcast_arrays(np.asarray(r, float), np.asarray(a, float))
    if profile._has("_abel_g_closed_form"):
        return profile._abel_g_closed_form(r, a), np.zeros(r.shape)
    if profile.has("semi_analytic_abel_g"):   # with an error estimate, or None: decline
        res = profile._abel_g_semi_analytic(r, a, rtol)
        if res is not None:
            return res
    out = np.zeros(r.shape)
    err = np.zeros(r.shape)
    inside = (r <= a) & (r > 0)
    if np.any(inside) and profile._has("_height"):
        out[inside] = profile._height(r[inside])
    elif np.any(inside):
        out[inside] = profile.inverse_transform(r[inside], rtol)
    outside = r > a
    if np.any(outside):
        ro, ao = r[outside], a[outside]
        theta_max = np.arctan2(ao, np.sqrt((ro - ao) * (ro + ao)))   # asin(a/r), exact near r = a
        cuts = sorted({b for b in (*profile.breakpoints, profile.flat_radius) if b > 0})
        ts = [np.clip(np.arcsin(np.minimum(b / ro, 1.0)), 0.0, theta_max) for b in cuts]
        edges = np.stack([np.zeros_like(ro), *ts, theta_max])
        lo, hi = edges[:-1], edges[1:]
        r_b = np.broadcast_to(ro, lo.shape).ravel()

        def integrand(th: np.ndarray, idx: np.ndarray) -> np.ndarray:
            return profile._g(r_b[idx][:, None] * np.sin(th), rtol)

        res = tanh_sinh(integrand, lo.ravel(), hi.ravel(), rtol=rtol)
        out[outside] = 2 / np.pi * res.value.reshape(lo.shape).sum(axis=0)
        err[outside] = 2 / np.pi * res.error.reshape(lo.shape).sum(axis=0)
    return out, err


def pressure(profile, E_star: float, r: np.ndarray, a: np.ndarray, d: np.ndarray,
             g_a: np.ndarray, rtol: float) -> tuple[np.ndarray, np.ndarray]:
    """Contact pressure ``p(r)``, Pa (0 outside the contact), with the edge term for ``d != g(a)``."""
    r, a, d, g_a = np.broadcast_arrays(*(np.asarray(v, float) for v in (r, a, d, g_a)))
    shape, err = pressure_shape(profile, r, a, rtol)
    return pressure_from_shape(E_star, shape, err, r, a, d, g_a)


def pressure_from_shape(E_star: float, shape: np.ndarray, shape_err: np.ndarray, r: np.ndarray,
                        a: np.ndarray, d: np.ndarray, g_a: np.ndarray
                        ) -> tuple[np.ndarray, np.ndarray]:
    """Contact pressure (Pa) from its shape part: ``p = (E*/π) [S(r, a) + (d - g(a))/sqrt(a² - r²)]``.

    ``shape`` is ``S(r, a)`` (1/m, with error estimate ``shape_err``), read only inside the
    contact; all arrays broadcast together. Returns the pressure (0 outside the contact, ±inf at
    the edge itself where the edge term of a flat punch or JKR contact is singular) and its error
    estimate. Shared by :func:`pressure` and the fixed-radii tables of
    :mod:`contactlab.physics.ring_pressure`, so both give bit-identical values.
    """
    inside = r < a
    edge = d - g_a
    off = edge != 0
    if not off.any():
        # d = g(a) throughout (a smooth profile's contact): the edge term is 0.0 everywhere and
        # no point lies on a singular edge; the same values as below, without their arithmetic
        return (np.where(inside, E_star / np.pi * (shape + 0.0), 0.0),
                E_star / np.pi * np.asarray(shape_err, float))
    with np.errstate(divide="ignore", invalid="ignore"):
        edge_term = np.where(inside & off,
                             edge / np.sqrt(np.maximum((a - r) * (a + r), 0.0)), 0.0)
    out = np.where(inside, E_star / np.pi * (shape + edge_term), 0.0)
    at_edge = (r == a) & (a > 0) & off
    out = np.where(at_edge, np.copysign(np.inf, edge), out)
    return out, E_star / np.pi * np.asarray(shape_err, float)


def displacement(profile, r: np.ndarray, a: np.ndarray, d: np.ndarray,
                 rtol: float) -> tuple[np.ndarray, np.ndarray]:
    """Normal surface displacement ``u_z(r)``, m, inside (``d - f``) and outside the contact.

    ``asin(a/r)`` is taken as ``atan2(a, sqrt((r-a)(r+a)))``: near the edge ``a/r`` rounds to
    within an ulp of 1, where ``asin`` amplifies that rounding to ~1e-8; the differences
    ``r - a`` are exact there.
    """
    r, a, d = np.broadcast_arrays(*(np.asarray(v, float) for v in (r, a, d)))
    shape = r.shape
    # 1D inside: profile hooks assign into boolean-indexed parts, which a 0-d array cannot take
    r, a, d = (v.reshape(-1) for v in (r, a, d))
    A, err = abel_g(profile, r, a, rtol)
    outside = r > a
    ang = np.full(r.shape, 0.5 * np.pi)
    ro, ao = r[outside], a[outside]
    ang[outside] = np.arctan2(ao, np.sqrt((ro - ao) * (ro + ao)))
    out = 2.0 / np.pi * d * ang - A
    out = np.where(a > 0, out, 0.0)
    return out.reshape(shape), np.asarray(err, float).reshape(shape)


def g_squared_integral(profile, a: np.ndarray, rtol: float) -> np.ndarray:
    """``∫_0^a g(x)² dx``, m³ (closed form where the profile has one)."""
    if profile._has("_g_squared_integral_closed_form"):
        return profile._g_squared_integral_closed_form(a)
    a = np.asarray(a, float)

    def integrand(x: np.ndarray, idx: np.ndarray) -> np.ndarray:
        return profile._g(x, rtol) ** 2

    lo = np.broadcast_to(profile.flat_radius, a.shape).astype(float)
    lo = np.minimum(lo, a)
    # split at the profile's breakpoints (g has kinks there)
    cuts = sorted({b for b in profile.breakpoints if b > 0})
    edges = np.stack([lo] + [np.clip(np.full(a.shape, b), lo, a) for b in cuts] + [a])
    table = profile.has("node_table") and not cuts
    atol: float | np.ndarray = 0.0
    if table and profile.has("linear_table"):
        # the square-root kinks of g at thousands of nodes keep the rule from converging to
        # rtol: without a floor it ran to its last level (9217 nodes per integral, each g
        # costing O(N): minutes on 10^6-point tables); a hundredth of the table's resolution
        # stops it at ~1153 nodes (measured true error 3.5e-7 relative on a random
        # 10^5-point table, floor 1.3e-5)
        atol = 0.01 * table_floor(profile, a, a * profile._g(a) ** 2)
        atol = np.broadcast_to(atol, edges[:-1].shape).ravel()
    res = tanh_sinh(integrand, edges[:-1].ravel(), edges[1:].ravel(), rtol=rtol, atol=atol,
                    raise_on_failure=not table)
    value = res.value.reshape(edges[:-1].shape).sum(axis=0)
    if table:
        # a table too fine to split at every node: g has a kink at each of them, which the
        # quadrature resolves only down to the table's own resolution (∫g² <= a g(a)²)
        err = res.error.reshape(edges[:-1].shape).sum(axis=0)
        missed = err > rtol * np.abs(value) + table_floor(profile, a, a * profile._g(a) ** 2)
        if np.any(missed):
            from ..errors import ConvergenceError
            i = int(np.argmax(missed))
            raise ConvergenceError(
                f"∫g² over [0, {a.ravel()[i]!r}] m: quadrature error estimate "
                f"{err.ravel()[i]:.3g} for {value.ravel()[i]:.6g} exceeds the table's "
                f"resolution (rtol={rtol:g}).")
    return value


def table_floor(profile, x: np.ndarray, scale: np.ndarray) -> np.ndarray:
    """Absolute floor ``scale · min(max((h/x)², 1e-3 h/x), 1)`` of a quadrature over ``[0, x]``
    of a table's g.

    ``h`` is the largest node spacing below ``x``: the interpolant is known only to the table's
    resolution (relative ``(h/x)²`` for data sampled from a smooth surface), and the kinks of g at
    thousands of nodes keep an adaptive quadrature from converging much beyond it: its error
    falls only about linearly in ``h`` (∫g² on uniform tables: 7e-8 relative at 10^4 points,
    9.5e-10 at 10^6, where ``(h/x)²`` is 1.2e-10), which ``1e-3 h/x`` covers.
    """
    nodes = profile.table_nodes()
    gaps = np.maximum.accumulate(np.diff(nodes))
    k = np.clip(np.searchsorted(nodes, x, side="left") - 1, 0, gaps.size - 1)
    with np.errstate(divide="ignore", invalid="ignore"):
        # q clipped at 1 first: the result is the same and q² cannot overflow at tiny x
        q = np.minimum(gaps[k] / np.where(x > 0, x, 1.0), 1.0)
        rel = np.where(x > 0, np.maximum(q * q, 1e-3 * q), 0.0)
    return np.abs(scale) * rel


def elastic_energy(E_star: float, a: np.ndarray, d: np.ndarray, g_int: np.ndarray,
                   g2_int: np.ndarray) -> np.ndarray:
    """Stored elastic energy ``E* ∫_{-a}^{a} (d-g)²/2 dx = E* (a d² - 2 d ∫g + ∫g²)``, J."""
    return E_star * (a * d * d - 2.0 * d * g_int + g2_int)


# ---------------------------------------------------------------------------- normal solves
def force_of_radius(profile, E_star: float, a: np.ndarray, rtol: float) -> np.ndarray:
    """Non-adhesive force at contact radius ``a``: ``2E*(a g(a) - ∫_0^a g)`` [S eq. 8], N."""
    return 2.0 * E_star * (a * profile._g(a, rtol) - profile._g_integral(a, rtol))


def _power_radius(profile, E_star: float, F: np.ndarray, term: tuple) -> np.ndarray:
    """Contact radius of forces ``F > 0`` on one power term ``(c, n)``: ``F/(2E*) = κ c n
    a^(n+1)/(n+1)`` inverted, in the operations of the scalar route
    (:mod:`contactlab.physics.normal_scalar`), so that both give the same radius; a
    paraboloid's ``a = cbrt(F/K)`` (:meth:`~contactlab.profiles.Paraboloid._hertz_force_constants`)."""
    hertz = getattr(profile, "_hertz_force_constants", None)
    if hertz is not None:
        # a paraboloid: F = K a³ with one constant K (Paraboloid._hertz_force_constants)
        return root_of_ratio(F, hertz(E_star)[0], 3.0)
    c, n = term
    n1 = n + 1.0
    x = F / (2.0 * E_star)
    x *= n1
    # (x / (κ c n))**(1/(n+1)), in logarithms where the quotient leaves the float range; x is
    # this function's own array, so the quotient and its root may take its buffer
    return root_of_ratio(x, profile._power_kappa(n) * c * n, n1, overwrite=True)


def radius_depth_of_force(profile, E_star: float, F: np.ndarray, rtol: float
                          ) -> tuple[np.ndarray, np.ndarray]:
    """Contact radius and depth (m) of non-adhesive normal forces ``F`` (N), any shape.

    Single power terms invert ``F(a)`` in closed form; a profile declaring
    ``"reduced_force_solver"`` solves itself; otherwise a bracket is grown from
    ``profile._initial_bracket()`` and refined by a bracketed root (never silently inexact).
    At a punch wall the depth follows from ``F = 2E*(b d - ∫_0^b g)``.

    Raises
    ------
    OutsideTheoryError
        The force needs a contact radius beyond ``profile.max_radius``, or g decreases
        (a ring contact).
    ConvergenceError
        The bracketed solve failed.
    """
    E = E_star
    terms = profile.power_terms()
    if (terms is not None and len(terms) == 1 and not np.isfinite(profile.wall_radius)
            and F.ndim and F.size and float(np.min(F)) > 0):
        # every force positive on a single power term (a gait): the closed form below without
        # the masks and scatters (the same values)
        a = _power_radius(profile, E, F, terms[0])
        d = profile._g(a, rtol)
        if profile._has("_check_monotone_upto"):    # (the base hook checks nothing)
            profile._check_monotone_upto(float(np.max(a)), float(np.max(d)))
        return a, d
    if (profile.has("reduced_force_solver") and not profile.has("reduced_force_state")
            and terms is None and not np.isfinite(profile.wall_radius)
            and F.ndim and F.size and float(np.min(F)) > 0):
        # every force positive on a profile solving its own radius (the exact sphere): the
        # branch below without its masks, copies and scatters (the same values)
        a = profile._radius_of_reduced_force(F / (2 * E), rtol)
        if a is not None:
            d = profile._g(a, rtol)
            if profile._has("_check_monotone_upto"):
                profile._check_monotone_upto(float(np.max(a)), float(np.max(d)))
            return a, d
    a = np.zeros(F.shape)
    d = np.zeros(F.shape)
    pos = F > 0
    if not np.any(pos):
        return a, d
    Fp = F[pos]
    ap = np.zeros(Fp.shape)
    solve = np.ones(Fp.shape, dtype=bool)
    walled = np.isfinite(profile.wall_radius)
    if walled:
        b = profile.wall_radius
        F_wall = (float(force_of_radius(profile, E, np.array(b), rtol))
                  if profile.flat_radius < b else 0.0)
        at_wall = Fp >= F_wall
        ap[at_wall] = b
        solve = ~at_wall
        limit = b
    else:
        limit = profile.max_radius
    if np.any(solve):
        Fs = Fp[solve]
        terms = profile.power_terms()
        fast = (profile._radius_of_reduced_force(Fs / (2 * E), rtol)
                if profile.has("reduced_force_solver") else None)
        if terms is not None and len(terms) == 1 and not walled:
            ap[solve] = _power_radius(profile, E, Fs, terms[0])
        elif profile.has("reduced_force_state") and not walled:
            pass                        # radius and depth below, in closed form
        elif fast is not None:          # profile-specific solver (convex linear tables)
            ap[solve] = fast
        else:
            lo = np.full(Fs.shape, profile.flat_radius)
            hi = np.full(Fs.shape, profile._initial_bracket())
            if (rtol >= LOOSE_RTOL and profile.g_route == "quadrature"
                    and profile._has("_height")):
                # at a loose rtol the first bracket from a lower bound of the force on f
                # (radius_bounds), checked by the loop below, instead of growing it from the
                # initial bracket with one force (two quadratures) per factor 4
                hb = upper_radius_from_f(profile, Fs / (2 * E), profile._initial_bracket(),
                                         limit * (1 - 1e-15) if np.isfinite(limit) else np.inf,
                                         "force")
                hi = np.where(np.isfinite(hb), hb, hi)
            F_top = np.full(Fs.shape, np.nan)
            for _ in range(400):
                hi_c = np.minimum(hi, limit * (1 - 1e-15)) if np.isfinite(limit) else hi
                F_hi = force_of_radius(profile, E, hi_c, rtol)
                short = F_hi < Fs
                if not np.any(short):
                    hi = hi_c
                    # a root far below the first bracket (forces of 1e-100 N): tightened
                    lo, hi, F_top = shrink_bracket(
                        lambda x, idx: force_of_radius(profile, E, x, rtol), Fs, lo, hi, F_hi)
                    break
                at_limit = short & (hi_c >= limit * (1 - 1e-15))
                if np.any(at_limit) and not walled:
                    i = int(np.argmax(at_limit))
                    raise OutsideTheoryError(
                        f"force={float(Fs[i])!r} N needs a contact radius >= max_radius={limit!r} m "
                        f"of {profile!r}; reduce the force.")
                lo = np.where(short, hi_c, lo)
                hi = np.where(short, hi * 4.0, hi)
            step0, ftol = None, 0.0
            if (rtol >= LOOSE_RTOL and profile.g_route == "quadrature"
                    and profile._has("_height")):
                # the first point where the bound of the force on f, scaled to the force at
                # hi, meets the request; and a stop once the force is that close to it
                step0 = first_step_from_f(
                    profile, Fs / (2 * E), lo, hi, F_top / (2 * E), profile._initial_bracket(),
                    limit * (1 - 1e-15) if np.isfinite(limit) else np.inf, "force")
                ftol = force_ftol(rtol)
            ap[solve] = bracketed_root(lambda x, idx: force_of_radius(profile, E, x, rtol), Fs, lo,
                                       hi, rtol=root_rtol(rtol), ftol=ftol, what="contact radius",
                                       first_step=step0)
    if walled:
        dp = np.where(ap >= profile.wall_radius,
                      (Fp / (2 * E) + profile._g_integral(ap, rtol)) / ap, profile._g(ap, rtol))
    elif profile.has("reduced_force_state"):
        # radius and depth together in closed form: next to the rim of a flat part the radius
        # rounds onto the rim and g(radius) would lose the depth (and the force) entirely
        ap, dp = profile._radius_depth_of_reduced_force(Fp / (2 * E))
    else:
        dp = profile._g(ap, rtol)
    a[pos] = ap
    d[pos] = dp
    if profile._has("_check_monotone_upto"):
        profile._check_monotone_upto(float(np.max(ap)), float(np.max(dp)))
    return a, d


def solve(profile, E_star: float, control: str, value: np.ndarray, rtol: float, *,
          error_estimate: bool | str = True, extremes: tuple[float, float] | None = None
          ) -> tuple[np.ndarray, np.ndarray, np.ndarray, Any]:
    """Non-adhesive normal contact for one control, with the force's relative error estimate.

    Parameters
    ----------
    profile : Profile
    E_star : float
        Effective modulus, Pa.
    control : {"depth", "force", "radius"}
    value : ndarray
        Depths (m), forces (N) or contact radii (m >= 0, below ``profile.max_radius``; not for
        a punch with a wall), validated by the caller.
    rtol : float
        Tolerance of every numeric route.
    error_estimate : bool or "lazy"
        Compute ``force_rel_error`` (default). ``False`` skips its arithmetic and returns
        ``None`` in its place (callers that discard it: the per-step normal states of a load
        path). ``"lazy"``: where ``∫g`` is exact (a closed form, whose error is its rounding
        floor) a callable of no arguments that computes the estimate when called (the same
        values, bit for bit, as ``True`` gives: a batched state pays for it only when it is read);
        the array itself on the quadrature routes. Depth, radius and force are bit-identical
        whichever is asked.
    extremes : (float, float), optional
        ``(min(value), max(value))`` where the caller has reduced them (the passes of a
        paraboloid under force control then reduce nothing); they do not change the results.

    Returns
    -------
    depth, radius, force, force_rel_error : ndarray
        Same shape as ``value`` (``force_rel_error`` is ``None`` with ``error_estimate=False``).
        The error sums the quadrature estimate of ``∫g``, the rounding of ``a d - ∫g`` and,
        under force control, the residual against the requested force; errors of ``a`` enter
        ``F`` only at second order (``dF/da = 2E*(d - g(a)) = 0``).
    """
    E = E_star
    g_a_err: np.ndarray | None = None
    if control == "depth":
        d = value
        a = profile._radius_of_depth(d, rtol)
    elif control == "radius":
        a = value.copy()
        small = a < profile.flat_radius
        a[small] = np.where(a[small] > 0, profile.flat_radius, 0.0)
        g_a, g_a_err = profile._g_with_error(a, rtol)
        d = np.where(a > 0, g_a, 0.0)
        profile._check_monotone_upto(float(np.max(a, initial=0.0)), float(np.max(d, initial=0.0)))
    else:
        if (error_estimate == "lazy" and value.size >= _fused.FUSED_FROM
                and type(profile) is Paraboloid):
            fused = _solve_force_fused(profile, E, value, rtol,
                                       _fused.backend() == "numba" or "numpy", extremes)
            if fused is not None:
                return fused
        a, d = radius_depth_of_force(profile, E, value, rtol)
        if getattr(profile, "_hertz_force_constants", None) is not None:
            return _hertz_state(profile, E, value, a, d, rtol, error_estimate)
    all_pos = a.size == 0 or bool(a.min() > 0)     # (one reduction, no mask)
    lazy = error_estimate == "lazy" and profile._g_integral_is_exact()
    if error_estimate and not lazy:
        g_int, g_int_err = profile._g_integral_with_error(a, rtol)
    else:
        g_int = profile._g_integral(a, rtol)
    if lazy:
        # F in one new array; a·d is recomputed (the same product) when the estimate is read
        F = np.multiply(a, d)
        if isinstance(F, np.ndarray):
            F -= g_int
            F *= 2.0 * E
        else:
            F = (F - g_int) * (2.0 * E)
        ad = F       # (unused below: recomputed by pending)
    else:
        ad = a * d
        F = ad - g_int
        F *= 2.0 * E
    if not all_pos:
        F = np.where(a > 0, F, 0.0)
    if not error_estimate:
        return np.asarray(d, float), np.asarray(a, float), F, None
    if lazy:
        # the exact routes' ∫g error is its rounding floor (Profile._g_integral_with_error):
        # recomputed from ∫g itself when the estimate is read; a force request is copied (the
        # caller's array may change before then)
        req = value.copy() if control == "force" and not all_pos else None
        resid = None
        reuse = False
        if control == "force" and all_pos:
            # every force requested is positive: the residual |F - F_req| is the whole
            # force-control term, kept (the caller reads it too: pending.residual). It takes
            # the buffer of ∫g when nothing else holds that array (then ∫g, a pure function of
            # the radius, is recomputed if the estimate is read): one new array fewer
            reuse = _is_own_temporary(g_int, np.shape(F))
            # (a 0-d request gives numpy scalars: the residual is then made a 0-d array; an
            # array difference is the residual's own new array, not copied again)
            resid = np.subtract(F, value, out=g_int) if reuse else np.subtract(F, value)
            if not isinstance(resid, np.ndarray):
                resid = np.array(resid, dtype=float)
            np.abs(resid, out=resid)
        kept = None if reuse else g_int
        del g_int

        def pending() -> np.ndarray:
            gi = profile._g_integral(a, rtol) if kept is None else kept
            return _force_rel_error(E, control, a, a * d, gi, ROUNDING * np.abs(gi), F,
                                    all_pos, req, g_a_err, resid)
        pending.residual = resid            # type: ignore[attr-defined]
        return np.asarray(d, float), np.asarray(a, float), F, pending
    return (np.asarray(d, float), np.asarray(a, float), F,
            _force_rel_error(E, control, a, ad, g_int, g_int_err, F, all_pos, value,
                             g_a_err))


def _hertz_state(profile, E: float, value: np.ndarray, a: np.ndarray, d: np.ndarray,
                 rtol: float, error_estimate: bool | str
                 ) -> tuple[np.ndarray, np.ndarray, np.ndarray, Any]:
    """:func:`solve`'s force route on a paraboloid from its radii and depths: the force of the
    state is the request itself (zero where it is not positive: no contact); the estimate
    (:func:`_hertz_rel_error`) carries the residual ``|F(a, d) - F|`` by which ``(a, d)`` miss
    it, which the lazy estimate also hands to the caller's request check
    (``pending.residual``)."""
    F = np.where(a > 0, value, 0.0)
    d, a = np.asarray(d, float), np.asarray(a, float)
    if not error_estimate:
        return d, a, F, None
    all_pos = a.size == 0 or bool(a.min() > 0)
    ad = a * d
    c_f = profile._hertz_force_constants(E)[1]
    resid = np.abs(ad * c_f - F)
    if not bool(np.all(resid <= _fused.FORCE_SANITY * F)):
        # (a, d) miss the request (a depth beyond the floats): the force of (a, d) is
        # reported where they do, so that the caller's request check sees it
        F = np.where(resid <= _fused.FORCE_SANITY * F, F, ad * c_f)
    if error_estimate == "lazy":
        def pending() -> np.ndarray:
            return _hertz_rel_error(profile, E, a, d, F, all_pos, rtol, resid)
        pending.residual = resid            # type: ignore[attr-defined]
        return d, a, F, pending
    return d, a, F, _hertz_rel_error(profile, E, a, d, F, all_pos, rtol, resid)


def _hertz_rel_error(profile, E: float, a: np.ndarray, d: np.ndarray, F: np.ndarray,
                     all_pos: bool, rtol: float, resid: np.ndarray | None = None
                     ) -> np.ndarray:
    """The relative force error of a paraboloid's force-controlled state, whose force ``F`` is
    the request: the rounding of ``a d - ∫g`` and of ``∫g`` (:func:`_force_rel_error`) and the
    residual ``|F(a, d) - F|`` of the state's radius and depth (``resid`` where the caller
    has it), ``F(a, d) = (a·d)·c``
    (:meth:`~contactlab.profiles.Paraboloid._hertz_force_constants`; 0 where there is no
    contact: ``a = d = F = 0``)."""
    ad = a * d
    gi = profile._g_integral(a, rtol)
    if resid is None:
        resid = np.abs(ad * profile._hertz_force_constants(E)[1] - F)
    return _force_rel_error(E, "force", a, ad, gi, ROUNDING * np.abs(gi), F, all_pos, None,
                            None, resid)


def _solve_force_fused(profile, E: float, value: np.ndarray, rtol: float,
                       compiled: bool | str = True,
                       extremes: tuple[float, float] | None = None
                       ) -> tuple[np.ndarray, np.ndarray, np.ndarray, Any] | None:
    """:func:`solve`'s lazy force route on a paraboloid by the passes of
    :func:`contactlab.physics.normal_fused.paraboloid_force` (compiled, or ``"numpy"``: the
    same values, bit for bit), or None where they decline. The pending estimate carries the
    residual (``pending.residual``) and ``pending.checked = True``: every force is finite and
    within :data:`~contactlab.physics.normal_fused.FORCE_SANITY` of its request (the caller's
    checks, made in the passes)."""
    if profile.g_route != "closed_form" or np.isfinite(profile.wall_radius):
        return None
    res = _fused.paraboloid_force(profile, E, value, compiled, extremes)
    if res is None:
        return None
    a, d, F = res

    def pending() -> np.ndarray:
        return _hertz_rel_error(profile, E, a, d, F, True, rtol)
    pending.checked = True              # type: ignore[attr-defined]
    return d, a, F, pending


def _is_own_temporary(v: Any, shape: tuple[int, ...]) -> bool:
    """Whether ``v`` is a float64 array of ``shape`` owning its writeable data that nothing but
    the caller's one local variable refers to, so that the caller may write into it: by the
    interpreter's reference count (a profile's cache of the array, or a view of it, would hold
    another reference), compared with that of a probe array held the same way
    (:data:`_OWN_REFS`). Without reference counts (not CPython): False."""
    return (_OWN_REFS > 0 and type(v) is np.ndarray and v.dtype == np.float64
            and v.shape == shape and v.flags.owndata and v.flags.writeable
            and v.flags.c_contiguous and sys.getrefcount(v) == _OWN_REFS)


def _probe_own_refs() -> int:
    probe = np.empty(1)
    return _refs_of(probe)


def _refs_of(v: Any) -> int:
    return sys.getrefcount(v) if hasattr(sys, "getrefcount") else 0


#: the reference count :func:`_is_own_temporary` sees for an array held by one local variable
#: of its caller (0 where the interpreter keeps none)
_OWN_REFS = _probe_own_refs()


def _force_rel_error(E: float, control: str, a: np.ndarray, ad: np.ndarray, g_int: np.ndarray,
                     g_int_err: np.ndarray, F: np.ndarray, all_pos: bool,
                     value: np.ndarray | None, g_a_err: np.ndarray | None,
                     residual: np.ndarray | None = None) -> np.ndarray:
    """The relative force error of :func:`solve` (see there) from its parts (``residual``:
    ``|F - value|`` when every requested force is positive, the same values as from
    ``value``)."""
    F_err = np.abs(ad)
    F_err += np.abs(g_int)
    F_err *= ROUNDING
    F_err += np.abs(g_int_err)
    F_err *= 2.0 * E
    if not all_pos:
        F_err = np.where(a > 0, F_err, 0.0)
    if control == "force" and residual is not None:
        F_err = F_err + residual
    elif control == "force":
        assert value is not None
        F_err = F_err + np.where(value > 0, np.abs(F - value), 0.0)
    elif control == "radius":       # the depth g(a) itself carries the error of g
        assert g_a_err is not None
        F_err = F_err + np.where(a > 0, 2.0 * E * a * np.abs(g_a_err), 0.0)
    with np.errstate(divide="ignore", invalid="ignore"):
        rel = F_err / F
    if not all_pos or rel.ndim == 0:
        rel = np.where(F > 0, rel, 0.0)
    return rel
