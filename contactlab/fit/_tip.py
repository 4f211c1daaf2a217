"""The force of a tip at unit modulus and its slope, fast, for fitting.

Non-adhesive normal contact through the MDR gives ``F(δ) = E* Φ(δ)`` with the force at unit
modulus ``Φ(δ) = 2(a δ - ∫_0^a g)`` and ``d = g(a)``, and ``dΦ/dδ = 2a(δ)`` for every profile.
A fit evaluates ``Φ`` and ``2a`` at thousands of indentations many times, so each profile gets
the cheapest exact-enough route, chosen once:

* ``"power"``: one power term ``f = c r^n``: ``a = (δ/(κ_n c))^(1/n)``,
  ``Φ = 2κ_n c n a^(n+1)/(n+1)`` (closed form, exact);
* ``"newton"``: a closed-form ``g`` and ``∫g`` that are cheap (the exact sphere, sums of powers):
  ``a`` from a start in a table and secant steps on ``g(a) = δ``, then
  ``Φ`` from the closed forms (exact to rounding);
* ``"table"``: any other profile (measured tables): a cubic Hermite interpolant of ``Φ(δ)`` on
  nodes ``δ_i = g(a_i)`` with the exact slopes ``Φ'_i = 2a_i``, built once per profile and depth
  range (cached on the profile). Its error (measured at the interval midpoints against the
  profile's own routes) is reported as the model error; the slope used in the Jacobian is the
  interpolant's own derivative, so the Jacobian is exact for the model being fitted.
"""
from __future__ import annotations

import numpy as np

from ..errors import NotSupportedError

__all__ = ["TABLE_NODES", "TipModel", "flat_radius", "g_prime"]

#: Hermite nodes of the ``"table"`` route (graded towards zero in the contact radius)
TABLE_NODES = 1025
#: nodes of the start table of the ``"newton"`` route
_START_NODES = 257
#: secant steps of the ``"newton"`` route after one step with the start table's slope (the
#: error falls superlinearly; four reach rounding from a start table of 257 nodes)
_SECANT_STEPS = 4


def _hermite(x: np.ndarray, xn: np.ndarray, yn: np.ndarray, mn: np.ndarray
             ) -> tuple[np.ndarray, np.ndarray]:
    """Cubic Hermite interpolant through ``(xn, yn)`` with slopes ``mn``: value and derivative
    at ``x`` (inside ``[xn[0], xn[-1]]``)."""
    k = np.clip(np.searchsorted(xn, x, side="right") - 1, 0, xn.size - 2)
    x0 = xn[k]
    h = xn[k + 1] - x0
    t = (x - x0) / h
    y0, y1, m0, m1 = yn[k], yn[k + 1], mn[k], mn[k + 1]
    t2 = t * t
    t3 = t2 * t
    val = ((2 * t3 - 3 * t2 + 1) * y0 + (t3 - 2 * t2 + t) * h * m0
           + (3 * t2 - 2 * t3) * y1 + (t3 - t2) * h * m1)
    der = ((6 * t2 - 6 * t) / h * (y0 - y1) + (3 * t2 - 4 * t + 1) * m0
           + (3 * t2 - 2 * t) * m1)
    return val, der


