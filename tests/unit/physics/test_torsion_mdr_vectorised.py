"""Contact.torsion(method="mdr") on many forces at once (issue 28): closed-form kernels for a
single power term and a screened validity check, vectorised over forces.

Expected values: per-force scalar calls (bit-identical), the generic quadrature route of the
same model (a second method) and the Hertz closed form written out with mpmath.
"""
from __future__ import annotations

import warnings

import mpmath as mp
import numpy as np
import pytest

import contactlab as cl
from contactlab.effects import torsion as et
from contactlab.errors import ValidityWarning
from contactlab.physics import torsion_mdr as tm
from contactlab.physics import torsion_validity as tv
from contactlab.physics.torsion import MDR_VALID_STICK_RATIO
from contactlab.profiles import Cone, Paraboloid, Polynomial, PowerLaw, Sphere
from tests.tolerances import (MDR_HERTZ_CLOSED, MDR_POWER_CLOSED_STICK,
                              MDR_POWER_CLOSED_TORQUE, MDR_SCALAR_ARRAY_FORCE)

MAT = (cl.Elastic(E=210e9, nu=0.3), cl.Rigid())
MU = 0.3
PROFILES = {"paraboloid": Paraboloid(R=0.01), "cone": Cone(slope=0.1),
            "power 1.5": PowerLaw(c=1e3, n=1.5), "power 0.7": PowerLaw(c=1e-2, n=0.7),
            "power 3": PowerLaw(c=1e7, n=3.0)}


def _contact(p):
    return cl.Contact(p, materials=MAT, friction=MU)


def _controls(c, F, rng):
    a = c.normal(force=F).radius
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ValidityWarning)
        M_s = c.torsion(force=F, stick_radius=np.zeros_like(F), method="mdr").torque
        phi_half = c.torsion(force=F, stick_radius=0.5 * a, method="mdr").twist
    return {"twist": phi_half * rng.uniform(1e-3, 3.0, F.size),
            "torque": M_s * rng.uniform(0.0, 0.999, F.size),
            "stick_radius": a * rng.uniform(0.0, 1.0, F.size)}


@pytest.mark.parametrize("name", list(PROFILES))
def test_array_equals_scalar_calls(name):
    """Bit-identical per state given the contact radius; given the force, within the last bits
    the scalar and array normal solves may differ by (docs/robustness.md)."""
    c = _contact(PROFILES[name])
    rng = np.random.default_rng(11)
    F = rng.uniform(0.5, 100.0, 40)
    a = c.normal(force=F).radius
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ValidityWarning)
        for ctrl, val in _controls(c, F, rng).items():
            by_a = c.torsion(radius=a, method="mdr", **{ctrl: val})
            by_F = c.torsion(force=F, method="mdr", **{ctrl: val})
            for i in range(F.size):
                one = c.torsion(radius=float(a[i]), method="mdr", **{ctrl: float(val[i])})
                assert float(one.torque) == by_a.torque[i]
                assert float(one.twist) == by_a.twist[i]
                assert float(one.stick_radius) == by_a.stick_radius[i]
                one = c.torsion(force=float(F[i]), method="mdr", **{ctrl: float(val[i])})
                for q in ("torque", "twist", "stick_radius"):
                    # under torque control the stick radius is a bracketed root: a last-bit
                    # change of the depth moves it within the root's tolerance
                    tol = (MDR_POWER_CLOSED_STICK if ctrl == "torque" and q != "torque"
                           else MDR_SCALAR_ARRAY_FORCE)
                    assert float(getattr(one, q)) == pytest.approx(getattr(by_F, q)[i],
                                                                   rel=tol, abs=0)


@pytest.mark.parametrize("name", list(PROFILES))
def test_closed_forms_agree_with_the_quadrature_route(name, monkeypatch):
    c = _contact(PROFILES[name])
    rng = np.random.default_rng(3)
    F = rng.uniform(0.5, 100.0, 200)
    ctrls = _controls(c, F, rng)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ValidityWarning)
        fast = {k: c.torsion(force=F, method="mdr", **{k: v}) for k, v in ctrls.items()}
        monkeypatch.setattr(tm, "_single_power", lambda profile: None)
        slow = {k: c.torsion(force=F, method="mdr", **{k: v}) for k, v in ctrls.items()}
    for k in ("twist", "stick_radius"):
        np.testing.assert_allclose(fast[k].torque, slow[k].torque, rtol=MDR_POWER_CLOSED_TORQUE,
                                   atol=0)
        np.testing.assert_allclose(fast[k].stick_radius, slow[k].stick_radius,
                                   rtol=MDR_POWER_CLOSED_STICK, atol=0)
    np.testing.assert_allclose(fast["torque"].twist, slow["torque"].twist,
                               rtol=MDR_POWER_CLOSED_STICK, atol=0)


