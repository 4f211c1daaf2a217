"""Product-integration panels of large tables for the exact torque-twist curve (issue 28).

Must show: the panels' slip function P and torque integral T agree with the composite rule they
replace (:data:`TOL.TABLE_PANELS`), the analytic continuations they evaluate agree with mpmath,
the fast g of a linear table agrees with the direct sum, and the curve itself agrees with the
composite route and, within the table's interpolation error, with the closed-form exact Hertz
curve of the paraboloid the table samples (an independent reference).
"""
import mpmath as mp
import numpy as np
import pytest

import contactlab as cl
from contactlab.physics import table_panels as tp
from contactlab.physics import torsion_exact as te
from contactlab.physics.torsion_elliptic import h_kernel, kme_over_m
from tests import tolerances as TOL

MAT = (cl.Elastic(E=210e9, nu=0.3), cl.Rigid())
MU = 0.3
R = 0.01
RTOL = 1e-10


def _hertz_radius(force=10.0):
    return float(cl.Contact(cl.profiles.Paraboloid(R=R), materials=MAT).normal(force=force)._radius)


def _tables():
    a = _hertz_radius()
    rng = np.random.default_rng(5)
    uni = np.linspace(0.0, 1.5 * a, 1000)
    rnd = 1.5 * a * np.sort(np.r_[0.0, rng.random(700), 1.0])
    yield pytest.param(uni, uni**2 / (2 * R), id="uniform-667-in-contact")
    yield pytest.param(rnd, rnd**2 / (2 * R) + 2e3 * rnd**3, id="random-nodes")
    # rough but admissible (convex): slope jumps of random size (exponential, 10x spread)
    slopes = np.cumsum(rng.exponential(uni[1] / R, uni.size - 1) * rng.uniform(0.1, 1.9))
    rough = np.r_[0.0, np.cumsum(slopes * np.diff(uni))]
    yield pytest.param(uni, rough, id="rough-convex")


def _state(r, f):
    c = cl.Contact(cl.profiles.Tabulated(r=r, f=f), materials=MAT, friction=MU, rtol=RTOL)
    n = c.normal(force=10.0)
    a, d = float(n._radius), float(n._depth)
    return c, a, d, float(c.profile._g(np.array(a)))


def test_continuations_against_mpmath():
    mp.mp.dps = 30
    v = np.array([1.0 + 1e-9, 1.01, 1.3, 1.7, 2.0])
    ref = [float(-mp.quad(lambda u: u**2 * mp.ellipk(1 - u**2), [1, x])) for x in v]
    np.testing.assert_allclose(h_kernel(v), ref, rtol=TOL.PANEL_CONTINUATION, atol=0)
    p = np.array([1.0 + 1e-9, 1.05, 1.2, 2.0, 4.0])
    ref = [float((mp.ellipk(1 - x) - mp.ellipe(1 - x)) / (1 - x)) for x in p]
    np.testing.assert_allclose(kme_over_m(p), ref, rtol=TOL.PANEL_CONTINUATION, atol=0)


@pytest.mark.parametrize("r, f", list(_tables()))
def test_panels_cover_whole_segments_within_a_factor_two(r, f):
    pan = tp.panels_of(cl.profiles.Tabulated(r=r, f=f))
    assert pan.start.size >= 2
    assert np.all(pan.end - pan.start >= tp.PANEL_MIN_SEGMENTS)
    assert np.all(r[pan.end] <= tp.PANEL_RATIO * r[pan.start])
    assert np.all(pan.start[1:] >= pan.end[:-1]) and pan.panel_of[0] == -1


@pytest.mark.parametrize("r, f", list(_tables()))
def test_fast_g_matches_the_direct_sum(r, f):
    prof = cl.profiles.Tabulated(r=r, f=f)
    x = np.concatenate([r[1:-1], np.nextafter(r[1:-1], 0.0),
                        np.random.default_rng(2).uniform(0.0, r[-1], 4000), [r[-1]]])
    got, ref = tp.fast_g(prof, x), prof._g(x)
    assert np.max(np.abs(got - ref)) <= TOL.FAST_G * np.max(np.abs(ref))


