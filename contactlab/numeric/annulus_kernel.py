"""Optional compiled kernels of the exact torsion solver's annulus step and its energy (extra
``fast``: numba).

A twist step of the exact path solver (:func:`contactlab.physics.torsion_annulus.step`) and the
energy of a chain of its stages (:mod:`contactlab.physics.torsion_energy`) are each some forty
small numpy operations on piecewise-linear densities of ~100-200 pieces, a few microseconds each:
Python's call overhead, not arithmetic, is their cost. Here each is one compiled pass over the
densities' plain arrays (piece ends ``lo``, ``hi`` and end values ``wl``, ``wr``):

* :func:`twist_step`: the piece ends of both densities below the contact radius, ``Ψ`` of both
  there, the bracket and root of the stick radius, the splice of the new density, its total
  turn and the traction check inside the stick radius (from a :class:`NodeTable`'s
  antiderivatives and the memo of the last density checked:
  :mod:`contactlab.numeric.inside_check`); :func:`slip_difference`: the difference density of
  the slip check and its sign;
* :func:`energy_nodes`, :func:`difference_psi`, :func:`family_energy` and
  :func:`release_family_energy`: the Gauss points and weights of the energy integrals, ``Ψ`` of a
  density there, ``Ψ`` of the difference of two densities, a family stage's products and those
  of a shrinking contact's release and family stages (:func:`shrink_energy`: with the release
  density's own step);
* :func:`nonnegative_band`: the test of the full-sliding density's ``Ψ >= 0``
  (:func:`nonnegative`) and the removal of the band where ``Ψ < 0``;
* :func:`coefficient_pieces`: the ring solver's hat coefficients as pieces cut at the contact
  radius;
* :func:`table_scatter`: the slip integral's jumps scattered onto a table's nodes (its matrix
  products stay numpy's).

Every value the solver's state or results take is computed with the IEEE operations of the
numpy route in its order (sums: numpy's pairwise order, :func:`pairwise_sum`; look-ups:
``searchsorted``'s; the root: the same safeguarded Newton), so the step's density, stick radius
and turn are bit-identical to the numpy route. Two things are not: the traction of the check
inside the stick radius is summed in another order than the numpy route's matrix-vector product,
or bounded from the last step's sums, so the check is decided here only where its margin exceeds
a bound on the difference to the numpy route's sums (else the caller decides it with the numpy
route: the verdict is always the numpy route's); and
the energy's dot products are left to numpy (the kernels return the arrays they take).

numba is used when it imports and :func:`contactlab.numeric.normal_kernels.backend` says
``"numba"``; the kernels compile on their first call (machine code cached on disk:
:func:`contactlab.numeric.jit.njit`).
"""
from __future__ import annotations

import threading
from collections.abc import Callable
from typing import Any

import numpy as np

from . import inside_check as _ic
from . import jit as _jit
from . import ring_kernels as _rk
from . import sorted_search as _ss

__all__ = ["pairwise_sum", "twist_step", "slip_difference", "energy_nodes", "difference_psi",
           "nonnegative_band", "BAND_NONE", "BAND_CUT", "BAND_REFERENCE", "table_scatter",
           "coefficient_pieces", "family_energy", "release_family_energy", "shrink_energy",
           "kernels",
           "INSIDE_FAIL", "INSIDE_OK", "INSIDE_OPEN", "STEP_DONE", "STEP_REFERENCE"]

#: :func:`twist_step`'s verdicts of the traction check inside the stick radius
INSIDE_FAIL, INSIDE_OK, INSIDE_OPEN = _ic.INSIDE_FAIL, _ic.INSIDE_OK, _ic.INSIDE_OPEN
#: :func:`twist_step`'s status: the step taken, or left to the numpy route (a nan among its inputs)
STEP_DONE, STEP_REFERENCE = 0, 1
#: :func:`nonnegative_band`'s status: ``Ψ >= 0`` (nothing removed), a band removed, or left to the
#: numpy route (a value not finite)
BAND_NONE, BAND_CUT, BAND_REFERENCE = 0, 1, 2

_EPS = float(np.finfo(float).eps)
_state: dict = {"kernels": None}
_lock = threading.Lock()

# the ring kernels the passes call (rebound to their compiled builds with the passes)
_psi_pass = _rk.psi_pass
_ends_pass = _rk.ends_pass
_piece_ends = _rk.piece_ends
_lines = _rk.lines
_psi_at = _rk.psi_at
# the sorted searches and the traction check inside the stick radius (rebound likewise)
_left = _ss.left
_right = _ss.right
_inside = _ic.inside
_inside_memo = _ic.inside_memo


