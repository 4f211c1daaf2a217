"""The power-sum slope's shortcut for all-positive radii (the quadrature nodes of one load) is
bit-identical to its general route (masks, zero array, times_power) on random inputs."""
from __future__ import annotations

import numpy as np
import pytest

from contactlab.numeric.powers import times_power
from contactlab.profiles import Cone, Paraboloid, Polynomial, PowerLaw
from contactlab.profiles.power_law import _slope_all_positive


def _general(terms, r):
    """The general route of _PowerSum._slope (its code before the shortcut)."""
    out = np.zeros_like(r)
    for c, n in terms:
        with np.errstate(divide="ignore"):
            out = out + np.where(r > 0, times_power(c * n, r, n - 1),
                                 c if n == 1 else (np.inf if n < 1 else 0.0))
    return out


def _radii(rng, shape):
    r = 10.0 ** rng.uniform(-12, 3, size=shape)
    kind = rng.integers(0, 6)
    if kind == 0:
        r.flat[rng.integers(0, r.size)] = 0.0
    elif kind == 1:
        r.flat[rng.integers(0, r.size)] = np.inf
    elif kind == 2:
        r.flat[rng.integers(0, r.size)] = 10.0 ** rng.uniform(-320, -300)
    elif kind == 3:
        r = r * 10.0 ** rng.uniform(200, 300)
    return r


@pytest.mark.parametrize("seed", range(6))
def test_shortcut_matches_general_route(seed):
    rng = np.random.default_rng(seed)
    for _ in range(400):
        m = rng.integers(1, 4)
        ns = rng.choice([1.0, 2.0, 4.0, 0.5, 3.0, float(rng.uniform(0.3, 50))], size=m)
        cs = 10.0 ** rng.uniform(-300, 300, size=m) if rng.random() < 0.3 else \
            10.0 ** rng.uniform(-3, 3, size=m)
        terms = [(float(c), float(n)) for c, n in zip(cs, ns)]
        r = _radii(rng, (int(rng.integers(1, 3)), int(rng.integers(1, 40))))
        with np.errstate(over="raise", under="raise"):   # the shortcut must not trip either
            fast = _slope_all_positive(terms, r)
        if fast is not None:
            ref = _general(terms, r)
            assert fast.dtype == ref.dtype and fast.shape == ref.shape
            assert fast.tobytes() == ref.tobytes(), (terms, r)


@pytest.mark.parametrize("prof", [Paraboloid(R=0.01), Cone(slope=0.3), PowerLaw(c=3e7, n=4),
                                  Polynomial({2: 10.0, 4: 1e5})])
def test_profiles_slope_matches_general_route(prof):
    rng = np.random.default_rng(7)
    for _ in range(50):
        r = _radii(rng, (1, 73))
        assert prof._slope(r).tobytes() == _general(prof.power_terms(), r).tobytes()
