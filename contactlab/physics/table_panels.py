"""Product-integration panels over a large table for the exact torsion integrals (issue 28).

The composite rule of :mod:`contactlab.physics.torsion_exact` integrates ``∫ F(t, g(t)) dt`` over
every whole table segment with 8 Gauss nodes (``t = r_j + Δ u²`` removes the square-root cusp of
``g`` at each node), so one integral costs 8 kernel evaluations per segment in contact: a
torque-twist curve on a table with hundreds of nodes in contact pays ``O(points × nodes)``.

Every integrand of the exact torsion kernels is linear in ``g``, ``F = A(t) g + B(t)``, and ``A``,
``B`` are analytic in ``t`` on the whole right half-plane (``(K - E)/k²`` of ``k² = 1 - x²/t²``,
``h(x/t)`` and ``K`` are analytic for ``Re(x/t) > 0``; only ``g`` has the cusps). So on a *panel*
of consecutive segments spanning at most a factor :data:`PANEL_RATIO` in ``t``, ``A`` and ``B``
are interpolated at :data:`PANEL_POINTS` Chebyshev points (Bernstein ellipse ``ρ = 3 + 2√2`` for
ratio 2, interpolation error ``ρ^-18 ≈ 2e-14`` of the kernel's scale), and

    ∫_{segments j1..j2-1} F dt = Σ_m A(τ_m) [Cg_m(j2) - Cg_m(j1)] + B(τ_m) [C1_m(j2) - C1_m(j1)]

with the prefix sums ``Cg_m(j) = Σ_{j' < j} ∫_seg g ℓ_m dt`` and ``C1_m`` (``ℓ_m`` the Lagrange basis
of the panel) computed once per table by the same 8-point rule (a panel holds at least
:data:`PANEL_MIN_SEGMENTS` segments, so ``ℓ_m`` is smooth on one segment: the rule integrates
``g ℓ_m`` as accurately as ``g``). A range that starts or ends inside a panel is a difference
of two prefix sums; the interpolation points below the range's lower limit evaluate the
kernels' analytic continuation (``torsion_elliptic``). One integral then costs
``PANEL_POINTS`` kernel evaluations per panel (about ``log2(a/r_1)`` panels) instead of 8 per
segment. Segments outside every panel (the first few, where a factor 2 holds fewer than
``PANEL_MIN_SEGMENTS`` of them) stay on the composite rule.

The kernels are analytic in the integral's lower limit ``x`` too (off ``x = 0``, where they
have a logarithm), and every kernel of the exact torsion module is ``F(t, x) (alpha g + beta)``
with per-element constants ``alpha``, ``beta``. So for ``x`` inside a panel's range (or inside
one of the ranges of ratio 2 below the first panel) ``F(τ_pm, x)`` is interpolated in ``x`` as
well, at :data:`X_POINTS` Chebyshev points ``ξ_qk`` of that range (the same Bernstein ellipse:
``ρ^-24 ≈ 4e-19``): a point's panel sums become ``Σ_k L_qk(x) W_k``, where ``W`` is a difference of
two rows of the own panel's prefix sums contracted once per table with ``F(τ_q, ξ_q)``, plus one
contraction per distinct upper end for the panels above (and for the last partial segment,
whose rule is contracted with ``F(t, ξ_q)`` once per distinct range and piece). A curve's
root-solver pass then evaluates kernels only on each point's first partial segment.

Pure functions and a per-table cache (by the profile's value identity, like the composite
rule's); used by the exact torque-twist curve of large tables (``panels=True``).
"""
from __future__ import annotations

import numpy as np

__all__ = ["PANEL_RATIO", "PANEL_POINTS", "PANEL_MIN_SEGMENTS", "Panels", "panels_of"]

#: largest ratio of a panel's ends (the interpolation's Bernstein ellipse: ρ = 3 + 2√2 at 2)
PANEL_RATIO = 2.0
#: Chebyshev points per panel: ρ^-18 = 1.6e-14 at ratio 2
PANEL_POINTS = 18
#: fewest table segments of a panel (fewer stay on the composite rule: a Lagrange polynomial
#: of degree 17 over 32 segments varies little on one, so the 8-point rule integrates g ℓ_m to
#: the accuracy it integrates g)
PANEL_MIN_SEGMENTS = 32

