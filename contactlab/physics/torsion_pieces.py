"""Piecewise-linear punch densities of the exact torsion solver: their algebra and integrals.

A density ``w(t)`` is held as *pieces* ``[lo_k, hi_k]`` (sorted; values ``wl_k``, ``wr_k`` at
their ends, jumps and gaps allowed between pieces). This module evaluates ``Ψ(x) = ∫_x^∞ w dt``,
the torque ``(16/3) G_t ∫ t³ w dt`` (whole and below a radius), the elastic energy
``8 G_t ∫ x² Ψ² dx``, the values at a radius, and forms cuts, splices, sums and differences of
densities. The solver's steps and their checks are :mod:`contactlab.physics.torsion_annulus`
(which re-exports these functions).

All functions are pure: arrays in, arrays out.
"""
from __future__ import annotations

import numpy as np

from ..numeric import annulus_kernel as _annulus_kernel
from ..numeric import normal_kernels as _normal_kernels
from ..numeric import ring_kernels as _ring_kernels
from ..numeric import torque_kernel as _torque_kernel

__all__ = ["Pieces", "empty", "from_nodes", "from_coefficients", "psi", "torque", "torque_below",
           "stored_energy", "splice", "difference", "add"]


#: a piecewise-linear density: (lo, hi, wl, wr), each an array over the pieces, sorted, abutting
Pieces = tuple

#: the compiled passes of :func:`psi` and :func:`_ends` (:mod:`contactlab.numeric.ring_kernels`,
#: the same bits as the numpy route): ``"on"`` None follows the backend
#: (:func:`contactlab.numeric.normal_kernels.backend`), True/False forces them (tests; False is
#: the numpy reference), ``"compiled"`` False runs the kernels' plain Python logic (tests)
_COMPILED: dict = {"on": None, "compiled": True}


def _kernels() -> dict | None:
    """The ring kernels to use, or None for the numpy route."""
    on = _COMPILED["on"]
    if on is None:
        on = _normal_kernels.backend() == "numba"
    return _ring_kernels.kernels(_COMPILED["compiled"]) if on else None


def empty() -> Pieces:
    """The zero density (no pieces)."""
    return tuple(np.zeros(0) for _ in range(4))


def from_nodes(b: np.ndarray, left: np.ndarray, right: np.ndarray) -> Pieces:
    """Pieces on the rings ``[b_j, b_{j+1}]`` with end values ``left[j]``, ``right[j]``."""
    return (b[:-1].copy(), b[1:].copy(), np.asarray(left, float), np.asarray(right, float))


def _lin(p: Pieces):
    lo, hi, wl, wr = p
    h = hi - lo
    if h.size and h.min() > 0:      # no zero-width piece (the usual case): the same values
        be = (wr - wl) / h
    else:
        be = np.where(h > 0, (wr - wl) / np.where(h > 0, h, 1.0), 0.0)
    return wl - be * lo, be


def _unique(a: np.ndarray) -> np.ndarray:
    """``np.unique`` of a 1-D float array, the same values (its sort and mask, without its
    wrapper's cost on the solver's small arrays; a nan, which it merges, goes to it)."""
    a = np.sort(a)
    if a.size and a[-1] != a[-1]:
        return np.unique(a)
    keep = np.empty(a.size, bool)
    keep[:1] = True
    np.not_equal(a[1:], a[:-1], out=keep[1:])
    return a[keep]


def psi(p: Pieces, x: np.ndarray) -> np.ndarray:
    """``Ψ(x) = ∫_x^∞ w dt`` at ``x``, m per (rad/m) (running sums: ``O((n + m) log n)``)."""
    lo, hi, _, _ = p
    x = np.asarray(x, float)
    if lo.size == 0:
        return np.zeros(x.shape)
    kern = _kernels()
    if kern is not None:
        out = np.empty(x.size)
        c = np.ascontiguousarray
        # (called ~10 times a solver step: the arguments spelled out, no generator)
        kern["psi"](c(lo, float), c(hi, float), c(p[2], float), c(p[3], float),
                    x if x.ndim == 1 and x.flags.c_contiguous else c(x).ravel(), out)
        return out if x.ndim == 1 else out.reshape(x.shape)
    al, be = _lin(p)
    whole = al * (hi - lo) + 0.5 * be * (hi * hi - lo * lo)
    tail = np.append(np.cumsum(whole[::-1])[::-1], 0.0)          # ∫ over pieces k, k+1, ...
    k = np.minimum(np.searchsorted(hi, x, "right"), lo.size - 1)
    lk, hk = lo[k], hi[k]
    t0 = np.minimum(np.maximum(x, lk), hk)
    part = al[k] * (hk - t0) + 0.5 * be[k] * (hk * hk - t0 * t0)
    return np.where(x >= hi[-1], 0.0, np.where(x < lo[0], tail[0], part + tail[k + 1]))


