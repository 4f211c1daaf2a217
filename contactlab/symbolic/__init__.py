"""Symbolic (sympy) route: exact MDR transforms of power-law sums and formula export."""
from .transform import g_expression, g_callable, kappa, kappa_sympy

__all__ = ["g_expression", "g_callable", "kappa", "kappa_sympy"]
