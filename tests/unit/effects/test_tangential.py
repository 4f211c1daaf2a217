"""Cattaneo–Mindlin closed forms (contact.tangential, contact.shift_history) against independent
re-implementations of theory §5 (Mindlin 1949, Mindlin–Deresiewicz 1953)."""
import numpy as np
import pytest
from scipy.integrate import quad

import contactlab as cl
from contactlab.errors import NotSupportedError, ParameterError

from tests import tolerances as TOL
from tests.reference import hertz as hz
from tests.tolerances import CLOSED_FORM, QUADRATURE

MU = 0.3
STEEL = cl.Elastic(E=210e9, nu=0.3)
RUBBER = cl.Elastic(E=10e6, nu=0.45)


def hertz():
    return cl.Contact(cl.profiles.Paraboloid(R=0.01), materials=(STEEL, STEEL), friction=MU)


def hertz_ref(c, F, u):
    """Mindlin: F_x = μF[1-(1-u/u*)^{3/2}], c = a(1-u/u*)^{1/2}, u* = 3μF/(4aG*)."""
    a = hz.radius_of_force(F, 0.01, hz.effective_modulus(210e9, 0.3, 210e9, 0.3))   # [J85]
    us = 3 * MU * F / (4 * a * c.moduli.tangential)
    x = np.clip(np.abs(u) / us, 0, 1)
    return np.sign(u) * MU * F * (1 - (1 - x) ** 1.5), a * np.sqrt(1 - x), us, a


def test_hertz_displacement_control():
    c = hertz()
    F = 50.0
    _, _, us, _ = hertz_ref(c, F, 1.0)
    u = np.linspace(-0.99, 0.99, 21) * us
    s = c.tangential(force=F, displacement=u)
    Fx, cc, _, _ = hertz_ref(c, F, u)
    np.testing.assert_allclose(s.tangential_force, Fx, rtol=CLOSED_FORM, atol=TOL.ABS_FLOOR * MU * F)
    np.testing.assert_allclose(s.stick_radius, cc, rtol=TOL.CM_CLOSED)
    np.testing.assert_allclose(s.stiffness, 2 * c.moduli.tangential * cc, rtol=TOL.CM_CLOSED)


def test_hertz_force_and_stick_radius_control_round_trip():
    c = hertz()
    F = 50.0
    _, _, us, a = hertz_ref(c, F, 1.0)
    T = np.array([0.1, 0.5, 0.9]) * MU * F
    s = c.tangential(force=F, tangential_force=T)
    Fx, cc, _, _ = hertz_ref(c, F, s.displacement)
    np.testing.assert_allclose(Fx, T, rtol=TOL.CM_CLOSED)
    s2 = c.tangential(force=F, stick_radius=s.stick_radius)
    np.testing.assert_allclose(s2.displacement, s.displacement, rtol=TOL.CM_CLOSED)


def test_cone_power_law_formula():
    c = cl.Contact(cl.profiles.Cone(slope=0.2), materials=(STEEL, RUBBER), friction=MU)
    ns = c.normal(force=2.0)
    E, Gs = c.moduli.normal, c.moduli.tangential
    us = MU * E * ns.depth / Gs
    u = np.linspace(0.01, 0.99, 9) * us
    s = c.tangential(force=2.0, displacement=u)
    # power law n = 1: F_x = μF[1 - (1-u/u*)^2], c = a(1-u/u*)
    np.testing.assert_allclose(s.tangential_force, MU * 2.0 * (1 - (1 - u / us) ** 2),
                               rtol=CLOSED_FORM)
    np.testing.assert_allclose(s.stick_radius, ns.radius * (1 - u / us), rtol=TOL.CM_CLOSED)


def test_gross_sliding_is_flagged_not_an_error():
    c = hertz()
    s = c.tangential(force=10.0, tangential_force=[0.5 * MU * 10, 2 * MU * 10])
    assert list(s.gross_sliding) == [False, True]
    assert s.tangential_force[1] == pytest.approx(MU * 10.0, rel=TOL.EXACT_ROUTES)


def test_hertz_shear_traction():
    c = hertz()
    F = 50.0
    s = c.tangential(force=F, displacement=0.5 * hertz_ref(c, F, 1.0)[2])
    a, cc = s.normal.radius, s.stick_radius
    p0 = 3 * F / (2 * np.pi * a ** 2)
    r = np.array([0.0, 0.3, 0.6, 0.8, 0.95]) * a
    ref = MU * p0 * (np.sqrt(1 - (r / a) ** 2) - np.where(r < cc, cc / a * np.sqrt(
        np.clip(1 - (r / cc) ** 2, 0, None)), 0))
    np.testing.assert_allclose(s.shear(r), ref, rtol=QUADRATURE * 10)


def md_loop(c, F, u0, u):
    """Masing unloading from +u0: F(u) = F(u0) - 2F_load((u0-u)/2)."""
    return hertz_ref(c, F, u0)[0] - 2 * hertz_ref(c, F, (u0 - u) / 2)[0]


