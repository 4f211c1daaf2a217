"""Subsurface stress fields of normal states (issue 31, part A).

References: tests/reference/stress.py (Johnson eqs. 3.44-3.45, Huber's field, Boussinesq's point
load integrated numerically) and checks that need no formula (equilibrium at every depth, the
surface values equal the surface pressure the library already computes).
"""
from __future__ import annotations

import warnings

import numpy as np
import pytest

import contactlab as cl
from contactlab.errors import ContactlabError, NotSupportedError, ParameterError
from contactlab.physics import stress as kern
from tests import tolerances as tol
from tests.reference import stress as ref

STEEL = cl.Elastic(E=210e9, nu=0.3)
ALU = cl.Elastic(E=70e9, nu=0.33)
R = 0.01
F = 100.0


def hertz_state(materials=(STEEL, STEEL)):
    st = cl.Contact(cl.profiles.Paraboloid(R=R), materials=materials).normal(force=F)
    a = st.radius
    return st, a, 3 * F / (2 * np.pi * a**2)


def test_hertz_axis_against_johnson_345():
    st, a, p0 = hertz_state()
    z = np.array([1e-6, 0.01, 0.1, 0.48, 1.0, 3.0, 10.0]) * a
    f = st.stress(0.0, z)
    sr, sz = ref.hertz_axis(z, a, p0, 0.3)
    assert f.meta["route"] == "hertz"
    np.testing.assert_allclose(f.szz, sz, rtol=0, atol=tol.STRESS_CLOSED_FORM * p0)
    np.testing.assert_allclose(f.srr, sr, rtol=0, atol=tol.STRESS_CLOSED_FORM * p0)
    np.testing.assert_allclose(f.stt, sr, rtol=0, atol=tol.STRESS_CLOSED_FORM * p0)
    assert np.all(f.srz == 0)


def test_hertz_surface_against_johnson_344_and_edge_radial_stress():
    st, a, p0 = hertz_state()
    r = np.array([0.01, 0.3, 0.7, 0.99, 1.0, 1.01, 1.5, 4.0]) * a
    f = st.stress(r, 0.0)
    sr, stt, sz = ref.hertz_surface(r, a, p0, 0.3)
    for got, want in ((f.srr, sr), (f.stt, stt), (f.szz, sz)):
        np.testing.assert_allclose(got, want, rtol=0, atol=tol.STRESS_CLOSED_FORM * p0)
    edge = st.stress(a, 0.0)
    assert abs(float(edge.srr) - (1 - 2 * 0.3) * p0 / 3) <= tol.STRESS_CLOSED_FORM * p0


def test_hertz_off_axis_against_huber_and_boussinesq():
    st, a, p0 = hertz_state()
    pts = [(0.3, 0.2), (0.9, 0.5), (1.2, 0.1), (0.5, 1.3), (2.0, 0.7)]
    for X, Z in pts:
        f = st.stress(X * a, Z * a)
        want = ref.hertz_huber(X * a, Z * a, a, p0, 0.3)
        got = (f.srr, f.stt, f.szz, f.srz)
        for g, w in zip(got, want):
            assert abs(float(g) - float(w)) <= tol.STRESS_CLOSED_FORM * p0
        bous = ref.boussinesq_field(lambda s: p0 * np.sqrt(1 - s**2 / a**2), a, X * a, Z * a, 0.3)
        for g, w in zip(got, bous):
            assert abs(float(g) - float(w)) <= tol.STRESS_BOUSSINESQ_HERTZ * p0


def test_hertz_maximum_shear_031_p0_at_048_a():
    st, a, p0 = hertz_state()
    val, depth = ref.hertz_max_shear(0.3)
    m = st.max_stress("max_shear")
    assert abs(m.value / p0 - val) <= tol.STRESS_CLOSED_FORM
    assert abs(m.z / a - depth) <= tol.STRESS_MAX_LOCATION
    assert m.r / a <= tol.STRESS_MAX_LOCATION
    assert round(val, 2) == 0.31 and round(depth, 2) == 0.48       # the textbook numbers


