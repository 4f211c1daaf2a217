"""Materials and the effective moduli of a contact pair."""
from .base import Material
from .elastic import Elastic, Rigid
from .pair import EffectiveModuli, effective_moduli

__all__ = ["Material", "Elastic", "Rigid", "EffectiveModuli", "effective_moduli"]


def _register_builtins(registry=None) -> None:
    """Register the built-in classes (into the global registry by default).

    The registry calls this at its first use of the kind ``material`` (not at import: the
    contract checks cost start-up time that a session without registry lookups need not pay).
    """
    if registry is None:
        from ..registry import registry
    from .viscoelastic import GeneralizedMaxwell, KelvinVoigt, Maxwell, StandardLinearSolid
    # the viscoelastic materials pass through the same registry (and its contract checks) as
    # any plugin; they live in their own module and are not top-level names
    for cls in (Elastic, Rigid, KelvinVoigt, Maxwell, StandardLinearSolid, GeneralizedMaxwell):
        registry.register(cls, "material", builtin=True)
