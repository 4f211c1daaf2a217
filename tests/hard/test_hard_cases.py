"""Hard cases of normal contact that must stay numerically stable (issue 7).

Every expected value is independent of contactlab: closed forms from docs/theory re-implemented in
``_reference.py`` (mpmath, 30 digits), or the definition of the transform integrated by scipy.
"""
from __future__ import annotations

from typing import ClassVar

import numpy as np
import pytest

import contactlab as cl
from contactlab.errors import ParameterError
from contactlab.profiles import (Cone, FlatPunch, Paraboloid, PowerLaw, Profile, Tabulated,
                                 TruncatedParaboloid)
from tests import tolerances as TOL
from tests.reference import power_law as ref
from tests.reference import tabulated as tab
from tests.reference.kappa import kappa
from tests.tolerances import (HARD_CLOSED, HARD_PRESSURE, QUADRATURE, ROUNDED_PUNCH_FACTOR,
                              TABLE_EXACT, TABLE_QUAD)

E_BODY, NU_BODY = 70e9, 0.3
E_STAR = E_BODY / (1 - NU_BODY**2)          # one elastic body on a rigid one


def contact(profile: Profile, **kw) -> cl.Contact:
    return cl.Contact(profile, materials=(cl.Elastic(E=E_BODY, nu=NU_BODY), cl.Rigid()), **kw)


def assert_finite(*arrays) -> None:
    for v in arrays:
        assert np.all(np.isfinite(v)), v


def rel(a, b):
    return np.abs(np.asarray(a, float) / np.asarray(b, float) - 1.0)


class QuadratureOnly(Profile):
    """Test double: exposes only f and f' of another profile, so g goes by quadrature."""

    name: ClassVar[str] = "quadrature_only_test"
    params: ClassVar[tuple] = ()

    def __init__(self, base: Profile) -> None:
        self.base = base

    def _param_values(self):
        return (self.base,)

    def _height(self, r):
        return self.base._height(r)

    def _slope(self, r):
        return self.base._slope_any(r)


# ---------------------------------------------------------------- flat punch
class TestFlatPunch:
    b, d = 1e-3, 1e-6

    def test_edge_singularity_coefficient(self):
        """p sqrt(a²-r²) = E* d/π exactly, down to 1e-14 of the radius from the edge."""
        s = contact(FlatPunch(self.b)).normal(depth=self.d)
        r = self.b * (1 - np.logspace(-1, -14, 14))
        p = s.pressure(r)
        assert_finite(p)
        coef = p * np.sqrt((self.b - r) * (self.b + r))
        np.testing.assert_allclose(coef, E_STAR * self.d / np.pi, rtol=HARD_CLOSED)

    def test_pressure_infinite_exactly_at_the_edge(self):
        """The documented singular point: r = a gives +inf, beyond it 0."""
        s = contact(FlatPunch(self.b)).normal(depth=self.d)
        p = s.pressure(np.array([self.b, 1.5 * self.b]))
        assert p[0] == np.inf and p[1] == 0.0

    def test_force_and_error_estimate(self):
        s = contact(FlatPunch(self.b)).normal(depth=self.d)
        assert rel(s.force, 2 * E_STAR * self.b * self.d) <= HARD_CLOSED
        assert 0 <= s.error_estimate <= 1e-12
        s2 = contact(FlatPunch(self.b)).normal(force=s.force)
        assert rel(s2.depth, self.d) <= HARD_CLOSED and s2.radius == self.b


