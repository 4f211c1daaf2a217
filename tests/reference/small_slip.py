"""Cattaneo–Mindlin force of an MDR contact at small displacement, in 40-digit arithmetic.

MDR (V. L. Popov, M. Heß, Method of Dimensionality Reduction in Contact Mechanics and Friction,
Springer 2015, ch. 3 and 5): the springs of the equivalent 1D profile ``g`` stick for
``|x| < c`` with ``g(c) = d - G* u/(μE*)`` and slide with force ``μE* (d - g(x)) dx`` outside,
so ``F_x = 2G* c u + 2μE* ∫_c^a (d - g(x)) dx``; ``F_x -> 2G* a u`` as ``u -> 0``.

Here ``c`` is found by bisection and the integral by mpmath's tanh-sinh quadrature (split at the
knots of a table), both at 40 digits, from the same double-precision ``a``, ``d`` the code
starts from. Nothing here imports contactlab.
"""
from __future__ import annotations

import mpmath as mp

__all__ = ["g_sphere", "g_cone", "g_paraboloid_cone", "g_linear_table", "mindlin_force"]


def g_sphere(R):
    """``g(x) = x artanh(x/R)`` of the exact sphere."""
    R = mp.mpf(R)
    return lambda x: x * mp.atanh(x / R)


def g_cone(s):
    """``g(x) = (π/2) s x`` of the cone ``f = s r``."""
    s = mp.mpf(s)
    return lambda x: mp.pi / 2 * s * x


def g_paraboloid_cone(R, s):
    """``g = x²/R + (π/2) s x`` of ``r²/(2R) + s r`` (MDR is linear in the profile)."""
    R, s = mp.mpf(R), mp.mpf(s)
    return lambda x: x * x / R + mp.pi / 2 * s * x


def g_linear_table(r, f):
    """``g(x) = x ∫_0^x f'(t)/sqrt(x² - t²) dt`` of the piecewise-linear interpolant through
    ``(r, f)`` (``r[0] = 0``): ``x Σ_j s_j [asin(min(r_j+1, x)/x) - asin(min(r_j, x)/x)]``."""
    r = [mp.mpf(float(v)) for v in r]
    f = [mp.mpf(float(v)) for v in f]
    slopes = [(f[j + 1] - f[j]) / (r[j + 1] - r[j]) for j in range(len(r) - 1)]

    def g(x):
        tot = mp.mpf(0)
        for j, s in enumerate(slopes):
            if r[j] >= x:
                break
            tot += s * (mp.asin(min(r[j + 1], x) / x) - mp.asin(r[j] / x))
        return x * tot
    g.knots = r
    return g


def mindlin_force(g, a, d, u, E_star, G_star, mu, digits=40):
    """``F_x`` (float) at displacement ``u >= 0`` for the contact radius ``a`` and depth ``d``."""
    with mp.workdps(digits):
        a, d, u = mp.mpf(a), mp.mpf(d), mp.mpf(u)
        E_star, G_star, mu = mp.mpf(E_star), mp.mpf(G_star), mp.mpf(mu)
        target = d - G_star * u / (mu * E_star)
        if g(a) <= target:
            c = a
        else:
            lo, hi = mp.mpf(0), a
            for _ in range(digits * 4):
                mid = (lo + hi) / 2
                if g(mid) < target:
                    lo = mid
                else:
                    hi = mid
            c = (lo + hi) / 2
        pts = [c] + [k for k in getattr(g, "knots", []) if c < k < a] + [a]
        slip = mp.quad(lambda x: d - g(x), pts) if c < a else mp.mpf(0)
        return float(2 * G_star * c * u + 2 * mu * E_star * slip)
