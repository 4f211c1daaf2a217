"""Materials and the effective moduli of a contact pair."""
from .base import Material
from .elastic import Elastic, Rigid
from .pair import EffectiveModuli, effective_moduli

__all__ = ["Material", "Elastic", "Rigid", "EffectiveModuli", "effective_moduli"]
