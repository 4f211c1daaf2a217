"""The far-field trees' Taylor terms chosen from the call's rtol (issue 29: accuracy that buys
speed).

Checked: the term counts (all 20 at the default rtol 1e-10 and below, fewer as rtol loosens);
the compiled pass, the numpy route and the plain Python logic give the same bits at every term
count (linear and cubic trees); the truncation bound covers the truncation actually made (the
tree's sums with few terms against its 20-term sums, every slot); the error estimates of g and
∫g at rtol 1e-2 .. 1e-10 cover the true error against 30-digit mpmath sums of the same nodes
(linear) and against the dense node sums (cubic), and stay below rtol; the default rtol keeps
the bits of the 20-term sums; a loose rtol reaches the trees (depth and force control) and a
call without one keeps the enclosing call's terms.
"""
from __future__ import annotations

import numpy as np
import pytest

import contactlab as cl
from contactlab.profiles import Tabulated
from contactlab.profiles.tabulated import _base, _far, _far_cols
from tests.tolerances import TABLE_FAR_FIELD_SUMS

R = 0.01
MATS = (cl.Elastic(E=210e9, nu=0.3), cl.Rigid())
RTOLS = [1e-2, 1e-3, 1e-6, 1e-8, 1e-10]


def _random(kind: str, n: int = 10**4) -> Tabulated:
    rng = np.random.default_rng(7)
    r = np.sort(rng.uniform(0.0, 1e-3, n))
    r[0] = 0.0
    return Tabulated(r, r * r / 0.02 + 1e3 * r**3 + 1e-10 * rng.standard_normal(n), kind)


def _wavy(kind: str, n: int = 10**4) -> Tabulated:
    r = np.linspace(0.0, 1e-3, n)
    return Tabulated(r, r * r / 0.02 + 2e-7 * np.sin(r / 3e-5), kind)


def _rough(kind: str) -> Tabulated:
    """Random nodes (linear; a cubic spline through them clusters its jump nodes and keeps the
    dense sums) or a wavy profile (cubic)."""
    return _random(kind) if kind == "linear" else _wavy(kind)


def _sphere(kind: str, n: int = 10**4) -> Tabulated:
    r = np.linspace(0.0, 1e-3, n)
    return Tabulated(r, R - np.sqrt(R * R - r * r), kind)


def _no_tree(tab: Tabulated) -> Tabulated:
    tab.__dict__["_far_cache"] = (None,)
    tab.__dict__["_cubic_tree_cache"] = (None,)
    return tab


def _points(tab: Tabulated, n: int = 200) -> np.ndarray:
    rng = np.random.default_rng(3)
    nodes = tab.r[[2, 150, 611, 4999, tab.r.size - 2]]
    return np.concatenate([rng.uniform(1e-6, tab.r[-1], n), nodes, [tab.r[-1]]])


def test_term_counts_fall_as_rtol_loosens_and_the_default_keeps_all():
    ratios = 5.0 ** -np.arange(_far.TERMS + 1.0)
    rtols = [1e-12, 1e-10, 1e-8, 1e-6, 1e-3, 1e-2, 0.1, 1.0]
    counts = [_far.terms_from_ratios(rt, ratios) for rt in rtols]
    assert counts[:2] == [_far.TERMS, _far.TERMS]
    assert counts == sorted(counts, reverse=True)
    assert min(counts) == _far.TERMS_MIN
    for rt, n in zip(rtols[2:], counts[2:]):
        assert ratios[n] <= _far.TAIL * rt and (n == _far.TERMS_MIN
                                                 or ratios[n - 1] > _far.TAIL * rt)
    assert _far.terms_from_ratios(1e-2, np.full(_far.TERMS + 1, np.inf)) == _far.TERMS
    tab = _sphere("linear")                     # the sampled sphere: 9, 5, 4 terms
    assert [_far.terms_from_ratios(rt, tab._tree_excess()) for rt in (1e-6, 1e-3, 1e-2)] \
        == [9, 5, 4]


