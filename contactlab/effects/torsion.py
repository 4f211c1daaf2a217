"""Torsion at constant normal load: the drivers behind :meth:`Contact.torsion` and
:meth:`Contact.twist_history`, and their results :class:`TorsionState` and :class:`TwistHistory`.

The three models (``method=``: ``"no-slip"``, ``"exact"``, ``"mdr"``) are the classes of
:data:`contactlab.physics.torsion.METHODS`, one face each; this module validates, broadcasts, picks
the model, and turns the kernel's absolute error estimates into relative ones. Twist histories
follow Masing's rule with turning-point memory (:func:`contactlab.physics.masing.masing_program`),
exact for both the exact solution and the MDR springs.
"""
from __future__ import annotations

import difflib
import math
import warnings
from dataclasses import dataclass, field
from functools import cached_property
from typing import Any, ClassVar

import numpy as np

from ..citations import Cited, sources_for
from ..errors import NotSupportedError, ParameterError, UnknownNameError, ValidityWarning
from ..params import (as_float_array, broadcast_inputs, check_memory, check_time, exactly_one,
                      scalar_or_array)
from ..physics import normal as _normal
from ..physics import torsion as _models
from ..physics import torsion_exact as _exact
from ..physics import torsion_noslip as _noslip
from ..physics.masing import masing_dissipation, masing_program, masing_response, merge_close, merge_step
from ..physics.torsion import (MDR_ERROR_THRESHOLD, MDR_VALID_STICK_RATIO, METHODS, ROOT_SAFETY)
from ..physics import model_error as _maps
from ..profiles.base import ROUNDING
from ._protocol import Result, reporting
from .sizes import (TORSION_FIELD_BYTES_PER_POINT, check_elements, check_field,
                    torsion_bytes_per_load)

__all__ = ["TorsionState", "TwistHistory", "METHODS", "MDR_ERROR_THRESHOLD",
           "MDR_VALID_STICK_RATIO", "solve_torsion", "twist_history", "mdr_torque_error",
           "mdr_validity_twist", "torsion_model", "resolve_method", "mdr_map_errors",
           "STATE_UNITS", "MDR_MAP_BASIS", "history_model_errors"]


def _scalar_or_array(v: np.ndarray) -> Any:
    return scalar_or_array(v)


def resolve_method(contact, method: str | None) -> str:
    """Default and validate ``method`` for ``contact`` (friction decides the default)."""
    if method is None:
        # the default is checked like an explicit choice: friction + adhesion has no default
        method = "no-slip" if contact.friction is None else "exact"
    if method not in METHODS:
        close = difflib.get_close_matches(str(method), METHODS, n=1)
        hint = f" Did you mean {close[0]!r}?" if close else ""
        raise UnknownNameError(f"method={method!r} is invalid: torsion models are "
                               f"{', '.join(repr(m) for m in METHODS)}.{hint}")
    if method != "no-slip":
        if contact.friction is None:
            raise ParameterError(
                f"method={method!r} needs a friction coefficient, but friction=None: give "
                "Contact(..., friction=mu) or use method='no-slip'.")
        if contact.is_adhesive:
            raise NotSupportedError(
                f"method={method!r} with work_of_adhesion={contact.work_of_adhesion!r}: torsion with "
                "slip of adhesive contacts is outside the implemented theory; use "
                "method='no-slip' (friction is then ignored).")
    return method


#: units of the columns of a torsion state and of a twist history (CSV headers)
STATE_UNITS = {"twist": "rad", "torque": "N*m", "stick_radius": "m", "radius": "m", "slip": "1",
               "dissipated_energy": "J"}
#: where the MDR torsion model's ``model_error`` comes from
MDR_MAP_BASIS = ("measured MDR-vs-exact map (docs/torsion.md, "
                 "contactlab.physics.model_error): the largest error of the profile's family "
                 "from c/a = 1 down to the ladder point below the exact stick ratio of the "
                 "largest twist")


def mdr_map_errors(contact, twist: np.ndarray, a: np.ndarray, d: np.ndarray, g_a: np.ndarray,
                   quantities: tuple[str, ...] = ("torque",)) -> dict[str, np.ndarray]:
    """Conservative relative errors of the MDR torsion model at twist magnitudes ``twist`` (rad)
    of normal states ``(a, d, g_a)`` (flat arrays), from the measured maps of
    :mod:`contactlab.physics.model_error` (0 without contact or twist)."""
    twist, a, d, g_a = (np.asarray(v, float).ravel() for v in (twist, a, d, g_a))
    k = _maps.ladder_index(contact.profile, contact.moduli.normal, contact.moduli.torsional,
                           contact.friction, twist, a, d, g_a, contact.rtol)
    live = (a > 0) & (twist != 0)
    return {q: np.where(live, _maps.error_at_index(contact.profile, q, k), 0.0)
            for q in quantities}


def _g_of_radii(profile, a: np.ndarray) -> np.ndarray:
    """``g(a)`` once per distinct contact radius (a torque-twist curve repeats one radius for
    every twist; on a large table each ``g`` costs a sum over its nodes). ``g`` is evaluated
    point by point, so the values are those of the full array."""
    if a.size > 1 and np.all(a == a[0]):
        return np.broadcast_to(profile._g(a[:1]), a.shape).copy()
    return profile._g(a)


