"""Node sums of a large linear table in O(log N) per point: near nodes exact, far ones expanded.

The linear interpolant's transform needs, at every point x, three sums over the slope-jump nodes
``b_j <= x`` (weights ``w_j = Δs_j``, ``t_j = b_j/x``):

* ``A(x) = Σ w_j asin(t_j)`` (g),
* ``C(x) = Σ w_j t_j / sqrt(1 - t_j²)`` (g', the square-root cusps),
* ``P(x) = x² Σ w_j Φ(t_j)``, ``Φ(t) = (t sqrt(1 - t²) + asin t)/2`` (``∫_0^x g``).

Summed node by node they cost O(N) per point, O(N M) for M points. Here the radius axis is cut
into a fixed dyadic tree (level L: ``2^L`` blocks of width ``Δ_L = r_end 2^-L``); every block keeps
the moments ``M_n = Σ_{j in block} w_j u_j^n`` of its nodes, ``u_j = (b_j - c)/h`` about its
centre c (half-width ``h = Δ_L/2``), set up once per table (the finest level from the nodes,
the others from their two children: :func:`level_moments`). At a point x, the nodes below x are
split into the blocks of each level that lie at least :data:`SEPARATION` block widths below the
block holding x (and not inside an accepted block of the coarser level: at most
``SEPARATION + 1`` per level), and the nodes of the finest level's remaining blocks up to x, the
*near* nodes, taken exactly. Inside an accepted block ``t = c/x + σ u`` (``σ = h/x``) stays at
least ``(2 SEPARATION + 1)`` half-widths from the kernels' branch point ``t = 1``, so their Taylor
series about ``c/x``, truncated after :data:`TERMS` terms, converge like ``(2 SEPARATION + 1)^-n``:

* ``asin(t0 + ε) = Σ a_n ε^n``, ``a_0 = asin t0``, ``a_1 = 1/sqrt(1 - t0²)``,
  ``a_{n+2} = [(2n+1)(n+1) t0 a_{n+1} + n² a_n] / ((1 - t0²)(n+2)(n+1))`` (from
  ``(1 - t²) y'' = t y'``; every term positive for ``t0 >= 0``: no cancellation);
* ``t/sqrt(1 - t²) = t asin'(t)``: coefficients ``t0 (n+1) a_{n+1} + n a_n``;
* ``Φ' = sqrt(1 - t²) = (1 - t²) asin'(t)``: ``φ_{n+1} = [(1 - t0²)(n+1) a_{n+1} - 2 t0 n a_n
  - (n-1) a_{n-1}] / (n+1)``, ``φ_0 = Φ(t0)``.

The recurrences run on the scaled coefficients ``a_n σ^n`` (no overflow), and a block
contributes ``Σ_n a_n σ^n M_n``. A call at a loose rtol takes fewer terms
(:func:`terms_from_ratios`: all of them at the default rtol 1e-10 and below) and its error
estimate carries the rigorous truncation bound of :func:`block_tails`: the kernels are analytic
in the open unit disk and bounded on the closed one (``K`` = π/2 for asin and acos, √2 for
``sqrt(1 - t²)``, 2√2 for its cube, (√2 + π/2)/2 for Φ); the disk ``|t - t0| <= d``,
``d = 1 - t0 = (x - c)/x``, lies inside it, so Cauchy's estimate bounds the scaled
coefficients by ``K (σ/d)^n <= K ρ^n``, ``ρ = 1/(2 SEPARATION + 1)`` (``x - c >= (2
SEPARATION + 1) h``), and a block's tail after T terms by ``K Σ_{n >= T} ρ^n |M_n|``, with
``|M_n| <= Σ_block |w_j|`` beyond the stored terms (``|u_j| <= 1``). The truncation error of a block is below
``(2 SEPARATION + 1)^-TERMS`` times ``Σ |w_j|`` of the block (5^-20 = 1e-14; the terms' own
decay, ``n^-3/2``, gains about 100x more). Measured against the node-by-node sums on even,
random and wavy 10^4-point tables: <= 3.3e-16 of the terms' magnitudes, the rounding of those
sums (16 terms leave 1.3e-14 in the cusp sum, 14 terms 4e-13;
tests/unit/profiles/test_table_far_field.py).

Every point is evaluated on its own, with the same blocks and the same operations in the same
order whatever the other points of its call (the near nodes and the blocks are summed
sequentially in fixed slots, padded with exact zeros), so a batch gives the bits of one call per
point. Private: used by :mod:`._linear` for tables of at least :data:`FAR_FIELD_FROM` slope-jump
nodes whose nodes are spread evenly enough (:data:`NEAR_MAX`).
"""
from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from ...numeric import jit as _jit
from ...numeric import normal_kernels as _normal_kernels