def _block(a: np.ndarray, i0: int, n: int) -> float:
    """numpy's sum of at most 128 elements ``a[i0:i0 + n]`` (less its identity ``0.0``)."""
    if n < 8:
        res = 0.0
        for i in range(i0, i0 + n):
            res += a[i]
        return res
    r0, r1, r2, r3 = a[i0], a[i0 + 1], a[i0 + 2], a[i0 + 3]
    r4, r5, r6, r7 = a[i0 + 4], a[i0 + 5], a[i0 + 6], a[i0 + 7]
    i = 8
    stop = n - n % 8
    while i < stop:
        j = i0 + i
        r0 += a[j]
        r1 += a[j + 1]
        r2 += a[j + 2]
        r3 += a[j + 3]
        r4 += a[j + 4]
        r5 += a[j + 5]
        r6 += a[j + 6]
        r7 += a[j + 7]
        i += 8
    res = ((r0 + r1) + (r2 + r3)) + ((r4 + r5) + (r6 + r7))
    while i < n:
        res += a[i0 + i]
        i += 1
    return res


def pairwise_sum(a: np.ndarray, i0: int, n: int) -> float:
    """numpy's sum of ``a[i0:i0 + n]`` in its order, less the identity ``0.0`` it starts from:
    blocks of at most 128 elements on eight accumulators, halves (rounded to multiples of eight)
    added pairwise; numpy's recursion as a loop over an explicit stack (a recursive kernel is
    not safely cached by numba)."""
    if n <= 128:
        return _block(a, i0, n)
    seg = np.empty((192, 3), np.int64)      # (start, length, halves added?); depth <= 64
    vals = np.empty(96)
    top, nv = 1, 0
    seg[0, 0], seg[0, 1], seg[0, 2] = i0, n, 0
    while top:
        top -= 1
        s0, m, done = seg[top, 0], seg[top, 1], seg[top, 2]
        if m <= 128:
            vals[nv] = _block(a, s0, m)
            nv += 1
        elif done:
            nv -= 1
            vals[nv - 1] = vals[nv - 1] + vals[nv]
        else:
            m2 = m // 2
            m2 -= m2 % 8
            seg[top, 2] = 1
            seg[top + 1, 0], seg[top + 1, 1], seg[top + 1, 2] = s0 + m2, m - m2, 0
            seg[top + 2, 0], seg[top + 2, 1], seg[top + 2, 2] = s0, m2, 0
            top += 3
    return vals[0]


def _unique_sorted(a: np.ndarray) -> np.ndarray:
    """``np.unique`` of ``a`` (no nan)."""
    a = np.sort(a)
    n = 0
    out = np.empty(a.size)
    for i in range(a.size):
        if i == 0 or a[i] != a[i - 1]:
            out[n] = a[i]
            n += 1
    return out[:n]


def _is_sorted(a: np.ndarray) -> bool:
    for i in range(1, a.size):
        if not a[i - 1] <= a[i]:
            return False
    return True


