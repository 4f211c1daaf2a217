"""contactlab: exact axisymmetric contact mechanics with the Method of Dimensionality Reduction.

Public entry points: :class:`Contact`, :class:`Elastic`, :class:`Rigid`, :class:`LoadPath`, the
:mod:`contactlab.profiles` and :mod:`contactlab.materials` subpackages and :mod:`contactlab.errors`.
Importing contactlab does no sympy work and scans no plugins.
"""
from . import citations, errors, foundation, loadpath, materials, profiles
from .citations import cite
from .contact import Contact
from .effects import (AdhesionCycle, AdhesiveNormalState, NormalState, PathResult, ShiftHistory,
                      TangentialState, TorsionState, TwistHistory, ViscoelasticHistory)
from .effects.law import ContactLaw, LawStep
from .loadpath import LoadPath
from .materials import Elastic, Rigid, effective_moduli
from .params import memory_budget, set_memory_budget
from . import registry
from .registry import register_material, register_profile

__version__ = "0.1.0"

__all__ = [
    "Contact", "Elastic", "Rigid", "effective_moduli", "LoadPath",
    "NormalState", "AdhesiveNormalState", "AdhesionCycle", "ViscoelasticHistory",
    "TangentialState", "ShiftHistory", "PathResult", "TorsionState", "TwistHistory",
    "ContactLaw", "LawStep",
    "profiles", "materials", "errors", "foundation", "loadpath", "registry",
    "register_profile", "register_material", "sweep", "memory_budget", "set_memory_budget",
    "fretting_map_sweep",
    "cite", "citations",
    "__version__",
]

#: imported on first use: the sweep machinery pulls in multiprocessing and concurrent.futures
#: (~0.03 s of a 0.15 s import budget) that single-contact users never need
_LAZY_SWEEPS = ("sweep", "fretting_map_sweep")


def __getattr__(name: str):
    if name in _LAZY_SWEEPS:
        from . import sweeps
        return getattr(sweeps, name)
    raise AttributeError(f"module 'contactlab' has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(_LAZY_SWEEPS))