def test_fast_g_of_a_cubic_table_is_its_g():
    r = np.linspace(0.0, 1e-4, 400)
    prof = cl.profiles.Tabulated(r=r, f=r**2 / (2 * R), interpolation="cubic")
    x = np.linspace(1e-7, 1e-4, 50)
    np.testing.assert_array_equal(tp.fast_g(prof, x), prof._g(x))


@pytest.mark.parametrize("r, f", list(_tables()))
def test_panels_agree_with_the_composite_rule(r, f):
    c, a, d, g_a = _state(r, f)
    nodes = r[(r > 0) & (r < a)]
    x = np.concatenate([nodes, 0.5 * (nodes[1:] + nodes[:-1]), [a * (1 - 1e-9), a * 1e-3],
                        np.random.default_rng(3).uniform(0.0, a, 300)])
    A, D, G = (np.full(x.shape, v) for v in (a, d, g_a))
    E = c.moduli.normal
    for fn in (te.slip_function, te.torque_integral):
        old, _ = fn(c.profile, E, x, A, D, G, RTOL)
        new, _ = fn(c.profile, E, x, A, D, G, RTOL, panels=True)
        assert np.max(np.abs(new - old)) <= TOL.TABLE_PANELS * np.max(np.abs(old)), fn.__name__


@pytest.mark.parametrize("r, f", list(_tables()))
def test_curve_agrees_with_the_composite_route(r, f):
    c, a, d, g_a = _state(r, f)
    s = MU * 10.0 / (c.moduli.torsional * a * a)
    phi = np.linspace(0.0, 0.95, 200) * s
    got = c.torsion(force=10.0, twist=phi, method="exact")
    # the composite route, written out: root of μP(c)/(2G_t) = φ, then M = (16/3)G_t φ c³ + 8μT
    A, D, G = (np.full(phi.shape, v) for v in (a, d, g_a))
    E, G_t = c.moduli.normal, c.moduli.torsional
    cc = te.solve_stick_of_twist(c.profile, E, G_t, MU, phi, A, D, G, RTOL)
    T, _ = te.torque_integral(c.profile, E, cc, A, D, G, RTOL)
    M = 16.0 / 3.0 * G_t * phi * cc**3 + 8.0 * MU * T
    live = cc < a                 # (no slip at φ = 0: both give 0)
    assert np.max(np.abs(got.torque - np.where(live, M, 0.0))) <= (
        TOL.TABLE_PANELS * np.max(np.abs(M)))
    # stick radii: the same root to its tolerance
    assert np.max(np.abs(got.stick_radius - cc)) <= 10 * RTOL * a


def test_curve_against_the_sampled_paraboloid():
    """Independent reference: the closed-form exact Hertz curve (Lubkin) of the paraboloid the
    table samples. The linear interpolant lies within Δ²/(8R) of it, a fraction (Δ/a)²/8 of the
    indentation depth; the torques differ by less (measured 1.9e-8 against 2.8e-7)."""
    r, f = next(iter(_tables())).values
    c, a, _, _ = _state(r, f)
    hertz = cl.Contact(cl.profiles.Paraboloid(R=R), materials=MAT, friction=MU, rtol=RTOL)
    s = MU * 10.0 / (c.moduli.torsional * a * a)
    phi = np.linspace(0.0, 0.95, 200) * s
    got = c.torsion(force=10.0, twist=phi, method="exact")
    ref = hertz.torsion(force=10.0, twist=phi, method="exact")
    bound = (r[1] / a) ** 2 / 8
    assert np.max(np.abs(got.torque - ref.torque)) <= bound * np.max(ref.torque)
    assert np.sum(r < a) == 667


