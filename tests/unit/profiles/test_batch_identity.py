"""A table's transform at a point does not depend on which other points share its call.

g, ∫g and ∫x g of linear and cubic tables sum terms over the nodes below each point; a batch
computes the nodes below its largest point, in chunks. The sums are grouped in fixed blocks of
the node axis (contactlab.numeric.fixed_sums), so a point alone, in any batch, in any chunk
size and with any number of BLAS threads gives bit-identical values (no tolerance).
"""
from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import contactlab.profiles.tabulated._cubic as tabulated_cubic
import contactlab.profiles.tabulated._linear as tabulated_linear
from contactlab.numeric.fixed_sums import BLOCK, row_sums, weighted_row_sums
from contactlab.profiles import Tabulated

N = 2000        # several summation blocks


def _table(kind: str, spacing: str) -> Tabulated:
    if spacing == "uniform":
        r = np.linspace(0.0, 2e-3, N)
    else:
        r = 2e-3 * np.sort(np.r_[0.0, np.random.default_rng(7).random(N - 2), 1.0])
    return Tabulated(r, r**2 / 0.02 + 2.0 * r**4, kind)


def _points() -> np.ndarray:
    rng = np.random.default_rng(11)
    return np.r_[rng.uniform(1e-6, 2e-3, 25), 1e-4, 1.999e-3]


def _evaluate(tab: Tabulated, x: np.ndarray) -> dict[str, np.ndarray]:
    out = {"g": tab.g(x), "int": tab.g_integral(x), "xg": tab._xg_integral_closed_form(x)}
    if tab.interpolation == "cubic":
        out["slope"] = tab.table_g_slope(x)[0]
    return out


@pytest.mark.parametrize("spacing", ["uniform", "random"])
@pytest.mark.parametrize("kind", ["linear", "cubic"])
def test_point_alone_and_in_any_batch_bit_identical(kind, spacing, monkeypatch):
    tab = _table(kind, spacing)
    x = _points()
    batch = _evaluate(tab, x)
    alone = [_evaluate(tab, x[i:i + 1]) for i in range(x.size)]
    order = np.random.default_rng(3).permutation(x.size)
    shuffled = _evaluate(tab, x[order])
    # a batch whose largest point reaches the table's end (more node columns for every point)
    wide = _evaluate(tab, np.r_[x, 2e-3])
    # chunks of ~3 points (each transform module reads its own binding of the block size)
    monkeypatch.setattr(tabulated_linear, "_CHUNK", 3 * N)
    monkeypatch.setattr(tabulated_cubic, "_CHUNK", 3 * N)
    chunked = _evaluate(tab, x)
    for q, v in batch.items():
        assert np.all(np.isfinite(v)), q
        assert np.array_equal(np.array([a[q][0] for a in alone]), v), q
        assert np.array_equal(shuffled[q], v[order]), q
        assert np.array_equal(wide[q][:-1], v), q
        assert np.array_equal(chunked[q], v), q


