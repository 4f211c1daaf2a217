"""Adhesive (JKR) contacts through the MDR against independent closed forms (theory §4)."""
from __future__ import annotations

import numpy as np
import pytest
from scipy.optimize import brentq, minimize_scalar

import contactlab as cl
from contactlab.errors import OutsideTheoryError, ParameterError, ValidityWarning
from contactlab.profiles import (Cone, FlatPunch, Paraboloid, PowerLaw, Sphere,
                                 TruncatedCone, TruncatedParaboloid)

from tests import tolerances as TOL
from tests.reference import adhesion as ref_jkr
from tests.reference.kappa import kappa_float as kappa
from tests.tolerances import (CLOSED_FORM, JKR_FINITE_DIFFERENCE, JKR_ROOT, JKR_SMALL_ADHESION,
                         PRESSURE_INTEGRAL)

E_STAR = 2.0e6          # Pa (rubber on glass)
DGAMMA = 0.05           # J/m²
R = 0.01                # m
# an incompressible body on a rigid one: E* = E/(1-ν²) = 4E/3
BODY = cl.Elastic(E=0.75 * E_STAR, nu=0.5)


def contact(profile, w=DGAMMA):
    return cl.Contact(profile, materials=(BODY, cl.Rigid()), work_of_adhesion=w)


# ---- paraboloid: JKR [JKR71] ------------------------------------------------------------
def jkr_force(a, w=DGAMMA):
    return ref_jkr.jkr_force(a, R, E_STAR, w)


def jkr_depth(a, w=DGAMMA):
    return ref_jkr.jkr_depth(a, R, E_STAR, w)


def test_moduli_setup():
    assert contact(Paraboloid(R)).moduli.normal == pytest.approx(E_STAR, rel=CLOSED_FORM)


def test_sphere_pull_off_force_control():
    s = contact(Paraboloid(R)).pull_off(control="force")
    assert s.force == pytest.approx(-1.5 * np.pi * DGAMMA * R, rel=JKR_ROOT)
    a_c = (9 * np.pi * DGAMMA * R**2 / (8 * E_STAR)) ** (1 / 3)
    assert s.radius == pytest.approx(a_c, rel=JKR_ROOT)
    assert s.depth == pytest.approx(jkr_depth(a_c), rel=JKR_ROOT)
    assert abs(s.stiffness) < TOL.JKR_STIFFNESS_ZERO * 2 * E_STAR * a_c        # dF/dd = 0 at the force minimum


def test_sphere_pull_off_displacement_control():
    s = contact(Paraboloid(R)).pull_off(control="displacement")
    assert s.force == pytest.approx(-5.0 / 6.0 * np.pi * DGAMMA * R, rel=JKR_ROOT)
    a_c = (np.pi * DGAMMA * R**2 / (8 * E_STAR)) ** (1 / 3)
    assert s.radius == pytest.approx(a_c, rel=JKR_ROOT)
    assert s.depth == pytest.approx(jkr_depth(a_c), rel=JKR_ROOT)


@pytest.mark.parametrize("a", [5e-5, 2e-4, 4e-4, 1e-3])
def test_jkr_curve_by_radius(a):
    s = contact(Paraboloid(R)).normal(radius=a)
    assert s.force == pytest.approx(jkr_force(a), rel=CLOSED_FORM)
    assert s.depth == pytest.approx(jkr_depth(a), rel=CLOSED_FORM)


def test_jkr_curve_by_depth_and_force_stable_branch():
    c = contact(Paraboloid(R))
    a_disp = (np.pi * DGAMMA * R**2 / (8 * E_STAR)) ** (1 / 3)
    a_force = (9 * np.pi * DGAMMA * R**2 / (8 * E_STAR)) ** (1 / 3)
    a_ref = np.array([1.2 * a_disp, 2 * a_disp, 3e-4, 8e-4])
    s = c.normal(depth=jkr_depth(a_ref))
    # independent root of the closed form on the stable branch
    a_bq = [brentq(lambda x, t=t: jkr_depth(x) - t, a_disp, 1.0, xtol=1e-16, rtol=1e-14)
            for t in jkr_depth(a_ref)]
    np.testing.assert_allclose(s.radius, a_bq, rtol=JKR_ROOT)
    np.testing.assert_allclose(s.force, jkr_force(np.array(a_bq)), rtol=JKR_ROOT)
    a_f = np.array([1.1 * a_force, 2 * a_force, 1e-3])
    sf = c.normal(force=jkr_force(a_f))
    np.testing.assert_allclose(sf.radius, a_f, rtol=JKR_ROOT)
    np.testing.assert_allclose(sf.depth, jkr_depth(a_f), rtol=JKR_ROOT)


