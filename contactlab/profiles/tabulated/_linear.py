"""Linear interpolation of a table: its exact MDR transform as sums over the slope jumps.

The piecewise-linear interpolant is a cone plus truncated cones at the interior nodes, so g, its
slope, ``∫g``, ``∫x g``, the pressure shape and the Abel transform are sums of elementary terms
over the nodes below each point (see :mod:`contactlab.profiles.tabulated`). Private: the public
class is :class:`~contactlab.profiles.tabulated.Tabulated`, which dispatches here.
"""
from __future__ import annotations

from typing import cast

import numpy as np

from ...numeric.fixed_sums import row_sums
from . import _far
from ._base import _CHUNK, _TableBase, _clip_index, _rows_per_chunk, _sorted, _unsorted

#: most radii whose tree sums a force solve keeps for the depth and ∫g asked next
#: (:meth:`_LinearTransform._far_prime`)
PRIME_MAX = 65536


class _LinearTransform(_TableBase):
    """Transform kernels of the linear interpolant (private helpers only)."""

    def _arcsine_sums(self, x: np.ndarray, with_slope: bool
                      ) -> tuple[np.ndarray, np.ndarray | None]:
        """g(x) and, if asked, g'(x) of the linear interpolant in one pass over the nodes.

        ``g = x [s_k π/2 − Σ Δs_j asin(r_j/x)]`` and
        ``g' = s_k π/2 − Σ Δs_j [asin(r_j/x) − r_j/sqrt(x² − r_j²)]`` (nodes r_j <= x; g' is
        infinite exactly at a node with a slope jump, the square-root cusp).
        """
        g, slope, _ = self._arcsine_pass(x, with_slope, False)
        return g, slope

    def _g_slope_integral(self, x: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """``(g, g', ∫_0^x g)`` of the linear interpolant in one pass over the nodes (the
        arcsines and square roots shared), each bit-identical to :meth:`_arcsine_sums` and
        :meth:`_linear_g_integral` (the force solve's Newton step needs all three)."""
        g, slope, integral = self._arcsine_pass(x, True, True)
        return g, cast(np.ndarray, slope), cast(np.ndarray, integral)

    def _far_tree(self) -> _far.FarTree | None:
        """The dyadic tree of the slope-jump nodes (:mod:`._far`), built on first use; None for
        tables that keep the node-by-node sums (small, or clustered)."""
        cached = self.__dict__.get("_far_cache")
        if cached is None:
            jump = self._dslope != 0
            cached = (_far.build(self.r[1:-1][jump], self._dslope[jump], float(self.r[-1])),)
            self.__dict__["_far_cache"] = cached
        return cast("_far.FarTree | None", cached[0])

    def _far_pass(self, tree: _far.FarTree, x: np.ndarray, with_g: bool, with_slope: bool,
                  with_integral: bool
                  ) -> tuple[np.ndarray, np.ndarray | None, np.ndarray | None]:
        """``(g, g', ∫_0^x g)`` from the tree's sums (:mod:`._far`): the formulas of
        :meth:`_arcsine_pass`, O(log N) per point; ``g'`` and ``∫g`` only when asked."""
        flat = x.ravel()
        g = np.zeros(flat.size)
        slope = np.zeros(flat.size) if with_slope else None
        integral = np.zeros(flat.size) if with_integral else None
        pos = flat > 0
        if np.any(pos):
            xs = flat[pos]
            sums = None
            terms = self._tree_terms()
            primed = self.__dict__.get("_far_primed")
            if primed is not None:
                # a force solve's radii (_far_prime): A and P kept for the depth and the ∫g
                # asked next at them; a call at other points (or for g', or with another
                # number of Taylor terms) drops them
                if not with_slope and primed[0] == xs.tobytes() and primed[3] == terms:
                    sums = (primed[1], None, primed[2])
                else:
                    self.__dict__.pop("_far_primed", None)
            A, C, P = sums if sums is not None else _far.sums(tree, xs, with_slope,
                                                              with_integral, terms)
            k = _clip_index(np.searchsorted(self.r, xs, side="right") - 1, 0, self._slopes.size - 1)
            s_k = self._slopes[k]
            base = 0.5 * np.pi * s_k - A
            g[pos] = xs * base
            if slope is not None:
                slope[pos] = base + cast(np.ndarray, C)
            if integral is not None:
                integral[pos] = s_k * 0.25 * np.pi * xs**2 - cast(np.ndarray, P)
        shape = x.shape
        return (g.reshape(shape), None if slope is None else slope.reshape(shape),
                None if integral is None else integral.reshape(shape))

    def _far_prime(self, a: np.ndarray) -> None:
        """After a force solve on the tree: the sums of g and ∫g at its radii ``a`` (every one
        positive) in one pass (A and P, the same bits as from separate passes: A's operations
        do not depend on which other sums a pass makes), kept for the depth and the ∫g its
        caller asks next at these radii (two passes over the tree become one). Batches above
        :data:`PRIME_MAX` points are not kept."""
        tree = self._far_tree()
        flat = a.ravel()
        if tree is None or flat.size > PRIME_MAX or not bool(np.all(flat > 0)):
            return
        terms = self._tree_terms()
        A, _, P = _far.sums(tree, flat, False, True, terms)
        self.__dict__["_far_primed"] = (flat.tobytes(), A, P, terms)

    def _far_truncation(self, x: np.ndarray, kind: str, terms: np.ndarray | None = None
                        ) -> np.ndarray:
        """Bound of the tree's Taylor truncation in ``g`` (``kind`` "g") or ``∫_0^x g``
        ("int") at ``x`` with the current call's terms (:meth:`_tree_terms`): zeros with all
        :data:`._far.TERMS` terms (their truncation is below the rounding) or without the tree.
        The sum over x's far blocks of :func:`._far.block_tails` (from each block's own
        moments) times ``K`` (π/2 for asin, (√2 + π/2)/2 for Φ) and x (g) or x² (∫g).
        ``terms`` (an array): the bounds for each of those counts, shape (len(terms), x.size)."""
        x = np.asarray(x, dtype=float)
        count = self._tree_terms() if terms is None else 0
        tree = self._far_tree() if count < _far.TERMS else None
        if tree is None:
            return np.zeros(x.shape if terms is None else (len(terms), *x.shape))
        tails = self.__dict__.get("_far_tails")
        if tails is None:
            tails = _far.block_tails(tree.moments[:, None, :], tree, tree.weights[None, :])
            self.__dict__["_far_tails"] = tails
        flat = x.ravel()
        pos = flat > 0
        b = np.zeros((1 if terms is None else len(terms), flat.size))
        if np.any(pos):
            b[:, pos] = _far.far_bound(tree, tails, flat[pos],
                                       np.array([count]) if terms is None else terms, [0])[0]
        k = 0.5 * np.pi if kind == "g" else 0.5 * (np.sqrt(2.0) + 0.5 * np.pi)
        b *= k * (flat if kind == "g" else flat * flat)
        return b[0].reshape(x.shape) if terms is None else b.reshape(len(terms), *x.shape)

    def _arcsine_pass(self, x: np.ndarray, with_slope: bool, with_integral: bool
                      ) -> tuple[np.ndarray, np.ndarray | None, np.ndarray | None]:
        self._guard(x, "x")
        x = np.asarray(x, dtype=float)
        tree = self._far_tree()
        if tree is not None:
            return self._far_pass(tree, x, True, with_slope, with_integral)
        flat, order = _sorted(x)
        out = np.zeros(flat.size)
        slope = np.zeros(flat.size) if with_slope else None
        integral = np.zeros(flat.size) if with_integral else None
        # only nodes with a slope jump contribute, and only those below the largest x
        jump = self._dslope != 0
        nodes_all = self.r[1:-1][jump]
        ds_all = self._dslope[jump]
        chunk = _rows_per_chunk(nodes_all.size)
        k_all = _clip_index(np.searchsorted(self.r, flat, side="right") - 1, 0, self._slopes.size - 1)
        for start in range(0, flat.size, chunk):
            xs = flat[start:start + chunk]
            pos = xs > 0
            if not pos.any():
                continue
            xp = xs[pos][:, None]
            m = int(np.searchsorted(nodes_all, xp.max(), side="right"))
            nodes, ds = nodes_all[:m], ds_all[:m]
            below = nodes[None, :] <= xp
            # nodes above x give 1 (masked below); dividing by max(x, node) keeps a tiny x
            # (radius floors of 1e-300) from overflowing node / x
            q = nodes[None, :] / np.maximum(xp, nodes[None, :])
            # a node at x itself contributes asin(1) (x exactly on a node: k includes its slope)
            asin = np.arcsin(q)
            asin_sum = row_sums(np.where(below, ds[None, :] * asin, 0.0), nodes_all.size)
            s_k = self._slopes[k_all[start:start + chunk][pos]]
            base = 0.5 * np.pi * s_k - asin_sum
            out[start:start + chunk][pos] = xs[pos] * base
            if slope is None and integral is None:
                continue
            with np.errstate(divide="ignore", invalid="ignore"):
                root = np.sqrt((xp - nodes[None, :]) * (xp + nodes[None, :]))
                if slope is not None:
                    cusp = np.where(below, ds[None, :] * nodes[None, :] / root, 0.0)
                    slope[start:start + chunk][pos] = base + row_sums(cusp, nodes_all.size)
                if integral is not None:
                    # the terms of _linear_g_integral, the same operations in the same order
                    P = 0.5 * (nodes[None, :] * root + xp**2 * asin)
                    integral[start:start + chunk][pos] = (
                        s_k * 0.25 * np.pi * xs[pos] ** 2
                        - row_sums(np.where(below, ds[None, :] * P, 0.0), nodes_all.size))
        return (_unsorted(out, order, x.shape),
                None if slope is None else _unsorted(slope, order, x.shape),
                None if integral is None else _unsorted(integral, order, x.shape))

    def _linear_g_integral(self, a: np.ndarray) -> np.ndarray:
        self._guard(a, "a")
        a = np.asarray(a, dtype=float)
        tree = self._far_tree()
        if tree is not None:
            return cast(np.ndarray, self._far_pass(tree, a, False, False, True)[2])
        flat, order = _sorted(a)
        out = np.zeros(flat.size)
        # summation by parts of Σ_i s_i ∫_{r_i}^{min(r_{i+1},a)} sqrt(a²-r²) dr: with
        # P_a(r) = (r sqrt(a²-r²) + a² asin(r/a))/2 and P_a(a) = πa²/4,
        # ∫_0^a g = s_k πa²/4 − Σ_{r_j <= a} Δs_j P_a(r_j) (only nodes with a slope jump)
        jump = self._dslope != 0
        nodes_all = self.r[1:-1][jump]
        ds_all = self._dslope[jump]
        k_all = _clip_index(np.searchsorted(self.r, flat, side="right") - 1, 0, self._slopes.size - 1)
        chunk = _rows_per_chunk(nodes_all.size)
        for start in range(0, flat.size, chunk):
            aa = flat[start:start + chunk]
            pos = aa > 0
            if not pos.any():
                continue
            ap = aa[pos][:, None]
            m = int(np.searchsorted(nodes_all, ap.max(), side="right"))
            nodes, ds = nodes_all[:m][None, :], ds_all[:m][None, :]
            below = nodes <= ap
            q = np.minimum(nodes / ap, 1.0)
            P = 0.5 * (nodes * np.sqrt(np.maximum((ap - nodes) * (ap + nodes), 0.0))
                       + ap**2 * np.arcsin(q))
            out[start:start + chunk][pos] = (
                self._slopes[k_all[start:start + chunk][pos]] * 0.25 * np.pi * aa[pos] ** 2
                - row_sums(np.where(below, ds * P, 0.0), nodes_all.size))
        return _unsorted(out, order, a.shape)

    def _linear_xg_integral(self, a: np.ndarray) -> np.ndarray:
        """``∫_0^a x g(x) dx`` (m³) of the interpolant in closed form, O(nodes below a) per point.

        With ``g = x [s_0 π/2 + Σ_{r_j<x} Δs_j acos(r_j/x)]`` (linear; the spline's node terms
        likewise, see :meth:`_cubic_sums`) every node contributes elementary integrals
        (``b = r_j``, ``s = sqrt(a² - b²)``, ``θ = acos(b/a)``, ``L = asinh(s/b)``):

        * ``P2 = ∫_b^a x² acos(b/x) dx = a³θ/3 - (b/6)(a s + b² L)``,
        * ``Q2 = ∫_b^a x² sqrt(x² - b²) dx = a(2a² - b²) s/8 - b⁴ L/8``,
        * ``P4 = ∫_b^a x⁴ acos(b/x) dx = a⁵θ/5 - (b/5)(a³ s/4 + 3b² (a s + b² L)/8)``.

        The quadratures this replaces (torsion's sliding torque, the spring foundation's
        ``∫_0^x s g(s) ds``) could not converge across thousands of square-root cusps.
        """
        a = np.asarray(a, dtype=float)
        flat = a.ravel()
        out = np.zeros(flat.size)
        jump = self._dslope != 0
        nodes_all = self.r[1:-1][jump]
        ds_all = self._dslope[jump]
        chunk = max(1, _CHUNK // max(nodes_all.size, 1))
        for start in range(0, flat.size, chunk):
            aa = flat[start:start + chunk]
            pos = aa > 0
            if not pos.any():
                continue
            av = aa[pos]
            m = int(np.searchsorted(nodes_all, av.max(), side="left"))
            ap = av[:, None]
            b, ds = nodes_all[:m][None, :], ds_all[:m][None, :]
            P2 = self._node_moments(ap, b)[0]
            out[start:start + chunk][pos] = (np.pi / 6.0 * self._slopes[0] * av**3
                                             + row_sums(np.where(b < ap, ds * P2, 0.0),
                                                        nodes_all.size))
        return out.reshape(a.shape)

    def _linear_pressure_shape(self, r: np.ndarray, a: np.ndarray, rtol: float
                                      ) -> tuple[np.ndarray, np.ndarray] | None:
        """``S(r, a) = ∫_r^a g'(x)/sqrt(x²-r²) dx`` of the linear interpolant, term by term.

        The interpolant is a cone of slope ``s_0`` plus truncated cones ``Δs_j (r - r_j)_+`` at the
        interior nodes, so ``S = s_0 (π/2) arccosh(a/r) + Σ_j Δs_j S_j`` with
        ``h_j'(x) = arccos(r_j/x) + r_j/sqrt(x²-r_j²)`` and

        * ``r > r_j``: ``S_j = ∫_0^{arccosh(a/r)} h_j'(r cosh u) du``,
        * ``r < r_j``: ``S_j = ∫_0^{arccosh(a/r_j)} r_j (1 + sinh v gd(v)) / sqrt(r_j² cosh²v - r²) dv``,

        both with bounded, smooth integrands (one batched tanh-sinh quadrature). At a node
        (``r = r_j``, a slope jump) the pressure is logarithmically infinite: ``±inf``. Cost
        O(number of nodes below ``a``) per radius. Returns ``None`` for the cubic spline (which
        takes the generic route).
        """
        from ...numeric.quadrature import tanh_sinh
        r, a = np.broadcast_arrays(np.asarray(r, float), np.asarray(a, float))
        out = np.zeros(r.shape)
        err = np.zeros(r.shape)
        inside = r < a
        if not np.any(inside):
            return out, err
        self._guard(a[inside], "a")
        rr, aa = r[inside], a[inside]
        s0 = self._slopes[0]
        if s0 != 0:             # (a flat first segment has no tip term, also on the axis)
            with np.errstate(divide="ignore"):
                val = s0 * 0.5 * np.pi * np.arccosh(aa / np.where(rr > 0, rr, 0.0))
        else:
            val = np.zeros(rr.shape)
        er = np.zeros(rr.shape)
        keep = self._dslope != 0
        nodes, ds = self.r[1:-1][keep], self._dslope[keep]
        chunk = max(1, 200_000 // max(nodes.size, 1))
        for start in range(0, rr.size, chunk):
            rc, ac = rr[start:start + chunk], aa[start:start + chunk]
            ip, jn = np.nonzero(nodes[None, :] < ac[:, None])
            if ip.size == 0:
                continue
            rp, ap, b, w = rc[ip], ac[ip], nodes[jn], ds[jn]
            hit = rp == b
            above = rp > b
            with np.errstate(divide="ignore", invalid="ignore"):
                hi = np.where(above, np.arccosh(ap / np.where(above, rp, 1.0)),
                              np.arccosh(ap / b))
            hi = np.where(hit, 0.0, hi)

            def integrand(t: np.ndarray, idx: np.ndarray, rp: np.ndarray = rp,
                          b: np.ndarray = b, above: np.ndarray = above) -> np.ndarray:
                rv, bv = rp[idx][:, None], b[idx][:, None]
                up = above[idx][:, None]
                ch, sh = np.cosh(t), np.sinh(t)
                x = rv * ch
                with np.errstate(divide="ignore", invalid="ignore"):
                    root = np.sqrt(np.maximum((x - bv) * (x + bv), 0.0))
                    f_above = np.arctan2(root, bv) + bv / root
                    q = np.sqrt(np.maximum((bv * ch - rv) * (bv * ch + rv), 0.0))
                    f_below = bv * (1.0 + sh * np.arctan(sh)) / q
                return np.where(up, f_above, f_below)

            res = tanh_sinh(integrand, np.zeros_like(hi), hi, rtol=rtol, raise_on_failure=False)
            terms = w * res.value
            terms = np.where(hit, np.sign(w) * np.inf, terms)
            part = np.zeros(rc.size)
            np.add.at(part, ip, terms)
            e = np.zeros(rc.size)
            np.add.at(e, ip, np.abs(w) * res.error)
            val[start:start + chunk] += part
            er[start:start + chunk] += e
        out[inside] = val
        err[inside] = er
        return out, err

    def _linear_abel_g(self, r: np.ndarray, a: np.ndarray, rtol: float
                              ) -> tuple[np.ndarray, np.ndarray] | None:
        """``A(r, a) = (2/π) ∫_0^{asin(min(1,a/r))} g(r sinθ) dθ`` of the linear interpolant.

        Inside the contact ``A = f(r)``. Outside, term by term over the cone plus truncated cones
        (``h_j(x) = x arccos(r_j/x)`` for ``x > r_j``), with ``θ_a = asin(a/r)``:
        ``A = s_0 r (1 - cos θ_a) + (2/π) Σ_j Δs_j ∫_{θ_j}^{θ_a} r sinθ arccos(r_j/(r sinθ)) dθ``,
        ``θ_j = asin(r_j/r)``. Each integrand is smooth inside its interval (the kink of ``h_j``
        sits at the lower end): one batched tanh-sinh quadrature. Returns ``None`` for the cubic
        spline.
        """
        from ...numeric.quadrature import tanh_sinh
        r, a = np.broadcast_arrays(np.asarray(r, float), np.asarray(a, float))
        out = np.zeros(r.shape)
        err = np.zeros(r.shape)
        inside = (r <= a) & (r > 0)
        if np.any(inside):
            out[inside] = self._height(r[inside])
        outside = r > a
        if not np.any(outside):
            return out, err
        self._guard(a[outside], "a")
        ro, ao = r[outside], a[outside]
        th_a = np.arcsin(ao / ro)
        cone = self._slopes[0] * ro * (1.0 - np.cos(th_a))
        val = np.zeros(ro.shape)
        er = np.zeros(ro.shape)
        keep = self._dslope != 0
        nodes, ds = self.r[1:-1][keep], self._dslope[keep]
        chunk = max(1, 200_000 // max(nodes.size, 1))
        for start in range(0, ro.size, chunk):
            rc, ac, tc = ro[start:start + chunk], ao[start:start + chunk], th_a[start:start + chunk]
            ip, jn = np.nonzero(nodes[None, :] < ac[:, None])
            if ip.size == 0:
                continue
            rp, b, w = rc[ip], nodes[jn], ds[jn]
            lo = np.arcsin(b / rp)

            def integrand(th: np.ndarray, idx: np.ndarray, rp: np.ndarray = rp,
                          b: np.ndarray = b) -> np.ndarray:
                x = rp[idx][:, None] * np.sin(th)
                bv = b[idx][:, None]
                root = np.sqrt(np.maximum((x - bv) * (x + bv), 0.0))
                return x * np.arctan2(root, bv)

            res = tanh_sinh(integrand, lo, tc[ip], rtol=rtol, raise_on_failure=False)
            part = np.zeros(rc.size)
            np.add.at(part, ip, w * res.value)
            e = np.zeros(rc.size)
            np.add.at(e, ip, np.abs(w) * res.error)
            val[start:start + chunk] += part
            er[start:start + chunk] += e
        out[outside] = cone + 2.0 / np.pi * val
        err[outside] = 2.0 / np.pi * er
        return out, err
