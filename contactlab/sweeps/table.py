"""The result table of a sweep (pandas) and its xarray view for full grids."""
from __future__ import annotations

import math
from typing import Any

from ..errors import ParameterError
from .grid import RESERVED, Grid

__all__ = ["assemble", "to_dataset", "output_name"]


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


def assemble(grid: Grid, records: dict[int, dict[str, Any]]) -> Any:
    """One row per point, in point order: ``point``, the grid values, the outputs (in the order
    the lowest-numbered point returned them), ``error``, ``message``, ``warnings``.

    Built from the records alone, so the table is the same whichever backend computed them and
    in whatever order they arrived.
    """
    pd = _pandas()
    order = sorted(records)
    outputs: dict[str, None] = {}
    for i in order:
        outputs.update(dict.fromkeys(records[i]["outputs"]))
    rows = []
    for i in order:
        r = records[i]
        row: dict[str, Any] = {"point": i, **grid.points[i]}
        row.update({k: r["outputs"].get(k, math.nan) for k in outputs})
        row.update(error=r["error"], message=r["message"], warnings=r["warnings"])
        rows.append(row)
    columns = ["point", *grid.names, *outputs, "error", "message", "warnings"]
    df = pd.DataFrame(rows, columns=columns)
    for col in ("error", "message", "warnings"):    # None (not NaN) where nothing happened
        df[col] = pd.Series([records[i][col] for i in order], index=df.index, dtype=object)
    df.attrs["sweep"] = {"axes": grid.axes, "names": list(grid.names)}
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
