"""Vectorised adaptive tanh-sinh (double-exponential) quadrature.

Every numeric integral in contactlab goes through :func:`tanh_sinh`. It integrates a batch of
integrals at once (one per element of ``lo``/``hi``), refines only those that have not converged,
and returns an error estimate for each. The double-exponential substitution makes integrable
endpoint singularities (``1/sqrt`` edges, ``r**(n-1)`` for ``n < 1``, logarithms, slope jumps placed
at an endpoint) converge as fast as smooth integrands, which is why it was chosen over
Gauss-Legendre.

References
----------
H. Takahasi, M. Mori, "Double exponential formulas for numerical integration",
Publ. RIMS 9 (1974) 721-741.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cache
from collections.abc import Callable

import numpy as np

from ..errors import ConvergenceError

__all__ = ["QuadratureResult", "tanh_sinh", "tanh_sinh_upto", "first_converged", "min_level_for",
           "DEFAULT_RTOL", "MAX_LEVEL", "UPTO_LEVEL"]

DEFAULT_RTOL = 1e-10
MAX_LEVEL = 9          # step h = 2**-9 / 2: ~ 6600 nodes per integral at most
# nodes reach within exp(-pi*sinh(4.5)) ~ 1e-61 of the ends: the tail of an r**-0.7 end
# singularity beyond them is < 1e-18 (3.15 would lose 1e-8)
_T_MAX = 4.5
_H0 = 0.5


#: rtol from which two levels (37 nodes per integral) may already stop the refinement
LOOSE_RTOL = 1e-3


def min_level_for(rtol: float) -> int:
    """The first level at which :func:`tanh_sinh` may stop, chosen from ``rtol``.

    The double-exponential error roughly squares from one level to the next, so the difference
    between levels 0 and 1 (19 and 37 nodes) bounds the error of level 1 by a wide margin when
    that difference is itself below a loose ``rtol`` (>= :data:`LOOSE_RTOL`); tighter tolerances
    keep the first check at level 2 (73 nodes), where the estimate has been measured to cover the
    error (docs/accuracy.md). The tail bound of the truncated range is part of the estimate at
    every level.
    """
    return 1 if rtol >= LOOSE_RTOL else 2


@dataclass(frozen=True)
class QuadratureResult:
    """Values of a batch of integrals with absolute error estimates.

    Attributes
    ----------
    value : ndarray
        The integrals, shape of the broadcast ``lo``/``hi``.
    error : ndarray
        Absolute error estimate per integral: the change between the last two refinement levels
        (conservative for the double-exponential rule, whose error roughly squares per level).
    level : int
        Highest refinement level used.
    evaluations : int
        Total integrand evaluations (nodes x integrals), a cost measure.
    """

    value: np.ndarray
    error: np.ndarray
    level: int
    evaluations: int


@cache
def _level_nodes(level: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Nodes new at ``level``: (lower-end fraction, upper-end fraction, weight without h).

    A node sits at ``lo + (hi-lo)*low_frac`` computed as ``hi - (hi-lo)*high_frac`` on the upper
    half, so points near either end keep full relative precision of their distance to that end.
    """
    h = _H0 / 2**level
    # the same t-range at every level (that of level 0), so refinement never mixes truncations
    k_max = int(np.ceil(_T_MAX / _H0)) * 2**level
    k = np.arange(-k_max, k_max + 1)
    if level > 0:
        k = k[k % 2 != 0]
    t = k * h
    s = np.pi * np.sinh(t)
    low = 1.0 / (np.exp(-s) + 1.0)         # (1+u)/2
    high = 1.0 / (np.exp(s) + 1.0)         # (1-u)/2
    w = 0.5 * np.pi * np.cosh(t) / np.cosh(0.5 * s) ** 2   # du/dt
    return low, high, w


@cache
def _levels_upto(top: int) -> tuple[np.ndarray, np.ndarray, tuple[np.ndarray, ...],
                                     tuple[int, ...]]:
    """Nodes of levels 0 … ``top`` side by side (level 0 first): (low, high, the weights of
    each level, the column where each level starts and, last, the total)."""
    parts = [_level_nodes(k) for k in range(top + 1)]
    starts = np.cumsum([0] + [p[0].size for p in parts])
    return (np.concatenate([p[0] for p in parts]), np.concatenate([p[1] for p in parts]),
            tuple(p[2] for p in parts), tuple(int(v) for v in starts))


