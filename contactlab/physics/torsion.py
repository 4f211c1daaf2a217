"""Torsion of an axisymmetric contact at constant normal load: three models behind one face.

:data:`METHODS` maps ``method=`` names to model classes (as scipy.integrate maps solver names to
``OdeSolver`` subclasses); every model answers the same questions for flat arrays of states:

* :meth:`TorsionModel.of_twist`, :meth:`~TorsionModel.of_torque`,
  :meth:`~TorsionModel.of_stick_radius`: monotonic twisting from the untwisted state, returned as
  a :class:`TorsionSolution` with absolute error estimates;
* :meth:`~TorsionModel.sliding_torque`, :meth:`~TorsionModel.dissipation`,
  :meth:`~TorsionModel.psi` (the lag ``φ - Φ(t)`` that the field quadratures need).

The models [physics: no slip (Reissner-Sagoci), Jäger's exact partial slip, the MDR narrow-slip
springs with μ* = 2μ]:

* :class:`NoSlip` (μ → ∞): ``M = (16/3) G_t a³ φ``;
* :class:`Exact`: Jäger's exact partial-slip solution for any profile (kernels in
  :mod:`contactlab.physics.torsion_exact`);
* :class:`MDR`: the MDR narrow-slip spring model (kernels in
  :mod:`contactlab.physics.torsion_mdr`), fast, exact only as ``c → a``.

All models use the torsional modulus ``G_t`` (``1/G_t = 1/G1 + 1/G2``). Models are immutable
parameter holders; every call returns its results and keeps nothing.
"""
from __future__ import annotations

from typing import TYPE_CHECKING, Any, ClassVar, NamedTuple, cast
from collections.abc import Callable

import numpy as np

from ..errors import NotSupportedError, OutsideTheoryError, ParameterError
from ..profiles.base import ROUNDING
from ..profiles.power_law import PowerLaw
from . import edge_annulus as _edge
from . import torsion_exact as _exact
from . import torsion_hertz as _hertz
from . import torsion_mdr as _mdr
from . import torsion_noslip as _noslip
from .torsion_validity import twist_at_stick_ratio

__all__ = ["TorsionModel", "NoSlip", "Exact", "MDR", "METHODS", "TorsionSolution",
           "ROOT_SAFETY", "ROOT_TERM_RTOL", "MDR_ERROR_THRESHOLD", "MDR_VALID_STICK_RATIO",
           "mdr_validity_twist", "mdr_torque_error"]

#: Safety factor on the root-solve terms of the error estimates: they come from a linearisation
#: (first order in the residual) or a finite-difference curvature (second order); measured on the
#: honesty ladder of the error-estimate tests they were within 0.92x of the actual error.
ROOT_SAFETY = 2.0

#: Twist control, exact model: above this ``rtol`` the second-order torque error of the
#: stick-radius root is estimated from the actual residual (one extra batched evaluation of ``P``);
#: at or below it the a-priori bound ``1e2 rtol² |M|`` (< 1e-16 relative) is used, so the default
#: rtol pays nothing for the estimate.
ROOT_TERM_RTOL = 1e-9

#: Relative torque error of the MDR model (vs the exact solution at the same twist) above which a
#: :class:`~contactlab.errors.ValidityWarning` is emitted.
MDR_ERROR_THRESHOLD = 0.01

#: Exact stick-radius ratio ``c/a`` below which the MDR torque errs by more than
#: :data:`MDR_ERROR_THRESHOLD` at the same twist. Measured by ``benchmarks/torsion_error_map.py``
#: (docs/torsion.md): as a function of the *exact* ``c/a`` the error is nearly universal, 1 % being
#: crossed at c/a = 0.80 (cone), 0.805 (paraboloid, truncated paraboloid), 0.81 (n = 4), 0.822
#: (n = 20) and 0.826 (flat punch).
MDR_VALID_STICK_RATIO = 0.83


