"""Torsion (issue 3): no slip, exact partial slip, MDR narrow-slip model, against theory §6.

Expected values come from tests/reference/torsion_reference.py (independent mpmath, 30 digits) or
from the reference tables of theory §6.3/6.4 (independent 30-digit computation), never from
contactlab's own output.
"""
from __future__ import annotations

import warnings

import numpy as np
import pytest

import contactlab as cl
from contactlab.errors import ValidityWarning
from tests import tolerances as TOL
from tests.reference import torsion_reference as ref

E1, NU1, E2, NU2 = 210e9, 0.3, 70e9, 0.33
G1, G2 = E1 / (2 * (1 + NU1)), E2 / (2 * (1 + NU2))
G_T = 1.0 / (1.0 / G1 + 1.0 / G2)                       # theory §1: compliances add
E_STAR = 1.0 / ((1 - NU1**2) / E1 + (1 - NU2**2) / E2)
MU = 0.3
R = 0.01
A = 2e-4                                                # contact radius, m
F_HERTZ = 4 * E_STAR * A**3 / (3 * R)
P0 = 2 * E_STAR * A / (np.pi * R)
PHI_SCALE = MU * F_HERTZ / (G_T * A**2)                 # φ̂ = φ / PHI_SCALE
M_SCALE = MU * F_HERTZ * A                              # M̂ = M / M_SCALE
RATIOS = [0.99, 0.9, 0.5, 0.1, 0.01]

# theory §6.3 reference table: c/a -> (φ̂ exact, M̂ exact, φ̂ MDR, M̂ MDR)
TABLE_63 = {0.99: (0.00375945, 0.0197514, 0.00376894, 0.0198010),
            0.9: (0.0385139, 0.176345, 0.0395833, 0.180975),
            0.5: (0.225712, 0.528576, 0.28125, 0.609375),
            0.1: (0.639718, 0.588620, 1.85625, 0.744975),
            0.01: (1.19159, 0.589048, 18.7481, 0.749950)}


def materials():
    return (cl.Elastic(E=E1, nu=NU1), cl.Elastic(E=E2, nu=NU2))


@pytest.fixture(scope="module")
def hertz():
    return cl.Contact(cl.profiles.Paraboloid(R=R), materials(), friction=MU)


def rel(x, y):
    return abs(float(x) / float(y) - 1.0)


# ---------------------------------------------------------------- no slip (§6.1)
def test_torsional_modulus_is_series_of_shear_moduli(hertz):
    assert rel(hertz.moduli.torsional, G_T) < TOL.CLOSED_FORM


def test_flat_punch_no_slip_reissner_sagoci():
    b = 1e-3
    c = cl.Contact(cl.profiles.FlatPunch(radius=b), materials())
    phi = np.array([-2e-4, 1e-5, 3e-4])
    s = c.torsion(depth=1e-6, twist=phi)
    assert s.method == "no-slip"
    np.testing.assert_allclose(s.torque, 16 / 3 * G_T * b**3 * phi, rtol=TOL.CLOSED_FORM)
    np.testing.assert_allclose(s.stick_radius, b, rtol=0)
    r = np.array([0.0, 0.3e-3, 0.9e-3, 0.999e-3, 1.5e-3])
    tau = s.shear(r)
    expect = np.where(r < b, 4 * G_T * phi[:, None] / np.pi * r / np.sqrt(np.abs(b**2 - r**2)), 0.0)
    np.testing.assert_allclose(tau, expect, rtol=TOL.CLOSED_FORM, atol=0)
    u = s.displacement(r)
    q = np.minimum(b / np.maximum(r, 1e-300), 1.0)
    out = 2 * phi[:, None] / np.pi * (r * np.arcsin(q) - b * np.sqrt(1 - q**2))
    np.testing.assert_allclose(u, np.where(r <= b, phi[:, None] * r, out), rtol=TOL.CLOSED_FORM)


def test_no_slip_compliances_add():
    """Twist of two elastic bodies = sum of the twists of each body against a rigid punch."""
    b, M = 1e-3, 0.7
    one = cl.Contact(cl.profiles.FlatPunch(radius=b), (cl.Elastic(E=E1, nu=NU1), cl.Rigid()))
    two = cl.Contact(cl.profiles.FlatPunch(radius=b), (cl.Rigid(), cl.Elastic(E=E2, nu=NU2)))
    both = cl.Contact(cl.profiles.FlatPunch(radius=b), materials())
    phis = [x.torsion(depth=1e-6, torque=M).twist for x in (one, two, both)]
    assert rel(phis[2], phis[0] + phis[1]) < TOL.CLOSED_FORM


