"""Node sums of large cubic tables over the dyadic tree (issue 29), the column sums of
``_far_cols``: against the dense node sums (the route before, kept by small and clustered
tables) within the rounding estimate that route reports, batch against one call per load
(bit-identical), the compiled pass against its numpy reference and plain Python logic
(bit-identical), the sampled paraboloid against its closed form, and the regression guard (no
dense (point, node) contractions on a 10^4-point table).
"""
from __future__ import annotations

import numpy as np
import pytest

import contactlab as cl
from contactlab.profiles import Paraboloid, Tabulated
from contactlab.profiles.tabulated import _cubic, _far, _far_cols
from tests.tolerances import TABLE_FAR_FIELD_CUBIC, TABLE_FAR_FIELD_SUMS

R = 0.01
MATS = (cl.Elastic(E=210e9, nu=0.3), cl.Rigid())


def _sphere(n: int = 10**4) -> Tabulated:
    r = np.linspace(0.0, 1e-3, n)
    return Tabulated(r, R - np.sqrt(R * R - r * r), "cubic")


def _wavy(n: int = 10**4) -> Tabulated:
    r = np.linspace(0.0, 1e-3, n)
    return Tabulated(r, r * r / 0.02 + 2e-7 * np.sin(r / 3e-5), "cubic")


def _dense(tab: Tabulated) -> Tabulated:
    tab.__dict__["_cubic_tree_cache"] = (None,)
    return tab


def _points(tab: Tabulated) -> np.ndarray:
    rng = np.random.default_rng(1)
    nodes = tab.r[[1, 2, 7, 150, 611, 4999, tab.r.size - 2]]
    return np.concatenate([rng.uniform(0.0, tab.r[-1], 300), nodes, nodes * (1 + 1e-12),
                           [0.0, 1e-300, 1e-12, tab.r[-1]]])


@pytest.mark.parametrize("make", [_sphere, _wavy])
@pytest.mark.parametrize("kind", ["g", "int"])
def test_tree_sums_within_the_dense_routes_rounding_estimate(make, kind):
    tree_tab, dense_tab = make(), _dense(make())
    assert tree_tab._cubic_tree() is not None
    x = _points(tree_tab)
    v, e, slope = tree_tab._cubic_sums(x, kind, kind == "g")
    v0, e0, slope0 = dense_tab._cubic_sums(x, kind, kind == "g")
    assert np.all(np.abs(v - v0) <= TABLE_FAR_FIELD_CUBIC * e0)
    # the estimate itself: sums of the parts' magnitudes, equal to rounding
    assert np.all(np.abs(e - e0) <= TABLE_FAR_FIELD_SUMS * e0)
    if kind == "g":
        scale = np.abs(slope0) + e0 / np.where(x > 0, x, 1.0)
        assert np.all(np.abs(slope - slope0) <= TABLE_FAR_FIELD_CUBIC * scale)


@pytest.mark.parametrize("control", ["depth", "force"])
def test_batch_equals_one_call_per_load_bit_for_bit(control):
    tab = _sphere()
    c = cl.Contact(tab, MATS, rtol=1e-6)
    d = np.random.default_rng(3).uniform(1e-9, 2.4e-5, 30)
    at_nodes = np.asarray(tab.g(tab.r[[7, 611, 4999]]), dtype=float)
    d = np.concatenate([d, d[:4], at_nodes])
    vals = d if control == "depth" else np.asarray(c.normal(depth=d).force)
    st = c.normal(**{control: vals})
    one = [c.normal(**{control: float(v)}) for v in vals]
    for name in ("radius", "depth", "force"):
        batch = np.asarray(getattr(st, name))
        assert np.array_equal(batch, [float(getattr(s, name)) for s in one]), name


