"""Torsion loops of tips that are not a single power law (the exact route of
``fit.torsion_loop``): friction and shear modulus recovered from loops made here by Masing's
rule from a first-loading curve computed by an independent quadrature of Jäger's equations
(pressure from the MDR transform, slip function and torque integral by nested scipy quadrature
in the stick radius, no root solving); the route on a paraboloid against the master curve and
Lubkin's closed form; its Jacobian against finite differences; a tabulated sphere."""
from __future__ import annotations

import numpy as np
import pytest
from scipy.integrate import quad
from scipy.optimize import brentq
from scipy.special import ellipe, ellipk

import contactlab as cl
from contactlab import Elastic, errors
from contactlab.fit import torsion_loop
from contactlab.fit.loops import _exact_virgin, _loop_model, _torsion_G_of
from contactlab.profiles import Cone, Paraboloid, Sphere, Tabulated
from tests.tolerances import (FIT_JACOBIAN_FD, FIT_RECOVERY, FIT_TORSION_ROUTES,
                              FIT_TORSION_VIRGIN)

R, FN, MU = 0.01, 100.0, 0.3
STEEL = Elastic(E=210e9, nu=0.3)
E_STAR = STEEL.E / (1 - STEEL.nu ** 2)        # rigid tip
GT = STEEL.G
Q = {"epsabs": 0.0, "epsrel": 1e-12, "limit": 200}


class Jaeger:
    """Jäger's first-loading torsion at constant normal force for a profile given by the
    derivative ``g1p`` of its MDR transform ``g1(x) = x ∫_0^x g'(r)/sqrt(x²-r²) dr`` and the
    force ``force(a)``: pressure ``p(r) = (E*/π) ∫_r^a g1'(x)/sqrt(x²-r²) dx``, slip function
    ``P(c) = ∫_c^a p(s)/sqrt(s²-c²) ds``, ``T(c) = ∫_c^a x² P(x) dx`` (inner integral in closed
    form), twist ``φ = μP(c)/(2G_t)``, torque ``M = (16/3) G_t φ c³ + 8μT(c)``."""

    def __init__(self, g1p, force):
        self.g1p = g1p
        self.a = brentq(lambda a: force(a) - FN, 1e-9, 0.5 * R, xtol=1e-22, rtol=1e-15)

    def p(self, r):
        a = self.a
        return E_STAR / np.pi * quad(lambda u: self.g1p(np.sqrt(r * r + u * u))
                                     / np.sqrt(r * r + u * u), 0, np.sqrt(a * a - r * r), **Q)[0]

    def P(self, c):
        return quad(lambda u: self.p(np.sqrt(c * c + u * u)) / np.sqrt(c * c + u * u), 0,
                    np.sqrt(self.a ** 2 - c * c), **Q)[0]

    def T(self, c):
        def f(s):
            return self.p(s) * (s * s / 2 * (np.pi / 2 - np.arcsin(min(c / s, 1.0)))
                                + c / 2 * np.sqrt(max(s * s - c * c, 0.0)))
        return quad(f, c, self.a, **Q)[0]

    def virgin(self, t):
        """Twist and torque at stick ratios ``t = c/a``."""
        c = np.asarray(t, float) * self.a
        phi = np.array([MU * self.P(cc) / (2 * GT) for cc in c])
        M = 16 / 3 * GT * phi * c ** 3 + 8 * MU * np.array([self.T(cc) for cc in c])
        return phi, M

    def loop(self, t0=0.3, n=30):
        (phi0,), (M0,) = self.virgin([t0])
        phi_v, M_v = self.virgin(np.linspace(1.0, t0, n))
        return (np.concatenate([phi0 - 2 * phi_v, (-phi0 + 2 * phi_v)[1:]]),
                np.concatenate([M0 - 2 * M_v, (-M0 + 2 * M_v)[1:]]))


def _sphere_force(a):
    g1 = lambda x: x / 2 * np.log((R + x) / (R - x))                      # noqa: E731
    return 2 * E_STAR * (a * g1(a) - quad(g1, 0, a, **Q)[0])


SPHERE = Jaeger(lambda x: 0.5 * np.log((R + x) / (R - x)) + x * R / (R * R - x * x),
                _sphere_force)
SLOPE = 0.02                                   # paraboloid + cone: g1 = x²/R + (π/2) s x
SUM = Jaeger(lambda x: 2 * x / R + np.pi / 2 * SLOPE,
             lambda a: 2 * E_STAR * (2 / 3 * a ** 3 / R + np.pi / 4 * SLOPE * a * a))


def rel(a, b):
    return abs(a / b - 1)


