"""Master curves of power-law contacts at constant normal load: torsion (exact) and
Cattaneo–Mindlin (closed form), for the vectorised contact law.

For ``f = c r^n`` the exact partial-slip torsion (Jäger's flat-punch superposition) is
self-similar [J95]: with the dimensionless twist

    y = 2 G_t a φ / (μ E* d)

the stick ratio ``c/a``, the torque over the full-sliding torque
``M_full = π n/(2(n+2)) μ E* d a²`` and the energy dissipated by monotonic twisting,
``D = M_full φ q(y)``, depend on ``y`` and ``n`` only. :func:`torsion_master` computes them once
per exponent with the exact solvers of :mod:`contactlab.physics.torsion_exact` (tolerance
``1e-14``) and stores them as a piecewise polynomial in ``s = r/(1 + r)``, ``r = (y/y_s)^(1/k)``
(uniform panels on ``[0, 1]``; ``m/s^k`` and ``q/s^(2k)`` are stored, so torque and dissipation
stay relative-accurate as ``y → 0``). ``k = 1`` for ``n >= 1``. For ``0 < n < 1`` the pressure
is singular at the centre (``p ∝ r^(n-1)``), the slip function grows as ``P(c) ∝ c^(n-1)`` and
the stick ratio decays algebraically, ``c/a ∝ y^(-1/(1-n))`` with ``ln y`` corrections: a
non-integer power of ``1 - s`` at ``k = 1`` (measured: 2e-6 at ``n = 0.2`` with 128 panels,
converging as ``h^1.25``). ``k = 4`` (:data:`MAP_POWER_BELOW_ONE`) turns it into
``(1 - s)^(4/(1-n))``, smooth enough that 128 panels certify at ~1e-15 for ``0.01 <= n < 1``.

Its accuracy is *certified* at construction: the curves are evaluated at points that
were not interpolation nodes (the panel midpoints between Chebyshev nodes) and compared with the
exact solvers; the maximum difference is kept in :attr:`MasterCurve.certified_error` and the
build fails (``ConvergenceError``) if it exceeds the requested tolerance.

Cattaneo–Mindlin needs no table: with ``x = G*|u|/(μE*d)`` (the displacement over the
full-slip displacement) ``F = μF_N(1 - (1-x)^{(n+1)/n})``, ``c = a(1-x)^{1/n}`` and the virgin
dissipation ``D = 2a(μE*d)²/G* [x J1(t) - J2(t)]`` with ``t = c/a``,
``J1 = ∫_t^1 (1-s^n) ds``, ``J2 = ∫_t^1 (1-s^n)² ds`` (:func:`tangential_master`).

Pure kernels: plain arrays in, arrays out.
"""
from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache
from typing import Any

import numpy as np

from ..errors import ConvergenceError, NotSupportedError

__all__ = ["MasterCurve", "torsion_master", "torsion_scales", "inverse_twist_scale",
           "tangential_master",
           "MASTER_RTOL", "MASTER_PANELS", "MAX_PANELS", "MASTER_DEGREE", "MIN_EXPONENT",
           "CERTIFY_TOL", "MAP_POWER_BELOW_ONE", "ESTRIN_TERMS", "evaluate", "map_power"]

#: tolerance of the exact solvers the master curves are built from
MASTER_RTOL = 1e-14
#: first panel count (doubled until certified, at most MAX_PANELS) and polynomial degree of the
#: torsion master curves; measured: n = 2 and 4 reach 1e-15 with 128 panels, n = 1 (cone, whose
#: stick ratio decays as exp(-sqrt(y))) needs 512, n = 10 needs 256
MASTER_PANELS = 128
MAX_PANELS = 1024
MASTER_DEGREE = 7
#: coefficients per panel evaluated by Estrin's scheme (degree 7: pairs, then u², then u⁴; the
#: same operations as Horner's rule in a dependency chain of 3 multiply-adds instead of 7,
#: measured 5-6 % less CPU time of the compiled law's constant-load pass at 10^6 contacts);
#: other degrees by Horner's rule. The compiled law evaluates in the same order (same bits)
ESTRIN_TERMS = 8
#: certified error of the curves (absolute; t, M/M_full and D/(M_full φ) are all O(1))
CERTIFY_TOL = 1e-13
#: smallest supported exponent. For n -> 0 the pressure p ∝ r^(n-1) approaches a non-integrable
#: centre singularity and the exact solvers' own results scatter more: measured certification
#: errors 5e-15 (n = 0.05), 3e-14 (n = 0.01), 3e-13 at any panel count (n = 0.001, above
#: CERTIFY_TOL)
MIN_EXPONENT = 0.01
#: power k of the panel map s = r/(1+r), r = (y/y_s)^(1/k), for exponents n < 1 (k = 1 for
#: n >= 1): the algebraic decay c/a ∝ y^(-1/(1-n)) becomes (1-s)^(4/(1-n)) (see the module text)
MAP_POWER_BELOW_ONE = 4


