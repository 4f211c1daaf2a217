"""Concrete load-path segments: :class:`Ramp`, :class:`Hold`, :class:`Sinusoid`,
:class:`Repeat` and :class:`Table` (measured arrays). All are frozen dataclasses validated at
construction."""
from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass
from typing import Any, cast

import numpy as np

from ..errors import ParameterError
from ..params import as_float_array
from .base import Segment, check_duration, check_quantities, check_steps, check_value

__all__ = ["Ramp", "Hold", "Sinusoid", "Repeat", "Table"]


def _pairs(pairs: Any, where: str) -> tuple[tuple[str, float], ...]:
    pairs = tuple(pairs)
    check_quantities([k for k, _ in pairs], where)
    return tuple((k, check_value(k, v)) for k, v in pairs)


@dataclass(frozen=True)
class Ramp(Segment):
    """Linear ramp from the current values to ``targets`` over ``steps`` steps."""

    targets: tuple
    steps: int = 1
    duration: float | None = None

    def __post_init__(self) -> None:
        if not self.targets:
            raise ParameterError("ramp() needs at least one target, e.g. ramp(force=100.0).")
        object.__setattr__(self, "targets", _pairs(self.targets, "ramp()"))
        object.__setattr__(self, "steps", check_steps("steps", self.steps))
        object.__setattr__(self, "duration", check_duration(self.duration, self.steps))

    @property
    def controls(self) -> frozenset:
        return frozenset(k for k, _ in self.targets)

    @property
    def n_steps(self) -> int:
        return self.steps

    def values(self, start):
        return self.values_of(start, self.controls)

    def values_of(self, start, names, *, time=True):
        f = np.arange(1, self.steps + 1) / self.steps
        return (f * cast(float, self.duration) if time else None,   # a float after __post_init__
                {k: start[k] + (v - start[k]) * f for k, v in self.targets if k in names})


@dataclass(frozen=True)
class Hold(Segment):
    """Keep every quantity at its current control value."""

    steps: int = 1
    duration: float | None = None

    def __post_init__(self) -> None:
        object.__setattr__(self, "steps", check_steps("steps", self.steps))
        object.__setattr__(self, "duration", check_duration(self.duration, self.steps))

    @property
    def controls(self) -> frozenset:
        return frozenset()

    @property
    def n_steps(self) -> int:
        return self.steps

    def values(self, start):
        return np.arange(1, self.steps + 1) / self.steps * cast(float, self.duration), {}


