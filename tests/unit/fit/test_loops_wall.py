"""Loop fits on tips with a punch wall, from loops made here by Masing's rule from independent
closed forms: the flat punch's tangential loop (no partial slip: ``Q = 2G*b u`` up to ``μF``, a
parallelogram), a paraboloid ending in a wall with the contact at the wall (Cattaneo-Mindlin
through the MDR with the force at unit modulus written here), and the flat punch's torsion
(Jäger's equations with the punch's pressure ``F/(2πb sqrt(b²-r²))``: slip function in closed
form with the complete elliptic integral, torque by quadrature); loops that never slide leave
the friction unidentifiable and raise."""
from __future__ import annotations

import numpy as np
import pytest
from scipy.integrate import quad
from scipy.optimize import brentq
from scipy.special import ellipk

import contactlab as cl
from contactlab import Elastic, errors
from contactlab.fit import tangential_loop, torsion_loop
from contactlab.fit._tip import TipModel
from contactlab.fit.loops import _loop_model
from contactlab.profiles import FlatPunch, Paraboloid
from tests.tolerances import FIT_JACOBIAN_FD, FIT_RECOVERY

FN, MU, B, R = 100.0, 0.3, 1e-3, 0.01
STEEL = Elastic(E=210e9, nu=0.3)
START = Elastic(E=100e9, nu=0.3)             # a wrong template: the punch's loop ignores E
E_STAR = STEEL.E / (1 - STEEL.nu ** 2)        # rigid tip
G_STAR = 4 * STEEL.G / (2 - STEEL.nu)
GT = STEEL.G
K_PUNCH = 2 * G_STAR * B                      # the punch's tangential stiffness
U_SLIDE = MU * FN / K_PUNCH                   # first loading reaches μF here
Q = {"epsabs": 0.0, "epsrel": 1e-13, "limit": 200}


def rel(a, b):
    return abs(a / b - 1)


def _loop(x0, v, Lv, L0):
    """Masing loop of amplitude x0 from the virgin curve sampled at branch travels/2 ``v``
    (from 0 to x0, increasing): down from x0, then up."""
    return (np.concatenate([x0 - 2 * v, (-x0 + 2 * v)[1:]]),
            np.concatenate([L0 - 2 * Lv, (-L0 + 2 * Lv)[1:]]))


def punch_tangential(u):
    return np.minimum(K_PUNCH * u, MU * FN)


def punch_loop(f, n=200):
    x0 = f * U_SLIDE
    v = np.linspace(0, x0, n)
    return _loop(x0, v, punch_tangential(v), punch_tangential(x0))


# ---------------------------------------------------------------- tangential, flat punch
@pytest.mark.parametrize("f", [1.0001, 1.2, 2.5, 10.0])
def test_flat_punch_tangential_loop_recovers_friction_and_modulus(f):
    x, y = punch_loop(f)
    res = tangential_loop(x + 3e-9, y, FN, FlatPunch(radius=B), sample=START)
    assert rel(res.params["friction"], MU) < FIT_RECOVERY
    assert rel(res.params["shear_modulus"], STEEL.G) < FIT_RECOVERY
    assert rel(res.params["G_star"], G_STAR) < FIT_RECOVERY
    assert res.meta["tip_route"] == "punch"


def test_flat_punch_library_is_the_parallelogram():
    """The library's own tangential routes give the closed form the fit uses."""
    c = cl.Contact(FlatPunch(radius=B), (cl.Rigid(), STEEL), friction=MU)
    u = np.linspace(0, 3 * U_SLIDE, 13)
    np.testing.assert_allclose(c.tangential(force=FN, displacement=u).tangential_force,
                               punch_tangential(u), rtol=FIT_RECOVERY, atol=0)
    x, y = punch_loop(2.0, n=41)
    h = c.shift_history(force=FN, displacement=np.concatenate([[0.0], np.linspace(
        0, x[0], 21)[1:], x[1:]]))
    np.testing.assert_allclose(h.tangential_force[-x.size:], y, rtol=0,
                               atol=FIT_RECOVERY * MU * FN)


