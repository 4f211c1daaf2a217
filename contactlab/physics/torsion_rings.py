"""Kernels of the exact ring solver for frictional torsion under any normal-load history.

Torsion decouples from the normal problem for every material pair, so with the pressure
``p(r, t)`` known exactly at every step, what remains is an axisymmetric frictional problem in the
radius alone: circumferential traction ``τ(r)`` and displacement ``u_φ(r)`` of the half-space,
Coulomb's law ``|τ| ≤ μ p`` with stick/slip complementarity, and memory between steps.

Representation (Jäger's superposition of twisted rigid flat punches): a traction supported on
``r < R`` is ``τ(r) = (4 G_t/π) r ∫_r^R w(t) / sqrt(t² − r²) dt``, the superposition of punches of
radius ``t`` twisted by ``w(t) dt`` (Reissner–Sagoci: ``τ = (4G_tω/π) r/sqrt(t²−r²)``). The
elastic energy of any two such tractions is local in the punch radius:

    ⟨τ_A, u_B⟩ = 2π ∫ r τ_A u_B dr = 16 G_t ∫_0^R x² Ψ_A(x) Ψ_B(x) dx,   Ψ(x) = ∫_x^R w(t) dt,

(the punch-punch energy is ``(16/3) G_t min(t, s)³``), so the influence (energy) matrix of any
basis is an exact quadrature. Here ``w`` is continuous piecewise linear on rings (hat functions at
the nodes, ``w(0) = 0``), which gives a continuous traction; the traction of each hat at any
radius and its torque are closed forms.

Discrete problem: the traction values ``z_i = τ(r_i)`` at one collocation point per ring (the ring
midpoints) are the unknowns. With ``B`` (traction at the points per hat), ``K`` (energy matrix) and
``m`` (torque per hat), the complementary-energy matrix is ``H = B⁻ᵀ K B⁻¹`` and the torque weights
``g = B⁻ᵀ m``; one step from traction ``z_o`` by a twist increment ``Δφ`` solves the
box-constrained quadratic programme

    min ½ zᵀ H z − zᵀ (H z_o + Δφ g)   subject to   |z_i| ≤ μ p_i,

whose multipliers ``λ = H z_o + Δφ g − H z`` are the (area-weighted) slip increments: zero where
the point sticks, of the sign of ``z_i`` where it slides. Points outside the contact have
``p_i = 0``, hence zero traction and a free ``λ`` (the surface moves freely there), which makes a
point entering the contact start traction-free with the displacement it had. Energy identities of
the discrete problem are exact: with the midpoint traction, ``ΔE = ½(M_o + M_n) Δφ − ½(z_o + z_n)·λ``.

Two additions to the basis keep the edge of the contact accurate: nodes at the path's contact
radii (:func:`aligned_grid`), so the traction of the last ring in contact ends at ``a(t)``, and
for a contact pinned at a wall the rigid punch of the wall radius itself (``edge_punch=True``:
``w = δ(t − b_N)``, one more collocation point), which carries the square-root singular edge
traction of a flat punch that continuous densities miss. At the contact-radius nodes inside the
grid the density may jump (``jumps``: a falling half-hat on the ring outside the node, one more
collocation point a quarter into that ring): a sliding edge has ``τ = μp`` up to ``a`` and zero
beyond, whose density ``w`` ends with a jump at ``a`` (``w(a⁻) = W(a) ≠ 0``), which a continuous
density can only smear over the next ring (the outer node ``b_N`` had that freedom already: its
hat only rises).

The exact solver of a load path keeps the punch density as its state and takes most steps in
closed form (:mod:`contactlab.physics.torsion_annulus`, stick radius inside its ring); the
box-constrained step here takes the others (two slip zones) and flat punches.

All functions are pure: arrays in, arrays out.
"""
from __future__ import annotations

import functools
from typing import cast

import numpy as np
import scipy.linalg as _la

from ..errors import ConvergenceError

__all__ = ["active_set", "hat_traction", "hat_psi", "hat_torque", "energy_matrix", "influence",
           "box_step", "gross_step", "stick_radius", "slip_density", "aligned_grid", "edge_punch_traction",
           "jump_traction", "jump_torque", "jump_psi", "radius_nodes", "GAUSS_NODES",
           "MAX_PIVOTS", "ALIGN_GAP", "ALIGN_MERGE", "ALIGN_MAX_FACTOR",
           "ALIGN_MAX_FACTOR_RTOL", "ALIGN_EXACT_FACTOR", "TORQUE_CHECK"]

