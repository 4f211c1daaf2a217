"""The slip check's own pass (:mod:`contactlab.numeric.slip_check`; issue 28, 180-step path row).

Must show: the pass's verdict is the numpy route's (the table's dense products) wherever it
decides, on the increments of random steps of both senses with and without a gross turn, and
it decides both ways; a threshold at a point's increment itself is left to the numpy route, well
above or below it is decided; a point off the table, a value not finite or pieces that do not
abut are left to the numpy route; the kernel's logic run uncompiled too.
"""
import numpy as np
import pytest

from contactlab.numeric import jit
from contactlab.numeric import slip_check as sc
from contactlab.physics import torsion_annulus as ta
from contactlab.physics import torsion_rings as tr

needs_numba = pytest.mark.skipif(not jit.available(), reason="numba (extra 'fast') not installed")
ROUTES = [pytest.param(True, marks=needs_numba, id="compiled"),
          pytest.param(False, id="uncompiled-logic")]
MU = 0.3


def _setup(n=60):
    b = np.linspace(0.0, 1.0, n + 1)
    r = 0.5 * (b[1:] + b[:-1])
    lu = tr.influence(b, r, 1.0)["lu"]
    bound = MU * np.sqrt(np.clip(1.0 - r * r, 0.0, None))
    return b, r, lu, bound, ta.NodeTable(r, b)


def _increments():
    """(increment above the stick radius, the points on the annulus) of random steps."""
    b, r, lu, bound, table = _setup()
    rng = np.random.default_rng(11)
    w = ta.empty()
    out = []
    for _ in range(30):
        radius = float(b[int(rng.integers(30, 61))])
        bd = np.where(r < radius, bound * (0.6 + 0.4 * rng.random()), 0.0)
        sl = ta.nonnegative_psi(ta.density(lu, b, np.zeros(0, int), bd, radius))
        st = ta.step(w, sl, radius, 1.0, dphi=float(rng.choice([-1.0, 1.0, 3.0]) * rng.random()
                                                     * 0.3))
        dw = ta.difference(st["w"], w, st["c"])
        reach = max(radius, float(w[1][-1]) if w[1].size else 0.0)
        on = ((bd > 0) | (r < reach)) & (r > st["c"])
        if on.any() and dw[0].size:
            out.append((tuple(np.ascontiguousarray(u, float) for u in dw), r[on]))
        w = st["w"]
    return out, table


def _numpy_fails(dw, r_on, s, gross, rtol, table):
    ds = ta.slip_kernel_integral(dw, r_on, table) + gross * r_on
    ref = float(np.max(np.abs(ds))) + float(np.max(r_on)) * abs(gross)
    return bool(np.any(s * ds < -rtol * ref)), ds


def _verdict(compiled, dw, r_on, s, gross, rtol, table):
    f = sc.kernels(compiled)["slip_check"]
    return f(*dw, r_on, s, gross, rtol, *table.arrays["slip"], table.r, table.nodes,
             *ta._G01_ONE)


@pytest.mark.parametrize("compiled", ROUTES)
def test_slip_check_verdict_is_the_numpy_routes(compiled):
    cases, table = _increments()
    decided = {sc.CHECK_OK: 0, sc.CHECK_FAIL: 0}
    for dw, r_on in cases:
        for s in (1.0, -1.0):
            for gross in (0.0, 1e-3 * s, -1e-3 * s):
                fails, _ = _numpy_fails(dw, r_on, s, gross, ta.CHECK_RTOL, table)
                v = _verdict(compiled, dw, r_on, s, gross, ta.CHECK_RTOL, table)
                assert v in (sc.CHECK_OPEN, sc.CHECK_FAIL if fails else sc.CHECK_OK)
                if v != sc.CHECK_OPEN:
                    decided[v] += 1
    assert decided[sc.CHECK_OK] > 20 and decided[sc.CHECK_FAIL] > 20


@pytest.mark.parametrize("compiled", ROUTES)
def test_slip_check_is_left_open_within_rounding(compiled):
    """All increments against the sense: the largest one's margin is zero at a relative
    threshold of 1 (left open), positive at 2 (no failure), negative at 0.5 (failure)."""
    cases, table = _increments()
    dw, r_on = max(cases, key=lambda c: c[1].size)
    _, ds = _numpy_fails(dw, r_on, 1.0, 0.0, 1.0, table)
    s = -float(np.sign(ds[np.argmax(np.abs(ds))]))
    assert np.all(s * ds <= 0)          # every increment against s: the largest decides
    assert _verdict(compiled, dw, r_on, s, 0.0, 1.0, table) == sc.CHECK_OPEN
    assert _verdict(compiled, dw, r_on, s, 0.0, 2.0, table) == sc.CHECK_OK
    assert _verdict(compiled, dw, r_on, s, 0.0, 0.5, table) == sc.CHECK_FAIL
    assert _numpy_fails(dw, r_on, s, 0.0, 0.5, table)[0]
    assert not _numpy_fails(dw, r_on, s, 0.0, 2.0, table)[0]


@pytest.mark.parametrize("compiled", ROUTES)
def test_slip_check_leaves_what_it_cannot_bound_to_numpy(compiled):
    cases, table = _increments()
    dw, r_on = cases[0]
    args = (1.0, 0.0, ta.CHECK_RTOL, table)
    off = r_on.copy()
    off[0] = 0.5 * (off[0] + table.r[0])            # a point not in the table
    assert _verdict(compiled, dw, off, *args) == sc.CHECK_OPEN
    bad = (dw[0], dw[1], dw[2].copy(), dw[3])
    bad[2][0] = np.nan
    assert _verdict(compiled, bad, r_on, *args) == sc.CHECK_OPEN
    if dw[0].size > 1:                              # pieces that do not abut
        gap = (dw[0].copy(), dw[1], dw[2], dw[3])
        gap[0][1] = 0.5 * (gap[0][1] + gap[1][1])
        assert _verdict(compiled, gap, r_on, *args) == sc.CHECK_OPEN
