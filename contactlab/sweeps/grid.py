"""Sweep grids: a dict of value lists (full product) or a table of rows.

:func:`make_grid` turns either form into a :class:`Grid`: the parameter names, one mapping per
point (in a fixed order: the product runs the last key fastest, like :func:`itertools.product`
and C-ordered arrays) and, for a full product, the axes (so the table can become an xarray
Dataset). :func:`parse_axis` reads the command-line form ``key=a:b:n[:log]``.
"""
from __future__ import annotations

import hashlib
import itertools
import json
import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from functools import cached_property
from typing import Any

import numpy as np

from ..errors import ParameterError
from ..params import check_memory

__all__ = ["Grid", "make_grid", "parse_axis"]

#: memory per grid point, bytes, checked against the memory budget before the product is built:
#: the point itself (measured 190-210 B with tracemalloc for 1-4 keys) and its record and table
#: row (a few dozen outputs), rounded up
POINT_BYTES = 1024

#: column names a sweep table reserves for itself
RESERVED = ("point", "error", "message", "warnings")


@dataclass(frozen=True)
class Grid:
    """The points of a sweep, held as one column of values per name.

    Attributes
    ----------
    names : tuple of str
        Parameter names (scene key paths or a study function's keyword names), in column order.
    columns : tuple of list
        One list of values per name; entry ``i`` of each is point ``i`` (row ``i`` of the result
        table). Columns, not one dict per point: a grid of 10^5 points is built, batched and
        tabulated without 10^5 small dicts.
    axes : dict or None
        ``{name: values}`` when the grid is the full product of these axes (dict-of-lists input),
        None for a table of rows.
    """

    names: tuple[str, ...]
    columns: tuple[list[Any], ...]
    axes: dict[str, list[Any]] | None

    def __len__(self) -> int:
        return len(self.columns[0]) if self.columns else 0

    def point(self, i: int) -> dict[str, Any]:
        """Point ``i`` as ``{name: value}``."""
        return {k: c[i] for k, c in zip(self.names, self.columns)}

    @cached_property
    def points(self) -> tuple[dict[str, Any], ...]:
        """Every point as ``{name: value}`` (built on first use)."""
        return tuple(dict(zip(self.names, values)) for values in zip(*self.columns))

    def fingerprint(self) -> str:
        """A hash of the names and every point's values (exact: floats by their repr)."""
        text = json.dumps([list(self.names),
                           [list(map(repr, values)) for values in zip(*self.columns)]])
        return hashlib.sha256(text.encode()).hexdigest()


_PLAIN = frozenset((bool, int, float, str))


def _plain(value: Any, where: str) -> Any:
    """A Python scalar (numbers, strings, bools) from a grid entry."""
    if type(value) not in _PLAIN:
        if isinstance(value, np.generic):
            value = value.item()
        if not isinstance(value, (bool, int, float, str)):
            raise ParameterError(f"{where}={value!r} is invalid: grid values must be numbers or "
                                 f"strings (got {type(value).__name__}).")
    if isinstance(value, float) and not math.isfinite(value):
        raise ParameterError(f"{where}={value!r} is invalid: grid values must be finite (a NaN "
                             "in the result table marks a failed point).")
    return value


def _column(values: Any, where: Callable[[int], str]) -> list[Any]:
    """``values`` (a list or 1D array) as a list of Python scalars, each checked by
    :func:`_plain` (``where(i)`` names entry ``i`` in a message). Whole columns of floats, of
    ints or of strings are converted and checked at once; anything else value by value."""
    if isinstance(values, np.ndarray):
        if (values.dtype.kind == "f" and np.isfinite(values).all()) or values.dtype.kind in "iuU":
            return values.tolist()                     # exact: float64 -> float, int64 -> int
        values = list(values)
    elif not isinstance(values, list):
        values = list(values)
    kinds = set(map(type, values))
    if kinds <= {float, np.float64}:
        arr = np.array(values, dtype=np.float64)
        if np.isfinite(arr).all():
            return arr.tolist() if np.float64 in kinds else values
    elif kinds == {int} or kinds == {str}:
        return values
    return [_plain(v, where(i)) for i, v in enumerate(values)]