#: Gauss–Legendre nodes per ring for the energy matrix: ``x² Ψ_j Ψ_k`` is a polynomial of degree
#: 6 on each ring for piecewise-linear ``w``, which 4 nodes integrate exactly
GAUSS_NODES = 4
#: iterations of the block-pivoting box-QP solve per step before it switches to single pivots
MAX_PIVOTS = 60
#: a torque-controlled step's torque ``g·z`` must meet its target within this share of the
#: full-sliding torque ``Σ |g_i| μ p_i`` (rounding of the solve; far more is a wrong state)
TORQUE_CHECK = 1e-9


#: contact radii closer than this fraction of the uniform ring width share one node
#: (:func:`aligned_grid`): smaller rings make the energy matrix ill-conditioned
ALIGN_GAP = 0.05
#: uniform nodes closer than this fraction of the ring width to a contact-radius node are dropped
ALIGN_MERGE = 0.34
#: at most this many times the uniform ring count after alignment (the gap grows to keep it)
ALIGN_MAX_FACTOR = 1.5
#: the same cap for a run whose rings a requested torque accuracy chose (``torque_rtol``): the
#: ring count's error law holds with the contact edge on a node, which a path with more distinct
#: contact radii than 1.5x the rings loses (on the benchmark's varying-load Hertz path at 10^3
#: steps, 142 rings: 2.9e-3 of the sliding torque at 1.5x, 3.9e-5 at 3x; 209 -> 399 rings)
ALIGN_MAX_FACTOR_RTOL = 3.0
#: with ``cover`` (:func:`aligned_grid`, a run whose rings ``torque_rtol`` chose): a node at
#: every contact radius while that takes at most this many times the uniform ring count (the
#: default rings' cap, :data:`ALIGN_MAX_FACTOR`), else the fewest nodes that keep every contact
#: radius within ``cover`` ring widths of one. The covering's size follows the span of the
#: contact radii, not how many distinct radii the path meets: on the benchmark's varying-load
#: Hertz path at ``torque_rtol=1e-3`` (142 rings) the 10^3- and 10^4-step paths took 399 and
#: 262 rings before, 176 and 180 covered (the 10^2-step path: 167, every radius a node)
ALIGN_EXACT_FACTOR = ALIGN_MAX_FACTOR


def _cover_nodes(ra: np.ndarray, delta: float) -> np.ndarray:
    """The fewest of the sorted radii ``ra`` as nodes, the largest among them, such that every
    radius lies within ``delta`` of a node (the largest radius, the outer node of the rings,
    covers those within ``delta`` below it; the rest greedily from the smallest: each node the
    largest radius within ``delta`` above the first radius not yet covered, optimal on a line).
    Consecutive nodes lie more than ``delta`` apart.

    The greedy chain is followed by pointer doubling (``log2`` of the radii passes over all of
    them, no loop over the nodes): ``nxt[i]`` is the first radius left uncovered by the node
    that radius ``i`` opens, and the chain's starts are the indices reached from 0.
    """
    top = ra[-1:]
    ra = ra[ra < top - delta]
    n = ra.size
    if n == 0:
        return top
    node = np.searchsorted(ra, ra + delta, side="right") - 1
    nxt = np.append(np.searchsorted(ra, ra[node] + delta, side="right"), n)
    reach = np.zeros(n + 1, bool)
    reach[0] = True
    jump = nxt
    span = 1
    while span <= n:                  # reach: the starts within ``2 span`` links of 0
        reach[jump[reach]] = True
        jump = jump[jump]
        span *= 2
    return np.append(ra[node[reach[:n]]], top)


