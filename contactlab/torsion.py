"""Torsion of an axisymmetric contact at constant normal load: solver, states, twist histories.

Three models (``method=``), physics.md §6:

* ``"no-slip"`` (μ → ∞): Reissner-Sagoci, ``M = (16/3) G_t a³ φ`` [RS44];
* ``"exact"``: Jäger's exact partial-slip solution for any profile [J95; S eq. 53];
* ``"mdr"``: the MDR narrow-slip spring model [S eqs. 47-52], fast, exact only as ``c → a``.

``G_t`` is the torsional modulus of the pair (``1/G_t = 1/G1 + 1/G2``), never the tangential ``G*``.
Twist histories follow Masing's rule with turning-point memory (physics.md §6.5), exact for both
the exact solution and the MDR springs.
"""
from __future__ import annotations

import warnings
from dataclasses import dataclass, field
from functools import cached_property
from typing import Any

import numpy as np

from .errors import (NotSupportedError, OutsideTheoryError, ParameterError, UnknownNameError,
                     ValidityWarning)
from .params import as_float_array
from .profiles.base import ROUNDING
from .physics import torsion_exact as _exact
from .physics import torsion_mdr as _mdr
from .physics import torsion_noslip as _noslip
from .physics import normal as _normal

__all__ = ["TorsionState", "TwistHistory", "METHODS", "MDR_ERROR_THRESHOLD",
           "MDR_VALID_STICK_RATIO", "solve_torsion", "twist_history", "mdr_torque_error",
           "mdr_validity_twist"]

#: Physics models of :meth:`Contact.torsion` (``method=``).
METHODS = ("no-slip", "exact", "mdr")

#: Relative torque error of the MDR model (vs the exact solution at the same twist) above which a
#: :class:`~contactlab.errors.ValidityWarning` is emitted.
MDR_ERROR_THRESHOLD = 0.01

#: Exact stick-radius ratio ``c/a`` below which the MDR torque errs by more than
#: :data:`MDR_ERROR_THRESHOLD` at the same twist. Measured by ``benchmarks/torsion_error_map.py``
#: (docs/torsion.md): as a function of the *exact* ``c/a`` the error is nearly universal, 1 % being
#: crossed at c/a = 0.80 (cone), 0.805 (paraboloid, truncated paraboloid), 0.81 (n = 4), 0.822
#: (n = 20) and 0.826 (flat punch). The MDR model warns when the twist exceeds the exact twist at
#: ``c = MDR_VALID_STICK_RATIO a`` (one quadrature per normal state, no exact root solve).
MDR_VALID_STICK_RATIO = 0.83

#: Safety factor on the root-solve terms of the error estimates (issue 7): they come from a
#: linearisation (first order in the residual) or a finite-difference curvature (second order);
#: measured on the honesty ladder of tests/test_torsion_error_estimate.py they were within 0.92x
#: of the actual error.
ROOT_SAFETY = 2.0

#: Twist control, exact model: above this ``rtol`` the second-order torque error of the stick-radius
#: root is estimated from the actual residual (one extra batched evaluation of ``P``); at or below
#: it the a-priori bound ``1e2 rtol² |M|`` (< 1e-16 relative) is used, so the default rtol pays
#: nothing for the estimate.
ROOT_TERM_RTOL = 1e-9


def _scalar_or_array(v: np.ndarray) -> Any:
    v = np.asarray(v)
    if v.dtype == bool:
        return bool(v) if v.ndim == 0 else v
    return float(v) if v.ndim == 0 else v


def resolve_method(contact, method: str | None) -> str:
    """Default and validate ``method`` for ``contact`` (friction decides the default)."""
    if method is None:
        return "no-slip" if contact.friction is None else "exact"
    if method not in METHODS:
        import difflib
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
                "slip of adhesive contacts is outside the implemented theory (physics.md §6); use "
                "method='no-slip'.")
    return method


def _one_of(kind: str, options: dict[str, Any]) -> tuple[str, Any]:
    given = {k: v for k, v in options.items() if v is not None}
    if len(given) != 1:
        raise ParameterError(f"{kind} needs exactly one of {', '.join(k + '=' for k in options)}; "
                             f"got {sorted(given) or 'none'}.")
    return next(iter(given.items()))


