"""Brute-force frictional torsion on many rings, independent of contactlab's ring solver.

A different discretisation and a different solver than ``contactlab.physics.torsion_rings``:
the punch density ``w`` (Jäger's superposition of twisted flat punches, Reissner–Sagoci traction
``(4G/π) r/sqrt(t² − r²)`` per punch of radius ``t``) is piecewise *constant* on uniform rings, so
the traction of a ring is ``(4G/π) r [acosh(t1/r) − acosh(max(t0, r)/r)]`` and the energy matrix
is the closed form of the punch-punch energy ``(16/3) G min(t, s)³`` integrated over two rings.
Each step is the bounded least-squares problem ``min ½|R z − R⁻ᵀ b|²``, ``|z_i| ≤ μ p_i``
(``H = RᵀR``), solved by scipy's BVLS. Converges at order ~1.5 in the ring width (slower than the
package's solver), so it is run with many rings.
"""
from __future__ import annotations

import numpy as np
import scipy.linalg as la
from scipy.optimize import lsq_linear


def _matrices(b, r, G):
    t0, t1 = b[:-1], b[1:]
    rr = r[:, None]
    lo = np.maximum(t0[None, :], rr)
    T1 = np.maximum(t1[None, :], rr)
    B = 4 * G / np.pi * rr * (np.arccosh(T1 / rr) - np.arccosh(lo / rr))
    m = 4.0 / 3.0 * G * (t1 ** 4 - t0 ** 4)
    h = t1 - t0
    K = np.triu(np.outer(m, h), 1)
    K = K + K.T
    K[np.diag_indices_from(K)] = 16.0 / 3.0 * G * 0.5 * ((t1 ** 5 - t0 ** 5) / 5 - t0 ** 4 * h)
    Bi = la.solve_triangular(B, np.eye(b.size - 1))
    H = Bi.T @ K @ Bi
    return 0.5 * (H + H.T), Bi.T @ m


def torque_history(radius_max, G, bound_of_step, twist, n_rings):
    """Torque per step of a twist history; ``bound_of_step(k, r)`` gives ``μ p`` at the points."""
    b = np.linspace(0.0, radius_max, n_rings + 1)
    r = 0.5 * (b[1:] + b[:-1])
    H, g = _matrices(b, r, G)
    R = la.cholesky(H)
    z = np.zeros(n_rings)
    out, phi_old = [], 0.0
    for k, phi in enumerate(twist):
        rhs = H @ z + (phi - phi_old) * g
        hi = bound_of_step(k, r) + 0.0
        c = la.solve_triangular(R, rhs, trans="T")
        free = hi > 0
        sol = lsq_linear(R[:, free], c, bounds=(-hi[free], hi[free]), method="bvls",
                         tol=1e-14, lsmr_tol=None)
        z = np.zeros(n_rings)
        z[free] = sol.x
        out.append(float(g @ z))
        phi_old = phi
    return np.array(out)
