"""Power-law profiles ``f = c r**n`` and their sums: paraboloid, cone, general power law, polynomial.

Every quantity has a closed form [H1; PH]: ``g = κ_n c x**n``, ``∫_0^a g = κ_n c a**(n+1)/(n+1)``,
the pressure shape ``∫_r^a g'/sqrt(x²-r²) dx = n κ_n c a**(n-1) sqrt(1-ρ²) ₂F₁(1-n/2, 1; 3/2; 1-ρ²)``
and the Abel integral of g outside the contact
``(2κ_n c/π) a**(n+1)/(r(n+1)) ₂F₁(1/2, (n+1)/2; (n+3)/2; a²/r²)``.
"""
from __future__ import annotations

import math
from collections.abc import Iterable, Mapping
from typing import ClassVar, cast

import numpy as np

from ..errors import ParameterError
from ..numeric.powers import _TINY, _all_normal, power_integral, times_power
from ..params import LENGTH_BOUNDS, Param, check_in_range, exactly_one
from ..symbolic.form import SympyForm, coefficient_symbols, power_form, rational, symbol
from ..symbolic.transform import kappa
from .base import Profile

#: surface slope at the contact edge above which a smooth profile's contact leaves the half-space
#: theory (ValidityWarning): tan 30°, the exact sphere's limit at a = R/2
#: (:data:`contactlab.profiles.sphere.VALIDITY_RATIO`)
VALIDITY_SLOPE = 1.0 / math.sqrt(3.0)

__all__ = ["PowerLaw", "Paraboloid", "Cone", "Polynomial"]


def _power_pressure_shape(c: float, n: float, r: np.ndarray, a: np.ndarray) -> np.ndarray:
    """``∫_r^a g'(x)/sqrt(x²-r²) dx`` for ``g = κ_n c x**n``, ``0 <= r < a`` (0 for r >= a).

    Near the edge (``1-ρ² <= 1/2``) the Gauss form ``n κ_n c a**(n-1) sqrt(1-ρ²)
    ₂F₁(1-n/2, 1; 3/2; 1-ρ²)`` is used, with ``1-ρ² = (a-r)(a+r)/a²`` free of cancellation.
    Closer to the axis ``₂F₁`` is evaluated near its branch point z = 1, where scipy's ``hyp2f1``
    loses accuracy (1e-6 relative at n = 1.5, O(1) errors or ``inf`` for n ≤ 1.01): there the
    integral ``n κ_n c ∫_0^U (r cosh u)**(n-1) du``, ``U = arccosh(a/r)``, is taken by tanh-sinh
    quadrature to 1e-13. On the axis ``S(0, a) = n κ_n c a**(n-1)/(n-1)`` for ``n > 1``, ``inf``
    for ``n <= 1``.
    """
    r, a = np.broadcast_arrays(r, a)
    out = np.zeros(r.shape)
    inside = r < a
    if not np.any(inside):
        return out
    rr, aa = r[inside], a[inside]
    k = kappa(n)
    if n == 2.0:
        val = 2 * k * c * np.sqrt((aa - rr) * (aa + rr))
    elif n == 1.0:
        with np.errstate(divide="ignore"):
            val = k * c * np.arccosh(aa / rr)
    else:
        val = np.empty(rr.shape)
        z = (aa - rr) * (aa + rr) / (aa * aa)
        edge = z <= 0.5
        if np.any(edge):
            ze, ae = z[edge], aa[edge]
            from scipy.special import hyp2f1   # lazy: scipy.special costs ~0.1 s at import
            val[edge] = times_power(n * k * c, ae, n - 1) * np.sqrt(ze) * hyp2f1(1 - 0.5 * n, 1.0,
                                                                                 1.5, ze)
        axis = rr == 0
        if np.any(axis):
            val[axis] = np.inf if n <= 1 else times_power(n * k * c, aa[axis], n - 1) / (n - 1)
        core = ~edge & ~axis
        if np.any(core):
            from ..numeric.quadrature import tanh_sinh
            rc = rr[core]
            U = np.arccosh(aa[core] / rc)

            def integrand(u: np.ndarray, idx: np.ndarray) -> np.ndarray:
                return (rc[idx][:, None] * np.cosh(u)) ** (n - 1)

            res = tanh_sinh(integrand, np.zeros_like(U), U, rtol=1e-13, raise_on_failure=False)
            val[core] = n * k * c * res.value
    out[inside] = val
    return out


