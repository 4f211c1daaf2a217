"""Subsurface stresses at snapshots of ``contact.simulate`` without a friction limit (no slip):
twisted and shifted paths under a constant and a varying normal force (issue 31).

References: Reissner & Sagoci's twisted punch by its Hankel integral (tests/reference/stress.py)
at a constant force, the surface traction of the tangentially displaced rigid punch
``Q/(2π a sqrt(a² - r²))`` in closed form, and equilibrium through planes: the torque and the
tangential force carried at several depths equal the step's ``M`` and ``Q`` under a varying
force (the ring solver's punches: exact; the springs: to their discretisation).
"""
from __future__ import annotations

import warnings

import numpy as np
import pytest

import contactlab as cl
from contactlab.effects.stress_path_noslip import entry_history, ring_punches
from contactlab.errors import ValidityWarning
from tests import tolerances as tol
from tests.reference import stress as ref

R, F = 0.01, 10.0
MAT = (cl.Elastic(E=210e9, nu=0.3), cl.Rigid())
C = cl.Contact(cl.profiles.Paraboloid(R=R), materials=MAT, friction=None)
A0 = C.normal(force=F).radius
G = C.moduli.torsional
S = 3.0 * F / (G * A0 * A0)       # a twist scale (rad)
N = 30
_T = np.arange(1, N + 1) / N
FORCE = F * (1 + 0.5 * np.sin(2 * np.pi * _T))        # unloads below F and reloads
TWIST = 0.05 * S * np.sin(3 * np.pi * _T)
SHIFT = 1e-7 * np.sin(3 * np.pi * _T)
_GL = np.polynomial.legendre.leggauss(400)


def _quiet(fn, *args, **kw):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ValidityWarning)
        return fn(*args, **kw)


def _nodes(a, z):
    t, w = _GL
    th_a = np.arctan(a / z)
    parts = [(0.0, th_a), (th_a, 0.5 * np.pi * (1 - 1e-12))]
    th = np.concatenate([lo + (hi - lo) * (t + 1) / 2 for lo, hi in parts])
    wt = np.concatenate([(hi - lo) / 2 * w for lo, hi in parts])
    return z * np.tan(th), z / np.cos(th) ** 2 * wt


def _torque(res, k, z):
    r, dr = _nodes(res.radius[k], z)
    f = res.stress(r, z, step=k, part="friction")
    return (float(np.sum(2 * np.pi * r * r * f.stz * dr)),
            float(np.sum(2 * np.pi * r * r * f.error * dr)))


def _shift_force(res, k, z):
    r, dr = _nodes(res.radius[k], z)
    ang = np.array([0.0, 0.5, 1.0, 1.5]) * np.pi
    f = res.stress(r[:, None] * np.cos(ang), r[:, None] * np.sin(ang), z, step=k,
                   part="friction")
    return (float(np.sum(2 * np.pi * r * np.mean(f.sxz, axis=1) * dr)),
            float(np.sum(2 * np.pi * r * np.mean(f.error, axis=1) * dr)))


@pytest.fixture(scope="module", params=["exact", "mdr"])
def twisted(request):
    return _quiet(C.simulate, cl.LoadPath.from_arrays(force=FORCE, twist=TWIST),
                  method=request.param, snapshots=[5, 20, 29])


def test_constant_force_is_reissner_sagoci():
    # force first, then the twist at that force: one rigid twisted punch of radius a
    tw = np.array([0.0, 0.01, 0.02, 0.03]) * S
    for method in ("exact", "mdr"):
        res = _quiet(C.simulate, cl.LoadPath.from_arrays(force=np.full(4, F), twist=tw),
                     method=method, snapshots=[3])
        a = res.radius[3]
        unit = 4 * G * tw[3] / np.pi
        for X, Z in [(0.3, 0.2), (0.9, 0.5), (1.2, 0.1), (0.5, 1.3), (2.5, 0.4)]:
            f = res.stress(X * a, Z * a, step=3, part="friction")
            for name, order in (("stz", 1), ("srt", 2)):
                want = unit * ref.twisted_punch_hankel(X, Z, 1.0, order)
                got = float(getattr(f, name))
                assert abs(got - want) <= float(f.error) + tol.PATH_NOSLIP_CLOSED * unit, \
                    (method, name, X, Z)
        assert res.torque[3] == pytest.approx(16 / 3 * G * a**3 * tw[3], rel=1e-9)


