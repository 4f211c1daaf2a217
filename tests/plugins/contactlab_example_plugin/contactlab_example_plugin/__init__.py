"""Example contactlab plugin (the worked example of docs/plugins.md).

* :class:`Quartic` defines only its height ``f(r) = c r**4``: contactlab supplies the transform
  (quadrature), normal contact, torsion, ... for free.
* :class:`RoundedCone` (``f = s r + r²/(2R)``) also supplies ``power_terms()``, which turns on the
  exact symbolic route: ``g`` by κ_n, closed-form force, and ``formulas()``.
* :class:`Incompressible` is a material given by its shear modulus only (ν = 1/2).
"""
from __future__ import annotations

from typing import ClassVar

import numpy as np

from contactlab.materials import Material
from contactlab.params import Param
from contactlab.profiles import Profile

__all__ = ["Quartic", "RoundedCone", "Incompressible"]


class Quartic(Profile):
    """Quartic profile ``f(r) = c r**4`` defined by its height only.

    Parameters
    ----------
    c : float
        Coefficient, 1/m³ (> 0).
    """

    name: ClassVar[str] = "quartic"
    params: ClassVar[tuple[Param, ...]] = (
        Param("c", "c", "m^-3", "positive", "quartic coefficient c", (1e3, 1e12)),
    )

    def __init__(self, c: float) -> None:
        self.c = self.params[0].check(c)

    def _height(self, r: np.ndarray) -> np.ndarray:
        return self.c * r**4

    def _length_scale(self) -> float:
        return self.c ** (-1.0 / 3.0)


class RoundedCone(Profile):
    """Cone with a parabolic tip, ``f(r) = slope r + r²/(2R)``, with an exact symbolic form.

    Parameters
    ----------
    slope : float
        Cone slope, dimensionless (> 0).
    R : float
        Tip radius of curvature, m (> 0).
    """

    name: ClassVar[str] = "rounded_cone"
    params: ClassVar[tuple[Param, ...]] = (
        Param("slope", "s", "1", "positive", "cone slope", (1e-3, 1.0)),
        Param("R", "R", "m", "positive", "tip radius of curvature", (1e-6, 1.0)),
    )

    def __init__(self, slope: float, R: float) -> None:
        self.slope = self.params[0].check(slope)
        self.R = self.params[1].check(R)

    def _height(self, r: np.ndarray) -> np.ndarray:
        return self.slope * r + r**2 / (2 * self.R)

    def _slope(self, r: np.ndarray) -> np.ndarray:
        return self.slope + r / self.R

    def power_terms(self) -> list[tuple[float, float]]:
        return [(self.slope, 1.0), (1.0 / (2 * self.R), 2.0)]

    def _height_sympy(self, r, slope, R):
        """The same height with sympy symbols: formulas() then keeps ``s`` and ``R``."""
        return slope * r + r**2 / (2 * R)


class Incompressible(Material):
    """Incompressible linear elastic body (ν = 1/2) given by its shear modulus.

    Parameters
    ----------
    G : float
        Shear modulus, Pa (> 0).
    """

    name: ClassVar[str] = "incompressible"
    params: ClassVar[tuple[Param, ...]] = (
        Param("G", "G", "Pa", "positive", "shear modulus G", (1e3, 1e11)),
    )

    def __init__(self, G: float) -> None:
        self.G = self.params[0].check(G)

    def _compliances(self) -> tuple[float, float, float]:
        # (1-ν²)/E with E = 3G, (2-ν)/(4G), 1/G  at ν = 1/2
        return (0.75 / (3.0 * self.G), 1.5 / (4.0 * self.G), 1.0 / self.G)