# ====================================================================== monotonic torsion
@reporting()
def solve_torsion(contact, *, depth: Any = None, force: Any = None, radius: Any = None,
                  twist: Any = None, torque: Any = None, stick_radius: Any = None,
                  method: str | None = None) -> TorsionState:
    """Implementation of :meth:`contactlab.Contact.torsion` (see there)."""
    method = resolve_method(contact, method)
    load_key, load_val = exactly_one("torsion()", {"depth": depth, "force": force,
                                                   "radius": radius})
    ctrl_key, ctrl_val = exactly_one("torsion()", {"twist": twist, "torque": torque,
                                                   "stick_radius": stick_radius})
    ctrl = as_float_array(ctrl_key, ctrl_val)
    shape = broadcast_inputs("torsion()", **{load_key: as_float_array(load_key, load_val),
                                              ctrl_key: ctrl})
    check_elements("torsion()", math.prod(shape), torsion_bytes_per_load(method, contact.profile),
                   f"{load_key} x {ctrl_key} broadcast to {shape}, method={method!r}")
    normal = contact.normal(**{load_key: load_val})
    a = np.broadcast_to(normal._radius, shape).astype(float).ravel()
    d = np.broadcast_to(normal._depth, shape).astype(float).ravel()
    g_a = np.where(a > 0, _g_of_radii(contact.profile, a), 0.0) if a.size else a.copy()
    if np.isfinite(contact.profile.wall_radius):
        g_a = np.where(a >= contact.profile.wall_radius, np.minimum(g_a, d), g_a)
    q = np.broadcast_to(ctrl, shape).astype(float).ravel()
    model = torsion_model(contact, method)
    sol = {"twist": model.of_twist, "torque": model.of_torque,
           "stick_radius": model.of_stick_radius}[ctrl_key](q, a, d, g_a)
    phi, M, c = sol.twist, sol.torque, sol.stick_radius
    slip = (c <= 0) & (phi != 0) & (method != "no-slip")
    if ctrl_key == "torque" and np.any(np.isinf(phi)):
        i = int(np.argmax(np.isinf(phi)))
        warnings.warn(
            f"torque={float(q[i])!r} N·m is the full-sliding torque of the {method!r} model at "
            f"this normal load: the whole contact slides and the twist that reaches it is "
            f"unbounded (twist=inf at {int(np.count_nonzero(np.isinf(phi)))} state(s)). Give "
            "twist= to prescribe the sliding.", ValidityWarning, stacklevel=4)
    if method == "mdr":
        _warn_mdr(contact, phi, a, d, g_a)
    # relative errors (issue 7): the kernel's absolute estimates, plus the normal solution's own
    # relative error (torques and twists scale with the pressure, hence with the normal force)
    n_rel = np.broadcast_to(np.asarray(normal.meta.get("error_estimate", 0.0), float),
                            shape).ravel()
    with np.errstate(divide="ignore", invalid="ignore"):
        rel_M = np.where(M != 0, sol.torque_error / np.abs(M), 0.0) + np.where(M != 0, n_rel, 0.0)
        rel_phi = (np.where(np.isfinite(phi) & (phi != 0), sol.twist_error / np.abs(phi), 0.0)
                   + np.where(np.isfinite(phi) & (phi != 0) & (ctrl_key != "twist"), n_rel, 0.0))
    deferred = sol.torque_error_deferred
    meta = {"rtol": contact.rtol, "control": ctrl_key, "load": load_key,
            "routes": {"g": contact.profile.g_route},
            "moduli": {"G_t": contact.moduli.torsional, "E_star": contact.moduli.normal},
            "error_estimate": _scalar_or_array(rel_M.reshape(shape)),
            "twist_error_estimate": _scalar_or_array(rel_phi.reshape(shape)),
            "citations": sources_for("normal", f"torsion:{method}")}
    if deferred is not None:
        absM = np.abs(M)

        def add_root_term() -> Any:
            with np.errstate(divide="ignore", invalid="ignore"):
                extra = np.where(absM != 0, deferred() / absM, 0.0)
            return _scalar_or_array((rel_M + extra).reshape(shape))

        meta["error_estimate"] = None          # filled on first access of .error_estimate
        meta["_error_estimate_pending"] = add_root_term
    twist_s, torque_s, stick_s, slip_s, a_s, d_s, g_s = (
        v.reshape(shape) for v in (phi, M, c, slip, a, d, g_a))
    return TorsionState(contact, normal, method, shape, twist_s, torque_s, stick_s, slip_s, a_s,
                        d_s, g_s, meta=meta)


def mdr_torque_error(contact, phi: np.ndarray, M_mdr: np.ndarray, a: np.ndarray,
                     d: np.ndarray, g_a: np.ndarray) -> np.ndarray:
    """Relative error ``M_MDR/M_exact - 1`` of MDR torques at the same twists (flat arrays)."""
    return _models.mdr_torque_error(contact.profile, contact.moduli.normal,
                                    contact.moduli.torsional, contact.friction, phi, M_mdr, a, d,
                                    g_a, contact.rtol)


