"""Numerical building blocks: vectorised adaptive quadrature, bracketed root finding and row sums
in a fixed order (:mod:`.fixed_sums`: a point's sum does not depend on its batch)."""
from .quadrature import QuadratureResult, tanh_sinh
from .roots import bracketed_root

__all__ = ["QuadratureResult", "tanh_sinh", "bracketed_root"]
