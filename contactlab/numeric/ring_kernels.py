"""Optional compiled kernels of the exact ring solver's punch densities (extra ``fast``: numba).

A step of the exact torsion path solver (:mod:`contactlab.physics.torsion_annulus`,
:mod:`contactlab.physics.torsion_energy`) evaluates its piecewise-linear punch densities many
times per step: ``Ψ(x) = ∫_x^∞ w dt`` at piece ends and Gauss points (:func:`psi_pass`), and the
end values of a density on the intervals of a finer partition (:func:`ends_pass`). In numpy each
evaluation is some fifteen small array operations of a few microseconds each on ~100-1000
elements; here it is one compiled pass. The step's checks (the traction inside the stick radius,
the slip on the annulus) need the antiderivatives ``arccosh(t/r)``, ``sqrt(t² − r²)`` and the
slip kernel's ``G0``, ``G1`` at the density's nodes off the precomputed table: there the
transcendental values stay numpy's own (``arccosh``, ``arccos``, ``** 3`` of the same vectors the
numpy route takes them of; a compiled one would be the C library's, which may differ in the last
bit) and two compiled passes do the rest (:func:`arccosh_args` / :func:`traction_fill`,
:func:`arccos_args` / :func:`slip_fill`).

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
from collections.abc import Callable
from typing import Any

import numpy as np

from . import jit as _jit
from . import sorted_search as _ss

__all__ = ["psi_pass", "ends_pass", "arccosh_args", "traction_fill", "arccos_args", "slip_fill",
           "traction_antiderivatives", "slip_antiderivatives", "kernels"]

_state: dict = {"kernels": None}
_lock = threading.Lock()
#: the sorted search (rebound to its compiled build, inlined, by :func:`kernels`)
_right = _ss.right


def psi_pass(lo: np.ndarray, hi: np.ndarray, wl: np.ndarray, wr: np.ndarray, x: np.ndarray,
             out: np.ndarray) -> None:
    """``Ψ(x) = ∫_x^∞ w dt`` of the pieces ``(lo, hi, wl, wr)`` (at least one, sorted, abutting
    or with gaps) at the radii ``x`` (1-D) into ``out``: the arithmetic of
    ``torsion_annulus.psi`` in its order."""
    n = lo.size
    al, be, tail = lines(lo, hi, wl, wr, True)
    for i in range(x.size):
        xi = x[i]
        if xi != xi:                      # nan propagates as in numpy's maximum/minimum
            out[i] = xi
            continue
        a = _right(hi, xi)                # searchsorted(hi, xi, "right")
        k = a if a < n - 1 else n - 1
        out[i] = psi_at(lo, hi, al, be, tail, k, xi)


def lines(lo, hi, wl, wr, tails):
    """``w = al + be t`` on each piece (``torsion_annulus._lin``: slope 0 on a piece of no
    width) and, with ``tails``, ``∫`` over the pieces ``k, k+1, ...`` (numpy's cumsum of the
    reversed per-piece integrals; ``n + 1`` values, 0 last; else empty): ``(al, be, tail)``
    (a helper of :func:`psi_pass` and of the annulus passes, inlined where compiled)."""
    n = lo.size
    al = np.empty(n)
    be = np.empty(n)
    for j in range(n):
        h = hi[j] - lo[j]
        be[j] = (wr[j] - wl[j]) / h if h > 0 else 0.0
        al[j] = wl[j] - be[j] * lo[j]
    tail = np.empty(n + 1 if tails else 0)
    if tails:
        tail[n] = 0.0
        acc = 0.0
        for j in range(n - 1, -1, -1):
            whole = al[j] * (hi[j] - lo[j]) + 0.5 * be[j] * (hi[j] * hi[j] - lo[j] * lo[j])
            acc = whole if j == n - 1 else acc + whole
            tail[j] = acc
    return al, be, tail


def psi_at(lo, hi, al, be, tail, k, x):
    """``Ψ(x)`` from piece ``k`` (``min(searchsorted(hi, x, "right"), n - 1)``) and the pieces'
    :func:`lines` and tails: ``torsion_annulus.psi``'s arithmetic (a helper of :func:`psi_pass`
    and of the annulus passes' walk, inlined where compiled)."""
    if x >= hi[hi.size - 1]:
        return 0.0
    if x < lo[0]:
        return tail[0]
    lk, hk = lo[k], hi[k]
    t0 = x if x > lk else lk
    t0 = t0 if t0 < hk else hk
    return al[k] * (hk - t0) + 0.5 * be[k] * (hk * hk - t0 * t0) + tail[k + 1]


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
        out_l[i], out_r[i] = piece_ends(plo, phi, wl, wr, a - 1, x, hi[i])


