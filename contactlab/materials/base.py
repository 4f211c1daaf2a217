"""The abstract :class:`Material`.

To implement a subclass
-----------------------
1. Declare ``name: ClassVar[str]`` and ``params: ClassVar[tuple[Param, ...]]``; store each
   parameter as an attribute of that name; validate in ``__init__``.
2. Elastic materials implement ``_compliances()`` returning ``(normal, tangential, torsional)``
   compliances: ``(1-ν²)/E``, ``(2-ν)/(4G)`` and ``1/G`` (all 0 for a rigid body).
3. Viscoelastic materials subclass :class:`contactlab.materials.Viscoelastic` (which sets
   ``is_viscoelastic = True``) and implement ``prony()`` returning ``(G_inf, moduli, times, eta)``
   (the Prony form the viscoelastic foundation integrates exactly); ``relaxation(t)``,
   ``glassy_modulus`` and ``relaxed_modulus`` come free from it. Only the pair (viscoelastic,
   rigid) is solvable (an incompressible half-space under a rigid indenter).

Comes free: ``pair(other)`` (effective moduli), ``repr``, ``==``, ``hash``. Both rules are
checked when the class is defined (``PluginError``), so the contract and the solvers agree.
"""
from __future__ import annotations

from abc import ABC
from typing import Any, ClassVar

from ..errors import NotSupportedError, PluginError
from ..params import Param, ParamIdentity

__all__ = ["Material"]

_VISCOELASTIC_MODULE = "contactlab.materials.viscoelastic"


class Material(ParamIdentity, ABC):
    """A homogeneous isotropic body material (half-space model)."""

    name: ClassVar[str] = ""
    params: ClassVar[tuple[Param, ...]] = ()
    is_viscoelastic: ClassVar[bool] = False

    def __init_subclass__(cls, **kwargs: Any) -> None:
        super().__init_subclass__(**kwargs)
        if cls.is_viscoelastic:
            if not any(c.__name__ == "Viscoelastic" and c.__module__ == _VISCOELASTIC_MODULE
                       for c in cls.__mro__):
                raise PluginError(f"viscoelastic material {cls.__qualname__} must subclass "
                                  "contactlab.materials.Viscoelastic and implement prony() "
                                  "(rule: Material contract, item 3).")
        elif cls._compliances is Material._compliances and not getattr(cls, "__abstract__", False):
            raise PluginError(f"material class {cls.__qualname__} must implement _compliances() "
                              "(rule: Material contract, item 2).")

    def _compliances(self) -> tuple[float, float, float]:
        raise NotSupportedError(f"{type(self).__name__} has no elastic compliances.")

    def pair(self, other: "Material"):
        """Effective moduli of this body against ``other``; see :func:`effective_moduli`."""
        from .pair import effective_moduli
        return effective_moduli(self, other)
