"""Linearly implicit cycle jumps for fretting wear: the Jacobian of the wear rate on the grid and a
Rosenbrock-W step with an embedded error estimate.

Kernels for :func:`contactlab.effects.wear.wear` with ``integrator="implicit"`` (theory in
docs/fretting.md, section 8). The wear rate ``R(h) = 4k q(h)``, ``q = p s_load`` at the grid
nodes (:mod:`contactlab.physics.wear`), is stiff through the elastic redistribution of the
pressure: a short wear wave of length λ is flattened at a rate ``~ k s E*/λ``, so explicit steps are
bounded by the grid cell, not by the accuracy. Its Jacobian is exact for the grid operators away
from the kinks of the positive parts (contact edge, slip edge):

* ``u = (d - g)_+`` with ``g = G (f0 + h)``, ``G = T D`` (the MDR transform of the table's slopes)
  and the depth from the force balance ``Σ w1 (d - g)_+ = F/(2E*)``, so on the contact set
  ``C``: ``∂d/∂h = c = (w1_C)ᵀ G / Σ w1_C`` and ``∂u/∂h = diag(1_C) (1 cᵀ - G)``;
* ``p = (K u)_+`` with ``K = -(E*/π) Pm D``;
* the slip: shift ``s1 = (δ - μE* u/G*)_+``, ``s = (A s1)_+``; twist ``Φ = (φ - θ_s)_+``,
  ``s = (B Φ)_+`` with ``θ_s = μ P/(2G_t)``, ``P = -(E*/π) KP D u`` (exact) or
  ``θ_s = μE* u/(4G_t r)`` (MDR springs);
* ``∂q/∂h = diag(s) ∂p/∂h + diag(p) ∂s/∂h`` and the axis row of the even extension.

The step is ROS34PW2 (Rang & Angermann, BIT 45 (2005) 761): four stages, order 3 for *any*
matrix in place of the Jacobian (a W-method, so a Jacobian kept from an earlier step costs accuracy
of the estimate only, never the order), L-stable, stiffly accurate, with an embedded solution of
order 2 whose difference is the local error estimate. No function here validates input.
"""
from __future__ import annotations

from collections.abc import Callable

import numpy as np
import scipy.linalg

__all__ = ["GAMMA", "ALPHA", "GAMMA_OFF", "B", "B_HAT", "ORDER", "jacobian_operators",
           "rate_jacobian", "factor", "rosenbrock_step"]

#: ROS34PW2 (Rang & Angermann 2005, table of the method): diagonal γ, the stage arguments α_ij,
#: the off-diagonal γ_ij, the weights b of the order-3 solution and b̂ of the order-2 one
GAMMA = 4.3586652150845900e-01
ALPHA = np.array([[0.0, 0.0, 0.0, 0.0],
                  [8.7173304301691801e-01, 0.0, 0.0, 0.0],
                  [8.4457060015369423e-01, -1.1299064236484185e-01, 0.0, 0.0],
                  [0.0, 0.0, 1.0, 0.0]])
GAMMA_OFF = np.array([[0.0, 0.0, 0.0, 0.0],
                      [-8.7173304301691801e-01, 0.0, 0.0, 0.0],
                      [-9.0338057013044082e-01, 5.4180672388095326e-02, 0.0, 0.0],
                      [2.4212380706095346e-01, -1.2232505839045147e+00,
                       5.4526025533510214e-01, 0.0]])
B = np.array([2.4212380706095346e-01, -1.2232505839045147e+00, 1.5452602553351020e+00,
              4.3586652150845900e-01])
B_HAT = np.array([3.7810903145819369e-01, -9.6042292212423178e-02, 0.5,
                  2.1793326075422950e-01])
#: order of the embedded solution: the local error estimate scales as ``ΔN**(ORDER + 1)``
ORDER = 2
#: nodes beyond the contact edge that the Jacobian's leading block keeps at least (the block does
#: not depend on a smaller padding, so a padded Jacobian differs only on its padded diagonal)
_MARGIN = 8


