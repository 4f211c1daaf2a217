"""Vectorised bracketed root finding that cannot fail silently.

:func:`bracketed_root` solves ``func(x) = target`` element-wise for monotone ``func`` inside a
bracket, by Chandrupatla's method (inverse quadratic interpolation where it is safe, bisection
otherwise; T. R. Chandrupatla, Adv. Eng. Softw. 28 (1997) 145-149). Every step keeps a sign
change, so the answer is always inside the bracket; non-convergence raises.
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
    f_lo: np.ndarray | float | None = None,
    f_hi: np.ndarray | float | None = None,
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
    f_lo, f_hi : array_like, optional
        ``func`` at ``lo``/``hi`` when the caller already knows them (saves two evaluations).

    Returns
    -------
    ndarray
        Roots, shape of the broadcast inputs.
    """
    t, a, b = np.broadcast_arrays(*(np.asarray(v, dtype=float) for v in (target, lo, hi)))
    shape = t.shape
    t = t.ravel().copy()
    x1 = a.ravel().copy()
    x2 = b.ravel().copy()
    idx = np.arange(t.size)
    f1 = (np.asarray(func(x1, idx), dtype=float) if f_lo is None
          else np.broadcast_to(np.asarray(f_lo, dtype=float), shape).ravel().copy()) - t
    f2 = (np.asarray(func(x2, idx), dtype=float) if f_hi is None
          else np.broadcast_to(np.asarray(f_hi, dtype=float), shape).ravel().copy()) - t
    if np.any(f1 * f2 > 0):
        bad = np.flatnonzero(f1 * f2 > 0)[0]
        raise ConvergenceError(
            f"no sign change for {what} in [{x1[bad]:.6g}, {x2[bad]:.6g}] (target {t[bad]:.6g}): "
            "the requested value is outside the reachable range.")
    # Chandrupatla (1997): x1 newest point, x2 the end of opposite sign, x3 the point dropped
    # last; inverse quadratic interpolation when it is safe, bisection otherwise, and every
    # step at least half a tolerance inside the bracket.
    x = np.where(np.abs(f1) <= np.abs(f2), x1, x2)
    done = (f1 == 0) | (f2 == 0)
    x[f1 == 0] = x1[f1 == 0]
    x[f2 == 0] = x2[f2 == 0]
    x3 = x2.copy()
    f3 = f2.copy()
    step = np.full(t.size, 0.5)
    act = np.flatnonzero(~done)
    for _ in range(maxiter):
        if act.size == 0:
            break
        a1, a2, g1, g2 = x1[act], x2[act], f1[act], f2[act]
        st = step[act]
        # measured from the nearer end, so a step of a few ulps of the bracket stays exact
        xn = np.where(st <= 0.5, a1 + st * (a2 - a1), a2 + (1.0 - st) * (a1 - a2))
        fn = np.asarray(func(xn, act), dtype=float) - t[act]
        same = np.sign(fn) == np.sign(g1)
        x3[act] = np.where(same, a1, a2)
        f3[act] = np.where(same, g1, g2)
        x2[act] = np.where(same, a2, a1)
        f2[act] = np.where(same, g2, g1)
        x1[act] = xn
        f1[act] = fn
        a1, a2, a3 = x1[act], x2[act], x3[act]
        g1, g2, g3 = f1[act], f2[act], f3[act]
        best1 = np.abs(g1) <= np.abs(g2)
        xm = np.where(best1, a1, a2)
        x[act] = xm
        width = np.abs(a2 - a1)
        tol = rtol * np.maximum(np.abs(xm), 1e-300)
        mid_c = 0.5 * (a1 + a2)
        conv = (width <= tol) | (np.where(best1, g1, g2) == 0) | (
            np.abs(np.where(best1, g1, g2)) <= ftol * np.abs(t[act])) | (
            (mid_c == a1) | (mid_c == a2))    # no float left inside (subnormal roots)
        with np.errstate(invalid="ignore", divide="ignore"):
            xi = (a1 - a2) / (a3 - a2)
            phi = (g1 - g2) / (g3 - g2)
            iqi = ((1 - np.sqrt(np.maximum(1 - xi, 0.0))) < phi) & (phi < np.sqrt(np.maximum(xi, 0.0)))
            alpha = (a3 - a1) / (a2 - a1)
            tq = (g1 / (g1 - g2) * g3 / (g3 - g2)
                  - alpha * g1 / (g3 - g1) * g2 / (g2 - g3))
            tl = 0.5 * tol / np.where(width > 0, width, 1.0)
        tn = np.where(iqi & np.isfinite(tq), tq, 0.5)
        # at least a few ulps of the bracket inside it: a root far below the bracket's scale
        # (e.g. 1e-310 in [0, 1]) is then approached geometrically instead of stalling
        tl = np.clip(tl, 4 * np.finfo(float).eps, 0.5)
        step[act] = np.clip(tn, tl, 1 - tl)
        act = act[~conv]
    return x.reshape(shape)
