"""The traction at a ring set's collocation points from tabulated differences
(physics.torsion_point_traction) against the route it replaces in the ring solver's steps,
``torsion_annulus.traction(..., columns=table)``: the same bits on every kind of density the
solver carries (ring ends, jump nodes, a stick radius between ring ends, pieces that skip ring
ends, gaps, none), on the compiled and the numpy route."""
from __future__ import annotations

import numpy as np
import pytest

from contactlab.physics import torsion_annulus as ta
from contactlab.physics import torsion_point_traction as tpt
from contactlab.physics import torsion_rings as tr

G = 80e9


def _ring_set():
    b = tr.aligned_grid(np.linspace(0.0, 1.0, 41), np.array([0.61, 0.733, 0.9]))
    jumps = tr.radius_nodes(b, np.array([0.61, 0.733, 0.9]))
    h = np.diff(b)
    r = np.sort(np.concatenate([0.5 * (b[1:] + b[:-1]), b[jumps] + 0.25 * h[jumps]]))
    return b, jumps, r, ta.NodeTable(r, b)


def _densities(b, jumps, r):
    rng = np.random.default_rng(3)
    lu = tr.influence(b, r, G, jumps=jumps)["lu"]
    coll = ta.density(lu, b, jumps, rng.uniform(0.5, 2.0, r.size) * (r < 0.733), 0.733)
    other = ta.density(lu, b, jumps, rng.uniform(-1.0, 1.0, r.size), b[-1])
    skip = b[::3]                       # pieces that span several rings
    yield coll
    yield other
    yield ta.splice(other, coll, 0.4567)                 # a stick radius between ring ends
    yield ta.splice(ta.splice(other, coll, 0.2), other, 0.555)
    yield ta.from_nodes(skip, rng.normal(size=skip.size - 1), rng.normal(size=skip.size - 1))
    yield (np.array([0.1, 0.5]), np.array([0.3, 0.8]), np.array([1.0, 2.0]),
           np.array([0.5, -1.0]))                         # a gap: not abutting
    yield ta.empty()


@pytest.mark.parametrize("compiled", [True, False])
def test_the_same_bits_as_the_columns_route(compiled, monkeypatch):
    monkeypatch.setitem(ta._COMPILED, "on", compiled)
    b, jumps, r, table = _ring_set()
    diffs = tpt.differences(table)
    n = 0
    for p in _densities(b, jumps, r):
        want = ta.traction(p, r, G, columns=table)
        got = tpt.traction_at_points(p, r, G, table, diffs)
        assert np.array_equal(got, want)
        n += bool(np.any(want != 0))
    assert n >= 5
    # other radii than the table's rows: the columns route itself
    p = next(_densities(b, jumps, r))
    assert np.array_equal(tpt.traction_at_points(p, r[::2], G, table, diffs),
                          ta.traction(p, r[::2], G, columns=table))


def test_the_differences_are_read_only_neighbouring_differences():
    table = _ring_set()[3]
    D0, D1 = tpt.differences(table)
    F0, F1 = table.arrays["traction"]
    assert np.array_equal(D0, F0[:, 1:] - F0[:, :-1]) and np.array_equal(D1, F1[:, 1:] - F1[:, :-1])
    with pytest.raises(ValueError):
        D0[0, 0] = 1.0


@pytest.mark.parametrize("runs", [0, 1, 2, 3, tpt._RUNS - 1, tpt._RUNS, 40])
def test_columns_by_runs_are_takes_columns(runs):
    """``_take_columns`` (slices of runs of consecutive columns, or ``take`` past ``_RUNS`` runs)
    gives ``np.take(D, j, axis=1)``: the same values in the same C order, with repeated and
    skipped columns between the runs."""
    rng = np.random.default_rng(runs)
    D = rng.normal(size=(7, 300))
    parts, col = [], 0
    for _ in range(runs):
        n = int(rng.integers(1, 6))
        parts.append(np.arange(col, col + n))
        col += n - int(rng.integers(0, 2)) + int(rng.integers(0, 3))    # repeat / skip
    j = np.concatenate(parts) if parts else np.zeros(0, np.int64)
    want = np.take(D, j, axis=1)
    got = tpt._take_columns(D, j)
    assert got.shape == want.shape and got.flags.c_contiguous
    assert np.array_equal(got, want)