def torque(p: Pieces, G_t: float) -> float:
    """Torque ``(16/3) G_t ∫ t³ w dt``, N·m (the powers as products: the same bits on every
    processor, and on the compiled route, :mod:`contactlab.numeric.torque_kernel`)."""
    lo, hi, wl, wr = p
    if _kernels() is not None:
        c = np.ascontiguousarray
        s = _torque_kernel.kernels(_COMPILED["compiled"])["torque_sum"](
            c(lo, float), c(hi, float), c(wl, float), c(wr, float))
        return float(16.0 / 3.0 * G_t * s)
    al, be = _lin(p)
    h2, l2 = hi * hi, lo * lo
    h4, l4 = h2 * h2, l2 * l2
    return float(16.0 / 3.0 * G_t * np.sum(al * (h4 - l4) / 4.0 + be * (h4 * hi - l4 * lo) / 5.0))


_GAUSS = np.polynomial.legendre.leggauss(4)


def stored_energy(p: Pieces, G_t: float) -> float:
    """Elastic energy ``8 G_t ∫ x² Ψ(x)² dx``, J (4-point Gauss per piece, exact).

    ``Ψ`` is constant wherever the density is zero: below the first piece and on every gap
    between two pieces (a density spliced above an earlier, smaller contact: the old density
    ends at the old contact radius ``a₀``, the new one starts at the stick radius ``c > a₀``).
    Those intervals are integrated in closed form, ``Ψ² (x₁³ − x₀³)/3``."""
    lo, hi, _, _ = p
    if lo.size == 0:
        return 0.0
    xg, wg = _GAUSS
    h = hi - lo
    X = lo[:, None] + 0.5 * (xg[None, :] + 1.0) * h[:, None]
    # Ψ inside piece k: the integral over the pieces above it plus the rest of piece k
    al, be = _lin(p)
    whole = al * h + 0.5 * be * (hi * hi - lo * lo)
    tail = np.append(np.cumsum(whole[::-1])[::-1], 0.0)
    Ps = (al[:, None] * (hi[:, None] - X) + 0.5 * be[:, None] * (hi[:, None] ** 2 - X * X)
          + tail[1:, None])
    # the zero-density intervals [0, lo_0] and [hi_{k-1}, lo_k] (empty where pieces abut), on
    # each of which Ψ is the integral over the pieces above: tail[k]
    below = np.concatenate([[0.0], hi[:-1]])
    gaps = np.sum(tail[:-1] ** 2 * (lo ** 3 - below ** 3)) / 3.0
    return float(8.0 * G_t * (np.sum(0.5 * wg[None, :] * h[:, None] * X * X * Ps * Ps) + gaps))


def _values(p: Pieces, x: np.ndarray, side: int) -> np.ndarray:
    """``w(x⁻)`` (side −1) or ``w(x⁺)`` (side +1) at the sorted radii ``x`` (0 outside)."""
    lo, hi, wl, wr = p
    x = np.asarray(x, float)
    k = (np.searchsorted(hi, x, "left") if side < 0 else np.searchsorted(lo, x, "right") - 1)
    valid = (k >= 0) & (k < lo.size)
    k = np.minimum(np.maximum(k, 0), max(lo.size - 1, 0))
    if lo.size == 0:
        return np.zeros(x.shape)
    h = hi[k] - lo[k]
    f = np.where(h > 0, (x - lo[k]) / np.where(h > 0, h, 1.0), 0.0)
    inside = valid & (((x > lo[k]) & (x <= hi[k])) if side < 0 else
                      ((x >= lo[k]) & (x < hi[k])))
    return np.where(inside, wl[k] + (wr[k] - wl[k]) * f, 0.0)


