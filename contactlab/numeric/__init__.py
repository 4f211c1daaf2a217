"""Numerical building blocks: vectorised adaptive quadrature and bracketed root finding."""
from .quadrature import QuadratureResult, tanh_sinh
from .roots import bracketed_root

__all__ = ["QuadratureResult", "tanh_sinh", "bracketed_root"]
