"""The exact Hertz torque-twist curve from its closed forms (physics.torsion_hertz and the
Exact model's paraboloid route) against the 30-digit mpmath Lubkin reference and against the
quadrature route it replaces."""
import mpmath as mp
import numpy as np
import pytest

from contactlab.physics import torsion as _torsion
from contactlab.physics import torsion_exact as _exact
from contactlab.physics import torsion_hertz as th
from contactlab.profiles import Paraboloid
from tests.reference import torsion_reference as ref
from tests.tolerances import HERTZ_TORSION_CLOSED, HERTZ_TORSION_VS_QUADRATURE

R, E_STAR, G_T, MU = 0.01, 1.2e11, 4.0e10, 0.3
A = np.array([1e-4, 2e-4, 5e-5])
RATIOS = [0.999999, 0.99, 0.9, 0.7, 0.5001, 0.4999, 0.3, 0.1, 0.01, 1e-5]


def _model():
    return _torsion.Exact(Paraboloid(R=R), E_STAR, G_T, MU, 1e-10)


def _states(a):
    a = np.asarray(a, float)
    return a, a * a / R, a * a / R


def test_stick_ratio_inverts_the_slip_function_of_the_reference():
    t = np.array(RATIOS)
    y = np.array([float(4 * mp.pi / 3 * ref.hertz_twist_hat(x)) for x in t])
    got = th.stick_ratio(y)
    # dt = dy / (dy/dt) with |dy/dt| = E/t >= 1: the twist's rounding moves t by less
    assert np.all(np.abs(got - t) <= HERTZ_TORSION_CLOSED * np.maximum(t, 1e-3))


@pytest.mark.parametrize("ratio", RATIOS)
def test_curve_matches_the_mpmath_lubkin_closed_form(ratio):
    model = _model()
    a, d, g = _states(A)
    F = 4 * E_STAR * a ** 3 / (3 * R)
    phi = np.array([float(ref.hertz_twist_hat(ratio)) * MU * f / (G_T * x * x)
                    for f, x in zip(F, a)])
    sol = model.of_twist(phi, a, d, g)
    want = np.array([float(ref.hertz_torque_hat(ratio)) for _ in a]) * MU * F * a
    assert np.all(np.abs(sol.torque - want) <= HERTZ_TORSION_CLOSED * want)
    assert np.allclose(sol.stick_radius, ratio * a, rtol=HERTZ_TORSION_CLOSED, atol=0)
    # the error estimate covers the actual error
    assert np.all(np.abs(sol.torque - want) <= sol.torque_error + 1e-300)


def test_curve_matches_the_quadrature_route_it_replaces():
    model = _model()
    a0 = 1e-4
    M_full = 3 * np.pi / 16 * MU * (4 * E_STAR * a0 ** 3 / (3 * R)) * a0
    # twists from the no-slip limit through partial slip to deep sliding
    scale = MU * (4 * E_STAR * a0 ** 3 / (3 * R)) / (G_T * a0 ** 2)
    phi = np.concatenate([[0.0, 1e-12], np.geomspace(1e-6, 30.0, 60)]) * scale
    a, d, g = (np.full(phi.shape, v) for v in _states(a0))
    got = model.of_twist(phi, a, d, g)
    c = _exact.solve_stick_of_twist(model.prof, E_STAR, G_T, MU, phi, a, d, g, 1e-10)
    T, _ = _exact.torque_integral(model.prof, E_STAR, c, a, d, g, 1e-10)
    want = 16.0 / 3.0 * G_T * phi * c ** 3 + 8.0 * MU * T
    assert np.all(np.abs(got.torque - want) <= HERTZ_TORSION_VS_QUADRATURE * M_full)
    assert np.all(np.abs(got.stick_radius - c) <= HERTZ_TORSION_VS_QUADRATURE * a0)


def test_ends_of_the_curve_no_slip_and_full_sliding():
    model = _model()
    a, d, g = _states(np.array([1e-4, 1e-4, 1e-4, 1e-4, 0.0]))
    phi = np.array([0.0, 1e-300, 1e3, np.inf, 1e-3])
    sol = model.of_twist(phi, a, d, g)
    M_full = model.sliding_torque(a[:1], d[:1])[0]
    assert sol.torque[0] == 0.0 and sol.stick_radius[0] == a[0]
    assert sol.torque[1] == pytest.approx(16 / 3 * G_T * 1e-300 * a[0] ** 3, rel=1e-12)
    assert sol.stick_radius[2] == 0.0 and sol.stick_radius[3] == 0.0
    assert sol.torque[2] == M_full and sol.torque[3] == M_full
    assert sol.torque[4] == 0.0            # no contact
    # signed twists: an odd curve
    neg = model.of_twist(-phi[:3], a[:3], d[:3], g[:3])
    assert np.array_equal(neg.torque, -sol.torque[:3])


def test_adhesive_states_and_other_profiles_keep_the_quadrature_route():
    a, d, g = _states(np.array([1e-4]))
    assert _torsion._hertz_p0(Paraboloid(R=R), E_STAR, a, d, g) is not None
    assert _torsion._hertz_p0(Paraboloid(R=R), E_STAR, a, d * 1.01, g) is None
    from contactlab.profiles import PowerLaw
    assert _torsion._hertz_p0(PowerLaw(c=1.0, n=3.0), E_STAR, a, d, g) is None
    # a power law with n = 2 is a paraboloid: same route, p0 = 4cE*a/π
    p0 = _torsion._hertz_p0(PowerLaw(c=1 / (2 * R), n=2.0), E_STAR, a, d, g)
    assert p0 == pytest.approx(2 * E_STAR * a / (np.pi * R), rel=1e-15)


def test_stick_radii_below_the_sliding_floor_are_full_sliding_as_on_the_quadrature_route():
    # y = 2G_tφ/(μp0) = 400 gives t = 4 exp(-401) ~ 1e-174 < C_MIN_REL: full sliding (c = 0),
    # as the quadrature route reports it (its kernels are not evaluated below C_MIN_REL a)
    model = _model()
    a, d, g = _states(np.array([1e-4, 1e-4]))
    p0 = 2 * E_STAR * a / (np.pi * R)
    phi = np.array([400.0, 200.0]) * MU * p0 / (2 * G_T)
    sol = model.of_twist(phi, a, d, g)
    assert sol.stick_radius[0] == 0.0 and sol.torque[0] == model.sliding_torque(a[:1], d[:1])[0]
    assert sol.stick_radius[1] == pytest.approx(4 * np.exp(-201.0) * a[1], rel=1e-12)
    assert _exact.C_MIN_REL * a[1] < sol.stick_radius[1]
