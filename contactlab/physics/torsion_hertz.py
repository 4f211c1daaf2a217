"""Exact partial-slip torsion of a Hertz contact in closed form, parametric in the stick radius.

For the paraboloid ``f = r²/(2R)`` under its non-adhesive pressure ``p = p0 sqrt(1 − r²/a²)``,
``p0 = 2E* a/(πR)``, Jäger's slip function is ``P(x) = p0 [K(m) − E(m)]``, ``m = 1 − x²/a²``
(complete elliptic integrals of parameter ``m``), so with ``t = c/a``

* twist ``φ(c) = μ p0 [K − E](1 − t²) / (2 G_t)`` (Lubkin's problem),
* torque ``M(c) = (16/3) G_t φ c³ + 8 μ ∫_c^a x² P(x) dx = (16/3) G_t φ c³ + 8 μ p0 a³ J(t)``,
  ``J(t) = ∫_t^1 s² [K − E](1 − s²) ds``, ``J(0) = π²/64`` (the sliding torque
  ``(3π/16) μ F a``).

The stick radius of a twist solves ``[K − E](1 − t²) = y``, ``y = 2 G_t φ/(μ p0)``: in ``u = ln t``
the left side decreases with slope ``−E`` and is concave (``d²/du² = −t² (K − E)/m``), so Newton's
method started right of the root (at ``u = 0``, or at the large-slip asymptote
``u = ln 4 − 1 − y``, which lies right of it) moves monotonically onto the root, quadratically
near it; all twists of a curve are iterated together (no per-point root solve). ``m = −expm1(2u)``
keeps the small slip annuli (``t → 1``) exact to rounding.

``J`` is a Gauss–Legendre sum: on ``[t, 1]`` for ``t >= 1/2`` (the integrand is analytic there),
else ``J(0)`` minus the integral over ``[0, t]`` in ``s = t v³`` (which turns the logarithm of
``K`` at ``s → 0`` into ``v⁸ ln v``, integrated to rounding by the same rule).

All functions are pure: arrays in, arrays out.
"""
from __future__ import annotations

import numpy as np
from scipy import special as _sp

__all__ = ["stick_ratio", "slip_hat", "j_integral", "torque_hat", "NEWTON_MAX"]

#: Newton iterations at most (quadratic convergence: ~6 from the asymptote, ~12 from u = 0)
NEWTON_MAX = 100
#: Gauss-Legendre nodes of the J quadrature (measured: J to 3e-16 of J(0) against mpmath)
_NODES = 32
_X, _W = np.polynomial.legendre.leggauss(_NODES)
_X01, _W01 = 0.5 * (_X + 1.0), 0.5 * _W
_J0 = np.pi ** 2 / 64.0
#: twists (per μ p0 / (2 G_t)) from which the large-slip asymptote is exact to rounding
_FAR = 25.0


