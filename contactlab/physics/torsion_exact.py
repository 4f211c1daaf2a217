"""Exact partial-slip torsion: Jäger's flat-punch superposition [J95; S eqs. 24-30, 35, 43-44, 53].

Pure, vectorised kernels (theory §6.2). With the slip function

    P(x) = ∫_x^a p(s)/sqrt(s²-x²) ds,

the stick radius ``c`` follows from ``φ = μ/(2G_t) P(c)`` [S eq. 53], the torque is
``M = (16/3) G_t φ c³ + 8μ T(c)`` with ``T(c) = ∫_c^a x² P(x) dx``, and full sliding
(``c → 0``) gives ``M_full = πμE* ∫_0^a x (d - g(x)) dx``.

Neither P nor T needs the pressure. Inserting ``p`` from the MDR profile ``g`` and swapping the order
of integration (``∫_x^t ds/sqrt((s²-x²)(t²-s²)) = K(k)/t`` with ``k² = 1 - x²/t²``) gives

    P(x) = (E*/π) [ ∫_x^a g'(t) K(k_t)/t dt + (d - g(a)) K(k_a)/a ]
         = (E*/π) [ (g(a)-g(x)) K(k_a)/a + ∫_x^a (g(t)-g(x)) (K-E)(k_t)/(k_t² t²) dt
                    + (d - g(a)) K(k_a)/a ]                                   (by parts)

    T(c) = (E*/π) [ ∫_c^a (g(a)-g(t)) (2t h(c/t) + (c³/t²) K(k_t)) dt + (d - g(a)) a² h(c/a) ]

with the universal kernel ``h(v) = ∫_v^1 u² K(sqrt(1-u²)) du`` (``h(0) = π²/16``). The by-parts forms
need only ``g`` (continuous even where ``g'`` is singular: truncated profiles, tables), their
integrands are bounded and positive (no cancellation), and the quadratures run in ``w = ln t`` so
that ``c/a`` down to 1e-100 costs no more than ``c/a = 0.5``. ``K`` and ``(K-E)/k²`` are evaluated as
Carlson integrals ``R_F(0, 1-k², 1)`` and ``R_D(0, 1-k², 1)/3`` (no cancellation as ``k → 0`` or
``k → 1``).

References
----------
J. Jäger, Arch. Appl. Mech. 65 (1995). R. L. Lubkin, J. Appl. Mech. 18 (1951) 183.
"""
from __future__ import annotations

import numpy as np

from ..numeric.quadrature import tanh_sinh
from .stick_brackets import _CURVE_REFINE, _bracketed, _grid_brackets
from .torsion_elliptic import K_comp, h_kernel, kme_over_m
from .torsion_split import Summed, per_element, split_at_cuts

__all__ = ["K_comp", "kme_over_m", "h_kernel", "slip_function", "torque_integral", "panels_apply",
           "x_g_integral", "sliding_torque", "twist_of_stick", "torque_of_stick",
           "dissipation_integral", "stick_shear", "circumferential_displacement",
           "solve_stick_of_twist", "solve_stick_of_torque",
           "C_MIN_REL", "sharpen_error", "QUAD_SAFETY"]

#: Stick radii below ``C_MIN_REL * a`` count as full sliding: the torque then differs from the
#: sliding torque by ~(c/a)³ < 1e-300 relative (and ``K(k)`` would overflow the float range).
C_MIN_REL = 1e-100


#: Safety factor of :func:`sharpen_error` (issue 7), measured on the honesty ladder of
#: tests/unit/effects/test_torsion_error_estimate.py.
QUAD_SAFETY = 10.0


def sharpen_error(err: np.ndarray, val: np.ndarray) -> np.ndarray:
    """Error of the *returned* tanh-sinh value from its estimate (issue 7).

    :func:`~contactlab.numeric.quadrature.tanh_sinh` reports the change between its last two
    levels, which bounds the error of the previous level; the error roughly squares per level, so
    the returned value errs by about ``err²/|val|``. Returns ``min(err, QUAD_SAFETY err²/|val|)``.
    """
    err = np.abs(err)
    with np.errstate(divide="ignore", invalid="ignore"):
        sq = QUAD_SAFETY * err * err / np.abs(val)
    return np.where(np.isfinite(sq), np.minimum(err, sq), err)


# ---------------------------------------------------------------- quadrature plumbing
#: tables (linear or cubic) with more nodes than this take the composite route
#: (:func:`_integrate_table`)
_TABLE_SPLIT_MAX = 48
#: Gauss-Legendre order per table segment of the composite route (with ``t = r_j + Δ u²``). The
#: nearest singularity (the cusp of g at the previous node) lies at ``u = ±i``, a Bernstein ellipse
#: of ρ ≈ 4.6 for ``u ∈ [0, 1]``: error ~ρ^(-16) ≈ 2e-11 of that node's share; measured agreement
#: with the split adaptive route: 3e-13 (rtol 1e-12). A cubic spline's g has only
#: ``(t - r_j)^(5/2)`` kinks at the nodes (``u^5`` after the substitution), so the same rule serves.
_TABLE_GL = 8


