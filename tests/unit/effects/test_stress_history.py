"""Subsurface stresses along histories and the fretting-fatigue indicator (issue 31, part D).

Masing's rule for the tractions is checked against hand sums of monotonic states (the library's
own surface tractions), the force and torque carried through a depth against the history's own
force and torque; the indicators against Hamilton's edge stress of the sliding sphere
(1983: ``p0[(1 - 2ν)/3 + μπ(4 + ν)/8]``), the Hertz edge stress ``(1 - 2ν)p0/3`` and hand
computed Smith–Watson–Topper values of uniaxial and shear cycles.
"""
from __future__ import annotations

import numpy as np
import pytest

import contactlab as cl
from contactlab.effects.stress_history import masing_terms
from contactlab.errors import ParameterError
from contactlab.physics import fatigue
from tests import tolerances as tol

STEEL = cl.Elastic(E=210e9, nu=0.3)
F = 100.0
MU = 0.3
C = cl.Contact(cl.profiles.Paraboloid(R=0.01), materials=(STEEL, STEEL), friction=MU)
A = C.normal(force=F).radius
P0 = 3 * F / (2 * np.pi * A**2)


def test_masing_terms_of_a_reversal():
    u = np.array([0.0, 1.0, 2.0, 1.0, 0.0, -0.5, 0.5, 3.0])
    assert masing_terms(u, 2) == [(1.0, 2.0)]
    assert masing_terms(u, 3) == [(-2.0, 0.5), (1.0, 2.0)]
    assert masing_terms(u, 5) == [(-2.0, 1.25), (1.0, 2.0)]
    assert masing_terms(u, 6) == [(2.0, 0.5), (-2.0, 1.25), (1.0, 2.0)]
    assert masing_terms(u, 7) == [(1.0, 3.0)]        # beyond the first peak: virgin again


def test_shift_history_snapshots_follow_masing_and_carry_the_force():
    u = np.array([0.0, 1e-7, 2e-7, 1e-7, 0.0, -0.5e-7, 0.5e-7])
    h = C.shift_history(force=F, displacement=u)
    r = np.array([0.1, 0.5, 0.9]) * A
    v = {d: np.asarray(C.tangential(force=F, displacement=d).shear(r)) for d in
         (2e-7, 0.5e-7, 1.25e-7)}
    hand = {2: v[2e-7], 3: v[2e-7] - 2 * v[0.5e-7], 5: v[2e-7] - 2 * v[1.25e-7]}
    for k, want in hand.items():
        f = h.stress(r, 0 * r, 0.0, step=k, part="friction")
        np.testing.assert_allclose(f.sxz, want, rtol=0,
                                   atol=tol.STRESS_TANGENTIAL_SURFACE * np.max(np.abs(want)))
    t, w = np.polynomial.legendre.leggauss(400)
    z = 0.5 * A
    th_a = np.arctan(A / z)
    bits = [(0.0, th_a), (th_a, 0.5 * np.pi * (1 - 1e-12))]
    th = np.concatenate([lo + (hi - lo) * (t + 1) / 2 for lo, hi in bits])
    wt = np.concatenate([(hi - lo) / 2 * w for lo, hi in bits])
    rr = z * np.tan(th)
    dr = z / np.cos(th) ** 2 * wt
    for k in (3, 5, 6):
        f0 = h.stress(rr, 0 * rr, z, step=k, part="friction")
        f90 = h.stress(0 * rr, rr, z, step=k, part="friction")
        Qx = np.sum(2 * np.pi * rr * 0.5 * (f0.sxz + f90.sxz) * dr)
        assert abs(Qx / h.tangential_force[k] - 1) <= tol.STRESS_EQUILIBRIUM
    tot = h.stress(rr[:5], 0.0, z, step=-1)
    assert tot.meta["step"] == len(u) - 1 and "hertz" in tot.meta["route"]


