"""``numpy.searchsorted`` on a sorted array as plain loops (helpers of the compiled passes of
:mod:`contactlab.numeric.annulus_kernel`, :mod:`contactlab.numeric.inside_check`,
:mod:`contactlab.numeric.slip_check` and :mod:`contactlab.numeric.ring_kernels`, compiled and
inlined with them: the same index as numpy's for any ``x`` not nan)."""
from __future__ import annotations

import numpy as np

__all__ = ["left", "right"]


def left(a: np.ndarray, x: float) -> int:
    """``searchsorted(a, x, "left")`` (``x`` not nan)."""
    lo, hi = 0, a.size
    while lo < hi:
        m = (lo + hi) >> 1
        if a[m] < x:
            lo = m + 1
        else:
            hi = m
    return lo


def right(a: np.ndarray, x: float) -> int:
    """``searchsorted(a, x, "right")`` (``x`` not nan)."""
    lo, hi = 0, a.size
    while lo < hi:
        m = (lo + hi) >> 1
        if a[m] <= x:
            lo = m + 1
        else:
            hi = m
    return lo