def mdr_validity_twist(contact, a: np.ndarray, d: np.ndarray, g_a: np.ndarray) -> np.ndarray:
    """Twist (rad) beyond which the MDR torque errs by more than :data:`MDR_ERROR_THRESHOLD`: the
    exact twist at the stick radius ``MDR_VALID_STICK_RATIO * a`` (flat arrays)."""
    return _models.mdr_validity_twist(contact.profile, contact.moduli.normal,
                                      contact.moduli.torsional, contact.friction, a, d, g_a,
                                      contact.rtol)


def _warn_mdr(contact, phi: np.ndarray, a: np.ndarray, d: np.ndarray, g_a: np.ndarray) -> None:
    """Warn where the MDR torque errs by more than :data:`MDR_ERROR_THRESHOLD` (see above).

    Many states are screened first (:func:`~contactlab.physics.torsion_validity.
    screen_twist_at_stick_ratio`, a fixed rule with an error bound): the exact limit is computed
    only for the states the bound cannot settle, those that may exceed their limit and may
    hold the largest ratio of twist to limit. The warning (and its numbers) is the one the
    exact limits of every state give.
    """
    from ..physics.torsion_validity import screen_twist_at_stick_ratio
    screen = screen_twist_at_stick_ratio(contact.profile, contact.moduli.normal,
                                         contact.moduli.torsional, contact.friction,
                                         MDR_VALID_STICK_RATIO, a, d)
    if screen is None:
        cand = np.arange(a.size)
    else:
        L_f, m = screen
        with np.errstate(divide="ignore", invalid="ignore"):
            r_f = np.abs(phi) / L_f
        maybe_bad = r_f > 1.0 - m
        if not np.any(maybe_bad):
            return
        top = float(np.max(r_f / (1.0 + m)))
        with np.errstate(invalid="ignore"):
            cand = np.flatnonzero(maybe_bad & ((r_f >= top * (1.0 - m)) | ~np.isfinite(m)))
    limit = mdr_validity_twist(contact, a[cand], d[cand], g_a[cand])
    phi = phi[cand]
    bad = np.abs(phi) > limit
    if np.any(bad):
        i = int(np.argmax(np.abs(phi) / limit))
        warnings.warn(
            f"MDR torsion model outside its validity: twist {abs(float(phi[i])):.4g} rad exceeds "
            f"{float(limit[i]):.4g} rad, where the exact stick radius falls below c/a="
            f"{MDR_VALID_STICK_RATIO}; the slip annulus is then so wide that the MDR torque errs "
            f"by more than {MDR_ERROR_THRESHOLD:.0%} against the exact solution (up to +27% at full "
            "sliding). Use method='exact'.", ValidityWarning, stacklevel=4)


def torsion_model(contact, method: str) -> _models.TorsionModel:
    """The torsion model ``method`` (a key of :data:`METHODS`) of ``contact``."""
    return METHODS[method](contact.profile, contact.moduli.normal, contact.moduli.torsional,
                           contact.friction, contact.rtol)


