"""Punch-density steps of the exact torsion solver with the stick radius inside its ring.

The ring solver (:mod:`contactlab.physics.torsion_rings`) keeps the traction at collocation
points; its stick–slip boundary can only switch a whole ring at a time, which limits it to
``O(h²)`` with a large constant. This module carries the state as the punch density itself,
``w(t)`` piecewise linear on *pieces* ``[lo_k, hi_k]`` (values ``wl_k``, ``wr_k`` at their ends,
jumps allowed between pieces), and takes a step in Jäger's form whenever the slip zone of the
step is one annulus ``c < r < a`` reaching the contact edge:

* on the slip annulus the traction is ``s μ p`` (``s = ±1``), and since the traction at ``r``
  depends on the density at ``t ≥ r`` only (``τ(r) = (4G_t/π) r ∫_r w(t)/sqrt(t² − r²) dt``),
  the new density there is ``s W(t)``, the density of the full-sliding traction ``μ p`` of the
  step, whatever ``c`` is;
* inside ``c`` the density is unchanged: every punch of radius ``t > r`` turns the point ``r``
  rigidly, so the stick zone turns by ``Ψ(0) = ∫ w dt`` and does not slip;
* ``c`` solves one scalar equation, the twist ``Ψ_new(0) − Ψ_old(0) = Δφ`` (or the torque
  ``(16/3) G_t ∫ t³ w dt`` = target), and is found inside its piece by a root solve.

The step is the exact solution of the incremental problem when the traction stays within
``μ p`` inside ``c`` and the slip on the annulus points the way of ``s`` (checked: :func:`step`
returns ``ok=False`` otherwise, and the caller takes the step with the ring solver). The slip
increment at ``r`` is ``Δs(r) = ∫_0^r Δw(t) K(r, t) dt`` with
``K = (2/π)[r arccos(t/r) + t sqrt(1 − t²/r²)] ≥ 0`` (the rigid turn minus the Reissner–Sagoci
displacement outside a punch), closed form on each piece.

A contact without a friction limit never slips: its density is a sum of rigid punches at the
contact radii of its steps (:func:`punch_step`, exact; from
:mod:`contactlab.physics.torsion_punches`).

All functions are pure: arrays in, arrays out.
"""
from __future__ import annotations

import threading
from typing import cast

import numpy as np
import scipy.linalg as _la

from ..numeric import annulus_kernel as _annulus_kernel
from ..numeric import inside_check as _inside_check
from ..numeric import ring_kernels as _ring_kernels
from ..numeric import slip_check as _slip_check
# the piece algebra (re-exported: the module's names, its compiled-route switch ``_COMPILED`` and
# its helpers, as before the split)
from .torsion_pieces import (_COMPILED, _LAST_DIFF, _LAST_TOTAL, Pieces, _cut,  # noqa: F401
                             _ends, _kernels, _lin, _scale, _total, _unique, _value, _values,
                             add, difference, empty, from_coefficients, from_nodes, psi, splice,
                             stored_energy, torque, torque_below)
from . import torsion_slip_sign as _slip_sign
from .torsion_punches import punch_energy, punch_step, punch_torque, punch_traction

__all__ = ["Pieces", "NodeTable", "empty", "from_nodes", "from_coefficients", "coefficients", "density",
           "psi", "torque",
           "torque_below", "traction", "slip_kernel_integral", "stored_energy", "splice",
           "difference", "add", "nonnegative_psi", "step", "punch_step", "punch_torque", "punch_energy",
           "punch_traction", "ROOT_XTOL", "CHECK_RTOL"]

#: relative tolerance (of the contact radius) of the stick radius's root solve
ROOT_XTOL = 1e-15
#: relative slack of the checks of a step (traction within μp inside ``c``; slip direction)
CHECK_RTOL = 1e-9
_WHY_INSIDE = "traction beyond the friction limit inside the stick radius"