def test_superposition_route_reproduces_hertz_within_its_estimate():
    # the general route on the paraboloid's g' = 2x/R, against Huber's closed form
    a, p0 = 1.0, 2.0 / np.pi          # E* = 1, R = 1
    rr, zz = np.meshgrid(np.linspace(0, 2, 41), np.array([0, 1e-6, 1e-3, 0.05, 0.3, 1, 2]))
    r, z = rr.ravel(), zz.ravel()
    got, err = kern.superposed_field(r, z, np.full(r.shape, a), np.zeros(r.shape),
                                     lambda x: 2 * x, 1.0, 0.3)
    want = kern.hertz_field(r, z, a, p0, 0.3)
    for g, w in zip(got, want):
        d = np.abs(g - w)
        assert np.max(d) <= tol.STRESS_SUPERPOSITION * p0
        assert np.all(d <= err)


def test_flat_punch_against_boussinesq_and_surface_pressure():
    prof = cl.profiles.FlatPunch(radius=1e-3)
    st = cl.Contact(prof, materials=(STEEL, STEEL)).normal(depth=1e-6)
    a, pm = st.radius, st.force / (np.pi * st.radius**2)
    E = st.contact.moduli.normal
    d = st.depth
    for X, Z in [(0.3, 0.2), (0.9, 0.5), (1.2, 0.1), (0.5, 1.3)]:
        f = st.stress(X * a, Z * a)
        assert f.meta["route"] == "flat_punch"
        bous = ref.boussinesq_field(lambda s: E * d / (np.pi * np.sqrt(a**2 - s**2)), a, X * a,
                                    Z * a, 0.3, flat=True)
        for g, w in zip((f.srr, f.stt, f.szz, f.srz), bous):
            assert abs(float(g) - float(w)) <= tol.STRESS_BOUSSINESQ_PUNCH * pm
    r = np.array([0.0, 0.2, 0.6, 0.95]) * a
    np.testing.assert_allclose(st.stress(r, 0.0).szz, -st.pressure(r), rtol=1e-13)
    # the rim is singular: the field says so instead of returning a number
    rim = st.stress(a, 0.0)
    assert not np.isfinite(rim.szz) and rim.error == np.inf
    assert st.max_stress("von_mises").value == np.inf


@pytest.mark.parametrize("make", [
    lambda: cl.profiles.Paraboloid(R=R),
    lambda: cl.profiles.Cone(slope=0.05),
    lambda: cl.profiles.FlatPunch(radius=1e-4),
    lambda: cl.profiles.PowerLaw(c=1e6, n=4.0),
])
def test_equilibrium_at_every_depth(make):
    st = cl.Contact(make(), materials=(STEEL, STEEL)).normal(force=F)
    a = st.radius
    t, w = np.polynomial.legendre.leggauss(400)
    for zr in (0.1, 0.5, 2.0):
        z = zr * a
        th_a = np.arctan(a / z)
        parts = [(0.0, th_a), (th_a, 0.5 * np.pi * (1 - 1e-9))]
        th = np.concatenate([lo + (hi - lo) * (t + 1) / 2 for lo, hi in parts])
        wt = np.concatenate([(hi - lo) / 2 * w for lo, hi in parts])
        r = z * np.tan(th)
        dr = z / np.cos(th) ** 2 * wt
        f = st.stress(r, z)
        total = np.sum(2 * np.pi * r * f.szz * dr)
        # the far tail beyond θ_max is F z³... negligible: (1 - θ_max) ~ 1e-9
        assert abs(total / F + 1) <= tol.STRESS_EQUILIBRIUM


def test_surface_values_equal_the_pressure_for_any_profile():
    for prof in (cl.profiles.Cone(slope=0.05), cl.profiles.Sphere(R=R),
                 cl.profiles.PowerLaw(c=1e6, n=4.0)):
        st = cl.Contact(prof, materials=(STEEL, STEEL)).normal(force=F)
        r = np.array([0.1, 0.4, 0.8, 0.97]) * st.radius
        f = st.stress(r, 0.0)
        p = st.pressure(r)
        assert f.meta["route"].startswith("superposition")
        np.testing.assert_allclose(f.szz, -p, rtol=tol.STRESS_SUPERPOSITION)
        assert np.all(np.abs(f.srz) <= 1e-12 * p)


