"""CSV input/output of load paths (measured histories).

Format: a header row naming the columns ``time`` (optional) and quantities (``depth`` or
``force``, ``displacement`` or ``tangential_force``, ``twist`` or ``torque``), each optionally
with a unit in the grammar of scene files (``time [ms]``, ``force (kN)``, ``twist/deg``,
``torque_N*m``); then one row per step, separated by commas, semicolons, tabs or whitespace
(detected; a UTF-8 byte-order mark is skipped). A column without a unit is SI; a
unit that is unknown or of another dimension is an error, never ignored. Written files use the
same ``name [unit]`` header style with SI units.
"""
from __future__ import annotations

import difflib
from typing import Any, cast

import numpy as np

from ..errors import TabulatedDataError
from ..numeric.tables import read_columns, write_columns
from .base import QUANTITIES, UNITS, LoadPath

__all__ = ["read_csv", "read_history", "write_csv"]

#: dimension of each load-path column (the unit grammar of :mod:`contactlab.numeric.units`)
DIMENSIONS = {"time": "time", "depth": "length", "force": "force", "displacement": "length",
              "tangential_force": "force", "twist": "angle", "torque": "torque"}


def read_history(path: Any, *, units: dict[str, str] | None = None,
                 delimiter: str | None = None, check_names: bool = True
                 ) -> dict[str, np.ndarray]:
    """Columns of a load-history CSV in SI units (``time`` and quantities).

    Parameters
    ----------
    path : path-like
        The CSV file.
    units : dict, optional
        Column name -> unit for columns whose header has none (``{"force": "kN"}``).
    delimiter : str, optional
        Column separator (default: detected: ``,``, ``;``, a tab or whitespace).
    check_names : bool
        Reject unknown column names (a scene validator reports them itself).

    Raises
    ------
    TabulatedDataError
        Unreadable file, no header, no data, unknown column name, a cell that is not a number.
    UnitError
        An unknown unit or one of the wrong dimension.
    """
    names, cols = read_columns(path, dimension=lambda n: DIMENSIONS.get(n),
                               units=cast("dict[str, str | None] | None", units),
                               delimiter=delimiter, known_names=tuple(DIMENSIONS))
    if any(n.startswith("column ") for n in names):
        raise TabulatedDataError(
            f"file={str(path)!r} has no header row: a load-path CSV starts with column names "
            f"such as 'time [s],force [kN],twist [deg]' (allowed: time, {', '.join(QUANTITIES)}).")
    for n in names if check_names else ():
        if n not in DIMENSIONS:
            close = difflib.get_close_matches(n, list(DIMENSIONS), n=1)
            hint = f" Did you mean {close[0]!r}?" if close else ""
            raise TabulatedDataError(f"file={str(path)!r}: column {n!r} is unknown; allowed are "
                                     f"time, {', '.join(QUANTITIES)}.{hint}")
    if len(set(names)) != len(names):
        raise TabulatedDataError(f"file={str(path)!r}: a column name repeats ({names}).")
    for n, col in cols.items():
        if not np.all(np.isfinite(col)):
            i = int(np.argmax(~np.isfinite(col)))
            raise TabulatedDataError(f"file={str(path)!r}: {n}[{i}]={float(col[i])!r} is not "
                                     "finite.")
    return cols


def read_csv(path: Any, *, delimiter: str | None = None,
             units: dict[str, str] | None = None) -> LoadPath:
    """Read a :class:`LoadPath` (one :class:`~contactlab.loadpath.segments.Table`) from CSV.

    The table composes with other segments: ``LoadPath().ramp(force=300.0, steps=20) +
    LoadPath.from_csv("gait.csv")``, then ``.repeat(100, last=1)``.
    """
    cols = read_history(path, units=units, delimiter=delimiter)
    time = cols.pop("time", None)
    if not cols:
        raise TabulatedDataError(f"file={str(path)!r} has no quantity column; give at least one "
                                 f"of {', '.join(QUANTITIES)}.")
    return LoadPath.from_arrays(time=time, **cols)


def write_csv(path: Any, columns: dict[str, np.ndarray], *, units: dict[str, str] | None = None,
              ) -> None:
    """Write equal-length columns with ``name [unit]`` headers (SI units by default)."""
    write_columns(path, columns, UNITS if units is None else units)
