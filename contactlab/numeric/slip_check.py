"""Optional compiled pass of the exact torsion step's slip check (extra ``fast``: numba).

A single-slip-annulus step (:func:`contactlab.physics.torsion_annulus.step`) must slip the way
of its traction on the annulus: where the sign of the density's increment alone does not show
it, the slip increments ``Δs(r) = (2/π) ∫_0^r Δw(t) K(r, t) dt + r × (gross turn)`` are formed at
the collocation points and none may point against the sense ``s`` by more than
``CHECK_RTOL`` of the largest (the numpy route: a :class:`~contactlab.physics.torsion_annulus.
NodeTable`'s antiderivatives times the density's jumps at every table node, two dense
matrix-vector products over all the table's nodes).

When the increments only feed that check (not returned), :func:`slip_check` sums, for each
point, the terms of the increment's own nodes below the point only (the antiderivatives vanish
at the nodes beyond it: exact zeros in the dense products), in another order than the dense
products, with the sum of the terms' magnitudes; it decides the check only where every point's
margin exceeds a bound on the difference between its sums and the numpy route's (the rounding
of either sum in any order, and a few units in the last place of the transcendental parts of a
node not in the table), else it leaves the check open and the caller takes the numpy route's
products. The verdict is always the numpy route's.

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

__all__ = ["CHECK_FAIL", "CHECK_OK", "CHECK_OPEN", "slip_check", "kernels"]

#: :func:`slip_check`'s verdicts: slip against the traction, none, or left to the numpy route
CHECK_FAIL, CHECK_OK, CHECK_OPEN = 0, 1, -1

_EPS = float(np.finfo(float).eps)
#: units in the last place allowed between two evaluations of a node's transcendental parts
_ULPS = 64.0
_state: dict = {"kernel": None}
# the shared helpers (rebound to their compiled builds with the pass)
_search = _ak._left
_lines = _rk.lines
_lock = threading.Lock()


def slip_check(lo, hi, wl, wr, r, s, gross, check_rtol, F0, F1, t_r, t_nodes, one0, one1):
    """The slip check of a step whose increment is the abutting pieces ``(lo, hi, wl, wr)`` at
    the points ``r`` (all rows of the table ``F0``, ``F1``, ``t_r``, ``t_nodes``: a
    ``NodeTable``'s slip antiderivatives, radii and nodes; ``one0``, ``one1``: the kernel's
    ``G0(1)``, ``G1(1)``), sense ``s``, gross turn ``gross``: :data:`CHECK_FAIL` where a point's
    increment points against ``s`` beyond ``check_rtol`` of the largest in the numpy route for
    certain, :data:`CHECK_OK` where none does for certain, else :data:`CHECK_OPEN` (also for
    pieces that do not abut, a piece of no width, a value not finite or a point not in the
    table)."""
    n, m = lo.size, r.size
    if n == 0 or m == 0 or F0.shape[0] == 0 or t_nodes.size == 0:
        return CHECK_OPEN
    for j in range(n):
        if not lo[j] - lo[j] == hi[j] - hi[j] == wl[j] - wl[j] == wr[j] - wr[j] == 0:
            return CHECK_OPEN
        if (j and lo[j] != hi[j - 1]) or not hi[j] > lo[j]:   # (a repeated node: OPEN)
            return CHECK_OPEN
    # the jumps of offset and slope at the nodes (torsion_annulus._jumps of its _lin)
    al, be, _ = _lines(lo, hi, wl, wr, False)
    t = np.empty(n + 1)
    c0 = np.empty(n + 1)
    c1 = np.empty(n + 1)
    col = np.empty(n + 1, np.int64)
    for j in range(n + 1):
        t[j] = lo[j] if j < n else hi[n - 1]
        c0[j] = (al[j - 1] if j > 0 else 0.0) - (al[j] if j < n else 0.0)
        c1[j] = (be[j - 1] if j > 0 else 0.0) - (be[j] if j < n else 0.0)
        k = _search(t_nodes, t[j])
        col[j] = k if k < t_nodes.size and t_nodes[k] == t[j] else -1
    ds = np.empty(m)
    err = np.empty(m)
    k2 = 2.0 / np.pi
    for i in range(m):
        ri = r[i]
        row = _search(t_r, ri)
        if row >= t_r.size or t_r[row] != ri or not ri > 0:
            return CHECK_OPEN
        acc = mag = off = 0.0
        for j in range(n + 1):
            if not t[j] < ri:        # nodes at or beyond the point add exact zeros
                break
            if col[j] >= 0:
                f0, f1 = F0[row, col[j]], F1[row, col[j]]
            else:
                # torsion_annulus._slip_antiderivatives at a node not in the table
                x = t[j] / ri
                x = x if x > 0.0 else 0.0
                q = np.sqrt(1.0 - x * x)
                ac = np.arccos(x)
                asn = 0.5 * np.pi - ac
                g0 = x * ac - q - q ** 3 / 3.0
                g1 = 0.5 * x * x * ac - 0.25 * x * q + 0.25 * asn + (x * (2.0 * x * x - 1.0) * q
                                                                     + asn) / 8.0
                f0, f1 = (g0 - one0) * (ri * ri), (g1 - one1) * ri ** 3
                off += _ULPS * _EPS * (
                    abs(c0[j]) * ri * ri * (abs(x * ac) + q + q ** 3 / 3.0 + abs(one0))
                    + abs(c1[j]) * ri ** 3 * (0.5 * x * x * ac + 0.25 * x * q + 0.25 * abs(asn)
                                              + (abs(x * (2.0 * x * x - 1.0) * q) + abs(asn)) / 8.0
                                              + abs(one1)))
            a = f0 * c0[j]
            b = f1 * c1[j]
            acc += a + b
            mag += abs(a) + abs(b)
        g = gross * ri
        ds[i] = k2 * acc + g
        # both sums' rounding in any order over every table node, the off-table parts, the
        # scaling and the gross turn
        err[i] = (k2 * (4.0 * (2 * t_nodes.size + n + 8) * _EPS * mag + off)
                  + 4.0 * _EPS * (abs(ds[i]) + abs(g)))
    big = rmax = emax = 0.0
    for i in range(m):
        big = max(big, abs(ds[i]))
        rmax = max(rmax, r[i])
        emax = max(emax, err[i])
    if not (big - big == 0 and emax - emax == 0):
        return CHECK_OPEN
    thr = check_rtol * (big + rmax * abs(gross))
    verdict = CHECK_OK
    for i in range(m):
        margin = s * ds[i] + thr
        tol = err[i] + check_rtol * emax + 4.0 * _EPS * (thr + abs(ds[i]))
        if margin < -tol:
            return CHECK_FAIL
        if not margin > tol:
            verdict = CHECK_OPEN
    return verdict


def kernels(compiled: bool = True) -> dict:
    """``{"slip_check": ...}`` compiled by numba (built once per process), or the plain Python
    function (``compiled=False``: its logic without numba, for tests)."""
    if not compiled:
        return {"slip_check": slip_check}
    built = _state["kernel"]
    if built is not None:
        return built
    with _lock:
        if _state["kernel"] is None:
            _ak.kernels(True)           # (compiles the ring kernels' lines and the search)
            g = globals()
            g["_search"], g["_lines"] = _ak._left, _rk.lines
            _state["kernel"] = {"slip_check": _jit.njit(slip_check, nogil=True,
                                                        error_model="numpy")}
    return _state["kernel"]