# ====================================================================== monotonic torsion
def solve_torsion(contact, *, depth: Any = None, force: Any = None, radius: Any = None,
                  twist: Any = None, torque: Any = None, stick_radius: Any = None,
                  method: str | None = None) -> "TorsionState":
    """Implementation of :meth:`contactlab.Contact.torsion` (see there)."""
    method = resolve_method(contact, method)
    load_key, load_val = _one_of("torsion()", {"depth": depth, "force": force, "radius": radius})
    ctrl_key, ctrl_val = _one_of("torsion()", {"twist": twist, "torque": torque,
                                               "stick_radius": stick_radius})
    ctrl = as_float_array(ctrl_key, ctrl_val)
    normal = contact.normal(**{load_key: load_val})
    shape = np.broadcast_shapes(normal.shape, ctrl.shape)
    a = np.broadcast_to(normal._radius, shape).astype(float).ravel()
    d = np.broadcast_to(normal._depth, shape).astype(float).ravel()
    g_a = np.where(a > 0, contact.profile._g(a), 0.0) if a.size else a.copy()
    if np.isfinite(contact.profile.wall_radius):
        g_a = np.where(a >= contact.profile.wall_radius, np.minimum(g_a, d), g_a)
    q = np.broadcast_to(ctrl, shape).astype(float).ravel()
    kernel = _MonotonicKernel(contact, method)
    if ctrl_key == "twist":
        phi, M, c = kernel.of_twist(q, a, d, g_a)
    elif ctrl_key == "torque":
        phi, M, c = kernel.of_torque(q, a, d, g_a)
    else:
        phi, M, c = kernel.of_stick_radius(q, a, d, g_a)
    slip = (c <= 0) & (phi != 0) & (method != "no-slip")
    if method == "mdr":
        _warn_mdr(contact, phi, a, d, g_a)
    # relative errors (issue 7): the kernel's absolute estimates, plus the normal solution's own
    # relative error (torques and twists scale with the pressure, hence with the normal force)
    n_rel = np.broadcast_to(np.asarray(normal.meta.get("error_estimate", 0.0), float),
                            shape).ravel()
    with np.errstate(divide="ignore", invalid="ignore"):
        rel_M = np.where(M != 0, kernel.err_torque / np.abs(M), 0.0) + np.where(M != 0, n_rel, 0.0)
        rel_phi = (np.where(np.isfinite(phi) & (phi != 0), kernel.err_twist / np.abs(phi), 0.0)
                   + np.where(np.isfinite(phi) & (phi != 0) & (ctrl_key != "twist"), n_rel, 0.0))
    deferred = getattr(kernel, "err_torque_deferred", None)
    meta = {"rtol": contact.rtol, "control": ctrl_key, "load": load_key,
            "routes": {"g": contact.profile.g_route},
            "moduli": {"G_t": contact.moduli.torsional, "E_star": contact.moduli.normal},
            "error_estimate": _scalar_or_array(rel_M.reshape(shape)),
            "twist_error_estimate": _scalar_or_array(rel_phi.reshape(shape))}
    if deferred is not None:
        absM = np.abs(M)

        def add_root_term() -> Any:
            with np.errstate(divide="ignore", invalid="ignore"):
                extra = np.where(absM != 0, deferred() / absM, 0.0)
            return _scalar_or_array((rel_M + extra).reshape(shape))

        meta["error_estimate"] = None          # filled on first access of .error_estimate
        meta["_error_estimate_pending"] = add_root_term
    return TorsionState(contact, normal, method, shape,
                        *(v.reshape(shape) for v in (phi, M, c, slip, a, d, g_a)), meta=meta)


def mdr_torque_error(contact, phi: np.ndarray, M_mdr: np.ndarray, a: np.ndarray,
                     d: np.ndarray, g_a: np.ndarray) -> np.ndarray:
    """Relative error ``M_MDR/M_exact - 1`` of MDR torques at the same twists (flat arrays)."""
    k = _MonotonicKernel(contact, "exact")
    _, M_ex, _ = k.of_twist(np.abs(phi), a, d, g_a)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(M_ex > 0, np.abs(M_mdr) / M_ex - 1.0, 0.0)


def mdr_validity_twist(contact, a: np.ndarray, d: np.ndarray, g_a: np.ndarray) -> np.ndarray:
    """Twist (rad) beyond which the MDR torque errs by more than :data:`MDR_ERROR_THRESHOLD`: the
    exact twist at the stick radius ``MDR_VALID_STICK_RATIO * a`` (flat arrays)."""
    out = np.full(a.shape, np.inf)
    live = a > 0
    if not np.any(live):
        return out
    keys, inv = np.unique(np.stack([a[live], d[live], g_a[live]], axis=1), axis=0,
                          return_inverse=True)
    ka, kd, kg = keys.T
    P, _ = _exact.slip_function(contact.profile, contact.moduli.normal, MDR_VALID_STICK_RATIO * ka,
                                ka, kd, kg, contact.rtol)
    out[live] = _exact.twist_of_stick(contact.friction, contact.moduli.torsional, P)[inv.ravel()]
    return out


