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
  codes; takes plain per-contact arrays instead of a contact).
"""
from .adhesion import AdhesionCycle, AdhesiveNormalState
from .fretting import FrettingLoop, FrettingMap
from .law import ContactLaw, LawStep
from .normal import NormalState
from .path import PathResult
from .tangential import ShiftHistory, TangentialState
from .torsion import TorsionState, TwistHistory
from .viscoelastic import ViscoelasticHistory

__all__ = ["NormalState", "AdhesiveNormalState", "AdhesionCycle", "TangentialState",
           "ShiftHistory", "TorsionState", "TwistHistory", "ViscoelasticHistory", "PathResult",
           "FrettingLoop", "FrettingMap", "ContactLaw", "LawStep"]
