"""Subsurface stress fields of contact states: :class:`StressField` and the drivers behind
``NormalState.stress``, ``NormalState.max_stress`` and ``NormalState.stress_field``.

The kernels are in :mod:`contactlab.physics.stress` (flat-punch superposition, Huber's Hertz
field). This module validates the points and the body, picks the route per profile
(``"hertz"``: closed form for a paraboloid; ``"flat_punch"``: the punch's closed form;
``"superposition"``: the 1D integral over punch radii for any other profile, with an error
estimate) and wraps the arrays in an immutable result.

Conventions: tension positive; ``z >= 0`` is the depth below the surface of the chosen body
(1 or 2 of ``Contact(materials=(body1, body2))``), whose Poisson ratio enters the field; the
normal field is the same formula in both bodies except for ``ν``.
"""
from __future__ import annotations

import warnings
from dataclasses import dataclass, field
from functools import cached_property
from typing import Any, ClassVar

import numpy as np

from ..citations import Cited
from ..errors import NotSupportedError, ParameterError, ValidityWarning
from ..params import as_float_array, check_memory
from ..physics import stress as _st
from ._protocol import Result

__all__ = [
    "KINDS",
    "StressDerived",
    "StressField",
    "StressMaximum",
    "body_poisson_ratio",
    "check_stress_memory",
    "g_prime_of",
    "normal_max_stress",
    "normal_stress",
    "normal_stress_field",
    "slope_route",
]

#: derived scalar fields :meth:`StressField` offers (names of its properties)
KINDS = ("von_mises", "max_shear", "tresca", "max_principal", "min_principal")

_CYL = ("srr", "stt", "szz", "srz", "stz", "srt")

#: sources of the fields: Sneddon's punch superposition, Johnson's half-space solutions
#: (Boussinesq, Hertz), Reissner-Sagoci's twisted punch (torsion)
NORMAL_SOURCES = ("Sn65", "J85")
TORSION_SOURCES = ("Sn65", "J85", "RS44")

#: units of the CSV columns of a :class:`StressField`
FIELD_UNITS = {"r": "m", "z": "m", **{k: "Pa" for k in _CYL}, "von_mises": "Pa",
               "max_shear": "Pa", "tresca": "Pa", "error": "Pa"}