class TipModel:
    """``Φ(δ)`` (m², force at unit modulus) and ``dΦ/dδ = 2a`` (m) of a profile for
    ``0 <= δ <= delta_max``.

    Parameters
    ----------
    profile : Profile
        Any axisymmetric profile (a punch wall only with ``allow_wall``).
    delta_max : float
        Largest indentation the fit may need, m (> 0).
    rtol : float
        Tolerance of the profile's own routes when a table is built.
    allow_wall : bool
        Accept a punch wall (the elastic and loop fits); ``False`` refuses it.

    Raises
    ------
    NotSupportedError
        A punch wall without ``allow_wall``.

    Notes
    -----
    A punch wall at ``b``: a flat punch takes the route ``"punch"`` (``Φ = 2bδ``); a profile
    rising up to the wall takes the table up to the depth ``g(b)`` where the contact reaches
    the wall, and ``Φ`` grows as ``2b`` per unit indentation beyond.
    """

    def __init__(self, profile, delta_max: float, rtol: float = 1e-12,
                 allow_wall: bool = False) -> None:
        if np.isfinite(profile.wall_radius) and not allow_wall:
            raise NotSupportedError(
                f"profile={profile!r} has a punch wall: its contact radius stops at the wall, "
                "which this fit (a viscoelastic one, beyond the flat punch) does not cover; fit a profile "
                "without a wall.")
        self.profile = profile
        self.rtol = rtol
        self.error = 0.0
        #: a wall stops the contact radius: beyond the depth it reaches, Φ grows as 2bδ
        self._wall = bool(np.isfinite(profile.wall_radius))
        if profile.is_flat_punch:
            self.route = "punch"            # a flat punch: Φ = 2bδ, a = b
            self._b = float(profile.wall_radius)
            self.delta_max = float(delta_max)
            return
        terms = profile.power_terms()
        if terms is not None and len(terms) == 1 and profile.flat_radius == 0.0:
            c, n = terms[0]
            self.route = "power"
            self._kc = profile._power_kappa(n) * c
            self._n = n
            self.delta_max = float(delta_max)
            return
        cheap = (profile.g_route == "closed_form" and not profile.has("linear_table")
                 and not profile.has("node_table")
                 and profile._g_integral_exact(np.array([0.0])) is not None)
        self.route = "newton" if cheap and not self._wall else "table"
        nodes = _START_NODES if cheap else TABLE_NODES
        self._build(float(delta_max), nodes)

    # ------------------------------------------------------------------ table
    def _build(self, delta_max: float, nodes: int) -> None:
        p = self.profile
        key = (self.route, nodes, delta_max, self.rtol)
        cache = p.__dict__.setdefault("_fit_tip_tables", {})
        if key not in cache:
            b = flat_radius(p)
            a_top = float(p._radius_of_depth(np.array([delta_max]), self.rtol)[0])
            a = b + (a_top - b) * np.linspace(0.0, 1.0, nodes) ** 2   # graded towards δ = 0
            g = p._g(a, self.rtol)
            g[0] = 0.0
            g_int = p._g_integral(a, self.rtol)
            phi = 2.0 * (a * g - g_int)
            phi[0] = 0.0
            ok = np.diff(g) > 0
            if not np.all(ok):
                raise NotSupportedError(
                    f"profile={p!r}: its transform g is not increasing below the contact radius "
                    f"{a_top!r} m (a ring contact), which fit.indentation does not cover.")
            err = 0.0
            if self.route == "table":       # measured error of the interpolant at the midpoints
                am = 0.5 * (a[1:] + a[:-1])
                dm = p._g(am, self.rtol)
                phim = 2.0 * (am * dm - p._g_integral(am, self.rtol))
                val, _ = _hermite(dm, g, phi, 2.0 * a)
                scale = np.maximum(np.abs(phim), 1e-300)
                inner = phim > 1e-6 * phi[-1]   # forces below 1e-6 of the largest: absolute
                err = float(np.max(np.abs(val - phim)[inner] / scale[inner], initial=0.0))
            cache[key] = (a, g, phi, err, a_top)
        self._a, self._g, self._phi, self.error, self._a_top = cache[key]
        self.delta_max = delta_max

    # ------------------------------------------------------------------ evaluation
    def __call__(self, delta: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """``Φ(δ)`` and ``dΦ/dδ`` at indentations ``δ`` (m, array); 0 where ``δ <= 0``."""
        d = np.maximum(np.asarray(delta, float), 0.0)
        if self.route == "punch":
            pos = d > 0
            return 2.0 * self._b * d, np.where(pos, 2.0 * self._b, 0.0)
        if self.route == "power":
            n = self._n
            if n == 2.0:                    # the paraboloid without general powers (speed)
                a = np.sqrt(d * (1.0 / self._kc))
                phi = a * a
                phi *= a
            elif n == 1.0:
                a = d * (1.0 / self._kc)
                phi = a * a
            else:
                a = (d / self._kc) ** (1.0 / n)
                phi = a ** (n + 1.0)
            phi *= 2.0 * self._kc * n / (n + 1.0)
            return phi, 2.0 * a
        d_in = d
        d = np.minimum(d, self._g[-1])
        if self.route == "table":
            phi, der = _hermite(d, self._g, self._phi, 2.0 * self._a)
            pos = d > 0
            if self._wall:                  # beyond the wall's depth: the punch's 2bδ
                phi = phi + 2.0 * self._a[-1] * (d_in - d)
            return np.where(pos, phi, 0.0), np.where(pos, der, 0.0)
        a = self._newton_radius(d)
        phi = 2.0 * (a * d - self.profile._g_integral(a, self.rtol))
        pos = d > 0
        return np.where(pos, phi, 0.0), np.where(pos, 2.0 * a, 0.0)

    def _newton_radius(self, d: np.ndarray) -> np.ndarray:
        """Contact radius of the ``"newton"`` route at indentations ``d`` (clipped, m)."""
        p = self.profile
        k = np.clip(np.searchsorted(self._g, d, side="right") - 1, 0, self._g.size - 2)
        a0 = np.interp(d, self._g, self._a)
        g0 = p._g(a0, self.rtol)
        a1 = np.clip(a0 + (d - g0) * (self._a[k + 1] - self._a[k]) / (self._g[k + 1] - self._g[k]),
                     p.flat_radius, self._a_top)
        for _ in range(_SECANT_STEPS):      # secant steps on g(a) = d
            g1 = p._g(a1, self.rtol)
            dg = g1 - g0
            moving = dg != 0
            step = np.where(moving, (d - g1) * (a1 - a0) / np.where(moving, dg, 1.0), 0.0)
            a0, g0 = a1, g1
            a1 = np.clip(a1 + step, p.flat_radius, self._a_top)
        return a1

    def radius(self, delta: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Contact radius ``a`` (m) of the model and its slope ``da/dδ`` at indentations ``δ``
        (m); both 0 where ``δ <= 0``. The model's own: ``a = Φ'/2`` and ``da/dδ = Φ''/2`` of
        the Hermite interpolant on the ``"table"`` route, ``1/g'(a)`` on the others."""
        d = np.maximum(np.asarray(delta, float), 0.0)
        pos = d > 0
        if self.route == "punch":
            return np.where(pos, self._b, 0.0), np.zeros(d.shape)
        if self.route == "power":
            n, kc = self._n, self._kc
            a = (d / kc) ** (1.0 / n)
            # g = K a^n: da/dδ = a/(n δ)
            slope = np.where(pos, a / (n * np.where(pos, d, 1.0)), 0.0)
            return a, slope
        d = np.minimum(d, self._g[-1])
        if self.route == "table":
            xn, yn, mn = self._g, self._phi, 2.0 * self._a
            k = np.clip(np.searchsorted(xn, d, side="right") - 1, 0, xn.size - 2)
            h = xn[k + 1] - xn[k]
            t = (d - xn[k]) / h
            der = ((6 * t * t - 6 * t) / h * (yn[k] - yn[k + 1])
                   + (3 * t * t - 4 * t + 1) * mn[k] + (3 * t * t - 2 * t) * mn[k + 1])
            der2 = ((12 * t - 6) / (h * h) * (yn[k] - yn[k + 1]) + (6 * t - 4) / h * mn[k]
                    + (6 * t - 2) / h * mn[k + 1])
            if self._wall:                  # at the wall the radius stops
                der2 = np.where(np.maximum(np.asarray(delta, float), 0.0) > xn[-1], 0.0, der2)
            return np.where(pos, 0.5 * der, 0.0), np.where(pos, 0.5 * der2, 0.0)
        a = self._newton_radius(d)
        gp = g_prime(self.profile, a, self.rtol)
        return np.where(pos, a, 0.0), np.where(pos & (gp > 0), 1.0 / np.where(gp > 0, gp, 1.0),
                                                0.0)


def flat_radius(profile) -> float:
    """Radius ``b`` (m) of the tip's flat centre: the profile's own, or for a measured table
    with linear interpolation the last node of its leading run of zero heights (``g = 0``
    exactly up to it); 0 without one."""
    b = float(profile.flat_radius)
    if b > 0.0 or not profile.has("linear_table"):
        return b
    f, r = np.asarray(profile.f, float), np.asarray(profile.r, float)
    k = int(np.argmax(f != f[0])) - 1 if np.any(f != f[0]) else 0
    return float(r[k]) if k > 0 and f[0] == 0.0 else 0.0


def g_prime(profile, a: np.ndarray, rtol: float = 1e-12) -> np.ndarray:
    """``g'(a)`` (dimensionless) of a profile: its closed form, the sum of its power terms'
    ``n κ_n c a^(n-1)``, else fourth-order central differences of ``g`` (step ``1e-4`` of ``a``
    or of the distance ``a - b`` from a flat centre's edge, whichever is smaller)."""
    if profile._has("_g_prime_closed_form"):
        with np.errstate(all="ignore"):
            gp = np.asarray(profile._g_prime_closed_form(a), float)
        if np.all(np.isfinite(gp)):
            return gp
    terms = profile.power_terms()
    if terms is not None and profile.flat_radius == 0.0:
        with np.errstate(divide="ignore", invalid="ignore"):
            return sum(n * profile._power_kappa(n) * c * a ** (n - 1.0) for c, n in terms)
    b = profile.flat_radius       # the stencil stays beyond a flat centre's edge
    eps = 1e-4 * np.maximum(np.minimum(a, a - b) if b > 0 else a, 1e-300)
    x = np.maximum(a, b + 2.0 * eps)
    f = [profile._g(x + k * eps, rtol) for k in (-2.0, -1.0, 1.0, 2.0)]
    return (f[0] - 8 * f[1] + 8 * f[2] - f[3]) / (12 * eps)


#: evaluations over which a stalled fit is recognised (see :func:`levenberg_marquardt`)
STALL_WINDOW = 40


class _AtRounding(Exception):
    """Raised inside the residual callback to stop MINPACK (at rounding, or stalled)."""

    def __init__(self, x: np.ndarray, message: str) -> None:
        super().__init__(message)
        self.x, self.message = x, message


def levenberg_marquardt(residual, jacobian, x0: np.ndarray, max_nfev: int = 500,
                        floor: float = 0.0, stall: float = 0.0) -> tuple:
    """MINPACK's Levenberg-Marquardt (``scipy.optimize.leastsq``, the routine behind
    ``least_squares(method="lm")`` and ``curve_fit``) with the exact Jacobian, without the
    wrapper's per-call overhead: returns ``(x, nfev, ok, message)``.

    ``floor``: a sum of squares at the rounding of the model (``(ROUNDING · |data|)²``); the
    first point whose residual reaches it is the solution (nothing is left to gain, and
    MINPACK's own tests, tight so that noisy fits converge fully, would otherwise spend several
    more evaluations on rounding noise). Noisy data never reach it and stop by MINPACK's tests.

    ``stall``: a relative decrease of the sum of squares; when the best sum of squares has
    fallen by less than this over the last :data:`STALL_WINDOW` evaluations, the best point is
    the solution. A model with jumps (the end of a JKR branch, the DMT step at contact) can
    have its least squares on the edge where a data point changes sides; MINPACK then creeps
    along that edge by rejected and tiny accepted steps until ``max_nfev``. Given as
    ``0.1/dof``, the fit stops once chi² falls by less than 0.1 over the window (a change of
    the parameters well inside their standard errors); ``0`` never stops.
    """
    from scipy.optimize import leastsq
    count = 0
    best_ss = np.inf                    # the best sum of squares and its point
    best_x = np.asarray(x0, dtype=float)
    marks = [np.inf] * STALL_WINDOW     # the best sum of squares at the last evaluations

    def res(x: np.ndarray) -> np.ndarray:
        nonlocal count, best_ss, best_x
        count += 1
        r = residual(x)
        ss = float(r @ r)
        if ss <= floor:
            raise _AtRounding(np.array(x, dtype=float), "the residual reached rounding")
        if ss < best_ss:
            best_ss, best_x = ss, np.array(x, dtype=float)
        old = marks[count % STALL_WINDOW]
        marks[count % STALL_WINDOW] = best_ss
        if stall > 0 and best_ss >= old * (1.0 - stall):
            raise _AtRounding(best_x, f"the sum of squares fell by less than {stall:.3g} "
                              f"(relative) over {STALL_WINDOW} evaluations")
        return r

    try:
        x, _, info, msg, ier = leastsq(res, x0, Dfun=jacobian, full_output=True, ftol=1e-15,
                                       xtol=1e-15, gtol=1e-15, maxfev=max_nfev)
    except _AtRounding as stop:
        return np.atleast_1d(stop.x), count, True, stop.message
    return np.atleast_1d(x), int(info["nfev"]), ier in (1, 2, 3, 4), msg


#: residual norm, relative to the data's norm, taken as the rounding of a model evaluation
#: (noise-free data reach ~1e-15; parameters are then exact to ~1e-13, far inside the fits'
#: tolerances)
ROUNDING = 1e-13


def covariance(J: np.ndarray, s2: float) -> np.ndarray:
    """``s² (JᵀJ)⁻¹`` through the columns normalised to unit length (so parameters of very
    different scales do not spoil the conditioning) and the eigen-decomposition of the small
    ``p × p`` matrix; ``inf`` everywhere when the normalised matrix is singular (parameters
    that the data cannot tell apart)."""
    norms = np.sqrt(np.einsum("ij,ij->j", J, J))
    p = J.shape[1]
    if not np.all(norms > 0):
        return np.full((p, p), np.inf)
    Jn = J / norms
    w, V = np.linalg.eigh(Jn.T @ Jn)
    if not w[0] > 1e-13 * w[-1]:
        return np.full((p, p), np.inf)
    return (V / w) @ V.T * s2 / np.outer(norms, norms)
