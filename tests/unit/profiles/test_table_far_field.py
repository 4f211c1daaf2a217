"""Node sums of large linear tables over a dyadic tree (issue 29: 10^3 depths on a 10^4-point
table in one pass of O(log N) per depth).

Checked: the tree's g, g' and ∫g against the node-by-node sums (the route before, still taken by
small tables) on even, random and wavy tables, to rounding; against 30-digit mpmath sums of the
same nodes; batch against one call per load (bit-identical, depth and force control, unsorted,
duplicates, loads at nodes); the compiled pass against its numpy reference and its plain Python
logic (bit-identical); the sampled paraboloid against its closed form to the interpolation bound;
the tables that keep the node-by-node sums (small, clustered); and the regression guard: a batch
of depths on a 10^4-point table never forms the dense (point, node) sums.
"""
from __future__ import annotations

import numpy as np
import pytest

import contactlab as cl
from contactlab.profiles import Paraboloid, Tabulated
from contactlab.profiles.tabulated import _far, _linear
from tests.tolerances import TABLE_FAR_FIELD_SUMS, TABLE_LINEAR_RANDOM_RADII_10K

R = 0.01
MATS = (cl.Elastic(E=210e9, nu=0.3), cl.Rigid())


def _sphere_table(n: int = 10**4) -> Tabulated:
    r = np.linspace(0.0, 1e-3, n)
    return Tabulated(r, R - np.sqrt(R * R - r * r))


def _random_table(n: int = 10**4) -> Tabulated:
    rng = np.random.default_rng(7)
    r = np.sort(rng.uniform(0.0, 1e-3, n))
    r[0] = 0.0
    return Tabulated(r, r * r / 0.02 + 1e3 * r**3 + 1e-10 * rng.standard_normal(n))


def _wavy_table(n: int = 10**4) -> Tabulated:
    r = np.linspace(0.0, 1e-3, n)
    return Tabulated(r, r * r / 0.02 + 2e-7 * np.sin(r / 3e-5))


def _node_by_node(tab: Tabulated) -> Tabulated:
    tab.__dict__["_far_cache"] = (None,)
    return tab


def _points(tab: Tabulated, n: int = 400, seed: int = 1) -> np.ndarray:
    rng = np.random.default_rng(seed)
    nodes = tab.r[[1, 2, 7, 150, 611, 4999, tab.r.size - 2]]
    return np.concatenate([rng.uniform(0.0, tab.r[-1], n), nodes, nodes * (1 + 1e-12),
                           [0.0, 1e-300, 1e-12, tab.r[-1]]])