class StressDerived:
    """Derived quantities shared by the stress-field results (a mixin): principal stresses,
    von Mises, maximum shear, Tresca, ``get``, ``to_dict`` and ``plot``, parametrised by the
    class's coordinate names ``_COORDS``, component names ``_COMPONENTS`` (as stored) and
    ``_TENSOR``, the components in the order ``(s11, s22, s33, s12, s13, s23)`` of an
    orthonormal frame."""

    _COORDS: ClassVar[tuple[str, ...]] = ()
    _COMPONENTS: ClassVar[tuple[str, ...]] = ()
    _TENSOR: ClassVar[tuple[str, ...]] = ()
    z: np.ndarray
    error: np.ndarray
    meta: dict

    def __post_init__(self) -> None:
        for name in (*self._COORDS, *self._COMPONENTS, "error"):
            arr = np.asarray(getattr(self, name), dtype=float)
            arr.setflags(write=False)
            object.__setattr__(self, name, arr)

    def _tensor(self) -> tuple[np.ndarray, ...]:
        return tuple(getattr(self, k) for k in self._TENSOR)

    @property
    def shape(self) -> tuple[int, ...]:
        """Shape of the point arrays."""
        return getattr(self, self._COMPONENTS[0]).shape

    @property
    def error_estimate(self) -> float:
        """Largest estimated error relative to the largest finite stress magnitude."""
        return float(self.meta.get("error_estimate", 0.0))

    def _principal(self) -> np.ndarray:
        return _st.principal_general(*self._tensor())

    @cached_property
    def principal(self) -> np.ndarray:
        """Principal stresses, Pa, descending along the last axis (``shape + (3,)``)."""
        out = self._principal()
        out.setflags(write=False)
        return out

    @cached_property
    def von_mises(self) -> np.ndarray:
        """Von Mises equivalent stress, Pa."""
        return _st.von_mises(*self._tensor())

    @cached_property
    def max_shear(self) -> np.ndarray:
        """Maximum shear stress ``(σ1 - σ3)/2``, Pa."""
        p = self.principal
        return 0.5 * (p[..., 0] - p[..., 2])

    @property
    def tresca(self) -> np.ndarray:
        """Tresca equivalent stress ``σ1 - σ3``, Pa."""
        return 2.0 * self.max_shear

    @property
    def max_principal(self) -> np.ndarray:
        """Largest principal stress ``σ1``, Pa (the tensile driver of crack initiation)."""
        return self.principal[..., 0]

    @property
    def min_principal(self) -> np.ndarray:
        """Smallest principal stress ``σ3``, Pa."""
        return self.principal[..., 2]

    def get(self, kind: str) -> np.ndarray:
        """A component or derived field by name (one of :data:`KINDS` or a component)."""
        if kind not in KINDS + self._COMPONENTS:
            raise ParameterError(f"kind={kind!r} is invalid: choose one of "
                                 f"{', '.join(repr(k) for k in KINDS + self._COMPONENTS)}.")
        return np.asarray(getattr(self, kind))

    def to_dict(self) -> dict[str, Any]:
        """Coordinates, components, derived fields and the error estimate as arrays (SI units;
        one CSV row per point, flattened in C order). The model error is 0.0: the fields are
        the exact elastic half-space solutions of the state's tractions."""
        out: dict[str, Any] = {k: getattr(self, k) for k in self._COORDS}
        out.update({k: getattr(self, k) for k in self._COMPONENTS})
        out.update({k: getattr(self, k) for k in ("von_mises", "max_shear", "tresca")})
        out["error"] = self.error
        return out

    def plot(self, kind: str = "von_mises", ax: Any = None, *, levels: int = 30):
        """Filled contour plot of ``kind`` over a 2D grid of the first coordinate and the
        depth (needs matplotlib); returns the axes. Depth is drawn downward."""
        from .. import plotting as pl
        plt = pl.pyplot()
        h = getattr(self, self._COORDS[0])
        if h.ndim != 2:
            raise ParameterError("plot() needs a 2D grid of points (use state.stress_field()).")
        if ax is None:
            _, ax = plt.subplots()
        vals = self.get(kind)
        cs = ax.contourf(h, -self.z, np.where(np.isfinite(vals), vals, np.nan), levels=levels)
        ax.figure.colorbar(cs, ax=ax, label=f"{kind} (Pa)")
        ax.set_xlabel(f"{self._COORDS[0]} (m)")
        ax.set_ylabel("-z (m)")
        ax.set_aspect("equal")
        return ax


@dataclass(frozen=True, eq=False)
class StressField(StressDerived, Result, Cited):
    """Stress field at a set of points (immutable; arrays of the broadcast shape of the points).

    Attributes
    ----------
    r, z : ndarray
        Radius and depth of each point, m.
    srr, stt, szz, srz, stz, srt : ndarray
        Cylindrical stress components ``σ_rr, σ_θθ, σ_zz, σ_rz, σ_θz, σ_rθ``, Pa (tension
        positive).
    error : ndarray
        Estimated absolute error of the components, Pa (0 for the closed forms up to rounding;
        ``inf`` at singular points).
    meta : dict
        ``route`` (``"hertz"``, ``"flat_punch"`` or ``"superposition"``), ``body``, ``nu``,
        ``error_estimate`` (largest error relative to the largest stress magnitude).

    Notes
    -----
    Derived fields are computed on first access (:class:`StressDerived`): :attr:`principal`
    (descending, last axis), :attr:`von_mises`, :attr:`max_shear` ``(σ1 - σ3)/2``,
    :attr:`tresca` ``σ1 - σ3``, :attr:`max_principal`, :attr:`min_principal`.
    """

    r: np.ndarray
    z: np.ndarray
    srr: np.ndarray
    stt: np.ndarray
    szz: np.ndarray
    srz: np.ndarray
    stz: np.ndarray
    srt: np.ndarray
    error: np.ndarray = field(repr=False)
    meta: dict = field(default_factory=dict, repr=False)

    units: ClassVar[dict[str, str]] = FIELD_UNITS
    _COORDS: ClassVar[tuple[str, ...]] = ("r", "z")
    _COMPONENTS: ClassVar[tuple[str, ...]] = _CYL
    _TENSOR: ClassVar[tuple[str, ...]] = ("srr", "stt", "szz", "srt", "srz", "stz")

    def _principal(self) -> np.ndarray:
        if not (np.any(self.stz) or np.any(self.srt)):
            return _st.principal_axisymmetric(self.srr, self.stt, self.szz, self.srz)
        return _st.principal_general(*self._tensor())


