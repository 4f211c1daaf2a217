"""Column node sums of a large cubic table over the dyadic tree of :mod:`._far`.

The cubic spline's node sums (:meth:`~._cubic._CubicTransform._cubic_sums`) contract per-node
coefficient columns ``c_kj`` with three kernels of ``t = b_j/x``: ``θ = acos t``,
``sqrt(1 - t²)`` (the root ``sqrt(x² - b²)`` over x) and ``(1 - t²)^(3/2)`` (its cube over x³).
The tree and the choice of blocks are those of :mod:`._far` (same separation and number of
terms; the finest level capped at :data:`LEVELS_MAX`: 14 columns take 14 times the memory);
each block stores the moments of every column, and a used block contributes
``Σ_n k_n (h/x)^n M_kn`` with the Taylor coefficients of the column's kernel about ``c/x``, all
from the arcsine's ``ã_n``:

* ``acos``: ``acos t0``, then ``-ã_n``;
* ``sqrt(1 - t²) = (1 - t²) asin'``: ``s̃_n = (1 - t0²)(n+1) ã_{n+1}/σ - 2 t0 n ã_n
  - (n-1) σ ã_{n-1}`` (``s̃_0 = sqrt(1 - t0²)``);
* ``(1 - t²)^(3/2)``: ``q̃_n = (1 - t0²) s̃_n - 2 t0 σ s̃_{n-1} - σ² s̃_{n-2}``.

The finest blocks next to x are summed node by node with the cubic route's own formulas
(``θ = arctan2(root, b)``). Each point's value is independent of the other points of its call.
Private: used by :mod:`._cubic` for tables of at least :data:`._far.FAR_FIELD_FROM` jump nodes.
"""
from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from . import _far

__all__ = ["LEVELS_MAX", "ColumnTree", "build", "sums", "far_columns"]

#: kernel of a column: acos t, sqrt(1 - t²), (1 - t²)^(3/2)
ACOS, ROOT, ROOT3 = 0, 1, 2


@dataclass(frozen=True)
class ColumnTree:
    """The tree of :mod:`._far` with the moments of several coefficient columns."""

    tree: _far.FarTree          # levels, blocks, node positions (its own moments unused)
    columns: np.ndarray         # (k, n) the columns
    moments: np.ndarray         # (blocks + 1, k, TERMS), the last block zeros
    cache: dict = field(default_factory=dict, compare=False, repr=False)   # numpy route's layout


#: finest level at most of a cubic table's tree (14 columns: 2^14 blocks hold 37 MB of moments)
LEVELS_MAX = 13


def build(nodes: np.ndarray, columns: np.ndarray, r_end: float) -> ColumnTree | None:
    """The column tree of ``nodes`` (sorted, > 0) with ``columns`` (k, n), or None when
    :func:`._far.layout` declines the table."""
    lay = _far.layout(nodes, r_end, LEVELS_MAX)
    if lay is None:
        return None
    levels, finest = lay
    per_level = _far.level_moments(nodes, columns, r_end, levels, finest)
    k = columns.shape[0]
    # the block geometry of the linear tree (its own moments unused: zeros)
    total = 2 ** (levels + 1) - 2
    tree = _far.tree_of(nodes, np.zeros(nodes.size), r_end, levels, finest,
                        np.zeros((total + 1, _far.TERMS)))
    moments = np.concatenate([*per_level, np.zeros((1, k, _far.TERMS))])
    return ColumnTree(tree, np.ascontiguousarray(columns), moments)


_COMPILED: dict = {"kernel": None}


def kernel(compiled: bool = True) -> Callable:
    """:func:`far_columns` compiled by numba (built once), or the plain Python function."""
    if not compiled:
        return far_columns
    if _COMPILED["kernel"] is None:
        from ...numeric import jit as _jit
        _COMPILED["kernel"] = _jit.njit(far_columns, nogil=True, error_model="numpy")
    return _COMPILED["kernel"]


