"""Subsurface stress fields of tangential (Cattaneo–Mindlin) states and of combined states
(issue 31, part C).

References: Hamilton's sliding-sphere field (tests/reference/stress_tangential.py, written from
the paper) and checks that need no formula: equilibrium of the elementary field by finite
differences, the force ``∫ σ_xz dA = F_x`` carried through every depth, the surface values equal
the library's own surface traction ``state.shear(r)``.
"""
from __future__ import annotations

import warnings

import numpy as np
import pytest

import contactlab as cl
from contactlab.effects.stress_tangential import combined_stress, to_cartesian
from contactlab.errors import ContactlabError, NotSupportedError, ParameterError, ValidityWarning
from contactlab.physics import stress_tangential as kern
from tests import tolerances as tol
from tests.reference import stress_tangential as ref

STEEL = cl.Elastic(E=210e9, nu=0.3)
ALU = cl.Elastic(E=70e9, nu=0.33)
F = 100.0
MU = 0.3


def contact(profile=None, materials=(STEEL, STEEL)):
    return cl.Contact(profile or cl.profiles.Paraboloid(R=0.01), materials=materials,
                      friction=MU)


PTS = np.array([(0.3, 0.4, 0.5), (1.2, -0.7, 0.2), (0.1, 0.05, 1.5), (2.0, 1.0, 0.05),
                (0.5, 0.2, 0.01), (0.9, 0.0, 0.3), (-0.6, 0.5, 0.8), (-1.05, 0.1, 0.02)])


def test_sliding_sphere_against_hamilton():
    c = contact()
    n = c.normal(force=F)
    a = n.radius
    p0 = 3 * F / (2 * np.pi * a**2)
    s = c.tangential(force=F, tangential_force=MU * F)
    assert s.gross_sliding
    X, Y, Z = PTS.T
    fr = s.stress(X * a, Y * a, Z * a, part="friction")
    want = ref.hamilton_shear(X, Y, Z, 0.3)
    # Hamilton's traction is applied along +x to the half-space (σ_xz = -q on the surface);
    # body 1 receives the library's traction +μp, so its field is minus Hamilton's
    near_edge = (np.abs(np.hypot(X, Y) - 1) < 0.06) & (Z <= 0.02)
    atol = np.where(near_edge, tol.STRESS_HAMILTON_EDGE, tol.STRESS_HAMILTON) * p0
    for k, w in want.items():
        assert np.all(np.abs(getattr(fr, k) + MU * p0 * w) <= atol), k
        assert np.all(np.abs(getattr(fr, k) + MU * p0 * w) <= fr.error)
    axis = s.stress(0.0, 0.0, np.array([0.01, 0.3, 1.0, 3.0]) * a, part="friction")
    np.testing.assert_allclose(axis.sxz, -MU * p0 * ref.hamilton_shear_axis([0.01, 0.3, 1, 3]),
                               rtol=0, atol=tol.STRESS_HAMILTON * p0)
    # the whole field: the normal preload's (cylindrical, rotated) plus the shear part
    tot = s.stress(X * a, Y * a, Z * a)
    nf = n.stress(np.hypot(X, Y) * a, Z * a)
    for k, v, w in zip(("sxx", "syy", "szz", "sxy", "sxz", "syz"),
                       to_cartesian(nf, X * a, Y * a), (fr.sxx, fr.syy, fr.szz, fr.sxy,
                                                        fr.sxz, fr.syz)):
        np.testing.assert_allclose(getattr(tot, k), v + w, rtol=1e-14, atol=1e-14 * p0)


def test_elementary_field_is_in_equilibrium_and_free_outside_the_load():
    nu = 0.27

    def tensor(X, Y, Z):
        r = np.hypot(X, Y)
        comps = kern.shear_components(kern.shear_kernel(r, Z, 1.0, nu), X / r, Y / r)
        sxx, syy, szz, sxy, sxz, syz = (float(v) for v in comps)
        return np.array([[sxx, sxy, sxz], [sxy, syy, syz], [sxz, syz, szz]])

    h = 1e-5
    for X, Y, Z in PTS[:-1]:
        d = [(tensor(X + h, Y, Z) - tensor(X - h, Y, Z)) / (2 * h),
             (tensor(X, Y + h, Z) - tensor(X, Y - h, Z)) / (2 * h),
             (tensor(X, Y, Z + h) - tensor(X, Y, Z - h)) / (2 * h)]
        div = sum(d[j][:, j] for j in range(3))
        # central differences of step 1e-5: truncation ~1e-10 of the field's scale
        assert np.max(np.abs(div)) <= 1e-8 * max(1.0, np.max(np.abs(tensor(X, Y, Z))))
    r = np.array([0.1, 0.5, 0.9, 1.3, 2.0])
    comps = kern.shear_components(kern.shear_kernel(r, 0.0, 1.0, nu), np.full(5, 0.6),
                                  np.full(5, 0.8))
    sxz, syz, szz = comps[4], comps[5], comps[2]
    inside = r < 1
    np.testing.assert_allclose(sxz[inside], -1 / np.sqrt(1 - r[inside]**2), rtol=1e-14)
    assert np.all(sxz[~inside] == 0) and np.all(syz == 0) and np.all(szz == 0)