class TestRoundedPunch:
    """TruncatedParaboloid whose rounded zone b..b(1+eps) is tiny converges to the flat punch."""

    b, d = 1e-3, 1e-6

    def profile(self, eps: float) -> TruncatedParaboloid:
        a = self.b * (1 + eps)
        # choose R so that the contact edge sits at a = b(1+eps): d = a sqrt(a²-b²)/R
        return TruncatedParaboloid(self.b, R=a * np.sqrt((a - self.b) * (a + self.b)) / self.d)

    @pytest.mark.parametrize("eps", [1e-2, 1e-4, 1e-6])
    def test_closed_form(self, eps):
        prof = self.profile(eps)
        s = contact(prof).normal(depth=self.d)
        a = self.b * (1 + eps)
        # theory §3: F = 2E*[a d - (a²-b²)^{3/2}/(3R)]
        F = 2 * E_STAR * (a * self.d - ((a - self.b) * (a + self.b)) ** 1.5 / (3 * prof.R))
        assert rel(s.radius, a) <= HARD_CLOSED
        assert rel(s.force, F) <= HARD_CLOSED
        s2 = contact(prof).normal(force=F)
        assert rel(s2.radius, a) <= HARD_CLOSED
        # d(a) = a sqrt(a²-b²)/R is ill-conditioned near b (condition ~ 1/(2 eps)): the depth
        # under force control is only as good as the rounding of a allows, and the state says so
        assert rel(s2.depth, self.d) <= s2.error_estimates["depth"] <= 1e-9

    @pytest.mark.parametrize("eps", [1e-2, 1e-4, 1e-6])
    def test_converges_to_flat_punch(self, eps):
        s = contact(self.profile(eps)).normal(depth=self.d)
        F_flat = 2 * E_STAR * self.b * self.d
        assert rel(s.force, F_flat) <= ROUNDED_PUNCH_FACTOR * eps
        r = self.b * np.array([0.0, 0.3, 0.6, 0.9])
        p = s.pressure(r)
        assert_finite(p)
        p_flat = E_STAR * self.d / (np.pi * np.sqrt(self.b**2 - r**2))
        # the rounded zone changes p by O(eps / (1 - r²/b²)) away from the edge
        assert np.all(rel(p, p_flat) <= ROUNDED_PUNCH_FACTOR * eps / (1 - (r / self.b) ** 2))


# ---------------------------------------------------------------- cones
class TestCone:
    @pytest.mark.parametrize("slope", [1e-4, 1.0, 1e2])
    def test_closed_forms(self, slope):
        a = 1e-4
        c = contact(Cone(slope))
        s = c.normal(radius=a)
        assert rel(s.force, 0.5 * np.pi * E_STAR * a * a * slope) <= HARD_CLOSED
        assert rel(s.depth, 0.5 * np.pi * a * slope) <= HARD_CLOSED
        s_F = c.normal(force=s.force)
        assert rel(s_F.radius, a) <= HARD_CLOSED
        # pressure: log singularity, including r = 1e-12 a
        r = a * np.array([1e-12, 1e-6, 0.1, 0.5, 0.999999])
        p = s.pressure(r)
        assert_finite(p)
        np.testing.assert_allclose(p, 0.5 * E_STAR * slope * np.arccosh(a / r), rtol=HARD_CLOSED)
        assert s.pressure(0.0) == np.inf          # documented singular point
        ro = a * np.array([1 + 1e-9, 1.001, 2.0, 100.0, 1e6])
        u = s.displacement(ro)
        expected = [ref.cone_displacement_outside(slope, a, x) for x in ro]
        np.testing.assert_allclose(u, expected, rtol=HARD_CLOSED)


# ---------------------------------------------------------------- power laws
N_VALUES = [0.3, 0.5, 0.7, 0.99, 1.01, 1.5, 3.0, 4.0, 8.0, 20.0, 50.0]


@pytest.mark.parametrize("n", N_VALUES)
def test_power_law_force_radius_depth(n):
    c_coef, a = 2.0, 0.5
    c = contact(PowerLaw(c_coef, n))
    F = ref.power_force(E_STAR, c_coef, n, a)
    d = ref.power_depth(c_coef, n, a)
    for s in (c.normal(radius=a), c.normal(depth=d), c.normal(force=F)):
        assert rel(s.force, F) <= HARD_CLOSED
        assert rel(s.radius, a) <= HARD_CLOSED
        assert rel(s.depth, d) <= HARD_CLOSED
        assert rel(s.stiffness, 2 * E_STAR * a) <= HARD_CLOSED


