"""The contact law's constant-load step written once for any array module ``xp`` (numpy on the
CPU, CuPy on a GPU): normal contact, the Cattaneo–Mindlin and exact-torsion loading curves and
Masing's rule with a bounded turning-point stack.

Every function takes the array namespace ``xp`` as its first argument and uses only
operations that numpy and CuPy both provide (ufuncs, ``where``, ``take_along_axis``,
``flatnonzero``, integer-array gathers and scatters): no Python loop runs over contacts. The only Python loop
is the loop closure of Masing's rule, in rounds (at most ``K // 2 + 1`` for ``K`` turning
points, ended as soon as no contact passes a closing point), each over the contacts that close
a loop in it, gathered by index.

With ``xp = numpy`` every function performs, element by element, the floating-point operations
of the numpy reference (:meth:`contactlab.effects.law.ContactLaw.normal`,
:func:`~contactlab.physics.master.tangential_master`,
:func:`~contactlab.physics.masing_stack.masing_step`) in the same order, so its results are the
reference's to the bit; the torsion curves are :func:`~contactlab.physics.master.evaluate`
itself, called with ``xp``, and the paraboloid's cube root with numpy is the reference's
:func:`contactlab.numeric.cube_root.cbrt`. On a GPU the elementwise transcendental functions
(``power``, ``sqrt``, ``cbrt``, ``expm1``, ``log1p``) come from the device's math library and
may differ from numpy's in the last bits.

Pure kernels: arrays in, arrays out; the stack state (``st``) is updated in place.
"""
from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np

from ..numeric import cube_root as _cube_root
from . import master as _master

__all__ = ["normal", "tangential_curve", "torsion_curves", "masing_step"]


def normal(xp: Any, by_force: bool, val: Any, kc: Any, E: Any, n: float, flat: Any
           ) -> tuple[Any, Any, Any]:
    """``(depth, radius, force)`` of every contact from a depth (m) or a force (N >= 0)
    ``val`` (checked by the caller); ``g = kc x^n``, ``flat``: punch radii (``n = inf``)."""
    if n == np.inf:                                 # flat punch: a = punch radius
        if not by_force:
            dp = xp.maximum(val, 0.0)
            return val.copy(), xp.where(dp > 0, flat, 0.0), 2.0 * E * dp * flat
        F = val
        return F / (2.0 * E * flat), xp.where(F > 0, flat, 0.0), F.copy()
    if not by_force:
        dp = xp.maximum(val, 0.0)
        a = (dp / kc) ** (1.0 / n) if n != 2.0 else xp.sqrt(dp / kc)
        F = 2.0 * n / (n + 1.0) * E * dp * a
        return val.copy(), a, F
    F = val
    c = (n + 1.0) / (2.0 * n * E * kc)
    cbrt = _cube_root.cbrt if xp is np else xp.cbrt     # numpy: the law's own cube root
    a = cbrt(F) * cbrt(c) if n == 2.0 else (F * c) ** (1.0 / (n + 1.0))
    d = kc * a**n if n != 2.0 else kc * a * a
    return d, a, F.copy()


def tangential_curve(xp: Any, n: float, x: Any) -> tuple[Any, Any, Any]:
    """``(t, f, w)`` of the Cattaneo–Mindlin virgin curve at ``x = G*|u|/(μE*d) >= 0``
    (:func:`contactlab.physics.master.tangential_master`, the same operations)."""
    xc = xp.minimum(x, 1.0)
    r = 1.0 - xc
    if n == 2.0:
        t = xp.sqrt(r)
        one_t = xc / (1.0 + t)
    elif n == 1.0:
        t = r
        one_t = xc
    elif n == np.inf:
        one_t = xp.where(xc >= 1.0, 1.0, 0.0)
        t = 1.0 - one_t
    else:
        one_t = -xp.expm1(xp.log1p(-xc) / n)
        t = 1.0 - one_t
    f = xc + r * one_t
    f2 = xc + r * f
    a1 = 1.0 / (n + 1.0)
    a2 = 1.0 / (2.0 * n + 1.0)
    J1 = one_t - f * a1
    J2 = one_t - 2.0 * f * a1 + f2 * a2
    return t, f, xp.maximum(x * J1 - J2, 0.0)


def torsion_curves(xp: Any, coef: Any, y_scale: float, y: Any, y0: float = 0.0,
                   m0: float = 0.0, scaled: bool = True, power: int = 1
                   ) -> tuple[Any, Any, Any]:
    """``(t, m, q)`` of a torsion master curve at dimensionless twists ``y >= 0``, ``coef``
    on the device: :func:`contactlab.physics.master.evaluate` with the array module ``xp``
    (one text for numpy and CuPy). A non-finite ``y`` gives non-finite curves (the panel
    index is clipped, never read outside the table)."""
    return _master.evaluate(coef, y_scale, y, y0, m0, scaled, power, xp=xp)


