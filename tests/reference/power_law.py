"""Power-law (and cone) contact in closed form at 30 digits: force, depth, pressure, outside
displacement of f = c rⁿ.

Sources: M. Heß, Cuvillier 2011 [H1]; V. L. Popov, M. Heß, MDR, Springer 2015, §3.3 (power-law
indenters, pressure via ₂F₁) [PH]; I. N. Sneddon, Int. J. Eng. Sci. 3 (1965) 47-57 (cone) [Sn65].
Nothing here imports contactlab.
"""
from __future__ import annotations

import mpmath as mp

from .kappa import kappa

mp.mp.dps = 30


def power_force(E_star: float, c: float, n: float, a: float) -> float:
    """F = 2E* κ_n c a^{n+1} n/(n+1)."""
    n_ = mp.mpf(n)
    return float(2 * mp.mpf(E_star) * kappa(n) * c * mp.mpf(a) ** (n_ + 1) * n_ / (n_ + 1))


def power_depth(c: float, n: float, a: float) -> float:
    """d = κ_n c a^n."""
    return float(kappa(n) * c * mp.mpf(a) ** n)


def power_pressure(E_star: float, c: float, n: float, a: float, r: float) -> float:
    """p(r) = (E*/π) ∫_0^{arccosh(a/r)} g'(r cosh u) du with g' = n κ_n c x^{n-1} (mpmath quad)."""
    r_, a_ = mp.mpf(r), mp.mpf(a)
    U = mp.acosh(a_ / r_)
    k = kappa(n)
    val = mp.quad(lambda u: n * k * c * (r_ * mp.cosh(u)) ** (n - 1), [0, U])
    return float(mp.mpf(E_star) / mp.pi * val)


def power_displacement_outside(c: float, n: float, a: float, d: float, r: float) -> float:
    """u_z(r > a) = (2/π)[d asin(a/r) - (κ_n c a^{n+1}/(r(n+1))) ₂F₁(1/2,(n+1)/2;(n+3)/2;a²/r²)]."""
    r_, a_, n_ = mp.mpf(r), mp.mpf(a), mp.mpf(n)
    hyp = mp.hyp2f1(mp.mpf(1) / 2, (n_ + 1) / 2, (n_ + 3) / 2, (a_ / r_) ** 2)
    return float(2 / mp.pi * (d * mp.asin(a_ / r_) - kappa(n) * c * a_ ** (n_ + 1) / (r_ * (n_ + 1)) * hyp))


def cone_displacement_outside(slope: float, a: float, r: float) -> float:
    """u_z(r > a) = tanβ [a asin(a/r) - r + sqrt(r²-a²)] (mpmath: no cancellation at r ≫ a)."""
    r_, a_ = mp.mpf(r), mp.mpf(a)
    return float(slope * (a_ * mp.asin(a_ / r_) - r_ + mp.sqrt(r_**2 - a_**2)))