def test_no_slip_mdr_spring_cross_check():
    from contactlab.physics import torsion_noslip
    a, phi = 1e-3, 1e-4
    n = 4000
    M = torsion_noslip.mdr_torque(G_T, np.array(a), np.array(phi), n_springs=n)
    exact = 16 / 3 * G_T * a**3 * phi
    assert rel(M, exact * (1 - 1 / (4 * n**2))) < TOL.CLOSED_FORM


def test_no_slip_far_field_displacement(hertz):
    s = hertz.torsion(radius=A, twist=1e-4, method="no-slip")
    r = 1e3 * A
    assert rel(s.displacement(r), s.torque / (4 * np.pi * G_T * r**2)) < TOL.FAR_FIELD_NEAR   # O((a/r)²)


# ---------------------------------------------------------------- Hertz exact (§6.3)
def test_hertz_full_sliding_torque(hertz):
    s = hertz.torsion(radius=A, twist=1e3 * PHI_SCALE)
    assert s.slip and s.stick_radius == 0.0
    assert rel(s.torque, 3 * np.pi / 16 * MU * F_HERTZ * A) < TOL.SLIDING_TORQUE
    assert rel(s.sliding_torque, 3 * np.pi / 16 * MU * F_HERTZ * A) < TOL.SLIDING_TORQUE


def test_hertz_small_twist_limit_is_no_slip_stiffness(hertz):
    phi = np.array([1e-9, 2e-9]) * PHI_SCALE
    s = hertz.torsion(radius=A, twist=phi)
    k0 = 16 / 3 * G_T * A**3
    assert rel((s.torque[1] - s.torque[0]) / (phi[1] - phi[0]), k0) < TOL.FD_STIFFNESS
    assert rel(s.stiffness[0], k0) < TOL.SMALL_TWIST_STIFFNESS


@pytest.mark.parametrize("t", RATIOS)
def test_hertz_partial_slip_against_lubkin_closed_form(hertz, t):
    s = hertz.torsion(radius=A, stick_radius=t * A)
    assert rel(s.twist / PHI_SCALE, ref.hertz_twist_hat(t)) < TOL.TORSION_EXACT
    assert rel(s.torque / M_SCALE, ref.hertz_torque_hat(t)) < TOL.TORSION_EXACT
    phi_hat, M_hat = TABLE_63[t][:2]
    assert rel(s.twist / PHI_SCALE, phi_hat) < TOL.TABLE_6_DIGITS
    assert rel(s.torque / M_SCALE, M_hat) < TOL.TABLE_6_DIGITS


def test_hertz_twist_and_torque_controls_invert(hertz):
    t = np.array(RATIOS)
    phi = np.array([float(ref.hertz_twist_hat(x)) for x in t]) * PHI_SCALE
    M = np.array([float(ref.hertz_torque_hat(x)) for x in t]) * M_SCALE
    s = hertz.torsion(force=F_HERTZ, twist=phi)
    np.testing.assert_allclose(s.stick_radius / A, t, rtol=TOL.TORSION_EXACT)
    np.testing.assert_allclose(s.torque, M, rtol=TOL.TORSION_EXACT)
    s2 = hertz.torsion(force=F_HERTZ, torque=-M)
    np.testing.assert_allclose(s2.twist, -phi, rtol=TOL.TORSION_EXACT)


@pytest.mark.parametrize("t", [1 - 1e-6, 1e-6])
def test_hertz_hard_stick_ratios(hertz, t):
    s = hertz.torsion(radius=A, stick_radius=t * A)
    tol_ = TOL.TORSION_NEAR_STICK if t > 0.5 else TOL.TORSION_EXACT
    assert rel(s.twist / PHI_SCALE, ref.hertz_twist_hat(t)) < tol_
    assert rel(s.torque / M_SCALE, ref.hertz_torque_hat(t)) < tol_
    back = hertz.torsion(radius=A, twist=s.twist)
    assert abs(back.stick_radius / A - t) < TOL.TORSION_EXACT * (1 - t if t > 0.5 else t) * 1e3


