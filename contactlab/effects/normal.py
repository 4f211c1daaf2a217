"""Normal contact: the driver behind :meth:`Contact.normal` and its result, :class:`NormalState`.

The kernels (force, radius and depth solves, pressure, displacement) are in
:mod:`contactlab.physics.normal`; adhesive contacts have their own driver in
:mod:`contactlab.effects.adhesion`.
Field quantities of a state are computed lazily, on request.
"""
from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field
from functools import cached_property
from typing import Any

import numpy as np

from ..citations import Cited, sources_for
from ..errors import (
    NotSupportedError,
    OutsideTheoryError,
    ParameterError,
    ValidityWarning,
)
from ..numeric.powers import root_of_ratio_float
from ..params import as_float_array, exactly_one, scalar_or_array
from ..physics import normal as _normal
from ..physics import normal_scalar as _scalar
from ..physics import normal_table_scalar as _table
from ..physics.normal_fused import FORCE_SANITY
from ._protocol import Result
from .sizes import (FIELD_BYTES_PER_POINT, NORMAL_BYTES_PER_LOAD, PEAK_RADII, check_elements,
                    check_field, check_peak, route_kind)

__all__ = ["NormalState", "normal", "warn_outside_validity", "warn_cone_tip",
           "outside_validity_note", "STATE_UNITS"]

#: units of the columns of a normal state (CSV headers)
STATE_UNITS = {"depth": "m", "radius": "m", "force": "N", "stiffness": "N/m"}


def outside_validity_note(profile, a: Any) -> str | None:
    """The text of :func:`warn_outside_validity` for contact radii ``a`` (None within range)."""
    limit = profile.validity_radius
    if not np.isfinite(limit):
        return None
    arr = np.asarray(a)
    if arr.size == 0:
        return None
    top = float(np.max(arr))            # one reduction (a NaN among them: the mask decides)
    if top > limit or (top != top and bool(np.any(arr > limit))):
        return (f"contact radius {float(np.nanmax(arr))!r} m of {profile!r} exceeds "
                f"{limit!r} m, the range of the half-space theory for this profile; the "
                "result is the half-space solution, not that of the real body.")
    return None


def warn_outside_validity(profile, a: float | np.ndarray, stacklevel: int = 3) -> None:
    """:class:`ValidityWarning` if a contact radius exceeds ``profile.validity_radius``."""
    note = outside_validity_note(profile, a)
    if note is not None:
        warnings.warn(note, ValidityWarning, stacklevel=stacklevel)

def warn_cone_tip(profile, value: np.ndarray, stacklevel: int = 3) -> None:
    """:class:`ValidityWarning` when an infinite pressure comes from the cone tip of a linear
    table (first segment not flat): real for that geometry, so it is said, with the smooth
    alternative."""
    if (profile.has("linear_table") and hasattr(profile, "table_axis_slope")
            and profile.table_axis_slope() != 0 and np.any(np.isposinf(value))):
        warnings.warn(
            f"{profile!r}: the linear interpolant's first segment is not flat (slope "
            f"{profile.table_axis_slope():.6g} on the axis), a cone tip whose pressure is "
            "logarithmically infinite at r = 0, so the peak pressure is inf. For the surface "
            "a smooth measured body has there, f'(0) = 0, use interpolation='cubic' (and "
            "smoothing='auto' for noisy data); or read pressure(r) at r > 0.",
            ValidityWarning, stacklevel=stacklevel)


_SCALARS = (float, int, np.float64)
#: sources of a normal-contact result (see :mod:`contactlab.citations`)
_SOURCES = sources_for("normal")


#: relative rounding floor of pressures computed from a quadrature-route g (benchmarks/
#: accuracy_cost.py measured up to 2e-12 at rtol <= 1e-12; since the deeper tanh-sinh truncation
#: (quadrature._T_MAX = 4.5) f' ~ r^-1/2 (n = 0.5) reaches 8.7e-12 at rtol 1e-12 and 1.1e-11 at
#: 1e-13, which the old floor 1e-11 under-estimated at 1e-13)
NESTED_ROUNDING = 3e-11


def _scalar_or_array(v: np.ndarray) -> Any:
    if type(v) is np.float64:           # the scalar fast path stores numpy float scalars
        return float(v)
    return scalar_or_array(np.asarray(v, dtype=float))


