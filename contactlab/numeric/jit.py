"""Optional numba compilation (extra ``fast``) with machine code cached on disk.

The compiled kernels of contactlab (:mod:`contactlab.foundation._compiled`,
:mod:`contactlab.foundation._compiled_viscoelastic`, :mod:`contactlab.physics.law_kernel`) are
plain module-level Python functions; :func:`njit` compiles one of them with numba on first use
and keeps the machine code on disk, so that only the first process on a machine pays the
compile time (several seconds) and every later process loads it (milliseconds).

Where the cache lives is numba's choice: ``NUMBA_CACHE_DIR`` when it is set (and writable),
else the ``__pycache__`` directory next to the kernel's source file when writable, else the
user's cache directory (``~/.cache/numba`` on Linux). An entry is keyed by the function's
source file contents, the argument types, the CPU and the numba version, so it is rebuilt when
any of them changes. With no writable directory at all the kernel compiles in memory, as
without a cache (the results are the same: a cache entry is the machine code of that compile).

Two processes compiling at once (sweep workers) take an advisory lock file in the cache
directory, one at a time: the second then loads what the first compiled instead of compiling
too (and numba's index of a function cannot lose an entry to the race). Importing this module
does not import numba; :func:`available` and :func:`njit` do.
"""
from __future__ import annotations

import importlib.util
import os
import types
from typing import Any
from collections.abc import Callable

__all__ = ["available", "njit", "LOCK_NAME"]

#: name of the lock file a compile holds in the cache directory (advisory, POSIX only)
LOCK_NAME = "contactlab-compile.lock"

_lock_state: dict = {"depth": 0, "file": None}


def available() -> bool:
    """Whether numba is installed and imports (imported on this first question when installed;
    a numba too old for the installed numpy refuses to import: then the numpy paths run)."""
    ok = _lock_state.get("available")
    if ok is None:
        ok = importlib.util.find_spec("numba") is not None
        if ok:
            try:
                import numba  # noqa: F401
            except ImportError:
                ok = False
        _lock_state["available"] = ok
    return ok


def _locked(compile_: Callable, cache_path: str) -> Callable:
    """``Dispatcher.compile`` under numba's (re-entrant, in-process) compiler lock and, for the
    outermost compile of this process, an exclusive ``flock`` on a file in the cache directory:
    the cache load, compile and save of one process at a time."""
    from numba.core.compiler_lock import global_compiler_lock

    fcntl: Any
    try:
        import fcntl
    except ImportError:                      # pragma: no cover - Windows: no lock
        fcntl = None

    def compile(sig: Any) -> Any:
        with global_compiler_lock:           # serialises threads; nested compiles re-enter
            st = _lock_state
            if st["depth"] == 0 and fcntl is not None:
                f = None
                try:
                    f = open(os.path.join(cache_path, LOCK_NAME), "a+b")
                    fcntl.flock(f.fileno(), fcntl.LOCK_EX)
                except OSError:     # not writable now, or no locks there: compile unlocked
                    if f is not None:
                        f.close()
                    f = None
                st["file"] = f
            st["depth"] += 1
            try:
                return compile_(sig)
            finally:
                st["depth"] -= 1
                if st["depth"] == 0 and st["file"] is not None:
                    fcntl.flock(st["file"].fileno(), fcntl.LOCK_UN)
                    st["file"].close()
                    st["file"] = None

    return compile


def njit(fn: Callable, name: str | None = None, **options: Any) -> Any:
    """``numba.njit(cache=True, **options)(fn)``, compiled on its first call.

    Parameters
    ----------
    fn
        A module-level function (numba caches by the function's source file and name).
    name
        Cache under this name instead of ``fn``'s own: numba keys an entry by function and
        argument types, not by compile options, so two builds of one function with different
        options (``parallel=True`` and serial) need two names.
    **options
        numba options (``nogil``, ``parallel``, ``fastmath``, ...).

    Returns
    -------
    numba dispatcher
        Cached on disk when numba finds a writable cache directory, else compiled in memory
        only (no warning: the result is the same, only the next process compiles again).
    """
    import numba

    if name is not None:
        fn = types.FunctionType(fn.__code__, fn.__globals__, name, fn.__defaults__,
                                fn.__closure__)
        fn.__qualname__ = name
    try:
        disp = numba.njit(cache=True, **options)(fn)
    except RuntimeError:     # "cannot cache function ...: no locator available" (read-only)
        return numba.njit(cache=False, **options)(fn)
    disp.compile = _locked(disp.compile, disp.stats.cache_path)
    return disp