def _warn_mdr(contact, phi: np.ndarray, a: np.ndarray, d: np.ndarray, g_a: np.ndarray) -> None:
    """Warn where the MDR torque errs by more than :data:`MDR_ERROR_THRESHOLD` (see above)."""
    limit = mdr_validity_twist(contact, a, d, g_a)
    bad = np.abs(phi) > limit
    if np.any(bad):
        i = int(np.argmax(np.abs(phi) / limit))
        warnings.warn(
            f"MDR torsion model outside its validity: twist {abs(float(phi[i])):.4g} rad exceeds "
            f"{float(limit[i]):.4g} rad, where the exact stick radius falls below c/a="
            f"{MDR_VALID_STICK_RATIO}; the slip annulus is then so wide that the MDR torque errs "
            f"by more than {MDR_ERROR_THRESHOLD:.0%} against the exact solution (up to +27% at full "
            "sliding). Use method='exact'.", ValidityWarning, stacklevel=4)


class _MonotonicKernel:
    """Monotonic twisting from the untwisted state for one contact and model (flat arrays)."""

    def __init__(self, contact, method: str) -> None:
        self.contact = contact
        self.method = method
        self.prof = contact.profile
        self.E = contact.moduli.normal
        self.G = contact.moduli.torsional
        self.mu = contact.friction
        self.rtol = contact.rtol

    # -- sliding torque
    def sliding_torque(self, a: np.ndarray, d: np.ndarray) -> np.ndarray:
        if self.method == "no-slip":
            return np.full(a.shape, np.inf)
        if self.method == "exact":
            return _exact.sliding_torque(self.prof, self.E, self.mu, a, d, self.rtol)
        return _mdr.sliding_torque(self.prof, self.E, self.mu, a, d, self.rtol)

    # -- controls (signs: odd in twist/torque)
    def of_twist(self, phi_s: np.ndarray, a: np.ndarray, d: np.ndarray, g_a: np.ndarray):
        sgn = np.sign(phi_s)
        phi = np.abs(phi_s)
        if self.method == "no-slip":
            c = a.copy()
            M = _noslip.torque(self.G, a, phi)
            M_err = 4 * ROUNDING * M
        elif self.method == "exact":
            c = _exact.solve_stick_of_twist(self.prof, self.E, self.G, self.mu, phi, a, d, g_a,
                                            self.rtol)
            T, T_err = _exact.torque_integral(self.prof, self.E, c, a, d, g_a, self.rtol)
            T_err = _exact.sharpen_error(T_err, T)
            M1 = 16.0 / 3.0 * self.G * phi * c**3
            M = M1 + 8.0 * self.mu * T
            # M(c) at fixed φ is stationary at the root (dM/dc = 8c²(2G_tφ - μP(c)) = 0), so the
            # root tolerance enters only at second order: quadrature of T plus rounding
            M_err = 8.0 * self.mu * T_err + ROUNDING * (np.abs(M1) + 8.0 * self.mu * np.abs(T))
            if self.rtol > ROOT_TERM_RTOL:
                # needs one extra batched evaluation of P: deferred to the first access of
                # state.error_estimate (lazy: a torque-twist curve does not pay for it)
                args = (phi.copy(), c.copy(), a.copy(), d.copy(), g_a.copy())
                self.err_torque_deferred = lambda: self._root_err_exact(*args)
            else:       # a-priori bound, below the rounding floor: no extra quadrature
                M_err += 1e2 * self.rtol**2 * np.abs(M)
            slid = (c <= 0) & (a > 0)
            if np.any(slid):
                M[slid] = self.sliding_torque(a[slid], d[slid])
                M_err[slid] = self._sliding_err(a[slid], d[slid], M[slid])
        else:
            c = _mdr.stick_radius(self.prof, self.E, self.G, self.mu, phi, a, d, self.rtol)
            # stationary in c as well (8G_tφc = 2μE*(d - g(c)) at the root)
            M, M_err = _mdr.torque_of_stick(self.prof, self.E, self.G, self.mu, phi, c, a, d,
                                            self.rtol, return_error=True)
            M_err += self._root_err_mdr(phi, c, a, d)
        M = np.where(a > 0, M, 0.0)
        self.err_torque = np.where(a > 0, M_err, 0.0)
        self.err_twist = ROUNDING * phi
        return sgn * phi, sgn * M, c

    def _root_err_exact(self, phi, c, a, d, g_a) -> np.ndarray:
        """Second-order torque error of an inexact stick radius at fixed twist (exact model).

        ``M(c)`` is stationary at the root; ``M'' = -16 G_t c² φ'(c)``, so a root off by ``δc``
        changes ``M`` by ``8 G_t c² |φ'| δc²`` with ``δc = (residual + μP_err/(2G_t))/|φ'|`` from the
        actual twist residual at ``c``. One batched evaluation of ``P`` at ``c`` and ``c - h``,
        ``h = 0.1 min(c, a - c)``.
        """
        out = np.zeros(c.shape)
        s = np.flatnonzero((c > 0) & (c < a))
        if s.size == 0:
            return out
        cs, as_ = c[s], a[s]
        h = 0.1 * np.minimum(cs, as_ - cs)
        two = lambda v: np.concatenate([v, v])             # noqa: E731
        P, P_err = _exact.slip_function(self.prof, self.E, np.concatenate([cs, cs - h]), two(as_),
                                        two(d[s]), two(g_a[s]), self.rtol)
        k = self.mu / (2.0 * self.G)
        n = s.size
        dphi_dc = np.abs(k * (P[n:] - P[:n])) / h
        res = np.abs(k * P[:n] - phi[s]) + k * _exact.sharpen_error(P_err[:n], P[:n])
        with np.errstate(divide="ignore", invalid="ignore"):
            out[s] = np.nan_to_num(ROOT_SAFETY * 8.0 * self.G * cs**2 * res**2 / dphi_dc,
                                   nan=0.0, posinf=0.0)
        return out

    def _root_err_mdr(self, phi, c, a, d) -> np.ndarray:
        """As :meth:`_root_err_exact` for the MDR springs: ``f(c) = 4G_tφc/(μE*) + g(c) = d``,
        ``M'' = 4 c μE* f'``, so ``δM = 2 c μE* r_f²/f'`` (closed forms, no quadrature)."""
        out = np.zeros(c.shape)
        s = np.flatnonzero((c > 0) & (c < a))
        if s.size == 0:
            return out
        cs, as_, ps = c[s], a[s], phi[s]
        h = 0.1 * np.minimum(cs, as_ - cs)
        kk = 4.0 * self.G / (self.mu * self.E)
        f0 = kk * ps * cs + self.prof._g(cs)
        f1 = kk * ps * (cs - h) + self.prof._g(cs - h)
        fp = np.abs(f0 - f1) / h
        r = np.abs(f0 - d[s]) + 4 * ROUNDING * np.abs(d[s])
        with np.errstate(divide="ignore", invalid="ignore"):
            out[s] = np.nan_to_num(ROOT_SAFETY * 2.0 * cs * self.mu * self.E * r**2 / fp, nan=0.0, posinf=0.0)
        return out

    def _sliding_err(self, a: np.ndarray, d: np.ndarray, M_full: np.ndarray) -> np.ndarray:
        """Absolute error estimate of the full-sliding torque: rounding of ``d a²/2 - ∫x g`` and,
        for a quadrature ``∫x g``, its tolerance."""
        pref = np.pi if self.method == "exact" else 4.0
        err = 4 * ROUNDING * pref * self.mu * self.E * 0.5 * d * a * a
        if self.prof.power_terms() is None:
            err = err + self.rtol * np.abs(M_full)
        return err

    def of_torque(self, M_s: np.ndarray, a: np.ndarray, d: np.ndarray, g_a: np.ndarray):
        sgn = np.sign(M_s)
        M = np.abs(M_s)
        if np.any((a <= 0) & (M > 0)):
            raise OutsideTheoryError(f"torque={float(M[(a <= 0) & (M > 0)][0])!r} N·m cannot be "
                                     "carried: the normal load gives no contact (radius 0).")
        if self.method == "no-slip":
            self.err_torque = ROUNDING * M
            self.err_twist = 4 * ROUNDING * _noslip.twist(self.G, a, M)
            return sgn * _noslip.twist(self.G, a, M), sgn * M, a.copy()
        M_full = self.sliding_torque(a, d)
        over = M > M_full * (1 + 1e-12)
        if np.any(over):
            i = int(np.argmax(over))
            raise OutsideTheoryError(
                f"torque={float(M[i])!r} N·m exceeds the full-sliding torque {float(M_full[i])!r} "
                f"N·m of the {self.method!r} model at this normal load: the contact slides "
                "entirely. Give twist= to prescribe sliding, or reduce the torque.")
        at_full = M >= M_full
        Mi = np.where(at_full, 0.0, M)
        if self.method == "exact":
            c = _exact.solve_stick_of_torque(self.prof, self.E, self.G, self.mu, Mi, a, d, g_a,
                                             self.rtol)
            cm = np.maximum(c, _exact.C_MIN_REL * a)
            P, P_err = _exact.slip_function(self.prof, self.E, cm, a, d, g_a, self.rtol)
            P_err = _exact.sharpen_error(P_err, P)
            phi = np.where(c < a, _exact.twist_of_stick(self.mu, self.G, P), 0.0)
            # torque the returned (c, φ) carries: its residual against the request plus its
            # quadrature error; along the curve dM = (16/3) G_t c³ dφ maps it onto the twist
            T, T_err = _exact.torque_integral(self.prof, self.E, cm, a, d, g_a, self.rtol)
            T_err = _exact.sharpen_error(T_err, T)
            M1 = 16.0 / 3.0 * self.G * phi * cm**3
            M_c = M1 + 8.0 * self.mu * T
            M_err = (ROOT_SAFETY * np.abs(M_c - Mi) + 8.0 * self.mu * T_err
                     + 2.0 / 3.0 * self.mu * cm**3 * P_err * 4.0
                     + ROUNDING * (np.abs(M1) + 8.0 * self.mu * np.abs(T)))
            phi_err = self.mu / (2.0 * self.G) * P_err + ROUNDING * phi
        else:
            c = _mdr.stick_radius_of_torque(self.prof, self.E, self.G, self.mu, Mi, a, d, self.rtol)
            cm = np.where(c > 0, c, 1.0)
            with np.errstate(divide="ignore", invalid="ignore"):
                phi = np.where(c < a, _mdr.twist_of_stick(self.prof, self.E, self.G, self.mu,
                                                          cm, d), 0.0)
            M_c, M_err = _mdr.torque_of_stick(self.prof, self.E, self.G, self.mu, phi, cm, a, d,
                                              self.rtol, return_error=True)
            M_err = M_err + ROOT_SAFETY * np.abs(M_c - Mi)
            phi_err = self._mdr_twist_rounding(phi, cm, d)
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            phi_err = phi_err + M_err / (16.0 / 3.0 * self.G * cm**3)
        self.err_torque = np.where((c < a) & (c > 0), M_err, ROUNDING * M)
        self.err_twist = np.where(c > 0, phi_err, 0.0)
        no_slip = (c >= a) & (a > 0)
        phi = np.where(no_slip, _noslip.twist(self.G, a, M), phi)
        self.err_twist = np.where(no_slip, 4 * ROUNDING * phi, self.err_twist)
        self.err_torque = np.where(no_slip | at_full, ROUNDING * M, self.err_torque)
        c = np.where(at_full | ((c <= 0) & (M > 0)), 0.0, c)
        phi = np.where(c <= 0, np.where(M > 0, np.inf, 0.0), phi)
        return sgn * phi, sgn * M, c

    def of_stick_radius(self, c: np.ndarray, a: np.ndarray, d: np.ndarray, g_a: np.ndarray):
        if self.method == "no-slip":
            raise NotSupportedError("stick_radius= does not determine a no-slip state (the whole "
                                    "contact sticks at every twist); give twist= or torque=, or "
                                    "use method='exact'/'mdr'.")
        bad = (c < 0) | (c > a * (1 + 1e-15))
        if np.any(bad):
            i = int(np.argmax(bad))
            raise ParameterError(f"stick_radius={float(c[i])!r} m is invalid: it must satisfy "
                                 f"0 <= stick_radius <= contact radius {float(a[i])!r} m.")
        c = np.minimum(c, a)
        M = np.zeros(c.shape)
        phi = np.zeros(c.shape)
        M_err = np.zeros(c.shape)
        phi_err = np.zeros(c.shape)
        live = a > 0
        zero = live & (c <= 0)
        part = live & (c > 0)
        if np.any(part):
            cp, ap, dp, gp = c[part], a[part], d[part], g_a[part]
            M1_scale = 16.0 / 3.0 * self.G * cp**3
            if self.method == "exact":
                P, P_err = _exact.slip_function(self.prof, self.E, cp, ap, dp, gp, self.rtol)
                T, T_err = _exact.torque_integral(self.prof, self.E, cp, ap, dp, gp, self.rtol)
                P_err = _exact.sharpen_error(P_err, P)
                T_err = _exact.sharpen_error(T_err, T)
                phi[part] = _exact.twist_of_stick(self.mu, self.G, P)
                M[part] = _exact.torque_of_stick(self.mu, self.G, cp, phi[part], T)
                phi_err[part] = self.mu / (2.0 * self.G) * P_err + ROUNDING * phi[part]
                M_err[part] = (M1_scale * phi_err[part] + 8.0 * self.mu * T_err
                               + ROUNDING * (M1_scale * phi[part] + 8.0 * self.mu * np.abs(T)))
            else:
                phi[part] = _mdr.twist_of_stick(self.prof, self.E, self.G, self.mu, cp, dp)
                M[part], Me = _mdr.torque_of_stick(self.prof, self.E, self.G, self.mu, phi[part],
                                                   cp, ap, dp, self.rtol, return_error=True)
                phi_err[part] = self._mdr_twist_rounding(phi[part], cp, dp)
                M_err[part] = Me + M1_scale * phi_err[part]
        if np.any(zero):
            phi[zero] = np.inf
            M[zero] = self.sliding_torque(a[zero], d[zero])
            M_err[zero] = self._sliding_err(a[zero], d[zero], M[zero])
        self.err_torque, self.err_twist = M_err, phi_err
        return phi, M, np.where(live, c, 0.0)

    def _mdr_twist_rounding(self, phi: np.ndarray, c: np.ndarray, d: np.ndarray) -> np.ndarray:
        """Rounding of the closed form ``φ = μE*(d - g(c))/(4G_t c)``: cancellation in ``d - g``."""
        with np.errstate(divide="ignore", invalid="ignore"):
            amp = np.where(phi > 0, self.mu * self.E * np.abs(d) / (4.0 * self.G * c), 0.0)
        return 4 * ROUNDING * (np.abs(phi) + amp)

    # -- fields
    def psi(self, a: np.ndarray, d: np.ndarray, g_a: np.ndarray):
        """Lag ``ψ(t) = φ - Φ(t)`` of the model as a vectorised ``(t, idx) -> values``."""
        if self.method == "exact":
            def psi(t: np.ndarray, idx: np.ndarray) -> np.ndarray:
                P, _ = _exact.slip_function(self.prof, self.E, t, a[idx][:, None], d[idx][:, None],
                                            g_a[idx][:, None], self.rtol)
                return self.mu / (2 * self.G) * P
        else:
            def psi(t: np.ndarray, idx: np.ndarray) -> np.ndarray:
                return _mdr.slip_displacement(self.prof, self.E, self.G, self.mu, t,
                                              d[idx][:, None]) / t
        return psi

    # -- dissipation under monotonic loading (Iwan picture)
    def dissipation(self, phi: np.ndarray, c: np.ndarray, a: np.ndarray, d: np.ndarray,
                    g_a: np.ndarray) -> np.ndarray:
        if self.method == "no-slip":
            return np.zeros(phi.shape)
        if self.method == "exact":
            J = _exact.dissipation_integral(self.prof, self.E, c, a, d, g_a, self.rtol)
            D = 4.0 * self.mu**2 / self.G * J
            # full sliding (c -> 0): the stick zone is gone; D grows as M_full (φ - φ(c_min))
            slid = (c <= 0) & (a > 0) & (phi > 0)
            if np.any(slid):
                cm = _exact.C_MIN_REL * a[slid]
                P, _ = _exact.slip_function(self.prof, self.E, cm, a[slid], d[slid], g_a[slid],
                                            self.rtol)
                phi_m = _exact.twist_of_stick(self.mu, self.G, P)
                M_full = self.sliding_torque(a[slid], d[slid])
                D[slid] += M_full * np.maximum(phi[slid] - phi_m, 0.0)
            return D
        return _mdr.dissipation(self.prof, self.E, self.G, self.mu, phi, c, a, d, self.rtol)