__all__ = ["FAR_FIELD_FROM", "TERMS", "TERMS_MIN", "FULL_TERMS_RTOL", "TAIL", "SEPARATION",
           "NEAR_MAX", "LEVELS_MAX", "COMPILED_FROM",
           "FarTree", "layout", "level_moments", "build", "tree_of", "sums", "far_rows",
           "used_pairs", "slot_sums", "sequential_rows", "terms_from_ratios", "block_tails",
           "far_bound"]

#: slope-jump nodes from which a linear table takes the tree (below it, the node-by-node sums
#: are as fast, and the tables of the stored path hashes keep their bits)
FAR_FIELD_FROM = 4096
#: Taylor terms per block (truncation below (2 SEPARATION + 1)^-TERMS of the block's Σ|w|)
TERMS = 20
#: accepted blocks end at least this many block widths below the block holding x
SEPARATION = 2
#: fewest Taylor terms a loose rtol takes (:func:`terms_from_ratios`)
TERMS_MIN = 4
#: rtol at and below which the tree keeps all :data:`TERMS` terms (the default rtol, 1e-10:
#: its results keep their bits)
FULL_TERMS_RTOL = 1e-10
#: the truncation bound (:func:`block_tails`) is kept below this fraction of rtol times |g|
#: (on a table's sample radii, :func:`terms_from_ratios`)
TAIL = 0.1
#: most nodes in SEPARATION + 1 adjacent finest blocks (the near zone); a table with denser
#: clusters keeps the node-by-node sums (its near zone would not be short)
NEAR_MAX = 64
#: finest level at most (a 10^6-node table: 2^17 blocks, 21 MB of moments); a table with more
#: than two nodes per finest block then sums more near nodes exactly
LEVELS_MAX = 16
#: points per call of the dense (point, slot) arrays
_ROWS = 4096
#: fewest points a call hands to the compiled pass (:func:`far_rows`, numba; the same bits as
#: the numpy route); below it numpy's per-call cost is small
COMPILED_FROM = 16
#: the compiled pass: ``"on"``: compiled by numba (False: its plain Python logic, for tests);
#: ``"from"``: fewest points it takes (tests set 0 or a huge number to force a route)
_COMPILED: dict = {"on": True, "from": COMPILED_FROM, "kernel": None}

# constants of the recurrences, shared by the numpy route and the compiled pass (the same
# floats in both): ã_{n+2} = CA[n] (u ã_{n+1}) + CB[n] (v ã_n); Φ: PD[n], PE[n]
_N = np.arange(TERMS + 1, dtype=float)
CA = (2.0 * _N + 1.0) / (_N + 2.0)
CB = (_N * _N) / ((_N + 2.0) * (_N + 1.0))
PD = 2.0 * _N / (_N + 1.0)
PE = (_N - 1.0) / (_N + 1.0)


