"""The abstract :class:`Profile`: an axisymmetric gap f(r) and its MDR transform g(x).

To implement a subclass
-----------------------
1. Declare ``name: ClassVar[str]`` (registry key, lowercase snake) and
   ``params: ClassVar[tuple[Param, ...]]``; store each parameter as an attribute of that name.
2. Implement at least one of ``_height(r)``, ``_g_closed_form(x)`` or ``power_terms()``.
   ``_height`` alone is enough: slope (by finite differences unless ``_slope`` is given),
   the transform, its integral, pressure, displacement and torsion then come by quadrature.
3. Optional, for speed and exactness: ``_slope(r)``, ``_g_closed_form(x)``,
   ``_g_integral_closed_form(a)`` (∫_0^a g dx), ``_g_inverse_closed_form(d)``,
   ``_pressure_shape_closed_form(r, a)`` (∫_r^a g'(x)/sqrt(x²-r²) dx),
   ``_abel_g_closed_form(r, a)`` ((2/π)∫_0^min(r,a) g(x)/sqrt(r²-x²) dx).
4. Optional, for ``formulas()``: the sympy shorthands ``_height_sympy(r, **symbols)``,
   ``_g_sympy(x, **symbols)``, ``_g_integral_sympy(a, **symbols)``, or the whole form by
   overriding ``_sympy_form()`` (as the built-ins do); see :meth:`Profile._sympy_form`.
5. Declare domain features when present: ``max_radius`` (largest admissible contact radius),
   ``flat_radius`` (g = 0 for |x| < it), ``wall_radius`` (the contact radius cannot exceed it, as
   for a flat punch), ``breakpoints`` (radii where f' jumps; quadratures split there).

Comes free: ``height``, ``derivative`` (f'), ``g`` (with ``strategy=``), ``g_integral``,
``radius_of_depth``, ``inverse_transform``, ``available_strategies``, ``formulas``, ``to_latex``,
``+`` and scalar ``*`` (giving :class:`~contactlab.profiles.compound.Sum`), ``repr``/``==``/``hash``.
"""
from __future__ import annotations

from abc import ABC
from typing import TYPE_CHECKING, Any, ClassVar

import numpy as np

from ..errors import (OutsideTheoryError, ParameterError, PluginError,
                      StrategyUnavailableError)
from ..numeric.quadrature import (DEFAULT_RTOL, LOOSE_RTOL, first_converged, min_level_for,
                                  tanh_sinh, tanh_sinh_upto)
from ..numeric.roots import bracketed_root, shrink_bracket
from ..numeric.normal_kernels import FORCE_SANITY
from ..params import Param, ParamIdentity, as_float_array
from ..symbolic.form import SympyForm, form_from_hooks
from .radius_bounds import first_step_from_f, upper_radius_from_f

if TYPE_CHECKING:
    from ..symbolic.formulas import FormulaSet

__all__ = ["Profile", "G_STRATEGIES", "CAPABILITIES", "ROUNDING", "root_rtol", "quadrature_root_rtol",
           "force_ftol"]


#: Capabilities a profile may declare (``Profile.capabilities``) and the hook each one promises.
CAPABILITIES = {
    "terms": "``terms``: the profile is a sum of profiles (the MDR is linear; each term takes its "
             "own route)",
    "linear_table": "``table_nodes()``: piecewise-linear table whose g has square-root cusps at "
                    "the returned nodes (m); ``table_slopes()`` the slope of each segment",
    "node_table": "``table_nodes()``: table whose g is analytic between the returned nodes (m) "
                  "(square-root cusps or weaker kinks at them, none elsewhere); "
                  "``table_g_first(t)``: g on the first segment ``[0, r_1]`` in closed form; "
                  "``table_g_slope(x)``: ``(g'(x), rounding estimate)`` between the nodes; "
                  "``table_axis_slope()``: ``f'(0+)``",
    "semi_analytic_pressure_shape": "``_pressure_shape_semi_analytic(r, a, rtol)`` -> (value, "
                                    "error) or None to decline",
    "semi_analytic_abel_g": "``_abel_g_semi_analytic(r, a, rtol)`` -> (value, error) or None",
    "reduced_force_solver": "``_radius_of_reduced_force(F/(2E*), rtol)`` -> contact radii or None "
                            "to decline",
    "reduced_force_state": "``_radius_depth_of_reduced_force(F/(2E*))`` -> (contact radii, "
                           "depths) in closed form, the depth not taken as g(radius) (a contact "
                           "radius that rounds onto a kink of g, as at a flat part's rim)",
}