class LazyMeta(dict):
    """A result's ``meta`` dict whose ``"error_estimate"`` is computed on first read.

    ``pending`` is a callable returning the value; any read of the dict (item, ``get``, ``in``,
    iteration, ``repr``, ...) computes it once. The value is a pure function of the result, so
    when it is computed changes no bit of it.
    """

    __slots__ = ("_pending", "checked", "residual")

    def __init__(self, base: dict, pending: Any, *args: Any) -> None:
        dict.__init__(self, base)
        self._pending: tuple[Any, tuple[Any, ...]] | None = (pending, args)
        #: ``|F - force|`` of a batched force-controlled solve (its request check), or None
        self.residual: np.ndarray | None = None
        #: True where a compiled force solve made the driver's checks on its way (every
        #: force finite and within _FORCE_SANITY of its request)
        self.checked = False

    def _resolve(self) -> None:
        pending = self._pending
        if pending is not None:
            dict.__setitem__(self, "error_estimate", pending[0](*pending[1]))
            self._pending = None

    def __getitem__(self, key: Any) -> Any:
        self._resolve()
        return dict.__getitem__(self, key)

    def get(self, key: Any, default: Any = None) -> Any:
        self._resolve()
        return dict.get(self, key, default)

    def __contains__(self, key: object) -> bool:
        self._resolve()
        return dict.__contains__(self, key)

    def __iter__(self):
        self._resolve()
        return dict.__iter__(self)

    def __len__(self) -> int:
        self._resolve()
        return dict.__len__(self)

    def __repr__(self) -> str:
        self._resolve()
        return dict.__repr__(self)

    def __eq__(self, other: object) -> bool:
        self._resolve()
        return dict.__eq__(self, other)

    __hash__ = None

    def keys(self):
        self._resolve()
        return dict.keys(self)

    def values(self):
        self._resolve()
        return dict.values(self)

    def items(self):
        self._resolve()
        return dict.items(self)

    def copy(self) -> dict:
        self._resolve()
        return dict(dict.items(self))

    def __reduce__(self):
        self._resolve()
        return (dict, (dict(dict.items(self)),))


_new_state = object.__new__
_f64 = np.float64


def _fast_normal(contact, key: str, value: Any) -> NormalState | None:
    """One finite depth or force on a profile with scalar forms: plain floats, no arrays.

    ``None`` when the profile has no scalar route (the array route then runs). The force's error
    estimate is computed only when it is read (:class:`LazyMeta`).
    """
    prof = contact.profile
    forms = prof.__dict__.get("_scalar_normal_forms", False)
    if forms is False:
        forms = _scalar.forms_of(prof)
    if forms is None:
        if _scalar.quadrature_scalar_ok(prof):
            return _fast_normal_quadrature(contact, key, value)
        if key == "depth" and _table.table_scalar_ok(prof):
            return _fast_normal_table(contact, value)
        return None
    v = float(value)
    if not math.isfinite(v):
        return None                     # the array route names the bad value
    E = contact.moduli.normal
    rtol = contact.rtol
    if key == "depth":
        if v > 0:
            a = _scalar.solve_depth(prof, forms, v, rtol)
            d = v
        else:
            a, d = 0.0, v
    elif v > 0:
        hertz = forms.force_constants
        if hertz is not None:
            # a paraboloid: a = cbrt(F/K), d = g(a) (the array route's operations,
            # _scalar.solve_force's), the force the request itself; the residual of (a, d),
            # |(a·d)·c - F|, checked here and carried by the estimate (read lazily, with ∫g)
            K, c_f = hertz(E)
            a = root_of_ratio_float(v, K, 3.0)
            d = forms.g(a)
            F = v
            if not abs(a * d * c_f - v) <= _FORCE_SANITY * v:
                raise FloatingPointError("inconsistent state")
            if a > forms.validity:
                warn_outside_validity(prof, a, stacklevel=5)
            meta = LazyMeta({"routes": {"g": forms.route}, "rtol": rtol, "control": key,
                             "citations": _SOURCES},
                            _scalar.hertz_force_rel_error, forms, E, a, d, F, c_f)
            state = _new_state(NormalState)
            state.__dict__.update(contact=contact, _depth=_f64(d), _radius=_f64(a),
                                  _force=_f64(F), meta=meta)
            return state
        a, d = _scalar.solve_force(prof, forms, E, v, rtol)
    else:
        a, d = 0.0, 0.0
    if a > forms.validity:
        warn_outside_validity(prof, a, stacklevel=5)
    if a > 0:
        g_int = forms.g_integral(a)
        F = (a * d - g_int) * (2.0 * E)
    else:
        g_int = F = 0.0
    meta = LazyMeta({"routes": {"g": forms.route}, "rtol": rtol, "control": key,
                     "citations": _SOURCES},
                    _scalar.force_rel_error, E, a, d, g_int, F, v if key == "force" else None)
    # (the dataclass __init__ and its frozen setattr cost more than the solve: fill the fields)
    state = _new_state(NormalState)
    # numpy float scalars: they act as 0-d arrays in every state method, at half the cost
    state.__dict__.update(contact=contact, _depth=_f64(d), _radius=_f64(a), _force=_f64(F),
                          meta=meta)
    return state