def _table_nodes(profile) -> np.ndarray | None:
    """Interior nodes of a piecewise-linear table (where ``g`` has sqrt cusps), else None."""
    return profile.table_nodes() if profile.has("linear_table") else None


def _composite_nodes(profile) -> np.ndarray | None:
    """Nodes of a table whose g is analytic between them (linear or cubic), else None."""
    return profile.table_nodes() if profile.has("node_table") else None


def _cuts(profile) -> list[float]:
    cuts = {b for b in (*profile.breakpoints, profile.flat_radius) if b > 0}
    nodes = _table_nodes(profile)
    if nodes is not None and nodes.size <= _TABLE_SPLIT_MAX:
        cuts |= {float(b) for b in nodes[1:-1] if b > 0}
    return sorted(cuts)


def _log_segments(profile, lo: np.ndarray, hi: np.ndarray):
    """Split ``[lo, hi]`` (per element) at the profile's breakpoints, in ``w = ln t``.

    Returns ``(w_lo, w_hi, t_lo, t_hi)`` of shape ``(n_seg, n)``; empty segments have equal ends.
    """
    cuts = _cuts(profile)
    t_edges = np.stack([lo] + [np.clip(np.full_like(lo, b), lo, hi) for b in cuts] + [hi])
    with np.errstate(divide="ignore"):
        w_edges = np.log(t_edges)
    return w_edges[:-1], w_edges[1:], t_edges[:-1], t_edges[1:]


def _integrate_log(profile, kernel, lo: np.ndarray, hi: np.ndarray, rtol: float,
                   atol: np.ndarray, panels: bool = False) -> tuple[np.ndarray, np.ndarray]:
    """``Σ_segments ∫ kernel(t, g(t), idx) t dw`` over ``t ∈ [lo, hi]`` (``w = ln t``), per element.

    ``kernel(t, g_t, idx)`` receives nodes ``t`` (shape (m, k)), ``g`` there and the flat element
    indices ``idx`` (shape (m,)) into ``lo``/``hi``. Nodes are clipped into their exact segment so
    that rounding of ``exp(ln t)`` never crosses a breakpoint. Large tables (linear or cubic) go
    through :func:`_integrate_table` (``panels``: with its product-integration panels).
    """
    nodes = _composite_nodes(profile)
    if nodes is not None and nodes.size > _TABLE_SPLIT_MAX:
        return _integrate_table(profile, kernel, lo, hi, rtol, atol, panels)
    w_lo, w_hi, t_lo, t_hi = _log_segments(profile, lo, hi)
    n_seg, n = w_lo.shape
    elem = np.broadcast_to(np.arange(n), (n_seg, n)).ravel()
    tl = t_lo.ravel()
    th = t_hi.ravel()

    def integrand(w: np.ndarray, idx: np.ndarray) -> np.ndarray:
        t = np.clip(np.exp(w), tl[idx][:, None], th[idx][:, None])
        return kernel(t, profile._g(t), elem[idx]) * t

    at = np.broadcast_to(np.asarray(atol, float), (n_seg, n)).ravel() / n_seg
    res = tanh_sinh(integrand, w_lo.ravel(), w_hi.ravel(), rtol=rtol, atol=at)
    return (res.value.reshape(n_seg, n).sum(axis=0), res.error.reshape(n_seg, n).sum(axis=0))


_TABLE_CACHE: dict = {}
_GAUSS: dict = {}


def _gauss_unit(q: int) -> tuple[np.ndarray, np.ndarray]:
    """``q``-point Gauss-Legendre nodes and weights on [0, 1] (cached: the eigenvalue solve
    costs ~1 ms, as much as a whole curve step)."""
    hit = _GAUSS.get(q)
    if hit is None:
        u, wu = np.polynomial.legendre.leggauss(q)
        hit = _GAUSS[q] = (0.5 * (u + 1.0), 0.5 * wu)
    return hit


def panels_apply(profile, a: np.ndarray) -> bool:
    """Whether the product-integration panels take part for contact radii ``a`` (m): a node
    table on the composite route (more than ``_TABLE_SPLIT_MAX`` nodes) with a panel starting
    inside the largest contact. Only then does the curve route differ from the composite one
    (every other profile and state keeps its bits)."""
    nodes = _composite_nodes(profile)
    if nodes is None or nodes.size <= _TABLE_SPLIT_MAX:
        return False
    from .table_panels import panels_of
    pan = panels_of(profile)
    return bool(pan.start.size) and float(nodes[pan.start[0]]) < float(np.max(a, initial=0.0))


def _g_route(profile, panels: bool):
    """``g`` of the profile at fresh points: with ``panels`` (the curve route) a linear table's
    per-segment cached form (:func:`contactlab.physics.table_panels.fast_g`, same values to
    rounding, O(1) per point), else ``profile._g``."""
    if not panels:
        return profile._g
    from .table_panels import fast_g
    return lambda t: fast_g(profile, t)