@pytest.mark.parametrize("n", N_VALUES)
def test_power_law_pressure(n):
    c_coef, a = 2.0, 0.5
    s = contact(PowerLaw(c_coef, n)).normal(radius=a)
    rho = np.array([1e-9, 1e-3, 0.2, 0.6, 0.8, 0.99, 0.999999])
    p = s.pressure(rho * a)
    assert_finite(p)
    expected = [ref.power_pressure(E_STAR, c_coef, n, a, x) for x in rho * a]
    np.testing.assert_allclose(p, expected, rtol=HARD_PRESSURE)
    centre = s.pressure(0.0)
    if n <= 1:
        assert centre == np.inf                  # documented singular point
    else:                                        # S(0,a) = n κ c a^{n-1}/(n-1)
        expected0 = float(E_STAR / np.pi * n * kappa(n) * c_coef * a ** (n - 1) / (n - 1))
        assert rel(centre, expected0) <= HARD_CLOSED


@pytest.mark.parametrize("n", N_VALUES)
def test_power_law_displacement_outside(n):
    c_coef, a = 2.0, 0.5
    s = contact(PowerLaw(c_coef, n)).normal(radius=a)
    r = a * np.array([1 + 1e-6, 1.01, 1.5, 4.0, 100.0])
    u = s.displacement(r)
    assert_finite(u)
    expected = [ref.power_displacement_outside(c_coef, n, a, s.depth, x) for x in r]
    # the far field is a difference of two O(d) terms: judge against d
    np.testing.assert_allclose(u, expected, rtol=0, atol=HARD_PRESSURE * s.depth)


def test_strong_slope_singularity_quadrature_route_is_accurate_and_honest():
    """f' ~ r^-0.7 (n = 0.3) on the generic route: the tanh-sinh nodes reach within 1e-61 of
    the ends (_T_MAX = 4.5), so the integrable end singularity is resolved to rtol; at every rtol
    the estimate covers the actual error."""
    for rtol in (1e-10, 1e-5):
        s = contact(QuadratureOnly(PowerLaw(2.0, 0.3)), rtol=rtol).normal(radius=0.5)
        err = rel(s.force, ref.power_force(E_STAR, 2.0, 0.3, 0.5))
        assert err <= s.error_estimate <= rtol


@pytest.mark.parametrize("n", [0.7, 1.0, 4.0, 20.0])
def test_power_law_quadrature_route(n):
    """The generic quadrature route (only f given) at hard exponents, against the closed form."""
    c_coef, a = 2.0, 0.5
    s = contact(QuadratureOnly(PowerLaw(c_coef, n))).normal(radius=a)
    assert s.meta["routes"]["g"] == "quadrature"
    assert rel(s.force, ref.power_force(E_STAR, c_coef, n, a)) <= QUADRATURE
    assert rel(s.depth, ref.power_depth(c_coef, n, a)) <= QUADRATURE
    assert s.error_estimate <= 1e-9
    rho = np.array([0.1, 0.5, 0.9])
    p, err = s.pressure(rho * a, return_error=True)
    expected = np.array([ref.power_pressure(E_STAR, c_coef, n, a, x) for x in rho * a])
    np.testing.assert_allclose(p, expected, rtol=QUADRATURE)
    assert np.all(np.abs(p - expected) <= err)