def test_jkr_unstable_branches():
    c = contact(Paraboloid(R))
    a_disp = (np.pi * DGAMMA * R**2 / (8 * E_STAR)) ** (1 / 3)
    a_force = (9 * np.pi * DGAMMA * R**2 / (8 * E_STAR)) ** (1 / 3)
    d = 0.5 * jkr_depth(a_disp)
    s = c.normal(depth=d, branch="unstable")
    a_bq = brentq(lambda x: jkr_depth(x) - d, 1e-12, a_disp, xtol=1e-18, rtol=1e-14)
    assert s.radius == pytest.approx(a_bq, rel=JKR_ROOT)
    assert not s.meta["stable_under_displacement"]
    F = 0.5 * jkr_force(a_force)
    sf = c.normal(force=F, branch="unstable")
    a_bq = brentq(lambda x: jkr_force(x) - F, 1e-12, a_force, xtol=1e-18, rtol=1e-14)
    assert sf.radius == pytest.approx(a_bq, rel=JKR_ROOT)
    assert not sf.meta["stable_under_force"]
    # between the two pull-off radii: stable only under fixed grips
    sm = c.normal(radius=0.5 * (a_disp + a_force))
    assert sm.meta["stable_under_displacement"] and not sm.meta["stable_under_force"]


def test_jkr_stiffness_along_the_curve():
    a = np.array([1.5e-4, 3e-4, 6e-4])
    s = contact(Paraboloid(R)).normal(radius=a)
    dF = 4 * E_STAR * a**2 / R - 1.5 * np.sqrt(8 * np.pi * a * E_STAR * DGAMMA)
    dd = 2 * a / R - 0.5 * np.sqrt(2 * np.pi * DGAMMA / (E_STAR * a))
    np.testing.assert_allclose(s.stiffness, dF / dd, rtol=CLOSED_FORM)


def test_detached_below_displacement_pull_off():
    c = contact(Paraboloid(R))
    d_c = c.pull_off("displacement").depth
    s = c.normal(depth=[1.01 * d_c, -1.0])
    np.testing.assert_array_equal(s.radius, 0.0)
    np.testing.assert_array_equal(s.force, 0.0)


def test_force_below_pull_off_raises():
    with pytest.raises(OutsideTheoryError, match="pull-off"):
        contact(Paraboloid(R)).normal(force=-2 * np.pi * DGAMMA * R)


# ---- pressure and displacement fields ------------------------------------------------------
def test_jkr_pressure_closed_form_and_integral():
    a = 3e-4
    s = contact(Paraboloid(R)).normal(radius=a)
    r = np.array([0.0, 0.3 * a, 0.9 * a, 0.999 * a])
    ref = (2 * E_STAR / (np.pi * R)) * np.sqrt(a**2 - r**2) + (E_STAR / np.pi) * (
        jkr_depth(a) - a**2 / R) / np.sqrt(a**2 - r**2)
    np.testing.assert_allclose(s.pressure(r), ref, rtol=CLOSED_FORM)
    assert s.pressure(0.999999 * a) < 0          # tensile edge singularity
    # 2π∫p r dr with r = a sinθ (the edge singularity cancels against cosθ)
    x, wts = np.polynomial.legendre.leggauss(96)
    th = 0.25 * np.pi * (x + 1)
    integrand = s.pressure(a * np.sin(th)) * a**2 * np.sin(th) * np.cos(th)
    F = 2 * np.pi * 0.25 * np.pi * np.sum(wts * integrand)
    assert F == pytest.approx(s.force, rel=PRESSURE_INTEGRAL)


def test_jkr_pressure_integral_exact_sphere():
    """Second profile (quadrature pressure route): 2π∫p r dr = F."""
    s = contact(Sphere(R)).normal(radius=4e-4)
    a = s.radius
    x, wts = np.polynomial.legendre.leggauss(96)
    th = 0.25 * np.pi * (x + 1)
    integrand = s.pressure(a * np.sin(th)) * a**2 * np.sin(th) * np.cos(th)
    F = 2 * np.pi * 0.25 * np.pi * np.sum(wts * integrand)
    assert F == pytest.approx(s.force, rel=PRESSURE_INTEGRAL)


