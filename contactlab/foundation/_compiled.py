"""Optional compiled kernels of the MDR foundation (extra ``fast``: numba), numpy as reference.

Plain-array signatures, no object state, so other drivers (a DEM contact law, a viscoelastic
foundation) can call them directly:

``jenkins_update(m, K, invK, L, inc) -> float``
    Advance Jenkins elements (springs of stiffness ``K`` in series with Coulomb sliders of limit
    ``L >= 0``) in place by the displacement increment ``inc``: ``m ← clip(m + K inc, -L, L)``;
    returns the energy dissipated, ``Σ (trial - m) m / K`` (``invK = 1/K``; any finite value
    where ``K = 0``). Float64 arrays of one length, ``m`` writable.

``winkler_steps(d, a, k, S_edge, T_edge, target, d0, k0, x0, release, c, w, dG, X1, dH, K, invK,
iKeff, S, m, bl, W0, out_F, out_W, out_stick, want_stick, block, block_from)
-> (direction, lo)``
    A run of fused steps of the Winkler foundation, each with a new depth and a prescribed
    displacement/twist (numba only; :func:`fused_step` returns it or None). Per step the normal
    springs move to depth ``d[j]`` (edge cell ``k[j]``, its partial integrals ``S_edge[j]``,
    ``T_edge[j]``), the slip limits ``c × (d X1 - dH)`` follow, the element stiffness is
    weighted by the contact over the step, and the elements advance to ``target[j]``: what
    ``Winkler.set_normal``, the stiffness weighting, ``Winkler.jenkins``, the element sum and
    ``Winkler.stick_radius`` do in ~20 numpy calls, here in one pass over three ranges of cells
    (bulk in contact ``i < lo``, cells the edge crossed ``lo <= i < hi``, outside). Only ``m`` and
    the few ``iKeff`` entries whose weight changes are written per step (``S`` is read at the
    first step: the normal state before the run); the slip limits, the normal state and
    ``iKeff[:lo]`` (= ``invK``, the bulk of the last step) after the run are the caller's.
    ``out_F``, ``out_W`` (cumulative from ``W0``) and ``out_stick`` are filled; returns the sign
    of the last non-zero increment (0 if none) and the last step's ``lo``. Element updates: the
    same arithmetic as the numpy calls; the sums run in four fixed interleaved partial sums
    (deterministic; within ~N ulps of numpy's pairwise sums). The springs go through the run in
    blocks of ``block`` (:data:`FUSED_BLOCK`) when there are more than ``block_from``
    (:data:`FUSED_BLOCK_FROM`): each block through every step while it sits in cache, so that
    10^6 springs are not bound by memory bandwidth (the per-step sums add the
    blocks' partial sums in a fixed order); up to that, all springs form one block. One step
    loop serves both (``_steps_block``).

The numba version is used automatically when numba imports (``backend() == "numba"``); numpy is
the reference and the fallback (``CONTACTLAB_BACKEND=numpy`` or :func:`set_backend` forces it).
The element updates are bit-identical between the two; the dissipated energy is a sum in another
order (sequential against numpy's pairwise), equal to ~``N`` ulps, far below 1e-12 relative for
the spring counts in use. numba compiles a kernel on its first call and keeps the machine code on disk
(:mod:`contactlab.numeric.jit`): the first process on a machine compiles (seconds), later
processes load it.
"""
from __future__ import annotations

import os
import threading

import numpy as np

# ``x ** p`` for whole ``p`` in 1...4 by the multiplications of numeric.powers.power, in its
# order (compiled with the kernels below for the edge-cell pass)
from ..numeric.powers import power_float as _whole_power

__all__ = ["jenkins_update", "jenkins_update_numpy", "backend", "set_backend", "available",
           "fused_step", "edge_cells"]

_state: dict = {"backend": None, "kernel": None, "fused": None, "edges": None}

#: elements per chunk of the numpy Jenkins update on long vectors (loaded 2-core VM, N = 10^6:
#: 12.3 -> 8.6 ns per update, bit-identical; no gain at 10^5)
NUMPY_CHUNK = 16384

#: springs per block of the fused step (each block runs every step of a run while its ~6 arrays
#: of ``FUSED_BLOCK`` floats stay in the core's cache) ...
FUSED_BLOCK = 8192
#: ... above this many springs; up to it one pass per step is as fast (measured on the 2-core VM,
#: kernel alone: N = 10^4 blocks of 2048 1.2x slower than one pass; N = 10^5 blocks of 8192 1.2x
#: faster, N = 10^6 1.3x faster)
FUSED_BLOCK_FROM = 2**16


