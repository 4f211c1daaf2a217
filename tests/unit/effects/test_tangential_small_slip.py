"""Cattaneo–Mindlin at vanishing displacement: the force tends to the no-slip force 2G* a u.

The slip zone's share ``2μE* ∫_c^a (d - g)`` was computed as a difference of integrals from 0
whose rounding (``ε d a``) is hundreds of times ``2G* a u`` at ``u = 1e-25`` m (sphere 450x,
cone and sums 1.7x, tables 1.18x). References: the no-slip limit and a 40-digit evaluation of the
MDR force (tests/reference/small_slip.py)."""
import numpy as np
import pytest

import contactlab as cl
from tests.reference import small_slip as ref
from tests.tolerances import SMALL_SLIP_FORCE

STEEL = cl.Elastic(E=210e9, nu=0.3)
_R = np.linspace(0.0, 2e-3, 41)
_F = _R**2 / (2 * 0.01) + 0.05 * _R

CASES = {
    "sphere": (cl.profiles.Sphere(R=0.01), ref.g_sphere(0.01)),
    "cone": (cl.profiles.Cone(slope=0.1), ref.g_cone(0.1)),
    "sum": (cl.profiles.Paraboloid(R=0.01) + cl.profiles.Cone(slope=0.1),
            ref.g_paraboloid_cone(0.01, 0.1)),
    "table": (cl.profiles.Tabulated(_R, _F), ref.g_linear_table(_R, _F)),
}


def _contact(name):
    return cl.Contact(CASES[name][0], materials=(STEEL, STEEL), friction=0.3)


@pytest.mark.parametrize("name", sorted(CASES))
@pytest.mark.parametrize("force", [1.0, 10.0])
def test_no_slip_limit(name, force):
    con = _contact(name)
    G = con.moduli.tangential
    u = np.array([1e-25, 1e-22, 1e-20])
    st = con.tangential(force=force, displacement=u)
    a = con.normal(force=force).radius
    np.testing.assert_allclose(st.tangential_force, 2.0 * G * a * u, rtol=SMALL_SLIP_FORCE)
    np.testing.assert_allclose(con.tangential(force=force, displacement=-u).tangential_force,
                               -2.0 * G * a * u, rtol=SMALL_SLIP_FORCE)
    hist = con.shift_history(force=force, displacement=np.array([1e-25, -1e-25, 3e-25, 0.0]))
    np.testing.assert_allclose(hist.tangential_force,
                               2.0 * G * a * np.array([1e-25, -1e-25, 3e-25, 0.0]),
                               rtol=SMALL_SLIP_FORCE, atol=0)


@pytest.mark.parametrize("name", sorted(CASES))
def test_small_slip_against_40_digits(name):
    """From u/u* = 1e-19 to 0.5: the force against the MDR force evaluated at 40 digits from
    the same contact radius and depth."""
    con = _contact(name)
    m = con.moduli
    ns = con.normal(force=10.0)
    a, d = ns.radius, ns.depth
    u_star = 0.3 * m.normal * d / m.tangential
    u = u_star * np.array([1e-19, 1e-14, 1e-10, 1e-6, 1e-3, 0.1, 0.5])
    got = con.tangential(force=10.0, displacement=u).tangential_force
    want = [ref.mindlin_force(CASES[name][1], a, d, x, m.normal, m.tangential, 0.3) for x in u]
    np.testing.assert_allclose(got, want, rtol=SMALL_SLIP_FORCE, atol=0)


@pytest.mark.parametrize("name", ["sphere", "sum"])
def test_stick_radius_control_near_the_edge(name):
    """F(c) for c -> a (stick radius control): the same cancellation in μ[F_N(a) - F_N(c)]."""
    con = _contact(name)
    m = con.moduli
    ns = con.normal(force=10.0)
    a, d = ns.radius, ns.depth
    c = a * (1.0 - np.array([1e-13, 1e-9, 1e-5]))
    st = con.tangential(force=10.0, stick_radius=c)
    want = [ref.mindlin_force(CASES[name][1], a, d, u, m.normal, m.tangential, 0.3)
            for u in st.displacement]
    np.testing.assert_allclose(st.tangential_force, want, rtol=SMALL_SLIP_FORCE, atol=0)
