"""Reading and writing numeric CSV tables with units in the header (``r [mm], f [um]``).

One reader serves measured profiles and measured load histories, so both accept the same
header grammar (:func:`~contactlab.numeric.units.split_header`), the same unit spellings
(:mod:`contactlab.numeric.units`) and fail with the same errors: a file that cannot be read, a
row with too few numbers, a unit that is unknown or of the wrong dimension. Written tables use
one header style, ``name [unit]``.
"""
from __future__ import annotations

import csv
import math
import os
import re
from collections.abc import Mapping
from typing import Any
from collections.abc import Callable

import numpy as np

from ..errors import ParameterError, TabulatedDataError, UnitError
from .units import (_allowed, canonical_unit, dimension_of_unit, split_header,
                    underscore_unit, unit_factor)

__all__ = ["read_columns", "write_columns"]


#: column separators a file may use (whitespace: runs of spaces or tabs, detected last)
_DELIMITERS = (",", ";", "\t")
#: a whitespace-separated header cell: a name with an optional bracketed unit (``r [mm]``)
_WS_CELL = re.compile(r"[^\s\[(]+(?:\s*[\[(][^\])]*[\])])?|[\[(][^\])]*[\])]")


def _detect(lines: list[str]) -> str | None:
    """The separator of the non-comment ``lines``: ``;`` if they hold more of them than commas
    (decimal commas), else ``,`` if any; a tab if every line has one; else None (whitespace)."""
    text = "\n".join(lines)
    if ";" in text and text.count(";") > text.count(","):
        return ";"
    if "," in text:
        return ","
    if lines and all("\t" in ln for ln in lines):
        return "\t"
    return None


def _rows(path: Any, delimiter: str | None) -> list[list[str]]:
    try:
        # utf-8-sig: a byte-order mark (spreadsheet exports) is not part of the first header
        with open(os.fspath(path), newline="", encoding="utf-8-sig") as fh:
            text = fh.read()
    except (OSError, TypeError, ValueError) as err:
        raise TabulatedDataError(f"file={str(path)!r} cannot be read: "
                                 f"{getattr(err, 'strerror', None) or err}.") from err
    lines = [ln for ln in text.splitlines()
             if ln.strip() and not ln.lstrip().startswith("#")]
    delim = delimiter or _detect(lines)
    if delim is None or delim == " ":
        # whitespace-separated: a header cell keeps its bracketed unit ("r [mm]  f [um]")
        return [_WS_CELL.findall(ln) if i == 0 else ln.split() for i, ln in enumerate(lines)]
    return [[c.strip() for c in row] for row in csv.reader(lines, delimiter=delim)
            if row and any(c.strip() for c in row)]


def _check_arguments(units: Any, delimiter: Any) -> None:
    """``units`` a mapping of column name (or position) -> unit string; ``delimiter`` one
    character or None."""
    if delimiter is not None and not (isinstance(delimiter, str) and len(delimiter) == 1
                                      and delimiter not in "\r\n\"'"):
        raise ParameterError(f"delimiter={delimiter!r} is invalid: give one character such as "
                             "',' or ';' (None detects it).")
    if units is None:
        return
    if not isinstance(units, Mapping):
        raise ParameterError(f"units={units!r} is invalid: give a mapping of column name to "
                             "unit, e.g. {'force': 'kN'}.")
    for key, unit in units.items():
        if isinstance(key, bool) or not isinstance(key, (str, int)):
            raise ParameterError(f"units key {key!r} is invalid: give a column name (str) or a "
                                 "column position (int).")
        if unit is not None and not isinstance(unit, str):
            raise ParameterError(f"units[{key!r}]={unit!r} is invalid: a unit is a string such "
                                 "as 'kN', 'mm' or 'deg'.")


def _is_number(text: str) -> bool:
    try:
        float(text)
    except ValueError:
        return False
    return True


