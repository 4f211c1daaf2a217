"""Exact spherical cap ``f(r) = R - sqrt(R² - r²)``.

``g(x) = x artanh(x/R)`` and ``∫_0^a g = (a²-R²)/2 artanh(a/R) + R a/2``. The contact radius must
stay below R (``g → ∞`` as ``a → R``); half-space theory needs ``a ≪ R``: beyond
``a = VALIDITY_RATIO R`` (the surface slope at the edge exceeds tan 30° = 0.58) results carry a
:class:`~contactlab.errors.ValidityWarning`.
"""
from __future__ import annotations

import math
from typing import Any, ClassVar

import numpy as np

from ..errors import ConvergenceError, OutsideTheoryError
from ..numeric import normal_kernels as _kernels
from ..numeric.roots import convex_newton_fused
from ..params import LENGTH_BOUNDS, Param
from ..symbolic.form import SympyForm, symbol
from .base import Profile, root_rtol

__all__ = ["Sphere", "VALIDITY_RATIO"]

#: rounding level of a Newton residual relative to the size of its terms
_NOISE = 8 * float(np.finfo(float).eps)
#: series coefficients of h(q)/(R² q³) in q², 2m/((2m-1)(2m+1)), m = 1..9 (q < 0.1: the tenth
#: term is below 1e-18 of the first), shared with the compiled Newton round
_H_SERIES = _kernels.SPHERE_SERIES
#: the series inverting the Hertz radius ``q_H = cbrt(3η/2)`` of the reduced force into the
#: contact radius, ``q = q_H Σ_k b_k q_H^(2k)`` (series reversion of ``q_H³ = (3/2) η(q)``,
#: exact rationals), the force solve's start below ``q_H = _DEEP_START``
_START_SERIES = (1.0, -2 / 15, -23 / 1575, -8 / 14175, 139 / 202125, 811016 / 2280403125,
                 103292159 / 1005657778125)
#: Hertz radius ``q_H`` above which the force solve starts from the tanh bound instead (the
#: series start errs by 7e-4 at q_H = 1.28, q = 0.96, and diverges towards q = 1)
_DEEP_START = 1.25
#: Newton rounds of the force solve before it gives up (ConvergenceError)
_MAXITER = 200


def _reduced_force(q: np.ndarray, at: np.ndarray | None = None) -> np.ndarray:
    """``h(q)/R² = [(q² + 1) artanh q - q]/2`` (series in ``q²`` below ``q = 0.1``)."""
    if at is None:
        at = np.arctanh(q)
    out = 0.5 * ((q * q + 1) * at - q)
    small = q < 0.1
    if np.any(small):
        out[small] = _series_of_small(q[small])
    return out


def _slope_into(q: np.ndarray, at: np.ndarray, out: np.ndarray, scratch: np.ndarray) -> None:
    """``out = artanh q + q/((1 - q)(1 + q))``, the derivative of ``q artanh q``, from
    ``at = artanh q`` (both Newton rounds below use it; ``scratch`` is overwritten)."""
    np.subtract(1.0, q, out=out)
    np.add(1.0, q, out=scratch)
    np.multiply(out, scratch, out=out)
    np.divide(q, out, out=out)
    np.add(out, at, out=out)


def _series_of_small(qs: np.ndarray) -> np.ndarray:
    """The series of :func:`_reduced_force` at ``qs < 0.1`` (Horner in ``q²``)."""
    x = qs * qs
    # (the first product c9·x written at once, not into a filled array: the same bits)
    acc = np.multiply(x, _H_SERIES[-1])
    for c in _H_SERIES[-2:0:-1]:
        acc += c
        acc *= x
    acc += _H_SERIES[0]
    x *= qs
    acc *= x
    return acc

