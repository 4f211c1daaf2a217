"""Root brackets of the exact stick-radius solves (:mod:`contactlab.physics.torsion_exact`).

Many roots that share one normal state (a torque-twist curve) share one evaluation of the
function on a grid in ``y = ln(c/a)``; each root is then bracketed by two neighbouring grid
points, split by one inverse-interpolation step, and (the curve route) tightened by a Newton
point just across the root, so that the bracketed root finder starts next to the root.
Private helpers of the exact torsion kernels.
"""
from __future__ import annotations

import numpy as np

from ..numeric.roots import bracketed_root

__all__: list[str] = []


#: subintervals of each root-bracketing grid interval on the curve route (``panels``): one more
#: batched evaluation of at most (roots x this) points buys a start closer to the root by
#: about ``(this + 1)³`` and saves passes of the root finder over all the curve's points
_CURVE_REFINE = 4
#: the curve route's grid is evaluated above this ``y = ln(c/a)`` first (stick radii below
#: 0.7 % of the contact radius, the costliest points, only for twists that need them)
_LAZY_Y = -5.0
#: the curve route's second point: a Newton step from the first, lengthened by this fraction
#: (the interpolant's slope errs by ~1e-2 relative on a 667-node table, the step itself by the
#: table's wiggles, ~1e-5 of y)
_NEWTON_OVERSHOOT = 0.05

_GRIDS: dict = {}


def _y_grid(y_min: float) -> np.ndarray:
    """``y = ln(c/a)`` grid used to bracket many roots that share one normal state (log-spaced
    in ``|y|`` from 1e-9 to ``|y_min|``, ~10 points per decade; cached per ``y_min``)."""
    hit = _GRIDS.get(y_min)
    if hit is None:
        hit = _GRIDS[y_min] = -np.logspace(-9.0, np.log10(-y_min), 120)[::-1]
    return hit


