"""A linear table of two points (the fewest a table takes) under force control.

With no interior node the table has no slope jumps, and the force solve's cusp term indexed
the empty array of jumps: ``IndexError`` (the command line reported an internal error). Two
points ``(0, 0)``, ``(b, k b)`` are a cone of slope ``k`` up to ``b``: Love's closed form
``F = (π/2) E* k a²``, ``d = (π/2) k a``.
"""
import math

import numpy as np
import pytest

import contactlab as cl
from contactlab.profiles import Tabulated
from tests.tolerances import CLOSED_FORM

STEEL = cl.Elastic(E=210e9, nu=0.3)
E_STAR = 210e9 / (2 * (1 - 0.3**2))
B, K = 1e-3, 1e-3


@pytest.mark.parametrize("F", [1.0, 10.0, np.array([1.0, 10.0])])
def test_two_point_table_by_force_is_the_cone(F):
    c = cl.Contact(Tabulated([0.0, B], [0.0, K * B]), materials=(STEEL, STEEL))
    s = c.normal(force=F)
    a = np.sqrt(np.asarray(F) / (0.5 * math.pi * E_STAR * K))
    assert np.all(a < B)
    np.testing.assert_allclose(s.radius, a, rtol=CLOSED_FORM)
    np.testing.assert_allclose(s.depth, 0.5 * math.pi * K * a, rtol=CLOSED_FORM)
    np.testing.assert_allclose(c.normal(depth=s.depth).force, F, rtol=CLOSED_FORM)
