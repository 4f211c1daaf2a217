"""One depth on a small linear table in plain floats (the single-load route of ``normal()``).

A linear :class:`~contactlab.profiles.tabulated.Tabulated` gives its exact transform as sums over
the slope jumps of its nodes (``g = x [s_k π/2 − Σ Δs_j asin(r_j/x)]``, its slope and ``∫g``
likewise). For a batch the table's kernels sort the points, cut them into chunks, mask the
nodes above each point and scatter the results back; for one point on a few nodes that
bookkeeping (some thirty small array operations per pass, two or three passes per solve) costs
more than the sums. Here the same solve runs for one depth with the node terms as short arrays
and everything else in floats: the same node interval (the memoised node values), the same
Newton iteration in ``u`` (:func:`~contactlab.profiles.tabulated._solve._newton_one`), the same
terms with numpy's ``arcsin`` and square root on the same values, summed by the same
:func:`~contactlab.numeric.fixed_sums.row_sums`: the array route's radius, ``∫g``, force and
error estimate, bit for bit (``tests/unit/physics/test_normal_table_scalar.py``).

Taken only where the array route would take those steps (:func:`table_scalar_ok`): a linear,
monotone table of at most :data:`MAX_NODES` nodes, without smoothing bands, whose class is
:class:`~contactlab.profiles.tabulated.Tabulated` itself. Anything else (a depth beyond the
table, a Newton iteration that would hand over to the bracketed fallback) returns ``None`` and the
array route runs, and raises where it should.
"""
from __future__ import annotations

import math
from bisect import bisect_left, bisect_right
from typing import Any

import numpy as np

from ..numeric.fixed_sums import BLOCK, row_sums
from ..profiles.base import ROUNDING, root_rtol

__all__ = ["table_scalar_ok", "solve_depth_table", "g_integral_table", "table_force_rel_error",
           "MAX_NODES"]

#: tables of at most this many nodes take the float route: every node is one of the memoised
#: coarse nodes (65), so the node interval is read off them, and the slope jumps fit one
#: summation block of :func:`row_sums`
MAX_NODES = min(65, BLOCK)

_KEY = "_scalar_table_parts"
_HALF_PI = 0.5 * np.pi


def _parts(profile: Any) -> tuple | None:
    """The table's node lists (kept on the profile: the table is immutable), or None where the
    float route does not apply."""
    got = profile.__dict__.get(_KEY, False)
    if got is not False:
        return got
    got = None
    from ..profiles.tabulated import Tabulated
    if (type(profile) is Tabulated and profile._spline is None and profile._monotone_f
            and profile.r.size <= MAX_NODES and profile._smoothing_band() is None
            and profile._far_tree() is None):
        jump = profile._dslope != 0
        nodes = np.array(profile.r[1:-1][jump], dtype=float)
        ds = np.array(profile._dslope[jump], dtype=float)
        coarse = profile._coarse_nodes()
        node_g = profile._node_g
        if coarse.size == profile.r.size and node_g is not None:
            got = (profile.r.tolist(), profile._slopes.tolist(), nodes, ds, nodes.tolist(),
                   int(nodes.size), node_g[coarse].tolist(), profile._dslope.tolist())
    profile.__dict__[_KEY] = got
    return got


def table_scalar_ok(profile: Any) -> bool:
    """Whether one depth on ``profile`` may take :func:`solve_depth_table` (kept on the
    profile)."""
    return _parts(profile) is not None


def _terms(parts: tuple, x: float) -> tuple[float, np.ndarray, np.ndarray, int]:
    """``(s_k, nodes, ds, m)``: the slope at ``x`` and the ``m`` slope-jump nodes ``<= x``."""
    r, slopes, nodes_all, ds_all, nodes_list = parts[:5]
    k = min(max(bisect_right(r, x) - 1, 0), len(slopes) - 1)
    m = bisect_right(nodes_list, x)
    return slopes[k], nodes_all[:m], ds_all[:m], m


def _g_and_slope_one(parts: tuple, x: float) -> tuple[float, float]:
    """``(g, g')`` at one ``0 < x <= r[-1]``: the operations of the table's arcsine pass on a
    point alone (the nodes above ``x`` masked out there are not formed here; their terms are
    the zeros that :func:`row_sums` pads)."""
    s_k, nodes, ds, m = _terms(parts, x)
    total = parts[5]
    if m:
        xp = np.array([[x]])
        nd = nodes[None, :]
        asin = np.arcsin(nd / np.maximum(xp, nd))
        asin_sum = float(row_sums(ds[None, :] * asin, total)[0])
        with np.errstate(divide="ignore", invalid="ignore"):
            root = np.sqrt((xp - nd) * (xp + nd))
            cusp = float(row_sums(ds[None, :] * nd / root, total)[0])
    else:
        asin_sum = cusp = 0.0         # (row_sums of no terms)
    base = _HALF_PI * s_k - asin_sum
    return x * base, base + cusp


def g_integral_table(profile: Any, a: float) -> float:
    """``∫_0^a g`` (m²) at one ``0 < a <= r[-1]`` of a table with :func:`table_scalar_ok`: the
    operations of its closed form on a point alone."""
    parts = profile.__dict__[_KEY]
    s_k, nodes, ds, m = _terms(parts, a)
    total = parts[5]
    if m:
        ap = np.array([[a]])
        nd = nodes[None, :]
        q = np.minimum(nd / ap, 1.0)
        P = 0.5 * (nd * np.sqrt(np.maximum((ap - nd) * (ap + nd), 0.0)) + ap**2 * np.arcsin(q))
        tail = float(row_sums(ds[None, :] * P, total)[0])
    else:
        tail = 0.0                    # (row_sums of no terms)
    return s_k * 0.25 * np.pi * (a * a) - tail      # (numpy's square of a: a·a)


def solve_depth_table(profile: Any, d: float, rtol: float) -> float | None:
    """Contact radius (m) of one depth ``d > 0`` (m) on a table with :func:`table_scalar_ok`,
    or ``None`` (the array route then runs, and raises where this one would)."""
    from ..profiles.tabulated._solve import _newton_one
    parts = profile.__dict__[_KEY]
    r, node_g, dslope = parts[0], parts[6], parts[7]
    if not d <= node_g[-1]:
        return None                 # beyond the table: the array route raises
    j = min(max(bisect_left(node_g, d), 1), len(node_g) - 1)
    lo, hi = j - 1, j
    x0, h = r[lo], r[hi] - r[lo]
    cusp = (dslope[lo - 1] if lo >= 1 else 0.0) * math.sqrt(2.0 * h * x0)

    def value_and_slope(x: np.ndarray) -> tuple[list[float], list[float]]:
        v, dv = _g_and_slope_one(parts, float(x[0]))
        return [v], [dv]

    a = _newton_one(x0, h, d, node_g[lo], node_g[hi], 0.5 * root_rtol(rtol), value_and_slope,
                    cusp)
    if a is None or not 0 < a < r[-1]:
        return None
    return a


def table_force_rel_error(E_star: float, a: float, d: float, g_int: float, F: float) -> float:
    """Relative force error of one depth on a table: the array route's operations (the
    rounding of ``a d - ∫g`` and of ``∫g``, whose error is its rounding floor)."""
    g_int_err = ROUNDING * abs(g_int)
    F_err = ((abs(a * d) + abs(g_int)) * ROUNDING + abs(g_int_err)) * (2.0 * E_star)
    return float(F_err / F) if F > 0 else 0.0