def _value(p: Pieces, x: float, side: int) -> float:
    """``w(x⁻)`` (side −1) or ``w(x⁺)`` (side +1) at one radius (scalar :func:`_values`)."""
    lo, hi, wl, wr = p
    if lo.size == 0:
        return 0.0
    k = int(np.searchsorted(hi, x, "left") if side < 0 else np.searchsorted(lo, x, "right") - 1)
    if k < 0 or k >= lo.size:
        return 0.0
    l0, h0 = float(lo[k]), float(hi[k])
    if not ((l0 < x <= h0) if side < 0 else (l0 <= x < h0)):
        return 0.0
    h = h0 - l0
    f = (x - l0) / h if h > 0 else 0.0
    return float(wl[k] + (wr[k] - wl[k]) * f)


def torque_below(p: Pieces, x: np.ndarray, G_t: float) -> np.ndarray:
    """Torque of the density below each radius ``x``, N·m (running sums)."""
    lo, hi, _, _ = p
    x = np.asarray(x, float)
    if lo.size == 0:
        return np.zeros(x.shape)
    al, be = _lin(p)
    whole = al * (hi ** 4 - lo ** 4) / 4.0 + be * (hi ** 5 - lo ** 5) / 5.0
    head = np.concatenate([[0.0], np.cumsum(whole)])              # ∫ over pieces < k
    k = np.minimum(np.searchsorted(hi, x, "right"), lo.size - 1)
    t1 = np.minimum(np.maximum(x, lo[k]), hi[k])
    part = al[k] * (t1 ** 4 - lo[k] ** 4) / 4.0 + be[k] * (t1 ** 5 - lo[k] ** 5) / 5.0
    below = np.where(x < lo[0], 0.0, head[k] + part)
    return 16.0 / 3.0 * G_t * np.where(x >= hi[-1], head[-1], below)


def _cut(p: Pieces, x: float, keep_below: bool) -> Pieces:
    """The part of ``p`` below (or above) ``x``, the piece holding ``x`` split there."""
    lo, hi, wl, wr = p
    if keep_below:
        # the pieces are sorted: ``lo < x`` is a leading run (a slice, the same values; a nan
        # ``x`` keeps none, as the mask)
        n = int(np.searchsorted(lo, x, "left")) if x == x else 0
        lo, hi, wl, wr = lo[:n], hi[:n], wl[:n], wr[:n]
        if lo.size and hi[-1] > x:
            h = hi[-1] - lo[-1]
            wr = wr.copy()
            hi = hi.copy()
            wr[-1] = wl[-1] + (wr[-1] - wl[-1]) * (x - lo[-1]) / h
            hi[-1] = x
    else:
        n = int(np.searchsorted(hi, x, "right")) if x == x else hi.size
        lo, hi, wl, wr = lo[n:], hi[n:], wl[n:], wr[n:]
        if lo.size and lo[0] < x:
            h = hi[0] - lo[0]
            wl = wl.copy()
            lo = lo.copy()
            wl[0] = wl[0] + (wr[0] - wl[0]) * (x - lo[0]) / h
            lo[0] = x
    return lo, hi, wl, wr


def difference(new: Pieces, old: Pieces, start: float) -> Pieces:
    """Pieces of ``new − old`` above ``start`` (on the union of both densities' piece ends); the
    last one kept (a step's and its energy's are the same)."""
    last, kern = _LAST_DIFF[0], _kernels()     # (kept per route: the routes stay tested)
    if last[0] is new and last[1] is old and last[2] == start and last[3] is kern:
        return last[4]
    xs = np.concatenate([new[0], new[1], old[0], old[1], [start]])
    xs = _unique(xs[xs >= start])
    if xs.size < 2:
        return tuple(np.zeros(0) for _ in range(4))
    lo, hi = xs[:-1], xs[1:]
    nl, nr = _ends(new, lo, hi)
    ol, orr = _ends(old, lo, hi)
    out = (lo, hi, nl - ol, nr - orr)
    _LAST_DIFF[0] = (new, old, start, kern, out)      # one tuple, replaced whole (threads)
    return out