def _jenkins_passes(m: np.ndarray, K: np.ndarray, invK: np.ndarray, L: np.ndarray,
                    nL: np.ndarray, inc: float, t: np.ndarray) -> None:
    """The element-wise passes of :func:`jenkins_update_numpy` on (views of) its arrays:
    ``m ← clip(m + K inc, -L, L)`` and each element's dissipation into ``t``."""
    np.multiply(K, inc, out=t)
    t += m
    np.minimum(t, L, out=m)
    np.maximum(m, nL, out=m)
    t -= m
    t *= m
    t *= invK


def jenkins_update_numpy(m: np.ndarray, K: np.ndarray, invK: np.ndarray, L: np.ndarray,
                         inc: float, tmp: np.ndarray | None = None,
                         nL: np.ndarray | None = None) -> float:
    """Reference numpy implementation of :func:`jenkins_update` (``tmp``: optional scratch,
    ``nL``: ``-L`` if the caller keeps it)."""
    tmp = np.empty_like(m) if tmp is None else tmp
    nL = -L if nL is None else nL
    n = m.size
    if n <= 2 * NUMPY_CHUNK:        # one chunk: the whole arrays, no views
        _jenkins_passes(m, K, invK, L, nL, inc, tmp)
    else:
        # long vectors: the element-wise passes a cache-sized chunk at a time (the same
        # operations per element, so bit-identical; 8 passes over 10^6-element arrays are
        # memory-bound)
        for s in range(0, n, NUMPY_CHUNK):
            e = min(n, s + NUMPY_CHUNK)
            _jenkins_passes(m[s:e], K[s:e], invK[s:e], L[s:e], nL[s:e], inc, tmp[s:e])
    # a plain (pairwise) sum, not np.dot: a BLAS dot runs multithreaded on long vectors and
    # costs 50x more at N = 10^5 on a loaded machine (and its result follows the thread count)
    return float(tmp.sum())


def _jenkins(m, K, invK, L, inc):     # pragma: no cover - compiled
    w = 0.0
    for i in range(m.size):
        t = K[i] * inc + m[i]
        v = min(t, L[i])
        v = max(v, -L[i])
        m[i] = v
        w += (t - v) * v * invK[i]
    return w


def _bulk(i0, i1, d, c, X1, dH, K, invK, m, inc, update, find):     # pragma: no cover
    """Cells ``i0 <= i < i1`` in contact before and after the step (weight 1): four
    interleaved partial sums in a fixed order (deterministic), so the loop is not
    latency-bound. With ``find`` and ``update``, also the first cell whose updated element
    sits at its limit (``-1`` if none): the stick-radius search in the same pass (the
    same comparison ``|m_i| >= L_i`` as the separate search, on the same numbers)."""
    W0 = W1 = W2 = W3 = 0.0
    F0 = F1 = F2 = F3 = 0.0
    first = -1
    nb = i1 - (i1 - i0) % 4 if i1 > i0 else i0
    if update:
        for i in range(i0, nb, 4):
            l0 = c * (d * X1[i] - dH[i])
            l1 = c * (d * X1[i + 1] - dH[i + 1])
            l2 = c * (d * X1[i + 2] - dH[i + 2])
            l3 = c * (d * X1[i + 3] - dH[i + 3])
            t0 = K[i] * inc + m[i]
            t1 = K[i + 1] * inc + m[i + 1]
            t2 = K[i + 2] * inc + m[i + 2]
            t3 = K[i + 3] * inc + m[i + 3]
            v0 = max(min(t0, l0), -l0)
            v1 = max(min(t1, l1), -l1)
            v2 = max(min(t2, l2), -l2)
            v3 = max(min(t3, l3), -l3)
            m[i] = v0
            m[i + 1] = v1
            m[i + 2] = v2
            m[i + 3] = v3
            W0 += (t0 - v0) * v0 * invK[i]
            W1 += (t1 - v1) * v1 * invK[i + 1]
            W2 += (t2 - v2) * v2 * invK[i + 2]
            W3 += (t3 - v3) * v3 * invK[i + 3]
            F0 += v0
            F1 += v1
            F2 += v2
            F3 += v3
            if find and first < 0:
                if abs(v0) >= l0:
                    first = i
                elif abs(v1) >= l1:
                    first = i + 1
                elif abs(v2) >= l2:
                    first = i + 2
                elif abs(v3) >= l3:
                    first = i + 3
        for i in range(nb, i1):
            li = c * (d * X1[i] - dH[i])
            t = K[i] * inc + m[i]
            v = max(min(t, li), -li)
            m[i] = v
            W0 += (t - v) * v * invK[i]
            F0 += v
            if find and first < 0 and abs(v) >= li:
                first = i
    else:
        for i in range(i0, nb, 4):
            F0 += m[i]
            F1 += m[i + 1]
            F2 += m[i + 2]
            F3 += m[i + 3]
        for i in range(nb, i1):
            F0 += m[i]
    return (W0 + W1) + (W2 + W3), (F0 + F1) + (F2 + F3), first