def test_incremental_stiffness_identity(hertz):
    """dM/dφ = (16/3) G_t c³ (theory §6.2 item 4), by central differences."""
    phi = 0.3 * PHI_SCALE
    h = 1e-5 * phi
    s = hertz.torsion(radius=A, twist=[phi - h, phi, phi + h])
    dM = (s.torque[2] - s.torque[0]) / (2 * h)
    assert rel(dM, s.stiffness[1]) < TOL.FD_STIFFNESS_FINE


# ---------------------------------------------------------------- traction and displacement
def test_hertz_stick_zone_traction(hertz):
    t = 0.5
    s = hertz.torsion(radius=A, stick_radius=t * A)
    rho = np.array([0.0, 0.1, 0.25, 0.4, 0.49])
    tau = s.shear(rho * A) / (MU * P0)
    expect = [float(ref.hertz_stick_shear_hat(x, t)) for x in rho]
    np.testing.assert_allclose(tau, expect, rtol=TOL.TORSION_EXACT, atol=TOL.ABS_FLOOR)
    # theory §8 item 2 (4 digits)
    np.testing.assert_allclose(tau[:4], [0, 0.0865, 0.231, 0.438], atol=TOL.TABLE_3_DIGITS)


@pytest.mark.parametrize("profile,load", [
    (cl.profiles.Paraboloid(R=R), {"radius": A}),
    (cl.profiles.Cone(slope=0.05), {"radius": A}),
    (cl.profiles.FlatPunch(radius=A), {"depth": 1e-7}),
    (cl.profiles.PowerLaw(c=1e10, n=4), {"radius": A}),
])
def test_traction_bounded_by_friction_and_continuous(profile, load):
    c = cl.Contact(profile, materials(), friction=MU)
    s = c.torsion(**load, stick_radius=0.6 * A)
    r = np.linspace(0.0, A, 101)[:-1]
    tau = s.shear(r)
    p = c.normal(**load).pressure(r)
    assert np.all(tau <= MU * p * (1 + 1e-9) + 1e-9 * MU * np.nanmax(p[np.isfinite(p)]))
    assert tau[0] == 0.0
    cc = s.stick_radius
    eps = 1e-7 * A
    left, right = s.shear([cc - eps, cc])
    assert rel(left, right) < TOL.CONTINUITY_SQRT                    # sqrt approach: O(sqrt(eps/c))
    # the torque is the moment of the traction: M = 2π ∫ τ r² dr (Gauss-Legendre after
    # substitutions that make both pieces smooth: r = c(1-u²) in the stick zone, r = a-(a-c)w²
    # in the slip annulus)
    u, w = np.polynomial.legendre.leggauss(48)
    u, w = 0.5 * (u + 1), 0.5 * w
    r1 = cc * (1 - u**2)
    stick = np.sum(w * s.shear(r1) * r1**2 * 2 * cc * u)
    r2 = A - (A - cc) * u**2
    slip = np.sum(w * MU * c.normal(**load).pressure(r2) * r2**2 * 2 * (A - cc) * u)
    assert rel(2 * np.pi * (stick + slip), s.torque) < TOL.SHEAR_INTEGRAL


def test_displacement_stick_and_far_field(hertz):
    s = hertz.torsion(radius=A, stick_radius=0.5 * A)
    r = np.array([0.2 * A, 0.5 * A])
    np.testing.assert_allclose(s.displacement(r), s.twist * r, rtol=TOL.EXACT_ROUTES)
    far = 300 * A
    assert rel(s.displacement(far), s.torque / (4 * np.pi * G_T * far**2)) < TOL.FAR_FIELD
    # continuous across the contact edge
    u_in, u_out = s.displacement([A * (1 - 1e-9), A * (1 + 1e-9)])
    assert rel(u_in, u_out) < TOL.CONTINUITY_EDGE


# ---------------------------------------------------------------- other profiles (hard cases)
def _general_case(profile, p_of_r, load, t, rtol=TOL.TORSION_EXACT):
    c = cl.Contact(profile, materials(), friction=MU)
    s = c.torsion(**load, stick_radius=t * A)
    phi_r, M_r = ref.torque_general(t * A, A, p_of_r, MU, G_T)
    assert rel(s.twist, phi_r) < rtol
    assert rel(s.torque, M_r) < rtol
    back = c.torsion(**load, twist=s.twist)
    assert abs(back.stick_radius / A - t) < TOL.STICK_ROUND_TRIP * t
    return c, s


