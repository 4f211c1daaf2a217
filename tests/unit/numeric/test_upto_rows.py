"""upto_rows (one interval's levels in floats, the products of all levels in one multiplication)
holds, bit for bit, what tanh_sinh_upto holds on the same integrand values, on random rows."""
from __future__ import annotations

import numpy as np
import pytest

from contactlab.numeric.quadrature import UPTO_LEVEL, _common_nodes, tanh_sinh_upto, upto_rows


@pytest.mark.parametrize("seed", range(4))
def test_upto_rows_matches_tanh_sinh_upto(seed):
    rng = np.random.default_rng(seed)
    for _ in range(300):
        lo = float(rng.uniform(-2, 1))
        hi = lo + float(10.0 ** rng.uniform(-6, 2))
        x, _, _ = _common_nodes(lo, hi, UPTO_LEVEL)
        rows = int(rng.integers(1, 4))
        # a smooth positive integrand, scaled per row over many decades (its level sums then
        # round differently in every summation order)
        scale = 10.0 ** rng.uniform(-8, 8, size=(rows, 1))
        power = rng.uniform(0.2, 4, size=(rows, 1))
        vals = scale * (1.0 + np.abs(x)) ** power * (1 + 1e-3 * rng.standard_normal(x.shape))
        got = upto_rows(vals, lo, hi)
        assert got is not None

        def integrand(_x, idx, vals=vals):
            return vals[idx]
        ref_v, ref_e = tanh_sinh_upto(integrand, np.full(rows, lo), np.full(rows, hi),
                                      common=True)
        for i, (values, errors) in enumerate(got):
            assert np.array(values).tobytes() == ref_v[:, i].tobytes()
            assert np.array(errors).tobytes() == ref_e[:, i].tobytes()
