"""MDR transform: closed form vs symbolic vs quadrature, forward vs inverse, tabulated profiles."""
from __future__ import annotations

import mpmath as mp
import numpy as np
import pytest

import contactlab as cl
from contactlab import profiles as P
from contactlab.errors import StrategyUnavailableError

from tests import tolerances as TOL
from tests.reference import normal as ref
from tests.tolerances import (CLOSED_FORM, QUADRATURE, TABLE_6_DIGITS, TABULATED_CUBIC_1000,
                         tabulated_linear)

ANALYTIC = [
    (P.Paraboloid(R=0.01), 1e-3),
    (P.Cone(slope=0.3), 1e-3),
    (P.PowerLaw(c=2.0, n=0.5), 1e-3),
    (P.PowerLaw(c=1e4, n=3.7), 1e-3),
    (P.PowerLaw(c=1e9, n=8), 1e-3),
    (P.PowerLaw(c=1e40, n=20), 1e-2),
    (P.Polynomial({1.5: 3.0, 2: 50.0, 4: 1e6}), 1e-3),
    (P.Sphere(R=0.01), 9e-3),
    (P.TruncatedParaboloid(radius=1e-4, R=0.01), 1e-3),
    (P.TruncatedCone(radius=1e-4, slope=0.05), 1e-3),
]


def rel(a, b):
    a, b = np.asarray(a, float), np.asarray(b, float)
    return np.max(np.abs(a - b) / np.maximum(np.abs(b), 1e-300))


@pytest.mark.parametrize("prof,xmax", ANALYTIC, ids=lambda v: repr(v)[:40])
def test_every_strategy_agrees(prof, xmax):
    x = np.array([0.01, 0.2, 0.5, 0.77, 1.0]) * xmax
    routes = prof.available_strategies()
    assert "quadrature" in routes
    base = prof.g(x, strategy=routes[0])
    for route in routes[1:]:
        tol = QUADRATURE if route == "quadrature" else CLOSED_FORM
        assert rel(prof.g(x, strategy=route), base) < tol, route
    # quadrature of ∫g against the closed form
    if prof._has("_g_integral_closed_form"):
        assert rel(prof._g_integral_quadrature(x)[0], prof.g_integral(x)) < QUADRATURE


@pytest.mark.parametrize("prof,xmax", ANALYTIC, ids=lambda v: repr(v)[:40])
def test_transform_matches_independent_mpmath_quadrature(prof, xmax):
    x = np.array([0.3, 0.9]) * xmax
    expect = [float(ref.transform_quad(lambda r: mp.mpf(float(prof.derivative(float(r)))), xi,
                                       prof.breakpoints)) for xi in x]
    assert rel(prof.g(x), expect) < QUADRATURE


def test_kappa_values_from_physics_md():
    from contactlab.symbolic import kappa, kappa_sympy
    table = {1: np.pi / 2, 2: 2.0, 3: 3 * np.pi / 4, 4: 8 / 3, 8: 128 / 35, 0.5: 1.31103,
             20: 5.67546}
    for n, k in table.items():
        tol = TABLE_6_DIGITS if n in (0.5, 20) else CLOSED_FORM   # 6 printed digits there
        assert abs(kappa(n) / k - 1) < tol
        assert abs(float(kappa_sympy(n)) / kappa(n) - 1) < CLOSED_FORM


def test_symbolic_route_is_sympy_expression():
    import sympy as sp
    from contactlab.symbolic import g_expression
    x = sp.Symbol("x", positive=True)
    R = 0.01
    expr = g_expression(((1 / (2 * R), 2.0),))
    assert sp.simplify(expr - x**2 / R) == 0


@pytest.mark.parametrize("prof,xmax", ANALYTIC[:8], ids=lambda v: repr(v)[:40])
def test_inverse_transform_recovers_profile(prof, xmax):
    r = np.array([0.1, 0.5, 0.95]) * xmax
    assert rel(prof.inverse_transform(r), prof.height(r)) < QUADRATURE


def test_strategy_unavailable_is_specific():
    with pytest.raises(StrategyUnavailableError, match="symbolic"):
        P.Sphere(R=1.0).g(0.1, strategy="symbolic")


