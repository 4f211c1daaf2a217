"""Subsurface stresses at snapshots of ``contact.simulate`` (issue 31: fields along a load path
with a varying normal force and a twist).

The torsional part is the field of the step's own surface traction (the ring solver's); it is
checked by equilibrium at depth (the torque carried through a plane equals the torque of the
surface traction, independent of the superposition), by its surface values (the traction
itself) and, at steps where the force has not yet varied, against ``TwistHistory.stress``
(Jäger's closed-form slip function, an independent route).
"""
from __future__ import annotations

import warnings

import numpy as np
import pytest

import contactlab as cl
from contactlab.errors import (ContactlabError, EffectNotPlannedError, NotSupportedError,
                              ParameterError, ValidityWarning)
from tests import tolerances as tol

R, MU, F = 0.01, 0.3, 10.0
MAT = (cl.Elastic(E=210e9, nu=0.3), cl.Rigid())
C = cl.Contact(cl.profiles.Paraboloid(R=R), materials=MAT, friction=MU)
A0 = C.normal(force=F).radius
S = MU * F / (C.moduli.torsional * A0 * A0)          # twist scale of the slip onset
N = 30
_T = np.arange(1, N + 1) / N
FORCE = np.concatenate([np.full(10, F), F * (1 + 0.3 * np.sin(2 * np.pi * _T[10:]))])
TWIST = np.concatenate([np.linspace(0.05, 0.6, 10) * S, 0.6 * S * np.cos(2 * np.pi * _T[10:])])


@pytest.fixture(scope="module")
def run():
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ValidityWarning)
        return C.simulate(cl.LoadPath.from_arrays(force=FORCE, twist=TWIST), method="exact",
                          snapshots=[9, 20])


def _plane(res, k, z):
    """Force and torque carried through the plane at depth ``z`` (trapezoid to 10⁴ a) and the
    bound of the field's own estimate on them."""
    a = res.snapshots[k]["radius"]
    r = np.concatenate([np.linspace(0.0, a, 800, endpoint=False), a * np.geomspace(1, 1e4, 6000)])
    f = res.stress(r, z, step=k)
    Fz = 2 * np.pi * np.trapezoid(f.szz * r, r)
    M = 2 * np.pi * np.trapezoid(f.stz * r * r, r)
    dM = 2 * np.pi * np.trapezoid(f.error * r * r, r)
    return Fz, M, dM


def _traction_torque(snap):
    r, t = snap["r"], snap["shear_torsion"]
    keep = r < snap["radius"]
    r, t = np.concatenate([[0.0], r[keep], [snap["radius"]]]), np.concatenate([[0.0], t[keep],
                                                                              [0.0]])
    return 2 * np.pi * np.trapezoid(t * r * r, r)     # exact: the traction is piecewise linear


@pytest.mark.parametrize("k", [9, 20])
@pytest.mark.parametrize("depth", [0.1, 0.5])
def test_force_and_torque_through_a_plane(run, k, depth):
    snap = run.snapshots[k]
    Fz, M, dM = _plane(run, k, depth * snap["radius"])
    assert Fz == pytest.approx(-run.force[k], rel=tol.PATH_STRESS_PLANE)
    M0 = _traction_torque(snap)
    assert abs(M - M0) <= dM + tol.PATH_STRESS_PLANE * abs(M0)
    assert abs(M - M0) < tol.PATH_STRESS_TORQUE * abs(M0)
    # the snapshot's traction carries the step's torque to the ring solver's accuracy
    assert M0 == pytest.approx(run.torque[k], rel=tol.PATH_STRESS_TORQUE)