def partial_states():
    cone = cl.profiles.Cone.from_half_angle(np.radians(80)) if hasattr(
        cl.profiles.Cone, "from_half_angle") else None
    out = [contact().tangential(force=F, tangential_force=0.5 * MU * F),
           contact().tangential(force=F, tangential_force=0.9 * MU * F)]
    if cone is not None:
        out.append(contact(cone).tangential(force=F, tangential_force=0.5 * MU * F))
    out.append(contact(cl.profiles.PowerLaw(c=1e6, n=4.0)).tangential(
        force=F, tangential_force=-0.6 * MU * F))
    return out


@pytest.mark.parametrize("i", range(4))
def test_surface_values_equal_the_shear_traction(i):
    s = partial_states()[i]
    a = s.normal.radius
    r = np.array([0.05, 0.3, 0.6, 0.85, 0.97]) * a
    assert 0 < s.stick_radius < a
    for ang in (0.0, 1.1, 2.5):
        f = s.stress(r * np.cos(ang), r * np.sin(ang), 0.0, part="friction")
        tau = np.asarray(s.shear(r))
        np.testing.assert_allclose(f.sxz, tau, rtol=0,
                                   atol=tol.STRESS_TANGENTIAL_SURFACE * np.max(np.abs(tau)))
        assert np.all(f.syz == 0) and np.all(f.szz == 0)


@pytest.mark.parametrize("i", range(4))
def test_force_equilibrium_at_every_depth(i):
    s = partial_states()[i]
    a = s.normal.radius
    t, w = np.polynomial.legendre.leggauss(400)
    for zr in (0.1, 0.5, 2.0):
        z = zr * a
        th_a = np.arctan(a / z)
        parts = [(0.0, th_a), (th_a, 0.5 * np.pi * (1 - 1e-12))]
        th = np.concatenate([lo + (hi - lo) * (t + 1) / 2 for lo, hi in parts])
        wt = np.concatenate([(hi - lo) / 2 * w for lo, hi in parts])
        r = z * np.tan(th)
        dr = z / np.cos(th) ** 2 * wt
        # σ_xz = P2(r, z) + P3(r, z) cos²θ: its mean over θ is the mean of θ = 0 and θ = 90°
        f0 = s.stress(r, 0 * r, z, part="friction")
        f90 = s.stress(0 * r, r, z, part="friction")
        Qx = np.sum(2 * np.pi * r * 0.5 * (f0.sxz + f90.sxz) * dr)
        assert abs(Qx / s.tangential_force - 1) <= tol.STRESS_EQUILIBRIUM


def test_body_two_is_mirrored_and_takes_its_poisson_ratio():
    c = contact(materials=(STEEL, ALU))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ValidityWarning)
        s = c.tangential(force=F, tangential_force=0.5 * MU * F)
    a = s.normal.radius
    X, Y, Z = PTS.T * a
    one = s.stress(X, Y, Z, body=1, part="friction")
    two = s.stress(X, Y, Z, body=2, part="friction")
    assert two.meta["nu"] == 0.33 and one.meta["nu"] == 0.3
    # σ_zz, σ_xz, σ_yz do not depend on ν; the in-plane components do
    for k in ("szz", "sxz", "syz"):
        np.testing.assert_allclose(getattr(two, k), -getattr(one, k), rtol=1e-12, atol=1e-6)
    assert not np.allclose(two.sxx, -one.sxx)


def test_negative_shift_flips_the_shear_part():
    c = contact()
    s1 = c.tangential(force=F, displacement=2e-7)
    s2 = c.tangential(force=F, displacement=-2e-7)
    a = s1.normal.radius
    X, Y, Z = PTS.T * a
    f1, f2 = s1.stress(X, Y, Z, part="friction"), s2.stress(X, Y, Z, part="friction")
    for k in ("sxx", "syy", "szz", "sxy", "sxz", "syz"):
        assert np.array_equal(getattr(f2, k), -getattr(f1, k))


