"""The compiled pass of a table's near-segment rules (issue 26, item 3). Must show: the same
bits as the numpy route (which stays the reference) for linear and cubic tables on uniform,
random and clustered nodes, at radii on the axis, on the nodes, at and just below the contact
edge and between; the kernel's logic uncompiled too (so it is covered without numba); and
``CONTACTLAB_BACKEND=numpy`` / ``set_backend("numpy")`` keeping the numpy route.
"""
import numpy as np
import pytest

import contactlab as cl
from contactlab.numeric import jit
from contactlab.numeric import normal_kernels as NK
from contactlab.physics import table_pressure as tp
from contactlab.profiles import Tabulated

needs_numba = pytest.mark.skipif(not jit.available(), reason="numba (extra 'fast') not installed")
STEEL = cl.Elastic(E=210e9, nu=0.3)
RTOL = 1e-10


def _tables():
    rng = np.random.default_rng(11)
    uni = np.linspace(0.0, 2e-3, 300)
    rnd = 2e-3 * np.sort(np.r_[0.0, rng.random(120), 1.0])
    pairs = np.sort(np.r_[uni[::3], uni[1:-1:15] + 2e-12])
    flat = uni**2 / 0.02
    flat[1] = 0.0                                   # flat first segment: finite axis pressure
    yield pytest.param(uni, flat, "linear", id="linear-flat-first")
    for name, r in (("uniform", uni), ("random", rnd), ("clustered", pairs)):
        for kind in ("linear", "cubic"):
            yield pytest.param(r, r**2 / 0.02 + 2.0 * r**4, kind, id=f"{kind}-{name}")


def _radii(nodes, a, n_random, seed):
    rng = np.random.default_rng(seed)
    return np.concatenate([[0.0], nodes[nodes < a], [a, np.nextafter(a, 0.0)],
                           rng.uniform(0.0, a, n_random), np.linspace(0.0, a, n_random)])


def _compare_pieces(monkeypatch, compiled):
    """Wrap ``_piece`` so that every call evaluates the numpy route and the kernel (compiled or
    its plain Python logic) on the same arguments and checks the bits; returns the calls."""
    original = tp._piece
    calls = []

    def both(c, k, *args):
        monkeypatch.setitem(tp._COMPILED, "from", 1 << 62)
        ref = original(c, k, *args)
        monkeypatch.setitem(tp._COMPILED, "from", 0)
        monkeypatch.setitem(tp._COMPILED, "on", compiled)
        got = original(c, k, *args)
        assert [x.tobytes() for x in got] == [x.tobytes() for x in ref]
        calls.append(k.size)
        return ref

    monkeypatch.setattr(tp, "_piece", both)
    if compiled:
        monkeypatch.setitem(NK._state, "backend", "numba")
    return calls


@needs_numba
@pytest.mark.parametrize("r, f, kind", list(_tables()))
def test_compiled_pass_has_the_numpy_bits(monkeypatch, r, f, kind):
    tab = Tabulated(r, f, kind)
    calls = _compare_pieces(monkeypatch, True)
    for a, seed in ((0.3e-3, 1), (1.2e-3, 2), (r[-1], 3)):
        radii = _radii(r, a, 300, seed)
        tp.pressure_shape(tab, radii, np.full(radii.shape, a), RTOL)
    assert max(calls) > 300                    # the pieces of whole radius arrays were checked


@pytest.mark.parametrize("r, f, kind", list(_tables())[:4])
def test_kernel_logic_uncompiled_has_the_numpy_bits(monkeypatch, r, f, kind):
    tab = Tabulated(r, f, kind)
    calls = _compare_pieces(monkeypatch, False)
    a = 0.9e-3
    radii = np.concatenate([[0.0, a, np.nextafter(a, 0.0)], r[(r < a)][::6],
                            np.random.default_rng(4).uniform(0.0, a, 8)])
    with np.errstate(all="raise"):             # the numpy route's own errstate only
        tp.pressure_shape(tab, radii, np.full(radii.shape, a), RTOL)
    assert calls


@needs_numba
def test_peak_of_the_issue_table_is_the_same_with_and_without_numba():
    r = np.linspace(0, 2e-3, 300)
    f = r**2 / 0.02
    f[1] = 0.0
    out = {}
    for route in ("numpy", "numba"):
        NK.set_backend(route)
        try:
            c = cl.Contact(Tabulated(r, f, interpolation="linear"), materials=(STEEL, STEEL))
            s = c.normal(force=50.0)
            out[route] = (s.peak_pressure, s.pressure(np.linspace(0.0, s.radius, 64)).tobytes())
        finally:
            NK.set_backend(None)
    assert out["numpy"] == out["numba"]
    assert np.isfinite(out["numpy"][0])


def test_numpy_backend_keeps_the_numpy_route(monkeypatch):
    monkeypatch.setitem(NK._state, "backend", "numpy")
    assert not tp._compiled_rows(1 << 20)
    assert not tp._compiled_rows(tp._COMPILED["from"] - 1)
