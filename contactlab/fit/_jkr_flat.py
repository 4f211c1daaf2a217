"""JKR through the MDR for a tip with a flat centre and a rising flank (no wall), exact.

A flat centre of radius ``b`` (``g = 0`` for ``a <= b``) with a flank beyond it (a truncated
cone or paraboloid): in contact the radius is at least ``b``, and Heß's rule gives the branch
``δ = h(a) = g(a) - β√a`` (``β = sqrt(2πΔγ/E*)``) for ``a >= a_c``, ``a_c`` the smallest radius
``>= b`` where ``h' >= 0``. When the flank starts with a finite slope, ``g'(b⁺)`` is infinite (a
square root at the edge of the flat), so ``a_c = b``: the branch ends with the contact radius
at the flat's edge, at ``δ_c = -β√b`` and the force ``-sqrt(8π b³ E* Δγ)`` (Kendall's punch).

``a(δ)`` is found by bisection in ``sqrt(a - a_c)`` (robust at the square-root edge) followed
by Newton steps on the profile's closed-form ``g``; the force is the MDR force at that radius,
``F = 2E*(a δ - ∫_0^a g)``, and the derivatives those of :mod:`contactlab.fit._jkr` with
``h_a = g'(a) - β/(2√a)`` (``g'`` from :func:`contactlab.fit._tip.g_prime`; at an infinite
``g'`` the radius does not move with ``δ``).
"""
from __future__ import annotations

from typing import Any

import numpy as np

from ._tip import g_prime

__all__ = ["JKRFlat"]

#: bisection steps in sqrt(a - a_c) before the Newton steps
_BISECT = 40
#: Newton steps on h(a) = δ after the bisection
_NEWTON = 3


class JKRFlat:
    """JKR for a flat-centred tip without a wall (the ``JKRTable`` interface).

    Parameters
    ----------
    profile : Profile
        The tip (``flat_radius > 0``, no wall, closed-form ``g`` and ``∫g``).
    a_max : float
        Largest contact radius the fit may need, m.
    rtol : float
        Tolerance of the profile's routes.
    """

    error = 0.0
    #: the branch end's force grows as Δγ^(1/2) when it lies at the flat's edge (Kendall):
    #: the start search matches Δγ to the smallest force with this power
    work_power = 2.0
    #: the start search reads the branch end at the jump, not at the smallest force (the
    #: force falls further along the branch before the end on a shallow flank)
    end_at_jump = True

    def __init__(self, profile: Any, a_max: float, rtol: float = 1e-12) -> None:
        self.profile, self.a_max, self.rtol = profile, float(a_max), rtol
        self.b = float(profile.flat_radius)
        self._memo: dict = {}

    def _g(self, a: np.ndarray) -> np.ndarray:
        return np.where(a > self.b, self.profile._g(np.maximum(a, self.b), self.rtol), 0.0)

    def _gp(self, a: np.ndarray) -> np.ndarray:
        with np.errstate(all="ignore"):
            gp = g_prime(self.profile, np.maximum(a, self.b * (1.0 + 1e-15)), self.rtol)
        return np.where(np.isfinite(gp), gp, np.inf)

    def critical(self, E_star: float, w: float) -> tuple[float, float]:
        """Contact radius ``a_c`` (m) and indentation ``δ_c`` (m) where the branch ends."""
        key = (E_star, w)
        if key not in self._memo:
            if len(self._memo) > 64:
                self._memo.clear()
            beta = np.sqrt(2.0 * np.pi * w / E_star)
            b = self.b
            lo = np.array([b * (1.0 + 1e-12)])
            if self._gp(lo)[0] - beta / (2.0 * np.sqrt(lo[0])) >= 0:
                a_c = b                 # h increasing from the flat's edge
            else:                       # bisection on h'(a) = 0 in (b, a_max)
                x0, x1 = b, self.a_max
                for _ in range(80):
                    xm = 0.5 * (x0 + x1)
                    if self._gp(np.array([xm]))[0] - beta / (2.0 * np.sqrt(xm)) >= 0:
                        x1 = xm
                    else:
                        x0 = xm
                a_c = x1
            d_c = float(self._g(np.array([a_c]))[0] - beta * np.sqrt(a_c))
            self._memo[key] = (a_c, d_c)
        return self._memo[key]

    def radius(self, delta: np.ndarray, E_star: float, w: float) -> np.ndarray:
        """Contact radius on the branch (m); ``nan`` below ``δ_c``."""
        beta = np.sqrt(2.0 * np.pi * w / E_star)
        a_c, d_c = self.critical(E_star, w)
        on = delta >= d_c
        d = np.where(on, delta, d_c)
        # bisection in u = sqrt(a - a_c): h is increasing in a on the branch
        lo = np.zeros(d.shape)
        hi = np.full(d.shape, np.sqrt(self.a_max - a_c))
        for _ in range(_BISECT):
            um = 0.5 * (lo + hi)
            am = a_c + um * um
            up = self._g(am) - beta * np.sqrt(am) >= d
            hi = np.where(up, um, hi)
            lo = np.where(up, lo, um)
        a = a_c + hi * hi
        for _ in range(_NEWTON):
            ha = self._gp(a) - beta / (2.0 * np.sqrt(a))
            step = np.where(np.isfinite(ha) & (ha > 0),
                            (self._g(a) - beta * np.sqrt(a) - d)
                            / np.where(np.isfinite(ha) & (ha > 0), ha, 1.0), 0.0)
            a = np.clip(a - step, a_c, self.a_max)
        return np.where(on, a, np.nan)

    def _integral(self, a: np.ndarray) -> np.ndarray:
        return np.where(a > self.b, self.profile._g_integral(np.maximum(a, self.b), self.rtol),
                        0.0)

    def force(self, delta: np.ndarray, E_star: float, w: float
              ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """Force (N) and ``dF/dδ``, ``dF/dE*``, ``dF/dΔγ`` (zeros where apart)."""
        a = self.radius(delta, E_star, w)
        on = np.isfinite(a)
        a = np.where(on, a, self.b)
        F = 2.0 * E_star * (a * delta - self._integral(a))
        s = np.sqrt(2.0 * np.pi * w * a / E_star)
        ha = self._gp(a) - s / (2.0 * a)
        ok = on & np.isfinite(ha) & (ha > 0)
        inv = np.where(ok, 1.0 / np.where(ok, ha, 1.0), 0.0)
        z = np.zeros_like(F)
        return (np.where(on, F, z), np.where(on, 2.0 * E_star * (a - s * inv), z),
                np.where(on, F / E_star + s * s * inv, z), np.where(on, -2.0 * np.pi * a * inv, z))

    def branch_end(self, E_star: float, w: float) -> tuple[float, float]:
        """Force (N) and indentation (m) at the end of the branch."""
        a_c, d_c = self.critical(E_star, w)
        return float(2.0 * E_star * (a_c * d_c - self._integral(np.array([a_c]))[0])), d_c
