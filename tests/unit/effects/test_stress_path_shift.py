"""Subsurface stresses at snapshots of ``contact.simulate`` along paths with a tangential shift
(issue 31: fields along a load path whose normal force and shift vary).

References independent of the superposition under test: the Cattaneo–Mindlin field written from
Hamilton's closed form (tests/reference/stress_tangential.py) at a constant-force step, the
field of ``ShiftHistory.stress`` (Masing sum of the library's Cattaneo–Mindlin states, another
route) at the same state, and equilibrium: the tangential and normal forces carried through
planes at several depths equal the step's ``Q`` and ``F`` (no formula for the field needed).
"""
from __future__ import annotations

import warnings

import numpy as np
import pytest

import contactlab as cl
from contactlab.errors import NotSupportedError, ParameterError, ValidityWarning
from tests import tolerances as tol
from tests.reference import stress_tangential as ref

R, MU, F = 0.01, 0.3, 10.0
MAT = (cl.Elastic(E=210e9, nu=0.3), cl.Rigid())
C = cl.Contact(cl.profiles.Paraboloid(R=R), materials=MAT, friction=MU)
A0 = C.normal(force=F).radius
P0 = 3 * F / (2 * np.pi * A0 * A0)
U1 = float(C.tangential(force=F, tangential_force=0.6 * MU * F).displacement)
N = 20
_T = np.arange(N) / (N - 1)
FORCE = F * (1 + 0.4 * np.sin(2 * np.pi * _T))
DISP = U1 * np.sin(1.5 * np.pi * _T)          # loads, reverses past zero
PTS = np.array([(0.3, 0.2, 0.1), (0.9, 0.1, 0.05), (1.2, 0.0, 0.3), (0.0, 0.5, 0.5),
                (0.5, 0.5, 0.2), (0.1, 0.0, 0.02), (-0.7, 0.3, 0.15), (0.6, -0.2, 0.8)])


def _quiet(fn, *args, **kw):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ValidityWarning)
        return fn(*args, **kw)


@pytest.fixture(scope="module")
def held():
    """Constant force, the shift rising from 0 to 60 % of the sliding force."""
    return _quiet(C.simulate, cl.LoadPath.from_arrays(force=np.full(6, F),
                                                      displacement=np.linspace(0, U1, 6)),
                  snapshots=[5])


@pytest.fixture(scope="module")
def varying():
    return _quiet(C.simulate, cl.LoadPath.from_arrays(force=FORCE, displacement=DISP),
                  snapshots=[6, 14])


_GL = np.polynomial.legendre.leggauss(400)


def _plane(res, k, z, part="total", torque=False):
    """Tangential and normal force carried through the plane at depth ``z`` and the bound of
    the field's own estimate on the first (or the torque): Gauss–Legendre in ``θ = atan(r/z)`` (split at the
    contact edge), the mean over the angles 0, 90, 180 and 270° exact for the field's
    ``cos θ``/``cos² θ`` dependence."""
    t, w = _GL
    th_a = np.arctan(res.radius[k] / z)
    parts = [(0.0, th_a), (th_a, 0.5 * np.pi * (1 - 1e-12))]
    th = np.concatenate([lo + (hi - lo) * (t + 1) / 2 for lo, hi in parts])
    wt = np.concatenate([(hi - lo) / 2 * w for lo, hi in parts])
    r = z * np.tan(th)
    dr = z / np.cos(th) ** 2 * wt
    ang = np.array([0.0, 0.5, 1.0, 1.5]) * np.pi
    f = res.stress(r[:, None] * np.cos(ang), r[:, None] * np.sin(ang), z, step=k, part=part)

    def integral(v):
        return float(np.sum(2 * np.pi * r * np.mean(v, axis=1) * dr))

    if torque:    # ∫ (x σ_yz - y σ_xz) dA = ∫ r σ_θz dA
        X, Y = r[:, None] * np.cos(ang), r[:, None] * np.sin(ang)
        return integral(X * f.syz - Y * f.sxz)
    return integral(f.sxz), integral(f.szz), integral(f.error)


