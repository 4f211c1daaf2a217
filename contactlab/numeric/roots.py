"""Vectorised bracketed root finding that cannot fail silently.

:func:`bracketed_root` solves ``func(x) = target`` element-wise for monotone ``func`` inside a
bracket, by Chandrupatla's method (inverse quadratic interpolation where it is safe, bisection
otherwise; T. R. Chandrupatla, Adv. Eng. Softw. 28 (1997) 145-149). Every step keeps a sign
change, so the answer is always inside the bracket; non-convergence raises.
"""
from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np

from ..errors import ConvergenceError

__all__ = ["convex_newton_fused", "bracketed_root", "scalar_root", "shrink_bracket", "shrink_bracket_scalar",
           "convex_newton", "DEFAULT_XTOL", "SHRINK_RATIO"]

_EPS = float(np.finfo(float).eps)
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
    secant_start: bool = False,
    first_step: np.ndarray | None = None,
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
    secant_start : bool
        Take the first step at the secant of the two ends instead of the midpoint (for brackets
        already tight around the root: one pass saved; default False keeps the classic start).
    first_step : ndarray, optional
        Per element (flat, the broadcast size), the first point as a fraction of the bracket
        from ``lo`` (in ``(0, 1)``; default 0.5, a bisection): a good guess of the root there
        saves the first bisections.

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
    if first_step is not None:
        step = np.array(first_step, dtype=float).ravel().copy()
    elif secant_start:
        with np.errstate(invalid="ignore", divide="ignore"):
            sec = f1 / (f1 - f2)
        step = np.where(np.isfinite(sec), np.clip(sec, 4 * _EPS, 1 - 4 * _EPS), 0.5)
    else:
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
    if act.size:
        i = int(act[0])
        raise ConvergenceError(
            f"{what}: bracketed solve did not converge in {maxiter} steps (bracket "
            f"[{min(x1[i], x2[i]):.17g}, {max(x1[i], x2[i]):.17g}], target {t[i]:.6g}).")
    return x.reshape(shape)


#: :func:`shrink_bracket` tightens a bracket whose upper value exceeds the target by more than
#: this factor (a root many orders of magnitude below the first bracket: forces of 1e-100 N);
#: below it the bracket is left as it is (and results as they were)
SHRINK_RATIO = 1e12
#: each shrinking step divides the upper end by this factor (16**270 spans the float range)
_SHRINK_FACTOR = 16.0