def test_flat_punch_loop_that_never_slides_leaves_friction_unidentified():
    x, y = punch_loop(0.6)                     # |Q| < μF everywhere: the elastic line
    with pytest.raises(errors.ParameterError, match="'friction' is not identifiable"):
        tangential_loop(x, y, FN, FlatPunch(radius=B), sample=START)
    res = tangential_loop(x, y, FN, FlatPunch(radius=B), sample=START, free="shear_modulus",
                          friction=0.5)       # any friction above 0.18 fits: G alone is exact
    assert rel(res.params["shear_modulus"], STEEL.G) < FIT_RECOVERY


def _tip_load(profile, force):
    """The fit's virgin tangential curve (the formula of ``tangential_loop``) for a profile,
    the depth and the tip model."""
    st = cl.Contact(profile, (cl.Rigid(), STEEL)).normal(force=force)
    d = float(st.depth)
    tip = TipModel(profile, d * 1.0001, allow_wall=True)

    def load(u, mu, Ge):
        phi, dphi = tip(d - Ge * u / (mu * E_STAR))
        return mu * (force - E_STAR * phi), Ge * dphi

    return load, d, tip


@pytest.mark.parametrize("profile", [FlatPunch(radius=B),
                                     Paraboloid(R=R) + FlatPunch(radius=2e-4)])
def test_wall_loop_jacobian_against_finite_differences(profile):
    """∂Q/∂μ only where the model slides (the punch: the plateau), ∂Q/∂G through the slope.
    Left out: points within a step of a kink (the punch's slide onset, where the second
    difference is not small) and, on the table route, points whose indentation lies within a
    step of a Hermite node (``Φ''`` jumps there, a central difference errs by O(step))."""
    force = FN if profile.flat_radius > 0 else 400.0     # at the wall (from 245 N)
    load, d, tip = _tip_load(profile, force)
    x0 = 2.5 * U_SLIDE * force / FN
    x = np.concatenate([np.linspace(x0, -x0, 61), np.linspace(-x0, x0, 61)[1:]])
    p = np.array([0.01, -0.02])
    start = {"friction": MU, "shear_modulus": STEEL.G}
    mu, Ge = MU * np.exp(p[0]), G_STAR * np.exp(p[1])

    def G_of(G):
        return 4 * G / (2 - STEEL.nu), 4 / (2 - STEEL.nu)

    parts = _loop_model(x, ("friction", "shear_modulus"), 0.0, x0, load, G_of, start, {})
    _, _, der = parts(p)
    h = 1e-6
    v = 0.5 * (x0 - np.sign(np.gradient(-x)) * x)          # the branch's travel / 2
    delta = d - Ge * v / (mu * E_STAR)
    near = np.zeros(x.size, bool)
    if tip.route == "table":
        gap = np.min(np.abs(delta[:, None] - tip._g[None, :]), axis=1)
        near = gap < 10 * h * np.abs(d - delta)
        assert np.min(np.abs(d - Ge * x0 / (mu * E_STAR) - tip._g)) > 10 * h * d  # L(x0)
    for i, name in enumerate(("friction", "shear_modulus")):
        e = np.zeros(2)
        e[i] = h
        hi, lo = parts(p + e)[1], parts(p - e)[1]
        one = parts(p)[1]
        smooth = (np.abs((hi - one) - (one - lo)) <= 1e-3 * np.abs(hi - lo) + 1e-300) & ~near
        assert np.count_nonzero(smooth) > 0.8 * x.size
        fd = (hi - lo) / (2 * h)
        np.testing.assert_allclose(der[name][smooth], fd[smooth], rtol=0,
                                   atol=FIT_JACOBIAN_FD * np.max(np.abs(fd)))


# ---------------------------------------------------------------- tangential, rising to a wall
B_W, F_W = 2e-4, 400.0                       # the wall's radius, a force beyond it (245 N)
WALL = Paraboloid(R=R) + FlatPunch(radius=B_W)