def test_random_cubic_table_with_local_pieces_bit_identical():
    """A random table with local (clustered) pieces: their corrections, near and far, are summed
    per point in fixed blocks too."""
    n = 20_000
    r = 2e-3 * np.sort(np.r_[0.0, np.random.default_rng(5).random(n - 2), 1.0])
    tab = Tabulated(r, r**2 / 0.02 + 2.0 * r**4, "cubic")
    lo = tab._cubic_local_lo
    assert lo.size > 0
    # points far from the local pieces, just above one (the θ-rule) and a node's width above
    x = np.r_[_points(), lo[0] + 1e-13, lo[-1] + 3e-12, lo[lo.size // 2] + 1e-9]
    batch = _evaluate(tab, x)
    for i in (0, 7, x.size - 3, x.size - 2, x.size - 1):
        one = _evaluate(tab, x[i:i + 1])
        for q in batch:
            assert one[q][0] == batch[q][i], (q, i)


_SCRIPT = """
import json, sys
import numpy as np
sys.path.insert(0, {root!r})
from contactlab.profiles import Tabulated
r = 2e-3 * np.sort(np.r_[0.0, np.random.default_rng(7).random({n} - 2), 1.0])
x = np.random.default_rng(11).uniform(1e-6, 2e-3, 40)
out = {{}}
for kind in ("linear", "cubic"):
    t = Tabulated(r, r**2 / 0.02 + 2.0 * r**4, kind)
    out[kind] = [float(v).hex() for v in np.r_[t.g(x), t.g_integral(x), t.g(x[:1])]]
print(json.dumps(out))
"""


def test_bit_identical_with_one_or_default_blas_threads():
    """The same values in a process with OPENBLAS_NUM_THREADS=1 and one with the default."""
    root = str(Path(__file__).resolve().parents[3])
    script = _SCRIPT.format(root=root, n=N)
    results = []
    for threads in ("1", None):
        env = dict(os.environ)
        env.pop("OPENBLAS_NUM_THREADS", None)
        if threads is not None:
            env["OPENBLAS_NUM_THREADS"] = threads
        proc = subprocess.run([sys.executable, "-c", script], env=env, capture_output=True,
                              text=True, timeout=300, check=True)
        results.append(json.loads(proc.stdout.strip().splitlines()[-1]))
    assert results[0] == results[1]


def test_row_sums_ignore_appended_zeros_at_any_width():
    rng = np.random.default_rng(2)
    total = 3 * BLOCK + 17
    terms = rng.standard_normal(2 * BLOCK) * 10.0 ** rng.integers(-8, 8, 2 * BLOCK)
    one = row_sums(terms[None, :], total)
    padded = np.zeros((1, total))
    padded[0, :terms.size] = terms
    assert row_sums(padded, total)[0] == one[0]
    # the sum itself is accurate (second method: exact rational summation via math.fsum)
    import math
    assert abs(one[0] - math.fsum(terms)) <= 1e-12 * np.sum(np.abs(terms))
    # a row cut anywhere (its later terms zero) sums like the whole row: the partly filled
    # block is padded with zeros, not summed at its own width (numpy's pairwise grouping
    # depends on the width)
    for cut in (1, 7, BLOCK - 1, BLOCK + 1, 2 * BLOCK + 5, 3 * BLOCK + 3, total):
        row = np.zeros(total)
        row[:min(cut, terms.size)] = terms[:min(cut, terms.size)]
        assert row_sums(row[None, :cut], total)[0] == row_sums(row[None, :], total)[0], cut
    with pytest.raises(ValueError):
        row_sums(np.zeros((1, total + 1)), total)


@pytest.mark.parametrize("m", [0, 1, 15, BLOCK, BLOCK + 1, 2 * BLOCK + 5, 3 * BLOCK + 17])
def test_weighted_row_sums_equal_row_sums_of_the_products(m):
    """One padded buffer for several coefficient columns sums each column bit for bit like
    ``row_sums`` of its own products (the cubic transform relies on it), whatever the width."""
    rng = np.random.default_rng(m)
    total = 3 * BLOCK + 17
    rows = 5
    terms = rng.standard_normal((rows, m)) * 10.0 ** rng.integers(-6, 6, (rows, m))
    columns = rng.standard_normal((3, total)) * 10.0 ** rng.integers(-6, 6, (3, total))
    got = weighted_row_sums(terms, columns, total)
    assert got.shape == (3, rows)
    for k in range(3):
        want = row_sums(terms * columns[k, :m], total)
        assert got[k].tobytes() == want.tobytes(), k
    # the sums themselves: exact rational summation as the second method
    import math
    for i in range(rows):
        prods = terms[i] * columns[0, :m]
        assert abs(got[0, i] - math.fsum(prods)) <= 1e-12 * (np.sum(np.abs(prods)) + 1e-300)
    with pytest.raises(ValueError):
        weighted_row_sums(np.zeros((1, total + 1)), np.zeros((1, total + 1)), total)