def _first_at_limit(i0, n, kj, dj, c, X1, dH, Te, m):     # pragma: no cover - compiled
    """The first cell from ``i0`` whose element sits at its limit (cells beyond the edge
    cell ``kj`` have limit 0, so the search ends there), or -1."""
    for i in range(i0, n):
        if i < kj:
            li = c * (dj * X1[i] - dH[i])
        elif i == kj:
            li = c * Te
        else:
            li = 0.0
        if abs(m[i]) >= li:
            return i
    return -1


def _edge_update(lo, hi, first, k_prev, kj, d_prev, dj, Se_prev, Se, Te, c, w, dG, X1, dH, K,
               invK, iKeff, S, m, inc, update, W, F):     # pragma: no cover - compiled
    """The cells ``lo ... hi - 1`` the contact edge crossed in a step (edge cell ``kj``
    now, ``k_prev`` before; ``first``: the run's first step, weights from ``S``): weight =
    change of the cell's S over the step / (w dd), Jenkins update, energy and force added
    to ``W``, ``F``."""
    dd = dj - d_prev
    for i in range(lo, hi):
        if first:
            s_old = S[i]
        elif i < k_prev:
            s_old = d_prev * w[i] - dG[i]
        elif i == k_prev:
            s_old = Se_prev
        else:
            s_old = 0.0
        if i < kj:
            si = dj * w[i] - dG[i]
            ti = dj * X1[i] - dH[i]
        elif i == kj:
            si = Se
            ti = Te
        else:
            si = 0.0
            ti = 0.0
        wt = (si - s_old) / (dd * w[i])
        wt = min(max(wt, 0.0), 1.0)
        li = c * ti
        mi = m[i]
        if update:
            t = K[i] * wt * inc + mi
            v = max(min(t, li), -li)
            m[i] = v
            if wt > 0:
                iKeff[i] = invK[i] / wt
            W += (t - v) * v * iKeff[i]
            mi = v
        F += mi
    return W, F


def _steps_block(d, k, S_edge, T_edge, target, d0, k0, x0, release, c, w, dG, X1, dH, K,
                invK, iKeff, S, m, off, F_step, W_step, first,
                want_stick):     # pragma: no cover - compiled
    """The springs ``off ... off + m.size - 1`` (arrays sliced to them; ``k``, ``k0``
    global) through every step (the one step loop of the fused run, all springs as one
    block or block by block): per step the bulk, the cells the edge crossed and the
    outside, the block's part of the step's sums into ``F_step``, ``W_step`` and of the
    first element at its limit (global index) into ``first`` where not found in an
    earlier block."""
    n = m.size
    d_prev = d0
    k_prev = k0 - off
    Se_prev = 0.0
    x = x0
    lo_prev = 0
    nz = n              # m is zero from nz on (unknown at first)
    for j in range(d.size):
        dj = d[j]
        kj = k[j] - off
        inc = target[j] - x
        update = inc != 0.0 or dj < d_prev or release
        lo = min(max(min(kj, k_prev), 0), n)
        hi = max(min(max(kj, k_prev) + 1, n), 0)
        # 1/K_eff of the cells that were in the bulk (weight 1) until now
        for i in range(lo, lo_prev):
            iKeff[i] = invK[i]
        find = want_stick and first[j] < 0
        W, F, st0 = _bulk(0, lo, dj, c, X1, dH, K, invK, m, inc, update, find)
        # the cells the edge crossed: weight = change of S over the step / (w dd)
        W, F = _edge_update(lo, hi, j == 0, k_prev, kj, d_prev, dj, Se_prev, S_edge[j],
                            T_edge[j], c, w, dG, X1, dH, K, invK, iKeff, S, m, inc, update,
                            W, F)
        # outside: limit 0, so an update leaves no element force
        if update:
            for i in range(hi, nz):
                if m[i] != 0.0:
                    m[i] = 0.0
            nz = hi
        if find:    # the first element at its limit, from the centre
            if st0 < 0:     # not in the bulk (found there during its update)
                st0 = _first_at_limit(lo if update else 0, n, kj, dj, c, X1, dH, T_edge[j], m)
            if st0 >= 0:
                first[j] = st0 + off
        release = False
        x = target[j]
        F_step[j] = F
        W_step[j] = W
        d_prev = dj
        k_prev = kj
        Se_prev = S_edge[j]
        lo_prev = lo


