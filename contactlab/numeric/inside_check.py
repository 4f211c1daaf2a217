"""Compiled traction check inside the stick radius of the exact torsion solver's annulus step,
with a memo carried from step to step (extra ``fast``: numba; a helper of
:func:`contactlab.numeric.annulus_kernel.twist_step`).

The check (``torsion_annulus._inside_ok``): at every collocation point ``r < c`` the traction of
the new density ``w``, ``τ(r) = (4 G_t/π) r X(r)`` with ``X(r) = Σ_j F0(r, t_j) c0_j + F1(r,
t_j) c1_j`` (``F0 = arccosh(t/r)``, ``F1 = sqrt(t² − r²)``, a ``NodeTable``'s antiderivatives,
times the density's jumps of offset and slope at its nodes ``t_j``), stays within ``μ p``. The
numpy route forms ``X`` at every point by dense products over the table's nodes: points ×
nodes terms per step, the part of an annulus step that grows with the ring set.

:func:`inside` sums ``X`` at each point in another order and decides only where the margin
exceeds a bound on the rounding of either sum (else :data:`INSIDE_OPEN`: the caller takes the
numpy route's verdict). :func:`inside_memo` does the same, but first tries each point from an
interval ``[L, U]`` on ``X`` of the step's old density (the memo: the intervals the previous
call left, valid where the old density is, to the last bit, the density that call checked):

* the new density equals the old one on its pieces below a node ``c'`` (``w`` keeps the old
  density below ``c``; only the piece holding ``c`` is cut), so with the lines ``L = al + be t``
  of the pieces, ``X_new(r) − X_old(r) = ∫_{c'}^∞ (L_new − L_old)(t) / sqrt(t² − r²) dt``
  exactly (the terms at nodes below ``c'`` are the same products; by parts the rest is that
  integral, the antiderivatives taken exact), plus the antiderivatives' rounding at the nodes
  from ``c'`` on;
* on each interval between consecutive nodes of either density ``|L_new − L_old|`` is at most
  its larger end value ``m_k`` (linear), and for ``r <= ρ < c' <= u_k``,
  ``∫_{u_k}^{u_{k+1}} dt / sqrt(t² − r²) <= (u_{k+1} − u_k) / u_k · 1/sqrt(1 − (ρ/u_k)²)``, so
  ``|ΔX(r)| <= g(r/c') S_near + g(r/(2c')) S_far`` with ``g(q) = 1/sqrt(1 − q²)`` and the sums of
  ``m_k (u_{k+1} − u_k)/u_k`` over the intervals below and above ``2c'``: one pass over the
  pieces per step, two square roots per point;
* the antiderivatives' rounding: ``arccosh(fl(t/r))`` within a few units in the last place of
  ``arccosh``, plus ``ε g(r/t)`` from the quotient's rounding; ``sqrt((u − 1)(u + 1)) r`` within
  ``ε t g(r/t)`` likewise: ``64 ε`` times those, times the sums of the jumps' magnitudes at the
  nodes from ``c'`` on (both densities), is added; ``arccosh(T/r) <= 2 sqrt(2T/r)`` bounds
  ``F0`` (``T`` the largest node);
* the numpy route's sum differs from ``X`` by at most ``4 (n + 4) ε`` times the sum of its
  terms' magnitudes, at most ``arccosh(T/r) Σ|c0| + T Σ|c1|``.

The interval widened by that bound decides a point where even its worst end, rounded, stays
below ``μ p (1 + rtol)``; a point it does not decide (near ``c'``, a memo not valid for it, or
a margin used up by the widening of many steps) is summed as by :func:`inside`, and its
interval restarts from that sum (``X`` within ``2 (n + 4) ε`` of the sum of its terms'
magnitudes). So every verdict is the numpy route's, the memo only saves the sums. The memo's
intervals are of ``X`` as summed with the table's values and, at a node not in the table, the
values computed here (deterministic), so they do not depend on ``G_t`` or ``μ p``.
"""
from __future__ import annotations

import numpy as np

from . import jit as _jit
from . import ring_kernels as _rk
from . import sorted_search as _ss

__all__ = ["INSIDE_FAIL", "INSIDE_OK", "INSIDE_OPEN", "LOWER", "UPPER", "VALID", "FAILED",
           "inside", "inside_memo", "build"]