def _wall_phi(delta):
    """Force at unit modulus of Paraboloid(R) ending in a wall at B_W: Hertz up to the depth
    B_W²/R where the contact reaches the wall, then the punch's 2B_W per unit indentation."""
    dw = B_W * B_W / R
    d = np.minimum(delta, dw)
    return 4 / 3 * np.sqrt(R) * np.maximum(d, 0) ** 1.5 + 2 * B_W * np.maximum(delta - dw, 0)


def test_paraboloid_in_a_wall_tangential_loop():
    """Contact at the wall (F_W = 400 N > 4E*B_W³/(3R) = 245 N): partial slip from the rounded
    part, the edge's singular pressure holds; Cattaneo-Mindlin through the MDR written here."""
    force = F_W
    dw = B_W * B_W / R
    d = dw + (force / E_STAR - _wall_phi(dw)) / (2 * B_W)
    assert d > dw

    def virgin(u):
        return MU * (force - E_STAR * _wall_phi(d - G_STAR * u / (MU * E_STAR)))

    prof = WALL
    c = cl.Contact(prof, (cl.Rigid(), STEEL), friction=MU)
    u_full = MU * E_STAR * d / G_STAR
    u = np.linspace(0, 1.2 * u_full, 9)
    np.testing.assert_allclose(c.tangential(force=force, displacement=u).tangential_force,
                               virgin(u), rtol=1e-12, atol=0)
    for f in (0.4, 2.0):
        x0 = f * u_full
        v = np.linspace(0, x0, 200)
        x, y = _loop(x0, v, virgin(v), virgin(x0))
        # the normal problem takes the template's E (it sets the depth beyond the wall)
        res = tangential_loop(x, y, force, prof, sample=STEEL)
        assert res.meta["tip_route"] == "table"
        assert 0 < res.model_error < 1e-5      # the tabulated Φ's measured error
        assert rel(res.params["friction"], MU) < FIT_RECOVERY
        assert rel(res.params["shear_modulus"], STEEL.G) < FIT_RECOVERY
    # the part beyond the wall is a punch's: no slip at all until the branch has travelled
    # 2μE*(d - B_W²/R)/G*, so a smaller loop is the elastic line and μ is not identifiable
    x0 = 0.9 * MU * E_STAR * (d - dw) / G_STAR
    v = np.linspace(0, x0, 100)
    x, y = _loop(x0, v, virgin(v), virgin(x0))
    np.testing.assert_allclose(y, 2 * G_STAR * B_W * x, rtol=1e-12, atol=0)
    with pytest.raises(errors.ParameterError, match="'friction' is not identifiable"):
        tangential_loop(x, y, force, prof, sample=STEEL)


# ---------------------------------------------------------------- torsion, flat punch
def _punch_virgin(t):
    """Jäger's first loading of the flat punch at stick ratios t = c/B (≤ 1): twist and
    torque. ``P(c) = ∫_c^B p/sqrt(s²-c²) ds = F K(1 - c²/B²)/(2πB²)``, ``φ = μP/(2G_t)``,
    ``M = (16/3) G_t φ c³ + 8μ ∫_c^B p(s) [s²/2 (π/2 - asin(c/s)) + c/2 sqrt(s²-c²)] ds``."""
    c = np.asarray(t, float) * B
    phi = MU * FN * ellipk(1 - (c / B) ** 2) / (2 * np.pi * B * B) / (2 * GT)

    def T(cc):
        def f(s):
            return (FN / (2 * np.pi * B * np.sqrt(B + s))
                    * (s * s / 2 * (np.pi / 2 - (np.arcsin(cc / s) if s > cc else np.pi / 2))
                       + cc / 2 * np.sqrt(max(s * s - cc * cc, 0.0))))
        return quad(f, cc, B, weight="alg", wvar=(0.0, -0.5), **Q)[0]

    stick = 16 / 3 * GT * np.where(c > 0, phi, 0.0) * c ** 3     # φ = ∞ at c = 0
    return phi, stick + 8 * MU * np.array([T(cc) for cc in c])


