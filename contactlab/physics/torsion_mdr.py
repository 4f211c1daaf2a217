"""MDR narrow-slip model of torsion with slip [S eqs. 47-52] (theory §6.4).

Springs of torsional stiffness ``8 G_t Δx`` with the equivalent friction coefficient ``μ* = 2μ``:
a spring at ``x`` sticks (``u_y = xφ``) until ``8 G_t |u_y| = μ* E* (d - g(x))``, then slides with
``u_y = u_s(x) = μE*(d - g(x))/(4G_t)``. Hence

* stick radius: ``8 G_t φ c = μ* E* (d - g(c))`` [S eq. 52];
* torque: ``M = (16/3) G_t φ c³ + 4μE* ∫_c^a x (d - g(x)) dx``;
* full sliding: ``4μE* ∫_0^a x (d - g) dx``, which is 4/π times the exact value for every profile.

The model is exact only as ``c → a`` (first order in ``1 - c/a``); the relative torque error at a
given twist is O((1 - c/a)²). Pure, vectorised kernels: flat arrays of equal size.

A single power term ``g = K x^n`` (paraboloid, cone, power law) has closed forms: the stick
radius solves ``β s + s^n = δ`` in ``s = c/a`` (``β = 4G_tφ a/(μE* K a^n)``,
``δ = d/(K a^n)``; a quadratic for the paraboloid), and the annulus integral is
``(d - K a^n)(a² - c²)/2 + K a^(n+2) h(c/a)``, ``h(s) = ∫_s^1 x (1 - x^n) dx``
(:func:`_annulus_shape`, free of cancellation as ``c → a``). Other profiles take quadratures.
"""
from __future__ import annotations

import numpy as np

from ..numeric.quadrature import tanh_sinh
from ..numeric.roots import bracketed_root
from ..profiles.base import ROUNDING as _ROUNDING
from . import edge_annulus as _edge
from .torsion_exact import (
    _TABLE_SPLIT_MAX,
    C_MIN_REL,
    _composite_nodes,
    _cuts,
    _integrate_log,
    sharpen_error,
    x_g_integral,
)

#: annuli ``[c, a]`` narrower than this fraction of ``a`` are integrated in ``x`` itself, wider
#: ones in ``ln x``: the width ``ln a - ln c`` of a narrow annulus carries the rounding of
#: ``ln a`` (relative ``eps |ln a| a/(a - c)``), 7e-12 of a flat punch's annulus integral at
#: ``1 - c/a = 1e-4``, 3e-9 at 1e-7 and a ConvergenceError from 1e-8 on, while ``a - c`` is exact
NEAR_REL = 1e-3