@dataclass(frozen=True, eq=False)
class TorsionState(Result, Cited):
    """State of a twisted contact at constant normal load (one or an array of states).

    Attributes
    ----------
    twist : float or ndarray
        Twist angle ``φ``, rad (``inf`` for a torque equal to the sliding torque).
    torque : float or ndarray
        Torque ``M``, N·m (same sense as the twist).
    stick_radius : float or ndarray
        Radius ``c`` of the central stick zone, m (``= radius`` without slip, 0 at full sliding).
    slip : bool or ndarray
        Full sliding (no stick zone left, to double precision).
    method : str
        ``"no-slip"``, ``"exact"`` or ``"mdr"``.
    normal : NormalState
        The normal preload (its own shape; torsion arrays broadcast it with the twist input).
    meta : dict
        ``rtol``, ``control``, ``load``, ``routes``, ``moduli``, ``error_estimate`` (relative,
        torque; under twist control at ``rtol > 1e-9`` it is ``None`` until
        :attr:`error_estimate` is first read, which pays one extra batched quadrature),
        ``twist_error_estimate`` (relative), ``notes`` (warnings raised).
    model_error : float or ndarray
        ``method="mdr"``: relative torque error of the MDR model against the exact solution at
        the same twist, from the measured map (:attr:`model_error_basis`; one slip function per
        ladder point and normal state, on first access); 0.0 for the exact and no-slip models.

    Notes
    -----
    Field methods :meth:`shear` and :meth:`displacement` return arrays of shape
    ``state.shape + r.shape``; they are computed on request (nested quadratures for the exact model).
    """

    contact: Any = field(repr=False)
    normal: Any = field(repr=False)
    method: str
    shape: tuple
    _twist: np.ndarray = field(repr=False)
    _torque: np.ndarray = field(repr=False)
    _stick: np.ndarray = field(repr=False)
    _slip: np.ndarray = field(repr=False)
    _a: np.ndarray = field(repr=False)
    _d: np.ndarray = field(repr=False)
    _g_a: np.ndarray = field(repr=False)
    meta: dict = field(default_factory=dict, repr=False)

    units: ClassVar[dict[str, str]] = {
        k: STATE_UNITS[k] for k in ("twist", "torque", "stick_radius", "radius", "slip")}
    _basis = MDR_MAP_BASIS

    def __repr__(self) -> str:
        return self._summary_repr(method=self.method)

    def to_dict(self) -> dict[str, Any]:
        """The state's quantities by name (``twist``, ``torque``, ``stick_radius``, ``radius``,
        ``slip``; scalars or arrays of the state's shape)."""
        return {"twist": self.twist, "torque": self.torque, "stick_radius": self.stick_radius,
                "radius": self.radius, "slip": self.slip}

    def _model_errors(self) -> dict[str, Any]:
        if self.method != "mdr":
            return {}
        err = mdr_map_errors(self.contact, self._twist, self._a, self._d, self._g_a)
        return {"torque": _scalar_or_array(err["torque"].reshape(self.shape))}

    @property
    def twist(self) -> Any:
        return _scalar_or_array(self._twist)

    @property
    def torque(self) -> Any:
        return _scalar_or_array(self._torque)

    @property
    def stick_radius(self) -> Any:
        return _scalar_or_array(self._stick)

    @property
    def slip(self) -> Any:
        return _scalar_or_array(self._slip)

    @property
    def error_estimate(self) -> Any:
        """Estimated relative error of :attr:`torque` (also ``meta["error_estimate"]``).

        Quadrature estimates of the torque integral (exact: ``T(c)``; MDR: the annulus integral),
        the rounding of the closed-form parts and the relative error of the normal solution. Under
        twist control the stick-radius root enters only at second order (the torque at fixed
        twist is stationary in ``c``); under torque control it is the residual of the returned
        state against the requested torque. docs/accuracy.md gives the measured honesty.
        """
        pending = self.meta.pop("_error_estimate_pending", None)
        if pending is not None:         # twist control at loose rtol: computed on first access
            self.meta["error_estimate"] = pending()
        return self.meta.get("error_estimate", 0.0)

    @cached_property
    def error_estimates(self) -> dict[str, Any]:
        """Estimated relative errors ``{"torque", "twist", "stick_radius"}`` of this state.

        The twist error under torque control maps the torque residual and quadrature error
        through ``dM = (16/3) G_t c³ dφ``; the stick-radius error maps the twist-side error (the
        root's actual residual and the quadrature error of ``P``) through ``dφ/dc``, found by a
        central difference (three extra evaluations of ``P``, done on first access only). 0 where
        the quantity is 0 or ``inf``.
        """
        return {"torque": self.error_estimate,
                "twist": self.meta.get("twist_error_estimate", 0.0),
                "stick_radius": _scalar_or_array(self._stick_error().reshape(self.shape))}

    def _stick_error(self) -> np.ndarray:
        c = self._stick.ravel().astype(float)
        a = self._a.ravel()
        out = np.zeros(c.shape)
        part = (c > 0) & (c < a)
        if self.method == "no-slip" or not np.any(part):
            return out
        ct = self.contact
        control = self.meta.get("control")
        if control == "stick_radius":
            out[part] = ROUNDING
            return out
        cp, ap = c[part], a[part]
        dp, gp = self._d.ravel()[part], self._g_a.ravel()[part]
        phi = np.abs(self._twist.ravel()[part])
        mu, G, E, rtol = ct.friction, ct.moduli.torsional, ct.moduli.normal, ct.rtol
        h = 0.1 * np.minimum(cp, ap - cp)      # the slope is needed to a factor ~2 only
        if self.method == "exact":
            P_lo, _ = _exact.slip_function(ct.profile, E, cp - h, ap, dp, gp, rtol)
            P_hi, _ = _exact.slip_function(ct.profile, E, cp + h, ap, dp, gp, rtol)
            dphi_dc = mu / (2 * G) * (P_hi - P_lo) / (2 * h)
            P_c, P_err = _exact.slip_function(ct.profile, E, cp, ap, dp, gp, rtol)
            P_err = _exact.sharpen_error(P_err, P_c)
            # twist side: quadrature of P and the actual residual of the root at c
            dphi = mu / (2 * G) * (P_err + np.abs(P_c - 2 * G * phi / mu))
        else:
            # root of f(c) = 4G_tφc/(μE*) + g(c) = d: its actual residual at c
            k = 4.0 * G / (mu * E)
            f_lo = k * phi * (cp - h) + ct.profile._g(cp - h)
            f_hi = k * phi * (cp + h) + ct.profile._g(cp + h)
            dphi_dc = (f_hi - f_lo) / (2 * h)
            f_c = k * phi * cp + ct.profile._g(cp)
            dphi = np.abs(f_c - dp) + 4 * ROUNDING * dp
        rel_tw = np.asarray(self.meta.get("twist_error_estimate", 0.0), float)
        if control == "torque":
            dphi = np.broadcast_to(rel_tw, self.shape).ravel()[part] * (
                phi if self.method == "exact" else k * phi * cp)
        with np.errstate(divide="ignore", invalid="ignore"):
            dc = ROOT_SAFETY * np.abs(dphi / dphi_dc)
        out[part] = np.where(np.isfinite(dc), dc / cp, np.inf) + 4 * ROUNDING
        return out

    @property
    def radius(self) -> Any:
        """Contact radius ``a``, m (broadcast to the state's shape)."""
        return _scalar_or_array(self._a)

    @property
    def stiffness(self) -> Any:
        """Incremental torsional stiffness ``dM/dφ = (16/3) G_t c³``, N·m/rad (theory §6.2)."""
        return _scalar_or_array(16.0 / 3.0 * self.contact.moduli.torsional * self._stick**3)

    @cached_property
    def _sliding(self) -> np.ndarray:
        k = torsion_model(self.contact, self.method)
        return k.sliding_torque(self._a.ravel(), self._d.ravel()).reshape(self.shape)

    @property
    def sliding_torque(self) -> Any:
        """Full-sliding torque of the model at this normal load, N·m (``inf`` for no slip)."""
        return _scalar_or_array(self._sliding)

    def _field_setup(self, r: Any, what: str):
        r = as_float_array("r", r)
        check_field(what, self.shape, r.shape, TORSION_FIELD_BYTES_PER_POINT[self.method])
        if np.any(r < 0):
            raise ParameterError(f"r contains {r[r < 0].ravel()[0]!r}: radii must be >= 0 m.")
        full = self.shape + r.shape
        ext = (1,) * r.ndim
        R = np.broadcast_to(r, full).ravel()
        A = np.broadcast_to(self._a.reshape(self.shape + ext), full).ravel()
        D = np.broadcast_to(self._d.reshape(self.shape + ext), full).ravel()
        GA = np.broadcast_to(self._g_a.reshape(self.shape + ext), full).ravel()
        PHI = np.broadcast_to(self._twist.reshape(self.shape + ext), full).ravel()
        C = np.broadcast_to(self._stick.reshape(self.shape + ext), full).ravel()
        return full, R, A, D, GA, PHI, C

    def shear(self, r: Any) -> Any:
        """Circumferential traction ``τ(r)``, Pa, at radii ``r`` (m); 0 outside the contact.

        Exact model: ``μ p(r)`` in the slip annulus ``c <= r < a`` and the stick-zone solution of
        theory §6.2 item 5 inside (continuous at ``r = c``, ``τ(0) = 0``, ``|τ| <= μ p``).
        MDR: the traction of the MDR twist distribution (§8 item 1). No slip: Reissner-Sagoci.
        Singular points return ``inf`` (no-slip edge).
        """
        full, R, A, D, GA, PHI, C = self._field_setup(r, "shear()")
        G = self.contact.moduli.torsional
        sgn = np.sign(PHI)
        phi = np.abs(PHI)
        if self.method == "no-slip":
            return _scalar_or_array(_noslip.shear(G, R, A, PHI).reshape(full))
        out = np.zeros(R.shape)
        rtol = self.contact.rtol
        k = torsion_model(self.contact, self.method)
        inside = (R < A) & (R > 0) & (phi > 0)
        stick = inside & (R < C)
        slipz = inside & (R >= C)
        if self.method == "exact" and np.any(slipz):
            p, _ = _normal.pressure(self.contact.profile, self.contact.moduli.normal, R[slipz],
                                    A[slipz], D[slipz], GA[slipz], rtol)
            out[slipz] = self.contact.friction * p
        elif np.any(slipz):
            i = np.flatnonzero(slipz)
            psi = k.psi(A[i], D[i], GA[i])
            psi_l = psi(R[i][:, None], np.arange(i.size))[:, 0]
            out[i] = _exact.stick_shear(psi, psi_l, G, R[i], R[i], A[i], rtol)
        if np.any(stick):
            i = np.flatnonzero(stick)
            psi = k.psi(A[i], D[i], GA[i])
            out[i] = _exact.stick_shear(psi, phi[i], G, R[i], C[i], A[i], rtol)
        return _scalar_or_array((sgn * out).reshape(full))

    def displacement(self, r: Any) -> Any:
        """Circumferential surface displacement ``u_φ(r)``, m, inside and outside the contact.

        ``φ r`` in the stick zone; theory §6.2 item 6 elsewhere (with the MDR twist
        distribution for ``method="mdr"``); Reissner-Sagoci for no slip. Decays as
        ``M/(4π G_t r²)`` far away.
        """
        full, R, A, D, GA, PHI, C = self._field_setup(r, "displacement()")
        if self.method == "no-slip":
            return _scalar_or_array(_noslip.displacement(R, A, PHI).reshape(full))
        sgn = np.sign(PHI)
        phi = np.abs(PHI)
        out = np.zeros(R.shape)
        live = (A > 0) & (phi > 0) & np.isfinite(phi)
        if np.any(live):
            i = np.flatnonzero(live)
            k = torsion_model(self.contact, self.method)
            psi_all = k.psi(A[i], D[i], GA[i])
            out[i] = _exact.circumferential_displacement(psi_all, phi[i], R[i], C[i], A[i],
                                                         self.contact.rtol)
        if np.any(~np.isfinite(phi) & (A > 0)):
            raise NotSupportedError("displacement() at full sliding (infinite twist) is undefined; "
                                    "prescribe a finite twist.")
        return _scalar_or_array((sgn * out).reshape(full))

    # ---- subsurface stresses (contactlab.effects.stress does the work)
    def stress(self, r: Any, z: Any, body: int = 1, part: str = "total") -> Any:
        """Subsurface stress field (a ``StressField``) at radii ``r`` and depths ``z`` (m): the
        normal preload's field plus the torsional ``σ_θz, σ_rθ`` (``part="friction"``: the
        torsional part alone). Body 1 receives the traction :meth:`shear` reports; body 2 its
        opposite. See docs/stress.md."""
        from .stress import torsion_stress
        return torsion_stress(self, r, z, body, part)

    def max_stress(self, kind: str = "von_mises", body: int = 1) -> Any:
        """Largest ``kind`` of the whole field in body 1 or 2 and its location."""
        from .stress import torsion_max_stress
        return torsion_max_stress(self, kind, body)

    def stress_field(self, grid: Any = None, body: int = 1, part: str = "total") -> Any:
        """Stress field on a 2D grid ``(r_values, z_values)`` for plots (default 200 x 100)."""
        from .stress import torsion_stress_field
        return torsion_stress_field(self, grid, body, part)