def read_columns(path: Any, *, names: tuple[str, ...] | None = None,
                 dimension: Callable[[str], str | None] | tuple[str | None, ...],
                 units: dict[str, str | None] | None = None,
                 delimiter: str | None = None, min_columns: int = 1, quote: bool = True,
                 known_names: tuple[str, ...] | None = None,
                 ) -> tuple[list[str], dict[str, np.ndarray]]:
    """Read a CSV table and convert every column to SI.

    Parameters
    ----------
    path : path-like
        The file. Lines starting with ``#`` are comments.
    names : tuple of str, optional
        Column names to use when the file has no header row (positional columns).
    dimension : callable
        Column name -> its dimension (``"length"``, ``"force"``, ...; see
        :data:`~contactlab.numeric.units.UNITS`), None for a column of plain numbers, or
        ``"ignore"`` for a column that is read but neither converted nor checked. A tuple gives
        the dimensions by position; columns beyond it are ignored.
    units : dict, optional
        Column name or position -> unit given by the caller (``{"force": "kN"}``, ``{0: "mm"}``);
        it must agree with a unit in the header, if there is one.
    delimiter : str, optional
        Column separator; default: detected, ``;`` if the file holds more of them than commas,
        else ``,`` if it holds any, else a tab if every line has one, else runs of whitespace
        (a header cell ``r [mm]`` keeps its unit). A UTF-8 byte-order mark is skipped.
    min_columns : int
        Columns every row must have.
    quote : bool
        Quote the file in error messages (a cell that is not a number, the header's names and
        units). False names rows and columns by position only: scene files use it, so that a
        file named by mistake (or on purpose) is never shown.
    known_names : tuple of str, optional
        Column names the caller knows: ``force_lbf`` then reads as ``force`` in the unknown unit
        ``lbf`` (an error), and ``tangential_force`` stays a name. Headers give units as
        ``r [mm]``, ``r (mm)``, ``r/mm`` or ``r_mm`` (:func:`~contactlab.numeric.units.split_header`).

    Returns
    -------
    names : list of str
        Column names (from the header, or ``names``).
    columns : dict of ndarray
        Column name -> values in SI units.

    Raises
    ------
    TabulatedDataError
        Unreadable file, no data rows, too few columns, a cell that is not a number, a unit
        given both in the header and by the caller that disagree.
    UnitError
        A unit that is unknown or of another dimension than the column's.
    """
    _check_arguments(units, delimiter)
    rows = _rows(path, delimiter)
    where = f"file={str(path)!r}"

    def q(text: Any) -> str:
        return repr(text) if quote else "(not shown)"

    def cname(j: int, name: str) -> str:
        return repr(name) if quote else f"{j + 1}"

    header: list[str] | None = None
    if rows and not all(_is_number(c) for c in rows[0] if c):
        header, rows = rows[0], rows[1:]
    if not rows:
        raise TabulatedDataError(f"{where} holds no data rows (expected a header row, then one "
                                 "row of numbers per point).")
    if header is not None:
        parsed = [split_header(h, known_names) for h in header]
        col_names = [n for n, _ in parsed]
        header_units = {n: u for n, u in parsed}
    else:
        width = len(rows[0])
        col_names = list(names[:width]) if names else [f"column {i}" for i in range(width)]
        header_units = {}
    if len(col_names) < min_columns:
        raise TabulatedDataError(
            f"{where} has {len(col_names)} column(s)"
            + (f" ({', '.join(col_names)})" if quote else "") + ": it needs at "
            f"least {min_columns}" + (f" ({', '.join(names[:min_columns])})" if names else "")
            + ".")
    width = len(col_names)
    data = np.empty((len(rows), width))
    for i, row in enumerate(rows):
        cells = [c for c in row]
        if len(cells) < width or any(c != "" for c in cells[width:]):
            raise TabulatedDataError(
                f"{where}: data row {i + 1} has {len(cells)} value(s)"
                + (f" {cells!r}" if quote else "") + f"; every row needs {width}"
                + (f" ({', '.join(col_names)})." if quote else "."))
        for j in range(width):
            try:
                data[i, j] = float(cells[j])
            except ValueError:
                raise TabulatedDataError(
                    f"{where}: data row {i + 1}, column {cname(j, col_names[j])} holds "
                    f"{q(cells[j])}, which is not a number.") from None
    given: dict[Any, str | None] = dict(units or {})   # keys: column names or positions
    for key in given:
        if key not in col_names and not (isinstance(key, int) and 0 <= key < len(col_names)):
            raise ParameterError(f"units names column {key!r}, which {where} does not have "
                                 + (f"(its columns: {', '.join(col_names)})." if quote
                                    else f"(it has {len(col_names)} columns)."))
    out: dict[str, np.ndarray] = {}
    for j, name in enumerate(col_names):
        if isinstance(dimension, tuple):
            dim = dimension[j] if j < len(dimension) else "ignore"
        else:
            dim = dimension(name)
        unit_h = header_units.get(name)
        unit_a = given.get(name, given.get(j))
        col = data[:, j]
        if dim == "ignore":
            out[name] = col
            continue
        if dim is None:
            if unit_h not in (None, "", "1", "-"):
                raise UnitError(f"{where}: column {cname(j, name)} has unit {q(unit_h)}, but it "
                                "takes plain numbers.",
                                [(f"{name} [unit]", unit_h, "no unit")] if quote else [])
            out[name] = col
            continue
        if unit_h is None and header is not None and isinstance(dimension, tuple):
            # positional columns of a dimension (a profile's r, f): 'r_furlong' is a unit
            # spelling we do not know, never a column in metres
            unit_h = underscore_unit(name)
        try:
            factor_h = None if unit_h is None else unit_factor(unit_h, dim, f"{name} [unit]")
        except UnitError as err:
            assert unit_h is not None   # only a unit that is there can be refused
            if not quote:
                raise UnitError(f"{where}: the unit in the header of column {j + 1} is unknown "
                                f"or not a unit of {dim}.") from None
            other = dimension_of_unit(canonical_unit(unit_h))
            why = (f"of dimension {other}, not {dim}" if other is not None
                   else f"not a unit contactlab knows (units of {dim}: {_allowed(dim)})")
            base = name[:-len(unit_h) - 1] if name.endswith("_" + unit_h) else name
            raise UnitError(f"{where}: column {name!r} has unit {unit_h!r}, {why}; write it "
                            f"as '{base} [<unit>]' with a unit of {dim}.",
                            issues=err.issues) from None
        factor_a = None if unit_a is None else unit_factor(unit_a, dim, f"unit of {name}")
        if factor_h is not None and factor_a is not None and not math.isclose(factor_h, factor_a):
            raise TabulatedDataError(
                f"{where}: column {cname(j, name)} is in {q(unit_h)} by its header but "
                f"{unit_a!r} was "
                f"given as an argument; give one unit, or make them agree.")
        factor = factor_h if factor_h is not None else (factor_a if factor_a is not None else 1.0)
        out[name] = col * factor if factor != 1.0 else col
    return col_names, out


def write_columns(path: Any, columns: dict[str, Any], units: dict[str, str]) -> None:
    """Write equal-length columns with ``name [unit]`` headers (``name`` alone when the column
    has no unit in ``units``); values as ``repr`` of floats, so they read back bit for bit."""
    names = list(columns)
    arrs = [np.asarray(columns[n], float).ravel() for n in names]
    with open(os.fspath(path), "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow([f"{n} [{units[n]}]" if units.get(n) else n for n in names])
        for row in zip(*arrs):
            w.writerow([repr(float(v)) for v in row])