def test_g_route_is_cached_and_recorded():
    prof = P.Paraboloid(R=0.01)
    assert prof.g_route == "closed_form"
    c = cl.Contact(P.TruncatedCone(radius=1e-4, slope=0.1) + P.Paraboloid(R=0.1),
                   materials=(cl.Rigid(), cl.Elastic(E=1e9, nu=0.4)))
    assert c.normal(depth=1e-6).meta["routes"]["g"] == "closed_form"


def _sampled(prof, n_points, rmax):
    r = np.linspace(0.0, rmax, n_points)
    return P.Tabulated(r=r, f=prof.height(r))


def test_tabulated_linear_transform_is_exact_sum_of_arcsines():
    """The closed form equals direct quadrature of the piecewise-linear interpolant."""
    r = np.array([0.0, 0.1, 0.25, 0.3, 0.6, 1.0]) * 1e-3
    f = np.array([0.0, 1.0, 2.0, 4.0, 5.0, 9.0]) * 1e-7
    tab = P.Tabulated(r=r, f=f)
    slopes = np.diff(f) / np.diff(r)

    def fp(s):
        k = min(int(np.searchsorted(r, float(s), side="right") - 1), len(slopes) - 1)
        return mp.mpf(slopes[k])

    x = np.array([0.05, 0.26, 0.31, 0.99]) * 1e-3   # (mpmath reference: off the nodes)
    expect = [float(ref.transform_quad(fp, xi, r[1:-1])) for xi in x]
    assert rel(tab.g(x), expect) < CLOSED_FORM
    assert rel(tab.g(x, strategy="quadrature"), expect) < QUADRATURE
    # ∫_0^a g by the closed form vs quadrature of the closed-form g
    from scipy.integrate import quad
    a = 0.8e-3
    brk = list(r[(r > 0) & (r < a)])
    total = quad(lambda t: float(tab.g(t)), 0, a, points=brk, epsabs=0, epsrel=1e-12, limit=200)[0]
    assert rel(tab.g_integral(a), total) < TOL.CLOSED_FORM


@pytest.mark.parametrize("prof,a", [(P.Paraboloid(R=0.01), 1e-4), (P.PowerLaw(c=1e10, n=4), 1e-3)])
@pytest.mark.parametrize("interpolation", ["linear", "cubic"])
def test_tabulated_1000_points_reproduces_force_and_radius(prof, a, interpolation):
    E = cl.Elastic(E=70e9, nu=0.33)
    depth = float(prof.g(a))
    exact = cl.Contact(prof, materials=(E, E)).normal(depth=depth)
    r = np.linspace(0.0, 2 * a, 1000)
    tab = cl.Contact(P.Tabulated(r, prof.height(r), interpolation), materials=(E, E)).normal(depth=depth)
    tol = (tabulated_linear((r[1] - r[0]) / a) if interpolation == "linear"
           else TABULATED_CUBIC_1000)
    assert rel(tab.radius, exact.radius) < tol
    assert rel(tab.force, exact.force) < tol


def test_tabulated_converges_at_second_order():
    prof = P.Paraboloid(R=0.01)
    E = cl.Elastic(E=70e9, nu=0.33)
    exact = cl.Contact(prof, materials=(E, E)).normal(depth=1e-6)
    ns = np.array([50, 100, 200, 400, 800])
    errs = [abs(cl.Contact(_sampled(prof, int(n), 2e-4), materials=(E, E)).normal(depth=1e-6).force
                / exact.force - 1) for n in ns]
    order = -np.polyfit(np.log(ns), np.log(errs), 1)[0]
    assert 1.8 < order < 2.2, (order, errs)


def test_tabulated_cubic_is_smooth_alternative():
    prof = P.Paraboloid(R=0.01)
    E = cl.Elastic(E=70e9, nu=0.33)
    r = np.linspace(0, 2e-4, 200)
    cub = P.Tabulated(r=r, f=prof.height(r), interpolation="cubic")
    # the spline's transform is summed in closed form (node terms, set up once); the per-interval
    # Gauss rule stays available as the second method (tests/unit/profiles/test_cubic_transform.py)
    assert cub.available_strategies() == ("closed_form", "quadrature")
    exact = cl.Contact(prof, materials=(E, E)).normal(depth=1e-6)
    s = cl.Contact(cub, materials=(E, E)).normal(depth=1e-6)
    # a cubic spline reproduces a parabola up to its end conditions: far better than linear
    assert rel(s.force, exact.force) < TOL.CUBIC_PARABOLA


