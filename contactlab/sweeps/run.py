"""``sweep``: one call for a parameter study, serially, on all local cores or on a Dask cluster.

The flow: the grid becomes points (:mod:`.grid`); a store, if given, supplies the points already
finished (:mod:`.store`); the first points run here, which times a point; the backend is chosen
(:mod:`.backends`) and its per-task round trip measured; the remaining points go out in batches
large enough that this round trip costs under :data:`TARGET_OVERHEAD` of a batch's compute time
(:func:`batch_size`); records come back in any order and the table is assembled by point
(:mod:`.table`), so it does not depend on the backend.
"""
from __future__ import annotations

import math
import os
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

from ..errors import ContactlabError, ParameterError
from .backends import DaskClient, Pool, Serial
from .grid import Grid, make_grid
from .store import Store
from .study import SceneStudy, as_study, evaluate, study_id
from .table import _pandas, assemble, output_name

__all__ = ["sweep", "batch_size", "TARGET_OVERHEAD"]

#: per-task overhead allowed, as a fraction of a batch's compute time
TARGET_OVERHEAD = 0.1
#: at least this many batches per worker while the overhead target allows (load balance)
BATCHES_PER_WORKER = 4
#: ``workers=None`` runs in this process when the whole sweep should take less than this (s)
SERIAL_BELOW_SECONDS = 1.0
#: points timed here before choosing the backend: the first warms caches, the rest are timed
CALIBRATION_POINTS = 3
#: a point slower than this (s) needs no more timing: batches of one already meet the target
SLOW_POINT_SECONDS = 0.05
#: a progress bar is shown when the sweep is expected to take longer than this (s)
PROGRESS_SECONDS = 2.0


def batch_size(point_seconds: float, overhead_seconds: float, remaining: int, workers: int) -> int:
    """Points per task so that the per-task overhead stays under :data:`TARGET_OVERHEAD`.

    The size is the smallest ``b`` with ``overhead <= TARGET_OVERHEAD * b * point_seconds``,
    reduced to leave :data:`BATCHES_PER_WORKER` batches per worker when the sweep is that
    small (then the whole sweep takes only a few round trips).

    Examples
    --------
    >>> batch_size(point_seconds=1e-4, overhead_seconds=2e-3, remaining=100_000, workers=2)
    200
    >>> batch_size(point_seconds=1.0, overhead_seconds=2e-3, remaining=100, workers=2)
    1
    """
    need = math.ceil(overhead_seconds / (TARGET_OVERHEAD * max(point_seconds, 1e-9)) - 1e-9)
    balance = math.ceil(remaining / (BATCHES_PER_WORKER * max(workers, 1)))
    return max(1, min(need, balance))


def _bar(total: int, initial: int, show: bool) -> Any:
    if not show:
        return None
    try:
        from tqdm.auto import tqdm
    except ImportError:
        return None
    return tqdm(total=total, initial=initial, unit="point", desc="sweep")


def _check_workers(workers: Any, client: Any) -> None:
    if client is not None and workers is not None:
        raise ParameterError(f"workers={workers!r} with client=: give one; the cluster behind "
                             "the client decides the workers.")
    if workers is not None and (isinstance(workers, bool) or not isinstance(workers, int)
                                or workers < 1):
        raise ParameterError(f"workers={workers!r} is invalid: give an integer >= 1 (1 runs "
                             "serially in this process) or None for every local core.")


def _cpu_count() -> int:
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:       # pragma: no cover - platforms without affinity
        return os.cpu_count() or 1


