"""Checks of the arguments the fits share: ``free``, ``start``, the adhesion values.

Every check raises a :class:`~contactlab.errors.ParameterError` (or
:class:`~contactlab.errors.UnknownNameError`) naming the argument, the value and what is
allowed, never a bare ``TypeError`` or ``ValueError`` from Python or numpy.
"""
from __future__ import annotations

import math
import warnings
from collections.abc import Iterable, Mapping
from typing import Any

import numpy as np

from ..errors import ParameterError, UnknownNameError, ValidityWarning
from ..params.checks import _short, as_real, check_positive

__all__ = ["data_array", "free_names", "start_values", "optional_positive", "needs_adhesion",
           "warn_undetermined"]


def data_array(name: str, value: Any) -> np.ndarray:
    """The measured series ``name`` (depth, force, time, ...) as a 1D float array.

    Raises
    ------
    ParameterError
        Not numbers, not 1D, or holding NaN or inf (the first such index is named).
    """
    try:
        arr = np.asarray(value, dtype=float)
    except (TypeError, ValueError) as err:
        raise ParameterError(f"{name}={_short(value)} is invalid: give a 1D array of "
                             "numbers.") from err
    if arr.ndim != 1:
        raise ParameterError(f"{name} has shape {arr.shape}: give a 1D array.")
    bad = ~np.isfinite(arr)
    if np.any(bad):
        i = int(np.argmax(bad))
        raise ParameterError(f"{name}[{i}]={float(arr[i])!r} is invalid: every value must be finite "
                             "(remove NaN and inf points before fitting).")
    return arr


def free_names(free: Any) -> tuple[str, ...]:
    """``free`` as a tuple of names: one name or an iterable of names (the caller checks that
    each is one it fits).

    Raises
    ------
    ParameterError
        ``free`` is not a string or an iterable of strings.
    """
    if isinstance(free, str):
        return (free,)
    if isinstance(free, (bytes, Mapping)) or not isinstance(free, Iterable):
        raise ParameterError(f"free={_short(free)} is invalid: give a parameter name or a "
                             "sequence of names, e.g. free=('E', 'contact_point').")
    out = tuple(free)
    for n in out:
        if not isinstance(n, str):
            raise ParameterError(f"free={_short(free)} is invalid: it holds {n!r}, not a "
                                 "parameter name (a string).")
    return out


def start_values(start: Any, names: tuple[str, ...], positive: Iterable[str],
                 units: Mapping[str, str] | None = None) -> dict[str, float]:
    """The starting values ``start`` (None or a mapping name -> number) checked against the
    fitted ``names``: each a finite real number, ``> 0`` for the names in ``positive`` (fitted
    through their logarithm).

    Raises
    ------
    ParameterError
        ``start`` is not a mapping, or a value is not a finite number (``> 0`` where the
        parameter must be positive).
    UnknownNameError
        A name that is not fitted (a fixed parameter's start would be ignored).
    """
    if start is None:
        return {}
    if not isinstance(start, Mapping):
        raise ParameterError(f"start={_short(start)} is invalid: give a dict of starting values "
                             f"by name, from the fitted parameters {names}.")
    pos = set(positive)
    units = units or {}
    out: dict[str, float] = {}
    for key, value in start.items():
        if not isinstance(key, str) or key not in names:
            raise UnknownNameError(
                f"start contains {key!r}, which is not fitted: starting values are allowed for "
                f"the fitted parameters {names} (free=...); a fixed value comes from the "
                "sample template or its own argument.")
        name, what, unit = f"start[{key!r}]", f"the starting value of {key!r}", units.get(key)
        if key in pos:
            out[key] = check_positive(name, value, what, unit or "")
            continue
        v = as_real(name, value, f"{what} must be a finite real number", unit=unit)
        if not math.isfinite(v):
            raise ParameterError(f"{name}={_short(value)} is invalid: {what} must be a finite "
                                 "real number.")
        out[key] = v
    return out


def optional_positive(name: str, value: Any, what: str, unit: str) -> float | None:
    """``value`` as a positive finite float, or None when it is None."""
    if value is None:
        return None
    return check_positive(name, value, what, unit)


def needs_adhesion(adhesion: str | None, **values: Any) -> None:
    """Refuse the adhesion values given without an adhesive model (they would be ignored).

    Raises
    ------
    ParameterError
        ``adhesion`` is None and one of ``values`` is not None.
    """
    if adhesion is not None:
        return
    for name, value in values.items():
        if value is not None:
            raise ParameterError(
                f"{name}={_short(value)} is given but adhesion=None: it is used by an adhesive "
                "fit only; give adhesion='jkr' or 'dmt', or drop it.")


def warn_undetermined(stderr: Mapping[str, float], stacklevel: int = 3) -> None:
    """Warn (:class:`~contactlab.errors.ValidityWarning`) where a fit's standard errors are not
    finite: the data do not tell its parameters apart (a singular Jacobian at the fitted
    values), so the values reached are one of many that fit as well."""
    bad = [n for n, v in stderr.items() if not math.isfinite(v)]
    if bad:
        warnings.warn(
            f"the data do not determine {bad} (a singular Jacobian at the fitted values): their "
            "standard errors and confidence intervals are infinite, and the values reached are "
            "one of many that fit as well; fix some of them (free=...) or add data that "
            "separate them.", ValidityWarning, stacklevel=stacklevel)
