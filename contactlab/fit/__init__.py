"""Fitting measured curves with the MDR's exact derivatives.

* :func:`indentation`: Young's modulus, contact point and force offset of a normal indentation
  curve, for any axisymmetric tip without a wall (closed forms, the exact sphere, cones,
  measured tables, sums);
* :class:`FitResult`: the parameters, standard errors, covariance, confidence intervals, the
  fitted contact, residuals and the result protocol.

scipy.optimize is imported at the first fit.
"""
from __future__ import annotations

from .indentation import indentation
from .result import FitResult

__all__ = ["FitResult", "indentation"]