def _winkler_steps(d, a, k, S_edge, T_edge, target, d0, k0, x0, release, c, w, dG, X1, dH,
                   K, invK, iKeff, S, m, bl, W0, out_F, out_W, out_stick, want_stick,
                   block, block_from):     # pragma: no cover - compiled
    """Up to ``block_from`` springs: all springs as one block through the steps (each step's
    sums straight into ``out_F``, ``out_W``); more: block by block (each block through every
    step while it sits in cache; the element updates do not couple springs, the per-step sums
    add the blocks in a fixed order)."""
    n = m.size
    ns = d.size
    first = np.full(ns, -1, np.int64)
    if n <= block_from:
        _steps_block(d, k, S_edge, T_edge, target, d0, k0, x0, release, c, w, dG, X1, dH, K,
                     invK, iKeff, S, m, 0, out_F, out_W, first, want_stick)
    else:
        Fb = np.empty(ns)
        Wb = np.empty(ns)
        for b0 in range(0, n, block):
            b1 = min(n, b0 + block)
            _steps_block(d, k, S_edge, T_edge, target, d0, k0, x0, release, c, w[b0:b1],
                         dG[b0:b1], X1[b0:b1], dH[b0:b1], K[b0:b1], invK[b0:b1],
                         iKeff[b0:b1], S[b0:b1], m[b0:b1], b0, Fb, Wb, first, want_stick)
            if b0 == 0:
                out_F[:] = Fb
                out_W[:] = Wb
            else:
                out_F += Fb
                out_W += Wb
    # out_W holds each step's energy: the running total from W0; the stick radii
    Wtot = W0
    sgn = 0.0
    x = x0
    for j in range(ns):
        Wtot += out_W[j]
        out_W[j] = Wtot
        if want_stick:
            out_stick[j] = bl[first[j]] if first[j] >= 0 else a[j]
        inc = target[j] - x
        if inc != 0.0:
            sgn = 1.0 if inc > 0 else -1.0
        x = target[j]
    k_prev = k0 if ns == 1 else k[ns - 2]
    return sgn, min(k[ns - 1], k_prev)


def _edge_cells_data(d, a, Ga, Ha, b, G_left, H_left, k, S, T, want_T, radius, kp, p1,
                     p2):  # pragma: no cover
    """Per step: the cell holding the contact edge ``min(a, radius)`` (``searchsorted(b, a) -
    1`` clipped to the cells; the search starts from the previous step's cell) and its partial
    integrals, the arithmetic of ``Winkler.edge_data`` in the same order. ``p1 > 0``: the
    profile is one power term ``c r^n`` with whole ``p1 = n + 1``, ``p2 = n + 2`` and
    ``kp = κ_n c``; ``G(a) = kp a^p1 / p1`` and ``H(a) = kp a^p2 / p2`` are computed here (as
    :func:`contactlab.numeric.powers.power_integral` does) instead of read from ``Ga``, ``Ha``."""
    nb = b.size
    n = nb - 1
    idx = 0
    for j in range(d.size):
        aj = min(a[j], radius)
        if p1 > 0.0:
            Gj = _whole_power(aj, p1) * kp / p1 if aj > 0.0 else 0.0
            Hj = _whole_power(aj, p2) * kp / p2 if aj > 0.0 and want_T else 0.0
        else:
            Gj = Ga[j]
            Hj = Ha[j]
        # first boundary >= aj (np.searchsorted side="left"), tried at the last one first
        if not ((idx == 0 or b[idx - 1] < aj) and (idx == nb or aj <= b[idx])):
            lo = 0
            hi = nb
            while lo < hi:
                mid = (lo + hi) >> 1
                if b[mid] < aj:
                    lo = mid + 1
                else:
                    hi = mid
            idx = lo
        kj = min(max(idx - 1, 0), n - 1)
        k[j] = kj
        bl = b[kj]
        dj = d[j]
        if aj > bl:
            s = dj * (aj - bl) - (Gj - G_left[kj])
        else:
            s = 0.0
        S[j] = s if s >= 0.0 else 0.0
        if want_T:
            if aj > bl:
                t = dj * (aj * aj - bl * bl) / 2.0 - (Hj - H_left[kj])
            else:
                t = 0.0
            T[j] = t if t >= 0.0 else 0.0


