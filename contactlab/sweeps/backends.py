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
import signal
import statistics
import threading
import time
import weakref
from collections import deque
from collections.abc import Callable, Iterator
from concurrent.futures import FIRST_COMPLETED, Future, ProcessPoolExecutor, wait
from concurrent.futures.process import BrokenProcessPool
from typing import Any

from ..errors import ParameterError, WorkerError
from .study import Points, Records, run_batch

__all__ = ["Serial", "Pool", "DaskClient", "noop", "DeferredInterrupt"]

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


class DeferredInterrupt:
    """Ctrl-C recorded, not raised, while a local pool runs; the pool raises it where it is safe.

    A KeyboardInterrupt raised wherever the main thread happens to be can land inside
    ``concurrent.futures``' own lock handling (``wait`` takes every future's lock in turn) and
    leave a future's lock held; shutting the pool down then waits forever for its manager
    thread, which needs that lock. Between :meth:`start` and :meth:`stop` SIGINT only sets a
    flag (:meth:`__call__`), which :meth:`Pool.completed` polls every :data:`POLL_SECONDS`
    and turns into a KeyboardInterrupt between batches. Nothing changes outside the main thread
    or when SIGINT has a handler other than Python's default.
    """

    def __init__(self) -> None:
        self.hit = False
        self._previous: Any = None

    def __call__(self) -> bool:
        return self.hit

    def _handler(self, signum: int, frame: Any) -> None:
        self.hit = True

    def start(self) -> DeferredInterrupt:
        if (self._previous is None and threading.current_thread() is threading.main_thread()
                and signal.getsignal(signal.SIGINT) is signal.default_int_handler):
            self._previous = signal.signal(signal.SIGINT, self._handler)
        return self

    def stop(self) -> None:
        if self._previous is not None:
            signal.signal(signal.SIGINT, self._previous)
            self._previous = None


#: seconds between two looks at a deferred Ctrl-C while a pool's batches run
POLL_SECONDS = 0.2


# ---- local process pool ------------------------------------------------------------------------
_WORKER_STUDY: Any = None
_WORKER_RUNNER: Callable[..., Records] = run_batch


def _init_worker(blob: bytes, runner: Callable[..., Records] = run_batch) -> None:
    """Set up a pool worker. Ctrl-C reaches every process of the terminal's group: a worker
    ignores it and finishes the batch it is running (the parent stops the sweep, sends no more
    batches and keeps what finished), so no worker prints a traceback of its own."""
    global _WORKER_STUDY, _WORKER_RUNNER
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    _WORKER_STUDY = pickle.loads(blob)
    _WORKER_RUNNER = runner


def _pool_batch(batch: Batch) -> Records:
    return _WORKER_RUNNER(_WORKER_STUDY, batch)


def _dumps(study: Any) -> bytes:
    """The study as bytes: by cloudpickle when installed (lambdas, notebook functions), else
    pickle (module-level functions and objects)."""
    try:
        import cloudpickle
        dumps = cloudpickle.dumps
        hint = "Make it (and what it refers to) picklable, or run with workers=1."
    except ImportError:
        dumps = pickle.dumps
        hint = ("Define it at module level, or install cloudpickle (pip install "
                "'contactlab[dist]'), or run with workers=1.")
    try:
        return dumps(study)
    except (pickle.PicklingError, AttributeError, TypeError, ValueError, RecursionError) as err:
        raise ParameterError(f"study={study!r} cannot be sent to worker processes "
                             f"({type(err).__name__}: {err}). {hint}") from err


def start_method() -> str:
    """``forkserver`` where the platform has it (no fork of a threaded process), else spawn."""
    methods = multiprocessing.get_all_start_methods()
    return "forkserver" if "forkserver" in methods else "spawn"


#: a local pool whose worker died is restarted this many times per sweep, its unfinished
#: batches sent again, before the sweep gives up with a WorkerError
POOL_RESTARTS = 2
#: seconds before the n-th restart: n times this (a killed process server must be reaped first)
RESTART_PAUSE = 0.2
#: what submitting to a pool raises when it is broken or cannot start a worker process (the
#: forkserver gone: its socket refuses, or its pipe ends early); never a study's own exception
_SPAWN_FAILURES = (BrokenProcessPool, OSError, EOFError)


def _span(batches: list[Batch]) -> str:
    points = sorted(i for b in batches for i in b.index)
    if not points:
        return "no points"
    return f"{len(points)} points ({points[0]}..{points[-1]})"