def aligned_grid(b: np.ndarray, radii: np.ndarray,
                 max_factor: float = ALIGN_MAX_FACTOR, cover: float | None = None) -> np.ndarray:
    """Ring nodes ``b`` (uniform, ``b[0] = 0``) with nodes added at the contact radii ``radii``.

    With the contact edge ``a(t)`` on a node, the traction of the last ring in contact vanishes
    beyond ``a`` exactly (on a uniform grid it leaks into the ring that straddles ``a``, which
    drops the order of convergence under a changing normal load from ~2 to ~1.2). Radii closer
    than :data:`ALIGN_GAP` ring widths to an already placed radius share its node (they sit that
    close to it); uniform nodes within :data:`ALIGN_MERGE` ring widths of a placed radius are
    dropped, so no ring is thinner than ``ALIGN_GAP`` widths. If more than
    ``max_factor`` (:data:`ALIGN_MAX_FACTOR`) times the uniform ring count would result, the gap
    is doubled until it does not.

    With ``cover`` (ring widths), where a node at every radius would take more than
    :data:`ALIGN_EXACT_FACTOR` times the uniform ring count, the nodes are instead the fewest
    radii that keep every radius within ``cover`` widths of a node (:func:`_cover_nodes`; the
    count then follows the span of the radii, not their number), uniform nodes within
    :data:`ALIGN_MERGE` widths of them dropped; where even those exceed ``max_factor``, the gap
    doubling above.

    Parameters
    ----------
    b : ndarray
        Uniform nodes ``0 = b_0 < ... < b_N``, m.
    radii : ndarray
        Contact radii of the path's steps, m (zeros and values outside ``(0, b_N]`` ignored).
    max_factor : float, optional
        Most rings after alignment, in uniform ring counts.
    cover : float, optional
        Largest distance of a contact radius from its node, in uniform ring widths, of the
        covering taken where a node at every radius exceeds :data:`ALIGN_EXACT_FACTOR`.

    Returns
    -------
    ndarray
        Sorted nodes, ``0`` first and ``b_N`` last, m.
    """
    n = b.size - 1
    h = float(b[-1] - b[0]) / n
    ra = np.unique(np.asarray(radii, float))
    ra = ra[(ra > ALIGN_MERGE * h) & (ra <= b[-1])]
    if ra.size == 0:
        return b
    gap = ALIGN_GAP * h
    tried = False
    while True:
        # greedy clustering in one pass: a radius opens a new node when it is at least ``gap``
        # beyond the last node opened (vectorised by snapping to a gap lattice first, then
        # dropping lattice neighbours that fall closer than the gap)
        cell = np.floor((ra - ra[0]) / gap).astype(np.int64)
        _, first = np.unique(cell, return_index=True)
        nodes = ra[first]
        keep = np.ones(nodes.size, bool)
        keep[1:] = np.diff(nodes) >= gap
        nodes = nodes[keep]
        dist = np.abs(b[:, None] - nodes[None, :]).min(axis=1) if nodes.size else np.full(
            b.size, np.inf)
        uni = b[(dist > ALIGN_MERGE * h) | (np.arange(b.size) == 0)]
        out = np.union1d(uni, nodes)
        if cover is not None and not tried and out.size - 1 > ALIGN_EXACT_FACTOR * n:
            tried = True
            nodes = _cover_nodes(ra, cover * h)
            dist = np.abs(b[:, None] - nodes[None, :]).min(axis=1)
            uni = b[(dist > ALIGN_MERGE * h) | (np.arange(b.size) == 0)]
            out = np.union1d(uni, nodes)
        if out.size - 1 <= max_factor * n:
            out[-1] = max(out[-1], b[-1])
            return out
        gap *= 2.0


def _ring_traction(b: np.ndarray, r: np.ndarray, G_t: float) -> tuple[np.ndarray, np.ndarray]:
    """Traction at ``r`` (rows) of ``w = 1`` and ``w = t`` on each ring ``[b_j, b_{j+1}]`` (cols)."""
    t0, t1 = b[:-1][None, :], b[1:][None, :]
    rr = np.asarray(r, float)[:, None]
    lo = np.maximum(t0, rr)
    s1 = np.sqrt(np.maximum(t1 * t1 - rr * rr, 0.0))
    s0 = np.sqrt(np.maximum(lo * lo - rr * rr, 0.0))
    inside = (rr < t1) & (rr > 0)
    c = 4.0 * G_t / np.pi
    with np.errstate(divide="ignore", invalid="ignore"):
        T1 = np.where(inside, c * rr * np.log((t1 + s1) / np.where(inside, lo + s0, 1.0)), 0.0)
    Tt = np.where(inside, c * rr * (s1 - s0), 0.0)
    return T1, Tt


def _hat_combine(b: np.ndarray, A1: np.ndarray, At: np.ndarray) -> np.ndarray:
    """Columns per hat (nodes ``b_1 .. b_N``) from the per-ring ``w = 1`` / ``w = t`` columns.

    Hat ``j`` rises on ring ``j−1`` as ``(t − b_{j−1})/h_{j−1}`` and falls on ring ``j`` as
    ``(b_{j+1} − t)/h_j`` (the last hat only rises: ``w`` may be non-zero at the outer radius).
    """
    h = np.diff(b)
    rise = (At - b[:-1] * A1) / h
    fall = (b[1:] * A1 - At) / h
    out = rise.copy()
    out[..., :-1] += fall[..., 1:]
    return out


