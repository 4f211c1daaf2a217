"""Optional compiled kernel of a table's near-segment pressure rules (extra ``fast``: numba).

:func:`contactlab.physics.table_pressure._piece` evaluates, per radius and rule point, the
integration point, the segment's degree-16 Chebyshev series in ``w = sqrt(x - b_k)`` (Clenshaw),
the kernel weight and the rules' sums: in numpy some 70 small array operations per call, for a
peak search's 1024 radii most of its time. :func:`piece_rows` does the same arithmetic in one
compiled pass per row, after numpy's own ``arccosh``, ``sinh`` and ``cosh`` (taken by the caller
on whole arrays: the C library's may differ by an ulp from numpy's). Every other operation is an
IEEE multiplication, division, addition, subtraction, square root or absolute value in the
order of the numpy route, and the row sums repeat numpy's pairwise summation (eight partial
sums, combined as a tree, then the remainder, added to the reduction's initial 0), so the
results are bit-identical to the numpy route (numba without ``fastmath`` contracts nothing into
fused multiply-adds; tests run both, and the kernel uncompiled).

numba is used when it imports and :func:`contactlab.numeric.normal_kernels.backend` says
``"numba"`` (``CONTACTLAB_BACKEND=numpy`` forces numpy), for calls of at least
:data:`TABLE_ROWS_FROM` rows; the kernel compiles on its first call (machine code cached on
disk: :func:`contactlab.numeric.jit.njit`).
"""
from __future__ import annotations

import threading
from collections.abc import Callable

import numpy as np

from . import jit as _jit

__all__ = ["TABLE_ROWS_FROM", "piece_rows", "kernel"]

#: fewest rows (radii) a call of the compiled pass takes (below it numpy's per-call cost is
#: small, and a process that never searches a table's peak never loads numba)
TABLE_ROWS_FROM = 256

_state: dict = {"kernel": None}
_lock = threading.Lock()


def piece_rows(coef_t: np.ndarray, sqrt_h: np.ndarray, fit_err: np.ndarray, k: np.ndarray,
               T: np.ndarray, delta: np.ndarray, s2: np.ndarray, span: np.ndarray,
               r: np.ndarray, sh: np.ndarray, ch: np.ndarray, u: np.ndarray, u2: np.ndarray,
               wts: np.ndarray, n_hi: int, r_is_s2: bool, v_out: np.ndarray,
               e_out: np.ndarray) -> None:
    """The rules of ``_piece`` row by row: per row ``i`` (segment ``k[i]``) and point ``p``
    (``n_hi`` points of the high rule, then the low rule's), with ``sh``, ``ch`` the
    ``sinh``/``cosh`` of ``T u_p / 2``: the point ``x`` and ``w``, ``F = `` the segment's series
    at ``y = 2w/sqrt(h) - 1``, the weight ``T w_p / sqrt(x + r)`` (``2 w_p/(u_p sqrt(x + r))``
    on rows with ``delta <= 0``, 0 on rows with ``span <= 0``); writes the high rule's sum to
    ``v_out`` and ``|high - low| + (sum of |weights|) fit_err`` to ``e_out``."""
    npt = u.size
    deg = coef_t.shape[0] - 1
    buf = np.empty(npt + n_hi)                 # the products, then |weight| of the high rule
    acc = np.empty(8)
    sums = np.empty(3)
    x = np.empty(npt)
    y = np.empty(npt)
    y2 = np.empty(npt)
    b1 = np.empty(npt)
    b2 = np.empty(npt)
    for i in range(T.size):
        ki = k[i]
        same = delta[i] <= 0.0
        empty = span[i] <= 0
        d2 = 2.0 * delta[i]
        sd2 = np.sqrt(d2)
        ssp = np.sqrt(span[i])
        sqh = sqrt_h[ki]
        for p in range(npt):
            if same:
                x[p] = s2[i] + span[i] * u2[p]
                w = ssp * u[p]
            else:
                x[p] = s2[i] + d2 * sh[i, p] * sh[i, p]
                w = sd2 * (ch[i, p] if r_is_s2 else sh[i, p])
            yp = 2.0 * w / sqh - 1.0
            y[p] = yp
            y2[p] = 2.0 * yp
            b1[p] = 0.0
            b2[p] = 0.0
        # Clenshaw, all points of the row per degree (the loop over points vectorises)
        for j in range(deg, 0, -1):
            cj = coef_t[j, ki]
            for p in range(npt):
                t = cj + y2[p] * b1[p]
                t = t - b2[p]
                b2[p] = b1[p]
                b1[p] = t
        c0 = coef_t[0, ki]
        for p in range(npt):
            f = c0 + y[p] * b1[p]
            f = f - b2[p]
            root = np.sqrt(x[p] + r[i])
            if empty:
                kern = 0.0
            elif same:
                kern = wts[p] * 2.0 / (u[p] * root)
            else:
                kern = T[i] * wts[p] / root
            buf[p] = kern * f
            if p < n_hi:
                buf[npt + p] = abs(kern)
        for s in range(3):                     # numpy's pairwise sum (8 <= n <= 128)
            lo = 0 if s == 0 else (n_hi if s == 1 else npt)
            n = npt - n_hi if s == 1 else n_hi
            for j in range(8):
                acc[j] = buf[lo + j]
            m = n - n % 8
            q = 8
            while q < m:
                for j in range(8):
                    acc[j] += buf[lo + q + j]
                q += 8
            res = ((acc[0] + acc[1]) + (acc[2] + acc[3])) + ((acc[4] + acc[5]) + (acc[6] + acc[7]))
            while q < n:
                res += buf[lo + q]
                q += 1
            sums[s] = 0.0 + res
        v_hi = sums[0]
        weight = sums[2]
        err = weight * fit_err[ki] if weight > 0 else 0.0
        v_out[i] = v_hi
        e_out[i] = abs(v_hi - sums[1]) + err


def kernel(compiled: bool = True) -> Callable:
    """:func:`piece_rows` compiled by numba (built once per process), or the plain Python
    function (``compiled=False``: the kernel's logic without numba, for tests)."""
    if not compiled:
        return piece_rows
    with _lock:
        if _state["kernel"] is None:
            _state["kernel"] = _jit.njit(piece_rows, nogil=True, error_model="numpy")
    return _state["kernel"]