@pytest.mark.parametrize("control", ["depth", "force"])
def test_solve_agrees_with_the_dense_route(control):
    tree_c = cl.Contact(_sphere(), MATS, rtol=1e-10)
    dense_c = cl.Contact(_dense(_sphere()), MATS, rtol=1e-10)
    d = np.random.default_rng(4).uniform(1e-9, 2.4e-5, 100)
    vals = d if control == "depth" else np.asarray(dense_c.normal(depth=d).force)
    a, b = tree_c.normal(**{control: vals}), dense_c.normal(**{control: vals})
    for name in ("radius", "depth", "force"):
        x, y = np.asarray(getattr(a, name)), np.asarray(getattr(b, name))
        assert np.max(np.abs(x / y - 1)) <= TABLE_FAR_FIELD_SUMS, name


def test_compiled_pass_numpy_route_and_python_logic_give_the_same_bits(monkeypatch):
    ct = _wavy()._cubic_tree()
    assert ct is not None
    x = np.sort(np.random.default_rng(2).uniform(1e-9, 1e-3, 300))
    x = np.concatenate([x, ct.tree.nodes[[0, 5, 500]], [1e-300]])
    cols = np.array([0, 1, 2, 3, 4, 5, 8, 9, 12, 13])
    kinds = np.array([_far_cols.ACOS] * 4 + [_far_cols.ROOT] * 4 + [_far_cols.ROOT3] * 2)
    routes = {"numpy": (True, 10**9), "python": (False, 0)}
    try:
        import numba  # noqa: F401
        routes["numba"] = (True, 0)
    except ImportError:
        pass
    out = {}
    for name, (on, frm) in routes.items():
        monkeypatch.setitem(_far._COMPILED, "on", on)
        monkeypatch.setitem(_far._COMPILED, "from", frm)
        out[name] = _far_cols.sums(ct, x, cols, kinds)
    for name in out:
        assert np.array_equal(out[name], out["numpy"]), name
    alone = _far_cols.sums(ct, x[7:8], cols, kinds)
    assert np.array_equal(alone, out["numpy"][:, 7:8])


@pytest.mark.parametrize("control", ["depth", "force"])
def test_sampled_paraboloid_against_its_closed_form(control):
    r = np.linspace(0.0, 1e-3, 10**4)
    tab = Tabulated(r, r * r / (2 * R), "cubic")
    assert tab._cubic_tree() is not None
    ct, cp = cl.Contact(tab, MATS, rtol=1e-10), cl.Contact(Paraboloid(R), MATS)
    a = np.random.default_rng(5).uniform(0.05e-3, 0.9e-3, 30)
    exact = cp.normal(radius=a)
    st = ct.normal(**{control: np.asarray(getattr(exact, control))})
    # the spline reproduces a parabola (up to its end conditions' rounding): the solve's
    # tolerance and the sums' rounding are all that is left
    assert np.max(np.abs(np.asarray(st.radius) / a - 1)) <= 1e-9


def test_cubic_batch_on_a_large_table_forms_no_dense_contractions(monkeypatch):
    """Regression: the cubic table's node sums contracted every point with every node below
    it (weighted_row_sums of (point, node) blocks, O(N M)); the tree never calls them."""
    tab = _sphere()
    c = cl.Contact(tab, MATS, rtol=1e-6)

    def refuse(*args, **kwargs):
        raise AssertionError("dense (point, node) contraction on a 10^4-point table")

    monkeypatch.setattr(_cubic, "weighted_row_sums", refuse)
    d = np.random.default_rng(2).uniform(1e-8, 2.4e-5, 500)
    st = c.normal(depth=d)
    c.normal(force=np.asarray(st.force))


def test_force_step_pass_equals_the_separate_passes_bit_for_bit():
    """The cubic force solve's one tree pass for g, g' and ∫g gives the bits of the separate
    kernels (and leaves no memo behind)."""
    tab = _wavy()
    x = _points(tab)
    g, gp, integral = tab._cubic_g_slope_integral(x)
    g2, gp2 = tab._g_and_slope(x)
    assert np.array_equal(g, g2)
    assert np.array_equal(gp, gp2, equal_nan=True)
    assert np.array_equal(integral, tab._g_integral_closed_form(x))
    assert "_cubic_pair" not in tab.__dict__