# ====================================================================== twist histories
#: peak memory of the turning-point bookkeeping and the per-step arrays of a history, bytes per
#: step: 254-343 B measured with tracemalloc at 10^5 steps (sine sweeps and random walks, whose
#: loop closures add branch segments), rounded up; checked before the history is walked
HISTORY_BYTES_PER_STEP = 512
#: peak memory of the loading-curve solve per distinct twist argument, bytes, by method:
#: measured with tracemalloc at 10^4-10^5 arguments, exact 0.2-1.7 KB for the closed-form routes
#: (paraboloid, power law n = 4) and 17.1 KB for the quadrature route (cone), mdr 2.9 KB; the
#: largest, rounded up (no-slip: the closed form, like the bookkeeping)
SOLVE_BYTES_PER_ARGUMENT = {"exact": 20 * 1024, "mdr": 4 * 1024, "no-slip": 512}
#: run time of a history's bookkeeping (turning points, the Masing response, the dissipation),
#: s per step, and of the loading-curve solve, s per distinct twist argument, by method; checked
#: against the time budget before any work (steps) and before the solve (distinct arguments).
#: Measured (CPU time, shared 2-core VM at load ~3.5, paraboloid, random walks of 10^4-10^5
#: steps): exact 5.4-40 µs per step in all (33-38 µs on the cone's quadrature route), mdr
#: 2.5-3.8 µs; taken at about 0.4 of the smallest (a lower estimate: a refused history takes at
#: least that long; benchmarks/time_estimates.py checks it)
HISTORY_SECONDS_PER_STEP = 5e-7
SOLVE_SECONDS_PER_ARGUMENT = {"exact": 2e-6, "mdr": 1e-6, "no-slip": 0.0}