class TorsionSolution(NamedTuple):
    """Monotonic torsion states (flat arrays) with absolute error estimates.

    Attributes
    ----------
    twist, torque, stick_radius : ndarray
        rad, N·m, m (signed twist and torque).
    torque_error, twist_error : ndarray
        Absolute error estimates, N·m and rad.
    torque_error_deferred : callable or None
        An extra torque-error term that needs one more batched quadrature; evaluated only when an
        error estimate is read (``None``: nothing deferred).
    """

    twist: np.ndarray
    torque: np.ndarray
    stick_radius: np.ndarray
    torque_error: np.ndarray
    twist_error: np.ndarray
    torque_error_deferred: Callable[[], np.ndarray] | None = None


class TorsionModel:
    """One torsion model of one contact (flat arrays of states ``a, d, g(a)``).

    To implement a subclass
    -----------------------
    1. Required: ``name`` and :meth:`_of_twist`, :meth:`_of_torque` (partial slip, ``|M|`` below
       the sliding torque), :meth:`_of_stick_radius`, :meth:`sliding_torque`,
       :meth:`dissipation`, :meth:`psi`.
    2. Free: sign handling and validation in :meth:`of_twist`, :meth:`of_torque`,
       :meth:`of_stick_radius`.

    Parameters
    ----------
    profile : Profile
    E_star : float
        Effective normal modulus, Pa.
    G_t : float
        Torsional modulus of the pair, Pa.
    mu : float or None
        Coulomb friction coefficient (``None``: no slip).
    rtol : float
        Tolerance of the quadratures and root solves.
    """

    name: ClassVar[str] = ""

    if TYPE_CHECKING:
        # the required hooks of item 1, declared for type checkers only (subclasses give them)
        def _of_twist(self, phi: np.ndarray, a: np.ndarray, d: np.ndarray, g_a: np.ndarray
                      ) -> tuple[np.ndarray, np.ndarray, np.ndarray, Any]: ...
        def _of_torque(self, M: np.ndarray, a: np.ndarray, d: np.ndarray, g_a: np.ndarray
                       ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]: ...
        def _of_stick_radius(self, c: np.ndarray, a: np.ndarray, d: np.ndarray, g_a: np.ndarray
                             ) -> TorsionSolution: ...

    def __init__(self, profile, E_star: float, G_t: float, mu: float | None, rtol: float) -> None:
        self.prof = profile
        self.E = E_star
        self.G = G_t
        self.mu = mu
        self.rtol = rtol

    def sliding_torque(self, a: np.ndarray, d: np.ndarray) -> np.ndarray:
        """Full-sliding torque of the model, N·m (``inf`` without slip)."""
        raise NotImplementedError

    def of_twist(self, phi_s: np.ndarray, a: np.ndarray, d: np.ndarray, g_a: np.ndarray
                 ) -> TorsionSolution:
        """States at signed twists ``phi_s`` (rad)."""
        sgn = np.sign(phi_s)
        phi = np.abs(phi_s)
        M, c, M_err, deferred = self._of_twist(phi, a, d, g_a)
        M = np.where(a > 0, M, 0.0)
        return TorsionSolution(sgn * phi, sgn * M, c, np.where(a > 0, M_err, 0.0),
                               ROUNDING * phi, deferred)

    def of_torque(self, M_s: np.ndarray, a: np.ndarray, d: np.ndarray, g_a: np.ndarray
                  ) -> TorsionSolution:
        """States at signed torques ``M_s`` (N·m); raises beyond the sliding torque."""
        sgn = np.sign(M_s)
        M = np.abs(M_s)
        if np.any((a <= 0) & (M > 0)):
            raise OutsideTheoryError(f"torque={float(M[(a <= 0) & (M > 0)][0])!r} N·m cannot be "
                                     "carried: the normal load gives no contact (radius 0).")
        phi, M, c, M_err, phi_err = self._of_torque(M, a, d, g_a)
        return TorsionSolution(sgn * phi, sgn * M, c, M_err, phi_err)

    def of_stick_radius(self, c: np.ndarray, a: np.ndarray, d: np.ndarray, g_a: np.ndarray
                        ) -> TorsionSolution:
        """States at stick radii ``c`` (m, ``0 <= c <= a``)."""
        bad = (c < 0) | (c > a * (1 + 1e-15))
        if np.any(bad):
            i = int(np.argmax(bad))
            raise ParameterError(f"stick_radius={float(c[i])!r} m is invalid: it must satisfy "
                                 f"0 <= stick_radius <= contact radius {float(a[i])!r} m.")
        return self._of_stick_radius(np.minimum(c, a), a, d, g_a)

    def dissipation(self, phi: np.ndarray, c: np.ndarray, a: np.ndarray, d: np.ndarray,
                    g_a: np.ndarray) -> np.ndarray:
        """Energy dissipated by monotonic twisting to ``phi`` (Iwan picture), J."""
        raise NotImplementedError

    def psi(self, a: np.ndarray, d: np.ndarray, g_a: np.ndarray):
        """Lag ``ψ(t) = φ - Φ(t)`` of the model as a vectorised ``(t, idx) -> values``."""
        raise NotImplementedError

    # -- shared error terms
    def _sliding_err(self, a: np.ndarray, d: np.ndarray, M_full: np.ndarray, pref: float
                     ) -> np.ndarray:
        """Absolute error estimate of the full-sliding torque: rounding of ``d a²/2 - ∫x g`` and,
        for a quadrature ``∫x g``, its tolerance."""
        # a shared term of the partial-slip models, which always have a friction coefficient
        err = 4 * ROUNDING * pref * cast(float, self.mu) * self.E * 0.5 * d * a * a
        if self.prof.power_terms() is None:
            err = err + self.rtol * np.abs(M_full)
        return err

    def _finish_torque_control(self, M, at_full, phi, c, cm, M_err, phi_err, a):
        """Common end of :meth:`_of_torque` for the partial-slip models."""
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            phi_err = phi_err + M_err / (16.0 / 3.0 * self.G * cm**3)
        err_torque = np.where((c < a) & (c > 0), M_err, ROUNDING * M)
        err_twist = np.where(c > 0, phi_err, 0.0)
        no_slip = (c >= a) & (a > 0)
        phi = np.where(no_slip, _noslip.twist(self.G, a, M), phi)
        err_twist = np.where(no_slip, 4 * ROUNDING * phi, err_twist)
        err_torque = np.where(no_slip | at_full, ROUNDING * M, err_torque)
        c = np.where(at_full | ((c <= 0) & (M > 0)), 0.0, c)
        phi = np.where(c <= 0, np.where(M > 0, np.inf, 0.0), phi)
        return phi, M, c, err_torque, err_twist

    def _check_below_sliding(self, M: np.ndarray, a: np.ndarray, d: np.ndarray):
        M_full = self.sliding_torque(a, d)
        over = M > M_full * (1 + 1e-12)
        if np.any(over):
            i = int(np.argmax(over))
            raise OutsideTheoryError(
                f"torque={float(M[i])!r} N·m exceeds the full-sliding torque {float(M_full[i])!r} "
                f"N·m of the {self.name!r} model at this normal load: the contact slides "
                "entirely. Give twist= to prescribe sliding, or reduce the torque.")
        at_full = M >= M_full
        return at_full, np.where(at_full, 0.0, M)


