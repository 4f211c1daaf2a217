"""Flat punch and flat punches with a rounded (truncated paraboloid) or conical (truncated cone) edge.

Closed forms (theory §2-3):

* flat punch radius b: ``g = 0`` for ``|x| <= b``, the wall fixes ``a = b``; the whole pressure is
  the edge term ``E* d/(π sqrt(b²-r²))`` (Boussinesq).
* truncated paraboloid: ``g = |x| sqrt(x²-b²)/R``, ``∫_0^a g = (a²-b²)^{3/2}/(3R)``,
  ``a² = [b² + sqrt(b⁴ + 4R²d²)]/2``.
* truncated cone: ``g = s|x| arccos(b/|x|)``,
  ``∫_0^a g = s[a²/2·arccos(b/a) - (b/2) sqrt(a²-b²)]``.

The slope jump at ``r = b`` of the truncated profiles gives a logarithmically singular pressure
there; ``breakpoints`` makes every quadrature split at ``b``.
"""
from __future__ import annotations

import math
from typing import ClassVar

import numpy as np

from ..params import LENGTH_BOUNDS, Param
from ..symbolic.form import SympyForm, symbol
from .base import Profile

__all__ = ["FlatPunch", "TruncatedParaboloid", "TruncatedCone"]


class FlatPunch(Profile):
    """Cylindrical flat punch of radius ``radius`` (f = 0 inside, a vertical wall at the edge).

    Parameters
    ----------
    radius : float
        Punch radius ``b``, m (> 0). The contact radius equals it for every positive depth.

    Notes
    -----
    ``g(x) = 0`` for ``|x| <= b``; beyond the wall ``g`` (and ``f``) are ``+inf``.
    """

    name: ClassVar[str] = "flat_punch"
    params: ClassVar[tuple[Param, ...]] = (
        Param("radius", "b", "m", "positive", "punch radius", (1e-6, 1e-1), LENGTH_BOUNDS),
    )

    def __init__(self, radius: float) -> None:
        self.radius = self.params[0].check(radius)

    @property
    def wall_radius(self) -> float:
        return self.radius

    @property
    def flat_radius(self) -> float:
        return self.radius

    def _length_scale(self) -> float:
        return self.radius

    def _height(self, r: np.ndarray) -> np.ndarray:
        return np.where(r <= self.radius, 0.0, np.inf)

    def _slope(self, r: np.ndarray) -> np.ndarray:
        return np.where(r <= self.radius, 0.0, np.inf)

    def _g_closed_form(self, x: np.ndarray) -> np.ndarray:
        return np.where(x <= self.radius, 0.0, np.inf)

    def _g_integral_closed_form(self, a: np.ndarray) -> np.ndarray:
        return np.where(a <= self.radius, 0.0, np.inf)

    def _g_squared_integral_closed_form(self, a: np.ndarray) -> np.ndarray:
        return self._g_integral_closed_form(a)

    def _pressure_shape_closed_form(self, r: np.ndarray, a: np.ndarray) -> np.ndarray:
        return np.zeros(np.broadcast(r, a).shape)

    def _abel_g_closed_form(self, r: np.ndarray, a: np.ndarray) -> np.ndarray:
        return np.zeros(np.broadcast(r, a).shape)

    def available_strategies(self) -> tuple[str, ...]:
        return ("closed_form",)

    def _sympy_form(self) -> SympyForm:
        import sympy as sp
        b = symbol("b")
        return SympyForm(values={b: self.radius}, wall_radius=b,
                         height=lambda r: sp.Piecewise((0, r <= b), (sp.oo, True)),
                         reason="the contact radius of a flat punch is its radius b at every depth")


class _FlatCentred(Profile):
    """Shared features of a flat centre of radius ``radius`` with a rising edge beyond it: g = 0
    inside, a slope jump (quadrature breakpoint) at the edge."""

    radius: float

    @property
    def flat_radius(self) -> float:
        return self.radius

    @property
    def breakpoints(self) -> tuple[float, ...]:
        return (self.radius,)

    def _length_scale(self) -> float:
        return self.radius