@dataclass(frozen=True)
class StressMaximum(Result, Cited):
    """Largest value of a stress measure in a body and where it occurs.

    Attributes
    ----------
    value : float
        The maximum, Pa (``inf`` where the field is singular, e.g. at a flat punch's rim).
    r, z : float
        Its radius and depth, m.
    kind : str
        The measure (one of :data:`KINDS`).
    meta : dict
        ``body``, ``citations``.
    """

    value: float
    r: float
    z: float
    kind: str
    meta: dict = field(default_factory=dict, repr=False, compare=False)

    units: ClassVar[dict[str, str]] = {"value": "Pa", "r": "m", "z": "m"}

    def to_dict(self) -> dict[str, Any]:
        """``value`` (Pa), ``r``, ``z`` (m) and ``kind``."""
        return {"value": self.value, "r": self.r, "z": self.z, "kind": self.kind}

    def _columns(self) -> dict[str, Any]:
        return {k: np.ravel(getattr(self, k)) for k in ("value", "r", "z")}


def body_poisson_ratio(contact, body: Any) -> float:
    """Poisson ratio of body ``1`` or ``2`` of ``contact``; errors for other values (an integer
    is required: ``1.0`` is refused like ``True``) or a rigid body (no strain, so the elastic
    field inside it is not defined by this theory)."""
    if (isinstance(body, bool) or not isinstance(body, (int, np.integer))
            or body not in (1, 2)):
        raise ParameterError(f"body={body!r} is invalid: a contact has body 1 and body 2 "
                             "(the integer 1 or 2, the order of Contact(materials=...)).")
    mat = contact.materials[body - 1]
    nu = getattr(mat, "nu", None)
    if nu is None:
        raise NotSupportedError(f"body={body} is {mat!r}, which has no Poisson ratio (a rigid "
                                "body does not deform); ask for the stresses in the other body.")
    return float(nu)


#: peak bytes per point of a stress call, the result included (tracemalloc, 10^4 to 10^6
#: points: 168-222 B for the Hertz and flat-punch routes, 137-150 B a point beyond the
#: superposition's chunk for the other routes; the derived fields, on first access, 88-167 B
#: with the result held)
STRESS_POINT_BYTES = 256
#: peak bytes per point of one chunk of the superposition (at most ``CHUNK`` points at a time;
#: measured 11 kB normal, 10 kB torsion, 21 kB tangential)
CHUNK_POINT_BYTES = 24 * 1024


def check_stress_memory(what: str, n_points: float, superposed: bool = True) -> None:
    """Raise :class:`~contactlab.errors.MemoryBudgetError` before a stress evaluation of
    ``n_points`` points whose estimated peak (:data:`STRESS_POINT_BYTES` a point, plus one
    chunk of the superposition at :data:`CHUNK_POINT_BYTES` a point where ``superposed``)
    exceeds the memory budget (:func:`contactlab.params.check_memory`)."""
    n = float(n_points)
    chunk = min(n, float(_st.CHUNK)) if superposed else 0.0
    check_memory(what, STRESS_POINT_BYTES * n + CHUNK_POINT_BYTES * chunk,
                 f"{n:.0f} points x {STRESS_POINT_BYTES} bytes"
                 + (f" + a chunk of {chunk:.0f} points x {CHUNK_POINT_BYTES} bytes"
                    if superposed else ""))


def _points(r: Any, z: Any, what: str = "stress()") -> tuple[np.ndarray, np.ndarray]:
    r = as_float_array("r", r)
    z = as_float_array("z", z)
    for name, v in (("r", r), ("z", z)):
        if np.any(v < 0):
            raise ParameterError(f"{name} contains {float(v[v < 0].ravel()[0])!r}: "
                                 f"{'radii' if name == 'r' else 'depths below the surface'} "
                                 "must be >= 0 m.")
    try:
        r, z = np.broadcast_arrays(r, z)
    except ValueError as err:
        raise ParameterError(f"r with shape {r.shape} and z with shape {z.shape} do not "
                             "broadcast.") from err
    check_stress_memory(what, r.size, superposed=False)
    return r, z