@pytest.mark.parametrize("t", [0.9, 0.3, 1e-6])
def test_cone_partial_slip(t):
    slope = 0.05
    p = lambda r: ref.pressure_cone(r, A, E_STAR, slope)  # noqa: E731
    c, s = _general_case(cl.profiles.Cone(slope=slope), p, {"radius": A}, t)
    assert rel(s.sliding_torque, ref.sliding_torque_general(A, p, MU)) < TOL.TORSION_EXACT


@pytest.mark.parametrize("t", [0.9, 0.2, 1e-6])
def test_power_law_n20(t):
    coef = 1e60
    p = lambda r: ref.pressure_power(r, A, E_STAR, coef, 20)  # noqa: E731
    c, s = _general_case(cl.profiles.PowerLaw(c=coef, n=20), p, {"radius": A}, t)
    assert rel(s.sliding_torque, ref.sliding_torque_general(A, p, MU)) < TOL.TORSION_EXACT


@pytest.mark.parametrize("t", [0.999, 0.5, 1e-6])
def test_flat_punch_partial_slip(t):
    d = 1e-7
    c = cl.Contact(cl.profiles.FlatPunch(radius=A), materials(), friction=MU)
    s = c.torsion(depth=d, stick_radius=t * A)
    assert rel(s.twist, ref.flat_twist(t, E_STAR, d, A, MU, G_T)) < TOL.TORSION_EXACT
    p = lambda r: ref.pressure_flat(r, A, E_STAR, d)  # noqa: E731
    _, M_r = ref.torque_general(t * A, A, p, MU, G_T)
    assert rel(s.torque, M_r) < TOL.TORSION_EXACT
    assert rel(s.sliding_torque, np.pi / 2 * MU * E_STAR * A**2 * d) < TOL.CLOSED_FORM


def test_flat_punch_no_slip_until_onset():
    d = 1e-7
    c = cl.Contact(cl.profiles.FlatPunch(radius=A), materials(), friction=MU)
    phi0, M0 = (float(v) for v in ref.flat_onset(E_STAR, d, A, MU, G_T))
    s = c.torsion(depth=d, twist=[0.5 * phi0, phi0 * (1 - 1e-12), 1.5 * phi0])
    assert list(s.stick_radius[:2]) == [A, A]
    assert s.stick_radius[2] < A
    np.testing.assert_allclose(s.torque[:2], 16 / 3 * G_T * A**3 * s.twist[:2], rtol=TOL.CLOSED_FORM)
    assert rel(s.torque[1], M0) < TOL.NO_SLIP_LIMIT
    # torque control inside the no-slip range
    assert rel(c.torsion(depth=d, torque=0.5 * M0).twist, 0.5 * phi0) < TOL.CLOSED_FORM


def test_tabulated_profile_matches_analytic():
    r = np.linspace(0, 1.5 * A, 1000)
    tab = cl.Contact(cl.profiles.Tabulated(r, r**2 / (2 * R)), materials(), friction=MU)
    ana = cl.Contact(cl.profiles.Paraboloid(R=R), materials(), friction=MU)
    phi = np.array([0.05, 0.4, 2.0]) * PHI_SCALE
    st = tab.torsion(radius=A, twist=phi)
    sa = ana.torsion(radius=A, twist=phi)
    np.testing.assert_allclose(st.torque, sa.torque, rtol=TOL.TORSION_TABLE_1000)
    np.testing.assert_allclose(st.stick_radius[:2], sa.stick_radius[:2], rtol=TOL.TORSION_TABLE_1000)
    # deep slip (c/a ~ 3e-4): c depends exponentially on P, so δc/c ~ δP/P · P/(c dP/dc) ~ 5x
    assert rel(st.stick_radius[2], sa.stick_radius[2]) < 5 * TOL.TORSION_TABLE_1000


def test_large_table_composite_route_equals_split_route(monkeypatch):
    """The cached composite rule for big linear tables against the adaptive split-at-every-node
    route (a second method) on the same 120-point table, down to c/a = 1e-6."""
    from contactlab.physics import torsion_exact
    r = np.linspace(0, 1.2 * A, 120)
    f = r**2 / (2 * R) + 0.3 * r**3 / A**2 * 1e-4       # a non-trivial smooth measured shape
    prof = cl.profiles.Tabulated(r, f)
    c = cl.Contact(prof, materials(), friction=MU)
    t = np.array([0.95, 0.5, 1e-2, 1e-6])
    a_split = []
    for limit in (10**6, 0):
        monkeypatch.setattr(torsion_exact, "_TABLE_SPLIT_MAX", limit)
        s = c.torsion(radius=A, stick_radius=t * A)
        a_split.append((s.twist, s.torque))
    np.testing.assert_allclose(a_split[1][0], a_split[0][0], rtol=TOL.TORSION_EXACT)
    np.testing.assert_allclose(a_split[1][1], a_split[0][1], rtol=TOL.TORSION_EXACT)


