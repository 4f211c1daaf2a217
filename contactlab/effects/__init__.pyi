# The public names of contactlab.effects for type checkers and IDEs; at run time each resolves
# on first use (contactlab/effects/__init__.py, through contactlab._lazy.attach).
from . import adhesion as adhesion
from . import fretting as fretting
from . import law as law
from . import law_source as law_source
from . import normal as normal
from . import path as path
from . import stress as stress
from . import tangential as tangential
from . import torsion as torsion
from . import viscoelastic as viscoelastic
from . import wear as wear
from .adhesion import AdhesionCycle as AdhesionCycle
from .adhesion import AdhesiveNormalState as AdhesiveNormalState
from .fretting import FrettingLoop as FrettingLoop
from .fretting import FrettingMap as FrettingMap
from .law import ContactLaw as ContactLaw
from .law import LawStep as LawStep
from .normal import NormalState as NormalState
from .path import PathResult as PathResult
from .stress import StressField as StressField
from .stress import StressMaximum as StressMaximum
from .tangential import ShiftHistory as ShiftHistory
from .tangential import TangentialState as TangentialState
from .torsion import TorsionState as TorsionState
from .torsion import TwistHistory as TwistHistory
from .viscoelastic import ViscoelasticHistory as ViscoelasticHistory

__all__ = ["NormalState", "AdhesiveNormalState", "AdhesionCycle", "TangentialState",
           "ShiftHistory", "TorsionState", "TwistHistory", "ViscoelasticHistory", "PathResult",
           "FrettingLoop", "FrettingMap", "ContactLaw", "LawStep", "StressField", "StressMaximum"]
