"""The traction check inside the stick radius with its memo (:mod:`contactlab.numeric.inside_check`;
issue 28, the row of the ring solver's cost per step against the path length).

Must show: along chains of annulus steps (loading, unloading, a changing force and contact
radius), the memo's interval at every point it holds contains the traction sum of the numpy
route (the invariant the memo's verdicts rest on: it fails if the step's widening bound is
dropped or too small), and the memo carries most points from step to step; every verdict the
memo route gives where it decides is the numpy route's, with friction limits a hair above or
below the traction, and a failed check marks one point whose numpy traction fails (where it
lies deeper inside than an allowance reaches, the numpy check with that allowance fails too); a
memo of another density is not used; the compiled pass gives the plain
function's verdicts and memos; a varying-load path gives the same bits with the memo as without.
"""
import numpy as np
import pytest

import contactlab as cl
from contactlab.numeric import annulus_kernel as ak
from contactlab.numeric import inside_check as ic
from contactlab.numeric import jit
from contactlab.physics import torsion_annulus as ta
from contactlab.physics import torsion_rings as tr

needs_numba = pytest.mark.skipif(not jit.available(), reason="numba (extra 'fast') not installed")
MU = 0.3
_EPS = float(np.finfo(float).eps)


def _plain(name):
    f = getattr(ic, name)
    return getattr(f, "py_func", f)