def test_max_stress_and_plane_grid():
    s = contact().tangential(force=F, tangential_force=MU * F)
    a = s.normal.radius
    m = s.max_stress("von_mises")
    g = s.stress_field(grid=(np.linspace(-2 * a, 2 * a, 81), np.linspace(0, 2 * a, 41)))
    assert g.shape == (41, 81)
    assert m.value >= np.max(g.von_mises) * (1 - 1e-12)
    back = s.stress(m.meta["x"], m.meta["y"], m.z)
    assert float(back.von_mises) == pytest.approx(m.value, rel=1e-12)
    # the largest tension lies on the surface at the edge x = +a: body 1 carries σ_xz = +μp,
    # i.e. the traction acting on it points along -x, and the surface is stretched behind it
    t = s.max_stress("max_principal")
    assert t.z <= 1e-3 * a and abs(t.meta["x"] / a - 1) <= 1e-3


def test_combined_state_is_the_sum_of_its_parts():
    c = contact()
    n = c.normal(force=F)
    a = n.radius
    sh = c.tangential(force=F, tangential_force=0.2 * MU * F)
    tw = c.torsion(force=F, torque=0.2 * MU * F * a, method="exact")
    X, Y, Z = PTS.T * a
    with warnings.catch_warnings(record=True) as seen:
        warnings.simplefilter("always")
        tot = combined_stress(X, Y, Z, tangential=sh, torsion=tw)
    parts = [to_cartesian(n.stress(np.hypot(X, Y), Z), X, Y),
             [getattr(sh.stress(X, Y, Z, part="friction"), k)
              for k in ("sxx", "syy", "szz", "sxy", "sxz", "syz")],
             to_cartesian(tw.stress(np.hypot(X, Y), Z, part="friction"), X, Y)]
    for i, k in enumerate(("sxx", "syy", "szz", "sxy", "sxz", "syz")):
        want = parts[0][i] + parts[1][i] + parts[2][i]
        np.testing.assert_allclose(getattr(tot, k), want, rtol=1e-13,
                                   atol=1e-13 * np.max(np.abs(want)))
    # both slip annuli reach the edge, where each traction is μp: their sum exceeds the friction
    # limit there, and the superposition says so (the decoupling assumption fails at the edge)
    assert [w for w in seen if "friction limit" in str(w.message)]
    assert any("friction limit" in n for n in tot.notes)
    # equilibrium of each resultant through a depth: F_x from σ_xz, torque from the θ-part
    t, w = np.polynomial.legendre.leggauss(400)
    z = 0.5 * a
    th_a = np.arctan(a / z)
    bits = [(0.0, th_a), (th_a, 0.5 * np.pi * (1 - 1e-12))]
    th = np.concatenate([lo + (hi - lo) * (t + 1) / 2 for lo, hi in bits])
    wt = np.concatenate([(hi - lo) / 2 * w for lo, hi in bits])
    r = z * np.tan(th)
    dr = z / np.cos(th) ** 2 * wt
    ang = np.linspace(0, 2 * np.pi, 16, endpoint=False)          # exact for cos²θ, sin²θ
    R, A = np.meshgrid(r, ang, indexing="ij")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ValidityWarning)
        f = combined_stress(R * np.cos(A), R * np.sin(A), z, tangential=sh, torsion=tw)
    Fx = np.sum(2 * np.pi * r * np.mean(f.sxz, axis=1) * dr)
    Fz = np.sum(2 * np.pi * r * np.mean(f.szz, axis=1) * dr)
    s_tz = -f.sxz * np.sin(A) + f.syz * np.cos(A)
    M = np.sum(2 * np.pi * r**2 * np.mean(s_tz, axis=1) * dr)
    assert abs(Fx / sh.tangential_force - 1) <= tol.STRESS_EQUILIBRIUM
    assert abs(Fz / -F - 1) <= tol.STRESS_EQUILIBRIUM
    assert abs(M / tw.torque - 1) <= tol.STRESS_EQUILIBRIUM