def _power_abel(c: float, n: float, r: np.ndarray, a: np.ndarray) -> np.ndarray:
    """``(2/π) ∫_0^{min(r,a)} g(x)/sqrt(r²-x²) dx`` for ``g = κ_n c x**n`` (= f(r) for r <= a).

    Outside the contact, with ``q = a²/r²``: far out (``q < 1/2``) the Gauss series
    ``(2κ_n c/π) a**(n+1)/(r(n+1)) ₂F₁(1/2, (n+1)/2; (n+3)/2; q)``; near the edge, where that
    ₂F₁ sits at its branch point z = 1, its connection formula about ``1 - q`` (the first term
    collapses to ``f(r)`` because ``₂F₁(1/2, b; 1/2; w) = (1-w)**-b``):
    ``f(r) - (2κ_n c/π) (a**(n+1)/r) sqrt(1-q) ₂F₁(n/2+1, 1; 3/2; 1-q)``, with
    ``1 - q = (r-a)(r+a)/r²`` free of cancellation.
    """
    r, a = np.broadcast_arrays(np.asarray(r, float), np.asarray(a, float))
    out = np.array(times_power(c, np.minimum(r, a), n), dtype=float, ndmin=1).reshape(r.shape)
    outside = r > a
    if np.any(outside):
        from scipy.special import hyp2f1
        rr, aa = np.atleast_1d(r[outside]), np.atleast_1d(a[outside])
        q = (aa / rr) ** 2
        w = (rr - aa) * (rr + aa) / (rr * rr)
        val = np.empty(rr.shape)
        far = w > 0.5
        k2 = 2 * kappa(n) * c / np.pi
        if np.any(far):
            rf, af = rr[far], aa[far]
            val[far] = times_power(k2, af, n + 1) / (rf * (n + 1)) * hyp2f1(
                0.5, 0.5 * (n + 1), 0.5 * (n + 3), q[far])
        near = ~far
        if np.any(near):
            rn, an, wn = rr[near], aa[near], w[near]
            val[near] = times_power(c, rn, n) - times_power(k2, an, n + 1) / rn * np.sqrt(wn) * hyp2f1(
                0.5 * n + 1, 1.0, 1.5, wn)
        out[outside] = val
    return out


_MIN, _MAX = np.minimum.reduce, np.maximum.reduce


def _slope_all_positive(terms: list[tuple[float, float]], r: np.ndarray) -> np.ndarray | None:
    """``Σ c n r**(n-1)`` where every radius is a positive finite float and every power a
    normal float (the quadrature nodes of one load): the operations of
    :meth:`_PowerSum._slope`'s general route there (``0 + k r**p`` is ``k r**p`` for these
    positive products; the ``np.where`` picks every element), without its masks, zero array
    and, for one term whose powers and products stay normal floats (power 1: ``r**1`` is
    ``r``; power 0: ``r**0`` is 1; else checked at the ends with a margin), without the
    floating-point state switch. None elsewhere (the caller takes
    the general route)."""
    if r.dtype != np.float64 or r.ndim == 0 or r.size == 0:
        return None
    # (r.min() and r.max() without their Python wrappers: the same reductions)
    lo, hi = float(_MIN(r, axis=None)), float(_MAX(r, axis=None))
    if not (lo > 0.0 and hi < math.inf):
        return None
    if len(terms) == 1:
        k, p = terms[0][0] * terms[0][1], terms[0][1] - 1
        if not k > 0:
            return None
        if p == 1.0 and lo >= _TINY and k * lo >= _TINY and k * hi < math.inf:
            return k * r
        if p == 0.0:
            return np.full(r.shape, k)
        # any other power: where r**p and k r**p stay well inside the normal range at both
        # ends (a factor 2 of margin for the rounding of numpy's power against Python's), no
        # element can leave it, and the state switch and the range check have nothing to do
        a, b = (lo, hi) if p > 0 else (hi, lo)
        try:
            pa, pb = a ** p, b ** p
        except OverflowError:
            pa = pb = math.inf
        if 2 * _TINY <= pa and pb <= 1e300 and 2 * _TINY <= k * pa and k * pb <= 1e300:
            return k * r ** p
    elif not all(c * n > 0 for c, n in terms):
        return None
    out = None
    with np.errstate(over="ignore", under="ignore"):
        for c, n in terms:
            pw = r ** (n - 1)
            if not _all_normal(pw):
                return None
            term = (c * n) * pw
            out = term if out is None else out + term
    return out