#: the check's verdicts (:func:`inside`)
INSIDE_FAIL, INSIDE_OK, INSIDE_OPEN = 0, 1, -1
#: the rows of a memo (:func:`inside_memo`): the interval on ``X`` at each point, and 1 where
#: it holds (0 where the point was not checked; :data:`FAILED` at the point that decided
#: :data:`INSIDE_FAIL`)
LOWER, UPPER, VALID = 0, 1, 2
#: the memo's mark (row :data:`VALID`) of the point whose traction failed the check
FAILED = -1.0
#: points within this fraction of ``c'`` below it are summed, not bounded (``g(r/c')`` <= 16)
_NEAR = 1.0 / 512.0
#: units in the last place allowed for the antiderivatives' rounding
_ULPS = 64.0
_EPS = float(np.finfo(float).eps)
_state: dict = {"built": False}

# the helpers (rebound to their compiled builds by :func:`build`)
_left = _ss.left
_lines = _rk.lines


def _jumps(lo, hi, wl, wr, t_nodes):
    """The pieces' lines ``(al, be)``, the jumps of offset and slope at the nodes ``lo_0, ...,
    lo_{n−1}, hi_{n−1}`` (``torsion_annulus._jumps``) and the nodes' columns in the table (−1
    for a node not in it)."""
    n = lo.size
    al, be, _ = _lines(lo, hi, wl, wr, False)
    c0 = np.empty(n + 1)
    c1 = np.empty(n + 1)
    cols = np.empty(n + 1, np.int64)
    for j in range(n + 1):
        c0[j] = (al[j - 1] if j > 0 else 0.0) - (al[j] if j < n else 0.0)
        c1[j] = (be[j - 1] if j > 0 else 0.0) - (be[j] if j < n else 0.0)
        t = lo[j] if j < n else hi[n - 1]
        k = _left(t_nodes, t)
        cols[j] = k if k < t_nodes.size and t_nodes[k] == t else -1
    return al, be, c0, c1, cols


def _point(ri, row, lo, hi, c0, c1, cols, F0, F1):
    """``X`` at the point ``ri`` (the table's row ``row``) summed over the nodes, and the sum of
    its terms' magnitudes; the antiderivatives of a node not in the table (the stick radius)
    computed here (the C library's ``acosh``: within a few units in the last place of
    numpy's)."""
    n = lo.size
    acc = 0.0
    mag = 0.0
    for j in range(n + 1):
        q = cols[j]
        if q >= 0:
            f0, f1 = F0[row, q], F1[row, q]
        else:
            t = lo[j] if j < n else hi[n - 1]
            u = t / ri if ri > 0 else 1.0
            f0 = np.arccosh(u) if u > 1.0 else 0.0
            f1 = np.sqrt((u - 1.0) * (u + 1.0)) * ri if u > 1.0 else 0.0
        a = f0 * c0[j]
        b = f1 * c1[j]
        acc += a + b
        mag += abs(a) + abs(b)
    return acc, mag


