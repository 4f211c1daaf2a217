"""Tangential contact (Cattaneo–Mindlin through the MDR): the drivers behind
:meth:`Contact.tangential` and :meth:`Contact.shift_history`, and their results
:class:`TangentialState` and :class:`ShiftHistory`.

:func:`tangential` gives the state for one monotonic shift at constant normal load;
:func:`shift_history` follows an arbitrary displacement history at constant normal load with the
Masing rule and turning-point memory (:mod:`contactlab.physics.masing`; exact for the MDR Jenkins
elements and for the 3D theory). The kernels are in :mod:`contactlab.physics.tangential`.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, ClassVar

import numpy as np

from ..citations import Cited, sources_for
from ..errors import NotSupportedError, ParameterError
from ..numeric.roots import bracketed_root
from ..params import (as_float_array, broadcast_inputs, check_memory, check_time, exactly_one,
                      scalar_or_array)
from ..physics import tangential as _tan
from ..physics.masing import masing_dissipation, masing_program, masing_response
from ._protocol import Result, reporting
from .sizes import (FIELD_BYTES_PER_POINT, TANGENTIAL_BYTES_PER_LOAD, check_elements, check_field,
                    route_kind)

__all__ = ["TangentialState", "ShiftHistory", "tangential", "shift_history", "STATE_UNITS"]

#: units of the columns of a tangential state and of a shift history (CSV headers)
STATE_UNITS = {"displacement": "m", "tangential_force": "N", "stick_radius": "m",
               "gross_sliding": "1", "dissipated_energy": "J"}


def _out(v: np.ndarray) -> Any:
    return scalar_or_array(np.asarray(v, float))


def _one(name_values: dict[str, Any], what: str) -> tuple[str, Any]:
    return exactly_one(what, name_values)


@dataclass(frozen=True, eq=False)
class TangentialState(Result, Cited):
    """Cattaneo–Mindlin state (one load or an array of loads) at constant normal load.

    Attributes
    ----------
    normal : NormalState
        The normal state the shift acts on.
    displacement : float or ndarray
        Tangential displacement of the indenter ``u``, m (signed).
    tangential_force : float or ndarray
        Tangential force ``F_x``, N (same sign as ``u``).
    stick_radius : float or ndarray
        Radius ``c`` of the stick zone, m (``a`` without slip, 0 at full sliding).
    gross_sliding : bool or ndarray
        True where the force reached ``μF_N`` (the displacement reported is the smallest one
        that reaches it).
    """

    contact: Any = field(repr=False)
    normal: Any = field(repr=False)
    _u: np.ndarray = field(repr=False)
    _F: np.ndarray = field(repr=False)
    _c: np.ndarray = field(repr=False)
    _sliding: np.ndarray = field(repr=False)
    meta: dict = field(default_factory=dict, repr=False)

    units: ClassVar[dict[str, str]] = {
        k: STATE_UNITS[k] for k in ("displacement", "tangential_force", "stick_radius",
                                    "gross_sliding")}

    def __repr__(self) -> str:
        return self._summary_repr()

    def to_dict(self) -> dict[str, Any]:
        """``displacement``, ``tangential_force``, ``stick_radius``, ``gross_sliding`` (scalars or
        arrays of the state's shape). The model error is 0.0: Cattaneo–Mindlin through the MDR
        is exact."""
        return {"displacement": self.displacement, "tangential_force": self.tangential_force,
                "stick_radius": self.stick_radius, "gross_sliding": self.gross_sliding}

    @property
    def displacement(self) -> Any:
        return _out(self._u)

    @property
    def tangential_force(self) -> Any:
        return _out(self._F)

    @property
    def stick_radius(self) -> Any:
        return _out(self._c)

    @property
    def gross_sliding(self) -> Any:
        s = np.asarray(self._sliding, bool)
        return bool(s) if s.ndim == 0 else s

    @property
    def stiffness(self) -> Any:
        """Incremental tangential stiffness ``dF_x/du = 2G*c``, N/m."""
        return _out(2.0 * self.contact.moduli.tangential * self._c)

    def shear(self, r: Any) -> Any:
        """Tangential traction ``τ_x(r)``, Pa (sign of the displacement), shape ``state + r``.

        Without a friction coefficient nothing slips: the traction of the rigidly shifted punch
        of the contact radius, ``Q/(2π a sqrt(a² - r²))`` (singular at the edge)."""
        r = as_float_array("r", r)
        sh = np.shape(self._c)
        check_field("shear()", sh, r.shape, FIELD_BYTES_PER_POINT[route_kind(self.contact.profile)])
        if np.any(r < 0):
            raise ParameterError(f"r contains {r[r < 0].ravel()[0]!r}: radii must be >= 0 m.")
        ex = (1,) * r.ndim
        a = np.asarray(self.normal._radius, float).reshape(sh + ex)
        d = np.asarray(self.normal._depth, float).reshape(sh + ex)
        c = np.asarray(self._c, float).reshape(sh + ex)
        sign = np.sign(np.asarray(self._u, float)).reshape(sh + ex)
        c_ = self.contact
        mu = np.inf if c_.friction is None else c_.friction
        if not np.isfinite(mu):
            # no friction limit, no slip: the rigidly shifted punch of the contact radius,
            # Q/(2π a sqrt(a² - r²)) inside (+inf at the edge itself), 0 outside
            Q = np.abs(np.asarray(self.tangential_force, float)).reshape(sh + ex)
            with np.errstate(divide="ignore", invalid="ignore"):
                tau = np.where(r < a, Q / (2.0 * np.pi * a * np.sqrt(np.maximum(a * a - r * r,
                                                                                 0.0))),
                               np.where((r == a) & (Q > 0), np.inf, 0.0))
            return _out(sign * tau)
        tau = _tan.shear(c_.profile, c_.moduli.normal, mu, r, a, d, c, c_.rtol)
        return _out(sign * tau)

    # ---- subsurface stresses (contactlab.effects.stress_tangential does the work)
    def stress(self, x: Any, y: Any, z: Any, body: int = 1, part: str = "total") -> Any:
        """Subsurface stress field (a ``CartesianStressField``) at points ``(x, y, z)`` (m,
        broadcast; ``x`` along the shift, ``z >= 0`` the depth): the normal preload's field plus
        the Cattaneo–Mindlin shear field (``part="friction"``: the shear part alone; without a
        friction limit the rigidly shifted punch's, ``q = Q/(2π a sqrt(a² - r²))``). Body 1
        receives the traction :meth:`shear` reports; body 2 its opposite. See docs/stress.md."""
        from .stress_tangential import tangential_stress
        return tangential_stress(self, x, y, z, body, part)

    def max_stress(self, kind: str = "von_mises", body: int = 1) -> Any:
        """Largest ``kind`` of the whole field in body 1 or 2 and its location (``r``, ``z``;
        ``meta["x"], meta["y"]``)."""
        from .stress_tangential import tangential_max_stress
        return tangential_max_stress(self, kind, body)

    def stress_field(self, grid: Any = None, body: int = 1, part: str = "total",
                     y: float = 0.0) -> Any:
        """Stress field on a grid ``(x_values, z_values)`` of the plane ``y`` for plots (default
        200 x 100 over ``[-2a, 2a] x [0, 1.5a]``)."""
        from .stress_tangential import tangential_stress_field
        return tangential_stress_field(self, grid, body, part, y)


@reporting()
def tangential(contact, *, depth: Any = None, force: Any = None, radius: Any = None,
               displacement: Any = None, tangential_force: Any = None,
               stick_radius: Any = None) -> TangentialState:
    """Cattaneo–Mindlin state; see :meth:`contactlab.Contact.tangential`."""
    if contact.is_adhesive:
        raise NotSupportedError("tangential() is implemented for non-adhesive contacts only "
                                "(work_of_adhesion=None).")
    nkey, nval = _one({"depth": depth, "force": force, "radius": radius}, "tangential()")
    tkey, tval = _one({"displacement": displacement, "tangential_force": tangential_force,
                       "stick_radius": stick_radius}, "tangential()")
    tv = as_float_array(tkey, tval)
    shape = broadcast_inputs("tangential()", **{nkey: as_float_array(nkey, nval), tkey: tv})
    check_elements("tangential()", math.prod(shape), TANGENTIAL_BYTES_PER_LOAD,
                   f"{nkey} x {tkey} broadcast to {shape}")
    ns = contact.normal(**{nkey: nval})
    a0, d0, F0 = (np.asarray(v, float) for v in (ns._radius, ns._depth, ns._force))
    a, d, FN, t = np.broadcast_arrays(a0, d0, F0, tv)
    if ns.shape != a.shape:
        # the same normal states, broadcast (re-solving from the depths could move a by an ulp,
        # and the stick radius c <= a must hold for the reported radius exactly)
        from .normal import NormalState
        meta = dict(ns.meta)
        meta["error_estimate"] = np.broadcast_to(np.asarray(ns.meta.get("error_estimate", 0.0),
                                                            float), a.shape).copy()
        ns = NormalState(contact, d.copy(), a.copy(), FN.copy(), meta)
    prof = contact.profile
    E, Gs = contact.moduli.normal, contact.moduli.tangential
    mu = contact.friction
    sign = np.sign(t)
    if mu is None:  # no slip (μ → ∞): rigid shift of the whole contact
        if tkey == "stick_radius":
            raise NotSupportedError("stick_radius= needs friction: without friction the stick "
                                    "radius is always the contact radius.")
        k = 2.0 * Gs * a
        if tkey == "displacement":
            u = t.copy()
        else:
            u = np.where(k > 0, t / np.where(k > 0, k, 1.0), 0.0)
            if np.any((k == 0) & (t != 0)):
                raise ParameterError("tangential_force != 0 is invalid without contact (force 0).")
        return TangentialState(contact, ns, u, k * u, a.copy(), np.zeros(a.shape, bool),
                               {"control": tkey, "method": "no-slip",
                                "citations": sources_for("normal", "tangential")})
    sliding = np.zeros(a.shape, bool)
    if tkey == "displacement":
        ustar = _tan.full_slip_displacement(E, Gs, mu, d)
        sliding = np.abs(t) >= ustar
        c = _tan.stick_radius_of_displacement(prof, E, Gs, mu, a, d, t)
        u = t.copy()
    elif tkey == "stick_radius":
        if np.any((t < 0) | (t > a)):
            bad = t[(t < 0) | (t > a)].ravel()[0]
            raise ParameterError(f"stick_radius={bad!r} m is invalid: it must satisfy "
                                 "0 <= stick_radius <= contact radius.")
        c = t.copy()
        u = _tan.displacement_of_stick_radius(prof, E, Gs, mu, d, c)
        sign = np.ones(a.shape)
        sliding = c == 0
    else:
        T = np.abs(t)
        sliding = T >= mu * FN
        ustar = _tan.full_slip_displacement(E, Gs, mu, d)
        u = np.where(sliding, ustar, 0.0)
        inner = ~sliding & (T > 0)
        if np.any(inner):
            ai, di = a[inner], d[inner]
            u[inner] = bracketed_root(
                lambda x, idx: _tan.force_of_displacement(prof, E, Gs, mu, ai[idx], di[idx], x)[0],
                T[inner], 0.0, ustar[inner], rtol=1e-14, what="tangential displacement")
        u = sign * u
    if tkey == "stick_radius":
        F = sign * _tan.force_of_stick_radius(prof, E, mu, a, d, c)
    else:
        Fm, c = _tan.force_of_displacement(prof, E, Gs, mu, a, d, u)
        F = np.sign(u) * Fm
    F = np.where(a > 0, F, 0.0)
    if tkey == "tangential_force":
        F = np.where(sliding, sign * mu * FN, F)
    return TangentialState(contact, ns, u, F, c, sliding,
                           {"control": tkey, "method": "cattaneo-mindlin", "rtol": contact.rtol,
                            "citations": sources_for("normal", "tangential")})


@dataclass(frozen=True, eq=False)
class ShiftHistory(Result, Cited):
    """Result of :meth:`Contact.shift_history`: per-step arrays at constant normal load.

    Attributes
    ----------
    displacement, tangential_force, stick_radius, dissipated_energy : ndarray
        Displacement (m), tangential force (N), stick radius of the active branch (m) and
        cumulative dissipated energy (J) per step.
    normal : NormalState
    """

    normal: Any = field(repr=False)
    displacement: np.ndarray
    tangential_force: np.ndarray
    stick_radius: np.ndarray
    dissipated_energy: np.ndarray
    meta: dict = field(default_factory=dict, repr=False)

    units: ClassVar[dict[str, str]] = {
        k: STATE_UNITS[k] for k in ("displacement", "tangential_force", "stick_radius",
                                    "dissipated_energy")}

    def to_dict(self) -> dict[str, np.ndarray]:
        """Per-step arrays by name (``displacement``, ``tangential_force``, ``stick_radius``,
        ``dissipated_energy``). The model error is 0.0 (exact, Masing)."""
        return {"displacement": self.displacement, "tangential_force": self.tangential_force,
                "stick_radius": self.stick_radius, "dissipated_energy": self.dissipated_energy}

    def plot(self, axes: Any = None, *, units: str = "si"):
        """Force–displacement loop and stick radius per step (needs matplotlib); returns the two
        axes. ``units="engineering"`` labels µm (see :mod:`contactlab.plotting`).
        """
        from .. import plotting as pl
        return pl.history(self.displacement, self.tangential_force, self.stick_radius,
                          x_name="displacement", x_unit="m", y_name="tangential force",
                          y_unit="N", units=units, axes=axes, title="shift history")

    def stress(self, x: Any, y: Any, z: Any, *, step: int, body: int = 1,
               part: str = "total") -> Any:
        """Subsurface stress field (a ``CartesianStressField``) at ``step`` of the history, at
        points ``(x, y, z)`` (m): the Masing sum of virgin Cattaneo–Mindlin fields over the
        active turning points, plus the normal preload (``part="friction"``: without it). See
        docs/stress.md."""
        from .stress_history import history_stress
        return history_stress(self, x, y, z, step=step, body=body, part=part)


#: peak memory of a shift history, bytes per step (turning-point bookkeeping, the loading curve
#: at every step's argument, the dissipation): 801 B measured with tracemalloc for random walks
#: of 10^5 steps on three profiles, rounded up; checked before the history is walked
HISTORY_BYTES_PER_STEP = 1024
#: run time of a shift history, s per step (bookkeeping, the loading curve at every step's
#: argument, the dissipation), checked against the time budget before any work: measured 4.7-12
#: µs per step (CPU time, shared 2-core VM at load ~3.5, paraboloid, random walks and sine
#: sweeps of 10^4-10^6 steps), taken at about 0.4 of the smallest (a lower estimate;
#: benchmarks/time_estimates.py checks it)
HISTORY_SECONDS_PER_STEP = 2e-6


@reporting()
def shift_history(contact, *, displacement: Any, depth: Any = None,
                  force: Any = None) -> ShiftHistory:
    """Exact tangential response to a displacement history at constant normal load.

    See :meth:`contactlab.Contact.shift_history`.
    """
    if contact.friction is None:
        raise NotSupportedError("shift_history() needs friction: without it the response is "
                                "linear, F_x = 2G*a u (use tangential()).")
    nkey, nval = _one({"depth": depth, "force": force}, "shift_history()")
    ns = contact.normal(**{nkey: nval})
    if ns.shape != ():
        raise ParameterError(f"{nkey} must be a scalar for shift_history() (constant normal load).")
    u = as_float_array("displacement", displacement).ravel()
    check_memory("shift_history()", float(u.size) * HISTORY_BYTES_PER_STEP,
                 f"displacement: {u.size} steps x {HISTORY_BYTES_PER_STEP} B")
    check_time("shift_history()", float(u.size) * HISTORY_SECONDS_PER_STEP,
               f"displacement: {u.size} steps x {HISTORY_SECONDS_PER_STEP * 1e6:g} us")
    prof, E, Gs, mu = (contact.profile, contact.moduli.normal, contact.moduli.tangential,
                       contact.friction)
    a, d = float(ns._radius), float(ns._depth)
    origin, factor, arg, segments = masing_program(u)

    def F_load(delta):
        return _tan.force_of_displacement(prof, E, Gs, mu, a, d, np.asarray(delta, float))

    Fl, c_out = F_load(arg)
    F = masing_response(u, origin, factor, Fl)

    def D(x: np.ndarray) -> np.ndarray:
        return _tan.virgin_dissipation(prof, E, Gs, mu, a, d, x, contact.rtol)

    W = masing_dissipation(segments, u.size, D, contact.rtol)
    return ShiftHistory(ns, u.copy(), F, c_out, W, {"method": "masing", "rtol": contact.rtol,
                         "citations": sources_for("normal", "tangential", "masing:tangential")})
