"""The spring passes' pieces written as LLVM vectors (numba intrinsics, extra ``fast``) give
the bits of their scalar source: both channels' Jenkins elements of a cell in two lanes
(``_slip2``), and four cells of a row inside the edge cell in four lanes (``_cells4``:
boundaries, limits, stiffnesses, elements, the row's stores, the sums in the cells' order,
dissipation and stick radii), on random cells and at the special values (±0, ±inf, NaN,
zero stiffness, elements at and beyond their limits), for every count of cells and every
driven channel."""
from __future__ import annotations

import itertools

import numpy as np
import pytest

import contactlab as cl
from contactlab.physics import law_springs

HAS_NUMBA = cl.effects.law._kernel.AVAILABLE
pytestmark = pytest.mark.skipif(not HAS_NUMBA, reason="numba (extra 'fast') not installed")

SPECIAL = np.array([0.0, -0.0, 1.0, -1.0, 2.5, -2.5, 1e-300, np.inf, -np.inf, np.nan])


def _built():
    from contactlab.physics import law_kernel as K
    K._kernels(False)
    S = K._springs
    assert S._slip2 is not S._SLIP2_PY and S._cells4 is not S._CELLS_PY     # the intrinsics
    return S


def _same(x, y):
    """Equal to the bit (NaN payloads aside: a NaN for a NaN)."""
    x, y = np.asarray(x, float), np.asarray(y, float)
    both_nan = np.isnan(x) & np.isnan(y)
    return bool(np.all(both_nan | (x.view(np.int64) == y.view(np.int64))))


def test_two_channel_lanes_give_the_scalar_bits():
    import numba
    S = _built()
    slip2 = S._slip2

    @numba.njit
    def run(a, out):
        for i in range(a.shape[0]):
            out[i, 0], out[i, 1], out[i, 2], out[i, 3] = slip2(a[i, 0], a[i, 1], a[i, 2],
                                                              a[i, 3], a[i, 4], a[i, 5],
                                                              a[i, 6], a[i, 7])

    rng = np.random.default_rng(5)
    rows = [rng.normal(size=8) for _ in range(500)]
    # elements, stiffnesses, limits and increments at the special values, each lane alone
    for v, k in itertools.product(SPECIAL, range(8)):
        row = rng.normal(size=8)
        row[[2, 3]] = np.abs(row[[2, 3]])
        row[[4, 5]] = np.abs(row[[4, 5]])
        row[k] = v
        rows.append(row)
    a = np.array(rows)
    a[:500, 4:6] = np.abs(a[:500, 4:6])             # limits >= 0, elements beyond them too
    got = np.empty((a.shape[0], 4))
    with np.errstate(all="ignore"):
        run(a, got)
        want = np.array([S._SLIP2_PY(*row) for row in a])
    assert _same(got, want)


@pytest.mark.parametrize("has_u, has_phi", [(True, True), (True, False), (False, True)])
def test_four_cell_lanes_give_the_scalar_bits(has_u, has_phi, monkeypatch):
    import numba
    S = _built()
    cells4 = S._cells4
    W = S._W

    @numba.njit
    def run(beta, bG, bH, mt, mr, r, i0, cnt, s, hu, hp, a, acc, ft, fm):
        return cells4(beta, bG, bH, mt, mr, r, i0, cnt, s[0], s[1], s[2], s[3], s[4], s[5],
                      s[6], s[7], s[8], s[9], hu, hp, a, acc[0], acc[1], acc[2], ft, fm,
                      acc[3], acc[4])

    N = 16
    beta = law_springs.unit_boundaries(N)
    rng = np.random.default_rng(11)
    nn = 2.0
    bG = beta ** (nn + 1.0) / (nn + 1.0)
    bH = beta ** (nn + 2.0) / (nn + 2.0)
    for trial in range(300):
        cov = rng.uniform(1e-4, 1e-3)
        kc = rng.uniform(10.0, 100.0)
        cp1 = kc * cov * cov * cov
        d = kc * (rng.uniform(0.3, 0.9) * cov) ** 2
        s = np.array([cov, cp1, cp1 * cov, d, 2.0 * 4.4e10, 16.0 * 4e10, 2 * 0.3 * 1e11,
                      4 * 0.3 * 1e11, rng.normal() * 1e-7, rng.normal() * 1e-4])
        mt = rng.normal(size=(3, N)) * 10.0 ** rng.uniform(-3, 2)
        mr = rng.normal(size=(3, N)) * 10.0 ** rng.uniform(-6, -1)
        if trial % 5 == 0:                          # special values in the row and controls
            mt[1, rng.integers(0, N)] = rng.choice(SPECIAL)
            mr[1, rng.integers(0, N)] = rng.choice(SPECIAL)
            s[rng.integers(8, 10)] = rng.choice(SPECIAL)
        i0 = int(rng.integers(0, N - W + 1))
        cnt = int(rng.integers(1, W + 1))
        a = rng.uniform(0.5, 1.0) * cov
        acc = np.array([rng.uniform(0, 1), rng.normal(), rng.normal(), a, a])
        free = (bool(rng.integers(0, 2)), bool(rng.integers(0, 2)))
        mt2, mr2 = mt.copy(), mr.copy()
        with np.errstate(all="ignore"), monkeypatch.context() as mp:
            got = run(beta, bG, bH, mt, mr, 1, i0, cnt, s, has_u, has_phi, a, acc, *free)
            mp.setattr(S, "_slip2", S._SLIP2_PY)    # the plain source throughout
            mp.setattr(S, "_sum", S._sum.py_func)
            want = S._CELLS_PY(beta, bG, bH, mt2, mr2, 1, i0, cnt, *s, has_u, has_phi, a,
                               acc[0], acc[1], acc[2], free[0], free[1], acc[3], acc[4])
        assert got[3:5] == want[3:5]
        assert _same([got[k] for k in (0, 1, 2, 5, 6)], [want[k] for k in (0, 1, 2, 5, 6)])
        assert _same(mt, mt2) and _same(mr, mr2)


