"""Bounded-cost validity limits of the MDR torsion model on large tables (issues 12, 13): the
fixed 16-point rule for Jäger's slip function against the exact slip function and against the
Hertz closed form; the switch between the two routes."""
from __future__ import annotations

import numpy as np
import pytest

import contactlab as cl
from contactlab.physics import torsion_exact as X
from contactlab.physics import torsion_validity as V
from tests.reference import fretting as fref
from tests.reference import hertz
from tests.tolerances import TABLE_BOUNDED_SLIP, TABLE_BOUNDED_SLIP_HERTZ

R, MU = 0.01, 0.3
MAT = (cl.Elastic(E=210e9, nu=0.3), cl.Rigid())


def sphere_table(n, interpolation, spacing, seed=3):
    if spacing == "uniform":
        r = np.linspace(0.0, 3e-4, n)
    else:
        rng = np.random.default_rng(seed)
        r = np.sort(np.concatenate(([0.0, 3e-4], rng.uniform(0.0, 3e-4, n - 2))))
    return cl.profiles.Tabulated(r, R - np.sqrt(R * R - r * r), interpolation)


@pytest.mark.parametrize("interpolation", ["linear", "cubic"])
@pytest.mark.parametrize("spacing", ["uniform", "random"])
def test_bounded_rule_against_the_exact_slip_function(interpolation, spacing):
    prof = sphere_table(2500, interpolation, spacing)
    a = np.array([2e-5, 6e-5, 1.3e-4, 2.9e-4])
    g_a = prof._g(a)
    for ratio in (0.83, 0.97):
        exact, _ = X.slip_function(prof, 1e11, ratio * a, a, g_a, g_a, 1e-11)
        bounded = V.slip_function_bounded(prof, 1e11, ratio * a, a, g_a, g_a)
        assert np.max(np.abs(bounded / exact - 1)) < TABLE_BOUNDED_SLIP


@pytest.mark.parametrize("interpolation", ["linear", "cubic"])
def test_bounded_limit_against_hertz(interpolation):
    """A 10^5-point table of a paraboloid takes the bounded rule; its validity twists against
    the exact Jäger solution of Hertz contact."""
    r = np.linspace(0.0, 2e-4, 10**5)
    prof = cl.profiles.Tabulated(r, r * r / (2 * R), interpolation)
    c = cl.Contact(prof, MAT, friction=MU)
    a = np.array([3e-5, 1e-4, 1.8e-4])
    assert V.uses_bounded_rule(prof, float(a.max()))
    g_a = prof._g(a)
    F = hertz.force_of_radius(a, R, c.moduli.normal)
    for ratio in (0.83, 0.97):
        lim = V.twist_at_stick_ratio(prof, c.moduli.normal, c.moduli.torsional, MU, ratio, a, g_a,
                                     g_a, c.rtol)
        ref = fref.hertz_twist_of_stick_ratio(ratio, F, MU, a, c.moduli.torsional)
        np.testing.assert_allclose(lim, ref, rtol=TABLE_BOUNDED_SLIP_HERTZ)


def test_route_switch_and_budget():
    small = sphere_table(V.BOUNDED_TABLE_NODES, "linear", "uniform")
    big = sphere_table(4 * V.BOUNDED_TABLE_NODES, "linear", "uniform")
    assert not V.uses_bounded_rule(cl.profiles.Paraboloid(R), 1.0)
    assert not V.uses_bounded_rule(small, 3e-4)
    assert V.uses_bounded_rule(big, 3e-4) and not V.uses_bounded_rule(big, 5e-5)
    assert V.affordable_states(small, 3e-4, 33) == 33
    huge = cl.profiles.Tabulated(np.linspace(0.0, 1.0, 10**6), np.linspace(0.0, 1.0, 10**6) ** 2)
    n = V.affordable_states(huge, 0.9, 33)
    assert 3 <= n < 33 and n * 17 * 9e5 <= V.BOUNDED_WORK * 1.01
    # no contact: no limit
    out = V.twist_at_stick_ratio(big, 1e11, 8e10, MU, 0.83, np.zeros(2), np.zeros(2), np.zeros(2),
                                 1e-10)
    assert np.all(np.isinf(out))