def test_tabulated_from_csv(tmp_path):
    path = tmp_path / "profile.csv"
    r = np.linspace(0, 1e-3, 50)
    path.write_text("r,f\n" + "\n".join(f"{float(a)!r},{float(b)!r}" for a, b in zip(r, r**2 / 0.02)))
    tab = P.Tabulated.from_csv(path)
    assert np.array_equal(tab.r, r)
    assert tab == P.Tabulated(r, r**2 / 0.02)
    assert hash(tab) == hash(P.Tabulated(r, r**2 / 0.02))


def test_sum_and_scaled_profiles_are_linear():
    a, b = P.Paraboloid(R=0.01), P.Cone(slope=0.02)
    x = np.array([1e-5, 1e-4])
    assert rel((a + b).g(x), a.g(x) + b.g(x)) < CLOSED_FORM
    assert rel((2 * a).g(x), 2 * a.g(x)) < CLOSED_FORM
    assert (a + b).terms[1].slope == 0.02
    assert (a + b) == (a + b) and len({a + b, a + b}) == 1



def test_table_shift_loop_evaluates_tiny_radii_quietly():
    """The ∫g² quadrature of a shift loop samples g next to x = 0 (tanh-sinh nodes down to
    ~1e-300): a linear table's arcsine sums divided a node by such an x and overflowed (a numpy
    RuntimeWarning, an error under -W error). The loop energy stays the sphere's to the
    table's resolution."""
    r = np.linspace(0.0, 1e-3, 200)
    steel = cl.Elastic(E=210e9, nu=0.3)
    tab = cl.Contact(P.Tabulated(r, 0.01 - np.sqrt(0.01**2 - r * r)), (steel, steel), friction=0.3)
    ball = cl.Contact(P.Sphere(R=0.01), (steel, steel), friction=0.3)
    u = [0.0, 1e-6, -1e-6, 1e-6]
    w_tab = tab.shift_history(displacement=u, force=10.0).dissipated_energy
    w_ball = ball.shift_history(displacement=u, force=10.0).dissipated_energy
    assert np.all(np.isfinite(w_tab))
    np.testing.assert_allclose(w_tab[-1], w_ball[-1], rtol=TOL.TABLE_200_SHIFT_LOOP)


def test_cubic_table_shift_loop_evaluates_tiny_radii_quietly():
    """Same as the linear table: the cubic table's per-interval rule and the table quadrature
    floor (``(h/x)²`` at x ~ 1e-300) overflowed next to x = 0."""
    r = np.linspace(0.0, 1e-3, 200)
    steel = cl.Elastic(E=210e9, nu=0.3)
    tab = cl.Contact(P.Tabulated(r, 0.01 - np.sqrt(0.01**2 - r * r), interpolation="cubic"),
                     (steel, steel), friction=0.3)
    ball = cl.Contact(P.Sphere(R=0.01), (steel, steel), friction=0.3)
    u = [0.0, 1e-6, -1e-6, 1e-6]
    w_tab = tab.shift_history(displacement=u, force=10.0).dissipated_energy
    w_ball = ball.shift_history(displacement=u, force=10.0).dissipated_energy
    assert np.all(np.isfinite(w_tab))
    np.testing.assert_allclose(w_tab[-1], w_ball[-1], rtol=TOL.TABLE_200_SHIFT_LOOP)


def test_kappa_in_double_precision_against_mpmath():
    """κ_n without scipy: whole-number n correctly rounded (even n exactly the rational
    4^k (k!)²/(2k)!), every other n within a few ulp of the 30-digit reference, also past the
    gamma function's overflow (the asymptotic series for n >= 300)."""
    from contactlab.symbolic import kappa
    from tests.reference.kappa import kappa as kappa_mp
    assert kappa(2.0) == 2.0 and kappa(4.0) == 8 / 3 and kappa(8.0) == 128 / 35
    assert kappa(1.0) == np.pi / 2
    for n in range(2, 601, 2):                       # even n: the exact rational, rounded once
        assert kappa(float(n)) == float(kappa_mp(n)), n
    ns = np.r_[np.arange(0.05, 40.0, 0.35), np.arange(40.0, 2000.0, 13.7), np.arange(1, 700, 7)]
    worst = max(abs(kappa(float(n)) / float(kappa_mp(float(n))) - 1.0) for n in ns)
    assert worst < TOL.KAPPA_DOUBLE, worst
