"""The pressure shape of a table at fixed radii for many contact radii (theory §3).

Along a load path the exact ring solver needs the pressure at the same collocation radii
``r_i`` for every step's contact radius ``a``. For a tabulated profile
(capability ``"node_table"``) the pressure shape

    S(r_i, a) = ∫_{r_i}^a g'(x) / sqrt(x² - r_i²) dx

is set up once per ring as running sums over the table segments (the knots ``X_k`` are the
table nodes below the path's largest contact radius):

    Φ_i(X_k) = S(r_i, X_k) = ∫_{r_i}^{X_{k_i}} + Σ_{k_i <= l < k} ∫_{X_l}^{X_{l+1}},

and a step then costs one partial segment per ring:

    S(r_i, a) = Φ_i(X_k) + ∫_{X_k}^a ...        (r_i < X_k <= a < X_{k+1})
    S(r_i, a) = ∫_{r_i}^a ...                   (X_k <= r_i < a: the ring lies in a's segment)

Every piece is a Gauss-Legendre rule in ``u`` with ``x = lo + (hi - lo) u²``: the square-root
cusp of g' at a node (linear tables) and the ``1/sqrt(x - r_i)`` of the weight at ``lo = r_i``
both become analytic in ``u``, and g' is analytic inside each segment (nodes are the only places
where it is not). The g' values of a segment are shared by all rings. The error estimate is the
difference of a 30- and a 20-point rule (the 20-point rule's error: the 30-point value is far
better) plus the rounding of g'; a piece whose estimate exceeds the tolerance (a ring or a node
very close below the segment's start, where the integrand is nearly singular) is recomputed by
the profile's own route (:func:`contactlab.physics.normal.pressure_shape`, per (ring, node)
quadratures). Cost: set-up O(rings x nodes below the largest radius) rule evaluations plus g' at
30 + 20 points per segment, then O(rings) per step plus g' at 50 points.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from . import normal as _normal

__all__ = ["FixedRadiiShape", "fixed_radii_shape", "shape_at", "pressure_at", "MAX_ENTRIES"]

#: largest rings x knots of a set-up (three float arrays of that size are held); beyond it the
#: profile's own route is used at every step
MAX_ENTRIES = 2_000_000
#: float64 entries of the temporary arrays of one set-up chunk
_CHUNK = 1_000_000


def _rule(n: int) -> tuple[np.ndarray, np.ndarray]:
    x, w = np.polynomial.legendre.leggauss(n)
    return 0.5 * (x + 1.0), 0.5 * w


_U_HI, _W_HI = _rule(30)
_U_LO, _W_LO = _rule(20)
#: the joint point set (30 then 20 points): g' is evaluated once for both rules
_U = np.concatenate([_U_HI, _U_LO])
_N_HI = _U_HI.size


@dataclass(frozen=True)
class FixedRadiiShape:
    """Running sums of the pressure shape of a table at fixed radii (see the module docstring).

    Attributes
    ----------
    radii : ndarray, shape (n,)
        The fixed radii ``r_i``, m (> 0).
    knots : ndarray, shape (K,)
        Table nodes below the largest contact radius, m.
    phi : ndarray, shape (n, K)
        ``S(r_i, X_k)`` for ``X_k > r_i`` (0 elsewhere), 1.
    phi_err : ndarray, shape (n, K)
        Error estimate of ``phi``.
    rtol : float
        Relative tolerance the pieces were accepted at.
    fallbacks : int
        Set-up pieces recomputed by the profile's own route.
    """

    radii: np.ndarray
    knots: np.ndarray
    phi: np.ndarray
    phi_err: np.ndarray
    rtol: float
    fallbacks: int


def _pieces(r: np.ndarray, lo: np.ndarray, hi: np.ndarray, gp: np.ndarray,
            gp_err: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``∫_lo^hi g'(x)/sqrt(x² - r²) dx`` and its error estimate for ``r < lo`` or ``r = lo``
    (arrays broadcast), with g' (and its rounding) given at ``x = lo + (hi - lo) u²`` of the
    joint rule points (last axis)."""
    h = (hi - lo)[..., None]
    hu2 = h * (_U * _U)
    own = lo == r
    if np.all(own):
        # at lo = r the weight times the Jacobian is 2 sqrt(h) / sqrt(x + r), analytic in u
        jac = 2.0 * np.sqrt(h) / np.sqrt((lo + r)[..., None] + hu2)
    else:
        # x - r = (lo - r) + h u² without cancellation
        with np.errstate(divide="ignore", invalid="ignore"):
            jac = 2.0 * h * _U / np.sqrt(((lo - r)[..., None] + hu2) * ((lo + r)[..., None] + hu2))
        if np.any(own):
            jac = np.where(own[..., None], 2.0 * np.sqrt(h) / np.sqrt((lo + r)[..., None] + hu2),
                           jac)
    # plain sums over the rule points (not BLAS): each element's rounding does not depend on
    # how many elements are computed together (chunks of steps give bit-identical results)
    f = gp * jac
    both = np.stack([np.sum(f[..., :_N_HI] * _W_HI, axis=-1),
                     np.sum(f[..., _N_HI:] * _W_LO, axis=-1)], axis=-1)
    val = both[..., 0]
    # rounding of g': at most max|δg'| ∫_lo^hi dx/sqrt(x² - r²), in closed form
    with np.errstate(divide="ignore", invalid="ignore"):
        span = np.arccosh(np.maximum(hi / r, 1.0)) - np.arccosh(np.maximum(lo / r, 1.0))
    err = np.abs(both[..., 0] - both[..., 1]) + np.max(gp_err, axis=-1) * np.abs(span)
    return val, np.where(hi > lo, err, 0.0)


