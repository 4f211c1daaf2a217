"""Twist histories (theory §6.5): Masing rule with turning-point memory, dissipated energy.

Independent checks: the Lubkin closed forms (mpmath), the loop-energy formula
W = 8∫M_load dφ - 4φ0M0 integrated in mpmath, the small-amplitude cube law of [D54], and a
brute-force simulation of Jenkins elements (the MDR springs, and the equivalent element picture of
the exact solution with slip rotation μP(x)/(2G_t), P from the Hertz closed form) that knows
nothing about turning points.
"""
from __future__ import annotations

import warnings

import numpy as np
import pytest
from scipy.special import ellipe, ellipk

import contactlab as cl
from contactlab.errors import ValidityWarning
from tests import tolerances as TOL
from tests.reference import torsion_reference as ref
from tests.unit.effects.test_torsion import A, E_STAR, F_HERTZ, G_T, M_SCALE, MU, P0, PHI_SCALE, R, materials, rel


@pytest.fixture(scope="module")
def hertz():
    return cl.Contact(cl.profiles.Paraboloid(R=R), materials(), friction=MU)


def cycle(phi0: float, n: int = 400) -> np.ndarray:
    up = np.linspace(0, phi0, n + 1)
    down = np.linspace(phi0, -phi0, 2 * n + 1)[1:]
    back = np.linspace(-phi0, phi0, 2 * n + 1)[1:]
    return np.concatenate([up, down, back])


def test_masing_unloading_branch(hertz):
    t_max = 0.5
    phi_max = float(ref.hertz_twist_hat(t_max)) * PHI_SCALE
    M_max = float(ref.hertz_torque_hat(t_max)) * M_SCALE
    t1 = np.array([0.99, 0.9, 0.7, 0.5])            # stick radius of the unloading increment
    phi = phi_max - 2 * np.array([float(ref.hertz_twist_hat(x)) for x in t1]) * PHI_SCALE
    M_exp = M_max - 2 * np.array([float(ref.hertz_torque_hat(x)) for x in t1]) * M_SCALE
    h = hertz.twist_history(twist=np.concatenate([[phi_max], phi]), force=F_HERTZ)
    np.testing.assert_allclose(h.torque[1:], M_exp, rtol=TOL.TORSION_EXACT, atol=TOL.TORSION_EXACT * M_max)
    np.testing.assert_allclose(h.stick_radius[1:] / A, t1, rtol=TOL.STICK_RADIUS)
    assert rel(h.torque[-1], -M_max) < TOL.TORSION_EXACT          # t1 = t_max reaches -φ_max


def test_hysteresis_loop_closes_symmetric_and_area_is_dissipation(hertz):
    t0 = 0.6
    phi0 = float(ref.hertz_twist_hat(t0)) * PHI_SCALE
    tw = cycle(phi0)
    h = hertz.twist_history(twist=tw, force=F_HERTZ)
    n = 400
    M0 = h.torque[n]
    assert rel(h.torque[-1], M0) < TOL.EXACT_ROUTES                          # the loop closes
    assert rel(-h.torque[3 * n], M0) < TOL.EXACT_ROUTES                      # and is symmetric
    mid = np.arange(n + 1, 3 * n + 1)
    np.testing.assert_allclose(h.torque[mid], -h.torque[mid + 2 * n], rtol=TOL.EXACT_ROUTES, atol=TOL.EXACT_ROUTES * M0)
    D = h.dissipated_energy
    W_cycle = D[-1] - D[n]
    W_ref = float(ref.hertz_loop_energy_hat(t0)) * MU**2 * F_HERTZ**2 / (G_T * A)
    assert rel(W_cycle, W_ref) < TOL.MASING_ENERGY
    # the loop area ∮ M dφ (Simpson on the steps) is the same energy
    loop_phi, loop_M = tw[n:], h.torque[n:]
    from scipy.integrate import simpson
    area = simpson(loop_M[:2 * n + 1], x=loop_phi[:2 * n + 1]) + simpson(loop_M[2 * n:], x=loop_phi[2 * n:])
    assert rel(area, W_ref) < TOL.LOOP_AREA_HISTORY
    assert np.all(np.diff(D) >= -1e-12 * W_ref)                    # dissipation never decreases