class _PowerSum(Profile):
    """Shared closed forms for ``f = Σ_i c_i r**n_i`` (all ``c_i > 0``, ``n_i > 0``)."""

    def power_terms(self) -> list[tuple[float, float]]:  # pragma: no cover - abstract-ish
        raise NotImplementedError

    def _height(self, r: np.ndarray) -> np.ndarray:
        return sum(times_power(c, r, n) for c, n in self.power_terms()) * np.ones_like(r)

    def _slope(self, r: np.ndarray) -> np.ndarray:
        fast = _slope_all_positive(self.power_terms(), r)
        if fast is not None:
            return fast
        out = np.zeros_like(r)
        for c, n in self.power_terms():
            with np.errstate(divide="ignore"):
                out = out + np.where(r > 0, times_power(c * n, r, n - 1),
                                     c if n == 1 else (np.inf if n < 1 else 0.0))
        return out

    def _g_closed_form(self, x: np.ndarray) -> np.ndarray:
        return sum(times_power(kappa(n) * c, x, n) for c, n in self.power_terms()) * np.ones_like(x)

    def _g_integral_closed_form(self, a: np.ndarray) -> np.ndarray:
        return power_integral(a, [(kappa(n) * c, n) for c, n in self.power_terms()], 1.0)

    def _g_squared_integral_closed_form(self, a: np.ndarray) -> np.ndarray:
        terms = [(kappa(n) * c, n) for c, n in self.power_terms()]
        return sum(times_power(k1 * k2, a, n1 + n2 + 1) / (n1 + n2 + 1)
                   for k1, n1 in terms for k2, n2 in terms) * np.ones_like(a)

    def _pressure_shape_closed_form(self, r: np.ndarray, a: np.ndarray) -> np.ndarray:
        return cast(np.ndarray, sum(_power_pressure_shape(c, n, r, a) for c, n in self.power_terms()))

    def _abel_g_closed_form(self, r: np.ndarray, a: np.ndarray) -> np.ndarray:
        return cast(np.ndarray, sum(_power_abel(c, n, r, a) for c, n in self.power_terms()))


class PowerLaw(_PowerSum):
    """Power-law indenter ``f(r) = c r**n``.

    Parameters
    ----------
    c : float
        Coefficient, m**(1-n) (> 0).
    n : float
        Exponent (> 0, any real). ``n = 2`` is a paraboloid, ``n = 1`` a cone.

    Notes
    -----
    ``g(x) = κ_n c |x|**n`` with ``κ_n = √π Γ(n/2+1)/Γ(n/2+1/2)`` [H1]. For ``n < 1`` the
    pressure is singular at the centre (``p ∝ r**(n-1)``), for ``n = 1`` logarithmic.

    Examples
    --------
    >>> from contactlab.profiles import PowerLaw
    >>> round(float(PowerLaw(c=1.0, n=2).g(0.5)), 12)
    0.5
    """

    name: ClassVar[str] = "power_law"
    params: ClassVar[tuple[Param, ...]] = (
        Param("c", "c", "m^(1-n)", "positive", "power-law coefficient c", (1e-3, 1e3)),
        Param("n", "n", "1", "positive", "power-law exponent n", (0.3, 50.0)),
    )

    def __init__(self, c: float, n: float) -> None:
        self.c = self.params[0].check(c)
        self.n = self.params[1].check(n)

    def power_terms(self) -> list[tuple[float, float]]:
        return [(self.c, self.n)]

    def _sympy_form(self) -> SympyForm:
        # the exponent stays a number: it fixes the form of every formula
        c = symbol("c")
        return power_form([(c, rational(self.n))], {c: self.c})

    def _g_inverse_closed_form(self, d: np.ndarray) -> np.ndarray:
        k = kappa(self.n) * self.c
        with np.errstate(over="ignore", under="ignore"):
            x = d / k
            out = np.asarray(x ** (1.0 / self.n), dtype=float)
            # the quotient alone may leave the float range (c = 1e294, n = 100): logarithms
            bad = ((x < np.finfo(float).tiny) | ~np.isfinite(x)) & (d > 0) & np.isfinite(d)
            if np.any(bad):
                out = np.array(out, dtype=float, ndmin=1).reshape(np.shape(d))
                out[bad] = np.exp((np.log(np.asarray(d, float)[bad]) - np.log(k)) / self.n)
        return out


