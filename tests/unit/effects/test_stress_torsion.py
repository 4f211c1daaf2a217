"""Subsurface stress fields of torsion states (issue 31, part B)."""
from __future__ import annotations

import warnings

import numpy as np
import pytest

import contactlab as cl
from contactlab.errors import ParameterError, ValidityWarning
from contactlab.physics import stress as kern
from tests import tolerances as tol
from tests.reference import stress as ref

STEEL = cl.Elastic(E=210e9, nu=0.3)
ALU = cl.Elastic(E=70e9, nu=0.33)
F = 100.0


def contact(profile=None, materials=(STEEL, STEEL)):
    return cl.Contact(profile or cl.profiles.Paraboloid(R=0.01), materials=materials,
                      friction=0.3)


def states():
    c = contact()
    a = c.normal(force=F).radius
    M_half = 0.5 * 3 * np.pi / 16 * 0.3 * F * a
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ValidityWarning)
        return [c.torsion(force=F, twist=1e-4, method="no-slip"),
                c.torsion(force=F, torque=M_half, method="exact"),
                c.torsion(force=F, torque=M_half, method="mdr"),
                contact(cl.profiles.FlatPunch(radius=1e-4)).torsion(depth=1e-6, twist=2e-3,
                                                                      method="exact")]


def test_twisted_punch_against_reissner_sagoci_hankel_integral():
    for X, Z in [(0.3, 0.2), (0.9, 0.5), (1.2, 0.1), (0.5, 1.3), (2.5, 0.4)]:
        stz, srt = kern.twist_kernel(X, Z, 1.0)
        assert abs(stz - ref.twisted_punch_hankel(X, Z, 1.0, 1)) <= tol.STRESS_TWIST_HANKEL
        assert abs(srt - ref.twisted_punch_hankel(X, Z, 1.0, 2)) <= tol.STRESS_TWIST_HANKEL


@pytest.mark.parametrize("i", range(4))
def test_surface_values_equal_the_shear_traction(i):
    s = states()[i]
    a = s.radius
    r = np.array([0.05, 0.3, 0.6, 0.85, 0.97]) * a
    f = s.stress(r, 0.0, part="friction")
    tau = s.shear(r)
    np.testing.assert_allclose(f.stz, tau, rtol=0,
                               atol=tol.STRESS_TORSION_SURFACE * np.max(np.abs(tau)))
    assert np.all(f.szz == 0) and np.all(f.srr == 0)
    assert 0 < s.stick_radius <= a


@pytest.mark.parametrize("i", range(4))
def test_torque_equilibrium_at_every_depth(i):
    s = states()[i]
    a = s.radius
    t, w = np.polynomial.legendre.leggauss(400)
    for zr in (0.1, 0.5, 2.0):
        z = zr * a
        th_a = np.arctan(a / z)
        parts = [(0.0, th_a), (th_a, 0.5 * np.pi * (1 - 1e-12))]
        th = np.concatenate([lo + (hi - lo) * (t + 1) / 2 for lo, hi in parts])
        wt = np.concatenate([(hi - lo) / 2 * w for lo, hi in parts])
        r = z * np.tan(th)
        dr = z / np.cos(th) ** 2 * wt
        f = s.stress(r, z, part="friction")
        M = np.sum(2 * np.pi * r**2 * f.stz * dr)
        assert abs(M / s.torque - 1) <= tol.STRESS_EQUILIBRIUM


def test_total_field_is_normal_plus_torsion_and_body_two_is_mirrored():
    c = contact(materials=(STEEL, ALU))
    a = c.normal(force=F).radius
    s = c.torsion(force=F, torque=0.3 * 0.3 * F * a, method="exact")
    r, z = np.array([0.2, 0.7, 1.1]) * a, 0.3 * a
    tot = s.stress(r, z)
    fr = s.stress(r, z, part="friction")
    nrm = c.normal(force=F).stress(r, z)
    for k in ("srr", "stt", "szz", "srz"):
        assert np.array_equal(getattr(tot, k), getattr(nrm, k))
    assert np.array_equal(tot.stz, fr.stz) and np.array_equal(tot.srt, fr.srt)
    two = s.stress(r, z, body=2)
    assert np.array_equal(two.stz, -tot.stz) and np.array_equal(two.srt, -tot.srt)
    assert two.meta["nu"] == 0.33
    # the principal stresses of a full tensor (σ_θz != 0) still bound von Mises
    p = tot.principal
    assert np.all(np.diff(p, axis=-1) <= 0)
    np.testing.assert_allclose(p.sum(-1), tot.srr + tot.stt + tot.szz, rtol=1e-10)


