"""Axisymmetric indenter profiles and their MDR transforms.

Built-ins: :class:`PowerLaw`, :class:`Paraboloid`, :class:`Cone`, :class:`Polynomial`,
:class:`Sphere`, :class:`FlatPunch`, :class:`TruncatedParaboloid`, :class:`TruncatedCone`,
:class:`Tabulated`, and the composites :class:`Sum` and :class:`Scaled` (``p1 + p2``, ``2 * p``).
"""
from .._lazy import attach as _attach
from .base import G_STRATEGIES, Profile
from .compound import Scaled, Sum
from .flat_punch import FlatPunch, TruncatedCone, TruncatedParaboloid
from .power_law import Cone, Paraboloid, Polynomial, PowerLaw
from .sphere import Sphere

__all__ = [
    "Profile", "G_STRATEGIES", "PowerLaw", "Paraboloid", "Cone", "Polynomial", "Sphere",
    "FlatPunch", "TruncatedParaboloid", "TruncatedCone", "Tabulated", "Sum", "Scaled",
]


def _register_builtins(registry=None) -> None:
    """Register the built-in classes (into the global registry by default).

    The registry calls this at its first use of the kind ``profile`` (not at import: the contract
    checks cost start-up time that a session without registry lookups need not pay).
    """
    if registry is None:
        from ..registry import registry
    from .tabulated import Tabulated
    for cls in (PowerLaw, Paraboloid, Cone, Polynomial, Sphere, FlatPunch, TruncatedParaboloid,
                TruncatedCone, Tabulated):
        registry.register(cls, "profile", builtin=True)


# imported on first use (start-up time; listed for type checkers in __init__.pyi): ``Tabulated``
# with its csv, pathlib and quadrature tables costs ~5 ms of ``import contactlab``;
# ``smoothing`` is its helper
__getattr__, __dir__, _LAZY = _attach(__name__, submodules=["tabulated", "smoothing"],
                                      submod_attrs={"tabulated": ["Tabulated"]})