def _drift(lo, hi, wl, wr, al, be, c0, c1, olo, ohi, owl, owr):
    """The bound's parts for the step ``old → w`` (module docstring): ``(c', I0, E, S_near,
    S_far, Σ|c0|, Σ|c1|, T)`` over the nodes from ``c'`` on, ``c'`` the end of the pieces both
    share from the start (or, sharing none, the first node of either), ``I0 = ∫ ΔL/t dt`` and
    ``E`` a bound on its rounding; ``c' = −1`` where ``c'`` is not positive (or a node is not a
    number)."""
    n, no = lo.size, olo.size
    k = 0
    while (k < n and k < no and lo[k] == olo[k] and hi[k] == ohi[k] and wl[k] == owl[k]
           and wr[k] == owr[k]):
        k += 1
    # (none shared: both densities are zero below their first nodes)
    cp = hi[k - 1] if k else min(lo[0], olo[0])
    if not cp > 0.0:
        return -1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0
    oal, obe, _ = _lines(olo, ohi, owl, owr, False)
    s0 = s1 = 0.0
    for j in range(k, n + 1):
        s0 += abs(c0[j])
        s1 += abs(c1[j])
    for j in range(k, no + 1):
        s0 += abs((oal[j - 1] if j > 0 else 0.0) - (oal[j] if j < no else 0.0))
        s1 += abs((obe[j - 1] if j > 0 else 0.0) - (obe[j] if j < no else 0.0))
    top = max(hi[n - 1], ohi[no - 1])
    p, q, u = k, k, cp
    i0 = e0 = near = far = 0.0
    count = 0
    while p < n or q < no:
        # each density's next node and its line on [u, that node] (zero before its first piece
        # and after its last)
        inw = p < n and u >= lo[p]
        ino = q < no and u >= olo[q]
        vw = (hi[p] if inw else lo[p]) if p < n else np.inf
        vo = (ohi[q] if ino else olo[q]) if q < no else np.inf
        v = min(vw, vo)
        aw, bw = (al[p], be[p]) if inw else (0.0, 0.0)
        ao, bo = (oal[q], obe[q]) if ino else (0.0, 0.0)
        if not (aw == ao and bw == bo):
            lg = np.log1p((v - u) / u)             # ∫ dt/t over the interval
            i0 += (aw - ao) * lg + (bw - bo) * (v - u)
            big = (abs(aw) + abs(ao)) * lg + (abs(bw) + abs(bo)) * (v - u)
            e0 += big
            d1 = abs((aw + bw * u) - (ao + bo * u))
            d2 = abs((aw + bw * v) - (ao + bo * v))
            mk = max(d1, d2) + 4.0 * _EPS * (abs(aw) + abs(ao) + (abs(bw) + abs(bo)) * v)
            if u < 2.0 * cp:
                near += mk * lg
            else:
                far += mk * lg
        moved = v > u
        if inw and vw == v:
            p += 1
            moved = True
        if ino and vo == v:
            q += 1
            moved = True
        if not moved:           # a node not a number
            return -1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0
        count += 1
        u = v
    f = 1.0 + 8.0 * (count + 8) * _EPS      # (the sums' own rounding)
    # I0's rounding: each term's within a few ε of the magnitudes it is made of, the sum's
    # within (count + 2) ε of their total
    e0 = 8.0 * (count + 8) * _EPS * e0 * f + 4.0 * _EPS * abs(i0)
    return cp, i0, e0, near * f, far * f, s0, s1, top