class NoSlip(TorsionModel):
    """No slip (μ → ∞): Reissner-Sagoci, ``M = (16/3) G_t a³ φ``."""

    name = "no-slip"

    def sliding_torque(self, a, d):
        return np.full(a.shape, np.inf)

    def _of_twist(self, phi, a, d, g_a):
        M = _noslip.torque(self.G, a, phi)
        return M, a.copy(), 4 * ROUNDING * M, None

    def _of_torque(self, M, a, d, g_a):
        phi = _noslip.twist(self.G, a, M)
        return phi, M, a.copy(), ROUNDING * M, 4 * ROUNDING * phi

    def of_stick_radius(self, c, a, d, g_a):
        raise NotSupportedError("stick_radius= does not determine a no-slip state (the whole "
                                "contact sticks at every twist); give twist= or torque=, or "
                                "use method='exact'/'mdr'.")

    def dissipation(self, phi, c, a, d, g_a):
        return np.zeros(phi.shape)


def _hertz_p0(profile, E_star: float, a: np.ndarray, d: np.ndarray, g_a: np.ndarray
              ) -> np.ndarray | None:
    """Peak pressures ``p0 = 4 c E* a/π`` (Pa) when ``profile`` is a paraboloid (``f = c r²``)
    and every state is non-adhesive (``d = g(a)`` to rounding), else ``None``."""
    if not isinstance(profile, PowerLaw) or float(profile.n) != 2.0:
        return None
    if not np.all(np.abs(d - g_a) <= 4.0 * ROUNDING * np.abs(g_a)):
        return None
    return 4.0 * float(profile.c) * E_star * a / np.pi