def _chain(n_rings=50, steps=60, seed=3):
    """(old, new, c, r, table) of a chain of annulus steps: twist up, then back, the force and
    the contact radius changing a little each step."""
    b = np.linspace(0.0, 1.0, n_rings + 1)
    r = 0.5 * (b[1:] + b[:-1])
    lu = tr.influence(b, r, 1.0)["lu"]
    table = ta.NodeTable(r, b)
    rng = np.random.default_rng(seed)
    w = ta.empty()
    out = []
    for k in range(steps):
        radius = float(b[n_rings - (k // 10) % 3])
        bd = np.where(r < radius, MU * np.sqrt(np.clip(1.0 - r * r, 0.0, None))
                      * (1.0 + 0.1 * np.sin(0.3 * k)), 0.0)
        sl = ta.nonnegative_psi(ta.density(lu, b, np.zeros(0, int), bd, radius))
        dphi = (0.004 if k < steps // 2 else -0.006) * (0.5 + rng.random())
        q = ta.step(w, sl, radius, 1.0, dphi=dphi)
        out.append((w, q["w"], q["c"], r, table))
        w = q["w"]
    return out


def _numpy_sums(w, r, table):
    """The numpy route's ``X`` at the points (its traction over ``(4 G_t/π) r``, ``G_t = 1``),
    and the sum of its terms' magnitudes."""
    t = ta.traction(w, r, 1.0, table) / (4.0 / np.pi * r)
    al, be = ta._lin(w)
    c0, c1 = ta._jumps(al, be)
    A, S = table.columns(r, np.append(w[0], w[1][-1]))
    return t, np.abs(A) @ np.abs(c0) + np.abs(S) @ np.abs(c1)


def _arrays(p):
    return [np.ascontiguousarray(a, float) for a in p]


def _memo_call(f, new, old, r, bound, c, table, memo):
    F0, F1 = table.arrays["traction"]
    return f(*_arrays(new), *_arrays(old), r, bound, c, 1.0, ta.CHECK_RTOL, F0, F1, table.r,
             table.nodes, *memo)


def test_memo_intervals_hold_the_numpy_sums_and_carry_most_points():
    f = _plain("inside_memo")
    memo = (np.zeros((4, 0)), np.zeros((3, 0)))
    carried = checked = 0
    for old, new, c, r, table in _chain():
        big = np.full(r.size, 1e9)          # (every point passes: no early verdict)
        prev = memo[1]
        verdict, mx = _memo_call(f, new, old, r, big, c, table, memo)
        memo = (np.vstack(_arrays(new)), mx)
        if verdict == ic.INSIDE_OPEN:           # (pieces that do not abut: the numpy route's)
            assert not mx[ic.VALID].any()
            continue
        assert verdict == ic.INSIDE_OK
        x, mag = _numpy_sums(new, r, table)
        valid = mx[ic.VALID] == 1.0
        assert np.array_equal(valid, r < c)
        n = new[0].size
        tol = 4.0 * (n + 4) * _EPS * mag[valid]
        assert np.all(mx[ic.LOWER, valid] - tol <= x[valid])
        assert np.all(x[valid] <= mx[ic.UPPER, valid] + tol)
        # points carried from the memo (their interval wider than one sum's rounding)
        if prev.shape[1]:
            width = mx[ic.UPPER] - mx[ic.LOWER]
            carried += int(np.sum(valid & (width > 8.0 * (n + 4) * _EPS * mag + 1e-300)))
        checked += int(valid.sum())
    # (the coarse chain's stick radius moves by a ring or two a step: the points near it are
    # summed)
    assert carried > 0.3 * checked > 0


def test_memo_verdicts_are_the_numpy_routes():
    f = _plain("inside_memo")
    rng = np.random.default_rng(5)
    memo = (np.zeros((4, 0)), np.zeros((3, 0)))
    decided = {ic.INSIDE_OK: 0, ic.INSIDE_FAIL: 0}
    beyond = {True: 0, False: 0}
    for old, new, c, r, table in _chain(steps=80, seed=8):
        tau = np.abs(ta.traction(new, r, 1.0, table))
        for scale in (10.0 ** rng.uniform(-7, -1), -(10.0 ** rng.uniform(-7, -1)), 1e-12):
            bound = tau * (1.0 + scale * rng.random(r.size)) + 1e-300
            verdict, mx = _memo_call(f, new, old, r, bound, c, table, memo)
            ref = ta._inside_ok(new, r, c, bound, 1.0, table)
            if verdict != ic.INSIDE_OPEN:
                assert (verdict == ic.INSIDE_OK) == ref
                decided[verdict] += 1
            marked = np.flatnonzero(mx[ic.VALID] == ic.FAILED)
            if verdict == ic.INSIDE_FAIL:
                # one point marked, inside c, whose numpy traction fails too
                assert marked.size == 1 and r[marked[0]] < c
                assert tau[marked[0]] > bound[marked[0]] * (1 + ta.CHECK_RTOL)
                _check_allowance(new, r, c, bound, table, mx, beyond)
            else:
                assert marked.size == 0
        # the chain's memo from a check every point passes
        _, mx = _memo_call(f, new, old, r, 2.0 * tau + 1.0, c, table, memo)
        memo = (np.vstack(_arrays(new)), mx)
    assert decided[ic.INSIDE_OK] and decided[ic.INSIDE_FAIL]
    # the allowance's short cut both taken and not
    assert beyond[True] and beyond[False]


def _check_allowance(new, r, c, bound, table, mx, beyond):
    """Where the short cut of an allowance (torsion_annulus._beyond_allowance) rejects a failed
    check, the numpy check with that allowance rejects it too (allowances of every reach)."""
    weights = r ** 3
    for reach in (0.0, 0.5 * (r[1] - r[0]), 3.0 * (r[1] - r[0]), 0.3 * c, 2.0 * c):
        allow = (weights, 1e30, reach)
        cut = ta._beyond_allowance(mx, r, c, allow)
        beyond[cut] += 1
        if cut:
            assert not ta._inside_ok(new, r, c, bound, 1.0, table, allow)


def test_memo_of_another_density_is_not_used():
    f = _plain("inside_memo")
    chain = _chain(steps=30)
    old, new, c, r, table = chain[20]
    big = np.full(r.size, 1e9)
    # a memo claiming X = 0 exactly at every point, of the density two steps back
    fake = np.zeros((3, r.size))
    fake[ic.VALID] = 1.0
    other = np.vstack(_arrays(chain[18][1]))
    # the points well inside c fail
    tight = np.where(r < 0.5 * c, np.abs(ta.traction(new, r, 1.0, table)) * 0.5, 1e9)
    assert _memo_call(f, new, old, r, tight, c, table, (other, fake))[0] == ic.INSIDE_FAIL
    # (the same fake memo of the old density itself is taken at its word there: OK)
    assert _memo_call(f, new, old, r, tight, c, table,
                      (np.vstack(_arrays(old)), fake))[0] == ic.INSIDE_OK
    assert _memo_call(f, new, old, r, big, c, table, (other, fake))[0] == ic.INSIDE_OK


@needs_numba
def test_compiled_pass_gives_the_plain_functions_verdicts_and_memos():
    ak.kernels()        # (builds the check's pass)
    memo_c = memo_p = (np.zeros((4, 0)), np.zeros((3, 0)))
    for old, new, c, r, table in _chain(steps=40, seed=4):
        bound = np.abs(ta.traction(new, r, 1.0, table)) * 1.01
        got = _memo_call(ic.inside_memo, new, old, r, bound, c, table, memo_c)
        ref = _memo_call(_plain("inside_memo"), new, old, r, bound, c, table, memo_p)
        assert got[0] == ref[0]
        # (the C library's acosh at the stick radius may differ from Python's in the last bit)
        np.testing.assert_allclose(got[1], ref[1], rtol=1e-12, atol=0.0)
        memo_c = (np.vstack(_arrays(new)), got[1])
        memo_p = (np.vstack(_arrays(new)), ref[1])


@needs_numba
def test_path_with_and_without_the_memo_is_bit_identical(monkeypatch):
    c = cl.Contact(cl.profiles.Paraboloid(R=0.01), materials=(cl.Elastic(E=210e9, nu=0.3),
                                                                cl.Rigid()), friction=MU)
    n = 600
    t = np.arange(1, n + 1) / n
    force = 10.0 * (1 + 0.4 * np.sin(4 * np.pi * t + 0.3))
    a_max = float(np.max(c.normal(force=force)._radius))
    phi = 0.8 * MU * 10.0 / (c.moduli.torsional * a_max ** 2) * np.sin(6 * np.pi * t) \
        * np.minimum(1, 2 * t)
    path = cl.LoadPath.from_arrays(force=force, twist=phi)

    class Off:
        last = None

        def __setattr__(self, k, v):
            pass

    with_memo = c.simulate(path, method="exact")
    monkeypatch.setattr(ta, "_MEMO", Off())
    without = c.simulate(path, method="exact")
    assert with_memo.torque.tobytes() == without.torque.tobytes()
    assert with_memo.dissipated_energy.tobytes() == without.dissipated_energy.tobytes()
    assert with_memo.meta["fallback_steps"] == without.meta["fallback_steps"]
