"""Exact MDR transform of sums of power terms, numerically and with sympy.

For ``f(r) = c r**n``, ``g(x) = κ_n c |x|**n`` with
``κ_n = √π Γ(n/2 + 1) / Γ(n/2 + 1/2)`` [H1; PH]. sympy derives κ_n from the transform integral
``κ_n = n ∫_0^{π/2} sin^{n-1}θ dθ``, evaluated through the Beta function (a route that always
terminates), so the symbolic route is independent of the numeric gamma-function one.

References
----------
V. L. Popov, M. Heß, "Method of dimensionality reduction in contact mechanics and friction: a
user's handbook. I. Axially-symmetric contacts", Facta Univ. Mech. Eng. 12 (2014) 1-14.
"""
from __future__ import annotations

import math
from fractions import Fraction
from functools import lru_cache
from collections.abc import Callable

import numpy as np

__all__ = ["kappa", "kappa_sympy", "g_expression", "g_callable"]


@lru_cache(maxsize=1024)
def kappa(n: float) -> float:
    """Numeric ``κ_n = √π Γ(n/2+1)/Γ(n/2+1/2)``.

    Whole-number n up to 600 in closed form with exact integer arithmetic: even
    ``n = 2k``: ``κ = 4^k (k!)² / (2k)!`` (κ_2 = 2, κ_4 = 8/3); odd ``n = 2k+1``:
    ``κ = π (2k+2)! / (4^(k+1) (k+1)! k!)`` (κ_1 = π/2; one more rounding for the factor π).
    Other n: the gamma ratio of :func:`math.gamma` (within 25 ulp measured, n < 300); beyond, the
    asymptotic series ``Γ(z+1)/Γ(z+1/2) = √z (1 + 1/(8z) + 1/(128z²) − 5/(1024z³) −
    21/(32768z⁴) + 399/(262144z⁵) + 869/(4194304z⁶) + …)``, z = n/2 >= 150, whose truncation
    error is below 1e-18 there (a log-gamma difference would lose ~ulp·ln Γ). Memoised
    on ``n`` (a pure function of it, so the cache never changes a result). Standard library
    only: a first normal solve does not wait for scipy.special to import (~0.1 s).
    """
    if float(n).is_integer() and 0 < n <= 600:
        k = int(n) // 2
        if int(n) % 2 == 0:
            return float(Fraction(4 ** k * math.factorial(k) ** 2, math.factorial(2 * k)))
        return math.pi * float(Fraction(math.factorial(2 * k + 2),
                                        4 ** (k + 1) * math.factorial(k + 1) * math.factorial(k)))
    if n < 300:
        return math.sqrt(math.pi) * math.gamma(0.5 * n + 1.0) / math.gamma(0.5 * n + 0.5)
    w = 2.0 / n                                                  # 1/z
    series = 1.0 + w * (1 / 8 + w * (1 / 128 + w * (-5 / 1024 + w * (
        -21 / 32768 + w * (399 / 262144 + w * 869 / 4194304)))))
    return math.sqrt(math.pi * 0.5 * n) * series


@lru_cache(maxsize=256)
def kappa_sympy(n: object):
    """sympy ``κ_n`` from ``n ∫_0^{π/2} sin^{n-1}θ dθ = n B(n/2, 1/2)/2``; exact for rational n."""
    import sympy as sp
    ns = sp.nsimplify(n) if not isinstance(n, sp.Basic) else n
    # ∫_0^{π/2} sin^{2p-1}θ cos^{2q-1}θ dθ = B(p, q)/2 with 2p-1 = n-1, q = 1/2
    integral = sp.beta(ns / 2, sp.Rational(1, 2)) / 2
    return sp.simplify(sp.gammasimp(sp.expand_func(ns * integral)))


@lru_cache(maxsize=256)
def g_expression(terms: tuple[tuple[float, float], ...]):
    """sympy expression of g(x) (symbol ``x``, positive) for ``f = Σ c r**n``."""
    import sympy as sp
    x = sp.Symbol("x", positive=True)
    return sp.Add(*[kappa_sympy(n) * sp.nsimplify(c, rational=False) * x ** sp.nsimplify(n)
                    for c, n in terms])


@lru_cache(maxsize=256)
def g_callable(terms: tuple[tuple[float, float], ...]) -> Callable[[np.ndarray], np.ndarray]:
    """Fast numeric callable of :func:`g_expression` (``lambdify`` with common subexpressions)."""
    import sympy as sp
    x = sp.Symbol("x", positive=True)
    fn = sp.lambdify(x, g_expression(terms), modules="numpy", cse=True)

    def g(xa: np.ndarray) -> np.ndarray:
        return np.asarray(fn(np.asarray(xa, dtype=float)), dtype=float) * np.ones_like(xa, dtype=float)

    return g