def test_negative_twist_flips_the_torsional_part():
    c = contact()
    a = c.normal(force=F).radius
    s1 = c.torsion(force=F, twist=1e-4, method="no-slip")
    s2 = c.torsion(force=F, twist=-1e-4, method="no-slip")
    f1, f2 = s1.stress(0.5 * a, 0.2 * a), s2.stress(0.5 * a, 0.2 * a)
    assert float(f1.stz) == -float(f2.stz) and float(f1.szz) == float(f2.szz)


def test_max_stress_and_grid():
    s = states()[1]
    m = s.max_stress("von_mises")
    n = s.normal.max_stress("von_mises") if s.normal.shape == () else None
    assert np.isfinite(m.value) and m.value >= n.value * (1 - 1e-9)
    g = s.stress_field(part="friction")
    assert g.shape == (100, 200)


def test_bad_part():
    with pytest.raises(ParameterError, match="part="):
        states()[0].stress(0.0, 0.0, part="both")


@pytest.mark.parametrize("method", ["exact", "mdr"])
@pytest.mark.parametrize("flat", [False, True])
def test_full_sliding(method, flat):
    # the slip annulus reaching the axis (stick_radius=0, infinite twist): the surface value
    # is the state's own traction (μp on the exact model, independent of the superposition)
    # and the torque through a plane the sliding torque
    prof = cl.profiles.FlatPunch(radius=1e-4) if flat else None
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ValidityWarning)       # the MDR model at full sliding
        s = contact(prof).torsion(force=F, stick_radius=0.0, method=method)
    a = float(s._a)
    r = np.array([0.05, 0.2, 0.5, 0.8, 0.95]) * a
    f = s.stress(r, 0.0, part="friction")
    tau = np.asarray(s.shear(r))
    assert np.all(np.abs(f.stz - tau) <= f.error + tol.STRESS_TORSION_SLIDING * np.max(tau))
    assert np.max(np.abs(f.stz - tau)) < tol.STRESS_TORSION_SLIDING * np.max(tau)
    if method == "exact":
        p = np.asarray(s.normal.pressure(r))
        np.testing.assert_allclose(tau, 0.3 * p, rtol=1e-12)
    assert "full sliding" in f.meta["route"]
    t, w = np.polynomial.legendre.leggauss(400)
    z = 0.3 * a
    th_a = np.arctan(a / z)
    parts = [(0.0, th_a), (th_a, 0.5 * np.pi * (1 - 1e-12))]
    th = np.concatenate([lo + (hi - lo) * (t + 1) / 2 for lo, hi in parts])
    wt = np.concatenate([(hi - lo) / 2 * w for lo, hi in parts])
    rr = z * np.tan(th)
    dr = z / np.cos(th) ** 2 * wt
    g = s.stress(rr, z, part="friction")
    M = np.sum(2 * np.pi * rr * rr * g.stz * dr)
    assert M == pytest.approx(s.torque, rel=tol.STRESS_EQUILIBRIUM * 10)


def test_twist_and_shift_surface_stress_a_hair_inside_the_edge_is_finite_and_the_traction():
    # the twisted and sheared punch kernels take x - r like the pressed one: a segment [r, a]
    # ~1e-12 a wide used to put a node on x = r (inf); sigma_tz (sigma_xz) on the surface is the
    # state's shear traction, from its own route
    soft = cl.Elastic(E=1e9, nu=0.3)
    C = cl.Contact(cl.profiles.Sphere(R=1e-3), (soft, soft), friction=0.3)
    tor = C.torsion(force=1.0, twist=1e-4)
    shift = C.tangential(force=1.0, tangential_force=0.1)
    for st, field in ((tor, lambda r: tor.stress(r, 0.0).stz),
                      (shift, lambda r: shift.stress(r, 0.0, 0.0).sxz)):
        a = float(C.normal(force=1.0).radius)
        r = a * (1.0 - np.array([1e-13, 1e-12, 1e-10, 1e-4]))
        with warnings.catch_warnings():
            warnings.simplefilter("error", RuntimeWarning)
            val = field(r)
            err = (tor.stress(r, 0.0) if st is tor else shift.stress(r, 0.0, 0.0)).error
        assert np.all(np.isfinite(val)) and np.all(np.isfinite(err))
        np.testing.assert_array_less(np.abs(val - st.shear(r)), err)
