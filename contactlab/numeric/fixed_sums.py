"""Row sums whose rounding does not depend on which other rows, or how many terms, share a call.

A transform evaluated at many points at once sums, for each point, terms over the table nodes
below it; a chunk of points computes the terms of the nodes below its *largest* point, so a
point's row carries zeros beyond its own nodes, and how many depends on its neighbours. numpy's
pairwise summation (and BLAS contractions) group a row's terms by the row's length, so the same
point would round differently alone and in a batch. Here every row is summed by one fixed binary
tree over the node index, counted from the first node: level by level, terms ``2k`` and
``2k + 1`` are added; an odd last term is carried up unchanged (the same as adding the zero
term of the next node). Zero terms of later nodes add exact zeros wherever they sit in the tree,
so a row's sum depends only on its own terms: a point alone, in any batch, in any chunk, gives
bit-identical sums. Callers compute the terms of the nodes below a batch's largest point only.
The tree is pairwise summation, so its rounding grows like ``log2(m)`` eps, not ``m`` eps.
"""
from __future__ import annotations

import numpy as np

__all__ = ["row_sums"]


def row_sums(terms: np.ndarray, total: int) -> np.ndarray:
    """Sum ``terms`` (rows, m) over its last axis in a fixed order, one value per row.

    Parameters
    ----------
    terms : ndarray, shape (rows, m)
        Terms of the first ``m <= total`` nodes of a node axis of ``total`` nodes (the terms of
        later nodes are zero).
    total : int
        Number of nodes of the whole axis.

    Returns
    -------
    ndarray, shape (rows,)
        Per-row sums by the fixed binary tree over the node index.
    """
    terms = np.asarray(terms, dtype=float)
    rows, m = terms.shape
    if m > total:
        raise ValueError(f"row_sums: m={m} columns exceed the node axis of {total}")
    if m == 0:
        return np.zeros(rows)
    while m > 1:
        half = m // 2
        out = np.empty((rows, (m + 1) // 2))
        np.add(terms[:, 0:2 * half:2], terms[:, 1:2 * half:2], out=out[:, :half])
        if m % 2:
            out[:, half] = terms[:, m - 1]
        terms, m = out, out.shape[1]
    return terms[:, 0].copy()
