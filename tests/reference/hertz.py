"""Hertz contact of a paraboloid f = r²/(2R) in closed form (double precision).

Source: H. Hertz, Über die Berührung fester elastischer Körper, J. reine angew. Math. 92 (1882)
156-171; K. L. Johnson, Contact Mechanics, Cambridge 1985, §4.2 [J85]:
a² = R d, F = (4/3) E* a³/R, hence a = (3FR/(4E*))^(1/3). Nothing here imports contactlab.
"""
from __future__ import annotations

import numpy as np

__all__ = ["radius_of_force", "radius_of_depth", "force_of_radius", "effective_modulus"]


def effective_modulus(E1: float, nu1: float, E2: float = np.inf, nu2: float = 0.0) -> float:
    """1/E* = (1-ν1²)/E1 + (1-ν2²)/E2 (second body rigid by default) [J85 eq. 4.22]."""
    return 1.0 / ((1 - nu1**2) / E1 + (1 - nu2**2) / E2)


def radius_of_force(F, R, E_star):
    """Contact radius a = (3FR/(4E*))^(1/3), m."""
    return np.cbrt(3.0 * np.asarray(F, float) * R / (4.0 * E_star))


def radius_of_depth(d, R):
    """Contact radius a = sqrt(R d), m."""
    return np.sqrt(R * np.asarray(d, float))


def force_of_radius(a, R, E_star):
    """Normal force F = 4E* a³/(3R), N."""
    return 4.0 * E_star * np.asarray(a, float) ** 3 / (3.0 * R)