@cache
def _weights_upto(top: int) -> np.ndarray:
    """The weights of levels 0 … ``top`` side by side (:func:`_levels_upto`'s order; kept
    read-only)."""
    w = np.concatenate(_levels_upto(top)[2])
    w.flags.writeable = False
    return w


@cache
def _common_nodes(lo: float, hi: float, top: int
                  ) -> tuple[np.ndarray, np.ndarray, np.ndarray | None]:
    """Nodes of levels 0 … ``top`` on one interval ``[lo, hi]`` (a row vector), their
    validity, and the positions of the invalid ones (None when every node is valid)."""
    low, high, *_ = _levels_upto(top)
    lo_, hi_ = np.array([lo]), np.array([hi])
    d = (hi_ - lo_)[:, None]
    x = np.where(low[None, :] <= 0.5, lo_[:, None] + d * low, hi_[:, None] - d * high)
    valid = (x > np.minimum(lo_, hi_)[:, None]) & (x < np.maximum(lo_, hi_)[:, None])
    x = np.where(valid, x, 0.5 * (lo_ + hi_)[:, None])
    x.flags.writeable = False
    valid.flags.writeable = False
    bad = np.flatnonzero(~valid[0])
    return x, valid, (bad if bad.size else None)


@cache
def _tail_constants() -> tuple[np.ndarray, np.ndarray]:
    """The end distances and the logarithms of their ratios :func:`_tail` takes at the lower
    and upper ends of level 0 (as a column pair: lower end first)."""
    low, high, _, starts = _levels_upto(0)
    n0 = starts[1]
    d0 = np.array([low[0], high[n0 - 1]])
    lnr = np.array([np.log(low[0] / low[1]), np.log(high[n0 - 1] / high[n0 - 2])])
    return d0[:, None], lnr[:, None]


def _tails(f0: np.ndarray) -> np.ndarray:
    """:func:`_tail` at both ends of the level-0 values ``f0`` (rows: integrals), summed: the
    same operations on both ends at once (the same values; in place where :func:`_tail` makes
    new arrays, and no ``where`` unless some end value is 0 or NaN)."""
    d0, lnr = _tail_constants()
    n = f0.shape[1]
    a0 = np.abs(f0[:, ::n - 1].T)               # the outermost nodes (columns 0 and n-1)
    a1 = np.abs(f0[:, 1:n - 1:n - 3].T)         # their neighbours (columns 1 and n-2)
    ok = (a0 > 0) & (a1 > 0)
    with np.errstate(divide="ignore", invalid="ignore"):
        e = np.log(a0 / a1)
    e /= lnr
    if not ok.all():
        np.copyto(e, 0.0, where=~ok)
    np.minimum(e, 0.0, out=e)
    e += 1.0
    np.maximum(e, 0.02, out=e)
    t = a0 * d0
    t /= e
    return t[0] + t[1]


_row_sum = np.add.reduce

#: the highest level :func:`tanh_sinh_upto` evaluates (73 nodes per integral)
UPTO_LEVEL = 2