def sums(ct: ColumnTree, x: np.ndarray, cols: np.ndarray, kinds: np.ndarray,
         terms: int = _far.TERMS) -> np.ndarray:
    """``Σ_j c_kj K_k(b_j, x)`` for the selected columns ``cols`` with kernels ``kinds``
    (:data:`ACOS`: ``acos(b/x)``; :data:`ROOT`: ``sqrt(x² - b²)``; :data:`ROOT3`:
    ``(x² - b²)^(3/2)/3``) at the points ``x`` (1D, ``0 < x <= r_end``): shape (len(cols),
    x.size); each block's series truncated after ``terms`` Taylor terms
    (:func:`._far.terms_from_ratios`, at most :data:`._far.TERMS`)."""
    if not 1 <= terms <= _far.TERMS:
        raise ValueError(f"terms must lie in 1..{_far.TERMS}, got {terms}")
    out = np.empty((cols.size, x.size))
    for start in range(0, x.size, _far._ROWS):
        sl = slice(start, start + _far._ROWS)
        out[:, sl] = _sums(ct, x[sl], cols, kinds, terms)
    return out


def _sums(ct: ColumnTree, x: np.ndarray, cols: np.ndarray, kinds: np.ndarray, terms: int
          ) -> np.ndarray:
    tree = ct.tree
    row, k_near = _far._slots(tree, x)
    xc = x[:, None]
    zero_row = tree.moments.shape[0] - 1
    if _far._compiled(x.size):
        far = np.empty((cols.size, x.size))
        acos_t, asin_t = _angles(tree, row, xc)[3:]
        kernel(_far._COMPILED["on"])(x, row, acos_t, asin_t, tree.centre, tree.half,
                                     ct.moments, zero_row, _far.CA, _far.CB, _far._N, cols,
                                     kinds, terms, far)
    else:
        far = _columns_numpy(ct, x, row, cols, kinds, zero_row, terms)
    # near nodes: finest blocks from k_near on, nodes below x (the cubic route's formulas)
    lo = np.searchsorted(tree.finest, k_near, side="left")
    hi = np.searchsorted(tree.nodes, x, side="left")
    width = int(np.max(hi - lo)) if x.size else 0
    near = np.zeros((cols.size, x.size))
    if width > 0:
        # (near node, point) arrays: each point's near terms summed in node order
        # (_far.sequential_rows)
        idx = lo[None, :] + np.arange(width)[:, None]
        inside = idx < hi[None, :]
        idx = np.where(inside, idx, 0)
        b = tree.nodes[idx]
        xr = x[None, :]
        root = np.sqrt(np.maximum((xr - b) * (xr + b), 0.0))
        theta = np.arctan2(root, b)
        root3 = root**3 / 3.0 if bool(np.any(kinds == ROOT3)) else root
        for i, (col, kind) in enumerate(zip(cols.tolist(), kinds.tolist())):
            w = np.where(inside, ct.columns[col][idx], 0.0)
            base = theta if kind == ACOS else (root if kind == ROOT else root3)
            near[i] = _far.sequential_rows(np.where(inside, w * base, 0.0))
    res = np.empty((cols.size, x.size))
    for i, kind in enumerate(kinds.tolist()):
        if kind == ACOS:
            res[i] = far[i] + near[i]
        elif kind == ROOT:
            res[i] = x * far[i] + near[i]
        else:
            res[i] = (x * x * x / 3.0) * far[i] + near[i]
    return res


def _by_term(ct: ColumnTree) -> np.ndarray:
    """``ct.moments`` term-major, ``(k, TERMS, blocks + 1)`` contiguous (the numpy route gathers
    one term of one column at a time from a contiguous vector), set up on first use."""
    cached = ct.cache.get("by_term")
    if cached is None:
        cached = np.ascontiguousarray(ct.moments.transpose(1, 2, 0))
        ct.cache["by_term"] = cached
    return cached