def _origin(xp: Any, st: dict, idx: Any) -> tuple[Any, Any, Any]:
    """Origin ``(x_o, y_o)`` and factor ``f`` of the active branch of the contacts ``idx``
    (an index array of ``xp``; None: every contact)."""
    X, Y = st["X"], st["Y"]
    if idx is None:
        dep = st["depth"]
        top = xp.maximum(dep - 1, 0)[:, None]
        Xo = xp.take_along_axis(X, top, 1)[:, 0]
        Yo = xp.take_along_axis(Y, top, 1)[:, 0]
    else:
        dep = st["depth"][idx]
        top = xp.maximum(dep - 1, 0)
        Xo, Yo = X[idx, top], Y[idx, top]
    has = dep > 0
    return xp.where(has, Xo, 0.0), xp.where(has, Yo, 0.0), xp.where(has, 2.0, 1.0)


def masing_step(xp: Any, st: dict, x: Any,
                load: Callable[[Any, Any], tuple[Any, Any, Any]]) -> tuple[Any, Any, Any]:
    """Advance every contact to the control ``x``; ``st`` (the fields of
    :func:`~contactlab.physics.masing_stack.new_stack`, arrays of ``xp``) is updated in place.

    ``load(arg, idx) -> (y_load, aux, D_load)``: the loading curve of the contacts ``idx`` (an
    index array of ``xp``; None: every contact) at arguments ``arg >= 0``. Returns
    ``(y, aux, dW)``: response, auxiliary quantity of the active branch and energy dissipated in
    this step (the bookkeeping of :func:`contactlab.physics.masing_stack.masing_step`). The
    contacts that reverse or close a loop are gathered by index (``flatnonzero``), so a step
    costs the full arrays once plus the contacts that reverse or close loops; a round of loop
    closures closes one loop per contact (its depth falls by 2 or to 0), so there are at most
    ``K // 2 + 1`` rounds.
    """
    n = x.size
    X, Y, depth, w, last = st["X"], st["Y"], st["depth"], st["w"], st["last"]
    K = X.shape[1]
    x_prev = st["x"]
    delta = x - x_prev
    moved = delta != 0.0
    s = xp.sign(delta).astype(np.int8)
    rev = moved & (last != 0) & (s != last)
    dW = xp.zeros(n)
    push = xp.flatnonzero(rev)
    if push.size:
        full = rev & (depth >= K)
        if bool(xp.any(full)):
            # no room: forget the innermost pending loop (the two newest turning points),
            # then record the reversal as usual
            st["overflow"][...] = st["overflow"] | full
            depth[...] = xp.where(full, depth - (2 if K >= 2 else 1), depth)
        dep = depth[push]
        X[push, dep] = x_prev[push]
        Y[push, dep] = st["y"][push]
        depth[push] = dep + 1
        w[push] = 0.0
    last[...] = xp.where(moved, s, last)
    # loop closure: only contacts moving in their branch direction can pass a closing point
    cand = xp.flatnonzero(moved & (s == last) & (depth > 0))
    while cand.size:
        dep = depth[cand]
        keep = dep > 0
        cand, dep = cand[keep], dep[keep]
        lim = xp.where(dep >= 2, X[cand, xp.maximum(dep - 2, 0)], -X[cand, 0])
        passing = (x[cand] - lim) * last[cand] > 0
        cand, lim, dep = cand[passing], lim[passing], dep[passing]
        if cand.size == 0:
            break
        xo, _, f = _origin(xp, st, cand)
        _, _, D = load(xp.abs(lim - xo) / f, cand)
        dW[cand] += xp.maximum(f * D - w[cand], 0.0)
        depth[cand] = xp.where(dep >= 2, dep - 2, 0)
        xo, _, f = _origin(xp, st, cand)
        _, _, D = load(xp.abs(lim - xo) / f, cand)
        w[cand] = f * D
    xo, yo, f = _origin(xp, st, None)
    y_l, aux, D = load(xp.abs(x - xo) / f, None)
    y = yo + xp.sign(x - xo) * f * y_l
    wn = f * D
    dW += xp.maximum(wn - w, 0.0)
    w[...] = xp.maximum(w, wn)
    x_prev[...] = x
    st["y"][...] = y
    return y, aux, dW
