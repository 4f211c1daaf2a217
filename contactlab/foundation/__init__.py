"""The discretised MDR foundation: independent springs with frictional memory."""
from .base import DEFAULT_N_SPRINGS, SPACINGS, Foundation
from .winkler import SpringState, Winkler

__all__ = ["Foundation", "Winkler", "SpringState", "DEFAULT_N_SPRINGS", "SPACINGS"]