@dataclass(frozen=True)
class FarTree:
    """The dyadic tree of a table's slope-jump nodes (see the module docstring)."""

    nodes: np.ndarray          # b_j, sorted
    weights: np.ndarray        # w_j
    r_end: float               # the tree's extent (the table's last radius)
    levels: int                # finest level L_max
    finest: np.ndarray         # each node's block index on the finest level
    offsets: np.ndarray        # row of level L's block 0 in `moments` (L = 1..levels)
    moments: np.ndarray        # (blocks + 1, TERMS): M_n per block, the last row zeros
    moments_t: tuple           # the columns of `moments`, each contiguous
    centre: np.ndarray         # (blocks + 1,): each block's centre c (the last row: 0)
    half: np.ndarray           # (blocks + 1,): each block's half-width h (the last row: 1)


def terms_from_ratios(rtol: float, ratios: np.ndarray) -> int:
    """The fewest terms T (at least :data:`TERMS_MIN`) with ``ratios[T] <= TAIL rtol``
    (``ratios[T]``: a table's largest truncation bound after T terms relative to its g); all
    :data:`TERMS` at and below :data:`FULL_TERMS_RTOL` or when none qualifies."""
    if not rtol > FULL_TERMS_RTOL:
        return TERMS
    ok = np.flatnonzero(ratios[TERMS_MIN:TERMS] <= TAIL * rtol)
    return int(TERMS_MIN + ok[0]) if ok.size else TERMS


#: relative rounding allowed in a stored moment (the children's recombination: <= 13 levels of
#: 20-term binomial sums), added to |M_n| in :func:`block_tails`
MOMENT_SLACK = 1e-12


def block_tails(moments: np.ndarray, tree: FarTree, columns: np.ndarray) -> np.ndarray:
    """``(TERMS + 1, k, blocks + 1)``: per T and column, each block's truncation bound after T
    terms
    per unit kernel bound K (the module docstring), from the block's own moments:
    ``Σ_{T <= n < TERMS} ρ^n (|M_n| + MOMENT_SLACK S) + ρ^TERMS/(1 - ρ) S``, ``S = Σ_block
    |c_j|`` (``|M_n| <= S`` beyond the stored terms). ``moments``: (blocks + 1, k, TERMS);
    ``columns``: (k, nodes). Far tighter than ``K ρ^T/(1 - ρ) S`` where the weights cancel
    inside a block."""
    ratio = 1.0 / (2 * SEPARATION + 1)
    k = columns.shape[0]
    S = np.zeros((moments.shape[0], k))
    absc = np.abs(columns)
    for L in range(1, tree.levels + 1):
        idx = tree.finest >> (tree.levels - L)
        lo = int(tree.offsets[L])
        for j in range(k):
            S[lo:lo + 2**L, j] = np.bincount(idx, weights=absc[j], minlength=2**L)
    pw = ratio ** np.arange(TERMS)
    terms = pw[None, None, :] * (np.abs(moments) + MOMENT_SLACK * S[:, :, None])
    out = np.empty((TERMS + 1, k, moments.shape[0]))
    out[TERMS] = (ratio**TERMS / (1.0 - ratio) * S).T
    for n in range(TERMS - 1, -1, -1):
        out[n] = out[n + 1] + terms[:, :, n].T
    return out


def far_bound(tree: FarTree, tails: np.ndarray, x: np.ndarray, terms: np.ndarray,
              cols: list[int]) -> np.ndarray:
    """``(len(cols), len(terms), x.size)``: the truncation bound (per unit K) of the far blocks
    of every point of ``x`` (1D, ``0 < x <= r_end``) after each count of ``terms``, for the
    columns ``cols``: the sum of :func:`block_tails` over the point's used slots (the near
    nodes are exact; an unused slot's zero row adds zero), one gather per column and count."""
    out = np.zeros((len(cols), terms.size, x.size))
    for start in range(0, x.size, _ROWS):
        sl = slice(start, start + _ROWS)
        row, _ = _slots(tree, x[sl])
        for i, col in enumerate(cols):
            for m, n in enumerate(terms.tolist()):
                out[i, m, sl] = np.take(tails[n, col], row).sum(axis=1)
    return out


