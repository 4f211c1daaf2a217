"""The power-law transform factor κ_n, written once for every reference module.

κ_n = √π Γ(n/2 + 1) / Γ(n/2 + 1/2): the MDR transform of f = c rⁿ is g = κ_n c |x|ⁿ.
Source: V. L. Popov, M. Heß, Method of Dimensionality Reduction in Contact Mechanics and
Friction, Springer 2015, eq. (3.14) [PH]; M. Heß, Über die exakte Abbildung ausgewählter
dreidimensionaler Kontakte auf Systeme mit niedrigerer räumlicher Dimension, Cuvillier 2011 [H1].
Nothing here imports contactlab.
"""
from __future__ import annotations

import mpmath as mp

mp.mp.dps = 30

__all__ = ["kappa", "kappa_float"]


def kappa(n) -> mp.mpf:
    """κ_n at 30 digits (mpmath)."""
    n = mp.mpf(n)
    return mp.sqrt(mp.pi) * mp.gamma(n / 2 + 1) / mp.gamma(n / 2 + mp.mpf(1) / 2)


def kappa_float(n) -> float:
    """κ_n rounded to double precision (for numpy-vectorised references)."""
    return float(kappa(n))