def test_shift_history_mindlin_deresiewicz_loop_and_energy():
    c = hertz()
    F = 50.0
    us = hertz_ref(c, F, 1.0)[2]
    u0 = 0.6 * us
    k = np.arange(1, 401)
    u = u0 * np.sin(2 * np.pi * k / 200)
    h = c.shift_history(force=F, displacement=u)
    down = (k > 50) & (k <= 150)
    np.testing.assert_allclose(h.tangential_force[down], md_loop(c, F, u0, u[down]),
                               rtol=TOL.CM_CLOSED, atol=TOL.ABS_FLOOR * MU * F)
    up = (k > 150) & (k <= 250)
    np.testing.assert_allclose(h.tangential_force[up], -md_loop(c, F, u0, -u[up]),
                               rtol=TOL.CM_CLOSED, atol=TOL.ABS_FLOOR * MU * F)
    # energy per cycle, Mindlin–Deresiewicz (theory §5), t = T/(μF)
    a = c.normal(force=F).radius
    T = hertz_ref(c, F, u0)[0]
    t = T / (MU * F)
    W = 18 / 5 * MU ** 2 * F ** 2 / (a * c.moduli.tangential) * (
        1 - (1 - t) ** (5 / 3) - 5 * t / 6 * (1 + (1 - t) ** (2 / 3)))
    per_cycle = h.dissipated_energy[349] - h.dissipated_energy[149]
    assert per_cycle == pytest.approx(W, rel=TOL.MASING_ENERGY)
    # loop area equals the dissipation (independent: trapezoid over a fine cycle)
    loop = np.trapezoid(h.tangential_force[150:350], u[150:350])
    assert loop == pytest.approx(W, rel=TOL.LOOP_TRAPEZOID_200)  # 200-point trapezoid of the loop


def test_shift_history_memory_erases_closed_loops():
    c = hertz()
    F = 50.0
    us = hertz_ref(c, F, 1.0)[2]
    u = np.array([0.4, 0.2, 0.3, 0.5, 0.7]) * us
    h = c.shift_history(force=F, displacement=u)
    # after passing 0.4 again the virgin curve resumes
    np.testing.assert_allclose(h.tangential_force[3:], hertz_ref(c, F, u[3:])[0], rtol=TOL.CLOSED_FORM)
    np.testing.assert_allclose(h.tangential_force[1], md_loop(c, F, u[0], u[1]), rtol=TOL.CLOSED_FORM)
    # reloading 0.2 -> 0.3 follows a Masing branch from (0.2, F1)
    F1 = h.tangential_force[1]
    assert h.tangential_force[2] == pytest.approx(F1 + 2 * hertz_ref(c, F, (u[2] - u[1]) / 2)[0],
                                                  rel=TOL.CLOSED_FORM)


def test_tangential_validation():
    c = hertz()
    with pytest.raises(ParameterError, match="displacement="):
        c.tangential(force=1.0)
    with pytest.raises(ParameterError, match="stick_radius"):
        c.tangential(force=1.0, stick_radius=1.0)
    with pytest.raises(NotSupportedError, match="friction"):
        cl.Contact(cl.profiles.Paraboloid(R=0.01), materials=(STEEL, STEEL)).shift_history(
            force=1.0, displacement=[1e-7])


def test_no_friction_is_rigid_shift():
    c = cl.Contact(cl.profiles.Paraboloid(R=0.01), materials=(STEEL, STEEL))
    s = c.tangential(force=10.0, displacement=1e-7)
    assert s.tangential_force == pytest.approx(2 * c.moduli.tangential * s.normal.radius * 1e-7,
                                               rel=CLOSED_FORM)


def test_virgin_dissipation_quadrature():
    """D(u) = 2∫_c^a h(u - h/G*) dx against scipy quad (cone)."""
    from contactlab.physics.tangential import virgin_dissipation
    c = cl.Contact(cl.profiles.Cone(slope=0.2), materials=(STEEL, RUBBER), friction=MU)
    ns = c.normal(force=2.0)
    E, Gs = c.moduli.normal, c.moduli.tangential
    a, d = ns.radius, ns.depth
    u = 0.4 * MU * E * d / Gs

    def h(x):
        return MU * E * (d - np.pi / 2 * 0.2 * x)

    cc = a * (1 - 0.4)
    ref = 2 * quad(lambda x: h(x) * (u - h(x) / Gs), cc, a, epsabs=0, epsrel=1e-13)[0]
    got = virgin_dissipation(c.profile, E, Gs, MU, a, d, u, 1e-12)
    assert float(got) == pytest.approx(ref, rel=TOL.QUADRATURE)


def test_flat_punch_sticks_fully_until_full_slip():
    """Flat punch: all springs carry d, so F_x = 2G*b u until u* = μE*d/G*, then μF_N."""
    b = 1e-3
    c = cl.Contact(cl.profiles.FlatPunch(radius=b), materials=(STEEL, STEEL), friction=MU)
    ns = c.normal(force=100.0)
    Gs = c.moduli.tangential
    us = MU * c.moduli.normal * ns.depth / Gs
    u = np.array([0.1, 0.5, 0.99]) * us
    s = c.tangential(force=100.0, displacement=u)
    np.testing.assert_allclose(s.tangential_force, 2 * Gs * b * u, rtol=CLOSED_FORM)
    np.testing.assert_allclose(s.stick_radius, b, rtol=CLOSED_FORM)
    s2 = c.tangential(force=100.0, tangential_force=2 * Gs * b * u)
    np.testing.assert_allclose(s2.displacement, u, rtol=TOL.EXACT_ROUTES)
