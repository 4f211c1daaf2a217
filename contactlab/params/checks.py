"""Parameter specifications and the checks every public constructor runs (re-exported by
:mod:`contactlab.params`).

A :class:`Param` says what a parameter is (name, symbol, unit, domain, a typical range); the
``check_*`` helpers turn a user value into a float or array and raise
:class:`~contactlab.errors.ParameterError` naming the parameter, the value and the allowed set.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, ClassVar

import numpy as np

from ..errors import ParameterError, UnitError

__all__ = ["Param", "ParamIdentity", "LENGTH_BOUNDS", "MODULUS_BOUNDS", "check_bounds",
           "check_positive", "check_finite", "check_in_range",
           "as_float_array", "as_real", "as_checked_array", "broadcast_inputs", "check_count",
           "check_result_finite", "exactly_one", "scalar_or_array", "step_indices", "check_flag",
           "name_list", "values_equal", "FieldsEqual", "QUANTITY_UNITS", "to_si", "to_si_values",
           "PLAIN_TYPES", "CACHE_KEYS", "without_caches"]

#: the range of a profile's lengths (radii of curvature, punch radii), m: where every route is
#: checked against the closed forms; far wider than any contact (an atom is 1e-10 m across,
#: the Earth's radius 6.4e6 m), and beyond it float64 gave wrong numbers or raw errors (a sphere
#: of 1e-200 m: ZeroDivisionError; of 1e60 m: overflow)
LENGTH_BOUNDS = (1e-30, 1e10)
#: the range of a material's elastic moduli (Young's and shear moduli, a contact law's E*, G*,
#: G_t), Pa: far wider than any material (soft gels 1e1 Pa, diamond 1.2e12 Pa); with the
#: lengths inside LENGTH_BOUNDS forces, torques and energies stay normal float64 numbers
#: (beyond it a modulus of 1e-300 Pa gave a subnormal force with five of its digits lost)
MODULUS_BOUNDS = (1e-10, 1e20)

_DOMAINS = {
    "positive": ("> 0", lambda v: v > 0),
    "nonnegative": (">= 0", lambda v: v >= 0),
    "real": ("finite", lambda v: True),
}


@dataclass(frozen=True)
class Param:
    """Specification of one model parameter.

    Parameters
    ----------
    name : str
        Keyword used in the API and in scene files (``R``, ``slope``).
    symbol : str
        sympy/LaTeX symbol name used in formula export.
    unit : str
        SI unit (``"m"``, ``"Pa"``, ``"1"`` for dimensionless).
    domain : str
        One of ``"positive"``, ``"nonnegative"``, ``"real"``.
    description : str
        One line for docs and error messages.
    typical : tuple of float
        A typical (low, high) range, used by property tests and docs.
    bounds : tuple of float, optional
        The range ``[low, high]`` (in :attr:`unit`) a value must lie in, beyond the domain:
        where the routes that use it are checked (a profile's lengths, :data:`LENGTH_BOUNDS`).
    """

    name: str
    symbol: str
    unit: str
    domain: str = "positive"
    description: str = ""
    typical: tuple[float, float] = (1e-3, 1.0)
    bounds: tuple[float, float] | None = None

    def check(self, value: object) -> float:
        """Return ``value`` as a float after checking it lies in the domain.

        ``value`` may carry a unit (``"210 GPa"``, a pint quantity): it is converted to
        :attr:`unit` first (:func:`to_si`).
        """
        allowed, ok = _DOMAINS[self.domain]
        v = as_real(self.name, value, f"{self.description or self.name} must be a real number "
                                      f"{allowed} (unit {self.unit})",
                    unit=None if self.unit in _NO_UNIT else self.unit)
        if not math.isfinite(v) or not ok(v):
            raise ParameterError(
                f"{self.name}={value!r} is invalid: {self.description or self.name} must be finite "
                f"and {allowed} (unit {self.unit})."
            )
        if self.bounds is not None and not self.bounds[0] <= v <= self.bounds[1]:
            lo, hi = self.bounds
            raise ParameterError(
                f"{self.name}={value!r} is invalid: {self.description or self.name} must lie "
                f"between {lo:g} and {hi:g} {self.unit} (check the units).")
        return v


#: attributes that objects keep as per-object caches of derived data (in their ``__dict__``):
#: never pickled (some hold closures; all are rebuilt on first use), so a profile or contact
#: that has already been used travels to a worker process like a fresh one. Every
#: ``__dict__[...]`` cache key in the package must be listed here (a test reads the sources).
CACHE_KEYS = frozenset({
    "_g_route_cache", "_theta_whole_cache", "_scalar_normal_forms", "_scalar_quadrature_ok",
    "_grid_cache", "_node_H", "_coarse_idx", "_cubic_cols", "_table_pressure_cache",
    "_fit_tip_tables", "_critical_memo", "_jkr_branches", "_xp_params", "_radius_bound_cache",
    "_far_cache", "_cubic_tree_cache", "_cubic_pair", "_scalar_table_parts", "_node_gp",
    "_cubic_primed", "_node_batches", "_far_primed",
    "_far_excess", "_far_tails",
})


def without_caches(state: dict[str, Any]) -> dict[str, Any]:
    """``state`` (an object's ``__dict__``) less the per-object caches of :data:`CACHE_KEYS`."""
    return {k: v for k, v in state.items() if k not in CACHE_KEYS}


class ParamIdentity:
    """Mixin: ``repr``, ``==`` and ``hash`` from the declared ``params`` (class + values), so two
    objects built with the same parameters are interchangeable (and usable as cache keys)."""

    params: ClassVar[tuple[Param, ...]] = ()

    def _param_values(self) -> tuple[Any, ...]:
        return tuple(getattr(self, p.name) for p in self.params)

    def __repr__(self) -> str:
        args = ", ".join(f"{p.name}={getattr(self, p.name)!r}" for p in self.params)
        return f"{type(self).__name__}({args})"

    def __eq__(self, other: object) -> bool:
        return (type(self) is type(other) and isinstance(other, ParamIdentity)
                and self._param_values() == other._param_values())

    def __hash__(self) -> int:
        return hash((type(self), self._param_values()))

    def __getstate__(self) -> dict[str, Any]:
        # caches of derived data stay behind (:data:`CACHE_KEYS`): rebuilt on first use
        return without_caches(self.__dict__)


# ---------------------------------------------------------------------------- units
#: SI unit of each public keyword that is not a declared :class:`Param` (driver arguments,
#: load-path controls): a string with a unit (``force="2 kN"``) or a pint quantity given for one
#: of these names is converted to this unit at the boundary (:func:`as_real`,
#: :func:`as_float_array`); every other name takes plain numbers only
QUANTITY_UNITS: dict[str, str] = {
    "depth": "m", "force": "N", "displacement": "m", "tangential_force": "N", "twist": "rad",
    "torque": "N*m", "time": "s", "r": "m", "radius": "m", "max_radius": "m", "noise": "m",
    "stick_radius": "m", "twist_amplitude": "rad", "displacement_amplitude": "m", "half_angle": "rad",
    "work_of_adhesion": "J/m^2", "wear_coefficient": "1/Pa", "duration": "s", "period": "s",
}
#: units that mean "not declared" (no conversion, plain numbers only)
_NO_UNIT = ("", "-")


def _is_quantity(value: object) -> bool:
    """A pint ``Quantity`` (recognised without importing pint: pint stays a lazy extra)."""
    return (type(value).__module__.partition(".")[0] == "pint"
            and hasattr(value, "to") and hasattr(value, "magnitude"))


def to_si(name: str, value: Any, unit: str | None = None) -> Any:
    """``value`` in the SI unit ``unit`` when it carries a unit of its own; else unchanged.

    The one place where a unit given by the caller is converted. A string ``"<number> <unit>"``
    is read by the unit grammar of scene files (:func:`contactlab.numeric.units.parse_quantity`:
    ``"210 GPa"``, ``"10 um"``, ``"5 deg"``, ``"1e-3 N*m"``); a pint ``Quantity`` (scalar or
    array) is converted by pint. A string without a unit (``"1e9"``) is not converted: a
    number is given as a number. Values of any other type are returned unchanged.

    Parameters
    ----------
    name : str
        The parameter, for messages.
    value : object
        The caller's value.
    unit : str, optional
        SI unit of the parameter (``"Pa"``, ``"m"``, ``"N*m"``, ``"1"``); default
        :data:`QUANTITY_UNITS` ``[name]``. ``"-"`` or an unknown name: no conversion.

    Raises
    ------
    UnitError
        The unit is unknown or of another dimension (the message names the parameter, the
        value and the units it accepts). Also a :class:`ParameterError`.

    Examples
    --------
    >>> to_si("E", "210 GPa", "Pa"), to_si("force", "2 kN"), to_si("R", 0.01, "m")
    (210000000000.0, 2000.0, 0.01)
    """
    is_str = isinstance(value, str)
    if not is_str and not _is_quantity(value):
        return value
    unit = QUANTITY_UNITS.get(name, "-") if unit is None else unit
    if unit in _NO_UNIT:
        return value
    from ..numeric.units import DIMENSION_OF_SI_UNIT, canonical_unit, parse_quantity, split_number
    dim = DIMENSION_OF_SI_UNIT.get(canonical_unit(unit))
    if dim is None:         # a unit outside the grammar (m^(1-n)): plain numbers only
        return value
    if is_str:
        number, given = split_number(value)
        if number is None or not given:
            return value    # not "<number> <unit>": refused as not a number by the caller
        return parse_quantity(value, dim, name)
    si = "dimensionless" if dim == "dimensionless" else canonical_unit(unit).replace("^", "**")
    try:
        magnitude = value.to(si).magnitude
    except Exception as err:    # pint's DimensionalityError (pint is not imported here)
        raise UnitError(f"{name}={_short(value)} has the wrong dimension: {name} is a "
                        f"{dim.replace('_', ' ')} in {unit}; give it in {unit} or a "
                        f"compatible unit.", issues=[(name, value, f"a {dim} ({unit})")]
                        ) from err
    return float(magnitude) if np.ndim(magnitude) == 0 else np.asarray(magnitude)


#: argument types that never carry a unit (passed on without a further look)
PLAIN_TYPES = frozenset({float, int, np.ndarray, np.float64, list, tuple, type(None)})


def to_si_values(**values: Any) -> tuple[Any, ...]:
    """The keyword values in their order, each converted by :func:`to_si` under its own name
    (``force="2 kN"`` -> ``2000.0``); plain numbers and arrays pass untouched.

    The first line of the :class:`~contactlab.Contact` methods: a value with a unit reaches the
    drivers as SI numbers. (A call, not a decorator: a wrapper would add a frame between the
    caller and the drivers, whose warnings point at the caller's line.)

    >>> to_si_values(depth=None, force="2 kN")
    (None, 2000.0)
    """
    return tuple(v if type(v) in PLAIN_TYPES else to_si(k, v) for k, v in values.items())


def check_positive(name: str, value: object, what: str = "", unit: str = "") -> float:
    """Check that ``value`` is a finite real number > 0 and return it as float."""
    return Param(name, name, unit or "-", "positive", what).check(value)


def check_finite(name: str, value: object, what: str = "", unit: str = "") -> float:
    """Check that ``value`` is a finite real number and return it as float."""
    return Param(name, name, unit or "-", "real", what).check(value)


def check_in_range(name: str, value: object, low: float, high: float, *, low_open: bool,
                   high_open: bool, what: str, unit: str | None = None) -> float:
    """Check ``low <(=) value <(=) high`` and return the value as float (``unit``: SI unit of
    the bounds, for a value given with a unit; see :func:`to_si`)."""
    lo_s = "<" if low_open else "<="
    hi_s = "<" if high_open else "<="
    v = as_real(name, value, f"{what} must be a real number with {low:g} {lo_s} {name} {hi_s} "
                             f"{high:g}", unit=unit)
    lo_ok = v > low if low_open else v >= low
    hi_ok = v < high if high_open else v <= high
    if not (lo_ok and hi_ok):   # also catches NaN
        raise ParameterError(
            f"{name}={value!r} is invalid: {what} must satisfy {low:g} {lo_s} {name} {hi_s} {high:g}."
        )
    return v


def _short(value: object, limit: int = 60) -> str:
    """``repr(value)``, shortened for an error message (long arrays are not echoed in full)."""
    text = repr(value)
    return text if len(text) <= limit else text[:limit - 3] + "..."


def _is_bool(value: object) -> bool:
    return isinstance(value, (bool, np.bool_))


def as_real(name: str, value: object, allowed: str = "expected a real number",
            unit: str | None = None) -> float:
    """``value`` as a Python float, the one scalar entry point of every check.

    A value with a unit (``"210 GPa"``, a pint quantity) is first converted to the SI unit
    ``unit`` (default :data:`QUANTITY_UNITS` ``[name]``; :func:`to_si`). Rejects what
    ``float()`` would silently accept although it is not a number: ``bool`` (``True`` is not
    1.0 Pa), strings without a unit (``"1e9"``) and 0-d arrays holding either. Does not check
    finiteness or a domain.

    Raises
    ------
    ParameterError
        ``value`` is not a real number; the message names ``name``, the value and ``allowed``.
    UnitError
        ``value`` has a unit of another dimension (a :class:`ParameterError` too).
    """
    if not isinstance(value, float):
        value = to_si(name, value, unit)
    arr = value if isinstance(value, np.ndarray) else None
    if (_is_bool(value) or isinstance(value, (str, bytes))
            or (arr is not None and (arr.ndim != 0 or arr.dtype.kind not in "iuf"))):
        raise ParameterError(f"{name}={_short(value)} is invalid: {allowed}"
                             f"{_string_hint(name, value, unit)}.")
    try:
        return float(value)  # type: ignore[arg-type]
    except (TypeError, ValueError, OverflowError) as err:
        raise ParameterError(f"{name}={_short(value)} is invalid: {allowed}.") from err


def _string_hint(name: str, value: object, unit: str | None) -> str:
    """For a string refused as a number: how to give the quantity with a unit, if it has one."""
    unit = QUANTITY_UNITS.get(name, "-") if unit is None else unit
    if not isinstance(value, str) or unit in _NO_UNIT or unit == "1" or "(" in unit:
        return ""
    return f"; give a number in {unit} or a string with a unit ('<number> <unit>')"


def _has_bool_or_str(seq: object) -> bool:
    """Whether a (nested) list/tuple holds a bool or a string anywhere."""
    stack: list[Any] = [seq]
    while stack:
        for v in stack.pop():
            if isinstance(v, (list, tuple)):
                stack.append(v)
            elif _is_bool(v) or isinstance(v, (str, bytes)):
                return True
    return False


def _all_finite(arr: np.ndarray) -> bool:
    """Whether every element of a float array is finite: by its two extremes (a NaN propagates
    through min and max), two reductions with no temporary (``np.isfinite`` would write a
    boolean array of the input's size first)."""
    if arr.size == 0:
        return True
    return math.isfinite(float(arr.min())) and math.isfinite(float(arr.max()))


def as_float_array(name: str, value: object, *, allow_nan: bool = False,
                   allow_empty: bool = False, unit: str | None = None) -> np.ndarray:
    """Convert ``value`` to a float ndarray, the one array entry point of every driver.

    A value with a unit (``"2 kN"``, a pint quantity, scalar or array) is first converted to
    the SI unit ``unit`` (default :data:`QUANTITY_UNITS` ``[name]``; :func:`to_si`). Rejects
    non-numeric input, booleans (``[True, False]`` is not ``[1.0, 0.0]``), strings without a
    unit, empty arrays (unless ``allow_empty``) and, unless ``allow_nan``, non-finite values.

    Raises
    ------
    ParameterError
        Naming ``name``, the offending value and what is allowed (:class:`UnitError` for a
        unit of another dimension).
    """
    if not isinstance(value, (np.ndarray, float)):
        value = to_si(name, value, unit)
    if (_is_bool(value) or isinstance(value, (str, bytes))
            or (isinstance(value, (list, tuple)) and _has_bool_or_str(value))):
        raise ParameterError(f"{name}={_short(value)} is invalid: expected real numbers "
                             "(not bool or str).")
    try:
        raw = np.asarray(value)
        if raw.dtype.kind not in "iuf" and not (raw.dtype.kind == "O" or raw.size == 0):
            raise TypeError(raw.dtype)
        if raw.dtype.kind == "O" and any(_is_bool(v) or isinstance(v, (str, bytes))
                                         for v in raw.ravel()):
            raise TypeError("bool or str element")
        arr = np.asarray(raw, dtype=float)
    except (TypeError, ValueError, OverflowError) as err:
        raise ParameterError(f"{name}={_short(value)} is invalid: expected real numbers "
                             "(a float or an array of floats; not bool or str).") from err
    if arr.size == 0 and not allow_empty:
        raise ParameterError(f"{name}={_short(value)} is invalid: it is empty; give at least one "
                             "value.")
    if not allow_nan and not _all_finite(arr):
        bad = float(arr[~np.isfinite(arr)].ravel()[0])
        raise ParameterError(f"{name} contains {bad!r}: every value must be finite.")
    return arr


_ARRAY_DOMAINS = {
    "positive": ("finite and > 0", lambda a: a > 0),
    "nonnegative": ("finite and >= 0", lambda a: a >= 0),
    "real": ("finite", lambda a: np.ones(a.shape, bool)),
}


def check_bounds(name: str, arr: np.ndarray, bounds: tuple[float, float], unit: str) -> None:
    """Every element of the (finite) array ``arr`` within ``bounds`` (inclusive), else a
    :class:`ParameterError` naming the first one outside, the range and ``unit`` (the ranges
    of :data:`LENGTH_BOUNDS`, :data:`MODULUS_BOUNDS`: check the units)."""
    lo, hi = bounds
    out = (arr < lo) | (arr > hi)
    if np.any(out):
        i = np.unravel_index(int(np.argmax(out)), arr.shape)
        at = "[" + ", ".join(str(int(k)) for k in i) + "]" if arr.ndim else ""
        raise ParameterError(f"{name}{at}={float(arr[i])!r} is invalid: it must lie between "
                             f"{lo:g} and {hi:g} {unit} (check the units).")


def as_checked_array(name: str, value: object, *, domain: str = "real", unit: str = "-",
                     size: int | None = None, allow_empty: bool = False,
                     bounds: tuple[float, float] | None = None) -> np.ndarray:
    """:func:`as_float_array` plus a domain check that names the first offending element.

    Parameters
    ----------
    name : str
        Parameter name for the message.
    value : array_like
        Scalar or array of real numbers (no bool, no str).
    domain : {"real", "positive", "nonnegative"}
        Every element must be finite and satisfy this.
    unit : str
        SI unit, for the message.
    size : int, optional
        A scalar or a 1D array of exactly this many values (one per item, e.g. per contact).
    allow_empty : bool
        Accept an empty array.
    bounds : tuple of float, optional
        Every element must also lie in ``[low, high]`` (:func:`check_bounds`).

    Raises
    ------
    ParameterError
        Naming ``name``, the offending value (with its index) and what is allowed.

    Examples
    --------
    >>> as_checked_array("R", [0.01, 0.02], domain="positive", unit="m", size=2)
    array([0.01, 0.02])
    """
    allowed, ok = _ARRAY_DOMAINS[domain]
    arr = as_float_array(name, value, allow_nan=True, allow_empty=allow_empty,
                         unit=None if unit in _NO_UNIT else unit)
    if size is not None and (arr.ndim > 1 or (arr.ndim == 1 and arr.size != size)):
        raise ParameterError(f"{name} has shape {arr.shape}: give a scalar or one value per "
                             f"item (1D, {size} values; unit {unit}).")
    with np.errstate(invalid="ignore"):
        bad = ~(np.isfinite(arr) & ok(arr))
    if np.any(bad):
        if arr.ndim == 0:
            raise ParameterError(f"{name}={float(arr)!r} is invalid: it must be {allowed} "
                                 f"(unit {unit}).")
        i = np.unravel_index(int(np.argmax(bad)), arr.shape)
        where = ", ".join(str(int(k)) for k in i)
        raise ParameterError(f"{name}[{where}]={float(arr[i])!r} is invalid: every value must be "
                             f"{allowed} (unit {unit}).")
    if bounds is not None:
        check_bounds(name, arr, bounds, unit)
    return arr


def broadcast_inputs(what: str, **arrays: Any) -> tuple[int, ...]:
    """The common shape of the keyword arrays, or a :class:`ParameterError` naming them.

    Parameters
    ----------
    what : str
        The caller, for the message (``"torsion()"``).
    **arrays : array_like
        Name -> array (or anything with a shape); ``None`` values are skipped.

    Examples
    --------
    >>> broadcast_inputs("torsion()", force=np.ones(3), twist=np.ones((2, 1)))
    (2, 3)
    """
    shapes = {k: np.shape(v) for k, v in arrays.items() if v is not None}
    try:
        return tuple(np.broadcast_shapes(*shapes.values()))
    except ValueError:
        given = ", ".join(f"{k} {s}" for k, s in shapes.items())
        raise ParameterError(f"{what}: the shapes of {given} do not broadcast together; give "
                             "scalars, equal shapes, or shapes that broadcast (numpy rules)."
                             ) from None


def check_count(name: str, value: object, minimum: int = 1) -> int:
    """An integer count (``n_springs``, ``steps``) ``>= minimum``: ints or integral floats only.

    Raises
    ------
    ParameterError
        ``value`` is a bool, a string, not integral, not finite or below ``minimum``.
    """
    v = as_real(name, value, f"it must be an integer >= {minimum}")
    if not math.isfinite(v) or v != int(v) or v < minimum:
        raise ParameterError(f"{name}={_short(value)} is invalid: it must be an integer >= "
                             f"{minimum}.")
    return int(v)


def check_result_finite(what: str, inputs: dict[str, Any], **results: Any) -> None:
    """Refuse a result that overflowed float64 (never return inf or NaN from valid inputs).

    Parameters
    ----------
    what : str
        The call (``"fretting_loop()"``), for the message.
    inputs : dict
        Name -> input array broadcast like the results, quoted at the first bad element.
    **results : array_like
        The outputs to check.

    Raises
    ------
    ParameterError
        Some result is not finite: the inputs are outside any physical range (``force=1e300``).
    """
    for key, val in results.items():
        arr = np.asarray(val, dtype=float)
        bad = ~np.isfinite(arr)
        if np.any(bad):
            i = int(np.argmax(bad.ravel()))
            given = ", ".join(f"{k}={float(np.ravel(v)[i % np.size(v)])!r}"
                              for k, v in inputs.items() if np.size(v))
            raise ParameterError(f"{what}: {given} gives {key}={float(arr.ravel()[i])!r}, which "
                                 "overflows float64: the inputs are outside any physical range "
                                 "(give them in SI units: m, N, rad, Pa).")


def values_equal(a: Any, b: Any) -> bool:
    """Exact equality of result values: arrays element for element (same shape and dtype; NaN
    equals NaN), dicts, lists and tuples item by item, everything else by ``==``.

    The ``==`` of result objects (a result and its unpickled copy compare equal).
    """
    if isinstance(a, np.ndarray) or isinstance(b, np.ndarray):
        a_, b_ = np.asarray(a), np.asarray(b)
        if a_.shape != b_.shape or a_.dtype != b_.dtype:
            return False
        return bool(np.array_equal(a_, b_, equal_nan=a_.dtype.kind in "fc"))
    if isinstance(a, dict) and isinstance(b, dict):
        return a.keys() == b.keys() and all(values_equal(a[k], b[k]) for k in a)
    if isinstance(a, (list, tuple)) and isinstance(b, (list, tuple)):
        return (type(a) is type(b) and len(a) == len(b)
                and all(values_equal(x, y) for x, y in zip(a, b)))
    if isinstance(a, float) and isinstance(b, float) and math.isnan(a) and math.isnan(b):
        return True
    return bool(a == b)


class FieldsEqual:
    """Mixin for result dataclasses: ``==`` compares the type and every field by
    :func:`values_equal` (arrays element for element), so a result equals its unpickled copy;
    unhashable (the fields hold arrays).

    Declare the dataclass with ``eq=False``: otherwise ``@dataclass`` writes its own ``__eq__``
    (tuple comparison, which raises on arrays) over this one.

    Examples
    --------
    >>> from dataclasses import dataclass
    >>> @dataclass(frozen=True, eq=False)
    ... class R(FieldsEqual):
    ...     x: np.ndarray
    >>> R(np.arange(3.0)) == R(np.arange(3.0)), R(np.arange(3.0)) == R(np.zeros(3))
    (True, False)
    """

    def __eq__(self, other: object) -> bool:
        if type(other) is not type(self):
            return NotImplemented
        from dataclasses import fields
        return all(values_equal(getattr(self, f.name), getattr(other, f.name))
                   for f in fields(self))  # type: ignore[arg-type]

    __hash__ = None  # type: ignore[assignment]


def exactly_one(what: str, options: dict[str, Any]) -> tuple[str, Any]:
    """The one keyword of ``options`` that is not None, as ``(name, value)``.

    Parameters
    ----------
    what : str
        The caller, for the message (``"torsion()"``).
    options : dict
        Keyword name -> value (None = not given), in the order they are documented.

    Raises
    ------
    ParameterError
        None or more than one of the keywords was given.
    """
    given = [(k, v) for k, v in options.items() if v is not None]
    if len(given) != 1:
        raise ParameterError(f"{what} needs exactly one of {', '.join(k + '=' for k in options)}; "
                             f"got {sorted(k for k, _ in given) or 'none'}.")
    return given[0]


def scalar_or_array(value: Any) -> Any:
    """A 0-d result as a Python ``float`` (``bool`` for boolean arrays), else the ndarray itself."""
    v = np.asarray(value)
    if v.dtype == bool:
        return bool(v) if v.ndim == 0 else v
    if v.dtype.kind != "f":
        v = v.astype(float)
    return float(v) if v.ndim == 0 else v


def step_indices(name: str, steps: Any, n_steps: int) -> set[int]:
    """Step indices of a path (0-based; negative counts from the end) as a set of 0-based ints.

    Raises
    ------
    ParameterError
        ``steps`` is not a list of integers (a bool, a string, a fraction, NaN), or an index
        outside ``-n_steps <= step < n_steps``.
    """
    if steps is None:
        return set()
    if isinstance(steps, (str, bytes)) or not hasattr(steps, "__iter__"):
        raise ParameterError(f"{name}={_short(steps)} is invalid: give a list of step indices "
                             "(integers; negative counts from the end).")
    out = set()
    for s in steps:
        v = as_real(name, s, "every step index must be an integer (negative counts from the end)")
        if not math.isfinite(v) or v != int(v):
            raise ParameterError(f"{name} contains {_short(s)}: every step index must be an "
                                 "integer (negative counts from the end).")
        k = int(v)
        k = k + n_steps if k < 0 else k
        if not 0 <= k < n_steps:
            raise ParameterError(f"{name} contains {int(v)!r}: steps must satisfy "
                                 f"-{n_steps} <= step < {n_steps}.")
        out.add(k)
    return out


def check_flag(name: str, value: Any) -> bool:
    """A switch given as ``True``/``False`` (numpy booleans too); anything else is refused
    (``"no"`` is truthy in Python, which would silently switch the option on)."""
    if not isinstance(value, (bool, np.bool_)):
        raise ParameterError(f"{name}={_short(value)} is invalid: give True or False.")
    return bool(value)


def name_list(name: str, value: Any, allowed: tuple[str, ...]) -> tuple[str, ...]:
    """A tuple of names from ``allowed``: one name or an iterable of names.

    Raises
    ------
    ParameterError
        Not a name or an iterable of names.
    UnknownNameError
        A name that is not allowed.
    """
    from ..errors import UnknownNameError
    if isinstance(value, str):
        value = (value,)
    if not hasattr(value, "__iter__"):
        raise ParameterError(f"{name}={_short(value)} is invalid: give a name or a list of names "
                             f"from {allowed}.")
    out = tuple(value)
    for o in out:
        if not isinstance(o, str) or o not in allowed:
            raise UnknownNameError(f"{name} contains {o!r}: allowed are {allowed}.")
    return out
