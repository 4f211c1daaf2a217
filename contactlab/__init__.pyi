# Every public name of the package face, for type checkers and IDEs: the names the module
# resolves on first use (contactlab/__init__.py, through contactlab._lazy.attach) as well as the
# ones it imports at once. tests/unit/test_lazy_imports.py checks that this list and __all__ agree.
from . import citations as citations
from . import errors as errors
from . import fit as fit
from . import foundation as foundation
from . import loadpath as loadpath
from . import materials as materials
from . import physics as physics
from . import profiles as profiles
from . import registry as registry
from ._version import __version__ as __version__
from .citations import cite as cite
from .contact import Contact as Contact
from .effects import AdhesionCycle as AdhesionCycle
from .effects import AdhesiveNormalState as AdhesiveNormalState
from .effects import NormalState as NormalState
from .effects import PathResult as PathResult
from .effects import ShiftHistory as ShiftHistory
from .effects import TangentialState as TangentialState
from .effects import TorsionState as TorsionState
from .effects import TwistHistory as TwistHistory
from .effects import ViscoelasticHistory as ViscoelasticHistory
from .effects.law import ContactLaw as ContactLaw
from .effects.law import LawStep as LawStep
from .loadpath import LoadPath as LoadPath
from .materials import Elastic as Elastic
from .materials import Rigid as Rigid
from .materials import effective_moduli as effective_moduli
from .params import memory_budget as memory_budget
from .params import set_memory_budget as set_memory_budget
from .params import set_time_budget as set_time_budget
from .params import time_budget as time_budget
from .registry import register_material as register_material
from .registry import register_profile as register_profile
from .sweeps import fretting_map_sweep as fretting_map_sweep
from .sweeps import sweep as sweep

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