def hat_traction(b: np.ndarray, r: np.ndarray, G_t: float) -> np.ndarray:
    """Traction (Pa per rad/m) at radii ``r`` of each hat of the ring grid ``b``, shape (r, N)."""
    T1, Tt = _ring_traction(b, r, G_t)
    return _hat_combine(b, T1, Tt)


def hat_torque(b: np.ndarray, G_t: float) -> np.ndarray:
    """Torque of each hat, ``∫ (16/3) G_t t³ w(t) dt`` (N·m per rad/m), closed form."""
    m1 = 4.0 / 3.0 * G_t * (b[1:] ** 4 - b[:-1] ** 4)
    mt = 16.0 / 15.0 * G_t * (b[1:] ** 5 - b[:-1] ** 5)
    return _hat_combine(b, m1[None, :], mt[None, :])[0]


def hat_psi(b: np.ndarray, x: np.ndarray) -> np.ndarray:
    """``Ψ_j(x) = ∫_x^∞ w_j(t) dt`` of each hat at ``x``, m per (rad/m), shape (x, N)."""
    x = np.asarray(x, float)[:, None]
    h = np.diff(b)
    left, mid = b[:-1][None, :], b[1:][None, :]
    right = np.append(b[2:], b[-1])[None, :]
    hl, hr = h[None, :], np.append(h[1:], 1.0)[None, :]
    last = np.zeros(h.size, bool)
    last[-1] = True
    tot = 0.5 * (right - left)
    v = np.where(x <= left, tot, 0.0)
    rise = (x > left) & (x <= mid)
    v = np.where(rise, tot - 0.5 * (x - left) ** 2 / hl, v)
    fall = (x > mid) & (x < right) & ~last[None, :]
    return np.where(fall, 0.5 * (right - x) ** 2 / hr, v)


def radius_nodes(b: np.ndarray, radii: np.ndarray) -> np.ndarray:
    """Indices of the interior nodes of ``b`` (not 0, not the last) that are contact radii."""
    idx = np.flatnonzero(np.isin(b, np.asarray(radii, float)))
    return idx[(idx > 0) & (idx < b.size - 1)]


def jump_traction(b: np.ndarray, r: np.ndarray, G_t: float, jumps: np.ndarray) -> np.ndarray:
    """Traction (Pa per rad/m) at ``r`` of the falling half-hat ``w = (b_{j+1} − t)/h_j`` on the
    ring outside each jump node ``b_j`` (``j`` in ``jumps``), shape (r, jumps)."""
    T1, Tt = _ring_traction(b, r, G_t)
    j = np.asarray(jumps, int)
    return (b[1:][j] * T1[:, j] - Tt[:, j]) / np.diff(b)[j]


def jump_torque(b: np.ndarray, G_t: float, jumps: np.ndarray) -> np.ndarray:
    """Torque of each falling half-hat of :func:`jump_traction`, N·m per rad/m."""
    j = np.asarray(jumps, int)
    lo, hi = b[j], b[j + 1]
    m1 = 4.0 / 3.0 * G_t * (hi ** 4 - lo ** 4)
    mt = 16.0 / 15.0 * G_t * (hi ** 5 - lo ** 5)
    return (hi * m1 - mt) / (hi - lo)


def jump_psi(b: np.ndarray, x: np.ndarray, jumps: np.ndarray) -> np.ndarray:
    """``Ψ(x) = ∫_x^∞ w dt`` of each falling half-hat at ``x``, shape (x, jumps)."""
    j = np.asarray(jumps, int)
    lo, hi = b[j][None, :], b[j + 1][None, :]
    h = hi - lo
    x = np.asarray(x, float)[:, None]
    return np.where(x <= lo, 0.5 * h, np.where(x < hi, 0.5 * (hi - x) ** 2 / h, 0.0))


def energy_matrix(b: np.ndarray, G_t: float, b_other: np.ndarray | None = None,
                  edge_punch: bool = False, jumps: np.ndarray | None = None) -> np.ndarray:
    """``K_jk = 16 G_t ∫ x² Ψ_j Ψ_k dx`` (hats of ``b`` against hats of ``b_other``), exact Gauss.

    ``jumps`` (node indices) appends the falling half-hats of :func:`jump_traction`, then
    ``edge_punch=True`` the rigid punch of radius ``b[-1]`` (``w = δ(t − b_N)``, ``Ψ = 1`` on
    ``[0, b_N]``) as a last basis function (neither with ``b_other``).
    """
    nodes = b if b_other is None else np.union1d(b, b_other)
    h = np.diff(nodes)
    xg, wg = np.polynomial.legendre.leggauss(GAUSS_NODES)
    X = (nodes[:-1, None] + 0.5 * (xg[None, :] + 1.0) * h[:, None]).ravel()
    W = (0.5 * wg[None, :] * h[:, None]).ravel() * X * X
    P = hat_psi(b, X)
    if jumps is not None and len(jumps):
        P = np.hstack([P, jump_psi(b, X, jumps)])
    if edge_punch:
        P = np.hstack([P, np.ones((X.size, 1))])
    Q = P if b_other is None else hat_psi(b_other, X)
    return 16.0 * G_t * (P.T * W) @ Q