def test_combined_state_checks_its_states():
    c = contact()
    a = c.normal(force=F).radius
    sh = c.tangential(force=F, tangential_force=0.8 * MU * F)
    tw = c.torsion(force=F, torque=0.3 * MU * F * a, method="exact")
    n = c.normal(force=F)
    with warnings.catch_warnings():
        warnings.simplefilter("error")        # a shift alone on a normal load: no warning
        f = combined_stress(0.5 * a, 0.1 * a, 0.2 * a, normal=n, tangential=sh)
    assert f.notes == ()
    want = sh.stress(0.5 * a, 0.1 * a, 0.2 * a)
    assert float(f.von_mises) == pytest.approx(float(want.von_mises), rel=1e-14)
    other = c.tangential(force=2 * F, tangential_force=0.1 * F)
    with pytest.raises(ParameterError, match="one normal load"):
        combined_stress(0.0, 0.0, 1e-5, tangential=other, torsion=tw)
    with pytest.raises(ParameterError):
        combined_stress(0.0, 0.0, 1e-5)


@pytest.mark.parametrize("kw, exc", [
    (dict(z=-1e-6), ParameterError), (dict(z=np.nan), ParameterError),
    (dict(x=np.nan), ParameterError), (dict(body=3), ParameterError),
    (dict(part="normal"), ParameterError)])
def test_bad_input_raises(kw, exc):
    s = contact().tangential(force=F, tangential_force=0.1 * F)
    args = dict(x=1e-5, y=0.0, z=1e-5)
    args.update(kw)
    with pytest.raises(exc) as info:
        s.stress(**args)
    assert isinstance(info.value, ContactlabError)


def test_arrays_of_states_and_rigid_bodies_are_refused():
    s = contact().tangential(force=F, tangential_force=[0.1 * F, 0.2 * F])
    with pytest.raises(NotSupportedError):
        s.stress(0.0, 0.0, 1e-5)
    rigid = cl.Contact(cl.profiles.Paraboloid(R=0.01), materials=(STEEL, cl.Rigid()),
                       friction=MU).tangential(force=F, tangential_force=0.1 * F)
    with pytest.raises(NotSupportedError):
        rigid.stress(0.0, 0.0, 1e-5, body=2)
    assert np.isfinite(float(rigid.stress(0.0, 0.0, 1e-5, body=1).von_mises))


def test_measured_paraboloid_reproduces_cattaneo_mindlin_within_its_error():
    # a 400-point cubic table of a paraboloid under partial slip against the Cattaneo–Mindlin
    # field written from Hamilton's closed form: the sliding field of the whole contact minus
    # (c/a) times that of the stick circle (independent of the library's kernels)
    R = 0.01
    rt = np.linspace(0, 3 * contact().normal(force=F).radius, 400)
    table = cl.profiles.Tabulated(rt, rt**2 / (2 * R), interpolation="cubic")
    sh = contact().tangential(force=F, tangential_force=0.6 * MU * F)
    st = contact(table).tangential(force=F, tangential_force=0.6 * MU * F)
    a, c = sh.normal.radius, sh.stick_radius
    p0 = 3 * F / (2 * np.pi * a**2)
    pts = np.concatenate([PTS, [(0.6, 0.3, 0.1), (0.2, -0.1, 0.05), (0.7, 0.0, 0.02)]])
    X, Y, Z = pts.T
    fr = st.stress(X * a, Y * a, Z * a, part="friction")
    assert fr.meta["route"].endswith("(table)")
    outer = ref.hamilton_shear(X, Y, Z, 0.3)
    inner = ref.hamilton_shear(X * a / c, Y * a / c, Z * a / c, 0.3)
    # the table's own contact and stick radii differ from Hertz's by its interpolation error
    da = max(abs(st.normal.radius / a - 1), abs(st.stick_radius / c - 1))
    for k in outer:
        want = -MU * p0 * (outer[k] - c / a * inner[k])
        assert np.all(np.abs(getattr(fr, k) - want) <= fr.error + 4 * da * p0), k
    assert fr.meta["error_estimate"] < 1e-3          # measured 1.1e-5
    # equilibrium through a plane: ∫ σ_xz dA = Q (as in test_force_equilibrium_at_every_depth)
    t, w = np.polynomial.legendre.leggauss(400)
    z = 0.3 * a
    th_a = np.arctan(a / z)
    parts = [(0.0, th_a), (th_a, 0.5 * np.pi * (1 - 1e-12))]
    th = np.concatenate([lo + (hi - lo) * (t + 1) / 2 for lo, hi in parts])
    wt = np.concatenate([(hi - lo) / 2 * w for lo, hi in parts])
    r = z * np.tan(th)
    dr = z / np.cos(th) ** 2 * wt
    f0 = st.stress(r, 0 * r, z, part="friction")
    f90 = st.stress(0 * r, r, z, part="friction")
    Qx = np.sum(2 * np.pi * r * 0.5 * (f0.sxz + f90.sxz) * dr)
    # to the table route's accuracy: the quadrature of its slope (measured 3.8e-8 of Q), within
    # the field's own estimate carried through the plane
    dQ = np.sum(2 * np.pi * r * 0.5 * (f0.error + f90.error) * dr)
    Q = st.tangential_force
    assert abs(Qx - Q) <= dQ + tol.STRESS_EQUILIBRIUM * Q
    assert dQ < 3e-5 * Q                               # measured 3.0e-6