def test_constant_force_step_is_cattaneo_mindlin(held):
    # the sliding field of the whole contact minus (c/a) times that of the stick circle, from
    # Hamilton's closed form, at the step's own contact and stick radii
    a, c = held.radius[5], held.stick_radius[5]
    assert held.tangential_force[5] == pytest.approx(0.6 * MU * F, rel=1e-6)
    X, Y, Z = PTS.T
    f = held.stress(X * a, Y * a, Z * a, step=5, part="friction")
    outer = ref.hamilton_shear(X, Y, Z, 0.3)
    inner = ref.hamilton_shear(X * a / c, Y * a / c, Z * a / c, 0.3)
    for k in outer:
        want = -MU * P0 * (outer[k] - c / a * inner[k])
        d = np.abs(getattr(f, k) - want)
        assert np.all(d <= f.error + tol.PATH_SHIFT_EXCESS * P0), k
        assert np.max(d) < tol.PATH_SHIFT_FIELD * P0, k
    assert f.meta["error_estimate"] < tol.PATH_SHIFT_ESTIMATE
    assert f.meta["step"] == 5 and "shift" in f.meta["route"]


def test_constant_force_step_is_the_shift_history_field(held):
    hist = C.shift_history(displacement=np.linspace(0, U1, 6), force=F)
    X, Y, Z = (PTS * A0).T
    f, g = held.stress(X, Y, Z, step=5), hist.stress(X, Y, Z, step=5)
    for k in ("sxx", "syy", "szz", "sxy", "sxz", "syz"):
        d = np.abs(getattr(f, k) - getattr(g, k))
        assert np.all(d <= f.error + g.error + tol.PATH_SHIFT_EXCESS * P0), k
        assert np.max(d) < tol.PATH_SHIFT_FIELD * P0, k


@pytest.mark.parametrize("depth", [0.1, 0.5, 1.5])
def test_forces_through_planes_at_constant_force(held, depth):
    Q, Fz, dQ = _plane(held, 5, depth * A0)
    Qk = held.tangential_force[5]
    assert Fz == pytest.approx(-F, rel=tol.PATH_STRESS_PLANE)
    assert abs(Q - Qk) <= dQ + tol.PATH_STRESS_PLANE * Qk
    assert abs(Q - Qk) < tol.PATH_SHIFT_PLANE * Qk


@pytest.mark.parametrize("k", [6, 14])
@pytest.mark.parametrize("depth", [0.1, 1.5])
def test_forces_through_planes_under_a_varying_force(varying, k, depth):
    # step 6: loading at a higher force; step 14: after the reversal, at a lower force
    Q, Fz, dQ = _plane(varying, k, depth * varying.radius[k])
    Qk = varying.tangential_force[k]
    assert Fz == pytest.approx(-varying.force[k], rel=tol.PATH_STRESS_PLANE)
    assert abs(Q - Qk) <= dQ + tol.PATH_STRESS_PLANE * abs(Qk)
    assert abs(Q - Qk) < tol.PATH_SHIFT_PLANE * abs(Qk)


@pytest.mark.parametrize("k", [6, 14])
def test_surface_values_are_the_step_traction(varying, k):
    snap = varying.snapshots[k]
    keep = snap["x"] < 0.98 * snap["radius"]
    x = snap["x"][keep][::7]
    q = snap["shear_tangential"][keep][::7]
    f = varying.stress(x, 0.0, 0.0, step=k, part="friction")
    assert np.all(np.abs(f.sxz - q) <= f.error + tol.PATH_SHIFT_EXCESS * np.max(np.abs(q)))
    assert np.all(f.szz == 0.0)


def test_shift_with_twist_carries_both_loads_through_a_plane():
    # two spring families (approximate=True): the field superposes the normal part and both
    # tractions; the force, tangential force and torque through a plane are the step's
    S = MU * F / (C.moduli.torsional * A0 * A0)
    path = cl.LoadPath.from_arrays(force=np.full(6, F), displacement=np.linspace(0, U1, 6),
                                   twist=np.linspace(0, 0.3 * S, 6))
    both = _quiet(C.simulate, path, snapshots=[5], approximate=True)
    Q, Fz, dQ = _plane(both, 5, 0.5 * A0)
    assert Fz == pytest.approx(-F, rel=tol.PATH_STRESS_PLANE)
    assert abs(Q - both.tangential_force[5]) < tol.PATH_SHIFT_PLANE * both.tangential_force[5]
    # the torque of the snapshot's torsional traction (the MDR springs' traction, whose torque
    # is the route's own, as in test_stress_path.py's MDR test)
    snap = both.snapshots[5]
    inside = snap["x"] < snap["radius"]
    r = np.concatenate([[0.0], snap["x"][inside], [snap["radius"]]])
    t = np.concatenate([[0.0], snap["shear_torsion"][inside], [0.0]])
    M0 = 2 * np.pi * np.trapezoid(t * r * r, r)
    M = _plane(both, 5, 0.5 * A0, torque=True)
    assert M == pytest.approx(M0, rel=tol.PATH_STRESS_TORQUE)