def test_independent_virgin_curve_is_lubkins_on_a_paraboloid():
    """The test's quadrature reproduces Lubkin's closed form for Hertz (so it checks the
    library, not itself)."""
    par = Jaeger(lambda x: 2 * x / R, lambda a: 4 * E_STAR * a ** 3 / (3 * R))
    t = np.array([0.9, 0.5, 0.2])
    phi, M = par.virgin(t)
    a, k2 = par.a, 1 - t * t
    phi_l = 3 * MU * FN / (4 * np.pi * GT * a * a) * (ellipk(k2) - ellipe(k2))
    M_l = MU * FN * a * (3 * np.pi / 16 - 4 / np.pi * np.array(
        [quad(lambda q: q * q * ellipe(1 - q * q), 0, tt, **Q)[0] for tt in t]))
    np.testing.assert_allclose(phi, phi_l, rtol=FIT_TORSION_VIRGIN)
    np.testing.assert_allclose(M, M_l, rtol=FIT_TORSION_VIRGIN)


@pytest.mark.parametrize("case", ["sphere", "sum"])
def test_exact_route_recovers_friction_and_modulus(case):
    jag, prof = {"sphere": (SPHERE, Sphere(R=R)),
                 "sum": (SUM, Paraboloid(R=R) + Cone(slope=SLOPE))}[case]
    x, y = jag.loop()
    res = torsion_loop(x + 1e-5, y, FN, prof, sample=Elastic(E=210e9, nu=0.3))
    assert res.meta["route"] == "exact"
    assert rel(res.params["friction"], MU) < FIT_RECOVERY
    assert rel(res.params["shear_modulus"], GT) < FIT_RECOVERY
    assert 0 <= res.model_error < 1e-9


def test_exact_route_on_a_paraboloid_matches_the_master_curve():
    x, y = SUM.loop(n=20)                       # any loop shape: the two routes' models agree
    prof = Paraboloid(R=R)
    G_of = _torsion_G_of(cl.Rigid())
    c1 = cl.Contact(prof, (cl.Rigid(), STEEL), friction=1.0)
    d = float(c1.normal(force=FN).depth)
    exact = torsion_loop(x, y, FN, prof, sample=STEEL, route="exact")
    master = torsion_loop(x, y, FN, prof, sample=STEEL)
    assert (exact.meta["route"], master.meta["route"]) == ("exact", "master")
    for name in ("friction", "shear_modulus"):
        assert rel(exact.params[name], master.params[name]) < FIT_TORSION_ROUTES
    amp = 0.5 * (x.max() - x.min())
    load = _exact_virgin(c1, d, c1.moduli.torsional)
    start = {"friction": 0.25, "shear_modulus": 7e10}
    parts = _loop_model(x, ("friction", "shear_modulus"), 0.0, amp, load, G_of, start, {})
    model = parts(np.zeros(2))[1]
    ref = torsion_loop(x, model, FN, prof, sample=STEEL, start=start)   # the master curve
    assert rel(ref.params["friction"], 0.25) < FIT_TORSION_ROUTES
    assert rel(ref.params["shear_modulus"], 7e10) < FIT_TORSION_ROUTES


def test_exact_route_jacobian_against_finite_differences():
    x, _ = SPHERE.loop(n=15)
    prof = Sphere(R=R)
    c1 = cl.Contact(prof, (cl.Rigid(), STEEL), friction=1.0)
    d = float(c1.normal(force=FN).depth)
    load = _exact_virgin(c1, d, c1.moduli.torsional)
    G_of = _torsion_G_of(cl.Elastic(E=400e9, nu=0.25))
    amp = 0.5 * (x.max() - x.min())
    start = {"friction": MU, "shear_modulus": GT}
    parts = _loop_model(x, ("friction", "shear_modulus"), 0.0, amp, load, G_of, start, {})
    p = np.array([0.1, -0.2])
    _, _, der = parts(p)
    h = 1e-5
    for i, name in enumerate(("friction", "shear_modulus")):
        e = np.zeros(2)
        e[i] = h
        fd = (parts(p + e)[1] - parts(p - e)[1]) / (2 * h)
        np.testing.assert_allclose(der[name], fd, rtol=0,
                                   atol=FIT_JACOBIAN_FD * np.max(np.abs(fd)))


def test_tabulated_sphere_within_its_table_error():
    x, y = SPHERE.loop(n=20)
    r = np.linspace(0.0, 0.5 * R, 4001)
    tab = Tabulated(r, R - np.sqrt(R * R - r * r))
    res = torsion_loop(x, y, FN, tab, sample=STEEL)
    assert res.meta["route"] == "exact"
    # the table's own distance from the sphere: its first-loading torque against the
    # quadrature's, over the loop's range of stick radii
    t = np.linspace(0.3, 0.95, 6)
    phi, M = SPHERE.virgin(t)
    c_tab = cl.Contact(tab, (cl.Rigid(), STEEL), friction=MU)
    d = float(c_tab.normal(force=FN).depth)
    M_tab = c_tab.torsion(depth=d, twist=phi).torque
    bound = float(np.max(np.abs(M_tab / M - 1)))
    assert 0 < bound < 1e-4
    assert rel(res.params["friction"], MU) < 10 * bound
    assert rel(res.params["shear_modulus"], GT) < 10 * bound


def test_unknown_route_refused():
    x, y = SUM.loop(n=10)
    with pytest.raises(errors.ParameterError, match="route='fast'"):
        torsion_loop(x, y, FN, Sphere(R=R), sample=STEEL, route="fast")
