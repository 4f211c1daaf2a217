"""Row sums whose rounding does not depend on which other rows, or how many terms, share a call.

A transform evaluated at many points at once sums, for each point, terms over the table nodes
below it; a chunk of points computes the terms of the nodes below its *largest* point, so a
point's row carries zeros beyond its own nodes, and how many depends on its neighbours. numpy's
pairwise summation (and BLAS contractions) group a row's terms by the row's length, so the same
point would round differently alone and in a batch. Here the node axis is cut into fixed blocks
of :data:`BLOCK` terms counted from the first node; each block is summed on its own (pairwise,
always over :data:`BLOCK` terms, or over the axis's last, shorter block), and the block sums are
added in block order. Blocks of zeros add exact zeros, so a row's sum depends only on its own
terms: a point alone, in any batch, in any chunk, gives bit-identical sums.

Callers compute the terms of the nodes below a batch's largest point only; :func:`row_sums`
pads the last, partly filled block with zeros itself (a write per zero, where a term costs
transcendental functions). The block is short so that padding stays cheap when many points
share a call over few nodes (a 10^4-step load path on a 200-node table with the contact over 15
nodes pads 15 columns to 64, not to 199), and long enough that numpy's pairwise sum of a block
runs at full speed.

:func:`weighted_row_sums` forms the sums of one term array against several coefficient columns
at once (``Σ_j t_ij c_kj`` for every column k): the products are written into one zero-padded
buffer and summed in the same blocks, so each sum is bit-identical to :func:`row_sums` of its
products, with one allocation and one reduction per call instead of one per column.
"""
from __future__ import annotations

import numpy as np

__all__ = ["BLOCK", "row_sums", "weighted_row_sums"]

#: ``ndarray.sum``'s reduction without its Python wrapper (the same sums)
_add = np.add.reduce

#: terms per summation block (node axis)
BLOCK = 64


def row_sums(terms: np.ndarray, total: int) -> np.ndarray:
    """Sum ``terms`` (rows, m) over its last axis in a fixed order, one value per row.

    Parameters
    ----------
    terms : ndarray, shape (rows, m)
        Terms of the first ``m <= total`` nodes of a node axis of ``total`` nodes (the terms of
        later nodes are zero).
    total : int
        Number of nodes of the whole axis (fixes where the last, shorter block starts).

    Returns
    -------
    ndarray, shape (rows,)
        Per-row sums: blockwise pairwise sums added in block order.
    """
    terms = np.asarray(terms, dtype=float)
    rows, m = terms.shape
    if m > total:
        raise ValueError(f"row_sums: m={m} columns exceed the node axis of {total}")
    if m == 0:
        return np.zeros(rows)
    full = (m // BLOCK) * BLOCK
    parts = []
    if full:
        parts.append(_add(terms[:, :full].reshape(rows, full // BLOCK, BLOCK), axis=2))
    if m > full:
        width = min(BLOCK, total - full)       # a whole block, or the axis's last, shorter one
        tail = terms[:, full:]
        if tail.shape[1] < width:              # the zero terms of the later nodes of the block
            tail = np.concatenate([tail, np.zeros((rows, width - tail.shape[1]))], axis=1)
        if not full:                           # one block: its sums (a new array) are the result
            return _add(tail, axis=1)
        parts.append(_add(tail, axis=1)[:, None])
    blocks = parts[0] if len(parts) == 1 else np.concatenate(parts, axis=1)
    if blocks.shape[1] == 1:
        return blocks[:, 0].copy()
    return np.add.accumulate(blocks, axis=1)[:, -1]


def _padded_width(m: int, total: int) -> tuple[int, int]:
    """``(full, width)``: columns in whole blocks, and the columns summed in all (the whole
    blocks plus the last block, padded to a whole block or to the axis's end)."""
    full = (m // BLOCK) * BLOCK
    if m > full:
        return full, full + min(BLOCK, total - full)
    return full, full


def weighted_row_sums(terms: np.ndarray, columns: np.ndarray, total: int) -> np.ndarray:
    """``Σ_j terms[i, j] columns[k, j]`` for every row i and column k, in :func:`row_sums` order.

    Parameters
    ----------
    terms : ndarray, shape (rows, m)
        Terms of the first ``m <= total`` nodes of a node axis of ``total`` nodes.
    columns : ndarray, shape (k, >= m)
        Per-node coefficient columns (only their first ``m`` entries are used).
    total : int
        Number of nodes of the whole axis.

    Returns
    -------
    ndarray, shape (k, rows)
        One row of sums per column, each bit-identical to ``row_sums(terms * columns[k, :m],
        total)``.
    """
    terms = np.asarray(terms, dtype=float)
    columns = np.asarray(columns, dtype=float)
    rows, m = terms.shape
    k = columns.shape[0]
    if m > total or columns.shape[1] < m:
        raise ValueError(f"weighted_row_sums: m={m} columns for a node axis of {total} and "
                         f"{columns.shape[1]} coefficients")
    if m == 0:
        return np.zeros((k, rows))
    full, width = _padded_width(m, total)
    buf = np.empty((k, rows, width))
    np.multiply(terms[None, :, :], columns[:, None, :m], out=buf[:, :, :m])
    buf[:, :, m:] = 0.0                        # the zero terms of the later nodes of the block
    parts = []
    if full:
        parts.append(buf[:, :, :full].reshape(k, rows, full // BLOCK, BLOCK).sum(axis=3))
    if width > full:
        parts.append(buf[:, :, full:].sum(axis=2)[:, :, None])
    blocks = parts[0] if len(parts) == 1 else np.concatenate(parts, axis=2)
    if blocks.shape[2] == 1:
        return blocks[:, :, 0].copy()
    return np.add.accumulate(blocks, axis=2)[:, :, -1]