def test_cone_field_against_boussinesq():
    st = cl.Contact(cl.profiles.Cone(slope=0.05), materials=(STEEL, STEEL)).normal(force=F)
    a = st.radius
    E = st.contact.moduli.normal
    pm = F / (np.pi * a**2)
    for X, Z in [(0.3, 0.3), (1.1, 0.5), (0.0, 1.0)]:
        f = st.stress(X * a, Z * a)
        bous = ref.boussinesq_field(lambda s: E * 0.05 / 2 * np.arccosh(a / s), a,
                                    X * a, Z * a, 0.3, n_r=400, n_t=240)
        for g, w in zip((f.srr, f.stt, f.szz, f.srz), bous):
            assert abs(float(g) - float(w)) <= tol.STRESS_BOUSSINESQ_HERTZ * pm


def test_measured_paraboloid_reproduces_hertz_within_its_error():
    st_h, a, p0 = hertz_state()
    rt = np.linspace(0, 3 * a, 400)
    table = cl.profiles.Tabulated(rt, rt**2 / (2 * R), interpolation="cubic")
    st = cl.Contact(table, materials=(STEEL, STEEL)).normal(force=F)
    rr, zz = np.meshgrid(np.linspace(0, 2 * a, 60), np.linspace(0, 1.5 * a, 30))
    ft, fh = st.stress(rr, zz), st_h.stress(rr, zz)
    # the table's own contact radius differs from Hertz by its interpolation error
    da = abs(st.radius / a - 1)
    for k in ("srr", "stt", "szz", "srz"):
        d = np.abs(getattr(ft, k) - getattr(fh, k))
        assert np.all(d <= ft.error + 4 * da * p0), k
    assert ft.meta["error_estimate"] < 5e-3          # measured 1.4e-3 (surface points)


def test_body_two_uses_its_own_poisson_ratio():
    st, a, p0 = hertz_state((STEEL, ALU))
    f1 = st.stress(0.4 * a, 0.3 * a, body=1)
    f2 = st.stress(0.4 * a, 0.3 * a, body=2)
    w2 = ref.hertz_huber(0.4 * a, 0.3 * a, a, p0, 0.33)
    assert abs(float(f2.srr) - float(w2[0])) <= tol.STRESS_CLOSED_FORM * p0
    assert float(f1.szz) == float(f2.szz) and float(f1.srr) != float(f2.srr)


def test_derived_quantities():
    st, a, p0 = hertz_state()
    f = st.stress(np.linspace(0, 2 * a, 7)[:, None], np.linspace(0, a, 5)[None, :])
    assert f.shape == (7, 5)
    p = f.principal
    assert np.all(p[..., 0] >= p[..., 1]) and np.all(p[..., 1] >= p[..., 2])
    np.testing.assert_allclose(p.sum(-1), f.srr + f.stt + f.szz, rtol=1e-12, atol=1e-6 * p0)
    np.testing.assert_allclose(f.tresca, 2 * f.max_shear)
    vm = np.sqrt(0.5 * ((p[..., 0] - p[..., 1])**2 + (p[..., 1] - p[..., 2])**2
                        + (p[..., 2] - p[..., 0])**2))
    np.testing.assert_allclose(f.von_mises, vm, rtol=1e-10, atol=1e-9 * p0)
    with pytest.raises(ValueError):
        f.srr[0, 0] = 1.0                                  # immutable arrays
    d = f.to_dict()
    assert set(d) >= {"r", "z", "srr", "stt", "szz", "srz", "stz", "srt", "von_mises",
                      "max_shear", "tresca", "error"}
    g = st.stress(np.linspace(0, 2 * a, 7)[:, None], np.linspace(0, a, 5)[None, :])
    assert np.array_equal(f.von_mises, g.von_mises)       # bit-identical on repeat


def test_stress_field_grid():
    st, a, _p0 = hertz_state()
    f = st.stress_field()
    assert f.shape == (100, 200)
    assert f.r.max() == 2 * a and f.z.max() == 1.5 * a
    g = st.stress_field((np.linspace(0, a, 5), np.linspace(0, a, 3)))
    assert g.shape == (3, 5)