def test_cubic_table_composite_route_equals_adaptive_route(monkeypatch):
    """Cubic tables take the cached composite rule too (their g has only (t - r_j)^(5/2) kinks at
    the nodes): against the adaptive route over the whole interval (no split, the route cubic
    tables took before) on a 1000-point spline of a non-polynomial shape, down to c/a = 1e-6."""
    from contactlab.physics import torsion_exact
    r = np.linspace(0, 1.5 * A, 1000)
    f = R - np.sqrt(R**2 - r**2) + 0.3 * r**3 / A**2 * 1e-4
    c = cl.Contact(cl.profiles.Tabulated(r, f, "cubic"), materials(), friction=MU)
    t = np.array([0.95, 0.5, 1e-2, 1e-6])
    phi = np.array([0.05, 0.4, 2.0]) * PHI_SCALE
    out = []
    for limit in (10**6, 0):
        monkeypatch.setattr(torsion_exact, "_TABLE_SPLIT_MAX", limit)
        s = c.torsion(radius=A, stick_radius=t * A)
        w = c.torsion(radius=A, twist=phi)
        out.append((s.twist, s.torque, w.torque, w.stick_radius))
    for new, old in zip(out[1], out[0]):
        np.testing.assert_allclose(new, old, rtol=TOL.TORSION_EXACT)


def test_cubic_table_of_paraboloid_matches_paraboloid():
    """A not-a-knot cubic spline reproduces a parabola, so the composite route on a 1000-point
    cubic table must give the paraboloid's exact torque-twist curve (whose g = x²/R comes from
    its power term: an independent route)."""
    r = np.linspace(0, 1.5 * A, 1000)
    tab = cl.Contact(cl.profiles.Tabulated(r, r**2 / (2 * R), "cubic"), materials(), friction=MU)
    ana = cl.Contact(cl.profiles.Paraboloid(R=R), materials(), friction=MU)
    phi = np.array([0.05, 0.4, 2.0]) * PHI_SCALE
    st = tab.torsion(radius=A, twist=phi)
    sa = ana.torsion(radius=A, twist=phi)
    np.testing.assert_allclose(st.torque, sa.torque, rtol=TOL.TORSION_EXACT)
    np.testing.assert_allclose(st.stick_radius, sa.stick_radius, rtol=TOL.TORSION_EXACT)


def test_truncated_cone_equals_two_segment_table():
    """A slope jump (log-singular pressure at r = b): the closed-form transform of TruncatedCone and
    the arcsine-sum transform of a two-segment linear table are two routes to the same g."""
    b, s_ = 0.4 * A, 0.05
    tc = cl.Contact(cl.profiles.TruncatedCone(radius=b, slope=s_), materials(), friction=MU)
    rr = np.array([0.0, b, 2 * A])
    tab = cl.Contact(cl.profiles.Tabulated(rr, np.maximum(rr - b, 0) * s_), materials(), friction=MU)
    t = np.array([0.9, 0.5, 0.3, 1e-3])
    s1 = tc.torsion(radius=A, stick_radius=t * A)
    s2 = tab.torsion(radius=A, stick_radius=t * A)
    np.testing.assert_allclose(s1.twist, s2.twist, rtol=TOL.TORSION_EXACT)
    np.testing.assert_allclose(s1.torque, s2.torque, rtol=TOL.TORSION_EXACT)
    # full sliding: 2πμ ∫ p r² dr with the core's pressure (an independent route)
    from scipy.integrate import quad
    n = tc.normal(radius=A)
    Mf = 2 * np.pi * MU * (quad(lambda r: n.pressure(r) * r**2, 0, b, epsrel=1e-12, limit=200)[0]
                           + quad(lambda r: n.pressure(r) * r**2, b, A, epsrel=1e-12, limit=200)[0])
    assert rel(s1.sliding_torque[0], Mf) < TOL.FIELD_INTEGRAL