def test_hertz_against_mpmath_closed_form():
    """MDR Hertz (g = x²/R): 4G_tφc/(μE*) + c²/R = d and
    M = (16/3) G_t φ c³ + 4μE* [d (a² - c²)/2 - (a⁴ - c⁴)/(4R)]."""
    R = 0.01
    c = _contact(Paraboloid(R=R))
    F = np.geomspace(0.1, 1000.0, 25)
    phi = np.geomspace(1e-6, 1e-2, 25)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ValidityWarning)
        st = c.torsion(force=F, twist=phi, method="mdr")
    E, G = c.moduli.normal, c.moduli.torsional
    with mp.workdps(30):
        for i in range(F.size):
            a = mp.mpf(float(st.radius[i]))
            d = a * a / R
            k = 4 * mp.mpf(G) / (MU * mp.mpf(E))
            p = mp.mpf(float(phi[i]))
            cs = (-k * p + mp.sqrt((k * p) ** 2 + 4 * d / R)) / (2 / mp.mpf(R))
            M = (mp.mpf(16) / 3 * G * p * cs**3
                 + 4 * MU * mp.mpf(E) * (d * (a * a - cs * cs) / 2 - (a**4 - cs**4) / (4 * R)))
            assert abs(st.stick_radius[i] - float(cs)) <= MDR_HERTZ_CLOSED * float(cs)
            assert abs(st.torque[i] - float(M)) <= MDR_HERTZ_CLOSED * float(M)


@pytest.mark.parametrize("prof", [Paraboloid(R=0.01), PowerLaw(c=1e3, n=1.5), Sphere(R=2e-3),
                                  Polynomial([(50.0, 2.0), (1e6, 4.0)]), Cone(slope=0.1)],
                         ids=["paraboloid", "power", "sphere", "polynomial", "cone"])
def test_screen_bound_holds(prof):
    """The screen's estimate of the validity twist is within its own bound of the exact one."""
    c = _contact(prof)
    F = np.geomspace(0.1, 200.0, 60)
    n = c.normal(force=F)
    a, d = n.radius, n.depth
    if isinstance(prof, Sphere):
        keep = a < 0.95 * prof.R
        a, d = a[keep], d[keep]
    g_a = prof._g(a)
    L, m = tv.screen_twist_at_stick_ratio(prof, c.moduli.normal, c.moduli.torsional, MU,
                                          MDR_VALID_STICK_RATIO, a, d)
    exact = et.mdr_validity_twist(c, a, d, g_a)
    assert np.all(np.abs(L / exact - 1.0) <= m)


def _old_warning(c, phi, a, d, g_a):
    """The warning of the unscreened check: exact limits of every state."""
    limit = et.mdr_validity_twist(c, a, d, g_a)
    bad = np.abs(phi) > limit
    if not np.any(bad):
        return None
    i = int(np.argmax(np.abs(phi) / limit))
    return abs(float(phi[i])), float(limit[i])


@pytest.mark.parametrize("scale", [0.5, 1.0 - 1e-9, 1.0 + 1e-9, 1.5])
def test_screened_warning_is_the_exact_one(scale):
    c = _contact(Paraboloid(R=0.01))
    F = np.linspace(1.0, 100.0, 500)
    n = c.normal(force=F)
    a, d = n.radius, n.depth
    g_a = c.profile._g(a)
    limit = et.mdr_validity_twist(c, a, d, g_a)
    phi = np.full(F.size, 0.5 * float(np.min(limit)))
    phi[123] = scale * limit[123]          # one state at the edge
    expect = _old_warning(c, phi, a, d, g_a)
    with warnings.catch_warnings(record=True) as rec:
        warnings.simplefilter("always")
        et._warn_mdr(c, phi, a, d, g_a)
    if expect is None:
        assert not rec
    else:
        assert len(rec) == 1
        assert f"twist {expect[0]:.4g} rad exceeds {expect[1]:.4g} rad" in str(rec[0].message)
