"""contactlab: exact axisymmetric contact mechanics with the Method of Dimensionality Reduction.

Public entry points: :class:`Contact`, :class:`Elastic`, :class:`Rigid`, :class:`LoadPath`, the
:mod:`contactlab.profiles` and :mod:`contactlab.materials` subpackages and :mod:`contactlab.errors`.
Importing contactlab does no sympy work and scans no plugins.
"""
from . import errors, materials, profiles, registry
from ._lazy import attach as _attach
from ._version import __version__
from .contact import Contact
from .materials import Elastic, Rigid, effective_moduli
from .params import memory_budget, set_memory_budget, set_time_budget, time_budget
from .registry import register_material, register_profile

__all__ = [
    "Contact", "Elastic", "Rigid", "effective_moduli", "LoadPath",
    "NormalState", "AdhesiveNormalState", "AdhesionCycle", "ViscoelasticHistory",
    "TangentialState", "ShiftHistory", "PathResult", "TorsionState", "TwistHistory",
    "ContactLaw", "LawStep",
    "profiles", "materials", "errors", "fit", "foundation", "loadpath", "registry",
    "register_profile", "register_material", "sweep", "memory_budget", "set_memory_budget",
    "time_budget", "set_time_budget", "fretting_map_sweep",
    "cite", "citations",
    "__version__",
]

# imported on first use (start-up time; ``import contactlab`` needs none of them; the names are
# listed for type checkers in __init__.pyi). The sweep machinery alone pulls in multiprocessing
# and concurrent.futures (~0.03 s); the effect drivers, foundations and load paths ~0.03 s together
__getattr__, __dir__, _LAZY = _attach(
    __name__,
    submodules=["citations", "fit", "foundation", "loadpath", "physics"],
    submod_attrs={
        "citations": ["cite"],
        "loadpath": ["LoadPath"],
        "effects": ["NormalState", "AdhesiveNormalState", "AdhesionCycle", "ViscoelasticHistory",
                    "TangentialState", "ShiftHistory", "PathResult", "TorsionState",
                    "TwistHistory"],
        "effects.law": ["ContactLaw", "LawStep"],
        "sweeps": ["sweep", "fretting_map_sweep"],
    },
)
