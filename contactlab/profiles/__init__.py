"""Axisymmetric indenter profiles and their MDR transforms.

Built-ins: :class:`PowerLaw`, :class:`Paraboloid`, :class:`Cone`, :class:`Polynomial`,
:class:`Sphere`, :class:`FlatPunch`, :class:`TruncatedParaboloid`, :class:`TruncatedCone`,
:class:`Tabulated`, and the composites :class:`Sum` and :class:`Scaled` (``p1 + p2``, ``2 * p``).
"""
import importlib as _importlib
import typing as _typing

from .base import G_STRATEGIES, Profile
from .compound import Scaled, Sum
from .flat_punch import FlatPunch, TruncatedCone, TruncatedParaboloid
from .power_law import Cone, Paraboloid, Polynomial, PowerLaw
from .sphere import Sphere

if _typing.TYPE_CHECKING:
    from .tabulated import Tabulated

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


#: modules imported on first use (start-up time): ``Tabulated`` with its csv, pathlib and
#: quadrature tables costs ~5 ms of ``import contactlab``; ``smoothing`` is its helper
_LAZY_MODULES = ("tabulated", "smoothing")


def __getattr__(name: str) -> object:
    if name == "Tabulated":
        from .tabulated import Tabulated
        globals()[name] = Tabulated         # later lookups are plain module attributes
        return Tabulated
    if name in _LAZY_MODULES:               # importing a submodule binds it as an attribute
        return _importlib.import_module(f"{__name__}.{name}")
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def __dir__() -> "list[str]":
    return sorted(set(globals()) | {"Tabulated", *_LAZY_MODULES})