@pytest.mark.parametrize("st_u, st_p", [(True, True), (True, False), (False, True)])
def test_four_cell_switch_lanes_give_the_scalar_bits(st_u, st_p, monkeypatch):
    """The switch-and-step of four cells (``_first4``: the turning points replayed through
    the cells' elements at the held depth, then the step) against its scalar source, on
    random stacks of 0 to 4 turning points per channel and special controls."""
    import numba
    S = _built()
    first4 = S._first4
    assert first4 is not S._FIRST_CELLS_PY
    W = S._W

    @numba.njit
    def run(beta, bG, bH, X, mt, mr, r, c, i0, cnt, dt, dr, s, incs, su, sp, a, acc):
        return first4(beta, bG, bH, X, mt, mr, r, c, i0, cnt, dt, dr, s[0], s[1], s[2], s[3],
                      s[4], s[5], s[6], s[7], s[8], incs, s[9], s[10], su, sp, a, acc)

    N = 16
    beta = law_springs.unit_boundaries(N)
    rng = np.random.default_rng(13)
    bG = beta ** 3.0 / 3.0
    bH = beta ** 4.0 / 4.0
    for trial in range(300):
        cov = rng.uniform(1e-4, 1e-3)
        kc = rng.uniform(10.0, 100.0)
        cp1 = kc * cov * cov * cov
        d0 = kc * (rng.uniform(0.3, 0.9) * cov) ** 2
        d = d0 * rng.uniform(0.9, 1.1)
        s = np.array([cov, cp1, cp1 * cov, d0, d, 2.0 * 4.4e10, 16.0 * 4e10, 2 * 0.3 * 1e11,
                      4 * 0.3 * 1e11, rng.normal() * 1e-7, rng.normal() * 1e-4])
        X = np.empty((2, 3, 4))
        X[0] = rng.normal(size=(3, 4)) * 1e-6
        X[1] = rng.normal(size=(3, 4)) * 1e-3
        dt, dr = int(rng.integers(0, 5)), int(rng.integers(0, 5))
        x = (rng.normal() * 1e-6, rng.normal() * 1e-3)
        incs = (X[0, 1, 0] - 0.0 if dt else 0.0, X[1, 1, 0] - 0.0 if dr else 0.0,
                x[0] - (X[0, 1, dt - 1] if dt else 0.0), x[1] - (X[1, 1, dr - 1] if dr else 0.0))
        if trial % 5 == 0:                          # special values in the controls
            s[rng.integers(9, 11)] = rng.choice(SPECIAL)
            X[rng.integers(0, 2), 1, rng.integers(0, 4)] = rng.choice(SPECIAL)
        mt = rng.normal(size=(3, N))
        mr = rng.normal(size=(3, N))
        i0 = int(rng.integers(0, N - W + 1))
        cnt = int(rng.integers(1, W + 1))
        a = rng.uniform(0.5, 1.0) * cov
        acc = (float(rng.uniform(0, 1)), float(rng.normal()), float(rng.normal()),
               bool(rng.integers(0, 2)), bool(rng.integers(0, 2)), a, a)
        mt2, mr2 = mt.copy(), mr.copy()
        with np.errstate(all="ignore"), monkeypatch.context() as mp:
            got = run(beta, bG, bH, X, mt, mr, 2, 1, i0, cnt, dt, dr, s, incs, st_u, st_p, a,
                      acc)
            mp.setattr(S, "_slip2", S._SLIP2_PY)    # the plain source throughout
            mp.setattr(S, "_sum", S._sum.py_func)
            want = S._FIRST_CELLS_PY(beta, bG, bH, X, mt2, mr2, 2, 1, i0, cnt, dt, dr,
                                     *s[:9], incs, s[9], s[10], st_u, st_p, a, acc)
        assert got[3:5] == want[3:5]
        assert _same([got[k] for k in (0, 1, 2, 5, 6)], [want[k] for k in (0, 1, 2, 5, 6)])
        # the cells of the four past ``cnt``: +0 (not loaded; the pass writes them after)
        past = slice(i0 + cnt, i0 + W)
        assert not np.any(np.signbit(mt[2, past])) and not np.any(mt[2, past])
        assert not np.any(np.signbit(mr[2, past])) and not np.any(mr[2, past])
        mt2[2, past] = mr2[2, past] = 0.0
        assert _same(mt, mt2) and _same(mr, mr2)
