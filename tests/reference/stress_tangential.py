"""Hamilton's closed form of the field under a sliding sphere (an independent reference).

G. M. Hamilton, "Explicit equations for the stresses beneath a sliding spherical contact",
Proc. Instn Mech. Engrs 197C (1983) 53-59: the shear part, a traction
``q0 sqrt(1 - r²/a²)`` along ``+x`` applied to the half-space ``z >= 0`` (so ``σ_xz = -q`` on the
surface). Written in the paper's variables, lengths in units of ``a``, stresses in units of
``q0``: ``A = r² + z² - 1``, ``S = sqrt(A² + 4z²)``, ``M = sqrt((S + A)/2)``,
``N = sqrt((S - A)/2)``, ``φ = atan(1/M)``. Off the axis only (``r > 0``), and the axis limit of
``σ_xz`` separately. Tension positive.
"""
from __future__ import annotations

import numpy as np


def hamilton_shear(x, y, z, nu):
    """``dict`` of ``sxx, syy, szz, sxy, sxz, syz`` at ``(x, y, z)`` (units ``a``, ``q0``)."""
    x, y, z = np.broadcast_arrays(*(np.asarray(v, float) for v in (x, y, z)))
    r2 = x * x + y * y
    A = r2 + z * z - 1.0
    S = np.sqrt(A * A + 4.0 * z * z)
    M = np.sqrt(0.5 * (S + A))
    N = np.sqrt(0.5 * (S - A))
    phi = np.arctan2(1.0, M)
    one = 1.0 - 2.0 * nu
    r4 = r2 * r2
    kx = 1.5 - 2.0 * x * x / r2          # recurring angular factors
    hx = 0.5 - 2.0 * x * x / r2
    hy = 0.5 - 2.0 * y * y / r2
    t_sxx = (-(1.0 + nu / 4.0) * x * phi
             + x * M / r4 * (kx * (nu * (S - 2.0 * A) + z * z) + x * x * z * z / S
                             + 1.75 * nu * r2 - 2.0 * nu * x * x + r2)
             + x * z * N / r4 * (kx * (-one * (S / 6.0 + A / 3.0) - 0.5 * (z * z + 3.0))
                                 + x * x / S - 0.25 * nu * r2 - 1.75 * r2)
             + 4.0 * x * z * one * kx / (3.0 * r4))
    t_syy = (-0.75 * nu * x * phi
             + x * M / r4 * (hy * (nu * (S - 2.0 * A + r2) + z * z) + y * y * z * z / S
                             + 0.75 * nu * r2)
             + x * z * N / r4 * (hy * (-one * (S / 6.0 + A / 3.0) - 0.5 * z * z - 1.5)
                                 + y * y / S - 0.75 * nu * r2 - 0.25 * r2)
             + 4.0 * x * z * one * hy / (3.0 * r4))
    t_szz = 0.5 * x * z * N / r2 * (1.0 - (r2 + z * z + 1.0) / S)
    t_sxy = (0.5 * y * (0.5 * nu - 1.0) * phi
             + y * M / r4 * (x * x * z * z / S
                             + nu * ((S - 2.0 * A) * hx - 2.0 * x * x + 0.25 * r2)
                             + 0.5 * r2 + z * z * hx)
             + y * z * N / r4 * (hx * (-one * (S / 6.0 + A / 3.0) - 0.5 * z * z - 1.5 - 0.5 * r2)
                                 + 0.25 * nu * r2 + x * x / S - 0.5 * y * y - 1.5 * x * x)
             + 4.0 * y * z * one * hx / (3.0 * r4))
    t_syz = 0.5 * x * y * z / r4 * (M * (0.5 + (0.5 * z * z - 1.5 - 0.5 * r2) / S)
                                    + 0.5 * z * N * (-3.0 + (5.0 + z * z + r2) / S))
    t_sxz = (1.5 * z * phi + z * M / r2 * (1.0 + x * x / r2 - x * x / S)
             + N / r2 * (-0.75 * (S + 2.0 * A) + z * z - 0.75 - 0.25 * r2 + 0.5 * z * z * hx))
    return {"sxx": t_sxx, "syy": t_syy, "szz": t_szz, "sxy": t_sxy, "sxz": t_sxz, "syz": t_syz}


def hamilton_shear_axis(z):
    """``σ_xz`` on the axis (the only non-zero component there), units ``q0``."""
    z = np.asarray(z, float)
    return -1.0 + 1.5 * z * np.arctan2(1.0, z) - 0.5 * z * z / (1.0 + z * z)
