"""JKR fits of a tip with a flat centre and a rising flank (a truncated cone), against the
branch written here from the closed forms: g = s a arccos(b/a),
∫_0^a g = s (a²/2 arccos(b/a) - b/2 sqrt(a² - b²)), δ = g(a) - sqrt(2πaΔγ/E*) and
F = 2E*(aδ - ∫g) for a >= b (Heß's rule through the MDR); the flank's finite slope makes
g'(b⁺) infinite, so the branch ends at the flat's edge with Kendall's pull-off force."""
from __future__ import annotations

import numpy as np
import pytest

from contactlab import Elastic
from contactlab.fit import indentation
from contactlab.fit._jkr_flat import JKRFlat
from contactlab.profiles import TruncatedCone
from tests.tolerances import FIT_JACOBIAN_FD, FIT_RECOVERY

B, S, Z0, W = 0.3e-6, 0.3, 12e-9, 0.005
E, NU = 2e6, 0.5
ESTAR = E / (1 - NU ** 2)
BETA = np.sqrt(2 * np.pi * W / ESTAR)
TIP = TruncatedCone(radius=B, slope=S)


def branch(a):
    d = S * a * np.arccos(B / a) - BETA * np.sqrt(a)
    F = 2 * ESTAR * (a * d - S * (a * a / 2 * np.arccos(B / a) - B / 2 * np.sqrt(a * a - B * B)))
    return d, F


def test_branch_end_at_the_flat_edge_is_kendalls():
    m = JKRFlat(TIP, 1.5e-6)
    a_c, d_c = m.critical(ESTAR, W)
    assert a_c == B
    assert d_c == pytest.approx(-BETA * np.sqrt(B), rel=1e-14)
    F_c, _ = m.branch_end(ESTAR, W)
    assert F_c == pytest.approx(-np.sqrt(8 * np.pi * B ** 3 * ESTAR * W), rel=1e-13)


def test_force_and_derivatives():
    m = JKRFlat(TIP, 1.5e-6)
    a = B * (1 + np.geomspace(1e-6, 3, 60))
    d, F = branch(a)
    Fm, Fd, Fe, Fw = m.force(d, ESTAR, W)
    np.testing.assert_allclose(Fm, F, rtol=1e-11, atol=1e-13 * np.max(np.abs(F)))
    h = 1e-6 * np.abs(d)
    scale = np.max(np.abs(Fd))
    fd = (m.force(d + h, ESTAR, W)[0] - m.force(d - h, ESTAR, W)[0]) / (2 * h)
    np.testing.assert_allclose(Fd, fd, rtol=FIT_JACOBIAN_FD, atol=FIT_JACOBIAN_FD * scale)
    fe = (m.force(d, ESTAR * (1 + 1e-6), W)[0] - m.force(d, ESTAR * (1 - 1e-6), W)[0]) / (
        2e-6 * ESTAR)
    np.testing.assert_allclose(Fe, fe, rtol=FIT_JACOBIAN_FD,
                               atol=FIT_JACOBIAN_FD * np.max(np.abs(fe)))
    # Δγ moves the branch's end: the difference must not cross it
    k = d > 0.5 * d.min()
    fw = (m.force(d[k], ESTAR, W * (1 + 1e-6))[0] - m.force(d[k], ESTAR, W * (1 - 1e-6))[0]) / (
        2e-6 * W)
    np.testing.assert_allclose(Fw[k], fw, rtol=FIT_JACOBIAN_FD,
                               atol=FIT_JACOBIAN_FD * np.max(np.abs(fw)))


def test_recovered_from_the_branch():
    d, F = branch(B * (1 + np.geomspace(1e-9, 2, 1700)))
    before = np.linspace(d[0] - 0.3 * (d[-1] - d[0]), d[0], 300, endpoint=False)
    z = np.concatenate([before, d]) + Z0
    force = np.concatenate([np.zeros(300), F])
    res = indentation(z, force, TIP, sample=Elastic(E=1e6, nu=NU), adhesion="jkr",
                      free=("E", "contact_point", "work_of_adhesion"))
    for k, want in {"E": E, "contact_point": Z0, "work_of_adhesion": W}.items():
        assert res.params[k] == pytest.approx(want, rel=FIT_RECOVERY), k


def test_truncated_paraboloid_recovered():
    """f = (r² - b²)/(2R) beyond b: g = (a/R) sqrt(a² - b²), ∫_0^a g = (a² - b²)^(3/2)/(3R)."""
    from contactlab.profiles import TruncatedParaboloid
    Rr = 5e-6
    a = B + (2 * B) * np.linspace(0.0, 1.0, 1700) ** 2      # uniform in sqrt(a - b)
    d = a / Rr * np.sqrt(a * a - B * B) - BETA * np.sqrt(a)
    F = 2 * ESTAR * (a * d - (a * a - B * B) ** 1.5 / (3 * Rr))
    before = np.linspace(d[0] - 0.3 * (d[-1] - d[0]), d[0], 300, endpoint=False)
    z = np.concatenate([before, d]) + Z0
    force = np.concatenate([np.zeros(300), F])
    res = indentation(z, force, TruncatedParaboloid(radius=B, R=Rr), sample=Elastic(E=1e6, nu=NU),
                      adhesion="jkr", free=("E", "contact_point", "work_of_adhesion"))
    for k, want in {"E": E, "contact_point": Z0, "work_of_adhesion": W}.items():
        assert res.params[k] == pytest.approx(want, rel=FIT_RECOVERY), k