# ---------------------------------------------------------------- MDR model (§6.4)
@pytest.mark.parametrize("t", RATIOS)
def test_mdr_reproduces_seed_eq52_hertz(hertz, t):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ValidityWarning)
        s = hertz.torsion(radius=A, stick_radius=t * A, method="mdr")
    phi_hat, M_hat = ref.hertz_mdr_hat(t)
    assert rel(s.twist / PHI_SCALE, phi_hat) < TOL.TORSION_EXACT
    assert rel(s.torque / M_SCALE, M_hat) < TOL.TORSION_EXACT
    assert rel(s.twist / PHI_SCALE, TABLE_63[t][2]) < TOL.TABLE_6_DIGITS
    assert rel(s.torque / M_SCALE, TABLE_63[t][3]) < TOL.TABLE_6_DIGITS
    # eq. 52 itself: 8 G_t φ c = 2μ E* (g(a) - g(c)) with g = x²/R
    assert rel(8 * G_T * s.twist * t * A, 2 * MU * E_STAR * (A**2 - (t * A) ** 2) / R) < TOL.CLOSED_FORM


def test_mdr_converges_to_exact_with_second_order(hertz):
    """Relative torque error at equal twist → 0 as c/a → 1, like (1 - c/a)² (theory §6.4)."""
    t = 1 - np.array([1e-2, 5e-3, 2.5e-3, 1.25e-3])
    ex = hertz.torsion(radius=A, stick_radius=t * A)
    md = hertz.torsion(radius=A, twist=ex.twist, method="mdr")
    err = md.torque / ex.torque - 1
    assert np.all(err > 0)
    slope = np.polyfit(np.log(1 - t), np.log(err), 1)[0]
    assert abs(slope - 2.0) < 0.05
    # theory §6.4 table: 2.5e-5 at c/a = 0.99 (same φ), 0.27 % at 0.9
    md2 = hertz.torsion(radius=A, stick_radius=np.array([0.99, 0.9]) * A, method="mdr")
    ex2 = hertz.torsion(radius=A, twist=md2.twist)
    np.testing.assert_allclose(md2.torque / ex2.torque, [1.000025, 1.00272], atol=TOL.TABLE_6_DIGITS)  # 6 digits


def test_mdr_full_slip_torque_is_4_over_pi_of_exact(hertz):
    """Known gap of the MDR model: +27.3 % at full sliding, for every profile."""
    for prof, load in ((cl.profiles.Paraboloid(R=R), {"radius": A}),
                       (cl.profiles.Cone(slope=0.05), {"radius": A}),
                       (cl.profiles.FlatPunch(radius=A), {"depth": 1e-7})):
        c = cl.Contact(prof, materials(), friction=MU)
        with pytest.warns(ValidityWarning, match="MDR"):
            md = c.torsion(**load, stick_radius=0.0, method="mdr")
        ex = c.torsion(**load, stick_radius=0.0)
        assert rel(md.torque / ex.torque, 4 / np.pi) < TOL.TORSION_EXACT
    assert rel(md.torque / ex.torque - 1, 0.2732395447) < TOL.TORSION_EXACT


def test_mdr_validity_warning(hertz):
    """Warns once the exact stick radius at that twist drops below 0.83 a (1 % error, error map)."""
    phi_lim = float(ref.hertz_twist_hat(cl.effects.torsion.MDR_VALID_STICK_RATIO)) * PHI_SCALE
    with pytest.warns(ValidityWarning, match="c/a=0.83"):
        hertz.torsion(radius=A, twist=1.001 * phi_lim, method="mdr")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        hertz.torsion(radius=A, twist=0.999 * phi_lim, method="mdr")
        hertz.torsion(radius=A, stick_radius=0.95 * A, method="mdr")
    # the criterion is conservative: at the limit the MDR error is just below 1 %
    md = hertz.torsion(radius=A, twist=phi_lim * 0.999, method="mdr")
    ex = hertz.torsion(radius=A, twist=phi_lim * 0.999)
    assert 0.005 < md.torque / ex.torque - 1 < 0.01


def test_mdr_error_helper_matches_table(hertz):
    from contactlab.effects.torsion import mdr_torque_error
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ValidityWarning)
        md = hertz.torsion(radius=A, stick_radius=np.array([0.7, 0.5, 0.3]) * A, method="mdr")
    a = np.full(3, A)
    d = np.full(3, A**2 / R)
    err = mdr_torque_error(hertz, md.twist, md.torque, a, d, d)
    np.testing.assert_allclose(1 + err, [1.02908, 1.09481, 1.19551], rtol=TOL.TABLE_6_DIGITS)