def test_twist_history_snapshots_carry_the_torque():
    phi = np.array([0.0, 2e-3, 4e-3, 1e-3, -2e-3])
    h = C.twist_history(force=F, twist=phi, method="exact")
    t, w = np.polynomial.legendre.leggauss(400)
    z = 0.3 * A
    th_a = np.arctan(A / z)
    bits = [(0.0, th_a), (th_a, 0.5 * np.pi * (1 - 1e-12))]
    th = np.concatenate([lo + (hi - lo) * (t + 1) / 2 for lo, hi in bits])
    wt = np.concatenate([(hi - lo) / 2 * w for lo, hi in bits])
    rr = z * np.tan(th)
    dr = z / np.cos(th) ** 2 * wt
    for k in (2, 3, 4):
        f = h.stress(rr, z, step=k, part="friction")
        M = np.sum(2 * np.pi * rr**2 * f.stz * dr)
        assert abs(M / h.torque[k] - 1) <= tol.STRESS_EQUILIBRIUM
    r = np.array([0.2, 0.6, 0.95]) * A
    s4 = C.torsion(force=F, twist=4e-3, method="exact")
    s15 = C.torsion(force=F, twist=1.5e-3, method="exact")
    want = np.asarray(s4.shear(r)) - 2 * np.asarray(s15.shear(r))
    got = h.stress(r, 0.0, step=3, part="friction").stz
    np.testing.assert_allclose(got, want, rtol=0,
                               atol=tol.STRESS_TORSION_SURFACE * np.max(np.abs(want)))


def test_gross_slip_loop_edge_stress_is_hamiltons():
    loop = C.fretting_loop(force=F, displacement_amplitude=1e-5)
    assert loop.regime == "gross_slip"
    ff = loop.fatigue()
    nu = 0.3
    shear_edge = MU * np.pi * (4 + nu) / 8
    assert abs(ff.edge_stress / P0 - ((1 - 2 * nu) / 3 + shear_edge)) <= tol.STRESS_HAMILTON
    assert abs(ff.edge_stress_range / P0 - 2 * shear_edge) <= tol.STRESS_HAMILTON
    assert abs(abs(ff.edge_normal[0]) - 1) <= 1e-12
    # the loop tips are the virgin state at ±amplitude (Masing): phase 0.5 mirrors phase 0
    X = np.array([0.3, -0.8]) * A
    up = loop.stress(X, 0.2 * A, 0.1 * A, phase=0.0, part="friction")
    down = loop.stress(X, 0.2 * A, 0.1 * A, phase=0.5, part="friction")
    np.testing.assert_allclose(down.sxz, -up.sxz, rtol=1e-12)
    tip = C.tangential(force=F, displacement=1e-5).stress(X, 0.2 * A, 0.1 * A, part="friction")
    np.testing.assert_allclose(up.sxx, tip.sxx, rtol=1e-12)


def test_small_amplitude_edge_stress_tends_to_hertz():
    ff = C.fretting_loop(force=F, displacement_amplitude=1e-12).fatigue(n_phases=4)
    hertz_edge = (1 - 2 * 0.3) * P0 / 3
    assert ff.edge_stress_range <= 2e-3 * P0
    assert abs(ff.edge_stress - hertz_edge) <= ff.edge_stress_range
    big = C.fretting_loop(force=F, displacement_amplitude=1e-7).fatigue(n_phases=4)
    assert big.edge_stress_range > ff.edge_stress_range and big.swt > ff.swt


def test_swt_of_hand_computed_cycles():
    E, nu = 200e9, 0.3
    smin, smax = -100e6, 300e6
    t = np.linspace(0, 2 * np.pi, 13)
    sx = 0.5 * (smax + smin) + 0.5 * (smax - smin) * np.cos(t)
    S = np.zeros((t.size, 1, 6))
    S[:, 0, 0] = sx
    val, n = fatigue.swt(S, E, nu)
    assert val[0] == pytest.approx(smax * (smax - smin) / (2 * E), rel=1e-12)
    assert abs(abs(n[0, 0]) - 1) <= 1e-12
    # fully reversed pure shear ±τ: σ_n = ±τ on the 45° planes, ε_n = (1 + ν)σ_n/E
    tau = 150e6
    S = np.zeros((t.size, 1, 6))
    S[:, 0, 3] = tau * np.cos(t)
    val, n = fatigue.swt(S, E, nu)
    assert val[0] == pytest.approx((1 + nu) * tau**2 / E, rel=1e-12)
    assert abs(abs(n[0, 0]) - np.sqrt(0.5)) <= 1e-12 and abs(n[0, 2]) <= 1e-12


