"""Optional compiled torque of a punch density (extra ``fast``: numba).

The exact path solver takes the torque ``(16/3) G_t ∫ t³ w dt`` of its new density every step
(:func:`contactlab.physics.torsion_pieces.torque`): on a piecewise-linear density the sum over
its pieces of ``al (hi⁴ − lo⁴)/4 + be (hi⁵ − lo⁵)/5`` (``w = al + be t`` on a piece). In numpy
that is some twenty small array operations; here it is one pass. The powers are products
(``h² = h h``, ``h⁴ = h² h²``, ``h⁵ = h⁴ h``) in both routes: IEEE multiplications give the same
bits everywhere, where numpy's vectorised ``**`` differs from the C library's ``pow`` in the last
bit on some processors. The sum over the pieces is numpy's pairwise order
(:func:`contactlab.numeric.annulus_kernel.pairwise_sum`), so both routes give the same bits.

numba is used when it imports and :func:`contactlab.numeric.normal_kernels.backend` says
``"numba"``; the pass compiles on its first call (machine code cached on disk:
:func:`contactlab.numeric.jit.njit`).
"""
from __future__ import annotations

import threading

import numpy as np

from . import annulus_kernel as _ak
from . import jit as _jit
from . import ring_kernels as _rk

__all__ = ["torque_sum", "kernels"]

_state: dict = {"kernel": None}
_lock = threading.Lock()
# the helpers (rebound to their compiled builds with the pass)
_lines = _rk.lines
_pairwise_sum = _ak.pairwise_sum


def torque_sum(lo, hi, wl, wr):
    """``Σ al (hi⁴ − lo⁴)/4 + be (hi⁵ − lo⁵)/5`` over the pieces, numpy's sum of the terms
    (``torsion_pieces.torque`` less its factor ``(16/3) G_t``)."""
    n = lo.size
    al, be, _ = _lines(lo, hi, wl, wr, False)
    terms = np.empty(n)
    for j in range(n):
        h2, l2 = hi[j] * hi[j], lo[j] * lo[j]
        h4, l4 = h2 * h2, l2 * l2
        terms[j] = al[j] * (h4 - l4) / 4.0 + be[j] * (h4 * hi[j] - l4 * lo[j]) / 5.0
    return 0.0 + _pairwise_sum(terms, 0, n)


def kernels(compiled: bool = True) -> dict:
    """``{"torque_sum": ...}`` compiled by numba (built once per process), or the plain Python
    function (``compiled=False``: its logic without numba, for tests)."""
    if not compiled:
        return {"torque_sum": torque_sum}
    built = _state["kernel"]
    if built is not None:
        return built
    with _lock:
        if _state["kernel"] is None:
            _ak.kernels(True)           # (compiles the ring kernels' lines and the pairwise sum)
            g = globals()
            g["_lines"], g["_pairwise_sum"] = _rk.lines, _ak.pairwise_sum
            _state["kernel"] = {"torque_sum": _jit.njit(torque_sum, nogil=True,
                                                        error_model="numpy")}
    return _state["kernel"]
