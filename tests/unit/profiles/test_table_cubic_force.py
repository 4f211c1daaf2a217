"""The spline table's radius solves (issue 29): a cubic Hermite start from the node values and
slopes, Newton steps on the column tree's signed columns with the rounding estimate checked at
the radius, the column sums there kept for the depth and ∫g asked next, and the node values of a
large batch evaluated in one pass.

Checked: the Hermite start in plain floats against the batch (bit for bit, degenerate
intervals included), the signed-column pass against the full node sums (bit for bit), the
force state against the radius state of a fresh table at the same radii (the kept sums give the
bits computed apart), the fallback to the full route where the estimate is too large, a batch
that evaluates every node against one load per call (bit for bit), and the number of passes
(the regression guard).
"""
from __future__ import annotations

import numpy as np
import pytest

import contactlab as cl
from contactlab.profiles import Tabulated
from contactlab.profiles.tabulated import _cubic, _far_cols, _solve

R = 0.01
MATS = (cl.Elastic(E=210e9, nu=0.3), cl.Rigid())


def _sphere(n: int = 10**4, kind: str = "cubic") -> Tabulated:
    r = np.linspace(0.0, 1e-3, n)
    return Tabulated(r, R - np.sqrt(R * R - r * r), kind)


def _wavy(n: int = 10**4) -> Tabulated:
    r = np.linspace(0.0, 1e-3, n)
    return Tabulated(r, r * r / 0.02 + 2e-7 * np.sin(r / 3e-5), "cubic")


def test_hermite_start_in_floats_is_the_batch_bit_for_bit():
    rng = np.random.default_rng(7)
    m = 400
    v0 = rng.uniform(0, 1, m)
    dv = rng.uniform(0, 1, m) ** 3
    dv[:20] = 0.0                                    # flat intervals: not ok
    v1 = v0 + dv
    h = rng.uniform(1e-6, 1e-3, m)
    s0 = rng.uniform(0, 2, m) * dv / h
    s1 = rng.uniform(0, 2, m) * dv / h
    s0[20:30] = 0.0
    s1[20:30] = 0.0
    s0[30:40] = -s0[30:40] * 50                      # wild slopes: Newton may leave [0, 1]
    target = v0 + rng.uniform(0, 1, m) * dv
    t, ok = _solve._hermite_start(target, v0, v1, s0, s1, h)
    assert 0 < ok.sum() < m
    for i in range(m):
        one = _solve._hermite_start_one(target[i], v0[i], v1[i], s0[i], s1[i], h[i])
        if ok[i]:
            assert one is not None and np.float64(one).tobytes() == t[i].tobytes(), i
        else:
            assert one is None, i
    # on a cubic the start is the root itself (to rounding)
    x = np.linspace(0.0, 1.0, 5)
    a, b = x[1], x[2]
    f = lambda z: 1 + z + z**2 + z**3                # noqa: E731
    fp = lambda z: 1 + 2 * z + 3 * z**2              # noqa: E731
    root = a + 0.3 * (b - a)
    tt, okk = _solve._hermite_start(np.array([f(root)]), np.array([f(a)]), np.array([f(b)]),
                                    np.array([fp(a)]), np.array([fp(b)]), np.array([b - a]))
    assert okk[0] and abs(tt[0] - 0.3) < 1e-14


@pytest.mark.parametrize("make", [_sphere, _wavy])
def test_signed_pass_is_the_full_node_sums_bit_for_bit(make):
    tab = make()
    assert tab._cubic_tree() is not None
    rng = np.random.default_rng(3)
    x = np.concatenate([rng.uniform(0.0, tab.r[-1], 500), tab.r[[1, 7, 611, 4999]], [0.0]])
    g, gp, gi = tab._cubic_signed_pass(x)
    g0, _, gp0 = tab._cubic_sums(x, "g", with_slope=True)
    gi0 = tab._cubic_sums(x, "int")[0]
    assert np.array_equal(g, g0) and np.array_equal(gp, gp0) and np.array_equal(gi, gi0)


@pytest.mark.parametrize("make", [_sphere, _wavy])
def test_force_state_is_the_radius_state_at_its_radii(make):
    """The depth and ∫g of a force solve come from the column sums kept at its radii: the
    bits a fresh table computes at the same radii."""
    tab, fresh = make(), make()
    c, cf = cl.Contact(tab, MATS, rtol=1e-6), cl.Contact(fresh, MATS, rtol=1e-6)
    d = np.random.default_rng(5).uniform(1e-8, 2.4e-5, 300)
    F = np.asarray(c.normal(depth=d).force)
    st = c.normal(force=F)
    ref = cf.normal(radius=np.asarray(st.radius))
    assert np.array_equal(np.asarray(st.depth), np.asarray(ref.depth))
    assert np.array_equal(np.asarray(st.force), np.asarray(ref.force))
    # and the force is the one requested, within the contact's tolerance (rtol)
    assert np.max(np.abs(np.asarray(st.force) / F - 1)) < 1e-6


