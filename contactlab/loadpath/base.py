"""Load paths: time-ordered sequences of controlled quantities, built from segments.

Quantities and their groups (one control per group at a time):

========== ==================== =====
group      quantity             unit
========== ==================== =====
normal     ``depth``, ``force`` m, N
tangential ``displacement``,    m, N
           ``tangential_force``
torsion    ``twist``, ``torque`` rad, N*m
========== ==================== =====

A group a segment does not control keeps its current control quantity at its current value.
Segments start from the state reached so far, so ``ramp(force=100)`` after a depth-controlled
segment ramps the force from its current value to 100 N.
"""
from __future__ import annotations

import difflib
from abc import ABC, abstractmethod
from collections.abc import Iterator
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np

from ..errors import ParameterError, UnknownNameError
from ..numeric.units import canonical_unit
from ..params import as_real

__all__ = ["LoadPath", "Segment", "Samples", "QUANTITIES", "GROUPS", "UNITS", "canonical_unit"]

QUANTITIES = ("depth", "force", "displacement", "tangential_force", "twist", "torque")
GROUPS = {"depth": "normal", "force": "normal", "displacement": "tangential",
          "tangential_force": "tangential", "twist": "torsion", "torque": "torsion"}
#: SI unit of each quantity, in the one spelling contactlab writes (products with ``*``)
UNITS = {"time": "s", "depth": "m", "force": "N", "displacement": "m", "tangential_force": "N",
         "twist": "rad", "torque": "N*m"}


def check_quantities(names: Any, where: str) -> None:
    """Known quantity names, at most one per group."""
    seen: dict[str, str] = {}
    for q in names:
        if q not in QUANTITIES:
            close = difflib.get_close_matches(str(q), QUANTITIES, n=1)
            hint = f" Did you mean {close[0]!r}?" if close else ""
            raise UnknownNameError(f"{where}: quantity {q!r} is unknown; allowed are "
                                   f"{QUANTITIES}.{hint}")
        g = GROUPS[q]
        if g in seen:
            raise ParameterError(f"{where}: {seen[g]!r} and {q!r} both control the {g} group; "
                                 "give at most one of them per segment.")
        seen[g] = q


def check_steps(name: str, value: Any) -> int:
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < 1:
        raise ParameterError(f"{name}={value!r} is invalid: it must be an integer >= 1.")
    return int(value)


def check_value(name: str, value: Any) -> float:
    v = as_real(name, value)        # the shared path: no bool, no str
    if not np.isfinite(v):
        raise ParameterError(f"{name}={value!r} is invalid: it must be finite.")
    return v


def check_duration(duration: Any, steps: int) -> float:
    if duration is None:
        return float(steps)
    v = check_value("duration", duration)
    if v <= 0:
        raise ParameterError(f"duration={duration!r} s is invalid: it must be > 0.")
    return v


class Segment(ABC):
    """One piece of a load path.

    To implement a subclass
    -----------------------
    1. Required: a frozen dataclass with ``controls`` (frozenset of quantities it prescribes),
       ``n_steps`` (int), ``duration`` (s), and ``values(start)`` returning
       ``(dt, {quantity: array})`` (time increments from the segment start, and the
       prescribed values per step; ``start`` holds the current value of every quantity).
    2. Optional: ``leaves()`` for composite segments (default: itself).
    3. Optional: ``values_readonly(start)``, :meth:`values` whose arrays may be read-only views
       of the segment's own data (no copy; default: :meth:`values`), for callers that only read.
    4. Optional: ``values_of(start, names, time=True)``, :meth:`values_readonly` of the
       quantities ``names`` only (default: :meth:`values_readonly`, filtered), for callers that
       read some of the controls: a segment that computes its values computes only those.
    """

    if TYPE_CHECKING:
        # the quantities the segment prescribes; a read-only property in every segment
        @property
        def controls(self) -> frozenset: ...

    @property
    @abstractmethod
    def n_steps(self) -> int: ...

    @abstractmethod
    def values(self, start: dict[str, float]) -> tuple[np.ndarray, dict[str, np.ndarray]]: ...

    def values_readonly(self, start: dict[str, float]
                        ) -> tuple[np.ndarray, dict[str, np.ndarray]]:
        """:meth:`values` for a caller that does not write into the arrays (they may be the
        segment's own read-only data: no copy of a 10^6-step table's columns)."""
        return self.values(start)

    def values_of(self, start: dict[str, float], names: Any, *, time: bool = True
                  ) -> tuple[np.ndarray | None, dict[str, np.ndarray]]:
        """:meth:`values_readonly` restricted to the quantities in ``names`` (those of them the
        segment controls; the same arrays) and, with ``time=False``, without the time increments
        (``None`` in their place). ``Contact.simulate`` reads the depth or force of a segment in
        its normal solve and the tangential and torsional controls in its time loop: each is
        computed once (a ramp or sinusoid computes only the quantities asked for)."""
        dt, vals = self.values_readonly(start)
        return (dt if time else None), {k: v for k, v in vals.items() if k in names}

    def leaves(self) -> Iterator["Segment"]:
        yield self