#: Numerical routes to g(x), in order of preference.
G_STRATEGIES = ("closed_form", "symbolic", "quadrature")

_HOOKS = ("_height", "_g_closed_form", "power_terms")

#: relative error floor assumed for exact (closed-form, symbolic) routes: a few hundred ulps covers
#: the rounding of the closed forms, including the arcsine sums of tabulated profiles
ROUNDING = 256 * np.finfo(float).eps


def root_rtol(rtol: float) -> float:
    """Relative bracket width of the contact-radius solves for the numeric tolerance ``rtol``.

    ``1e-5 * rtol``, floored at 1e-15: 1e-15 at the default ``rtol = 1e-10`` (the bracket of the
    regula-falsi solver shrinks superlinearly, so the tight width costs a few iterations only; see
    ``docs/accuracy.md``), and never looser than ``rtol`` itself.
    """
    return max(1e-15, 1e-5 * rtol)


def quadrature_root_rtol(rtol: float) -> float:
    """:func:`root_rtol` of a depth's contact radius on the quadrature route: ``1e-3 * rtol`` at
    a loose ``rtol >= LOOSE_RTOL`` (each g there is a whole quadrature, and the force of a depth
    does not move to first order with the radius: ``dF/da = 2E*(d - g(a))`` vanishes at the
    root), :func:`root_rtol` otherwise (results at tighter tolerances unchanged). Not for a
    force's radius: the depth of a force moves with it (``g'(a) δa``).
    """
    return 1e-3 * rtol if rtol >= LOOSE_RTOL else root_rtol(rtol)


def force_ftol(rtol: float) -> float:
    """Relative residual ``|F(a) - F| <= force_ftol · F`` at which the contact radius of a
    force on the quadrature route stops at a loose ``rtol >= LOOSE_RTOL``: ``1e-3 * rtol`` as a
    depth's (:func:`quadrature_root_rtol`), but at most a tenth of
    :data:`~contactlab.numeric.normal_kernels.FORCE_SANITY` (the driver's check that a force
    state carries its request). The depth then errs by at most about that much
    (``δd/d = (n/(n+1)) δF/F`` for g ∝ a^n), and the residual is part of the state's force
    error estimate. 0 (no residual stop) at tighter tolerances: results there unchanged.
    """
    return min(1e-3 * rtol, 0.1 * FORCE_SANITY) if rtol >= LOOSE_RTOL else 0.0