def _grid_brackets(func, target: np.ndarray, a: np.ndarray, d: np.ndarray, g_a: np.ndarray,
                   y_min: float, min_group: int = 16, refine: int = 0):
    """Narrow brackets in ``y = ln(c/a)`` for roots of a function decreasing in ``y``.

    Elements sharing one normal state ``(a, d, g(a))`` (a torque-twist curve) share one evaluation
    of ``func`` on :func:`_y_grid`. Each root is bracketed by two neighbouring grid nodes, then
    one inverse-interpolation step (quadratic in ``y`` through three grid nodes) splits that bracket
    at a point very close to the root, so the root finder starts with one end nearly on the root.
    Returns ``(lo, hi, f_lo, f_hi)`` (``f`` = NaN where unknown); groups smaller than ``min_group``
    keep the full bracket ``[y_min, 0]``.

    ``refine > 0`` (curves of many points): every grid interval that brackets a root of a
    one-state group is split into ``refine + 1`` (one more batched evaluation), so the
    interpolated start lies much closer to the root and the root finder needs fewer passes; the
    second bracket point is then a Newton step on the interpolant's slope, lengthened by
    :data:`_NEWTON_OVERSHOOT`, so that it lands just across the root.
    """
    n = target.size
    lo = np.full(n, y_min)
    hi = np.zeros(n)
    f_lo = np.full(n, np.nan)
    f_hi = np.full(n, np.nan)
    keys, inverse, counts = np.unique(np.stack([a, d, g_a], axis=1), axis=0, return_inverse=True,
                                      return_counts=True)
    inverse = inverse.ravel()
    big = np.flatnonzero(counts >= min_group)
    if big.size == 0:
        return lo, hi, f_lo, f_hi
    first = np.array([np.flatnonzero(inverse == k)[0] for k in big])
    grid = np.concatenate([[y_min], _y_grid(y_min)[_y_grid(y_min) > y_min], [0.0]])
    n_g = grid.size
    if refine > 0 and big.size == 1:
        # one state (a curve): the grid from its top down to _LAZY_Y first; the points below
        # (the smallest stick radii, the costliest to integrate) only when a target lies
        # beyond the values reached. Unevaluated points count as above every target (φ
        # decreases along the grid), so the brackets are those of the whole grid.
        cut = int(np.searchsorted(grid, _LAZY_Y))
        vals = np.full((1, n_g), np.inf)
        vals[0, cut:] = func(grid[cut:], np.full(n_g - cut, first[0]))
        if cut > 0 and not np.max(target[inverse == big[0]]) < vals[0, cut]:
            vals[0, :cut] = func(grid[:cut], np.full(cut, first[0]))
    else:
        vals = func(np.tile(grid, big.size), np.repeat(first, n_g)).reshape(big.size, n_g)
    row = np.full(keys.shape[0], -1)
    row[big] = np.arange(big.size)
    sel = np.flatnonzero(row[inverse] >= 0)
    v = vals[row[inverse[sel]]]                       # (m, n_g), decreasing along the grid
    tg = target[sel]
    k = np.clip(np.sum(v > tg[:, None], axis=1), 1, n_g - 1)
    if refine > 0 and big.size == 1:
        # one state (a curve): split the bracketing intervals, evaluate once, re-bracket
        used = np.unique(k)
        frac = np.arange(1, refine + 1) / (refine + 1)
        new = (grid[used - 1][:, None] + frac * (grid[used] - grid[used - 1])[:, None]).ravel()
        f_new = func(new, np.full(new.size, first[0]))
        grid = np.concatenate([grid, new])
        order = np.argsort(grid, kind="stable")
        grid = grid[order]
        n_g = grid.size
        row0 = np.concatenate([vals[0], f_new])[order]
        v = np.broadcast_to(row0, (sel.size, n_g))                    # one row, no copies
        k = np.clip(np.sum(v > tg[:, None], axis=1), 1, n_g - 1)
    ylo, yhi = grid[k - 1], grid[k]
    flo = v[np.arange(sel.size), k - 1]
    fhi = v[np.arange(sel.size), k]
    # inverse quadratic interpolation y(f) through the bracket and its neighbour
    j = np.clip(np.where(k + 1 < n_g, k + 1, k - 2), 0, n_g - 1)
    y3, f3 = grid[j], v[np.arange(sel.size), j]
    with np.errstate(divide="ignore", invalid="ignore"):
        L1 = (tg - fhi) * (tg - f3) / ((flo - fhi) * (flo - f3))
        L2 = (tg - flo) * (tg - f3) / ((fhi - flo) * (fhi - f3))
        L3 = (tg - flo) * (tg - fhi) / ((f3 - flo) * (f3 - fhi))
        y0 = L1 * ylo + L2 * yhi + L3 * y3
        y_lin = ylo + (tg - flo) * (yhi - ylo) / (fhi - flo)
    y0 = np.where(np.isfinite(y0) & (y0 > ylo) & (y0 < yhi), y0, y_lin)
    y0 = np.where(np.isfinite(y0) & (y0 > ylo) & (y0 < yhi), y0, 0.5 * (ylo + yhi))
    f0 = func(y0, sel)
    above = f0 > tg                                   # root lies above y0
    lo_s = np.where(above, y0, ylo)
    flo_s = np.where(above, f0, flo)
    hi_s = np.where(above, yhi, y0)
    fhi_s = np.where(above, fhi, f0)
    # a second point just across the root (4x the quadratic-vs-linear discrepancy), so that both
    # ends are close: regula falsi then stops at once instead of bisecting from the far end
    step = np.maximum(4.0 * np.abs(y0 - np.where(np.isfinite(y_lin), y_lin, y0)),
                      1e-9 * np.maximum(np.abs(y0), 1e-6))
    if refine > 0:
        # the curve route: y0's error is set by the table's wiggles between the grid points,
        # not by the interpolant's order; a Newton step from y0 on the interpolant's slope,
        # overshot by _NEWTON_OVERSHOOT, lands just across the root (the slope errs by far
        # less than that), so the bracket is a fraction of y0's error wide and the secant that
        # follows meets the tolerance in one pass
        with np.errstate(divide="ignore", invalid="ignore"):
            dy = (((tg - fhi) + (tg - f3)) / ((flo - fhi) * (flo - f3)) * ylo
                  + ((tg - flo) + (tg - f3)) / ((fhi - flo) * (fhi - f3)) * yhi
                  + ((tg - flo) + (tg - fhi)) / ((f3 - flo) * (f3 - fhi)) * y3)
            newton = np.abs((f0 - tg) * dy) * (1.0 + _NEWTON_OVERSHOOT)
        good = np.isfinite(newton) & (newton > 0)
        step = np.where(good, np.maximum(newton, 1e-9 * np.maximum(np.abs(y0), 1e-6)), step)
    y1 = np.where(above, np.minimum(y0 + step, yhi), np.maximum(y0 - step, ylo))
    inner = (y1 > lo_s) & (y1 < hi_s)
    if np.any(inner):
        k1 = np.flatnonzero(inner)
        f1 = func(y1[k1], sel[k1])
        up = f1 > tg[k1]                              # root above y1
        lo_s[k1] = np.where(up, y1[k1], lo_s[k1])
        flo_s[k1] = np.where(up, f1, flo_s[k1])
        hi_s[k1] = np.where(up, hi_s[k1], y1[k1])
        fhi_s[k1] = np.where(up, fhi_s[k1], f1)
    lo[sel], f_lo[sel], hi[sel], f_hi[sel] = lo_s, flo_s, hi_s, fhi_s
    return lo, hi, f_lo, f_hi


def _bracketed(func, target: np.ndarray, lo: np.ndarray, hi: np.ndarray, f_lo: np.ndarray,
               f_hi: np.ndarray, rtol: float, what: str, ftol: float | None = None,
               secant_start: bool = False) -> np.ndarray:
    """:func:`bracketed_root` with the end values known where ``f_lo``/``f_hi`` are finite.

    ``ftol`` (default ``rtol``): residual test; 0 keeps refining the bracket in ``y`` to ``rtol``
    (needed where the function is flat in ``y``: the torque near full sliding)."""
    ftol = rtol if ftol is None else ftol
    known = np.isfinite(f_lo) & np.isfinite(f_hi)
    out = np.empty(target.shape)
    for mask, use in ((known, True), (~known, False)):
        if not np.any(mask):
            continue
        ids = np.flatnonzero(mask)

        def sub(y: np.ndarray, idx: np.ndarray, *, ids: np.ndarray = ids) -> np.ndarray:
            return func(y, ids[idx])   # ids bound now: the closure runs in this iteration only

        out[ids] = bracketed_root(sub, target[ids], lo[ids], hi[ids], rtol=rtol, ftol=ftol,
                                  what=what, f_lo=f_lo[ids] if use else None,
                                  f_hi=f_hi[ids] if use else None,
                                  secant_start=secant_start and use)
    return out
