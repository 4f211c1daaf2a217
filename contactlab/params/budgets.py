"""The memory and time budgets every user-sized computation is checked against first
(re-exported by :mod:`contactlab.params`).

The memory budget (bytes) is what one call may allocate; the time budget (seconds) is what a
planned run may take by its cost estimate. Each is set by :func:`set_memory_budget` /
:func:`set_time_budget`, else by its environment variable, else by its default.
"""
from __future__ import annotations

import math
import os
import threading

from ..errors import MemoryBudgetError, ParameterError, TimeBudgetError
from .checks import _short, as_real

__all__ = ["memory_budget", "set_memory_budget", "check_memory", "DEFAULT_MEMORY_BUDGET",
           "MEMORY_BUDGET_ENV", "time_budget", "set_time_budget", "check_time",
           "DEFAULT_TIME_BUDGET", "TIME_BUDGET_ENV"]


# ---------------------------------------------------------------------------- memory budget
#: environment variable read for the budget (bytes; ``512M``, ``4G`` and ``inf`` accepted)
MEMORY_BUDGET_ENV = "CONTACTLAB_MEMORY_BUDGET"
#: default budget, bytes: 2 GiB, far above any documented example (a 10^5-step path through
#: 2000 springs needs ~20 MB) and below what makes a shared machine swap
DEFAULT_MEMORY_BUDGET = 2 * 1024**3

_SUFFIX = {"": 1, "K": 1024, "M": 1024**2, "G": 1024**3, "T": 1024**4}
_budget_lock = threading.Lock()
_budget_set: float | None = None


def _parse_budget(name: str, value: object) -> float:
    if isinstance(value, str):
        text = value.strip().upper().removesuffix("B").removesuffix("I")
        if text in ("INF", "INFINITY", "NONE"):
            return math.inf
        unit = text[-1:] if text[-1:] in _SUFFIX and text[-1:] != "" else ""
        try:
            number = float(text[: len(text) - len(unit)])
        except ValueError:
            number = math.nan
        v = number * _SUFFIX[unit]
    else:
        v = as_real(name, value, "the memory budget must be a number of bytes > 0")
    if not v > 0:       # also NaN
        raise ParameterError(f"{name}={_short(value)} is invalid: the memory budget must be a "
                             "number of bytes > 0 (suffixes K, M, G allowed; 'inf' for none).")
    return v


def memory_budget() -> float:
    """The memory budget, bytes, that large requests are checked against.

    :func:`set_memory_budget` if called, else the environment variable ``CONTACTLAB_MEMORY_BUDGET``
    (bytes, ``512M``, ``4G`` or ``inf``), else :data:`DEFAULT_MEMORY_BUDGET` (2 GiB).
    """
    with _budget_lock:
        if _budget_set is not None:
            return _budget_set
    env = os.environ.get(MEMORY_BUDGET_ENV)
    if env:
        return _parse_budget(MEMORY_BUDGET_ENV, env)
    return float(DEFAULT_MEMORY_BUDGET)


def set_memory_budget(n_bytes: float | str | None) -> float | None:
    """Set the memory budget for this process; returns the previous setting (None = default).

    Parameters
    ----------
    n_bytes : float, str or None
        Bytes (> 0; ``math.inf`` or ``"inf"`` disables the check; ``"4G"`` style strings
        accepted). ``None`` returns to the environment variable or the default.

    Examples
    --------
    >>> import contactlab as cl
    >>> previous = cl.set_memory_budget("8G")
    >>> cl.memory_budget() == 8 * 1024**3
    True
    >>> _ = cl.set_memory_budget(previous)
    """
    global _budget_set
    new = None if n_bytes is None else _parse_budget("n_bytes", n_bytes)
    with _budget_lock:
        old, _budget_set = _budget_set, new
    return old


def check_memory(what: str, n_bytes: float, detail: str) -> None:
    """Raise :class:`MemoryBudgetError` if ``n_bytes`` exceeds :func:`memory_budget`.

    Parameters
    ----------
    what : str
        The request (``"simulate()"``).
    n_bytes : float
        Estimated peak memory of the request, bytes (estimated before anything is allocated).
    detail : str
        What drives the estimate (``"10**9 steps x 2000 springs"``), for the message.
    """
    budget = memory_budget()
    if n_bytes > budget:
        raise MemoryBudgetError(
            f"{what} would need about {n_bytes / 1024**3:.3g} GiB ({detail}), above the memory "
            f"budget of {budget / 1024**3:.3g} GiB: reduce what drives it, or raise the "
            f"budget with contactlab.set_memory_budget(...) or {MEMORY_BUDGET_ENV}=...")


