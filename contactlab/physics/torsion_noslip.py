"""Torsion without slip (μ → ∞): Reissner-Sagoci [RS44; S eqs. 21-23, 30-34] (theory §6.1).

The whole contact of radius ``a`` turns rigidly by ``φ``; the result depends on ``a`` only:

* ``M = (16/3) G_t a³ φ`` with the torsional modulus ``1/G_t = 1/G1 + 1/G2``;
* ``τ(r) = (4 G_t φ/π) r/sqrt(a²-r²)`` for ``r < a``;
* ``u_φ = φ r`` for ``r <= a``, ``(2φ/π)[r asin(a/r) - a sqrt(1 - a²/r²)]`` beyond.

MDR cross-check [S eqs. 31-34]: springs ``8 G_t Δx`` displaced by ``u_y = x φ`` give
``M = 16 G_t ∫_0^a x u_y dx``, the same torque.
"""
from __future__ import annotations

import numpy as np

__all__ = ["torque", "twist", "shear", "displacement", "mdr_torque"]


def torque(G_t: float, a: np.ndarray, phi: np.ndarray) -> np.ndarray:
    """``M = (16/3) G_t a³ φ`` (N·m) [RS44; S eq. 21]."""
    return 16.0 / 3.0 * G_t * a**3 * phi


def twist(G_t: float, a: np.ndarray, M: np.ndarray) -> np.ndarray:
    """Inverse of :func:`torque`: ``φ = 3M/(16 G_t a³)`` (rad); 0 where ``a = 0`` and ``M = 0``."""
    a = np.asarray(a, float)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(a > 0, 3.0 * M / (16.0 * G_t * np.where(a > 0, a, 1.0) ** 3), 0.0)


def shear(G_t: float, r: np.ndarray, a: np.ndarray, phi: np.ndarray) -> np.ndarray:
    """``τ(r) = (4G_tφ/π) r/sqrt(a²-r²)`` inside, 0 outside (Pa) [S eq. 23]; ``inf`` at ``r = a``."""
    r, a, phi = np.broadcast_arrays(*(np.asarray(v, float) for v in (r, a, phi)))
    out = np.zeros(r.shape)
    inside = r < a
    out[inside] = 4.0 * G_t * phi[inside] / np.pi * r[inside] / np.sqrt(
        (a[inside] - r[inside]) * (a[inside] + r[inside]))
    edge = (r == a) & (a > 0) & (phi != 0)
    out[edge] = np.copysign(np.inf, phi[edge])
    return out


def displacement(r: np.ndarray, a: np.ndarray, phi: np.ndarray) -> np.ndarray:
    """Circumferential surface displacement ``u_φ(r)`` (m) inside and outside [S eq. 22]."""
    r, a, phi = np.broadcast_arrays(*(np.asarray(v, float) for v in (r, a, phi)))
    out = phi * r
    outside = r > a
    if np.any(outside):
        ro, ao = r[outside], a[outside]
        q = ao / ro
        out[outside] = 2.0 * phi[outside] / np.pi * (ro * np.arcsin(q) - ao * np.sqrt((1 - q) * (1 + q)))
    return out


def mdr_torque(G_t: float, a: np.ndarray, phi: np.ndarray, n_springs: int = 2000) -> np.ndarray:
    """MDR torque ``16 G_t Σ x u_y Δx`` from ``n_springs`` springs on ``[0, a]`` (midpoint rule).

    A cross-check of the spring picture [S eqs. 30-34]; the midpoint sum of ``x²`` is exact up to
    ``-a³/(12 n²)``, so this returns ``(16/3) G_t a³ φ (1 - 1/(4 n²))``.
    """
    a, phi = np.broadcast_arrays(np.asarray(a, float), np.asarray(phi, float))
    k = (np.arange(n_springs) + 0.5) / n_springs
    x = a[..., None] * k
    dx = a[..., None] / n_springs
    u_y = x * phi[..., None]
    return 16.0 * G_t * np.sum(x * u_y * dx, axis=-1)