class Profile(ParamIdentity, ABC):
    """Axisymmetric gap ``f(r)`` between two undeformed surfaces and its MDR transform.

    ``f(0) = 0``; ``f`` may be non-monotone (measured data) as long as its transform
    ``g(x) = |x| ∫_0^{|x|} f'(r)/sqrt(x²-r²) dr`` is non-decreasing over the contact: otherwise the
    contact is an annulus, outside the MDR, and :class:`~contactlab.errors.OutsideTheoryError` is
    raised at the depth where that happens.

    See the module docstring for how to implement a subclass.
    """

    name: ClassVar[str] = ""
    params: ClassVar[tuple[Param, ...]] = ()
    #: default relative tolerance of the numeric routes
    rtol: float = DEFAULT_RTOL

    if TYPE_CHECKING:
        # the optional hooks of the module docstring (items 2 and 3), declared for type checkers
        # only: at run time Profile has none of them, and _has() tells whether a subclass does
        def _height(self, r: np.ndarray) -> np.ndarray: ...
        def _slope(self, r: np.ndarray) -> np.ndarray: ...
        def _g_closed_form(self, x: np.ndarray) -> np.ndarray: ...
        def _g_integral_closed_form(self, a: np.ndarray) -> np.ndarray: ...
        def _g_inverse_closed_form(self, d: np.ndarray) -> np.ndarray: ...
        def _g_prime_closed_form(self, x: np.ndarray) -> np.ndarray: ...
        def _scalar_closed_forms(self) -> dict: ...

    def __init_subclass__(cls, **kwargs: Any) -> None:
        super().__init_subclass__(**kwargs)
        if getattr(cls, "__abstractmethods__", None) or cls.__name__.startswith("_"):
            return      # abstract or private intermediate bases are not checked
        if not any(getattr(cls, h) is not getattr(Profile, h, None) for h in _HOOKS
                   if hasattr(cls, h)):
            raise PluginError(
                f"profile class {cls.__qualname__} must implement one of _height(r), "
                f"_g_closed_form(x) or power_terms() (rule: Profile contract, item 2).")

    # ------------------------------------------------------------------ domain features
    @property
    def max_radius(self) -> float:
        """Largest admissible contact radius, m (``inf`` if unbounded)."""
        return np.inf

    @property
    def validity_radius(self) -> float:
        """Largest contact radius inside the half-space theory's range, m (``inf`` if none).

        A state with a larger contact radius is still returned, with a
        :class:`~contactlab.errors.ValidityWarning` (:class:`~contactlab.profiles.Sphere`:
        ``a > R/2``).
        """
        return np.inf

    @property
    def flat_radius(self) -> float:
        """Radius of a flat central part (``g = 0`` for ``|x|`` below it), m."""
        return 0.0

    @property
    def wall_radius(self) -> float:
        """Radius of a vertical wall limiting the contact radius (flat punch), m."""
        return np.inf

    @property
    def is_flat_punch(self) -> bool:
        """Whether the profile is flat up to its wall (``g = 0`` in every contact, contact
        radius the wall's from the first touch)."""
        return bool(np.isfinite(self.wall_radius) and self.flat_radius >= self.wall_radius)

    @property
    def breakpoints(self) -> tuple[float, ...]:
        """Radii, m, where the slope f' jumps (quadratures split there)."""
        return ()

    def power_terms(self) -> list[tuple[float, float]] | None:
        """``[(c, n), ...]`` when ``f = Σ c r**n`` exactly (enables the symbolic route)."""
        return None

    # ------------------------------------------------------------------ identity
    def __add__(self, other: "Profile") -> "Profile":
        from .compound import Sum
        if not isinstance(other, Profile):
            return NotImplemented
        return Sum(self, other)

    def __mul__(self, factor: float) -> "Profile":
        from .compound import Scaled
        return Scaled(self, factor)

    __rmul__ = __mul__

    # ------------------------------------------------------------------ geometry
    def height(self, r: Any) -> np.ndarray:
        """Gap ``f(r)``, m, for radii ``r >= 0`` (m)."""
        r = self._check_radii("r", r)
        if self._has("_height"):
            return self._height(r)
        raise StrategyUnavailableError(
            f"{type(self).__name__} defines no f(r); only its transform g(x) is known.")

    def derivative(self, r: Any) -> np.ndarray:
        """Slope ``f'(r)`` (dimensionless) for radii ``r >= 0`` (m).

        (Named ``derivative`` because ``slope`` is a parameter of cone-like profiles.)
        """
        r = self._check_radii("r", r)
        return self._slope_any(r)

    def _slope_any(self, r: np.ndarray) -> np.ndarray:
        if self._has("_slope"):
            return self._slope(r)
        if self._has("_height"):
            return self._slope_finite_difference(r)
        raise StrategyUnavailableError(f"{type(self).__name__} defines no f(r).")

    def _slope_finite_difference(self, r: np.ndarray) -> np.ndarray:
        """Fourth-order central differences of ``_height`` (one-sided fallback near r = 0)."""
        scale = np.maximum(np.abs(r), self._length_scale())
        h = 1e-3 * scale
        h = np.minimum(h, np.where(r > 0, 0.5 * r, h))
        central = (8 * (self._height(r + h) - self._height(np.maximum(r - h, 0.0)))
                   - (self._height(r + 2 * h) - self._height(np.maximum(r - 2 * h, 0.0)))) / (12 * h)
        # Richardson with a halved step
        h2 = 0.5 * h
        central2 = (8 * (self._height(r + h2) - self._height(np.maximum(r - h2, 0.0)))
                    - (self._height(r + 2 * h2) - self._height(np.maximum(r - 2 * h2, 0.0)))) / (12 * h2)
        est = (16 * central2 - central) / 15
        near0 = r <= 0
        if np.any(near0):
            hh = 1e-6 * self._length_scale()
            one_sided = (self._height(np.full_like(r, hh)) - self._height(np.zeros_like(r))) / hh
            est = np.where(near0, one_sided, est)
        return est

    def _length_scale(self) -> float:
        """A length typical of the profile (for finite-difference steps); override if known."""
        finite = [v for v in (self.max_radius, self.wall_radius) if np.isfinite(v)]
        finite += [b for b in self.breakpoints if b > 0]
        return min(finite) * 1e-3 if finite else 1e-6

    # ------------------------------------------------------------------ the MDR transform
    def available_strategies(self) -> tuple[str, ...]:
        """Numerical routes to ``g`` this profile offers, best first."""
        out = []
        if self._has("_g_closed_form"):
            out.append("closed_form")
        if self.power_terms() is not None:
            out.append("symbolic")
        if self._has("_height") or self._has("_slope"):
            out.append("quadrature")
        return tuple(out)

    @property
    def g_route(self) -> str:
        """The route ``g`` takes when no strategy is forced (cached choice)."""
        route = self.__dict__.get("_g_route_cache")
        if route is None:
            route = self.available_strategies()[0]
            self.__dict__["_g_route_cache"] = route
            import logging      # once per profile; the module costs ~2.5 ms of import
            logging.getLogger("contactlab").debug("%r: g(x) route %s", self, route)
        return route

    def g(self, x: Any, strategy: str | None = None, rtol: float | None = None) -> np.ndarray:
        """MDR-transformed profile ``g(x) = |x| ∫_0^{|x|} f'(r)/sqrt(x²-r²) dr``, m.

        Parameters
        ----------
        x : array_like
            1D coordinate, m (``|x|`` is used).
        strategy : {"closed_form", "symbolic", "quadrature"}, optional
            Force a route; default: the best available (:attr:`g_route`).
        rtol : float, optional
            Relative tolerance of the quadrature route (default :attr:`rtol`).

        Raises
        ------
        StrategyUnavailableError
            If ``strategy`` is not offered by this profile.
        """
        xa = np.abs(as_float_array("x", x))
        return self._g_route_eval(xa, strategy, rtol)

    def _g_route_eval(self, xa: np.ndarray, strategy: str | None = None,
                      rtol: float | None = None) -> np.ndarray:
        route = strategy or self.g_route
        if route not in self.available_strategies():
            raise StrategyUnavailableError(
                f"strategy={route!r} is not available for {type(self).__name__}; available: "
                f"{', '.join(self.available_strategies())}.")
        if route == "closed_form":
            return self._g_closed_form(xa)
        if route == "symbolic":
            return self._g_symbolic(xa)
        return self._g_quadrature(xa, rtol)[0]

    def _g(self, xa: np.ndarray, rtol: float | None = None) -> np.ndarray:
        """g for ``xa >= 0`` by the default route (hot path, no validation).

        ``rtol`` is the relative tolerance of a quadrature route (default :attr:`rtol`); exact
        routes ignore it.
        """
        return self._g_route_eval(xa, None, rtol)

    def _g_with_error(self, xa: np.ndarray, rtol: float | None = None
                      ) -> tuple[np.ndarray, np.ndarray]:
        """``(g, absolute error estimate)`` for ``xa >= 0`` by the default route.

        Quadrature: the quadrature's own estimate. Exact routes: a rounding floor
        (:data:`ROUNDING` times ``|g|``).
        """
        if self.g_route == "quadrature":
            return self._g_quadrature(xa, rtol)
        val = self._g(xa, rtol)
        return val, ROUNDING * np.abs(val)

    def _g_symbolic(self, xa: np.ndarray) -> np.ndarray:
        from ..symbolic.transform import g_callable
        terms = self.power_terms()
        assert terms is not None   # the symbolic route is offered for power terms only
        return g_callable(tuple(terms))(xa)

    def _g_quadrature(self, xa: np.ndarray, rtol: float | None = None
                      ) -> tuple[np.ndarray, np.ndarray]:
        """g by tanh-sinh quadrature of ``x ∫_0^{π/2} f'(x sinθ) dθ``; returns (value, error)."""
        rtol = self.rtol if rtol is None else rtol
        xa = np.asarray(xa, dtype=float)
        flat = xa.ravel()
        val, err = self._theta_quadrature(
            flat, lambda x, th: self._slope_any(x * np.sin(th)), rtol)
        return (val * flat).reshape(xa.shape), (err * flat).reshape(xa.shape)

    def _theta_segments(self, flat: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Split ``θ ∈ [0, π/2]`` at ``asin(b/x)`` for each breakpoint ``b < x``.

        Returns ``(lo, hi, x)``, each of shape ``(n_segments * len(flat),)`` when raveled, so one
        batched quadrature covers all segments of all points.
        """
        cuts = [b for b in sorted(set(self.breakpoints) | {self.flat_radius}) if b > 0]
        with np.errstate(divide="ignore", invalid="ignore"):
            thetas = [np.where(flat > b, np.arcsin(np.minimum(b / flat, 1.0)), 0.5 * np.pi)
                      for b in cuts]
        edges = np.stack([np.zeros_like(flat), *thetas, np.full_like(flat, 0.5 * np.pi)])
        lo, hi = edges[:-1], edges[1:]
        return lo, hi, np.broadcast_to(flat, lo.shape)

    def _theta_whole(self) -> bool:
        """Whether θ is never split (no breakpoint, no flat part, the base class's
        :meth:`_theta_segments`): every θ integral then runs over ``[0, π/2]`` (kept on the
        profile, a pure function of it)."""
        whole = self.__dict__.get("_theta_whole_cache")
        if whole is None:
            whole = (type(self)._theta_segments is Profile._theta_segments
                     and not [b for b in self.breakpoints if b > 0] and not self.flat_radius > 0)
            self.__dict__["_theta_whole_cache"] = whole
        return bool(whole)

    def _theta_quadrature(self, flat: np.ndarray, weight, rtol: float
                          ) -> tuple[np.ndarray, np.ndarray]:
        """``Σ_segments ∫ weight(x, θ) dθ`` over the split θ range for each ``x`` in ``flat``.

        ``rtol`` applies to the sum over the segments of one ``x``, not to each segment: a
        segment far smaller than the sum (a table with hundreds of nodes splits θ at each of them)
        need not reach ``rtol`` relative to itself.
        """
        val = np.zeros(flat.shape)
        err = np.zeros(flat.shape)
        nz = flat > 0          # x = 0 contributes nothing (every caller multiplies by a power of x)
        if not np.any(nz):
            return val, err
        whole = self._theta_whole()
        if whole:       # one segment [0, π/2] for every x: _theta_segments' arrays, built directly
            xr = flat[nz]
            lo = np.zeros((1, xr.size))
            hi = np.full((1, xr.size), 0.5 * np.pi)
        else:
            lo, hi, xs = self._theta_segments(flat[nz])
            xr = xs.ravel()

        def integrand(theta: np.ndarray, idx: np.ndarray) -> np.ndarray:
            return weight(xr[idx][:, None], theta)

        lo_f, hi_f = lo.ravel(), hi.ravel()
        if rtol >= LOOSE_RTOL:
            # the first levels in one pass (tanh_sinh stops there for every integral whose level
            # difference is within rtol: the same values); the others refine in tanh_sinh
            v, e, done = first_converged(*tanh_sinh_upto(integrand, lo_f, hi_f, common=whole),
                                         rtol, min_level_for(rtol))
            more = np.flatnonzero(~done)
            if more.size:
                xr_all = xr

                def integrand_more(theta: np.ndarray, idx: np.ndarray) -> np.ndarray:
                    return weight(xr_all[more[idx]][:, None], theta)

                res = tanh_sinh(integrand_more, lo_f[more], hi_f[more], rtol=rtol,
                                raise_on_failure=False, min_level=min_level_for(rtol))
                v[more] = res.value
                e[more] = res.error
        else:
            res = tanh_sinh(integrand, lo_f, hi_f, rtol=rtol, raise_on_failure=False,
                            min_level=min_level_for(rtol))
            v, e = res.value, res.error
        val[nz] = v.reshape(lo.shape).sum(axis=0)
        err[nz] = e.reshape(lo.shape).sum(axis=0)
        missed = err > rtol * np.abs(val) + self._quadrature_floor(flat, val)
        if np.any(missed):
            from ..errors import ConvergenceError
            i = int(np.argmax(missed))
            raise ConvergenceError(
                f"quadrature over θ at x={float(flat[i])!r} m did not reach rtol={rtol:g} "
                f"(value {val[i]:.6g}, error estimate {err[i]:.3g} summed over "
                f"{lo.shape[0]} segments); loosen rtol.")
        return val, err

    def _quadrature_floor(self, x: np.ndarray, value: np.ndarray) -> np.ndarray | float:
        """Absolute error accepted from a θ quadrature at ``x`` beyond ``rtol`` (hook; 0: none).

        Profiles known only to a finite resolution (tables) may accept their own resolution."""
        return 0.0

    def g_integral(self, a: Any) -> np.ndarray:
        """``∫_0^a g(x) dx = ∫_0^a f'(r) sqrt(a²-r²) dr``, m², for contact radii ``a`` (m)."""
        a = self._check_radii("a", a)
        return self._g_integral(a)

    def _g_integral(self, a: np.ndarray, rtol: float | None = None) -> np.ndarray:
        """``∫_0^a g dx`` (hot path); ``rtol`` applies to the quadrature route only. The exact
        routes skip the error estimate's arithmetic (the same value)."""
        if type(self)._g_integral_with_error is Profile._g_integral_with_error:
            val = self._g_integral_exact(a)
            if val is not None:
                return val
        return self._g_integral_with_error(a, rtol)[0]

    def _g_integral_is_exact(self) -> bool:
        """Whether :meth:`_g_integral_with_error` is this base class's exact route (a closed form
        or power terms), whose error estimate is ``ROUNDING · |∫g|`` of the value itself."""
        return (type(self)._g_integral_with_error is Profile._g_integral_with_error
                and (self._has("_g_integral_closed_form") or self.power_terms() is not None))

    def _g_integral_exact(self, a: np.ndarray) -> np.ndarray | None:
        """``∫_0^a g dx`` by a closed form or the power terms, or None (quadrature route)."""
        if self._has("_g_integral_closed_form"):
            return self._g_integral_closed_form(a)
        terms = self.power_terms()
        if terms is not None:
            from ..numeric.powers import power_integral
            return power_integral(a, [(self._power_kappa(n) * c, n) for c, n in terms], 1.0)
        return None

    def _g_integral_with_error(self, a: np.ndarray, rtol: float | None = None
                               ) -> tuple[np.ndarray, np.ndarray]:
        """``(∫_0^a g dx, absolute error estimate)``; exact routes carry a rounding floor."""
        val = self._g_integral_exact(a)
        if val is None:
            return self._g_integral_quadrature(a, rtol)
        return val, ROUNDING * np.abs(val)

    def _g_integral_quadrature(self, a: np.ndarray, rtol: float | None = None
                               ) -> tuple[np.ndarray, np.ndarray]:
        """``a² ∫_0^{π/2} f'(a sinθ) cos²θ dθ`` with breakpoint splits; returns (value, error)."""
        rtol = self.rtol if rtol is None else rtol
        a = np.asarray(a, dtype=float)
        flat = a.ravel()
        val, err = self._theta_quadrature(
            flat, lambda x, th: self._slope_any(x * np.sin(th)) * np.cos(th) ** 2, rtol)
        return (val * flat**2).reshape(a.shape), (err * flat**2).reshape(a.shape)

    @staticmethod
    def _power_kappa(n: float) -> float:
        from ..symbolic.transform import kappa
        return kappa(n)

    # ------------------------------------------------------------------ inverse problems
    def radius_of_depth(self, depth: Any) -> np.ndarray:
        """Non-adhesive contact radius ``a`` with ``g(a) = depth`` (m); 0 for ``depth <= 0``.

        Raises
        ------
        OutsideTheoryError
            If ``a`` would exceed :attr:`max_radius`, or g decreases below ``a`` (ring contact).
        """
        d = as_float_array("depth", depth)
        return self._radius_of_depth(d)

    def _radius_of_depth(self, d: np.ndarray, rtol: float | None = None) -> np.ndarray:
        pos = d > 0
        all_pos = bool(pos.all())
        if not all_pos and not pos.any():
            return np.zeros(d.shape)
        dp = d if all_pos else d[pos]        # (no masked copies in the common all-positive case)
        if np.isfinite(self.wall_radius):
            a = np.full(dp.shape, self.wall_radius)
            if self.flat_radius < self.wall_radius:
                # profile rises before the wall: the contact may be smaller than the wall
                g_wall = self._g(np.array(self.wall_radius), rtol)
                inner = dp < g_wall
                if np.any(inner):
                    a[inner] = self._solve_radius(dp[inner], self.wall_radius, rtol)
        elif self._has("_g_inverse_closed_form"):
            a = self._g_inverse_closed_form(dp)
        else:
            a = self._solve_radius(dp, self.max_radius, rtol)
        if np.isfinite(self.max_radius) and np.any(a >= self.max_radius):
            i = int(np.argmax(a >= self.max_radius))
            raise OutsideTheoryError(
                f"depth={float(dp.ravel()[i])!r} m needs a contact radius >= max_radius="
                f"{self.max_radius!r} m of {self!r}; reduce the depth/force.")
        if all_pos:
            out = np.asarray(a, dtype=float).reshape(d.shape)
        else:
            out = np.zeros(d.shape)
            out[pos] = a
        if self._has("_check_monotone_upto"):     # (the base hook checks nothing)
            self._check_monotone_upto(np.max(a), d_for_message=float(np.max(dp)))
        return out

    def _check_monotone_upto(self, a_max: float, d_for_message: float) -> None:
        """Hook: raise OutsideTheoryError if g decreases on [0, a_max] (default: f' >= 0 assumed)."""

    def _solve_radius(self, d: np.ndarray, limit: float, rtol: float | None = None) -> np.ndarray:
        """Bracketed solve of g(a) = d (g non-decreasing) with an expanding upper bracket.

        ``rtol`` (default :attr:`rtol`) sets the quadrature tolerance of g and, through
        :func:`root_rtol`, the relative width of the final bracket.
        """
        rtol = self.rtol if rtol is None else rtol
        lo = np.full(d.shape, self.flat_radius)
        hi = np.full(d.shape, self._initial_bracket())
        if self.g_route == "quadrature" and self._has("_height"):
            # each g costs a quadrature, f almost nothing: grow the bracket on f first. Where
            # f' >= 0, g(a) = a ∫_0^a f'(r)/sqrt(a²-r²) dr >= ∫_0^a f' = f(a), so the first
            # radius with f >= d is at or above the root (the loop below still checks g there)
            # (f that stops rising, saturating or falling, stops the growth: g takes over there)
            cap = limit * (1 - 1e-15) if np.isfinite(limit) else np.inf
            found = np.zeros(d.shape, dtype=bool)
            if rtol >= LOOSE_RTOL:
                # at a loose rtol a tighter bracket from a lower bound of g on f (radius_bounds):
                # fewer of the (few, costly) g evaluations of the root; the loop below checks g
                hb = upper_radius_from_f(self, d, self._initial_bracket(), cap, "depth")
                found = np.isfinite(hb)
                hi = np.where(found, hb, hi)
            f_prev = np.full(d.shape, -np.inf)
            for _ in range(200):
                hc = np.minimum(hi, cap)
                with np.errstate(over="ignore", invalid="ignore"):
                    f_hc = self._height(hc)
                short = (f_hc < d) & (hc < cap) & (f_hc > f_prev) & ~found
                if not np.any(short):
                    break
                f_prev = f_hc
                hi = np.where(short, hi * 4.0, hi)
        g_top = np.full(d.size, np.nan)
        for _ in range(400):
            hi_c = np.minimum(hi, limit * (1 - 1e-15)) if np.isfinite(limit) else hi
            g_hi = self._g(hi_c, rtol)
            short = g_hi < d
            if not np.any(short):
                hi = hi_c
                # a root far below the first bracket (depths of 1e-200 m): tightened
                lo, hi, g_top = shrink_bracket(lambda x, idx: self._g(x, rtol), d.ravel(),
                                               lo.ravel(), hi.ravel(), np.ravel(g_hi))
                lo, hi = lo.reshape(d.shape), hi.reshape(d.shape)
                break
            if np.isfinite(limit) and np.any(short & (hi >= limit * (1 - 1e-15))):
                i = int(np.argmax(short & (hi >= limit * (1 - 1e-15))))
                raise OutsideTheoryError(
                    f"depth={float(d.ravel()[i])!r} m needs a contact radius >= max_radius={limit!r} m "
                    f"of {self!r}; reduce the depth/force.")
            lo = np.where(short, hi_c, lo)
            hi = np.where(short, hi * 4.0, hi)
        d_flat = d.ravel()

        def func(x: np.ndarray, idx: np.ndarray) -> np.ndarray:
            return self._g(x, rtol)

        tol = quadrature_root_rtol(rtol) if self.g_route == "quadrature" else root_rtol(rtol)
        step0, ftol = None, 0.0
        if rtol >= LOOSE_RTOL and self.g_route == "quadrature" and self._has("_height"):
            # (and a stop once g is within tol of the depth: the radius is then within about
            # tol/n of the root, n the local power of g, and the force unmoved to first order)
            ftol = tol
            # the first point where the bound of g on f, scaled to g at hi, meets the depth
            step0 = first_step_from_f(
                self, d_flat, lo.ravel(), hi.ravel(), g_top, self._initial_bracket(),
                limit * (1 - 1e-15) if np.isfinite(limit) else np.inf, "depth")
        return bracketed_root(func, d_flat, lo.ravel(), hi.ravel(), rtol=tol, ftol=ftol,
                              what="contact radius", first_step=step0).reshape(d.shape)

    def _initial_bracket(self) -> float:
        finite = [v for v in (self.max_radius, self.wall_radius) if np.isfinite(v)]
        return 0.5 * min(finite) if finite else max(self.flat_radius * 2, 1e-6)

    def inverse_transform(self, r: Any, rtol: float | None = None) -> np.ndarray:
        """Recover ``f(r) = (2/π) ∫_0^{π/2} g(r sinθ) dθ`` from g (a check of the forward route)."""
        r = self._check_radii("r", r)
        rtol = self.rtol if rtol is None else rtol
        val, _ = self._theta_quadrature(r.ravel(), lambda x, th: self._g(x * np.sin(th), rtol), rtol)
        return (2 / np.pi * val).reshape(r.shape)

    # ------------------------------------------------------------------ symbolic
    def _sympy_form(self) -> SympyForm:
        """Hook: the closed forms :meth:`formulas` derives every named formula from.

        The one road to ``formulas()`` for built-in and plugin profiles alike. The default builds
        the form from the shorthands ``_height_sympy(r, **symbols)``, ``_g_sympy(x, **symbols)``,
        ``_g_integral_sympy(a, **symbols)`` (one positive symbol per parameter, named by
        ``Param.symbol``, passed by ``Param.name``) or, without them, from :meth:`power_terms`.
        Override it to declare more (a flat centre, a wall, piecewise forms, ``∫x g``, the
        inverse ``a(d)``, the pressure shape); see :class:`~contactlab.symbolic.form.SympyForm`.
        """
        values = {}
        for p in self.params:
            try:
                values[p.name] = float(getattr(self, p.name))
            except (TypeError, ValueError, AttributeError):
                pass
        return form_from_hooks(
            self.params, values, height_sympy=getattr(self, "_height_sympy", None),
            g_sympy=getattr(self, "_g_sympy", None),
            g_integral_sympy=getattr(self, "_g_integral_sympy", None),
            power_terms=self.power_terms, owner=type(self).__name__)

    def formulas(self) -> FormulaSet:
        """Named sympy expressions for this profile (``height``, ``g``, …); see ``symbolic``."""
        from ..symbolic.formulas import profile_formulas
        return profile_formulas(self)

    def to_latex(self) -> str:
        """LaTeX of ``g(x)`` (and ``f(r)``) for this profile."""
        import sympy as sp
        f = self.formulas()
        return "\n".join(f"{k} = {sp.latex(v)}" for k, v in f.items())

    # ------------------------------------------------------------------ capabilities
    @property
    def capabilities(self) -> frozenset[str]:
        """Optional routes this profile declares, by name (see :data:`CAPABILITIES`).

        Kernels ask ``profile.has(name)`` instead of probing attributes; a profile that declares
        a capability implements the hook that :data:`CAPABILITIES` names for it.
        """
        return frozenset()

    def has(self, capability: str) -> bool:
        """Whether the profile declares ``capability`` (one of :data:`CAPABILITIES`)."""
        return capability in self.capabilities

    # ------------------------------------------------------------------ helpers
    def _has(self, hook: str) -> bool:
        own = getattr(type(self), hook, None)
        return own is not None and own is not getattr(Profile, hook, None)

    def _check_radii(self, name: str, r: Any) -> np.ndarray:
        arr = as_float_array(name, r)
        if np.any(arr < 0):
            raise ParameterError(f"{name} contains {float(arr[arr < 0].ravel()[0])!r}: radii must be >= 0 m.")
        return arr
