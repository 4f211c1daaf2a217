"""The traction of a punch density at a ring set's collocation points, by differences of the
traction antiderivatives tabulated once per ring set.

:func:`contactlab.physics.torsion_annulus.traction` with a
:class:`~contactlab.physics.torsion_annulus.NodeTable` as ``columns`` evaluates, for a density of
abutting pieces with nodes ``t_0 < … < t_m``, ``(4 G_t/π) r (ΔA @ α + ΔS @ β)`` where ``A``,
``S`` are the antiderivatives ``arccosh(t/r)`` and ``sqrt(t² − r²)`` at the nodes (columns taken
from the table where a node is one of its ring ends) and ``ΔA`` their differences between
neighbouring nodes. Most neighbouring nodes of the solver's densities are neighbouring ring ends,
whose differences do not change between steps: :func:`differences` tabulates them once per ring
set, and :func:`traction_at_points` takes them from there (the same subtraction of the same two
values, so the same bits; the other differences, at a node that is no ring end or between ring
ends that are not neighbours, computed as before). That saves the pass that formed ``ΔA`` and
``ΔS`` from the taken columns, a points × nodes array each, in every step the ring solver takes
(its start tractions) at the ring set's full size.

Pure functions: arrays in, arrays out.
"""
from __future__ import annotations

import numpy as np

from . import torsion_annulus as _ta

__all__ = ["differences", "traction_at_points"]


def differences(table: "_ta.NodeTable") -> tuple[np.ndarray, np.ndarray]:
    """The differences of the traction antiderivatives of ``table`` between neighbouring nodes
    (``np.diff`` along the nodes), read-only: two ``points × (nodes − 1)`` arrays."""
    F0, F1 = table.arrays["traction"]
    out = (np.diff(F0, axis=1), np.diff(F1, axis=1))
    for a in out:
        a.flags.writeable = False
    return out


def traction_at_points(p: "_ta.Pieces", r: np.ndarray, G_t: float, table: "_ta.NodeTable",
                       diffs: tuple[np.ndarray, np.ndarray]) -> np.ndarray:
    """``torsion_annulus.traction(p, r, G_t, columns=table)``, the same bits, with the
    differences between neighbouring ring ends taken from ``diffs`` (:func:`differences` of
    ``table``). ``r`` must be the table's radii (all its rows, in its order) for the tabulated
    route; any other input goes to ``traction`` itself.

    Parameters
    ----------
    p : tuple of ndarray
        Pieces of the punch density (``lo``, ``hi``, ``wl``, ``wr``), m and rad/m.
    r : ndarray
        Radii, m (the table's collocation points).
    G_t : float
        Torsional modulus, Pa.
    table : NodeTable
        The ring set's antiderivatives.
    diffs : tuple of ndarray
        :func:`differences` of ``table``.

    Returns
    -------
    ndarray
        Traction at ``r``, Pa.
    """
    lo, hi = p[0], p[1]
    r = np.asarray(r, float)
    if (lo.size == 0 or not table.same_radii(r) or not bool((lo[1:] == hi[:-1]).all())
            or table.nodes.size < 2):
        return _ta.traction(p, r, G_t, columns=table)
    al, be = _ta._lin(p)
    nodes = np.append(lo, hi[-1])
    tn = table.nodes
    k = np.minimum(np.searchsorted(tn, nodes), tn.size - 1)
    hit = tn[k] == nodes
    # neighbouring nodes that are neighbouring ring ends: their difference is tabulated
    j = np.minimum(k[:-1], tn.size - 2)
    tab = hit[:-1] & hit[1:] & (k[1:] == k[:-1] + 1)
    D0, D1 = diffs
    dA, dS = _take_columns(D0, j), _take_columns(D1, j)
    if not tab.all():
        # the other differences from the columns, as the route without the tabulated
        # differences forms them (columns from the table or computed: the same bits)
        miss = np.flatnonzero(~tab)
        ends = np.zeros(nodes.size, bool)
        ends[miss] = ends[miss + 1] = True
        ends = np.flatnonzero(ends)             # np.union1d(miss, miss + 1)
        A, S = _columns(table, r, nodes[ends], k[ends], hit[ends])
        pos = np.searchsorted(ends, miss)
        dA[:, miss] = A[:, pos + 1] - A[:, pos]
        dS[:, miss] = S[:, pos + 1] - S[:, pos]
    return 4.0 * G_t / np.pi * r * (dA @ al + dS @ be)


#: the most runs of consecutive columns :func:`_take_columns` copies one by one
_RUNS = 8


def _take_columns(D: np.ndarray, j: np.ndarray) -> np.ndarray:
    """``np.take(D, j, axis=1)`` (a new C-ordered array, the same values), copied as slices
    where the indices ``j`` run in a few runs of consecutive columns (a density's nodes are
    mostly neighbouring ring ends): measured 4-5x faster at a ring set's size (279 x 193)
    than ``take``, whose gather along the rows is the slow part here. (``D[:, j]`` comes out in
    Fortran order: its products would sum in another order.)"""
    if j.size == 0:
        return np.take(D, j, axis=1)
    cut = np.flatnonzero(np.diff(j) != 1) + 1
    if cut.size >= _RUNS:
        return np.take(D, j, axis=1)
    out = np.empty((D.shape[0], j.size))
    start = 0
    for stop in (*cut.tolist(), j.size):        # (at most _RUNS runs)
        first = int(j[start])
        out[:, start:stop] = D[:, first:first + stop - start]
        start = stop
    return out


def _columns(table: "_ta.NodeTable", r: np.ndarray, nodes: np.ndarray, k: np.ndarray,
             hit: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``table.columns(r, nodes)`` for the table's own radii ``r``, with the nodes' columns ``k``
    and whether each is a node of the table (``hit``) known: the table's columns where it has
    them, the others computed (the same values)."""
    F0, F1 = table.arrays["traction"]
    A, S = F0[:, k], F1[:, k]
    if not hit.all():
        A[:, ~hit], S[:, ~hit] = _ta._antiderivatives(r, nodes[~hit])
    return A, S
