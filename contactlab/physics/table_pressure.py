"""The pressure shape of a measured table, per segment with rules cached per table (theory §3).

For a table (capability ``"node_table"``: g analytic between the nodes ``b_k``) the pressure
shape

    S(r, a) = ∫_r^a g'(x) / sqrt(x² - r²) dx

is a sum over the table segments. The axis slope ``s = f'(0+)`` is taken out in closed form, a
cone's ``s (π/2) arccosh(a/r)`` (``inf`` on the axis when ``s != 0``: a cone tip), and the rest,
``q(x) = g'(x) - s π/2``, is integrated per piece by Gauss-Legendre rules in ``u`` with
``x = lo + (hi - lo) u²``, which makes the square-root cusp of g' at a segment's left node (linear
tables) analytic:

* segments at least three above the one holding ``r`` (``b_k >= b_{k_r + 3}``), whole ones below
  ``a``: an 8-point rule whose nodes ``x_kp`` and weighted values ``w_p 2 h_k u_p q(x_kp)`` are
  set up once per table (g' by the table's own closed-form node sums); a radius then costs one
  ``1/sqrt(x_kp² - r²)`` per cached point, no g' evaluation. The weight's singularity at
  ``x = r`` lies at least two segments below (``u = i sqrt(2)`` on a uniform table: error
  ~6^-16 ≈ 3e-13 relative), estimated from a 6-point rule on the nearest such segment;
* the piece ``[r, b_{k_r+1}]``, the next two segments and the part of ``a``'s segment below
  ``a``: 20-point rules in ``t`` with ``x = m + δ cosh t`` (see :func:`_piece`: the two nearly
  coalescing singular points, ``r`` and a node, handled together), error from a 12-point rule.
  Their g' values come from a Chebyshev series per segment in ``w = sqrt(x - b_k)`` (degree 16,
  set up once per table and checked against the node sums at five more points).

A radius whose estimate exceeds the tolerance (a radius within a small fraction of a segment of a
node of a linear table, where the pressure is logarithmically large) is recomputed by the
profile's own route. A radius exactly on a node where the linear interpolant's slope jumps gets
``±inf`` (a logarithmic singularity of that geometry), as from the profile's own route.

Cost: set-up 14 g' evaluations per segment (O(nodes) each); then O(radii x segments x 8)
arithmetic plus 64 g' evaluations per radius. Tables beyond :data:`MAX_NODES` nodes take the
profile's own route (the set-up would be O(nodes²)). With numba (extra ``fast``) the 20/12-point
rules of whole radius arrays (a peak search's 1024 radii) run in one compiled pass per radius
(:mod:`contactlab.numeric.table_kernels`; the same operations in the same order, so the same
bits as the numpy route here, which ``CONTACTLAB_BACKEND=numpy`` keeps).
"""
from __future__ import annotations

import numpy as np

from ..numeric import normal_kernels as _normal_kernels
from ..numeric import table_kernels as _table_kernels

__all__ = ["MAX_NODES", "pressure_shape"]

#: largest table (nodes) set up here; finer ones take the profile's own route
MAX_NODES = 2000
#: segments from the one holding ``r`` on that take the per-radius rules (the rest: cached)
NEAR_SEGMENTS = 3
#: radii per block of the cached-rule sums (a block's array: radii x segments x 8 points)
_BLOCK = 64


def _rule(n: int) -> tuple[np.ndarray, np.ndarray]:
    x, w = np.polynomial.legendre.leggauss(n)
    return 0.5 * (x + 1.0), 0.5 * w


_FAR = _rule(8)
_FAR_LO = _rule(6)
_NEAR = _rule(20)
_NEAR_LO = _rule(12)
#: the near rules side by side (one pass evaluates both)
_NEAR_BOTH = (np.concatenate([_NEAR[0], _NEAR_LO[0]]), np.concatenate([_NEAR[1], _NEAR_LO[1]]))
_N_HI = _NEAR[0].size
#: degree of the per-segment Chebyshev series of ``F_k(w) = w q(b_k + w²)``
_DEG = 16
_CHEB_Y = np.cos(np.pi * (np.arange(_DEG + 1) + 0.5) / (_DEG + 1))
#: Chebyshev coefficients from values at ``_CHEB_Y``: ``c = V @ F``
_CHEB_V = (2.0 / (_DEG + 1)) * np.cos(np.outer(np.arange(_DEG + 1),
                                               np.arccos(_CHEB_Y)))