@dataclass(frozen=True, eq=False)
class TorsionState:
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
        ``twist_error_estimate`` (relative).

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
        """Incremental torsional stiffness ``dM/dφ = (16/3) G_t c³``, N·m/rad (physics.md §6.2)."""
        return _scalar_or_array(16.0 / 3.0 * self.contact.moduli.torsional * self._stick**3)

    @cached_property
    def _sliding(self) -> np.ndarray:
        k = _MonotonicKernel(self.contact, self.method)
        return k.sliding_torque(self._a.ravel(), self._d.ravel()).reshape(self.shape)

    @property
    def sliding_torque(self) -> Any:
        """Full-sliding torque of the model at this normal load, N·m (``inf`` for no slip)."""
        return _scalar_or_array(self._sliding)

    def _field_setup(self, r: Any):
        r = as_float_array("r", r)
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
        physics.md §6.2 item 5 inside (continuous at ``r = c``, ``τ(0) = 0``, ``|τ| <= μ p``).
        MDR: the traction of the MDR twist distribution (§8 item 1). No slip: Reissner-Sagoci.
        Singular points return ``inf`` (no-slip edge).
        """
        full, R, A, D, GA, PHI, C = self._field_setup(r)
        G = self.contact.moduli.torsional
        sgn = np.sign(PHI)
        phi = np.abs(PHI)
        if self.method == "no-slip":
            return _scalar_or_array(_noslip.shear(G, R, A, PHI).reshape(full))
        out = np.zeros(R.shape)
        rtol = self.contact.rtol
        k = _MonotonicKernel(self.contact, self.method)
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

        ``φ r`` in the stick zone; physics.md §6.2 item 6 elsewhere (with the MDR twist
        distribution for ``method="mdr"``); Reissner-Sagoci for no slip. Decays as
        ``M/(4π G_t r²)`` far away.
        """
        full, R, A, D, GA, PHI, C = self._field_setup(r)
        if self.method == "no-slip":
            return _scalar_or_array(_noslip.displacement(R, A, PHI).reshape(full))
        sgn = np.sign(PHI)
        phi = np.abs(PHI)
        out = np.zeros(R.shape)
        live = (A > 0) & (phi > 0) & np.isfinite(phi)
        if np.any(live):
            i = np.flatnonzero(live)
            k = _MonotonicKernel(self.contact, self.method)
            psi_all = k.psi(A[i], D[i], GA[i])
            out[i] = _exact.circumferential_displacement(psi_all, phi[i], R[i], C[i], A[i],
                                                         self.contact.rtol)
        if np.any(~np.isfinite(phi) & (A > 0)):
            raise NotSupportedError("displacement() at full sliding (infinite twist) is undefined; "
                                    "prescribe a finite twist.")
        return _scalar_or_array((sgn * out).reshape(full))


