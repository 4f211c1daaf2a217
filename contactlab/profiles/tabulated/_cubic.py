"""Cubic-spline interpolation of a table: its MDR transform as node sums, with a Gauss fallback.

The spline's slope is written once as jumps at the nodes (clustered pieces kept local), so g,
``∫g`` and ``∫x g`` are closed-form node sums with a rounding estimate; points whose estimate is
too large are recomputed by a Gauss-Legendre rule per table interval in θ (see
:mod:`contactlab.profiles.tabulated`). Private: the public class is
:class:`~contactlab.profiles.tabulated.Tabulated`, which dispatches here.
"""
from __future__ import annotations

import contextlib
from collections.abc import Iterator
from typing import cast

import numpy as np

from ...numeric.fixed_sums import row_sums, weighted_row_sums
from . import _far, _far_cols
from ._base import _CHUNK, _TableBase, _clip_index, _rows_per_chunk, _sorted, _unsorted

_GL_HI = np.polynomial.legendre.leggauss(12)
_GL_LO = np.polynomial.legendre.leggauss(8)
#: local corrections of cubic tables (tiny pieces): 2 points, error estimate from the midpoint
_GL_LOC_HI = np.polynomial.legendre.leggauss(2)
_GL_LOC_LO = np.polynomial.legendre.leggauss(1)
#: local pieces nearer x than this many piece widths are integrated in θ, farther ones by the
#: two-term Taylor form (relative error ~ (width / distance)² / 8 of a rounding-level term)
_LOCAL_NEAR = 300.0
#: cubic tables: points whose closed-form node sum carries a worst-case rounding estimate (8 eps
#: times the sum of |terms|, pessimistic by 5-50x) above this fraction
#: of the value are recomputed by the per-interval Gauss rule
CUBIC_SUM_RTOL = 1e-6
#: cubic tables: pieces whose cubic coefficient d satisfies |d| r_max² > this times the largest
#: slope are local (see :meth:`Tabulated._setup_cubic_jumps`). On a uniform 10^6-point table
#: (rounding noise alone) |d| r_max² reaches ~300 times the slope, on a random one 1e14 times;
#: with 300, 29 % of a random 10^6-point table's pieces are local and its node sums are
#: accurate to ~5e-10 (rounding estimate < 4e-7; 1e3: 18 % local, 1.3e-9; 1e4: 6 %, 7e-9)
CUBIC_LOCAL_RATIO = 300.0
#: most radii of a force solve whose column sums are kept for the depth and ∫g asked next
#: (12 floats each)
_PRIME_MAX = 65536
#: the columns a force solve's radii are summed for (:meth:`_CubicTransform._cubic_prime`):
#: g's value and rounding columns 0-5 and ∫g's 8-13 (its θ-columns are g's 0-3)
_PRIMED_COLS = np.array([0, 1, 2, 3, 4, 5, 8, 9, 10, 11, 12, 13])