_CHEB_V[0] *= 0.5
#: points where each series is checked against the node sums (between the fitting points)
_CHECK_Y = np.array([-0.98, -0.9, -0.5, 0.0, 0.5, 0.95, 0.999])
#: ``∫_{-1}^{1} T_n dy``: the series' integral over its segment, checked against the node values
_CHEB_INT = np.array([2.0 / (1.0 - n * n) if n % 2 == 0 else 0.0 for n in range(_DEG + 1)])


def _axis_term(profile) -> float:
    """``g'(0+) = (π/2) f'(0+)``."""
    return 0.5 * np.pi * float(profile.table_axis_slope())


def _q(profile, x: np.ndarray, g0: float) -> tuple[np.ndarray, np.ndarray]:
    """``g'(x) - g'(0+)`` and its rounding estimate, at points between the nodes."""
    gp, est = profile.table_g_slope(x)
    return gp - g0, est


def _clenshaw(coef: np.ndarray, y: np.ndarray) -> np.ndarray:
    """Chebyshev series with per-point coefficient rows ``coef`` (..., DEG+1) at ``y``."""
    b1 = np.zeros(y.shape)
    b2 = np.zeros(y.shape)
    y2 = 2.0 * y
    for k in range(coef.shape[-1] - 1, 0, -1):
        b1, b2 = coef[..., k] + y2 * b1 - b2, b1
    return coef[..., 0] + y * b1 - b2


def _clenshaw_rows(coef_t: np.ndarray, y: np.ndarray) -> np.ndarray:
    """:func:`_clenshaw` with one coefficient row per row of ``y`` (rows x points), the
    coefficients given degree-major (``coef_t``: DEG+1 x rows). In place on three buffers, the
    same operations in the same order (``(c_k + 2y b1) - b2``), so the same bits."""
    b1 = np.zeros(y.shape)
    b2 = np.zeros(y.shape)
    t = np.empty(y.shape)
    y2 = 2.0 * y
    for k in range(coef_t.shape[0] - 1, 0, -1):
        np.multiply(y2, b1, out=t)
        np.add(coef_t[k][:, None], t, out=t)
        np.subtract(t, b2, out=t)
        b1, b2, t = t, b1, b2
    np.multiply(y, b1, out=t)
    np.add(coef_t[0][:, None], t, out=t)
    return np.subtract(t, b2, out=t)


def _cache(profile) -> dict:
    """Cached far-segment rules and per-segment series of ``profile`` (set up on first use).

    Per segment ``k`` of width ``h``, ``F_k(w) = w q(b_k + w²)`` on ``0 <= w <= sqrt(h)`` is
    analytic (the square-root cusp of a linear table's g' at ``b_k`` becomes ``1/w``), its
    nearest singularity the previous node at ``w = i sqrt(h_{k-1})``: a degree-16 Chebyshev
    series, checked against the node sums at 7 further points and, like the far rules, against
    the segment's exact ``∫ q dx = g(b_{k+1}) - g(b_k) - g'(0+) h`` (``fit_err``, absolute, in
    units of ``F``)."""
    cache = profile.__dict__.get("_table_pressure_cache")
    if cache is None:
        b = np.asarray(profile.table_nodes(), dtype=float)
        g0 = _axis_term(profile)
        h = np.diff(b)
        sq = np.sqrt(h)
        out = {"nodes": b, "g0": g0, "sqrt_h": sq}
        # each segment's integral of q is known exactly from g at the nodes: the rules and the
        # series are checked against it (a segment next to a much narrower one, whose node's
        # cusp sits almost on this segment's start, fails here and its radii fall back)
        g_nodes = profile._g(b)
        seg_int = np.diff(g_nodes) - g0 * h
        seg_tol = 64 * np.finfo(float).eps * (np.abs(g_nodes[1:]) + np.abs(g_nodes[:-1]))
        for key, (u, w) in (("hi", _FAR), ("lo", _FAR_LO)):
            x = np.minimum(b[:-1, None] + h[:, None] * u[None, :] ** 2, b[1:, None])
            q, est = _q(profile, x, g0)
            jac = w[None, :] * 2.0 * h[:, None] * u[None, :]
            wq = jac * q
            miss = np.maximum(np.abs(wq.sum(axis=1) - seg_int) - seg_tol, 0.0)
            out[key] = (np.ascontiguousarray(x * x), np.ascontiguousarray(wq),
                        np.abs(jac * est).sum(axis=1) + miss)
        ys = np.concatenate([_CHEB_Y, _CHECK_Y])
        wv = 0.5 * sq[:, None] * (1.0 + ys[None, :])
        xv = np.minimum(b[:-1, None] + wv * wv, b[1:, None])
        q, est = _q(profile, xv, g0)
        F = wv * q
        coef = F[:, :_DEG + 1] @ _CHEB_V.T
        fit = _clenshaw(coef[:, None, :], np.broadcast_to(_CHECK_Y, (h.size, _CHECK_Y.size)))
        out["coef"] = np.ascontiguousarray(coef)
        out["coef_t"] = np.ascontiguousarray(coef.T)
        # ∫ q dx over the segment = ∫ 2 F dw = sqrt(h) ∫ F dy: its miss, as a mean error of F
        miss = np.maximum(np.abs(sq * (coef @ _CHEB_INT) - seg_int) - seg_tol, 0.0)
        out["fit_err"] = (np.max(np.abs(fit - F[:, _DEG + 1:]), axis=1)
                          + np.max(wv * est, axis=1) + miss / (2.0 * sq))
        cache = out
        profile.__dict__["_table_pressure_cache"] = cache
    return cache


