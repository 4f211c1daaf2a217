"""Solving a table for its contact radius: node search, then Newton across one node interval.

Depth (``g(a) = d``) and force (``a g(a) - ∫_0^a g = F/(2E*)``) are solved on the memoised node
values first, then inside the node interval in a variable that removes the square-root cusp of
g; tables whose g may decrease are solved for the first crossing and checked for annular
contacts. A spline table starts the Newton step from the cubic Hermite interpolant of the node
values and node slopes (g' memoised with g: one pass mostly suffices), and its force steps on
the column tree sum the signed columns only, the rounding estimate checked once at the radius.
From the second batch on a table with at least one load per :data:`_FILL_PER_LOAD` nodes,
every node is evaluated in one pass (the values per node are the same bits however grouped).
Private: the public class is :class:`~contactlab.profiles.tabulated.Tabulated`, which
dispatches here.
"""
from __future__ import annotations

import math
from typing import cast

import numpy as np

from ...errors import OutsideTheoryError
from ._base import _TableBase, _clip_index

#: safety factor on the error predicted from quadratic convergence (|step|³/prev²) before a
#: Newton iteration of :meth:`_TableSolver._newton_on_node_interval` stops without a further
#: pass over the nodes
_NEWTON_MARGIN = 100.0
#: Newton steps on the cubic Hermite interpolant of a spline table's node interval (the start
#: of its contact-radius solves): from the linear fraction, off by ~h/a, three steps reach
#: rounding (h the node spacing, a the radius)
_HERMITE_STEPS = 3
#: the second (and any later) batch of loads on a table evaluates g (or the reduced force) at
#: every node not yet memoised when there are at most this many per load: a fresh load's node
#: search evaluates 2-3 nodes (two calls of the pairs test), so the whole table costs at most
#: ~6 such searches, once
_FILL_PER_LOAD = 16