def _ends(p: Pieces, lo: np.ndarray, hi: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``w(lo⁺)`` and ``w(hi⁻)`` on intervals ``[lo, hi]`` that each lie inside one piece of
    ``p`` or in a gap (the piece ends of ``p`` among the interval ends): :func:`_values` at both
    ends with one look-up, the same values."""
    plo, phi, wl, wr = p
    if plo.size == 0:
        return np.zeros(lo.shape), np.zeros(lo.shape)
    kern = _kernels()
    if kern is not None:
        out_l, out_r = np.empty(lo.size), np.empty(lo.size)
        kern["ends"](*(np.ascontiguousarray(a, float) for a in p), np.ascontiguousarray(lo, float),
                     np.ascontiguousarray(hi, float), out_l, out_r)
        return out_l, out_r
    k = np.searchsorted(plo, lo, "right") - 1
    inside = (k >= 0) & (hi <= phi[np.maximum(k, 0)])
    k = np.maximum(k, 0)
    l0, h0, a, d = plo[k], phi[k], wl[k], wr[k] - wl[k]
    h = h0 - l0
    pos = h > 0
    hh = np.where(pos, h, 1.0)
    fl = np.where(pos, (lo - l0) / hh, 0.0)
    fr = np.where(pos, (hi - l0) / hh, 0.0)
    return np.where(inside, a + d * fl, 0.0), np.where(inside, a + d * fr, 0.0)


def add(p: Pieces, q: Pieces) -> Pieces:
    """The sum of two densities (on the union of their piece ends)."""
    return difference(p, (q[0], q[1], -q[2], -q[3]), 0.0)


def from_coefficients(b: np.ndarray, coef: np.ndarray, jumps: np.ndarray,
                      radius: float | None = None) -> Pieces:
    """Pieces of the ring solver's density: hat coefficients at ``b_1 .. b_N`` (``w(0) = 0``),
    then one falling half-hat per node in ``jumps``; cut at ``radius`` when given."""
    if _kernels() is not None:
        # one compiled pass (numeric.annulus_kernel), the same values
        ok, out = _annulus_kernel.kernels(_COMPILED["compiled"])["coefficient_pieces"](
            np.ascontiguousarray(b, float), np.ascontiguousarray(coef, float),
            np.ascontiguousarray(jumps, np.int64), 0.0 if radius is None else float(radius),
            radius is not None)
        if ok:
            return out[0], out[1], out[2], out[3]
    n = b.size - 1
    hat = np.asarray(coef, float)[:n]
    left = np.concatenate([[0.0], hat[:-1]])
    right = hat.copy()
    jumps = np.asarray(jumps, int)
    if jumps.size:
        left[jumps] += np.asarray(coef, float)[n:n + jumps.size]
    p = from_nodes(b, left, right)
    return p if radius is None else _cut(p, float(radius), True)


def splice(old: Pieces, new: Pieces, c: float) -> Pieces:
    """``old`` below ``c`` and ``new`` above it (zero-width pieces dropped)."""
    a, b = _cut(old, c, True), _cut(new, c, False)
    out = tuple(np.concatenate([u, v]) for u, v in zip(a, b))
    keep = out[1] > out[0]
    return out if keep.all() else tuple(u[keep] for u in out)


def _scale(p: Pieces) -> float:
    return float(np.max(np.abs(p[2]), initial=0.0) + np.max(np.abs(p[3]), initial=0.0)) or 1.0


def _total(p: Pieces) -> float:
    """``Ψ(0) = ∫ w dt`` (rad); the last density's kept (a step's old density is the last
    step's new one: the same tuple, never changed in place)."""
    for last in _LAST_TOTAL:
        if last[0] is p:
            return last[1]
    lo, hi, _, _ = p
    if lo.size == 0:
        return 0.0
    al, be = _lin(p)
    v = float(np.sum(al * (hi - lo) + 0.5 * be * (hi * hi - lo * lo)))
    # the last two (a shrinking step's energy takes one more step): pairs replaced whole, so
    # threads read consistent pairs
    _LAST_TOTAL[:] = [(p, v), _LAST_TOTAL[0]]
    return v


_LAST_TOTAL: list = [(None, 0.0), (None, 0.0)]
_LAST_DIFF: list = [(None,) * 5]     #: the last (new, old, start, kernels, difference)
