"""numeric.roots.scalar_root: Newton with a closed-form derivative, Chandrupatla without."""
from __future__ import annotations

import math

import pytest

from contactlab.errors import ConvergenceError
from contactlab.numeric.roots import scalar_root


@pytest.mark.parametrize("with_derivative", [True, False])
@pytest.mark.parametrize("target", [1e-30, 2.0, 1e12])
def test_cube_root(target, with_derivative):
    fp = (lambda x: 3 * x * x) if with_derivative else None
    x = scalar_root(lambda x: x**3, target, 0.0, 1e5, rtol=1e-15, fprime=fp)
    assert abs(x - target ** (1 / 3)) <= 4e-15 * target ** (1 / 3)


def test_newton_counts_few_evaluations():
    calls = []

    def f(x):
        calls.append(x)
        return x * math.atanh(x)       # the exact sphere's g with R = 1

    x = scalar_root(f, 1e-4, 0.0, 0.5, rtol=1e-15,
                    fprime=lambda x: math.atanh(x) + x / (1 - x * x))
    assert abs(f(x) - 1e-4) <= 1e-15 * 1e-4
    assert len(calls) <= 20


def test_no_sign_change_raises():
    with pytest.raises(ConvergenceError, match="no sign change"):
        scalar_root(lambda x: x, 5.0, 0.0, 1.0)