class Pool:
    """A local pool of ``workers`` processes (the default when no client is given).

    A worker that dies (killed from outside, out of memory, a native crash in a study) breaks a
    :class:`~concurrent.futures.ProcessPoolExecutor` as a whole: every batch still running or
    waiting fails with ``BrokenProcessPool``. The pool is then started again and those batches
    are sent again, up to :data:`POOL_RESTARTS` times; after that :class:`WorkerError` is raised
    (the batches finished before were already delivered).
    """

    def __init__(self, study: Callable[..., Any], workers: int,
                 runner: Callable[..., Records] = run_batch) -> None:
        self.workers = int(workers)
        self._initargs = (_dumps(study), runner)
        self._futures: dict[Any, Batch] = {}
        #: a deferred Ctrl-C (:class:`DeferredInterrupt`) that :meth:`completed` polls
        self.interrupted: Callable[[], bool] = lambda: False
        self.restarts = 0
        self._pool = self._start()

    def _start(self) -> ProcessPoolExecutor:
        ctx = multiprocessing.get_context(start_method())
        return ProcessPoolExecutor(max_workers=self.workers, mp_context=ctx,
                                   initializer=_init_worker, initargs=self._initargs)

    def _restart(self, pending: list[Batch], err: BaseException) -> None:
        """The pool broke: start a new one (or give up) and send ``pending`` to it."""
        while True:
            self._pool.shutdown(wait=True, cancel_futures=True)
            self.restarts += 1
            if self.restarts > POOL_RESTARTS:
                raise WorkerError(
                    f"a sweep worker process died {self.restarts} time(s) ({err}); the pool was "
                    f"restarted {POOL_RESTARTS} time(s) and {_span(pending)} are left undone. "
                    "A study that crashes the interpreter (out of memory, a native crash, "
                    "os._exit) kills its worker every time: run those points with workers=1 to "
                    "see the crash. A script that runs a sweep on several processes must start "
                    "it under `if __name__ == \"__main__\":` (worker processes import the main "
                    "module); with store= the points finished so far are kept.") from err
            time.sleep(RESTART_PAUSE * self.restarts)   # let a killed process server be reaped
            self._pool = self._start()
            sent: dict[Any, Batch] = {}
            try:
                for b in pending:
                    sent[self._pool.submit(_pool_batch, b)] = b
            except _SPAWN_FAILURES as e:        # no new worker could be started (yet)
                err = e
                continue
            self._futures.update(sent)
            return

    def roundtrip(self) -> float:
        """Start every worker at once (they import in parallel), then time empty tasks."""
        while True:
            try:
                for f in [self._pool.submit(noop) for _ in range(self.workers)]:
                    f.result()
                return _median_roundtrip(lambda: self._pool.submit(noop).result())
            except _SPAWN_FAILURES as err:
                self._restart([], err)

    def submit_all(self, batches: list[Batch]) -> None:
        for b in batches:
            try:
                future = self._pool.submit(_pool_batch, b)
            except _SPAWN_FAILURES as err:      # broken, or no worker could start: completed()
                future = Future()               # restarts the pool and sends the batch again
                future.set_exception(err if isinstance(err, BrokenProcessPool) else
                                     BrokenProcessPool(f"a worker could not start: {err!r}"))
            self._futures[future] = b

    def completed(self) -> Iterator[Records]:
        while self._futures:
            done, _ = wait(self._futures, timeout=POLL_SECONDS, return_when=FIRST_COMPLETED)
            if self.interrupted():
                raise KeyboardInterrupt
            broken: BaseException | None = None
            for f in done:
                batch = self._futures.pop(f)
                err = f.exception()
                if err is None:
                    yield f.result()
                elif isinstance(err, BrokenProcessPool):
                    broken = err
                    self._futures[f] = batch          # sent again below
                else:
                    raise err
            if broken is not None:
                self._pool.shutdown(wait=True, cancel_futures=True)   # every future settles
                pending = []
                for f, batch in list(self._futures.items()):
                    if f.done() and not f.cancelled() and f.exception() is None:
                        yield f.result()               # finished before the pool broke
                    else:
                        pending.append(batch)
                self._futures = {}
                self._restart(pending, broken)

    def cancel(self) -> None:
        for f in self._futures:
            f.cancel()
        self._futures = {}

    def close(self) -> None:
        """Cancel the batches not started and shut the pool down once the running ones finish.

        Also after Ctrl-C (the workers ignore it): a worker ended from outside while it sends a
        result leaves a partial message in the result pipe, on which the executor's manager
        thread would wait forever, so workers are never terminated here.
        """
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
        killed: tuple[type[BaseException], ...]
        try:
            from distributed.scheduler import KilledWorker
            killed = (KilledWorker,)
        except ImportError:                     # pragma: no cover - moved in some release
            killed = ()
        # results gathered by as_completed itself, not by one blocking result() call per task
        # from this thread; on this client's event loop: without loop=, as_completed tracks the
        # futures on the loop of Dask's *default* client (the latest one made), which drives this
        # client's connections from a second thread (seen as tornado assertions and "deque
        # mutated during iteration" errors, and hung sweeps, with two clients in one process)
        done = iter(self._as_completed(self._futures, loop=self.client.loop, with_results=True))
        while True:
            try:
                _, rec = next(done)
            except StopIteration:
                break
            except killed as err:
                raise WorkerError(
                    f"a Dask worker died on every try of a sweep batch ({err}); the scheduler "
                    "gave up on it (Dask's distributed.scheduler.allowed-failures). A study "
                    "that crashes the interpreter (out of memory, a native crash) kills the "
                    "worker each time: run those points with workers=1 to see the crash; with "
                    "store= the points finished so far are kept.") from err
            yield rec
        self._futures = []

    def cancel(self) -> None:
        if self._futures:
            self.client.cancel(self._futures)
        self._futures = []

    def close(self) -> None:
        self.cancel()