def _magnitudes(tab: Tabulated, x: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The sizes of the sums' terms before they cancel (g, g', ∫g), node by node in numpy."""
    jump = tab._dslope != 0
    b, w = tab.r[1:-1][jump], np.abs(tab._dslope[jump])
    s0 = float(np.max(np.abs(tab._slopes)))
    xp = x[:, None]
    below = b[None, :] < xp
    with np.errstate(divide="ignore", invalid="ignore"):
        t = np.where(below, b[None, :] / np.where(xp > 0, xp, 1.0), 0.0)
        asin = np.arcsin(t)
        cusp = np.where(below, t / np.sqrt(1 - t * t), 0.0)
    mg = x * (0.5 * np.pi * s0 + (w * asin).sum(1))
    ms = 0.5 * np.pi * s0 + (w * (asin + cusp)).sum(1)
    mi = x * x * (0.25 * np.pi * s0 + (w * asin).sum(1))
    return mg, ms, mi


@pytest.mark.parametrize("make", [_sphere_table, _random_table, _wavy_table])
def test_tree_sums_agree_with_the_node_by_node_sums(make):
    tree_tab, node_tab = make(), _node_by_node(make())
    assert tree_tab._far_tree() is not None
    x = _points(tree_tab)
    g, gp, integral = tree_tab._g_slope_integral(x)
    g0, gp0, integral0 = node_tab._g_slope_integral(x)
    mg, ms, mi = _magnitudes(tree_tab, x)
    assert np.all(np.abs(g - g0) <= TABLE_FAR_FIELD_SUMS * mg)
    assert np.all(np.abs(integral - integral0) <= TABLE_FAR_FIELD_SUMS * mi)
    finite = np.isfinite(gp0)                  # (g' is infinite at a node with a slope jump)
    assert np.array_equal(np.isfinite(gp), finite)
    assert np.all(np.abs(gp[finite] - gp0[finite]) <= TABLE_FAR_FIELD_SUMS * ms[finite])
    # the separate kernels give the bits of the one pass, as on the node-by-node route
    assert np.array_equal(g, tree_tab._g_closed_form(x))
    assert np.array_equal(integral, tree_tab._g_integral_closed_form(x))
    assert np.array_equal(gp, tree_tab._g_and_slope(x)[1])


def test_tree_sums_against_30_digit_sums_of_the_same_nodes():
    mpmath = pytest.importorskip("mpmath")
    tab = _random_table()
    jump = tab._dslope != 0
    b, w = tab.r[1:-1][jump], tab._dslope[jump]
    x = np.array([3.3e-6, 1.234e-4, 5.0e-4, 9.87654e-4])
    g, gp, integral = tab._g_slope_integral(x)
    mg, ms, mi = _magnitudes(tab, x)
    with mpmath.workdps(30):
        for i, xi in enumerate(x):
            X = mpmath.mpf(float(xi))
            k = int(np.searchsorted(tab.r, xi, side="right") - 1)
            sk = mpmath.mpf(float(tab._slopes[k]))
            m = int(np.searchsorted(b, xi, side="right"))
            A = C = P = mpmath.mpf(0)
            for bj, wj in zip(b[:m].tolist(), w[:m].tolist()):
                B, W = mpmath.mpf(bj), mpmath.mpf(wj)
                root = mpmath.sqrt(X * X - B * B)
                A += W * mpmath.asin(B / X)
                C += W * B / root
                P += W * (B * root + X * X * mpmath.asin(B / X)) / 2
            ref_g = X * (mpmath.pi / 2 * sk - A)
            ref_gp = mpmath.pi / 2 * sk - A + C
            ref_i = sk * mpmath.pi / 4 * X * X - P
            assert abs(float(ref_g - g[i])) <= TABLE_FAR_FIELD_SUMS * mg[i]
            assert abs(float(ref_gp - gp[i])) <= TABLE_FAR_FIELD_SUMS * ms[i]
            assert abs(float(ref_i - integral[i])) <= TABLE_FAR_FIELD_SUMS * mi[i]


@pytest.mark.parametrize("control", ["depth", "force"])
def test_batch_equals_one_call_per_load_bit_for_bit(control):
    tab = _sphere_table()
    c = cl.Contact(tab, MATS, rtol=1e-6)
    rng = np.random.default_rng(3)
    d = rng.uniform(1e-9, 2.4e-5, 40)
    at_nodes = np.asarray(tab.g(tab.r[[7, 150, 611, 4999]]), dtype=float)
    d = np.concatenate([d, d[:5], at_nodes, at_nodes[:2]])
    vals = d if control == "depth" else np.asarray(c.normal(depth=d).force)
    st = c.normal(**{control: vals})
    one = [c.normal(**{control: float(v)}) for v in vals]
    for name in ("radius", "depth", "force"):
        batch = np.asarray(getattr(st, name))
        single = np.array([float(getattr(s, name)) for s in one])
        assert np.array_equal(batch, single), name
    assert np.array_equal(np.asarray(st.radius)[40:45], np.asarray(st.radius)[:5])


@pytest.mark.parametrize("rtol", [1e-10, 1e-6])
@pytest.mark.parametrize("control", ["depth", "force"])
def test_solve_agrees_with_the_node_by_node_route(control, rtol):
    tree_c = cl.Contact(_sphere_table(), MATS, rtol=rtol)
    node_c = cl.Contact(_node_by_node(_sphere_table()), MATS, rtol=rtol)
    d = np.random.default_rng(4).uniform(1e-9, 2.4e-5, 200)
    vals = d if control == "depth" else np.asarray(node_c.normal(depth=d).force)
    a, b = tree_c.normal(**{control: vals}), node_c.normal(**{control: vals})
    for name in ("radius", "depth", "force"):
        x, y = np.asarray(getattr(a, name)), np.asarray(getattr(b, name))
        # the default rtol: the same Newton steps on sums equal to rounding, the same root to
        # rounding; a loose one: the tree's Taylor series truncated for rtol (terms_from_ratios),
        # within rtol
        tol = TABLE_FAR_FIELD_SUMS if rtol <= _far.FULL_TERMS_RTOL else rtol
        assert np.max(np.abs(x / y - 1)) <= tol, name


def test_compiled_pass_numpy_route_and_python_logic_give_the_same_bits(monkeypatch):
    tab = _random_table()
    tree = tab._far_tree()
    assert tree is not None
    x = np.sort(_points(tab, 300))
    x = x[x > 0]
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
        out[name] = _far.sums(tree, x, True, True)
    for name in out:
        for v, ref in zip(out[name], out["numpy"]):
            assert np.array_equal(v, ref, equal_nan=True), name


def test_a_point_alone_gives_its_bits_in_any_batch():
    tab = _random_table()
    tree = tab._far_tree()
    assert tree is not None
    x = _points(tab, 200)
    x = x[x > 0]
    batch = _far.sums(tree, x, True, True)
    for i in (0, 17, 199, x.size - 1):
        alone = _far.sums(tree, x[i:i + 1], True, True)
        for v, ref in zip(alone, batch):
            assert np.array_equal(v, ref[i:i + 1])


@pytest.mark.parametrize("control", ["depth", "force"])
def test_sampled_paraboloid_within_the_tables_interpolation_bound(control):
    r = np.linspace(0.0, 1e-3, 10**4)
    tab = Tabulated(r, r * r / (2 * R))
    assert tab._far_tree() is not None
    ct, cs = cl.Contact(tab, MATS, rtol=1e-10), cl.Contact(Paraboloid(R), MATS)
    a = np.random.default_rng(5).uniform(0.05e-3, 0.9e-3, 50)
    exact = cs.normal(radius=a)
    vals = np.asarray(exact.depth if control == "depth" else exact.force)
    st = ct.normal(**{control: vals})
    bound = TABLE_LINEAR_RANDOM_RADII_10K * ((tab.r[1] - tab.r[0]) / a) ** 2
    assert np.all(np.abs(np.asarray(st.radius) / a - 1) < bound)
    other = "force" if control == "depth" else "depth"
    assert np.all(np.abs(np.asarray(getattr(st, other)) / np.asarray(getattr(exact, other)) - 1)
                  < 2 * bound)


def test_small_and_clustered_tables_keep_the_node_by_node_sums():
    small = _sphere_table(_far.FAR_FIELD_FROM)          # FAR_FIELD_FROM - 2 jump nodes
    assert small._far_tree() is None
    r = np.concatenate([np.linspace(0.0, 1e-3, 6000), 5e-4 + 1e-9 * np.arange(1, 200)])
    r = np.unique(r)
    clustered = Tabulated(r, r * r / 0.02)
    assert clustered._far_tree() is None
    ok = np.asarray(clustered.g(np.array([5.0001e-4, 9e-4])), dtype=float)
    assert np.all(np.isfinite(ok))


def test_depth_batch_on_a_large_table_forms_no_dense_node_sums(monkeypatch):
    """Regression: 10^3 depths on a 10^4-point linear table summed every point against every
    node below it (row_sums of a (point, node) block per pass, O(N M)); the tree takes
    O(log N) per point and never calls them."""
    tab = _sphere_table()
    c = cl.Contact(tab, MATS, rtol=1e-6)

    def refuse(*args, **kwargs):
        raise AssertionError("dense (point, node) sums on a 10^4-point table")

    monkeypatch.setattr(_linear, "row_sums", refuse)
    d = np.random.default_rng(2).uniform(1e-8, 2.4e-5, 1000)
    st = c.normal(depth=d)
    c.normal(force=np.asarray(st.force))


def test_block_moments_from_children_equal_the_direct_sums():
    """The coarser levels' moments come from their children (binomial re-expansion); against
    the moments summed directly from the nodes, to the rounding of the offsets ``u = (b - c)/h``
    (an ulp of b over h: ``eps r_end / h``) times n, of Σ|w| (measured 5.8e-13 at n = 19 on
    level 11, whose bound here is 1.5e-10)."""
    tab = _random_table()
    jump = tab._dslope != 0
    b, w = tab.r[1:-1][jump], tab._dslope[jump]
    levels, finest = _far.layout(b, float(tab.r[-1]))
    per_level = _far.level_moments(b, w[None, :], float(tab.r[-1]), levels, finest)
    for L in (1, 4, levels - 1):
        k = finest >> (levels - L)
        width = tab.r[-1] * 2.0**-L
        u = (b - (k + 0.5) * width) / (0.5 * width)
        scale = np.bincount(k, weights=np.abs(w), minlength=2**L)
        for n in (0, 1, 7, _far.TERMS - 1):
            direct = np.bincount(k, weights=w * u**n, minlength=2**L)
            bound = 8 * np.finfo(float).eps * (n + 1) * 2.0 ** (L + 1) * scale
            assert np.all(np.abs(per_level[L - 1][:, 0, n] - direct) <= bound)


def test_a_capped_tree_sums_more_near_nodes_to_the_same_values():
    """A tree capped at a coarse finest level (as 10^6-node tables are) leaves more nodes to
    the exact near zone: the sums stay those of the node-by-node route."""
    tab, node_tab = _sphere_table(), _node_by_node(_sphere_table())
    jump = tab._dslope != 0
    capped = _far.build(tab.r[1:-1][jump], tab._dslope[jump], float(tab.r[-1]), max_levels=8)
    assert capped is not None and capped.levels == 8
    tab.__dict__["_far_cache"] = (capped,)
    x = _points(tab)
    g, gp, integral = tab._g_slope_integral(x)
    g0, gp0, integral0 = node_tab._g_slope_integral(x)
    mg, ms, mi = _magnitudes(tab, x)
    finite = np.isfinite(gp0)
    assert np.all(np.abs(g - g0) <= TABLE_FAR_FIELD_SUMS * mg)
    assert np.all(np.abs(integral - integral0) <= TABLE_FAR_FIELD_SUMS * mi)
    assert np.all(np.abs(gp[finite] - gp0[finite]) <= TABLE_FAR_FIELD_SUMS * ms[finite])


def test_force_solve_sums_depth_and_integral_in_one_tree_pass(monkeypatch):
    """Regression: after a force solve on the tree, the depth g(a) and ∫g(a) at the solved
    radii took two more passes over the tree; they come from one (A and P together, kept by
    _far_prime), with the bits of the separate passes (a fresh table, never primed)."""
    d = np.random.default_rng(5).uniform(1e-8, 2.4e-5, 300)
    F = np.asarray(cl.Contact(_sphere_table(), MATS, rtol=1e-6).normal(depth=d).force)
    tab = _sphere_table()
    c = cl.Contact(tab, MATS, rtol=1e-6)
    c.normal(force=F[:5])                              # (node memo filled)
    calls = []
    orig = _far.sums

    def counted(tree, x, want_cusp, want_phi, terms=_far.TERMS):
        calls.append((x.size, want_cusp, want_phi))
        return orig(tree, x, want_cusp, want_phi, terms)

    monkeypatch.setattr(_far, "sums", counted)
    st = c.normal(force=F)
    # the last Newton pass (it asks for g'), then one pass for g and ∫g (was: two)
    assert calls[-2][1] and calls[-1] == (F.size, False, True)
    monkeypatch.setattr(_far, "sums", orig)
    ref = _sphere_table()
    a = np.asarray(st.radius)
    with ref._tree_rtol(1e-6):                         # (the tree's terms of the call's rtol)
        assert np.array_equal(np.asarray(st.depth), ref._g_closed_form(a))
    assert np.array_equal(ref._g_integral_closed_form(a), tab._g_integral_closed_form(a))
    # a call at other points drops the kept sums
    tab._g_closed_form(a[:7] * 0.5)
    assert "_far_primed" not in tab.__dict__


def test_pair_sums_give_the_bits_of_the_dense_sequential_sums():
    """The numpy routes sum each point's used slots only (_far.used_pairs, _far.slot_sums)
    and near terms by rows (_far.sequential_rows): the bits of the dense left-to-right sums
    with exact zeros in the unused slots, signed zeros, cancellation and empty rows included."""
    rng = np.random.default_rng(11)
    P, S = 300, 36
    used = rng.random((P, S)) < 0.6
    used[7] = False                                   # a point with no used slot
    vals = rng.standard_normal((P, S)) * 10.0 ** rng.integers(-20, 20, (P, S))
    vals[3, :] = -0.0
    vals[5, :2] = (1e300, -1e300)
    dense = np.where(used, vals, 0.0)
    flat, point, bounds = _far.used_pairs(used)
    got = _far.slot_sums(np.take(vals, flat), point, bounds, P)
    assert got.tobytes() == _far._sequential(dense).tobytes()
    assert _far.sequential_rows(dense.T).tobytes() == _far._sequential(dense).tobytes()
    two = np.stack([vals, -vals])                    # several columns at once
    both = _far.slot_sums(np.take(two.reshape(2, -1), flat, axis=1), point, bounds, P)
    assert both[1].tobytes() == _far._sequential(np.where(used, -vals, 0.0)).tobytes()
