"""contactlab: exact axisymmetric contact mechanics with the Method of Dimensionality Reduction.

Public entry points: :class:`Contact`, :class:`Elastic`, :class:`Rigid`, :class:`LoadPath`, the
:mod:`contactlab.profiles` and :mod:`contactlab.materials` subpackages and :mod:`contactlab.errors`.
Importing contactlab does no sympy work and scans no plugins.
"""
import importlib as _importlib
import typing as _typing

from . import errors, materials, profiles, registry
from .contact import Contact
from .materials import Elastic, Rigid, effective_moduli
from .params import memory_budget, set_memory_budget
from .registry import register_material, register_profile

if _typing.TYPE_CHECKING:   # resolved on first use by the module __getattr__ below
    from . import citations, fit, foundation, loadpath
    from .citations import cite
    from .effects import (AdhesionCycle, AdhesiveNormalState, NormalState, PathResult,
                          ShiftHistory, TangentialState, TorsionState, TwistHistory,
                          ViscoelasticHistory)
    from .effects.law import ContactLaw, LawStep
    from .loadpath import LoadPath
    from .sweeps import fretting_map_sweep, sweep

__version__ = "0.1.0"

__all__ = [
    "Contact", "Elastic", "Rigid", "effective_moduli", "LoadPath",
    "NormalState", "AdhesiveNormalState", "AdhesionCycle", "ViscoelasticHistory",
    "TangentialState", "ShiftHistory", "PathResult", "TorsionState", "TwistHistory",
    "ContactLaw", "LawStep",
    "profiles", "materials", "errors", "fit", "foundation", "loadpath", "registry",
    "register_profile", "register_material", "sweep", "memory_budget", "set_memory_budget",
    "fretting_map_sweep",
    "cite", "citations",
    "__version__",
]

#: imported on first use (start-up time; ``import contactlab`` needs none of them): subpackage ->
#: None, name -> the module defining it. The sweep machinery alone pulls in multiprocessing and
#: concurrent.futures (~0.03 s); the effect drivers, foundations and load paths ~0.03 s together
_LAZY: "dict[str, str | None]" = {
    "citations": None, "fit": None, "foundation": None, "loadpath": None, "physics": None,
    "cite": ".citations", "LoadPath": ".loadpath",
    "NormalState": ".effects", "AdhesiveNormalState": ".effects", "AdhesionCycle": ".effects",
    "ViscoelasticHistory": ".effects", "TangentialState": ".effects", "ShiftHistory": ".effects",
    "PathResult": ".effects", "TorsionState": ".effects", "TwistHistory": ".effects",
    "ContactLaw": ".effects.law", "LawStep": ".effects.law",
    "sweep": ".sweeps", "fretting_map_sweep": ".sweeps",
}


def __getattr__(name: str) -> object:
    try:
        home = _LAZY[name]
    except KeyError:
        raise AttributeError(f"module 'contactlab' has no attribute {name!r}") from None
    if home is None:                        # a subpackage: importing it binds the attribute
        return _importlib.import_module(f".{name}", __name__)
    value = getattr(_importlib.import_module(home, __name__), name)
    globals()[name] = value                 # later lookups are plain module attributes
    return value


def __dir__() -> "list[str]":
    return sorted(set(globals()) | set(_LAZY))
