"""Linear elastic and rigid materials."""
from __future__ import annotations

from typing import ClassVar

from ..params import MODULUS_BOUNDS, Param, check_in_range
from .base import Material

__all__ = ["Elastic", "Rigid"]


class Elastic(Material):
    """Isotropic linear elastic material.

    Parameters
    ----------
    E : float
        Young's modulus, Pa, in ``[1e-10, 1e20]`` (:data:`contactlab.params.MODULUS_BOUNDS`).
    nu : float
        Poisson's ratio, ``-1 < nu <= 0.5``.

    Examples
    --------
    >>> from contactlab import Elastic
    >>> Elastic(E=210e9, nu=0.3).G
    80769230769.23077
    """

    name: ClassVar[str] = "elastic"
    params: ClassVar[tuple[Param, ...]] = (
        Param("E", "E", "Pa", "positive", "Young's modulus E", (1e3, 1e12), MODULUS_BOUNDS),
        Param("nu", "nu", "1", "real", "Poisson's ratio", (0.0, 0.5)),
    )
    #: a scene's [materials] table may give the shear modulus G instead of E
    #: (:meth:`from_shear_modulus`)
    scene_keys: ClassVar[dict[str, str]] = {"G": "quantity:pressure"}
    scene_one_of: ClassVar[tuple[tuple[str, ...], ...]] = (("E",), ("G",))

    def __init__(self, E: float, nu: float) -> None:
        self.E = self.params[0].check(E)
        self.nu = check_in_range("nu", nu, -1.0, 0.5, low_open=True, high_open=False,
                                 what="Poisson's ratio")

    @classmethod
    def from_shear_modulus(cls, G: float, nu: float) -> "Elastic":
        """Material from shear modulus ``G`` (Pa, > 0) and Poisson's ratio: ``E = 2G(1+ν)``."""
        G = Param("G", "G", "Pa", "positive", "shear modulus G",
                  bounds=MODULUS_BOUNDS).check(G)
        nu_v = check_in_range("nu", nu, -1.0, 0.5, low_open=True, high_open=False,
                              what="Poisson's ratio")
        return cls(E=2.0 * G * (1.0 + nu_v), nu=nu_v)

    @property
    def G(self) -> float:
        """Shear modulus ``E/(2(1+ν))``, Pa."""
        return self.E / (2.0 * (1.0 + self.nu))

    def _compliances(self) -> tuple[float, float, float]:
        return ((1.0 - self.nu**2) / self.E, (2.0 - self.nu) / (4.0 * self.G), 1.0 / self.G)


class Rigid(Material):
    """A rigid body (all compliances zero: ``1/E = 1/G = 0`` 1/Pa)."""

    name: ClassVar[str] = "rigid"
    params: ClassVar[tuple[Param, ...]] = ()

    def _compliances(self) -> tuple[float, float, float]:
        return (0.0, 0.0, 0.0)