class Exact(TorsionModel):
    """Jäger's exact partial-slip solution for any profile (torsion_exact kernels)."""

    name = "exact"
    mu: float   # a partial-slip model always has a friction coefficient (declaration only)

    def sliding_torque(self, a, d):
        return _exact.sliding_torque(self.prof, self.E, self.mu, a, d, self.rtol)

    def _of_twist(self, phi, a, d, g_a):
        p0 = _hertz_p0(self.prof, self.E, a, d, g_a)
        if p0 is not None:
            return self._of_twist_hertz(phi, a, d, p0)
        # large tables: the whole segments on product-integration panels (issue 28: a curve
        # costs O(points x panels), not O(points x nodes in contact); agrees to TABLE_PANELS)
        panels = _exact.panels_apply(self.prof, a)
        c = _exact.solve_stick_of_twist(self.prof, self.E, self.G, self.mu, phi, a, d, g_a,
                                        self.rtol, panels=panels)
        T, T_err = _exact.torque_integral(self.prof, self.E, c, a, d, g_a, self.rtol,
                                          panels=panels)
        T_err = _exact.sharpen_error(T_err, T)
        M1 = 16.0 / 3.0 * self.G * phi * c**3
        M = M1 + 8.0 * self.mu * T
        # M(c) at fixed φ is stationary at the root (dM/dc = 8c²(2G_tφ - μP(c)) = 0), so the
        # root tolerance enters only at second order: quadrature of T plus rounding
        M_err = 8.0 * self.mu * T_err + ROUNDING * (np.abs(M1) + 8.0 * self.mu * np.abs(T))
        deferred = None
        if self.rtol > ROOT_TERM_RTOL:
            # needs one extra batched evaluation of P: deferred to the first access of
            # state.error_estimate (lazy: a torque-twist curve does not pay for it)
            args = (phi.copy(), c.copy(), a.copy(), d.copy(), g_a.copy())
            deferred = lambda: self._root_err(*args)       # noqa: E731
        else:       # a-priori bound, below the rounding floor: no extra quadrature
            M_err += 1e2 * self.rtol**2 * np.abs(M)
        slid = (c <= 0) & (a > 0)
        if np.any(slid):
            M[slid] = self.sliding_torque(a[slid], d[slid])
            M_err[slid] = self._sliding_err(a[slid], d[slid], M[slid], np.pi)
        # a stick zone within EDGE_FORCE_RATIO a of a smooth edge: the no-slip torque minus the
        # annulus correction (M1 + 8μT reads the normal solve's rounding d - g(a) as a punch
        # step there, an error growing like 1/φ)
        thin = np.flatnonzero((c > a * (1.0 - _edge.EDGE_FORCE_RATIO)) & (phi > 0) & (a > 0))
        edge = _edge.edge_of(self.prof) if thin.size else None
        if edge is not None:
            _, C, s_c = _edge.exact_torsion_any(edge, self.E, self.G, self.mu, a[thin],
                                                phi[thin])
            ok = s_c < _edge.EDGE_FORCE_RATIO
            t, Ct = thin[ok], C[ok]
            M[t] = 16.0 / 3.0 * self.G * phi[t] * a[t] ** 3 - Ct
            M_err[t] = 4.0 * ROUNDING * M[t] + _edge.ANNULUS_RTOL * Ct
        return M, c, M_err, deferred

    def _of_twist_hertz(self, phi, a, d, p0):
        """:meth:`_of_twist` of a non-adhesive paraboloid from the closed forms of
        :mod:`contactlab.physics.torsion_hertz` (one vectorised Newton pass for the stick
        radius, a fixed Gauss rule for the torque): agrees with the quadrature route to its
        tolerance, and is exact to rounding (error estimate: rounding of the two torque terms,
        measured <= 4e-15 of the torque against the mpmath reference)."""
        live = p0 > 0
        # (a twist near the float's range overflows y to inf: full sliding, t = 0 below)
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            y = np.where(live, 2.0 * self.G * phi / (self.mu * np.where(live, p0, 1.0)), 0.0)
        t = _hertz.stick_ratio(y)
        # stick radii below C_MIN_REL a count as full sliding, as on the quadrature route
        t = np.where(t < _exact.C_MIN_REL, 0.0, t)
        c = np.where(live, t * a, a)
        scale = self.mu * p0 * a**3
        M1 = np.where(c > 0, 16.0 / 3.0 * self.G * np.where(c > 0, phi, 0.0) * c**3, 0.0)
        M2 = scale * 8.0 * _hertz.j_integral(t)
        M = M1 + M2
        M_err = 4.0 * ROUNDING * (np.abs(M1) + np.abs(M2))
        slid = (c <= 0) & (a > 0)
        if np.any(slid):
            M[slid] = self.sliding_torque(a[slid], d[slid])
            M_err[slid] = self._sliding_err(a[slid], d[slid], M[slid], np.pi)
        return M, c, M_err, None

    def _root_err(self, phi, c, a, d, g_a) -> np.ndarray:
        """Second-order torque error of an inexact stick radius at fixed twist.

        ``M(c)`` is stationary at the root; ``M'' = -16 G_t c² φ'(c)``, so a root off by ``δc``
        changes ``M`` by ``8 G_t c² |φ'| δc²`` with ``δc = (residual + μP_err/(2G_t))/|φ'|`` from
        the actual twist residual at ``c``. One batched evaluation of ``P`` at ``c`` and ``c - h``,
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

    def _of_torque(self, M, a, d, g_a):
        at_full, Mi = self._check_below_sliding(M, a, d)
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
        return self._finish_torque_control(M, at_full, phi, c, cm, M_err, phi_err, a)

    def _of_stick_radius(self, c, a, d, g_a):
        M, phi, M_err, phi_err = (np.zeros(c.shape) for _ in range(4))
        live = a > 0
        zero = live & (c <= 0)
        part = live & (c > 0)
        if np.any(part):
            cp, ap, dp, gp = c[part], a[part], d[part], g_a[part]
            M1_scale = 16.0 / 3.0 * self.G * cp**3
            P, P_err = _exact.slip_function(self.prof, self.E, cp, ap, dp, gp, self.rtol)
            T, T_err = _exact.torque_integral(self.prof, self.E, cp, ap, dp, gp, self.rtol)
            P_err = _exact.sharpen_error(P_err, P)
            T_err = _exact.sharpen_error(T_err, T)
            phi[part] = _exact.twist_of_stick(self.mu, self.G, P)
            M[part] = _exact.torque_of_stick(self.mu, self.G, cp, phi[part], T)
            phi_err[part] = self.mu / (2.0 * self.G) * P_err + ROUNDING * phi[part]
            M_err[part] = (M1_scale * phi_err[part] + 8.0 * self.mu * T_err
                           + ROUNDING * (M1_scale * phi[part] + 8.0 * self.mu * np.abs(T)))
        if np.any(zero):
            phi[zero] = np.inf
            M[zero] = self.sliding_torque(a[zero], d[zero])
            M_err[zero] = self._sliding_err(a[zero], d[zero], M[zero], np.pi)
        return TorsionSolution(phi, M, np.where(live, c, 0.0), M_err, phi_err)

    def psi(self, a, d, g_a):
        def psi(t: np.ndarray, idx: np.ndarray) -> np.ndarray:
            P, _ = _exact.slip_function(self.prof, self.E, t, a[idx][:, None], d[idx][:, None],
                                        g_a[idx][:, None], self.rtol)
            return self.mu / (2 * self.G) * P
        psi.cuts = _exact._cuts(self.prof)      # kinks of ψ: field quadratures split there
        return psi

    def dissipation(self, phi, c, a, d, g_a):
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
        # a thin annulus (σ_c < EDGE_SLIP_RATIO a) of a single power law: in annulus
        # coordinates, accurate to rounding down to twists of one ulp (J at the stick radius
        # errs by ~ε a/σ_c, and c rounds to a below an annulus of one ulp)
        pw = _edge.power_edge(self.prof)
        if pw is not None:
            live = np.flatnonzero((a > 0) & (phi > 0) & np.isfinite(phi))
            D_e, s_c = _edge.exact_torsion_dissipation(*pw, self.E, self.G, self.mu, a[live],
                                                       phi[live])
            thin = s_c < _edge.EDGE_SLIP_RATIO
            D[live[thin]] = D_e[thin]
        else:
            # any other profile: P from g' integrated on the annulus
            edge = _edge.edge_of(self.prof)
            live = np.flatnonzero((a > 0) & (phi > 0) & np.isfinite(phi))
            if edge is not None and live.size:
                D_e, _, s_c = _edge.exact_torsion_any(edge, self.E, self.G, self.mu, a[live],
                                                      phi[live])
                thin = s_c < _edge.EDGE_SLIP_RATIO
                D[live[thin]] = D_e[thin]
        return D


class MDR(TorsionModel):
    """The MDR narrow-slip spring model (springs ``8G_tΔx``, ``μ* = 2μ``; torsion_mdr kernels)."""

    name = "mdr"
    mu: float   # a partial-slip model always has a friction coefficient (declaration only)

    def sliding_torque(self, a, d):
        return _mdr.sliding_torque(self.prof, self.E, self.mu, a, d, self.rtol)

    def _of_twist(self, phi, a, d, g_a):
        c = _mdr.stick_radius(self.prof, self.E, self.G, self.mu, phi, a, d, self.rtol)
        # stationary in c as well (8G_tφc = 2μE*(d - g(c)) at the root)
        M, M_err = _mdr.torque_of_stick(self.prof, self.E, self.G, self.mu, phi, c, a, d,
                                        self.rtol, return_error=True)
        M_err += self._root_err(phi, c, a, d)
        return M, c, M_err, None

    def _root_err(self, phi, c, a, d) -> np.ndarray:
        """As :meth:`Exact._root_err` for the springs: ``f(c) = 4G_tφc/(μE*) + g(c) = d``,
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
            out[s] = np.nan_to_num(ROOT_SAFETY * 2.0 * cs * self.mu * self.E * r**2 / fp,
                                   nan=0.0, posinf=0.0)
        return out

    def _twist_rounding(self, phi: np.ndarray, c: np.ndarray, d: np.ndarray) -> np.ndarray:
        """Rounding of the closed form ``φ = μE*(d - g(c))/(4G_t c)``: cancellation in ``d - g``."""
        with np.errstate(divide="ignore", invalid="ignore"):
            amp = np.where(phi > 0, self.mu * self.E * np.abs(d) / (4.0 * self.G * c), 0.0)
        return 4 * ROUNDING * (np.abs(phi) + amp)

    def _of_torque(self, M, a, d, g_a):
        at_full, Mi = self._check_below_sliding(M, a, d)
        c = _mdr.stick_radius_of_torque(self.prof, self.E, self.G, self.mu, Mi, a, d, self.rtol)
        cm = np.where(c > 0, c, 1.0)
        with np.errstate(divide="ignore", invalid="ignore"):
            phi = np.where(c < a, _mdr.twist_of_stick(self.prof, self.E, self.G, self.mu, cm, d),
                           0.0)
        M_c, M_err = _mdr.torque_of_stick(self.prof, self.E, self.G, self.mu, phi, cm, a, d,
                                          self.rtol, return_error=True)
        M_err = M_err + ROOT_SAFETY * np.abs(M_c - Mi)
        phi_err = self._twist_rounding(phi, cm, d)
        return self._finish_torque_control(M, at_full, phi, c, cm, M_err, phi_err, a)

    def _of_stick_radius(self, c, a, d, g_a):
        M, phi, M_err, phi_err = (np.zeros(c.shape) for _ in range(4))
        live = a > 0
        zero = live & (c <= 0)
        part = live & (c > 0)
        if np.any(part):
            cp, ap, dp = c[part], a[part], d[part]
            M1_scale = 16.0 / 3.0 * self.G * cp**3
            phi[part] = _mdr.twist_of_stick(self.prof, self.E, self.G, self.mu, cp, dp)
            M[part], Me = _mdr.torque_of_stick(self.prof, self.E, self.G, self.mu, phi[part],
                                               cp, ap, dp, self.rtol, return_error=True)
            phi_err[part] = self._twist_rounding(phi[part], cp, dp)
            M_err[part] = Me + M1_scale * phi_err[part]
        if np.any(zero):
            phi[zero] = np.inf
            M[zero] = self.sliding_torque(a[zero], d[zero])
            M_err[zero] = self._sliding_err(a[zero], d[zero], M[zero], 4.0)
        return TorsionSolution(phi, M, np.where(live, c, 0.0), M_err, phi_err)

    def psi(self, a, d, g_a):
        def psi(t: np.ndarray, idx: np.ndarray) -> np.ndarray:
            return _mdr.slip_displacement(self.prof, self.E, self.G, self.mu, t,
                                          d[idx][:, None]) / t
        return psi

    def dissipation(self, phi, c, a, d, g_a):
        return _mdr.dissipation(self.prof, self.E, self.G, self.mu, phi, c, a, d, self.rtol)


