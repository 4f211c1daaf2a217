"""Where a vectorised computation over steps fails: the longest prefix of steps that succeeds.

A run over many steps is solved in whole arrays (no Python loop over steps); when such a call
raises, :func:`solved_prefix` finds the first failing step by bisection over prefixes, with
``log2(n)`` further calls, so a failed run can name its step and keep what came before it.
"""
from __future__ import annotations

from collections.abc import Callable
from typing import Any

from ..errors import ContactlabError

__all__ = ["solved_prefix"]


def solved_prefix(solve: Callable[[int], Any], n: int) -> tuple[int, Any]:
    """The longest prefix of ``n`` steps that ``solve`` computes, after ``solve(n)`` failed.

    Parameters
    ----------
    solve : callable
        ``solve(m)`` computes the first ``m`` steps (``1 <= m < n``) or raises a
        :class:`~contactlab.errors.ContactlabError`. Prefixes must not depend on later steps
        (true of path-independent states and of histories alike).
    n : int
        Number of steps of the call that failed.

    Returns
    -------
    m : int
        Steps ``0 .. m-1`` compute; step ``m`` is the first that fails (``0 <= m < n``).
    result : object or None
        ``solve(m)`` (None when ``m == 0``).

    Examples
    --------
    >>> from contactlab.errors import ConvergenceError
    >>> def solve(m):
    ...     if m > 6:
    ...         raise ConvergenceError("step 6 fails")
    ...     return list(range(m))
    >>> solved_prefix(solve, 10)
    (6, [0, 1, 2, 3, 4, 5])
    """
    lo, hi, got = 0, int(n), None
    while hi - lo > 1:          # solve(lo) succeeds (or lo == 0), solve(hi) fails
        mid = (lo + hi) // 2
        try:
            r = solve(mid)
        except ContactlabError:
            hi = mid
        else:
            lo, got = mid, r
    return lo, (got if lo else None)