def inside_memo(lo, hi, wl, wr, olo, ohi, owl, owr, r, bound, c, G_t, check_rtol, F0, F1, t_r,
                t_nodes, memo_w, memo_x):
    """The traction check inside the stick radius ``c`` of the density ``(lo, hi, wl, wr)``
    reached from the old density ``(olo, ohi, owl, owr)`` at the points ``r`` with ``μ p`` =
    ``bound`` (``F0``, ``F1``, ``t_r``, ``t_nodes``: the table's traction antiderivatives, radii
    and nodes), with the memo ``memo_x`` (``3 × r.size``: :data:`LOWER`, :data:`UPPER`,
    :data:`VALID`) of the density ``memo_w`` (``4 × n``: its pieces' rows), used where that is the
    old density to the last bit.

    Returns ``(verdict, memo)``: :data:`INSIDE_OK` / :data:`INSIDE_FAIL` where every point's
    margin (one failing point's) exceeds a bound on the difference to the numpy route's sums,
    else :data:`INSIDE_OPEN` (also without a table, with pieces that do not abut, or a radius not
    in the table); the memo of this density (the points checked; with :data:`INSIDE_FAIL` the
    failing point, the innermost whose margin decides, marked :data:`FAILED`)."""
    m_all = r.size
    out = np.zeros((3, m_all))
    m = 0
    for i in range(m_all):
        if r[i] < c:
            m += 1
    if c <= 0 or m == 0:
        return INSIDE_OK, out
    n = lo.size
    if n == 0 or F0.shape[0] == 0:
        return INSIDE_OPEN, out
    for j in range(n - 1):
        if lo[j + 1] != hi[j]:
            return INSIDE_OPEN, out
    al, be, c0, c1, cols = _jumps(lo, hi, wl, wr, t_nodes)
    cp = -1.0
    i0 = e0 = near = far = s0 = s1 = top = 0.0
    if memo_x.shape[1] == m_all and olo.size and memo_w.shape[1] == olo.size:
        same = True
        for j in range(olo.size):
            if not (memo_w[0, j] == olo[j] and memo_w[1, j] == ohi[j]
                    and memo_w[2, j] == owl[j] and memo_w[3, j] == owr[j]):
                same = False
                break
        if same:
            cp, i0, e0, near, far, s0, s1, top = _drift(lo, hi, wl, wr, al, be, c0, c1,
                                                        olo, ohi, owl, owr)
    a0 = a1 = 0.0
    for j in range(n + 1):
        a0 += abs(c0[j])
        a1 += abs(c1[j])
    top = max(top, hi[n - 1])
    reach = cp * (1.0 - _NEAR)
    gam = 4.0 * (n + 4) * _EPS
    k4 = 4.0 * G_t / np.pi
    verdict = INSIDE_OK
    for i in range(m_all):
        ri = r[i]
        if not ri < c:
            continue
        row = _left(t_r, ri)
        if row >= t_r.size or t_r[row] != ri:
            return INSIDE_OPEN, out
        lim = bound[i] * (1 + check_rtol)
        if 0.0 < ri <= reach and memo_x[VALID, i] == 1.0:
            # the old interval widened by the step's bound (module docstring)
            q2 = (ri / cp) * (ri / cp)
            h1 = np.sqrt(1.0 - q2)
            h2 = np.sqrt(1.0 - 0.25 * q2)
            g1 = 1.0 / h1
            # g − 1 = q² / (h (1 + h)), h = sqrt(1 − q²): without cancellation
            d = ((q2 / (h1 * (1.0 + h1))) * near + (0.25 * q2 / (h2 * (1.0 + h2))) * far) \
                * (1.0 + 16.0 * _EPS)
            x0 = 2.0 * np.sqrt(2.0 * top / ri) + 1.0          # >= arccosh(top / ri)
            d += e0 + _ULPS * _EPS * ((x0 + g1) * s0 + g1 * top * s1)
            lower = (memo_x[LOWER, i] + i0) - d
            upper = (memo_x[UPPER, i] + i0) + d
            slack = 4.0 * _EPS * (abs(memo_x[LOWER, i]) + abs(memo_x[UPPER, i]) + abs(i0) + d)
            lower -= slack
            upper += slack
            ey = gam * (x0 * a0 + top * a1)         # the numpy route's rounding
            tau = abs(k4 * ri) * max(abs(lower - ey), abs(upper + ey)) * (1.0 + 8.0 * _EPS)
            if lim - tau > 4.0 * _EPS * (tau + abs(lim)):
                out[LOWER, i], out[UPPER, i], out[VALID, i] = lower, upper, 1.0
                continue
        acc, mag = _point(ri, row, lo, hi, c0, c1, cols, F0, F1)
        e = 2.0 * (n + 4) * _EPS * mag + 2.0 * _EPS * abs(acc)
        if acc - acc == 0 and e - e == 0:           # (finite)
            out[LOWER, i], out[UPPER, i], out[VALID, i] = acc - e, acc + e, 1.0
        scale = k4 * ri
        tau = abs(scale * acc)
        err = 4.0 * (n + 4) * _EPS * abs(scale) * mag + 4.0 * _EPS * (tau + abs(lim))
        if tau - lim > err:
            out[VALID, i] = FAILED
            return INSIDE_FAIL, out
        if not lim - tau > err or tau != tau or lim != lim:
            verdict = INSIDE_OPEN
    return verdict, out


def inside(lo, hi, wl, wr, r, bound, c, G_t, check_rtol, F0, F1, t_r, t_nodes) -> int:
    """The check of :func:`inside_memo` without a memo (every point summed)."""
    z = np.zeros(0)
    return inside_memo(lo, hi, wl, wr, z, z, z, z, r, bound, c, G_t, check_rtol, F0, F1, t_r,
                       t_nodes, np.zeros((4, 0)), np.zeros((3, 0)))[0]


def build(left) -> None:
    """Compile the passes with numba (once per process; called by
    :func:`contactlab.numeric.annulus_kernel.kernels` under its lock, with its compiled search
    ``left``): the module's names rebound to their compiled builds."""
    if _state["built"]:
        return
    g = globals()
    g["_left"], g["_lines"] = left, _rk.lines
    for name in ("_jumps", "_point"):
        g[name] = _jit.njit(g[name], nogil=True, error_model="numpy", inline="always")
    for name in ("_drift", "inside_memo", "inside"):
        g[name] = _jit.njit(g[name], nogil=True, error_model="numpy")
    _state["built"] = True