def layout(nodes: np.ndarray, r_end: float, max_levels: int = LEVELS_MAX
           ) -> tuple[int, np.ndarray] | None:
    """``(levels, finest block of each node)`` of the tree of ``nodes``, or None when the table
    is too small (:data:`FAR_FIELD_FROM`) or its nodes cluster: more than :data:`NEAR_MAX` (or,
    when ``max_levels`` caps the tree, that many times the mean occupancy of two nodes per
    block) in ``SEPARATION + 1`` adjacent finest blocks."""
    n = nodes.size
    if n < FAR_FIELD_FROM or not r_end > 0:
        return None
    levels = int(np.clip(np.floor(np.log2(n / 2.0)), 1, max_levels))
    finest = np.minimum(np.floor(nodes / r_end * 2.0**levels).astype(np.int64), 2**levels - 1)
    counts = np.bincount(finest, minlength=2**levels)
    window = np.convolve(counts, np.ones(SEPARATION + 1, dtype=np.int64), mode="valid")
    limit = NEAR_MAX * max(1, int(np.ceil(n / 2.0 ** (levels + 1))))
    if window.size and int(window.max()) > limit:
        return None
    return levels, finest


def level_moments(nodes: np.ndarray, columns: np.ndarray, r_end: float, levels: int,
                  finest: np.ndarray) -> list[np.ndarray]:
    """Moments ``M_n = Σ c_kj u_j^n`` of every block, one (2^L, k, TERMS) array per level L =
    1..levels: the finest level from the nodes, each coarser one from its two children,
    ``M_n = 2^-n Σ_i C(n, i) (±1)^(n-i) M_child,i`` (a child's offset is ``∓h/2``, its
    half-width ``h/2``): O(N TERMS k) for the nodes, O(TERMS² k) per block above."""
    k = columns.shape[0]
    nb = 2**levels
    width = r_end * 2.0**-levels
    u = (nodes - (finest + 0.5) * width) / (0.5 * width)
    mom = np.zeros((nb, k, TERMS))
    # the nodes are sorted, so every block's nodes are contiguous: one reduceat per power
    counts = np.bincount(finest, minlength=nb)
    filled = np.flatnonzero(counts)
    starts = np.searchsorted(finest, filled, side="left")
    term = np.array(columns, dtype=float)
    for j in range(TERMS):
        mom[filled, :, j] = np.add.reduceat(term, starts, axis=1).T
        term = term * u
    nn = np.arange(TERMS)
    binom = np.array([[float(math.comb(a, b)) for b in range(TERMS)] for a in range(TERMS)])
    scale = (2.0 ** -nn)[:, None] * binom
    sign = (-1.0) ** (nn[:, None] - nn[None, :])
    left = np.tril(scale * sign)              # child below the centre: offset -h/2
    right = np.tril(scale)
    out = [mom]
    for _ in range(levels - 1):
        child = out[-1]
        out.append(np.einsum("ni,bci->bcn", left, child[0::2])
                   + np.einsum("ni,bci->bcn", right, child[1::2]))
    return out[::-1]


def build(nodes: np.ndarray, weights: np.ndarray, r_end: float,
          max_levels: int = LEVELS_MAX) -> FarTree | None:
    """The tree of ``nodes`` (sorted, > 0) with ``weights``, or None (:func:`layout`)."""
    lay = layout(nodes, r_end, max_levels)
    if lay is None:
        return None
    levels, finest = lay
    per_level = level_moments(nodes, weights[None, :], r_end, levels, finest)
    moments = np.concatenate([*(m[:, 0, :] for m in per_level), np.zeros((1, TERMS))])
    return tree_of(nodes, weights, r_end, levels, finest, moments)


