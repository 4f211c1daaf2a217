"""Fitting measured curves with the MDR's exact derivatives.

* :func:`indentation`: Young's modulus, contact point and force offset of a normal indentation
  curve, for any axisymmetric tip without a wall (closed forms, the exact sphere, cones,
  measured tables, sums);
* :func:`tangential_loop`, :func:`torsion_loop`: friction coefficient and shear modulus of
  steady hysteresis loops at a known normal force (Cattaneo-Mindlin and Jäger with Masing's
  rule, exact);
* :func:`tangential_loop`, :func:`torsion_loop`: friction coefficient and shear modulus of
  steady hysteresis loops at a known normal force (Cattaneo-Mindlin and Jäger with Masing's
  rule, exact);
* :class:`FitResult`: the parameters, standard errors, covariance, confidence intervals, the
  fitted contact, residuals and the result protocol.

scipy.optimize is imported at the first fit.
"""
from __future__ import annotations

from .indentation import indentation
from .loops import tangential_loop, torsion_loop
from .result import FitResult

__all__ = ["FitResult", "indentation", "tangential_loop", "torsion_loop"]
