"""The result table of a sweep (pandas) and its xarray view for full grids."""
from __future__ import annotations

import math
from typing import Any

from ..errors import ParameterError
from .grid import RESERVED, Grid
from .study import Records

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


def assemble(grid: Grid, records: Records | list[Records]) -> Any:
    """One row per point, in point order: ``point``, the grid values, the outputs (in the order
    the lowest-numbered point returned them), ``error``, ``message``, ``warnings``.

    Built from the records alone, column by column, so the table is the same whichever backend
    computed them, in whatever batches and order they arrived.
    """
    pd = _pandas()
    chunks = [records] if isinstance(records, Records) else list(records)
    rec = Records()
    for chunk in chunks:
        rec.extend(chunk)
    n = len(rec)
    order = sorted(range(n), key=rec.point.__getitem__)
    # an output's column position: the first point that returned it, then that point's own order
    rank: dict[str, tuple[int, int]] = {}
    for chunk in chunks:
        for pos, (key, col) in enumerate(chunk.outputs.items()):
            first = min((chunk.point[j] for j, v in enumerate(col) if v is not None),
                        default=None)
            if first is not None and (key not in rank or (first, pos) < rank[key]):
                rank[key] = (first, pos)
    outputs = sorted(rank, key=rank.__getitem__)
    points = [rec.point[j] for j in order]
    data: dict[str, Any] = {"point": points}
    for name in grid.names:
        data[name] = [grid.points[i][name] for i in points]
    nan = math.nan
    for key in outputs:
        col = rec.outputs[key]
        data[key] = [nan if col[j] is None else col[j] for j in order]
    df = pd.DataFrame(data, columns=["point", *grid.names, *outputs])
    for col in ("error", "message", "warnings"):    # None (not NaN) where nothing happened
        values = getattr(rec, col)
        df[col] = pd.Series([values[j] for j in order], index=df.index, dtype=object)
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