def tree_of(nodes: np.ndarray, weights: np.ndarray, r_end: float, levels: int,
            finest: np.ndarray, moments: np.ndarray) -> FarTree:
    """The :class:`FarTree` of a layout (:func:`layout`) with ``moments`` (blocks + 1,
    TERMS): the blocks' offsets per level, centres and half-widths (the extra last block: 0
    and 1)."""
    offsets = np.zeros(levels + 1, dtype=np.int64)
    total = 0
    centres, halves = [], []
    for L in range(1, levels + 1):
        offsets[L] = total
        nb = 2**L
        width = r_end * 2.0**-L
        centres.append((np.arange(nb) + 0.5) * width)
        halves.append(np.full(nb, 0.5 * width))
        total += nb
    return FarTree(nodes, weights, float(r_end), levels, finest, offsets, moments,
                   tuple(np.ascontiguousarray(moments[:, j]) for j in range(TERMS)),
                   np.concatenate([*centres, np.zeros(1)]),
                   np.concatenate([*halves, np.ones(1)]))


def sums(tree: FarTree, x: np.ndarray, want_cusp: bool, want_phi: bool, terms: int = TERMS
         ) -> tuple[np.ndarray, np.ndarray | None, np.ndarray | None]:
    """``(A, C, P)`` of the module docstring at the points ``x`` (1D, ``0 < x <= r_end``);
    ``C`` and ``P`` only when asked (else None); each block's Taylor series truncated after
    ``terms`` terms (:func:`terms_from_ratios`; at most :data:`TERMS`). Each point's value is
    independent of the others in ``x``."""
    if not 1 <= terms <= TERMS:
        raise ValueError(f"terms must lie in 1..{TERMS}, got {terms}")
    a_out = np.empty(x.size)
    c_out = np.empty(x.size) if want_cusp else None
    p_out = np.empty(x.size) if want_phi else None
    for start in range(0, x.size, _ROWS):
        sl = slice(start, start + _ROWS)
        a, c, p = _sums(tree, x[sl], want_cusp, want_phi, terms)
        a_out[sl] = a
        if c_out is not None:
            c_out[sl] = c
        if p_out is not None:
            p_out[sl] = p
    return a_out, c_out, p_out