@reporting()
def twist_history(contact, *, twist: Any, depth: Any = None, force: Any = None,
                  method: str | None = None) -> TwistHistory:
    """Implementation of :meth:`contactlab.Contact.twist_history` (see there)."""
    method = resolve_method(contact, method)
    load_key, load_val = exactly_one("twist_history()", {"depth": depth, "force": force})
    load = as_float_array(load_key, load_val)
    if load.ndim != 0:
        raise ParameterError(f"{load_key} has shape {load.shape}: twist_history() holds the normal "
                             "load constant; give a scalar.")
    phi = as_float_array("twist", twist)
    if phi.ndim != 1:
        raise ParameterError(f"twist has shape {phi.shape}: give a 1D array of twist angles (rad), "
                             "one per step.")
    check_memory("twist_history()", float(phi.size) * HISTORY_BYTES_PER_STEP,
                 f"twist: {phi.size} steps x {HISTORY_BYTES_PER_STEP} B")
    check_time("twist_history()", float(phi.size) * HISTORY_SECONDS_PER_STEP,
               f"twist: {phi.size} steps x {HISTORY_SECONDS_PER_STEP * 1e6:g} us of bookkeeping")
    normal = contact.normal(**{load_key: float(load)})
    origin, factor, arg, segs = masing_program(phi)
    model = torsion_model(contact, method)
    a = float(normal._radius)
    d = float(normal._depth)
    g_a = float(contact.profile._g(np.array(a))) if a > 0 else 0.0
    if np.isfinite(contact.profile.wall_radius) and a >= contact.profile.wall_radius:
        g_a = min(g_a, d)
    # the loading curve at every distinct argument, one batched solve; near-duplicates (closer
    # than merge_step: 1e-11 of the largest argument at rtol 1e-10) share one solve, so rounding
    # jitter of the amplitudes does not multiply the solves (cost follows the steps)
    u_arg, inv, shift = merge_close(arg, merge_step(np.max(arg, initial=0.0), contact.rtol))
    inv = inv.ravel()
    per = SOLVE_BYTES_PER_ARGUMENT.get(method, max(SOLVE_BYTES_PER_ARGUMENT.values()))
    check_memory("twist_history()", float(u_arg.size) * per,
                 f"twist: {u_arg.size} distinct amplitudes of the {phi.size} steps x {per} B for "
                 f"the method={method!r} loading curve")
    solve = SOLVE_SECONDS_PER_ARGUMENT.get(method, max(SOLVE_SECONDS_PER_ARGUMENT.values()))
    check_time("twist_history()", phi.size * HISTORY_SECONDS_PER_STEP + u_arg.size * solve,
               f"twist: {phi.size} steps x {HISTORY_SECONDS_PER_STEP * 1e6:g} us of bookkeeping "
               f"and {u_arg.size} distinct amplitudes x {solve * 1e6:g} us for the "
               f"method={method!r} loading curve")
    A = np.full(u_arg.shape, a)
    Dd = np.full(u_arg.shape, d)
    GA = np.full(u_arg.shape, g_a)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ValidityWarning)     # judged on the history below
        sol = model.of_twist(u_arg, A, Dd, GA)
    M_u, c_u = sol.torque, sol.stick_radius
    M_load = M_u[inv]
    c = c_u[inv]
    k_t = 16.0 / 3.0 * contact.moduli.torsional
    if np.any(shift > 0):
        # a merged step moves along the loading curve from its group's representative with the
        # curve's tangent stiffness, that of the stick zone, (16/3) G_t c³ [J95]; the slope lies
        # in [0, (16/3) G_t a³], so the linearisation errs by at most that bound times the shift
        dphi = arg - u_arg[inv]
        M_load = M_load + k_t * np.where(np.isfinite(c), c, 0.0) ** 3 * dphi
        shift = shift * (k_t * a**3)
    torque = masing_response(phi, origin, factor, M_load)
    meta = {"rtol": contact.rtol, "load": load_key, "method": method,
            "moduli": {"G_t": contact.moduli.torsional, "E_star": contact.moduli.normal},
            "citations": sources_for("normal", f"torsion:{method}", "masing:torsion")}
    deferred = None
    if method == "mdr":
        _warn_mdr(contact, u_arg, A, Dd, GA)
        deferred = _mdr_history_errors(contact, meta, float(np.max(u_arg, initial=0.0)), a, d,
                                       g_a)
    # error bookkeeping for torque_error (computed on first access): the loading curve's
    # absolute errors at the distinct arguments, its deferred root term, and the recursion
    errors = (sol.torque_error + shift, sol.torque_error_deferred,
              inv, origin, factor, float(normal.meta.get("error_estimate", 0.0)))
    hist = TwistHistory(contact, normal, method, phi.copy(), torque, c, (a, d, g_a), segs, meta,
                        errors)
    if deferred is not None:
        hist._defer_model_errors(deferred)
    return hist