# ---------------------------------------------------------------- scales and materials
@pytest.mark.parametrize("R, E, F", [(1e-9, 1e12, 1e-12), (10.0, 1e3, 1e-3)])
def test_extreme_scales_incompressible(R, E, F):
    """R = 1 nm on 1 TPa and R = 10 m on 1 kPa, ν = 0.5 (E* = 4E/3): Hertz closed forms."""
    s = cl.Contact(Paraboloid(R), materials=(cl.Elastic(E=E, nu=0.5), cl.Rigid())).normal(force=F)
    Es = 4 * E / 3
    a = (3 * F * R / (4 * Es)) ** (1 / 3)
    assert rel(s.radius, a) <= HARD_CLOSED
    assert rel(s.depth, a * a / R) <= HARD_CLOSED
    assert rel(s.pressure(0.0), 2 * Es * a / (np.pi * R)) <= HARD_CLOSED
    assert rel(s.elastic_energy, 0.4 * F * a * a / R) <= HARD_CLOSED   # ∫F dd = (2/5) F d
    assert_finite(s.force, s.error_estimate, *s.error_estimates.values())


def test_one_rigid_body_either_order():
    m = cl.Elastic(E=E_BODY, nu=NU_BODY)
    s1 = cl.Contact(Paraboloid(0.01), materials=(m, cl.Rigid())).normal(depth=1e-6)
    s2 = cl.Contact(Paraboloid(0.01), materials=(cl.Rigid(), m)).normal(depth=1e-6)
    a = np.sqrt(0.01 * 1e-6)
    assert rel(s1.force, 4 * E_STAR * a**3 / (3 * 0.01)) <= HARD_CLOSED
    assert s1.force == s2.force


def test_two_rigid_bodies_rejected():
    with pytest.raises(ParameterError, match="materials"):
        cl.Contact(Paraboloid(0.01), materials=(cl.Rigid(), cl.Rigid()))


def test_very_dissimilar_moduli():
    """E ratio 1e6: E* from theory §1, Hertz force, no loss of the soft body's term."""
    hard, soft = cl.Elastic(E=1e12, nu=0.2), cl.Elastic(E=1e6, nu=0.45)
    Es = 1.0 / ((1 - 0.2**2) / 1e12 + (1 - 0.45**2) / 1e6)
    c = cl.Contact(Paraboloid(0.01), materials=(hard, soft))
    assert rel(c.moduli.normal, Es) <= HARD_CLOSED
    s = c.normal(force=1e-3)
    assert rel(s.radius, (3 * 1e-3 * 0.01 / (4 * Es)) ** (1 / 3)) <= HARD_CLOSED


# ---------------------------------------------------------------- tabulated profiles
R_TAB = 0.01


def _tables():
    rng = np.random.default_rng(7)
    r10 = np.linspace(0, 1e-3, 10)
    r_nonuni = 1e-3 * np.sort(np.concatenate([[0.0, 1.0], rng.uniform(0, 1, 60)])) ** 0.5
    r_off = np.linspace(2e-4, 1e-3, 40)
    r_noisy = np.linspace(0, 1e-3, 200)
    # measured-like noise, small enough that g stays non-decreasing (see the test below for
    # noise that makes it decrease)
    f_noisy = r_noisy**2 / (2 * R_TAB) * (1 + 1e-6 * rng.standard_normal(r_noisy.size))
    return {
        "10 points": (r10, r10**2 / (2 * R_TAB)),
        "non-uniform": (r_nonuni, r_nonuni**2 / (2 * R_TAB)),
        "offset start": (r_off, 5e-6 + r_off**2 / (2 * R_TAB)),
        "noisy": (r_noisy, f_noisy),
    }