def shrink_bracket(func: Callable[[np.ndarray, np.ndarray], np.ndarray], target: np.ndarray,
                   lo: np.ndarray, hi: np.ndarray, f_hi: np.ndarray
                   ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Tighten brackets ``[lo, hi]`` of a non-decreasing ``func`` from above where
    ``func(hi) > SHRINK_RATIO * target > 0``: ``hi`` is divided by 16 while ``func`` there
    stays ``>= target`` (and above ``lo``), the last point below becomes ``lo``.

    Without it a root tens of orders of magnitude below the first bracket (``[0, R/2]`` of a
    sphere at a force of 1e-100 N) is approached by halving or by Newton steps that shrink by a
    constant factor, and runs out of iterations. Returns new ``(lo, hi, f_hi)`` arrays (1D,
    ``func(x, idx)`` as for :func:`bracketed_root`).
    """
    t = np.asarray(target, float).ravel()
    lo = np.array(lo, float).ravel()
    hi = np.array(hi, float).ravel()
    f_hi = np.array(f_hi, float).ravel()
    act = np.flatnonzero((t > 0) & (f_hi > SHRINK_RATIO * t))
    while act.size:
        trial = hi[act] / _SHRINK_FACTOR
        inside = trial > lo[act]
        act, trial = act[inside], trial[inside]
        if act.size == 0:
            break
        f_t = np.asarray(func(trial, act), float)
        above = f_t >= t[act]
        lo[act[~above]] = trial[~above]
        hi[act[above]] = trial[above]
        f_hi[act[above]] = f_t[above]
        act = act[above]
    return lo, hi, f_hi


def shrink_bracket_scalar(func: Callable[[float], float], target: float, lo: float, hi: float,
                          f_hi: float) -> tuple[float, float, float]:
    """:func:`shrink_bracket` for one bracket in plain floats (the same steps)."""
    if not (target > 0 and f_hi > SHRINK_RATIO * target):
        return lo, hi, f_hi
    while True:
        trial = hi / _SHRINK_FACTOR
        if not trial > lo:
            return lo, hi, f_hi
        f_t = func(trial)
        if f_t < target:
            return trial, hi, f_hi
        hi, f_hi = trial, f_t


def scalar_root(func: Callable[[float], float], target: float, lo: float, hi: float, *,
                rtol: float = DEFAULT_XTOL, fprime: Callable[[float], float] | None = None,
                f_lo: float | None = None, f_hi: float | None = None, maxiter: int = 200,
                what: str = "root") -> float:
    """Solve ``func(x) = target`` for one monotone non-decreasing scalar function in ``[lo, hi]``.

    The scalar counterpart of :func:`bracketed_root` for single calls, in plain floats (no array
    overhead per iteration). With a closed-form derivative ``fprime`` it takes Newton steps,
    safeguarded by the bracket (a step that leaves the bracket, or a non-positive slope, bisects
    instead); without one, Chandrupatla's method as in :func:`bracketed_root`. Stops when the
    bracket or the last step is ``<= rtol |x|``; never returns a point outside ``[lo, hi]``.

    Raises
    ------
    ConvergenceError
        No sign change in ``[lo, hi]``, or no convergence in ``maxiter`` steps.
    """
    f1 = (func(lo) if f_lo is None else f_lo) - target
    f2 = (func(hi) if f_hi is None else f_hi) - target
    if f1 * f2 > 0:
        raise ConvergenceError(
            f"no sign change for {what} in [{lo:.6g}, {hi:.6g}] (target {target:.6g}): "
            "the requested value is outside the reachable range.")
    if f1 == 0:
        return lo
    if f2 == 0:
        return hi
    if fprime is not None:
        return _newton(func, fprime, target, lo, hi, f1, f2, rtol, maxiter, what)
    return _chandrupatla(func, target, lo, hi, f1, f2, rtol, maxiter, what)


def _newton(func, fprime, target, a, b, fa, fb, rtol, maxiter, what) -> float:
    # bracket [a, b] with fa < 0 < fb (func non-decreasing); start at the end with the smaller
    # residual
    x = a if abs(fa) <= abs(fb) else b
    fx = fa if x == a else fb
    for _ in range(maxiter):
        d = fprime(x)
        step = fx / d if d > 0 and math.isfinite(d) else math.nan
        if abs(step) <= rtol * abs(x):       # the next Newton step is below the tolerance
            return x
        xn = x - step
        if not (a < xn < b):                 # also catches nan: bisect, in log scale while the
            # bracket spans more than a factor 4 (a root far below a wide first bracket)
            xn = 0.25 * b if a <= 0 else (math.sqrt(a * b) if b > 4 * a else 0.5 * (a + b))
            step = x - xn
        fn = func(xn) - target
        if fn == 0:
            return xn
        if fn < 0:
            a = xn
        else:
            b = xn
        x, fx = xn, fn
        if abs(step) <= rtol * abs(x) or b - a <= rtol * abs(x) or 0.5 * (a + b) in (a, b):
            return x
    raise ConvergenceError(f"{what}: Newton iteration did not converge in {maxiter} steps "
                           f"(bracket [{a:.17g}, {b:.17g}]).")


def _chandrupatla(func, target, x1, x2, f1, f2, rtol, maxiter, what, first_step=0.5,
                  ftol=0.0) -> float:
    # the same iteration as bracketed_root, for one element in plain floats
    eps4 = 4 * _EPS
    x3, f3 = x2, f2
    t = first_step
    x = x1 if abs(f1) <= abs(f2) else x2
    for _ in range(maxiter):
        xn = x1 + t * (x2 - x1) if t <= 0.5 else x2 + (1.0 - t) * (x1 - x2)
        fn = func(xn) - target
        if (fn > 0) == (f1 > 0) and fn != 0:
            x3, f3 = x1, f1
        else:
            x3, f3 = x2, f2
            x2, f2 = x1, f1
        x1, f1 = xn, fn
        xm, fm = (x1, f1) if abs(f1) <= abs(f2) else (x2, f2)
        x = xm
        width = abs(x2 - x1)
        tol = rtol * max(abs(xm), 1e-300)
        mid = 0.5 * (x1 + x2)
        if width <= tol or fm == 0 or abs(fm) <= ftol * abs(target) or mid == x1 or mid == x2:
            return x
        tl = min(max(0.5 * tol / width, eps4), 0.5)
        xi = (x1 - x2) / (x3 - x2) if x3 != x2 else math.nan
        phi = (f1 - f2) / (f3 - f2) if f3 != f2 else math.nan
        tn = 0.5
        if (1 - math.sqrt(max(1 - xi, 0.0))) < phi < math.sqrt(max(xi, 0.0)):
            alpha = (x3 - x1) / (x2 - x1)
            try:
                tq = (f1 / (f1 - f2) * f3 / (f3 - f2) - alpha * f1 / (f3 - f1) * f2 / (f2 - f3))
            except ZeroDivisionError:
                tq = 0.5
            if math.isfinite(tq):
                tn = tq
        t = min(max(tn, tl), 1 - tl)
    raise ConvergenceError(f"{what}: bracketed solve did not converge in {maxiter} steps.")


def convex_newton(residual: Callable[[np.ndarray, np.ndarray],
                                     tuple[np.ndarray, np.ndarray, np.ndarray]],
                  x0: np.ndarray, *, rtol: float, maxiter: int = 200, what: str = "root"
                  ) -> np.ndarray:
    """Roots of increasing convex functions by Newton's method from above, element-wise.

    ``residual(x, index)`` returns ``(r, r', noise)`` for the elements ``index`` (flat positions
    in ``x0``) still iterating: the residual ``φ(x) - target``, its derivative (> 0) and the
    rounding level of ``r`` (absolute). Every start ``x0`` must lie at or above its root: on an
    increasing convex function Newton's steps then fall monotonically onto the root and never
    overshoot, so no bracket is needed. An element stops after a step no larger than
    ``rtol · x`` (the error left is of the order of that step squared) or, without that step,
    once its residual is within its rounding noise; only the elements still iterating are
    evaluated, and an element's value does not depend on the other elements of the batch.

    Raises
    ------
    ConvergenceError
        If some element has not stopped after ``maxiter`` steps.
    """
    x = np.array(x0, dtype=float, copy=True).ravel()
    idx = np.arange(x.size)
    xa = x.copy()
    for _ in range(maxiter):
        r, dr, noise = residual(xa, idx)
        with np.errstate(divide="ignore", invalid="ignore"):
            step = r / dr
        new = xa - step
        quiet = np.abs(r) <= noise
        np.copyto(new, xa, where=quiet)                 # (a quiet element keeps its value)
        done = np.abs(step) <= rtol * np.abs(new)
        done |= quiet
        if done.all():
            x[idx] = new
            return x.reshape(np.shape(x0))
        if done.any():
            x[idx[done]] = new[done]
            keep = ~done
            idx, xa = idx[keep], new[keep]
        else:
            xa = new
    raise ConvergenceError(f"{what}: Newton's method did not converge in {maxiter} steps "
                           f"(at {xa[0]!r}).")


def convex_newton_fused(step_of: Callable[[np.ndarray, np.ndarray, np.ndarray], None],
                        x0: np.ndarray, *, rtol: float, maxiter: int = 200, what: str = "root",
                        overwrite: bool = False) -> np.ndarray:
    """:func:`convex_newton` on whole arrays with no per-round allocation: the same iterates,
    the same stopping rule, the same values bit for bit.

    ``step_of(x, step, quiet)`` writes, for every element of the flat float array ``x``, the
    Newton step ``r/r'`` into ``step`` and whether ``|r| <= noise`` into the boolean ``quiet``
    (both of ``x``'s shape, with the operations :func:`convex_newton`'s ``residual`` would
    perform, so that the bits agree). Elements that have stopped are evaluated too and keep
    their value: each round costs the whole array, but no masked copies or scatters, which on
    arrays of 10^5 elements cost more than the arithmetic (a fresh array is a page fault per
    4 KiB). An element's value does not depend on the other elements of the batch. With
    ``overwrite``, a C-contiguous float64 ``x0`` of the caller's own is iterated in place (and
    returned).

    Raises
    ------
    ConvergenceError
        If some element has not stopped after ``maxiter`` steps.
    """
    if (overwrite and type(x0) is np.ndarray and x0.dtype == np.float64
            and x0.flags.c_contiguous and x0.flags.writeable):
        x = x0.reshape(-1)
    else:
        x = np.array(x0, dtype=float, copy=True).ravel()
    step = np.empty_like(x)
    new = np.empty_like(x)
    quiet = np.empty(x.shape, dtype=bool)
    done = np.empty(x.shape, dtype=bool)
    live = np.ones(x.shape, dtype=bool)
    for _ in range(maxiter):
        with np.errstate(divide="ignore", invalid="ignore"):
            step_of(x, step, quiet)
            np.subtract(x, step, out=new)
        np.copyto(new, x, where=quiet)                  # (a quiet element keeps its value)
        np.copyto(x, new, where=live)
        # done: |step| <= rtol |new|, with x = new wherever it matters (the live elements)
        np.abs(x, out=new)
        new *= rtol
        np.abs(step, out=step)
        np.less_equal(step, new, out=done)
        done |= quiet
        np.logical_not(done, out=done)
        live &= done
        if not live.any():
            return x.reshape(np.shape(x0))
    raise ConvergenceError(f"{what}: Newton's method did not converge in {maxiter} steps "
                           f"(at {x[np.argmax(live)]!r}).")