_CACHE: dict = {}


def _chebyshev(n: int) -> tuple[np.ndarray, np.ndarray]:
    """First-kind Chebyshev points on [-1, 1] and their barycentric weights."""
    k = np.arange(n)
    theta = (2 * k + 1) * np.pi / (2 * n)
    return np.cos(theta), (-1.0) ** k * np.sin(theta)


def _lagrange(t: np.ndarray, tau: np.ndarray, bw: np.ndarray) -> np.ndarray:
    """Lagrange basis of the points ``tau`` (weights ``bw``) at ``t``: shape ``t.shape + (n,)``."""
    diff = t[..., None] - tau
    hit = diff == 0.0
    with np.errstate(divide="ignore", invalid="ignore"):
        q = bw / diff
        out = q / np.sum(q, axis=-1, keepdims=True)
    if np.any(hit):
        rows = np.any(hit, axis=-1)
        out[rows] = hit[rows].astype(float)
    return out


class Panels:
    """The panels of one table: segment ranges, points and (lazily) prefix sums of weights.

    Attributes
    ----------
    start, end : ndarray of int
        Segment range ``[start, end)`` of each panel.
    panel_of : ndarray of int
        Panel of each segment (-1: not in a panel, composite rule).
    tau : ndarray, shape (n_panels, PANEL_POINTS)
        Interpolation points of each panel, m.
    """

    def __init__(self, r: np.ndarray) -> None:
        n_seg = r.size - 1
        starts, ends = [], []
        s = 1                               # segment 0 ([0, r_1]) never: its ratio is infinite
        while s < n_seg:
            e = min(int(np.searchsorted(r, PANEL_RATIO * r[s], side="right")) - 1, n_seg)
            if e - s >= PANEL_MIN_SEGMENTS:
                starts.append(s)
                ends.append(e)
                s = e
            else:
                s += 1
        self.start = np.array(starts, dtype=np.intp)
        self.end = np.array(ends, dtype=np.intp)
        self.panel_of = np.full(n_seg, -1, dtype=np.intp)
        for p, (s0, e0) in enumerate(zip(starts, ends)):
            self.panel_of[s0:e0] = p
        x, self._bw = _chebyshev(PANEL_POINTS)
        lo, hi = r[self.start], r[self.end]
        self.r_lo, self.r_hi = lo, hi
        self.r1 = float(r[1])               # segment 0 ends here
        self.tau = 0.5 * (lo + hi)[:, None] + 0.5 * (hi - lo)[:, None] * x
        # per-segment weights and prefix sums per panel (rows start..end), flattened with
        # offsets; built on demand up to the segments a call needs (g is known only there)
        self.offset = np.concatenate([[0], np.cumsum(self.end - self.start + 1)])
        self.cum_g = np.zeros((int(self.offset[-1]), PANEL_POINTS))
        self.cum_1 = np.zeros((int(self.offset[-1]), PANEL_POINTS))
        self._wg = np.zeros((int(self.offset[-1]), PANEL_POINTS))
        self._w1 = np.zeros((int(self.offset[-1]), PANEL_POINTS))
        self.built = np.zeros(self.start.size, dtype=np.intp)     # segments built per panel
        self.separated: dict = {}       # kernel kind -> _Separated (x-interpolated kernels)

    def build(self, which: np.ndarray, upto: np.ndarray, t: np.ndarray, w: np.ndarray,
              g: np.ndarray) -> None:
        """Prefix sums of the panels ``which`` over their first ``upto`` segments from the
        composite rule (nodes ``t``, weights ``w``, ``g`` there; rows = segments, g filled for
        those segments). The weights of a segment are its own (elementwise), and the prefix sums
        are one sequential ``cumsum`` from the panel's start, so their values do not depend on
        how the panel grew (same call, same bits)."""
        for p, u in zip(which, upto):
            b = int(self.built[p])
            if u <= b:
                continue
            s0 = int(self.start[p])
            o = int(self.offset[p])
            rows = slice(s0 + b, s0 + u)
            ell = _lagrange(t[rows], self.tau[p], self._bw)           # (seg, q, n)
            self._wg[o + b:o + u] = np.einsum("sq,sqn->sn", w[rows] * g[rows], ell)
            self._w1[o + b:o + u] = np.einsum("sq,sqn->sn", w[rows], ell)
            self.cum_g[o + 1:o + 1 + u] = np.cumsum(self._wg[o:o + u], axis=0)
            self.cum_1[o + 1:o + 1 + u] = np.cumsum(self._w1[o:o + u], axis=0)
            self.built[p] = u