def _size(values: Any) -> int | None:
    """The number of values of a grid axis without listing them (None when unknown)."""
    if isinstance(values, (str, bytes)):
        return None
    try:
        return len(values)
    except TypeError:                   # a generator: its values are listed, then checked
        return None
    except OverflowError:               # range(10**20): len() cannot say, the range can
        if isinstance(values, range):
            return max(0, (values.stop - values.start + values.step
                           - (1 if values.step > 0 else -1)) // values.step)
        return None


def _values(key: str, values: Any) -> list[Any]:
    if isinstance(values, (str, bytes)) or (not isinstance(values, (Sequence, np.ndarray)) \
            and not hasattr(values, "__iter__")):
        raise ParameterError(f"grid[{key!r}]={values!r} is invalid: give a list of values, "
                             f"e.g. [{values!r}].")
    if isinstance(values, np.ndarray) and values.ndim > 1:
        raise ParameterError(f"grid[{key!r}] has shape {values.shape}: give a 1D list of values "
                             "per key (the grid is their product).")
    arr = np.asarray(values).ravel() if isinstance(values, np.ndarray) else list(values)
    if not len(arr):
        raise ParameterError(f"grid[{key!r}] is empty: give at least one value.")
    return _column(arr, lambda i: f"grid[{key!r}][{i}]")


def _check_name(name: Any) -> str:
    if not isinstance(name, str) or not name:
        raise ParameterError(f"grid key {name!r} is invalid: keys must be non-empty strings.")
    if name in RESERVED:
        raise ParameterError(f"grid key {name!r} is invalid: {list(RESERVED)} are the sweep "
                             "table's own columns.")
    return name


def make_grid(grid: Any) -> Grid:
    """The :class:`Grid` of a dict of value lists or of a table of rows.

    Parameters
    ----------
    grid : dict of lists, pandas.DataFrame or list of dicts
        ``{"interface.friction": [0.1, 0.2], "load_path[1].sinusoid.twist": [1e-3, 2e-3]}``
        sweeps the full product (4 points, the last key running fastest); a DataFrame or a list
        of dicts with the same keys sweeps its rows, in order.

    Raises
    ------
    ParameterError
        An empty grid or axis, a value that is not a number or string, rows with different keys.

    Examples
    --------
    >>> g = make_grid({"a": [1, 2], "b": [0.5, 1.5]})
    >>> len(g), g.point(1)
    (4, {'a': 1, 'b': 1.5})
    """
    if isinstance(grid, Grid):
        return grid
    if isinstance(grid, Mapping):
        if not grid:
            raise ParameterError("grid={} is empty: give at least one key with a list of values.")
        names = tuple(_check_name(k) for k in grid)
        sizes = [_size(grid[k]) for k in names]      # the product's size before any list is made
        known = [m for m in sizes if m is not None]
        if len(known) == len(sizes):
            n = math.prod(known)
            check_memory("sweep grid", float(n) * POINT_BYTES,
                         f"{n} points = " + " x ".join(map(str, known)))
        axes = {k: _values(k, grid[k]) for k in names}
        n = math.prod(len(v) for v in axes.values())
        check_memory("sweep grid", float(n) * POINT_BYTES,
                     f"{n} points = " + " x ".join(str(len(v)) for v in axes.values()))
        if len(names) == 1:
            columns: tuple[list[Any], ...] = (list(axes[names[0]]),)
        else:
            columns = tuple(map(list, zip(*itertools.product(*axes.values()))))
        return Grid(names, columns, axes)
    if hasattr(grid, "columns") and hasattr(grid, "to_dict"):          # a pandas DataFrame
        names = tuple(_check_name(k) for k in grid.columns)
        if not len(grid) or not names:
            raise ParameterError("grid has no rows: give at least one point.")
        return Grid(names, tuple(_column(grid[k].to_numpy(), _row_entry(k)) for k in names), None)
    if isinstance(grid, Sequence) and not isinstance(grid, (str, bytes)):
        rows = list(grid)
        if rows and not all(isinstance(r, Mapping) for r in rows):
            raise ParameterError("grid rows must be dicts {name: value}, e.g. "
                                 "[{'interface.friction': 0.1}, {'interface.friction': 0.2}].")
        names = tuple(_check_name(k) for k in rows[0]) if rows else ()
    else:
        raise ParameterError(f"grid of type {type(grid).__name__} is invalid: give a dict of "
                             "value lists, a pandas DataFrame or a list of dicts.")
    if not rows or not names:
        raise ParameterError("grid has no rows: give at least one point.")
    keys = set(names)
    for i, row in enumerate(rows):
        if row.keys() != keys:
            raise ParameterError(f"grid row {i} has keys {sorted(row)}: every row needs exactly "
                                 f"the keys of row 0, {sorted(names)}.")
    return Grid(names, tuple(_column([r[k] for r in rows], _row_entry(k)) for k in names), None)


def _row_entry(key: str) -> Callable[[int], str]:
    """Names entry ``key`` of row ``i`` in a message: ``grid row 3 ['interface.friction']``."""
    return lambda i: f"grid row {i} [{key!r}]"


def _number_or_text(text: str) -> Any:
    t = text.strip()
    try:
        v = float(t)
    except ValueError:
        return t
    return int(v) if t.lstrip("+-").isdigit() else v


def parse_axis(spec: str) -> tuple[str, list[Any]]:
    """One grid axis from its command-line form.

    Forms: ``key=a:b:n`` (``n`` values evenly spaced from ``a`` to ``b``), ``key=a:b:n:log``
    (evenly spaced in the logarithm, ``a, b > 0``), ``key=v1,v2,...`` (the values as given;
    numbers or text such as ``"10 um"`` or ``exact``).

    Raises
    ------
    ParameterError
        Not ``key=values``, ``n`` not a positive integer, a log axis with a bound <= 0.

    Examples
    --------
    >>> parse_axis("interface.friction=0.1:0.3:3")
    ('interface.friction', [0.1, 0.2, 0.3])
    >>> parse_axis("x=1e-3:1e-1:3:log")[1]
    [0.001, 0.01, 0.1]
    """
    key, sep, rhs = spec.partition("=")
    key = key.strip()
    if not sep or not key or not rhs.strip():
        raise ParameterError(f"--grid {spec!r} is invalid: expected KEY=A:B:N[:log] or "
                             "KEY=V1,V2,..., e.g. interface.friction=0.1:0.5:9.")
    if ":" not in rhs:
        return key, [_number_or_text(v) for v in rhs.split(",") if v.strip()]
    parts = rhs.split(":")
    log = len(parts) == 4 and parts[3].strip().lower() == "log"
    if len(parts) not in (3, 4) or (len(parts) == 4 and not log):
        raise ParameterError(f"--grid {spec!r} is invalid: a range is A:B:N or A:B:N:log.")
    try:
        a, b = float(parts[0]), float(parts[1])
        n = int(parts[2])
    except ValueError as err:
        raise ParameterError(f"--grid {spec!r} is invalid: A and B must be numbers and N an "
                             "integer, e.g. 0.1:0.5:9.") from err
    if n < 1 or not (math.isfinite(a) and math.isfinite(b)):
        raise ParameterError(f"--grid {spec!r} is invalid: N={n} must be >= 1 and A, B finite.")
    check_memory(f"--grid {spec!r}", float(n) * POINT_BYTES,      # before the values are made
                 f"N={n} points x {POINT_BYTES} B")
    if log:
        if a <= 0 or b <= 0:
            raise ParameterError(f"--grid {spec!r} is invalid: a log axis needs A > 0 and B > 0.")
        vals = np.geomspace(a, b, n)
    else:
        vals = np.linspace(a, b, n)
    return key, [float(v) for v in vals]