def tanh_sinh_upto(integrand: Callable[[np.ndarray, np.ndarray], np.ndarray],
                   lo: np.ndarray, hi: np.ndarray, top: int = UPTO_LEVEL, common: bool = False
                   ) -> tuple[np.ndarray, np.ndarray]:
    """Levels 0 … ``top`` of :func:`tanh_sinh` in one pass (one integrand call for all nodes).

    Returns ``(values, errors)``, shape ``(top, m)`` for 1D ``lo``/``hi`` of size ``m``: row
    ``k - 1`` holds, bit for bit, the value and error estimate (level difference plus the tail
    bound) that :func:`tanh_sinh` holds after its level ``k``: the same nodes, the same
    integrand values and the same row sums in the same order. :func:`tanh_sinh` with
    ``min_level`` stops an integral at the first level ``k >= min_level`` whose
    ``error <= atol + rtol |value|``: where that level is ``<= top`` its result can be read off
    here (:func:`first_converged`), which saves the refinement loop's bookkeeping (a few dozen
    small array operations per level, most of the cost of one integral at a loose ``rtol``).
    ``common``: every row has the interval of the first, ``lo < hi`` (its nodes are then kept
    between calls).
    """
    low, high, ws, starts = _levels_upto(top)
    width = hi - lo
    if common:          # every row the same interval: its nodes, computed once
        x1, valid1, bad = _common_nodes(float(lo[0]), float(hi[0]), top)
        x = x1 if lo.size == 1 else np.broadcast_to(x1, (lo.size, x1.shape[1]))
        fx = np.asarray(integrand(x, np.arange(lo.size)), dtype=float)
        if bad is not None:
            fx = np.where(valid1, fx, 0.0)
        same = None
    else:
        d = width[:, None]
        x = np.where(low[None, :] <= 0.5, lo[:, None] + d * low, hi[:, None] - d * high)
        valid = (x > np.minimum(lo, hi)[:, None]) & (x < np.maximum(lo, hi)[:, None])
        x = np.where(valid, x, 0.5 * (lo + hi)[:, None])
        fx = np.asarray(integrand(x, np.arange(lo.size)), dtype=float)
        fx = np.where(valid, fx, 0.0)
        same = hi == lo
    half = 0.5 * width
    f0 = fx[:, :starts[1]]
    tail = _tails(f0) * np.abs(width)
    # np.sum's reduction itself (np.add.reduce: the same row sums, without its wrapper)
    sums = 0.0 + _row_sum(f0 * ws[0], axis=1)         # (tanh_sinh's sums start at +0.0)
    prev = half * _H0 * sums
    values = []
    errors = []
    for k in range(1, top + 1):
        sums = sums + _row_sum(fx[:, starts[k]:starts[k + 1]] * ws[k], axis=1)
        value = half * (_H0 / 2**k) * sums
        values.append(value)
        errors.append(np.abs(value - prev) + tail)
        prev = value
    out_v, out_e = np.array(values), np.array(errors)
    if same is not None and same.any():
        out_v[:, same] = 0.0
        out_e[:, same] = 0.0
    return out_v, out_e


def upto_rows(fx: np.ndarray, lo: float, hi: float, top: int = UPTO_LEVEL
              ) -> list[tuple[list[float], list[float]]] | None:
    """:func:`tanh_sinh_upto` on one interval ``[lo, hi]`` (``lo < hi``) from the integrand
    values ``fx`` on its nodes (:func:`common_nodes`, one row per integral, invalid nodes
    included), in floats: per row ``(values, errors)`` of levels 1 … ``top``, the same
    operations in the same order (numpy's row sums and logarithm, the rest IEEE float
    arithmetic): the same bits, without the array bookkeeping that dominates one integral.
    ``None`` where an end value is not finite (the caller then takes :func:`tanh_sinh_upto`)."""
    _, valid1, bad = _common_nodes(lo, hi, top)
    if bad is not None:
        fx = np.where(valid1, fx, 0.0)
    starts = _levels_upto(top)[3]
    n0 = starts[1]
    d_lo, d_hi, ln_lo, ln_hi = _tail_floats()
    width = hi - lo
    half = 0.5 * width
    aw = abs(width)
    # the products of every level in one multiplication (the same products), then each
    # level's row sums on its columns (the same sums, in the same order)
    prod = fx * _weights_upto(top)
    sums_k = [_row_sum(prod[:, starts[k]:starts[k + 1]], axis=1).tolist()
              for k in range(top + 1)]
    out = []
    for i, row in enumerate(fx[:, :n0].tolist()):
        a0, a1, b1, b0 = abs(row[0]), abs(row[1]), abs(row[n0 - 2]), abs(row[n0 - 1])
        if not (math.isfinite(a0) and math.isfinite(a1) and math.isfinite(b0)
                and math.isfinite(b1)):
            return None
        ok_lo, ok_hi = a0 > 0 and a1 > 0, b0 > 0 and b1 > 0
        logs = np.log(np.array([a0 / a1 if ok_lo else 1.0, b0 / b1 if ok_hi else 1.0]))
        e_lo = float(logs[0]) / ln_lo if ok_lo else 0.0
        e_hi = float(logs[1]) / ln_hi if ok_hi else 0.0
        t_lo = a0 * d_lo / max(1.0 + min(e_lo, 0.0), 0.02)
        t_hi = b0 * d_hi / max(1.0 + min(e_hi, 0.0), 0.02)
        tail = (t_lo + t_hi) * aw
        sums = 0.0 + sums_k[0][i]
        prev = half * _H0 * sums
        values, errors = [], []
        for k in range(1, top + 1):
            sums = sums + sums_k[k][i]
            value = half * (_H0 / 2**k) * sums
            values.append(value)
            errors.append(abs(value - prev) + tail)
            prev = value
        out.append((values, errors))
    return out


