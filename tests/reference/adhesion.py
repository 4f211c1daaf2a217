"""JKR adhesion of a paraboloid f = r²/(2R) in closed form (double precision).

Source: K. L. Johnson, K. Kendall, A. D. Roberts, Proc. R. Soc. Lond. A 324 (1971) 301-313
[JKR71]; MDR form: V. L. Popov, M. Heß, MDR, Springer 2015, §6.2 [PH]:
F(a) = 4E*a³/(3R) - sqrt(8π a³ E* Δγ), d(a) = a²/R - sqrt(2π a Δγ/E*).
Nothing here imports contactlab.
"""
from __future__ import annotations

import numpy as np

__all__ = ["jkr_force", "jkr_depth"]


def jkr_force(a, R, E_star, work_of_adhesion):
    """Normal force at contact radius ``a``, N."""
    a = np.asarray(a, float)
    return 4 * E_star * a**3 / (3 * R) - np.sqrt(8 * np.pi * a**3 * E_star * work_of_adhesion)


def jkr_depth(a, R, E_star, work_of_adhesion):
    """Indentation depth at contact radius ``a``, m."""
    a = np.asarray(a, float)
    return a**2 / R - np.sqrt(2 * np.pi * a * work_of_adhesion / E_star)