def test_jkr_displacement_inside_and_outside():
    a = 3e-4
    s = contact(Paraboloid(R)).normal(radius=a)
    d = jkr_depth(a)
    r_in = np.array([0.0, 0.5 * a])
    np.testing.assert_allclose(s.displacement(r_in), d - r_in**2 / (2 * R), rtol=CLOSED_FORM,
                               atol=TOL.ABS_FLOOR * abs(d))
    r = np.array([1.5 * a, 4 * a])
    ref = (2 * d / np.pi) * np.arcsin(a / r) - (r**2 * np.arcsin(a / r)
                                              - a * np.sqrt(r**2 - a**2)) / (np.pi * R)
    np.testing.assert_allclose(s.displacement(r), ref, rtol=TOL.QUADRATURE)


# ---- other profiles ------------------------------------------------------------------------
def test_kendall_flat_punch():
    b = 1e-3
    c = contact(FlatPunch(b))
    F_k = -np.sqrt(8 * np.pi * E_STAR * DGAMMA * b**3)
    for control in ("force", "displacement"):
        s = c.pull_off(control=control)
        assert s.force == pytest.approx(F_k, rel=CLOSED_FORM)
        assert s.radius == b
        assert s.depth == pytest.approx(-np.sqrt(2 * np.pi * b * DGAMMA / E_STAR), rel=CLOSED_FORM)
    d = np.array([1e-6, -1e-6, -1e-3])
    s = c.normal(depth=d)
    np.testing.assert_allclose(s.force, [2 * E_STAR * b * 1e-6, -2 * E_STAR * b * 1e-6, 0.0],
                               rtol=CLOSED_FORM)
    sf = c.normal(force=[0.5 * F_k, 1.0])
    np.testing.assert_allclose(sf.depth, np.array([0.5 * F_k, 1.0]) / (2 * E_STAR * b),
                               rtol=CLOSED_FORM)
    assert sf.peak_pressure[1] == np.inf and np.isfinite(sf.peak_pressure[0])
    # a partially detached face (a < b) is an (unstable) equilibrium: F = -sqrt(8πE*Δγa³)
    su = c.normal(radius=0.5 * b)
    assert su.force == pytest.approx(-np.sqrt(8 * np.pi * E_STAR * DGAMMA * (0.5 * b) ** 3),
                                     rel=CLOSED_FORM)
    assert not su.meta["stable_under_force"] and not su.meta["stable_under_displacement"]


def test_truncated_paraboloid_detaches_at_its_rim_like_kendall():
    """g' is infinite at the rim of the flat part, so both pull-offs sit there (F = Kendall)."""
    b = 1e-4
    for prof in (TruncatedParaboloid(b, 1e-3), TruncatedCone(b, 0.1)):
        s = contact(prof).pull_off()               # steep edge: φ > 3/2 for all a > b
        assert s.radius == b                       # the crossing is snapped onto the rim
        assert s.force == pytest.approx(-np.sqrt(8 * np.pi * E_STAR * DGAMMA * b**3),
                                        rel=CLOSED_FORM)


def test_gently_rounded_punch_warns_about_a_second_branch():
    """With R = 10 mm φ dips below 3/2 beyond the rim: two force-stable branches."""
    b = 1e-4
    with pytest.warns(ValidityWarning, match="another stable branch"):
        s = contact(TruncatedParaboloid(b, R)).pull_off()
    assert s.radius > 1.5 * b


def test_cone_pull_off():
    tb = 0.2
    s = contact(Cone(tb)).pull_off()
    assert s.radius == pytest.approx(18 * DGAMMA / (np.pi * E_STAR * tb**2), rel=JKR_ROOT)
    assert s.force == pytest.approx(-54 * DGAMMA**2 / (np.pi * E_STAR * tb**3), rel=JKR_ROOT)


@pytest.mark.parametrize("n", [0.75, 1.5, 3.0, 6.0])
def test_power_law_pull_off(n):
    c_coef = 50.0 ** (n - 1)   # keeps a_c at a sensible size
    A = 2 * E_STAR * kappa(n) * c_coef * n / (n + 1)
    B = np.sqrt(8 * np.pi * E_STAR * DGAMMA)
    a_c = (3 * B / (2 * (n + 1) * A)) ** (1 / (n - 0.5))
    F_c = -B * a_c**1.5 * (2 * n - 1) / (2 * (n + 1))
    con = contact(PowerLaw(c_coef, n))
    s = con.pull_off()
    assert s.radius == pytest.approx(a_c, rel=JKR_ROOT)
    assert s.force == pytest.approx(F_c, rel=JKR_ROOT)
    # fixed grips (derived here from dd/da = 0): a^(n-1/2) = sqrt(2πΔγ/E*)/(2nκc)
    a_d = (np.sqrt(2 * np.pi * DGAMMA / E_STAR) / (2 * n * kappa(n) * c_coef)) ** (1 / (n - 0.5))
    assert con.pull_off("displacement").radius == pytest.approx(a_d, rel=JKR_ROOT)