def _series_tail_vanishes(q_top: float, k: int) -> bool:
    """Whether the terms ``k, k+1, ...`` of the ``∫g`` series
    ``Σ q^(2k+1)/((2k-1)(2k+1))`` (positive, each below ``q²`` times the one before) leave the
    partial sum unchanged for every ``q <= q_top``: a positive addend below half an ulp of the
    sum rounds away, and the sum, at least its first term ``q³/3``, has an ulp above
    ``2^-53`` of itself. The ratio of term ``k`` to the first, ``3 q^(2k-2)/((2k-1)(2k+1))``,
    grows with ``q``, so ``q_top`` bounds it for the whole batch; ``2^-55`` (half of what is
    needed) covers the rounding of the terms. Skipping those terms gives the same bits as
    adding them: just below q = 0.1, 8 terms of 17 are evaluated."""
    return 3.0 * q_top ** (2 * k - 2) / ((2 * k - 1) * (2 * k + 1)) < 2.0 ** -55


#: a/R above which a sphere contact leaves the half-space theory (ValidityWarning): the theory
#: linearises the boundary conditions in the surface slope, here a/sqrt(R²-a²) = 0.58 (30°) at
#: the edge; the exact-sphere MDR solution stays exact for the half-space problem but no longer
#: describes a real sphere (large strains, the load no longer normal to the surface)
VALIDITY_RATIO = 0.5