class _CubicTransform(_TableBase):
    """Transform kernels of the cubic spline (private helpers only)."""

    def _setup_cubic_jumps(self, r: np.ndarray) -> None:
        """Node-jump form of the spline's slope, with clustered pieces kept local.

        ``f'(r) = P_0(r) + Σ_j ΔP_j(r) [r > r_j]``, ``P_k`` the slope polynomial of piece k and
        ``ΔP_j = α_j + β_j (r - r_j) + γ_j (r - r_j)²`` its change at node j. For a C² spline only
        ``γ_j = 3 Δd_j`` is nonzero in exact arithmetic; the rounding-level α, β are kept so the sum
        telescopes to every piece exactly (without them the node terms, extrapolated over the whole
        table, drift by ~1e-9 at 10^4 points).

        Pieces whose cubic coefficient is huge (:data:`CUBIC_LOCAL_RATIO`: nearly coincident
        nodes, whose third derivative is rounding noise of the data divided by h³) are *local*:
        their jumps, extrapolated over the whole table, would be ~1e13 times the slope and
        cancel between neighbours, leaving rounding errors of 1e-7 of g in every sum (random
        10^6-point tables). A run of local pieces is instead represented by the regular piece
        before it, continued across the run (one merged, modest jump at the run's end), plus a
        local correction ``D_k = P_k - P_prev`` integrated over each local piece only
        (:meth:`_cubic_local`)."""
        c = self._spline.c
        f_scale = max(float(np.max(np.abs(c[2]))), np.finfo(float).tiny)
        local = np.abs(c[0]) * float(r[-1]) ** 2 > CUBIC_LOCAL_RATIO * f_scale
        local[0] = False                    # piece 0 is the base polynomial
        reg = np.flatnonzero(~local)

        def jumps(prev: np.ndarray, k: np.ndarray) -> np.ndarray:
            """(α, β, γ) of P_k - P_prev at r_k, in powers of (r - r_k)."""
            H = r[k] - r[prev]
            return np.stack([c[2, k] - (c[2, prev] + (2.0 * c[1, prev] + 3.0 * c[0, prev] * H) * H),
                             2.0 * c[1, k] - (2.0 * c[1, prev] + 6.0 * c[0, prev] * H),
                             3.0 * (c[0, k] - c[0, prev])])

        self._cubic_base = (float(c[2, 0]), float(c[1, 0]), float(c[0, 0]))
        prev, nxt = reg[:-1], reg[1:]
        jmp = jumps(prev, nxt)
        keep = np.any(jmp != 0, axis=0)
        self._cubic_nodes = np.ascontiguousarray(r[nxt][keep])
        self._cubic_jumps = np.ascontiguousarray(jmp[:, keep])
        loc = np.flatnonzero(local)
        base = reg[np.searchsorted(reg, loc) - 1]
        # per local piece: its ends and the coefficients of D_k in powers of (r - r_k)
        self._cubic_local_lo = np.ascontiguousarray(r[loc])
        self._cubic_local_hi = np.ascontiguousarray(r[loc + 1])
        self._cubic_local_d = d = np.ascontiguousarray(jumps(base, loc))
        # moments of D over each piece about its midpoint, and the bound of the next Taylor term
        h = self._cubic_local_hi - self._cubic_local_lo
        mu0 = h * (d[0] + h * (0.5 * d[1] + h * d[2] / 3.0))
        mu1 = h ** 3 * (d[1] + h * d[2]) / 12.0
        q2 = (np.abs(d[0]) + h * (np.abs(d[1]) + h * np.abs(d[2]))) * h ** 3 / 24.0
        nu0 = h * (d[1] + h * d[2])
        nu1 = h ** 3 * d[2] / 6.0
        self._cubic_local_mom = np.ascontiguousarray(np.stack(
            [0.5 * (self._cubic_local_lo + self._cubic_local_hi), mu0, mu1, q2, nu0, nu1]))

    @staticmethod
    def _spline_rounding(r: np.ndarray, f_scale: float, x: np.ndarray) -> np.ndarray:
        """Rounding bound of the cubic spline's slope at ``x``, 1: ``4096 eps max|f| / h``,
        ``h`` the narrowest interval within 8 of the one holding ``x`` (2-sqrt(3))^8 = 3e-5)."""
        from scipy.ndimage import minimum_filter1d
        h = minimum_filter1d(np.diff(r), size=17, mode="nearest")
        k = _clip_index(np.searchsorted(r, x, side="right") - 1, 0, h.size - 1)
        return 4096.0 * np.finfo(float).eps * f_scale / h[k]

    def _cubic_value(self, x: np.ndarray, kind: str, with_slope: bool = False
                     ) -> tuple[np.ndarray, np.ndarray, np.ndarray | None]:
        """``(value, error)`` of the spline's transform (``kind`` "g" or "int"): the closed-form
        node sums, and the per-interval Gauss rule at the points where their rounding estimate
        exceeds :data:`CUBIC_SUM_RTOL` (tables with nearly coincident nodes, whose spline has
        huge third-derivative jumps that cancel in the sums)."""
        val, err, slope = self._cubic_sums(x, kind, with_slope)
        bad = err > CUBIC_SUM_RTOL * np.abs(val)
        if np.any(bad):
            xb = np.asarray(x, dtype=float)[bad]
            rules: dict[str, tuple[int | str, int]] = {"g": (0, 1), "int": (2, 2), "xg": ("xg", 3)}
            weight, p = rules[kind]
            v, e = self._spline_theta_sum(xb, weight)
            val[bad], err[bad] = v * xb**p, e * xb**p
        return val, err, slope

    def _cubic_sums(self, x: np.ndarray, kind: str, with_slope: bool = False
                    ) -> tuple[np.ndarray, np.ndarray, np.ndarray | None]:
        """Closed-form transform of the cubic spline: ``(value, rounding estimate, g')``.

        With ``f'(r) = b0 + 2c0 r + 3d0 r² + Σ_j [α_j + β_j (r - r_j) + J_j (r - r_j)²]_+`` (set
        up once; α, β are rounding-level, their terms ``α acos + β (sqrt - r_j acos)`` and
        ``α K0 + β (s³/3 - r_j K0)``, ``K0 = (a²θ - r_j s)/2``, are included below):

        * ``kind="g"``: ``g = x [b0 π/2 + 2c0 x + 3d0 πx²/4 + Σ_{r_j<x} J_j S_j]``,
          ``S_j = (x²/2 + r_j²) acos(r_j/x) - 1.5 r_j sqrt(x² - r_j²)``, and
          ``g' = g/x + x [2c0 + 3d0 πx/2 + Σ J_j (x acos(r_j/x) - (r_j/x) sqrt(x² - r_j²))]``;
        * ``kind="int"``: ``∫_0^a g = b0 πa²/4 + 2c0 a³/3 + 3d0 πa⁴/16 + Σ_{r_j<a} J_j T_j``,
          ``T_j = θ (a⁴/8 + a² r_j²/2) - r_j s (13a²/24 + r_j²/12)``, ``θ = acos(r_j/a)``,
          ``s = sqrt(a² - r_j²)``.

        * ``kind="xg"``: ``∫_0^a x g dx`` with the node integrals of
          :meth:`_xg_integral_closed_form`.

        O(nodes below x) per point, no quadrature; the rounding estimate is 8 eps times the sum
        of the absolute values of every part of every term before they cancel (conservative also
        for nearly coincident nodes, whose huge jumps cancel between neighbours and inside each
        term as r_j -> x).
        """
        self._guard(x, "x" if kind == "g" else "a")
        x = np.asarray(x, dtype=float)
        flat, order = _sorted(x)
        out = np.zeros(flat.size)
        err = np.zeros(flat.size)
        slope = np.zeros(flat.size) if with_slope else None
        b0, c0, d0 = self._cubic_base
        nodes_all, jump_all = self._cubic_nodes, self._cubic_jumps
        total = nodes_all.size
        chunk = _rows_per_chunk(total)
        eps = np.finfo(float).eps
        # large tables: the column sums over the tree (_far_cols), O(log N) per point
        ct = self._cubic_tree() if kind in ("g", "int") else None
        if ct is not None:
            chunk = max(chunk, 4096)
        for start in range(0, flat.size, chunk):
            xs = flat[start:start + chunk]
            pos = xs > 0
            if not np.any(pos):
                continue
            xv = xs[pos]
            xp = xv[:, None]
            if ct is not None:
                T, S, R3 = self._cubic_tree_sums(ct, xv, kind, with_slope)
                xv2 = xv * xv
            else:
                # the nodes below the chunk's largest point; row_sums groups every point's
                # sums the same whatever else is in its chunk (fixed_sums)
                m = int(np.searchsorted(nodes_all, xv.max(), side="left"))
                nodes = nodes_all[:m][None, :]
                al, be, jmp = (jump_all[k, :m][None, :] for k in range(3))
                below = nodes < xp
                root = np.sqrt(np.maximum((xp - nodes) * (xp + nodes), 0.0))
                theta = np.arctan2(root, nodes)                   # acos(r_j/x), accurate near x

            # each node term is a difference of parts that cancel as r_j -> x (the J term by
            # (root/x)^2 and more): its rounding is eps times the parts' magnitudes, not its value.
            # g and ∫g: the node terms are θ, root (and root³) times per-node coefficients and
            # powers of x, so their sums (and the parts' magnitudes) are contractions with
            # coefficient columns set up once (θ = root = 0 at nodes >= x: no mask needed)
            if kind in ("g", "int") and ct is None:
                c_th, c_rt, c_r3 = self._cubic_columns(kind)
                # one padded product buffer and one blocked sum per term array (weighted_row_sums)
                T = weighted_row_sums(theta, c_th, total)
                S = weighted_row_sums(root, c_rt if kind == "int" or with_slope else c_rt[:2],
                                      total)
                xv2 = xv * xv
            loc_val, loc_mag, loc_slope = self._cubic_local(xv, kind, with_slope)
            if kind == "g":
                total_nodes = T[0] + 0.5 * xv2 * T[1] + S[0]
                mag_nodes = T[2] + 0.5 * xv2 * T[3] + S[1]
                head = (b0 * 0.5 * np.pi, 2.0 * c0 * xv, 0.75 * np.pi * d0 * xv2)
                total_g = head[0] + head[1] + head[2] + total_nodes + loc_val
                size = abs(head[0]) + np.abs(head[1]) + np.abs(head[2]) + mag_nodes
                out[start:start + chunk][pos] = xv * total_g
                err[start:start + chunk][pos] = 8 * eps * xv * size + xv * loc_mag
                if slope is not None:
                    # (the rounding-level α term, a cusp, is left out of the Newton slope)
                    dnodes = (S[2] - S[3]) / xv + xv * T[1]
                    slope[start:start + chunk][pos] = total_g + xv * (
                        2.0 * c0 + 1.5 * np.pi * d0 * xv + dnodes + loc_slope)
                continue
            if kind == "int":
                if ct is None:
                    R3 = weighted_row_sums(root ** 3 / 3.0, cast(np.ndarray, c_r3), total)
                R3 = cast(np.ndarray, R3)
                c13 = 13.0 / 24.0 * xv2
                out[start:start + chunk][pos] = (
                    0.25 * np.pi * b0 * xv2 + 2.0 / 3.0 * c0 * xv2 * xv
                    + 0.1875 * np.pi * d0 * xv2 * xv2
                    + 0.5 * xv2 * T[0] + 0.125 * xv2 * xv2 * T[1] + S[0]
                    - c13 * S[1] + R3[0] + xv2 * loc_val)
                err[start:start + chunk][pos] = 8 * eps * (
                    np.abs(0.25 * np.pi * b0 * xv2) + np.abs(2.0 / 3.0 * c0 * xv2 * xv)
                    + np.abs(0.1875 * np.pi * d0 * xv2 * xv2)
                    + 0.5 * xv2 * T[2] + 0.125 * xv2 * xv2 * T[3] + S[2]
                    + c13 * S[3] + R3[1]) + xv2 * loc_mag
                continue
            # "xg": ∫_0^a x g dx
            P2, Q2, P4, (m2, mq, m4) = self._node_moments(xp, nodes)
            b2 = nodes * nodes
            terms = np.where(below, al * P2 + be * (Q2 - nodes * P2)
                             + jmp * (0.5 * P4 + b2 * P2 - 1.5 * nodes * Q2), 0.0)
            mags = np.where(below, np.abs(al) * m2 + np.abs(be) * (mq + nodes * m2)
                            + np.abs(jmp) * (0.5 * m4 + b2 * m2 + 1.5 * nodes * mq), 0.0)
            av2 = xv * xv
            head = (np.pi / 6.0 * b0 * av2 * xv, 0.5 * c0 * av2 * av2,
                    0.15 * np.pi * d0 * av2 * av2 * xv)
            out[start:start + chunk][pos] = (head[0] + head[1] + head[2]
                                             + row_sums(terms, total) + av2 * xv * loc_val)
            err[start:start + chunk][pos] = 8 * eps * (
                np.abs(head[0]) + np.abs(head[1]) + np.abs(head[2]) + row_sums(mags, total)) \
                + av2 * xv * loc_mag
        return (_unsorted(out, order, x.shape), _unsorted(err, order, x.shape),
                None if slope is None else _unsorted(slope, order, x.shape))

    def _cubic_local(self, xv: np.ndarray, kind: str, with_slope: bool
                     ) -> tuple[np.ndarray, np.ndarray, np.ndarray | None]:
        """Local corrections of :meth:`_cubic_sums` at ``xv > 0``: ``∫ D_k(r) w(r, x) dr`` over
        every local piece k below x (``D_k = P_k - P_prev``, see :meth:`_setup_cubic_jumps`), in
        the units of the node sums of ``kind`` (``w = 1/s``; ``s/x²``; ``(x s + r² L)/(2x³)``,
        ``s = sqrt(x² - r²)``, ``L = acosh(x/r)``): ``(value, error, slope term)``, the slope
        term ``∫ D'(x sinθ) sinθ dθ`` (``kind="g"``: the derivative at fixed θ-limits; the
        moving limits give cusp terms that cancel the merged jumps' α cusps, which the Newton
        slope of :meth:`_cubic_sums` leaves out too).

        The pieces are tiny (nearly coincident nodes). A piece more than
        :data:`_LOCAL_NEAR` widths below x contributes ``w(r_m) μ0 + w'(r_m) μ1`` (``r_m`` its
        midpoint, ``μ0 = ∫D``, ``μ1 = ∫D (r - r_m)``; ``ν0, ν1``
        likewise of ``D'`` for the slope term; set up once), with the next Taylor term as
        its error; a piece nearer x (or holding it) is integrated in θ by a 2-point Gauss rule,
        its error the difference to the midpoint rule. Both add 8 eps times the magnitudes.
        The corrections are at the rounding level of the data (~1e-10 of g); they make the sum
        the exact transform of the spline all the same."""
        rows = xv.size
        lo_all = self._cubic_local_lo
        total = lo_all.size
        zero = np.zeros(rows)
        m = int(np.searchsorted(lo_all, xv.max(), side="left")) if total else 0
        if m == 0:
            return zero, zero, (zero if with_slope else None)
        eps = np.finfo(float).eps
        xp = xv[:, None]
        lo, hi = lo_all[None, :m], self._cubic_local_hi[None, :m]
        rm, mu0, mu1, q2 = (self._cubic_local_mom[k, None, :m] for k in range(4))
        below = lo < xp
        near = below & ((xp - hi) < _LOCAL_NEAR * (hi - lo))
        far = below & ~near
        s = np.sqrt(np.where(far, (xp - rm) * (xp + rm), 1.0))
        slope = None
        # (entries of pieces not below x, masked below, may divide by a tiny x² = 0)
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            if kind == "g":
                s3 = s * s * s
                vals = mu0 / s + mu1 * rm / s3
                mags = np.abs(mu0) / s + np.abs(mu1) * rm / s3
                w2 = (1.0 + 3.0 * rm * rm / (s * s)) / s3
                if with_slope:
                    nu0, nu1 = (self._cubic_local_mom[k, None, :m] for k in (4, 5))
                    dvals = (nu0 * rm / s + nu1 * xp * xp / s3) / xp
            elif kind == "int":
                vals = (mu0 * s - mu1 * rm / s) / (xp * xp)
                mags = (np.abs(mu0) * s + np.abs(mu1) * rm / s) / (xp * xp)
                w2 = xp / (s * s * s)
            else:
                L = np.arccosh(np.maximum(xp / np.where(far, rm, xp), 1.0))
                x3 = xp * xp * xp
                w0 = 0.5 * (xp * s + rm * rm * L)
                w1 = rm * L - xp * rm / s
                vals = (mu0 * w0 + mu1 * w1) / x3
                mags = (np.abs(mu0) * w0 + np.abs(mu1) * np.abs(w1)) / x3
                w2 = (L + xp / s + x3 / (s * s * s)) / x3
            vals = np.where(far, vals, 0.0)
            errs = np.where(far, q2 * w2 + 8 * eps * mags, 0.0)
        if with_slope:
            dvals = np.where(far, dvals, 0.0)
        ri, ki = np.nonzero(near)
        if ri.size:
            nv, ne, nd = self._cubic_local_gauss(xv[ri], ki, kind, with_slope)
            vals[ri, ki], errs[ri, ki] = nv, ne
            if with_slope:
                dvals[ri, ki] = nd
        if with_slope:
            slope = row_sums(dvals, total)
        return row_sums(vals, total), row_sums(errs, total), slope

    def _cubic_local_gauss(self, x: np.ndarray, k: np.ndarray, kind: str, with_slope: bool
                           ) -> tuple[np.ndarray, np.ndarray, np.ndarray | None]:
        """:meth:`_cubic_local` for local pieces ``k`` near ``x`` (1-D, paired): a 2-point Gauss
        rule in θ over the piece's part below x, error from the midpoint rule."""
        lo, hi = self._cubic_local_lo[k], self._cubic_local_hi[k]
        d0, d1, d2 = (self._cubic_local_d[j, k][:, None] for j in range(3))
        xc = x[:, None]
        th_lo = np.arcsin(np.minimum(lo / x, 1.0))[:, None]
        half = 0.5 * (np.arcsin(np.minimum(hi / x, 1.0))[:, None] - th_lo)
        res = []
        for u, wts in (_GL_LOC_HI, _GL_LOC_LO):
            dth = half * (u + 1.0)
            th = th_lo + dth
            # r - r_k = x (sinθ - sinθ_k), without cancelling
            t = 2.0 * xc * np.sin(0.5 * dth) * np.cos(th_lo + 0.5 * dth)
            D = d0 + t * (d1 + t * d2)
            if kind == "g":
                w = np.ones_like(th)
            elif kind == "int":
                w = np.cos(th) ** 2
            else:
                co, si = np.cos(th), np.sin(th)
                w = 0.5 * co * (co + si * si * np.arcsinh(co / si))
            res.append(np.sum(D * w * wts, axis=-1) * half[:, 0])
            if len(res) == 1:
                mag = np.sum(np.abs(D * w) * wts, axis=-1) * half[:, 0]
                dv = (np.sum((d1 + 2.0 * d2 * t) * np.sin(th) * wts, axis=-1) * half[:, 0]
                      if with_slope else None)
        err = np.abs(res[0] - res[1]) + 8 * np.finfo(float).eps * mag
        return res[0], err, dv

    def _cubic_tree(self) -> _far_cols.ColumnTree | None:
        """The column tree (:mod:`._far_cols`) of the node sums' coefficient columns (θ-columns,
        root-columns of g and of ∫g, root³/3-columns: 14 in all), built on first use; None for
        tables that keep the dense node sums (small, or clustered nodes)."""
        cached = self.__dict__.get("_cubic_tree_cache")
        if cached is None:
            th, rt_g, _ = self._cubic_columns("g")
            _, rt_i, r3 = self._cubic_columns("int")
            cols = np.concatenate([th, rt_g, rt_i, cast(np.ndarray, r3)])
            cached = (_far_cols.build(self._cubic_nodes, cols, float(self.r[-1])),)
            self.__dict__["_cubic_tree_cache"] = cached
        return cast("_far_cols.ColumnTree | None", cached[0])

    def _cubic_tree_sums(self, ct: _far_cols.ColumnTree, xv: np.ndarray, kind: str,
                         with_slope: bool) -> tuple[np.ndarray, np.ndarray, np.ndarray | None]:
        """``(T, S, R3)`` of :meth:`_cubic_sums` from the column tree (R3 for ``"int"`` only).

        Inside :meth:`_cubic_g_slope_integral` every column is summed on the first call and
        kept for the second at the same points (a column's sums do not depend on which other
        columns share the call: the same bits)."""
        A, R, R3k = _far_cols.ACOS, _far_cols.ROOT, _far_cols.ROOT3
        terms = self._tree_terms()
        primed = self.__dict__.get("_cubic_primed")
        if primed is not None and not (kind == "g" and with_slope):
            # the column sums at a force solve's radii (_cubic_prime), for the depth and the
            # ∫g its caller asks next at the same radii (12 columns: not g's slope columns 6
            # and 7, which neither needs); a call at other points drops them
            key = (xv.tobytes(), terms)
            out = primed.get(key)
            if out is None and primed.get("fill"):
                out = _far_cols.sums(ct, xv, _PRIMED_COLS,
                                     np.array([A] * 4 + [R] * 6 + [R3k] * 2), terms)
                primed[key] = out
            if out is not None:
                if kind == "g":
                    return out[:4], out[4:6], None
                return out[:4], out[6:10], out[10:12]
            self.__dict__.pop("_cubic_primed", None)
        memo = self.__dict__.get("_cubic_pair")
        if memo is not None:
            key = (xv.tobytes(), terms)
            out = memo.get(key)
            if out is None:
                out = _far_cols.sums(
                    ct, xv, np.arange(14), np.array([A] * 4 + [R] * 8 + [R3k] * 2), terms)
                # every chunk of the pass is kept (up to _PRIME_MAX points; beyond, the last)
                if sum(v.shape[1] for v in memo.values()) + xv.size > _PRIME_MAX:
                    memo.clear()
                memo[key] = out
            if kind == "g":
                return out[:4], out[4:8] if with_slope else out[4:6], None
            return out[:4], out[8:12], out[12:14]
        if kind == "g":
            n_rt = 4 if with_slope else 2
            cols = np.array([0, 1, 2, 3, *range(4, 4 + n_rt)])
            kinds = np.array([A] * 4 + [R] * n_rt)
        else:
            cols = np.arange(14)
            cols = np.concatenate([cols[:4], cols[8:14]])
            kinds = np.array([A] * 4 + [R] * 4 + [R3k] * 2)
        out = _far_cols.sums(ct, xv, cols, kinds, terms)
        if kind == "g":
            return out[:4], out[4:], None
        return out[:4], out[4:8], out[8:10]

    def _cubic_truncation(self, x: np.ndarray, kind: str, terms: np.ndarray | None = None
                          ) -> np.ndarray:
        """Bound of the column tree's Taylor truncation in ``g`` (``kind`` "g") or
        ``∫_0^x g`` ("int") at ``x`` with the current call's terms (:meth:`_tree_terms`): zeros
        with all :data:`._far.TERMS` terms or without the tree. Each signed column's far sum
        is off by at most ``K`` (π/2 for acos, √2 for the root, 2√2 for its cube) times the
        sum over x's far blocks of :func:`._far.block_tails` (from each block's own moments),
        taken with the factors of :meth:`_cubic_sums`' combination (g:
        ``x [T0 + x² T1/2 + x S0]``; ∫g: ``x² T0/2 + x⁴ T1/8 + x (S0 + 13x²/24 S1) + x³
        R3/3``). ``terms`` (an array): the bounds for each of those counts."""
        x = np.asarray(x, dtype=float)
        count = self._tree_terms() if terms is None else 0
        ct = self._cubic_tree() if count < _far.TERMS else None
        if ct is None:
            return np.zeros(x.shape if terms is None else (len(terms), *x.shape))
        tails = ct.cache.get("tails")
        if tails is None:
            tails = _far.block_tails(ct.moments, ct.tree, ct.columns)
            ct.cache["tails"] = tails
        flat = x.ravel()
        pos = flat > 0
        nt = 1 if terms is None else len(terms)
        cols = [0, 1, 4] if kind == "g" else [0, 1, 8, 9, 12]
        W = np.zeros((tails.shape[1], nt, flat.size))
        if np.any(pos):
                W[np.ix_(np.array(cols), np.arange(nt), np.flatnonzero(pos))] = _far.far_bound(
                ct.tree, tails, flat[pos], np.array([count]) if terms is None else terms, cols)
        xa = np.maximum(flat, 0.0)
        k_acos, k_root = 0.5 * np.pi, np.sqrt(2.0)
        x2 = xa * xa
        if kind == "g":
            b = xa * (k_acos * (W[0] + 0.5 * x2 * W[1]) + k_root * xa * W[4])
        else:
            b = (k_acos * (0.5 * x2 * W[0] + 0.125 * x2 * x2 * W[1])
                 + k_root * xa * (W[8] + 13.0 / 24.0 * x2 * W[9])
                 + 2.0 * k_root * xa * x2 / 3.0 * W[12])
        return b[0].reshape(x.shape) if terms is None else b.reshape(nt, *x.shape)

    def _cubic_g_slope_integral(self, x: np.ndarray
                                ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """``(g, g', ∫_0^x g)`` of the spline, the same bits as :meth:`_g_and_slope` and
        :meth:`_g_integral_closed_form` apart; on the column tree the node sums of both come
        from one pass (the force solve's Newton step needs all three)."""
        with self._cubic_shared_pass():
            g, gp = self._g_and_slope(x)
            integral = self._g_integral_closed_form(x)
        return g, gp, integral

    def _cubic_signed_pass(self, x: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray] | None:
        """``(g, g', ∫_0^x g)`` of the spline on the column tree from the signed columns only
        (8 of 14: no rounding estimate, no Gauss fallback), for the force solve's Newton steps;
        the same operations as :meth:`_cubic_sums`, so the same bits wherever that route keeps
        its node sums. None for tables without the tree. The solve checks the estimate at its
        radius afterwards (:meth:`_cubic_prime`)."""
        ct = self._cubic_tree()
        if ct is None:
            return None
        self._guard(x, "x")
        flat, order = _sorted(np.asarray(x, dtype=float))
        g, gp, gi = np.zeros(flat.size), np.zeros(flat.size), np.zeros(flat.size)
        b0, c0, d0 = self._cubic_base
        A, R, R3k = _far_cols.ACOS, _far_cols.ROOT, _far_cols.ROOT3
        cols = np.array([0, 1, 4, 6, 7, 8, 9, 12])
        kinds = np.array([A, A, R, R, R, R, R, R3k])
        chunk = max(_rows_per_chunk(self._cubic_nodes.size), 4096)
        for start in range(0, flat.size, chunk):
            xs = flat[start:start + chunk]
            pos = xs > 0
            if not np.any(pos):
                continue
            xv = xs[pos]
            t0, t1, sg0, sg2, sg3, si0, si1, r30 = _far_cols.sums(ct, xv, cols, kinds,
                                                                   self._tree_terms())
            xv2 = xv * xv
            # g and g' (the expressions of _cubic_sums, kind "g")
            loc_val, _, loc_slope = self._cubic_local(xv, "g", True)
            total_nodes = t0 + 0.5 * xv2 * t1 + sg0
            head = (b0 * 0.5 * np.pi, 2.0 * c0 * xv, 0.75 * np.pi * d0 * xv2)
            total_g = head[0] + head[1] + head[2] + total_nodes + loc_val
            g[start:start + chunk][pos] = xv * total_g
            dnodes = (sg2 - sg3) / xv + xv * t1
            gp[start:start + chunk][pos] = total_g + xv * (
                2.0 * c0 + 1.5 * np.pi * d0 * xv + dnodes + cast(np.ndarray, loc_slope))
            # ∫g (kind "int")
            loc_int = self._cubic_local(xv, "int", False)[0]
            c13 = 13.0 / 24.0 * xv2
            gi[start:start + chunk][pos] = (
                0.25 * np.pi * b0 * xv2 + 2.0 / 3.0 * c0 * xv2 * xv
                + 0.1875 * np.pi * d0 * xv2 * xv2
                + 0.5 * xv2 * t0 + 0.125 * xv2 * xv2 * t1 + si0
                - c13 * si1 + r30 + xv2 * loc_int)
        shape = np.shape(x)
        return _unsorted(g, order, shape), _unsorted(gp, order, shape), _unsorted(gi, order, shape)

    def _cubic_prime(self, a: np.ndarray) -> np.ndarray:
        """After a force solve on the column tree: the node sums of g and ∫g at its radii ``a``
        in one pass over their 12 columns, kept for the depth and the ∫g its caller asks next (the
        same bits as computed apart); returns where their rounding estimate exceeds
        :data:`CUBIC_SUM_RTOL` (there the signed-column Newton steps are redone on the full
        route). Batches above :data:`_PRIME_MAX` points are checked without keeping the sums."""
        keep = a.size <= _PRIME_MAX
        if keep:
            self.__dict__["_cubic_primed"] = {"fill": True}
        try:
            vg, eg, _ = self._cubic_sums(a, "g")
            vi, ei, _ = self._cubic_sums(a, "int")
        finally:
            primed = self.__dict__.get("_cubic_primed")
            if primed is not None:
                primed["fill"] = False
        return (eg > CUBIC_SUM_RTOL * np.abs(vg)) | (ei > CUBIC_SUM_RTOL * np.abs(vi))

    @contextlib.contextmanager
    def _cubic_shared_pass(self) -> Iterator[None]:
        """Inside: the column tree's sums at a set of points are computed once for every
        column and reused by the next call at the same points (g, then ∫g; the same bits)."""
        self.__dict__["_cubic_pair"] = {}
        try:
            yield
        finally:
            self.__dict__.pop("_cubic_pair", None)

    def _cubic_columns(self, kind: str) -> tuple[np.ndarray, np.ndarray, np.ndarray | None]:
        """Per-node coefficient columns of the node sums of :meth:`_cubic_sums` (set up once).

        ``kind="g"``: θ-columns ``[α - bβ + b²J, J, |α| + b|β| + b²|J|, |J|]``, root-columns
        ``[β - 1.5bJ, |β| + 1.5b|J|, β, bJ]``; ``kind="int"``: θ-columns as for g, root-columns
        ``[-bα/2 + b²β/2 - b³J/12, bJ, b|α|/2 + b²|β|/2 + b³|J|/12, b|J|]``, root³/3-columns
        ``[β, |β|]`` (b = r_j; the signed columns give the value, the absolute ones the parts'
        magnitudes for the rounding estimate). Each is returned as a contiguous (columns, nodes)
        array, one row per column.
        """
        cache = self.__dict__.setdefault("_cubic_cols", {})
        if kind not in cache:
            b = self._cubic_nodes
            al, be, J = self._cubic_jumps
            aa, ab, aJ = np.abs(al), np.abs(be), np.abs(J)
            th = np.stack([al - b * be + b * b * J, J, aa + b * ab + b * b * aJ, aJ], axis=1)
            if kind == "g":
                rt = np.stack([be - 1.5 * b * J, ab + 1.5 * b * aJ, be, b * J], axis=1)
                r3 = None
            else:
                rt = np.stack([-0.5 * b * al + 0.5 * b * b * be - b**3 * J / 12.0, b * J,
                               0.5 * b * aa + 0.5 * b * b * ab + b**3 * aJ / 12.0, b * aJ], axis=1)
                r3 = np.stack([be, ab], axis=1)
            cache[kind] = tuple(None if v is None else np.ascontiguousarray(v.T)
                                for v in (th, rt, r3))
        return cache[kind]

    def _spline_theta_sum(self, x: np.ndarray, weight_power: int | str
                          ) -> tuple[np.ndarray, np.ndarray]:
        """``∫_0^{π/2} f'(x sinθ) w(θ) dθ`` for the spline, one Gauss-Legendre rule per table
        interval in θ (the integrand is analytic inside each interval, so 12 nodes reach rounding
        level; the 8-node rule gives the error estimate).

        ``w = cos^p θ`` for ``weight_power = p`` (``g/x``: p = 0, ``∫g / a²``: p = 2), or
        ``w = cosθ (cosθ + sin²θ asinh(cotθ))/2`` for ``"xg"`` (``∫_0^a x g dx / a³``, from
        ``∫_0^a x g = ∫_0^a f'(r) ∫_r^a x²/sqrt(x² - r²) dx dr``)."""
        flat = np.asarray(x, dtype=float).ravel()
        val = np.zeros(flat.size)
        err = np.zeros(flat.size)
        lo_n, hi_n = self.r[:-1], self.r[1:]
        chunk = max(1, _CHUNK // (lo_n.size * _GL_HI[0].size))
        for start in range(0, flat.size, chunk):
            xs = flat[start:start + chunk]
            pos = xs > 0
            if not np.any(pos):
                continue
            xp = xs[pos][:, None]
            # min(node / x, 1) without overflow for tiny x (node / max(x, node))
            t_lo = np.arcsin(lo_n[None, :] / np.maximum(xp, lo_n[None, :]))
            t_hi = np.arcsin(hi_n[None, :] / np.maximum(xp, hi_n[None, :]))
            half = 0.5 * (t_hi - t_lo)
            mid = 0.5 * (t_hi + t_lo)
            sums = []
            for nodes, weights in (_GL_HI, _GL_LO):
                th = mid[..., None] + half[..., None] * nodes
                vals = self._spline_d(np.minimum(xp[..., None] * np.sin(th), self.r[-1]))
                if weight_power == "xg":
                    co, si = np.cos(th), np.sin(th)
                    vals = vals * 0.5 * co * (co + si * si * np.arcsinh(co / si))
                elif weight_power:
                    vals = vals * np.cos(th) ** weight_power
                # plain sums (not BLAS): a point's rounding does not depend on its batch
                sums.append((np.sum(vals * weights, axis=-1) * half).sum(axis=1))
            val[start:start + chunk][pos] = sums[0]
            err[start:start + chunk][pos] = np.abs(sums[0] - sums[1])
        return val.reshape(np.shape(x)), err.reshape(np.shape(x))
