"""contactlab: exact axisymmetric contact mechanics with the Method of Dimensionality Reduction.

Public entry points: :class:`Contact`, :class:`Elastic`, :class:`Rigid`, the
:mod:`contactlab.profiles` and :mod:`contactlab.materials` subpackages and :mod:`contactlab.errors`.
Importing contactlab does no sympy work and scans no plugins.
"""
from . import errors, materials, profiles
from .contact import Contact
from .materials import Elastic, Rigid, effective_moduli
from .states import NormalState
from .torsion import TorsionState, TwistHistory

__version__ = "0.1.0"

__all__ = ["Contact", "Elastic", "Rigid", "effective_moduli", "NormalState", "profiles",
           "materials", "errors", "__version__"]
__all__ += ["TorsionState", "TwistHistory"]
