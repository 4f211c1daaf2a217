"""Independent closed forms and a second method for subsurface contact stresses.

Written from the sources, not from :mod:`contactlab.physics.stress`:

* Johnson, *Contact Mechanics* (1985), eqs. 3.44 (surface, inside and outside the contact) and
  3.45 (axis) for the Hertz pressure ``p0 sqrt(1 - r²/a²)``;
* Huber (1904) full Hertz field, in the form printed by Fischer-Cripps, *Introduction to Contact
  Mechanics* (2007), eq. 6.2.2 (variable ``u`` of the confocal ellipsoid);
* Boussinesq's point-load field (Johnson eq. 3.22, cylindrical, tension positive) integrated
  numerically over any axisymmetric pressure: a second method, independent of any
  superposition of punches.

Tension is positive, ``z >= 0`` is the depth.
"""
from __future__ import annotations

import numpy as np


def hertz_axis(z, a, p0, nu):
    """Johnson eq. 3.45: ``(σ_r, σ_z)`` on the axis (σ_θ = σ_r)."""
    z = np.asarray(z, float)
    sz = -p0 * a**2 / (a**2 + z**2)
    sr = -p0 * ((1 + nu) * (1 - (z / a) * np.arctan(a / z)) - 0.5 * a**2 / (a**2 + z**2))
    return sr, sz


def hertz_surface(r, a, p0, nu):
    """Johnson eq. 3.44: ``(σ_r, σ_θ, σ_z)`` on the surface, inside and outside the contact."""
    r = np.asarray(r, float)
    inside = r < a
    ri = np.where(inside, r, a)
    ro = np.where(inside, a, r)
    w = np.sqrt(1 - ri**2 / a**2)
    sr_in = p0 * ((1 - 2 * nu) / 3 * (a**2 / ri**2) * (1 - w**3) - w)
    st_in = -p0 * ((1 - 2 * nu) / 3 * (a**2 / ri**2) * (1 - w**3) + 2 * nu * w)
    sz_in = -p0 * w
    sr_out = p0 * (1 - 2 * nu) / 3 * a**2 / ro**2
    return (np.where(inside, sr_in, sr_out), np.where(inside, st_in, -sr_out),
            np.where(inside, sz_in, 0.0))


def hertz_huber(r, z, a, p0, nu):
    """Huber's full field (Fischer-Cripps eq. 6.2.2): ``(σ_r, σ_θ, σ_z, τ_rz)``, off the axis and
    below the surface (``r > 0``, ``z > 0``).

    The bracket of σ_θ carries a minus sign: with ``+`` (as printed in one edition) σ_θ fails
    Johnson's axis value (eq. 3.45) and surface value (eq. 3.44) and the numerical Boussinesq
    integration below; with ``-`` it meets all three."""
    r, z = np.broadcast_arrays(np.asarray(r, float), np.asarray(z, float))
    u = 0.5 * ((r**2 + z**2 - a**2) + np.sqrt((r**2 + z**2 - a**2)**2 + 4 * a**2 * z**2))
    q = z / np.sqrt(u)
    sr = p0 * ((1 - 2 * nu) / 3 * (a**2 / r**2) * (1 - q**3)
               + q**3 * a**2 * u / (u**2 + a**2 * z**2)
               + q * (u * (1 - nu) / (a**2 + u) + (1 + nu) * np.sqrt(u) / a
                      * np.arctan(a / np.sqrt(u)) - 2))
    st = p0 * (-(1 - 2 * nu) / 3 * (a**2 / r**2) * (1 - q**3)
               - q * (2 * nu + u * (1 - nu) / (a**2 + u)
                      - (1 + nu) * np.sqrt(u) / a * np.arctan(a / np.sqrt(u))))
    sz = -p0 * q**3 * a**2 * u / (u**2 + a**2 * z**2)
    trz = -p0 * r * z**2 / (u**2 + a**2 * z**2) * a**2 * np.sqrt(u) / (a**2 + u)
    return sr, st, sz, trz


