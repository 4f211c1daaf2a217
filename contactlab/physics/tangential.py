"""Cattaneo–Mindlin tangential contact through the MDR: pure, vectorised kernels.

[Cat38, Min49, H1, PH]; theory §5. The normal load is constant and non-adhesive
(``d = g(a)``, or ``d >= g(b)`` for a flat punch). MDR springs ``Δk_x = G*Δx`` stick while
``G*|u_x1D| < μE*(d - g(x))``. With ``h(x) = μE*(d - g(x))``:

* stick radius at displacement ``u``: ``g(c) = d - G*|u|/(μE*)`` (``c = 0`` at and beyond
  full slip ``u* = μE* (d - g(0))/G*``);
* force ``F_x = μ [F_N(a) - F_N(c)]`` with ``F_N(c) = 2E*(c g(c) - ∫_0^c g)``;
* traction ``τ = μ [p_a(r) - p_c(r)]`` for ``r < c`` and ``μ p_a(r)`` for ``c < r < a``;
* dissipation on the virgin curve ``D(u) = 2∫_c^a h (|u| - h/G*) dx``; Masing branches dissipate
  ``2 D(δ/2)`` over an excursion ``δ`` from their turning point.

No function here validates its input (hot path); callers do.
"""
from __future__ import annotations

import numpy as np

from . import edge_annulus as _edge
from . import normal as _normal

__all__ = ["stick_radius_of_displacement", "displacement_of_stick_radius", "force_of_stick_radius",
           "force_of_displacement",
           "stick_radius_of_force", "virgin_dissipation", "shear", "full_slip_displacement",
           "slip_integral",
           "pressure_shape_difference_on_axis", "AXIS_RATIO"]


def _g0(profile, x: np.ndarray) -> np.ndarray:
    """``g`` with ``g(0) = 0`` guarded (profiles are called with x > 0 only where it matters)."""
    x = np.asarray(x, float)
    return np.where(x > 0, profile._g(np.maximum(x, 1e-300)), 0.0)


def _gint0(profile, x: np.ndarray) -> np.ndarray:
    x = np.asarray(x, float)
    return np.where(x > 0, profile._g_integral(np.maximum(x, 1e-300)), 0.0)


def full_slip_displacement(E_star: float, G_star: float, mu: float, d: np.ndarray) -> np.ndarray:
    """``u* = μE* d / G*``, m: the displacement at which the whole contact slides (g(0) = 0)."""
    return mu * E_star * np.asarray(d, float) / G_star


def stick_radius_of_displacement(profile, E_star: float, G_star: float, mu: float, a: np.ndarray,
                                 d: np.ndarray, u: np.ndarray) -> np.ndarray:
    """Stick radius ``c``, m, of the virgin curve at displacement magnitude ``|u|``.

    Solves ``g(c) = d - G*|u|/(μE*)`` [theory §5]; ``c = a`` at ``u = 0`` and ``c = 0`` at and
    beyond full slip. For a flat punch, ``c`` stays at the punch radius until full slip.
    """
    a, d, u = np.broadcast_arrays(*(np.asarray(v, float) for v in (a, d, u)))
    target = d - G_star * np.abs(u) / (mu * E_star)
    c = np.zeros(a.shape)
    pos = target > 0
    if np.any(pos):
        c[pos] = profile._radius_of_depth(target[pos])
    return np.minimum(np.where(np.abs(u) == 0, a, c), a)


def displacement_of_stick_radius(profile, E_star: float, G_star: float, mu: float, d: np.ndarray,
                                 c: np.ndarray) -> np.ndarray:
    """Virgin-curve displacement ``u = μE*(d - g(c))/G*``, m, for stick radius ``c``."""
    return mu * E_star * (np.asarray(d, float) - _g0(profile, c)) / G_star