def history_model_errors(contact, arg: float, a: float, d: float, g_a: float
                         ) -> dict[str, float]:
    """``model_errors`` of an MDR twist history: torque and dissipated energy from the measured
    maps at the largest loading-curve argument ``arg`` (rad; every step of a Masing history is
    a loading-curve value at an argument up to it) of the normal state ``(a, d, g_a)``."""
    errs = mdr_map_errors(contact, np.array([arg]), np.array([a]), np.array([d]),
                          np.array([g_a]), ("torque", "energy"))
    return {"torque": float(errs["torque"][0]), "dissipated_energy": float(errs["energy"][0])}


def _mdr_history_errors(contact, meta: dict, arg: float, a: float, d: float, g_a: float):
    """Defer the ``model_errors`` of an MDR twist history (:func:`history_model_errors`, on first
    access; returns the callable); warn now when the largest twist passes the energy validity limit,
    the exact twist at ``c/a = 0.97`` (beyond it the MDR energy errs by more than 1 %; one slip
    function, the criterion of the fretting functions)."""
    from functools import partial

    from ..physics.fretting import MDR_VALID_STICK_RATIOS, mdr_validity_twists
    meta["model_error_basis"] = MDR_MAP_BASIS
    lim = float(mdr_validity_twists(contact.profile, contact.moduli.normal,
                                    contact.moduli.torsional, contact.friction, np.array([a]),
                                    np.array([d]), np.array([g_a]), ("energy",),
                                    contact.rtol)["energy"][0])
    if a > 0 and arg > lim:
        warnings.warn(
            f"MDR torsion model: the dissipated energy of this twist history errs by more than "
            f"1 % against the exact solution: the largest twist {arg:.4g} rad exceeds "
            f"{lim:.4g} rad, where the exact stick ratio falls below c/a = "
            f"{MDR_VALID_STICK_RATIOS['energy']} (the energy is the most sensitive quantity; "
            "result.model_errors gives the measured bound). Use method='exact'.",
            ValidityWarning, stacklevel=4)
    return partial(history_model_errors, contact, arg, a, d, g_a)