def _antiderivatives(r: np.ndarray, nodes: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``arccosh(t/r)`` and ``sqrt(t² − r²)`` at the nodes ``t`` (columns) for the radii ``r``
    (rows), ``t`` clipped to ``r`` (both vanish for nodes below ``r``): elementwise, so a column
    taken from a :class:`NodeTable` is the same to the last bit as one computed here."""
    kern = _kernels()
    if kern is not None:
        return _ring_kernels.traction_antiderivatives(kern, r, nodes)
    rr = r[:, None]
    with np.errstate(divide="ignore", invalid="ignore"):
        u = np.where(rr > 0, np.maximum(nodes[None, :] / np.where(rr > 0, rr, 1.0), 1.0), 1.0)
    # the antiderivatives vanish at u = 1 (nodes below r): evaluated above r only
    m = u > 1.0
    A, S = np.zeros(u.shape), np.zeros(u.shape)
    um = u[m]
    A[m] = np.arccosh(um)
    S[m] = np.sqrt((um - 1.0) * (um + 1.0))
    S *= rr
    return A, S


class NodeTable:
    """The antiderivatives of :func:`traction` and :func:`slip_kernel_integral` at fixed radii
    ``r`` (sorted) and fixed nodes (sorted), computed once: a ring set's collocation points and
    ring ends, which most piece ends of the solver's densities are (four ``r.size ×
    nodes.size`` arrays, read-only).

    With a table, those functions sum each antiderivative times the density's jump of offset
    and slope at each node (one matrix-vector product; columns computed only for nodes not in
    the table) instead of differencing the antiderivatives piece by piece: the same terms added
    in another order, equal to rounding, not to the last bit (the slip kernel's antiderivatives
    are kept relative to their value at ``t = r``, so that nodes beyond ``r`` add exact zeros)."""

    def __init__(self, r: np.ndarray, nodes: np.ndarray) -> None:
        self.r = np.array(r, float)
        self.nodes = np.array(nodes, float)
        self.arrays = {"traction": _antiderivatives(self.r, self.nodes),
                       "slip": _slip_antiderivatives(self.r, self.nodes)}
        # the rows of the table's own radii: where equal radii repeat, the first of them, as
        # a search of the radii finds it (their rows hold the same values)
        self._all_rows = np.searchsorted(self.r, self.r)
        for a in (self.r, self.nodes, self._all_rows, *self.arrays["traction"],
                  *self.arrays["slip"]):
            a.flags.writeable = False

    @property
    def nbytes(self) -> int:
        return int(sum(a.nbytes for pair in self.arrays.values() for a in pair))

    def same_radii(self, r: np.ndarray) -> bool:
        """Whether ``r`` are the table's radii, all its rows in its order (one comparison)."""
        return r is self.r or (r.shape == self.r.shape and bool((r == self.r).all()))

    def rows(self, r: np.ndarray) -> np.ndarray | None:
        """Row indices of the radii ``r`` (``None`` unless every one is a row of the table)."""
        if r.size == 0:
            return None
        if self.same_radii(r):      # (the usual case: the table's own collocation points)
            return self._all_rows
        k = np.minimum(np.searchsorted(self.r, r), self.r.size - 1)
        return k if bool((self.r[k] == r).all()) else None      # (shapes equal)

    def columns(self, r: np.ndarray, nodes: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """:func:`_antiderivatives` at the radii ``r`` and ``nodes``, the same bits: the columns
        of nodes in the table taken from it (elementwise values, so equal to the last bit),
        the others computed; all computed unless every radius is a row of the table."""
        rows = self.rows(r)
        if rows is None or nodes.size == 0:
            return _antiderivatives(r, nodes)
        F0, F1 = self.arrays["traction"]
        k = np.minimum(np.searchsorted(self.nodes, nodes), self.nodes.size - 1)
        hit = self.nodes[k] == nodes
        # C order, as computed (the products below sum in the layout's order)
        if rows.size == self.r.size:                       # rows sorted and distinct: all rows
            A, S = np.take(F0, k, axis=1), np.take(F1, k, axis=1)
        else:
            A, S = F0[np.ix_(rows, k)], F1[np.ix_(rows, k)]
        if not hit.all():
            A[:, ~hit], S[:, ~hit] = _antiderivatives(r, nodes[~hit])
        return np.ascontiguousarray(A), np.ascontiguousarray(S)

    def sums(self, kind: str, rows: np.ndarray, r: np.ndarray, nodes: np.ndarray,
             c0: np.ndarray, c1: np.ndarray) -> np.ndarray:
        """``Σ_n F0(r, t_n) c0_n + F1(r, t_n) c1_n`` at the rows ``rows`` (radii ``r``) for the
        antiderivatives ``kind`` (``"traction"`` or ``"slip"``) at the nodes ``t_n``."""
        F0, F1 = self.arrays[kind]
        k = np.minimum(np.searchsorted(self.nodes, nodes), self.nodes.size - 1)
        hit = self.nodes[k] == nodes
        whole = bool(hit.all())
        v0, v1 = np.zeros(self.nodes.size), np.zeros(self.nodes.size)
        if whole:       # every node in the table (the usual case): no masks
            v0[k], v1[k] = c0, c1
        else:
            v0[k[hit]], v1[k[hit]] = c0[hit], c1[hit]
        # the rows asked for lie in one contiguous band of the table (radii sorted)
        i0, i1 = int(rows.min()), int(rows.max()) + 1
        out = (F0[i0:i1] @ v0 + F1[i0:i1] @ v1)[rows - i0]
        if not whole:
            make = _antiderivatives if kind == "traction" else _slip_antiderivatives
            A, S = make(r, nodes[~hit])
            out += A @ c0[~hit] + S @ c1[~hit]
        return out


def _jumps(al: np.ndarray, be: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Jumps of the offset and slope of abutting pieces at their nodes (zero outside)."""
    zero = np.zeros(1)
    return (np.concatenate([zero, al]) - np.concatenate([al, zero]),
            np.concatenate([zero, be]) - np.concatenate([be, zero]))


def traction(p: Pieces, r: np.ndarray, G_t: float, table: NodeTable | None = None, *,
             columns: NodeTable | None = None) -> np.ndarray:
    """Traction ``(4G_t/π) r ∫_r w(t)/sqrt(t² − r²) dt`` at ``r``, Pa (closed form per piece).

    ``table`` (optional): antiderivatives computed once for radii that include ``r`` and most of
    the density's nodes (:class:`NodeTable`; equal to rounding). ``columns`` (optional, without
    ``table``): a :class:`NodeTable` whose columns replace the antiderivatives of its nodes in
    the route without a table (:meth:`NodeTable.columns`; the same bits)."""
    lo, hi, _, _ = p
    al, be = _lin(p)
    r = np.asarray(r, float)
    rr = r[:, None]
    if lo.size and bool((lo[1:] == hi[:-1]).all()):
        # abutting pieces: the antiderivatives arccosh(t/r) and sqrt(t² − r²) once per node
        # (t clipped to r: a piece below r gives 0, the piece holding r starts there)
        nodes = np.append(lo, hi[-1])
        rows = None if table is None else table.rows(r)
        if table is not None and rows is not None:
            return 4.0 * G_t / np.pi * r * table.sums("traction", rows, r, nodes, *_jumps(al, be))
        A, S = _antiderivatives(r, nodes) if columns is None else columns.columns(r, nodes)
        return 4.0 * G_t / np.pi * r * (np.diff(A, axis=1) @ al + np.diff(S, axis=1) @ be)
    t0 = np.maximum(lo[None, :], rr)
    inside = (rr < hi[None, :]) & (rr > 0)
    s1 = np.sqrt(np.maximum(hi * hi - rr * rr, 0.0))
    s0 = np.sqrt(np.maximum(t0 * t0 - rr * rr, 0.0))
    with np.errstate(divide="ignore", invalid="ignore"):
        T1 = np.where(inside, np.log((hi + s1) / np.where(inside, t0 + s0, 1.0)), 0.0)
    Tt = np.where(inside, s1 - s0, 0.0)
    return 4.0 * G_t / np.pi * rr[:, 0] * (T1 @ al + Tt @ be)


def _G01(x):
    """The antiderivatives ``G0``, ``G1`` of the slip kernel (per unit ``r²``, ``r³``) at ``x``."""
    q = np.sqrt(np.maximum(1.0 - x * x, 0.0))
    ac = np.arccos(x)
    asn = 0.5 * np.pi - ac
    g0 = x * ac - q - q ** 3 / 3.0
    g1 = (0.5 * x * x * ac - 0.25 * x * q + 0.25 * asn + (x * (2.0 * x * x - 1.0) * q + asn) / 8.0)
    return g0, g1


def _slip_antiderivatives(r: np.ndarray, nodes: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``r² (G0(t/r) − G0(1))`` and ``r³ (G1(t/r) − G1(1))`` at the nodes ``t`` (columns) for the
    radii ``r`` (rows), ``t/r`` clipped to ``[0, 1]``: exact zeros for nodes beyond ``r``."""
    rr = r[:, None]
    kern = _kernels()
    if kern is not None:
        return _ring_kernels.slip_antiderivatives(kern, rr, nodes, *_G01_ONE)
    with np.errstate(divide="ignore", invalid="ignore"):
        x = np.where(rr > 0, np.minimum(np.maximum(nodes[None, :] / rr, 0.0), 1.0), 1.0)
    m = x < 1.0
    one0, one1 = _G01(np.ones(1))
    g0, g1 = np.zeros(x.shape), np.zeros(x.shape)
    x0, x1 = _G01(x[m])
    g0[m], g1[m] = x0 - one0, x1 - one1
    return g0 * (rr * rr), g1 * rr ** 3


#: ``G0(1)``, ``G1(1)`` (:func:`_G01` at 1, numpy's values)
_G01_ONE = tuple(float(v[0]) for v in _G01(np.ones(1)))


def slip_kernel_integral(p: Pieces, r: np.ndarray, table: NodeTable | None = None
                         ) -> np.ndarray:
    """``v(r) = ∫_0^r w(t) K(r, t) dt`` (m): the lag of the surface at ``r`` behind the rigid turn
    ``Ψ(0) r``; a step's slip increment is ``Δv`` (plus ``r`` times any gross-sliding turn).

    ``table`` (optional): :class:`NodeTable` for radii that include ``r`` (equal to rounding)."""
    lo, hi, _, _ = p
    rr = np.asarray(r, float)[:, None]
    # abutting pieces share their ends: the antiderivatives once per node
    shared = bool(lo.size) and bool((lo[1:] == hi[:-1]).all())
    ak = None if table is None or not shared else _annulus_kernels()
    if ak is not None:
        assert table is not None
        # the look-ups and the scatter of the jumps in one pass (the same arguments as below)
        r1 = np.ascontiguousarray(rr[:, 0])
        ok, rows, i0, i1, v0, v1, missed, c0m, c1m = ak["table_scatter"](
            *_arrays(p), r1, table.r, table.nodes)
        if ok:
            F0, F1 = table.arrays["slip"]
            out = (F0[i0:i1] @ v0 + F1[i0:i1] @ v1)[rows - i0]
            if missed.size:
                A, S = _slip_antiderivatives(r1, missed)
                out += A @ c0m + S @ c1m
            return 2.0 / np.pi * out
    al, be = _lin(p)        # (after the compiled pass, which does not need them)
    rows = None if table is None or not shared else table.rows(rr[:, 0])
    if table is not None and rows is not None:
        return 2.0 / np.pi * table.sums("slip", rows, rr[:, 0], np.append(lo, hi[-1]),
                                        *_jumps(al, be))
    ends = np.append(lo, hi[-1]) if shared else np.concatenate([lo, hi])
    with np.errstate(divide="ignore", invalid="ignore"):
        x = np.where(rr > 0, np.minimum(np.maximum(ends / rr, 0.0), 1.0), 1.0)
    # nodes beyond r (x = 1) give the constants G0(1), G1(1): evaluated below r only
    m = x < 1.0
    g0, g1 = (np.full(x.shape, v) for v in _G01(np.ones(1)))
    g0[m], g1[m] = _G01(x[m])
    if shared:
        d0, d1 = np.diff(g0, axis=1), np.diff(g1, axis=1)
    else:
        n = lo.size
        d0, d1 = g0[:, n:] - g0[:, :n], g1[:, n:] - g1[:, :n]
    r1 = rr[:, 0]
    return 2.0 / np.pi * (r1 * r1 * (d0 @ al) + r1 ** 3 * (d1 @ be))


#: the last twist step's (old, slide, radius, kernels, (piece ends, Ψ of both there))
_LAST_ENDS: list = [(None,) * 5]


_RTOL = 4 * np.finfo(float).eps


def _root(d_lo: float, d_hi: float, x0: float, x1: float, f1: float, target: float, s: float,
          kind: str, G_t: float, xtol: float) -> float:
    """The stick radius inside ``[x0, x1]``: the root of ``s (f1 + ∫_x^{x1} κ d dt − target)``
    for the linear difference ``d`` with ends ``d_lo``, ``d_hi`` (``κ = 1`` for the twist,
    ``(16/3) G_t t³`` for the torque), a polynomial in ``x`` increasing from ``x1`` inwards.

    Safeguarded Newton from the end nearer the linear interpolant's root, bisection whenever a
    Newton step leaves the bracket, to ``xtol`` (m) or to rounding; the bracket's ends are
    returned when the residual there already has the root's sign (a bracket lost to rounding,
    values ~1e-21)."""
    be = (d_hi - d_lo) / (x1 - x0)
    al = d_lo - be * x0
    if kind == "twist":
        def res(x):
            return s * (f1 + al * (x1 - x) + 0.5 * be * (x1 * x1 - x * x) - target)

        def der(x):
            return -s * (al + be * x)
    else:
        k = 16.0 / 3.0 * G_t
        x14, x15 = x1 ** 4, x1 ** 5

        def res(x):
            x2 = x * x
            return s * (f1 + k * (al * (x14 - x2 * x2) / 4.0 + be * (x15 - x2 * x2 * x) / 5.0)
                        - target)

        def der(x):
            return -s * k * x ** 3 * (al + be * x)
    r0, r1 = res(x0), res(x1)
    if r0 < 0:
        return x0
    if r1 >= 0:
        return x1
    lo, hi = x0, x1               # res(lo) >= 0 > res(hi)
    x = x1 - r1 * (x1 - x0) / (r1 - r0)
    for _ in range(100):
        fx = res(x)
        if fx == 0:
            return x
        if fx > 0:
            lo = x
        else:
            hi = x
        d = der(x)
        xn = x - fx / d if d != 0 else 0.5 * (lo + hi)
        if not (lo < xn < hi):
            xn = 0.5 * (lo + hi)
        if abs(xn - x) <= xtol + _RTOL * abs(x) or hi - lo <= xtol:
            return xn
        x = xn
    return 0.5 * (lo + hi)


def step(old: Pieces, slide: Pieces, radius: float, G_t: float, *, dphi: float | None = None,
         target_torque: float | None = None, r: np.ndarray | None = None,
         bound: np.ndarray | None = None, slip: bool = True,
         table: NodeTable | None = None, allow: tuple | None = None) -> dict:
    """One step with a single slip annulus ``c < r < radius``.

    Parameters
    ----------
    old : Pieces
        Density before the step, rad/m per m.
    slide : Pieces
        Density ``W`` of the full-sliding traction ``μ p`` of this step (zero beyond ``radius``).
    radius : float
        Contact radius of the step, m.
    G_t : float
        Torsional modulus, Pa.
    dphi, target_torque : float
        Twist increment (rad) or the torque to reach (N·m); exactly one.
    r, bound : ndarray, optional
        Check points (m) and ``μ p`` there (Pa, 0 outside the contact): the traction inside ``c``
        is checked against ``μ p``, the slip increments on the annulus against the sense.
    slip : bool
        Compute and return the slip increments at ``r`` (else zeros: the check forms them only
        where the sign of the density's increment does not decide it, and keeps them).
    table : NodeTable, optional
        Antiderivatives at the points ``r`` computed once, for the checks (:func:`traction`,
        :func:`slip_kernel_integral`; equal to rounding). The returned slip increments are
        computed without it.
    allow : (ndarray, float, float), optional
        Torque weights of the points (m³), a torque (N·m) and a distance (m): a traction beyond
        ``μ p`` inside ``c`` is accepted where every point beyond it lies within that distance
        of ``c`` and its excess, weighted, stays within that torque (``None``: none; not for a
        torque target beyond the step's sliding torque).

    Returns
    -------
    dict
        ``w`` (new pieces), ``c`` (stick radius, m), ``sense`` (``s``), ``dpsi`` (``Ψ_new(0) −
        Ψ_old(0)``, rad), ``gross`` (twist turned beyond full sliding, rad; ``nan`` when a torque
        target exceeds the sliding torque), ``slip`` (slip increments at the points ``r`` in
        contact at the start or the end of the step, m; zeros with ``slip=False``, ``None``
        without ``r``), ``ok`` (the checks held) and ``why`` (the failed check, or ``""``).
    """
    if target_torque is None and _kernels() is not None:
        # the compiled route: one pass (numeric.annulus_kernel), the same bits; None where it
        # leaves the step to the passes below
        out = _compiled_step(old, slide, radius, G_t, float(cast(float, dphi)), r, bound, slip,
                             table, allow)
        if out is not None:
            return out
    kind = "twist" if target_torque is None else "torque"
    # the piece ends of both densities below the radius, from the edge inwards (the first is
    # the radius itself): the twist (torque) of both densities there, once
    last, kern = _LAST_ENDS[0], _kernels()   # (a shrinking step's energy retakes it: kept)
    if (target_torque is None and last[0] is old and last[1] is slide and last[2] == radius
            and last[3] is kern):
        xs, f_sl, f_old = last[4]
        target = float(cast(float, dphi))
    elif target_torque is None:   # kind == "twist": the twist increment is given
        xs = np.concatenate([old[0], old[1], slide[0], slide[1], [0.0, radius]])
        xs = _unique(xs[xs <= radius])[::-1]
        f_sl, f_old = psi(slide, xs), psi(old, xs)
        _LAST_ENDS[0] = (old, slide, radius, kern, (xs, f_sl, f_old))
        target = float(cast(float, dphi))
    else:
        xs = np.concatenate([old[0], old[1], slide[0], slide[1], [0.0, radius]])
        xs = _unique(xs[xs <= radius])[::-1]
        M_sl = torque(slide, G_t)
        f_sl = M_sl - torque_below(slide, xs, G_t)
        f_old = -torque_below(old, xs, G_t)
        target = float(target_torque)
        if abs(target) > abs(M_sl):     # no allowance: an excess must not carry a torque
            allow = None                # beyond the step's sliding torque (gross sliding)
    base = float(f_sl[0] - f_old[0])
    gross = 0.0
    s = 1.0 if target >= base else -1.0
    if target == base:
        c = float(radius)
    else:
        # the first piece end where the twist (torque) reaches the target brackets the stick
        # radius, inside which both densities are linear (a polynomial root)
        fx = s * f_sl - f_old
        vals = s * (fx - target)
        hit = np.flatnonzero(vals >= 0)
        if hit.size == 0:
            c = 0.0
            gross = target - float(fx[-1]) if kind == "twist" else float("nan")
        else:
            k = int(hit[0])
            if vals[k] == 0 or k == 0:
                c = float(xs[k])
            else:
                x0, x1 = float(xs[k]), float(xs[k - 1])
                d_lo = s * _value(slide, x0, 1) - _value(old, x0, 1)
                d_hi = s * _value(slide, x1, -1) - _value(old, x1, -1)
                c = _root(d_lo, d_hi, x0, x1, float(fx[k - 1]), target, s, kind, G_t,
                          ROOT_XTOL * radius)
    signed = (slide[0], slide[1], s * slide[2], s * slide[3])
    w = splice(old, signed, c)
    t_old = _total(old)
    dpsi = _total(w) - t_old
    why, ds = "", None
    if r is not None:
        assert bound is not None   # r and bound come together (Parameters)
        # points in contact at the start or the end of the step (a point leaving the contact
        # slips while its traction is released)
        reach = max(float(radius), float(old[1][-1]) if old[1].size else 0.0)
        on = ((bound > 0) | (r < reach)) & (r > c)
        ds = np.zeros(r.size)
        # without the increments the traction check first: a step with a second slip zone
        # (the ring solver's) fails it and needs no increments (only the check named may differ)
        inside_ok = None if slip else _inside_ok(w, r, c, bound, G_t, table, allow)
        if inside_ok is False:
            return {"w": w, "c": float(c), "sense": s, "dpsi": dpsi, "gross": gross,
                    "slip": ds, "ok": False, "why": _WHY_INSIDE}
        # slip increments Δs = ∫ Δw K dt (+ r × a gross turn) on the annulus must point the way
        # of s: since K >= 0, s Δw >= 0 on the annulus (and s × the gross turn >= 0) suffices;
        # else (or when the increments are wanted) they are computed at the points
        # w − old from 0 (kept: the step's energy takes it), above c the check's (the same
        # intervals and values where c is one of its ends)
        full = difference(w, old, 0.0)
        i = int(np.searchsorted(full[0], c))
        dw = (tuple(u[i:] for u in full) if i < full[0].size and full[0][i] == c else
              difference(w, old, c))
        slack = -CHECK_RTOL * _scale(slide)
        sufficient = (s * gross >= 0 and bool(np.all(s * dw[2] >= slack))
                      and bool(np.all(s * dw[3] >= slack))) or _slip_sign.running_turn_ok(
            dw[0], dw[1], dw[2], dw[3], s, gross)
        if on.any() and not np.isnan(gross) and (slip or not sufficient):
            # (the table's sums where the increments only feed the check)
            ds_on = slip_kernel_integral(dw, r[on], None if slip else table) + gross * r[on]
            if slip:        # (else they only feed the check: not returned)
                ds[on] = ds_on
            ref = float(np.max(np.abs(ds_on))) + float(np.max(r[on])) * abs(gross)
            if not sufficient and np.any(s * ds_on < -CHECK_RTOL * ref):
                why = "slip against the traction on the annulus"
        if not why and inside_ok is None and not _inside_ok(w, r, c, bound, G_t, table, allow):
            why = _WHY_INSIDE
    return {"w": w, "c": float(c), "sense": s, "dpsi": dpsi, "gross": gross, "slip": ds,
            "ok": not why, "why": why}


#: the table arguments of the compiled step without a table (read-only, as a table's: one
#: compiled specialisation)
_NO_TABLE = (np.zeros((0, 0)), np.zeros((0, 0)), np.zeros(0), np.zeros(0))
for _a in _NO_TABLE:
    _a.flags.writeable = False


#: the traction check's memo, per thread: ``last`` = (points, table, density as a ``4 × n``
#: array, its memo) of the last compiled step with a table (numeric.inside_check.inside_memo)
_MEMO = threading.local()
#: (writable, as the memos the pass returns: one compiled specialisation; empty, never written)
_NO_MEMO = (np.zeros((4, 0)), np.zeros((3, 0)))


def _annulus_kernels() -> dict | None:
    """The compiled step and energy passes (:mod:`contactlab.numeric.annulus_kernel`), or None
    for the numpy route (the switch of :func:`psi`'s passes, ``_COMPILED``)."""
    return None if _kernels() is None else _annulus_kernel.kernels(_COMPILED["compiled"])


def _arrays(p: Pieces) -> tuple:
    c = np.ascontiguousarray
    return c(p[0], float), c(p[1], float), c(p[2], float), c(p[3], float)


def _compiled_step(old: Pieces, slide: Pieces, radius: float, G_t: float, dphi: float,
                   r: np.ndarray | None, bound: np.ndarray | None, slip: bool,
                   table: NodeTable | None, allow: tuple | None = None) -> dict | None:
    """:func:`step` with a twist increment by the compiled pass
    (:func:`contactlab.numeric.annulus_kernel.twist_step`): the density, stick radius and turn
    in one pass, the same bits; the checks' verdicts are the numpy route's (the traction check
    from the pass where its margin exceeds the rounding of its sums and no allowance is to be
    weighed, else from :func:`_inside_ok`); the slip increments, where wanted or needed by the check, from
    :func:`slip_kernel_integral` on the pass's difference density. None for an input the pass
    leaves to the numpy route (a nan)."""
    ak = _annulus_kernels()
    assert ak is not None
    tab = _NO_TABLE if table is None else (*table.arrays["traction"], table.r, table.nodes)
    rr = np.zeros(0) if r is None else np.ascontiguousarray(r, float)
    bb = np.zeros(0) if bound is None else np.ascontiguousarray(bound, float)
    o, sl = _arrays(old), _arrays(slide)
    # the traction check's memo of the density it last checked at these points on this table
    # (numeric.inside_check: used only where that density is this step's old one, bit for bit)
    last = getattr(_MEMO, "last", None)
    memo = (last[2:] if last is not None and last[0] is rr and last[1] is table
            else _NO_MEMO)
    st, ws, c, s, gross, dpsi, inside, memo_x = ak["twist_step"](
        *o, *sl, float(radius), dphi, ROOT_XTOL * radius, _RTOL, rr, bb, float(G_t), CHECK_RTOL,
        *tab, *memo)
    if st != _annulus_kernel.STEP_DONE:
        return None
    if table is not None and memo_x.shape[1]:
        _MEMO.last = (rr, table, ws, memo_x)
    w = (ws[0], ws[1], ws[2], ws[3])     # (the pieces come as the rows of one array)
    c, s, gross, dpsi = float(c), float(s), float(gross), float(dpsi)
    if r is None:
        return {"w": w, "c": c, "sense": s, "dpsi": dpsi, "gross": gross, "slip": None,
                "ok": True, "why": ""}
    assert bound is not None   # r and bound come together
    ds = np.zeros(r.size)
    inside_ok = None
    if not slip:
        inside_ok = _DECIDED.get(inside)
        if inside_ok is None or (not inside_ok and allow is not None
                                 and not _beyond_allowance(memo_x, r, c, allow)):
            inside_ok = _inside_ok(w, r, c, bound, G_t, table, allow)
        if not inside_ok:
            return {"w": w, "c": c, "sense": s, "dpsi": dpsi, "gross": gross, "slip": ds,
                    "ok": False, "why": _WHY_INSIDE}
    # w − old above c and the check by its sign alone
    dw, sufficient = ak["slip_difference"](*w, *o, sl[2], sl[3], c, s, gross, CHECK_RTOL)
    # (or by the running integral of the difference: the steps with the edge off a node)
    sufficient = sufficient or _slip_sign.running_turn_ok_compiled(dw[0], dw[1], dw[2], dw[3], s, gross)
    why = ""
    if (slip or not sufficient) and gross == gross:
        # points in contact at the start or the end of the step, outside c
        reach = max(float(radius), float(old[1][-1]) if old[1].size else 0.0)
        on = ((bound > 0) | (r < reach)) & (r > c)
        if on.any():
            dw = (dw[0], dw[1], dw[2], dw[3])
            r_on = r[on]        # (the points once; ds_on the values written to ds)
            verdict = _slip_check.CHECK_OPEN
            if not slip and table is not None:
                # the check alone: by the increment's own nodes where its margin exceeds the
                # rounding (numeric.slip_check), else by the numpy route's products below
                verdict = _slip_check.kernels(_COMPILED["compiled"])["slip_check"](
                    dw[0], dw[1], dw[2], dw[3], r_on, s, gross, CHECK_RTOL,
                    *table.arrays["slip"], table.r, table.nodes, *_G01_ONE)
            if verdict == _slip_check.CHECK_FAIL:
                why = "slip against the traction on the annulus"
            elif verdict == _slip_check.CHECK_OPEN:
                ds_on = slip_kernel_integral(dw, r_on, None if slip else table) + gross * r_on
                if slip:
                    ds[on] = ds_on
                ref = float(np.max(np.abs(ds_on))) + float(np.max(r_on)) * abs(gross)
                if not sufficient and np.any(s * ds_on < -CHECK_RTOL * ref):
                    why = "slip against the traction on the annulus"
    if not why and inside_ok is None:
        ok = _DECIDED.get(inside)
        if ok is None or (not ok and allow is not None      # (the allowance: the numpy check)
                          and not _beyond_allowance(memo_x, r, c, allow)):
            ok = _inside_ok(w, r, c, bound, G_t, table, allow)
        if not ok:
            why = _WHY_INSIDE
    return {"w": w, "c": c, "sense": s, "dpsi": dpsi, "gross": gross, "slip": ds,
            "ok": not why, "why": why}


_DECIDED = {_annulus_kernel.INSIDE_OK: True, _annulus_kernel.INSIDE_FAIL: False}


def _beyond_allowance(memo_x: np.ndarray, r: np.ndarray, c: float, allow: tuple) -> bool:
    """Whether the pass's failed traction check fails beyond what ``allow`` can accept: its
    failing point (marked in the check's memo ``memo_x``) lies deeper than ``allow[2]`` inside
    the stick radius ``c``, and :func:`_inside_ok` rejects any excess there (its verdict, without
    its sums: the pass decides a failure only where the numpy route's traction fails too)."""
    hit = np.flatnonzero(memo_x[_inside_check.VALID] == _inside_check.FAILED)
    return bool(hit.size) and bool(r[hit[0]] < c - allow[2])


def shrink_energy_arrays(old: Pieces, slide: Pieces, radius: float, G_t: float, new: Pieces,
                         gauss: tuple, gross: float) -> tuple | None:
    """The compiled pass of a shrinking contact's step energy
    (:func:`contactlab.numeric.annulus_kernel.shrink_energy`): the release density ``step(old,
    slide, radius, G_t, dphi=0.0)["w"]`` taken by the arguments of :func:`_compiled_step` (the
    same bits), then the products of the release and family stages ``old → it → new`` with the
    Gauss rule ``gauss`` and the gross turn ``gross``. None for the numpy route (no compiled
    passes, or an input the pass leaves to it)."""
    ak = _annulus_kernels()
    if ak is None:
        return None
    out = ak["shrink_energy"](*_arrays(old), *_arrays(slide), float(radius),
                              ROOT_XTOL * radius, _RTOL, float(G_t), CHECK_RTOL, np.zeros(0),
                              np.zeros(0), *_NO_TABLE, *_NO_MEMO, *_arrays(new), *gauss,
                              float(gross))
    return None if out[0] != _annulus_kernel.STEP_DONE else out[1:]


def _inside_ok(w: Pieces, r: np.ndarray, c: float, bound: np.ndarray, G_t: float,
               table: NodeTable | None, allow: tuple | None = None) -> bool:
    """:func:`step`'s check inside the stick radius: the traction at the points ``r < c``
    within ``μ p`` (``bound``), or its weighted excess within ``allow`` (:func:`step`)."""
    inside = r < c
    if c <= 0 or not inside.any():
        return True
    exc = np.abs(traction(w, r[inside], G_t, table)) - bound[inside] * (1 + CHECK_RTOL)
    bad = exc > 0
    return not bad.any() or (allow is not None and bool(
        float(allow[0][inside][bad] @ exc[bad]) <= float(allow[1]))
        and bool(np.all(r[inside][bad] >= c - allow[2])))


#: right-hand sides of one :func:`coefficients` solve come in multiples of this (a multiple of the
#: widths of OpenBLAS's triangular-solve kernels measured: 2 on AVX-512, 4 on AVX2 hosts)
RHS_GROUP = 4


def coefficients(lu, values: np.ndarray) -> np.ndarray:
    """The ring solver's basis coefficients (hats then jumps) whose traction at its collocation
    points is each row of ``values`` (steps × points; ``lu``: the LU factors of the
    traction-per-basis matrix), one row per row of ``values``.

    One LAPACK ``getrs`` for all rows, the right-hand sides padded with zero rows to a multiple
    of :data:`RHS_GROUP`: OpenBLAS's triangular solves take the right-hand sides in groups of
    its kernel's width (2 with AVX-512, 4 with AVX2) and the columns left over by another kernel
    (a single vector by yet another), whose last bits differ; in whole groups every column is
    solved alike wherever it stands and however many there are (tested), so a row's coefficients
    do not depend on the other rows of the call; about half the time per row of one solve per
    row."""
    values = np.asarray(values, float)
    k = values.shape[0]
    rhs = np.zeros((values.shape[1], -(-k // RHS_GROUP) * RHS_GROUP), order="F")
    rhs[:, :k] = values.T
    # scipy's getrs wrapper turns the pivots 1-based in place for the call and back after it,
    # outside the GIL: on an array shared by threads (a ring set's cached factors) concurrent
    # calls corrupted each other's pivots and the heap (measured: aborts within 3000 calls on 8
    # threads); each call takes its own copy
    coef, info = _getrs(lu[0], lu[1].copy(), rhs, overwrite_b=True)
    if info != 0:
        raise ValueError(f"illegal value in argument {-info} of getrs")
    return coef[:, :k].T


def density(lu, b: np.ndarray, jumps: np.ndarray, values: np.ndarray, radius: float) -> Pieces:
    """Pieces of the ring solver's density whose traction at its collocation points is
    ``values`` (``lu``: the LU factors of the traction-per-basis matrix, hats then jumps), cut at
    the contact radius. With ``values = μ p`` it is the full-sliding density ``W`` of a step.
    The coefficients are :func:`coefficients`' (the same bits as a row of a batch)."""
    values = np.asarray(values, float)
    if values.ndim != 1 or values.size != lu[0].shape[0]:
        coef = _la.lu_solve((lu[0], lu[1].copy()), values, check_finite=False)   # (pivots)
    else:
        coef = coefficients(lu, values[None, :])[0]
    return from_coefficients(b, coef, jumps, radius)


_getrs, = _la.get_lapack_funcs(("getrs",), (np.zeros((1, 1)),))


def _psi_roots(p: Pieces, psi_hi: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The roots of ``Ψ`` strictly inside each piece (two columns, ``nan`` where none): on a
    piece ``Ψ(hi − u) = Ψ(hi) + w_r u − ½ m u²`` (``m`` the slope), a quadratic in ``u``."""
    lo, hi, wl, wr = p
    h = hi - lo
    m = np.where(h > 0, (wr - wl) / np.where(h > 0, h, 1.0), 0.0)
    a, b, c = -0.5 * m, wr, psi_hi
    disc = b * b - 4.0 * a * c
    sq = np.sqrt(np.maximum(disc, 0.0))
    q = -0.5 * (b + np.where(b >= 0, sq, -sq))
    with np.errstate(divide="ignore", invalid="ignore"):
        u1 = np.where(a != 0, q / np.where(a != 0, a, 1.0), np.nan)
        u2 = np.where(q != 0, c / np.where(q != 0, q, 1.0), np.nan)
    u1 = np.where(disc >= 0, u1, np.nan)
    u2 = np.where(disc >= 0, u2, np.nan)
    roots = np.stack([hi - u1, hi - u2], axis=1)
    inside = (roots > lo[:, None]) & (roots < hi[:, None])
    return np.where(inside, roots, np.nan), h


def nonnegative_psi(p: Pieces) -> Pieces:
    """The density whose ``Ψ`` is ``max(Ψ_p, 0)``: ``p`` with its density removed wherever
    ``Ψ_p < 0`` (``p`` itself, the same arrays, where ``Ψ_p >= 0`` everywhere).

    The full-sliding density of a step must have ``Ψ >= 0`` (for ``τ >= 0``,
    ``Ψ(x) = (1/2G_t) ∫_x^a τ(r)/sqrt(r² − x²) dr``); a collocated one can dip below zero near
    the contact edge, where the pressure falls like a square root. Every region where
    ``Ψ_p < 0`` is bounded by zeros of ``Ψ_p`` (or the outer end, where ``Ψ = 0``), so removing
    the density there removes a band of zero net turn and leaves ``Ψ_p`` unchanged elsewhere.
    ``max(Ψ_p, 0)`` is the projection of ``Ψ_p`` onto ``Ψ >= 0`` in the energy norm
    ``8 G_t ∫ x² Ψ² dx``: the nearest density, in the elastic energy, that slides the way of
    its traction."""
    lo, hi, wl, wr = p
    if lo.size == 0:
        return p
    ak = _annulus_kernels()
    if ak is not None:                  # the test and the cuts below, one pass
        status, out = ak["nonnegative_band"](*_arrays(p))
        if status == _annulus_kernel.BAND_NONE:
            return p
        if status == _annulus_kernel.BAND_CUT:
            return out[0], out[1], out[2], out[3]
    # the smallest Ψ on each piece: at an end or where w = 0 inside it (Ψ' = −w); Ψ at all
    # three in one call (elementwise: the same values)
    al, be = _lin(p)
    with np.errstate(divide="ignore", invalid="ignore"):
        xs = np.where(be != 0, -al / np.where(be != 0, be, 1.0), lo)
    xs = np.minimum(np.maximum(xs, lo), hi)
    P, n = psi(p, np.concatenate([hi, lo, xs])), lo.size
    psi_hi, psi_lo, psi_xs = P[:n], P[n:2 * n], P[2 * n:]
    low = np.minimum(np.minimum(psi_lo, psi_hi), psi_xs)
    if low.min() >= 0.0:
        return p
    roots, h = _psi_roots(p, psi_hi)
    cuts = np.sort(np.column_stack([lo, roots, hi]), axis=1)        # nan sort last
    cuts = np.where(np.isnan(cuts), hi[:, None], cuts)
    nlo, nhi = cuts[:, :-1].ravel(), cuts[:, 1:].ravel()
    par = np.repeat(np.arange(lo.size), cuts.shape[1] - 1)
    keep = nhi > nlo
    nlo, nhi, par = nlo[keep], nhi[keep], par[keep]
    hp = np.where(h[par] > 0, h[par], 1.0)
    vl = wl[par] + (wr[par] - wl[par]) * (nlo - lo[par]) / hp
    vr = wl[par] + (wr[par] - wl[par]) * (nhi - lo[par]) / hp
    # keep the sub-pieces where Ψ_p >= 0 (its sign at the midpoint: no root inside)
    neg = psi(p, 0.5 * (nlo + nhi)) < 0.0
    return nlo, nhi, np.where(neg, 0.0, vl), np.where(neg, 0.0, vr)
