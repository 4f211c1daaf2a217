"""Compiled (numba, extra ``fast``) version of one Masing step of the contact law.

The same arithmetic as :func:`contactlab.physics.masing_stack.masing_step` with the loading
curves of :mod:`contactlab.physics.master` (torsion master curve or Cattaneo–Mindlin closed
form), one loop over contacts instead of array passes; the numpy path stays the reference and
the tests compare the two. :data:`AVAILABLE` is False when numba is not installed.
"""
from __future__ import annotations

import math

import numpy as np

__all__ = ["AVAILABLE", "channel_step", "scales", "TORSION", "TANGENTIAL"]

TORSION = 0
TANGENTIAL = 1

try:                                    # optional dependency (extra "fast")
    import numba
    AVAILABLE = True
    _prange = numba.prange
except ImportError:                     # pragma: no cover - exercised without numba only
    numba = None
    AVAILABLE = False
    _prange = range


def _load(kind, arg, i, xs, ys, auxs, Ds, coef, y_scale, n):
    """(y_load, aux, D_load) of contact i at argument arg >= 0."""
    if kind == TORSION:
        y = arg / xs[i]
        N = coef.shape[1]
        s = y / (y + y_scale)
        z = s * N
        j = min(int(z), N - 1)
        u = 2.0 * (z - j) - 1.0
        P = coef.shape[2]
        t = coef[0, j, P - 1]
        m = coef[1, j, P - 1]
        q = coef[2, j, P - 1]
        for p in range(P - 2, -1, -1):
            t = t * u + coef[0, j, p]
            m = m * u + coef[1, j, p]
            q = q * u + coef[2, j, p]
        t = min(max(t, 0.0), 1.0)
        m = m * s
        q = q * (s * s)
        return ys[i] * m, auxs[i] * t, ys[i] * arg * q
    x = arg / xs[i]
    xc = min(x, 1.0)
    r = 1.0 - xc
    if n == 2.0:
        t = math.sqrt(r)
        one_t = xc / (1.0 + t)
    elif n == 1.0:
        t = r
        one_t = xc
    else:
        one_t = -math.expm1(math.log1p(-xc) / n) if xc < 1.0 else 1.0
        t = 1.0 - one_t
    f = xc + r * one_t
    f2 = xc + r * f
    a1 = 1.0 / (n + 1.0)
    a2 = 1.0 / (2.0 * n + 1.0)
    J1 = one_t - f * a1
    J2 = one_t - 2.0 * f * a1 + f2 * a2
    w = max(x * J1 - J2, 0.0)
    return ys[i] * f, auxs[i] * t, Ds[i] * w


def _channel_step(kind, x, sx, sy, sw, last, depth, X, Y, overflow, xs, ys, auxs, Ds, coef,
                  y_scale, n, out_y, out_aux, out_dW):
    K = X.shape[1]
    for i in _prange(x.size):
        xi = x[i]
        xp = sx[i]
        dW = 0.0
        if xi != xp:
            s = 1 if xi > xp else -1
            if last[i] != 0 and s != last[i]:
                if depth[i] >= K:
                    overflow[i] = True
                    depth[i] -= 2
                d = depth[i]
                X[i, d] = xp
                Y[i, d] = sy[i]
                depth[i] = d + 1
                sw[i] = 0.0
            last[i] = s
            while depth[i] > 0:
                d = depth[i]
                lim = X[i, d - 2] if d >= 2 else -X[i, 0]
                if (xi - lim) * last[i] <= 0:
                    break
                xo = X[i, d - 1]
                D = _load(kind, abs(lim - xo) / 2.0, i, xs, ys, auxs, Ds, coef, y_scale, n)[2]
                dW += max(2.0 * D - sw[i], 0.0)
                d = d - 2 if d >= 2 else 0
                depth[i] = d
                if d > 0:
                    xo2, f2 = X[i, d - 1], 2.0
                else:
                    xo2, f2 = 0.0, 1.0
                D = _load(kind, abs(lim - xo2) / f2, i, xs, ys, auxs, Ds, coef, y_scale, n)[2]
                sw[i] = f2 * D
        d = depth[i]
        if d > 0:
            xo, yo, f = X[i, d - 1], Y[i, d - 1], 2.0
        else:
            xo, yo, f = 0.0, 0.0, 1.0
        yl, aux, D = _load(kind, abs(xi - xo) / f, i, xs, ys, auxs, Ds, coef, y_scale, n)
        sg = 1.0 if xi > xo else (-1.0 if xi < xo else 0.0)
        yv = yo + sg * f * yl
        wn = f * D
        dW += max(wn - sw[i], 0.0)
        sw[i] = max(sw[i], wn)
        sx[i] = xi
        sy[i] = yv
        out_y[i] = yv
        out_aux[i] = aux
        out_dW[i] = dW


def _scales(mu, E, G, Gt, a, d, FN, n, u_star, muF, Dscale, phi_s, M_full):
    c = math.pi * n / (2.0 * (n + 2.0))
    for i in _prange(a.size):
        mEd = mu[i] * E[i] * d[i]
        u_star[i] = mEd / G[i]
        muF[i] = mu[i] * FN[i]
        Dscale[i] = 2.0 * a[i] * (mEd * mEd) / G[i]
        phi_s[i] = mEd / (2.0 * Gt[i] * a[i])
        M_full[i] = c * mu[i] * E[i] * d[i] * a[i] * a[i]


if AVAILABLE:
    _load = numba.njit(cache=False, nogil=True)(_load)
    # serial (default) and threaded builds of the same loops; contacts are independent, so the
    # threaded build gives bit-identical results (prange is range in the serial build)
    _KERNELS = {par: (numba.njit(cache=False, nogil=True, parallel=par)(_scales),
                      numba.njit(cache=False, nogil=True, parallel=par)(_channel_step))
                for par in (False, True)}
else:                                   # pragma: no cover - without numba
    _KERNELS = {False: (_scales, _channel_step), True: (_scales, _channel_step)}


def channel_step(kind: int, st: dict, x: np.ndarray, xs, ys, auxs, Ds, coef, y_scale: float,
                 n: float, parallel: bool = False):
    """One compiled Masing step of a channel (state ``st`` of
    :func:`~contactlab.physics.masing_stack.new_stack`, updated in place).

    ``xs`` scales the argument (twist scale or full-slip displacement), ``ys`` the response
    (full-sliding torque, μF_N), ``auxs`` the stick ratio (contact radius), ``Ds`` the
    tangential dissipation (unused for torsion). ``parallel``: the threaded build (numba
    threads over contacts, same results). Returns ``(y, aux, dW)``.
    """
    m = x.size
    out = (np.empty(m), np.empty(m), np.empty(m))
    _KERNELS[parallel][1](kind, x, st["x"], st["y"], st["w"], st["last"], st["depth"], st["X"],
                          st["Y"], st["overflow"], xs, ys, auxs, Ds, coef, float(y_scale),
                          float(n), *out)
    return out


def scales(mu, E, G, Gt, a, d, FN, n: float, parallel: bool = False):
    """One compiled pass for the scales of both channels (the same arithmetic as the numpy
    path): ``(u_star, muF, Dscale, phi_s, M_full)``."""
    m = a.size
    out = tuple(np.empty(m) for _ in range(5))
    _KERNELS[parallel][0](mu, E, G, Gt, a, d, FN, float(n), *out)
    return out