def _union(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """``np.unique`` of the sorted arrays ``a`` and ``b`` together (a merge: the piece ends of
    densities are sorted; no nan)."""
    out = np.empty(a.size + b.size)
    i = j = n = 0
    while i < a.size or j < b.size:
        if j >= b.size or (i < a.size and a[i] <= b[j]):
            v = a[i]
            i += 1
        else:
            v = b[j]
            j += 1
        if n == 0 or v != out[n - 1]:
            out[n] = v
            n += 1
    return out[:n]


def _nodes(lo, hi):
    """The sorted distinct piece ends of one density whose pieces are ordered
    (``lo_k <= hi_k <= lo_{k+1}``: then ``lo_0, hi_0, lo_1, ...`` ascends), or an empty array and
    False for pieces out of that order."""
    n = lo.size
    out = np.empty(2 * n)
    m = 0
    for j in range(n):
        a, b = lo[j], hi[j]
        if not (a <= b and (j + 1 == n or b <= lo[j + 1])):
            return out[:0], False
        if m == 0 or a != out[m - 1]:
            out[m] = a
            m += 1
        if b != out[m - 1]:
            out[m] = b
            m += 1
    return out[:m], True


def _ends_union(alo, ahi, blo, bhi, extra):
    """``np.unique`` of the piece ends of two densities and the sorted values ``extra`` (merges
    where the pieces are ordered, else a sort)."""
    na, oka = _nodes(alo, ahi)
    nb, okb = _nodes(blo, bhi)
    if oka and okb:
        return _union(_union(na, nb), extra)
    return _unique_sorted(np.concatenate((alo, ahi, blo, bhi, extra)))


def _psi_walk(lo, hi, wl, wr, x, out):
    """``ring_kernels.psi_pass`` at ascending radii ``x``: the pieces' indices found by one walk
    instead of a binary search per radius (the same index, the same arithmetic)."""
    n = lo.size
    al, be, tail = _lines(lo, hi, wl, wr, True)
    p = 0
    for i in range(x.size):
        xi = x[i]
        while p < n and hi[p] <= xi:          # searchsorted(hi, xi, "right")
            p += 1
        k = p if p < n - 1 else n - 1
        out[i] = _psi_at(lo, hi, al, be, tail, k, xi)


def _psi(lo, hi, wl, wr, x):
    """``torsion_pieces.psi`` (zeros for no pieces; a walk where ``x`` ascends and ``hi`` is
    sorted, no nan)."""
    out = np.zeros(x.size)
    if lo.size:
        if _is_sorted(x) and _is_sorted(hi):
            _psi_walk(lo, hi, wl, wr, x, out)
        else:
            _psi_pass(lo, hi, wl, wr, x, out)
    return out


def _ends_walk(plo, phi, wl, wr, lo, hi, out_l, out_r):
    """``ring_kernels.ends_pass`` on ascending ``lo`` (``plo`` sorted): the pieces' indices by one
    walk (the same index, the same arithmetic)."""
    n = plo.size
    a = 0
    for i in range(lo.size):
        x = lo[i]
        while a < n and plo[a] <= x:          # searchsorted(plo, x, "right")
            a += 1
        out_l[i], out_r[i] = _piece_ends(plo, phi, wl, wr, a - 1, x, hi[i])


def _total(lo, hi, wl, wr) -> float:
    """``torsion_pieces._total``: ``Ψ(0)``, numpy's sum of the pieces' integrals."""
    n = lo.size
    if n == 0:
        return 0.0
    whole = np.empty(n)
    for j in range(n):
        h = hi[j] - lo[j]
        be = (wr[j] - wl[j]) / h if h > 0 else 0.0
        al = wl[j] - be * lo[j]
        whole[j] = al * (hi[j] - lo[j]) + 0.5 * be * (hi[j] * hi[j] - lo[j] * lo[j])
    return 0.0 + pairwise_sum(whole, 0, n)


def _value(lo, hi, wl, wr, x: float, side: int) -> float:
    """``torsion_pieces._value``: ``w(x⁻)`` (side −1) or ``w(x⁺)`` (side +1)."""
    if lo.size == 0:
        return 0.0
    k = _left(hi, x) if side < 0 else _right(lo, x) - 1
    if k < 0 or k >= lo.size:
        return 0.0
    l0, h0 = lo[k], hi[k]
    if not ((l0 < x <= h0) if side < 0 else (l0 <= x < h0)):
        return 0.0
    h = h0 - l0
    f = (x - l0) / h if h > 0 else 0.0
    return wl[k] + (wr[k] - wl[k]) * f


def _root_twist(d_lo, d_hi, x0, x1, f1, target, s, xtol, rtol):
    """``torsion_annulus._root`` for the twist: the same safeguarded Newton."""
    be = (d_hi - d_lo) / (x1 - x0)
    al = d_lo - be * x0
    r0 = s * (f1 + al * (x1 - x0) + 0.5 * be * (x1 * x1 - x0 * x0) - target)
    r1 = s * (f1 + al * (x1 - x1) + 0.5 * be * (x1 * x1 - x1 * x1) - target)
    if r0 < 0:
        return x0
    if r1 >= 0:
        return x1
    lo, hi = x0, x1
    x = x1 - r1 * (x1 - x0) / (r1 - r0)
    for _ in range(100):
        fx = s * (f1 + al * (x1 - x) + 0.5 * be * (x1 * x1 - x * x) - target)
        if fx == 0:
            return x
        if fx > 0:
            lo = x
        else:
            hi = x
        d = -s * (al + be * x)
        xn = x - fx / d if d != 0 else 0.5 * (lo + hi)
        if not (lo < xn < hi):
            xn = 0.5 * (lo + hi)
        if abs(xn - x) <= xtol + rtol * abs(x) or hi - lo <= xtol:
            return xn
        x = xn
    return 0.5 * (lo + hi)


def _difference(nlo, nhi, nwl, nwr, olo, ohi, owl, owr, start):
    """``torsion_pieces.difference``: ``new − old`` above ``start`` on the union of the ends."""
    xs = _ends_union(nlo, nhi, olo, ohi, np.array([start]))
    xs = xs[xs >= start]
    if xs.size < 2:
        z = np.zeros(0)
        return z, z.copy(), z.copy(), z.copy()
    lo, hi = xs[:-1].copy(), xs[1:].copy()
    m = lo.size
    nl, nr = np.zeros(m), np.zeros(m)
    ol, orr = np.zeros(m), np.zeros(m)
    # (lo ascends: the ends of each piece by a walk where its density's lo is sorted)
    if nlo.size:
        if _is_sorted(nlo):
            _ends_walk(nlo, nhi, nwl, nwr, lo, hi, nl, nr)
        else:
            _ends_pass(nlo, nhi, nwl, nwr, lo, hi, nl, nr)
    if olo.size:
        if _is_sorted(olo):
            _ends_walk(olo, ohi, owl, owr, lo, hi, ol, orr)
        else:
            _ends_pass(olo, ohi, owl, owr, lo, hi, ol, orr)
    return lo, hi, nl - ol, nr - orr


def twist_step(olo, ohi, owl, owr, slo, shi, swl, swr, radius, target, xtol, rtol,
               r, bound, G_t, check_rtol, F0, F1, t_r, t_nodes, memo_w, memo_x):
    """The twist step of ``torsion_annulus.step`` (the old density ``o``, the full-sliding one
    ``s``, the contact radius, the twist increment ``target``; the root's ``xtol``, ``rtol``), its
    checks' parts at the points ``r`` with ``μ p`` = ``bound`` when ``r`` is not empty (``F0``,
    ``F1``, ``t_r``, ``t_nodes``: a :class:`NodeTable`'s traction antiderivatives, radii and nodes,
    or empty).

    ``memo_w``, ``memo_x``: the density the traction check last checked and its memo
    (:func:`contactlab.numeric.inside_check.inside_memo`; empty for none).

    Returns ``(status, w, c, s, gross, dpsi, inside, memo)``: ``w`` the new pieces (as the rows
    of one ``4 × n`` array), ``inside`` the traction check's verdict, ``memo`` the check's memo
    of ``w``; the slip check's part is :func:`slip_difference`."""
    empty = np.zeros((4, 0))
    none = np.zeros((3, 0))
    if target != target or radius != radius:
        return STEP_REFERENCE, empty, 0.0, 0.0, 0.0, 0.0, INSIDE_OPEN, none
    for a in (olo, ohi, slo, shi):
        for i in range(a.size):
            if a[i] != a[i]:
                return STEP_REFERENCE, empty, 0.0, 0.0, 0.0, 0.0, INSIDE_OPEN, none
    xs = _ends_union(olo, ohi, slo, shi, np.array([0.0, radius]) if radius >= 0.0
                     else np.array([radius, 0.0]))
    xs = xs[xs <= radius]
    # Ψ of both at the ascending ends, then from the edge inwards
    f_sl = _psi(slo, shi, swl, swr, xs)[::-1].copy()
    f_old = _psi(olo, ohi, owl, owr, xs)[::-1].copy()
    xs = xs[::-1].copy()
    base = f_sl[0] - f_old[0]
    gross = 0.0
    s = 1.0 if target >= base else -1.0
    if target == base:
        c = radius
    else:
        k = -1
        for i in range(xs.size):
            if s * ((s * f_sl[i] - f_old[i]) - target) >= 0:
                k = i
                break
        if k < 0:
            c = 0.0
            gross = target - (s * f_sl[xs.size - 1] - f_old[xs.size - 1])
        else:
            vk = s * ((s * f_sl[k] - f_old[k]) - target)
            if vk == 0 or k == 0:
                c = xs[k]
            else:
                x0, x1 = xs[k], xs[k - 1]
                d_lo = (s * _value(slo, shi, swl, swr, x0, 1)
                        - _value(olo, ohi, owl, owr, x0, 1))
                d_hi = (s * _value(slo, shi, swl, swr, x1, -1)
                        - _value(olo, ohi, owl, owr, x1, -1))
                c = _root_twist(d_lo, d_hi, x0, x1, s * f_sl[k - 1] - f_old[k - 1], target, s,
                                xtol, rtol)
    # splice(old, s W, c): old below c, s W above it, zero-width pieces dropped
    na = _left(olo, c)
    nb = _right(shi, c)
    m = na + shi.size - nb
    lo, hi, wl, wr = np.empty(m), np.empty(m), np.empty(m), np.empty(m)
    for j in range(na):
        lo[j], hi[j], wl[j], wr[j] = olo[j], ohi[j], owl[j], owr[j]
    if na and ohi[na - 1] > c:
        j = na - 1
        wr[j] = owl[j] + (owr[j] - owl[j]) * (c - olo[j]) / (ohi[j] - olo[j])
        hi[j] = c
    for j in range(nb, shi.size):
        q = na + j - nb
        lo[q], hi[q], wl[q], wr[q] = slo[j], shi[j], s * swl[j], s * swr[j]
    if shi.size - nb and slo[nb] < c:
        q = na
        wl[q] = s * swl[nb] + (s * swr[nb] - s * swl[nb]) * (c - slo[nb]) / (shi[nb] - slo[nb])
        lo[q] = c
    keep = 0
    for j in range(m):
        if hi[j] > lo[j]:
            keep += 1
    if keep < m:
        sel = hi > lo
        lo, hi, wl, wr = lo[sel], hi[sel], wl[sel], wr[sel]
    dpsi = _total(lo, hi, wl, wr) - _total(olo, ohi, owl, owr)
    w = _stack(lo, hi, wl, wr)
    if r.size == 0:
        return STEP_DONE, w, c, s, gross, dpsi, INSIDE_OK, none
    inside, memo = _inside_memo(lo, hi, wl, wr, olo, ohi, owl, owr, r, bound, c, G_t,
                                check_rtol, F0, F1, t_r, t_nodes, memo_w, memo_x)
    return STEP_DONE, w, c, s, gross, dpsi, inside, memo


def slip_difference(wlo, whi, wwl, wwr, olo, ohi, owl, owr, swl, swr, c, s, gross, check_rtol):
    """The slip check's part of :func:`twist_step`, a pass of its own (inside the step's pass the
    same code ran ~3x slower, measured: the step's one large function optimises worse): the
    difference ``w − old`` above ``c`` (the numpy step's slice of ``w − old`` from 0 at ``c``: the
    same intervals and values, ``c`` being a piece end of ``w``, or its difference from ``c``
    where ``c`` is no such end), as the rows of one ``4 × n`` array, and whether its sign alone
    shows the slip pointing the way of ``s`` (the step's ``sufficient``; ``swl``, ``swr``: the
    full-sliding density's end values, its scale)."""
    d = _difference(wlo, whi, wwl, wwr, olo, ohi, owl, owr, c)
    dw = _stack(d[0], d[1], d[2], d[3])
    sc = 0.0
    if swl.size:
        sc = np.max(np.abs(swl)) + np.max(np.abs(swr))
    if sc == 0.0:
        sc = 1.0
    slack = -check_rtol * sc
    sufficient = s * gross >= 0
    if sufficient:
        dl, dr = d[2], d[3]
        for j in range(dl.size):
            if not (s * dl[j] >= slack and s * dr[j] >= slack):
                sufficient = False
                break
    return dw, sufficient


def _stack(lo, hi, wl, wr):
    """The pieces as the rows of one ``4 × n`` array (one array to return)."""
    out = np.empty((4, lo.size))
    for j in range(lo.size):
        out[0, j], out[1, j], out[2, j], out[3, j] = lo[j], hi[j], wl[j], wr[j]
    return out


def nonnegative(lo, hi, wl, wr) -> bool:
    """Whether ``Ψ >= 0`` at every piece's ends and at its interior zero of ``w`` (the smallest
    ``Ψ`` on the piece): ``torsion_annulus.nonnegative_psi``'s test with its arithmetic (False
    also for a nan, where that function goes on to its cuts)."""
    n = lo.size
    if n == 0:
        return True
    xs = np.empty(n)
    for j in range(n):
        h = hi[j] - lo[j]
        be = (wr[j] - wl[j]) / h if h > 0 else 0.0
        al = wl[j] - be * lo[j]
        x = -al / be if be != 0 else lo[j]
        if x == x:                       # np.maximum / np.minimum: a nan stays nan
            x = x if x >= lo[j] else lo[j]
            x = x if x <= hi[j] else hi[j]
        xs[j] = x
    for x in (hi, lo, xs):
        P = _psi(lo, hi, wl, wr, x)
        for j in range(n):
            if not P[j] >= 0.0:
                return False
    return True


def _sort4(v):
    """``np.sort`` of four values in place (ascending, a nan last)."""
    for i in range(1, 4):
        x = v[i]
        j = i - 1
        while j >= 0 and (v[j] > x or (v[j] != v[j] and x == x)):
            v[j + 1] = v[j]
            j -= 1
        v[j + 1] = x


def nonnegative_band(lo, hi, wl, wr):
    """``torsion_annulus.nonnegative_psi`` (its test, roots, cuts and arithmetic):
    ``(status, pieces)``, :data:`BAND_NONE` where ``Ψ >= 0`` (the density itself), :data:`BAND_CUT`
    with the pieces as the rows of one ``4 × n`` array, :data:`BAND_REFERENCE` (nothing computed)
    for a value not finite (left to the numpy route)."""
    n = lo.size
    for j in range(n):
        if not lo[j] - lo[j] == hi[j] - hi[j] == wl[j] - wl[j] == wr[j] - wr[j] == 0:
            return BAND_REFERENCE, np.zeros((4, 0))
    if nonnegative(lo, hi, wl, wr):
        return BAND_NONE, np.zeros((4, 0))
    psi_hi, nan, v = _psi(lo, hi, wl, wr, hi), np.nan, np.empty(4)
    out = np.empty((4, 3 * n))
    m = 0
    for j in range(n):
        # the roots of Ψ strictly inside the piece (``_psi_roots``)
        h = hi[j] - lo[j]
        a = -0.5 * ((wr[j] - wl[j]) / h if h > 0 else 0.0)
        b, c = wr[j], psi_hi[j]
        disc = b * b - 4.0 * a * c
        sq = np.sqrt(disc if disc >= 0.0 or disc != disc else 0.0)     # np.maximum: nan stays
        q = -0.5 * (b + (sq if b >= 0 else -sq))
        u1 = q / a if a != 0 else nan
        u2 = c / q if q != 0 else nan
        if not disc >= 0:
            u1 = u2 = nan
        r1, r2 = hi[j] - u1, hi[j] - u2
        v[0], v[1], v[2], v[3] = lo[j], r1 if lo[j] < r1 < hi[j] else nan, \
            r2 if lo[j] < r2 < hi[j] else nan, hi[j]
        _sort4(v)
        hp = h if h > 0 else 1.0
        for k in range(3):
            x0 = v[k] if v[k] == v[k] else hi[j]
            x1 = v[k + 1] if v[k + 1] == v[k + 1] else hi[j]
            if x1 > x0:
                out[0, m], out[1, m] = x0, x1
                out[2, m] = wl[j] + (wr[j] - wl[j]) * (x0 - lo[j]) / hp
                out[3, m] = wl[j] + (wr[j] - wl[j]) * (x1 - lo[j]) / hp
                m += 1
    out = out[:, :m].copy()
    # the sub-pieces where Ψ < 0 (its sign at the midpoint: no root inside) set to zero
    P = _psi(lo, hi, wl, wr, 0.5 * (out[0] + out[1]))
    for k in range(m):
        if P[k] < 0.0:
            out[2, k] = 0.0
            out[3, k] = 0.0
    return BAND_CUT, out


def table_scatter(lo, hi, wl, wr, r, t_r, t_nodes):
    """The arguments of ``NodeTable.sums`` for the abutting pieces ``(lo, hi, wl, wr)`` at the
    radii ``r`` (``torsion_annulus.slip_kernel_integral``'s, the same values): ``(ok, rows, i0,
    i1, v0, v1, missed, c0m, c1m)``, the table rows of ``r`` and their band ``[i0, i1)``, the
    jumps of offset and slope scattered onto the table's nodes, and the nodes not in the table
    with their jumps; ``ok`` False where a radius is not a row of the table (or none given)."""
    z = np.zeros(0)
    zi = np.zeros(0, np.int64)
    n, m, nt = lo.size, r.size, t_nodes.size
    if m == 0 or n == 0 or t_r.size == 0 or nt == 0:
        return False, zi, 0, 0, z, z, z, z, z
    rows = np.empty(m, np.int64)
    i0, i1 = t_r.size, 0
    for i in range(m):
        k = _left(t_r, r[i])
        k = k if k < t_r.size - 1 else t_r.size - 1
        if t_r[k] != r[i]:
            return False, zi, 0, 0, z, z, z, z, z
        rows[i] = k
        i0 = k if k < i0 else i0
        i1 = k + 1 if k + 1 > i1 else i1
    al, be, _ = _lines(lo, hi, wl, wr, False)
    v0 = np.zeros(nt)
    v1 = np.zeros(nt)
    missed = np.empty(n + 1)
    c0m = np.empty(n + 1)
    c1m = np.empty(n + 1)
    q = 0
    for j in range(n + 1):
        c0 = (al[j - 1] if j > 0 else 0.0) - (al[j] if j < n else 0.0)
        c1 = (be[j - 1] if j > 0 else 0.0) - (be[j] if j < n else 0.0)
        t = lo[j] if j < n else hi[n - 1]
        k = _left(t_nodes, t)
        k = k if k < nt - 1 else nt - 1
        if t_nodes[k] == t:
            v0[k] = c0
            v1[k] = c1
        else:
            missed[q], c0m[q], c1m[q] = t, c0, c1
            q += 1
    return True, rows, i0, i1, v0, v1, missed[:q], c0m[:q], c1m[:q]


def coefficient_pieces(b, coef, jumps, radius, cut):
    """``torsion_pieces.from_coefficients`` (its arithmetic; ``cut``: at ``radius``) as the rows of
    one ``4 × n`` array; ``(ok, pieces)``, ``ok`` False (nothing computed) for too few
    coefficients, a jump index outside the rings or a nan radius."""
    n = b.size - 1
    if n < 1 or coef.size < n + jumps.size or radius != radius:
        return False, np.zeros((4, 0))
    for j in range(jumps.size):
        if jumps[j] < 0 or jumps[j] >= n:
            return False, np.zeros((4, 0))
    left = np.empty(n)
    left[0] = 0.0
    for j in range(1, n):
        left[j] = coef[j - 1]
    # numpy's ``left[jumps] += v``: every sum from the values before, then written in order
    add = np.empty(jumps.size)
    for j in range(jumps.size):
        add[j] = left[jumps[j]] + coef[n + j]
    for j in range(jumps.size):
        left[jumps[j]] = add[j]
    m = n
    if cut:
        m = _left(b[:n], radius)          # the pieces with lo < radius
    out = np.empty((4, m))
    for j in range(m):
        out[0, j], out[1, j], out[2, j], out[3, j] = b[j], b[j + 1], left[j], coef[j]
    if cut and m and out[1, m - 1] > radius:
        k = m - 1
        h = out[1, k] - out[0, k]
        out[3, k] = out[2, k] + (out[3, k] - out[2, k]) * (radius - out[0, k]) / h
        out[1, k] = radius
    return True, out


def energy_nodes(alo, ahi, awl, awr, blo, bhi, bwl, bwr, clo, chi, xg, wg):
    """``torsion_energy._nodes`` of the piece ends of up to three densities ``a``, ``b``, ``c``
    (``c``'s ends only, empty for two) and 0, with the Gauss rule ``xg``, ``wg``; ``Ψ`` of ``a``
    there and ``Ψ`` of the difference ``b − a`` there and at 0: ``(X0, W, P, dP)``, ``X0`` the
    points with a 0 appended."""
    u = _ends_union(alo, ahi, blo, bhi, np.zeros(1))
    if _is_sorted(clo) and _is_sorted(chi):
        u = _union(_union(u, clo), chi)
    else:
        u = _unique_sorted(np.concatenate((u, clo, chi)))
    n = u.size - 1
    g = xg.size
    X0 = np.empty(n * g + 1)
    W = np.empty(n * g)
    for i in range(n):
        h = u[i + 1] - u[i]
        for j in range(g):
            x = u[i] + 0.5 * (xg[j] + 1.0) * h
            X0[i * g + j] = x
            W[i * g + j] = 0.5 * wg[j] * h * x * x
    X0[n * g] = 0.0
    P = _psi(alo, ahi, awl, awr, X0[:n * g])
    return X0, W, P, difference_psi(blo, bhi, bwl, bwr, alo, ahi, awl, awr, X0)


def family_energy(alo, ahi, awl, awr, blo, bhi, bwl, bwr, xg, wg, gross):
    """The arrays of ``torsion_energy._stages`` for the family stage ``a → b`` with the gross turn
    ``gross`` (its elementwise products, in its order; the dot products with the weights are left
    to numpy): ``(W, P_a², ΔΨ², Ψ_b, Ψ_b², Ψ_b (Δφ − ΔΨ), Δφ)``, ``Δφ = ΔΨ(0) + gross``."""
    _, W, P, dP = energy_nodes(alo, ahi, awl, awr, blo, bhi, bwl, bwr, np.zeros(0),
                               np.zeros(0), xg, wg)
    m = W.size
    dphi = dP[m] + gross
    q0, qd, Pb, qbb, qdiss = (np.empty(m), np.empty(m), np.empty(m), np.empty(m), np.empty(m))
    for i in range(m):
        d = dP[i]
        b = P[i] + d
        q0[i] = P[i] * P[i]
        qd[i] = d * d
        Pb[i] = b
        qbb[i] = b * b
        qdiss[i] = b * (dphi - d)
    return W, q0, qd, Pb, qbb, qdiss, dphi


def release_family_energy(alo, ahi, awl, awr, blo, bhi, bwl, bwr, clo, chi, cwl, cwr, xg, wg,
                          gross):
    """The arrays of ``torsion_energy._stages`` for a shrinking contact's chain ``a → b → c``: a
    release ``a → b`` at the held twist, then the family stage ``b → c`` with the gross turn
    ``gross`` (its elementwise products, in its order; the dot products are left to numpy):
    ``(W, ΔΨ₁², Ψ_b, Ψ_b (ΔΨ₁(0) − ΔΨ₁), ΔΨ₁(0), ΔΨ₂², Ψ_c, Ψ_c (Δφ − ΔΨ₂), Ψ_c², Ψ_a², Δφ)``,
    ``Δφ = ΔΨ₂(0) + gross``."""
    X0, W, P, dP1 = energy_nodes(alo, ahi, awl, awr, blo, bhi, bwl, bwr, clo, chi, xg, wg)
    dP2 = difference_psi(clo, chi, cwl, cwr, blo, bhi, bwl, bwr, X0)
    m = W.size
    d01 = dP1[m]
    dphi = dP2[m] + gross
    qd1, Pb, qdiss1, qd2, Pc, qdiss2, qcc, q0 = (np.empty(m), np.empty(m), np.empty(m),
                                                 np.empty(m), np.empty(m), np.empty(m),
                                                 np.empty(m), np.empty(m))
    for i in range(m):
        d = dP1[i]
        b = P[i] + d
        e = dP2[i]
        c = b + e
        qd1[i] = d * d
        Pb[i] = b
        qdiss1[i] = b * (d01 - d)
        qd2[i] = e * e
        Pc[i] = c
        qdiss2[i] = c * (dphi - e)
        qcc[i] = c * c
        q0[i] = P[i] * P[i]
    return W, qd1, Pb, qdiss1, d01, qd2, Pc, qdiss2, qcc, q0, dphi


def shrink_energy(olo, ohi, owl, owr, slo, shi, swl, swr, radius, xtol, rtol, G_t, check_rtol,
                  r, bound, F0, F1, t_r, t_nodes, memo_w, memo_x, nlo, nhi, nwl, nwr, xg, wg,
                  gross):
    """A shrinking contact's step energy whose twist goes on (``torsion_energy.annulus_energy``)
    in one pass: the release density (:func:`twist_step` of the old density ``o`` onto the
    full-sliding one ``s`` at twist increment 0, without checks: ``r``, ``bound`` empty, the
    table and memo arguments those of such a call), then :func:`release_family_energy` of
    ``o`` → it → the new density ``n``. Returns ``(status, *arrays)``: :func:`twist_step`'s
    status and :func:`release_family_energy`'s arrays (empty where the status leaves the step
    to the numpy route)."""
    step = twist_step(olo, ohi, owl, owr, slo, shi, swl, swr, radius, 0.0, xtol, rtol, r, bound,
                      G_t, check_rtol, F0, F1, t_r, t_nodes, memo_w, memo_x)
    st, ws = step[0], step[1]
    if st != STEP_DONE:
        e = np.zeros(0)
        return st, e, e, e, e, 0.0, e, e, e, e, e, 0.0
    W, qd1, Pb, qdiss1, d01, qd2, Pc, qdiss2, qcc, q0, dphi = release_family_energy(
        olo, ohi, owl, owr, ws[0], ws[1], ws[2], ws[3], nlo, nhi, nwl, nwr, xg, wg, gross)
    return st, W, qd1, Pb, qdiss1, d01, qd2, Pc, qdiss2, qcc, q0, dphi


def difference_psi(blo, bhi, bwl, bwr, alo, ahi, awl, awr, X0):
    """``Ψ`` of ``torsion_pieces.difference(b, a, 0)`` at the points ``X0``."""
    d = _difference(blo, bhi, bwl, bwr, alo, ahi, awl, awr, 0.0)
    m = X0.size - 1
    out = np.empty(X0.size)
    out[:m] = _psi(d[0], d[1], d[2], d[3], X0[:m])      # ascending points, then the 0
    out[m:] = _psi(d[0], d[1], d[2], d[3], X0[m:])
    return out


#: helpers (compiled before the passes that call them)
_HELPERS: tuple = ("_stack", "_block", "pairwise_sum", "_left", "_right", "_unique_sorted",
                   "_is_sorted", "_union", "_nodes", "_ends_union", "_psi_walk", "_psi", "_ends_walk",
                   "_total", "_value", "_root_twist", "_difference",
                   "difference_psi", "energy_nodes", "_sort4", "nonnegative", "twist_step",
                   "release_family_energy")
#: helpers small enough to inline
_INLINE = frozenset({"_stack", "_block", "_left", "_right", "_is_sorted", "_value", "_total",
                     "_root_twist", "_nodes", "_ends_union", "_union", "_unique_sorted", "_psi",
                     "_sort4", "nonnegative"})
#: the passes by name (plain Python functions)
_PLAIN: dict[str, Callable[..., Any]] = {"twist_step": twist_step, "energy_nodes": energy_nodes,
                                         "difference_psi": difference_psi,
                                         "nonnegative_band": nonnegative_band,
                                         "table_scatter": table_scatter,
                                         "coefficient_pieces": coefficient_pieces,
                                         "family_energy": family_energy,
                                         "release_family_energy": release_family_energy,
                                         "shrink_energy": shrink_energy,
                                         "slip_difference": slip_difference}


def kernels(compiled: bool = True) -> dict:
    """The passes by name (the keys of ``_PLAIN``: ``"twist_step"``, ``"nonnegative_band"``, ...)
    compiled by numba (built once per process), or the plain Python functions (``compiled=False``:
    their logic without numba, for tests)."""
    if not compiled:
        return dict(_PLAIN)
    built = _state["kernels"]
    if built is not None:
        return built
    with _lock:
        if _state["kernels"] is None:
            g = globals()
            rk = _rk.kernels(True)
            g["_psi_pass"], g["_ends_pass"] = rk["psi"], rk["ends"]
            # (compiled by the ring kernels' build)
            g["_piece_ends"], g["_lines"], g["_psi_at"] = _rk.piece_ends, _rk.lines, _rk.psi_at
            for name in _HELPERS:
                # the small helpers inlined into their callers at numba's IR level (no compile
                # and cache entry of their own)
                extra = {"inline": "always"} if name in _INLINE else {}
                g[name] = _jit.njit(g[name], nogil=True, error_model="numpy", **extra)
            _ic.build(g["_left"])
            g["_inside"], g["_inside_memo"] = _ic.inside, _ic.inside_memo
            # (a pass that is also a helper of another pass: its helper build, one compile)
            _state["kernels"] = {name: g[name] if name in _HELPERS else
                                 _jit.njit(f, nogil=True, error_model="numpy")
                                 for name, f in _PLAIN.items()}
    return _state["kernels"]