@dataclass(frozen=True, eq=False)
class Samples:
    """A load path sampled at its steps (see :meth:`LoadPath.sample`).

    Attributes
    ----------
    time : ndarray
        Time of each step, s.
    values : dict of ndarray
        Quantity -> prescribed value at each step (SI, see :data:`UNITS`), for every quantity
        the path controls; a segment that does not prescribe a quantity holds its last value.
    leaf : ndarray of int
        Index of the leaf segment (:meth:`LoadPath.leaves`) each step belongs to.
    """

    time: np.ndarray
    values: dict
    leaf: np.ndarray

    @property
    def n_steps(self) -> int:
        return int(self.time.size)


@dataclass(frozen=True)
class LoadPath:
    """A time-ordered sequence of :class:`Segment` s (immutable; builder calls return new paths).

    Examples
    --------
    >>> import contactlab as cl
    >>> path = (cl.LoadPath().ramp(force=100.0, steps=50).hold(steps=10)
    ...         .sinusoid(twist=8e-4, cycles=10, steps_per_cycle=200))
    >>> path.n_steps, sorted(path.controls)
    (2060, ['force', 'twist'])
    """

    segments: tuple = field(default=())

    def __post_init__(self) -> None:
        for s in self.segments:
            if not isinstance(s, Segment):
                raise ParameterError(f"segments contains {s!r}: expected Segment objects.")

    # ------------------------------------------------------------------ builder
    def then(self, segment: Segment) -> "LoadPath":
        """Return a new path with ``segment`` appended."""
        return LoadPath(self.segments + (segment,))  # noqa: RUF005 - kept: tuple + tuple

    def __add__(self, other: "LoadPath") -> "LoadPath":
        if not isinstance(other, LoadPath):
            return NotImplemented
        return LoadPath(self.segments + other.segments)

    def ramp(self, *, steps: int = 1, duration: float | None = None, **targets: float) -> "LoadPath":
        """Linear ramp of the given quantities from their current values to ``targets``.

        Example: ``path.ramp(force=100.0, steps=50)``.
        """
        from .segments import Ramp
        return self.then(Ramp(tuple(targets.items()), steps, duration))

    def hold(self, *, steps: int = 1, duration: float | None = None) -> "LoadPath":
        """Keep every controlled quantity at its current value for ``steps`` steps."""
        from .segments import Hold
        return self.then(Hold(steps, duration))

    def sinusoid(self, *, cycles: float = 1, steps_per_cycle: int = 100,
                 period: float | None = None, mean: dict[str, float] | None = None,
                 **amplitudes: float) -> "LoadPath":
        """``value = mean + amplitude sin(2π t/period)`` for ``cycles`` cycles (fractions allowed).

        ``mean`` defaults to the current value of each quantity. Example:
        ``path.sinusoid(twist=8e-4, cycles=10, steps_per_cycle=200)``.
        """
        from .segments import Sinusoid
        return self.then(Sinusoid(tuple(amplitudes.items()), cycles, steps_per_cycle, period,
                                  None if mean is None else tuple(mean.items())))

    def repeat(self, times: int, *, last: int | None = None) -> "LoadPath":
        """Run the last ``last`` segments (default: all so far) ``times`` times in total."""
        from .segments import Repeat
        times = check_steps("times", times)
        k = len(self.segments) if last is None else check_steps("last", last)
        if k > len(self.segments) or k == 0:
            raise ParameterError(f"last={last!r} is invalid: the path has {len(self.segments)} "
                                 "segment(s); give 1 <= last <= that.")
        return LoadPath(self.segments[:-k] + (Repeat(self.segments[-k:], times),))  # noqa: RUF005 - kept: tuple + tuple

    @classmethod
    def from_arrays(cls, *, time: Any = None, **values: Any) -> "LoadPath":
        """A path from measured arrays, one step per row.

        Parameters
        ----------
        time : array_like, optional
            Non-decreasing times, s (default 1, 2, ..., n).
        **values : array_like
            At most one quantity per group (``depth=`` or ``force=``; ``displacement=`` or
            ``tangential_force=``; ``twist=`` or ``torque=``), each of the same length.
        """
        from .segments import Table
        return cls((Table.create(time, values),))

    @classmethod
    def from_csv(cls, path: Any, **kwargs: Any) -> "LoadPath":
        """Read a path from CSV (see :func:`contactlab.loadpath.io.read_csv`)."""
        from .io import read_csv
        return read_csv(path, **kwargs)

    # ------------------------------------------------------------------ introspection
    def leaves(self) -> Iterator[Segment]:
        """Leaf segments in execution order (repeats expanded)."""
        for s in self.segments:
            yield from s.leaves()

    @property
    def n_steps(self) -> int:
        return int(sum(s.n_steps for s in self.segments))

    def sample(self, *, start_time: float = 0.0) -> "Samples":
        """The prescribed values at every step, leaf segment after leaf segment.

        Each segment starts from the values prescribed so far (0 before the first segment) and
        its times follow the previous segment's last time (``start_time`` before the first one),
        with the time arithmetic of :meth:`Contact.simulate`. A simulation starts each segment
        from the contact's response instead (a force computed back from the depth), which can
        differ from the prescribed value in the last digit.

        Parameters
        ----------
        start_time : float, optional
            Time the first segment starts from, s.

        Returns
        -------
        Samples
            ``time``, the values of every quantity the path controls, and the leaf index of
            each step.

        Raises
        ------
        ParameterError
            A group changes its control quantity (``depth`` then ``force``): the values of the
            new control at the switch depend on the contact's response, which only a simulation
            knows.

        Examples
        --------
        >>> s = LoadPath().ramp(force=2.0, steps=2).hold(steps=1).sample()
        >>> s.time.tolist(), s.values["force"].tolist(), s.leaf.tolist()
        ([1.0, 2.0, 3.0], [1.0, 2.0, 2.0], [0, 0, 1])
        """
        controls = self.controls
        by_group: dict[str, str] = {}
        for q in sorted(controls, key=QUANTITIES.index):
            g = GROUPS[q]
            if g in by_group:
                raise ParameterError(
                    f"sample(): the path controls the {g} group by both {by_group[g]!r} and "
                    f"{q!r}; the value of one after a segment driven by the other depends on the "
                    "contact's response. Use Contact.simulate(path), or one control per group.")
            by_group[g] = q
        cur = dict.fromkeys(QUANTITIES, 0.0)
        t0 = check_value("start_time", start_time)
        times, leaf_index = [], []
        vals: dict[str, list[np.ndarray]] = {q: [] for q in controls}
        for i, leaf in enumerate(self.leaves()):
            dt, v = leaf.values(cur)
            n = leaf.n_steps
            t = t0 + dt
            times.append(t)
            leaf_index.append(np.full(n, i))
            for q in controls:
                col = v[q] if q in v else np.full(n, cur[q])
                vals[q].append(col)
                cur[q] = float(col[-1])
            t0 = float(t[-1])
        if not times:
            return Samples(np.zeros(0), {}, np.zeros(0, dtype=int))
        return Samples(np.concatenate(times), {q: np.concatenate(vals[q]) for q in controls},
                       np.concatenate(leaf_index))

    @property
    def controls(self) -> frozenset:
        """Every quantity some segment prescribes."""
        out: set[str] = set()
        for s in self.segments:
            out |= set(s.controls)
        return frozenset(out)

    @property
    def groups(self) -> frozenset:
        """Load groups the path drives (``normal``, ``tangential``, ``torsion``)."""
        return frozenset(GROUPS[q] for q in self.controls)