class TruncatedParaboloid(_FlatCentred):
    """Flat punch of radius ``radius`` with a parabolic rounded edge of radius ``R``.

    ``f = 0`` for ``r < b`` and ``(r² - b²)/(2R)`` beyond.

    Parameters
    ----------
    radius : float
        Radius ``b`` of the flat part, m (> 0).
    R : float
        Radius of curvature of the rounded edge, m (> 0).
    """

    name: ClassVar[str] = "truncated_paraboloid"
    params: ClassVar[tuple[Param, ...]] = (
        Param("radius", "b", "m", "positive", "flat radius b", (1e-6, 1e-1), LENGTH_BOUNDS),
        Param("R", "R", "m", "positive", "edge rounding radius R", (1e-6, 1.0), LENGTH_BOUNDS),
    )

    def __init__(self, radius: float, R: float) -> None:
        self.radius = self.params[0].check(radius)
        self.R = self.params[1].check(R)

    def _height(self, r: np.ndarray) -> np.ndarray:
        b = self.radius
        return np.where(r > b, (r - b) * (r + b) / (2 * self.R), 0.0)

    def _slope(self, r: np.ndarray) -> np.ndarray:
        return np.where(r > self.radius, r / self.R, 0.0)

    def _g_closed_form(self, x: np.ndarray) -> np.ndarray:
        b = self.radius
        return np.where(x > b, x * np.sqrt(np.maximum((x - b) * (x + b), 0.0)) / self.R, 0.0)

    def _g_integral_closed_form(self, a: np.ndarray) -> np.ndarray:
        b = self.radius
        return np.where(a > b, np.maximum((a - b) * (a + b), 0.0) ** 1.5 / (3 * self.R), 0.0)

    def _pressure_shape_semi_analytic(self, r: np.ndarray, a: np.ndarray, rtol: float
                                      ) -> tuple[np.ndarray, np.ndarray]:
        """``S(r, a) = ∫_r^a g'(x)/sqrt(x² - r²) dx`` (1/m) and its error, in rim coordinates.

        With ``s = sqrt(x² - b²)``, ``dg = (b² + 2s²)/(R sqrt(b² + s²)) ds`` and
        ``x² - r² = s² - s_r²`` (``s_r² = (r - b)(r + b)``, of either sign), so
        ``S = (1/R) ∫ (b² + 2s²)/sqrt(b² + s²) dv`` with ``s = s_r cosh v`` outside the flat
        part (``v`` up to ``arccosh(s_a/s_r)``) and ``s = β sinh v``, ``β² = b² - r²``, over it
        (``v`` up to ``asinh(s_a/β)``): a smooth, bounded integrand. In ``x`` the integrand is
        singular at the rim ``b`` and, next to it, every node's ``x - b`` carries the rounding
        of ``x``: the quadrature failed for most radii in a thin annulus outside the rim.
        ``inf`` at ``r = b`` (the pressure's logarithmic rim singularity), 0 for ``r >= a``.
        """
        from ..numeric.quadrature import tanh_sinh
        b, R = self.radius, self.R
        r, a = np.broadcast_arrays(np.asarray(r, float), np.asarray(a, float))
        shape = r.shape
        r, a = r.ravel(), a.ravel()
        out = np.zeros(r.shape)
        err = np.zeros(r.shape)
        s_a = np.sqrt(np.maximum((a - b) * (a + b), 0.0))
        q = (r - b) * (r + b)                       # s_r² (> 0 outside the flat part)
        todo = (r < a) & (s_a > 0)
        rim = todo & (q == 0)
        out[rim] = np.inf
        idx = np.flatnonzero(todo & (q != 0))
        if idx.size:
            out_side = q[idx] > 0
            scale = np.sqrt(np.abs(q[idx]))         # s_r or β
            ratio = s_a[idx] / scale
            V = np.where(out_side, np.arccosh(np.maximum(ratio, 1.0)), np.arcsinh(ratio))

            def integrand(v: np.ndarray, k: np.ndarray) -> np.ndarray:
                sc = scale[k][:, None]
                s = np.where(out_side[k][:, None], sc * np.cosh(v), sc * np.sinh(v))
                return (b * b + 2.0 * s * s) / np.sqrt(b * b + s * s)

            # S ~ g(a)/a: the absolute floor of each integral
            mag = (b * b + 2.0 * s_a[idx] ** 2) / np.sqrt(b * b + s_a[idx] ** 2)
            res = tanh_sinh(integrand, np.zeros(idx.size), V, rtol=rtol,
                            atol=rtol * mag * 1e-3 + 1e-300)
            out[idx] = res.value / R
            err[idx] = res.error / R
        return out.reshape(shape), err.reshape(shape)

    def _xg_integral_closed_form(self, a: np.ndarray) -> np.ndarray:
        """``∫_0^a x g(x) dx = ∫_0^S s² sqrt(b² + s²) ds / R`` (m³), ``S = sqrt(a² - b²)``.

        The antiderivative ``[S(2S² + b²) a - b⁴ asinh(S/b)]/(8R)`` cancels as ``S → 0`` (its
        leading term is ``b S³/(3R)``): below ``S = b/2`` the binomial series
        ``(b S³/R) Σ_k C(1/2, k) (S/b)^(2k)/(2k + 3)`` is summed instead (40 terms: < 1e-17).
        A quadrature of ``x g(x)`` next to the rim, where ``x - b`` carries the rounding of
        ``x``, could not converge there.
        """
        b, R = self.radius, self.R
        a = np.asarray(a, dtype=float)
        S = np.sqrt(np.maximum((a - b) * (a + b), 0.0))
        out = np.zeros(np.shape(S))
        big = S >= 0.5 * b
        if np.any(big):
            Sb, ab = S[big], np.maximum(a, b)[big] if a.ndim else np.maximum(a, b)
            out[big] = (Sb * (2.0 * Sb * Sb + b * b) * ab - b**4 * np.arcsinh(Sb / b)) / (8.0 * R)
        small = (S > 0) & ~big
        if np.any(small):
            Ss = S[small]
            u = (Ss / b) ** 2
            coef, tot, uk = 1.0, np.zeros(Ss.shape), np.ones(Ss.shape)
            for k in range(40):
                tot += coef * uk / (2 * k + 3)
                coef *= (0.5 - k) / (k + 1)
                uk = uk * u
            out[small] = b * Ss**3 * tot / R
        return out

    def _g_inverse_closed_form(self, d: np.ndarray) -> np.ndarray:
        b = self.radius
        bb = b * b          # hypot: no overflow of b⁴ or d² (plain floats raise on ** overflow)
        return np.sqrt(0.5 * (bb + np.hypot(bb, 2.0 * self.R * d)))

    def _sympy_form(self) -> SympyForm:
        import sympy as sp
        b, R = symbol("b"), symbol("R")

        def xg_integral(a):
            root = sp.sqrt(a**2 - b**2)
            return (a * (2 * a**2 - b**2) * root / 8 - b**4 / 8 * sp.acosh(a / b)) / R
        return SympyForm(
            values={b: self.radius, R: self.R}, flat_radius=b,
            height=lambda r: (r**2 - b**2) / (2 * R),
            height_piecewise=lambda r: sp.Max(r**2 - b**2, 0) / (2 * R),
            g=lambda x: x * sp.sqrt(x**2 - b**2) / R,
            g_piecewise=lambda x: x * sp.sqrt(sp.Max(x**2 - b**2, 0)) / R,
            g_integral=lambda a: (a**2 - b**2) ** sp.Rational(3, 2) / (3 * R),
            xg_integral=xg_integral,
            radius_of_depth=lambda d: sp.sqrt((b**2 + sp.sqrt(b**4 + 4 * R**2 * d**2)) / 2),
            reason="the pressure of a truncated paraboloid has no closed form here "
                   "(elliptic integrals; theory §3: quadrature)")

    def _scalar_closed_forms(self) -> dict:
        """Plain-float ``g``, ``∫g`` and ``g'`` for the scalar normal solve (same formulas)."""
        b, R = self.radius, self.R

        def g(x: float) -> float:
            return x * math.sqrt(max((x - b) * (x + b), 0.0)) / R if x > b else 0.0

        def g_integral(a: float) -> float:
            return max((a - b) * (a + b), 0.0) ** 1.5 / (3 * R) if a > b else 0.0

        def g_prime(x: float) -> float:     # (2x² - b²)/(R sqrt(x² - b²)), inf at the rim
            q = (x - b) * (x + b)
            return (2 * x * x - b * b) / (R * math.sqrt(q)) if q > 0 else math.inf

        def radius_depth(fr: float) -> tuple[float, float]:
            s = math.sqrt(2.0) * b * math.sinh(math.asinh(1.5 * math.sqrt(2.0) * R * fr
                                                          / (b * b * b)) / 3.0)
            a = math.hypot(b, s)
            return a, a * s / R

        return {"g": g, "g_integral": g_integral, "g_prime": g_prime,
                "radius_depth_of_reduced_force": radius_depth}

    @property
    def capabilities(self) -> frozenset[str]:
        return frozenset({"reduced_force_state", "semi_analytic_pressure_shape"})

    def _radius_depth_of_reduced_force(self, fr: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Contact radius and depth (m) of reduced forces ``F/(2E*) > 0`` (m²) in closed form.

        With ``s = sqrt(a² - b²)``: ``F/(2E*) = a g(a) - ∫_0^a g = (b² s + (2/3) s³)/R``, a
        cubic in ``s`` with one real root, ``s = √2 b sinh(asinh(3√2 R F/(4E* b³))/3)``
        (no cancellation for small forces); then ``a = hypot(b, s)`` and ``d = a s/R``. Next to
        the rim the radius rounds onto ``b`` while ``s`` (and the depth) keep every digit:
        a root solve in ``a`` lost them and reported the state as an overflow.
        """
        b, R = self.radius, self.R
        fr = np.asarray(fr, dtype=float)
        s = math.sqrt(2.0) * b * np.sinh(np.arcsinh(1.5 * math.sqrt(2.0) * R * fr / (b * b * b))
                                         / 3.0)
        a = np.hypot(b, s)
        return a, a * s / R


class TruncatedCone(_FlatCentred):
    """Flat punch of radius ``radius`` with a conical edge of slope ``slope``.

    ``f = 0`` for ``r < b`` and ``slope (r - b)`` beyond.

    Parameters
    ----------
    radius : float
        Radius ``b`` of the flat part, m (> 0).
    slope : float
        Slope of the conical edge (dimensionless, > 0).
    """

    name: ClassVar[str] = "truncated_cone"
    params: ClassVar[tuple[Param, ...]] = (
        Param("radius", "b", "m", "positive", "flat radius b", (1e-6, 1e-1), LENGTH_BOUNDS),
        Param("slope", "s", "1", "positive", "edge slope", (1e-4, 1e2)),
    )

    def __init__(self, radius: float, slope: float) -> None:
        self.radius = self.params[0].check(radius)
        self.slope = self.params[1].check(slope)

    def _height(self, r: np.ndarray) -> np.ndarray:
        return np.where(r > self.radius, self.slope * (r - self.radius), 0.0)

    def _slope(self, r: np.ndarray) -> np.ndarray:
        return np.where(r > self.radius, self.slope, 0.0)

    def _g_closed_form(self, x: np.ndarray) -> np.ndarray:
        b = self.radius
        root = np.sqrt(np.maximum((x - b) * (x + b), 0.0))
        return np.where(x > b, self.slope * x * np.arctan2(root, b), 0.0)  # arccos(b/x), accurate near b

    def _g_integral_closed_form(self, a: np.ndarray) -> np.ndarray:
        b = self.radius
        root = np.sqrt(np.maximum((a - b) * (a + b), 0.0))
        val = self.slope * (0.5 * a**2 * np.arctan2(root, b) - 0.5 * b * root)
        return np.where(a > b, val, 0.0)

    def _radius_depth_of_reduced_force(self, fr: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Contact radius and depth (m) of reduced forces ``F/(2E*) >= 0`` (m²).

        With ``t = tan θ``, ``θ = arccos(b/a)``: ``a = b sqrt(1 + t²)``, ``d = g(a) = s a θ`` and
        ``F/(2E*) = a g(a) - ∫_0^a g = (s b²/2) [θ (1 + t²) + t]``, increasing and convex in
        ``t`` (derivative ``s b² (1 + t θ)``). Newton from ``t0 = min(q, sqrt(8q/π))``
        (``q = F/(2E* s b²)``, an upper bound of the root) descends monotonically onto the root
        and stops when a step no longer descends. For small forces ``t ≈ q`` and
        ``d ≈ F/(2E* b)`` (the flat punch): the radius rounds onto the rim ``b`` while ``t``
        and the depth keep every digit. A root solve in ``a`` lost them (a depth of 0 below
        1e-10 N on the scalar route, an overflow report on the array route).
        """
        b, s = self.radius, self.slope
        q = np.asarray(fr, dtype=float) / (s * b) / b
        t = _cone_rim_tangent(q)
        a = b * np.hypot(1.0, t)
        return a, s * a * np.arctan(t)

    def _scalar_closed_forms(self) -> dict:
        """The scalar normal solve's radius and depth of a reduced force: the array formula on a
        one-element array (the same operations, the same bits as the array route)."""
        def radius_depth(fr: float) -> tuple[float, float]:
            a, d = self._radius_depth_of_reduced_force(np.array([fr]))
            return float(a[0]), float(d[0])

        return {"radius_depth_of_reduced_force": radius_depth}

    @property
    def capabilities(self) -> frozenset[str]:
        return frozenset({"reduced_force_state"})

    def _sympy_form(self) -> SympyForm:
        import sympy as sp
        b, s = symbol("b"), symbol("s")

        def xg_integral(a):
            return s * (a**3 / 3 * sp.acos(b / a)
                        - b / 6 * (a * sp.sqrt(a**2 - b**2) + b**2 * sp.acosh(a / b)))
        return SympyForm(
            values={b: self.radius, s: self.slope}, flat_radius=b,
            height=lambda r: s * (r - b),
            height_piecewise=lambda r: s * sp.Max(r - b, 0),
            g=lambda x: s * x * sp.acos(b / x),
            g_piecewise=lambda x: s * x * sp.acos(sp.Min(b / x, 1)),
            g_integral=lambda a: s * (a**2 / 2 * sp.acos(b / a) - b / 2 * sp.sqrt(a**2 - b**2)),
            xg_integral=xg_integral,
            reason="a truncated cone has no closed-form inverse of d = s a arccos(b/a) and no "
                   "closed-form pressure (theory §3: quadrature)")


def _cone_rim_tangent(q: np.ndarray) -> np.ndarray:
    """The root ``t >= 0`` of ``[arctan(t) (1 + t²) + t]/2 = q`` for every ``q >= 0`` (see
    :meth:`TruncatedCone._radius_depth_of_reduced_force`): Newton from an upper bound, every
    element stopped at its first step that does not descend (convexity makes the iterates
    decrease onto the root; the stop is rounding, never a tolerance)."""
    q = np.asarray(q, dtype=float)
    flat_q = q.reshape(-1)
    out = np.minimum(flat_q, np.sqrt(flat_q * (8.0 / math.pi)))
    todo = np.flatnonzero(flat_q > 0)
    tt, qq = out[todo], flat_q[todo]
    for _ in range(200):          # quadratic convergence: < 10 steps from the bound
        if not tt.size:
            break
        at = np.arctan(tt)
        new = tt - (0.5 * (at * (1.0 + tt * tt) + tt) - qq) / (1.0 + tt * at)
        keep = new < tt
        out[todo[~keep]] = tt[~keep]
        todo, tt, qq = todo[keep], new[keep], qq[keep]
    out[todo] = tt
    return out.reshape(q.shape)