def piece_ends(plo, phi, wl, wr, k, x, y):
    """``w(x⁺)`` and ``w(y⁻)`` on piece ``k`` (``searchsorted(plo, x, "right") - 1``) of the
    pieces ``(plo, phi, wl, wr)``: ``torsion_annulus._ends``' arithmetic; zeros where ``[x, y]``
    is not inside the piece (a helper of :func:`ends_pass` and of the annulus passes, inlined
    where compiled)."""
    if not (k >= 0 and y <= phi[k if k > 0 else 0]):
        return 0.0, 0.0
    l0, h0, v, d = plo[k], phi[k], wl[k], wr[k] - wl[k]
    h = h0 - l0
    if h > 0:
        return v + d * ((x - l0) / h), v + d * ((y - l0) / h)
    return v + d * 0.0, v + d * 0.0


def arccosh_args(r: np.ndarray, t: np.ndarray, um: np.ndarray, idx: np.ndarray) -> int:
    """First pass of ``torsion_annulus._antiderivatives``: ``u = max(t/r, 1)`` (1 where
    ``r <= 0``) over the rows ``r`` and columns ``t``; the ``u > 1`` into ``um`` and their flat
    (row-major) indices into ``idx``, in numpy's boolean-mask order; returns their count (the
    caller takes ``arccosh(um[:n])`` with numpy)."""
    k = t.size
    n = 0
    for i in range(r.size):
        ri = r[i]
        for j in range(k):
            if ri > 0:
                q = t[j] / ri
                u = q if (q >= 1.0 or q != q) else 1.0     # np.maximum: nan propagates
            else:
                u = 1.0
            if u > 1.0:
                um[n] = u
                idx[n] = i * k + j
                n += 1
    return n


def traction_fill(r: np.ndarray, um: np.ndarray, a: np.ndarray, idx: np.ndarray,
                  A: np.ndarray, S: np.ndarray) -> None:
    """Second pass of ``torsion_annulus._antiderivatives``: ``A`` (zeros, ``r.size × k``) gets
    ``arccosh`` values ``a`` at the flat indices ``idx``, ``S`` gets ``sqrt((u − 1)(u + 1))``
    there, then ``S *= r`` by rows (every element, as numpy's)."""
    k = A.shape[1]
    Af = A.ravel()
    Sf = S.ravel()
    for n in range(um.size):
        u = um[n]
        Af[idx[n]] = a[n]
        Sf[idx[n]] = np.sqrt((u - 1.0) * (u + 1.0))
    for i in range(r.size):
        ri = r[i]
        for j in range(k):
            S[i, j] = S[i, j] * ri


def arccos_args(r: np.ndarray, t: np.ndarray, xm: np.ndarray, qm: np.ndarray,
                idx: np.ndarray) -> int:
    """First pass of ``torsion_annulus._slip_antiderivatives``: ``x = min(max(t/r, 0), 1)`` (1
    where ``r <= 0``); the ``x < 1`` into ``xm``, ``q = sqrt(max(1 − x², 0))`` of them into
    ``qm``, their flat indices into ``idx``; returns their count (the caller takes ``arccos``
    and ``q ** 3`` with numpy)."""
    k = t.size
    n = 0
    for i in range(r.size):
        ri = r[i]
        for j in range(k):
            if ri > 0:
                x = t[j] / ri
                if x != x:
                    pass                                  # np.maximum/minimum: nan propagates
                else:
                    x = x if x >= 0.0 else 0.0
                    x = x if x <= 1.0 else 1.0
            else:
                x = 1.0
            if x < 1.0:
                xm[n] = x
                w = 1.0 - x * x
                qm[n] = np.sqrt(w if w >= 0.0 else 0.0)
                idx[n] = i * k + j
                n += 1
    return n