def _series(c: dict, k: np.ndarray, w: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``F_k(w)`` on segment ``k[i]`` at the points ``w[i, :]``, and the series' fit error per
    row."""
    y = 2.0 * w / c["sqrt_h"][k][:, None] - 1.0
    return _clenshaw_rows(c["coef_t"][:, k], y), c["fit_err"][k]


#: the compiled pass (:mod:`contactlab.numeric.table_kernels`): ``"on"``: compiled by numba
#: (False: its plain Python logic, for tests); ``"from"``: fewest rows it takes
_COMPILED: dict = {"on": True, "from": _table_kernels.TABLE_ROWS_FROM}
_NEAR_U2 = _NEAR_BOTH[0] ** 2


def _compiled_rows(rows: int) -> bool:
    """Whether :func:`_piece` takes the compiled pass for ``rows`` radii (the same bits as the
    numpy route below it)."""
    if rows < _COMPILED["from"]:
        return False
    return not _COMPILED["on"] or _normal_kernels.backend() == "numba"


def _piece(c: dict, k: np.ndarray, s1: np.ndarray, s2: np.ndarray, hi: np.ndarray,
           r: np.ndarray, r_is_s2: bool) -> tuple[np.ndarray, np.ndarray]:
    """``∫_{s2}^{hi} q(x)/sqrt(x² - r²) dx`` inside segment ``k`` (1-D arrays), with ``s1 <= s2``
    the two nearly coalescing singular points (the segment's left node ``b_k`` and ``r``, in
    either order: ``r_is_s2``).

    ``x = m + δ cosh t`` (``m``, ``δ`` the centre and half-distance of ``s1``, ``s2``) turns
    ``dx / sqrt((x - s1)(x - s2))`` into ``dt``; with ``w = sqrt(x - b_k)`` the integrand is
    ``F_k(w) / sqrt(x + r)``, smooth in ``t``. 20-point rule in ``t``, error from 12 points plus
    the series' fit error. ``s1 == s2`` (``r`` on the node: the axis, or a cubic table's node)
    takes ``x = r + L u²`` instead."""
    delta = 0.5 * (s2 - s1)
    span = np.maximum(hi - s2, 0.0)
    same = delta <= 0.0
    with np.errstate(divide="ignore", invalid="ignore"):
        T = np.where(same, 1.0, np.arccosh(np.maximum(1.0 + span / np.where(same, 1.0, delta),
                                                      1.0)))
    # both rules in one pass (points of the 20-point rule, then the 12-point one); rows with
    # s1 == s2 are rare (the axis, a cubic table's node) and patched afterwards
    u, wts = _NEAR_BOTH
    half = 0.5 * (T[:, None] * u[None, :])
    sh = np.sinh(half)
    ch = np.cosh(half)
    if _compiled_rows(k.size):
        v_hi = np.empty(k.shape)
        err = np.empty(k.shape)
        with np.errstate(divide="ignore", invalid="ignore"):
            _table_kernels.kernel(_COMPILED["on"])(
                c["coef_t"], c["sqrt_h"], c["fit_err"], k, T, delta, s2, span, r, sh, ch, u,
                _NEAR_U2, wts, _N_HI, r_is_s2, v_hi, err)
        return v_hi, err
    d2 = 2.0 * delta[:, None]
    # x - s2 = 2δ sinh²(t/2), x - s1 = 2δ cosh²(t/2)
    x = s2[:, None] + d2 * sh * sh
    w = np.sqrt(d2) * (ch if r_is_s2 else sh)
    some = bool(np.any(same))
    if some:
        sm = np.flatnonzero(same)
        x[sm] = s2[sm, None] + span[sm, None] * u[None, :] ** 2          # x = r + L u²
        w[sm] = np.sqrt(span[sm])[:, None] * u[None, :]
    F, fe = _series(c, k, w)
    with np.errstate(divide="ignore", invalid="ignore"):
        # t-rule: dt-weight T w; u²-rule: dx/sqrt(x² - r²) q = 2 L u du F/(w sqrt(x-r)
        # sqrt(x+r)) with x - r = L u², w = sqrt(L) u: 2 F/(u sqrt(x + r)) * sqrt(L)/sqrt(L)
        root = np.sqrt(x + r[:, None])
        kern = T[:, None] * wts[None, :] / root
        if some:
            kern[sm] = wts[None, :] * 2.0 / (u[None, :] * root[sm])
    empty = span <= 0
    if np.any(empty):
        kern[empty] = 0.0
    prod = kern * F
    v_hi = np.sum(prod[:, :_N_HI], axis=1)
    v_lo = np.sum(prod[:, _N_HI:], axis=1)
    weight = np.sum(np.abs(kern[:, :_N_HI]), axis=1)
    with np.errstate(invalid="ignore"):
        err = np.where(weight > 0, weight * fe, 0.0)
    return v_hi, np.abs(v_hi - v_lo) + err


def pressure_shape(profile, r: np.ndarray, a: np.ndarray, rtol: float
                   ) -> tuple[np.ndarray, np.ndarray] | None:
    """``S(r, a)`` of a table and its error estimate, or None (not a table, or too fine).

    ``r`` and ``a`` broadcast; 0 for ``r >= a``. See the module docstring.
    """
    if not profile.has("node_table") or not hasattr(profile, "table_axis_slope"):
        return None
    nodes = profile.table_nodes()
    if nodes.size > MAX_NODES:
        return None
    r, a = np.broadcast_arrays(np.asarray(r, float), np.asarray(a, float))
    out = np.zeros(r.shape)
    err = np.zeros(r.shape)
    inside = r < a
    if not np.any(inside):
        return out, err
    profile._guard(a[inside], "a")
    c = _cache(profile)
    b, g0 = c["nodes"], c["g0"]
    nseg = b.size - 1
    rr, aa = r[inside], a[inside]
    # the cone of the axis slope, in closed form
    if g0 != 0.0:
        with np.errstate(divide="ignore"):
            val = g0 * np.arccosh(aa / rr)
    else:
        val = np.zeros(rr.shape)
    er = np.zeros(rr.shape)
    kr = np.clip(np.searchsorted(b, rr, side="right") - 1, 0, nseg - 1)
    ka = np.clip(np.searchsorted(b, aa, side="left") - 1, 0, nseg - 1)   # a in (b_ka, b_ka+1]
    b0 = b[kr]
    b1 = b[np.minimum(kr + 1, nseg)]
    b2 = b[np.minimum(kr + 2, nseg)]
    # [r, min(b_{kr+1}, a)] in r's segment (singular points b_kr <= r), then
    # [b_{kr+1}, min(b_{kr+2}, a)] in the next one (singular points r < b_{kr+1})
    vA, eA = _piece(c, kr, b0, rr, np.minimum(b1, aa), rr, True)
    nxt = (kr + 1 < nseg) & (b1 < aa)
    vB, eB = _piece(c, np.minimum(kr + 1, nseg - 1), rr, b1, np.where(nxt, np.minimum(b2, aa), b1),
                    rr, False)
    val += vA + vB
    er += eA + eB
    for j in range(2, NEAR_SEGMENTS):       # the next whole segments, same rule
        lo_j = b[np.minimum(kr + j, nseg)]
        hi_j = b[np.minimum(kr + j + 1, nseg)]
        more = (kr + j < nseg) & (lo_j < aa)
        vj, ej = _piece(c, np.minimum(kr + j, nseg - 1), rr, lo_j,
                        np.where(more, np.minimum(hi_j, aa), lo_j), rr, False)
        val += vj
        er += ej
    # the part of a's segment below a, when it lies beyond b_{kr+3}
    tail = ka >= kr + NEAR_SEGMENTS
    if np.any(tail):
        kt = ka[tail]
        lo_t = b[kt]
        vT, eT = _piece(c, kt, rr[tail], lo_t, aa[tail], rr[tail], False)
        val[tail] += vT
        er[tail] += eT
    # whole segments kr+3 <= k < ka, from the cached rules: per radius and segment the rule's
    # sum (entries outside that range are finite and then dropped)
    x2, wq, rnd = c["hi"]
    x2_lo, wq_lo, _ = c["lo"]
    # radii in blocks (sorted: the blocks of a radius array like the peak's 1024 see only the
    # segments above their own smallest radius, half the work of the full rectangle)
    order = np.argsort(rr, kind="stable")
    tiny = np.finfo(float).tiny
    for start in range(0, rr.size, _BLOCK):
        idx = order[start:start + _BLOCK]
        k_lo = int(np.min(kr[idx])) + NEAR_SEGMENTS
        k_hi = int(np.max(ka[idx]))
        if k_hi <= k_lo:
            continue
        xs2, ws = x2[k_lo:k_hi], wq[k_lo:k_hi]
        segs = np.arange(k_lo, k_hi)
        d = xs2[None, :, :] - (rr[idx] * rr[idx])[:, None, None]
        np.maximum(d, tiny, out=d)
        np.sqrt(d, out=d)
        np.divide(1.0, d, out=d)
        per_seg = np.einsum("msp,sp->ms", d, ws)
        use = (segs[None, :] >= kr[idx, None] + NEAR_SEGMENTS) & (segs[None, :] < ka[idx, None])
        val[idx] += np.where(use, per_seg, 0.0).sum(axis=1)
        # rounding of the cached values, bounded by the largest kernel (nearest segment)
        k_near = np.clip(kr[idx] + NEAR_SEGMENTS - k_lo, 0, segs.size - 1)
        er[idx] += d[np.arange(idx.size), k_near, 0] * np.where(use, rnd[k_lo:k_hi], 0.0).sum(axis=1)
    # far-rule error: the nearest cached segment, 8 against 6 points
    near_far = kr + NEAR_SEGMENTS
    has = near_far < ka
    if np.any(has):
        k = near_far[has]
        r2 = (rr[has] ** 2)[:, None]
        hi8 = np.sum(wq[k] / np.sqrt(np.maximum(x2[k] - r2, 1e-300)), axis=1)
        lo6 = np.sum(wq_lo[k] / np.sqrt(np.maximum(x2_lo[k] - r2, 1e-300)), axis=1)
        er[has] += np.abs(hi8 - lo6)
    # exactly on a node where a linear table's slope jumps: logarithmically infinite
    on = np.zeros(rr.shape, dtype=bool)
    if profile.has("linear_table"):
        jn = np.searchsorted(b, rr)   # (j is the segment loop's int above)
        on = (jn > 0) & (jn < nseg) & (b[np.minimum(jn, nseg)] == rr)
        ds = np.diff(profile.table_slopes())
        jump = np.where(on, ds[np.clip(jn - 1, 0, ds.size - 1)], 0.0)
        on &= jump != 0
        val[on] = np.sign(jump[on]) * np.inf
        er[on] = 0.0
    # radii the rules could not resolve (estimate above the tolerance, or not finite): the
    # profile's own route
    a_u, inv = np.unique(aa, return_inverse=True)
    scale = np.abs(val) + (profile._g(a_u, rtol) / a_u)[inv.reshape(aa.shape)]   # S ~ g(a)/a
    with np.errstate(invalid="ignore"):
        fine = np.isfinite(val) & (er <= rtol * scale)
    tip = np.isinf(val) & (rr == 0) & (g0 != 0.0)           # the cone tip on the axis
    bad = ~(fine | on | tip)
    if np.any(bad):
        from .normal import pressure_shape as general
        v2, e2 = general(profile, rr[bad], aa[bad], rtol, table_rules=False)
        val[bad], er[bad] = v2, e2
    out[inside] = val
    err[inside] = er
    return out, err
