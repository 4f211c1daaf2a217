"""The discretised MDR foundations: :class:`Winkler` (independent springs with frictional
memory, for tangential and torsional load paths) and :class:`Viscoelastic` (rheological elements
for viscoelastic normal contact)."""
from .base import DEFAULT_N_SPRINGS, SPACINGS, Foundation
from .viscoelastic import Viscoelastic
from .winkler import SpringState, Winkler

__all__ = ["Foundation", "Winkler", "Viscoelastic", "SpringState", "DEFAULT_N_SPRINGS",
           "SPACINGS"]
