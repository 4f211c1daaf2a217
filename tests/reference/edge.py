"""Surface displacement just outside the contact edge and shear on the axis, at 40 digits.

Without importing contactlab. Sources: the displacement outside a power-law contact
``u(r) = (2d/π) asin(a/r) - (2/π) ∫_0^a g(x)/sqrt(r²-x²) dx`` with ``g = κ_n c x**n`` [H1, PH]
(the integral as Gauss's series ``₂F₁(1/2, (n+1)/2; (n+3)/2; a²/r²)``, which mpmath evaluates to
full precision up to its branch point); the Ciavarella–Jäger stick-zone traction
``τ = μ(p_a - p_c)`` with the MDR pressure ``p = (E*/π) ∫_r^a g'(x)/sqrt(x²-r²) dx`` [H1].
"""
from __future__ import annotations

import mpmath as mp

from .kappa import kappa

DPS = 40


def power_law_displacement(c, n, a, d, r):
    """``u_z(r)``, m, for ``r > a`` of ``f = c r**n`` at contact radius ``a`` and depth ``d``."""
    with mp.workdps(DPS):
        c, n, a, d, r = map(mp.mpf, (c, n, a, d, r))
        k = kappa(n)
        A = 2 * k * c / mp.pi * a ** (n + 1) / (r * (n + 1)) * mp.hyp2f1(
            mp.mpf(1) / 2, (n + 1) / 2, (n + 3) / 2, (a / r) ** 2)
        return 2 * d / mp.pi * mp.asin(a / r) - A


def displacement_by_quadrature(g, a, d, r):
    """``u_z(r)``, m, for ``r > a`` of any profile with transformed profile ``g`` (mpmath
    function): ``(2/π)[d θ_a - ∫_0^{θ_a} g(r sinθ) dθ]``, ``θ_a = asin(a/r)``."""
    with mp.workdps(DPS):
        a, d, r = map(mp.mpf, (a, d, r))
        th = mp.asin(a / r)
        return 2 / mp.pi * (d * th - mp.quad(lambda t: g(r * mp.sin(t)), [0, th]))


def power_law_axis_shear(mu, E_star, c, n, a, c_stick):
    """``τ(0)``, Pa, of ``f = c r**n``: ``μ(E*/π) ∫_c^a g'(x)/x dx`` with ``g' = nκ_n c x**(n-1)``,
    i.e. ``μ(E*/π) nκ_n c (a**(n-1) - c**(n-1))/(n-1)`` (``μ(E*/π) κ_1 c ln(a/c)`` for n = 1).

    Derivation: for ``r < c``, ``p_a(r) - p_c(r) = (E*/π) ∫_c^a g'(x)/sqrt(x²-r²) dx`` (the
    integrals over ``[r, c]`` cancel; no edge terms, ``d = g(a)`` and ``g(c)``); the remaining
    integrand is bounded for ``r → 0`` because ``x >= c > 0``, so ``τ(0)`` is this finite limit
    even where ``p_a(0)`` and ``p_c(0)`` are infinite (n <= 1).
    """
    with mp.workdps(DPS):
        mu, E, c, n, a, cs = map(mp.mpf, (mu, E_star, c, n, a, c_stick))
        k = kappa(n)
        if n == 1:
            integral = k * c * mp.log(a / cs)
        else:
            integral = n * k * c * (a ** (n - 1) - cs ** (n - 1)) / (n - 1)
        return mu * E / mp.pi * integral
