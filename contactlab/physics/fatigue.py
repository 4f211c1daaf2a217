"""Critical-plane fatigue parameters of a stress cycle at a set of points.

Smith–Watson–Topper (Smith, Watson & Topper 1970, J. Materials 5, 767-778; critical-plane form
of Socie 1987): on the plane of unit normal ``n``, with ``σ_n = n·σ·n`` and the elastic normal
strain ``ε_n = ((1 + ν) σ_n - ν tr σ)/E``::

    SWT(n) = max_t σ_n(t) · (max_t ε_n(t) - min_t ε_n(t))/2

and ``SWT = max_n SWT(n)`` (Pa), searched over a grid of plane normals. A uniaxial cycle
``σ_min .. σ_max`` gives ``σ_max (σ_max - σ_min)/(2E)`` on the plane normal to the load.

Findley (Findley 1959, J. Eng. Industry 81, 301-306): on the plane of unit normal ``n``, with
the shear amplitude ``τ_a(n)`` (the largest over the in-plane directions ``s`` of half the range
over the cycle of the resolved shear ``s·σ·n``, the longest-projection amplitude: half the shear
range for a proportional cycle) and the largest normal stress ``max_t σ_n``::

    FP = max_n [τ_a(n) + k max_t σ_n(t)]

with ``k`` a material constant (typically 0.2-0.3 for steels). A uniaxial cycle ``σ_min ..
σ_max`` gives ``k σ_max/2 + sqrt((Δσ/4)² + (k σ_max/2)²)``; a fully reversed shear ``±τ``
gives ``τ sqrt(1 + k²)``.
"""
from __future__ import annotations

import numpy as np

__all__ = ["plane_normals", "normal_stress_on_planes", "swt", "findley"]

#: polar and azimuthal steps of the plane-normal grid, degrees (a hemisphere: n and -n are one
#: plane). The grid holds the coordinate axes and the 45° planes; off the grid a plane is at
#: most 1.25° from a grid plane, where σ_n differs by O(sin² 1.25°) ≈ 5e-4 of the stress
PLANE_STEP_DEG = 2.5
#: step of the in-plane shear directions of :func:`findley`, degrees (over 0..180°): the largest
#: resolved range is within ``1 - cos 1.25° ≈ 2.4e-4`` of the grid's
SHEAR_STEP_DEG = 2.5


def plane_normals(step_deg: float = PLANE_STEP_DEG) -> np.ndarray:
    """Unit normals ``(N, 3)`` of a hemisphere grid (polar angle 0..90°, azimuth 0..180°)."""
    th = np.radians(np.arange(0.0, 90.0 + 1e-9, step_deg))
    ph = np.radians(np.arange(0.0, 180.0, step_deg))
    T, P = np.meshgrid(th, ph, indexing="ij")
    n = np.stack([np.sin(T) * np.cos(P), np.sin(T) * np.sin(P), np.cos(T)], axis=-1)
    return np.unique(np.round(n.reshape(-1, 3), 15), axis=0)


def normal_stress_on_planes(S: np.ndarray, n: np.ndarray) -> np.ndarray:
    """``σ_n = n·σ·n`` for tensors ``S`` (``(..., 6)``: xx, yy, zz, xy, xz, yz) and normals
    ``n`` (``(N, 3)``); returns ``(..., N)``."""
    sxx, syy, szz, sxy, sxz, syz = np.moveaxis(S, -1, 0)
    nx, ny, nz = n[:, 0], n[:, 1], n[:, 2]
    e = (..., None)
    return (sxx[e] * nx * nx + syy[e] * ny * ny + szz[e] * nz * nz
            + 2.0 * (sxy[e] * nx * ny + sxz[e] * nx * nz + syz[e] * ny * nz))


def swt(S: np.ndarray, E: float, nu: float, normals: np.ndarray | None = None
        ) -> tuple[np.ndarray, np.ndarray]:
    """Smith–Watson–Topper parameter of the cycles ``S`` (``(T, P, 6)``: ``T`` instants of the
    cycle, ``P`` points, Cartesian components), Pa, per point; and the critical plane's normal
    per point ``(P, 3)``. ``normals`` defaults to :func:`plane_normals`."""
    n = plane_normals() if normals is None else np.asarray(normals, float)
    sn = normal_stress_on_planes(S, n)                          # (T, P, N)
    tr = (S[..., 0] + S[..., 1] + S[..., 2])[..., None]
    en = ((1.0 + nu) * sn - nu * tr) / E
    val = np.max(sn, axis=0) * 0.5 * (np.max(en, axis=0) - np.min(en, axis=0))   # (P, N)
    k = np.argmax(val, axis=-1)
    return np.take_along_axis(val, k[:, None], axis=-1)[:, 0], n[k]


def _plane_bases(n: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Two unit vectors ``(N, 3)`` spanning each plane of normal ``n``."""
    helper = np.where(np.abs(n[:, 2:3]) < 0.9, [[0.0, 0.0, 1.0]], [[1.0, 0.0, 0.0]])
    e1 = np.cross(helper, n)
    e1 /= np.linalg.norm(e1, axis=1, keepdims=True)
    return e1, np.cross(n, e1)


def findley(S: np.ndarray, k: float, normals: np.ndarray | None = None
            ) -> tuple[np.ndarray, np.ndarray]:
    """Findley's parameter ``max_n [τ_a(n) + k max_t σ_n(t)]`` of the cycles ``S`` (``(T, P,
    6)`` as :func:`swt`), Pa, per point; and the critical plane's normal per point ``(P, 3)``.
    ``k`` is the material's (dimensionless) normal-stress sensitivity."""
    n = plane_normals() if normals is None else np.asarray(normals, float)
    sxx, syy, szz, sxy, sxz, syz = np.moveaxis(S, -1, 0)
    e = (..., None)
    t = np.stack([sxx[e] * n[:, 0] + sxy[e] * n[:, 1] + sxz[e] * n[:, 2],
                  sxy[e] * n[:, 0] + syy[e] * n[:, 1] + syz[e] * n[:, 2],
                  sxz[e] * n[:, 0] + syz[e] * n[:, 1] + szz[e] * n[:, 2]], axis=-1)  # (T,P,N,3)
    e1, e2 = _plane_bases(n)
    t1 = np.einsum("tpnc,nc->tpn", t, e1)
    t2 = np.einsum("tpnc,nc->tpn", t, e2)
    amp = np.zeros(t1.shape[1:])
    for th in np.radians(np.arange(0.0, 180.0, SHEAR_STEP_DEG)):   # in-plane directions
        res = np.cos(th) * t1 + np.sin(th) * t2
        np.maximum(amp, 0.5 * (np.max(res, axis=0) - np.min(res, axis=0)), out=amp)
    val = amp + k * np.max(np.einsum("tpnc,nc->tpn", t, n), axis=0)           # (P, N)
    j = np.argmax(val, axis=-1)
    return np.take_along_axis(val, j[:, None], axis=-1)[:, 0], n[j]
