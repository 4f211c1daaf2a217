"""Subsurface stresses under a tangential (shear) traction along ``+x`` whose magnitude is
axisymmetric: the elementary field of the Cattaneo–Mindlin superposition.

A traction ``q(r)`` in ``+x`` on the half-space ``z >= 0`` has, with Love's potentials (Johnson
1985 §3.2) reduced to one axisymmetric harmonic family ``v, f, f1`` (``v`` the Newtonian
potential of ``q`` divided by ``2π``, ``∂f/∂z = v``, ``∂f1/∂z = f``), the displacement
``2G u = (2 f_z + 2ν f1_xx - z f_xx, 2ν f1_xy - z f_xy, (1 - 2ν) f_x - z f_xz)`` and the stresses
(derived for this module; they satisfy equilibrium, the traction-free surface outside the load
and ``σ_xz = -q`` on the surface)::

    σ_zz = -z v_xz                 σ_xz = v_z - z v_xx           σ_yz = -z v_xy
    σ_xx = 2(1+ν) v_x + 2ν f1_xxx - z f_xxx
    σ_yy = 2ν v_x + 2ν f1_xyy - z f_xyy
    σ_xy = v_y + 2ν f1_xxy - z f_xxy

For the punch-type traction ``q = 1/sqrt(x² - r²)`` on ``r < x`` (``x`` the punch radius) all
derivatives are rational in ``m, n`` (notation of :mod:`contactlab.physics.stress`:
``m² = x² - l1²``, ``n² = l2² - x²``, ``Q = m² + n²``, ``l2² = x² + n²``), with ``D = (1/r)∂/∂r``
(``Dm = -m/Q``, ``Dn = n/Q``)::

    D v   = -x n/(l2² Q)                       v_z = -m/Q
    D v_z = -m (m² - 3n²)/Q³                   D² v = -n x (m²n² + 3m²x² - 3n⁴ - n²x²)/(Q³ l2⁴)
    D f   = x²/(l2² (x + m))                   D² f = x² (m x² - m n² - 2n² x)/((x+m)² Q l2⁴)
    D f1  = -x n (x - m)/(2 l2² (x + m)) - arcsin(x/l2)/2    (integrated in z from infinity)
    D² f1 = n x³/((x + m)² l2⁴)                D³ f1 = n x³ (x³ - 3n² x + 3m x² - m n²)/((x+m)³ Q l2⁶)

and ``D³ f`` (long; below). Cartesian derivatives of an axisymmetric ``h`` follow from
``h_x = X Dh``, ``h_xx = Dh + X² D²h``, ``h_xxx = 3X D²h + X³ D³h`` and so on.
"""
from __future__ import annotations

import numpy as np

from .stress import spheroidal

__all__ = ["shear_kernel", "shear_components", "N_SHEAR_RADIAL"]

#: number of radial functions :func:`shear_kernel` returns
N_SHEAR_RADIAL = 7


def shear_kernel(r: np.ndarray, z: np.ndarray, x: np.ndarray | float, nu: float,
                 offset: np.ndarray | None = None) -> tuple[np.ndarray, ...]:
    """Radial functions ``(P1, ..., P7)`` of the field of a shear traction ``1/sqrt(x² - r²)``
    along ``+x`` on ``r < x`` (applied to the half-space; per unit amplitude, Pa).

    With ``θ`` the polar angle of the point from the ``x`` axis (``c = cos θ``, ``s = sin θ``)::

        σ_zz = P1 c            σ_xz = P2 + P3 c²          σ_yz = P3 c s
        σ_xx = P4 c + P5 c³    σ_yy = P6 c + P5 c s²      σ_xy = P7 s + P5 c² s

    (:func:`shear_components` assembles them). On the surface under the load
    ``σ_xz = -1/sqrt(x² - r²)``. Arguments broadcast; ``inf`` at the rim ``(x, 0)``;
    ``offset``: ``x - r`` to full precision where the caller has it
    (:func:`~contactlab.physics.stress.spheroidal`).
    """
    r, z, x, x2, _A, Q, m2, n2 = spheroidal(r, z, x, offset)
    with np.errstate(divide="ignore", invalid="ignore"):
        m = np.sqrt(m2)
        n = np.sqrt(n2)
        L2 = x2 + n2
        xm = x + m
        vz = -m / Q
        A1 = -x * n / (L2 * Q)
        A2 = -n * x * (m2 * n2 + 3.0 * m2 * x2 - 3.0 * n2 * n2 - n2 * x2) / (Q**3 * L2 * L2)
        Bz = -m * (m2 - 3.0 * n2) / Q**3
        C2 = x2 * (m * x2 - m * n2 - 2.0 * n2 * x) / (xm * xm * Q * L2 * L2)
        C3 = x2 * (-m2 * m2 * n2 * n2 - 6.0 * m2 * m2 * n2 * x2 + 3.0 * m2 * m2 * x2 * x2
                   - 3.0 * m2 * m * n2 * n2 * x - 18.0 * m2 * m * n2 * x2 * x
                   + m2 * m * x2 * x2 * x + 3.0 * m2 * n2 * n2 * n2 - 6.0 * m2 * n2 * n2 * x2
                   - 9.0 * m2 * n2 * x2 * x2 + 9.0 * m * n2 * n2 * n2 * x
                   - 10.0 * m * n2 * n2 * x2 * x - 3.0 * m * n2 * x2 * x2 * x
                   + 8.0 * n2 * n2 * n2 * x2) / (xm**3 * Q**3 * L2**3)
        E2 = n * x2 * x / (xm * xm * L2 * L2)
        E3 = n * x2 * x * (x2 * x - 3.0 * n2 * x + 3.0 * m * x2 - m * n2) / (xm**3 * Q * L2**3)
        r2 = r * r
        P1 = -z * r * Bz
        P2 = vz - z * A1
        P3 = -z * r2 * A2
        P4 = 2.0 * (1.0 + nu) * r * A1 + 6.0 * nu * r * E2 - 3.0 * z * r * C2
        P5 = r * r2 * (2.0 * nu * E3 - z * C3)
        P6 = 2.0 * nu * r * (A1 + E2) - z * r * C2
        P7 = r * (A1 + 2.0 * nu * E2 - z * C2)
    out: tuple[np.ndarray, ...] = (P1, P2, P3, P4, P5, P6, P7)
    rim = Q == 0
    if np.any(rim):
        val = np.where(x > 0, -np.inf, 0.0)
        out = tuple(np.where(rim, val, p) for p in out)
    return out


def shear_components(P: tuple[np.ndarray, ...], cos: np.ndarray, sin: np.ndarray
                     ) -> tuple[np.ndarray, ...]:
    """Cartesian ``(σ_xx, σ_yy, σ_zz, σ_xy, σ_xz, σ_yz)`` from the radial functions of
    :func:`shear_kernel` (or their superposition) at polar angles ``(cos θ, sin θ)``."""
    P1, P2, P3, P4, P5, P6, P7 = P
    c2 = cos * cos
    with np.errstate(invalid="ignore"):
        sxx = P4 * cos + P5 * c2 * cos
        syy = P6 * cos + P5 * cos * sin * sin
        szz = P1 * cos
        sxy = P7 * sin + P5 * c2 * sin
        sxz = P2 + P3 * c2
        syz = P3 * cos * sin
    return sxx, syy, szz, sxy, sxz, syz
