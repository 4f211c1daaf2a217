"""row_sums without ndarray.sum's wrapper (and, for one block, without the block column and its
copy) gives the bits of its earlier form, on random terms of every block layout."""
from __future__ import annotations

import numpy as np

from contactlab.numeric.fixed_sums import BLOCK, row_sums


def _reference(terms, total):
    """row_sums as it was written before (ndarray.sum, the block column, its copy)."""
    rows, m = terms.shape
    if m == 0:
        return np.zeros(rows)
    full = (m // BLOCK) * BLOCK
    parts = []
    if full:
        parts.append(terms[:, :full].reshape(rows, full // BLOCK, BLOCK).sum(axis=2))
    if m > full:
        width = min(BLOCK, total - full)
        tail = terms[:, full:]
        if tail.shape[1] < width:
            tail = np.concatenate([tail, np.zeros((rows, width - tail.shape[1]))], axis=1)
        parts.append(tail.sum(axis=1)[:, None])
    blocks = parts[0] if len(parts) == 1 else np.concatenate(parts, axis=1)
    if blocks.shape[1] == 1:
        return blocks[:, 0].copy()
    return np.add.accumulate(blocks, axis=1)[:, -1]


def test_row_sums_matches_earlier_form():
    rng = np.random.default_rng(11)
    for _ in range(1500):
        total = int(rng.choice([3, 7, 40, BLOCK, BLOCK + 5, 3 * BLOCK + 17]))
        m = int(rng.integers(0, total + 1))
        rows = int(rng.integers(1, 5))
        terms = rng.standard_normal((rows, m)) * 10.0 ** rng.uniform(-10, 10, (rows, m))
        if rng.random() < 0.2:
            terms[:, ::2] = -0.0
        got, ref = row_sums(terms, total), _reference(terms, total)
        assert got.shape == ref.shape and got.dtype == ref.dtype
        assert got.tobytes() == ref.tobytes()
