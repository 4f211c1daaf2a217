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

__all__ = ["JKRFlat", "JKRFlatTable"]

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

    def __init__(self, profile: Any, a_max: float, rtol: float = 1e-12,
                 b: float | None = None) -> None:
        self.profile, self.a_max, self.rtol = profile, float(a_max), rtol
        self.b = float(profile.flat_radius if b is None else b)
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


class JKRFlatTable(JKRFlat):
    """:class:`JKRFlat` for a measured flat-centred tip (a linear table whose heights are zero
    up to ``b``): ``g`` as a cubic Hermite interpolant in ``u = sqrt(a - b)``, where it is
    smooth at the flat's edge (``g ~ u`` there), through the table's exact ``g`` and slope
    ``dg/du = 2u g'(a)`` at the nodes; ``g'(a) = (dg/du)/(2u)`` (infinite at the edge) and
    ``∫_b^a g = ∫ g(u) 2u du`` exactly per piece. ``error``: the interpolant's largest relative
    error in ``g``, measured at the interval midpoints against the table's exact ``g``.

    Parameters
    ----------
    profile : Profile
        The measured tip (``profile.has("linear_table")``).
    a_max : float
        Largest contact radius the fit may need, m.
    rtol : float
        Tolerance of the profile's routes.
    b : float
        Radius of the flat centre, m.
    nodes : int
        Nodes of the interpolant.
    """

    def __init__(self, profile: Any, a_max: float, rtol: float = 1e-12, b: float = 0.0,
                 nodes: int = 2049) -> None:
        super().__init__(profile, a_max, rtol, b)
        key = ("jkr_flat", nodes, a_max, b)
        cache = profile.__dict__.setdefault("_fit_tip_tables", {})
        if key not in cache:
            u = np.sqrt(a_max - b) * np.linspace(0.0, 1.0, nodes)
            g, gp = profile._g_and_slope(b + u * u)
            g = np.asarray(g, float).copy()
            g[0] = 0.0
            with np.errstate(invalid="ignore"):
                m = 2.0 * u * np.asarray(gp, float)
            # dg/du at the edge: g = s a acos(b/a) + (smoother terms) ~ s sqrt(2b) u, with s
            # the table's slope just beyond the flat
            k = int(np.searchsorted(profile.r, b))
            m[0] = float(profile._slopes[min(k, profile._slopes.size - 1)]) * np.sqrt(2.0 * b)
            h = np.diff(u)
            bad = ~np.isfinite(m)               # a node on a table node's square-root cusp
            if np.any(bad):
                sec = np.diff(g) / h
                i = np.flatnonzero(bad)
                m[i] = 0.5 * (sec[np.maximum(i - 1, 0)] + sec[np.minimum(i, sec.size - 1)])
            # ∫ g 2u du per piece: the cubic's power coefficients times (u_k + h t), exactly
            c0, c1 = g[:-1], h * m[:-1]
            c2 = 3.0 * (g[1:] - g[:-1]) - h * (2.0 * m[:-1] + m[1:])
            c3 = 2.0 * (g[:-1] - g[1:]) + h * (m[:-1] + m[1:])
            piece = 2.0 * h * (u[:-1] * (c0 + c1 / 2 + c2 / 3 + c3 / 4)
                               + h * (c0 / 2 + c1 / 3 + c2 / 4 + c3 / 5))
            cum = np.concatenate([[0.0], np.cumsum(piece)])
            um = 0.5 * (u[1:] + u[:-1])
            gm = np.asarray(profile._g_and_slope(b + um * um)[0], float)
            val = 0.5 * (g[:-1] + g[1:]) + h * (m[:-1] - m[1:]) / 8
            inner = gm > 1e-6 * g[-1]
            err = float(np.max(np.abs(val - gm)[inner] / gm[inner], initial=0.0))
            cache[key] = (u, g, m, cum, err)
        self._u, self._gn, self._mn, self._In, self.error = cache[key]

    def _cubic(self, a: np.ndarray) -> tuple[np.ndarray, ...]:
        un = self._u
        uu = np.sqrt(np.clip(a - self.b, 0.0, None))
        k = np.clip(np.searchsorted(un, uu, side="right") - 1, 0, un.size - 2)
        h = un[k + 1] - un[k]
        t = (uu - un[k]) / h
        y0, y1, m0, m1 = self._gn[k], self._gn[k + 1], self._mn[k], self._mn[k + 1]
        c0, c1 = y0, h * m0
        c2 = 3.0 * (y1 - y0) - h * (2.0 * m0 + m1)
        c3 = 2.0 * (y0 - y1) + h * (m0 + m1)
        return uu, un[k], h, t, c0, c1, c2, c3, k

    def _g(self, a: np.ndarray) -> np.ndarray:
        _, _, _, t, c0, c1, c2, c3, _ = self._cubic(a)
        return np.where(a > self.b, c0 + t * (c1 + t * (c2 + t * c3)), 0.0)

    def _gp(self, a: np.ndarray) -> np.ndarray:
        uu, _, h, t, _, c1, c2, c3, _ = self._cubic(a)
        dgdu = (c1 + t * (2.0 * c2 + 3.0 * t * c3)) / h
        with np.errstate(divide="ignore", invalid="ignore"):
            gp = dgdu / (2.0 * uu)
        return np.where(uu > 0, gp, np.inf)

    def _integral(self, a: np.ndarray) -> np.ndarray:
        _, u0, h, t, c0, c1, c2, c3, k = self._cubic(a)
        part = 2.0 * h * (u0 * t * (c0 + t * (c1 / 2 + t * (c2 / 3 + t * c3 / 4)))
                          + h * t * t * (c0 / 2 + t * (c1 / 3 + t * (c2 / 4 + t * c3 / 5))))
        return np.where(a > self.b, self._In[k] + part, 0.0)