def force_of_stick_radius(profile, E_star: float, mu: float, a: np.ndarray, d: np.ndarray,
                          c: np.ndarray) -> np.ndarray:
    """Virgin-curve tangential force ``μ[F_N(a) - F_N(c)]``, N [theory §5].

    Valid where the stick boundary satisfies ``G*u = μE*(d - g(c))`` (smooth profiles); for a
    stick zone held at a punch wall use :func:`force_of_displacement`.
    """
    a, d, c = np.broadcast_arrays(*(np.asarray(v, float) for v in (a, d, c)))
    # μ[F_N(a) - F_N(c)] = 2μE*[c (d - g(c)) + ∫_c^a (d - g) dx], the second form without the
    # cancellation of the first as c -> a
    return 2.0 * mu * E_star * (c * (d - _g0(profile, c)) + slip_integral(profile, a, c, d))


def force_of_displacement(profile, E_star: float, G_star: float, mu: float, a: np.ndarray,
                          d: np.ndarray, u: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Virgin-curve force magnitude and stick radius at displacement ``|u|`` (any profile).

    ``F_x = 2G*c|u| + 2μE* ∫_c^a (d - g) dx`` — the MDR spring sum; it equals
    ``μ[F_N(a) - F_N(c)]`` for smooth profiles and ``2G*b|u|`` for a flat punch before full slip.
    """
    a, d, u = np.broadcast_arrays(*(np.asarray(v, float) for v in (a, d, u)))
    u = np.abs(u)
    c = stick_radius_of_displacement(profile, E_star, G_star, mu, a, d, u)
    slip = slip_integral(profile, a, c, d)
    F = 2.0 * G_star * c * u + 2.0 * mu * E_star * np.maximum(slip, 0.0)
    # a stick zone within EDGE_FORCE_RATIO a of a smooth edge: the no-slip force minus the
    # annulus correction (the form above reads the normal solve's rounding d - g(a) as a punch
    # step there, an error growing like 1/u)
    thin = (c > a * (1.0 - _edge.EDGE_FORCE_RATIO)) & (u > 0) & (a > 0)
    if np.any(thin):
        F = _edge_any_override(profile, E_star, G_star, mu, np.where(thin, a, 0.0), u, F, 1,
                               _edge.EDGE_FORCE_RATIO)
    return F, c


#: slip-zone width ``(a - c)/a`` below which :func:`slip_integral` also integrates across a
#: breakpoint of the profile (split there: the pieces then end at the kink of ``g``, where the
#: rule converges only algebraically, ~3e-5 of the slip term; the slip term is ~(a - c)/(2a)
#: of the force, so this costs < 2e-11 of it, against ``ε a/(a - c)`` > 2e-10 for the closed
#: form there)
TINY_SLIP_RATIO = 1e-6
#: breakpoints handled inside one slip zone by :func:`slip_integral` (more: the closed form)
_MAX_PIECES = 4


def slip_integral(profile, a: np.ndarray, c: np.ndarray, d: np.ndarray) -> np.ndarray:
    """``∫_c^a (d - g(x)) dx`` for ``0 <= c <= a``, m² (the slip zone's share of the force,
    divided by ``μE*``).

    In closed form ``d (a - c) - (∫_0^a g - ∫_0^c g)``, which cancels as ``c -> a``: its
    absolute error ``ε d a`` made the force at ``u -> 0`` hundreds of times the no-slip force
    ``2G* a u`` (the exact slip term vanishes as ``u²``). Slip zones narrower than
    ``SMALL_SLIP_RATIO a`` (and than that fraction of the distance to ``max_radius``) are
    integrated directly by 16-point Gauss-Legendre on ``[c, a]``: each node's ``d - g(x)`` is
    good to ``ε d`` absolutely, so the error is ``ε d (a - c)``, relative ``ε`` of the force.
    A breakpoint within one slip-zone width of ``[c, a]`` would spoil the rule's convergence:
    such zones keep the closed form unless narrower than ``TINY_SLIP_RATIO a``, where the
    interval is split at the breakpoints inside it.
    """
    a, c, d = np.broadcast_arrays(*(np.asarray(v, float) for v in (a, c, d)))
    shape = a.shape
    a, c, d = a.ravel(), c.ravel(), d.ravel()
    L = a - c
    out = d * L - (_gint0(profile, a) - _gint0(profile, c))
    cand = (L > 0) & (L <= SMALL_SLIP_RATIO * a) & (c >= profile.flat_radius)
    if np.isfinite(profile.max_radius):
        cand &= L <= SMALL_SLIP_RATIO * (profile.max_radius - a)
    bp = np.array(sorted({b for b in (*profile.breakpoints, profile.flat_radius) if b > 0}))
    pieces = 1
    if bp.size:
        near = np.searchsorted(bp, a + L, "left") > np.searchsorted(bp, c - L, "right")
        inside = np.searchsorted(bp, a, "left") - np.searchsorted(bp, c, "right")
        cand &= ~near | ((L <= TINY_SLIP_RATIO * a) & (inside <= _MAX_PIECES))
        if np.any(cand & near):
            pieces = 1 + min(_MAX_PIECES, bp.size)
    if np.any(cand):
        ai, ci, di = a[cand], c[cand], d[cand]
        if pieces == 1:
            edges = np.stack([ci, ai])
        else:
            j = np.searchsorted(bp, ci, "right")[None, :] + np.arange(pieces - 1)[:, None]
            inner = np.where(j < bp.size, bp[np.minimum(j, bp.size - 1)], np.inf)
            edges = np.concatenate([ci[None], np.minimum(inner, ai[None]), ai[None]])
        lo, hi = edges[:-1], edges[1:]
        x = lo[..., None] + 0.5 * (hi - lo)[..., None] * (_GL_X + 1.0)
        h = di[None, :, None] - profile._g(x)
        out[cand] = (0.5 * (hi - lo) * (h @ _GL_W)).sum(axis=0)
    return out.reshape(shape)


def stick_radius_of_force(normal_force_inverse, mu: float, F_normal: np.ndarray,
                          T: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Stick radius and ``g(c)`` for a virgin-curve tangential force magnitude ``T < μF_N``.

    ``normal_force_inverse(F) -> (radius, depth)`` is the non-adhesive normal solve of the same
    profile; ``F_N(c) = F_N(a) - T/μ``.
    """
    return normal_force_inverse(np.asarray(F_normal, float) - np.abs(np.asarray(T, float)) / mu)


def virgin_dissipation(profile, E_star: float, G_star: float, mu: float,
                       a: np.ndarray | float, d: np.ndarray | float, u: np.ndarray,
                       rtol: float) -> np.ndarray:
    """Energy dissipated on the virgin curve from 0 to ``|u|``, J.

    ``D = 2∫_c^a h(|u| - h/G*) dx`` with ``h = μE*(d - g)``; uses ``∫g`` and ``∫g²``. A thin
    slip annulus (``σ_c < EDGE_SLIP_RATIO a``) takes the annulus form of
    :mod:`~contactlab.physics.edge_annulus` (accurate to rounding down to amplitudes of one ulp;
    the forms from ``∫g``, ``∫g²`` err by ``~ε a/σ_c`` and their quadratures need not converge
    on an interval of a few ulps next to a table node), the rest the forms below.
    """
    a, d, u = np.broadcast_arrays(*(np.asarray(v, float) for v in (a, d, u)))
    shape = a.shape
    af, df, uf = (np.ravel(v) for v in (a, d, np.abs(u)))
    out = np.zeros(af.shape)
    thin = np.zeros(af.shape, bool)
    live = np.flatnonzero((af > 0) & (uf > 0) & np.isfinite(uf))
    pw = _edge.power_edge(profile)
    edge = None if pw is not None or live.size == 0 else _edge.edge_of(profile)
    if live.size and (pw is not None or edge is not None):
        if pw is not None:
            D, s_c = _edge.shift_dissipation(*pw, E_star, G_star, mu, af[live], uf[live])
        elif edge is not None:
            # any other profile: the drop g(a) - g(a - σ) integrated from g' on the annulus
            D, _, s_c = _edge.shift_any(edge, E_star, G_star, mu, af[live], uf[live])
        t = s_c < _edge.EDGE_SLIP_RATIO
        out[live[t]] = D[t]
        thin[live[t]] = True
    rest = ~thin & (uf != 0)                   # no shift: no dissipation
    if np.all(rest):
        return _virgin_stick_form(profile, E_star, G_star, mu, a, d, u, rtol)
    if np.any(rest):
        out[rest] = _virgin_stick_form(profile, E_star, G_star, mu, af[rest], df[rest],
                                       uf[rest], rtol)
    return out.reshape(shape)


def _virgin_stick_form(profile, E_star, G_star, mu, a, d, u, rtol) -> np.ndarray:
    """:func:`virgin_dissipation` at the stick radius (closed form from ``∫g``, ``∫g²``; by
    Gauss-Legendre on ``[c, a]`` for slip zones up to ``SMALL_SLIP_RATIO a``)."""
    u = np.abs(u)
    c = stick_radius_of_displacement(profile, E_star, G_star, mu, a, d, u)
    L = a - c
    dG = _gint0(profile, a) - _gint0(profile, c)

    def g2(x: np.ndarray) -> np.ndarray:
        return np.where(x > 0, _normal.g_squared_integral(profile, np.maximum(x, 1e-300), rtol),
                        0.0)

    dG2 = g2(a) - g2(c)
    h1 = mu * E_star * (d * L - dG)                       # ∫_c^a h
    h2 = (mu * E_star) ** 2 * (d * d * L - 2 * d * dG + dG2)  # ∫_c^a h²
    out = np.maximum(2.0 * (u * h1 - h2 / G_star), 0.0)
    # small loops: the closed form cancels by ~(a/L)² (3e-10 of D at u = 0.01 u*); integrate
    # the definition directly over [c, a] where g is smooth there
    small = (L > 0) & (L <= SMALL_SLIP_RATIO * a) & (c >= profile.flat_radius)
    for b in profile.breakpoints:
        small &= ~((b > c) & (b < a))
    if np.any(small):
        shape = out.shape
        out, small = np.array(out, float).ravel(), np.ravel(small)
        pick = [np.ravel(np.broadcast_to(v, shape))[small] for v in (a, c, d, u)]
        out[small] = _dissipation_by_quadrature(profile, E_star, G_star, mu, *pick)
        out = out.reshape(shape)
    return out


def _edge_any_override(profile, E_star, G_star, mu, a, u, out, which: int, ratio: float):
    """``out`` with the entries whose stick width ``σ_c/a`` is below ``ratio`` replaced by
    the annulus form of :func:`edge_annulus.shift_any` (``which``: 0 the dissipation, 1 the
    force ``2G*a|u| -`` its slip correction)."""
    edge = _edge.edge_of(profile)
    if edge is None:
        return out
    shape = np.shape(out)
    out = np.array(out, float).ravel()
    af, uf = (np.ravel(np.broadcast_to(v, shape)) for v in (a, u))
    live = np.flatnonzero((af > 0) & (uf > 0) & np.isfinite(uf))
    if live.size == 0:
        return out.reshape(shape)
    D, C, s_c = _edge.shift_any(edge, E_star, G_star, mu, af[live], uf[live])
    thin = s_c < ratio
    val = D if which == 0 else 2.0 * G_star * af[live] * np.abs(uf[live]) - C
    out[live[thin]] = val[thin]
    return out.reshape(shape)


#: slip-zone width ``(a - c)/a`` up to which :func:`virgin_dissipation` integrates its definition
#: by Gauss-Legendre over ``[c, a]`` instead of differencing integrals from 0 (the singularity
#: of ``g`` nearest to the interval is at ``x = 0``, at least one interval width away: the rule
#: below converges to rounding there)
SMALL_SLIP_RATIO = 0.2
_GL_X, _GL_W = np.polynomial.legendre.leggauss(16)


def _dissipation_by_quadrature(profile, E_star, G_star, mu, a, c, d, u):
    """``2∫_c^a h (u - h/G*) dx`` by a 16-point Gauss-Legendre rule on ``[c, a]``.

    Each node's ``h(x) = μE*(d - g(x))`` and ``u - h(x)/G*`` are differences of numbers of the
    size of ``d`` and ``u``: the relative error is a few ``ε a/(a - c)`` (4e-14 at
    ``u = 0.01 u*`` for a paraboloid), against ``ε (a/(a - c))²`` and worse for the closed form.
    """
    L = a - c
    x = c[:, None] + 0.5 * L[:, None] * (_GL_X[None, :] + 1.0)
    h = mu * E_star * (d[:, None] - profile._g(x))
    f = h * (u[:, None] - h / G_star)
    return np.maximum(L * (f @ _GL_W), 0.0)            # 2 · (L/2) Σ w f


#: below ``r = AXIS_RATIO * c`` the stick-zone traction takes its value on the axis: the
#: difference ``S(r, a) - S(r, c) = ∫_c^a g'(x)/sqrt(x²-r²) dx`` is even and analytic in r for
#: ``r < c`` with relative change ``O(r²/c²)``, below 1e-16 there
AXIS_RATIO = 1e-8


def pressure_shape_difference_on_axis(profile, a: np.ndarray, c: np.ndarray,
                                      rtol: float) -> np.ndarray:
    """``S(0, a) - S(0, c) = ∫_c^a g'(x)/x dx`` for ``0 < c <= a``, 1/m (finite even where
    ``S(0, ·)`` itself is infinite: cone tips, ``n <= 1``).

    By parts, ``g(a)/a - g(c)/c + ∫_c^a g(x)/x² dx`` (g only), the integral by tanh-sinh split
    at the profile's breakpoints.
    """
    from ..numeric.quadrature import tanh_sinh
    a = np.asarray(a, float)
    c = np.asarray(c, float)
    g_a = profile._g(a, rtol)
    g_c = profile._g(c, rtol)
    cuts = sorted({b for b in (*profile.breakpoints, profile.flat_radius) if b > 0})
    edges = np.stack([c] + [np.clip(np.full_like(c, b), c, a) for b in cuts] + [a])
    lo, hi = edges[:-1], edges[1:]

    def integrand(x: np.ndarray, idx: np.ndarray) -> np.ndarray:
        return profile._g(x, rtol) / (x * x)

    scale = np.broadcast_to(rtol * np.abs(g_a) / a, lo.shape).ravel()
    res = tanh_sinh(integrand, lo.ravel(), hi.ravel(), rtol=rtol, atol=scale)
    return g_a / a - g_c / c + res.value.reshape(lo.shape).sum(axis=0)


def shear(profile, E_star: float, mu: float, r: np.ndarray, a: np.ndarray, d: np.ndarray,
          c: np.ndarray, rtol: float) -> np.ndarray:
    """Tangential traction magnitude ``τ_x(r)``, Pa (Ciavarella–Jäger superposition, §5).

    In the stick zone ``τ = μ(p_a - p_c)``. Near the axis (``r <= AXIS_RATIO c``) both pressures
    may be infinite (cone tip) or lose digits to cancellation; there the finite limit
    ``μ(E*/π)[∫_c^a g'(x)/x dx + (d - g(a))/sqrt(a² - r²)]`` is used.
    """
    r, a, d, c = np.broadcast_arrays(*(np.asarray(v, float) for v in (r, a, d, c)))
    shape = r.shape
    r, a, d, c = (v.reshape(-1) for v in (r, a, d, c))
    ga = _g0(profile, a)
    gc = _g0(profile, c)
    out = np.zeros(r.shape)
    inner = (r < c) & (c > 0)
    axis = inner & (r <= AXIS_RATIO * c)
    rest = ~axis
    if np.any(rest):
        pa, _ = _normal.pressure(profile, E_star, r[rest], a[rest], d[rest], ga[rest], rtol)
        pc = np.zeros(pa.shape)
        inn = inner[rest]
        if np.any(inn):
            cc, gg = c[rest][inn], gc[rest][inn]
            pc[inn], _ = _normal.pressure(profile, E_star, r[rest][inn], cc, gg, gg, rtol)
        out[rest] = mu * (pa - pc)
    if np.any(axis):
        ra, aa, da, ca = r[axis], a[axis], d[axis], c[axis]
        diff = pressure_shape_difference_on_axis(profile, aa, ca, rtol)
        edge = (da - ga[axis]) / np.sqrt((aa - ra) * (aa + ra))
        out[axis] = mu * E_star / np.pi * (diff + edge)
    return out.reshape(shape)