def _hermite_start(target: np.ndarray, v0: np.ndarray, v1: np.ndarray, s0: np.ndarray,
                   s1: np.ndarray, h: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``(t, ok)``: the fraction ``t`` of node intervals where the cubic Hermite interpolant of
    ``v`` (end values ``v0, v1``, end slopes ``dv/dx = s0, s1``, width ``h``) meets ``target``,
    by :data:`_HERMITE_STEPS` Newton steps on the cubic from the linear fraction; ``ok`` where
    it is finite and inside ``[0, 1]`` (else the caller keeps its own start)."""
    with np.errstate(all="ignore"):
        dv = v1 - v0
        c1 = h * s0
        c2 = 3.0 * dv - 2.0 * c1 - h * s1
        c3 = c1 + h * s1 - 2.0 * dv
        rhs = target - v0
        t = rhs / dv
        for _ in range(_HERMITE_STEPS):
            p = ((c3 * t + c2) * t + c1) * t - rhs
            dp = (3.0 * c3 * t + 2.0 * c2) * t + c1
            t = t - p / dp
        ok = (dv > 0) & np.isfinite(t) & (t >= 0) & (t <= 1)
    return t, ok


def _hermite_start_one(target: float, v0: float, v1: float, s0: float, s1: float, h: float
                       ) -> float | None:
    """:func:`_hermite_start` for one element in plain floats (the same IEEE operations in the
    same order), or None where it is not ``ok``."""
    dv = v1 - v0
    if not dv > 0:
        return None
    c1 = h * s0
    c2 = 3.0 * dv - 2.0 * c1 - h * s1
    c3 = c1 + h * s1 - 2.0 * dv
    rhs = target - v0
    t = rhs / dv
    for _ in range(_HERMITE_STEPS):
        p = ((c3 * t + c2) * t + c1) * t - rhs
        dp = (3.0 * c3 * t + 2.0 * c2) * t + c1
        if dp == 0:
            return None         # (the batch's inf or nan fraction: not ok there either)
        t = t - p / dp
    return t if math.isfinite(t) and 0 <= t <= 1 else None


def _newton_one(x0: float, h: float, target: float, v0: float, v1: float, tol: float,
                value_and_slope, cusp: float | None,
                slopes: tuple[float, float] | None = None) -> float | None:
    """:meth:`_TableSolver._newton_on_node_interval` for one element in plain floats: the same
    IEEE operations in the same order (``u ** 2`` as ``u * u``, which numpy's square is; the
    cube of the convergence test through numpy's power on a one-element array, as on the
    batch), so the same radius bit for bit; None where the batch's bracketed fallback would run
    (the caller then takes the array route, which runs it)."""
    if v1 > v0:
        u = math.sqrt(min(max((target - v0) / (v1 - v0), 1e-12), 1.0))
    else:
        u = math.sqrt(0.25)
    if cusp is not None:
        c = target - v0
        beta = (v1 - v0) - cusp
        disc = cusp * cusp + 4.0 * beta * c
        if v1 > v0 and disc >= 0:
            den = cusp + math.sqrt(disc)
            if den != 0:
                uq = 2.0 * c / den
                if math.isfinite(uq) and 0 < uq <= 1:
                    u = uq
    if slopes is not None:
        t = _hermite_start_one(target, v0, v1, slopes[0], slopes[1], h)
        if t is not None:
            u = math.sqrt(min(max(t, 1e-12), 1.0))
    prev = math.inf
    for _ in range(6):
        x = x0 + h * (u * u)
        v, dv = value_and_slope(np.array([x]))
        v, dv = float(v[0]), float(dv[0])
        den = dv * 2 * h * u
        if den == 0 or not (math.isfinite(den) and math.isfinite(v)):
            return None             # (inf or nan steps: the batch's own handling)
        step = (v - target) / den
        u_new = u - step
        ok = math.isfinite(u_new) and 0 < u_new <= 1
        if ok:
            u = u_new
        size = abs(step)
        if math.isfinite(prev) and size <= 0.1 * prev:
            cube = float(np.power(np.array([size]), 3)[0])
            left = _NEWTON_MARGIN * (cube / (prev * prev))
        else:
            left = math.inf
        scale = 2 * h * u
        bound = tol * (x0 + h * (u * u))
        conv = ok and (size * scale <= bound or left * scale <= bound)
        prev = size if ok else math.inf
        if conv:
            return x0 + h * u * u
    return None


class _TableSolver(_TableBase):
    """Contact-radius solvers of a table (private helpers only)."""

    def _grid_g(self) -> tuple[np.ndarray, np.ndarray]:
        """g on the nodes and interval midpoints (cached; O(N²), built only for tables whose
        interpolant is not monotone, where the first crossing g = d must be located)."""
        cached = self.__dict__.get("_grid_cache")
        if cached is None:
            grid = np.sort(np.concatenate([self.r, 0.5 * (self.r[1:] + self.r[:-1])]))
            cached = (grid, self._g(grid))
            self.__dict__["_grid_cache"] = cached
        return cached

    def _solve_radius_first_crossing(self, d: np.ndarray, rtol: float) -> np.ndarray:
        """Smallest ``a`` with ``g(a) = d`` for tables whose g may decrease somewhere: bisection
        could land beyond a dip that lies outside the true contact, so the first crossing is
        located on the cached node/midpoint grid (the one the ring-contact check needs anyway)."""
        from ..base import root_rtol
        grid, g = self._grid_g()
        running = np.maximum.accumulate(g)
        i = np.searchsorted(running, d, side="left")
        if np.any(i >= grid.size):
            k = int(np.argmax(i >= grid.size))
            raise OutsideTheoryError(
                f"depth={float(d.ravel()[k])!r} m needs a contact radius beyond the table (last "
                f"radius {self.r[-1]!r} m); extend the measured profile or reduce the load.")
        i = np.maximum(i, 1)
        from ...numeric.roots import bracketed_root
        return bracketed_root(lambda x, idx: self._g(x), d, grid[i - 1], grid[i],
                              rtol=root_rtol(rtol), what="contact radius")

    def _solve_table_radius(self, d: np.ndarray, limit: float, rtol: float | None = None) -> np.ndarray:
        """g(a) = d for the linear interpolant: a search over the nodes, then a smooth solve.

        The node interval holding ``a`` is found by safeguarded interpolation search (g is nearly
        linear across many nodes; each step tests the two nodes around the guess in one call and
        alternates with bisection when the bracket does not halve), typically 2-3 calls instead
        of ``log2(N)`` bisections. Between two nodes g is analytic except for the
        ``sqrt(x - r_k)`` kink at the left node, which ``x = r_k + (r_{k+1} - r_k) u²`` removes,
        so the bracketed solve in ``u`` (started with the memoised node values) converges
        superlinearly. The cubic spline takes the generic route.
        """
        if not self._monotone_f:
            return self._solve_radius_first_crossing(d, self.rtol if rtol is None else rtol)
        from ...errors import OutsideTheoryError
        from ..base import root_rtol
        rtol = self.rtol if rtol is None else rtol
        flat = np.asarray(d, dtype=float).ravel()
        coarse = self._coarse_nodes()               # includes the last node
        self._fill_nodes(self._g_at_nodes, self._node_g, flat.size, "g")
        node_g = cast(np.ndarray, self._node_g)     # (set by _coarse_nodes)
        g_end = float(node_g[-1])
        if np.any(flat > g_end):
            i = int(np.argmax(flat > g_end))
            raise OutsideTheoryError(
                f"depth={flat[i]!r} m needs a contact radius >= max_radius={limit!r} m of "
                f"{self!r}; reduce the depth/force.")
        # bracket from the cached coarse node grid (65 nodes, computed once per table)
        j = _clip_index(np.searchsorted(node_g[coarse], flat, side="left"), 1, coarse.size - 1)
        lo, hi = coarse[j - 1], coarse[j]
        g_lo, g_hi = node_g[lo].copy(), node_g[hi].copy()
        lo, hi = self._node_search(self._g_at_nodes, flat, lo, hi, g_lo, g_hi)
        slopes = ((self._node_slopes(lo), self._node_slopes(hi)) if self._hermite_nodes()
                  else None)
        return self._newton_on_node_interval(
            flat, lo, hi, self._g_at_nodes(lo), self._g_at_nodes(hi), 0.5 * root_rtol(rtol),
            self._g_and_slope, self._g, cusp=self._cusp_in_u(lo, hi),
            slopes=slopes).reshape(np.shape(d))

    def _cusp_in_u(self, lo: np.ndarray, hi: np.ndarray) -> np.ndarray:
        """Leading term ``α u`` of g across node intervals ``[r[lo], r[hi]]`` in ``u`` (``x = r_lo
        + h u²``): the left node's slope jump gives ``x Δs acos(r_lo/x) ≈ Δs sqrt(2 h r_lo) u``
        (0 on the axis, which carries no jump). The cubic spline's g has no cusp: 0."""
        x0, h = self.r[lo], self.r[hi] - self.r[lo]
        if self._spline is not None or self._dslope.size == 0:
            return np.zeros(x0.shape)       # (two nodes: no interior node, no slope jump)
        ds = np.where(lo >= 1, self._dslope[np.maximum(lo - 1, 0)], 0.0)
        return ds * np.sqrt(2.0 * h * x0)

    @staticmethod
    def _node_search(at_nodes, target: np.ndarray, lo: np.ndarray, hi: np.ndarray,
                     v_lo: np.ndarray, v_hi: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Narrow node brackets ``[lo, hi]`` of an increasing node function to adjacent nodes.

        Safeguarded interpolation search: guess the node from the bracket values, test the two
        nodes around the guess in one call of ``at_nodes`` (memoised), alternate with a bisection
        step whenever the bracket did not halve.
        """
        interpolate = True
        while True:
            open_ = np.flatnonzero(hi - lo > 1)
            if open_.size == 0:
                break
            lo_o, hi_o = lo[open_], hi[open_]
            if interpolate:
                # the function is nearly linear across a coarse bracket: guess the node interval
                # from the bracket values and test both of its nodes in one call
                with np.errstate(divide="ignore", invalid="ignore"):
                    frac = (target[open_] - v_lo[open_]) / (v_hi[open_] - v_lo[open_])
                frac = np.where(np.isfinite(frac), frac, 0.5)
                k = lo_o + np.floor(frac * (hi_o - lo_o)).astype(np.intp)
                k = np.clip(k, lo_o, hi_o - 1)
                pair = at_nodes(np.concatenate([k, k + 1])).reshape(2, -1)
                below_k = pair[0] < target[open_]
                below_k1 = pair[1] < target[open_]
                # keep the tighter of the two tested nodes on each side of the target
                new_lo = np.where(below_k1, k + 1, np.where(below_k, k, lo_o))
                new_hi = np.where(~below_k, k, np.where(~below_k1, k + 1, hi_o))
                v_lo[open_] = np.where(below_k1, pair[1], np.where(below_k, pair[0], v_lo[open_]))
                v_hi[open_] = np.where(~below_k, pair[0], np.where(~below_k1, pair[1], v_hi[open_]))
                shrunk = (new_hi - new_lo) <= 0.5 * (hi_o - lo_o)
                lo[open_], hi[open_] = new_lo, new_hi
                interpolate = bool(np.all(shrunk))   # else alternate with a bisection step
            else:
                mid = (lo_o + hi_o) // 2
                v_mid = at_nodes(mid)
                below = v_mid < target[open_]
                lo[open_] = np.where(below, mid, lo_o)
                hi[open_] = np.where(below, hi_o, mid)
                v_lo[open_] = np.where(below, v_mid, v_lo[open_])
                v_hi[open_] = np.where(below, v_hi[open_], v_mid)
                interpolate = True
        return lo, hi

    def _reduced_force_at_nodes(self, idx: np.ndarray) -> np.ndarray:
        """``H = a g(a) - ∫_0^a g`` (force / 2E*) at table nodes, memoised like g."""
        cache = self.__dict__.get("_node_H")
        if cache is None:
            cache = np.full(self.r.size, np.nan)
            self.__dict__["_node_H"] = cache
        vals = cache[idx]
        missing = np.isnan(vals)
        if np.any(missing):
            new = np.unique(idx[missing])
            x = self.r[new]
            if self._hermite_nodes():
                # g, g' and ∫g in one pass: g' kept for the Hermite start (the same bits of g)
                g, gp, integral = self._cubic_g_slope_integral(x)
                self._store_node_slopes(new, g, gp)
                cache[new] = x * g - integral
            else:
                with self._cubic_shared_pass():    # (a spline on the column tree: one pass)
                    cache[new] = x * self._g_at_nodes(new) - self._g_integral_closed_form(x)
            vals = cache[idx]
        return vals

    def _fill_nodes(self, at_nodes, memo: np.ndarray | None, loads: int, what: str) -> None:
        """Evaluate the node function at every node not yet memoised, in one pass, from the
        second batch on the table (``what``: "g" or "H") with at most :data:`_FILL_PER_LOAD`
        times as many missing nodes as ``loads``: a table that serves batches again and again
        (a fit, a sweep) then searches without evaluating anything, and a table used once pays
        nothing extra. A node's value does not depend on the other points of its pass, so this
        changes no bit, only when the work is done."""
        if memo is None or self.r.size > _FILL_PER_LOAD * loads:
            return
        seen = self.__dict__.setdefault("_node_batches", {})
        seen[what] = seen.get(what, 0) + 1
        if seen[what] < 2:
            return
        missing = np.flatnonzero(np.isnan(memo))
        if 0 < missing.size <= _FILL_PER_LOAD * loads:
            at_nodes(missing)

    def _hermite_nodes(self) -> bool:
        """Whether the radius solves start from the cubic Hermite interpolant of the node values
        (a spline table on its closed-form route: g is smooth across the nodes; g' is memoised
        with g at every node the solves visit)."""
        return self._spline is not None and self.g_route == "closed_form"

    def _store_node_slopes(self, new: np.ndarray, g: np.ndarray, gp: np.ndarray) -> None:
        """Memoise g (where missing) and g' at the nodes ``new`` (unique indices)."""
        if self._node_g is None:
            self._node_g = np.full(self.r.size, np.nan)
        gp_memo = self.__dict__.get("_node_gp")
        if gp_memo is None:
            gp_memo = np.full(self.r.size, np.nan)
            self.__dict__["_node_gp"] = gp_memo
        miss = np.isnan(self._node_g[new])
        self._node_g[new[miss]] = g[miss]
        gp_memo[new] = gp

    def _node_slopes(self, idx: np.ndarray) -> np.ndarray:
        """g' at table nodes ``r[idx]`` (spline tables), memoised like g."""
        memo = self.__dict__.get("_node_gp")
        vals = memo[idx] if memo is not None else np.full(idx.size, np.nan)
        missing = np.isnan(vals)
        if np.any(missing):
            new = np.unique(idx[missing])
            g, gp = self._g_and_slope(self.r[new])
            self._store_node_slopes(new, g, gp)
            vals = self.__dict__["_node_gp"][idx]
        return vals

    def _table_radius_of_reduced_force(self, target: np.ndarray, rtol: float) -> np.ndarray | None:
        """Contact radius with ``a g(a) - ∫_0^a g = target`` (= F/(2E*)), or None (generic route).

        The same scheme as :meth:`_solve_radius`: node search on the memoised values, then Newton
        in ``u`` with ``dH/da = a g'(a)``; used for convex linear tables only.
        """
        if not self._monotone_f:
            return None
        from ...errors import OutsideTheoryError
        from ..base import root_rtol
        r = self.r
        flat = np.asarray(target, dtype=float).ravel()
        coarse = self._coarse_nodes()
        H_c = self._reduced_force_at_nodes(coarse)
        self._fill_nodes(self._reduced_force_at_nodes, self.__dict__["_node_H"], flat.size, "H")
        if np.any(flat > H_c[-1]):
            i = int(np.argmax(flat > H_c[-1]))
            raise OutsideTheoryError(
                f"force/E* = {2 * float(flat[i]):.6g} m² needs a contact radius beyond the table "
                f"(last radius {float(r[-1])!r} m, which carries force/E* = "
                f"{2 * float(H_c[-1]):.6g} m²); extend the measured profile or reduce the force.")
        j = _clip_index(np.searchsorted(H_c, flat, side="left"), 1, coarse.size - 1)
        lo, hi = coarse[j - 1], coarse[j]
        lo, hi = self._node_search(self._reduced_force_at_nodes, flat, lo, hi,
                                   H_c[j - 1].copy(), H_c[j].copy())

        signed = self._hermite_nodes() and self._cubic_tree() is not None

        def value_and_slope(x: np.ndarray, full: bool = False
                            ) -> tuple[np.ndarray, np.ndarray]:
            if self._spline is None:
                # g, g' and ∫g of the linear interpolant in one pass (the same bits as apart)
                g, gp, integral = self._g_slope_integral(x)
            elif signed and not full:
                # the spline's column tree, signed columns only (checked at the radius below)
                g, gp, integral = cast(tuple, self._cubic_signed_pass(x))
            else:
                # (one pass over the spline's column tree for both, the same bits as apart)
                g, gp, integral = self._cubic_g_slope_integral(x)
            return x * g - integral, x * gp      # dH/da = a g'(a)

        def value(x: np.ndarray) -> np.ndarray:
            return x * self._g(x) - self._g_integral_closed_form(x)

        v0, v1 = self._reduced_force_at_nodes(lo), self._reduced_force_at_nodes(hi)
        cusp = self.r[lo] * self._cusp_in_u(lo, hi)
        slopes = ((r[lo] * self._node_slopes(lo), r[hi] * self._node_slopes(hi))
                  if self._hermite_nodes() else None)
        tol = 0.5 * root_rtol(rtol)
        a = self._newton_on_node_interval(flat, lo, hi, v0, v1, tol, value_and_slope, value,
                                          cusp=cusp, slopes=slopes)
        if self._spline is None:
            self._far_prime(a)          # (the depth and ∫g at these radii: one tree pass)
        if signed:
            # the rounding estimate of the node sums at the radii (one pass over every column,
            # kept for the depth and ∫g asked next); where it is too large (the Gauss rule takes
            # over there) the solve is redone on the full route
            bad = np.flatnonzero(self._cubic_prime(a))
            if bad.size:
                a[bad] = self._newton_on_node_interval(
                    flat[bad], lo[bad], hi[bad], v0[bad], v1[bad], tol,
                    lambda x: value_and_slope(x, full=True), value, cusp=cusp[bad],
                    slopes=(cast(tuple, slopes)[0][bad], cast(tuple, slopes)[1][bad]))
        return a.reshape(np.shape(target))

    def _newton_on_node_interval(self, target: np.ndarray, lo: np.ndarray, hi: np.ndarray,
                                 v0: np.ndarray, v1: np.ndarray, tol: float, value_and_slope,
                                 value, cusp: np.ndarray | None = None,
                                 slopes: tuple[np.ndarray, np.ndarray] | None = None
                                 ) -> np.ndarray:
        """Solve ``v(x) = target`` inside node intervals ``[r[lo], r[hi]]`` (``v`` increasing).

        Newton in ``u`` with ``x = r_lo + h u²`` (removes the square-root cusp of g at the left
        node), started from linear interpolation of ``v`` in ``x`` (dense tables: the smooth part
        dominates); each step costs one pass over the nodes for ``v`` and ``dv/dx`` together, and
        three to four steps reach ``tol``. Elements that leave ``[0, 1]`` or do not converge go to
        the bracketed solver on the same interval (``value`` only, end values known).
        """
        from ...numeric.roots import bracketed_root
        if target.size == 1:
            x1 = _newton_one(float(self.r[lo[0]]), float(self.r[hi[0]] - self.r[lo[0]]),
                             float(target[0]), float(v0[0]), float(v1[0]), tol, value_and_slope,
                             None if cusp is None else float(cusp[0]),
                             None if slopes is None else (float(slopes[0][0]),
                                                          float(slopes[1][0])))
            if x1 is not None:
                return np.array([x1])
        x0, h = self.r[lo], self.r[hi] - self.r[lo]
        with np.errstate(divide="ignore", invalid="ignore"):
            u = np.sqrt(np.clip(np.where(v1 > v0, (target - v0) / (v1 - v0), 0.25), 1e-12, 1.0))
            if cusp is not None:
                # start from the quadratic v0 + α u + β u² through both ends, α the left node's
                # square-root cusp (in u it is linear): one or two Newton passes fewer
                c = target - v0
                beta = (v1 - v0) - cusp
                disc = cusp * cusp + 4.0 * beta * c
                uq = 2.0 * c / (cusp + np.sqrt(disc))
                good = (v1 > v0) & (disc >= 0) & np.isfinite(uq) & (uq > 0) & (uq <= 1)
                u = np.where(good, uq, u)
            if slopes is not None:
                # a spline table: the cubic Hermite interpolant of v across the interval
                # (node slopes memoised with the node values) is off by ~(h/a)^4, so the first
                # Newton step mostly stops the iteration
                t, ok = _hermite_start(target, v0, v1, slopes[0], slopes[1], h)
                u = np.where(ok, np.sqrt(np.clip(t, 1e-12, 1.0)), u)
        done = np.zeros(target.size, dtype=bool)
        prev = np.full(target.size, np.inf)        # |previous Newton step| in u
        for _ in range(6):
            act = np.flatnonzero(~done)
            if act.size == 0:
                break
            x = x0[act] + h[act] * u[act] ** 2
            v, dv = value_and_slope(x)
            step = (v - target[act]) / (dv * 2 * h[act] * u[act])
            u_new = u[act] - step
            ok = np.isfinite(u_new) & (u_new > 0) & (u_new <= 1)
            u[act] = np.where(ok, u_new, u[act])
            size = np.abs(step)
            # quadratic convergence: the error left after this step is about C step², with C
            # estimated from the last two steps (step ≈ C prev²): |step|³/prev², taken with a
            # margin of _NEWTON_MARGIN and only while the steps contract by 10x or more
            pa = prev[act]
            with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
                left = np.where(np.isfinite(pa) & (size <= 0.1 * pa),
                                _NEWTON_MARGIN * (size**3 / pa**2), np.inf)
                scale = 2 * h[act] * u[act]
                bound = tol * (x0[act] + h[act] * u[act] ** 2)
                conv = ok & ((size * scale <= bound) | (left * scale <= bound))
            prev[act] = np.where(ok, size, np.inf)
            done[act[conv]] = True
        rest = np.flatnonzero(~done)
        if rest.size:
            def func(uu: np.ndarray, idx: np.ndarray) -> np.ndarray:
                return value(x0[rest][idx] + h[rest][idx] * uu * uu)

            u[rest] = bracketed_root(func, target[rest], np.zeros(rest.size), np.ones(rest.size),
                                     rtol=tol, what="contact radius", f_lo=v0[rest],
                                     f_hi=v1[rest])
        return x0 + h * u * u

    def _coarse_nodes(self) -> np.ndarray:
        """Indices of 65 evenly spaced nodes whose g is memoised once (the search's first bracket)."""
        idx = self.__dict__.get("_coarse_idx")
        if idx is None:
            idx = np.unique(np.linspace(0, self.r.size - 1, 65).round().astype(np.intp))
            self._g_at_nodes(idx)
            self.__dict__["_coarse_idx"] = idx
        return idx

    def _g_at_nodes(self, idx: np.ndarray) -> np.ndarray:
        """g at table nodes ``r[idx]``, memoised per node (the bisection revisits the same
        nodes for every depth; the table is immutable, so the cache never goes stale)."""
        if self._node_g is None:
            self._node_g = np.full(self.r.size, np.nan)
        vals = self._node_g[idx]
        missing = np.isnan(vals)
        if np.any(missing):
            new = np.unique(idx[missing])
            if self._hermite_nodes():
                # (with g' for the Hermite start: the same bits of g)
                g, gp = self._g_and_slope(self.r[new])
                self._store_node_slopes(new, g, gp)
            else:
                self._node_g[new] = self._g(self.r[new])
            vals = self._node_g[idx]
        return vals

    def _check_table_monotone(self, a_max: float, d_for_message: float) -> None:
        if self._monotone_f or a_max <= self._verified_upto:
            return
        grid, g = self._grid_g()
        upto = grid < a_max
        gg = np.append(g[upto], float(self._g(np.array(a_max))))
        xx = np.append(grid[upto], a_max)
        dg = np.diff(gg)
        scale = max(float(np.max(np.abs(gg))), 1e-300)
        bad = np.flatnonzero(dg < -1e-12 * scale)
        if not bad.size:
            self._verified_upto = a_max
        if bad.size:
            i = int(bad[0])
            raise OutsideTheoryError(
                f"depth={d_for_message!r} m: the transformed profile g(x) decreases at x="
                f"{xx[i]:.6g} m (g={gg[i]:.6g} m, then {gg[i + 1]:.6g} m), so beyond depth "
                f"{gg[i]:.6g} m the contact is an annulus, outside the MDR. Smooth the measured "
                "profile (Tabulated(..., smoothing='auto')), take the nearest admissible table "
                "(admissible='nearest', slopes made non-decreasing) or limit the load.")