@pytest.mark.parametrize("n", [0.5, 0.3])
def test_power_law_n_at_most_half_has_no_pull_off(n):
    c = contact(PowerLaw(1.0, n))
    with pytest.raises(OutsideTheoryError, match="n <= 1/2"):
        c.pull_off()
    with pytest.raises(OutsideTheoryError, match="n <= 1/2"):
        c.normal(depth=1e-6)
    s = c.normal(radius=1e-4)          # the radius-controlled curve is still defined
    A = 2 * E_STAR * kappa(n) * 1.0 * n / (n + 1)
    assert s.force == pytest.approx(A * 1e-4 ** (n + 1) - np.sqrt(8 * np.pi * E_STAR * DGAMMA)
                                    * 1e-4**1.5, rel=CLOSED_FORM)


def test_exact_sphere_pull_off_against_direct_minimisation():
    """Sphere g = x artanh(x/R): minimise the closed-form F(a) independently (scipy)."""
    Rs = 2e-4                              # small sphere: a_c/R is not negligible

    def F(a):
        g = a * np.arctanh(a / Rs)
        gi = 0.5 * (a**2 - Rs**2) * np.arctanh(a / Rs) + 0.5 * Rs * a
        return 2 * E_STAR * (a * g - gi) - np.sqrt(8 * np.pi * a**3 * E_STAR * DGAMMA)

    ref = minimize_scalar(F, bounds=(1e-7, 0.9 * Rs), method="bounded",
                          options={"xatol": 1e-15})
    s = contact(Sphere(Rs)).pull_off()
    assert s.force == pytest.approx(ref.fun, rel=TOL.CLOSED_FORM)
    assert s.radius == pytest.approx(ref.x, rel=TOL.MINIMISER_LOCATION_DEFAULT)    # minimiser located to ~sqrt(eps)


def test_finite_difference_route_pull_off():
    """A profile known only by f(r) (no closed-form g'): finite-difference φ, same pull-off."""
    from contactlab.profiles.base import Profile

    class Bowl(Profile):
        name = "bowl_test"

        def _height(self, r):
            return r**2 / (2 * R)

    s = contact(Bowl()).pull_off()
    assert s.force == pytest.approx(-1.5 * np.pi * DGAMMA * R, rel=JKR_FINITE_DIFFERENCE)


# ---- limits --------------------------------------------------------------------------------
def test_small_adhesion_recovers_hertz():
    d = np.array([1e-7, 1e-6, 4e-6])
    hertz = cl.Contact(Paraboloid(R), materials=(BODY, cl.Rigid())).normal(depth=d)
    s = contact(Paraboloid(R), w=1e-20).normal(depth=d)
    np.testing.assert_allclose(s.force, 4 * E_STAR * np.sqrt(R) * d**1.5 / 3,
                               rtol=JKR_SMALL_ADHESION)
    np.testing.assert_allclose(s.radius, hertz.radius, rtol=JKR_SMALL_ADHESION)
    np.testing.assert_allclose(s.stiffness, hertz.stiffness, rtol=JKR_SMALL_ADHESION)
    # at fixed depth F is stationary in a (∂F/∂a = 2E*(d - g(a)) = 0 for Hertz), so the force
    # gap closes like Δγ while the radius gap closes like sqrt(Δγ)
    states = [contact(Paraboloid(R), w=w).normal(depth=1e-6) for w in (1e-8, 1e-10)]
    gaps_F = [abs(st.force - hertz.force[1]) for st in states]
    gaps_a = [abs(st.radius - hertz.radius[1]) for st in states]
    assert gaps_F[0] / gaps_F[1] == pytest.approx(100.0, rel=TOL.CONVERGENCE_ORDER)
    assert gaps_a[0] / gaps_a[1] == pytest.approx(10.0, rel=TOL.CONVERGENCE_ORDER)


def test_zero_adhesion_is_the_non_adhesive_solver():
    c = contact(Paraboloid(R), w=0.0)
    assert not c.is_adhesive
    assert type(c.normal(depth=1e-6)) is cl.NormalState