class Sphere(Profile):
    """Exact sphere of radius ``R`` (not the parabolic approximation).

    Parameters
    ----------
    R : float
        Sphere radius, m (> 0). Contact radii must satisfy ``a < R``; above
        ``a = VALIDITY_RATIO R = R/2`` the half-space theory is outside its range and states
        carry a :class:`~contactlab.errors.ValidityWarning`.

    Raises
    ------
    OutsideTheoryError
        When a radius ``>= R`` is evaluated or a depth needs ``a >= R``.
    """

    name: ClassVar[str] = "sphere"
    params: ClassVar[tuple[Param, ...]] = (
        Param("R", "R", "m", "positive", "sphere radius R", (1e-6, 1.0), LENGTH_BOUNDS),
    )

    def __init__(self, R: float) -> None:
        self.R = self.params[0].check(R)

    @property
    def max_radius(self) -> float:
        return self.R

    @property
    def validity_radius(self) -> float:
        return VALIDITY_RATIO * self.R

    def _length_scale(self) -> float:
        return self.R

    def _guard(self, r: np.ndarray, name: str) -> None:
        # (by the largest radius: one reduction and no boolean temporary; a NaN passes, as
        # it did the comparison)
        if np.size(r) and np.max(r) >= self.R:
            raise OutsideTheoryError(
                f"{name}={float(np.max(r))!r} m is invalid for Sphere(R={self.R!r}): radii must stay "
                "below the sphere radius R.")

    def _height(self, r: np.ndarray) -> np.ndarray:
        self._guard(r, "r")
        # R - sqrt(R²-r²) without cancellation
        return r**2 / (self.R + np.sqrt((self.R - r) * (self.R + r)))

    def _slope(self, r: np.ndarray) -> np.ndarray:
        self._guard(r, "r")
        return r / np.sqrt((self.R - r) * (self.R + r))

    def _g_closed_form(self, x: np.ndarray) -> np.ndarray:
        self._guard(x, "x")
        # x artanh(x/R), in one new array
        out = np.divide(x, self.R)
        if not isinstance(out, np.ndarray):
            return x * np.arctanh(out)
        np.arctanh(out, out=out)
        out *= x
        return out

    def _g_integral_closed_form(self, a: np.ndarray) -> np.ndarray:
        self._guard(a, "a")
        R = self.R
        # (a²-R²)/2·artanh(a/R) + R a/2 cancels for a ≪ R: use its series below a/R = 0.1
        a = np.asarray(a, dtype=float)
        shape = a.shape
        a = a.reshape(-1)
        q = a / R
        small = q < 0.1
        any_small = bool(small.any())
        qs = q[small] if any_small else None
        if any_small and bool(small.all()):
            out = np.empty_like(a)
        else:
            # the closed form on the whole array in place (the series replaces it below 0.1):
            # 0.5 (a² - R²) artanh(a/R) + (0.5 R) a
            at = np.arctanh(q, out=q)
            out = np.multiply(a, a)
            out -= R**2
            out *= 0.5
            out *= at
            np.multiply(0.5 * R, a, out=at)
            out += at
        if qs is not None:
            # series: R² Σ_{k>=1} q^(2k+1) / ((2k-1)(2k+1))
            ser = np.zeros_like(qs)
            term = qs**3
            part = np.empty_like(qs)
            q_top = float(qs.max())
            for k in range(1, 18):
                if k > 1:
                    if _series_tail_vanishes(q_top, k):
                        break       # (the remaining terms leave every sum's bits unchanged)
                    term *= qs
                    term *= qs
                np.divide(term, (2 * k - 1) * (2 * k + 1), out=part)
                ser += part
            ser *= R**2
            out[small] = ser
        # (1-D input: out itself, an array of the caller's own, not a view of it)
        return out if out.shape == shape else out.reshape(shape)

    def _sympy_form(self) -> SympyForm:
        import sympy as sp
        from sympy.codegen.cfunctions import log1p   # accurate for a << R (numpy.log1p)
        R = symbol("R")

        def xg_integral(a):
            return (a**3 / 3 * sp.atanh(a / R) + R * a**2 / 6
                    + R**3 / 6 * log1p(-a**2 / R**2))
        return SympyForm(values={R: self.R}, height=lambda r: R - sp.sqrt(R**2 - r**2),
                         g=lambda x: x * sp.atanh(x / R),
                         g_integral=lambda a: (a**2 - R**2) / 2 * sp.atanh(a / R) + R * a / 2,
                         xg_integral=xg_integral,
                         reason="the exact sphere has no closed-form inverse of d = a artanh(a/R) "
                                "and no closed-form pressure (theory §3: quadrature)")

    @property
    def capabilities(self) -> frozenset[str]:
        return frozenset({"reduced_force_solver"})

    def _solve_radius(self, d: np.ndarray, limit: float, rtol: float | None = None) -> np.ndarray:
        """Contact radii of depths ``d > 0``: Newton on ``q artanh q = d/R`` (``q = a/R``) from
        the Hertz radius ``sqrt(R d)`` (or, for deep contacts, ``tanh(δ/tanh δ)``), both above
        the root of this increasing convex function (``artanh q >= q``), so the steps fall onto
        it without a bracket (:func:`~contactlab.numeric.roots.convex_newton_fused`)."""
        rtol = self.rtol if rtol is None else rtol
        R = self.R
        shape = np.shape(d)
        d = np.asarray(d, dtype=float).reshape(-1)      # (1-D: the buffers below are arrays)
        delta = d / R
        q_cap = limit * (1 - 1e-15) / R
        # start: q² = δ - δ²/3 + δ³/45 + O(δ⁴) inverts δ = q artanh q = q² + q⁴/3 + q⁶/5 + ...
        # (relative error ~δ³ of q: one or two steps below δ = 0.01); if it falls below the root,
        # the first step lands above it (convexity) and the steps then fall onto it
        ds = np.minimum(delta, 0.25)        # (the series is used below 0.25 only)
        # q0 = sqrt(δ (1 - ds (1/3 - ds/45))), in two buffers
        q0 = np.divide(ds, 45.0)
        np.subtract(1.0 / 3.0, q0, out=q0)
        q0 *= ds
        np.subtract(1.0, q0, out=q0)
        np.multiply(delta, q0, out=q0)
        np.sqrt(q0, out=q0)
        del ds
        if delta.size and np.max(delta) > 0.25:
            deep = delta > 0.25         # Hertz / the tanh bound there, both above the root
            dd = delta[deep]
            q0[deep] = np.minimum(np.sqrt(dd), np.tanh(dd / np.tanh(dd)))
        self._refuse_beyond(q0, q_cap, lambda q: q * np.arctanh(q), delta, d, "depth", "m",
                            "depth/force")
        np.minimum(q0, q_cap, out=q0)

        flat = delta.ravel()
        # residual q artanh q - δ, its derivative artanh q + q/((1-q)(1+q)) and rounding level
        # _NOISE·δ, written into buffers of the whole batch (convex_newton_fused)
        at, res, w = (np.empty(flat.shape) for _ in range(3))
        noise = _NOISE * flat

        def step_of(q: np.ndarray, step: np.ndarray, quiet: np.ndarray) -> None:
            np.arctanh(q, out=at)
            np.multiply(q, at, out=res)
            np.subtract(res, flat, out=res)
            np.abs(res, out=w)
            np.less_equal(w, noise, out=quiet)
            _slope_into(q, at, w, step)
            np.divide(res, w, out=step)

        q = convex_newton_fused(step_of, q0, rtol=root_rtol(rtol), what="contact radius",
                                overwrite=True)
        q *= R
        return q.reshape(shape)

    def _radius_of_reduced_force(self, target: np.ndarray, rtol: float) -> np.ndarray | None:
        """Contact radii of reduced forces ``F/(2E*) > 0``: Newton on
        ``h(q) = a g(a) - ∫_0^a g = R² [(q² + 1) artanh q - q]/2`` (``q = a/R``; below
        ``q = 0.1``, where that form cancels, its series ``R² Σ 2m q^(2m+1)/((2m-1)(2m+1))``)
        from the inverted series of the Hertz radius (within 1e-6 of the root up to
        ``q = 0.85``: a start below the root steps above it, this increasing function being
        convex, ``h'' = g' + a g'' > 0``) or, deeper, from the Hertz radius or the tanh bound,
        both above the root."""
        R = self.R
        shape = np.shape(target)
        eta = np.asarray(target, dtype=float).reshape(-1) / (R * R)
        q_cap = self.max_radius * (1 - 1e-15) / R
        # start: η = (2/3) q³ (1 + 2q²/5 + 9q⁴/35 + ...) gives the Hertz radius
        # q_H = cbrt(3η/2) = q (1 + 2q²/15 + ...); its series inverted, q = q_H P(q_H²)
        # (_START_SERIES), is within 2.4e-10 of the root up to q = 0.45, 1e-6 up to 0.85 and
        # above the root from there to q_H = _DEEP_START (q = 0.95): Newton then stops after
        # two or three rounds on most batches instead of four or more
        qh = np.multiply(1.5, eta)
        np.cbrt(qh, out=qh)
        # q0 = q_H P(q_H²), Horner in q_H² in two more buffers
        qh2 = np.multiply(qh, qh)
        q0 = np.multiply(qh2, _START_SERIES[-1])
        for c in _START_SERIES[-2:0:-1]:
            q0 += c
            q0 *= qh2
        q0 += 1.0
        q0 *= qh
        if qh.size and np.max(qh) > _DEEP_START:
            deep = qh > _DEEP_START     # Hertz / the tanh bound there, both above the root
            ed = eta[deep]
            ql = np.tanh(ed)
            q0[deep] = np.minimum(qh[deep], np.tanh((2 * ed + 1) / (ql * ql + 1)))
        if q0.size and np.max(q0) >= q_cap:     # (one reduction; the mask only when needed)
            over = q0 >= q_cap
            if np.any(_reduced_force(np.full(int(np.count_nonzero(over)), q_cap)) < eta[over]):
                return None     # a radius beyond R: declined, the bracketed solve names the force
        np.minimum(q0, q_cap, out=q0)
        del qh

        flat = eta.ravel()
        if flat.size >= _kernels.FUSED_FROM and _kernels.backend() == "numba":
            # the same rounds compiled (numeric.normal_kernels: bit-identical)
            # (qh2's buffer, free now, takes artanh q)
            stuck = _kernels.sphere_force_newton(q0, flat, _NOISE, root_rtol(rtol), _MAXITER,
                                                 work=qh2)
            if stuck is not None:
                raise ConvergenceError(f"contact radius: Newton's method did not converge in "
                                       f"{_MAXITER} steps (at {stuck!r}).")
            q0 *= R
            return q0.reshape(shape)
        del qh2
        at, p, h, w = (np.empty(flat.shape) for _ in range(4))
        small = np.empty(flat.shape, dtype=bool)

        def step_of(q: np.ndarray, step: np.ndarray, quiet: np.ndarray) -> None:
            # the operations of _reduced_force(q) - η, of its derivative
            # q (artanh q + q/((1-q)(1+q))) and of the rounding level of the residual (of the
            # series (~η) below q = 0.1, of the cancelling terms (~q) above), into buffers
            np.arctanh(q, out=at)
            np.multiply(q, q, out=p)
            np.add(p, 1, out=p)
            np.multiply(p, at, out=p)                                 # (q² + 1) artanh q
            np.subtract(p, q, out=h)
            np.multiply(h, 0.5, out=h)
            np.less(q, 0.1, out=small)
            if small.any():
                h[small] = _series_of_small(q[small])
            np.subtract(h, flat, out=h)                               # the residual
            np.add(p, q, out=w)
            np.multiply(w, 0.5, out=w)
            np.copyto(w, flat, where=small)
            np.multiply(w, _NOISE, out=w)
            np.abs(h, out=p)
            np.less_equal(p, w, out=quiet)
            _slope_into(q, at, w, step)
            np.multiply(w, q, out=w)
            np.divide(h, w, out=step)

        q = convex_newton_fused(step_of, q0, rtol=root_rtol(rtol), what="contact radius",
                                overwrite=True, maxiter=_MAXITER)
        q *= R
        return q.reshape(shape)

    def _refuse_beyond(self, q0: np.ndarray, q_cap: float, phi: Any, goal: np.ndarray,
                       value: np.ndarray, what: str, unit: str, fix: str) -> None:
        """OutsideTheoryError where a root of ``phi(q) = goal`` lies beyond ``q_cap``
        (``phi(q_cap) < goal``): the same refusal as the bracketed solve's."""
        over = q0 >= q_cap
        if np.any(over):
            short = phi(np.full(int(np.count_nonzero(over)), q_cap)) < goal[over]
            if np.any(short):
                v = float(np.asarray(value)[over][np.argmax(short)])
                raise OutsideTheoryError(
                    f"{what}={v!r} {unit} needs a contact radius >= max_radius="
                    f"{self.max_radius!r} m of {self!r}; reduce the {fix}.")

    def _g_prime_closed_form(self, x: np.ndarray) -> np.ndarray:
        self._guard(x, "x")
        return np.arctanh(x / self.R) + x * self.R / ((self.R - x) * (self.R + x))

    def _scalar_closed_forms(self) -> dict:
        """Plain-float ``g``, ``∫g`` and ``g'`` for the scalar normal solve (same formulas)."""
        R = self.R

        def g(x: float) -> float:
            if x >= R:
                self._guard(np.array(x), "x")
            return x * math.atanh(x / R)

        def g_integral(a: float) -> float:
            if a >= R:
                self._guard(np.array(a), "a")
            q = a / R
            if q >= 0.1:
                return 0.5 * (a**2 - R**2) * math.atanh(q) + 0.5 * R * a
            ser, term = 0.0, q
            for k in range(1, 18):
                term = term * q * q if k > 1 else q**3
                ser += term / ((2 * k - 1) * (2 * k + 1))
            return R**2 * ser

        def g_prime(x: float) -> float:
            return math.atanh(x / R) + x * R / ((R - x) * (R + x))

        return {"g": g, "g_integral": g_integral, "g_prime": g_prime}
