"""Masing's rule with turning-point memory, for any history at constant normal load.

One routine serves torsion and tangential shift (and any hysteretic quantity whose virgin curve
is known): after a reversal at ``(x_r, y_r)`` the response is ``y_r ± 2 y_load(|x - x_r|/2)``; a
branch that passes an older turning point closes that loop, which is then forgotten (Iwan
erasure). The bookkeeping is scalar work per step; the loading curve is evaluated, batched, by
the caller at the arguments returned here.
"""
from __future__ import annotations

from collections.abc import Callable

import numpy as np

__all__ = ["masing_program", "masing_response", "masing_dissipation", "merge_close", "merge_step"]


def merge_step(amplitude: float, rtol: float) -> float:
    """Largest gap, in the units of the argument, below which two loading-curve arguments merge.

    ``min(0.1 rtol, 1e-11) amplitude`` (``amplitude = max |argument|``): 1e-11 of the amplitude
    at the default ``rtol = 1e-10``, far below the loading curve's own tolerance and above the
    rounding jitter of amplitudes written as ``A sin(2πk/n)`` (~1e-12 of ``A`` after 10^4 steps),
    which would otherwise make every step a distinct argument and a separate solve. Never
    coarser than 1e-11, so loose tolerances do not merge genuinely different amplitudes.
    """
    x = min(0.1 * rtol, 1e-11) * float(amplitude)
    return x if (x > 0.0 and np.isfinite(x)) else 0.0


def merge_close(x: np.ndarray, step: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Distinct arguments of a history, near-duplicates merged: ``(values, inverse, shift)``.

    Sorted distinct values closer than ``step`` to their neighbour form one group (a chain),
    represented by its middle member, so ``values[inverse]`` equals ``x`` except within such
    groups. ``shift[k]`` is the largest ``|x - values[k]|`` of group ``k`` (0 for a value that
    stands alone), for the caller's error bound. Arguments that are not near-duplicates keep
    their exact value; ``step = 0`` is :func:`numpy.unique`.
    """
    u, inv = np.unique(np.asarray(x, dtype=float), return_inverse=True)
    inv = inv.ravel()
    if step <= 0.0 or u.size < 2:
        return u, inv, np.zeros(u.shape)
    new = np.empty(u.size, dtype=bool)
    new[0] = True
    new[1:] = np.diff(u) >= step
    if new.all():
        return u, inv, np.zeros(u.shape)
    group = np.cumsum(new) - 1
    first = np.flatnonzero(new)
    last = np.append(first[1:], u.size) - 1
    rep = u[(first + last) // 2]
    shift = np.maximum(rep - u[first], u[last] - rep)
    return rep, group[inv], shift


def masing_program(phi: np.ndarray):
    """Turning-point bookkeeping of Masing's rule (O(1) amortised work per step).

    ``phi`` is the prescribed history of the controlling quantity (twist, tangential
    displacement), starting from the virgin state at 0. Returns per step: ``origin`` (step
    index of the branch's turning point, -1 for the virgin curve), ``factor`` (1 virgin, 2
    after a reversal), ``arg`` = ``|φ - φ_o|/factor``, and the list of
    branch segments ``(step, φ_o, factor, φ_from, φ_to)`` traversed between consecutive steps (a
    step may close several loops, each closure switching to an older branch).
    """
    n = phi.size
    origin = np.full(n, -1, dtype=np.int64)
    factor = np.ones(n)
    arg = np.zeros(n)
    segments: list[tuple[int, float, float, float, float]] = []
    stack: list[int] = []          # step indices of the active turning points
    prev = 0.0
    direction = 0.0
    for i in range(n):
        p = float(phi[i])
        delta = p - prev
        if delta != 0.0:
            s = 1.0 if delta > 0 else -1.0
            if direction != 0.0 and s != direction:
                stack.append(i - 1)            # the previous step is a turning point (i >= 1)
            direction = s
        start = prev
        # walk along the active branch, closing loops that the new point passes
        while True:
            if stack:
                o = stack[-1]
                po, fo = float(phi[o]), 2.0
            else:
                po, fo = 0.0, 1.0
            if len(stack) >= 2:
                limit = float(phi[stack[-2]])
            elif len(stack) == 1:
                limit = -po                      # rejoins the virgin curve at the mirror point
            else:
                limit = None
            if limit is not None and direction != 0.0 and (p - limit) * direction > 0:
                segments.append((i, po, fo, start, limit))
                start = limit
                if len(stack) >= 2:
                    del stack[-2:]
                else:
                    stack.pop()
                continue
            segments.append((i, po, fo, start, p))
            origin[i] = stack[-1] if stack else -1
            factor[i] = fo
            arg[i] = abs(p - po) / fo
            break
        prev = p
    arr = np.asarray(segments, float).reshape(-1, 5)
    segs = tuple(arr[:, k].copy() for k in range(5))
    return origin, factor, arg, segs


def masing_response(x: np.ndarray, origin: np.ndarray, factor: np.ndarray,
                    y_load: np.ndarray) -> np.ndarray:
    """Response per step from the loading curve ``y_load`` evaluated at the program's arguments.

    ``y[i] = y[o] + s factor[i] y_load[i]`` with ``o = origin[i]`` (0 on the virgin curve) and
    ``s`` the sign of ``x[i] - x[o]``.
    """
    y = np.empty(x.shape)
    for i in range(x.size):                                 # O(1) per step
        o = origin[i]
        xo = x[o] if o >= 0 else 0.0
        yo = y[o] if o >= 0 else 0.0
        s = 1.0 if x[i] >= xo else -1.0
        y[i] = yo + s * factor[i] * y_load[i]
    return y


def masing_dissipation(segments: tuple, n_steps: int,
                       dissipation_load: Callable[[np.ndarray], np.ndarray],
                       rtol: float = 0.0) -> np.ndarray:
    """Cumulative dissipated energy per step from the monotonic-loading dissipation.

    Along a branch of factor ``f`` from its turning point ``x_o`` the dissipation grows by
    ``f (D(|x_to - x_o|/f) - D(|x_from - x_o|/f))`` (Iwan picture); ``dissipation_load``
    evaluates ``D`` on an array of (unique, sorted) loading-curve arguments; near-duplicates
    (closer than :func:`merge_step` for ``rtol``; 0: none) are merged by :func:`merge_close`.
    """
    step, xo, f, x_from_, x_to_ = segments
    if step.size == 0:
        return np.zeros(n_steps)
    x_from = np.abs(x_from_ - xo) / f
    x_to = np.abs(x_to_ - xo) / f
    both = np.concatenate([x_from, x_to])
    u, inv, _ = merge_close(both, merge_step(np.max(both), rtol) if rtol > 0 else 0.0)
    D = dissipation_load(u)[inv.ravel()]
    incr = f * (D[step.size:] - D[:step.size])
    per_step = np.bincount(step.astype(np.int64), weights=incr, minlength=n_steps)
    return np.cumsum(per_step)
