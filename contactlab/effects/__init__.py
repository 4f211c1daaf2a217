"""One driver and its result objects per effect.

Each module takes the :class:`~contactlab.Contact` as a parameter (it never imports
``contact.py``), validates and broadcasts, calls the pure kernels of :mod:`contactlab.physics`
(and, for load paths, a foundation of :mod:`contactlab.foundation`) and wraps the arrays in an
immutable result:

* :mod:`~contactlab.effects.normal`: :class:`NormalState`;
* :mod:`~contactlab.effects.adhesion`: :class:`AdhesiveNormalState`, :class:`AdhesionCycle`;
* :mod:`~contactlab.effects.tangential`: :class:`TangentialState`, :class:`ShiftHistory`;
* :mod:`~contactlab.effects.torsion`: :class:`TorsionState`, :class:`TwistHistory`;
* :mod:`~contactlab.effects.viscoelastic`: :class:`ViscoelasticHistory`;
* :mod:`~contactlab.effects.path`: :class:`PathResult` (``contact.simulate``);
* :mod:`~contactlab.effects.fretting`: :class:`FrettingLoop`, :class:`FrettingMap`;
* :mod:`~contactlab.effects.law`: :class:`ContactLaw`, :class:`LawStep` (many contacts, for DEM
  codes; takes plain per-contact arrays instead of a contact);
* :mod:`~contactlab.effects.stress`: :class:`StressField`, :class:`StressMaximum` (subsurface
  stresses of a state: ``state.stress(r, z)``).
"""
import importlib as _importlib
import typing as _typing

if _typing.TYPE_CHECKING:   # the names below resolve on first use (module ``__getattr__``)
    from .adhesion import AdhesionCycle, AdhesiveNormalState
    from .fretting import FrettingLoop, FrettingMap
    from .law import ContactLaw, LawStep
    from .normal import NormalState
    from .path import PathResult
    from .stress import StressField, StressMaximum
    from .tangential import ShiftHistory, TangentialState
    from .torsion import TorsionState, TwistHistory
    from .viscoelastic import ViscoelasticHistory

__all__ = ["NormalState", "AdhesiveNormalState", "AdhesionCycle", "TangentialState",
           "ShiftHistory", "TorsionState", "TwistHistory", "ViscoelasticHistory", "PathResult",
           "FrettingLoop", "FrettingMap", "ContactLaw", "LawStep", "StressField", "StressMaximum"]

#: result name -> module of this package that defines it. Imported on first use: the drivers
#: together cost ~20 ms of import (start-up time), and a session needs only the ones it calls
_HOME = {
    "NormalState": "normal", "AdhesiveNormalState": "adhesion", "AdhesionCycle": "adhesion",
    "TangentialState": "tangential", "ShiftHistory": "tangential", "TorsionState": "torsion",
    "TwistHistory": "torsion", "ViscoelasticHistory": "viscoelastic", "PathResult": "path",
    "FrettingLoop": "fretting", "FrettingMap": "fretting", "ContactLaw": "law", "LawStep": "law",
    "StressField": "stress", "StressMaximum": "stress",
}


#: the driver modules, attributes of the package once imported (``contactlab.effects.law``)
_MODULES = ("adhesion", "fretting", "law", "law_source", "normal", "path", "stress", "tangential",
            "torsion", "torsion_path", "viscoelastic", "wear")


def __getattr__(name: str) -> object:
    if name in _MODULES:            # importing a submodule binds it as a package attribute
        return _importlib.import_module(f"{__name__}.{name}")
    try:
        home = _HOME[name]
    except KeyError:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}") from None
    value = getattr(_importlib.import_module(f"{__name__}.{home}"), name)
    globals()[name] = value         # later lookups are plain module attributes
    return value


def __dir__() -> "list[str]":
    return sorted(set(globals()) | set(_HOME) | set(_MODULES))