def g_prime_of(profile, rtol: float):
    """``g'(x)`` of a profile as a callable on arrays: the profile's closed form, its power
    terms, a table's node sums, the terms of a sum, or (last) a central difference of ``g``."""
    if profile._has("_g_prime_closed_form"):
        return profile._g_prime_closed_form
    terms = profile.power_terms()
    if terms is not None:
        ks = [(profile._power_kappa(n) * c * n, n) for c, n in terms]

        def power(x: np.ndarray) -> np.ndarray:
            return sum(k * x ** (n - 1.0) for k, n in ks)
        return power
    if profile.has("node_table"):
        return lambda x: profile.table_g_slope(x.ravel())[0].reshape(x.shape)
    if profile.has("terms"):
        parts = [g_prime_of(t, rtol) for t in profile.terms]
        return lambda x: sum(p(x) for p in parts)
    flat = profile.flat_radius

    def difference(x: np.ndarray) -> np.ndarray:
        h = 1e-5 * np.maximum(x, 1e-300)
        lo = np.maximum(x - h, 0.0)
        hi = x + h
        out = (profile._g(hi, rtol) - profile._g(lo, rtol)) / (hi - lo)
        return np.where(x <= flat, 0.0, out)
    return difference


#: samples of a table's g' over [0, a] for the interpolated slope (cost O(samples x nodes) once)
TABLE_SLOPE_SAMPLES = 4096


def table_slope(profile, a: float):
    """A table's ``g'`` on ``[0, a]`` as ``(value, error)`` callables.

    The exact node sums cost O(nodes) per point, too much for every quadrature node of a grid,
    and a linear table's ``g'`` has an inverse-square-root spike after every node (its slope
    jumps), which point samples cannot represent. So ``g`` itself (closed form) is sampled at
    :data:`TABLE_SLOPE_SAMPLES` + 1 equidistant radii and ``g'`` is the cell slope
    ``(g_{k+1} - g_k)/Δ`` at the cell midpoints, linearly interpolated: every cell carries the
    exact increment of ``g``, spikes included. The error callable is the difference to the same
    construction on cells twice as wide (not divided by 3, as second order would allow: below the
    first midpoint the interpolant is constant, and there the difference is the error), plus the
    rounding of the slopes."""
    n = TABLE_SLOPE_SAMPLES
    xs = np.linspace(0.0, a, n + 1)
    g = profile._g(xs)
    dx = a / n
    mids = 0.5 * (xs[1:] + xs[:-1])
    slopes = np.diff(g) / dx
    mids2 = 0.5 * (xs[2::2] + xs[:-2:2])
    slopes2 = (g[2::2] - g[:-2:2]) / (2.0 * dx)
    coarse = np.interp(mids, mids2, slopes2)
    diff = np.abs(slopes - coarse) + 8 * np.finfo(float).eps * np.max(np.abs(g)) / dx

    def value(x: np.ndarray) -> np.ndarray:
        return np.interp(x, mids, slopes)

    def error(x: np.ndarray) -> np.ndarray:
        return np.interp(x, mids, diff)

    def values(x: np.ndarray) -> np.ndarray:
        return np.interp(x, xs, g)
    return value, error, values


def slope_route(prof, a: float, rtol: float):
    """``(g', g' error or None, g or None, cuts, is_table)`` of a profile on ``[0, a]`` for
    :func:`~contactlab.physics.stress.superposed_field`: a table's interpolated slope (a linear
    table: the Riemann-Stieltjes cell sums of ``g`` itself; a spline: its smooth ``g'`` with the
    interpolation error), else :func:`g_prime_of` cut at the profile's breakpoints."""
    cuts = tuple(b for b in (*prof.breakpoints, prof.flat_radius) if 0 < b < a)
    if prof.has("node_table"):
        gp, gp_err, g_vals = table_slope(prof, a)
        cuts = ()       # the interpolated slope is continuous; node cuts cost O(nodes)
        if prof.interpolation != "linear":
            g_vals = None   # a spline's g' is smooth: the Gauss-Kronrod sums on g'
        else:
            gp_err = None   # the cell sums carry the exact increments of g
        return gp, gp_err, g_vals, cuts, True
    return g_prime_of(prof, rtol), None, None, cuts, False