def _integrate_annulus(profile, kernel, lo: np.ndarray, hi: np.ndarray, rtol: float,
                       atol: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``∫_lo^hi kernel(x, g(x), idx) dx`` per element (the MDR annulus integrals).

    Annuli with ``hi - lo > NEAR_REL hi`` (and large tables) go through
    :func:`contactlab.physics.torsion_exact._integrate_log`; narrower ones are integrated in the
    offset ``x - lo`` of each segment between the profile's breakpoints (nodes clipped into it).
    """
    near = (hi - lo) <= NEAR_REL * hi
    nodes = _composite_nodes(profile)
    if not np.any(near) or (nodes is not None and nodes.size > _TABLE_SPLIT_MAX):
        return _integrate_log(profile, kernel, lo, hi, rtol, atol)
    val = np.zeros(lo.shape)
    err = np.zeros(lo.shape)
    far = np.flatnonzero(~near)
    if far.size:
        val[far], err[far] = _integrate_log(
            profile, lambda x, gx, idx: kernel(x, gx, far[idx]), lo[far], hi[far], rtol,
            np.broadcast_to(atol, lo.shape)[far])
    idx_n = np.flatnonzero(near)
    ln, hn = lo[idx_n], hi[idx_n]
    edges = np.stack([ln] + [np.clip(np.full_like(ln, b), ln, hn) for b in _cuts(profile)] + [hn])
    n_seg = edges.shape[0] - 1
    t_lo, t_hi = edges[:-1].ravel(), edges[1:].ravel()
    elem = np.broadcast_to(idx_n, (n_seg, idx_n.size)).ravel()

    def integrand(u: np.ndarray, k: np.ndarray) -> np.ndarray:
        t = np.clip(t_lo[k][:, None] + u, t_lo[k][:, None], t_hi[k][:, None])
        return kernel(t, profile._g(t), elem[k])

    at = np.broadcast_to(np.asarray(atol, float), lo.shape)[idx_n]
    # in the offset u = x - lo over [0, hi - lo] (an exact width): nodes in x itself collapse
    # onto the ends of a narrow annulus, and the weight they drop (relative ~eps a/(a - c))
    # reads as quadrature error
    res = tanh_sinh(integrand, np.zeros(t_lo.shape), t_hi - t_lo, rtol=rtol,
                    atol=np.broadcast_to(at / n_seg, (n_seg, idx_n.size)).ravel())
    val[idx_n] = res.value.reshape(n_seg, -1).sum(axis=0)
    err[idx_n] = res.error.reshape(n_seg, -1).sum(axis=0)
    return val, err

__all__ = ["slip_displacement", "stick_radius", "torque_of_stick", "annulus_integral",
           "sliding_torque", "twist_of_stick", "stick_radius_of_torque", "dissipation"]


def _single_power(profile) -> tuple[float, float] | None:
    """``(K, n)`` with ``g(x) = K x**n`` for a single power term without a flat part or a wall
    (paraboloid, cone, power law), else ``None``: the MDR kernels then have closed forms."""
    if (not np.isfinite(profile.wall_radius)) and profile.flat_radius == 0:
        terms = profile.power_terms()
        if terms is not None and len(terms) == 1:
            c, n = (float(v) for v in terms[0])
            return profile._power_kappa(n) * c, n
    return None


#: Gauss-Legendre rule of :func:`_annulus_shape` on ``[0, 1]`` (nodes, weights)
_GL_V, _GL_W = np.polynomial.legendre.leggauss(20)
_GL_V, _GL_W = 0.5 * (_GL_V + 1.0), 0.5 * _GL_W


def _annulus_shape(s: np.ndarray, n: float) -> np.ndarray:
    """``h(s) = ∫_s^1 x (1 - x**n) dx`` for ``0 <= s <= 1`` (flat arrays).

    ``n = 2``: ``(1 - s²)²/4``; ``n = 1``: ``(1 - s)² (1 + 2s)/6`` (no cancellation). Else
    ``(1 - s²)/2 - (1 - s**(n+2))/(n+2)`` below ``s = 1/2``; above it (where the two terms
    cancel as ``u = 1 - s -> 0``, ``h ~ n u²/2``) a 20-point Gauss-Legendre rule in the offset
    ``v = 1 - x`` over ``[0, u]`` of ``(1 - v)(-expm1(n log1p(-v)))``, analytic on a disc of
    radius ``1 - u >= 1/2`` about ``[0, u]`` (error below 1e-20 relative).
    """
    out = np.empty(s.shape)
    if n == 2.0:                    # (1 - s²)²/4, 1 - s² = u (1 + s)
        w = (1.0 - s) * (1.0 + s)
        return 0.25 * w * w
    if n == 1.0:                    # u² (1 + 2s)/6
        u = 1.0 - s
        return u * u * (1.0 + 2.0 * s) / 6.0
    far = s < 0.5
    sf = s[far]
    out[far] = 0.5 * (1.0 - sf) * (1.0 + sf) - (1.0 - sf ** (n + 2.0)) / (n + 2.0)
    u = 1.0 - s[~far]
    v = u[:, None] * _GL_V
    f = (1.0 - v) * -np.expm1(n * np.log1p(-v))
    # a row sum, not BLAS: a state's rounding must not depend on the other states of the call
    out[~far] = u * np.sum(f * _GL_W, axis=1)
    return out


def _stick_ratio(beta: np.ndarray, delta: np.ndarray, n: float) -> np.ndarray:
    """Root ``s`` in ``(0, 1]`` of ``beta s + s**n = delta`` (``beta > 0``, ``delta ≈ 1``):
    in closed form for ``n = 1, 2``, else Newton safeguarded by the bracket ``[lo, hi]`` (the
    residual is increasing in ``s``), per element, until the bracket or the step reaches
    rounding (flat arrays)."""
    if n == 2.0:                    # the stable root of s² + β s - δ = 0
        return 2.0 * delta / (beta + np.sqrt(beta * beta + 4.0 * delta))
    if n == 1.0:
        return delta / (beta + 1.0)
    lo = np.zeros(beta.shape)
    hi = np.minimum(delta / beta, delta ** (1.0 / n))     # each term alone reaches delta
    s = 0.5 * hi if n < 1 else hi.copy()
    todo = np.arange(beta.size)
    for _ in range(200):
        if not todo.size:
            break
        b, dl, ss = beta[todo], delta[todo], s[todo]
        sn = ss ** n
        F = b * ss + sn - dl
        pos = F > 0
        hi[todo] = np.where(pos, ss, hi[todo])
        lo[todo] = np.where(pos, lo[todo], ss)
        with np.errstate(divide="ignore", invalid="ignore"):
            new = ss - F / (b + n * sn / ss)
        l_, h_ = lo[todo], hi[todo]
        new = np.where((new > l_) & (new < h_), new, 0.5 * (l_ + h_))
        s[todo] = new
        keep = (np.abs(new - ss) > 2e-16 * ss) & (h_ - l_ > 2e-16 * h_) & (F != 0)
        s[todo[~keep & (F == 0)]] = ss[~keep & (F == 0)]
        todo = todo[keep]
    return s


def slip_displacement(profile, E_star: float, G_t: float, mu: float, x: np.ndarray,
                      d: np.ndarray) -> np.ndarray:
    """Spring displacement in the slip zone ``u_s = μE*(d - g(x))/(4G_t)`` (m) [S eq. 51]."""
    return mu * E_star * (d - profile._g(x)) / (4.0 * G_t)


def twist_of_stick(profile, E_star: float, G_t: float, mu: float, c: np.ndarray,
                   d: np.ndarray) -> np.ndarray:
    """``φ = μE*(d - g(c))/(4 G_t c)`` (rad): the twist at which the stick radius is ``c`` [S eq. 52]."""
    return slip_displacement(profile, E_star, G_t, mu, c, d) / c


def stick_radius(profile, E_star: float, G_t: float, mu: float, phi: np.ndarray, a: np.ndarray,
                 d: np.ndarray, rtol: float) -> np.ndarray:
    """Stick radius ``c`` (m) for twists ``phi >= 0``: root of ``8G_tφc = 2μE*(d - g(c))``.

    ``c = a`` (no slip) while ``φ <= μE*(d - g(a))/(4G_t a)`` (> 0 only for a flat punch); solved in
    ``y = ln(c/a)``.
    """
    c = np.where(a > 0, a, 0.0)
    live = (a > 0) & (phi > 0)
    if not np.any(live):
        return c
    al, dl, pl = a[live], d[live], phi[live]
    power = _single_power(profile)
    if power is not None:           # β s + s^n = δ in s = c/a, no quadrature
        K, n = power
        kk = 4.0 * G_t / (mu * E_star)
        Kan = K * al ** n
        c[live] = al * _stick_ratio(kk * pl * al / Kan, dl / Kan, n)
        return c
    phi_top = twist_of_stick(profile, E_star, G_t, mu, al, dl)
    solve = pl > phi_top
    out = al.copy()
    if np.any(solve):
        s_a, s_d, s_p = al[solve], dl[solve], pl[solve]
        k = 4.0 * G_t / (mu * E_star)

        def func(y: np.ndarray, idx: np.ndarray) -> np.ndarray:
            cc = s_a[idx] * np.exp(y)
            return k * s_p[idx] * cc + profile._g(cc)      # increasing in y; root at = d

        y_min = np.log(C_MIN_REL)
        f_lo = func(np.full(s_a.shape, y_min), np.arange(s_a.size))
        sliding = f_lo >= s_d
        res = np.zeros(s_a.shape)
        ok = ~sliding
        if np.any(ok):
            idx_ok = np.flatnonzero(ok)

            def func_ok(y: np.ndarray, idx: np.ndarray) -> np.ndarray:
                return func(y, idx_ok[idx])

            y = bracketed_root(func_ok, s_d[ok], y_min, 0.0, rtol=rtol, ftol=rtol * 1e-3,
                               what="MDR stick radius")
            res[ok] = s_a[ok] * np.exp(y)
        out[solve] = res
    c[live] = out
    return c


def annulus_integral(profile, c: np.ndarray, a: np.ndarray, d: np.ndarray,
                     rtol: float, return_error: bool = False):
    """``∫_c^a x (d - g(x)) dx`` (m³) by quadrature of the non-negative integrand (no cancellation
    as ``c → a``), split at the profile's breakpoints (composite rule for large tables), in ``x``
    for annuli narrower than :data:`NEAR_REL` ``a`` (else in ``ln x``). The part below
    ``C_MIN_REL a`` (relative size 1e-200) is dropped. ``return_error=True``: also the
    absolute quadrature error estimate (m³)."""
    out = np.zeros(c.shape)
    err = np.zeros(c.shape)
    todo = np.flatnonzero(c < a)
    if todo.size == 0:
        return (out, err) if return_error else out
    as_, ds = a[todo], d[todo]
    cs = np.maximum(c[todo], C_MIN_REL * as_)
    power = _single_power(profile)
    if power is not None:
        # d (a² - c²)/2 - K (a^(n+2) - c^(n+2))/(n+2) = (d - K a^n)(a² - c²)/2 + K a^(n+2) h(c/a)
        K, n = power
        Kan = K * as_ ** n
        val = ((ds - Kan) * (0.5 * (as_ - cs) * (as_ + cs))
               + Kan * as_ * as_ * _annulus_shape(cs / as_, n))
        out[todo] = val
        err[todo] = _ROUNDING * (np.abs(val) + np.abs(ds - Kan) * as_ * as_)
        return (out, err) if return_error else out

    def kernel(x: np.ndarray, gx: np.ndarray, idx: np.ndarray) -> np.ndarray:
        return x * (ds[idx][:, None] - gx)

    scale = ds * as_ * (as_ - cs)
    val, e = _integrate_annulus(profile, kernel, cs, as_, rtol, rtol * scale * 1e-3 + 1e-300)
    out[todo] = val
    err[todo] = e
    return (out, err) if return_error else out


def torque_of_stick(profile, E_star: float, G_t: float, mu: float, phi: np.ndarray,
                    c: np.ndarray, a: np.ndarray, d: np.ndarray, rtol: float,
                    return_error: bool = False):
    """``M = (16/3) G_t φ c³ + 4μE* ∫_c^a x (d - g) dx`` (N·m); ``return_error=True``: also the
    absolute error estimate (N·m) from the quadrature and the rounding of the sum."""
    if not return_error:
        A = annulus_integral(profile, c, a, d, rtol)
        return 16.0 / 3.0 * G_t * phi * c**3 + 4.0 * mu * E_star * A
    A, A_err = annulus_integral(profile, c, a, d, rtol, return_error=True)
    M1 = 16.0 / 3.0 * G_t * phi * c**3
    M2 = 4.0 * mu * E_star * A
    return M1 + M2, 4.0 * mu * E_star * sharpen_error(A_err, A) + _ROUNDING * (np.abs(M1) + np.abs(M2))


def sliding_torque(profile, E_star: float, mu: float, a: np.ndarray, d: np.ndarray,
                   rtol: float) -> np.ndarray:
    """MDR full-sliding torque ``4μE* ∫_0^a x (d - g) dx`` (N·m); 4/π times the exact one."""
    return 4.0 * mu * E_star * (0.5 * d * a * a - np.where(a > 0, x_g_integral(profile, a, rtol), 0.0))


def stick_radius_of_torque(profile, E_star: float, G_t: float, mu: float, M: np.ndarray,
                           a: np.ndarray, d: np.ndarray, rtol: float) -> np.ndarray:
    """Stick radius for torques ``0 <= M < M_full`` (MDR): root of ``M(c) = M``, ``c`` in (0, a]."""
    c = np.where(a > 0, a, 0.0)
    live = (a > 0) & (M > 0)
    if not np.any(live):
        return c
    al, dl, Ml = a[live], d[live], M[live]
    phi_top = twist_of_stick(profile, E_star, G_t, mu, al, dl)
    M_top = 16.0 / 3.0 * G_t * al**3 * phi_top
    solve = Ml > M_top
    out = al.copy()
    if np.any(solve):
        s_a, s_d = al[solve], dl[solve]

        def func(y: np.ndarray, idx: np.ndarray) -> np.ndarray:
            cc = s_a[idx] * np.exp(y)
            ph = twist_of_stick(profile, E_star, G_t, mu, cc, s_d[idx])
            return torque_of_stick(profile, E_star, G_t, mu, ph, cc, s_a[idx], s_d[idx], rtol)

        y = bracketed_root(func, Ml[solve], np.log(C_MIN_REL), 0.0, rtol=rtol, ftol=0.0,
                           what="MDR stick radius")
        out[solve] = s_a * np.exp(y)
    c[live] = out
    return c


def dissipation(profile, E_star: float, G_t: float, mu: float, phi: np.ndarray, c: np.ndarray,
                a: np.ndarray, d: np.ndarray, rtol: float) -> np.ndarray:
    """Energy dissipated by the springs while twisting monotonically from 0 to ``φ`` (J).

    ``D = 16 G_t ∫_c^a u_s (xφ - u_s) dx``: each sliding spring (force ``8G_t u_s`` per unit
    length, both sides of the axis) has slid by ``xφ - u_s``.
    """
    out = np.zeros(c.shape)
    todo = np.flatnonzero(c < a)
    if todo.size:
        out[todo] = _stick_radius_form(profile, E_star, G_t, mu, phi[todo], c[todo], a[todo],
                                       d[todo], rtol)
    # a thin annulus (σ_c < EDGE_SLIP_RATIO a) of a single power law: in annulus coordinates,
    # accurate to rounding down to twists of one ulp (the stick-radius form errs by ~ε a/σ_c,
    # and c rounds to a below an annulus of one ulp)
    pw = _edge.power_edge(profile)
    if pw is not None:
        live = np.flatnonzero((a > 0) & (phi > 0) & np.isfinite(phi))
        D, s_c = _edge.torsion_dissipation(*pw, E_star, G_t, mu, a[live], phi[live])
        thin = s_c < _edge.EDGE_SLIP_RATIO
        out[live[thin]] = D[thin]
    else:
        # any other profile: the drop g(a) - g(a - σ) integrated from g' on the annulus
        edge = _edge.edge_of(profile)
        live = np.flatnonzero((a > 0) & (phi > 0) & np.isfinite(phi))
        if edge is not None and live.size:
            D, s_c = _edge.torsion_any(edge, E_star, G_t, mu, a[live], phi[live])
            thin = s_c < _edge.EDGE_SLIP_RATIO
            out[live[thin]] = D[thin]
    return out


def _stick_radius_form(profile, E_star: float, G_t: float, mu: float, phi: np.ndarray,
                       c: np.ndarray, a: np.ndarray, d: np.ndarray, rtol: float) -> np.ndarray:
    """:func:`dissipation` at the stick radii ``c < a`` (quadrature over ``[c, a]``)."""
    as_, ds, ps = a, d, phi
    cs = np.maximum(c, C_MIN_REL * as_)

    def kernel(x: np.ndarray, gx: np.ndarray, idx: np.ndarray) -> np.ndarray:
        us = mu * E_star * (ds[idx][:, None] - gx) / (4.0 * G_t)
        return us * np.maximum(x * ps[idx][:, None] - us, 0.0)

    us_scale = mu * E_star * ds / (4 * G_t)
    scale = us_scale * ps * as_ * (as_ - cs)
    val, _ = _integrate_annulus(profile, kernel, cs, as_, rtol, rtol * scale * 1e-3 + 1e-300)
    return 16.0 * G_t * val