def _table_rule(profile, upto: float | None = None
                ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Composite rule over every table segment: nodes (n_seg, q), weights, g at the nodes, ends.

    On segment ``[r_j, r_{j+1}]``: ``t = r_j + Δ u²`` (the sqrt cusp of g at ``r_j`` becomes smooth)
    and ``q``-point Gauss-Legendre in ``u ∈ [0, 1]``. g is evaluated once per profile (cached by
    the profile's value identity; a few tables at most are kept), and only on the segments below
    ``upto`` (extended on demand): each g costs O(nodes below it), so a contact over the first
    tenth of a table costs a hundredth of the whole table.
    """
    key = (hash(profile), profile.table_nodes().size)
    hit = _TABLE_CACHE.get(key)
    if hit is None or hit[0] != profile:
        u, wu = np.polynomial.legendre.leggauss(_TABLE_GL)
        u = 0.5 * (u + 1.0)
        wu = 0.5 * wu
        r = profile.table_nodes()
        left, width = r[:-1, None], np.diff(r)[:, None]
        t = left + width * u**2
        w = 2.0 * width * u * wu
        # (unfilled g is 0, not NaN: masked-out segments still pass through the kernels, and
        # special functions of NaN take slow paths)
        hit = [profile, (t, w, np.zeros(t.shape), r), 0]
        if len(_TABLE_CACHE) > 8:
            _TABLE_CACHE.clear()
        _TABLE_CACHE[key] = hit
    t, w, g, r = hit[1]
    n_seg = t.shape[0]
    need = n_seg if upto is None else min(n_seg, int(np.searchsorted(r, upto, side="left")) + 1)
    done = hit[2]
    if need > done:
        # grow geometrically so that a slowly rising contact radius costs O(1) extensions
        need = min(n_seg, max(need, done + done // 2))
        g[done:need] = profile._g(t[done:need].ravel()).reshape(need - done, t.shape[1])
        hit[2] = need
    return hit[1]


def _integrate_table(profile, kernel, lo: np.ndarray, hi: np.ndarray, rtol: float,
                     atol: np.ndarray, panels: bool = False) -> tuple[np.ndarray, np.ndarray]:
    """``∫_lo^hi kernel(t, g(t), idx) dt`` for a large table (N nodes, g analytic between them:
    sqrt cusps of a linear table, weaker kinks of a cubic spline).

    Every table segment is integrated with ``t = left + Δ u²`` and 8-point Gauss-Legendre in ``u``
    (the sqrt cusp of g at a node becomes smooth): the whole segments by the cached rule of
    :func:`_table_rule` (g at fixed nodes, nothing of O(N) recomputed), the last partial segment
    ``[r_j, hi]`` with g computed once per distinct ``hi``, the first partial segment
    ``[lo, r_{j+1}]`` with 8 fresh nodes (its length is at most ``lo``, so the kernel, which
    varies on the scale ``lo``, is smooth there). A ``lo`` inside the first segment, where the
    kernel may vary over many decades, is integrated adaptively in ``ln t`` with the closed-form
    g of that segment (``profile.table_g_first``); only this part carries an error estimate. The composite
    rule's own error is verified in the tests against the split adaptive route (1e-9).

    ``panels=True``: the whole segments inside the product-integration panels of
    :mod:`contactlab.physics.table_panels` are integrated there (``PANEL_POINTS`` kernel
    evaluations per panel instead of 8 per segment; ``kernel`` must be linear in ``g`` and
    analytic in ``t > 0``, as every kernel of this module is; a kernel that declares its
    factors ``kernel.separated`` is interpolated in the lower limit ``lo`` as well, so points
    in a panel's range take no kernel evaluation on the panels).
    """
    t_n, w_n, g_n, r = _table_rule(profile, float(np.max(hi, initial=0.0)))
    g_of = _g_route(profile, panels)
    n = lo.size
    q = t_n.shape[1]
    u, wu = _gauss_unit(q)
    j_lo = np.clip(np.searchsorted(r, lo, side="right") - 1, 0, r.size - 2)
    j_hi = np.clip(np.searchsorted(r, hi, side="left") - 1, 0, r.size - 2)
    same = j_lo >= j_hi
    a_end = np.where(same, hi, r[j_lo + 1])
    val = np.zeros(n)
    err = np.zeros(n)
    # first piece [lo, a_end]
    seg0 = j_lo == 0
    if np.any(seg0):
        ids = np.flatnonzero(seg0)
        l0, h0 = lo[ids], a_end[ids]

        def integrand(w: np.ndarray, idx: np.ndarray) -> np.ndarray:
            t = np.clip(np.exp(w), l0[idx][:, None], h0[idx][:, None])
            return kernel(t, profile.table_g_first(t), ids[idx]) * t

        at = np.broadcast_to(np.asarray(atol, float), (n,))[ids] / 2.0
        res = tanh_sinh(integrand, np.log(l0), np.log(np.maximum(h0, l0)), rtol=rtol, atol=at)
        val[ids] += res.value
        err[ids] += res.error
    rest = np.flatnonzero(~seg0 & (a_end > lo))
    if rest.size:
        width = (a_end[rest] - lo[rest])[:, None]
        tt = lo[rest][:, None] + width * u**2
        ww = 2.0 * width * u * wu
        if panels:                  # every node in segment j_lo (j_lo >= 1 here)
            from .table_panels import fast_g_in
            gg = fast_g_in(profile, tt, j_lo[rest])
        else:
            gg = g_of(tt.ravel()).reshape(tt.shape)
        with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
            val[rest] += np.sum(kernel(tt, gg, rest) * ww, axis=1)
    # last piece [r_j_hi, hi], g once per distinct piece
    ends = np.flatnonzero(~same)
    piece = None
    if ends.size:
        b0, h0 = r[j_hi[ends]], hi[ends]
        if np.all(h0 == h0[0]):            # one normal state (a curve): np.unique's answer
            keys, inv = np.array([[b0[0], h0[0]]]), np.zeros(ends.size, dtype=np.intp)
        else:
            keys, inv = np.unique(np.stack([b0, h0], axis=1), axis=0, return_inverse=True)
            inv = inv.ravel()
        kw = (keys[:, 1] - keys[:, 0])[:, None]
        kt = keys[:, :1] + kw * u**2
        kg = g_of(kt.ravel()).reshape(kt.shape)
        kww = 2.0 * kw * u * wu
        piece_of = np.full(n, -1, dtype=np.intp)
        piece_of[ends] = inv
        piece = (kt, kg, kww, piece_of)
    # whole segments j_lo+1 .. j_hi-1: one row of q rule nodes per (element, segment), no
    # padding, chunked over elements so that a chunk holds at most ~2e6 nodes
    first, last = j_lo + 1, j_hi - 1
    covered = None
    v_p = None
    if panels:
        from . import table_panels as _tp
        pan = _tp.panels_of(profile)
        # (g is filled up to the largest hi, beyond every segment a panel takes here; the
        # panels' x-interpolated sums take the last pieces of their points too)
        v_p, covered, taken = _tp.integrate(pan, kernel, first, last, n, (t_n, w_n, g_n), lo,
                                            piece)
        if piece is not None:
            keep = ~taken[ends]
            ends, inv = ends[keep], inv[keep]
    if ends.size and piece is not None:
        with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
            val[ends] += np.sum(kernel(kt[inv], kg[inv], ends) * kww[inv], axis=1)
    if v_p is not None:
        val += v_p
    count = np.maximum(last - first + 1, 0)
    direct = None
    if covered is not None:
        # only the segments outside every panel, as positions in their sorted list
        direct = np.flatnonzero(~covered)
        first = np.searchsorted(direct, first, side="left")
        count = np.maximum(np.searchsorted(direct, last, side="right") - first, 0)
    todo = np.flatnonzero(count > 0)
    q = t_n.shape[1]
    ends = np.cumsum(count[todo])
    start = 0
    while start < todo.size:
        base = ends[start - 1] if start else 0
        stop = max(start + 1, int(np.searchsorted(ends, base + 2_000_000 // q, side="right")))
        ids = todo[start:stop]
        cnt = count[ids]
        elem = np.repeat(ids, cnt)                                  # element of each row
        offs = np.arange(elem.size) - np.repeat(np.cumsum(cnt) - cnt, cnt)
        seg = first[elem] + offs
        if direct is not None:                    # the panels took the other segments
            seg = direct[seg]
        with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
            f = kernel(t_n[seg], g_n[seg], elem)
        val += np.bincount(elem, weights=np.sum(f * w_n[seg], axis=1), minlength=n)
        start = stop
    return val, err


# ---------------------------------------------------------------- the slip function P
def _slip_shape(t: np.ndarray, x: np.ndarray) -> np.ndarray:
    """``(K - E)/k² / t²`` with ``k² = 1 - x²/t²``: the slip kernel is this times ``g(t) - g(x)``."""
    return kme_over_m((x / t) ** 2) / (t * t)


def _torque_shape(t: np.ndarray, c: np.ndarray) -> np.ndarray:
    """``2t h(c/t) + (c³/t²) K(k_t)``: the torque kernel is this times ``g(a) - g(t)``."""
    v = c / t
    return 2.0 * t * h_kernel(v) + c * v * v * K_comp(v * v)


def slip_function(profile, E_star: float, x: np.ndarray, a: np.ndarray, d: np.ndarray,
                  g_a: np.ndarray, rtol: float, panels: bool = False
                  ) -> tuple[np.ndarray, np.ndarray]:
    """``P(x) = ∫_x^a p(s)/sqrt(s²-x²) ds`` (Pa), ``0 < x <= a``; returns (value, error estimate).

    [S eq. 53]; by-parts swapped form of the module docstring. ``P(a) = 0`` unless ``d != g(a)``
    (flat punch: ``P(a) = π E* d/(2a)``). Arrays broadcast. ``panels``: large tables integrate
    on their product-integration panels (:mod:`contactlab.physics.table_panels`).
    """
    x, a, d, g_a = np.broadcast_arrays(*(np.asarray(v, float) for v in (x, a, d, g_a)))
    shape = x.shape
    x, a, d, g_a = (v.ravel() for v in (x, a, d, g_a))
    g_x = _g_route(profile, panels)(x)
    # (a = 0, out of contact: nan here, never read by the callers, which mask those states)
    with np.errstate(divide="ignore", invalid="ignore"):
        p_a = (x / a) ** 2
        Ka = K_comp(p_a)
        boundary = (g_a - g_x) * Ka / a + (d - g_a) * Ka / a
    val = boundary.copy()
    err = np.zeros(x.shape)
    todo = np.flatnonzero((x < a) & (g_a > 0))
    if todo.size:
        xs, as_, gxs = x[todo], a[todo], g_x[todo]

        def kernel(t: np.ndarray, gt: np.ndarray, idx: np.ndarray) -> np.ndarray:
            xx = xs[idx][:, None]
            dg = gt - gxs[idx][:, None]
            return dg * kme_over_m((xx / t) ** 2) / (t * t)

        def linear(t: np.ndarray, idx: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
            A = kme_over_m((xs[idx][:, None] / t) ** 2) / (t * t)      # kernel = A g + B
            return A, -gxs[idx][:, None] * A

        kernel.linear = linear     # type: ignore[attr-defined]  # the panels' one evaluation
        # ... and kernel = F(t, x) (g - g(x)) with F analytic in x: interpolated in x as well
        kernel.separated = ("slip", _slip_shape, np.ones(todo.size), -gxs)  # type: ignore[attr-defined]
        scale = np.abs(boundary[todo]) + (g_a[todo] - gxs) / as_
        v, e = _integrate_log(profile, kernel, xs, as_, rtol, rtol * scale, panels)
        val[todo] += v
        err[todo] = e
    return E_star / np.pi * val.reshape(shape), E_star / np.pi * err.reshape(shape)


def torque_integral(profile, E_star: float, c: np.ndarray, a: np.ndarray, d: np.ndarray,
                    g_a: np.ndarray, rtol: float, panels: bool = False
                    ) -> tuple[np.ndarray, np.ndarray]:
    """``T(c) = ∫_c^a x² P(x) dx`` (N), ``0 <= c <= a``, as one swapped integral; (value, error).
    ``panels`` as in :func:`slip_function`."""
    c, a, d, g_a = np.broadcast_arrays(*(np.asarray(v, float) for v in (c, a, d, g_a)))
    shape = c.shape
    c, a, d, g_a = (v.ravel() for v in (c, a, d, g_a))
    edge = (d - g_a) * a * a * h_kernel(np.where(a > 0, c / np.where(a > 0, a, 1.0), 1.0))
    val = edge.copy()
    err = np.zeros(c.shape)
    todo = np.flatnonzero((c < a) & (g_a > 0))
    if todo.size:
        cs, as_, gas = c[todo], a[todo], g_a[todo]
        zero = cs <= 0
        if np.any(zero):
            # c = 0: T = (π²/8) ∫_0^a t (g(a) - g(t)) dt
            val[todo[zero]] += np.pi**2 / 8 * (0.5 * as_[zero] ** 2 * gas[zero]
                                               - x_g_integral(profile, as_[zero], rtol))
        pos = np.flatnonzero(~zero)
        if pos.size:
            cp, ap, gp = cs[pos], as_[pos], gas[pos]

            def kernel(t: np.ndarray, gt: np.ndarray, idx: np.ndarray) -> np.ndarray:
                cc = cp[idx][:, None]
                v = cc / t
                D = 2.0 * t * h_kernel(v) + cc * v * v * K_comp(v * v)
                return (gp[idx][:, None] - gt) * D

            def linear(t: np.ndarray, idx: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
                cc = cp[idx][:, None]
                v = cc / t
                D = 2.0 * t * h_kernel(v) + cc * v * v * K_comp(v * v)
                return -D, gp[idx][:, None] * D                           # kernel = A g + B

            kernel.linear = linear     # type: ignore[attr-defined]
            kernel.separated = ("torque", _torque_shape, -np.ones(pos.size), gp)  # type: ignore[attr-defined]
            scale = gp * ap * ap
            v, e = _integrate_log(profile, kernel, cp, ap, rtol, rtol * scale * 1e-3, panels)
            val[todo[pos]] += v
            err[todo[pos]] = e
    return E_star / np.pi * val.reshape(shape), E_star / np.pi * err.reshape(shape)


def x_g_integral(profile, a: np.ndarray, rtol: float) -> np.ndarray:
    """``∫_0^a x g(x) dx`` (m³): closed form for power terms and tables, otherwise quadrature."""
    a = np.asarray(a, float)
    if profile._has("_xg_integral_closed_form"):
        return np.where(a > 0, profile._xg_integral_closed_form(np.maximum(a, 0.0)), 0.0)
    terms = profile.power_terms()
    if terms is not None and not np.isfinite(profile.wall_radius):
        from ..symbolic.transform import kappa
        from ..numeric.powers import power_integral
        return power_integral(a, [(kappa(n) * cc, n) for cc, n in terms], 2.0)
    flat = a.ravel()
    lo = np.minimum(np.full(flat.shape, profile.flat_radius), flat)
    cuts = [b for b in _cuts(profile) if b > profile.flat_radius]
    edges = np.stack([lo] + [np.clip(np.full_like(flat, b), lo, flat) for b in cuts] + [flat])
    n_seg = edges.shape[0] - 1

    def integrand(x: np.ndarray, idx: np.ndarray) -> np.ndarray:
        return x * profile._g(x)

    res = tanh_sinh(integrand, edges[:-1].ravel(), edges[1:].ravel(), rtol=rtol,
                    atol=np.broadcast_to(1e-300, (n_seg * flat.size,)))
    return res.value.reshape(n_seg, flat.size).sum(axis=0).reshape(a.shape)


def sliding_torque(profile, E_star: float, mu: float, a: np.ndarray, d: np.ndarray,
                   rtol: float) -> np.ndarray:
    """Full-sliding torque ``M_full = 2πμ∫_0^a p r² dr = πμE* ∫_0^a x (d - g) dx`` (N·m).

    Includes the flat-punch edge term; Hertz: ``(3π/16) μ F a``.
    """
    a = np.asarray(a, float)
    d = np.asarray(d, float)
    return np.pi * mu * E_star * (0.5 * d * a * a - np.where(a > 0, x_g_integral(profile, a, rtol), 0.0))


def twist_of_stick(mu: float, G_t: float, P_c: np.ndarray) -> np.ndarray:
    """``φ = μ/(2G_t) P(c)`` [S eq. 53 with Φ(c) = 0], rad."""
    return mu / (2.0 * G_t) * P_c


def torque_of_stick(mu: float, G_t: float, c: np.ndarray, phi: np.ndarray,
                    T_c: np.ndarray) -> np.ndarray:
    """``M = (16/3) G_t φ c³ + 8μ T(c)`` (theory §6.2 item 3), N·m."""
    return 16.0 / 3.0 * G_t * phi * c**3 + 8.0 * mu * T_c


# ---------------------------------------------------------------- dissipation (Iwan picture)
def dissipation_integral(profile, E_star: float, c: np.ndarray, a: np.ndarray, d: np.ndarray,
                         g_a: np.ndarray, rtol: float) -> np.ndarray:
    """``J(c) = ∫_c^a x² P(x) (P(c) - P(x)) dx`` (N·Pa·m) for the dissipated energy.

    Under monotonic twisting the exact solution is a set of independent Jenkins elements in the
    1D coordinate: at ``x`` a rotational stiffness ``16 G_t x² dx`` that slips at the rotation
    ``(μ/2G_t) P(x)`` (theory §6.2 item 3). The energy dissipated while twisting from 0 to
    ``φ(c)`` is therefore ``D = 16G_t ∫_c^a x² θ_s (φ - θ_s) dx = (4μ²/G_t) J(c)``.

    Computed as ``J = P(c) T(c) - I(c)`` with ``I(c) = ∫_c^a x² P² dx`` accumulated from ``x = a``
    downwards over all requested ``c`` of one normal state at once: the pieces between consecutive
    stick radii, profile breakpoints and table nodes (refined to at most a factor 2 in ``x``) get a
    10-point Gauss-Legendre rule in ``x = left + Δu²`` (P has at most a sqrt cusp at a left end),
    with P at all nodes in one batched call. ``c >= a`` gives 0; ``c`` below ``C_MIN_REL a`` counts
    as ``C_MIN_REL a`` (the rest is ~1e-300 relative).
    """
    c, a, d, g_a = np.broadcast_arrays(*(np.asarray(v, float) for v in (c, a, d, g_a)))
    shape = c.shape
    c, a, d, g_a = (v.ravel() for v in (c, a, d, g_a))
    out = np.zeros(c.shape)
    todo = np.flatnonzero((c < a) & (a > 0))
    if todo.size == 0:
        return out.reshape(shape)
    cs = np.maximum(c[todo], C_MIN_REL * a[todo])
    keys, inv = np.unique(np.stack([a[todo], d[todo], g_a[todo]], axis=1), axis=0,
                          return_inverse=True)
    inv = inv.ravel()
    u, wu = np.polynomial.legendre.leggauss(10)
    u, wu = 0.5 * (u + 1.0), 0.5 * wu
    cut_pts = np.array(_cuts(profile), dtype=float)
    nodes = _table_nodes(profile)
    if nodes is not None:
        cut_pts = np.union1d(cut_pts, nodes[nodes > 0])
    for k, (ka, kd, kg) in enumerate(keys):
        sel = np.flatnonzero(inv == k)
        cc = cs[sel]
        lo = float(np.min(cc))
        n_geo = int(np.ceil(np.log2(ka / lo))) + 1
        edges = np.unique(np.concatenate([cc, cut_pts[(cut_pts > lo) & (cut_pts < ka)],
                                          ka * 2.0 ** -np.arange(n_geo), [ka]]))
        edges = edges[(edges >= lo) & (edges <= ka)]
        left, width = edges[:-1, None], np.diff(edges)[:, None]
        x = left + width * u**2
        w = 2.0 * width * u * wu
        P, _ = slip_function(profile, E_star, x.ravel(), ka, kd, kg, rtol)
        piece = np.sum(w * x**2 * P.reshape(x.shape) ** 2, axis=1)
        above = np.concatenate([np.cumsum(piece[::-1])[::-1], [0.0]])     # I at every edge
        I_c = above[np.searchsorted(edges, cc)]
        Pc, _ = slip_function(profile, E_star, cc, ka, kd, kg, rtol)
        Tc, _ = torque_integral(profile, E_star, cc, ka, kd, kg, rtol)
        out[todo[sel]] = np.maximum(Pc * Tc - I_c, 0.0)
    return out.reshape(shape)


# ---------------------------------------------------------------- fields
def stick_shear(psi, psi_l: np.ndarray, G_t: float, r: np.ndarray, ell: np.ndarray,
                a: np.ndarray, rtol: float) -> np.ndarray:
    """Circumferential traction from the twist distribution (theory §6.2 item 5, §8 item 1).

    ``τ(r) = (4G_t r/π) [ψ(ℓ)/sqrt(a²-r²) - ∫_ℓ^a (ψ(t) - ψ(ℓ)) t/(t²-r²)^{3/2} dt]`` for
    ``r <= ℓ < a`` (``ℓ = c`` in the stick zone, ``ℓ = r`` in the slip zone), where
    ``ψ(t) = φ - Φ(t)`` is the lag of the superposed flat-punch twists (exact model:
    ``ψ = μP/(2G_t)``; MDR: ``ψ = u_y/t``) and ``psi_l = ψ(ℓ)`` (``= φ`` at ``ℓ = c``).
    ``psi(t, idx)`` is vectorised over nodes ``t`` (m, k) of elements ``idx``. The bounded form
    handles the flat-punch jump of Φ at ``t = a``. Flat arrays of equal size, ``r < a``.
    """
    lo, hi, owner = split_at_cuts(psi, ell, a)

    def integrand(t: np.ndarray, idx: np.ndarray) -> np.ndarray:
        el = owner[idx]
        rr = r[el][:, None]
        dpsi = psi(t, el) - psi_l[el][:, None]
        return dpsi * t / ((t - rr) * (t + rr)) ** 1.5

    root = np.sqrt((a - r) * (a + r))
    scale = np.abs(psi_l) / root
    # ψ(t) - ψ(ℓ) carries the relative noise (~rtol) of the inner quadrature, amplified near
    # t = ℓ by (t²-r²)^{-3/2} when r is close to ℓ: the outer tolerance allows for it
    res = tanh_sinh(integrand, lo, hi, rtol=rtol, atol=10 * rtol * scale[owner] + 1e-300,
                    raise_on_failure=False)
    value = per_element(res.value, owner, ell.size)
    error = per_element(res.error, owner, ell.size)
    _check_field(Summed(value, error), rtol, scale, "stick-zone traction")
    return 4.0 * G_t * r / np.pi * (psi_l / root - value)


def _check_field(res, rtol: float, scale: np.ndarray, what: str) -> None:
    bad = res.error > 1e3 * rtol * (np.abs(res.value) + scale) + 1e-300
    if np.any(bad):
        from ..errors import ConvergenceError
        i = int(np.argmax(bad))
        raise ConvergenceError(f"{what}: quadrature error estimate {res.error.ravel()[i]:.3g} for a "
                               f"value {res.value.ravel()[i]:.6g} (rtol={rtol:g}); loosen rtol.")


def circumferential_displacement(psi, phi: np.ndarray, r: np.ndarray, c: np.ndarray,
                                 a: np.ndarray, rtol: float) -> np.ndarray:
    """``u_φ(r)`` (m) inside and outside the contact (theory §6.2 item 6, integrated by parts).

    ``u_φ = r φ`` for ``r <= c``; otherwise
    ``u_φ = (2/π) [φ W(c) + ∫_c^{min(r,a)} ψ(t) 2t²/(r sqrt(r²-t²)) dt]`` with
    ``W(t) = r asin(t/r) - t sqrt(1 - t²/r²)``. Flat arrays of equal size.
    """
    out = r * phi
    todo = np.flatnonzero(r > c)
    if todo.size == 0:
        return out
    rr, cc, aa, ph = r[todo], c[todo], a[todo], phi[todo]
    q = np.minimum(cc / rr, 1.0)
    W = rr * np.arcsin(q) - cc * np.sqrt((1 - q) * (1 + q))
    hi = np.minimum(rr, aa)

    lo, up, owner = split_at_cuts(psi, cc, hi)

    def integrand(t: np.ndarray, idx: np.ndarray) -> np.ndarray:
        el = owner[idx]
        rv = rr[el][:, None]
        return psi(t, todo[el]) * 2 * t * t / (rv * np.sqrt((rv - t) * (rv + t)))

    scale = np.abs(ph) * rr
    res = tanh_sinh(integrand, lo, up, rtol=rtol, atol=10 * rtol * scale[owner] + 1e-300,
                    raise_on_failure=False)
    value = per_element(res.value, owner, cc.size)
    _check_field(Summed(value, per_element(res.error, owner, cc.size)), rtol, scale,
                 "circumferential displacement")
    out[todo] = 2.0 / np.pi * (ph * W + value)
    return out


# ---------------------------------------------------------------- inverse problems
def solve_stick_of_twist(profile, E_star: float, G_t: float, mu: float, phi: np.ndarray,
                         a: np.ndarray, d: np.ndarray, g_a: np.ndarray,
                         rtol: float, panels: bool = False) -> np.ndarray:
    """Stick radius ``c`` (m) for twists ``phi >= 0`` (rad): root of ``μ P(c)/(2G_t) = φ``.

    Solved in ``y = ln(c/a)`` by the bracketed root finder (``φ`` is monotone in ``y`` and nearly
    linear as ``c → 0``). ``c = a`` while ``φ <= μP(a)/(2G_t)`` (no slip; > 0 only for a flat
    punch), ``c = 0`` when the stick radius would lie below ``C_MIN_REL a`` (full sliding to double
    precision). Flat arrays of equal size. ``panels`` as in :func:`slip_function`.
    """
    c = a.copy()
    live = (a > 0) & (phi > 0)
    if not np.any(live):
        return np.where(a > 0, c, 0.0)
    idx_live = np.flatnonzero(live)
    al, dl, gl, pl = a[live], d[live], g_a[live], phi[live]
    # P at both ends of the bracket, once per distinct normal state
    keys, inv = np.unique(np.stack([al, dl, gl], axis=1), axis=0, return_inverse=True)
    inv = inv.ravel()
    ka, kd, kg = keys.T
    P_top = slip_function(profile, E_star, ka, ka, kd, kg, rtol)[0][inv]
    y_min = np.log(C_MIN_REL)
    # (the curve route: the whole segments on the panels, as every later evaluation)
    P_bot = slip_function(profile, E_star, ka * C_MIN_REL, ka, kd, kg, rtol, panels)[0][inv]
    phi_top = twist_of_stick(mu, G_t, P_top)
    phi_bot = twist_of_stick(mu, G_t, P_bot)
    no_slip = pl <= phi_top
    sliding = pl >= phi_bot
    solve = ~(no_slip | sliding)
    out = al.copy()
    out[sliding] = 0.0
    if np.any(solve):
        s_a, s_d, s_g = al[solve], dl[solve], gl[solve]

        def func(y: np.ndarray, idx: np.ndarray) -> np.ndarray:
            P, _ = slip_function(profile, E_star, s_a[idx] * np.exp(y), s_a[idx], s_d[idx],
                                 s_g[idx], rtol, panels)
            return twist_of_stick(mu, G_t, P)

        lo, hi, f_lo, f_hi = _grid_brackets(func, pl[solve], s_a, s_d, s_g, y_min,
                                            refine=_CURVE_REFINE if panels else 0)
        y = _bracketed(func, pl[solve], lo, hi, f_lo, f_hi, rtol, "stick radius",
                       secant_start=panels)
        out[solve] = s_a * np.exp(y)
    c[idx_live] = out
    return np.where(a > 0, c, 0.0)


def solve_stick_of_torque(profile, E_star: float, G_t: float, mu: float, M: np.ndarray,
                          a: np.ndarray, d: np.ndarray, g_a: np.ndarray,
                          rtol: float) -> np.ndarray:
    """Stick radius ``c`` (m) for torques ``0 <= M < M_full`` (N·m): root of ``M(c) = M`` with
    ``M(c) = (8/3) μ c³ P(c) + 8μ T(c)`` (decreasing in ``c``), solved in ``y = ln(c/a)``.

    ``c = a`` while ``M <= (16/3) G_t a³ φ_0`` (flat punch: no slip up to ``φ_0``); ``c = 0`` when the
    root lies below ``C_MIN_REL a``. Flat arrays of equal size.
    """
    c = np.where(a > 0, a, 0.0)
    live = (a > 0) & (M > 0)
    if not np.any(live):
        return c
    al, dl, gl, Ml = a[live], d[live], g_a[live], M[live]

    def torque_at(cc, aa, dd, gg):
        P, _ = slip_function(profile, E_star, cc, aa, dd, gg, rtol)
        T, _ = torque_integral(profile, E_star, cc, aa, dd, gg, rtol)
        return torque_of_stick(mu, G_t, cc, twist_of_stick(mu, G_t, P), T)

    keys, inv = np.unique(np.stack([al, dl, gl], axis=1), axis=0, return_inverse=True)
    inv = inv.ravel()
    ka, kd, kg = keys.T
    M_top = torque_at(ka, ka, kd, kg)[inv]
    y_min = np.log(C_MIN_REL)
    M_bot = torque_at(ka * C_MIN_REL, ka, kd, kg)[inv]
    no_slip = Ml <= M_top
    sliding = Ml >= M_bot
    solve = ~(no_slip | sliding)
    out = al.copy()
    out[sliding] = 0.0
    if np.any(solve):
        s_a, s_d, s_g = al[solve], dl[solve], gl[solve]

        def func(y: np.ndarray, idx: np.ndarray) -> np.ndarray:
            return torque_at(s_a[idx] * np.exp(y), s_a[idx], s_d[idx], s_g[idx])

        lo, hi, f_lo, f_hi = _grid_brackets(func, Ml[solve], s_a, s_d, s_g, y_min)
        y = _bracketed(func, Ml[solve], lo, hi, f_lo, f_hi, rtol, "stick radius", ftol=0.0)
        out[solve] = s_a * np.exp(y)
    c[live] = out
    return c