# ====================================================================== twist histories
def _masing_program(phi: np.ndarray):
    """Turning-point bookkeeping of Masing's rule (O(1) amortised work per step).

    Returns per step: ``origin`` (step index of the branch's turning point, -1 for the virgin
    curve), ``factor`` (1 virgin, 2 after a reversal), ``arg`` = ``|φ - φ_o|/factor``, and the list of
    branch segments ``(step, φ_o, factor, φ_from, φ_to)`` traversed between consecutive steps (a
    step may close several loops, each closure switching to an older branch).
    """
    n = phi.size
    origin = np.full(n, -1, dtype=np.int64)
    factor = np.ones(n)
    arg = np.zeros(n)
    segments: list[tuple[int, float, float, float, float]] = []
    stack: list[int] = []          # step indices of the active turning points
    prev = 0.0
    direction = 0.0
    for i in range(n):
        p = float(phi[i])
        delta = p - prev
        if delta != 0.0:
            s = 1.0 if delta > 0 else -1.0
            if direction != 0.0 and s != direction:
                stack.append(i - 1)            # the previous step is a turning point (i >= 1)
            direction = s
        start = prev
        # walk along the active branch, closing loops that the new point passes
        while True:
            if stack:
                o = stack[-1]
                po, fo = float(phi[o]), 2.0
            else:
                po, fo = 0.0, 1.0
            if len(stack) >= 2:
                limit = float(phi[stack[-2]])
            elif len(stack) == 1:
                limit = -po                      # rejoins the virgin curve at the mirror point
            else:
                limit = None
            if limit is not None and direction != 0.0 and (p - limit) * direction > 0:
                segments.append((i, po, fo, start, limit))
                start = limit
                if len(stack) >= 2:
                    del stack[-2:]
                else:
                    stack.pop()
                continue
            segments.append((i, po, fo, start, p))
            origin[i] = stack[-1] if stack else -1
            factor[i] = fo
            arg[i] = abs(p - po) / fo
            break
        prev = p
    arr = np.asarray(segments, float).reshape(-1, 5)
    segs = tuple(arr[:, k].copy() for k in range(5))
    return origin, factor, arg, segs