def test_body_two_and_bad_calls(held):
    steel = cl.Contact(cl.profiles.Paraboloid(R=R), materials=(MAT[0], MAT[0]), friction=MU)
    res = _quiet(steel.simulate, cl.LoadPath.from_arrays(force=np.full(3, F),
                                                         displacement=[0.0, 2e-8, 4e-8]),
                 snapshots=[2])
    X, Y, Z = (PTS[:3] * A0).T
    one = res.stress(X, Y, Z, step=2, part="friction")
    two = res.stress(X, Y, Z, step=2, part="friction", body=2)
    np.testing.assert_array_equal(two.sxz, -one.sxz)        # same ν: the mirrored traction
    with pytest.raises(ParameterError, match=r"\(x, y, z\)"):
        held.stress(0.0, 1e-5, step=5)
    with pytest.raises(NotSupportedError, match="Poisson"):
        held.stress(0.0, 0.0, 1e-5, step=5, body=2)
    # a paraboloid pressed to its wall, below the slip limit at the edge: the singular edge
    # traction is not sampled (a plain flat punch is: test_flat_punch_with_friction_...)
    walled = cl.profiles.Paraboloid(R=0.01) + cl.profiles.FlatPunch(radius=1e-4)
    flat = cl.Contact(walled, materials=MAT, friction=MU)
    stuck = _quiet(flat.simulate, cl.LoadPath.from_arrays(depth=[3e-6] * 3,
                                                          displacement=[0.0, 1e-9, 2e-9]),
                   snapshots=[2])
    with pytest.raises(NotSupportedError, match="sticks at the contact edge"):
        stuck.stress(0.0, 0.0, 1e-5, step=2)


def test_a_path_without_shift_in_cartesian_points():
    # (x, y, z) on a twisted path: the cylindrical field rotated (to_cartesian)
    S = MU * F / (C.moduli.torsional * A0 * A0)
    res = _quiet(C.simulate, cl.LoadPath.from_arrays(force=np.full(4, F),
                                                     twist=np.linspace(0, 0.3 * S, 4)),
                 snapshots=[3])
    X, Y, Z = (PTS * A0).T
    f = res.stress(X, Y, Z, step=3)
    g = res.stress(np.hypot(X, Y), Z, step=3)
    c, s = X / np.hypot(X, Y), Y / np.hypot(X, Y)
    np.testing.assert_array_equal(f.szz, g.szz)
    np.testing.assert_allclose(f.sxz, g.srz * c - g.stz * s, rtol=1e-12, atol=1e-12 * P0)
    np.testing.assert_allclose(f.syz, g.srz * s + g.stz * c, rtol=1e-12, atol=1e-12 * P0)
    np.testing.assert_array_equal(f.error, g.error)


def test_flat_punch_with_friction_under_a_varying_force():
    """Every spring of a flat punch sticks or slides with the others: at any step the shift
    traction is Q_k/(2π a sqrt(a² - r²)) (the closed form, written here), sticking (step 3) or
    sliding (step 6) alike; the tangential force through a plane is Q_k."""
    b = 1e-3
    punch = cl.Contact(cl.profiles.FlatPunch(radius=b), materials=MAT, friction=MU)
    force = F * np.array([1.0, 1.0, 1.2, 1.2, 0.8, 0.6, 0.6])
    u_slide = MU * F / (2 * punch.moduli.tangential * b)
    disp = u_slide * np.array([0.0, 0.3, 0.6, 0.9, 0.9, 1.2, 1.5])
    res = _quiet(punch.simulate, cl.LoadPath.from_arrays(force=force, displacement=disp),
                 snapshots=[3, 6])
    assert abs(res.tangential_force[3]) < MU * force[3]            # stuck
    assert res.tangential_force[6] == pytest.approx(MU * force[6], rel=1e-12)   # sliding
    for k in (3, 6):
        Qk = float(res.tangential_force[k])
        r = np.array([0.0, 0.3, 0.6, 0.9]) * b
        f = res.stress(r, 0.0 * r, 0.0, step=k, part="friction")
        want = Qk / (2 * np.pi * b * np.sqrt(b * b - r * r))
        np.testing.assert_allclose(f.sxz, want, rtol=1e-12)
        Q, Fz, dQ = _plane(res, k, 0.5 * b)
        assert Q == pytest.approx(Qk, rel=tol.PATH_STRESS_PLANE)
        assert Fz == pytest.approx(-force[k], rel=tol.PATH_STRESS_PLANE)