def sweep(study: Any, grid: Any, *, client: Any = None, workers: int | None = None,
          progress: bool = True, on_error: str = "record", store: str | Path | None = None,
          batch_size: int | None = None, allow_outside: bool | None = None) -> Any:
    """Run a study at every point of a grid: serially, on all local cores or on a Dask cluster.

    Parameters
    ----------
    study : Scene, path, mapping or callable
        A scene (a :class:`~contactlab.scene.Scene`, a TOML file or its tables) whose values the
        grid overrides by key path (``"interface.friction"``, ``"load_path[1].sinusoid.twist"``),
        or a picklable function of keyword arguments (one per grid name) returning a dict of
        numbers or a contactlab result (see :func:`~contactlab.sweeps.scalars`).
    grid : dict of lists, pandas.DataFrame or list of dicts
        A dict of value lists sweeps their full product (the last key runs fastest); a table
        sweeps its rows. Scene values may carry units (``"10 um"``).
    client : dask.distributed.Client, optional
        Run on this cluster (a ``LocalCluster`` or a remote scheduler).
    workers : int, optional
        Without a client: the size of the local process pool; 1 runs serially in this process;
        None (default) uses every core, or this process for a sweep expected to take under
        :data:`SERIAL_BELOW_SECONDS`.
    progress : bool
        Show a progress bar (tqdm, if installed) for sweeps expected to take over
        :data:`PROGRESS_SECONDS`.
    on_error : {"record", "raise"}
        ``"record"`` (default): a point that raises gets its error class, message and NaN
        outputs in its row and the sweep goes on. ``"raise"``: the first failure stops the sweep
        and its exception is raised (recomputed here, with its traceback).
    store : path, optional
        A checkpoint folder (``"study.parquet"``): results are written as they arrive and a
        sweep started again with the same study, grid and store computes only the missing points.
    batch_size : int, optional
        Points per task; default chosen so the per-task overhead stays under
        :data:`TARGET_OVERHEAD` of the compute time (see :func:`batch_size`).
    allow_outside : bool, optional
        Scene studies: let relative file names in the scene (tables, histories) leave the scene's
        folder, as ``contactlab run --allow-outside``; default: the Scene's own setting (False
        for files and tables).

    Returns
    -------
    pandas.DataFrame
        One row per point, in grid order: ``point``, the grid values, the outputs, ``error``
        and ``message`` (None for a point that succeeded), ``warnings`` (each distinct warning
        as ``"Class: text"``, or None). The same for every backend, bit for bit.
        ``table.attrs["sweep"]`` holds the grid axes (:func:`~contactlab.sweeps.to_dataset`
        makes an xarray Dataset of a full grid) and ``stats`` of the run.

    Raises
    ------
    ParameterError
        An invalid grid, a grid key that is no key of the scene, bad ``workers``/``on_error``,
        a store of another sweep.
    ImportError
        pandas missing (``pip install 'contactlab[data]'``); pyarrow for ``store=``;
        dask.distributed for ``client=``.

    Examples
    --------
    >>> import contactlab
    >>> def study(x, y):
    ...     return {"sum": x + y}
    >>> table = contactlab.sweep(study, {"x": [1.0, 2.0], "y": [10.0, 20.0]})  # doctest: +SKIP
    >>> table["sum"].tolist()                                                 # doctest: +SKIP
    [11.0, 21.0, 12.0, 22.0]
    """
    _pandas()
    g = make_grid(grid)
    _check_workers(workers, client)
    if on_error not in ("record", "raise"):
        raise ParameterError(f"on_error={on_error!r} is invalid: give 'record' or 'raise'.")
    if batch_size is not None and (isinstance(batch_size, bool) or not isinstance(batch_size, int)
                                   or batch_size < 1):
        raise ParameterError(f"batch_size={batch_size!r} is invalid: give an integer >= 1 or None.")
    fn = as_study(study, allow_outside)
    if isinstance(fn, SceneStudy):
        fn.check(g.points[0])
    st = Store(store, g, study_id(fn)) if store is not None else None
    records: dict[int, dict[str, Any]] = st.load() if st is not None else {}
    resumed = len(records)
    todo = [i for i in range(len(g)) if i not in records]
    stats: dict[str, Any] = {"points": len(g), "resumed": resumed, "computed": len(todo)}
    t_start = time.perf_counter()
    backend = None
    bar = None
    try:
        # ---- calibration: the first points run here and time a point ------------------------
        timed: list[float] = []
        while todo and len(timed) < CALIBRATION_POINTS:
            i = todo.pop(0)
            rec = _accept(evaluate(fn, i, g.points[i]), g, fn, on_error)
            records[i] = rec
            timed.append(rec.pop("seconds"))
            if st is not None:
                st.add([rec])
            if timed[-1] >= SLOW_POINT_SECONDS:
                break
        point_seconds = min(timed[1:] or timed) if timed else 0.0
        expected = point_seconds * len(todo)
        stats["point_seconds"] = point_seconds
        # ---- backend and batches -------------------------------------------------------------
        if todo:
            if client is not None:
                backend = DaskClient(fn, client)
            elif workers == 1 or (workers is None and (expected < SERIAL_BELOW_SECONDS
                                                       or _cpu_count() == 1)):
                backend = Serial(fn)
            else:
                backend = Pool(fn, workers or _cpu_count())
            overhead = backend.roundtrip()
            size = batch_size or (1 if isinstance(backend, Serial) else
                                  _size(point_seconds, overhead, len(todo), backend.workers))
            batches = [[(i, g.points[i]) for i in todo[k:k + size]]
                       for k in range(0, len(todo), size)]
            stats.update(backend=type(backend).__name__, workers=backend.workers,
                         roundtrip_seconds=overhead, batch_size=size, tasks=len(batches))
            bar = _bar(len(g), len(records), progress and expected / backend.workers
                       >= PROGRESS_SECONDS)
            backend.submit_all(batches)
            for recs in backend.completed():
                for rec in recs:
                    rec = _accept(rec, g, fn, on_error, backend)
                    rec.pop("seconds")
                    records[rec["point"]] = rec
                if st is not None:
                    st.add(recs)
                if bar is not None:
                    bar.update(len(recs))
    finally:
        if bar is not None:
            bar.close()
        if backend is not None:
            backend.close()
        if st is not None:
            st.flush()
    if st is not None:
        st.compact()
    stats.setdefault("backend", "Serial")     # every point ran here (calibration or resumed)
    stats["seconds"] = time.perf_counter() - t_start
    table = assemble(g, records)
    table.attrs["sweep"]["stats"] = stats
    return table


_size = batch_size   # the module function; ``sweep``'s keyword shadows the name inside it


def _accept(rec: dict[str, Any], grid: Grid, fn: Callable[..., Any], on_error: str,
            backend: Any = None) -> dict[str, Any]:
    """Rename colliding outputs; under ``on_error="raise"`` re-raise a failure here."""
    rec["outputs"] = {output_name(k, grid): v for k, v in rec["outputs"].items()}
    if rec["error"] is not None and on_error == "raise":
        if backend is not None:
            backend.cancel()
        fn(**grid.points[rec["point"]])     # recompute here: the genuine exception and traceback
        raise ContactlabError(f"point {rec['point']} failed on a worker but not here: "
                              f"{rec['error']}: {rec['message']}")
    return rec