def slip_fill(r: np.ndarray, r3: np.ndarray, xm: np.ndarray, qm: np.ndarray, q3: np.ndarray,
              ac: np.ndarray, idx: np.ndarray, one0: float, one1: float, g0: np.ndarray,
              g1: np.ndarray) -> None:
    """Second pass of ``torsion_annulus._slip_antiderivatives``: at the flat indices ``idx`` of
    ``g0``, ``g1`` (zeros, ``r.size × k``) the antiderivatives ``G0(x) − G0(1)``, ``G1(x) −
    G1(1)`` from ``x``, ``q``, ``q³`` and ``arccos x`` (``torsion_annulus._G01``'s arithmetic),
    then ``g0 *= r²``, ``g1 *= r3`` (numpy's ``r ** 3``) by rows (every element)."""
    k = g0.shape[1]
    f0 = g0.ravel()
    f1 = g1.ravel()
    half_pi = 0.5 * np.pi
    for n in range(xm.size):
        x, q, c = xm[n], qm[n], ac[n]
        asn = half_pi - c
        v0 = x * c - q - q3[n] / 3.0
        v1 = (0.5 * x * x * c - 0.25 * x * q + 0.25 * asn + (x * (2.0 * x * x - 1.0) * q + asn) / 8.0)
        f0[idx[n]] = v0 - one0
        f1[idx[n]] = v1 - one1
    for i in range(r.size):
        r2 = r[i] * r[i]
        c3 = r3[i]
        for j in range(k):
            g0[i, j] = g0[i, j] * r2
            g1[i, j] = g1[i, j] * c3


def traction_antiderivatives(kern: dict, r: np.ndarray, nodes: np.ndarray
                             ) -> tuple[np.ndarray, np.ndarray]:
    """``torsion_annulus._antiderivatives`` by the kernels ``kern`` (:func:`kernels`): two
    passes around numpy's own ``arccosh`` of the same vector (the same bits)."""
    r = np.ascontiguousarray(r, float)
    nodes = np.ascontiguousarray(nodes, float)
    size = r.size * nodes.size
    um, idx = np.empty(size), np.empty(size, np.int64)
    n = kern["arccosh_args"](r, nodes, um, idx)
    um, idx = um[:n], idx[:n]
    A, S = np.zeros((r.size, nodes.size)), np.zeros((r.size, nodes.size))
    kern["traction_fill"](r, um, np.arccosh(um), idx, A, S)
    return A, S


def slip_antiderivatives(kern: dict, rr: np.ndarray, nodes: np.ndarray, one0: float,
                         one1: float) -> tuple[np.ndarray, np.ndarray]:
    """``torsion_annulus._slip_antiderivatives`` (radii ``rr`` as a column; ``one0``, ``one1``:
    ``G0(1)``, ``G1(1)``) by the kernels ``kern``: two passes around numpy's own ``arccos``,
    ``q ** 3`` and ``r ** 3`` of the same vectors (the same bits)."""
    rr = np.ascontiguousarray(rr, float)
    r = rr.ravel()
    nodes = np.ascontiguousarray(nodes, float)
    size = r.size * nodes.size
    xm, qm, idx = np.empty(size), np.empty(size), np.empty(size, np.int64)
    n = kern["arccos_args"](r, nodes, xm, qm, idx)
    xm, qm, idx = xm[:n], qm[:n], idx[:n]
    g0, g1 = np.zeros((r.size, nodes.size)), np.zeros((r.size, nodes.size))
    kern["slip_fill"](r, (rr ** 3).ravel(), xm, qm, qm ** 3, np.arccos(xm), idx, one0, one1,
                      g0, g1)
    return g0, g1


#: the kernels by name (plain Python functions)
_PLAIN: dict[str, Callable[..., Any]] = {
    "psi": psi_pass, "ends": ends_pass, "arccosh_args": arccosh_args,
    "traction_fill": traction_fill, "arccos_args": arccos_args, "slip_fill": slip_fill}


def kernels(compiled: bool = True) -> dict:
    """The kernels by name (``"psi"``, ``"ends"``, ``"arccosh_args"``, ``"traction_fill"``,
    ``"arccos_args"``, ``"slip_fill"``) compiled by numba (built once per process), or
    the plain Python functions (``compiled=False``: the kernels' logic without numba, for
    tests)."""
    if not compiled:
        return dict(_PLAIN)
    built = _state["kernels"]
    if built is not None:               # built: no lock (asked ~15 times a solver step)
        return built
    with _lock:
        if _state["kernels"] is None:
            # the helpers inlined into their callers at numba's IR level (here and in
            # contactlab.numeric.annulus_kernel), compiled before them
            g = globals()
            for name in ("lines", "psi_at", "piece_ends", "_right"):
                g[name] = _jit.njit(g[name], nogil=True, error_model="numpy", inline="always")
            _state["kernels"] = {name: _jit.njit(f, nogil=True, error_model="numpy")
                                 for name, f in _PLAIN.items()}
    return _state["kernels"]