def boussinesq_field(pressure, a, X, z, nu, n_r=240, n_t=240, flat=False):
    """Second method: Boussinesq's point load integrated over the pressure ``pressure(ρ)`` on the
    disc ``ρ < a``, at the point ``(X, 0, z)``, ``z > 0``: ``(σ_rr, σ_θθ, σ_zz, σ_rz)`` there.

    Gauss-Legendre in ``ρ`` (split at ``X``; ``ρ = a sin t`` near the rim when ``flat``, for an
    inverse-square-root pressure) and in the angle (0..π, doubled by symmetry)."""
    tg, wg = np.polynomial.legendre.leggauss(n_r)
    tg, wg = 0.5 * (tg + 1), 0.5 * wg
    ang, wa = np.polynomial.legendre.leggauss(n_t)
    th = 0.5 * np.pi * (ang + 1)
    wth = 0.5 * np.pi * wa * 2.0
    if flat:
        rho = a * np.sin(0.5 * np.pi * tg)
        wr = wg * a * 0.5 * np.pi * np.cos(0.5 * np.pi * tg)
        with np.errstate(divide="ignore"):
            pw = pressure(rho) * wr
    else:
        lo = [0.0, min(X, a)] if 0 < X < a else [0.0]
        hi = [min(X, a), a] if 0 < X < a else [a]
        rho = np.concatenate([l + (h - l) * tg for l, h in zip(lo, hi)])
        wr = np.concatenate([(h - l) * wg for l, h in zip(lo, hi)])
        pw = pressure(rho) * wr
    R, T = np.meshgrid(rho, th, indexing="ij")
    W = (pw[:, None] * wth[None, :]) * R          # p dA
    dx = X - R * np.cos(T)
    dy = -R * np.sin(T)
    rp2 = dx**2 + dy**2
    rp = np.sqrt(rp2)
    rho3 = np.sqrt(rp2 + z**2)
    s_r = (1 / (2 * np.pi)) * ((1 - 2 * nu) / rp2 * (1 - z / rho3) - 3 * z * rp2 / rho3**5)
    s_t = -(1 / (2 * np.pi)) * (1 - 2 * nu) * (1 / rp2 * (1 - z / rho3) - z / rho3**3)
    s_z = -(3 / (2 * np.pi)) * z**3 / rho3**5
    t_rz = -(3 / (2 * np.pi)) * rp * z**2 / rho3**5
    c, s = dx / rp, dy / rp
    sxx = np.sum(W * (s_r * c**2 + s_t * s**2))
    syy = np.sum(W * (s_r * s**2 + s_t * c**2))
    szz = np.sum(W * s_z)
    sxz = np.sum(W * t_rz * c)
    return sxx, syy, szz, sxz


def hertz_max_shear(nu, a=1.0, p0=1.0):
    """Maximum of ``(σ_θ - σ_z)/2`` on the axis from eq. 3.45 (the global maximum of the Hertz
    field's principal shear lies on the axis): ``(value/p0, depth/a)``, by bounded minimisation."""
    from scipy.optimize import minimize_scalar

    def neg(z):
        sr, sz = hertz_axis(z, a, p0, nu)
        return -0.5 * (sr - sz)

    res = minimize_scalar(neg, bounds=(0.05 * a, 2 * a), method="bounded",
                          options={"xatol": 1e-12})
    return -res.fun / p0, res.x / a


def twisted_punch_hankel(r, z, a, order):
    """Reissner & Sagoci's twisted rigid punch by its Hankel integral, per unit ``4Gφ/π``:
    ``σ_θz`` (``order=1``) and ``σ_rθ`` (``order=2``) at ``(r, z)``, ``z > 0``.

    The surface traction ``(4Gφ/π) r/sqrt(a² - r²)`` has the order-1 Hankel transform
    ``(4Gφ/π)(sin ξa - ξa cos ξa)/ξ²``; the circumferential displacement field
    ``u = ∫ B(ξ) e^(-ξz) J1(ξr) dξ`` solves the torsion equation, so
    ``σ_θz = ∫ ξ τ̄(ξ) e^(-ξz) J1(ξr) dξ`` and ``σ_rθ`` the same with ``J2``."""
    from scipy.integrate import quad
    from scipy.special import jv

    def f(xi):
        return (np.sin(xi * a) - xi * a * np.cos(xi * a)) / xi * np.exp(-xi * z) * jv(order, xi * r)

    return quad(f, 0, np.inf, limit=4000, epsabs=1e-14, epsrel=1e-12)[0]