@pytest.mark.parametrize("t0,excess", [(0.999, 0.0033), (0.99, 0.033)])
def test_small_amplitude_cube_law(hertz, t0, excess):
    """W ≈ 3 M0³/(16 μ F G_t a⁴) [D54]; the exact W is larger by 0.33 % (c0/a = 0.999), 3.3 % (0.99)."""
    phi0 = float(ref.hertz_twist_hat(t0)) * PHI_SCALE
    h = hertz.twist_history(twist=[phi0, -phi0, phi0], force=F_HERTZ)
    W = h.dissipated_energy[2] - h.dissipated_energy[0]
    M0 = h.torque[0]
    cube = 3 * M0**3 / (16 * MU * F_HERTZ * G_T * A**4)
    assert abs(W / cube - 1 - excess) < 0.1 * excess
    W_ref = float(ref.hertz_loop_energy_hat(t0)) * MU**2 * F_HERTZ**2 / (G_T * A)
    assert rel(W, W_ref) < TOL.MASING_HISTORY


def _hertz_slip_rotation(x: np.ndarray) -> np.ndarray:
    """μ P(x)/(2G_t) with P = p0 [K(k) - E(k)], k² = 1 - x²/a² (theory §6.3; scipy, not contactlab)."""
    m = 1 - (x / A) ** 2
    return MU * P0 * (ellipk(m) - ellipe(m)) / (2 * G_T)


IRREGULAR = np.array([0.0, 0.3, 0.8, 0.5, 0.65, 0.45, 1.2, -0.2, 0.4, 0.1, 0.3, -0.9, 1.5,
                      0.6, 0.9, 0.7, 1.0, 0.0, 0.05])


def test_exact_history_against_jenkins_elements(hertz):
    phi_hist = IRREGULAR * PHI_SCALE * 0.4
    # refine each step so that the element simulation follows the path (it is rate independent:
    # the refinement only guarantees clipping happens at the right places)
    fine = np.concatenate([np.linspace(phi_hist[i], phi_hist[i + 1], 50, endpoint=False)
                           for i in range(len(phi_hist) - 1)] + [phi_hist[-1:]])
    N = 4000
    x = (np.arange(N) + 0.5) / N * A
    dx = A / N
    stiff = 16 * G_T * x**2 * dx          # torque per unit rotation of an element
    limit = _hertz_slip_rotation(x)
    th = np.zeros(N)
    prev = 0.0
    M_el, D_el = [], []
    acc = 0.0
    for p in fine:
        trial = th + (p - prev)
        new = np.clip(trial, -limit, limit)
        acc += np.sum(stiff * limit * np.abs(trial - new))
        th, prev = new, p
        M_el.append(np.sum(stiff * th))
        D_el.append(acc)
    keep = np.arange(0, len(fine), 50)
    h = hertz.twist_history(twist=phi_hist, force=F_HERTZ)
    np.testing.assert_allclose(h.torque, np.array(M_el)[keep], rtol=0,
                               atol=TOL.JENKINS_4000 * M_SCALE)
    np.testing.assert_allclose(h.dissipated_energy, np.array(D_el)[keep], rtol=TOL.JENKINS_DISSIPATION,
                               atol=TOL.JENKINS_4000 * M_SCALE * PHI_SCALE)


def test_mdr_history_against_jenkins_springs(hertz):
    phi_hist = IRREGULAR * PHI_SCALE * 0.03                     # small: MDR stays valid
    fine = np.concatenate([np.linspace(phi_hist[i], phi_hist[i + 1], 50, endpoint=False)
                           for i in range(len(phi_hist) - 1)] + [phi_hist[-1:]])
    N = 4000
    x = (np.arange(N) + 0.5) / N * A
    dx = A / N
    k = 16 * G_T * dx                                            # both sides of the axis
    u_s = MU * E_STAR * (A**2 / R - x**2 / R) / (4 * G_T)
    u = np.zeros(N)
    prev = 0.0
    M_el, D_el, acc = [], [], 0.0
    for p in fine:
        trial = u + x * (p - prev)
        new = np.clip(trial, -u_s, u_s)
        acc += np.sum(k * u_s * np.abs(trial - new))
        u, prev = new, p
        M_el.append(np.sum(k * x * u))
        D_el.append(acc)
    keep = np.arange(0, len(fine), 50)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        # the torque stays valid; the dissipated energy, the most sensitive quantity, is past
        # its 1 % limit at this twist (c/a ~ 0.89: ~2.5 % against the exact solution), which
        # twist_history now says (issue 26); here the MDR is compared with MDR springs
        warnings.filterwarnings("ignore", message=".*dissipated energy", category=ValidityWarning)
        h = hertz.twist_history(twist=phi_hist, force=F_HERTZ, method="mdr")
    assert "dissipated_energy" in h.model_errors and h.model_errors["torque"] < 0.01
    scale = np.max(np.abs(h.torque))
    np.testing.assert_allclose(h.torque, np.array(M_el)[keep], rtol=0, atol=TOL.JENKINS_4000 * scale)
    np.testing.assert_allclose(h.dissipated_energy, np.array(D_el)[keep], rtol=TOL.JENKINS_DISSIPATION,
                               atol=TOL.JENKINS_4000 * scale * np.max(np.abs(phi_hist)))