@pytest.mark.parametrize("terms", [4, 6, 8, 12, 15])
def test_routes_give_the_same_bits_at_every_term_count(monkeypatch, terms):
    tab, cub = _random("linear"), _wavy("cubic")
    tree, ct = tab._far_tree(), cub._cubic_tree()
    assert tree is not None and ct is not None
    x = np.sort(_points(tab, 150))
    cols = np.array([0, 1, 2, 3, 4, 5, 8, 9, 12, 13])
    kinds = np.array([_far_cols.ACOS] * 4 + [_far_cols.ROOT] * 4 + [_far_cols.ROOT3] * 2)
    routes = {"numpy": (True, 10**9), "python": (False, 0)}
    try:
        import numba  # noqa: F401
        routes["numba"] = (True, 0)
    except ImportError:
        pass
    lin, col = {}, {}
    for name, (on, frm) in routes.items():
        monkeypatch.setitem(_far._COMPILED, "on", on)
        monkeypatch.setitem(_far._COMPILED, "from", frm)
        lin[name] = _far.sums(tree, x, True, True, terms)
        col[name] = _far_cols.sums(ct, x, cols, kinds, terms)
    for name in routes:
        for v, ref in zip(lin[name], lin["numpy"]):
            assert np.array_equal(v, ref, equal_nan=True), name
        assert np.array_equal(col[name], col["numpy"]), name
    # fewer terms: different sums (the count reaches both routes)
    assert not np.array_equal(lin["numpy"][0], _far.sums(tree, x, False, False)[0])


@pytest.mark.parametrize("terms", [4, 6, 8, 12])
def test_truncation_bound_covers_the_truncation(terms):
    """The tree's sums after ``terms`` terms against its 20-term sums (whose own truncation,
    below 2e-14 of Σ|w|, and rounding are far below the bound): within the bound."""
    for kind in ("linear", "cubic"):
        tab = _rough(kind)
        x = _points(tab)
        full = (tab._g_closed_form(x), tab._g_integral_closed_form(x))
        _base._call_terms()[id(tab)] = terms
        try:
            few = (tab._g_closed_form(x), tab._g_integral_closed_form(x))
            trunc = (tab._cubic_truncation(x, "g"), tab._cubic_truncation(x, "int")) \
                if kind == "cubic" else (tab._far_truncation(x, "g"),
                                         tab._far_truncation(x, "int"))
        finally:
            _base._call_terms().pop(id(tab))
        for f, v, b in zip(full, few, trunc):
            assert np.all(b >= 0) and np.any(b > 0)
            assert np.all(np.abs(v - f) <= b), kind
            assert np.any(v != f)


@pytest.mark.parametrize("rtol", RTOLS)
def test_linear_estimates_cover_30_digit_sums(rtol):
    mpmath = pytest.importorskip("mpmath")
    tab = _random("linear")
    jump = tab._dslope != 0
    b, w = tab.r[1:-1][jump], tab._dslope[jump]
    x = np.array([3.3e-6, 1.234e-4, 5.0e-4, 9.87654e-4])
    g, eg = tab._g_with_error(x, rtol)
    gi, ei = tab._g_integral_with_error(x, rtol)
    with mpmath.workdps(30):
        for i, xi in enumerate(x):
            X = mpmath.mpf(float(xi))
            k = int(np.searchsorted(tab.r, xi, side="right") - 1)
            sk = mpmath.mpf(float(tab._slopes[k]))
            m = int(np.searchsorted(b, xi, side="right"))
            A = P = mpmath.mpf(0)
            for bj, wj in zip(b[:m].tolist(), w[:m].tolist()):
                B, W = mpmath.mpf(bj), mpmath.mpf(wj)
                asin = mpmath.asin(B / X)
                A += W * asin
                P += W * (B * mpmath.sqrt(X * X - B * B) + X * X * asin) / 2
            ref_g = X * (mpmath.pi / 2 * sk - A)
            ref_i = sk * mpmath.pi / 4 * X * X - P
            assert abs(float(ref_g - g[i])) <= eg[i]
            assert abs(float(ref_i - gi[i])) <= ei[i]
            assert eg[i] <= rtol * abs(g[i]) and ei[i] <= rtol * abs(gi[i])


@pytest.mark.parametrize("rtol", RTOLS)
@pytest.mark.parametrize("make", [_rough, _sphere])
def test_estimates_cover_the_node_by_node_sums(make, rtol):
    """Many points, linear and cubic: the tree's values at rtol within their estimate of the
    route without the tree, plus that route's estimate and the rounding difference of the two
    routes with all terms (tested to the terms' magnitudes in test_table_far_field*: on the
    noisy table it exceeds the linear route's rounding floor); the estimate within rtol."""
    for kind in ("linear", "cubic"):
        tab, ref = make(kind), _no_tree(make(kind))
        x = _points(tab)
        for name in ("_g_with_error", "_g_integral_with_error"):
            v, e = getattr(tab, name)(x, rtol)
            v0, e0 = getattr(ref, name)(x, 1e-10)
            v20 = getattr(tab, name)(x, 1e-10)[0]
            slack = e0 + np.abs(v20 - v0) + TABLE_FAR_FIELD_SUMS * np.abs(v0)
            assert np.all(np.abs(v - v0) <= e + slack), (kind, name)
            if rtol >= 1e-6:
                assert np.all(e <= rtol * np.abs(v)), (kind, name)