def _route(profile, a: float) -> str:
    terms = profile.power_terms()
    if terms is not None and len(terms) == 1 and terms[0][1] == 2.0:
        return "hertz"
    if profile.flat_radius >= a:
        return "flat_punch"
    return "superposition"


def normal_stress(state, r: Any, z: Any, body: Any = 1) -> StressField:
    """Field of a normal state (implementation of ``NormalState.stress``)."""
    nu = body_poisson_ratio(state.contact, body)
    r, z = _points(r, z)
    sh = state.shape
    if sh != ():
        raise NotSupportedError(f"stress() needs a single state, this one has shape {sh}: index "
                                "the loads or call contact.normal() per load.")
    ct = state.contact
    prof = ct.profile
    E = ct.moduli.normal
    a = float(state._radius)
    d = float(state._depth)
    ga = float(state._g_at_radius)
    edge = d - ga if a > 0 else 0.0
    R, Z = r.ravel(), z.ravel()
    zero = np.zeros(R.shape)
    route = _route(prof, a) if a > 0 else "flat_punch"
    if route == "superposition":
        check_stress_memory("stress()", R.size)
    comps: tuple[np.ndarray, ...]
    if a <= 0:
        comps, err = (zero, zero, zero, zero), zero
    elif route == "hertz":
        c = prof.power_terms()[0][0]
        p0 = 4.0 * E * c * a / np.pi            # g = 2c x²: p0 = 2E* a/(πR), R = 1/(2c)
        comps = _st.hertz_field(R, Z, a, p0, nu)
        err = 4e-15 * np.maximum.reduce([np.abs(v) for v in comps]) + 1e-16 * p0
    else:
        comps, err = (zero,) * 4, zero
        if route == "superposition":
            gp, gp_err, g_vals, cuts, table = slope_route(prof, a, ct.rtol)
            if table:
                route = "superposition (table)"
            comps, err = _st.superposed_field(R, Z, np.full(R.shape, a), zero, gp, E, nu, cuts,
                                              gp_err, g_vals)
    if a > 0 and edge != 0:
        k = E * edge / np.pi
        extra = _st.punch_kernel(R, Z, a, nu)
        comps = tuple(c + k * e for c, e in zip(comps, extra))
        err = err + 4e-15 * np.maximum.reduce([np.abs(k * e) for e in extra])
    comps = tuple(np.asarray(c, float).reshape(r.shape) for c in comps)
    err = np.asarray(err, float).reshape(r.shape)
    singular = ~np.all(np.isfinite(np.stack(comps)), axis=0)
    err = np.where(singular, np.inf, err)
    finite_mag = np.max(np.abs(np.stack(comps))[:, ~singular], initial=0.0)
    rel = float(np.max(err[~singular], initial=0.0) / finite_mag) if finite_mag > 0 else 0.0
    srr, stt, szz, srz = comps
    zero = np.zeros(r.shape)
    return StressField(r, z, srr, stt, szz, srz, zero, zero, err,
                       {"route": route, "body": body, "nu": nu, "error_estimate": rel,
                        "edge_depth": edge, "citations": NORMAL_SOURCES})


#: distance from the contact centre, in contact radii, beyond which a non-finite value met by the
#: polish of :func:`_maximise` is an overflow of the kernels (the field there has decayed to 0),
#: not a singular point
FAR_FIELD = 1e3