@dataclass(frozen=True)
class Sinusoid(Segment):
    """``mean + amplitude sin(2π k/steps_per_cycle)``, k = 1 … round(cycles·steps_per_cycle).

    One cycle is computed and tiled, so every cycle has bit-identical values; the samples where
    the sine is zero (half period, end of cycle) are exactly the mean. ``cycles`` may be
    fractional (``0.25`` ends at the first peak); it is rounded to whole steps, at least one.
    Step ``k`` is at ``k period / steps_per_cycle`` after the segment start.
    """

    amplitudes: tuple
    cycles: float = 1
    steps_per_cycle: int = 100
    period: float | None = None
    mean: tuple | None = None

    def __post_init__(self) -> None:
        if not self.amplitudes:
            raise ParameterError("sinusoid() needs at least one amplitude, e.g. "
                                 "sinusoid(twist=1e-3).")
        object.__setattr__(self, "amplitudes", _pairs(self.amplitudes, "sinusoid()"))
        object.__setattr__(self, "cycles", _check_cycles(self.cycles))
        object.__setattr__(self, "steps_per_cycle",
                           check_steps("steps_per_cycle", self.steps_per_cycle))
        object.__setattr__(self, "period", check_duration(self.period, self.steps_per_cycle))
        if self.mean is not None:
            mean = _pairs(self.mean, "sinusoid(mean=)")
            extra = {k for k, _ in mean} - {k for k, _ in self.amplitudes}
            if extra:
                raise ParameterError(f"mean has {sorted(extra)} without an amplitude; allowed "
                                     f"are {sorted(k for k, _ in self.amplitudes)}.")
            object.__setattr__(self, "mean", mean)

    @property
    def controls(self) -> frozenset:
        return frozenset(k for k, _ in self.amplitudes)

    @property
    def n_steps(self) -> int:
        return max(1, round(self.cycles * self.steps_per_cycle))

    @property
    def duration(self) -> float:
        return self.n_steps * cast(float, self.period) / self.steps_per_cycle

    def values(self, start):
        return self.values_of(start, self.controls)

    def values_of(self, start, names, *, time=True):
        n = self.steps_per_cycle
        m = self.n_steps
        amplitudes = [(k, A) for k, A in self.amplitudes if k in names]
        vals = {}
        if amplitudes:
            one = np.sin(2.0 * np.pi * np.arange(1, n + 1) / n)
            one[-1] = 0.0
            if n % 2 == 0:
                one[n // 2 - 1] = 0.0
            wave = np.tile(one, -(-m // n))[:m]
            mean = dict(self.mean or ())
            vals = {k: mean.get(k, start[k]) + A * wave for k, A in amplitudes}
        return (np.arange(1, m + 1) * self.period / n if time else None), vals


def _check_cycles(value: Any) -> float:
    """Whole cycles stay ints; fractional ones must be finite and > 0."""
    if isinstance(value, (int, np.integer)) and not isinstance(value, bool):
        if value <= 0:          # (not "an integer >= 1": fractions are allowed)
            raise ParameterError(f"cycles={value!r} is invalid: it must be > 0 (fractions "
                                 "allowed).")
        return check_steps("cycles", value)
    if isinstance(value, bool):
        raise ParameterError(f"cycles={value!r} is invalid: it must be a number > 0.")
    v = check_value("cycles", value)
    if v <= 0:
        raise ParameterError(f"cycles={value!r} is invalid: it must be > 0 (fractions allowed).")
    return int(v) if v.is_integer() else v


@dataclass(frozen=True)
class Repeat(Segment):
    """Run ``segments`` ``times`` times in a row (each run starts from the state reached)."""

    segments: tuple
    times: int = 1

    def __post_init__(self) -> None:
        object.__setattr__(self, "segments", tuple(self.segments))
        object.__setattr__(self, "times", check_steps("times", self.times))
        for s in self.segments:
            if not isinstance(s, Segment):
                raise ParameterError(f"segments contains {s!r}: expected Segment objects.")

    @property
    def controls(self) -> frozenset:
        out: set[str] = set()
        for s in self.segments:
            out |= set(s.controls)
        return frozenset(out)

    @property
    def n_steps(self) -> int:
        return self.times * sum(s.n_steps for s in self.segments)

    @property
    def duration(self) -> float:
        return self.times * sum(s.duration for s in self.segments)

    def values(self, start):  # pragma: no cover - composite, expanded by leaves()
        raise TypeError("Repeat is composite; iterate leaves().")

    def leaves(self) -> Iterator[Segment]:
        for _ in range(self.times):
            for s in self.segments:
                yield from s.leaves()


@dataclass(frozen=True, eq=False)
class Table(Segment):
    """Measured arrays, one step per row. ``time`` is relative to the table's first row, which
    is the segment's first step (time offsets ``time - time[0]``; the first row may coincide
    with the end of the previous segment)."""

    time: np.ndarray
    columns: tuple

    @classmethod
    def create(cls, time: Any, values: dict[str, Any]) -> "Table":
        if not values:
            raise ParameterError("from_arrays() needs at least one quantity array, e.g. "
                                 "force=[...].")
        check_quantities(values, "from_arrays()")
        cols = []
        n = None
        for k, v in values.items():
            arr = as_float_array(k, v)
            if arr.ndim != 1 or arr.size < 1:
                raise ParameterError(f"{k} must be a 1-D array with at least one value; got "
                                     f"shape {arr.shape}.")
            if n is not None and arr.size != n:
                raise ParameterError(f"{k} has {arr.size} values but other arrays have {n}; "
                                     "all arrays need the same length.")
            n = arr.size
            arr = arr.copy()
            arr.flags.writeable = False
            cols.append((k, arr))
        assert n is not None                    # values is not empty
        if time is None:
            t = np.arange(1, n + 1, dtype=float)
        else:
            t = as_float_array("time", time).copy()
            if t.shape != (n,):
                raise ParameterError(f"time has shape {t.shape}; it must match the {n} values.")
            if np.any(np.diff(t) < 0):
                i = int(np.argmax(np.diff(t) < 0))
                raise ParameterError(f"time is not ordered: time[{i + 1}]={t[i + 1]!r} s < "
                                     f"time[{i}]={t[i]!r} s; times must be non-decreasing.")
        t.flags.writeable = False
        return cls(t, tuple(cols))

    @property
    def controls(self) -> frozenset:
        return frozenset(k for k, _ in self.columns)

    @property
    def n_steps(self) -> int:
        return int(self.time.size)

    @property
    def duration(self) -> float:
        return float(self.time[-1] - self.time[0])

    def values(self, start):
        return self.time - self.time[0], {k: np.array(v) for k, v in self.columns}

    def values_readonly(self, start):
        return self.time - self.time[0], dict(self.columns)    # read-only since create()

    def values_of(self, start, names, *, time=True):
        return ((self.time - self.time[0]) if time else None,
                {k: v for k, v in self.columns if k in names})  # read-only since create()