@pytest.mark.parametrize("name", list(_tables()))
def test_tabulated_exact_transform(name):
    r, f = _tables()[name]
    prof = Tabulated(r, f)
    # the reference table as the profile defines it: heights relative to the first value,
    # flat extension to the axis when r[0] > 0
    r_ref = r if r[0] == 0 else np.concatenate([[0.0], r])
    f_ref = f - f[0] if r[0] == 0 else np.concatenate([[0.0], f - f[0]])
    x = np.concatenate([np.array([0.05, 0.3, 0.55, 0.77, 0.999]) * r[-1], r[[1, 3, -2]]])
    g = prof.g(x)          # (the last three sit exactly on nodes)
    g_quad = np.array([tab.table_g_quad(r_ref, f_ref, xi) for xi in x])
    np.testing.assert_allclose(g, g_quad, rtol=TABLE_QUAD, atol=TOL.ABS_ZERO)
    np.testing.assert_allclose(g, tab.table_g_sum(r_ref, f_ref, x), rtol=TABLE_EXACT, atol=TOL.ABS_ZERO)
    a = 0.8123 * r[-1]
    c = contact(prof)
    s = c.normal(radius=a)
    gi = tab.table_g_integral_quad(r_ref, f_ref, a)
    d = tab.table_g_sum(r_ref, f_ref, np.array([a]))[0]
    assert rel(s.force, 2 * E_STAR * (a * d - gi)) <= TABLE_QUAD
    s_d = c.normal(depth=d)
    assert rel(s_d.radius, a) <= TABLE_QUAD
    rr = np.linspace(0, a, 50, endpoint=False)[1:] * (1 + 1e-7)     # off the nodes
    p = s.pressure(rr)
    assert_finite(p, s_d.force, s_d.error_estimate)
    assert np.all(p >= 0)
    # the pressure integrates to the force (theory §3: F = 2π ∫ p r dr); the integrand has
    # log singularities at the nodes, so this is a coarse consistency check only
    u = s.displacement(np.array([0.5 * a, 1.5 * a, 10 * a]))
    assert_finite(u)
    assert rel(u[0], s.depth - np.interp(0.5 * a, r_ref, f_ref)) <= TABLE_QUAD


def test_noisy_table_with_decreasing_g_is_outside_theory():
    """Monotone but noisy heights: the slope drops at some nodes, so g decreases there (a monotone
    f does not imply a monotone g) and deep contacts are ring contacts: OutsideTheoryError, with
    the depth where it happens, never a silent wrong radius."""
    from contactlab.errors import OutsideTheoryError
    rng = np.random.default_rng(3)
    r = np.linspace(0, 1e-3, 200)
    f = np.maximum.accumulate(r**2 / (2 * R_TAB) * (1 + 1e-2 * rng.standard_normal(r.size)))
    prof = Tabulated(r, f)
    g = tab.table_g_sum(r, f - f[0], r[1:])
    assert np.any(np.diff(g) < 0)             # the independent transform does decrease
    with pytest.raises(OutsideTheoryError, match="annulus"):
        contact(prof).normal(depth=0.999 * float(g[-1]))


def test_tabulated_million_points():
    """10^6 points: exact transform against the independent sum, and Hertz within Δr²."""
    r = np.linspace(0, 1e-3, 10**6)
    f = r**2 / (2 * R_TAB)
    prof = Tabulated(r, f)
    x = np.array([1e-4, 5e-4, 9e-4])
    np.testing.assert_allclose(prof.g(x), tab.table_g_sum(r, f, x), rtol=TABLE_EXACT)
    a = 5e-4
    s = contact(prof).normal(depth=a * a / R_TAB)
    # the linear interpolant of r²/2R lies above it by ≤ Δr²/(8R): the radius is smaller
    # by a relative O((Δr/a)²)
    # plus the table's own rounding: heights carry eps·f, slopes eps·f/Δr, amplified by a/Δr
    dr = r[1]
    bound = (dr / a) ** 1.5 + 4 * np.finfo(float).eps * a / dr
    assert rel(s.radius, a) <= bound
    assert rel(s.force, 4 * E_STAR * a**3 / (3 * R_TAB)) <= 3 * bound