def _maximise(evaluate, kind: str, a: float, meta: dict) -> StressMaximum:
    """Grid search over ``0 <= r, z <= 2a`` then a Nelder-Mead polish (``|r|, |z|`` mirrored)."""
    from scipy.optimize import minimize
    rg = np.linspace(0.0, 2.0 * a, 41)
    zg = np.linspace(0.0, 2.0 * a, 41)
    RG, ZG = np.meshgrid(rg, zg, indexing="ij")
    vals = evaluate(RG, ZG).get(kind)
    if not np.all(np.isfinite(vals)):
        i = np.unravel_index(np.argmax(~np.isfinite(vals)), vals.shape)
        return StressMaximum(float("inf"), float(RG[i]), float(ZG[i]), kind, meta)
    i = np.unravel_index(np.argmax(vals), vals.shape)

    def neg(p: np.ndarray) -> float:
        v = float(evaluate(np.abs(p[0:1]) * a, np.abs(p[1:2]) * a).get(kind)[0])
        if not np.isfinite(v):
            if np.hypot(p[0], p[1]) > FAR_FIELD:
                return 0.0      # the kernels overflow far out, where the field has decayed to 0
            # the polish reached a singular point (a cone's apex): the maximum is inf there
            raise _Singular(float(abs(p[0]) * a), float(abs(p[1]) * a))
        return -v

    try:
        res = minimize(neg, np.array([RG[i] / a, ZG[i] / a]), method="Nelder-Mead",
                       options={"xatol": 1e-10, "fatol": 0.0, "maxiter": 4000,
                                "initial_simplex": np.array([[RG[i] / a, ZG[i] / a],
                                                             [RG[i] / a + 0.02, ZG[i] / a],
                                                             [RG[i] / a, ZG[i] / a + 0.02]])})
    except _Singular as hit:
        return StressMaximum(float("inf"), hit.r, hit.z, kind, meta)
    return StressMaximum(-float(res.fun), float(abs(res.x[0]) * a), float(abs(res.x[1]) * a), kind,
                         meta)


class _Singular(Exception):
    """Raised inside the polish of :func:`_maximise` at a point where the measure is not finite
    (it stops there: the optimiser is not fed inf or NaN)."""

    def __init__(self, r: float, z: float) -> None:
        super().__init__(r, z)
        self.r, self.z = r, z


def normal_max_stress(state, kind: str = "von_mises", body: Any = 1) -> StressMaximum:
    """Implementation of ``NormalState.max_stress``."""
    if kind not in KINDS:
        raise ParameterError(f"kind={kind!r} is invalid: choose one of "
                             f"{', '.join(repr(k) for k in KINDS)}.")
    body_poisson_ratio(state.contact, body)
    meta = {"body": body, "citations": NORMAL_SOURCES}
    a = float(np.asarray(state._radius))
    if state.shape != ():
        raise NotSupportedError("max_stress() needs a single state.")
    if a <= 0:
        return StressMaximum(0.0, 0.0, 0.0, kind, meta)
    return _maximise(lambda r, z: normal_stress(state, r, z, body), kind, a, meta)


def _field_grid(grid: Any, a: float) -> tuple[np.ndarray, np.ndarray]:
    """The ``(R, Z)`` mesh of ``stress_field``: ``grid = (r_values, z_values)`` or, for None, 200
    radii over ``[0, 2a]`` by 100 depths over ``[0, 1.5a]``."""
    if grid is None:
        if a <= 0:
            raise ParameterError("stress_field() without grid= needs a contact (radius > 0).")
        rv, zv = np.linspace(0.0, 2.0 * a, 200), np.linspace(0.0, 1.5 * a, 100)
    else:
        try:
            rv, zv = grid
        except (TypeError, ValueError) as err:
            raise ParameterError(f"grid={grid!r} is invalid: give (r_values, z_values).") from err
        rv, zv = as_float_array("grid r", rv).ravel(), as_float_array("grid z", zv).ravel()
    check_stress_memory("stress_field()", float(rv.size) * float(zv.size), superposed=False)
    R, Z = np.meshgrid(rv, zv, indexing="xy")
    return R, Z


def normal_stress_field(state, grid: Any = None, body: Any = 1) -> StressField:
    """Implementation of ``NormalState.stress_field``: the field on a 2D ``(r, z)`` grid.

    ``grid`` is ``(r_values, z_values)`` (1D arrays, m) or ``None`` for 200 radii over
    ``[0, 2a]`` by 100 depths over ``[0, 1.5a]``.
    """
    a = float(np.asarray(state._radius)) if state.shape == () else 0.0
    R, Z = _field_grid(grid, a)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ValidityWarning)
        return normal_stress(state, R, Z, body)


# ====================================================================== torsion
#: Chebyshev points for the twist density Φ' = -ψ'(x) on the slip annulus (and half as many for
#: its error estimate); the lag ψ is interpolated in ln x, where the logarithmic growth of
#: Jäger's slip function towards small radii is smooth
TWIST_DENSITY_POINTS = 48
#: at full sliding the twisted punches narrower than this fraction of the contact radius are
#: left out (the lag grows like ln x towards the axis: its Chebyshev interpolant in ln x spans
#: ln(1e6)); the torque they carry is O(1e-18) of the sliding torque
FULL_SLIDING_CORE = 1e-6


