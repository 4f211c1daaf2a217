"""Normal and torsion solves at the edges of the float range (adversarial campaign, issue 26).

Every expected value is a closed form or a 40-digit evaluation (mpmath), never our output:

* ``PowerLaw(c=1e294, n=100)``: ``d = κ_n c a^n`` and ``F = 2E* n/(n+1) a d`` underflowed in
  ``a^n`` alone (depth and force 0 at ``radius=5e-4``);
* forces of 1e-100 and 1e-200 N and depths of 1e-200 m: the Newton solve ran out of steps from a
  bracket tens of orders above the root, and the array route returned radius 0 silently; at such
  loads every smooth profile is its leading term (Hertz, cone);
* a truncated paraboloid at 1e-30 N (contact radius within rounding of the rim) was called an
  overflow: ``F/(2E*) = (b² s + 2s³/3)/R`` with ``s² = a² - b²``, ``d = a s/R``;
* torsion of truncated paraboloids and linear tables raised ConvergenceError in ~7 % of fuzzed
  cases (the quadratures of ``∫ x g``, of the stick-zone traction across the rim, and of the
  pressure just outside the rim).
"""
import math

import mpmath as mp
import numpy as np
import pytest

import contactlab as cl
from tests.tolerances import CLOSED_FORM, EXTREME_SCALE

STEEL = cl.Elastic(E=210e9, nu=0.3)


def _contact(profile, **kw):
    return cl.Contact(profile, materials=(STEEL, STEEL), **kw)


def _kappa(n):
    n = mp.mpf(n)
    return mp.sqrt(mp.pi) * mp.gamma(n / 2 + 1) / mp.gamma(n / 2 + mp.mpf(1) / 2)


def test_power_law_with_huge_coefficient():
    con = _contact(cl.profiles.PowerLaw(c=1e294, n=100))
    E = con.moduli.normal
    with mp.workdps(40):
        a = mp.mpf(5e-4)
        d = _kappa(100) * mp.mpf(1e294) * a**100
        F = 2 * mp.mpf(E) * mp.mpf(100) / 101 * a * d
        d, F = float(d), float(F)
    for st in (con.normal(radius=5e-4), con.normal(radius=[5e-4, 4e-4])):
        assert np.ravel(st.depth)[0] == pytest.approx(d, rel=EXTREME_SCALE)
        assert np.ravel(st.force)[0] == pytest.approx(F, rel=EXTREME_SCALE)
    for key, val in (("depth", d), ("force", F)):
        assert con.normal(**{key: val}).radius == pytest.approx(5e-4, rel=EXTREME_SCALE)
        assert con.normal(**{key: [val, 1e-3 * val]}).radius[0] == pytest.approx(
            5e-4, rel=EXTREME_SCALE)


def _hertz_radius(F, R, E):
    return (3.0 * F * R / (4.0 * E)) ** (1.0 / 3.0)


@pytest.mark.parametrize("name", ["sphere", "polynomial", "sum"])
@pytest.mark.parametrize("F", [1e-100, 1e-200])
def test_tiny_forces(name, F):
    """At contact radii of 1e-38 m and below every profile is its leading term: Hertz with
    R = 0.01 m (sphere; polynomial 50 r² + 1000 r⁴), the cone 0.1 r (paraboloid + cone:
    F = (π/2) E* s a²); the next terms are 1e-70 relative and below."""
    prof = {"sphere": cl.profiles.Sphere(R=0.01),
            "polynomial": cl.profiles.Polynomial({2: 50.0, 4: 1e3}),
            "sum": cl.profiles.Paraboloid(R=0.01) + cl.profiles.Cone(slope=0.1)}[name]
    con = _contact(prof)
    E = con.moduli.normal
    want = (math.sqrt(2.0 * F / (math.pi * E * 0.1)) if name == "sum"
            else _hertz_radius(F, 0.01, E))
    assert con.normal(force=F).radius == pytest.approx(want, rel=EXTREME_SCALE)
    assert con.normal(force=[F, 1.0]).radius[0] == pytest.approx(want, rel=EXTREME_SCALE)