# ---------------------------------------------------------------------------- time budget
#: environment variable read for the time budget (seconds; ``90s``, ``10min``, ``2h``, ``inf``)
TIME_BUDGET_ENV = "CONTACTLAB_TIME_BUDGET"
#: default time budget, seconds: 10 minutes, far above any documented example and below the
#: runs that were found to go on for 20 minutes and more (exact fretting maps of 10^6 points)
DEFAULT_TIME_BUDGET = 600.0

_TIME_SUFFIX = {"S": 1.0, "SEC": 1.0, "MIN": 60.0, "M": 60.0, "H": 3600.0}
_time_set: float | None = None


def _parse_time(name: str, value: object) -> float:
    if isinstance(value, str):
        text = value.strip().upper()
        if text in ("INF", "INFINITY", "NONE"):
            return math.inf
        unit = next((u for u in sorted(_TIME_SUFFIX, key=len, reverse=True)
                     if text.endswith(u)), "")
        try:
            number = float(text[: len(text) - len(unit)])
        except ValueError:
            number = math.nan
        v = number * _TIME_SUFFIX.get(unit, 1.0)
    else:
        v = as_real(name, value, "the time budget must be a number of seconds > 0")
    if not v > 0:       # also NaN
        raise ParameterError(f"{name}={_short(value)} is invalid: the time budget must be a "
                             "number of seconds > 0 (suffixes s, min, h allowed; 'inf' for none).")
    return v


def time_budget() -> float:
    """The time budget, s, that long requests are checked against before they start.

    :func:`set_time_budget` if called, else the environment variable ``CONTACTLAB_TIME_BUDGET``
    (seconds, ``90s``, ``10min``, ``2h`` or ``inf``), else :data:`DEFAULT_TIME_BUDGET` (600 s).
    """
    with _budget_lock:
        if _time_set is not None:
            return _time_set
    env = os.environ.get(TIME_BUDGET_ENV)
    if env:
        return _parse_time(TIME_BUDGET_ENV, env)
    return float(DEFAULT_TIME_BUDGET)


def set_time_budget(seconds: float | str | None) -> float | None:
    """Set the time budget for this process; returns the previous setting (None = default).

    Parameters
    ----------
    seconds : float, str or None
        Time budget, s (> 0; ``math.inf`` or ``"inf"`` disables the check; ``"30min"`` style strings
        accepted). ``None`` returns to the environment variable or the default.

    Examples
    --------
    >>> import contactlab as cl
    >>> previous = cl.set_time_budget("1h")
    >>> cl.time_budget()
    3600.0
    >>> _ = cl.set_time_budget(previous)
    """
    global _time_set
    new = None if seconds is None else _parse_time("seconds", seconds)
    with _budget_lock:
        old, _time_set = _time_set, new
    return old


def check_time(what: str, seconds: float, detail: str) -> None:
    """Raise :class:`TimeBudgetError` if the estimated run time exceeds :func:`time_budget`.

    Parameters
    ----------
    what : str
        The request (``"fretting_map()"``).
    seconds : float
        Estimated run time, s, from a calibrated cost per unit of work (a lower estimate: the
        costs were measured on an unloaded core, so a refusal means the run is at least that
        long).
    detail : str
        What drives the estimate (``"10**6 points x 0.3 ms"``), for the message.
    """
    budget = time_budget()
    if seconds > budget:
        raise TimeBudgetError(
            f"{what} would run for about {_duration(seconds)} ({detail}), above the time budget "
            f"of {_duration(budget)}: reduce what drives it, or raise the budget with "
            f"contactlab.set_time_budget(...) (seconds, '2h', 'inf') or {TIME_BUDGET_ENV}=...")


def _duration(seconds: float) -> str:
    if not math.isfinite(seconds):
        return "inf"
    if seconds < 120:
        return f"{seconds:.3g} s"
    if seconds < 7200:
        return f"{seconds / 60:.3g} min"
    return f"{seconds / 3600:.3g} h"
