"""Row sums whose rounding does not depend on which other rows, or how many terms, share a call.

A transform evaluated at many points at once sums, for each point, terms over the table nodes
below it; a chunk of points computes the terms of the nodes below its *largest* point, so a
point's row carries zeros beyond its own nodes, and how many depends on its neighbours. numpy's
pairwise summation (and BLAS contractions) group a row's terms by the row's length, so the same
point would round differently alone and in a batch. Here the node axis is cut into fixed blocks
of :data:`BLOCK` terms counted from the first node; each block is summed on its own (pairwise,
always over :data:`BLOCK` terms, or over the table's last, shorter block), and the block sums
are added in order. Blocks of zeros add exact zeros, so a row's sum depends only on its own
terms: a point alone, in any batch, in any chunk, gives bit-identical sums.
"""
from __future__ import annotations

import numpy as np

__all__ = ["BLOCK", "block_extent", "row_sums"]

#: terms per summation block (node axis)
BLOCK = 256


def block_extent(m: int, total: int) -> int:
    """Number of node columns to compute so that the first ``m`` are covered in whole blocks:
    ``m`` rounded up to a multiple of :data:`BLOCK`, at most ``total`` (the table's node count)."""
    return min(int(total), -(-int(m) // BLOCK) * BLOCK)


def row_sums(terms: np.ndarray, total: int) -> np.ndarray:
    """Sum ``terms`` (rows, m) over its last axis in a fixed order, one value per row.

    Parameters
    ----------
    terms : ndarray, shape (rows, m)
        Terms of the first ``m`` nodes of a node axis of ``total`` nodes, with
        ``m = block_extent(k, total)`` for some ``k`` (a multiple of :data:`BLOCK`, or ``total``).
    total : int
        Number of nodes of the whole axis (fixes where the last, shorter block starts).

    Returns
    -------
    ndarray, shape (rows,)
        Per-row sums: blockwise pairwise sums added in block order.
    """
    terms = np.asarray(terms, dtype=float)
    rows, m = terms.shape
    if m % BLOCK and m != total:
        raise ValueError(f"row_sums: m={m} columns is neither a multiple of {BLOCK} nor the "
                         f"total {total}")
    full = (m // BLOCK) * BLOCK
    parts = []
    if full:
        parts.append(terms[:, :full].reshape(rows, full // BLOCK, BLOCK).sum(axis=2))
    if m > full:
        parts.append(terms[:, full:].sum(axis=1)[:, None])
    if not parts:
        return np.zeros(rows)
    blocks = parts[0] if len(parts) == 1 else np.concatenate(parts, axis=1)
    if blocks.shape[1] == 1:
        return blocks[:, 0].copy()
    return np.add.accumulate(blocks, axis=1)[:, -1]
