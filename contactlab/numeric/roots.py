"""Vectorised bracketed root finding that cannot fail silently.

:func:`bracketed_root` solves ``func(x) = target`` element-wise for monotone ``func`` inside a
bracket, by the Anderson-Björck variant of regula falsi safeguarded by bisection. Every step
keeps a sign change, so the answer is always inside the bracket; non-convergence raises.
"""
from __future__ import annotations

from typing import Callable

import numpy as np

from ..errors import ConvergenceError

__all__ = ["bracketed_root", "DEFAULT_XTOL"]

DEFAULT_XTOL = 4 * np.finfo(float).eps


def bracketed_root(
    func: Callable[[np.ndarray, np.ndarray], np.ndarray],
    target: np.ndarray | float,
    lo: np.ndarray | float,
    hi: np.ndarray | float,
    *,
    rtol: float = DEFAULT_XTOL,
    ftol: float = 0.0,
    maxiter: int = 200,
    what: str = "root",
) -> np.ndarray:
    """Solve ``func(x, index) = target`` for each element with a bracket ``[lo, hi]``.

    Parameters
    ----------
    func : callable ``(x, index) -> values``
        Vectorised; ``x`` has shape ``(m,)`` and ``index`` gives the flat positions of those
        elements in the broadcast inputs (for per-element parameters).
    target, lo, hi : array_like
        Broadcast together. ``func(lo) - target`` and ``func(hi) - target`` must not have the same
        strict sign.
    rtol : float
        Relative width of the final bracket: stop when ``hi - lo <= rtol * |x|`` (or the
        residual is ``<= ftol * |target|``).
    maxiter : int
        Iteration cap; reaching it raises :class:`~contactlab.errors.ConvergenceError`.
    what : str
        Name of the unknown, used in error messages.

    Returns
    -------
    ndarray
        Roots, shape of the broadcast inputs.
    """
    t, a, b = np.broadcast_arrays(*(np.asarray(v, dtype=float) for v in (target, lo, hi)))
    shape = t.shape
    t = t.ravel().copy()
    a = a.ravel().copy()
    b = b.ravel().copy()
    idx = np.arange(t.size)
    fa = np.asarray(func(a, idx), dtype=float) - t
    fb = np.asarray(func(b, idx), dtype=float) - t
    if np.any(fa * fb > 0):
        bad = np.flatnonzero(fa * fb > 0)[0]
        raise ConvergenceError(
            f"no sign change for {what} in [{a[bad]:.6g}, {b[bad]:.6g}] (target {t[bad]:.6g}): "
            "the requested value is outside the reachable range.")
    x = np.where(np.abs(fa) <= np.abs(fb), a, b)
    done = (fa == 0) | (fb == 0)
    x[fa == 0] = a[fa == 0]
    x[fb == 0] = b[fb == 0]
    side = np.zeros(t.size, dtype=int)
    act = np.flatnonzero(~done)
    for _ in range(maxiter):
        if act.size == 0:
            break
        aa, bb, ffa, ffb = a[act], b[act], fa[act], fb[act]
        # regula falsi step, bisection when it would stall at an end
        with np.errstate(invalid="ignore", divide="ignore"):
            # step from the end with the smaller residual (same point, less cancellation; keeps
            # roots near an end at 0 accurate down to subnormal values)
            step = (bb - aa) / (ffb - ffa)
            xs = np.where(np.abs(ffa) < np.abs(ffb), aa - ffa * step, bb - ffb * step)
        mid = 0.5 * (aa + bb)
        width = np.abs(bb - aa)
        bad = ~np.isfinite(xs) | (xs <= np.minimum(aa, bb)) | (xs >= np.maximum(aa, bb))
        xs = np.where(bad, mid, xs)
        fx = np.asarray(func(xs, act), dtype=float) - t[act]
        left = np.sign(fx) == np.sign(ffa)
        # Anderson-Björck: scale the retained end's value when the same end is kept twice
        keep_b = left
        with np.errstate(invalid="ignore", divide="ignore"):   # a scaled end value may underflow
            m = 1.0 - fx / np.where(left, ffa, ffb)
        m = np.where(np.isfinite(m) & (m > 0), m, 0.5)
        same = side[act] == np.where(keep_b, 1, -1)
        new_fa = np.where(left, fx, np.where(same, ffa * m, ffa))
        new_fb = np.where(left, np.where(same, ffb * m, ffb), fx)
        a[act] = np.where(left, xs, aa)
        b[act] = np.where(left, bb, xs)
        fa[act] = new_fa
        fb[act] = new_fb
        side[act] = np.where(keep_b, 1, -1)
        x[act] = xs
        new_width = np.abs(b[act] - a[act])
        # guarantee progress: force a bisection when the bracket shrank by less than half
        slow = new_width > 0.5 * width
        if np.any(slow):
            s = act[slow]
            ms = 0.5 * (a[s] + b[s])
            fm = np.asarray(func(ms, s), dtype=float) - t[s]
            lm = np.sign(fm) == np.sign(fa[s])
            a[s] = np.where(lm, ms, a[s])
            fa[s] = np.where(lm, fm, fa[s])
            b[s] = np.where(lm, b[s], ms)
            fb[s] = np.where(lm, fb[s], fm)
            x[s] = ms
            fx[slow] = fm
        mid_c = 0.5 * (a[act] + b[act])
        conv = (np.abs(b[act] - a[act]) <= rtol * np.maximum(np.abs(x[act]), 1e-300)) | (
            fx == 0) | (np.abs(fx) <= ftol * np.abs(t[act])) | (
            (mid_c == a[act]) | (mid_c == b[act]))    # no float left inside (subnormal roots)
        act = act[~conv]
    if act.size:
        raise ConvergenceError(
            f"{what} did not converge in {maxiter} iterations for {act.size} element(s) "
            f"(bracket [{a[act[0]]:.17g}, {b[act[0]]:.17g}]).")
    return x.reshape(shape)