def _twist_density(lag, c: float, a: float):
    """``Φ'(x) = -dψ/dx`` on ``[c, a]`` from the lag ``ψ(x) = φ - Φ(x)`` (a callable on arrays):
    Chebyshev interpolation of ``ψ`` in ``s = ln x`` at :data:`TWIST_DENSITY_POINTS` points,
    differentiated; returns ``(density, error)`` callables (the error: the difference to the
    interpolant on half as many points)."""
    from numpy.polynomial import chebyshev as C
    lo, hi = np.log(c), np.log(a)

    def fit(n: int) -> np.ndarray:
        k = np.arange(n)
        u = np.cos(np.pi * (k + 0.5) / n)                       # first-kind points
        x = np.exp(lo + (hi - lo) * 0.5 * (u + 1.0))
        return C.chebder(C.chebfit(u, lag(x), n - 1)) * (2.0 / (hi - lo))

    d_full, d_half = fit(TWIST_DENSITY_POINTS), fit(TWIST_DENSITY_POINTS // 2)

    def at(coef: np.ndarray, x: np.ndarray) -> np.ndarray:
        inside = (x > c) & (x < a)
        u = np.clip(2.0 * (np.log(np.where(inside, x, c)) - lo) / (hi - lo) - 1.0, -1.0, 1.0)
        return np.where(inside, -C.chebval(u, coef) / np.where(inside, x, 1.0), 0.0)

    return (lambda x: at(d_full, x)), (lambda x: np.abs(at(d_full, x) - at(d_half, x)))


def _torsion_density(state, stick: float | None = None):
    """``(lag, density, density_error)`` of a single partial-slip torsion state (on
    ``[stick, a]``, by default the state's stick radius)."""
    from ..physics.torsion import METHODS
    ct = state.contact
    model = METHODS[state.method](ct.profile, ct.moduli.normal, ct.moduli.torsional,
                                  ct.friction, ct.rtol)
    psi = model.psi(np.array([float(state._a)]), np.array([float(state._d)]),
                    np.array([float(state._g_a)]))
    idx = np.array([0])

    def lag(x: np.ndarray) -> np.ndarray:
        return psi(np.asarray(x, float)[None, :], idx)[0]

    c = float(state._stick) if stick is None else stick
    return (lag, *_twist_density(lag, c, float(state._a)))


def torsion_stress(state, r: Any, z: Any, body: Any = 1, part: str = "total",
                   _density: Any = None) -> StressField:
    """Field of a torsion state (implementation of ``TorsionState.stress``; ``_density`` is the
    cached :func:`_torsion_density` of the state)."""
    if part not in ("total", "friction"):
        raise ParameterError(f"part={part!r} is invalid: choose 'total' (normal preload "
                             "included) or 'friction' (the torsional part alone).")
    nu = body_poisson_ratio(state.contact, body)
    r, z = _points(r, z)
    check_stress_memory("stress()", r.size)
    if state.shape != ():
        raise NotSupportedError(f"stress() needs a single state, this one has shape "
                                f"{state.shape}: index the twists or call torsion() per load.")
    ct = state.contact
    G = ct.moduli.torsional
    phi = float(state._twist)
    a, c = float(state._a), float(state._stick)
    sign = (1.0 if body == 1 else -1.0) * np.sign(phi)
    phi = abs(phi)
    R, Z = r.ravel(), z.ravel()
    k = 4.0 * G / np.pi
    zero = np.zeros(R.shape)
    sliding = not np.isfinite(phi)
    if sliding:
        # full sliding, τ = μp: the slip annulus reaching the axis; the twisted punches narrower
        # than FULL_SLIDING_CORE·a are left out (their traction sits on that disc; its effect
        # is added to the estimate below)
        c = FULL_SLIDING_CORE * a
    if a <= 0 or phi == 0:
        stz, srt, err = zero, zero, zero
        route = "torsion: none"
    elif state.method == "no-slip" or c >= a:
        stz, srt = (k * phi * v for v in _st.twist_kernel(R, Z, a))
        err = 4e-15 * (np.abs(stz) + np.abs(srt))
        route = "torsion: twisted punch"
    else:
        lag, dens, dens_err = (_density if _density is not None else
                               _torsion_density(state, c if sliding else None))
        (stz, srt), err = _st.superposed_field(R, Z, np.full(R.shape, a), zero, dens, 0.0, nu,
                                               (c,), dens_err, None, _st.twist_kernel, k)
        edge = float(lag(np.array([a * (1 - 1e-15)]))[0])
        ref = abs(float(lag(np.array([c]))[0])) if sliding else phi
        # a lag left at the rim (flat punch; MDR with d != g(a)) is a twisted punch of radius a;
        # a smooth non-adhesive profile's lag vanishes there (to rounding: not an edge term)
        if sliding:
            # the left-out core: at most μp there, its torque's field falling as (c/ρ)³
            p_core = float(np.max(np.asarray(state.normal.pressure(np.array([0.5 * c, c]))
                                             if state.normal.shape == () else
                                             _one_normal(state).pressure(
                                                 np.array([0.5 * c, c])), float)))
            rho = np.maximum(np.hypot(R, Z), c)
            err = err + 2.0 * ct.friction * p_core * (c / rho) ** 3
            route_extra = " at full sliding"
        else:
            route_extra = ""
        if abs(edge) > 1e-9 * ref:
            e_tz, e_rt = _st.twist_kernel(R, Z, a)
            stz, srt = stz + k * edge * e_tz, srt + k * edge * e_rt
        route = f"torsion: superposition ({state.method}){route_extra}"
    stz, srt = sign * stz, sign * srt
    if part == "total":
        base = normal_stress(state.normal if state.normal.shape == () else _one_normal(state),
                             r, z, body)
        comps = (base.srr, base.stt, base.szz, base.srz)
        err = np.asarray(err).reshape(r.shape) + base.error
        route = f"{base.meta['route']} + {route}"
    else:
        comps = (np.zeros(r.shape),) * 4
        err = np.asarray(err).reshape(r.shape)
    stz, srt = stz.reshape(r.shape), srt.reshape(r.shape)
    singular = ~(np.isfinite(stz) & np.isfinite(srt))
    err = np.where(singular, np.inf, err)
    mags = np.abs(np.stack([*comps, stz, srt]))
    fin = np.all(np.isfinite(mags), axis=0)
    top = np.max(mags[:, fin], initial=0.0)
    rel = float(np.max(err[fin], initial=0.0) / top) if top > 0 else 0.0
    return StressField(r, z, *comps, stz, srt, err,
                       {"route": route, "body": body, "nu": nu, "error_estimate": rel,
                        "part": part, "citations": TORSION_SOURCES})


def _one_normal(state):
    """The normal preload of a single torsion state as a single NormalState."""
    n = state.normal
    return type(n)(n.contact, np.float64(state._d), np.float64(state._a),
                       np.float64(np.ravel(n._force)[0]), dict(n.meta))


def torsion_max_stress(state, kind: str = "von_mises", body: Any = 1) -> StressMaximum:
    """Implementation of ``TorsionState.max_stress`` (the whole state's field)."""
    if kind not in KINDS:
        raise ParameterError(f"kind={kind!r} is invalid: choose one of "
                             f"{', '.join(repr(k) for k in KINDS)}.")
    body_poisson_ratio(state.contact, body)
    if state.shape != ():
        raise NotSupportedError("max_stress() needs a single state.")
    a = float(state._a)
    meta = {"body": body, "citations": TORSION_SOURCES}
    if a <= 0:
        return StressMaximum(0.0, 0.0, 0.0, kind, meta)
    partial = (state.method != "no-slip" and 0 < float(state._stick) < a
               and np.isfinite(float(state._twist)) and float(state._twist) != 0)
    sliding = state.method != "no-slip" and not np.isfinite(float(state._twist))
    dens = (_torsion_density(state) if partial else
            _torsion_density(state, FULL_SLIDING_CORE * a) if sliding else None)
    return _maximise(lambda r, z: torsion_stress(state, r, z, body, "total", dens), kind, a, meta)


def torsion_stress_field(state, grid: Any = None, body: Any = 1, part: str = "total"
                         ) -> StressField:
    """Implementation of ``TorsionState.stress_field`` (see :func:`normal_stress_field`)."""
    a = float(state._a) if state.shape == () else 0.0
    R, Z = _field_grid(grid, a)
    return torsion_stress(state, R, Z, body, part)
