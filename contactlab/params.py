"""Parameter specifications and the checks every public constructor runs.

A :class:`Param` says what a parameter is (name, symbol, unit, domain, a typical range); the
``check_*`` helpers turn a user value into a float or array and raise
:class:`~contactlab.errors.ParameterError` naming the parameter, the value and the allowed set.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from .errors import ParameterError

__all__ = ["Param", "ParamIdentity", "check_positive", "check_finite", "check_in_range", "as_float_array",
           "exactly_one", "scalar_or_array"]

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
    """

    name: str
    symbol: str
    unit: str
    domain: str = "positive"
    description: str = ""
    typical: tuple[float, float] = (1e-3, 1.0)

    def check(self, value: object) -> float:
        """Return ``value`` as a float after checking it lies in the domain."""
        allowed, ok = _DOMAINS[self.domain]
        try:
            v = float(value)  # type: ignore[arg-type]
        except (TypeError, ValueError) as err:
            raise ParameterError(
                f"{self.name}={value!r} is invalid: {self.description or self.name} must be a real "
                f"number {allowed} (unit {self.unit})."
            ) from err
        if not math.isfinite(v) or not ok(v):
            raise ParameterError(
                f"{self.name}={value!r} is invalid: {self.description or self.name} must be finite "
                f"and {allowed} (unit {self.unit})."
            )
        return v


class ParamIdentity:
    """Mixin: ``repr``, ``==`` and ``hash`` from the declared ``params`` (class + values), so two
    objects built with the same parameters are interchangeable (and usable as cache keys)."""

    params: tuple[Param, ...] = ()

    def _param_values(self) -> tuple[Any, ...]:
        return tuple(getattr(self, p.name) for p in self.params)

    def __repr__(self) -> str:
        args = ", ".join(f"{p.name}={getattr(self, p.name)!r}" for p in self.params)
        return f"{type(self).__name__}({args})"

    def __eq__(self, other: object) -> bool:
        return (type(self) is type(other)
                and self._param_values() == other._param_values())  # type: ignore[attr-defined]

    def __hash__(self) -> int:
        return hash((type(self), self._param_values()))


def check_positive(name: str, value: object, what: str = "", unit: str = "") -> float:
    """Check that ``value`` is a finite real number > 0 and return it as float."""
    return Param(name, name, unit or "-", "positive", what).check(value)


def check_finite(name: str, value: object, what: str = "", unit: str = "") -> float:
    """Check that ``value`` is a finite real number and return it as float."""
    return Param(name, name, unit or "-", "real", what).check(value)


def check_in_range(name: str, value: object, low: float, high: float, *, low_open: bool,
                   high_open: bool, what: str) -> float:
    """Check ``low <(=) value <(=) high`` and return the value as float."""
    try:
        v = float(value)  # type: ignore[arg-type]
    except (TypeError, ValueError):
        v = float("nan")
    lo_ok = v > low if low_open else v >= low
    hi_ok = v < high if high_open else v <= high
    if not (lo_ok and hi_ok):   # also catches NaN
        lo_s = "<" if low_open else "<="
        hi_s = "<" if high_open else "<="
        raise ParameterError(
            f"{name}={value!r} is invalid: {what} must satisfy {low:g} {lo_s} {name} {hi_s} {high:g}."
        )
    return v


def as_float_array(name: str, value: object, *, allow_nan: bool = False) -> np.ndarray:
    """Convert ``value`` to a float ndarray; reject non-numeric and (by default) non-finite input."""
    try:
        arr = np.asarray(value, dtype=float)
    except (TypeError, ValueError) as err:
        raise ParameterError(f"{name}={value!r} is invalid: expected real numbers.") from err
    if not allow_nan and not np.all(np.isfinite(arr)):
        bad = float(arr[~np.isfinite(arr)].ravel()[0])
        raise ParameterError(f"{name} contains {bad!r}: every value must be finite.")
    return arr


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