@pytest.mark.parametrize("kw, exc, match", [
    ({"r": 0.0, "z": -1e-6}, ParameterError, "z contains"),
    ({"r": -1e-6, "z": 0.0}, ParameterError, "r contains"),
    ({"r": np.nan, "z": 0.0}, ParameterError, "r"),
    ({"r": 0.0, "z": np.nan}, ParameterError, "z"),
    ({"r": 0.0, "z": 0.0, "body": 3}, ParameterError, "body=3"),
    ({"r": 0.0, "z": 0.0, "body": True}, ParameterError, "body=True"),
    ({"r": 0.0, "z": 0.0, "body": 1.0}, ParameterError, r"body=1\.0 .*integer 1 or 2"),
    ({"r": 0.0, "z": 0.0, "body": 2.0}, ParameterError, r"body=2\.0 .*integer 1 or 2"),
    ({"r": 0.0, "z": 0.0, "body": "1"}, ParameterError, "body='1'"),
    ({"r": [0.0, 1.0], "z": [0.0, 1.0, 2.0]}, ParameterError, "broadcast"),
])
def test_bad_input(kw, exc, match):
    st, _a, _p0 = hertz_state()
    with pytest.raises(exc, match=match):
        st.stress(**kw)
    assert issubclass(exc, ContactlabError)


def test_float_body_refused_by_every_stress_entry_point():
    st, _a, _p0 = hertz_state()
    for call in (lambda: st.max_stress(body=2.0), lambda: st.stress_field(body=1.0)):
        with pytest.raises(ParameterError, match=r"body=\d\.0 is invalid"):
            call()
    # numpy integers are integers
    assert np.isfinite(st.stress(0.0, 1e-6, body=np.int64(1)).szz)


def test_rigid_body_and_bad_kind():
    st = cl.Contact(cl.profiles.Paraboloid(R=R), materials=(STEEL, cl.Rigid())).normal(force=F)
    with pytest.raises(NotSupportedError, match="body=2"):
        st.stress(0.0, 0.0, body=2)
    with pytest.raises(ParameterError, match="kind="):
        st.max_stress("nonsense")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        st.stress(0.0, 1e-6, body=1)


def test_adhesive_state_adds_the_tensile_edge_punch():
    # JKR: Hertz plus a flat punch of radius a pulled by the edge depth d - g(a) < 0
    rubber = cl.Elastic(E=1e9, nu=0.5)
    c = cl.Contact(cl.profiles.Paraboloid(R=R), materials=(rubber, cl.Rigid()),
                   work_of_adhesion=0.05)
    st = c.normal(force=1e-3)
    a = st.radius
    r = np.array([0.1, 0.5, 0.9, 0.99]) * a
    f = st.stress(r, 0.0)
    p = st.pressure(r)
    assert p[-1] < 0                                      # tensile near the edge
    np.testing.assert_allclose(f.szz, -p, rtol=1e-12)
    assert f.meta["edge_depth"] < 0
    t, w = np.polynomial.legendre.leggauss(400)
    z = 0.5 * a
    th_a = np.arctan(a / z)
    parts = [(0.0, th_a), (th_a, 0.5 * np.pi * (1 - 1e-12))]
    th = np.concatenate([lo + (hi - lo) * (t + 1) / 2 for lo, hi in parts])
    wt = np.concatenate([(hi - lo) / 2 * w for lo, hi in parts])
    rr = z * np.tan(th)
    total = np.sum(2 * np.pi * rr * st.stress(rr, z).szz * z / np.cos(th) ** 2 * wt)
    # F is small against the compressive and tensile parts: compare with their scale
    assert abs(total + st.force) <= tol.STRESS_EQUILIBRIUM * (4 / 3 * c.moduli.normal * a**3 / R)
    assert not np.isfinite(st.stress(a, 0.0).szz)          # the JKR edge is singular