def jacobian_operators(ops: dict, E_star: float) -> dict[str, np.ndarray]:
    """Dense operators of the Jacobian (each ``(n+1) x (n+1)``), built once per grid: ``G = T D``
    (profile heights -> 1D profile), ``K = -(E*/π) Pm D`` (1D displacement -> pressure) and
    ``KPD = -(E*/π) KP D`` (1D displacement -> Jäger's ``P``)."""
    dr = ops["dr"]

    def times_d(M: np.ndarray) -> np.ndarray:        # M @ D, D the slope operator (diff / dr)
        out = np.zeros((M.shape[0], M.shape[1] + 1))
        out[:, :-1] -= M
        out[:, 1:] += M
        return out / dr

    c = -E_star / np.pi
    return {"G": times_d(ops["T"]), "K": c * times_d(ops["Pm"]), "KPD": c * times_d(ops["KP"])}


def rate_jacobian(ops: dict, jops: dict, g: np.ndarray, d: float, E_star: float, G_mod: float,
                  mu: float, amplitude: float, mode: str, method: str, edge: int = 0) -> np.ndarray:
    """``∂q/∂h`` at the nodes, Pa (``q = p s_load``, see the module docstring): ``mode`` is
    ``"tangential"`` (``G_mod = G*``) or ``"torsion"`` (``G_mod = G_t``, ``method`` exact|mdr).

    ``edge > 0`` adds, on the diagonal of the ``edge`` nodes beyond the contact edge, the stiff
    self-coupling each would have if it touched (the side of the kink a growing scar reaches):
    it damps a node that a step brings into contact, which keeps a long step stable there, and
    it leaves every other entry, so a node that stays out of contact gets no increment
    (``edge = 0``: the exact derivative on the current contact set)."""
    # every row and column beyond the contact edge (and the padded nodes) is zero: the work is
    # done on the leading block of the grid, which the contact covers, and embedded at the end
    n1 = ops["r"].size
    inside = np.flatnonzero(d - g > 0)
    L = n1 if inside.size == 0 else min(n1, int(inside[-1]) + 2 + max(edge, _MARGIN))
    G, K = jops["G"][:L, :L], jops["K"][:L, :L]
    A_op, B_op = ops["A"][:L, :L], ops["B"][:L, :L]
    w1, r, g = ops["w1"][:L], ops["r"][:L], g[:L]
    gap = d - g
    m = gap > 0
    pad = np.zeros(0, dtype=int)
    if edge > 0 and np.any(m):
        last = int(np.flatnonzero(m)[-1])
        pad = np.arange(last + 1, min(last + 1 + edge, r.size))
    u = np.where(m, gap, 0.0)
    w = np.where(m, w1, 0.0)
    c = (w @ G) / np.sum(w)
    Gm = G[m]
    # ∂u/∂h = diag(m)(1 cᵀ - G): only contact rows; U_m = its rows on the contact set
    U_m = c[None, :] - Gm
    p_raw = K @ u
    Dp = K[:, m] @ U_m
    Dp[p_raw <= 0] = 0.0
    p = np.maximum(p_raw, 0.0)
    if mode == "tangential":
        s1 = amplitude - mu * E_star * u / G_mod
        act = (s1 > 0)[m]
        a3 = A_op @ np.maximum(s1, 0.0)
        Ds = (-mu * E_star / G_mod) * (A_op[:, m][:, act] @ U_m[act])
    else:
        theta = np.full(r.shape, np.inf)
        if method == "exact":
            KPD = jops["KPD"][:L, :L]
            theta[1:] = mu * (KPD[1:] @ u) / (2.0 * G_mod)
            act = (amplitude - theta) > 0
            dtheta = (mu / (2.0 * G_mod)) * (KPD[act][:, m] @ U_m)
        else:
            theta[1:] = mu * E_star * u[1:] / (4.0 * G_mod * r[1:])
            act = (amplitude - theta) > 0
            scale = np.zeros(r.shape)
            scale[1:] = mu * E_star / (4.0 * G_mod * r[1:])
            dU = np.zeros((r.size, r.size))
            dU[m] = U_m
            dtheta = scale[act, None] * dU[act]
        a3 = B_op @ np.maximum(amplitude - theta, 0.0)
        Ds = -(B_op[:, act] @ dtheta)
    s3 = np.maximum(a3, 0.0)
    Ds[a3 <= 0] = 0.0
    J = s3[:, None] * Dp + p[:, None] * Ds
    if pad.size:
        # ∂p_j/∂h_j of a padded node as if it touched: contact set and force balance with it
        mp = m.copy()
        mp[pad] = True
        wp = np.where(mp, w1, 0.0)
        cp = (wp @ G[:, pad]) / np.sum(wp)
        self_p = np.einsum("ij,ji->i", K[pad][:, mp], cp[None, :] - G[mp][:, pad])
        J[pad, pad] += s3[pad] * np.minimum(self_p, 0.0)
    # the axis row: q_0 = max((4 q_1 - q_2)/3, 0) (physics.wear._extrapolate_axis)
    q = p * s3
    J[0] = (4.0 * J[1] - J[2]) / 3.0 if (4.0 * q[1] - q[2]) > 0 else 0.0
    if L == n1:
        return J
    out = np.zeros((n1, n1))
    out[:L, :L] = J
    return out


