"""Effective moduli of a pair of bodies (theory §1).

* normal ``1/E* = (1-ν1²)/E1 + (1-ν2²)/E2`` [J85];
* tangential ``1/G* = (2-ν1)/(4G1) + (2-ν2)/(4G2)`` (MDR handbook, Cattaneo-Mindlin) [H1];
* torsional ``1/G_t = 1/G1 + 1/G2`` (the Reissner-Sagoci compliances of the two bodies add; torsion
  decouples exactly from normal loading for any pair). ``G_t`` is not ``G*``.
"""
from __future__ import annotations

from dataclasses import dataclass

from ..errors import NotSupportedError, ParameterError
from .base import Material

__all__ = ["EffectiveModuli", "effective_moduli", "viscoelastic_body"]


@dataclass(frozen=True)
class EffectiveModuli:
    """Effective moduli of a contact pair, Pa.

    Attributes
    ----------
    normal : float
        ``E*``.
    tangential : float
        ``G*`` (Cattaneo-Mindlin / MDR tangential springs ``G* Δx``).
    torsional : float
        ``G_t`` (no-slip torque ``(16/3) G_t a³ φ``; MDR torsional springs ``8 G_t Δx``).
    elastically_similar : bool
        ``(1-2ν1)/G1 == (1-2ν2)/G2``: normal-tangential decoupling is exact.
    """

    normal: float
    tangential: float
    torsional: float
    elastically_similar: bool


def effective_moduli(m1: Material, m2: Material) -> EffectiveModuli:
    """Effective normal, tangential and torsional moduli of two bodies.

    Parameters
    ----------
    m1, m2 : Material
        The two bodies; at most one may be rigid.

    Raises
    ------
    ParameterError
        Both bodies rigid (the contact has no compliance).
    NotSupportedError
        A viscoelastic body (use the viscoelastic solver).
    """
    for i, m in enumerate((m1, m2), 1):
        if not isinstance(m, Material):
            raise ParameterError(f"materials[{i - 1}]={m!r} is invalid: expected a Material "
                                 "(e.g. contactlab.Elastic(E=..., nu=...) or Rigid()).")
        if m.is_viscoelastic:
            raise NotSupportedError(
                f"materials[{i - 1}]={m!r} is viscoelastic: it has no single effective modulus. "
                "Only normal contact of a rigid indenter on an incompressible viscoelastic "
                "half-space is covered (contact.viscoelastic_history); elastic solvers (normal, "
                "tangential, torsion) with viscoelastic materials are not covered by the theory "
                "in docs/theory.")
    c1, c2 = m1._compliances(), m2._compliances()
    tot = [a + b for a, b in zip(c1, c2)]
    if min(tot) <= 0:
        raise ParameterError("materials=(Rigid(), Rigid()) is invalid: at least one body must be "
                             "deformable.")
    similar = _dundurs_beta_zero(m1, m2)
    return EffectiveModuli(1.0 / tot[0], 1.0 / tot[1], 1.0 / tot[2], similar)


def _dundurs_beta_zero(m1: Material, m2: Material) -> bool:
    def k(m: Material) -> float:
        E = getattr(m, "E", None)
        if E is None:
            return 0.0
        return (1.0 - 2.0 * m.nu) / m.G  # type: ignore[attr-defined]
    a, b = k(m1), k(m2)
    return abs(a - b) <= 1e-12 * max(abs(a), abs(b), 1e-300)


def viscoelastic_body(m1: Material, m2: Material):
    """The viscoelastic body of a (viscoelastic, rigid) pair, in either order.

    Raises
    ------
    NotSupportedError
        No viscoelastic body, two deformable bodies, or a partner that is not rigid: the MDR
        viscoelastic rules cover a rigid indenter on one incompressible viscoelastic half-space
        (``E*(t) = 4G(t)``) only.
    """
    from .elastic import Rigid
    from .viscoelastic import Viscoelastic
    visco = [m for m in (m1, m2) if isinstance(m, Material) and m.is_viscoelastic]
    other = [m for m in (m1, m2) if not (isinstance(m, Material) and m.is_viscoelastic)]
    if len(visco) == 1 and len(other) == 1 and isinstance(other[0], Rigid) \
            and isinstance(visco[0], Viscoelastic):
        return visco[0]
    if len(visco) == 0:
        raise NotSupportedError(
            f"materials={(m1, m2)!r}: viscoelastic_history() needs a viscoelastic body; use "
            "normal() for elastic bodies.")
    raise NotSupportedError(
        f"materials={(m1, m2)!r} is not supported: the MDR viscoelastic rules cover a rigid "
        "indenter on one incompressible viscoelastic half-space (E*(t) = 4G(t)) only; two "
        "deformable bodies or a compressible partner need the general E*(t) operator, which is "
        "not covered here. Use materials=(viscoelastic, Rigid()).")
