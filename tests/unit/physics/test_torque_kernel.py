"""The torque of a punch density by products (:func:`contactlab.physics.torsion_pieces.torque`,
its compiled pass :mod:`contactlab.numeric.torque_kernel`; issue 28, 180-step path row).

Must show: the torque ``(16/3) G_t ∫ t³ w dt`` of random piecewise-linear densities (sizes across
numpy's pairwise-sum blocks, zero-width pieces and gaps included) against an independent
three-point Gauss–Legendre rule per piece (exact for the degree-4 integrand), and the same bits
on the numpy route, the compiled pass and its logic uncompiled.
"""
import numpy as np
import pytest

from contactlab.numeric import jit
from contactlab.physics import torsion_pieces as tp
from tests import tolerances as TOL

needs_numba = pytest.mark.skipif(not jit.available(), reason="numba (extra 'fast') not installed")
G_T = 8.1e10


def _densities():
    rng = np.random.default_rng(5)
    for n in (0, 1, 7, 8, 9, 127, 128, 129, 300, 1000):
        ends = np.sort(rng.random(2 * n)).reshape(n, 2) if n else np.zeros((0, 2))
        lo, hi = ends[:, 0].copy(), ends[:, 1].copy()
        if n > 3:                   # (sorted pairs: gaps between the pieces)
            hi[2] = lo[2]                               # a piece of no width
        yield lo, hi, rng.standard_normal(n), rng.standard_normal(n)


def _gauss(p) -> float:
    lo, hi, wl, wr = p
    x, wg = np.polynomial.legendre.leggauss(3)
    h = hi - lo
    t = lo[:, None] + 0.5 * (x[None, :] + 1.0) * h[:, None]
    w = wl[:, None] + (wr - wl)[:, None] * 0.5 * (x[None, :] + 1.0)
    return float(16.0 / 3.0 * G_T * np.sum(0.5 * h[:, None] * wg[None, :] * t ** 3 * w))


def test_torque_against_gauss_legendre(monkeypatch):
    monkeypatch.setitem(tp._COMPILED, "on", False)
    for p in _densities():
        scale = 16.0 / 3.0 * G_T * float(np.sum(np.abs(p[2]) + np.abs(p[3])) + 1e-300)
        assert abs(tp.torque(p, G_T) - _gauss(p)) <= TOL.CLOSED_FORM * scale


@pytest.mark.parametrize("compiled", [pytest.param(True, marks=needs_numba, id="compiled"),
                                      pytest.param(False, id="uncompiled-logic")])
def test_torque_is_bit_identical_on_the_compiled_route(monkeypatch, compiled):
    for p in _densities():
        monkeypatch.setitem(tp._COMPILED, "on", False)
        ref = tp.torque(p, G_T)
        monkeypatch.setitem(tp._COMPILED, "on", True)
        monkeypatch.setitem(tp._COMPILED, "compiled", compiled)
        got = tp.torque(p, G_T)
        assert type(got) is float and np.float64(got).tobytes() == np.float64(ref).tobytes()