def test_spheroidal_setup_satisfies_its_defining_identities():
    """``m² n² = x² z²``, ``n² - m² = A`` and ``m² + n² = Q``, to rounding, on points inside,
    outside and on the surface, and m², n² never negative (no cancellation near the surface)."""
    rng = np.random.default_rng(7)
    r = np.concatenate([rng.uniform(0, 3, 500), [0.0, 0.5, 2.0]])
    z = np.concatenate([rng.uniform(0, 2, 500), [0.0, 0.0, 1e-9]])
    r, z, x, x2, A, Q, m2, n2 = kern.spheroidal(r, z, 1.3)
    assert np.all(m2 >= 0) and np.all(n2 >= 0)
    scale = r * r + z * z + x2
    assert np.all(np.abs(m2 * n2 - x2 * z * z) <= 8e-16 * scale * scale)
    assert np.all(np.abs(n2 - m2 - A) <= 8e-16 * scale)
    assert np.all(np.abs(m2 + n2 - Q) <= 8e-16 * scale)


# ---------------------------------------------------------------- points a hair inside the edge
#: distances below the contact edge, in contact radii (1e-16: one ulp; the quadrature segment
#: [r, a] of the points below 1e-11 used to round onto x = r and give -inf)
EDGE_GAPS = np.array([1e-16, 1e-14, 1e-12, 1e-11, 1e-10, 1e-8, 1e-5, 1e-2, 0.5])
SOFT = cl.Elastic(E=1e9, nu=0.3)


def _acosh_one_plus(e):
    """acosh(1 + e) without the cancellation of acosh((a/r)) for e -> 0."""
    return np.log1p(e + np.sqrt(e * (2.0 + e)))


def _edge_points(st):
    a = float(st.radius)
    r = a * (1.0 - EDGE_GAPS)
    return a, r, (a - r) / r


def _surface_checked_against(st, p_exact):
    """The surface field a hair inside the edge: finite, and σ_zz = -p within the estimate."""
    _a, r, _e = _edge_points(st)
    with warnings.catch_warnings():
        warnings.simplefilter("error", RuntimeWarning)
        f = st.stress(r, 0.0)
        vm = f.von_mises
    comps = np.stack([f.srr, f.stt, f.szz, f.srz])
    assert np.all(np.isfinite(comps)) and np.all(np.isfinite(f.error))
    assert np.all(np.isfinite(vm))
    np.testing.assert_array_less(np.abs(f.szz + p_exact), f.error)


def test_cone_surface_stress_a_hair_inside_the_edge_is_its_closed_form_pressure():
    s = np.tan(np.radians(20.0))                            # half angle 70 deg
    st = cl.Contact(cl.profiles.Cone(half_angle=np.radians(70)), (SOFT, cl.Rigid())).normal(
        force=1.0)
    _a, _r, e = _edge_points(st)
    E = SOFT.E / (1 - SOFT.nu**2)
    _surface_checked_against(st, 0.5 * E * s * _acosh_one_plus(e))    # (E* s/2) acosh(a/r)


@pytest.mark.parametrize("n", [3.0, 4.0])
def test_power_law_surface_stress_a_hair_inside_the_edge_is_its_closed_form_pressure(n):
    from math import gamma, pi, sqrt
    c = 1e3 if n == 3.0 else 1e6
    st = cl.Contact(cl.profiles.PowerLaw(c=c, n=n), (SOFT, cl.Rigid())).normal(force=1.0)
    _a, r, e = _edge_points(st)
    E = SOFT.E / (1 - SOFT.nu**2)
    kappa = sqrt(pi) * gamma(n / 2 + 1) / gamma(n / 2 + 0.5)       # g = kappa c x^n (MDR)
    U = _acosh_one_plus(e)
    # p = (E*/pi) kappa c n r^(n-1) int_0^U cosh^(n-1) u du   (x = r cosh u)
    cosh_int = (0.5 * U + 0.25 * np.sinh(2 * U) if n == 3.0
                else np.sinh(U) + np.sinh(U)**3 / 3.0)
    _surface_checked_against(st, E / np.pi * kappa * c * n * r**(n - 1) * cosh_int)


def test_sphere_surface_stress_a_hair_inside_the_edge_is_the_pressure():
    st = cl.Contact(cl.profiles.Sphere(R=1e-3), (SOFT, cl.Rigid())).normal(force=1.0)
    a = float(st.radius)
    r = a * (1.0 - np.array([1e-12, 1e-10, 1e-4]))
    with warnings.catch_warnings():
        warnings.simplefilter("error", RuntimeWarning)
        f = st.stress(r, 0.0)
    # the second method: the profile's own pressure route
    np.testing.assert_array_less(np.abs(f.szz + st.pressure(r)), f.error)
    assert np.all(np.isfinite(f.von_mises))


