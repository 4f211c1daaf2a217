"""Parameter studies at scale: one call runs a sweep serially, on all cores or on a Dask cluster.

>>> import contactlab
>>> table = contactlab.sweep("examples/steel_ball_twist.toml",          # doctest: +SKIP
...                          {"interface.friction": [0.1, 0.2, 0.3]})

:func:`sweep` (also ``contactlab.sweep``) runs a study over a grid; :func:`to_dataset` turns the
table of a full grid into an xarray Dataset; :func:`read_store` reads a checkpoint folder;
:class:`SceneStudy` is a scene as a study; :func:`parse_axis` reads ``key=a:b:n[:log]``;
:func:`fretting_map_sweep` (also ``contactlab.fretting_map_sweep``) computes a large fretting map
on all cores or a Dask cluster; :func:`run_tasks` runs any list of array-valued tasks that way.
pandas is needed for the table (extra ``data``), dask.distributed for clusters (extra ``dist``);
neither is imported until used.
"""
from .fretting import fretting_map_sweep
from .grid import Grid, make_grid, parse_axis
from .keypath import parse_key_path, set_key_path
from .run import TARGET_OVERHEAD, batch_size, run_tasks, sweep
from .store import read_store
from .study import SceneStudy, scalars
from .table import to_dataset

__all__ = ["sweep", "to_dataset", "read_store", "SceneStudy", "scalars", "Grid", "make_grid",
           "parse_axis", "parse_key_path", "set_key_path", "batch_size", "TARGET_OVERHEAD",
           "fretting_map_sweep", "run_tasks"]