@pytest.mark.parametrize("d", [1e-200, 1e-300])
def test_tiny_depths_sphere(d):
    """a = sqrt(R d) to 1e-100 relative; the array route returned 0 (an unfinished bracket)."""
    con = _contact(cl.profiles.Sphere(R=0.01))
    want = math.sqrt(0.01 * d)
    assert con.normal(depth=d).radius == pytest.approx(want, rel=EXTREME_SCALE)
    assert con.normal(depth=[d, 1e-6]).radius[0] == pytest.approx(want, rel=EXTREME_SCALE)


def test_tiny_force_sphere_subnormal_targets_do_not_raise():
    """1e-300 N: F/(2E*) = 4e-312 is subnormal (11 digits left); the radius keeps ~10."""
    con = _contact(cl.profiles.Sphere(R=0.01))
    want = _hertz_radius(1e-300, 0.01, con.moduli.normal)
    assert con.normal(force=1e-300).radius == pytest.approx(want, rel=1e-9)
    assert con.normal(force=[1e-300, 1.0]).radius[0] == pytest.approx(want, rel=1e-9)


def _truncated_reference(F, b, R, E):
    """(radius, depth) of the truncated paraboloid at force F, 40 digits."""
    with mp.workdps(40):
        b, R, fr = mp.mpf(b), mp.mpf(R), mp.mpf(F) / (2 * mp.mpf(E))
        s = mp.findroot(lambda s: (b * b * s + 2 * s**3 / 3) / R - fr, R * fr / (b * b))
        a = mp.sqrt(b * b + s * s)
        return float(a), float(a * s / R)


@pytest.mark.parametrize("F", [1e-100, 1e-30, 1e-10, 1.0, 100.0])
def test_truncated_paraboloid_force_next_to_the_rim(F):
    b, R = 1e-4, 0.01
    con = _contact(cl.profiles.TruncatedParaboloid(radius=b, R=R))
    a_ref, d_ref = _truncated_reference(F, b, R, con.moduli.normal)
    for st in (con.normal(force=F), con.normal(force=[F, 2.0])):
        assert np.ravel(st.radius)[0] == pytest.approx(a_ref, rel=CLOSED_FORM)
        assert np.ravel(st.depth)[0] == pytest.approx(d_ref, rel=EXTREME_SCALE)
        assert np.ravel(st.force)[0] == pytest.approx(F, rel=EXTREME_SCALE)


def test_truncated_paraboloid_x_g_integral():
    """∫_b^a x² sqrt(x² - b²)/R dx, next to the rim and far from it, against mpmath."""
    b, R = 3e-4, 5e-3
    p = cl.profiles.TruncatedParaboloid(radius=b, R=R)
    a = np.array([b * (1 + 1e-12), b * (1 + 1e-4), 3.3e-4, 1e-3, 1e-2])
    got = p._xg_integral_closed_form(a)
    with mp.workdps(40):
        bm, Rm = mp.mpf(b), mp.mpf(R)
        ref = [float(mp.quad(lambda x: x * x * mp.sqrt(x * x - bm * bm) / Rm, [bm, mp.mpf(v)]))
               for v in a]
    np.testing.assert_allclose(got, ref, rtol=EXTREME_SCALE, atol=0)


