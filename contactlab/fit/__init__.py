"""Fitting measured curves with the MDR's exact derivatives.

* :func:`indentation`: Young's modulus, contact point and force offset of a normal indentation
  curve, for any axisymmetric tip without a wall (closed forms, the exact sphere, cones,
  measured tables, sums);
  (adhesion: JKR by Heß's rule, DMT; viscoelastic samples with ``time=``: Lee-Radok and
  Ting);
* :func:`tangential_loop`, :func:`torsion_loop`: friction coefficient and shear modulus of
  steady hysteresis loops at a known normal force (Cattaneo-Mindlin and Jäger with Masing's
  rule, exact; any tip, flat punches and profiles rising to a wall included);
* :func:`read_curve`: a curve from a CSV file (units in the header) or an AFM instrument file
  (through ``afmformats``, the extra ``afm``);
* :class:`FitResult`: the parameters, standard errors, covariance, confidence intervals, the
  fitted contact, residuals and the result protocol.

scipy.optimize is imported at the first fit.
"""
from __future__ import annotations

from .indentation import indentation
from .io import Curve, read_curve
from .loops import tangential_loop, torsion_loop
from .result import FitResult

__all__ = ["Curve", "FitResult", "indentation", "read_curve", "tangential_loop", "torsion_loop"]