def _fast_normal_quadrature(contact, key: str, value: Any) -> NormalState | None:
    """One finite positive depth or force on a profile whose g goes by quadrature: the contact
    radius (and depth) by :func:`contactlab.physics.normal_scalar.solve_depth_quadrature` or
    :func:`~contactlab.physics.normal_scalar.solve_force_quadrature` (the array route's, bit for
    bit), then ``∫g`` with its error and the force as :func:`contactlab.physics.normal.solve`
    forms them. ``None`` (the array route) otherwise."""
    prof = contact.profile
    v = float(value)
    if not (math.isfinite(v) and v > 0):
        return None
    rtol = contact.rtol
    E = contact.moduli.normal
    try:
        # as the array route runs (normal()): an overflow raises, and the array route then
        # reports it
        with np.errstate(over="raise"):
            if key == "depth":
                a = _scalar.solve_depth_quadrature(prof, v, rtol)
                d = v
                if a is None or not a > 0:
                    return None
                g_int, g_int_err = _scalar.g_integral_one(prof, a, rtol,
                                                          _scalar._lean(prof, rtol))
            else:
                # (∫g at the radius from the root's own force evaluation: the same bits)
                got = _scalar.solve_force_quadrature(prof, E, v, rtol)
                if got is None:
                    return None
                a, d, g_int, g_int_err = got
    except FloatingPointError:
        return None
    warn_outside_validity(prof, np.array(a), stacklevel=6)
    F = (a * d - g_int) * (2.0 * E)
    meta = LazyMeta({"routes": {"g": prof.g_route}, "rtol": rtol, "control": key,
                     "citations": _SOURCES},
                    _scalar.quadrature_force_rel_error, E, a, d, g_int, g_int_err, F,
                    v if key == "force" else None)
    state = _new_state(NormalState)
    state.__dict__.update(contact=contact, _depth=_f64(d), _radius=_f64(a), _force=_f64(F),
                          meta=meta)
    return state


def _fast_normal_table(contact, value: Any) -> NormalState | None:
    """One finite positive depth on a small linear table: the radius by
    :func:`contactlab.physics.normal_table_scalar.solve_depth_table`, ``∫g``, the force and its
    error estimate as :func:`contactlab.physics.normal.solve` forms them (the array route's
    bits); ``None`` (the array route) otherwise."""
    prof = contact.profile
    d = float(value)
    if not (math.isfinite(d) and d > 0):
        return None
    rtol = contact.rtol
    a = _table.solve_depth_table(prof, d, rtol)
    if a is None:
        return None
    E = contact.moduli.normal
    g_int = _table.g_integral_table(prof, a)
    F = (a * d - g_int) * (2.0 * E)
    if not F > 0:
        return None
    warn_outside_validity(prof, np.array(a), stacklevel=5)
    meta = LazyMeta({"routes": {"g": prof.g_route}, "rtol": rtol, "control": "depth",
                     "citations": _SOURCES},
                    _table.table_force_rel_error, E, a, d, g_int, F)
    state = _new_state(NormalState)
    state.__dict__.update(contact=contact, _depth=_f64(d), _radius=_f64(a), _force=_f64(F),
                          meta=meta)
    return state


#: a force-controlled state whose force is further than this (relative) from the request is not a
#: solution but a numerical breakdown (overflow): raised, never returned. Smaller residuals of the
#: radius solve are reported by the state's error estimate (measured up to 1.4e-8 next to a
#: truncated profile's rim).
_FORCE_SANITY = FORCE_SANITY