#: Torsion models by ``method=`` name.
METHODS: dict[str, type[TorsionModel]] = {"no-slip": NoSlip, "exact": Exact, "mdr": MDR}


def mdr_validity_twist(profile, E_star: float, G_t: float, mu: float, a: np.ndarray,
                       d: np.ndarray, g_a: np.ndarray, rtol: float) -> np.ndarray:
    """Twist (rad) beyond which the MDR torque errs by more than :data:`MDR_ERROR_THRESHOLD`: the
    exact twist at the stick radius ``MDR_VALID_STICK_RATIO * a`` (flat arrays; bounded cost on
    large tables, :mod:`contactlab.physics.torsion_validity`)."""
    return twist_at_stick_ratio(profile, E_star, G_t, mu, MDR_VALID_STICK_RATIO, a, d, g_a, rtol)


def mdr_torque_error(profile, E_star: float, G_t: float, mu: float, phi: np.ndarray,
                     M_mdr: np.ndarray, a: np.ndarray, d: np.ndarray, g_a: np.ndarray,
                     rtol: float) -> np.ndarray:
    """Relative error ``M_MDR/M_exact - 1`` of MDR torques at the same twists (flat arrays)."""
    M_ex = Exact(profile, E_star, G_t, mu, rtol).of_twist(np.abs(phi), a, d, g_a).torque
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(M_ex > 0, np.abs(M_mdr) / M_ex - 1.0, 0.0)