# ---- hysteresis ----------------------------------------------------------------------------
def test_adhesion_cycle_depth_control_jumps():
    c = contact(Paraboloid(R))
    a_d = (np.pi * DGAMMA * R**2 / (8 * E_STAR)) ** (1 / 3)
    d_c = jkr_depth(a_d)
    approach = np.linspace(d_c * 2, 5e-6, 41)     # passes d = 0 at index 16 ... exactly 0?
    approach = np.r_[np.linspace(2 * d_c, -1e-9, 10), 0.0, np.linspace(1e-7, 5e-6, 10)]
    retract = np.linspace(5e-6, 1.5 * d_c, 60)
    cyc = c.adhesion_cycle(depth=np.r_[approach, retract])
    n_app = approach.size
    # approach: apart below d = 0, then jump in at d = 0 with a³ = 2πΔγR²/E*
    assert not np.any(cyc.in_contact[:10])
    a0 = (2 * np.pi * DGAMMA * R**2 / E_STAR) ** (1 / 3)
    assert cyc.radius[10] == pytest.approx(a0, rel=JKR_ROOT)
    assert cyc.force[10] == pytest.approx(jkr_force(a0), rel=JKR_ROOT)
    # retraction: contact held through negative depths down to d_c, then lost
    ret = slice(n_app, None)
    held = cyc.depth[ret] >= d_c
    np.testing.assert_array_equal(cyc.in_contact[ret], held)
    assert np.any(cyc.in_contact[ret] & (cyc.depth[ret] < 0))
    assert cyc.pull_off_value == pytest.approx(d_c, rel=JKR_ROOT)
    assert list(cyc.jumps) == [10, n_app + int(np.sum(held))]


def test_adhesion_cycle_force_control():
    c = contact(Paraboloid(R))
    F_c = -1.5 * np.pi * DGAMMA * R
    F = np.r_[-1e-3, 0.0, 1e-2, 0.0, 0.9 * F_c, 1.1 * F_c, 0.5 * F_c]
    cyc = c.adhesion_cycle(force=F)
    np.testing.assert_array_equal(cyc.in_contact, [False, True, True, True, True, False, False])
    a_zero = (9 * np.pi * DGAMMA * R**2 / (2 * E_STAR)) ** (1 / 3)   # JKR radius at zero load
    assert cyc.radius[1] == pytest.approx(a_zero, rel=JKR_ROOT)


def _relay(history, lim):
    """The cycle's contact rule stepped one value at a time (the definition)."""
    state, out = False, []
    for v in history:
        state = (v >= lim) if state else (v >= 0.0)
        out.append(state)
    return np.array(out, bool)


@pytest.mark.parametrize("seed", range(8))
def test_contact_flags_follow_the_relay_step_by_step(seed):
    """The one-pass contact flags equal the rule stepped value by value on random histories
    (values at 0 and at the pull-off value exactly included), and on the edge cases."""
    from contactlab.effects.adhesion import contact_flags
    rng = np.random.default_rng(seed)
    lim = -rng.uniform(0.1, 1.0)
    h = rng.choice([rng.uniform(-2.0, 1.0), 0.0, lim, lim / 2], size=500)
    h = np.where(rng.random(500) < 0.7, rng.uniform(-2.0, 1.0, 500), h)
    np.testing.assert_array_equal(contact_flags(h, lim), _relay(h, lim))
    for edge in ([], [lim / 2], [0.0], [lim], [lim / 2, 0.0, lim / 2, lim, lim / 2]):
        e = np.array(edge, float)
        np.testing.assert_array_equal(contact_flags(e, lim), _relay(e, lim))


# ---- validation ----------------------------------------------------------------------------
def test_branch_validation():
    with pytest.raises(ParameterError, match="branch"):
        contact(Paraboloid(R)).normal(depth=1e-6, branch="middle")


def test_branch_without_adhesion():
    with pytest.raises(ParameterError, match="branch"):
        cl.Contact(Paraboloid(R), (BODY, cl.Rigid())).normal(depth=1e-6, branch="unstable")


def test_unstable_branch_out_of_range():
    with pytest.raises(ParameterError, match="depth"):
        contact(Paraboloid(R)).normal(depth=1e-6, branch="unstable")


def test_control_validation():
    with pytest.raises(ParameterError, match="control"):
        contact(Paraboloid(R)).pull_off(control="grips")


def test_pull_off_needs_adhesion():
    with pytest.raises(ParameterError, match="work_of_adhesion"):
        cl.Contact(Paraboloid(R), (BODY, cl.Rigid())).pull_off()


def test_cycle_needs_1d_history():
    with pytest.raises(ParameterError, match="depth"):
        contact(Paraboloid(R)).adhesion_cycle(depth=[[0.0, 1e-6]])


def test_radius_beyond_wall():
    with pytest.raises(OutsideTheoryError, match="radius"):
        contact(FlatPunch(1e-3)).normal(radius=2e-3)