def test_without_friction_the_shifted_punch():
    # no friction limit: nothing slips, the traction is the rigidly shifted punch's
    # q = Q/(2π a sqrt(a² - r²)) (closed form, written here), carried through every depth
    nofr = cl.Contact(cl.profiles.Paraboloid(R=0.01), materials=(STEEL, STEEL), friction=None)
    s = nofr.tangential(force=F, displacement=2e-8)
    a, Q = s.normal.radius, s.tangential_force
    r = np.array([0.0, 0.2, 0.6, 0.95]) * a
    f = s.stress(r, 0.3 * r, 0.0, part="friction")
    rho = np.hypot(r, 0.3 * r)
    want = Q / (2 * np.pi * a * np.sqrt(a * a - rho * rho))
    np.testing.assert_allclose(f.sxz, want, rtol=tol.STRESS_TANGENTIAL_SURFACE, atol=0)
    assert np.all(np.abs(f.syz) <= tol.STRESS_TANGENTIAL_SURFACE * want)
    assert "no-slip" in f.meta["route"]
    t, w = np.polynomial.legendre.leggauss(400)
    for z in (0.1 * a, 0.7 * a):
        th_a = np.arctan(a / z)
        parts = [(0.0, th_a), (th_a, 0.5 * np.pi * (1 - 1e-12))]
        th = np.concatenate([lo + (hi - lo) * (t + 1) / 2 for lo, hi in parts])
        wt = np.concatenate([(hi - lo) / 2 * w for lo, hi in parts])
        rr = z * np.tan(th)
        dr = z / np.cos(th) ** 2 * wt
        f0 = s.stress(rr, 0 * rr, z, part="friction")
        f90 = s.stress(0 * rr, rr, z, part="friction")
        Qx = np.sum(2 * np.pi * rr * 0.5 * (f0.sxz + f90.sxz) * dr)
        assert Qx == pytest.approx(Q, rel=tol.STRESS_EQUILIBRIUM)
    two = s.stress(r, 0.3 * r, 0.1 * a, part="friction", body=2)
    np.testing.assert_array_equal(two.sxz, -s.stress(r, 0.3 * r, 0.1 * a, part="friction").sxz)
    tot = s.stress(r, 0.3 * r, 0.1 * a)
    assert np.all(tot.szz < 0)                   # the normal preload is included


def test_shear_without_friction_is_the_shifted_punch_and_the_field_surface():
    """Without friction nothing slips: shear() is Q/(2π a sqrt(a² - r²)) with Q = 2 G* a u
    (the closed form, written here), its integral over the contact is Q, and the stress
    field's surface σ_xz equals it."""
    nofr = cl.Contact(cl.profiles.Paraboloid(R=0.01), materials=(STEEL, STEEL), friction=None)
    st = nofr.tangential(force=F, displacement=1e-7)
    a = float(st.normal.radius)
    Q = 2 * nofr.moduli.tangential * a * 1e-7
    assert float(st.tangential_force) == pytest.approx(Q, rel=1e-14)
    r = np.array([0.0, 0.2, 0.5, 0.9, 0.99]) * a
    tau = np.asarray(st.shear(r))
    np.testing.assert_allclose(tau, Q / (2 * np.pi * a * np.sqrt(a * a - r * r)), rtol=1e-14)
    assert np.asarray(st.shear(np.array([a, 1.5 * a]))).tolist() == [np.inf, 0.0]
    # ∫ 2π r τ dr with r = a sin t (the edge singularity removed): Q
    t, w = np.polynomial.legendre.leggauss(40)
    th = (t + 1) * np.pi / 4
    rr = a * np.sin(th)
    integral = np.sum(2 * np.pi * rr * np.asarray(st.shear(rr)) * a * np.cos(th) * w) * np.pi / 4
    assert integral == pytest.approx(Q, rel=1e-12)
    f = st.stress(r[1:4], 0.0 * r[1:4], 0.0, part="friction")
    np.testing.assert_allclose(f.sxz, tau[1:4], rtol=1e-12)
    back = nofr.tangential(force=F, displacement=-1e-7)
    np.testing.assert_array_equal(np.asarray(back.shear(r)), -tau)
