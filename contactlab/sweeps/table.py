"""The result table of a sweep (pandas) and its xarray view for full grids."""
from __future__ import annotations

import math
from typing import Any

import numpy as np

from ..errors import ParameterError
from .grid import RESERVED, Grid
from .study import Records

__all__ = ["assemble", "to_dataset", "output_name", "column_units", "write_table",
           "table_csv_text"]


def column_units(columns: list[str]) -> dict[str, str]:
    """SI unit of each column of a sweep table whose name (without ``output.``, ``_min`` or
    ``_max``) is a scene series (:data:`contactlab.scene.run.SERIES_UNITS`); other columns
    (grid keys, ``point``, ``error``, ...) have none (``""``)."""
    from ..scene.run import SERIES_UNITS
    out = {}
    for c in columns:
        base = str(c).removeprefix("output.")
        for tail in ("_min", "_max"):
            if base.endswith(tail) and base[: -len(tail)] in SERIES_UNITS:
                base = base[: -len(tail)]
        out[c] = SERIES_UNITS.get(base, "")
    return out


def table_notes(table: Any) -> list[str]:
    """The distinct warnings recorded by the points of a sweep table, in point order."""
    notes: list[str] = []
    for w in table["warnings"] if "warnings" in table else ():
        if isinstance(w, str) and w and w not in notes:
            notes.append(w)
    return notes


def table_csv_text(table: Any) -> str:
    """A sweep table as CSV text in the result protocol's style: ``# notes: ...`` lines (the
    distinct warnings of the points) when there are any, ``name [unit]`` headers for the
    columns with a unit (:func:`column_units`). Read it back with
    ``pandas.read_csv(path, comment="#")``."""
    from ..effects._protocol import metadata_lines
    units = table.attrs.get("units") or column_units(list(table.columns))
    named = table.rename(columns={c: f"{c} [{u}]" for c, u in units.items() if u})
    lines = metadata_lines({"notes": table_notes(table)})
    return "".join(line + "\n" for line in lines) + named.to_csv(index=False)


def write_table(table: Any, path: Any) -> None:
    """Write a sweep table as CSV (:func:`table_csv_text`)."""
    with open(path, "w", newline="") as fh:
        fh.write(table_csv_text(table))


def _pandas() -> Any:
    try:
        import pandas
    except ImportError as err:
        raise ImportError("sweep results are pandas DataFrames: pip install "
                          "'contactlab[data]'") from err
    return pandas


def output_name(name: str, grid: Grid) -> str:
    """An output named like a grid key or a table column becomes ``output.<name>``."""
    return f"output.{name}" if name in grid.names or name in RESERVED else name


def _array(col: list[Any]) -> Any:
    """A column of Python floats as a float64 array (what pandas would make of it, made here in
    one step); any other column as it is, for pandas to infer."""
    if col and set(map(type, col)) == {float}:
        return np.array(col, dtype=np.float64)
    return col


def _first_point(points: list[int], col: list[Any]) -> int | None:
    """The lowest point whose entry of ``col`` is not None."""
    if col.count(None) == 0:
        return min(points)
    return min((points[j] for j, v in enumerate(col) if v is not None), default=None)


def assemble(grid: Grid, records: Records | list[Records]) -> Any:
    """One row per point, in point order: ``point``, the grid values, the outputs (in the order
    the lowest-numbered point returned them), ``error``, ``message``, ``warnings``.

    Built from the records alone, column by column, so the table is the same whichever backend
    computed them, in whatever batches and order they arrived.
    """
    pd = _pandas()
    chunks = [records] if isinstance(records, Records) else list(records)
    chunks = sorted((c for c in chunks if len(c)), key=lambda c: c.point[0])
    # an output's column position: the first point that returned it, then that point's own order
    rank: dict[str, tuple[int, int]] = {}
    for chunk in chunks:
        for pos, (key, col) in enumerate(chunk.outputs.items()):
            first = _first_point(chunk.point, col)
            if first is not None and (key not in rank or (first, pos) < rank[key]):
                rank[key] = (first, pos)
    outputs = sorted(rank, key=rank.__getitem__)
    if len(chunks) == 1:
        rec = chunks[0]
    else:
        rec = Records()
        for chunk in chunks:
            rec.extend(chunk)
    points = rec.point
    n = len(points)
    if points == sorted(points):                # batches arrive whole: usually nothing to do
        def order(col: list[Any]) -> list[Any]:
            return col
    else:
        perm = sorted(range(n), key=points.__getitem__)

        def order(col: list[Any]) -> list[Any]:
            return [col[j] for j in perm]
        points = order(points)
    data: dict[str, Any] = {"point": np.array(points, dtype=np.int64)}
    every = n == len(grid) and (n == 0 or (points[0] == 0 and points[-1] == n - 1))
    for name, col in zip(grid.names, grid.columns):
        data[name] = _array(col if every else [col[i] for i in points])
    nan = math.nan
    for key in outputs:
        col = order(rec.outputs[key])
        data[key] = _array([nan if v is None else v for v in col] if col.count(None) else col)
    df = pd.DataFrame(data, columns=["point", *grid.names, *outputs])
    for field in ("error", "message", "warnings"):  # None (not NaN) where nothing happened
        df[field] = pd.Series(order(getattr(rec, field)), index=df.index, dtype=object)
    df.attrs["sweep"] = {"axes": grid.axes, "names": list(grid.names)}
    df.attrs["units"] = column_units(list(df.columns))
    df.attrs["notes"] = table_notes(df)
    return df


def to_dataset(table: Any, axes: dict[str, list[Any]] | None = None) -> Any:
    """The sweep table of a full grid as an :class:`xarray.Dataset`, one dimension per axis.

    Parameters
    ----------
    table : pandas.DataFrame
        A table returned by :func:`~contactlab.sweep` for a dict-of-lists grid.
    axes : dict, optional
        ``{name: values}``; default the axes the table carries in ``table.attrs["sweep"]``.

    Raises
    ------
    ParameterError
        The table is not a full grid (rows, or attributes lost) and no ``axes`` were given.
    """
    try:
        import xarray  # noqa: F401
    except ImportError as err:
        raise ImportError("to_dataset needs xarray: pip install 'contactlab[data]'") from err
    axes = axes or table.attrs.get("sweep", {}).get("axes")
    if not axes:
        raise ParameterError("table is not a full grid: a Dataset needs the grid axes (the sweep "
                             "of a dict of lists carries them); pass axes={name: values}.")
    ds = table.drop(columns=["point"]).set_index(list(axes)).to_xarray()
    return ds.reindex({k: list(v) for k, v in axes.items()})