def _g_slope(profile, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    gp, err = profile.table_g_slope(x.ravel())
    return gp.reshape(x.shape), err.reshape(x.shape)


def fixed_radii_shape(profile, radii: np.ndarray, a_max: float, rtol: float
                      ) -> FixedRadiiShape | None:
    """Set up :class:`FixedRadiiShape` for ``radii`` (m) and contact radii up to ``a_max`` (m),
    or ``None`` when the profile is not a table (``"node_table"``), a radius is not positive or
    the set-up would exceed :data:`MAX_ENTRIES` (then use
    :func:`contactlab.physics.normal.pressure_shape` directly)."""
    if not profile.has("node_table"):
        return None
    r = np.asarray(radii, dtype=float).ravel()
    if r.size == 0 or np.any(r <= 0) or not np.all(np.isfinite(r)):
        return None
    nodes = np.asarray(profile.table_nodes(), dtype=float)
    X = nodes[(nodes > 0) & (nodes < a_max)]
    K = X.size
    n = r.size
    if n * max(K, 1) > MAX_ENTRIES:
        return None
    phi = np.zeros((n, K))
    perr = np.zeros((n, K))
    if K == 0:
        return FixedRadiiShape(r, X, phi, perr, float(rtol), 0)
    # first knot above each ring, and the ring's own piece up to it
    k_i = np.searchsorted(X, r, side="right")
    has = k_i < K
    own = np.zeros(n)
    own_err = np.zeros(n)
    if np.any(has):
        ri, hi = r[has], X[k_i[has]]
        x = ri[:, None] + (hi - ri)[:, None] * _U * _U
        gp, ge = _g_slope(profile, x)
        own[has], own_err[has] = _pieces(ri, ri, hi, gp, ge)
    # full segments [X_l, X_{l+1}]: g' shared by every ring
    lo_s, hi_s = X[:-1], X[1:]
    seg = np.zeros((n, max(K - 1, 0)))
    seg_err = np.zeros((n, max(K - 1, 0)))
    if K > 1:
        x = lo_s[:, None] + (hi_s - lo_s)[:, None] * _U * _U
        gp, ge = _g_slope(profile, x)
        step = max(1, _CHUNK // (n * _U.size))
        for c0 in range(0, K - 1, step):
            c1 = min(K - 1, c0 + step)
            below = r[:, None] < lo_s[None, c0:c1]
            rr = np.where(below, r[:, None], 0.5 * lo_s[None, c0:c1])   # unused entries: benign
            v, e = _pieces(rr, np.broadcast_to(lo_s[c0:c1], rr.shape),
                           np.broadcast_to(hi_s[c0:c1], rr.shape), gp[None, c0:c1],
                           ge[None, c0:c1])
            seg[:, c0:c1] = np.where(below, v, 0.0)
            seg_err[:, c0:c1] = np.where(below, e, 0.0)
    # running sums: Φ_i(X_k) = own_i + Σ_{k_i <= l < k} seg_il  (k >= k_i)
    cols = np.arange(K)
    run = np.concatenate([np.zeros((n, 1)), np.cumsum(seg, axis=1)], axis=1)       # (n, K)
    run_err = np.concatenate([np.zeros((n, 1)), np.cumsum(seg_err, axis=1)], axis=1)
    start = np.minimum(k_i, K - 1)
    valid = cols[None, :] >= k_i[:, None]
    phi = np.where(valid, own[:, None] + run - run[np.arange(n), start][:, None], 0.0)
    perr = np.where(valid, own_err[:, None] + run_err - run_err[np.arange(n), start][:, None], 0.0)
    # pieces the rules did not resolve: the profile's own route at both ends of the piece
    scale = np.abs(_g(profile, X, rtol)) / X
    tol = rtol * (np.abs(phi) + scale[None, :])
    piece_err = np.zeros((n, K))
    piece_err[np.arange(n)[has], k_i[has]] = own_err[has]
    if K > 1:
        piece_err[:, 1:] = np.where(valid[:, 1:] & (cols[None, 1:] > k_i[:, None]),
                                    seg_err, piece_err[:, 1:])
    bad = valid & (piece_err > 0.1 * tol)
    fallbacks = int(np.count_nonzero(bad))
    if fallbacks:
        # recompute Φ exactly at every knot of a bad piece and from there on carry the
        # corrected offset: Φ_i(X_k) = S_ref(r_i, X_k) at the bad knots, the running sums between
        ii, kk = np.nonzero(bad)
        ref, ref_err = _normal.pressure_shape(profile, r[ii], X[kk], rtol)
        prev = kk - 1
        need_prev = prev >= k_i[ii]
        ref_prev = np.zeros(ii.size)
        ref_prev_err = np.zeros(ii.size)
        if np.any(need_prev):
            ref_prev[need_prev], ref_prev_err[need_prev] = _normal.pressure_shape(
                profile, r[ii][need_prev], X[prev[need_prev]], rtol)
        fixed = np.zeros((n, K))
        fixed_err = np.zeros((n, K))
        # the bad piece's value, exactly: S(X_k) - S(X_{k-1}) (or S(X_{k_i}) for the own piece)
        piece = np.where(need_prev, ref - ref_prev, ref)
        old_piece = phi[ii, kk] - np.where(need_prev, phi[ii, np.maximum(prev, 0)], 0.0)
        fixed[ii, kk] = piece - old_piece
        fixed_err[ii, kk] = ref_err + ref_prev_err - piece_err[ii, kk]
        phi = phi + np.where(valid, np.cumsum(fixed, axis=1), 0.0)
        perr = perr + np.where(valid, np.cumsum(fixed_err, axis=1), 0.0)
    return FixedRadiiShape(r, X, phi, perr, float(rtol), fallbacks)


def _g(profile, x: np.ndarray, rtol: float) -> np.ndarray:
    return profile._g(np.asarray(x, float), rtol)


def shape_at(profile, table: FixedRadiiShape, a: np.ndarray, g_a: np.ndarray | None = None
             ) -> tuple[np.ndarray, np.ndarray]:
    """``S(r_i, a_s)`` at the table's radii for contact radii ``a`` (m, shape (m,)): value and
    error estimate, shape (m, n) (0 where ``r_i >= a_s``). ``g_a``: g at ``a`` (optional,
    the tolerance scale)."""
    r, X, rtol = table.radii, table.knots, table.rtol
    a = np.asarray(a, dtype=float).ravel()
    m, n = a.size, r.size
    out = np.zeros((m, n))
    err = np.zeros((m, n))
    inside = r[None, :] < a[:, None]
    if not np.any(inside):
        return out, err
    k = np.searchsorted(X, a, side="right") - 1              # largest knot <= a (-1: none)
    lo = np.where(k >= 0, X[np.maximum(k, 0)], 0.0) if X.size else np.zeros(m)
    # rings below the knot: Φ plus the step's partial segment (g' shared by the rings)
    far = inside & (r[None, :] < lo[:, None])
    if np.any(far):
        rows = np.flatnonzero(np.any(far, axis=1))
        lo_r, a_r = lo[rows], a[rows]
        x = lo_r[:, None] + (a_r - lo_r)[:, None] * _U * _U
        gp, ge = _g_slope(profile, x)
        rr = np.where(far[rows], r[None, :], 0.5 * lo_r[:, None])
        v, e = _pieces(rr, np.broadcast_to(lo_r[:, None], rr.shape),
                       np.broadcast_to(a_r[:, None], rr.shape), gp[:, None, :], ge[:, None, :])
        kk = k[rows]
        base = table.phi[:, kk].T
        base_err = table.phi_err[:, kk].T
        out[rows] = np.where(far[rows], base + v, 0.0)
        err[rows] = np.where(far[rows], base_err + e, 0.0)
    # rings inside the step's segment: their own piece from r_i to a
    near = inside & ~far
    if np.any(near):
        si, ri = np.nonzero(near)
        rv, av = r[ri], a[si]
        x = rv[:, None] + (av - rv)[:, None] * _U * _U
        gp, ge = _g_slope(profile, x)
        out[si, ri], err[si, ri] = _pieces(rv, rv, av, gp, ge)
    # elements the rules did not resolve: the profile's own route
    if g_a is None:
        g_a = _g(profile, a, rtol)
    scale = np.abs(np.asarray(g_a, float).ravel()) / np.where(a > 0, a, 1.0)
    piece = err - np.where(far, table.phi_err[:, np.maximum(k, 0)].T, 0.0) if X.size else err
    bad = inside & ((piece > 0.1 * rtol * (np.abs(out) + scale[:, None])) | ~np.isfinite(out))
    if np.any(bad):
        si, ri = np.nonzero(bad)
        out[si, ri], err[si, ri] = _normal.pressure_shape(profile, r[ri], a[si], rtol)
    return out, err


def pressure_at(profile, E_star: float, table: FixedRadiiShape, a: np.ndarray, d: np.ndarray,
                g_a: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Contact pressure (Pa) at the table's radii for steps with contact radius ``a``, depth
    ``d`` and ``g(a)`` (m, shape (m,)): value and error estimate, shape (m, n); 0 outside the
    contact. Same formula as :func:`contactlab.physics.normal.pressure`:
    ``p = (E*/π) [S(r, a) + (d - g(a))/sqrt(a² - r²)]``."""
    a = np.asarray(a, float).ravel()
    d = np.asarray(d, float).ravel()
    g_a = np.asarray(g_a, float).ravel()
    S, err = shape_at(profile, table, a, g_a)
    return _normal.pressure_from_shape(E_star, S, err, table.radii[None, :], a[:, None],
                                       d[:, None], g_a[:, None])