def normal(contact, *, depth: Any = None, force: Any = None, radius: Any = None,
           branch: str = "stable") -> NormalState:
    """Driver of :meth:`contactlab.Contact.normal` for non-adhesive contacts (see there for the
    parameters; adhesive contacts go to :func:`contactlab.effects.adhesion.adhesive_normal`).

    A state whose numbers leave double precision (lengths of 1e100 m, say) raises
    :class:`~contactlab.errors.OutsideTheoryError` instead of returning inf or NaN.
    """
    try:
        if (radius is None and branch == "stable" and (depth is None) != (force is None)
                and type(depth if force is None else force) in _SCALARS
                and not contact.work_of_adhesion):
            value = depth if force is None else force
            state = _fast_normal(contact, "depth" if force is None else "force", value)
            if state is not None:           # plain floats: overflow gives inf (or raises)
                F = state._force
                if not math.isfinite(F + state._depth + state._radius) or (
                        force is not None and force > 0 and not abs(F - force) <= _FORCE_SANITY * force):
                    raise FloatingPointError("non-finite or inconsistent state")
                return state
        with np.errstate(over="raise"):
            state = _normal_state(contact, depth, force, radius, branch)
        F, d, a = (np.asarray(v, float) for v in (state._force, state._depth, state._radius))
        if not getattr(state.meta, "checked", False) and (
                not _finite_state(F, d, a) or (force is not None and not _carries_request(
                    F, force, getattr(state.meta, "residual", None)))):
            raise FloatingPointError("non-finite or inconsistent state")
        if isinstance(state.meta, LazyMeta):
            state.meta.residual = None          # (read: the state does not keep them)
            state.meta.checked = False
        return state
    except (FloatingPointError, OverflowError) as err:
        given = {k: v for k, v in (("depth", depth), ("force", force), ("radius", radius))
                 if v is not None}
        raise OutsideTheoryError(
            f"normal({', '.join(f'{k}={v!r}' for k, v in given.items())}) of {contact.profile!r} "
            "overflows double precision: the problem's scales are too far apart (check the units "
            "of the profile parameters, moduli and loads; SI: m, Pa, N).") from err


def _finite_state(F: np.ndarray, d: np.ndarray, a: np.ndarray) -> bool:
    """Whether ``F + d + a`` is finite everywhere: by the extremes of each array (a NaN
    propagates through min and max), instead of a sum, a mask and its test.

    Where every radius is positive (and none NaN), three reductions decide: the solve computed
    ``F = 2E* (a d - ∫g)`` from these very ``a`` and ``d`` with no mask, and a non-finite ``a``
    or ``d`` there leaves ``a·d`` non-finite (``inf·0`` and ``inf - inf`` are NaN), hence ``F``.
    """
    if F.size == 0:
        return True
    if F.shape == a.shape == d.shape and F.ndim and float(a.min()) > 0:
        lo, hi = float(F.min()), float(F.max())
        if math.isfinite(lo) and math.isfinite(hi):
            return True
    hi = float(F.max()) + float(d.max()) + float(a.max())
    lo = float(F.min()) + float(d.min()) + float(a.min())
    if math.isfinite(hi) and math.isfinite(lo):
        return True
    return bool(np.all(np.isfinite(F + d + a)))


def _carries_request(F: np.ndarray, force: Any, residual: np.ndarray | None = None) -> bool:
    """Whether every positive requested force is met to :data:`_FORCE_SANITY` (relative).

    ``residual``: ``|F - force|`` when the solve kept it. The largest residual against the
    smallest request accepts at once (two reductions); otherwise every force is checked."""
    req = np.broadcast_to(np.asarray(force, float), F.shape)
    if req.size and F.ndim and float(req.min()) > 0:
        dev = residual if residual is not None else np.abs(F - req)
        if float(dev.max()) <= _FORCE_SANITY * float(req.min()):
            return True
        return bool(np.all(dev <= _FORCE_SANITY * req))
    return not bool(np.any((req > 0) & ~(np.abs(F - req) <= _FORCE_SANITY * req)))