def test_same_call_same_bits_whatever_the_panels_built_before():
    """The panels grow with the contact radius; a curve after a smaller contact (panels built
    part-way) is bit-identical to the same curve on fresh caches."""
    from contactlab.physics import torsion_exact as te_mod
    r, f = next(iter(_tables())).values

    def curve():
        c = cl.Contact(cl.profiles.Tabulated(r=r, f=f), materials=MAT, friction=MU)
        a = float(c.normal(force=10.0)._radius)
        phi = np.linspace(0.0, 0.9, 50) * MU * 10.0 / (c.moduli.torsional * a * a)
        return c, c.torsion(force=10.0, twist=phi).torque

    for cache in (tp._CACHE, tp._G_CACHE, te_mod._TABLE_CACHE):
        cache.clear()
    _, fresh = curve()
    for cache in (tp._CACHE, tp._G_CACHE, te_mod._TABLE_CACHE):
        cache.clear()
    small = cl.Contact(cl.profiles.Tabulated(r=r, f=f), materials=MAT, friction=MU)
    small.torsion(force=1.0, twist=np.linspace(0.0, 1e-4, 40))  # a smaller contact first
    assert 0 < tp.panels_of(small.profile).built.max() < (
        tp.panels_of(small.profile).end - tp.panels_of(small.profile).start).max()
    _, after = curve()
    np.testing.assert_array_equal(after, fresh)


@pytest.mark.parametrize("profile", [cl.profiles.Cone(slope=0.02),
                                     cl.profiles.Tabulated(r=np.linspace(0.0, 1e-4, 40),
                                                           f=np.linspace(0.0, 1e-4, 40) ** 2
                                                           / (2 * R))],
                         ids=["cone", "small-table"])
def test_curves_without_panels_keep_their_bits(profile):
    """Profiles the panels do not serve (no node table, or too few nodes) take the composite
    route unchanged: the curve is bit-identical to its solve written out with panels=False."""
    from contactlab.physics.torsion import METHODS
    c = cl.Contact(profile, materials=MAT, friction=MU)
    n = c.normal(force=10.0)
    a, d = float(n._radius), float(n._depth)
    assert not te.panels_apply(c.profile, np.array([a]))
    phi = np.linspace(0.0, 0.9, 60) * MU * 10.0 / (c.moduli.torsional * a * a)
    A, D = np.full(phi.shape, a), np.full(phi.shape, d)
    G = np.full(phi.shape, float(c.profile._g(np.array(a))))
    E, G_t = c.moduli.normal, c.moduli.torsional
    cc = te.solve_stick_of_twist(c.profile, E, G_t, MU, phi, A, D, G, c.rtol, panels=False)
    model = METHODS["exact"](c.profile, E, G_t, MU, c.rtol)
    got = model.of_twist(phi, A, D, G)
    np.testing.assert_array_equal(got.stick_radius, cc)


@pytest.mark.parametrize("r, f", list(_tables()))
def test_kernels_separated_in_x_agree_with_the_kernels_at_each_point(r, f, monkeypatch):
    """The panel sums of points in a panel's x-range (or below the first panel) come from
    kernels interpolated in the lower limit x too; against the same panel sums with the kernels
    evaluated at every point (``integrate`` without ``x``), over points in every x-range,
    segment 0 and the contact edge included."""
    c, a, d, g_a = _state(r, f)
    nodes = r[(r > 0) & (r < a)]
    x = np.concatenate([nodes, 0.5 * (nodes[1:] + nodes[:-1]), [a * (1 - 1e-9), a * 1e-3],
                        np.random.default_rng(4).uniform(0.0, a, 300)])
    A, D, G = (np.full(x.shape, v) for v in (a, d, g_a))
    E = c.moduli.normal
    pan = tp.panels_of(c.profile)
    assert np.any(x < r[pan.start[0]]) and np.any(x > r[pan.start[-1]])
    for fn in (te.slip_function, te.torque_integral):
        got, _ = fn(c.profile, E, x, A, D, G, RTOL, panels=True)
        with monkeypatch.context() as m:
            plain = tp.integrate
            m.setattr(tp, "integrate",
                      lambda pan, k, first, last, n, rule, x=None, piece=None:
                      plain(pan, k, first, last, n, rule))
            ref, _ = fn(c.profile, E, x, A, D, G, RTOL, panels=True)
        assert np.max(np.abs(got - ref)) <= TOL.TABLE_PANELS_X * np.max(np.abs(ref)), fn.__name__


