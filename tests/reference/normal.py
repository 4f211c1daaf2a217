"""Independent reference implementations of normal-contact closed forms (theory §2-3).

Written with mpmath at 30 digits, from the published formulas, without importing contactlab.
Sources: Hertz / Boussinesq / Sneddon [Sn65], power laws [H1, PH], exact sphere [PH].
"""
from __future__ import annotations

import mpmath as mp

from .kappa import kappa  # noqa: F401 (re-exported: ref.kappa)

mp.mp.dps = 30



def hertz(E, R, d):
    """Paraboloid f = r²/(2R): a, F, p(r) callable, u_outside(r) callable."""
    E, R, d = map(mp.mpf, (E, R, d))
    a = mp.sqrt(R * d)
    F = 4 * E * a**3 / (3 * R)

    def p(r):
        r = mp.mpf(r)
        return 2 * E / (mp.pi * R) * mp.sqrt(a**2 - r**2) if r < a else mp.mpf(0)

    def u(r):
        r = mp.mpf(r)
        return ((2 * a**2 - r**2) * mp.asin(a / r) + a * mp.sqrt(r**2 - a**2)) / (mp.pi * R)

    return a, F, p, u


def power_law(E, c, n, a):
    """f = c r^n at contact radius a: d, F, p(r), u_outside(r) (theory §3 table)."""
    E, c, n, a = map(mp.mpf, (E, c, n, a))
    k = kappa(n)
    d = k * c * a**n
    F = 2 * E * k * c * a ** (n + 1) * n / (n + 1)

    def p(r):
        rho = mp.mpf(r) / a
        return E * n * k * c * a ** (n - 1) / mp.pi * mp.sqrt(1 - rho**2) * mp.hyp2f1(
            1 - n / 2, 1, mp.mpf(3) / 2, 1 - rho**2)

    def u(r):
        r = mp.mpf(r)
        return 2 * k * c / mp.pi * (a**n * mp.asin(a / r) - a ** (n + 1) / (r * (n + 1)) * mp.hyp2f1(
            mp.mpf(1) / 2, (n + 1) / 2, (n + 3) / 2, a**2 / r**2))

    return d, F, p, u


def cone(E, slope, a):
    """f = slope r: d, F, p(r), u_outside(r)."""
    E, s, a = map(mp.mpf, (E, slope, a))
    d = mp.pi / 2 * a * s
    F = mp.pi / 2 * E * a**2 * s

    def p(r):
        return E * s / 2 * mp.acosh(a / mp.mpf(r))

    def u(r):
        r = mp.mpf(r)
        return s * (a * mp.asin(a / r) - r + mp.sqrt(r**2 - a**2))

    return d, F, p, u


def flat_punch(E, b, d):
    """Boussinesq flat punch: F, p(r), u_outside(r)."""
    E, b, d = map(mp.mpf, (E, b, d))

    def p(r):
        return E * d / (mp.pi * mp.sqrt(b**2 - mp.mpf(r) ** 2))

    def u(r):
        return 2 * d / mp.pi * mp.asin(b / mp.mpf(r))

    return 2 * E * b * d, p, u


def sphere(E, R, a):
    """Exact spherical cap: d, F (theory §3 table); pressure by mp.quad of the MDR integral."""
    E, R, a = map(mp.mpf, (E, R, a))
    d = a / 2 * mp.log((R + a) / (R - a))
    F = E * ((a**2 + R**2) / 2 * mp.log((R + a) / (R - a)) - a * R)

    def gprime(x):
        return mp.atanh(x / R) + x * R / (R**2 - x**2)

    def p(r):
        r = mp.mpf(r)
        return E / mp.pi * mp.quad(lambda u: gprime(r * mp.cosh(u)), [0, mp.acosh(a / r)])

    def u(r):
        r = mp.mpf(r)
        th = mp.asin(a / r)
        return 2 / mp.pi * mp.quad(lambda t: d - r * mp.sin(t) * mp.atanh(r * mp.sin(t) / R), [0, th])

    return d, F, p, u


def transform_quad(fprime, x, breaks=()):
    """g(x) = x ∫_0^{π/2} f'(x sinθ) dθ by mpmath quadrature (split at asin(b/x))."""
    x = mp.mpf(x)
    pts = [mp.mpf(0)] + [mp.asin(mp.mpf(b) / x) for b in breaks if b < x] + [mp.pi / 2]
    return x * mp.quad(lambda t: fprime(x * mp.sin(t)), pts)
