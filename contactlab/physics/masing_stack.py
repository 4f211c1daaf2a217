"""Masing's rule for many contacts at once: one step, a turning-point stack of bounded depth per
contact.

The scalar bookkeeping of :mod:`contactlab.physics.masing` (turning points, loop closure and
Iwan erasure) is carried here as arrays over contacts, one step at a time, so that a time loop
outside contactlab (a DEM or multibody code) can advance every contact by O(1) work per step.

State of one channel (twist/torque or displacement/force) over ``n`` contacts, all plain arrays:

``x``, ``y`` (n)
    Control and response at the previous step.
``w`` (n)
    Dissipation of the active branch at its furthest point, ``f D(|x - x_o|/f)``.
``last`` (n, int8)
    Sign of the last non-zero increment (0: virgin, never moved).
``depth`` (n, int64)
    Number of turning points on the stack.
``X``, ``Y`` (n, K)
    Turning points (control, response); ``X[:, :depth]`` are active.
``overflow`` (n, bool)
    A reversal found the stack full (see below).

A branch starting at the turning point ``(x_o, y_o)`` follows ``y = y_o ± f y_load(|x-x_o|/f)``
(``f = 2``; ``f = 1`` and origin 0 on the virgin curve). It closes when it passes the previous
turning point (depth >= 2) or the mirror point ``-x_o`` (depth 1); both points are then
forgotten and the older branch continues (Iwan erasure), which may repeat within one step.

**Overflow.** With room for ``K`` turning points, a reversal that finds the stack full first
forgets the two newest turning points (the innermost loop still open) and then records the
reversal; the contact's ``overflow`` flag is set. The response stays continuous at the reversal
and keeps its hysteresis, but when the history later passes the forgotten loop's closing point
it follows the branch of the new turning point instead of the forgotten one, and at the next
closure the response may jump by the difference (of the order of the forgotten loop). Results of
a flagged contact are approximate from the overflow on; ``K = 8`` holds eight nested reversals
(a ring-down of four full cycles without any loop closing). Callers report it: the contact law
sets ``exact`` False for flagged contacts and warns in the step of the overflow.
"""
from __future__ import annotations

from collections.abc import Callable

import numpy as np

__all__ = ["new_stack", "masing_step", "STACK_FIELDS"]

#: state arrays of one channel, in the order of :func:`new_stack`
STACK_FIELDS = ("x", "y", "w", "last", "depth", "X", "Y", "overflow")


def new_stack(n: int, K: int) -> dict[str, np.ndarray]:
    """Virgin state of ``n`` contacts with room for ``K`` turning points each."""
    return {"x": np.zeros(n), "y": np.zeros(n), "w": np.zeros(n),
            "last": np.zeros(n, np.int8), "depth": np.zeros(n, np.int64),
            "X": np.zeros((n, K)), "Y": np.zeros((n, K)), "overflow": np.zeros(n, bool)}


def _origin(st, idx):
    """Origin (x_o, y_o) and factor f of the active branch of contacts ``idx`` (None: all)."""
    if idx is None:
        dep = st["depth"]
        top = np.maximum(dep - 1, 0)[:, None]
        X = np.take_along_axis(st["X"], top, 1)[:, 0]
        Y = np.take_along_axis(st["Y"], top, 1)[:, 0]
    else:
        dep = st["depth"][idx]
        top = np.maximum(dep - 1, 0)
        X, Y = st["X"][idx, top], st["Y"][idx, top]
    has = dep > 0
    return np.where(has, X, 0.0), np.where(has, Y, 0.0), np.where(has, 2.0, 1.0)


def masing_step(st: dict, x: np.ndarray,
                load: Callable[[np.ndarray, np.ndarray | None],
                               tuple[np.ndarray, np.ndarray, np.ndarray]]
                ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Advance every contact to the control ``x``; update ``st`` in place.

    Parameters
    ----------
    st : dict
        Channel state (:func:`new_stack`).
    x : ndarray (n)
        New control values.
    load : callable
        ``load(arg, idx) -> (y_load, aux, D_load)``: the virgin (loading) curve of contacts
        ``idx`` (``None``: all contacts) at arguments ``arg >= 0``: response, an auxiliary
        quantity of the branch (the stick radius) and the energy dissipated by monotonic loading to ``arg``.

    Returns
    -------
    y, aux, dW : ndarray (n)
        Response, auxiliary quantity of the active branch and energy dissipated in this step.
    """
    n = x.size
    K = st["X"].shape[1]
    xp = st["x"]
    delta = x - xp
    moved = delta != 0.0
    s = np.sign(delta).astype(np.int8)
    last = st["last"]
    rev = moved & (last != 0) & (s != last)
    dW = np.zeros(n)
    if np.any(rev):
        full = rev & (st["depth"] >= K)
        if np.any(full):
            # no room: forget the innermost pending loop (the two newest turning points), then
            # record the reversal as usual
            st["overflow"] |= full
            st["depth"][full] -= 2 if K >= 2 else 1
        push = np.flatnonzero(rev)
        dep = st["depth"][push]
        st["X"][push, dep] = xp[push]
        st["Y"][push, dep] = st["y"][push]
        st["depth"][push] = dep + 1
        st["w"][push] = 0.0
    last[moved] = s[moved]
    # loop closure: only contacts moving in their branch direction can pass a closing point
    cand = np.flatnonzero(moved & (s == last) & (st["depth"] > 0))
    while cand.size:
        dep = st["depth"][cand]
        keep = dep > 0
        cand, dep = cand[keep], dep[keep]
        lim = np.where(dep >= 2, st["X"][cand, np.maximum(dep - 2, 0)], -st["X"][cand, 0])
        passing = (x[cand] - lim) * last[cand] > 0
        cand, lim, dep = cand[passing], lim[passing], dep[passing]
        if cand.size == 0:
            break
        xo, _, f = _origin(st, cand)
        _, _, D = load(np.abs(lim - xo) / f, cand)
        dW[cand] += np.maximum(f * D - st["w"][cand], 0.0)
        st["depth"][cand] = np.where(dep >= 2, dep - 2, 0)
        xo, _, f = _origin(st, cand)
        _, _, D = load(np.abs(lim - xo) / f, cand)
        st["w"][cand] = f * D
    xo, yo, f = _origin(st, None)
    y_l, aux, D = load(np.abs(x - xo) / f, None)
    y = yo + np.sign(x - xo) * f * y_l
    wn = f * D
    dW += np.maximum(wn - st["w"], 0.0)
    np.maximum(st["w"], wn, out=st["w"])
    st["x"][:] = x
    st["y"][:] = y
    return y, aux, dW