def test_truncated_paraboloid_pressure_shape_at_the_rim():
    """S(r, a) = ∫_r^a g'(x)/sqrt(x² - r²) dx on both sides of the rim, against mpmath (the
    quadrature in x failed for most radii in a thin annulus outside the rim)."""
    b, R, a = 3e-4, 5e-3, 3.5e-4
    p = cl.profiles.TruncatedParaboloid(radius=b, R=R)
    r = np.array([0.0, 1e-4, 2.9e-4, 3.1e-4, 3.4e-4])
    got, _ = p._pressure_shape_semi_analytic(r, np.full(r.shape, a), 1e-12)
    with mp.workdps(30):
        bm, Rm, am = mp.mpf(b), mp.mpf(R), mp.mpf(a)

        def S(rv):
            rm = mp.mpf(rv)
            lo = max(bm, rm)
            return mp.quad(lambda x: (2 * x * x - bm * bm) / (Rm * mp.sqrt(x * x - bm * bm)
                                                               * mp.sqrt(x * x - rm * rm)),
                           [lo, (lo + am) / 2, am])
        ref = [float(S(v)) for v in r]
    np.testing.assert_allclose(got, ref, rtol=EXTREME_SCALE, atol=0)
    # a radius within 1e-9 of the rim: the pressure exists (it failed to converge before)
    con = _contact(cl.profiles.TruncatedParaboloid(radius=7.339234737959978e-4,
                                                   R=0.012793205355110289))
    ns = con.normal(force=0.37995324032651123)
    rb = 7.339234737959978e-4 + (ns.radius - 7.339234737959978e-4) * np.array([0.3, 0.7])
    assert np.all(np.isfinite(ns.pressure(rb))) and np.all(ns.pressure(rb) > 0)


@pytest.mark.parametrize("b,R,mu,F,phi", [
    (0.00024971723791065477, 0.0726367327716171, 0.6732416485032553, 5.5800931923713195,
     0.0003110273405649995),
    (3.0492542773705147e-05, 0.004366091834718815, 0.16047353934029426, 0.2012470557116576,
     0.00014030252573260307),
])
def test_torsion_shear_of_truncated_paraboloid(b, R, mu, F, phi):
    """Fuzzed cases that raised ConvergenceError: the traction field now integrates to the
    torque, M = 2π ∫_0^a τ r² dr (QUADPACK, split at the stick radius and the rim)."""
    from scipy.integrate import quad
    con = _contact(cl.profiles.TruncatedParaboloid(radius=b, R=R), friction=mu)
    st = con.torsion(force=F, twist=phi, method="exact")
    a, c = st.normal.radius, st.stick_radius
    edges = sorted({0.0, min(c, a), b, a})
    M = sum(2 * np.pi * quad(lambda r: float(st.shear(r)) * r * r, lo, hi, epsrel=1e-11,
                             epsabs=0, limit=200)[0]
            for lo, hi in zip(edges[:-1], edges[1:]) if hi > lo)
    assert M == pytest.approx(st.torque, rel=EXTREME_SCALE)


def test_torsion_fields_fuzz_tables_and_truncated():
    """A seeded fuzz over truncated paraboloids and linear tables (forces, twists, radii): no
    ConvergenceError (7 % of such cases raised), and the slip-zone traction within the Coulomb
    bound |τ| <= μ p of the normal pressure."""
    rng = np.random.default_rng(26)
    for i in range(24):
        if i % 2:
            prof = cl.profiles.TruncatedParaboloid(radius=10 ** rng.uniform(-5, -2),
                                                   R=10 ** rng.uniform(-3, 0))
        else:
            m = int(rng.integers(3, 9))
            r = np.sort(np.concatenate([[0.0], 10 ** rng.uniform(-5, -2, m)]))
            f = np.cumsum(np.concatenate([[0.0], np.sort(rng.uniform(1e-3, 1.0, m))
                                          * np.diff(r)]))
            prof = cl.profiles.Tabulated(r, f)
        mu = rng.uniform(0.1, 0.8)
        con = _contact(prof, friction=mu)
        F = 10 ** rng.uniform(-4, 3)
        st = con.torsion(force=F, twist=10 ** rng.uniform(-8, -1), method="exact")
        a = st.normal.radius
        radii = a * np.sort(rng.uniform(0.0, 0.999, 6))
        tau = np.abs(st.shear(radii))
        p = st.normal.pressure(radii)
        assert np.all(np.isfinite(tau))
        assert np.all(tau <= mu * p * (1 + 1e-9) + 1e-12 * np.max(mu * p))
