"""Result objects of adhesive (JKR) contacts: :class:`AdhesiveNormalState`, :class:`AdhesionCycle`.

The solvers live in :mod:`contactlab.physics.adhesion`; :meth:`Contact.normal` dispatches to them
when ``work_of_adhesion > 0``.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

from .physics import normal as _normal
from .states import NormalState, _scalar_or_array

__all__ = ["AdhesiveNormalState", "AdhesionCycle"]


@dataclass(frozen=True, eq=False)
class AdhesiveNormalState(NormalState):
    """State of an adhesive (JKR) normal contact.

    Same interface as :class:`~contactlab.NormalState`; ``.pressure(r)`` carries the tensile
    edge term ``(E*/π)(d - g(a))/sqrt(a² - r²)`` and ``.displacement(r)`` the matching field.

    Attributes
    ----------
    stiffness : float or ndarray
        Incremental stiffness along the equilibrium curve, ``dF/dd = 2E* a (φ-3/2)/(φ-1/2)``
        with ``φ = a g'(a)/Δl(a)``, N/m (zero at the force-controlled pull-off, infinite at the
        displacement-controlled one; ``2E* b`` when pinned at a punch wall).
    meta : dict
        Besides the usual keys: ``control``, ``branch``, ``work_of_adhesion``,
        ``stable_under_force`` and ``stable_under_displacement`` (bool arrays).
    """

    _stiff: Any = field(default=None, repr=False)

    @property
    def stiffness(self) -> Any:
        return _scalar_or_array(self._stiff)

    @property
    def surface_energy(self) -> Any:
        """Adhesion energy of the contact area, ``-π a² Δγ``, J."""
        return _scalar_or_array(-np.pi * self._radius**2 * self.contact.work_of_adhesion)

    @property
    def peak_pressure(self) -> Any:
        """Largest (compressive) pressure over the contact, Pa (sampled on 1024 radii).

        ``inf`` only where the edge term is compressive (an adhesive flat punch pushed in).
        """
        rho = np.linspace(0.0, 1.0, 1025)[:-1]
        a = self._radius[..., None]
        val, _ = _normal.pressure(self.contact.profile, self.contact.moduli.normal, rho * a, a,
                                  self._depth[..., None], self._g_at_radius[..., None],
                                  self.contact.rtol)
        compressive_edge = (self._radius > 0) & (self._depth > self._g_at_radius)
        peak = np.where(compressive_edge, np.inf, np.max(val, axis=-1))
        return _scalar_or_array(np.where(self._radius > 0, peak, 0.0))


@dataclass(frozen=True)
class AdhesionCycle:
    """An approach/retraction history of an adhesive contact (JKR hysteresis).

    Attributes
    ----------
    control : str
        ``"depth"`` or ``"force"``.
    depth, force, radius : ndarray
        Per step, m, N, m (out of contact: force and radius 0; under force control the depth
        out of contact is reported as 0).
    in_contact : ndarray of bool
        Contact flag per step.
    jumps : ndarray of int
        Steps at which contact was made or lost (the state changes discontinuously there).
    pull_off_value : float
        Depth (m) or force (N) below which contact is lost.
    """

    control: str
    depth: np.ndarray
    force: np.ndarray
    radius: np.ndarray
    in_contact: np.ndarray
    jumps: np.ndarray
    pull_off_value: float

    def to_dict(self) -> dict[str, Any]:
        """Per-step arrays as a dict (for pandas/CSV)."""
        return {"depth": self.depth, "force": self.force, "radius": self.radius,
                "in_contact": self.in_contact}