def _angles(tree: _far.FarTree, row: np.ndarray, xc: np.ndarray
            ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """``(t, σ, 1 - t², acos t, asin t)`` of the slots ``row`` at the points ``xc`` (arrays
    of one shape): the same operations for both routes (numpy's arctan2 and arcsin)."""
    c = tree.centre[row]
    with np.errstate(all="ignore"):
        t = c / xc
        h = tree.half[row]
        sig = h / xc
        one_m = (xc - c) * (xc + c) / (xc * xc)
        # acos t0 accurately (as arctan2 of the root), numpy's for both routes
        acos_t = np.arctan2(np.sqrt(one_m), t)
        asin_t = np.arcsin(t)
    return t, sig, one_m, acos_t, asin_t


def _columns_numpy(ct: ColumnTree, x: np.ndarray, row: np.ndarray, cols: np.ndarray,
                   kinds: np.ndarray, zero_row: int, terms: int = _far.TERMS) -> np.ndarray:
    """The blocks' sums per selected column (numpy route, reference of :func:`far_columns`).

    Every operation is an element-wise multiplication, division, addition or subtraction in the
    order of :func:`far_columns` (products by a constant written in place: IEEE multiplication
    and addition are commutative, so ``x *= c`` gives the bits of ``c * x``), on the used
    (point, slot) pairs only (:func:`._far.used_pairs`: a third of the slots are unused),
    summed per point in slot order (:func:`._far.slot_sums`). The terms run in the outer loop:
    term n's coefficients (``ã_n``, ``s̃_n``, ``q̃_n``) are made from the few before them and
    added into every column's sum, so only a window of coefficient arrays is alive and their
    buffers are reused (a new array per operation, and all TERMS of them kept, cost a page
    fault per 4 KiB written: most of this route's time before); each term's moments are
    gathered from a contiguous vector (:func:`_by_term`)."""
    T = terms
    N = _far._N
    CA, CB = _far.CA, _far.CB
    need_root = bool(np.any(kinds != ACOS))
    need_r3 = bool(np.any(kinds == ROOT3))
    flat, point, bounds = _far.used_pairs(row != zero_row)
    row = np.take(row, flat)
    t, sig, one_m, acos_t, asin_t = _angles(ct.tree, row, np.take(x, point))
    shape = row.shape
    by_term = _by_term(ct)
    col_list, kind_list = cols.tolist(), kinds.tolist()
    vals = np.empty((cols.size, *shape))
    tmp = np.empty(shape)
    mom = np.empty(shape)
    spare: list = []

    def buffer() -> np.ndarray:
        return spare.pop() if spare else np.empty(shape)

    with np.errstate(all="ignore"):
        u = np.multiply(t, sig)
        u /= one_m                                  # (t σ)/(1 - t²)
        v = np.multiply(sig, sig)
        v /= one_m                                  # σ²/(1 - t²)
        a1 = np.sqrt(one_m)
        np.divide(sig, a1, out=a1)
        a: dict = {0: asin_t, 1: a1}                # ã_n, a window of them
        s: dict = {}
        q: dict = {}
        two_t = 2.0 * t if need_root else t                 # (t: unused placeholders)
        tts = np.multiply(two_t, sig) if need_r3 else t
        ss = np.multiply(sig, sig) if need_r3 else t
        for n in range(T):
            # ã_{n+1} (s̃_n needs it; ã_{m+2} = CA[m] (u ã_{m+1}) + CB[m] (v ã_m), m = n - 1)
            m = n - 1
            if m >= 0 and n + 1 not in a:
                nxt = np.multiply(u, a[m + 1], out=buffer())
                nxt *= CA[m]
                if m:
                    np.multiply(v, a[m], out=tmp)
                    tmp *= CB[m]
                    nxt += tmp
                a[m + 2] = nxt
            if need_root:
                if n == 0:
                    s[0] = np.sqrt(one_m)
                else:
                    sn = np.multiply(a[n + 1], N[n + 1], out=buffer())
                    sn /= sig
                    sn *= one_m
                    np.multiply(a[n], N[n], out=tmp)
                    tmp *= two_t
                    sn -= tmp
                    if n >= 2:
                        np.multiply(sig, a[n - 1], out=tmp)
                        tmp *= N[n - 1]
                        sn -= tmp
                    s[n] = sn
            if need_r3:
                qn = np.multiply(one_m, s[n], out=buffer())
                if n >= 1:
                    np.multiply(tts, s[n - 1], out=tmp)
                    qn -= tmp
                if n >= 2:
                    np.multiply(ss, s[n - 2], out=tmp)
                    qn -= tmp
                q[n] = qn
            for i, (col, kind) in enumerate(zip(col_list, kind_list)):
                np.take(by_term[col, n], row, out=mom, mode="clip")
                if n == 0:
                    np.multiply(acos_t if kind == ACOS else (s[0] if kind == ROOT else q[0]),
                                mom, out=vals[i])
                    continue
                np.multiply(a[n] if kind == ACOS else (s[n] if kind == ROOT else q[n]), mom,
                            out=tmp)
                if kind == ACOS:
                    vals[i] -= tmp
                else:
                    vals[i] += tmp
            # release what no later term reads: ã_{n-1}, s̃_{n-2}, q̃_n
            for window, old in ((a, n - 1), (s, n - 2), (q, n)):
                arr = window.pop(old, None)
                if arr is not None and arr is not asin_t:
                    spare.append(arr)
    # the slots summed in order (the unused ones, exact zeros, left out)
    return _far.slot_sums(vals, point, bounds, x.size)


def far_columns(x: np.ndarray, row: np.ndarray, acos_t: np.ndarray, asin_t: np.ndarray,
                centre: np.ndarray, half: np.ndarray, moments: np.ndarray, zero_row: int,
                ca: np.ndarray, cb: np.ndarray, nf: np.ndarray, cols: np.ndarray,
                kinds: np.ndarray, terms: int, out: np.ndarray) -> None:
    """:func:`_columns_numpy` point by point (compiled by numba): the same operations in the
    same order, unused slots skipped (exact zeros there).

    A point's used blocks advance side by side in the recurrences (n outer, blocks inner), so
    their independent chains of dependent multiplications overlap in the processor; every
    block's own chain, and the order in which the blocks are added, are those of the numpy
    route. The first ``terms`` Taylor terms of each block."""
    T = terms
    S = row.shape[1]
    k = cols.size
    need_root = False
    need_r3 = False
    for i in range(k):
        if kinds[i] != 0:
            need_root = True
        if kinds[i] == 2:
            need_r3 = True
    used = np.empty(S, dtype=np.int64)
    rows = np.empty(S, dtype=np.int64)
    tt = np.empty(S)
    sg = np.empty(S)
    om = np.empty(S)
    uu = np.empty(S)
    vv = np.empty(S)
    a = np.empty((T + 1, S))
    s = np.empty((T, S))
    q = np.empty((T, S))
    acc = np.zeros(k)
    for p in range(x.size):
        xi = x[p]
        m = 0
        for sl in range(S):
            rw = row[p, sl]
            if rw == zero_row:
                continue
            used[m] = sl
            rows[m] = rw
            c = centre[rw]
            t = c / xi
            sig = half[rw] / xi
            one_m = (xi - c) * (xi + c) / (xi * xi)
            tt[m] = t
            sg[m] = sig
            om[m] = one_m
            uu[m] = t * sig / one_m
            vv[m] = sig * sig / one_m
            a[0, m] = asin_t[p, sl]
            a[1, m] = sig / np.sqrt(one_m)
            m += 1
        for j in range(m):
            a[2, j] = ca[0] * (uu[j] * a[1, j])
        for n in range(1, T - 1):
            for j in range(m):
                a[n + 2, j] = ca[n] * (uu[j] * a[n + 1, j]) + cb[n] * (vv[j] * a[n, j])
        if need_root:
            for j in range(m):
                s[0, j] = np.sqrt(om[j])
            for j in range(m):
                s[1, j] = (om[j] * (nf[2] * a[2, j] / sg[j])
                           - (2.0 * tt[j]) * (nf[1] * a[1, j]))
            for n in range(2, T):
                for j in range(m):
                    s[n, j] = (om[j] * (nf[n + 1] * a[n + 1, j] / sg[j])
                               - (2.0 * tt[j]) * (nf[n] * a[n, j])
                               - nf[n - 1] * (sg[j] * a[n - 1, j]))
        if need_r3:
            for j in range(m):
                q[0, j] = om[j] * s[0, j]
            for j in range(m):
                q[1, j] = om[j] * s[1, j] - (2.0 * tt[j] * sg[j]) * s[0, j]
            for n in range(2, T):
                for j in range(m):
                    q[n, j] = (om[j] * s[n, j] - (2.0 * tt[j] * sg[j]) * s[n - 1, j]
                               - (sg[j] * sg[j]) * s[n - 2, j])
        for j in range(m):
            rw = rows[j]
            for i in range(k):
                col = cols[i]
                kind = kinds[i]
                if kind == 0:
                    v = acos_t[p, used[j]] * moments[rw, col, 0]
                    for n in range(1, T):
                        v = v - a[n, j] * moments[rw, col, n]
                elif kind == 1:
                    v = s[0, j] * moments[rw, col, 0]
                    for n in range(1, T):
                        v = v + s[n, j] * moments[rw, col, n]
                else:
                    v = q[0, j] * moments[rw, col, 0]
                    for n in range(1, T):
                        v = v + q[n, j] * moments[rw, col, n]
                acc[i] = v if j == 0 else acc[i] + v
        for i in range(k):
            out[i, p] = (acc[i] if m else 0.0) + 0.0
