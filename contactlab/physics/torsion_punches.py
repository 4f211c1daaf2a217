"""Steps of the exact torsion solver for a contact without a friction limit (nothing slips).

Its punch density is a sum of rigid punches (point masses) ``Σ m_k δ(t − t_k)`` at the contact
radii of its steps, exact (:func:`punch_step`); the exact solver with a friction limit is
:mod:`contactlab.physics.torsion_annulus`, which re-exports these functions.

All functions are pure: arrays in, arrays out.
"""
from __future__ import annotations

from typing import cast

import numpy as np

__all__ = ["punch_step", "punch_torque", "punch_energy", "punch_traction"]


def punch_step(t: np.ndarray, m: np.ndarray, radius: float, G_t: float, *,
               dphi: float | None = None, target_torque: float | None = None):
    """One step of a contact without a friction limit (nothing slips), exact.

    The density is ``Σ m_k δ(t − t_k)``: rigid punches of radii ``t_k`` turned by ``m_k``. With
    no slip inside the new contact radius ``a`` the increment is a rigid punch of radius ``a``;
    the punches beyond ``a`` leave (the points outside carry no traction) and the rigid turn they
    gave the points inside is put back into the punch at ``a`` (points entering the contact start
    traction-free: they keep the displacement they had).

    Parameters
    ----------
    t, m : ndarray
        Punch radii (m, sorted) and turns (rad) before the step.
    radius : float
        Contact radius of the step, m.
    G_t : float
        Torsional modulus, Pa.
    dphi, target_torque : float
        Twist increment (rad) or the torque to reach (N·m); exactly one.

    Returns
    -------
    t, m : ndarray
        Punches after the step.
    dphi : float
        The twist increment, rad.
    """
    keep = t < radius
    gone = float(np.sum(m[~keep]))
    t, m = t[keep], m[keep]
    k = 16.0 / 3.0 * G_t
    if target_torque is None:   # exactly one of dphi, target_torque is given
        add = float(cast(float, dphi)) + gone
    else:
        add = (float(target_torque) - k * float(np.sum(t ** 3 * m))) / (k * radius ** 3)
        dphi = add - gone
    return np.append(t, radius), np.append(m, add), float(cast(float, dphi))


def punch_torque(t: np.ndarray, m: np.ndarray, G_t: float) -> float:
    """Torque ``(16/3) G_t Σ t_k³ m_k``, N·m."""
    return float(16.0 / 3.0 * G_t * np.sum(t ** 3 * m))


def punch_energy(t: np.ndarray, m: np.ndarray, G_t: float) -> float:
    """Elastic energy ``8 G_t ∫ x² Ψ² dx`` with ``Ψ(x) = Σ_{t_k > x} m_k`` (a step function), J."""
    if t.size == 0:
        return 0.0
    order = np.argsort(t, kind="stable")
    ts, ms = t[order], m[order]
    tail = np.cumsum(ms[::-1])[::-1]                    # Ψ on (t_{k-1}, t_k)
    lo = np.concatenate([[0.0], ts[:-1]])
    return float(8.0 * G_t * np.sum(tail ** 2 * (ts ** 3 - lo ** 3)) / 3.0)


def punch_traction(t: np.ndarray, m: np.ndarray, r: np.ndarray, G_t: float) -> np.ndarray:
    """Traction ``(4 G_t/π) Σ_{t_k > r} m_k r / sqrt(t_k² − r²)`` at ``r`` (Reissner–Sagoci), Pa."""
    rr = np.asarray(r, float)[:, None]
    with np.errstate(divide="ignore", invalid="ignore"):
        k = np.where(t[None, :] > rr, rr / np.sqrt(np.maximum(t * t - rr * rr, 1e-300)), 0.0)
    return 4.0 * G_t / np.pi * (k @ m)
