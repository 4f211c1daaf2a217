"""JKR force of a power-law tip at a given indentation, with exact parameter derivatives.

Heß's rule through the MDR: the contact radius ``a`` at indentation ``δ`` solves
``h(a) = g(a) - s(a) - δ = 0`` with the critical elongation ``s = sqrt(2π a Δγ/E*)``, and the
force is the MDR force at that radius, ``F = 2E*(a δ - ∫_0^a g)``. For ``g = K a^n``
(``K = κ_n c``) everything is closed form except ``a(δ)``, found by Newton steps on the stable
branch ``a > a_c`` (``h'(a_c) = 0``), where ``h`` is increasing and convex for ``n >= 1``, from
a start to the right of the root (monotone convergence).

Derivatives at fixed ``δ`` (``a`` implicit, ``h_a = g'(a) - s/(2a) > 0`` on the branch;
``∂F/∂a|_δ = 2E*(δ - g(a)) = -2E* s``):

* ``dF/dδ = 2E* a - 2E* s/h_a``;
* ``dF/dE* = F/E* + s²/h_a``;
* ``dF/dΔγ = -2π a/h_a``.

Below the branch's smallest indentation ``δ_c = δ(a_c)`` (fixed grips: the surfaces have come
apart) the force and its derivatives are zero.
"""
from __future__ import annotations

import numpy as np

__all__ = ["JKRPower"]

_NEWTON = 60


class JKRPower:
    """JKR through the MDR for ``f = c r^n`` (``n >= 1``).

    Parameters
    ----------
    kc : float
        ``K = κ_n c`` of the transform ``g = K a^n``.
    n : float
        Exponent (>= 1).
    """

    def __init__(self, kc: float, n: float) -> None:
        self.K, self.n = float(kc), float(n)
        self._last: np.ndarray | None = None    # radii of the previous call (warm start)

    def critical(self, E_star: float, w: float) -> tuple[float, float]:
        """Contact radius ``a_c`` (m) and indentation ``δ_c`` (m) where the branch ends."""
        K, n = self.K, self.n
        beta = np.sqrt(2.0 * np.pi * w / E_star)
        if beta == 0.0:
            return 0.0, 0.0
        a_c = (beta / (2.0 * n * K)) ** (1.0 / (n - 0.5))
        return a_c, K * a_c ** n - beta * np.sqrt(a_c)

    def radius(self, delta: np.ndarray, E_star: float, w: float) -> np.ndarray:
        """Contact radius on the stable branch (m); ``nan`` below ``δ_c``."""
        K, n = self.K, self.n
        beta = np.sqrt(2.0 * np.pi * w / E_star)
        a_c, d_c = self.critical(E_star, w)
        on = delta >= d_c
        dp = np.maximum(delta, 0.0)
        a = (2.0 * dp / K) ** (1.0 / n) + a_c
        if beta > 0:
            a += (2.0 * beta / K) ** (1.0 / (n - 0.5))
        last = self._last
        if last is not None and last.shape == a.shape:
            # the previous call's radii (a fit moves its parameters little between calls): on
            # the convex, increasing h one Newton step from either side lands right of the
            # root, and the iteration is monotone from there
            warm = np.isfinite(last) & (last > a_c)
            a = np.where(warm, last, a)
        last_step = False
        for _ in range(_NEWTON):
            sa = np.sqrt(a)
            an = a * a if n == 2.0 else a ** n
            h = K * an - beta * sa - delta
            ha = n * K * an / a - beta / (2.0 * sa)
            step = np.where(on & (ha > 0), h / np.where(ha > 0, ha, 1.0), 0.0)
            a = np.maximum(a - step, a_c)
            if last_step:
                break
            # quadratic convergence: one more step after 1e-10 reaches rounding
            last_step = not np.any(np.abs(step) > 1e-10 * a)
        out = np.where(on, a, np.nan)
        self._last = out
        return out

    def force(self, delta: np.ndarray, E_star: float, w: float
              ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """Force (N) and its derivatives ``dF/dδ``, ``dF/dE*``, ``dF/dΔγ`` at indentations
        ``δ``; zeros where the surfaces are apart."""
        K, n = self.K, self.n
        a = self.radius(delta, E_star, w)
        on = np.isfinite(a)
        a = np.where(on, a, 0.0)
        G = K * a ** (n + 1.0) / (n + 1.0)
        F = 2.0 * E_star * (a * delta - G)
        s = np.sqrt(2.0 * np.pi * w * a / E_star)
        with np.errstate(divide="ignore", invalid="ignore"):
            ha = n * K * a ** (n - 1.0) - s / (2.0 * a)
            inv = np.where(on & (ha > 0), 1.0 / ha, 0.0)
        dF_dd = 2.0 * E_star * (a - s * inv)
        dF_dE = F / E_star + s * s * inv
        dF_dw = -2.0 * np.pi * a * inv
        z = np.zeros_like(F)
        return (np.where(on, F, z), np.where(on, dF_dd, z), np.where(on, dF_dE, z),
                np.where(on, dF_dw, z))
