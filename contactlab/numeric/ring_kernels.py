"""Optional compiled kernels of the exact ring solver's punch densities (extra ``fast``: numba).

A step of the exact torsion path solver (:mod:`contactlab.physics.torsion_annulus`,
:mod:`contactlab.physics.torsion_energy`) evaluates its piecewise-linear punch densities many
times per step: ``Ψ(x) = ∫_x^∞ w dt`` at piece ends and Gauss points (:func:`psi_pass`), and the
end values of a density on the intervals of a finer partition (:func:`ends_pass`). In numpy each
evaluation is some fifteen small array operations of a few microseconds each on ~100-1000
elements; here it is one compiled pass.

Every operation is an IEEE multiplication, division, addition, subtraction or comparison in the
order of the numpy route, the running sum of the tail integrals is numpy's ``cumsum`` order
(sequential, from the outer piece inwards) and the look-ups are ``searchsorted``'s, so the
results are bit-identical to the numpy route (numba without ``fastmath`` contracts nothing into
fused multiply-adds; tests run both, and the kernels uncompiled).

numba is used when it imports and :func:`contactlab.numeric.normal_kernels.backend` says
``"numba"`` (``CONTACTLAB_BACKEND=numpy`` forces numpy); the kernels compile on their first call
(machine code cached on disk: :func:`contactlab.numeric.jit.njit`).
"""
from __future__ import annotations

import threading

import numpy as np

from . import jit as _jit

__all__ = ["psi_pass", "ends_pass", "kernels"]

_state: dict = {"kernels": None}
_lock = threading.Lock()


def psi_pass(lo: np.ndarray, hi: np.ndarray, wl: np.ndarray, wr: np.ndarray, x: np.ndarray,
             out: np.ndarray) -> None:
    """``Ψ(x) = ∫_x^∞ w dt`` of the pieces ``(lo, hi, wl, wr)`` (at least one, sorted, abutting
    or with gaps) at the radii ``x`` (1-D) into ``out``: the arithmetic of
    ``torsion_annulus.psi`` in its order."""
    n = lo.size
    # w = al + be t on each piece (torsion_annulus._lin)
    al = np.empty(n)
    be = np.empty(n)
    for j in range(n):
        h = hi[j] - lo[j]
        be[j] = (wr[j] - wl[j]) / h if h > 0 else 0.0
        al[j] = wl[j] - be[j] * lo[j]
    tail = np.empty(n + 1)
    tail[n] = 0.0
    acc = 0.0
    for j in range(n - 1, -1, -1):        # cumsum of the reversed per-piece integrals
        whole = al[j] * (hi[j] - lo[j]) + 0.5 * be[j] * (hi[j] * hi[j] - lo[j] * lo[j])
        acc = whole if j == n - 1 else acc + whole
        tail[j] = acc
    top, bottom = hi[n - 1], lo[0]
    for i in range(x.size):
        xi = x[i]
        if xi != xi:                      # nan propagates as in numpy's maximum/minimum
            out[i] = xi
            continue
        a, b = 0, n                       # searchsorted(hi, xi, "right")
        while a < b:
            m = (a + b) >> 1
            if hi[m] <= xi:
                a = m + 1
            else:
                b = m
        k = a if a < n - 1 else n - 1
        if xi >= top:
            out[i] = 0.0
        elif xi < bottom:
            out[i] = tail[0]
        else:
            lk, hk = lo[k], hi[k]
            t0 = xi if xi > lk else lk
            t0 = t0 if t0 < hk else hk
            part = al[k] * (hk - t0) + 0.5 * be[k] * (hk * hk - t0 * t0)
            out[i] = part + tail[k + 1]


def ends_pass(plo: np.ndarray, phi: np.ndarray, wl: np.ndarray, wr: np.ndarray, lo: np.ndarray,
              hi: np.ndarray, out_l: np.ndarray, out_r: np.ndarray) -> None:
    """``w(lo⁺)`` and ``w(hi⁻)`` of the pieces ``(plo, phi, wl, wr)`` (at least one) on the
    intervals ``[lo, hi]`` into ``out_l``, ``out_r``: the arithmetic of
    ``torsion_annulus._ends`` in its order."""
    n = plo.size
    for i in range(lo.size):
        x = lo[i]
        a, b = 0, n                       # searchsorted(plo, x, "right") - 1
        while a < b:
            m = (a + b) >> 1
            if plo[m] <= x or x != x:
                a = m + 1
            else:
                b = m
        k = a - 1
        inside = k >= 0 and hi[i] <= phi[k if k > 0 else 0]
        if k < 0:
            k = 0
        if not inside:
            out_l[i] = 0.0
            out_r[i] = 0.0
            continue
        l0, h0, v, d = plo[k], phi[k], wl[k], wr[k] - wl[k]
        h = h0 - l0
        if h > 0:
            out_l[i] = v + d * ((x - l0) / h)
            out_r[i] = v + d * ((hi[i] - l0) / h)
        else:
            out_l[i] = v + d * 0.0
            out_r[i] = v + d * 0.0


def kernels(compiled: bool = True) -> dict:
    """``{"psi": psi_pass, "ends": ends_pass}`` compiled by numba (built once per process), or
    the plain Python functions (``compiled=False``: the kernels' logic without numba, for
    tests)."""
    if not compiled:
        return {"psi": psi_pass, "ends": ends_pass}
    built = _state["kernels"]
    if built is not None:               # built: no lock (asked ~15 times a solver step)
        return built
    with _lock:
        if _state["kernels"] is None:
            _state["kernels"] = {
                "psi": _jit.njit(psi_pass, nogil=True, error_model="numpy"),
                "ends": _jit.njit(ends_pass, nogil=True, error_model="numpy")}
    return _state["kernels"]