def punch_torsion_loop(t0=0.3, n=100):
    """A loop sampled evenly in twist: the stick ratio at each twist by root finding on the
    closed-form twist."""
    phi_s = MU * FN / (8 * GT * B * B)        # slip starts at the edge here (K(0) = π/2)
    assert rel(_punch_virgin([1.0])[0][0], phi_s) < 1e-14
    x0 = float(_punch_virgin([t0])[0][0])
    v = np.linspace(0, x0, n)

    def stick(vv):
        return brentq(lambda tt: _punch_virgin([tt])[0][0] - vv, t0 * 0.99, 1.0, xtol=1e-16,
                      rtol=1e-15)

    t = np.array([1.0 if vv <= phi_s else stick(vv) for vv in v])
    M = _punch_virgin(t)[1]
    Lv = np.where(v <= phi_s, 16 / 3 * GT * B ** 3 * v, M)   # before: the no-slip line
    return _loop(x0, v, Lv, Lv[-1])


def test_flat_punch_sliding_torque_closed_form():
    """Full sliding: ``M = μ ∫ p r 2πr dr = μF πB/4``; the test's quadrature and the
    library's exact torsion both reach it."""
    M_full = MU * FN * np.pi * B / 4
    assert rel(_punch_virgin([0.0])[1][0], M_full) < 1e-12
    c = cl.Contact(FlatPunch(radius=B), (cl.Rigid(), STEEL), friction=MU)
    assert rel(float(c.torsion(force=FN, twist=1e3 * MU * FN / (GT * B * B),
                               method="exact").torque), M_full) < 1e-12
    phi, M = _punch_virgin([0.9, 0.5, 0.1])
    np.testing.assert_allclose(c.torsion(force=FN, twist=phi, method="exact").torque, M,
                               rtol=1e-10)


def test_flat_punch_torsion_loop_recovers_friction_and_modulus():
    x, y = punch_torsion_loop()
    res = torsion_loop(x + 1e-5, y, FN, FlatPunch(radius=B), sample=START)
    assert res.meta["route"] == "exact"
    assert rel(res.params["friction"], MU) < FIT_RECOVERY
    assert rel(res.params["shear_modulus"], GT) < FIT_RECOVERY
    assert 0 <= res.model_error < 1e-9


def test_flat_punch_torsion_that_never_slips_leaves_friction_unidentified():
    phi_s = MU * FN / (8 * GT * B * B)
    v = np.linspace(0, 0.7 * phi_s, 50)
    L = 16 / 3 * GT * B ** 3 * v
    x, y = _loop(v[-1], v, L, L[-1])
    with pytest.raises(errors.ParameterError, match="'friction' is not identifiable"):
        torsion_loop(x, y, FN, FlatPunch(radius=B), sample=START)
    res = torsion_loop(x, y, FN, FlatPunch(radius=B), sample=START, free="shear_modulus",
                       friction=0.5)
    assert rel(res.params["shear_modulus"], GT) < FIT_RECOVERY