@dataclass(frozen=True, eq=False)
class TwistHistory(Result, Cited):
    """Response to a twist history at constant normal load (Masing rule with turning-point memory).

    Attributes
    ----------
    twist : ndarray
        Prescribed twist per step, rad (the history starts from the untwisted virgin state).
    torque : ndarray
        Torque per step, N·m.
    stick_radius : ndarray
        Radius of the central zone that has not slipped since the last turning point, m.
    dissipated_energy : ndarray
        Cumulative energy dissipated by friction, J (computed on first access).
    torque_error, error_estimate : ndarray, float
        Estimated absolute torque error per step (N·m) and its maximum relative to the torque
        amplitude (computed on first access).
    method : str
        ``"exact"``, ``"mdr"`` or ``"no-slip"``.
    normal : NormalState
        The constant normal preload.
    model_error : float
        ``method="mdr"``: the larger relative error of the torque and the dissipated energy
        against the exact solution (:attr:`model_errors`), from the measured MDR-vs-exact maps
        at the exact stick ratio of the largest twist of the history; 0.0 for the exact and
        no-slip models.

    Notes
    -----
    After a reversal at ``(φ_r, M_r)``: ``M = M_r ± 2 M_load(|φ - φ_r|/2)``; a branch that passes
    an older turning point closes that loop, which is then forgotten (theory §6.5). Exact for
    the exact solution (flat-punch superposition) and for the MDR springs (Jenkins elements).
    The dissipated energy uses the Jenkins-element (Iwan) form of both models: along a branch
    ``D = D_r + 2 D_load(|φ - φ_r|/2)`` with ``D_load`` the energy dissipated under monotonic
    loading (see :func:`contactlab.physics.torsion_exact.dissipation_integral`).
    """

    contact: Any = field(repr=False)
    normal: Any = field(repr=False)
    method: str
    twist: np.ndarray = field(repr=False)
    torque: np.ndarray = field(repr=False)
    stick_radius: np.ndarray = field(repr=False)
    _state: tuple = field(repr=False)
    _segments: tuple = field(repr=False)
    meta: dict = field(default_factory=dict, repr=False)
    _errors: tuple = field(default=(), repr=False)

    units: ClassVar[dict[str, str]] = {
        k: STATE_UNITS[k] for k in ("twist", "torque", "stick_radius", "dissipated_energy")}
    _basis = MDR_MAP_BASIS

    @cached_property
    def torque_error(self) -> np.ndarray:
        """Estimated absolute error of :attr:`torque` per step, N·m (issue 7).

        Every step is ``M_r ± f M_load(arg)`` (Masing, ``f = 2`` after a reversal), so the error
        of the loading-curve values (quadrature estimates, rounding floors and the stick-radius
        root term of :attr:`TorsionState.error_estimate`) is carried through the same recursion,
        added in absolute value, plus the normal solution's relative error times ``|M|``.
        """
        if not self._errors:
            return np.zeros(self.torque.shape)
        err_u, deferred, inv, origin, factor, n_rel = self._errors
        if deferred is not None:
            err_u = err_u + deferred()
        err_load = err_u[inv]
        out = np.empty(self.torque.shape)
        for i in range(out.size):                              # O(1) per step
            o = origin[i]
            out[i] = (out[o] if o >= 0 else 0.0) + factor[i] * err_load[i]
        return out + n_rel * np.abs(self.torque)

    @property
    def error_estimate(self) -> float:
        """Estimated error of the torque history relative to its amplitude ``max|M|``."""
        amp = float(np.max(np.abs(self.torque), initial=0.0))
        return float(np.max(self.torque_error, initial=0.0)) / amp if amp > 0 else 0.0

    @property
    def slip(self) -> np.ndarray:
        """Full sliding at the step (no stick zone left)."""
        return (self.stick_radius <= 0) & (self.twist != 0) & (self.method != "no-slip")

    @cached_property
    def dissipated_energy(self) -> np.ndarray:
        a, d, g_a = self._state
        step, _po, _f, _p_from, _p_to = self._segments
        n = self.twist.size
        if self.method == "no-slip" or step.size == 0 or a <= 0:
            return np.zeros(n)
        model = torsion_model(self.contact, self.method)

        def loading(u: np.ndarray) -> np.ndarray:
            A = np.full(u.shape, a)
            Dd = np.full(u.shape, d)
            GA = np.full(u.shape, g_a)
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", ValidityWarning)
                sol = model.of_twist(u, A, Dd, GA)
            return model.dissipation(np.abs(sol.twist), sol.stick_radius, A, Dd, GA)

        return masing_dissipation(self._segments, n, loading, self.contact.rtol)

    def stress(self, r: Any, z: Any, *, step: int, body: int = 1, part: str = "total") -> Any:
        """Subsurface stress field (a ``StressField``) at ``step`` of the history, at radii
        ``r`` and depths ``z`` (m): the Masing sum of virgin torsion fields over the active
        turning points, plus the normal preload (``part="friction"``: without it)."""
        from .stress_history import history_stress
        return history_stress(self, r, z, step=step, body=body, part=part)

    def plot(self, axes: Any = None, *, units: str = "si"):
        """Torque–twist loop and stick radius per step (needs matplotlib); returns the two axes.

        ``units="engineering"`` labels mrad, mN·m and µm (see :mod:`contactlab.plotting`).
        """
        from .. import plotting as pl
        return pl.history(self.twist, self.torque, self.stick_radius, x_name="twist",
                          x_unit="rad", y_name="torque", y_unit="N*m", units=units, axes=axes,
                          title=f"twist history ({self.method})")

    def to_dict(self) -> dict[str, np.ndarray]:
        """Per-step arrays by name (``twist``, ``torque``, ``stick_radius``, ``dissipated_energy``)."""
        return {"twist": self.twist, "torque": self.torque, "stick_radius": self.stick_radius,
                "dissipated_energy": self.dissipated_energy}
