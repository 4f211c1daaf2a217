"""Immutable result states. Field quantities are computed lazily, on request."""
from __future__ import annotations

from dataclasses import dataclass, field
from functools import cached_property
from typing import Any

import numpy as np

from .params import as_float_array
from .physics import normal as _normal

__all__ = ["NormalState"]


def _scalar_or_array(v: np.ndarray) -> Any:
    v = np.asarray(v, dtype=float)
    return float(v) if v.ndim == 0 else v


@dataclass(frozen=True, eq=False)
class NormalState:
    """State of a normal contact (one load or an array of loads).

    Attributes
    ----------
    depth : float or ndarray
        Indentation depth ``d``, m.
    radius : float or ndarray
        Contact radius ``a``, m.
    force : float or ndarray
        Normal force ``F_N``, N (compressive > 0).
    stiffness : float or ndarray
        Incremental normal stiffness ``dF/dd = 2E* a``, N/m.
    meta : dict
        ``routes`` (numerical route per quantity), ``rtol``, ``error_estimate`` (relative, force).

    Notes
    -----
    Field methods (:meth:`pressure`, :meth:`displacement`) take radii ``r`` and return an array of
    shape ``state.shape + r.shape``.
    """

    contact: Any = field(repr=False)
    _depth: np.ndarray = field(repr=False)
    _radius: np.ndarray = field(repr=False)
    _force: np.ndarray = field(repr=False)
    meta: dict = field(default_factory=dict, repr=False)

    @property
    def shape(self) -> tuple[int, ...]:
        """Shape of the load array (``()`` for a single load)."""
        return np.shape(self._depth)

    @property
    def depth(self) -> Any:
        return _scalar_or_array(self._depth)

    @property
    def radius(self) -> Any:
        return _scalar_or_array(self._radius)

    @property
    def force(self) -> Any:
        return _scalar_or_array(self._force)

    @property
    def stiffness(self) -> Any:
        return _scalar_or_array(2.0 * self.contact.moduli.normal * self._radius)

    @cached_property
    def _g_at_radius(self) -> np.ndarray:
        return np.where(self._radius > 0, self.contact.profile._g(self._radius), 0.0)

    @cached_property
    def elastic_energy(self) -> Any:
        """Elastic energy stored in the contact, J (``∫ F dd`` for non-adhesive contacts)."""
        prof = self.contact.profile
        a = self._radius
        g_int = prof._g_integral(a)
        g2 = _normal.g_squared_integral(prof, a, self.contact.rtol)
        return _scalar_or_array(_normal.elastic_energy(self.contact.moduli.normal, a, self._depth,
                                                       g_int, g2))

    def _field_args(self, r: Any) -> tuple[np.ndarray, ...]:
        r = as_float_array("r", r)
        if np.any(r < 0):
            from .errors import ParameterError
            raise ParameterError(f"r contains {r[r < 0].ravel()[0]!r}: radii must be >= 0 m.")
        sh = self.shape
        a = self._radius.reshape(sh + (1,) * r.ndim)
        d = self._depth.reshape(sh + (1,) * r.ndim)
        ga = self._g_at_radius.reshape(sh + (1,) * r.ndim)
        return r, a, d, ga

    def pressure(self, r: Any) -> Any:
        """Contact pressure ``p(r)``, Pa, at radii ``r`` (m); 0 outside the contact.

        Singular points return ``inf`` (the flat-punch edge, the centre of a cone or of a power
        law with ``n < 1``).
        """
        r, a, d, ga = self._field_args(r)
        val, err = _normal.pressure(self.contact.profile, self.contact.moduli.normal, r, a, d, ga,
                                    self.contact.rtol)
        return _scalar_or_array(val)

    def displacement(self, r: Any) -> Any:
        """Normal surface displacement ``u_z(r)``, m, inside (``d - f(r)``) and outside the contact."""
        r, a, d, _ = self._field_args(r)
        val, err = _normal.displacement(self.contact.profile, r, a, d, self.contact.rtol)
        return _scalar_or_array(val)

    @property
    def peak_pressure(self) -> Any:
        """Maximum pressure over the contact, Pa (sampled on 1024 radii from the centre).

        ``inf`` where the pressure is singular (flat-punch edge, cone tip, ``n < 1``).
        """
        rho = np.linspace(0.0, 1.0, 1025)[:-1]
        a = self._radius[..., None]
        val, _ = _normal.pressure(self.contact.profile, self.contact.moduli.normal, rho * a, a,
                                  self._depth[..., None], self._g_at_radius[..., None],
                                  self.contact.rtol)
        flat_edge = (self._radius > 0) & (self._depth != self._g_at_radius)
        peak = np.where(flat_edge, np.inf, np.max(val, axis=-1))
        return _scalar_or_array(peak)