def twist_history(contact, *, twist: Any, depth: Any = None, force: Any = None,
                  method: str | None = None) -> "TwistHistory":
    """Implementation of :meth:`contactlab.Contact.twist_history` (see there)."""
    method = resolve_method(contact, method)
    load_key, load_val = _one_of("twist_history()", {"depth": depth, "force": force})
    load = as_float_array(load_key, load_val)
    if load.ndim != 0:
        raise ParameterError(f"{load_key} has shape {load.shape}: twist_history() holds the normal "
                             "load constant; give a scalar.")
    phi = as_float_array("twist", twist)
    if phi.ndim != 1:
        raise ParameterError(f"twist has shape {phi.shape}: give a 1D array of twist angles (rad), "
                             "one per step.")
    normal = contact.normal(**{load_key: float(load)})
    origin, factor, arg, segs = _masing_program(phi)
    kernel = _MonotonicKernel(contact, method)
    a = float(normal._radius)
    d = float(normal._depth)
    g_a = float(contact.profile._g(np.array(a))) if a > 0 else 0.0
    if np.isfinite(contact.profile.wall_radius) and a >= contact.profile.wall_radius:
        g_a = min(g_a, d)
    # the loading curve at every distinct argument, one batched solve
    u_arg, inv = np.unique(arg, return_inverse=True)
    A = np.full(u_arg.shape, a)
    Dd = np.full(u_arg.shape, d)
    GA = np.full(u_arg.shape, g_a)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ValidityWarning)     # judged on the history below
        _, M_u, c_u = kernel.of_twist(u_arg, A, Dd, GA)
    M_load = M_u[inv.ravel()]
    c = c_u[inv.ravel()]
    torque = np.empty(phi.shape)
    for i in range(phi.size):                                 # O(1) per step
        o = origin[i]
        po = phi[o] if o >= 0 else 0.0
        Mo = torque[o] if o >= 0 else 0.0
        s = 1.0 if phi[i] >= po else -1.0
        torque[i] = Mo + s * factor[i] * M_load[i]
    if method == "mdr":
        _warn_mdr(contact, u_arg, A, Dd, GA)
    meta = {"rtol": contact.rtol, "load": load_key, "method": method,
            "moduli": {"G_t": contact.moduli.torsional, "E_star": contact.moduli.normal}}
    # error bookkeeping for torque_error (computed on first access): the loading curve's
    # absolute errors at the distinct arguments, its deferred root term, and the recursion
    errors = (kernel.err_torque.copy(), getattr(kernel, "err_torque_deferred", None),
              inv.ravel(), origin, factor, float(normal.meta.get("error_estimate", 0.0)))
    return TwistHistory(contact, normal, method, phi.copy(), torque, c, (a, d, g_a), segs, meta,
                        errors)


