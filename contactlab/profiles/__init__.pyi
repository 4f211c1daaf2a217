# The public names of contactlab.profiles for type checkers and IDEs (``Tabulated`` and the
# ``tabulated``/``smoothing`` modules resolve on first use: contactlab/profiles/__init__.py).
from . import smoothing as smoothing
from . import tabulated as tabulated
from .base import G_STRATEGIES as G_STRATEGIES
from .base import Profile as Profile
from .compound import Scaled as Scaled
from .compound import Sum as Sum
from .flat_punch import FlatPunch as FlatPunch
from .flat_punch import TruncatedCone as TruncatedCone
from .flat_punch import TruncatedParaboloid as TruncatedParaboloid
from .power_law import Cone as Cone
from .power_law import Paraboloid as Paraboloid
from .power_law import Polynomial as Polynomial
from .power_law import PowerLaw as PowerLaw
from .sphere import Sphere as Sphere
from .tabulated import Tabulated as Tabulated

__all__ = [
    "Profile", "G_STRATEGIES", "PowerLaw", "Paraboloid", "Cone", "Polynomial", "Sphere",
    "FlatPunch", "TruncatedParaboloid", "TruncatedCone", "Tabulated", "Sum", "Scaled",
]

def _register_builtins(registry: object = None) -> None: ...