#: the numba kernels above (plain Python here; :func:`_build` compiles them)
_KERNEL_NAMES = ("_jenkins", "_bulk", "_first_at_limit", "_edge_update", "_steps_block",
                 "_winkler_steps", "_whole_power", "_edge_cells_data")
_PY_KERNELS = {name: globals()[name] for name in _KERNEL_NAMES}
#: numba options beyond ``nogil`` per kernel: the bulk loop inlined into the step loop in
#: numba's IR (a gait at N = 100 springs: ~8 of ~113 ns per step of the compiled run; the
#: other callees are inlined by LLVM, and inlining them in numba's IR measured slower)
_KERNEL_OPTIONS = {"_bulk": {"inline": "always"}}
_compiled_kernels: dict = {}
_build_lock = threading.Lock()


def _build() -> dict:
    """The numba dispatchers of the kernels, by name (built once per process, compiled on their
    first call, machine code cached on disk: :func:`contactlab.numeric.jit.njit`). The module
    names are rebound to the dispatchers, so that a kernel calls the compiled callees."""
    with _build_lock:
        if not _compiled_kernels:
            from ..numeric.jit import njit
            built = {name: njit(fn, nogil=True, **_KERNEL_OPTIONS.get(name, {}))
                     for name, fn in _PY_KERNELS.items()}
            globals().update(built)
            _compiled_kernels.update(built)
    return _compiled_kernels


def edge_cells():
    """The compiled edge-cell locator of ``Winkler.edge_data`` (numba backend), or None with
    numpy (the caller then runs the numpy reference): ``edge_cells(d, a, Ga, Ha, b, G_left,
    H_left, k, S, T, want_T, radius, kp, p1, p2)`` fills ``k``, ``S`` (and ``T`` if ``want_T``)
    per step from the depths ``d``, the edge radii ``a`` (clipped here to the foundation's
    ``radius``) and the profile's integrals ``G(a)``, ``H(a)``: read from ``Ga``, ``Ha``, or
    for one power term with whole exponents (``p1 = n + 1 > 0``, ``p2``, ``kp = κ_n c``)
    computed in the same pass; bit-identical to the numpy calls."""
    if backend() != "numba":
        return None
    if _state["edges"] is None:
        _state["edges"] = _build()["_edge_cells_data"]
    return _state["edges"]


def fused_step():
    """The compiled fused Winkler step (see the module docstring), or None with the numpy
    backend (the caller then runs the numpy reference calls)."""
    if backend() != "numba":
        return None
    if _state["fused"] is None:
        _state["fused"] = _build()["_winkler_steps"]
    return _state["fused"]


def available() -> tuple[str, ...]:
    """Backends usable in this environment (``"numpy"`` always)."""
    from ..numeric.jit import available as numba_available
    return ("numpy", "numba") if numba_available() else ("numpy",)


def set_backend(name: str | None) -> None:
    """Force ``"numpy"`` or ``"numba"``; ``None`` returns to the automatic choice."""
    from ..errors import ParameterError
    if name is not None and name not in available():
        raise ParameterError(f"backend={name!r} is invalid: available here: "
                             f"{', '.join(available())} (numba comes with the extra 'fast').")
    _state.update(backend=name, kernel=None, fused=None, edges=None)


def backend() -> str:
    """The backend :func:`jenkins_update` uses (chosen on first use)."""
    name = _state["backend"]
    if name is None:
        forced = os.environ.get("CONTACTLAB_BACKEND", "").strip().lower()
        name = forced if forced in available() else available()[-1]
        _state["backend"] = name
    return name


def jenkins_update(m: np.ndarray, K: np.ndarray, invK: np.ndarray, L: np.ndarray,
                   inc: float, tmp: np.ndarray | None = None,
                   nL: np.ndarray | None = None) -> float:
    """Advance Jenkins elements in place by ``inc``; return the dissipated energy, J (see module)."""
    kernel = _state["kernel"]
    if kernel is None:
        kernel = _build()["_jenkins"] if backend() == "numba" else jenkins_update_numpy
        _state["kernel"] = kernel
    if kernel is jenkins_update_numpy:
        return jenkins_update_numpy(m, K, invK, L, inc, tmp, nL)
    return float(kernel(m, K, invK, L, float(inc)))