@pytest.mark.parametrize("interpolation", ["linear", "cubic"])
def test_tabulated_converges_to_analytic(interpolation):
    """A sampled exact sphere converges to the theory's sphere force as the table is refined.

    The linear interpolant's slope error makes g converge like (Δr/a)^{3/2} (the 1/sqrt weight
    of the transform near x = r); the spline converges much faster. Bounds, not fitted orders:
    the linear error changes sign with the position of a between nodes.
    """
    R, a = 0.01, 5.0615e-4
    F = E_STAR * ((a * a + R * R) / 2 * np.log((R + a) / (R - a)) - a * R)
    for N in (21, 81, 321):
        r = np.linspace(0, 1e-3, N)
        s = contact(Tabulated(r, R - np.sqrt(R * R - r * r), interpolation)).normal(radius=a)
        h = r[1] / a
        assert rel(s.force, F) <= (h**1.5 if interpolation == "linear" else h**4), N


# ---------------------------------------------------------------- accuracy switch
def test_rtol_is_threaded_and_estimate_is_honest():
    """A quadrature-route paraboloid at a ladder of rtol: error <= estimate, cost falls."""
    R, a = 0.01, 1e-4
    F = 4 * E_STAR * a**3 / (3 * R)
    for rtol in (1e-3, 1e-6, 1e-9, 1e-12):
        s = contact(QuadratureOnly(Paraboloid(R)), rtol=rtol).normal(depth=a * a / R)
        err = rel(s.force, F)
        assert err <= max(s.error_estimate, 1e-15), (rtol, err, s.error_estimate)
        assert err <= 10 * rtol
        assert rel(s.radius, a) <= max(s.error_estimates["radius"], 1e-15)


def test_default_rtol_unchanged():
    c = contact(Paraboloid(0.01))
    assert c.rtol == 1e-10 == c.profile.rtol


@pytest.mark.parametrize("bad", [0.0, -1e-6, 1.0, 2.0])
def test_rtol_validation(bad):
    with pytest.raises(ParameterError, match="rtol"):
        contact(Paraboloid(0.01), rtol=bad)


def test_tabulated_pressure_and_displacement_against_quad():
    """The truncated-cone sums for p and u_z of a 10-point table against scipy quad of the
    definitions built on the independent g (theory §3)."""
    r = np.linspace(0, 1e-3, 10)
    f = r**2 / (2 * R_TAB) + 1e-2 * r**3
    a = 0.777e-3
    s = contact(Tabulated(r, f)).normal(radius=a)
    for rr in (0.0123e-3, 0.3e-3 * 1.0001, 0.7e-3):
        expected = E_STAR / np.pi * tab.table_pressure_shape_quad(r, f, rr, a)
        assert rel(s.pressure(rr), expected) <= TABLE_QUAD
    for ro in (0.8e-3, 2e-3, 1e-2):
        expected = 2 / np.pi * s.depth * np.arcsin(a / ro) - tab.table_abel_outside_quad(r, f, ro, a)
        assert rel(s.displacement(ro), expected) <= TABLE_QUAD


@pytest.mark.parametrize("e", [-0.3, -0.5, -0.7, -0.9])
@pytest.mark.parametrize("rtol", [1e-3, 1e-8])
def test_quadrature_endpoint_singularity_is_honest_or_loud(e, rtol):
    """∫_0^1 x^e dx = 1/(1+e): the estimate (with the truncated-tail bound) covers the actual
    error, or the quadrature raises."""
    from contactlab.errors import ConvergenceError
    from contactlab.numeric.quadrature import tanh_sinh
    try:
        res = tanh_sinh(lambda x, i: x**e, 0.0, 1.0, rtol=rtol)
    except ConvergenceError:
        assert e <= -0.7          # only the strong singularities may fail
        return
    assert abs(float(res.value) - 1 / (1 + e)) <= float(res.error) + 1e-15


def test_root_near_zero_down_to_subnormal():
    """A root at 1e-310 inside [0, 1] (regula falsi from the smaller residual, no float left)."""
    from contactlab.numeric.roots import bracketed_root
    x = bracketed_root(lambda x, i: 3.0 * x, np.array([3e-310]), 0.0, 1.0)
    assert x[0] == pytest.approx(1e-310, rel=TOL.SUBNORMAL_ROOT)
