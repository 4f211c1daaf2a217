"""JKR fits of a tip with a flat centre and a rising flank (a truncated cone), against the
branch written here from the closed forms: g = s a arccos(b/a),
∫_0^a g = s (a²/2 arccos(b/a) - b/2 sqrt(a² - b²)), δ = g(a) - sqrt(2πaΔγ/E*) and
F = 2E*(aδ - ∫g) for a >= b (Heß's rule through the MDR); the flank's finite slope makes
g'(b⁺) infinite, so the branch ends at the flat's edge with Kendall's pull-off force.
And tips with a wall: a rounded end inside a wall (the paraboloid's JKR branch until the contact
reaches the wall, then the punch's line), with and without adhesion, and the flat punch."""
from __future__ import annotations

import numpy as np
import pytest

from contactlab import Elastic
from contactlab.fit import indentation
from contactlab.fit._jkr_flat import JKRFlat
from contactlab.profiles import TruncatedCone
from tests.tolerances import (
    FIT_CLOSED_FORM_ROUNDING,
    FIT_JACOBIAN_FD,
    FIT_MODEL_SOLVE,
    FIT_RECOVERY,
)

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
    assert d_c == pytest.approx(-BETA * np.sqrt(B), rel=FIT_CLOSED_FORM_ROUNDING)
    F_c, _ = m.branch_end(ESTAR, W)
    assert F_c == pytest.approx(-np.sqrt(8 * np.pi * B ** 3 * ESTAR * W),
                                rel=FIT_CLOSED_FORM_ROUNDING)


def test_force_and_derivatives():
    m = JKRFlat(TIP, 1.5e-6)
    a = B * (1 + np.geomspace(1e-6, 3, 60))
    d, F = branch(a)
    Fm, Fd, Fe, Fw = m.force(d, ESTAR, W)
    np.testing.assert_allclose(Fm, F, rtol=FIT_MODEL_SOLVE,
                               atol=FIT_MODEL_SOLVE * np.max(np.abs(F)))
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


# ---- a rounded end inside a wall: f = r²/(2R) up to the wall at b (a punch with a rounded face)
RW, BW, WW = 5e-6, 1.0e-6, 0.005
BETAW = np.sqrt(2 * np.pi * WW / ESTAR)


def walled():
    from contactlab.profiles import FlatPunch, Paraboloid
    return FlatPunch(radius=BW) + Paraboloid(R=RW)


def walled_curve():
    """JKR of the paraboloid while a < b (δ = a²/R - β√a, F = 2E*(aδ - a³/(3R))), then the
    contact radius stays at the wall: F = 2E*(bδ - b³/(3R)) for δ >= b²/R - β√b."""
    a_c = (np.pi * WW * RW * RW / (8 * ESTAR)) ** (1 / 3)
    a = np.linspace(1.01 * a_c, BW, 1200)
    d = a * a / RW - BETAW * np.sqrt(a)
    F = 2 * ESTAR * (a * d - a ** 3 / (3 * RW))
    dw = np.linspace(d[-1], d[-1] + 300e-9, 501)[1:]
    Fw = 2 * ESTAR * (BW * dw - BW ** 3 / (3 * RW))
    dd, FF = np.concatenate([d, dw]), np.concatenate([F, Fw])
    before = np.linspace(dd[0] - 0.3 * (dd[-1] - dd[0]), dd[0], 300, endpoint=False)
    return np.concatenate([before, dd]) + Z0, np.concatenate([np.zeros(300), FF])


def test_rounded_end_inside_a_wall_recovered():
    z, F = walled_curve()
    res = indentation(z, F, walled(), sample=Elastic(E=1e6, nu=NU), adhesion="jkr",
                      free=("E", "contact_point", "work_of_adhesion"))
    for k, want in {"E": E, "contact_point": Z0, "work_of_adhesion": WW}.items():
        assert res.params[k] == pytest.approx(want, rel=FIT_RECOVERY), k


def test_wall_part_of_the_jkr_model_and_its_derivatives():
    """At the wall the radius stays b: F = 2E*(bδ - ∫_0^b g), ∂F/∂δ = 2E*b, ∂F/∂E* = F/E*,
    ∂F/∂Δγ = 0."""
    from contactlab.fit._jkr import JKRTable
    m = JKRTable(walled(), BW)
    d = BW * BW / RW - BETAW * np.sqrt(BW) + np.array([1e-9, 1e-8, 1e-7])
    F, Fd, Fe, Fw = m.force(d, ESTAR, WW)
    want = 2 * ESTAR * (BW * d - BW ** 3 / (3 * RW))
    np.testing.assert_allclose(F, want, rtol=FIT_MODEL_SOLVE)
    np.testing.assert_allclose(Fd, 2 * ESTAR * BW, rtol=FIT_CLOSED_FORM_ROUNDING)
    np.testing.assert_allclose(Fe, want / ESTAR, rtol=FIT_MODEL_SOLVE)
    assert np.all(Fw == 0.0)


def test_non_adhesive_walls():
    """Without adhesion: a flat punch (F = 2E*bδ, its own route) and the rounded end inside a
    wall (Hertz up to δ = b²/R, then 2E*(bδ - b³/(3R))) within the table's error."""
    from contactlab.profiles import FlatPunch
    z = np.linspace(-60e-9, 400e-9, 2000)
    d = np.maximum(z - Z0, 0.0)
    res = indentation(z, 2 * ESTAR * BW * d, FlatPunch(radius=BW), sample=Elastic(E=1e6, nu=NU))
    assert res.meta["tip_route"] == "punch"
    assert res.params["E"] == pytest.approx(E, rel=FIT_RECOVERY)
    assert res.params["contact_point"] == pytest.approx(Z0, rel=FIT_RECOVERY)
    F = np.where(d < BW * BW / RW, 4 / 3 * ESTAR * np.sqrt(RW) * d ** 1.5,
                 2 * ESTAR * (BW * d - BW ** 3 / (3 * RW)))
    res = indentation(z, F, walled(), sample=Elastic(E=1e6, nu=NU))
    err = res.meta["tip_model_errors"]["force"]
    assert 0 < err < 1e-5
    assert res.params["E"] == pytest.approx(E, rel=10 * err)
    assert res.params["contact_point"] == pytest.approx(Z0, rel=10 * err)
