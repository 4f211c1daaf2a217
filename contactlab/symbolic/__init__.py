"""Symbolic (sympy) route: exact MDR transforms of power-law sums and formula export."""
from .form import SympyForm
from .formulas import FormulaSet, contact_formulas, profile_formulas
from .transform import g_expression, g_callable, kappa, kappa_sympy

__all__ = ["g_expression", "g_callable", "kappa", "kappa_sympy", "FormulaSet", "SympyForm",
           "profile_formulas", "contact_formulas"]