@dataclass(frozen=True, eq=False)
class MasterCurve:
    """Piecewise-polynomial master curves of one power-law family (exact torsion).

    Attributes
    ----------
    n : float
        Exponent of the family.
    y_scale : float
        ``y_s`` of the map ``s = r/(1 + r)``, ``r = (y/y_s)^(1/k)``.
    coef : ndarray, shape (3, panels, degree + 1)
        Monomial coefficients in each panel's local variable ``u ∈ [-1, 1]`` (lowest power
        first) of ``t = c/a``, ``m/s^k`` and ``q/s^(2k)`` with ``m = M/M_full`` and
        ``q = D/(M_full φ)``.
    certified_error : float
        Largest absolute difference to the exact solvers at the certification points.
    y0, m0 : float
        Flat punch (``n = inf``): no slip up to ``y0 = 1/2`` (``t = 1``, ``m = m0 y``, no
        dissipation); the panels map ``s = (y - y0)/(y - y0 + y_s)`` beyond. 0 for power laws.
    scaled : bool
        The table holds ``m/s^k`` and ``q/s^(2k)`` (power laws, where both vanish as
        ``y → 0``) or ``m`` and ``q`` themselves (flat punch).
    power : int
        ``k`` of the map (1 for ``n >= 1`` and the flat punch, :data:`MAP_POWER_BELOW_ONE`
        below).
    """

    n: float
    y_scale: float
    coef: np.ndarray
    certified_error: float
    y0: float = 0.0
    m0: float = 0.0
    scaled: bool = True
    power: int = 1

    @property
    def panels(self) -> int:
        return int(self.coef.shape[1])

    def __call__(self, y: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """``(t, m, q)`` at dimensionless twists ``y >= 0`` (any shape)."""
        return evaluate(self.coef, self.y_scale, np.asarray(y, float), self.y0, self.m0,
                        self.scaled, self.power)


def evaluate(coef: np.ndarray, y_scale: float, y: np.ndarray, y0: float = 0.0,
             m0: float = 0.0, scaled: bool = True, power: int = 1, xp: Any = np
             ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Evaluate the three curves of ``coef`` at ``y`` (the reference of the compiled kernel).

    The table holds ``t``, ``m/s^k`` and ``q/s^(2k)`` (smooth and non-zero at ``s = 0``, so
    torque and dissipation keep their relative accuracy as ``y → 0``), as monomials in the
    panel's local variable ``u ∈ [-1, 1]`` (degree 7 by Estrin's scheme, :data:`ESTRIN_TERMS`;
    other degrees by Horner's rule), with ``s = y/(y + y_s)`` (``k = power = 1``) or
    ``s = r/(1 + r)``, ``r = (y/y_s)^(1/k)``. Flat punch (``y0 > 0``, ``scaled`` False): ``t = 1``,
    ``m = m0 y``, ``q = 0`` up to ``y0``; the table holds ``t``, ``m``, ``q`` in
    ``s = (y - y0)/(y - y0 + y_s)`` beyond.

    ``xp`` is the array module of ``coef`` and ``y`` (numpy by default, CuPy on a GPU): only
    ufuncs, ``where``, ``clip`` and integer gathers are used, so one text serves both. The
    panel index is clipped to the table: for ``y >= 0`` (and ``-0.0``) it already lies in it,
    and a non-finite ``y`` (``inf / inf`` in ``s``) gives NaN curves instead of an index
    outside the table.
    """
    if y0 > 0.0:
        stuck = y <= y0
        t, m, q = evaluate(coef, y_scale, xp.maximum(y - y0, 0.0), 0.0, 0.0, scaled, xp=xp)
        return (xp.where(stuck, 1.0, t), xp.where(stuck, m0 * y, m),
                xp.where(stuck, 0.0, q))
    N = coef.shape[1]
    if power == 1:
        s = y / (y + y_scale)
    else:
        r = (y / y_scale) ** (1.0 / power)
        s = r / (1.0 + r)
    z = s * N
    j = xp.clip(z.astype(np.intp), 0, N - 1)
    u = 2.0 * (z - j) - 1.0
    out = []
    if coef.shape[2] == 8:      # degree 7 (ESTRIN_TERMS, a literal: the law's exported source
        # copies this function): Estrin's scheme, in this order of operations
        u2 = u * u
        u4 = u2 * u2
        for k in range(3):
            ck = coef[k]
            out.append(((ck[j, 0] + ck[j, 1] * u) + (ck[j, 2] + ck[j, 3] * u) * u2)
                       + ((ck[j, 4] + ck[j, 5] * u) + (ck[j, 6] + ck[j, 7] * u) * u2) * u4)
    else:                                   # any other degree: Horner
        for k in range(3):
            ck = coef[k]
            acc = ck[j, -1]
            for p in range(coef.shape[2] - 2, -1, -1):
                acc = acc * u + ck[j, p]
            out.append(acc)
    if not scaled:
        return xp.clip(out[0], 0.0, 1.0), out[1], out[2]
    if power != 1:
        s = s**power
    return xp.clip(out[0], 0.0, 1.0), out[1] * s, out[2] * (s * s)


def torsion_scales(n: float, E_star, G_t, mu, a, d):
    """``(φ_s, M_full, n)``: twist scale ``μE*d/(2G_t a)`` (rad) and full-sliding torque
    ``π n/(2(n+2)) μ E* d a²`` (N·m) of power-law contacts (flat punch, ``n = inf``:
    ``π/2 μ E* d a²``); ``y = φ/φ_s``."""
    phi_s = mu * E_star * d / (2.0 * G_t * a)
    cM = np.pi * n / (2.0 * (n + 2.0)) if n != np.inf else 0.5 * np.pi
    M_full = cM * mu * E_star * d * a * a
    return phi_s, M_full


def inverse_twist_scale(E_star, G_t, mu, a, d):
    """``1/φ_s = 2 G_t a / (μ E* d)`` (1/rad), so that ``y = φ (1/φ_s)``: the contact law's
    argument of the master curve by a multiply (one division per contact and step instead of
    one per curve evaluation; the compiled law forms it in this order, the same bits)."""
    return (2.0 * G_t * a) / (mu * E_star * d)


def _exact_curves(n: float, y: np.ndarray, rtol: float = MASTER_RTOL):
    """``(t, m, q)`` at ``y`` from the exact solvers (unit contact: c = a = E* = G_t = μ = 1)."""
    from ..profiles import PowerLaw
    from ..symbolic.transform import kappa
    from . import torsion_exact as ex
    from .torsion import Exact
    prof = PowerLaw(c=1.0, n=n)
    kap = float(kappa(n))
    y = np.asarray(y, float)
    one = np.ones(y.shape)
    d = kap * one
    phi = 0.5 * kap * y                       # φ = y μE*d/(2G_t a)
    model = Exact(prof, 1.0, 1.0, 1.0, rtol)
    t = model.of_twist(phi, one, d, d).stick_radius
    # polish the root (the bracketing solver stops at ~1e-12): Newton on P(t)/κ = y, with the
    # slope from a central difference (it only scales the tiny correction)
    part = np.flatnonzero((t > 0) & (t < 1))
    if part.size:
        tp, yp = t[part], y[part]

        def yfun(tt):
            return ex.slip_function(prof, 1.0, tt, 1.0, kap, kap, rtol)[0] / kap

        for _ in range(2):
            h = 1e-6 * np.minimum(tp, 1.0 - tp)
            slope = (yfun(tp + h) - yfun(tp - h)) / (2.0 * h)
            with np.errstate(divide="ignore", invalid="ignore"):
                corr = (yfun(tp) - yp) / slope
            tp = np.clip(tp - np.where(np.isfinite(corr), corr, 0.0), 0.0, 1.0)
        t[part] = tp
    T, _ = ex.torque_integral(prof, 1.0, t, one, d, d, rtol)
    M = ex.torque_of_stick(1.0, 1.0, t, phi, T)
    M_full = np.pi * n / (2.0 * (n + 2.0)) * kap
    M = np.where(t > 0, M, M_full)
    D = model.dissipation(phi, t, one, d, d)
    with np.errstate(divide="ignore", invalid="ignore"):
        q = np.where(phi > 0, D / (M_full * phi), 0.0)
    return t, M / M_full, q


#: flat punch: no slip up to y = 1/2 (the edge's shear and pressure singularities have the same
#: strength, so slip starts at the edge at φ = μE*d/(4 G_t a)); torque 16/3 G_t a³ φ there
FLAT_Y0 = 0.5
FLAT_M0 = 16.0 / (3.0 * np.pi)


def _flat_exact_curves(y: np.ndarray, rtol: float = MASTER_RTOL):
    """``(t, m, q)`` of the flat punch at ``y > 1/2`` (unit contact: a = d = E* = G_t = μ = 1).

    Closed forms with ``P(x) = K(√(1-x²))/π`` (only the edge term of the slip function
    survives, ``g = 0`` inside): the stick ratio from ``P(t) = y`` (bisection in ``ln t`` to
    rounding), ``M = (16/3)(y/2) t³ + 8 h(t)/π`` over ``M_full = π/2``; the dissipation by the
    exact solver's integral (:func:`~contactlab.physics.torsion_exact.dissipation_integral`)."""
    from ..profiles import FlatPunch
    from . import torsion_exact as ex
    from .torsion import Exact
    y = np.asarray(y, float)
    lo = np.full(y.shape, np.log(ex.C_MIN_REL))
    hi = np.zeros(y.shape)
    for _ in range(80):                     # K(√(1-t²)) decreases with t; ln t in [-230, 0]
        mid = 0.5 * (lo + hi)
        big = ex.K_comp(np.exp(2.0 * mid)) / np.pi > y
        lo = np.where(big, mid, lo)
        hi = np.where(big, hi, mid)
    t = np.exp(0.5 * (lo + hi))
    t = np.where(t <= ex.C_MIN_REL * 1.0000001, 0.0, t)
    phi = 0.5 * y
    M = 16.0 / 3.0 * phi * t**3 + 8.0 * ex.h_kernel(t) / np.pi
    M_full = 0.5 * np.pi
    one = np.ones(y.shape)
    D = Exact(FlatPunch(radius=1.0), 1.0, 1.0, 1.0, rtol).dissipation(phi, t, one, one,
                                                                    np.zeros(y.shape))
    return t, M / M_full, D / (M_full * phi)


def map_power(n: float) -> int:
    """``k`` of the panel map for exponent ``n`` (see :data:`MAP_POWER_BELOW_ONE`)."""
    return MAP_POWER_BELOW_ONE if n < 1.0 else 1


def _fit(n: float, N: int, p: int, y_scale: float, power: int = 1):
    """Interpolate at Chebyshev points of each panel; certify at the midpoints between them."""
    from numpy.polynomial import chebyshev as C
    uc = -np.cos(np.pi * (np.arange(p + 1) + 0.5) / (p + 1))          # Chebyshev points in (-1, 1)
    left = np.arange(N)[:, None] / N
    s = left + 0.5 * (uc + 1.0) / N
    s_chk = left + 0.25 * (uc[1:] + uc[:-1] + 2.0) / N
    s_all = np.concatenate([s.ravel(), s_chk.ravel(), [1.0 - 1e-9]])
    y_all = y_scale * (s_all / (1.0 - s_all)) ** power
    flat = n == np.inf
    if flat:
        t, m, q = _flat_exact_curves(FLAT_Y0 + y_all)
    else:
        t, m, q = _exact_curves(n, y_all)
    ns = s.size
    sk = s_all**power
    table = (t, m, q) if flat else (t, m / sk, q / sk**2)
    V = C.chebvander(uc, p)
    to_mono = np.stack([np.pad(C.cheb2poly(e), (0, p + 1 - j - 1))
                        for j, e in enumerate(np.eye(p + 1))])      # row j: T_j in monomials
    coef = np.stack([np.linalg.solve(V, v[:ns].reshape(N, p + 1).T).T @ to_mono
                     for v in table])
    approx = evaluate(coef, y_scale, y_all[ns:], scaled=not flat, power=power)
    err = max(float(np.max(np.abs(ap - v[ns:]))) for ap, v in zip(approx, (t, m, q)))
    return coef, err


@lru_cache(maxsize=16)
def torsion_master(n: float, degree: int = MASTER_DEGREE, tol: float = CERTIFY_TOL
                   ) -> MasterCurve:
    """Certified master curves of exact torsion for ``f = c r^n`` (computed once per ``n``;
    ``n = inf``: the flat punch).

    The panels start at :data:`MASTER_PANELS` and double until the certified error is at most
    ``tol`` (at most :data:`MAX_PANELS`); a build takes 1-5 s.

    Raises
    ------
    NotSupportedError
        ``n < 0.01`` (see :data:`MIN_EXPONENT`).
    ConvergenceError
        The certified error still exceeds ``tol`` with :data:`MAX_PANELS` panels.
    """
    n = float(n)
    if not n >= MIN_EXPONENT:
        raise NotSupportedError(
            f"n={n!r} is not supported by the torsion master curves: the exponent must satisfy "
            f"n >= {MIN_EXPONENT:g} (below, the centre singularity of the pressure, p ∝ r^(n-1), "
            f"approaches non-integrability and the exact solvers no longer certify the curves "
            f"to {CERTIFY_TOL:g}).")
    # y_s: the twist at which c/a = 1/2, so that the panels split the curve evenly
    flat = n == np.inf
    if flat:
        from . import torsion_exact as ex
        y_scale = float(ex.K_comp(np.array(0.25)) / np.pi) - FLAT_Y0
    else:
        y_scale = float(_y_half(n))
    panels = MASTER_PANELS
    power = 1 if flat else map_power(n)
    while True:
        coef, err = _fit(n, panels, degree, y_scale, power)
        if err <= tol:
            if flat:
                return MasterCurve(n, y_scale, coef, err, FLAT_Y0, FLAT_M0, False)
            return MasterCurve(n, y_scale, coef, err, power=power)
        if panels >= MAX_PANELS:
            raise ConvergenceError(f"torsion master curve for n={n!r}: certified error "
                                   f"{err:.3g} exceeds {tol:.3g} with {panels} panels of degree "
                                   f"{degree}.")
        panels *= 2


def _y_half(n: float) -> float:
    from ..profiles import PowerLaw
    from ..symbolic.transform import kappa
    from . import torsion_exact as ex
    kap = float(kappa(n))
    P, _ = ex.slip_function(PowerLaw(c=1.0, n=n), 1.0, np.array([0.5]), np.array([1.0]),
                            np.array([kap]), np.array([kap]), MASTER_RTOL)
    return float(P[0]) / kap


# ---------------------------------------------------------------- Cattaneo–Mindlin, closed form
def tangential_master(n: float, x: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``(t, f, w)`` of the Cattaneo–Mindlin virgin curve at ``x = G*|u|/(μE*d) >= 0``.

    ``t = c/a = (1-x)_+^{1/n}``, ``f = F/(μF_N) = 1 - (1-x)_+^{(n+1)/n}`` and
    ``w = x J1(t) - J2(t)`` with the dissipation ``D = 2a(μE*d)²/G* · w`` (grows as
    ``x (1 - 1/(n+1))`` beyond full slip, ``x >= 1``).
    """
    x = np.asarray(x, float)
    xc = np.minimum(x, 1.0)
    r = 1.0 - xc
    # 1 - t, 1 - t^(n+1) and 1 - t^(2n+1) without cancellation as x -> 0
    if n == 2.0:
        t = np.sqrt(r)
        one_t = xc / (1.0 + t)
    elif n == 1.0:
        t = r
        one_t = xc
    elif n == np.inf:                   # flat punch: stick until full slip (uniform limits)
        one_t = np.where(xc >= 1.0, 1.0, 0.0)
        t = 1.0 - one_t
    else:
        with np.errstate(divide="ignore"):
            one_t = -np.expm1(np.log1p(-xc) / n)
        t = 1.0 - one_t
    f = xc + r * one_t                  # 1 - r t
    f2 = xc + r * f                     # 1 - r² t
    a1 = 1.0 / (n + 1.0)
    a2 = 1.0 / (2.0 * n + 1.0)
    J1 = one_t - f * a1
    J2 = one_t - 2.0 * f * a1 + f2 * a2
    return t, f, np.maximum(x * J1 - J2, 0.0)