@pytest.mark.parametrize("kind", ["linear", "cubic"])
def test_default_rtol_keeps_the_bits_of_all_terms(kind):
    tab = _sphere(kind)
    x = _points(tab)
    g20, i20 = tab._g_closed_form(x), tab._g_integral_closed_form(x)
    for rtol in (None, 1e-10, 1e-12):
        v, e = tab._g_with_error(x, rtol)
        assert np.array_equal(v, g20)
        assert np.array_equal(e, tab._g_with_error(x, 1e-10)[1])
        assert np.array_equal(tab._g_integral_with_error(x, rtol)[0], i20)
    assert not np.any(tab._far_truncation(x, "g")) and not np.any(tab._cubic_truncation(x, "g"))


@pytest.mark.parametrize("kind", ["linear", "cubic"])
@pytest.mark.parametrize("control", ["depth", "force"])
def test_a_loose_rtol_reaches_every_tree_pass(monkeypatch, kind, control):
    """Regression: every tree pass of a contact at rtol 1e-6 takes its fewer terms (the
    force control's depth at the solved radii included: profile._g without a tree setting of
    its own)."""
    seen = []
    lin, col = _far.sums, _far_cols.sums

    def spy_lin(tree, x, cusp, phi, terms=_far.TERMS):
        seen.append(terms)
        return lin(tree, x, cusp, phi, terms)

    def spy_col(ct, x, cols, kinds, terms=_far.TERMS):
        seen.append(terms)
        return col(ct, x, cols, kinds, terms)

    monkeypatch.setattr(_far, "sums", spy_lin)
    monkeypatch.setattr(_far_cols, "sums", spy_col)
    tab = _sphere(kind)
    c = cl.Contact(tab, MATS, rtol=1e-6)
    d = np.random.default_rng(4).uniform(1e-9, 2.4e-5, 300)
    vals = d if control == "depth" else np.asarray(
        cl.Contact(_sphere(kind), MATS).normal(depth=d).force)
    tab._tree_excess()          # (set up once per table, on 64 radii with all terms)
    seen.clear()
    c.normal(**{control: vals})
    assert seen and set(seen) == {_far.terms_from_ratios(1e-6, tab._tree_excess())} != {_far.TERMS}
    assert id(tab) not in _base._call_terms()     # (the setting ends with the call)


def test_a_call_without_rtol_keeps_the_enclosing_calls_terms():
    tab = _sphere("linear")
    loose, mid = (_far.terms_from_ratios(rt, tab._tree_excess()) for rt in (1e-3, 1e-6))
    assert loose < mid < _far.TERMS
    with tab._tree_rtol(1e-3):
        assert tab._tree_terms() == loose
        with tab._tree_rtol(None):
            assert tab._tree_terms() == loose
        with tab._tree_rtol(1e-6):
            assert tab._tree_terms() == mid
        assert tab._tree_terms() == loose
    assert tab._tree_terms() == _far.TERMS
    with tab._tree_rtol(None):                  # outside a call: the table's rtol (1e-10)
        assert tab._tree_terms() == _far.TERMS


def test_a_table_whose_jumps_cancel_takes_more_terms():
    """The noisy random table's slope jumps cancel (their Σ|w| is 10^4 times its g): its bound
    relative to g is far above the sampled sphere's, so the same rtol takes more terms."""
    smooth, noisy = _sphere("linear"), _random("linear")
    assert noisy._tree_excess()[8] > 100 * smooth._tree_excess()[8]
    with smooth._tree_rtol(1e-3), noisy._tree_rtol(1e-3):
        assert noisy._tree_terms() > smooth._tree_terms()


def test_a_calls_terms_belong_to_its_thread():
    """The terms of a call in progress are the calling thread's: a call on the same table from
    another thread meanwhile (at the default rtol) takes all the terms and gives the bits it
    gives alone."""
    import threading
    tab = _sphere("cubic")
    x = _points(tab)
    alone = tab._g_closed_form(x)
    seen: dict = {}

    def other():
        seen["terms"] = tab._tree_terms()
        with tab._tree_rtol(None):
            seen["g"] = tab._g_closed_form(x)

    with tab._tree_rtol(1e-2):
        assert tab._tree_terms() < _far.TERMS
        t = threading.Thread(target=other)
        t.start()
        t.join()
        assert tab._tree_terms() < _far.TERMS
    assert seen["terms"] == _far.TERMS
    assert seen["g"].tobytes() == alone.tobytes()
