"""Tolerances of the conformance checks, each with its reason.

A subclass of a check mixin may override the matching class attribute (``rtol_transform``, ...)
when its profile is known to be less accurate, and should say why.
"""
from __future__ import annotations

__all__ = ["TRANSFORM", "INVERSE", "ROUND_TRIP", "FLOOR"]

#: g(x) against scipy quad (epsrel 1e-12) of x ∫_0^{π/2} f'(x sinθ) dθ: the package's default
#: quadrature rtol is 1e-10; rounding near slope jumps and finite-difference slopes of
#: height-only profiles (~1e-10) leave a margin of 10
TRANSFORM = 1e-9
#: inverse transform (2/π)∫_0^{π/2} g(r sinθ) dθ, a quadrature of a quadrature at rtol 1e-10,
#: against f(r); measured <= 1e-11 for the built-ins
INVERSE = 1e-8
#: normal(force=F).depth against the depth that gave F: the radius solve is converged to a
#: relative bracket of 1e-15 and the force is a smooth function of it; quadrature routes add
#: the 1e-10 default rtol
ROUND_TRIP = 1e-9
#: absolute floor of relative comparisons, as a fraction of the largest value compared (values
#: that are exactly zero, e.g. g inside a flat punch, are compared against this)
FLOOR = 1e-12
