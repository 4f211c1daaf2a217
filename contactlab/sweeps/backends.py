"""Where batches of points run: in this process, in a local process pool, on a Dask cluster.

Every backend has one face: ``submit_all(batches)`` then iterate ``completed()`` for the
:class:`~contactlab.sweeps.study.Records` of each batch in the order they finish, ``roundtrip()``
for the time one empty task takes (the per-task overhead that batching must hide), ``cancel()``
and ``close()``. A batch is a :class:`~contactlab.sweeps.study.Points`. Results do not depend on
the backend: each point is computed by :func:`~contactlab.sweeps.study.run_batch` alone.
"""
from __future__ import annotations

import math
import multiprocessing
import pickle
import statistics
import time
import weakref
from collections import deque
from collections.abc import Callable, Iterator
from concurrent.futures import FIRST_COMPLETED, ProcessPoolExecutor, wait
from concurrent.futures.process import BrokenProcessPool
from typing import Any

from ..errors import ParameterError
from .study import Points, Records, run_batch

__all__ = ["Serial", "Pool", "DaskClient", "noop"]

Batch = Points


def noop() -> None:
    """An empty task: its round trip is the backend's per-task overhead."""
    return None


def _median_roundtrip(submit: Callable[[], Any], n: int = 5) -> float:
    submit()                                  # warm: start workers, import on them
    times = []
    for _ in range(n):
        t0 = time.perf_counter()
        submit()
        times.append(time.perf_counter() - t0)
    return statistics.median(times)


class Serial:
    """Batches run one after the other in this process (``workers=1``).

    If a point is interrupted (KeyboardInterrupt), the points of its batch finished before it
    are left in :attr:`partial`, so the caller can keep them.
    """

    workers = 1

    def __init__(self, study: Callable[..., Any], runner: Callable[..., Records] = run_batch
                 ) -> None:
        self.study = study
        self.runner = runner
        self._batches: deque[Batch] = deque()
        self.partial: Records | None = None

    def roundtrip(self) -> float:
        return 0.0

    def run(self, batch: Batch) -> Records:
        """Run one batch here."""
        out = Records()
        try:
            return self.runner(self.study, batch, out)
        except BaseException:
            self.partial = out
            raise

    def submit_all(self, batches: list[Batch]) -> None:
        self._batches = deque(batches)

    def completed(self) -> Iterator[Records]:
        while self._batches:
            yield self.run(self._batches.popleft())

    def cancel(self) -> None:
        self._batches = deque()

    def close(self) -> None:
        self.cancel()


# ---- local process pool ------------------------------------------------------------------------
_WORKER_STUDY: Any = None
_WORKER_RUNNER: Callable[..., Records] = run_batch


def _init_worker(blob: bytes, runner: Callable[..., Records] = run_batch) -> None:
    global _WORKER_STUDY, _WORKER_RUNNER
    _WORKER_STUDY = pickle.loads(blob)
    _WORKER_RUNNER = runner


def _pool_batch(batch: Batch) -> Records:
    return _WORKER_RUNNER(_WORKER_STUDY, batch)


def _dumps(study: Any) -> bytes:
    """The study as bytes: by cloudpickle when installed (lambdas, notebook functions), else
    pickle (module-level functions and objects)."""
    try:
        import cloudpickle
        return cloudpickle.dumps(study)
    except ImportError:
        pass
    try:
        return pickle.dumps(study)
    except (pickle.PicklingError, AttributeError, TypeError) as err:
        raise ParameterError(f"study={study!r} cannot be sent to worker processes: {err}. Define "
                             "it at module level, or install cloudpickle (pip install "
                             "'contactlab[dist]'), or run with workers=1.") from err


def start_method() -> str:
    """``forkserver`` where the platform has it (no fork of a threaded process), else spawn."""
    methods = multiprocessing.get_all_start_methods()
    return "forkserver" if "forkserver" in methods else "spawn"


class Pool:
    """A local pool of ``workers`` processes (the default when no client is given)."""

    def __init__(self, study: Callable[..., Any], workers: int,
                 runner: Callable[..., Records] = run_batch) -> None:
        self.workers = int(workers)
        ctx = multiprocessing.get_context(start_method())
        self._pool = ProcessPoolExecutor(max_workers=self.workers, mp_context=ctx,
                                         initializer=_init_worker,
                                         initargs=(_dumps(study), runner))
        self._futures: set[Any] = set()

    def roundtrip(self) -> float:
        return _median_roundtrip(lambda: self._result(self._pool.submit(noop)))

    @staticmethod
    def _result(future: Any) -> Any:
        try:
            return future.result()
        except BrokenProcessPool as err:
            raise BrokenProcessPool(
                f"a sweep worker process died ({err}). A script that runs a sweep on several "
                "processes must start it under `if __name__ == \"__main__\":` (worker processes "
                "import the main module); a study that crashes the interpreter (out of memory, a "
                "native crash) kills its worker too.") from err

    def submit_all(self, batches: list[Batch]) -> None:
        self._futures = {self._pool.submit(_pool_batch, b) for b in batches}

    def completed(self) -> Iterator[Records]:
        while self._futures:
            done, self._futures = wait(self._futures, return_when=FIRST_COMPLETED)
            for f in done:
                yield self._result(f)

    def cancel(self) -> None:
        for f in self._futures:
            f.cancel()
        self._futures = set()

    def close(self) -> None:
        self.cancel()
        self._pool.shutdown(wait=True, cancel_futures=True)


#: a client's measured round trip is reused for this long (s): measuring costs a few round trips
ROUNDTRIP_CACHE_SECONDS = 300.0
_ROUNDTRIPS: weakref.WeakKeyDictionary[Any, tuple[float, float]] = weakref.WeakKeyDictionary()


class DaskClient:
    """Batches as tasks of a ``dask.distributed.Client`` (local cluster or remote scheduler).

    The per-task round trip is measured once per client (the first measurement also imports
    contactlab on the workers) and reused for :data:`ROUNDTRIP_CACHE_SECONDS`.
    """

    def __init__(self, study: Callable[..., Any], client: Any,
                 runner: Callable[..., Records] = run_batch) -> None:
        try:
            from distributed import as_completed
        except ImportError as err:
            raise ImportError("client= needs dask.distributed: pip install "
                              "'contactlab[dist]'") from err
        if not (hasattr(client, "submit") and hasattr(client, "nthreads")):
            raise ParameterError(f"client={client!r} is invalid: give a "
                                 "dask.distributed.Client (or None for a local process pool).")
        self.client = client
        self.study = study
        self.runner = runner
        self._as_completed = as_completed
        self._futures: list[Any] = []
        self.workers = max(1, sum(client.nthreads().values()))

    def roundtrip(self) -> float:
        try:
            when, value = _ROUNDTRIPS[self.client]
        except (KeyError, TypeError):
            when, value = -math.inf, math.nan
        if time.monotonic() - when < ROUNDTRIP_CACHE_SECONDS:
            return value
        value = _median_roundtrip(lambda: self.client.submit(noop, pure=False).result())
        try:
            _ROUNDTRIPS[self.client] = (time.monotonic(), value)
        except TypeError:        # pragma: no cover - a client object that takes no weak reference
            pass
        return value

    def submit_all(self, batches: list[Batch]) -> None:
        self._futures = [self.client.submit(self.runner, self.study, b, pure=False)
                         for b in batches]

    def completed(self) -> Iterator[Records]:
        for f in self._as_completed(self._futures):
            yield f.result()
        self._futures = []

    def cancel(self) -> None:
        if self._futures:
            self.client.cancel(self._futures)
        self._futures = []

    def close(self) -> None:
        self.cancel()