def _slots(tree: FarTree, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Per point: the moment row of each slot (level-major, SEPARATION + 1 slots per level;
    the zero row for an unused slot), and the finest block index where the near zone starts."""
    levels, S = tree.levels, SEPARATION + 1
    q = x / tree.r_end
    zero_row = tree.moments.shape[0] - 1
    # every level at once: x's block kx, the accepted blocks below k1, and this level's
    # slots from twice the coarser level's k1 on
    kx = np.floor(q[:, None] * (2.0 ** np.arange(1, levels + 1))[None, :]).astype(np.int64)
    k1 = np.maximum(kx - SEPARATION, 0)
    k1_prev = np.concatenate([np.zeros((x.size, 1), dtype=np.int64), k1[:, :-1]], axis=1)
    k = 2 * k1_prev[:, :, None] + np.arange(S)[None, None, :]
    row = np.where(k < k1[:, :, None], tree.offsets[1:][None, :, None] + k, zero_row)
    k1_prev = k1[:, -1]
    return row.reshape(x.size, -1), k1_prev


def _compiled(rows: int) -> bool:
    if rows < _COMPILED["from"]:
        return False
    return not _COMPILED["on"] or _normal_kernels.backend() == "numba"


def kernel(compiled: bool = True) -> Callable:
    """:func:`far_rows` compiled by numba (built once per process), or the plain Python
    function (``compiled=False``, for tests)."""
    if not compiled:
        return far_rows
    if _COMPILED["kernel"] is None:
        _COMPILED["kernel"] = _jit.njit(far_rows, nogil=True, error_model="numpy")
    return _COMPILED["kernel"]


def _sums(tree: FarTree, x: np.ndarray, want_cusp: bool, want_phi: bool, terms: int
          ) -> tuple[np.ndarray, np.ndarray | None, np.ndarray | None]:
    row, k_near = _slots(tree, x)
    xc = x[:, None]
    zero_row = tree.moments.shape[0] - 1
    used = row != zero_row
    if _compiled(x.size):
        c = tree.centre[row]
        t = c / xc
        asin_t = np.arcsin(t)       # numpy's, for both routes (libm's may differ by an ulp)
        a_far = np.empty(x.size)
        c_far = np.empty(x.size) if want_cusp else None
        p_far = np.empty(x.size) if want_phi else None
        kernel(_COMPILED["on"])(x, row, asin_t, tree.centre, tree.half, tree.moments,
                                zero_row, terms, CA, CB, PD, PE, want_cusp, want_phi, a_far,
                                a_far if c_far is None else c_far,
                                a_far if p_far is None else p_far)
    else:
        a_far, c_far, p_far = _far_numpy(tree, x, row, used, want_cusp, want_phi, terms)
    # near nodes: finest blocks from k_near on, nodes up to x (a node at x included)
    lo = np.searchsorted(tree.finest, k_near, side="left")
    hi = np.searchsorted(tree.nodes, x, side="right")
    width = int(np.max(hi - lo)) if x.size else 0
    a_near = np.zeros(x.size)
    c_near = np.zeros(x.size)
    p_near = np.zeros(x.size)
    if width > 0:
        # (near node, point) arrays, each point's terms summed in node order by sequential_rows
        idx = lo[None, :] + np.arange(width)[:, None]
        inside = idx < hi[None, :]
        idx = np.where(inside, idx, 0)
        b = tree.nodes[idx]
        w = np.where(inside, tree.weights[idx], 0.0)
        xr = x[None, :]
        # the operations of the node-by-node route (_linear._arcsine_pass)
        q = b / np.maximum(xr, b)
        asin = np.arcsin(q)
        a_near = sequential_rows(np.where(inside, w * asin, 0.0))
        if want_cusp or want_phi:
            with np.errstate(divide="ignore", invalid="ignore"):
                root = np.sqrt(np.where(inside, (xr - b) * (xr + b), 1.0))
                if want_cusp:
                    c_near = sequential_rows(np.where(inside, w * b / root, 0.0))
                if want_phi:
                    p_near = sequential_rows(np.where(inside, w * (0.5 * (b * root + xr**2 * asin)),
                                                      0.0))
    A_tot = a_far + a_near
    C_tot = None if c_far is None else c_far + c_near
    P_tot = None if p_far is None else x * x * p_far + p_near
    return A_tot, C_tot, P_tot


def used_pairs(used: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The used (point, slot) pairs of a (points, slots) mask, slot-major: their flat indices
    into the (points, slots) arrays, their points, and where each slot's run starts (slots + 1
    bounds). The numpy routes compute on these pairs only (a third of the slots are unused)."""
    P, S = used.shape
    flat_t = np.flatnonzero(used.T)                  # slot-major: slot * P + point
    slot, point = np.divmod(flat_t, P)
    bounds = np.searchsorted(flat_t, np.arange(S + 1) * P)
    return point * S + slot, point, bounds


def slot_sums(vals: np.ndarray, point: np.ndarray, bounds: np.ndarray, points: int
              ) -> np.ndarray:
    """Per point, its used slots' values (``vals``: (..., pairs) in :func:`used_pairs`'
    order) added in slot order, then +0.0: the bits of :func:`_sequential` over the dense
    (points, slots) row with exact zeros in the unused slots (adding an exact zero changes
    no sum but the sign of a zero one, which the final +0.0 makes +0.0 in both)."""
    acc = np.zeros((*vals.shape[:-1], points))
    for j in range(bounds.size - 1):
        lo, hi = int(bounds[j]), int(bounds[j + 1])
        if hi > lo:
            pts = point[lo:hi]                       # (each point once per slot)
            acc[..., pts] += vals[..., lo:hi]
    acc += 0.0
    return acc


def _far_numpy(tree: FarTree, x: np.ndarray, row: np.ndarray, used: np.ndarray,
               want_cusp: bool, want_phi: bool, terms: int = TERMS
               ) -> tuple[np.ndarray, np.ndarray | None, np.ndarray | None]:
    """The blocks' sums (A, C, P / x²) per point, slot by slot: the numpy route (reference of
    :func:`far_rows`; the same operations in the same order).

    Computed on the used (point, slot) pairs only (:func:`used_pairs`), the terms in the outer
    loop, each term's moments gathered into one buffer and its Taylor coefficient made from
    the two before it: only a window of coefficient arrays is alive, and every operation
    writes into a buffer of the pairs' size (a new array per operation, and all TERMS
    coefficients and moments kept, cost a page fault per 4 KiB written: most of this route's
    time before). Products by a constant are written in place (IEEE multiplication and
    addition are commutative: the bits of the expression)."""
    flat, point, bounds = used_pairs(used)
    row = np.take(row, flat)
    xc = np.take(x, point)
    c = tree.centre[row]
    h = tree.half[row]
    t = c / xc
    asin_t = np.arcsin(t)           # numpy's, for both routes (libm's may differ by an ulp)
    shape = row.shape
    mom = np.empty(shape)
    tmp = np.empty(shape)
    work = np.empty(shape)
    spare: list = []
    A = np.empty(shape)
    C = np.empty(shape) if want_cusp else None
    P = np.empty(shape) if want_phi else None
    with np.errstate(all="ignore"):
        sig = h / xc
        one_m = (xc - c) * (xc + c) / (xc * xc)      # 1 - t², accurate as t -> 1
        # scaled Taylor coefficients of asin about t: ã_n = a_n σ^n, n = 0 .. TERMS, a window
        u = np.multiply(t, sig)
        u /= one_m
        v = np.multiply(sig, sig)
        v /= one_m
        root = np.sqrt(one_m)
        coef: dict = {0: asin_t, 1: np.divide(sig, root)}
        ts = t / sig if want_cusp else t                    # (t: unused placeholders)
        tsig, ss = (t * sig, sig * sig) if want_phi else (t, t)
        for m in range(terms):
            # ã_{m+1} (the cusp sum's term m needs it): CA[k] (u ã_{k+1}) + CB[k] (v ã_k)
            k = m - 1
            if k >= 0 and m + 1 not in coef:
                nxt = np.multiply(u, coef[k + 1], out=spare.pop() if spare else None)
                nxt *= CA[k]
                if k:
                    np.multiply(v, coef[k], out=tmp)
                    tmp *= CB[k]
                    nxt += tmp
                coef[k + 2] = nxt
            np.take(tree.moments_t[m], row, out=mom, mode="clip")     # M_m per slot
            if m == 0:
                np.multiply(coef[0], mom, out=A)
            else:
                np.multiply(coef[m], mom, out=tmp)
                A += tmp
            if C is not None:
                # t asin'(t): t (n+1) a_{n+1} + n a_n; scaled by σ^n: (t/σ)(n+1) ã_{n+1} + n ã_n
                if m == 0:
                    np.multiply(ts, coef[1], out=C)
                    C *= mom
                else:
                    np.multiply(coef[m + 1], _N[m + 1], out=work)
                    work *= ts
                    np.multiply(coef[m], _N[m], out=tmp)
                    work += tmp
                    work *= mom
                    C += work
            if P is not None:
                # Φ: φ_0 = Φ(t), φ_{n+1} σ^{n+1} = (1-t²) ã_{n+1} - [2n/(n+1)] t σ ã_n
                #                                   - [(n-1)/(n+1)] σ² ã_{n-1}   (n = m - 1)
                if m == 0:
                    np.multiply(t, root, out=work)
                    work += coef[0]
                    work *= 0.5
                    np.multiply(work, mom, out=P)
                else:
                    n = m - 1
                    np.multiply(one_m, coef[n + 1], out=work)
                    if n >= 1:
                        np.multiply(tsig, coef[n], out=tmp)
                        tmp *= PD[n]
                        work -= tmp
                    if n >= 2:
                        np.multiply(ss, coef[n - 1], out=tmp)
                        tmp *= PE[n]
                        work -= tmp
                    work *= mom
                    P += work
            # release ã_{m-2} (no later term reads it; ã_0 is the caller's arcsine)
            old = coef.pop(m - 2, None)
            if old is not None and old is not asin_t:
                spare.append(old)
    # the slots summed in a fixed order (the unused ones, exact zeros, left out)
    P_ = x.size
    a_far = slot_sums(A, point, bounds, P_)
    c_far = None if C is None else slot_sums(C, point, bounds, P_)
    p_far = None if P is None else slot_sums(P, point, bounds, P_)
    return a_far, c_far, p_far


def far_rows(x: np.ndarray, row: np.ndarray, asin_t: np.ndarray, centre: np.ndarray,
             half: np.ndarray, moments: np.ndarray, zero_row: int, terms: int, ca: np.ndarray,
             cb: np.ndarray, pd: np.ndarray, pe: np.ndarray, want_cusp: bool, want_phi: bool,
             a_out: np.ndarray, c_out: np.ndarray, p_out: np.ndarray) -> None:
    """The blocks' sums of :func:`_far_numpy` point by point (compiled by numba): the same
    IEEE operations in the same order (the arcsines taken by numpy), unused slots skipped (they
    add exact zeros there; the final ``+ 0.0`` makes the sign of a zero sum agree); the first
    ``terms`` Taylor terms of each block."""
    coef = np.empty(terms + 1)
    for i in range(x.size):
        xi = x[i]
        a_sum = 0.0
        c_sum = 0.0
        p_sum = 0.0
        first = True
        for s in range(row.shape[1]):
            rw = row[i, s]
            if rw == zero_row:
                continue
            c = centre[rw]
            t = c / xi
            sig = half[rw] / xi
            one_m = (xi - c) * (xi + c) / (xi * xi)
            u = t * sig / one_m
            v = sig * sig / one_m
            coef[0] = asin_t[i, s]
            coef[1] = sig / np.sqrt(one_m)
            for n in range(terms - 1):
                nxt = ca[n] * (u * coef[n + 1])
                if n:
                    nxt = nxt + cb[n] * (v * coef[n])
                coef[n + 2] = nxt
            A = coef[0] * moments[rw, 0]
            for n in range(1, terms):
                A = A + coef[n] * moments[rw, n]
            C = 0.0
            if want_cusp:
                ts = t / sig
                C = (ts * coef[1]) * moments[rw, 0]
                for n in range(1, terms):
                    C = C + (ts * ((n + 1.0) * coef[n + 1]) + n * coef[n]) * moments[rw, n]
            P = 0.0
            if want_phi:
                P = (0.5 * (t * np.sqrt(one_m) + coef[0])) * moments[rw, 0]
                tsig = t * sig
                ss = sig * sig
                for n in range(terms - 1):
                    phi = one_m * coef[n + 1]
                    if n >= 1:
                        phi = phi - pd[n] * (tsig * coef[n])
                    if n >= 2:
                        phi = phi - pe[n] * (ss * coef[n - 1])
                    P = P + phi * moments[rw, n + 1]
            if first:
                a_sum, c_sum, p_sum = A, C, P
                first = False
            else:
                a_sum = a_sum + A
                c_sum = c_sum + C
                p_sum = p_sum + P
        a_out[i] = a_sum + 0.0
        if want_cusp:
            c_out[i] = c_sum + 0.0
        if want_phi:
            p_out[i] = p_sum + 0.0


def sequential_rows(terms: np.ndarray) -> np.ndarray:
    """Column sums of ``terms`` (rows, points), the rows added in order, then +0.0: the bits
    of :func:`_sequential` of the transposed array, by adding contiguous rows (numpy's
    accumulate along short rows is slow)."""
    acc = np.zeros(terms.shape[1])
    for j in range(terms.shape[0]):
        acc += terms[j]
    acc += 0.0
    return acc


def _sequential(terms: np.ndarray) -> np.ndarray:
    """Row sums added left to right, then +0.0 (so that trailing zero padding, and a -0.0
    sum, give the same bits as a narrower row)."""
    if terms.shape[1] == 0:
        return np.zeros(terms.shape[0])
    return np.add.accumulate(terms, axis=1)[:, -1] + 0.0