# ---------------------------------------------------------------- torsion, rising to a wall
class WallJaeger:
    """Jäger's first-loading torsion of ``WALL`` held at its wall (force ``F_W``): pressure
    ``p(r) = (E*/π) [2 sqrt(B_W² - r²)/R + (d - B_W²/R)/sqrt(B_W² - r²)]`` (the paraboloid's
    part plus the punch's for the indentation beyond the wall); ``q = p sqrt(B_W² - r²)`` is
    smooth, so the slip function and the torque integral are algebraic-weight quadratures."""

    def __init__(self):
        b, dw = B_W, B_W * B_W / R
        self.d = dw + (F_W / E_STAR - _wall_phi(dw)) / (2 * b)

    def q(self, s):
        return E_STAR / np.pi * (2 * (B_W * B_W - s * s) / R + self.d - B_W * B_W / R)

    def pressure(self, r):
        return self.q(r) / np.sqrt(B_W * B_W - r * r)

    def P(self, c):
        if c >= B_W:                            # ∫_c^b ds/sqrt((b²-s²)(s²-c²)) -> π/(2b)
            return self.q(B_W) * np.pi / (2 * B_W)
        return quad(lambda s: self.q(s) / np.sqrt((B_W + s) * (s + c)), c, B_W,
                    weight="alg", wvar=(-0.5, -0.5), **Q)[0]

    def T(self, c):
        def f(s):
            return (self.q(s) / np.sqrt(B_W + s)
                    * (s * s / 2 * (np.pi / 2 - (np.arcsin(c / s) if s > c else np.pi / 2))
                       + c / 2 * np.sqrt(max(s * s - c * c, 0.0))))
        return quad(f, c, B_W, weight="alg", wvar=(0.0, -0.5), **Q)[0] if c < B_W else 0.0

    def virgin(self, t):
        c = np.asarray(t, float) * B_W
        phi = np.array([MU * self.P(cc) / (2 * GT) for cc in c])
        return phi, 16 / 3 * GT * phi * c ** 3 + 8 * MU * np.array([self.T(cc) for cc in c])

    def loop(self, t0=0.3, n=80):
        x0 = float(self.virgin([t0])[0][0])
        phi_s = float(self.virgin([1.0])[0][0])

        def stick(vv):
            return brentq(lambda tt: self.virgin([tt])[0][0] - vv, t0 * 0.99, 1.0,
                          xtol=1e-16, rtol=1e-15)

        v = np.linspace(0, x0, n)
        t = np.array([1.0 if vv <= phi_s else stick(vv) for vv in v])
        Lv = np.where(v <= phi_s, 16 / 3 * GT * B_W ** 3 * v, self.virgin(t)[1])
        return _loop(x0, v, Lv, Lv[-1])


def test_paraboloid_in_a_wall_torsion_loop():
    jag = WallJaeger()
    c = cl.Contact(WALL, (cl.Rigid(), STEEL), friction=MU)
    st = c.normal(force=F_W)
    assert rel(float(st.depth), jag.d) < 1e-12 and float(st.radius) == B_W
    r = np.array([0.0, 0.5, 0.9, 0.99]) * B_W
    np.testing.assert_allclose(st.pressure(r), jag.pressure(r), rtol=1e-10)
    phi, M = jag.virgin([0.95, 0.6, 0.3])
    np.testing.assert_allclose(c.torsion(force=F_W, twist=phi, method="exact").torque, M,
                               rtol=1e-10)
    x, y = jag.loop()
    res = torsion_loop(x, y, F_W, WALL, sample=STEEL)     # the template's E: the depth
    assert res.meta["route"] == "exact"
    assert rel(res.params["friction"], MU) < FIT_RECOVERY
    assert rel(res.params["shear_modulus"], GT) < FIT_RECOVERY


def test_wall_not_reached_is_mindlin():
    """Below the wall's force (30.8 kN here) a paraboloid ending in a wall is Hertz:
    Mindlin-Deresiewicz's closed form, recovered on the tip's table route."""
    a = (3 * FN * R / (4 * E_STAR)) ** (1 / 3)
    u_star = 3 * MU * FN / (4 * a * G_STAR)

    def virgin(u):
        return MU * FN * (1 - (1 - np.minimum(u / u_star, 1)) ** 1.5)

    x0 = 0.7 * u_star
    v = np.linspace(0, x0, 200)
    x, y = _loop(x0, v, virgin(v), virgin(x0))
    res = tangential_loop(x, y, FN, Paraboloid(R=R) + FlatPunch(radius=B), sample=STEEL)
    assert res.meta["tip_route"] == "table"
    assert rel(res.params["friction"], MU) < FIT_RECOVERY
    assert rel(res.params["shear_modulus"], STEEL.G) < FIT_RECOVERY