def test_findley_of_hand_computed_cycles():
    # uniaxial σ_min..σ_max along x: on the plane at θ from x, σ_n = σ cos²θ and the shear
    # σ sinθ cosθ (fixed direction), so FP(θ) = (Δσ/4) sin 2θ + (kσ_max/2)(1 + cos 2θ), whose
    # maximum over θ is kσ_max/2 + sqrt((Δσ/4)² + (kσ_max/2)²)
    k = 0.3
    smin, smax = -100e6, 300e6
    t = np.linspace(0, 2 * np.pi, 13)
    S = np.zeros((t.size, 1, 6))
    S[:, 0, 0] = 0.5 * (smax + smin) + 0.5 * (smax - smin) * np.cos(t)
    val, n = fatigue.findley(S, k)
    ds = smax - smin
    want = k * smax / 2 + np.hypot(ds / 4, k * smax / 2)
    # the 2.5° grids of normals and shear directions: within O((1.25°)²) of the maximum
    assert want * (1 - tol.FINDLEY_GRID) <= val[0] <= want * (1 + 1e-12)
    theta = 0.5 * np.arctan2(ds / 4, k * smax / 2)                # the critical plane
    assert abs(abs(n[0, 0]) - np.cos(theta)) < np.radians(2.5)
    # fully reversed shear ±τ in xy: on the plane at α from x in xy, τ_a = τ|cos 2α| and
    # σ_n,max = τ|sin 2α|, so FP = τ sqrt(1 + k²)
    tau = 150e6
    S = np.zeros((t.size, 1, 6))
    S[:, 0, 3] = tau * np.cos(t)
    val, _ = fatigue.findley(S, k)
    want = tau * np.sqrt(1 + k * k)
    assert want * (1 - tol.FINDLEY_GRID) <= val[0] <= want * (1 + 1e-12)
    # k = 0: the largest shear amplitude, τ on the x and y planes
    val, n = fatigue.findley(S, 0.0)
    assert val[0] == pytest.approx(tau, rel=1e-12)


def test_loop_findley_beside_swt():
    loop = C.fretting_loop(force=F, displacement_amplitude=1e-7)
    plain = loop.fatigue(n_phases=4)
    ff = loop.fatigue(n_phases=4, findley_k=0.25)
    assert plain.findley is None and "findley" not in plain.to_dict()
    assert ff.swt == plain.swt and ff.findley == ff.findley_at_point.max()
    assert ff.to_dict()["findley"] == ff.findley and ff.meta["findley_k"] == 0.25
    for bad in (-0.1, np.nan, "x", True):
        with pytest.raises(ParameterError):
            loop.fatigue(n_phases=4, findley_k=bad)


def test_bad_steps_and_phases_raise():
    h = C.shift_history(force=F, displacement=np.array([0.0, 1e-7]))
    for bad in (2, -3, 1.0, True):
        with pytest.raises(ParameterError):
            h.stress(0.0, 0.0, 1e-5, step=bad)
    loop = C.fretting_loop(force=F, displacement_amplitude=1e-7)
    for bad in (-0.1, 1.5, np.nan, "x"):
        with pytest.raises(ParameterError):
            loop.stress(0.0, 0.0, 1e-5, phase=bad)
    with pytest.raises(ParameterError):
        loop.stress(0.0, 0.0, -1e-5, phase=0.2)
    with pytest.raises(ParameterError):
        loop.fatigue(body=3)


def test_fatigue_checks_its_memory_first_and_the_estimate_covers_the_peak():
    import tracemalloc

    from contactlab.effects.stress_history import FATIGUE_POINT_PHASE_BYTES
    from contactlab.effects.stress import CHUNK_POINT_BYTES
    from contactlab.errors import MemoryBudgetError
    loop = C.fretting_loop(force=F, displacement_amplitude=1e-7)
    x = np.linspace(-1.2 * A, 1.2 * A, 300)
    tracemalloc.start()
    try:
        loop.fatigue(n_phases=4, points=(x, 0.0, 0.0), findley_k=0.3)
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert peak <= FATIGUE_POINT_PHASE_BYTES * 302 * 4 + CHUNK_POINT_BYTES * 302
    previous = cl.set_memory_budget("100M")
    try:
        tracemalloc.start()
        try:
            with pytest.raises(MemoryBudgetError, match=r"fatigue\(\).*n_phases=24 x 10002 points"):
                loop.fatigue(points=(np.zeros(10_000), 0.0, 0.0))
            assert tracemalloc.get_traced_memory()[1] < 20e6            # refused up front
        finally:
            tracemalloc.stop()
    finally:
        cl.set_memory_budget(previous)