def edge_punch_traction(b: np.ndarray, r: np.ndarray, G_t: float) -> np.ndarray:
    """Traction (Pa per rad/m) at ``r`` of the rigid punch of radius ``b[-1]`` twisted by a unit
    density, ``(4 G_t/π) r / sqrt(b_N² − r²)`` (Reissner–Sagoci), zero outside."""
    r = np.asarray(r, float)
    a = float(b[-1])
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(r < a, 4.0 * G_t / np.pi * r / np.sqrt(np.maximum(a * a - r * r,
                                                                          1e-300)), 0.0)


def influence(b: np.ndarray, r: np.ndarray, G_t: float, edge_punch: bool = False,
              jumps: np.ndarray | None = None) -> dict[str, np.ndarray]:
    """Matrices of the ring grid ``b`` (nodes, m) with collocation points ``r`` (one per ring).

    ``jumps`` (indices of interior nodes) lets the punch density jump at those nodes (a falling
    half-hat per node, one more point each), ``edge_punch=True`` adds the rigid punch of radius
    ``b[-1]`` to the basis (one more point): it carries the square-root singular edge traction of
    a contact pinned at a wall (flat punch), which the continuous hat densities cannot represent.

    Returns
    -------
    dict
        ``H`` (the complementary-energy matrix in point tractions, J/Pa²), its inverse ``C``,
        ``g`` (torque per point traction, m³), ``B`` (traction per hat at the points) and ``lu`` (its LU
        factors, to map point tractions back to punch densities).
    """
    B = hat_traction(b, r, G_t)
    K = energy_matrix(b, G_t, edge_punch=edge_punch, jumps=jumps)
    m = hat_torque(b, G_t)
    if jumps is not None and len(jumps):
        B = np.hstack([B, jump_traction(b, r, G_t, jumps)])
        m = np.append(m, jump_torque(b, G_t, jumps))
    if edge_punch:
        B = np.hstack([B, edge_punch_traction(b, r, G_t)[:, None]])
        m = np.append(m, 16.0 / 3.0 * G_t * float(b[-1]) ** 3)
    lu = _la.lu_factor(B, check_finite=False)
    Y = _la.lu_solve(lu, K, trans=1, check_finite=False)
    H = _la.lu_solve(lu, Y.T, trans=1, check_finite=False).T
    H = 0.5 * (H + H.T)
    g = _la.lu_solve(lu, m, trans=1, check_finite=False)
    C = _la.cho_solve(_la.cho_factor(H, check_finite=False), np.eye(g.size), check_finite=False)
    return {"H": H, "C": 0.5 * (C + C.T), "g": g, "B": B, "lu": lu}