@pytest.mark.parametrize("k", [9, 20])
def test_surface_values_are_the_step_traction_and_pressure(run, k):
    snap = run.snapshots[k]
    a = snap["radius"]
    keep = snap["r"] < 0.98 * a
    r = snap["r"][keep]
    f = run.stress(r, 0.0, step=k)
    t = snap["shear_torsion"][keep]
    assert np.all(np.abs(f.stz - t) <= f.error + tol.PATH_STRESS_EXCESS * np.max(np.abs(t)))
    p = np.asarray(C.normal(depth=snap["depth"]).pressure(r))
    assert np.allclose(f.szz, -p, rtol=tol.PATH_STRESS_NORMAL, atol=0.0)


def test_at_the_constant_force_step_it_is_the_twist_history_field(run):
    hist = C.twist_history(twist=TWIST[:10], force=F)
    r = np.linspace(0.0, 2.0 * A0, 9)[:, None]
    z = np.array([0.05, 0.3, 0.8])[None, :] * A0
    f, g = run.stress(r, z, step=9), hist.stress(r, z, step=9)
    for name in ("srr", "stt", "szz", "srz"):
        np.testing.assert_allclose(getattr(f, name), getattr(g, name),
                                   rtol=tol.PATH_STRESS_NORMAL, atol=0.0)
    top = np.max(np.abs(g.stz))
    for name in ("stz", "srt"):
        d = np.abs(getattr(f, name) - getattr(g, name))
        assert np.all(d <= f.error + g.error + tol.PATH_STRESS_EXCESS * top), name
        assert np.max(d) < tol.PATH_STRESS_TORQUE * top, name


def test_friction_part_and_body_two(run):
    r, z = np.array([0.2, 0.7]) * A0, 0.2 * A0
    tot, fr = run.stress(r, z, step=20), run.stress(r, z, step=20, part="friction")
    assert np.all(fr.szz == 0.0) and np.array_equal(fr.stz, tot.stz)
    with pytest.raises(NotSupportedError, match="Poisson"):
        run.stress(r, z, step=20, body=2)                  # body 2 is rigid
    assert np.array_equal(run.stress(r, z, step=-10).stz, tot.stz)


def test_bad_calls_raise(run):
    with pytest.raises(EffectNotPlannedError, match="snapshot"):
        run.stress(0.0, 1e-5, step=3)
    with pytest.raises(ParameterError, match="step"):
        run.stress(0.0, 1e-5, step=N)
    with pytest.raises(ParameterError, match="part"):
        run.stress(0.0, 1e-5, step=9, part="normal")
    with pytest.raises(ContactlabError):
        run.stress(0.0, -1e-5, step=9)
    shifted = C.simulate(cl.LoadPath.from_arrays(force=FORCE[:3], displacement=[0, 1e-8, 2e-8]),
                         snapshots=[2])
    with pytest.raises(ParameterError, match="shift"):       # it takes (x, y, z)
        shifted.stress(0.0, 1e-5, step=2)


def test_mdr_route_uses_its_own_traction():
    # the MDR snapshot's traction (cell midpoints ``x``) at the constant-force step
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ValidityWarning)
        res = C.simulate(cl.LoadPath.from_arrays(force=FORCE[:10], twist=TWIST[:10]),
                         method="mdr", snapshots=[9])
    snap = res.snapshots[9]
    a = snap["radius"]
    keep = snap["x"] < 0.98 * a
    t = snap["shear_torsion"][keep]
    f = res.stress(snap["x"][keep], 0.0, step=9)
    assert np.all(np.abs(f.stz - t) <= f.error + tol.PATH_STRESS_EXCESS * np.max(np.abs(t)))
    inside = snap["x"] < a
    r = np.concatenate([[0.0], snap["x"][inside], [a]])
    M0 = 2 * np.pi * np.trapezoid(np.concatenate([[0.0], snap["shear_torsion"][inside], [0.0]])
                                  * r * r, r)
    Fz, M, _ = _plane(res, 9, 0.5 * a)
    assert Fz == pytest.approx(-res.force[9], rel=tol.PATH_STRESS_PLANE)
    assert M == pytest.approx(M0, rel=tol.PATH_STRESS_TORQUE)     # measured 2.1e-4