def _normal_state(contact, depth: Any, force: Any, radius: Any, branch: str) -> NormalState:
    """The array route of :func:`normal` (validation, the kernel, the state)."""
    key, value = exactly_one("normal()", {"depth": depth, "force": force, "radius": radius})
    if branch != "stable":
        raise ParameterError(f"branch={branch!r} is invalid without adhesion: a non-adhesive "
                             "contact has a single equilibrium (use branch='stable').")
    extremes = None
    if key == "force" and isinstance(value, np.ndarray) and value.size:
        # the finiteness check's two reductions, kept for the force solve (a paraboloid's
        # passes decide their range from them: normal_fused.paraboloid_force)
        arr = as_float_array(key, value, allow_nan=True)
        extremes = (float(arr.min()), float(arr.max()))
        if not (math.isfinite(extremes[0]) and math.isfinite(extremes[1])):
            as_float_array(key, arr)            # raises, naming the first bad value
    else:
        arr = as_float_array(key, value)
    prof = contact.profile
    check_elements("normal()", arr.size, NORMAL_BYTES_PER_LOAD[route_kind(prof)],
                   f"{key} {arr.shape}")
    if key == "radius":
        if np.any(arr < 0):
            raise ParameterError(f"radius contains {float(arr[arr < 0].ravel()[0])!r}: contact "
                                 "radii must be >= 0 m.")
        if np.isfinite(prof.wall_radius):
            raise NotSupportedError(
                f"radius= does not determine the state of {prof!r}: its contact radius is "
                "fixed by the punch wall. Give depth= or force=.")
        if np.any(arr >= prof.max_radius):
            raise OutsideTheoryError(f"radius={float(np.max(arr))!r} m is invalid: it must stay "
                                     f"below max_radius={prof.max_radius!r} m of {prof!r}.")
    d, a, F, rel = _normal.solve(prof, contact.moduli.normal, key, arr, contact.rtol,
                                 error_estimate="lazy", extremes=extremes)
    warn_outside_validity(prof, a, stacklevel=4)
    base = {"routes": {"g": prof.g_route}, "rtol": contact.rtol, "control": key,
            "citations": _SOURCES}
    meta: dict
    if callable(rel):       # exact routes: the estimate is computed when it is first read
        meta = LazyMeta(base, _estimate_value, rel)
        meta.residual = getattr(rel, "residual", None)   # |F - force| for the caller's check
        meta.checked = getattr(rel, "checked", False)
    else:
        meta = {**base, "error_estimate": _estimate_value(lambda: rel)}
    return NormalState(contact, d, a, F, meta)


def _estimate_value(pending: Any) -> Any:
    rel = pending()
    return float(rel) if rel.ndim == 0 else rel