def test_max_stress_of_smooth_contacts_is_finite_and_quiet():
    with warnings.catch_warnings():
        warnings.simplefilter("error", RuntimeWarning)
        for prof in (cl.profiles.PowerLaw(c=1e6, n=4), cl.profiles.Sphere(R=1e-3)):
            st = cl.Contact(prof, (SOFT, cl.Rigid())).normal(force=1.0)
            a = float(st.radius)
            m = st.max_stress("von_mises")
            assert np.isfinite(m.value)
            grid = st.stress_field(grid=(np.linspace(0, 2 * a, 41), np.linspace(0, 2 * a, 41)))
            assert m.value >= np.max(grid.von_mises) * (1 - 1e-12)
        # the cone's apex: logarithmically singular, reported as inf, without numpy warnings
        st = cl.Contact(cl.profiles.Cone(half_angle=np.radians(70)), (SOFT, cl.Rigid())).normal(
            force=1.0)
        m = st.max_stress("von_mises")
        assert m.value == np.inf and m.r < 1e-6 * st.radius and m.z < 1e-6 * st.radius


# ---------------------------------------------------------------- memory budget
def _peak(call):
    import tracemalloc
    tracemalloc.start()
    try:
        out = call()
        _ = out.von_mises
        return tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()


def test_stress_memory_estimate_covers_the_measured_peak():
    from contactlab.effects.stress import CHUNK_POINT_BYTES, STRESS_POINT_BYTES
    st, a, _p0 = hertz_state()
    sphere = cl.Contact(cl.profiles.Sphere(R=R), materials=(STEEL, STEEL)).normal(force=F)
    for n in (2_000, 50_000, 200_000):
        r = np.linspace(0, 2 * a, n)
        assert _peak(lambda: st.stress(r, 0.3 * a)) <= STRESS_POINT_BYTES * n
        assert (_peak(lambda: sphere.stress(r, 0.3 * a))
                <= STRESS_POINT_BYTES * n + CHUNK_POINT_BYTES * min(n, kern.CHUNK))
    m = 300
    grid = (np.linspace(0, a, m), np.linspace(0, a, m))
    assert _peak(lambda: st.stress_field(grid=grid)) <= STRESS_POINT_BYTES * m * m


def test_stress_entry_points_check_the_memory_budget_first():
    import tracemalloc

    from contactlab.errors import MemoryBudgetError
    st, a, _p0 = hertz_state()
    sphere = cl.Contact(cl.profiles.Sphere(R=R), materials=(STEEL, STEEL)).normal(force=F)
    shift = cl.Contact(cl.profiles.Paraboloid(R=R), materials=(STEEL, STEEL),
                       friction=0.3).tangential(force=F, tangential_force=10.0)
    twist = cl.Contact(cl.profiles.Paraboloid(R=R), materials=(STEEL, STEEL),
                       friction=0.3).torsion(force=F, twist=1e-5)
    r = np.zeros(1_000_000)                       # 8 MB of points, ~256 MB of field
    previous = cl.set_memory_budget("100M")
    try:
        calls = {"stress()": (lambda: st.stress(r, 0.3 * a),
                              lambda: sphere.stress(r[:100_000], 0.3 * a),
                              lambda: twist.stress(r, 0.3 * a),
                              lambda: shift.stress(r, 0.0, 0.3 * a)),
                 "stress_field()": (lambda: st.stress_field(grid=(np.zeros(20_000),) * 2),
                                    lambda: shift.stress_field(grid=(np.zeros(20_000),) * 2))}
        for what, fns in calls.items():
            for fn in fns:
                tracemalloc.start()
                try:
                    with pytest.raises(MemoryBudgetError, match=rf"{what}.*points x 256 bytes"):
                        fn()
                    assert tracemalloc.get_traced_memory()[1] < 50e6    # refused up front
                finally:
                    tracemalloc.stop()
        assert st.stress(r[:100_000], 0.3 * a).szz.shape == (100_000,)   # 26 MB: within
    finally:
        cl.set_memory_budget(previous)