def test_radii_whose_estimate_is_too_large_are_solved_on_the_full_route(monkeypatch):
    """With every estimate 'too large' (CUBIC_SUM_RTOL = 0) each radius is redone with the
    full node sums: the radius a solve on the full route gives from the start."""
    monkeypatch.setattr(_cubic, "CUBIC_SUM_RTOL", 0.0)
    tab, full = _sphere(), _sphere()
    full._cubic_signed_pass = full._cubic_g_slope_integral      # the full route throughout
    F = np.asarray(cl.Contact(_sphere(), MATS, rtol=1e-6).normal(
        depth=np.random.default_rng(9).uniform(1e-8, 2.4e-5, 50)).force)
    a = np.asarray(cl.Contact(tab, MATS, rtol=1e-6).normal(force=F).radius)
    a_full = np.asarray(cl.Contact(full, MATS, rtol=1e-6).normal(force=F).radius)
    assert np.array_equal(a, a_full)


@pytest.mark.parametrize("kind", ["linear", "cubic"])
@pytest.mark.parametrize("control", ["depth", "force"])
def test_batch_that_evaluates_every_node_is_one_load_per_call(kind, control):
    """The second batch of at least 1/_FILL_PER_LOAD loads per node evaluates every node once
    (the first only the nodes its searches visit); a load alone evaluates the few its search
    visits: the same bits."""
    big, small = _sphere(1200, kind), _sphere(1200, kind)
    cb, cs = cl.Contact(big, MATS, rtol=1e-6), cl.Contact(small, MATS, rtol=1e-6)
    d = np.random.default_rng(4).uniform(1e-8, 2.4e-5, 100)
    vals = d if control == "depth" else np.asarray(
        cl.Contact(_sphere(1200, kind), MATS, rtol=1e-6).normal(depth=d).force)
    first = cb.normal(**{control: vals})
    memo = big._node_g if control == "depth" else big.__dict__["_node_H"]
    assert np.any(np.isnan(memo))                     # (the first batch: its searches only)
    st = cb.normal(**{control: vals})
    assert not np.any(np.isnan(memo))                 # (every node evaluated)
    for name in ("radius", "depth", "force"):
        assert np.array_equal(np.asarray(getattr(st, name)), np.asarray(getattr(first, name)))
    one = [cs.normal(**{control: float(v)}) for v in vals]
    assert np.any(np.isnan(small._node_g))
    for name in ("radius", "depth", "force"):
        assert np.array_equal(np.asarray(getattr(st, name)),
                              np.array([float(getattr(s, name)) for s in one])), name


@pytest.mark.parametrize("control", ["depth", "force"])
def test_cubic_solve_makes_one_newton_pass_at_rtol_1e_6(control, monkeypatch):
    """Regression: 10^3 random loads on a 10^4-point cubic table took two Newton passes over
    every column (force: then g and ∫g in two more passes); with the Hermite start one pass
    (force: the 8 signed columns, then one pass at the radius over the 12 columns the depth
    and ∫g need: not g's slope columns)."""
    tab = _sphere()
    c = cl.Contact(tab, MATS, rtol=1e-6)
    rng = np.random.default_rng(2)
    for _ in range(2):                  # (from the second batch: every node evaluated once)
        d0 = rng.uniform(1e-8, 2.4e-5, 1000)
        c.normal(force=np.asarray(c.normal(depth=d0).force))
    d = rng.uniform(1e-8, 2.4e-5, 1000)
    vals = d if control == "depth" else np.asarray(c.normal(depth=d).force)
    calls: list[tuple[int, int]] = []
    real = _far_cols.sums

    def counted(ct, x, cols, kinds, terms=_far_cols._far.TERMS):
        calls.append((int(x.size), int(cols.size)))
        return real(ct, x, cols, kinds, terms)

    monkeypatch.setattr(_far_cols, "sums", counted)
    c.normal(**{control: vals})
    if control == "depth":
        # the Newton pass (g and g'), then ∫g with its estimate at the radius
        assert calls == [(1000, 8), (1000, 10)], calls
    else:
        assert calls == [(1000, 8), (1000, 12)], calls
