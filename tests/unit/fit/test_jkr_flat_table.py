"""Measured flat-centred tips (linear tables whose heights are zero up to b): JKR and
non-adhesive fits against branches written here from the closed forms of the truncated cone
(g = s a arccos(b/a)) and truncated paraboloid (g = (a/R) sqrt(a² - b²),
∫_0^a g = (a² - b²)^(3/2)/(3R)), δ = g(a) - sqrt(2πaΔγ/E*), F = 2E*(aδ - ∫g) (Heß's rule
through the MDR). A table that is the truncated cone exactly recovers to 1e-8; a table of the
curved flank within the table's own distance from the shape; the model's derivatives against
finite differences."""
from __future__ import annotations

import numpy as np
import pytest

from contactlab import Elastic
from contactlab.fit import indentation
from contactlab.fit._jkr_flat import JKRFlatTable
from contactlab.fit._tip import flat_radius
from contactlab.profiles import Tabulated
from tests.tolerances import FIT_JACOBIAN_FD, FIT_RECOVERY

B, S, Z0, W, RR = 0.3e-6, 0.3, 12e-9, 0.005, 5e-6
E, NU = 2e6, 0.5
ESTAR = E / (1 - NU ** 2)
BETA = np.sqrt(2 * np.pi * W / ESTAR)
R_TAB = np.linspace(0.0, 4 * B, 4801)          # B is the node 1200
CONE_TAB = Tabulated(R_TAB, np.where(R_TAB < B, 0.0, S * (R_TAB - B)))
PARA_TAB = Tabulated(R_TAB, np.where(R_TAB < B, 0.0, (R_TAB ** 2 - B * B) / (2 * RR)))


def cone_branch(a):
    d = S * a * np.arccos(B / a) - BETA * np.sqrt(a)
    F = 2 * ESTAR * (a * d - S * (a * a / 2 * np.arccos(B / a) - B / 2 * np.sqrt(a * a - B * B)))
    return d, F


def para_g(a):
    return a / RR * np.sqrt(a * a - B * B)


def para_branch(a, beta=BETA):
    d = para_g(a) - beta * np.sqrt(a)
    return d, 2 * ESTAR * (a * d - (a * a - B * B) ** 1.5 / (3 * RR))


def with_baseline(d, F):
    before = np.linspace(d[0] - 0.3 * (d[-1] - d[0]), d[0], 300, endpoint=False)
    return np.concatenate([before, d]) + Z0, np.concatenate([np.zeros(300), F])


def table_distance(tab):
    """The table's own distance from the truncated paraboloid: the largest relative difference
    of its transform g (exact for the linear interpolant) over the data's contact radii."""
    a = B + 2 * B * np.linspace(0.01, 1.0, 400) ** 2
    return float(np.max(np.abs(tab._g(a, 1e-12) / para_g(a) - 1)))


def test_flat_radius_of_a_table():
    assert flat_radius(CONE_TAB) == R_TAB[1200] == pytest.approx(B, rel=1e-15)
    assert flat_radius(Tabulated(R_TAB, R_TAB ** 2)) == 0.0


def test_exact_table_of_a_truncated_cone_recovered():
    z, F = with_baseline(*cone_branch(B * (1 + np.geomspace(1e-9, 2, 1700))))
    res = indentation(z, F, CONE_TAB, sample=Elastic(E=1e6, nu=NU), adhesion="jkr",
                      free=("E", "contact_point", "work_of_adhesion"))
    for k, want in {"E": E, "contact_point": Z0, "work_of_adhesion": W}.items():
        assert res.params[k] == pytest.approx(want, rel=FIT_RECOVERY), k
    assert 0 < res.model_error < 1e-8


def test_table_of_a_truncated_paraboloid_within_its_error():
    a = B + (2 * B) * np.linspace(0.0, 1.0, 1700) ** 2
    z, F = with_baseline(*para_branch(a))
    res = indentation(z, F, PARA_TAB, sample=Elastic(E=1e6, nu=NU), adhesion="jkr",
                      free=("E", "contact_point", "work_of_adhesion"))
    bound = table_distance(PARA_TAB) + res.model_error
    assert 0 < bound < 1e-3
    for k, want in {"E": E, "contact_point": Z0, "work_of_adhesion": W}.items():
        assert abs(res.params[k] / want - 1) < bound, k


def test_non_adhesive_fit_of_a_flat_centred_table():
    a = B + 2 * B * np.linspace(0.0, 1.0, 800) ** 2
    z, F = with_baseline(*para_branch(a, beta=0.0))
    res = indentation(z, F, PARA_TAB, sample=Elastic(E=1e6, nu=NU))
    bound = table_distance(PARA_TAB) + res.model_error
    assert abs(res.params["E"] / E - 1) < bound
    assert abs(res.params["contact_point"] / Z0 - 1) < bound


def test_table_force_and_derivatives():
    m = JKRFlatTable(PARA_TAB, 3.5 * B, 1e-12, B)
    a_c, _ = m.critical(ESTAR, W)
    a = a_c + (3 * B - a_c) * np.linspace(0.05, 1.0, 40) ** 2
    d = m._g(a) - BETA * np.sqrt(a)
    _, Fd, Fe, Fw = m.force(d, ESTAR, W)
    # a small step: the interpolant's curvature is large near the table's square-root cusps
    # (central differences at 1e-6 of the range err by 1.2e-6, at 1e-7 by 1.3e-8)
    h = 1e-7 * np.max(np.abs(d))
    fd = (m.force(d + h, ESTAR, W)[0] - m.force(d - h, ESTAR, W)[0]) / (2 * h)
    np.testing.assert_allclose(Fd, fd, rtol=0, atol=FIT_JACOBIAN_FD * np.max(np.abs(fd)))
    fe = (m.force(d, ESTAR * (1 + 1e-7), W)[0] - m.force(d, ESTAR * (1 - 1e-7), W)[0]) / (
        2e-7 * ESTAR)
    np.testing.assert_allclose(Fe, fe, rtol=0, atol=FIT_JACOBIAN_FD * np.max(np.abs(fe)))
    k = d > 0.5 * d.min()
    fw = (m.force(d[k], ESTAR, W * (1 + 1e-7))[0] - m.force(d[k], ESTAR, W * (1 - 1e-7))[0]) / (
        2e-7 * W)
    np.testing.assert_allclose(Fw[k], fw, rtol=0, atol=FIT_JACOBIAN_FD * np.max(np.abs(fw)))
    # ∫g of the interpolant: its own g integrated in u = sqrt(a - b) by 5-point Gauss-Legendre
    # per node interval (exact for the pieces, polynomials of degree 4 in u)
    x, w = np.polynomial.legendre.leggauss(5)
    for aa in (1.2 * B, 2.7 * B):
        ue = np.sqrt(aa - B)
        un = np.append(m._u[m._u < ue], ue)
        lo, hi = un[:-1, None], un[1:, None]
        u = 0.5 * (lo + hi) + 0.5 * (hi - lo) * x
        ref = float(np.sum(0.5 * (hi - lo) * w * m._g(B + u * u) * 2 * u))
        assert float(m._integral(np.array([aa]))[0]) == pytest.approx(ref, rel=1e-12)