def test_separated_panel_sums_evaluate_no_kernel_per_point(monkeypatch):
    """Points whose lower limit lies in a panel's x-range take no kernel evaluation on the
    panels (only the per-table matrices at the interpolation points, once) nor on the last
    partial segment (once per x-range and piece, at the interpolation points)."""
    r, f = next(iter(_tables())).values
    c, a, d, g_a = _state(r, f)
    pan = tp.panels_of(c.profile)
    x = np.linspace(r[pan.start[0]], 0.9 * a, 5000)
    A, D, G = (np.full(x.shape, v) for v in (a, d, g_a))
    te.slip_function(c.profile, c.moduli.normal, x, A, D, G, RTOL, panels=True)   # tables built
    sizes = []
    real = te._slip_shape
    monkeypatch.setattr(te, "_slip_shape", lambda t, xx: sizes.append(np.size(t)) or real(t, xx))
    te.slip_function(c.profile, c.moduli.normal, x, A, D, G, RTOL, panels=True)
    n_ranges = pan.separated["slip"].xi.shape[0]
    assert sum(sizes) <= n_ranges * tp.X_POINTS * 8 < x.size


def test_curve_root_solve_takes_three_passes_over_its_points(monkeypatch):
    """The curve's stick radii: the grid bracket's interpolated point, a Newton point just across
    the root, then one secant pass; only a few points (table wiggles within the bracket) need
    more. Counted as evaluations of P at more than half of the curve's points."""
    r, f = next(iter(_tables())).values
    c, a, _, _ = _state(r, f)
    phi = np.linspace(0.0, 0.95, 1000) * MU * 10.0 / (c.moduli.torsional * a * a)
    sizes = []
    real = te.slip_function

    def counted(*args, **kw):
        sizes.append(np.size(args[2]))
        return real(*args, **kw)

    monkeypatch.setattr(te, "slip_function", counted)
    c.torsion(force=10.0, twist=phi, method="exact")
    big = [s for s in sizes if s > phi.size // 2]
    assert len(big) == 3, sizes
    assert sum(s for s in sizes if s <= phi.size // 2) <= 0.5 * phi.size, sizes


@pytest.mark.parametrize("r, f", list(_tables()))
def test_fast_g_in_known_segments_is_fast_g(r, f):
    """g at points grouped by a known segment (the first partial segment of an integral) is
    bit-identical to fast_g at the same points located one by one."""
    prof = cl.profiles.Tabulated(r=r, f=f)
    j = np.arange(1, r.size - 1)
    u = np.polynomial.legendre.leggauss(8)[0] * 0.5 + 0.5
    t = r[j][:, None] + (r[j + 1] - r[j])[:, None] * u**2
    ref = tp.fast_g(prof, t.ravel()).reshape(t.shape)          # builds the cached form
    np.testing.assert_array_equal(tp.fast_g_in(prof, t, j), ref)


def test_curve_near_full_sliding_takes_the_whole_grid():
    """Twists whose stick radii lie below exp(-5) a (the curve grid's lazily evaluated part):
    the curve still agrees with the composite route there (stick radii and torques)."""
    r, f = next(iter(_tables())).values
    c, a, d, g_a = _state(r, f)
    E, G_t = c.moduli.normal, c.moduli.torsional
    c_low = a * np.array([1e-3, 1e-5, 1e-8])
    P, _ = te.slip_function(c.profile, E, c_low, a, d, g_a, RTOL)
    phi = np.concatenate([np.linspace(0.0, 0.95, 100) * MU * 10.0 / (G_t * a * a),
                          te.twist_of_stick(MU, G_t, P)])
    got = c.torsion(force=10.0, twist=phi, method="exact")
    A, D, G = (np.full(phi.shape, v) for v in (a, d, g_a))
    cc = te.solve_stick_of_twist(c.profile, E, G_t, MU, phi, A, D, G, RTOL)
    T, _ = te.torque_integral(c.profile, E, cc, A, D, G, RTOL)
    M = np.where(cc < a, 16.0 / 3.0 * G_t * phi * cc**3 + 8.0 * MU * T, 0.0)
    assert np.all(got.stick_radius[-3:] < np.exp(-5.0) * a)
    # the root's tolerance is rtol in y = ln(c/a) (|y| <= 18 here) or in the twist, which is
    # nearly flat in c as c -> 0 (measured 2e-10)
    np.testing.assert_allclose(got.stick_radius[-3:], c_low, rtol=100 * RTOL)
    assert np.max(np.abs(got.torque - M)) <= TOL.TABLE_PANELS * np.max(np.abs(M))
    assert np.max(np.abs(got.stick_radius - cc)) <= 10 * RTOL * a
