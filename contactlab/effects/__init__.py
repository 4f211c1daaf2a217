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
from .._lazy import attach as _attach

__all__ = ["NormalState", "AdhesiveNormalState", "AdhesionCycle", "TangentialState",
           "ShiftHistory", "TorsionState", "TwistHistory", "ViscoelasticHistory", "PathResult",
           "FrettingLoop", "FrettingMap", "ContactLaw", "LawStep", "StressField", "StressMaximum"]

# Every name resolves on first use (listed for type checkers in __init__.pyi): the drivers
# together cost ~20 ms of import (start-up time), and a session needs only the ones it calls.
# The driver modules become attributes of the package once imported (contactlab.effects.law).
__getattr__, __dir__, _LAZY = _attach(
    __name__,
    submodules=["adhesion", "fretting", "law", "law_source", "normal", "path", "stress",
                "tangential", "torsion", "viscoelastic", "wear"],
    submod_attrs={
        "normal": ["NormalState"], "adhesion": ["AdhesiveNormalState", "AdhesionCycle"],
        "tangential": ["TangentialState", "ShiftHistory"],
        "torsion": ["TorsionState", "TwistHistory"], "viscoelastic": ["ViscoelasticHistory"],
        "path": ["PathResult"], "fretting": ["FrettingLoop", "FrettingMap"],
        "law": ["ContactLaw", "LawStep"], "stress": ["StressField", "StressMaximum"],
    },
)