@dataclass(frozen=True, eq=False)
class TwistHistory:
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

    Notes
    -----
    After a reversal at ``(φ_r, M_r)``: ``M = M_r ± 2 M_load(|φ - φ_r|/2)``; a branch that passes
    an older turning point closes that loop, which is then forgotten (physics.md §6.5). Exact for
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
        step, po, f, p_from, p_to = self._segments
        n = self.twist.size
        if self.method == "no-slip" or step.size == 0 or a <= 0:
            return np.zeros(n)
        x_from = np.abs(p_from - po) / f
        x_to = np.abs(p_to - po) / f
        xs = np.concatenate([x_from, x_to])
        u, inv = np.unique(xs, return_inverse=True)
        kernel = _MonotonicKernel(self.contact, self.method)
        A = np.full(u.shape, a)
        Dd = np.full(u.shape, d)
        GA = np.full(u.shape, g_a)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", ValidityWarning)
            phi_u, _, c_u = kernel.of_twist(u, A, Dd, GA)
        D_u = kernel.dissipation(np.abs(phi_u), c_u, A, Dd, GA)
        D = D_u[inv.ravel()]
        incr = f * (D[step.size:] - D[:step.size])
        per_step = np.bincount(step.astype(np.int64), weights=incr, minlength=n)
        return np.cumsum(per_step)

    def to_dict(self) -> dict[str, np.ndarray]:
        """Per-step arrays by name (``twist``, ``torque``, ``stick_radius``, ``dissipated_energy``)."""
        return {"twist": self.twist, "torque": self.torque, "stick_radius": self.stick_radius,
                "dissipated_energy": self.dissipated_energy}
