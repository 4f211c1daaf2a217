"""CSV input/output of load paths (measured histories).

Format: a header row naming the columns ``time`` (optional) and quantities (``depth`` or
``force``, ``displacement`` or ``tangential_force``, ``twist`` or ``torque``), optionally with a
unit in brackets that must be the SI unit (``force [N]``, ``torque [N*m]``; ``N m`` and ``N·m`` are
read as ``N*m``); then one row per step.
"""
from __future__ import annotations

import csv
import os
from typing import Any

import numpy as np

from ..errors import ParameterError, TabulatedDataError
from .base import UNITS, LoadPath, canonical_unit

__all__ = ["read_csv", "write_csv"]


def _parse_header(name: str) -> str:
    name = name.strip()
    if "[" in name:
        q, unit = name.split("[", 1)
        q, unit = q.strip(), unit.rstrip("]").strip()
        if q in UNITS and canonical_unit(unit) != UNITS[q]:
            raise ParameterError(f"column {name!r}: unit {unit!r} is invalid; {q} must be given "
                                 f"in {UNITS[q]}.")
        return q
    return name


def read_csv(path: Any, *, delimiter: str = ",") -> LoadPath:
    """Read a :class:`LoadPath` (one :class:`~contactlab.loadpath.segments.Table`) from CSV."""
    with open(os.fspath(path), newline="") as fh:
        rows = [r for r in csv.reader(fh, delimiter=delimiter) if r and not r[0].startswith("#")]
    if len(rows) < 2:
        raise TabulatedDataError(f"{path}: a load-path CSV needs a header and at least one row.")
    names = [_parse_header(h) for h in rows[0]]
    try:
        data = np.array([[float(v) for v in r] for r in rows[1:]], dtype=float)
    except ValueError as err:
        raise TabulatedDataError(f"{path}: every value must be a number ({err}).") from err
    if data.ndim != 2 or data.shape[1] != len(names):
        raise TabulatedDataError(f"{path}: every row needs {len(names)} values.")
    cols = {n: data[:, i] for i, n in enumerate(names)}
    time = cols.pop("time", None)
    return LoadPath.from_arrays(time=time, **cols)


def write_csv(path: Any, columns: dict[str, np.ndarray], *, units: dict[str, str] | None = None,
              ) -> None:
    """Write equal-length columns with ``name [unit]`` headers."""
    units = UNITS if units is None else units
    names = list(columns)
    arrs = [np.asarray(columns[n], float).ravel() for n in names]
    with open(os.fspath(path), "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow([f"{n} [{units[n]}]" if n in units else n for n in names])
        for row in zip(*arrs):
            w.writerow([repr(float(v)) for v in row])
