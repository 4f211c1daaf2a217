"""``sweep``: one call for a parameter study, serially, on all local cores or on a Dask cluster.

The flow: the grid becomes points (:mod:`.grid`); a store, if given, supplies the points already
finished (:mod:`.store`); the first points run here in growing batches (1, 2, 8, 32, ... until a
batch takes :data:`CALIBRATION_SECONDS`), which warms this process and times a point; the backend
is chosen (:mod:`.backends`) and its per-task round trip measured; if the points left would take
less than that round trip, they run here; else they go out in batches large enough that this
round trip costs under :data:`TARGET_OVERHEAD` of a batch's compute time (:func:`batch_size`).
Batches travel as columns (:class:`~.study.Points` out, :class:`~.study.Records` back), not as
per-point dicts; records come back in any order and the table is assembled by point
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
from ..params import check_time, time_budget
from .backends import DaskClient, DeferredInterrupt, Pool, Serial, _dumps
from .grid import Grid, make_grid
from .store import Store
from .study import Points, Records, SceneStudy, as_study, run_calls, study_id
from .table import _pandas, assemble, output_name

__all__ = ["sweep", "run_tasks", "batch_size", "TARGET_OVERHEAD"]

#: per-task overhead allowed, as a fraction of a batch's compute time
TARGET_OVERHEAD = 0.1
#: at least this many batches per worker while the overhead target allows (load balance)
BATCHES_PER_WORKER = 4
#: ``workers=None`` runs in this process when the whole sweep should take less than this (s)
SERIAL_BELOW_SECONDS = 1.0
#: the timing batches run here grow until one takes this long (s)
CALIBRATION_SECONDS = 0.01
#: ... or until this share of the sweep ran here (at least 3 points)
CALIBRATION_SHARE = 1 / 16
#: batches of the serial backend take about this long (s): progress, checkpoints, interrupts
SERIAL_BATCH_SECONDS = 0.25
#: a point slower than this (s) needs no more timing: batches of one already meet the target
SLOW_POINT_SECONDS = 0.05
#: a progress bar is shown when the sweep is expected to take longer than this (s)
PROGRESS_SECONDS = 2.0


def batch_size(point_seconds: float, overhead_seconds: float, remaining: int, workers: int) -> int:
    """Points per task so that the per-task overhead stays under :data:`TARGET_OVERHEAD`.

    The size is the smallest ``b`` with ``overhead <= TARGET_OVERHEAD * b * point_seconds``.
    Where that still leaves :data:`BATCHES_PER_WORKER` batches per worker, it is the size;
    where it does not (a sweep whose whole compute time is a few round trips), the overhead
    target wins over load balance, but no batch is made larger than one worker's share of the
    sweep (every worker gets work; a sweep whose share is under ten round trips cannot meet the
    target on that cluster at all).

    Examples
    --------
    >>> batch_size(point_seconds=1e-4, overhead_seconds=2e-3, remaining=100_000, workers=2)
    200
    >>> batch_size(point_seconds=1.0, overhead_seconds=2e-3, remaining=100, workers=2)
    1
    """
    need = math.ceil(overhead_seconds / (TARGET_OVERHEAD * max(point_seconds, 1e-9)) - 1e-9)
    balance = math.ceil(remaining / (BATCHES_PER_WORKER * max(workers, 1)))
    if need <= balance:
        return max(1, need)
    return max(1, min(need, math.ceil(remaining / max(workers, 1))))


def _bar(total: int, initial: int, show: bool, unit: str = "point") -> Any:
    if not show:
        return None
    try:
        from tqdm.auto import tqdm
    except ImportError:
        return None
    return tqdm(total=total, initial=initial, unit=unit, desc="sweep")


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
        :data:`SERIAL_BELOW_SECONDS`. Wherever they run, points left after the timing points
        that would take less than one round trip to the workers are finished here.
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
    WorkerError
        A worker process died more often than the sweep restarts its workers (a local pool is
        restarted twice, a Dask scheduler retries per its configuration); the points finished
        before are in the store.
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
        fn.check(g.point(0))
    if client is None and workers is not None and workers > 1:
        _dumps(fn)                         # an unpicklable study: refused before any point runs
    st = Store(store, g, study_id(fn)) if store is not None else None
    chunks: list[Records] = [st.load()] if st is not None else []
    resumed = len(chunks[0]) if chunks else 0
    finished = set(chunks[0].point) if chunks else set()
    todo = [i for i in range(len(g)) if i not in finished] if finished else list(range(len(g)))
    stats: dict[str, Any] = {"points": len(g), "resumed": resumed, "computed": len(todo)}
    t_start = time.perf_counter()
    local = Serial(fn)
    backend: Any = None
    bar = None

    def keep(chunk: Records, source: Any) -> None:
        chunk = _accept(chunk, g, fn, on_error, source)
        chunks.append(chunk)
        if st is not None:
            st.add(chunk)
        if bar is not None:
            bar.update(len(chunk))

    interrupt = DeferredInterrupt()
    try:
        # ---- calibration: growing batches run here, warm this process and time a point -------
        point_seconds, size, timed = 0.0, 1, 0
        cap = max(3, math.ceil(len(todo) * CALIBRATION_SHARE))
        while todo:
            take, todo = todo[:size], todo[size:]
            t0 = time.perf_counter()
            chunk = local.run(Points.take(g, take))
            point_seconds = (time.perf_counter() - t0) / len(take)
            keep(chunk, None)
            timed += len(take)
            if point_seconds >= SLOW_POINT_SECONDS or (
                    timed > 1 and (len(take) * point_seconds >= CALIBRATION_SECONDS
                                   or timed >= cap)):
                break
            size = 2 if timed == 1 else min(4 * size, cap - timed)
        expected = point_seconds * len(todo)
        stats["point_seconds"] = point_seconds
        stats["calibration_points"] = timed
        # ---- backend and batches -------------------------------------------------------------
        if todo:
            if client is not None:
                backend = DaskClient(fn, client)
            elif workers == 1 or (workers is None and (expected < SERIAL_BELOW_SECONDS
                                                       or _cpu_count() == 1)):
                backend = local
            else:
                interrupt.start()            # Ctrl-C from here on: raised between batches
                backend = Pool(fn, workers or _cpu_count())
                backend.interrupted = interrupt
            overhead = backend.roundtrip()
            if backend is not local and batch_size is None and expected <= overhead:
                # the rest takes less here than one round trip to the workers: keep it here
                backend.close()
                backend = local
                interrupt.stop()
            if batch_size is not None:
                size = batch_size
            elif backend is local:
                size = max(1, math.ceil(SERIAL_BATCH_SECONDS / max(point_seconds, 1e-9)))
            else:
                size = _size(point_seconds, overhead, len(todo), backend.workers)
            _check_time(point_seconds, timed, len(todo), backend.workers, store)
            batches = [Points.take(g, todo[k:k + size]) for k in range(0, len(todo), size)]
            stats.update(backend=type(backend).__name__, workers=backend.workers,
                         roundtrip_seconds=overhead, batch_size=size, tasks=len(batches))
            bar = _bar(len(g), len(g) - len(todo), progress and expected / backend.workers
                       >= PROGRESS_SECONDS)
            backend.submit_all(batches)
            for chunk in backend.completed():
                keep(chunk, backend)
                if interrupt():
                    raise KeyboardInterrupt
    finally:
        interrupt.stop()
        if bar is not None:
            bar.close()
        if local.partial is not None and st is not None:      # points done before an interrupt
            st.add(_accept(local.partial, g, fn, "record"))
        if backend is not None and backend is not local:
            backend.close()
        if st is not None:
            st.flush()
    if st is not None:
        st.compact()
    stats.setdefault("backend", "Serial")     # every point ran here (calibration or resumed)
    stats["restarts"] = getattr(backend, "restarts", 0)
    stats["seconds"] = time.perf_counter() - t_start
    table = assemble(g, chunks)
    table.attrs["sweep"]["stats"] = stats
    return table


_size = batch_size   # the module function; ``sweep``'s keyword shadows the name inside it


def _check_time(point_seconds: float, timed: int, remaining: int, workers: int,
                store: Any) -> None:
    """Refuse to run on (:class:`~contactlab.errors.TimeBudgetError`) when the remaining points,
    at the time per point measured on the timing points run here, spread over the workers,
    would take longer than the time budget. The timing points are kept in the store; the
    message says how to resume with a larger budget."""
    est = point_seconds * remaining / max(workers, 1)
    if est <= time_budget():
        return
    kept = (f"the {timed} points done are kept in the store {str(store)!r}: run the same sweep "
            f"again with a larger budget and the same store to resume from them"
            if store is not None else
            f"the {timed} points done are not kept (no store): give store='study.parquet' "
            "(CLI: -o) to keep the finished points and resume")
    check_time("sweep()", est,
               f"{remaining} points left x {point_seconds:.3g} s per point measured on the "
               f"first {timed}, over {max(workers, 1)} worker{'s' if workers > 1 else ''}; "
               f"{kept}")


def _accept(rec: Records, grid: Grid, fn: Callable[..., Any], on_error: str,
            backend: Any = None) -> Records:
    """Rename colliding outputs; under ``on_error="raise"`` re-raise a failure here."""
    rec.rename(lambda k: output_name(k, grid))
    if on_error == "raise":
        for j, error in enumerate(rec.error):
            if error is not None:
                if backend is not None:
                    backend.cancel()
                i = rec.point[j]
                fn(**grid.point(i))     # recompute here: the genuine exception and traceback
                raise ContactlabError(f"point {i} failed on a worker but not here: "
                                      f"{error}: {rec.message[j]}")
    return rec


class _ItemCall:
    """``fn(item)`` called as a study, ``study(item=...)`` (pickles when ``fn`` does)."""

    def __init__(self, fn: Callable[[Any], Any]) -> None:
        self.fn = fn

    def __call__(self, item: Any) -> Any:
        return self.fn(item)


def run_tasks(fn: Callable[[Any], Any], items: Any, *, client: Any = None,
              workers: int | None = None, progress: bool = True, unit: str = "task") -> list[Any]:
    """``[fn(item) for item in items]``, run the way :func:`sweep` runs points.

    For work whose pieces return arrays rather than table rows (the blocks of a fretting map):
    the first item runs here and times an item, then the others go to this process, a local
    process pool or a Dask cluster exactly as in :func:`sweep` (same ``client``/``workers``
    rules, batches sized by :func:`batch_size`, a progress bar counting ``unit``).

    Returns
    -------
    list
        The results in the order of ``items``.

    Raises
    ------
    Exception
        The first exception an item raises (on a worker or here) is raised here; the rest of
        the work is cancelled.
    WorkerError
        A worker process died more often than the pool is restarted (see :func:`sweep`).
    """
    _check_workers(workers, client)
    items = list(items)
    study = _ItemCall(fn)
    local = Serial(study, run_calls)
    results: list[Any] = [None] * len(items)
    if not items:
        return results
    t0 = time.perf_counter()
    first = local.run(Points([0], ("item",), [[items[0]]]))
    item_seconds = time.perf_counter() - t0
    results[0] = first.outputs["value"][0]
    todo = list(range(1, len(items)))
    if not todo:
        return results
    expected = item_seconds * len(todo)
    if client is not None:
        backend: Any = DaskClient(study, client, run_calls)
    elif workers == 1 or (workers is None and (expected < SERIAL_BELOW_SECONDS
                                               or _cpu_count() == 1)):
        backend = local
    else:
        backend = Pool(study, workers or _cpu_count(), run_calls)
    bar = None
    try:
        size = 1
        if backend is not local:
            overhead = backend.roundtrip()
            if expected <= overhead:          # less work left than one round trip: here
                backend.close()
                backend = local
            else:
                size = _size(item_seconds, overhead, len(todo), backend.workers)
        backend.submit_all([Points(todo[k:k + size], ("item",),
                                   [[items[i] for i in todo[k:k + size]]])
                            for k in range(0, len(todo), size)])
        bar = _bar(len(items), 1, progress and expected / backend.workers >= PROGRESS_SECONDS,
                   unit)
        for chunk in backend.completed():
            for i, value in zip(chunk.point, chunk.outputs["value"]):
                results[i] = value
            if bar is not None:
                bar.update(len(chunk))
    finally:
        if bar is not None:
            bar.close()
        if backend is not local:
            backend.close()
    return results