@dataclass(frozen=True, eq=False)
class NormalState(Result, Cited):
    """State of a normal contact (one load or an array of loads).

    Attributes
    ----------
    depth : float or ndarray
        Indentation depth ``d``, m.
    radius : float or ndarray
        Contact radius ``a``, m.
    force : float or ndarray
        Normal force ``F_N``, N (compressive > 0).
    stiffness : float or ndarray
        Incremental normal stiffness ``dF/dd = 2E* a``, N/m.
    meta : dict
        ``routes`` (numerical route per quantity), ``rtol``, ``error_estimate`` (relative, force).
    model_error : float
        0.0: the MDR normal solution is exact [Sn65].
    notes : tuple of str
        The validity warning of a contact radius beyond the profile's half-space range, if any.

    Notes
    -----
    Field methods (:meth:`pressure`, :meth:`displacement`) take radii ``r`` and return an array of
    shape ``state.shape + r.shape``.
    """

    contact: Any = field(repr=False)
    _depth: np.ndarray = field(repr=False)
    _radius: np.ndarray = field(repr=False)
    _force: np.ndarray = field(repr=False)
    meta: dict = field(default_factory=dict, repr=False)

    units = STATE_UNITS

    def __repr__(self) -> str:
        return self._summary_repr()

    def to_dict(self) -> dict[str, Any]:
        """``depth``, ``radius``, ``force`` and ``stiffness`` (scalars or arrays of the state's
        shape)."""
        return {"depth": self.depth, "radius": self.radius, "force": self.force,
                "stiffness": self.stiffness}

    @property
    def notes(self) -> tuple[str, ...]:
        """Warnings of this state (the half-space range of the profile), as text."""
        base = tuple(self.meta.get("notes", ())) if isinstance(self.meta, dict) else ()
        note = outside_validity_note(self.contact.profile, self._radius)
        return base + ((note,) if note is not None and note not in base else ())

    @property
    def shape(self) -> tuple[int, ...]:
        """Shape of the load array (``()`` for a single load)."""
        return np.shape(self._depth)

    @property
    def depth(self) -> Any:
        return _scalar_or_array(self._depth)

    @property
    def radius(self) -> Any:
        return _scalar_or_array(self._radius)

    @property
    def force(self) -> Any:
        return _scalar_or_array(self._force)

    @property
    def stiffness(self) -> Any:
        return _scalar_or_array(2.0 * self.contact.moduli.normal * self._radius)

    @cached_property
    def _g_at_radius(self) -> np.ndarray:
        return np.where(self._radius > 0, self.contact.profile._g(self._radius, self.contact.rtol),
                        0.0)

    @cached_property
    def elastic_energy(self) -> Any:
        """Elastic energy stored in the contact, J (``∫ F dd`` for non-adhesive contacts)."""
        prof = self.contact.profile
        a = self._radius
        g_int = prof._g_integral(a, self.contact.rtol)
        g2 = _normal.g_squared_integral(prof, a, self.contact.rtol)
        return _scalar_or_array(_normal.elastic_energy(self.contact.moduli.normal, a, self._depth,
                                                       g_int, g2))

    @cached_property
    def _edge_g(self) -> np.ndarray:
        """The ``g(a)`` the pressure's edge term ``(d - g(a))/sqrt(a² - r²)`` is judged against.

        A non-adhesive contact has no edge term where ``d = g(a)`` up to rounding (``d = g(a)``
        defines its radius): the depth itself is returned there, so the term is exactly 0 and
        not the difference of a root solve's two ends (which left ``±inf`` at the edge and in
        :attr:`peak_pressure`). The term is kept where ``d - g(a)`` exceeds the rounding of the
        depth solve and the error of ``g(a)``: a contact pinned at a punch wall (``d - g(b) >
        0``, physics), and a radius the float cannot place finely enough where ``g`` is steep
        (next to the rim of a truncated profile, ``g(a)`` then errs while the depth is accurate:
        the term carries the difference, as the superposition of flat punches does).
        """
        prof = self.contact.profile
        d = np.asarray(self._depth, dtype=float)
        a = np.asarray(self._radius, dtype=float)
        if not np.any(a > 0):
            return d
        from ..profiles.base import ROUNDING
        g = np.asarray(self._g_at_radius, dtype=float)
        _, g_err = prof._g_with_error(np.maximum(a, 1e-300), self.contact.rtol)
        tol = 8 * ROUNDING * (np.abs(d) + np.abs(g)) + np.abs(g_err)
        return np.where((a > 0) & (np.abs(d - g) > tol), g, d)

    @property
    def _edge_at_wall(self) -> np.ndarray:
        """Where the contact edge sits at a punch wall (its edge term a real singularity)."""
        a = np.asarray(self._radius, dtype=float)
        return (a > 0) & (a >= self.contact.profile.wall_radius)

    def _field_args(self, r: Any, what: str) -> tuple[np.ndarray, ...]:
        r = as_float_array("r", r)
        check_field(what, self.shape, r.shape,
                    FIELD_BYTES_PER_POINT[route_kind(self.contact.profile)])
        if np.any(r < 0):
            raise ParameterError(f"r contains {r[r < 0].ravel()[0]!r}: radii must be >= 0 m.")
        sh = self.shape
        a = self._radius.reshape(sh + (1,) * r.ndim)
        d = self._depth.reshape(sh + (1,) * r.ndim)
        ga = np.asarray(self._edge_g).reshape(sh + (1,) * r.ndim)
        return r, a, d, ga

    def pressure(self, r: Any, return_error: bool = False) -> Any:
        """Contact pressure ``p(r)``, Pa, at radii ``r`` (m); 0 outside the contact.

        Singular points return ``inf`` (the flat-punch edge, the centre of a cone or of a power
        law with ``n < 1``, the axis of a linear table whose first segment is not flat, and
        each node of a linear table where its slope jumps).

        Parameters
        ----------
        r : array_like
            Radii, m (>= 0).
        return_error : bool
            Also return an absolute error estimate, Pa, of the same shape: the quadrature
            estimate of the pressure integral (plus the tolerance of a quadrature-route g), a
            rounding floor, and the effect of the contact-radius error
            (:attr:`error_estimates`) through ``∂p/∂a ≈ p a/(a²-r²)``. It is ``inf`` at
            singular points and grows towards the contact edge.

        Returns
        -------
        p : float or ndarray
            Pressure, Pa (shape ``state.shape + r.shape``).
        error : float or ndarray
            Only with ``return_error=True``.
        """
        r, a, d, ga = self._field_args(r, "pressure()")
        prof = self.contact.profile
        E = self.contact.moduli.normal
        rtol = self.contact.rtol
        val, err = _normal.pressure(prof, E, r, a, d, ga, rtol)
        if not return_error:
            return _scalar_or_array(val)
        from ..profiles.base import ROUNDING
        r_b, a_b = np.broadcast_arrays(r, a)
        inner = 0.0
        if prof.g_route == "quadrature":
            # the tolerance of g itself, carried by S ∝ g, and the rounding floor of the nested
            # by-parts route (differences g(x) - g(r) over sinh²u), measured at ~2e-12 relative
            inner = (rtol + NESTED_ROUNDING) * np.abs(val)
        da = np.asarray(self.error_estimates["radius"]).reshape(a.shape) * a
        with np.errstate(divide="ignore", invalid="ignore"):
            edge = np.where(r_b < a_b, 2.0 * np.abs(val) * a_b * da / ((a_b - r_b) * (a_b + r_b)),
                            0.0)
        total = np.abs(err) + inner + 4 * ROUNDING * np.abs(val) + np.nan_to_num(edge, nan=np.inf)
        total = np.where(np.isfinite(val), total, np.inf)
        return _scalar_or_array(val), _scalar_or_array(total)

    @property
    def error_estimate(self) -> Any:
        """Estimated relative error of :attr:`force` (also ``meta["error_estimate"]``).

        For force control it includes the residual against the requested force.
        """
        return self.meta.get("error_estimate", 0.0)

    @cached_property
    def error_estimates(self) -> dict[str, Any]:
        """Estimated relative errors ``{"force", "radius", "depth"}`` of this state.

        The radius error combines the root-finder bracket width and the error of ``g`` (or of
        ``F(a)`` under force control) divided by the local slope, found by a central difference
        of g (two extra evaluations of g, done on first access only).
        """
        from ..profiles.base import ROUNDING, root_rtol
        prof = self.contact.profile
        rtol = self.contact.rtol
        E = self.contact.moduli.normal
        a = self._radius
        control = self.meta.get("control", "depth")
        rel_F = np.asarray(self.meta.get("error_estimate", 0.0), dtype=float) * np.ones(a.shape)
        pos = a > 0
        rel_a = np.zeros(a.shape)
        rel_d = np.zeros(a.shape)
        if np.any(pos):
            ap = a[pos]
            g, g_err = prof._g_with_error(ap, rtol)
            h = 1e-4 * ap
            at_wall = ap >= prof.wall_radius
            lo = np.maximum(ap - h, 0.0)
            hi = np.where(ap + h < prof.max_radius, ap + h, ap)
            with np.errstate(invalid="ignore", divide="ignore"):
                slope_a = ap * (prof._g(hi, rtol) - prof._g(lo, rtol)) / (hi - lo)  # a g'(a)
            slope_a = np.where(np.isfinite(slope_a) & (slope_a > 0), slope_a, np.inf)
            roots = root_rtol(rtol)
            if control == "force":
                F_abs = rel_F[pos] * np.abs(self._force[pos]) + 2 * E * ap * np.abs(g_err)
                ra = roots + F_abs / (2 * E * ap * slope_a)
                rd = ra * slope_a / np.maximum(g, 1e-300) + np.abs(g_err) / np.maximum(g, 1e-300)
                rd = np.where(at_wall, rel_F[pos], rd)
            elif control == "radius":
                ra = np.zeros(ap.shape)
                rd = np.abs(g_err) / np.maximum(np.abs(g), 1e-300) + ROUNDING
            else:
                ra = roots + np.abs(g_err) / slope_a
                rd = np.zeros(ap.shape)
            rel_a[pos] = np.where(at_wall, 0.0, ra)
            rel_d[pos] = rd
        out = {"force": rel_F, "radius": rel_a, "depth": rel_d}
        return {k: (float(v) if v.ndim == 0 else v) for k, v in out.items()}

    def displacement(self, r: Any) -> Any:
        """Normal surface displacement ``u_z(r)``, m, inside (``d - f(r)``) and outside the contact."""
        r, a, d, _ = self._field_args(r, "displacement()")
        val, _err = _normal.displacement(self.contact.profile, r, a, d, self.contact.rtol)
        return _scalar_or_array(val)

    @property
    def peak_pressure(self) -> Any:
        """Maximum pressure over the contact, Pa (sampled on 1024 radii from the centre).

        ``inf`` where the pressure is singular (flat-punch edge, cone tip, ``n < 1``). A linear
        table whose first segment is not flat is a cone tip: ``inf``, with a
        :class:`~contactlab.errors.ValidityWarning` naming the smooth alternative
        (``interpolation="cubic"``, whose axis slope is 0); the axis is computed first, and
        where its pressure is ``+inf`` the other radii are not. Tables take per-segment rules
        cached per table (:mod:`contactlab.physics.table_pressure`); a cubic table's smooth
        pressure is searched on every 8th radius and then around the three largest samples
        (173 radii instead of 1024; the same maximum to rounding).
        """
        check_peak(self)
        rho = np.linspace(0.0, 1.0, PEAK_RADII + 1)[:-1]
        a = self._radius[..., None]
        g_edge = np.asarray(self._edge_g)
        prof, E, rtol = self.contact.profile, self.contact.moduli.normal, self.contact.rtol
        d, g = self._depth[..., None], g_edge[..., None]
        # the axis first: where the pressure there is +inf (a cone tip: a linear table whose
        # first segment is not flat) on every state, that is the peak, and the other 1023 radii
        # need not be computed (otherwise all 1024 are, as one array: the same bits)
        axis, _ = _normal.pressure(prof, E, rho[:1] * a, a, d, g, rtol)
        if np.all(np.isposinf(axis)):
            top = axis[..., 0]
        elif prof.has("node_table") and getattr(prof, "interpolation", None) == "cubic":
            top = np.maximum(axis[..., 0], _table_peak(prof, E, rho, a, d, g, rtol))
        else:
            val, _ = _normal.pressure(prof, E, rho * a, a, d, g, rtol)
            top = np.max(val, axis=-1)
        flat_edge = self._edge_at_wall & (self._depth != g_edge)
        peak = np.where(flat_edge, np.inf, top)
        warn_cone_tip(self.contact.profile, axis[..., 0])
        return _scalar_or_array(peak)

    # ---- subsurface stresses (contactlab.effects.stress does the work)
    def stress(self, r: Any, z: Any, body: int = 1) -> Any:
        """Subsurface stress field at radii ``r`` and depths ``z >= 0`` (m, broadcast) in body 1
        or 2: a :class:`~contactlab.effects.stress.StressField` (cylindrical components, Pa,
        tension positive; von Mises, maximum shear, Tresca, principal stresses). See
        docs/stress.md."""
        from .stress import normal_stress
        return normal_stress(self, r, z, body)

    def max_stress(self, kind: str = "von_mises", body: int = 1) -> Any:
        """Largest ``kind`` (``"von_mises"``, ``"max_shear"``, ``"tresca"``, ``"max_principal"``,
        ``"min_principal"``) in body 1 or 2 and its location (a ``StressMaximum``)."""
        from .stress import normal_max_stress
        return normal_max_stress(self, kind, body)

    def stress_field(self, grid: Any = None, body: int = 1) -> Any:
        """Stress field on a 2D grid ``(r_values, z_values)`` (default 200 x 100 points over
        ``2a`` by ``1.5a``) for plots: ``state.stress_field().plot("von_mises")``."""
        from .stress import normal_stress_field
        return normal_stress_field(self, grid, body)