def panels_of(profile) -> Panels:
    """The (cached) panels of the node table ``profile``."""
    r = profile.table_nodes()
    key = (hash(profile), r.size)
    hit = _CACHE.get(key)
    if hit is None or hit[0] != profile:
        if len(_CACHE) > 8:
            _CACHE.clear()
        hit = (profile, Panels(r))
        _CACHE[key] = hit
    return hit[1]


def integrate(pan: Panels, kernel, first: np.ndarray, last: np.ndarray, n: int,
              rule: tuple[np.ndarray, np.ndarray, np.ndarray],
              x: np.ndarray | None = None, piece: tuple | None = None
              ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The panel part of ``Σ_elements ∫ kernel`` over whole segments ``first..last`` (inclusive,
    per element): returns ``(values, covered)`` with ``covered[seg]`` True for segments the panels
    take (the caller integrates the others by the composite rule).

    ``kernel(t, g_t, idx)`` must be linear in ``g_t`` and analytic in ``t`` for ``t > 0``
    (evaluated at ``g = 0`` and ``g = 1``, or once by its attribute ``kernel.linear(t, idx)``
    returning ``(A, B)`` with ``kernel = A g + B``). A kernel with the attribute
    ``kernel.separated = (kind, F, alpha, beta)``, ``kernel = F(t, x) (alpha g + beta)`` with
    ``F`` analytic in the lower limit ``x`` (given: one per element) as well, takes
    :func:`_separated_sum` for the elements whose ``x`` lies in a panel (no kernel evaluation
    per element; ``kind`` names ``F`` in the per-table cache). ``piece = (t, g, w, of)``: the
    rule of the last partial segments (rows: distinct pieces; ``of``: the piece of each
    element, -1 none); the separated sums take the pieces of their elements as well.

    Returns ``(values, covered, taken)``: ``taken`` marks the elements whose last piece the
    values hold.
    """
    val = np.zeros(n)
    taken = np.zeros(n, dtype=bool)
    n_p = pan.start.size
    if n_p == 0:
        return val, np.zeros(pan.panel_of.size, dtype=bool), taken
    lo = np.maximum(first[:, None], pan.start[None, :])             # (elements, panels)
    hi = np.minimum(last[:, None] + 1, pan.end[None, :])
    el, p = np.nonzero(hi > lo)
    if el.size:
        need = np.unique(p)
        upto = np.zeros(n_p, dtype=np.intp)
        np.maximum.at(upto, p, hi[el, p] - pan.start[p])
        t, w, g = rule
        pan.build(need, upto[need], t, w, g)
        sep = getattr(kernel, "separated", None)
        if sep is not None and x is not None:
            kind, fn, alpha, beta = sep
            sp = pan.separated.get(kind)
            if sp is None:
                sp = pan.separated[kind] = _Separated(pan, fn)
            # the x-range of each element's lower limit (in segment first - 1): its panel's,
            # or one below the first panel; -1: none (segment 0, or between two panels)
            seg = first - 1
            q = np.where(seg >= 1, pan.panel_of[np.clip(seg, 0, pan.panel_of.size - 1)], -1)
            low = (seg >= 1) & (seg < pan.start[0])
            if np.any(low):
                q[low] = sp.low_range(x[low])
            q[np.bincount(el, minlength=n) == 0] = -1                # no panel sums at all
            fast = np.flatnonzero(q >= 0)
            if fast.size:
                pc = None
                if piece is not None:
                    pc = (*piece[:3], piece[3][fast])
                    taken[fast] = pc[3] >= 0
                val[fast] = _separated_sum(pan, sp, fn, q[fast], first[fast], last[fast],
                                           x[fast], alpha[fast], beta[fast], pc)
                keep = q[el] < 0
                el, p = el[keep], p[keep]
    if el.size:
        base = pan.offset[p]
        i1 = base + lo[el, p] - pan.start[p]
        i2 = base + hi[el, p] - pan.start[p]
        sg = pan.cum_g[i2] - pan.cum_g[i1]
        s1 = pan.cum_1[i2] - pan.cum_1[i1]
        tau = pan.tau[p]
        with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
            if hasattr(kernel, "linear"):          # kernel = A g + B in one evaluation
                A, B = kernel.linear(tau, el)
            else:
                B = kernel(tau, np.zeros(tau.shape), el)
                A = kernel(tau, np.ones(tau.shape), el) - B
        val += np.bincount(el, weights=np.sum(A * sg + B * s1, axis=1), minlength=n)
    return val, pan.panel_of >= 0, taken


# ---------------------------------------------------------------- kernels separated in x too
#: Chebyshev points in the lower limit ``x`` per panel range: the kernels are analytic in
#: ``x`` off ``x = 0`` (a logarithm there), so on a range of ratio 2 the Bernstein ellipse is
#: ``ρ = 3 + 2√2`` again, and ``ρ^-24 ≈ 4e-19`` of the kernel's scale
X_POINTS = 24


def _contract(c: np.ndarray, m: np.ndarray) -> np.ndarray:
    """``Σ_j c[..., j] m[..., k, j]`` -> shape ``(..., k)``: the products, then one reduction
    over their last, contiguous axis, so each output's rounding depends on its own terms only
    (no BLAS; the same bits in any batch). Rows in chunks (a large panel's prefix rows)."""
    c = np.asarray(c)
    if c.ndim == 2 and c.shape[0] > _CONTRACT_ROWS:
        return np.concatenate([_contract(c[i:i + _CONTRACT_ROWS],
                                         m if m.ndim == 2 else m[i:i + _CONTRACT_ROWS])
                               for i in range(0, c.shape[0], _CONTRACT_ROWS)])
    return np.add.reduce(c[..., None, :] * m, axis=-1)


#: rows per product array of :func:`_contract` (``X_POINTS x PANEL_POINTS`` products each)
_CONTRACT_ROWS = 2048


class _Separated:
    """One kernel ``F(t, x)`` of the panels interpolated in the lower limit ``x`` as well.

    For ``x`` in panel ``q``'s range ``[r_lo, r_hi]``, ``F(τ_pm, x) = Σ_k L_qk(x) F(τ_pm, ξ_qk)``
    (``ξ_qk`` :data:`X_POINTS` Chebyshev points of that range, ``L_qk`` their Lagrange basis), so
    a panel's sum ``Σ_m F(τ_pm, x) ΔC_pm`` is ``Σ_k L_qk(x) Σ_m M[q, p, k, m] ΔC_pm`` with the
    per-table matrices ``M[q, p] = F(τ_p, ξ_q)`` (``q <= p``: a panel is never below the lower
    limit of a range it takes part in). The own panel's contracted prefix sums ``D = C M[q,q]ᵀ``
    are kept per row (built with the prefix sums); the panels above need one row per distinct
    upper end.
    """

    def __init__(self, pan: Panels, fn) -> None:
        n_p = pan.start.size
        x, self.bw = _chebyshev(X_POINTS)
        # x-ranges: the panels' own, then below the first panel ranges of ratio 2 down to the
        # end of segment 0 (there every panel lies above x)
        top = float(pan.r_lo[0])
        self.n_low = max(0, int(np.ceil(np.log2(top / pan.r1)))) if top > pan.r1 else 0
        scale = 2.0 ** -np.arange(self.n_low + 1)
        lo = np.concatenate([pan.r_lo, top * scale[1:]])
        hi = np.concatenate([pan.r_hi, top * scale[:-1]])
        self.xi = 0.5 * (lo + hi)[:, None] + 0.5 * (hi - lo)[:, None] * x
        self.top = top
        # the last panel below each range's points (a panel range: itself; below: none)
        self.below = np.concatenate([np.arange(n_p), np.full(self.n_low, -1)])
        q, p = np.nonzero(np.arange(n_p)[None, :] >= np.maximum(self.below, 0)[:, None])
        self.M = np.zeros((n_p + self.n_low, n_p, X_POINTS, PANEL_POINTS))
        with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
            self.M[q, p] = fn(pan.tau[p][:, None, :], self.xi[q][:, :, None])
        rows = pan.cum_g.shape[0]
        self.dg = np.zeros((rows, X_POINTS))
        self.d1 = np.zeros((rows, X_POINTS))
        self.built = np.zeros(n_p, dtype=np.intp)

    def low_range(self, x: np.ndarray) -> np.ndarray:
        """x-range of points below the first panel (and above segment 0)."""
        with np.errstate(divide="ignore"):
            k = np.floor(np.log2(self.top / x))
        return self.below.size - self.n_low + np.clip(k, 0, self.n_low - 1).astype(np.intp)

    def extend(self, pan: Panels, which: np.ndarray) -> None:
        """Contracted prefix rows of the panels ``which`` up to the segments their prefix sums
        hold (row by row: the same bits however the panel grew)."""
        for p in which:
            b, u = int(self.built[p]), int(pan.built[p])
            if u <= b:
                continue
            o = int(pan.offset[p])
            rows = slice(o + b + 1, o + u + 1)
            self.dg[rows] = _contract(pan.cum_g[rows], self.M[p, p])
            self.d1[rows] = _contract(pan.cum_1[rows], self.M[p, p])
            self.built[p] = u


def _separated_sum(pan: Panels, sep: _Separated, fn, q: np.ndarray, first: np.ndarray,
                   last: np.ndarray, x: np.ndarray, alpha: np.ndarray, beta: np.ndarray,
                   piece: tuple | None = None) -> np.ndarray:
    """Panel sums of ``F(t, x) (alpha g + beta)`` over segments ``first..last`` for elements
    whose lower limit ``x`` lies in x-range ``q`` of ``sep`` (a panel's, holding segment
    ``first - 1``, or one below the first panel): the own panel from its contracted prefix
    rows, the panels above from one contraction per distinct ``(q, upper end)``, then the
    x-interpolation ``Σ_k L_qk(x) W_k``. ``piece = (t, g, w, of)``: the last partial segments'
    rule (one row per distinct piece) and each element's piece (-1: none), contracted with
    ``F(t, ξ_q)`` once per distinct ``(q, piece)`` (``F`` analytic in ``x`` below the piece)."""
    n_p = pan.start.size
    wg = np.zeros((q.size, X_POINTS))
    w1 = np.zeros((q.size, X_POINTS))
    own = np.flatnonzero(q < n_p)
    if own.size:
        qo, fo = q[own], first[own]
        sep.extend(pan, np.unique(qo))
        base, s0 = pan.offset[qo], pan.start[qo]
        i1 = base + fo - s0
        i2 = base + np.maximum(np.minimum(last[own] + 1, pan.end[qo]), fo) - s0
        wg[own] = sep.dg[i2] - sep.dg[i1]
        w1[own] = sep.d1[i2] - sep.d1[i1]
    # the panels above: full but the one holding the upper end, so the same for every element
    # of one (q, last) (a curve: one or a few)
    stride = pan.panel_of.size + 1
    keys, inv = np.unique(q * stride + last, return_inverse=True)
    kq, klast = keys // stride, keys % stride
    kb = sep.below[kq]
    tg = np.zeros((keys.size, X_POINTS))
    t1 = np.zeros((keys.size, X_POINTS))
    for p in range(int(np.min(kb)) + 1, n_p):
        up = np.minimum(klast + 1, pan.end[p]) - pan.start[p]
        sel = np.flatnonzero((kb < p) & (up > 0))
        if sel.size == 0:
            continue
        mq = sep.M[kq[sel], p]                                       # (keys, X, points)
        rows = pan.offset[p] + up[sel]
        tg[sel] += _contract(pan.cum_g[rows], mq)
        t1[sel] += _contract(pan.cum_1[rows], mq)
    wg += tg[inv]
    w1 += t1[inv]
    if piece is not None:
        pt, pg, pw, of = piece
        has = np.flatnonzero(of >= 0)
        if has.size:
            n_k = pt.shape[0]
            keys, inv = np.unique(q[has] * n_k + of[has], return_inverse=True)
            cq, ck = keys // n_k, keys % n_k
            with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
                f = fn(pt[ck][:, None, :], sep.xi[cq][:, :, None])          # (keys, X, q)
            wg[has] += np.add.reduce(f * (pw * pg)[ck][:, None, :], axis=-1)[inv]
            w1[has] += np.add.reduce(f * pw[ck][:, None, :], axis=-1)[inv]
    ell = _lagrange(x, sep.xi[q], sep.bw)
    return np.sum(ell * (alpha[:, None] * wg + beta[:, None] * w1), axis=1)


# ---------------------------------------------------------------- g of a linear table, fast
#: nodes below a segment whose arcsine terms are summed exactly at every point (the others,
#: analytic on the segment, are interpolated): the nearest interpolated singularity lies
#: (G_NEAR + 1) segments below, a Bernstein ellipse of ρ ≈ 18 for a uniform table
G_NEAR = 3
#: Chebyshev terms of the interpolated far sum per segment (ρ^-14 ≈ 3e-18 at ρ = 18)
G_POINTS = 14
#: segments whose ellipse is smaller (strongly non-uniform tables) take the exact sum
#: (ρ^-14 <= 8e-16 above it)
_G_RHO_MIN = 12.0


class _FastG:
    """``g`` of a linear table at any point of segment ``j >= 1``:
    ``g(t) = t [s_j π/2 - Σ_{i<=j} Δs_i asin(r_i/t)]`` with the terms of the nodes more than
    :data:`G_NEAR` below summed as a Chebyshev series per segment (coefficients built on
    demand from the sum at the Chebyshev points, cached per table; Clenshaw's recurrence)."""

    def __init__(self, r: np.ndarray, slopes: np.ndarray) -> None:
        self.r = r
        self.s = slopes
        self.ds = np.concatenate([[0.0], np.diff(slopes)])     # jump at node i (ds[0] unused)
        n_seg = r.size - 1
        x, _ = _chebyshev(G_POINTS)
        theta = np.arccos(x)
        # values at the points -> Chebyshev coefficients (discrete orthogonality)
        self.to_coef = 2.0 / G_POINTS * np.cos(np.outer(theta, np.arange(G_POINTS)))
        self.to_coef[:, 0] *= 0.5
        lo, hi = r[:-1], r[1:]
        self.tau = 0.5 * (lo + hi)[:, None] + 0.5 * (hi - lo)[:, None] * x
        self.coef = np.zeros((G_POINTS, n_seg))      # one row per term: Clenshaw reads rows
        # the near nodes of each segment j: j - k for k = 0..G_NEAR (node 0 and below: no jump)
        near = np.arange(n_seg)[None, :] - np.arange(G_NEAR + 1)[:, None]
        live = near >= 1
        self.near_r = np.where(live, r[np.maximum(near, 1)], r[1])
        self.near_ds = np.where(live, self.ds[np.maximum(near, 1)], 0.0)
        self.done = 0
        # ρ of the far sum's nearest singularity, r_{j-G_NEAR-1}, seen from segment j
        j = np.arange(n_seg)
        near = r[np.clip(j - G_NEAR - 1, 0, None)]
        h = 0.5 * (hi - lo)
        m = np.where(h > 0, (0.5 * (lo + hi) - near) / np.where(h > 0, h, 1.0), np.inf)
        rho = m + np.sqrt(np.maximum(m * m - 1.0, 0.0))
        self.ok = (j >= 1) & ((j - G_NEAR <= 1) | (rho >= _G_RHO_MIN))

    def _build(self, need: int) -> None:
        if need <= self.done:
            return
        need = min(self.r.size - 1, max(need, self.done + self.done // 2))
        for j in range(self.done, need):                      # O(j) each, once per table
            k = j - G_NEAR                                     # nodes 1 .. k-1 are far
            if k <= 1 or not self.ok[j]:
                continue
            far = np.arcsin(self.r[1:k][None, :] / self.tau[j][:, None]) @ self.ds[1:k]
            self.coef[:, j] = far @ self.to_coef
        self.done = need

    def segment(self, t: np.ndarray) -> np.ndarray:
        """Segment of each point (flat)."""
        return np.clip(np.searchsorted(self.r, t, side="right") - 1, 0, self.r.size - 2)

    def __call__(self, t: np.ndarray) -> np.ndarray:
        """g at points ``t`` (flat) whose segments it serves (``ok``)."""
        return self.at(t, self.segment(t))

    def at(self, t: np.ndarray, j: np.ndarray) -> np.ndarray:
        """g at points ``t`` (flat) in segments ``j`` that it serves (``ok``: not segment 0
        nor one whose far sum does not interpolate to rounding, strongly non-uniform tables)."""
        r = self.r
        self._build(int(np.max(j, initial=0)) + 1)
        # t may have trailing axes of points sharing one segment: j broadcasts over them (the
        # same operations per point)
        j = j.reshape(j.shape + (1,) * (t.ndim - j.ndim))
        lo, hi = r[j], r[j + 1]
        x2 = 2.0 * (2.0 * t - lo - hi) / (hi - lo)
        c = np.take(self.coef, j, axis=1)
        b1 = np.zeros(t.shape)
        b2 = np.zeros(t.shape)
        for m in range(G_POINTS - 1, 0, -1):
            b1, b2 = c[m] + x2 * b1 - b2, b1
        far = c[0] + 0.5 * x2 * b1 - b2
        # the near nodes j, j-1, .., j-G_NEAR, one row each (a jump of 0 where none)
        terms = np.arcsin(np.minimum(np.take(self.near_r, j, axis=1) / t, 1.0))
        terms *= np.take(self.near_ds, j, axis=1)
        near = terms[0]
        for k in range(1, G_NEAR + 1):
            near = near + terms[k]
        return t * (0.5 * np.pi * self.s[j] - near - far)


_G_CACHE: dict = {}


def _fast_g_of(profile) -> _FastG:
    key = (hash(profile), profile.table_nodes().size)
    hit = _G_CACHE.get(key)
    if hit is None or hit[0] != profile:
        if len(_G_CACHE) > 8:
            _G_CACHE.clear()
        hit = (profile, _FastG(profile.table_nodes(), profile.table_slopes()))
        _G_CACHE[key] = hit
    return hit[1]


def fast_g_in(profile, t: np.ndarray, j: np.ndarray) -> np.ndarray:
    """:func:`fast_g` at points ``t`` (shape ``(n, q)``) known to lie in segments ``j`` (shape
    ``(n,)``, ``r_j <= t < r_{j+1}``, ``j >= 1``): the same values, without locating the points
    and with one gather per row (the first partial segment of an integral). Falls back to
    :func:`fast_g` where the cached form is not built that far or does not serve a segment."""
    t = np.asarray(t, float)
    if not profile.has("linear_table") or t.size == 0:
        return fast_g(profile, t)
    fg = _fast_g_of(profile)
    if int(np.max(j)) + 1 > fg.done or not np.all(fg.ok[j]):
        return fast_g(profile, t)
    return fg.at(t, j)


def fast_g(profile, t: np.ndarray) -> np.ndarray:
    """``profile._g(t)`` of a linear table from per-segment cached far sums (O(1) per point
    instead of O(nodes below)); any other profile, and points it cannot serve, by ``_g``.
    Agrees with the direct sum to rounding (the interpolation errs by ``ρ^-14 < 1e-15`` of the
    far sum)."""
    t = np.asarray(t, float)
    if not profile.has("linear_table") or t.size == 0:
        return profile._g(t)
    flat = t.ravel()
    fg = _fast_g_of(profile)
    ok = (flat > 0) & np.isfinite(flat) & (flat < fg.r[-1])
    need = int(np.searchsorted(fg.r, np.max(flat[ok], initial=0.0), side="right"))
    if need > fg.done:
        # building the far sums up to segment `need` costs ~G_POINTS need²/2 arcsines, the
        # direct sums ~(points x need): build only when this call alone repays most of it
        # (a curve's passes do; one state of a huge table does not)
        build = G_POINTS * 0.5 * (float(need) ** 2 - float(fg.done) ** 2)
        if build > 4.0 * float(np.count_nonzero(ok)) * need:
            return profile._g(t)
    j = fg.segment(flat)
    ok &= fg.ok[j]                       # the points fg serves
    if np.all(ok):
        return fg.at(flat, j).reshape(t.shape)
    out = np.empty(flat.shape)
    if np.any(ok):
        out[ok] = fg.at(flat[ok], j[ok])
    out[~ok] = profile._g(flat[~ok])
    return out.reshape(t.shape)