class Paraboloid(PowerLaw):
    """Paraboloid ``f(r) = r²/(2R)`` (Hertz).

    Parameters
    ----------
    R : float
        Radius of curvature at the apex, m (> 0).

    Examples
    --------
    >>> from contactlab.profiles import Paraboloid
    >>> float(Paraboloid(R=0.01).g(1e-4))  # x²/R
    1e-06
    """

    name: ClassVar[str] = "paraboloid"
    params: ClassVar[tuple[Param, ...]] = (
        Param("R", "R", "m", "positive", "radius of curvature R", (1e-6, 1.0), LENGTH_BOUNDS),
    )

    def __init__(self, R: float) -> None:
        self.R = self.params[0].check(R)
        self.c = 1.0 / (2.0 * self.R)
        self.n = 2.0

    def _sympy_form(self) -> SympyForm:
        import sympy as sp
        R = symbol("R")
        return power_form([(1 / (2 * R), sp.Integer(2))], {R: self.R})

    def _g_closed_form(self, x: np.ndarray) -> np.ndarray:
        # x**2 / R, in one new array (numpy squares by x·x: the same values)
        out = np.multiply(x, x)
        if isinstance(out, np.ndarray):
            out /= self.R
            return out
        return out / self.R

    def _g_inverse_closed_form(self, d: np.ndarray) -> np.ndarray:
        return np.sqrt(self.R * d)

    def _scalar_closed_forms(self) -> dict:
        """Plain-float ``g`` and its inverse for the scalar normal solve: the operations of
        :meth:`_g_closed_form` and :meth:`_g_inverse_closed_form` (bit-identical results)."""
        R = self.R

        def g(x: float) -> float:
            return x * x / R

        def g_inverse(d: float) -> float:
            return math.sqrt(R * d)

        return {"g": g, "g_inverse": g_inverse}

    def _hertz_force_constants(self, E_star: float) -> tuple[float, float]:
        """``(K, c)`` of the force-controlled solve (Hertz): ``F = K a³`` with
        ``K = 4E*/(3R)`` (``F/(2E*) = a g(a) - ∫g = a³/R - a³/(3R)``), so ``a = cbrt(F/K)``;
        and the force of the state ``F = c·(a d)`` with ``c = 4E*/3`` (``∫g = a d/3`` for
        ``d = a²/R``). Every force-controlled route of a paraboloid (scalar, array, the numpy
        and compiled passes) takes these two floats and the operations ``a = cbrt(F/K)``,
        ``d = (a·a)/R``, ``F = (a·d)·c``: one constant per contact instead of a chain of
        divisions, the same values on every route."""
        return (4.0 * E_star) / (3.0 * self.R), (4.0 * E_star) / 3.0

    def _length_scale(self) -> float:
        return self.R

    @property
    def validity_radius(self) -> float:
        """``R/√3``: the contact radius where the surface slope ``a/R`` reaches tan 30°, the
        limit :class:`~contactlab.profiles.Sphere` takes (``a = R/2`` there); beyond it the
        half-space theory's linearised boundary conditions are outside their range and states
        carry a :class:`~contactlab.errors.ValidityWarning`."""
        return self.R * VALIDITY_SLOPE