def common_nodes(lo: float, hi: float, top: int = UPTO_LEVEL) -> np.ndarray:
    """The nodes of levels 0 … ``top`` on ``[lo, hi]`` as :func:`tanh_sinh_upto` passes them
    to the integrand of one integral (a read-only row vector, kept between calls)."""
    return _common_nodes(lo, hi, top)[0]


@cache
def _tail_floats() -> tuple[float, float, float, float]:
    """:func:`_tail_constants` as floats: end distances (lower, upper), their log ratios."""
    d0, lnr = _tail_constants()
    return float(d0[0, 0]), float(d0[1, 0]), float(lnr[0, 0]), float(lnr[1, 0])


def first_converged(values: np.ndarray, errors: np.ndarray, rtol: float, min_level: int
                    ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """:func:`tanh_sinh`'s stopping rule (``atol = 0``) on :func:`tanh_sinh_upto`'s levels:
    ``(value, error, done)`` per integral, at the first level ``>= min_level`` with
    ``error <= rtol |value|``; ``done`` is False where no level up to the top one stops (value
    and error are then those of the top level)."""
    top = values.shape[0]
    value = values[top - 1].copy()
    error = errors[top - 1].copy()
    done = np.zeros(values.shape[1], dtype=bool)
    for k in range(top, min_level - 1, -1):      # the lowest stopping level wins: last
        ok = errors[k - 1] <= rtol * np.abs(values[k - 1])
        if k == top:
            done = ok
        else:
            done = done | ok
        value = np.where(ok, values[k - 1], value)
        error = np.where(ok, errors[k - 1], error)
    return value, error, done


def _tail(f0: np.ndarray, f1: np.ndarray, d0: float, d1: float) -> np.ndarray:
    """``|f0| d0/(1+e)`` with the local exponent ``e = ln|f0/f1| / ln(d0/d1)`` (capped)."""
    a0, a1 = np.abs(f0), np.abs(f1)
    with np.errstate(divide="ignore", invalid="ignore"):
        e = np.where((a0 > 0) & (a1 > 0), np.log(a0 / np.where(a1 > 0, a1, 1.0)) / np.log(d0 / d1),
                     0.0)
    return a0 * d0 / np.maximum(1.0 + np.minimum(e, 0.0), 0.02)


def tanh_sinh(
    integrand: Callable[[np.ndarray, np.ndarray], np.ndarray],
    lo: np.ndarray | float,
    hi: np.ndarray | float,
    *,
    rtol: float = DEFAULT_RTOL,
    atol: np.ndarray | float = 0.0,
    min_level: int = 2,
    max_level: int = MAX_LEVEL,
    raise_on_failure: bool = True,
) -> QuadratureResult:
    """Integrate a batch of integrals ``∫_lo^hi integrand dx`` to ``rtol``.

    Parameters
    ----------
    integrand : callable ``(x, index) -> values``
        ``x`` has shape ``(m, k)``: ``k`` nodes for each of the ``m`` integrals still being
        refined; ``index`` (shape ``(m,)``) gives their flat positions in the broadcast
        ``lo``/``hi`` so that the integrand can pick its per-integral parameters. Must return an
        array of shape ``(m, k)``. Nodes never coincide with ``lo`` or ``hi``.
    lo, hi : float or array_like
        Limits; broadcast together. ``hi == lo`` gives 0.
    rtol, atol : float (atol may be an array broadcast with ``lo``)
        Stop refining an integral once its error estimate is ``<= atol + rtol*|value|``.
    min_level, max_level : int
        Refinement levels (step ``0.5 * 2**-level``); each level doubles the node count.
    raise_on_failure : bool
        Raise :class:`~contactlab.errors.ConvergenceError` if some integral misses the tolerance at
        ``max_level`` (default); otherwise return with the honest error estimate.

    Returns
    -------
    QuadratureResult
    """
    lo_b, hi_b = np.broadcast_arrays(np.asarray(lo, dtype=float), np.asarray(hi, dtype=float))
    shape = lo_b.shape
    lo_f = lo_b.ravel()
    hi_f = hi_b.ravel()
    n = lo_f.size
    atol_f = np.broadcast_to(np.asarray(atol, dtype=float), shape).ravel()
    half = 0.5 * (hi_f - lo_f)
    sums = np.zeros(n)
    value = np.zeros(n)
    prev = np.full(n, np.nan)
    error = np.full(n, np.inf)
    active = np.flatnonzero(hi_f != lo_f)
    error[hi_f == lo_f] = 0.0
    evaluations = 0
    level = 0
    tail = np.zeros(n)       # bound on the parts beyond the outermost nodes (see below)
    for level in range(max_level + 1):
        if active.size == 0:
            break
        low, high, w = _level_nodes(level)
        d = (hi_f - lo_f)[active, None]
        x = np.where(low[None, :] <= 0.5, lo_f[active, None] + d * low, hi_f[active, None] - d * high)
        # Nodes that collapsed onto an endpoint in floating point carry no information; their
        # weights are below the rounding level of the sum, so they are dropped.
        valid = (x > np.minimum(lo_f[active, None], hi_f[active, None])) & (
            x < np.maximum(lo_f[active, None], hi_f[active, None]))
        x = np.where(valid, x, 0.5 * (lo_f[active, None] + hi_f[active, None]))
        fx = np.asarray(integrand(x, active), dtype=float)
        fx = np.where(valid, fx, 0.0)
        evaluations += fx.size
        if level == 0:
            # The t-range is truncated at ±_T_MAX. For a strong endpoint singularity (e.g.
            # x**-0.7) the cut-off pieces are not negligible and do not change between levels, so
            # the level-difference estimate would miss them: bound them by |f| at the outermost
            # node times its distance to the end (negligible for bounded integrands).
            # For f ~ δ**e near the end (δ = distance), the cut-off piece is f(δ0) δ0/(1+e); e
            # is read off the two outermost nodes (e = 0 when either value is 0).
            tail[active] = (_tail(fx[:, 0], fx[:, 1], low[0], low[1])
                            + _tail(fx[:, -1], fx[:, -2], high[-1], high[-2])) * np.abs(d[:, 0])
        # a plain row sum, not BLAS: an integral's rounding must not depend on which other
        # integrals share the call (gemv groups rows by their position in the batch)
        sums[active] += np.sum(fx * w, axis=1)
        h = _H0 / 2**level
        value[active] = half[active] * h * sums[active]
        if level >= 1:
            error[active] = np.abs(value[active] - prev[active]) + tail[active]
        prev[active] = value[active]
        if level >= min_level:
            done = error[active] <= atol_f[active] + rtol * np.abs(value[active])
            active = active[~done]
    if not np.all(np.isfinite(value)):
        raise ConvergenceError("quadrature produced a non-finite value: the integrand is not "
                               "integrable on the interval or returned NaN/inf inside it.")
    if active.size and raise_on_failure:
        worst = active[np.argmax(error[active] / np.maximum(np.abs(value[active]), 1e-300))]
        raise ConvergenceError(
            f"quadrature did not reach rtol={rtol:g} on {active.size} of {n} integrals after "
            f"{max_level} levels (worst: value {value[worst]:.6g}, error estimate "
            f"{error[worst]:.3g}). Loosen rtol or split the interval at the singularity.")
    return QuadratureResult(value.reshape(shape), error.reshape(shape), level, evaluations)
