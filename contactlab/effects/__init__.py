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
>>>>>>> a454b13 (ContactLaw: vectorised exact contact law at constant normal load for many contacts (power-law families n >= 1): certified torsion master curves (physics/master.py, piecewise polynomials built from the exact solvers, certified at non-node points), Cattaneo-Mindlin closed form, vectorised Masing step with a bounded turning-point stack (physics/masing_stack.py); state save/restore, reset, validation naming the index; tests against twist_history/shift_history for 50 random contacts)
from .normal import NormalState
from .path import PathResult
from .tangential import ShiftHistory, TangentialState
from .torsion import TorsionState, TwistHistory
from .viscoelastic import ViscoelasticHistory

__all__ = ["NormalState", "AdhesiveNormalState", "AdhesionCycle", "TangentialState",
           "ShiftHistory", "TorsionState", "TwistHistory", "ViscoelasticHistory", "PathResult",
           "FrettingLoop", "FrettingMap", "ContactLaw", "LawStep"]
