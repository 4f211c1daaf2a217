"""The discretised MDR foundations: :class:`Winkler` (independent springs with frictional
memory, for tangential and torsional load paths; its time loop in :mod:`.winkler_path`),
:class:`~contactlab.foundation.rings.Rings` (the exact torsion solver's rings and its time loop)
and :class:`ViscoelasticElements` (rheological elements for viscoelastic normal contact).

:class:`Foundation` is the face of those that run a load path: ``for_path`` builds the
discretisation a path needs, ``run`` its time loop (:func:`~contactlab.foundation.base.run_path`
strings them together)."""
from .base import DEFAULT_N_SPRINGS, SPACINGS, Foundation
from .viscoelastic import ViscoelasticElements
from .winkler import SpringState, Winkler

__all__ = ["Foundation", "Winkler", "ViscoelasticElements", "SpringState", "DEFAULT_N_SPRINGS",
           "SPACINGS"]