#: the cubic table peak's search: every PEAK_COARSE-th of the 1024 radii, then the radii around
#: the PEAK_CANDIDATES largest of those: the fine grid's maximum wherever it lies within
#: PEAK_COARSE - 1 fine steps of one of them, which the smooth pressure of a cubic table (its
#: slope is continuous) does unless it has several near-equal maxima. A linear table is not
#: searched this way: each node where its slope jumps is a logarithmic pressure spike, which
#: only the full pass samples as before.
PEAK_COARSE, PEAK_CANDIDATES = 8, 3


def _table_peak(prof: Any, E: float, rho: np.ndarray, a: np.ndarray, d: np.ndarray,
                g: np.ndarray, rtol: float) -> np.ndarray:
    """Largest pressure (Pa) of a table's states on the 1024 radii ``rho * a`` (shape
    ``(..., 1)`` arrays ``a``, ``d``, ``g``), from a coarse pass and a fine pass around its
    largest samples; each radius is computed as in the full pass (the same bits)."""
    n = rho.size
    coarse = np.arange(0, n, PEAK_COARSE)
    val_c, _ = _normal.pressure(prof, E, rho[coarse] * a, a, d, g, rtol)
    k = min(PEAK_CANDIDATES, coarse.size)
    best = np.argpartition(-val_c, k - 1, axis=-1)[..., :k]          # (..., k) coarse indices
    offs = np.arange(-(PEAK_COARSE - 1), PEAK_COARSE)
    fine = np.clip(coarse[best][..., None] + offs, 0, n - 1).reshape(*best.shape[:-1], -1)
    val_f, _ = _normal.pressure(prof, E, rho[fine] * a, a, d, g, rtol)
    return np.maximum(np.max(val_c, axis=-1), np.max(val_f, axis=-1))