def factor(J: np.ndarray, dN: float) -> tuple:
    """LU factors of ``I - γ dN J``, the matrix of every stage of a step of ``dN`` cycles.

    Only the leading block that holds every off-diagonal entry is factored (the wear Jacobian
    is zero beyond the contact edge but for a padded diagonal): ``(lu, n, tail)`` with the
    factors of the leading ``n x n`` block and the diagonal ``tail`` of the rest."""
    off = J != 0
    np.fill_diagonal(off, False)
    nz = np.flatnonzero(np.any(off, axis=0) | np.any(off, axis=1))
    n = int(nz[-1]) + 1 if nz.size else 0
    lu = (scipy.linalg.lu_factor(np.eye(n) - (GAMMA * dN) * J[:n, :n], check_finite=False)
          if n else None)
    return lu, n, 1.0 - (GAMMA * dN) * np.diag(J)[n:]


def _solve(lu: tuple, rhs: np.ndarray) -> np.ndarray:
    """Solve with the factors of :func:`factor`."""
    block, n, tail = lu
    out = np.empty_like(rhs)
    if n:
        out[:n] = scipy.linalg.lu_solve(block, rhs[:n], check_finite=False)
    out[n:] = rhs[n:] / tail
    return out


def rosenbrock_step(rate: Callable[[np.ndarray], np.ndarray], y: np.ndarray, f0: np.ndarray,
                    dN: float, J: np.ndarray, lu: tuple, dN_lu: float
                    ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """One ROS34PW2 step of ``dy/dN = rate(y)`` from ``y`` (``f0 = rate(y)``) over ``dN``:
    ``(I - γ dN W) k_i = dN rate(y + Σ α_ij k_j) + dN W Σ γ_ij k_j``, ``y1 = y + Σ b_i k_i``.

    ``lu`` are the factors of ``I - γ dN_lu J`` (:func:`factor`), kept from an earlier step: the
    step uses ``W = (dN_lu/dN) J``, which a W-method may (any matrix keeps its order), so a
    change of step does not need a new factorisation.

    The increment is kept on the support of the rates only (components whose rate vanishes at
    every stage and at the end stay put): the linear solves spread a little of every increment
    over all components, which for wear would wear the surface outside the contact.

    Returns ``y1``, the local error estimate ``Σ (b_i - b̂_i) k_i`` (of the order-2 solution) and
    the rate at ``y1``. ``rate`` may raise; the caller retries with a smaller step."""
    ks: list[np.ndarray] = []
    active = f0 != 0
    for i in range(4):
        f = f0 if i == 0 else rate(y + ALPHA[i, :i] @ np.array(ks))
        active |= f != 0
        rhs = dN * f
        if i > 0 and np.any(GAMMA_OFF[i, :i]):
            rhs = rhs + dN_lu * (J @ (GAMMA_OFF[i, :i] @ np.array(ks)))
        ks.append(_solve(lu, rhs))
    K = np.array(ks)
    step, err = B @ K, (B - B_HAT) @ K
    y1 = y + step
    f1 = rate(y1)                       # the next step's first rate: the end of this one
    active |= f1 != 0
    if not np.all(active):
        y1[~active] = y[~active]
        err[~active] = 0.0
        f1 = rate(y1)
    return y1, err, f1