def _pos_solve(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """``scipy.linalg.solve(a, b, assume_a="pos", check_finite=False)`` by the LAPACK calls it
    makes (Cholesky of the upper triangle, ``potrf``, then ``potrs``; for one unknown a
    division: the same bits), without
    its wrapper's copies and its condition estimate (a third of the time at the ring solver's
    sizes). The matrices here are principal submatrices of the positive-definite ``H`` or its
    inverse (Cholesky-factored when the ring set is built), whose eigenvalues interlace theirs,
    so they are no worse conditioned than those. Not positive definite: ``LinAlgError``, as
    scipy's."""
    return _sub_solve(lambda: a, a.shape[0], b)


def _sub_solve(block, size: int, b: np.ndarray, memo: dict | None = None,
               key: tuple | None = None) -> np.ndarray:
    """:func:`_pos_solve` of the matrix ``block()`` (``size`` unknowns) with its Cholesky factor
    kept in ``memo`` under ``key``: a later solve with the same key (the same principal block of
    the same matrix) reuses the factor instead of building and factoring the block again, the
    same bits (``potrf`` of the same values, then ``potrs``)."""
    if size == 0:
        return np.empty(b.shape)
    if size == 1:                         # scipy divides (no factorisation) for one unknown
        a = block()
        if a[0, 0] == 0.0:
            raise np.linalg.LinAlgError("A singular matrix detected.")
        return b / a[0, 0]
    if memo is not None and memo.get("key") == key:
        c = memo["factor"]
    else:
        c, info = _potrf(block(), lower=0, clean=0)
        if info > 0:
            raise np.linalg.LinAlgError("the ring solver's system is not positive definite "
                                        f"(leading minor {info})")
        if memo is not None:
            memo["key"], memo["factor"] = key, c
    x, info = _potrs(c, b, lower=0)
    if info != 0:
        raise np.linalg.LinAlgError(f"potrs failed (info={info})")
    # in C order as scipy returns it (later products sum in the layout's order)
    return np.ascontiguousarray(x)


_potrf, _potrs = _la.get_lapack_funcs(("potrf", "potrs"), (np.zeros((1, 1)),))


def _block(M: np.ndarray, rows: np.ndarray, cols: np.ndarray) -> np.ndarray:
    """``M[np.ix_(rows, cols)]`` for boolean masks: the same values in C order, by two
    ``compress`` (a few times faster at the ring solver's sizes)."""
    return M.compress(rows, axis=0).compress(cols, axis=1)


def _memo_key(memo: dict | None, M: np.ndarray, mask: np.ndarray) -> tuple | None:
    """The key of the principal block ``mask`` of the matrix ``M`` in a factor memo (``None``:
    no memo); the memo holds ``M`` while its key names it."""
    if memo is None:
        return None
    memo.setdefault("held", {})[id(M)] = M
    return (id(M), mask.tobytes())


def _solve_free(H, rhs, F, zA, A, memo=None):
    HF = H.compress(F, axis=0)
    r = rhs[F] - HF.compress(A, axis=1) @ zA if zA.size else rhs[F]
    return _sub_solve(lambda: HF.compress(F, axis=1), r.shape[0], r, memo,
                      _memo_key(memo, H, F))


def _solve_active(C, rhs_cols, A, zA, memo=None):
    """Solution with the multipliers of the active set (``H = C⁻¹``): ``z = C(rhs − λ)``,
    ``C_AA λ_A = (C rhs)_A − z_A``; cheaper than the free-set solve when few points are active."""
    Cr = C @ rhs_cols
    if not A.any():
        return Cr, np.zeros((0, *rhs_cols.shape[1:]))
    rhs_A = Cr[A] - (zA if rhs_cols.ndim == 1 else np.stack([zA, np.zeros_like(zA)], axis=1))
    lamA = _sub_solve(lambda: _block(C, A, A), rhs_A.shape[0], rhs_A, memo,
                      _memo_key(memo, C, A))
    return Cr - C[:, A] @ lamA, lamA


def active_set(active: np.ndarray | tuple, r: np.ndarray) -> np.ndarray:
    """An active set for :func:`box_step`'s ``guess``: ``active`` itself, or for a tuple
    ``(c, s, bound)`` (a single-slip-annulus step's stick radius, m, sense ±1 and ``μ p`` at the
    points ``r``, Pa) its active set: ``s`` at the points ``r >= c``, 0 inside, 2 out of
    contact (``bound == 0``)."""
    if isinstance(active, tuple):
        c, s, bound = active
        act = np.where(r >= c, int(s), 0)
        act[bound == 0] = 2
        return act
    return active


def box_step(H: np.ndarray, g: np.ndarray, z_old: np.ndarray, bound: np.ndarray, *,
             dphi: float | None = None, torque: float | None = None,
             guess: np.ndarray | None = None, C: np.ndarray | None = None,
             memo: dict | None = None) -> tuple[np.ndarray, np.ndarray, float, int]:
    """One load step: the box-constrained QP of the module docstring, twist or torque controlled.

    Parameters
    ----------
    H, g : ndarray
        Complementary-energy matrix and torque weights (:func:`influence`).
    z_old : ndarray
        Point tractions before the step, Pa.
    bound : ndarray
        ``μ p_i`` at the end of the step, Pa (0 outside the contact, ``inf`` without slip).
    dphi : float, optional
        Twist increment, rad (twist control).
    torque : float, optional
        Target torque, N·m (torque control; the twist increment is solved for).
    guess : ndarray of int, optional
        Active-set guess per point (-1 lower bound, 0 free, +1 upper bound).
    C : ndarray, optional
        ``H⁻¹``; when given, each pivot solves the smaller of the free-set system (size of the
        stuck set) and the active-set system (size of the sliding and out-of-contact set).
    memo : dict, optional
        Keeps the Cholesky factor of the last system solved (an empty dict to start, kept by
        the caller between the steps of one run with the same ``H`` and ``C``): a step whose
        first pivot meets the last step's stuck (or active) set reuses it, the same bits. The
        ring solver's steps come in runs (a second slip zone lasts many steps), most of them
        one pivot from their guess, the last step's final set.

    Returns
    -------
    z : ndarray
        Point tractions after the step, Pa.
    lam : ndarray
        Area-weighted slip increments (``H z_old + Δφ g − H z``), m³.
    dphi : float
        The twist increment (``nan`` when a torque target exceeds the full-sliding torque).
    iterations : int
    """
    n = g.size
    fixed = bound == 0.0
    base = H @ z_old
    state = np.zeros(n, int) if guess is None else guess.copy()
    state[(state == 2) | ~np.isfinite(bound)] = 0
    state[fixed] = 2
    single = False
    for it in range(1, 4 * n + MAX_PIVOTS + 2):
        lo_set, up_set = state == -1, state == 1
        z = np.zeros(n)
        z[up_set] = bound[up_set]
        z[lo_set] = -bound[lo_set]
        F = state == 0
        A = ~F
        zA = z[A]
        if C is not None and A.sum() < F.sum():
            if torque is None:
                rhs = base + dphi * g
                z, _ = _solve_active(C, rhs, A, zA, memo)
                d = dphi
            else:
                cols, _ = _solve_active(C, np.stack([base, g], axis=1), A, zA, memo)
                d = (torque - g @ cols[:, 0]) / (g @ cols[:, 1])
                z = cols[:, 0] + d * cols[:, 1]
                rhs = base + d * g
            z[A] = zA
        elif torque is None:
            rhs = base + dphi * g
            if F.any():
                z[F] = _solve_free(H, rhs, F, zA, A, memo)
            d = dphi
        else:
            if F.any():
                both = np.stack([base, g], axis=1)
                r0 = both[F, 0] - (_block(H, F, A) @ zA if zA.size else 0.0)
                sol = _sub_solve(functools.partial(_block, H, F, F), int(F.sum()),
                                 np.stack([r0, both[F, 1]], axis=1), memo,
                                 _memo_key(memo, H, F))
                gz0 = g[A] @ zA + g[F] @ sol[:, 0]
                gz1 = g[F] @ sol[:, 1]
                d = (torque - gz0) / gz1
                z[F] = sol[:, 0] + d * sol[:, 1]
                rhs = base + d * g
            else:
                cap = float(g[A] @ zA)
                if abs(torque - cap) > 1e-12 * abs(cap):
                    # every point at a bound carries the torque ``cap``, not the target: a point
                    # must leave its bound the way of the missing torque (else the target lies
                    # beyond the sliding torque that way: gross sliding)
                    k = _release(H, g, z, base, state, torque - cap)
                    if k < 0:
                        return z, np.zeros(n), float("nan"), it
                    state[k] = 0
                    continue
                d, rhs = 0.0, base
        Hz = H @ z
        lam = rhs - Hz
        tol = 1e-12 * np.maximum(bound, np.abs(z)).clip(min=1e-300)
        bad_hi = F & (z > bound + tol)
        bad_lo = F & (z < -bound - tol)
        ltol = 1e-13 * (np.abs(rhs) + np.abs(Hz)).clip(min=1e-300)
        bad_up = up_set & (lam < -ltol)
        bad_dn = lo_set & (lam > ltol)
        bad = bad_hi | bad_lo | bad_up | bad_dn
        if not bad.any():
            lam[F] = 0.0
            if torque is not None and not abs(float(g @ z) - torque) <= TORQUE_CHECK * float(
                    np.abs(g) @ np.where(np.isfinite(bound), bound, np.abs(z))):
                raise ConvergenceError(
                    f"the ring solver's torque-controlled step ended at torque {float(g @ z)!r} "
                    f"N·m, not its target {torque!r} N·m")
            return z, lam, float(cast(float, d)), it   # d: the given or the solved twist
        if it > MAX_PIVOTS:
            single = True
        if single:  # one pivot at a time (Murty): the largest index among the violators
            k = int(np.flatnonzero(bad)[-1])
            keep = np.zeros(n, bool)
            keep[k] = True
            bad_hi, bad_lo, bad_up, bad_dn = (m & keep for m in (bad_hi, bad_lo, bad_up, bad_dn))
        state[bad_hi] = 1
        state[bad_lo] = -1
        state[bad_up | bad_dn] = 0
    raise ConvergenceError("the ring solver's active-set iteration did not converge "
                           f"({4 * n + MAX_PIVOTS + 1} pivots)")


def _release(H: np.ndarray, g: np.ndarray, z: np.ndarray, base: np.ndarray,
             state: np.ndarray, missing: float) -> int:
    """The point to free when every point is at a bound (``z``, torque ``g·z``) under a torque
    target ``missing`` N·m away: -1 when none can carry it (all at the bound of its sense).

    Only a point at the bound opposite to ``σ = sign(missing)`` can move the torque the way of
    ``σ``. With the twist increment ``Δφ`` free, such a point keeps sliding while
    ``σ λ_i <= 0``, i.e. ``σ Δφ <= σ t_i`` with ``t_i = ((H z)_i − base_i)/g_i``; as ``σ Δφ``
    grows towards the target the first to stop sliding is the one with the least ``σ t_i``:
    it sticks (is freed) and the next pivot solves the step with it free."""
    sig = 1.0 if missing > 0 else -1.0
    cand = (state == -sig) & (g != 0)
    if not cand.any():
        return -1
    idx = np.flatnonzero(cand)
    t = ((H[idx] @ z) - base[idx]) / g[idx]
    return int(idx[np.argmin(sig * t)])


def gross_step(H: np.ndarray, g: np.ndarray, z_old: np.ndarray, bound: np.ndarray,
               sense: float) -> tuple[np.ndarray, np.ndarray, float]:
    """The step of a torque target beyond the full-sliding torque: every point in contact
    slides, ``z = s μ p``, and the twist turns by the smallest increment at which all of them
    slide the way of their traction.

    With ``λ = H z_old + Δφ g − H z`` (the area-weighted slips of :func:`box_step`), all points
    slide the way of ``s`` when ``s λ_i >= 0``, i.e. ``s Δφ >= max_i (s (H (z − z_old))_i /
    g_i)``. Where that bound is positive (the force rose: a held twist would make points slide
    against their traction) the twist turns by it; else it is held (``Δφ = 0``: the force fell,
    the step releases energy and does no work).

    Parameters
    ----------
    H, g : ndarray
        Complementary-energy matrix and torque weights (:func:`influence`).
    z_old : ndarray
        Point tractions before the step, Pa.
    bound : ndarray
        ``μ p_i`` at the end of the step, Pa (0 outside the contact).
    sense : float
        Sense of the torque target, ``±1``.

    Returns
    -------
    z : ndarray
        Point tractions after the step (``s μ p``), Pa.
    lam : ndarray
        Area-weighted slip increments, m³ (``s λ >= 0``; 0 outside the contact).
    dphi : float
        The twist increment, rad (0: held).
    """
    s = 1.0 if sense >= 0 else -1.0
    z = s * bound
    base = H @ (z_old - z)
    on = bound > 0
    need = float(np.max(-s * base[on] / g[on], initial=0.0))
    dphi = s * need
    lam = np.where(on, base + dphi * g, 0.0)
    return z, lam, dphi


def stick_radius(r: np.ndarray, z: np.ndarray, bound: np.ndarray, radius: float,
                 rtol: float = 1e-9) -> float:
    """Outer radius of the central zone below the friction limit, m.

    The first point at its limit is found; the boundary between it and the last point below the
    limit is placed by the square-root approach of the traction to ``μp`` at a stick–slip
    boundary (``(μp − |τ|)²`` linear in ``r``, extrapolated from the two points inside).
    """
    inside = (bound > 0) & (r < radius)
    at = inside & (np.abs(z) >= bound * (1.0 - rtol))
    idx = np.flatnonzero(at)
    if idx.size == 0:
        return float(radius)
    k = int(idx[0])
    if k == 0:
        return 0.0
    s1 = (bound[k - 1] - abs(z[k - 1])) ** 2
    if k >= 2 and np.isfinite(bound[k - 2]):
        s0 = (bound[k - 2] - abs(z[k - 2])) ** 2
        if s0 > s1 > 0:
            c = r[k - 1] + s1 * (r[k - 1] - r[k - 2]) / (s0 - s1)
            return float(min(max(c, r[k - 1]), r[k]))
    return float(0.5 * (r[k - 1] + r[k]))


def slip_density(S: np.ndarray, r: np.ndarray, g: np.ndarray) -> np.ndarray:
    """Slip displacement at the points, m, from the area-weighted slips ``S`` (``g_i/r_i`` is the
    area ``2π r_i Δr_i`` each point represents)."""
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(g != 0, S * r / g, 0.0)
