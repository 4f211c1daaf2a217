"""Batched contact-radius solves on tables (issue 29): the Newton iteration inside one node
interval starts from the left node's square-root cusp and stops on its quadratic convergence.

Checked: batch against one call per load (bit-identical, with unsorted input, duplicates and
depths exactly at the nodes), against the previous iteration (plain start, stop only on a small
step) to the solve's tolerance, against the closed form of the sampled paraboloid to the
table's interpolation bound, and the number of passes over the nodes (the regression guard).
"""
from __future__ import annotations

import numpy as np
import pytest

import contactlab as cl
from contactlab.profiles import Paraboloid, Tabulated
from contactlab.profiles.base import root_rtol
from tests.tolerances import TABLE_LINEAR_RANDOM_RADII, TABLE_NEWTON_ROUTES

R = 0.01
MATS = (cl.Elastic(E=210e9, nu=0.3), cl.Rigid())


def _table(n: int = 2000, kind: str = "linear") -> Tabulated:
    r = np.linspace(0.0, 1e-3, n)
    return Tabulated(r, r * r / (2 * R), kind)


def _depths(tab: Tabulated, n: int = 60, seed: int = 3) -> np.ndarray:
    """Random depths (unsorted), duplicates and depths exactly at table nodes."""
    rng = np.random.default_rng(seed)
    d = rng.uniform(1e-9, 0.8 * float(tab.g(np.array(0.5e-3))), n)
    nodes = tab.r[[7, 150, 611, 999]]
    at_nodes = np.asarray(tab.g(nodes), dtype=float)
    return np.concatenate([d, d[:5], at_nodes, at_nodes[:2]])


def _old_route(tab: Tabulated) -> None:
    """Make ``tab`` iterate as before: linear start in u², stop only on a small step."""
    orig = tab._newton_on_node_interval

    def plain(*args, cusp=None, **kw):
        import contactlab.profiles.tabulated._solve as S
        saved = S._NEWTON_MARGIN
        S._NEWTON_MARGIN = np.inf      # the quadratic-convergence stop never fires
        try:
            return orig(*args, **kw)
        finally:
            S._NEWTON_MARGIN = saved

    tab._newton_on_node_interval = plain


@pytest.mark.parametrize("kind", ["linear", "cubic"])
@pytest.mark.parametrize("control", ["depth", "force"])
def test_batch_equals_one_call_per_load_bit_for_bit(kind, control):
    tab = _table(1200, kind)
    c = cl.Contact(tab, MATS, rtol=1e-6)
    d = _depths(tab)
    vals = d if control == "depth" else np.asarray(c.normal(depth=d).force)
    st = c.normal(**{control: vals})
    one = [c.normal(**{control: float(v)}) for v in vals]
    for name in ("radius", "depth", "force"):
        batch = np.asarray(getattr(st, name))
        single = np.array([float(getattr(s, name)) for s in one])
        assert np.array_equal(batch, single), name
    # duplicates give the same numbers as their originals
    assert np.array_equal(np.asarray(st.radius)[60:65], np.asarray(st.radius)[:5])


@pytest.mark.parametrize("kind", ["linear", "cubic"])
@pytest.mark.parametrize("rtol", [1e-6, 1e-10])
@pytest.mark.parametrize("control", ["depth", "force"])
def test_agrees_with_the_previous_iteration_to_its_tolerance(rtol, control, kind):
    new, old = _table(kind=kind), _table(kind=kind)
    _old_route(old)
    cn, co = cl.Contact(new, MATS, rtol=rtol), cl.Contact(old, MATS, rtol=rtol)
    d = _depths(new)
    vals = d if control == "depth" else np.asarray(co.normal(depth=d).force)
    a_new = np.asarray(cn.normal(**{control: vals}).radius)
    a_old = np.asarray(co.normal(**{control: vals}).radius)
    # both stop within the solve's tolerance of the same root
    assert np.max(np.abs(a_new / a_old - 1)) <= TABLE_NEWTON_ROUTES * root_rtol(rtol)


@pytest.mark.parametrize("control", ["depth", "force"])
def test_sampled_paraboloid_within_the_tables_bound(control):
    tab = _table(2000)
    ct, cp = cl.Contact(tab, MATS, rtol=1e-6), cl.Contact(Paraboloid(R), MATS)
    a = np.random.default_rng(5).uniform(0.05e-3, 0.9e-3, 50)
    exact = cp.normal(radius=a)
    vals = np.asarray(exact.depth if control == "depth" else exact.force)
    st = ct.normal(**{control: vals})
    bound = TABLE_LINEAR_RANDOM_RADII * ((tab.r[1] - tab.r[0]) / a) ** 2
    assert np.all(np.abs(np.asarray(st.radius) / a - 1) < bound)
    other = "force" if control == "depth" else "depth"
    assert np.all(np.abs(np.asarray(getattr(st, other)) / np.asarray(getattr(exact, other)) - 1)
                  < 2 * bound)


@pytest.mark.parametrize("kind, passes", [("linear", 2), ("cubic", 1)])
def test_depth_solve_makes_two_passes_over_the_nodes_at_rtol_1e_6(kind, passes):
    """Regression: the plain start and the small-step stop took 4 passes (10^3 random depths on
    a 10^4-point linear table: 1000, 1000, 970, 24 points); the cusp start and the quadratic
    stop take 2, and the spline's Hermite start from the node values and slopes 1. Counted
    through the pass that evaluates g and g'."""
    tab = _table(10**4, kind)
    c = cl.Contact(tab, MATS, rtol=1e-6)
    # (two batches: the second memoises g, and the spline's g', at every node)
    for seed in (0, 1):
        c.normal(depth=np.random.default_rng(seed).uniform(1e-8, 2.4e-5, 1000))
    sizes: list[int] = []
    orig = tab._g_and_slope

    def counted(x):
        sizes.append(int(np.size(x)))
        return orig(x)

    tab._g_and_slope = counted
    c.normal(depth=np.random.default_rng(2).uniform(1e-8, 2.4e-5, 1000))
    assert len(sizes) == passes, sizes


def test_force_step_pass_equals_the_separate_passes_bit_for_bit():
    """The force solve's one pass for g, g' and ∫g (linear) gives the bits of the separate
    kernels, on a random table with noise, at random points, at nodes, at 0 and at a tiny x."""
    rng = np.random.default_rng(11)
    r = np.sort(rng.uniform(0.0, 1e-3, 3000))
    r[0] = 0.0
    tab = Tabulated(r, r * r / 0.02 + 1e3 * r**3 + 1e-9 * rng.standard_normal(r.size))
    x = np.concatenate([rng.uniform(0.0, r[-1], 300), r[5:40], [0.0, r[-1], 1e-300]])
    g, gp, integral = tab._g_slope_integral(x)
    g2, gp2 = tab._arcsine_sums(x, with_slope=True)
    assert np.array_equal(g, g2)
    assert np.array_equal(gp, gp2, equal_nan=True)
    assert np.array_equal(integral, tab._linear_g_integral(x))
