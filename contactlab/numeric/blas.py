"""One BLAS thread around small dense kernels: bit-identical results for any thread setting.

The ring solver's matrices are a few hundred rows; a threaded BLAS splits their products and
solves into parts whose sums it adds in an order that depends on the thread count (results differ
in the last bits between ``OPENBLAS_NUM_THREADS=1`` and ``=2``), and the threads' start-up costs
more than the work they share (a 180-step exact path took 3x longer with two threads than with
one). :func:`serial_blas` limits every loaded BLAS to one thread for the duration of a block and
restores the previous setting when the last block that holds it ends (blocks may nest and run in
several Python threads at once: the limit is process-wide, so it is taken by the first block and
given back by the last); entering it costs ~10 µs (the libraries are looked up once per process).

threadpoolctl comes with the extra ``fast``; without it the block runs with the process's BLAS
setting (correct, but the last bits then follow the thread count and a threaded BLAS is slower
on these small systems).

A block works the same in any Python thread. threadpoolctl (3.8 and later) lets only one thread,
the first that set an OpenBLAS limit, set another, and silently ignores the others, since
OpenBLAS's pthreads pool is process-wide; its ``limit()`` without a ``with`` never hands that
role back. The blocks here hold the process-wide limit under a lock of their own, so the thread
that takes or gives back the limit first releases that role (:func:`_release_control`): a block
first entered in a worker thread runs on one BLAS thread too, with the main thread's bits.
"""
from __future__ import annotations

import contextlib
import sys
import threading
from collections.abc import Iterator
from typing import Any

__all__ = ["serial_blas"]

_CONTROLLER: list[Any] = []
_LOCK = threading.Lock()
#: blocks inside :func:`serial_blas` now, and the limiter the first of them entered
_HELD: dict[str, Any] = {"count": 0, "limiter": None}


def _controller() -> Any:
    """The process's thread-pool controller (built once, after scipy's BLAS is loaded), or
    None without threadpoolctl (extra ``fast``)."""
    if not _CONTROLLER:
        import scipy.linalg  # noqa: F401  (loads scipy's own BLAS before the look-up)
        try:
            from threadpoolctl import ThreadpoolController
        except ImportError:
            _CONTROLLER.append(None)
        else:
            _CONTROLLER.append(ThreadpoolController())
    return _CONTROLLER[0]


def _release_control() -> None:
    """Let any thread set the OpenBLAS limit next (threadpoolctl >= 3.8 keeps the first thread
    that set one as the only one whose settings take effect; older versions have no such role)."""
    owner = getattr(sys.modules.get("threadpoolctl"), "OpenBLASController", None)
    clear = getattr(owner, "clear_controlling_thread", None)
    if clear is not None:
        clear(force=True)


@contextlib.contextmanager
def serial_blas() -> Iterator[None]:
    """Run the block with one BLAS thread (every BLAS library loaded in the process).

    Examples
    --------
    >>> import numpy as np
    >>> with serial_blas():
    ...     x = np.linalg.solve(np.eye(3), np.ones(3))
    >>> x.tolist()
    [1.0, 1.0, 1.0]
    """
    with _LOCK:
        if _HELD["count"] == 0:
            ctl = _controller()
            if ctl is not None:
                _release_control()
                _HELD["limiter"] = ctl.limit(limits=1, user_api="blas")
                _release_control()
        _HELD["count"] += 1
    try:
        yield
    finally:
        with _LOCK:
            _HELD["count"] -= 1
            if _HELD["count"] == 0 and _HELD["limiter"] is not None:
                _release_control()
                _HELD["limiter"].restore_original_limits()
                _release_control()
                _HELD["limiter"] = None
