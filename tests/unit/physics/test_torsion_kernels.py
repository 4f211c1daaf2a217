"""Special functions of the exact torsion kernels against mpmath (independent definitions)."""
from __future__ import annotations

import mpmath as mp
import numpy as np

from contactlab.physics import torsion_elliptic as te_elliptic
from contactlab.physics import torsion_exact as te
from tests import tolerances as TOL
from tests.reference.torsion_reference import K_of_comp

mp.mp.dps = 30


def test_h_kernel_against_mpmath_quadrature():
    v = np.concatenate([[0.0, 1e-300, 1e-8, 1e-3], np.linspace(0, 1, 41)[1:-1],
                        [0.70710678, 0.7071068, 1 - 1e-6, 1.0]])
    got = te.h_kernel(v)
    for vi, gi in zip(v, got):
        ref = mp.quad(lambda u: u**2 * K_of_comp(u), [vi, 1]) if vi < 1 else mp.mpf(0)
        assert abs(gi - ref) <= 5e-14 * max(abs(ref), 1e-3), (vi, gi, ref)
    assert abs(te.h_kernel(np.array([0.0]))[0] - np.pi**2 / 16) < TOL.ULPS


def test_series_and_chebyshev_routes_agree():
    v = np.linspace(0, 1, 2001)
    np.testing.assert_allclose(te.h_kernel(v), te_elliptic._h_series(v), rtol=TOL.LONG_ARITHMETIC, atol=TOL.H_SERIES_ABS)


def test_k_minus_e_over_m_against_carlson_and_mpmath():
    from scipy.special import elliprd
    p = np.concatenate([np.logspace(-200, -1e-3, 300), 1 - np.logspace(-17, -0.01, 300)])
    np.testing.assert_allclose(te.kme_over_m(p), elliprd(0, p, 1) / 3, rtol=TOL.ELLIPTIC_KERNEL)
    for pi in (1e-20, 0.3, 0.95, 1 - 1e-12):
        m = 1 - mp.mpf(pi)
        ref = (mp.ellipk(m) - mp.ellipe(m)) / m
        assert abs(te.kme_over_m(np.array([pi]))[0] / ref - 1) < TOL.LONG_ARITHMETIC   # scipy ellipkm1: ~5e-14
    np.testing.assert_allclose(te.K_comp(np.array([1e-300, 0.5])),
                               [float(K_of_comp(mp.mpf("1e-150"))), float(K_of_comp(mp.sqrt(0.5)))],
                               rtol=TOL.SHORT_ARITHMETIC)