class Cone(PowerLaw):
    """Cone ``f(r) = slope * r``.

    Give exactly one of ``slope`` and ``half_angle``.

    Parameters
    ----------
    slope : float, optional
        ``tan β`` with β the surface inclination (= ``cot α`` for the half angle α at the apex),
        dimensionless, > 0.
    half_angle : float or str, optional
        Half angle α at the apex, rad (``"70 deg"`` with a unit), 0 < α < π/2; the cone
        then has ``slope = 1/tan α``.

    Examples
    --------
    >>> Cone(half_angle=np.pi / 4)
    Cone(slope=1.0000000000000002)
    >>> Cone(half_angle="45 deg") == Cone(half_angle=np.pi / 4)
    True

    See Also
    --------
    Cone.from_half_angle
    """

    name: ClassVar[str] = "cone"
    params: ClassVar[tuple[Param, ...]] = (
        Param("slope", "s", "1", "positive", "cone slope tan(beta)", (1e-4, 1e2)),
    )
    #: a scene's [profile] table gives one of the two
    scene_one_of: ClassVar[tuple[tuple[str, ...], ...]] = (("slope",), ("half_angle",))

    def __init__(self, slope: float | None = None, *, half_angle: float | None = None) -> None:
        key, value = exactly_one("Cone()", {"slope": slope, "half_angle": half_angle})
        if key == "half_angle":
            alpha = check_in_range("half_angle", value, 0.0, np.pi / 2, low_open=True,
                                   high_open=True, what="the cone's half angle at the apex (rad)",
                                   unit="rad")
            value = 1.0 / np.tan(alpha)
        self.slope = self.params[0].check(value)
        self.c = self.slope
        self.n = 1.0

    def _sympy_form(self) -> SympyForm:
        import sympy as sp
        s = symbol("s")
        return power_form([(s, sp.Integer(1))], {s: self.slope})

    @classmethod
    def from_half_angle(cls, half_angle: float) -> "Cone":
        """Cone with apex half angle ``half_angle`` (rad, 0 < α < π/2): slope = cot α; the
        same as ``Cone(half_angle=half_angle)``."""
        return cls(half_angle=half_angle)

    def _g_closed_form(self, x: np.ndarray) -> np.ndarray:
        return 0.5 * np.pi * self.slope * x

    def _g_inverse_closed_form(self, d: np.ndarray) -> np.ndarray:
        return 2.0 * d / (np.pi * self.slope)


class Polynomial(_PowerSum):
    """Sum of power terms ``f(r) = Σ c_i r**n_i`` with positive coefficients and exponents.

    Parameters
    ----------
    terms : mapping {n: c} or iterable of (c, n) pairs
        Exponents ``n_i > 0`` (any real) and coefficients ``c_i > 0``, m**(1-n_i).

    Examples
    --------
    >>> from contactlab.profiles import Polynomial
    >>> p = Polynomial({2: 50.0, 4: 1e3})
    >>> p.terms
    ((50.0, 2.0), (1000.0, 4.0))
    """

    name: ClassVar[str] = "polynomial"
    params: ClassVar[tuple[Param, ...]] = (
        Param("terms", "c_i, n_i", "m^(1-n_i)", "positive", "polynomial terms (c, n)"),
    )
    #: a scene gives the terms as a list of [c, n] pairs of plain numbers (SI)
    scene_keys: ClassVar[dict[str, str]] = {"terms": "terms"}

    def __init__(self, terms: Mapping[float, float] | Iterable[tuple[float, float]]) -> None:
        pairs = ([(c, n) for n, c in terms.items()] if isinstance(terms, Mapping)
                 else list(terms))
        if not pairs:
            raise ParameterError("terms=[] is invalid: a Polynomial needs at least one (c, n) term.")
        checked = []
        for i, pair in enumerate(pairs):
            try:
                c, n = pair
            except (TypeError, ValueError) as err:
                raise ParameterError(f"terms[{i}]={pair!r} is invalid: expected a (c, n) pair.") from err
            checked.append((Param(f"terms[{i}].c", "c", "m^(1-n)", "positive", "coefficient c").check(c),
                            Param(f"terms[{i}].n", "n", "1", "positive", "exponent n").check(n)))
        self.terms = tuple(sorted(checked, key=lambda t: t[1]))

    def power_terms(self) -> list[tuple[float, float]]:
        return list(self.terms)

    def _sympy_form(self) -> SympyForm:
        cs = coefficient_symbols(len(self.terms))
        return power_form([(ci, rational(n)) for ci, (_, n) in zip(cs, self.terms)],
                          {ci: cv for ci, (cv, _) in zip(cs, self.terms)})