def _slip(p: np.ndarray, m: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``K − E`` and ``E`` at ``m = 1 − t²`` given both ``p = t²`` and ``m`` (each exact where it
    is small: ``K`` from ``p`` near the logarithm at ``m → 1``, both from ``m`` near 0)."""
    # each point's K by the one branch it takes (elementwise: the bits of evaluating both and
    # choosing, at half the elliptic integrals)
    p, m = np.asarray(p, float), np.asarray(m, float)
    near = p < 0.5
    if near.all():
        K = _sp.ellipkm1(p)
    elif not near.any():
        K = _sp.ellipk(np.minimum(m, 0.5))
    else:
        K = np.empty(p.shape)     # (p and m come with one shape)
        K[near] = _sp.ellipkm1(p[near])
        far = ~near
        K[far] = _sp.ellipk(np.minimum(m[far], 0.5))
    E = _sp.ellipe(m)
    return K - E, E


def slip_hat(t: np.ndarray) -> np.ndarray:
    """``K(m) − E(m)``, ``m = 1 − t²``: Jäger's slip function of Hertz per ``p0`` at ``x = t a``."""
    t = np.asarray(t, float)
    return _slip(t * t, (1.0 - t) * (1.0 + t))[0]


def stick_ratio(y: np.ndarray) -> np.ndarray:
    """``t = c/a`` with ``K(1 − t²) − E(1 − t²) = y`` (``y >= 0``), vectorised Newton in ``ln t``;
    ``t`` underflows to 0 beyond ``y ≈ 745`` (full sliding)."""
    y_in = np.asarray(y, float)
    # beyond y = 25 (t < 1e-11) K − E = ln(4/t) − 1 to rounding (the next term is ~t² ln t):
    # t = 4 exp(−1 − y) directly (it underflows to 0, full sliding, beyond y ≈ 745)
    far = y_in >= _FAR
    y = np.where(np.isfinite(y_in) & ~far, y_in, 0.0)
    # two starts right of the root (f(u) <= y): the large-slip asymptote ln(4/t) − 1 = y (below
    # the curve's f by ~t² ln t / 4) and the small-slip m = 4y/π / (1 + 3y/π + 3y²/π²)^... the
    # one nearer the root (larger f) is kept; u = 0 (f = 0) where neither is right of it
    uL = np.minimum(0.0, np.log(4.0) - 1.0 - y)
    mS = np.minimum(4.0 / np.pi * y / (1.0 + 0.5 * y + 0.5 * y * y), 1.0)
    uS = 0.5 * np.log1p(-mS)
    fL = _slip(np.exp(2.0 * uL), -np.expm1(2.0 * uL))[0]
    fS = _slip(np.exp(2.0 * uS), -np.expm1(2.0 * uS))[0]
    okL, okS = fL <= y, fS <= y
    u = np.where(okS & (~okL | (fS > fL)), uS, np.where(okL, uL, 0.0))
    live = y > 0
    for _ in range(NEWTON_MAX):
        if not live.any():
            break
        ul = u[live]
        f, E = _slip(np.exp(2.0 * ul), -np.expm1(2.0 * ul))
        # concave and decreasing: each step moves left and stays right of the root; a step
        # that comes out positive is rounding at the root
        step = np.minimum((f - y[live]) / E, 0.0)
        un = ul + step
        u[live] = un
        done = np.abs(step) <= 4.0 * np.finfo(float).eps * np.maximum(1.0, np.abs(un))
        idx = np.flatnonzero(live)
        live[idx[done]] = False
    with np.errstate(under="ignore"):
        t_far = 4.0 * np.exp(-1.0 - np.where(far, y_in, _FAR))
    return np.where(far, t_far, np.where(y > 0, np.exp(u), 1.0))


def j_integral(t: np.ndarray) -> np.ndarray:
    """``J(t) = ∫_t^1 s² [K − E](1 − s²) ds`` (see the module docstring)."""
    t = np.asarray(t, float)
    out = np.empty(t.shape)
    hi = t >= 0.5
    if hi.any():
        th = t[hi][:, None]
        h = 1.0 - th
        s = th + h * _X01[None, :]
        f = s * s * slip_hat(s)
        out[hi] = (h[:, 0]) * (f @ _W01)
    # below t = 1e-100 the part over [0, t] (~t³ ln t) is far below J(0)'s rounding
    out[t < 1e-100] = _J0
    lo = ~hi & (t >= 1e-100)
    if lo.any():
        tl = t[lo][:, None]
        v = _X01[None, :]
        s = tl * v ** 3
        f = 3.0 * tl ** 3 * v ** 8 * slip_hat(s)
        out[lo] = _J0 - f @ _W01
    return out


def torque_hat(t: np.ndarray, y: np.ndarray) -> np.ndarray:
    """``M / (μ p0 a³)`` at stick ratio ``t`` and twist ``y = [K − E](1 − t²)``:
    ``(8/3) y t³ + 8 J(t)``."""
    t = np.asarray(t, float)
    return 8.0 / 3.0 * y * t ** 3 + 8.0 * j_integral(t)