@pytest.mark.parametrize("k", [5, 20, 29])
@pytest.mark.parametrize("depth", [0.1, 1.0])
def test_torque_through_planes_under_a_varying_force(twisted, k, depth):
    # step 5: loading; 20: after unloading; 29: reloaded past the smallest radius
    M, dM = _torque(twisted, k, depth * twisted.radius[k])
    Mk = twisted.torque[k]
    exact = twisted.meta["foundation"].startswith("Rings")
    bound = tol.PATH_NOSLIP_RINGS if exact else tol.PATH_NOSLIP_SPRINGS
    assert abs(M - Mk) < bound * abs(Mk)
    # the same torque at the surface's depth 0.1 a as here (equilibrium of the field itself)
    M1, dM1 = _torque(twisted, k, 0.1 * twisted.radius[k])
    assert abs(M - M1) <= dM + dM1 + tol.PATH_STRESS_PLANE * abs(Mk)
    assert "no-slip" in twisted.stress(0.0, 1e-6, step=k).meta["route"]


def test_ring_punches_replay_the_ring_solver():
    # an independent replay of the punch bookkeeping: increment j at radius min(a_j..a_k)
    a = np.array([1.0, 2.0, 1.5, 3.0, 2.5])
    phi = np.array([0.1, 0.3, 0.2, 0.6, 0.7])
    t, m = ring_punches(a, phi)
    torque = {}
    for j in range(5):
        rad = min(a[j:])
        torque[rad] = torque.get(rad, 0.0) + phi[j] - (phi[j - 1] if j else 0.0)
    assert list(t) == sorted(torque) and np.allclose(m, [torque[x] for x in sorted(torque)])


def test_entry_history_by_hand():
    # depth 0 -> 1 -> 2 -> 1 -> 3 with the control 0 -> 1 -> 3 -> 4 -> 8
    d, c = np.array([1.0, 2.0, 1.0, 3.0]), np.array([1.0, 3.0, 4.0, 8.0])
    got = entry_history(np.array([0.5, 1.5, 2.5]), d, c)
    # g = 0.5: entered in the first step at half of it (control 0.5): 8 - 0.5
    # g = 1.5: left at depth 1, re-entered in the last step at (1.5-1)/(3-1) of it: 4 + 1
    # g = 2.5: entered in the last step at 3/4 of it: 4 + 3
    np.testing.assert_allclose(got, [7.5, 3.0, 1.0], rtol=0, atol=1e-15)


def test_shift_constant_force_surface_traction_and_force():
    u = np.array([0.0, 2e-8, 4e-8, 6e-8])
    res = _quiet(C.simulate, cl.LoadPath.from_arrays(force=np.full(4, F), displacement=u),
                 snapshots=[3])
    a, Q = res.radius[3], res.tangential_force[3]
    assert Q == pytest.approx(2 * C.moduli.tangential * a * u[3], rel=1e-9)
    r = np.array([0.1, 0.4, 0.7, 0.9]) * a
    f = res.stress(r, 0.0, 0.0, step=3, part="friction")
    want = Q / (2 * np.pi * a * np.sqrt(a * a - r * r))
    assert np.all(np.abs(f.sxz - want) <= f.error + tol.PATH_NOSLIP_CLOSED * Q / a**2)
    for depth in (0.1, 1.0):
        Qz, dQ = _shift_force(res, 3, depth * a)
        assert abs(Qz - Q) <= dQ + tol.PATH_STRESS_PLANE * Q


@pytest.mark.parametrize("k", [5, 20, 29])
def test_shift_force_through_planes_under_a_varying_force(k):
    res = _shift_run()
    Qk = res.tangential_force[k]
    (Q1, dQ1), (Q2, dQ2) = (_shift_force(res, k, d * res.radius[k]) for d in (0.1, 1.0))
    for Q in (Q1, Q2):
        assert abs(Q - Qk) < tol.PATH_NOSLIP_SPRINGS * abs(Qk)
    assert abs(Q1 - Q2) <= dQ1 + dQ2 + tol.PATH_STRESS_PLANE * abs(Qk)


_RUNS: dict = {}


def _shift_run():
    if "shift" not in _RUNS:
        _RUNS["shift"] = _quiet(C.simulate, cl.LoadPath.from_arrays(force=FORCE,
                                                                    displacement=SHIFT),
                                snapshots=[5, 20, 29])
    return _RUNS["shift"]