def test_wiped_out_loop_returns_to_virgin_curve(hertz):
    p = PHI_SCALE * np.array([0.2, 0.1, 0.15, 0.12, 0.35])
    h = hertz.twist_history(twist=p, force=F_HERTZ)
    mono = hertz.torsion(force=F_HERTZ, twist=p[-1])
    assert rel(h.torque[-1], mono.torque) < TOL.EXACT_ROUTES
    assert rel(h.stick_radius[-1], mono.stick_radius) < TOL.EXACT_ROUTES


def test_mdr_history_warns_when_slip_is_wide(hertz):
    with pytest.warns(ValidityWarning, match="MDR"):
        hertz.twist_history(twist=[0.0, 2 * PHI_SCALE, -2 * PHI_SCALE], force=F_HERTZ, method="mdr")


def test_no_slip_history_is_linear_and_lossless():
    c = cl.Contact(cl.profiles.Paraboloid(R=R), materials())
    tw = np.array([0.0, 1e-4, -2e-4, 3e-4])
    h = c.twist_history(twist=tw, force=F_HERTZ)
    np.testing.assert_allclose(h.torque, 16 / 3 * G_T * A**3 * tw, rtol=TOL.TORSION_EXACT)
    assert np.all(h.dissipated_energy == 0)


def test_tabulated_history_matches_analytic(hertz):
    r = np.linspace(0, 1.5 * A, 1000)
    tab = cl.Contact(cl.profiles.Tabulated(r, r**2 / (2 * R)), materials(), friction=MU)
    tw = PHI_SCALE * np.array([0.0, 0.3, -0.2, 0.25, -0.3])
    ht = tab.twist_history(twist=tw, force=F_HERTZ)
    ha = hertz.twist_history(twist=tw, force=F_HERTZ)
    np.testing.assert_allclose(ht.torque, ha.torque, rtol=TOL.TORSION_TABLE_1000)
    np.testing.assert_allclose(ht.dissipated_energy[1:], ha.dissipated_energy[1:],
                               rtol=TOL.TORSION_TABLE_1000)


def test_flat_punch_history_energy_per_cycle():
    """Flat punch: no dissipation below φ_0 (no slip); above, the loop energy follows
    W = 8∫_0^{φ0} M dφ - 4φ0M0 with M from torsion() (trapezoid over a fine monotonic curve)."""
    d = 1e-7
    c = cl.Contact(cl.profiles.FlatPunch(radius=A), materials(), friction=MU)
    phi_0 = MU * E_STAR * d / (4 * G_T * A)
    small = c.twist_history(twist=[0.5 * phi_0, -0.5 * phi_0, 0.5 * phi_0], depth=d)
    assert np.all(small.dissipated_energy == 0)
    phi0 = 3 * phi_0
    h = c.twist_history(twist=[phi0, -phi0, phi0], depth=d)
    W = h.dissipated_energy[2] - h.dissipated_energy[0]
    grid = np.linspace(0, phi0, 4001)
    M = c.torsion(depth=d, twist=grid).torque
    from scipy.integrate import simpson
    W_ref = 8 * simpson(M, x=grid) - 4 * phi0 * M[-1]
    assert rel(W, W_ref) < TOL.SIMPSON_KINK          # Simpson across the kink of M at φ_0


@pytest.mark.parametrize("t0,low", [(0.99, 0.0025), (0.9, 0.024)])
def test_mdr_loop_energy_vs_exact(hertz, t0, low):
    """theory §6.5: at the same φ0 the MDR W is 0.25 % low at c0/a = 0.99, 2.4 % low at 0.9."""
    phi0 = float(ref.hertz_twist_hat(t0)) * PHI_SCALE
    tw = [phi0, -phi0, phi0]
    W_ex = np.diff(hertz.twist_history(twist=tw, force=F_HERTZ).dissipated_energy[[0, 2]])[0]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ValidityWarning)
        hm = hertz.twist_history(twist=tw, force=F_HERTZ, method="mdr")
    W_md = hm.dissipated_energy[2] - hm.dissipated_energy[0]
    assert abs((1 - W_md / W_ex) / low - 1) < 0.05      # docs/theory quotes two digits
