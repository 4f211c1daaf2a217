"""Loop fits recover friction and shear modulus from steady loops made here from independent
closed forms with Masing's rule: Mindlin-Deresiewicz (Hertz), the power-law Cattaneo-Mindlin
curve (cone) and Lubkin's exact Hertz torsion (Jäger); the loop Jacobian against finite
differences."""
from __future__ import annotations

import numpy as np
import pytest
from scipy.integrate import quad
from scipy.special import ellipe, ellipk

import contactlab as cl
from contactlab import Elastic, errors
from contactlab.fit import tangential_loop, torsion_loop
from contactlab.fit.loops import _loop_model
from contactlab.profiles import Cone, Paraboloid
from tests.tolerances import FIT_JACOBIAN_FD, FIT_RECOVERY

R, FN, MU = 0.01, 100.0, 0.3
STEEL = Elastic(E=210e9, nu=0.3)
G_STAR = 4 * STEEL.G / (2 - STEEL.nu)        # rigid tip


def _normal(profile):
    st = cl.Contact(profile, (cl.Rigid(), STEEL)).normal(force=FN)
    return float(st.radius), float(st.depth)


def _loop(load, x0, n=200):
    """A steady Masing loop of amplitude x0 from the virgin curve ``load``: down, then up."""
    down = np.linspace(x0, -x0, n)
    up = np.linspace(-x0, x0, n)[1:]
    L0 = load(x0)
    return (np.concatenate([down, up]),
            np.concatenate([L0 - 2 * load((x0 - down) / 2), -L0 + 2 * load((x0 + up) / 2)]))


def test_mindlin_deresiewicz_hertz_loop():
    a, _ = _normal(Paraboloid(R=R))
    u_star = 3 * MU * FN / (4 * a * G_STAR)

    def load(u):
        return MU * FN * (1 - (1 - np.minimum(u / u_star, 1)) ** 1.5)

    x, y = _loop(load, 0.7 * u_star)
    res = tangential_loop(x + 3e-9, y, FN, Paraboloid(R=R), sample=Elastic(E=210e9, nu=0.3))
    assert abs(res.params["friction"] / MU - 1) < FIT_RECOVERY
    assert abs(res.params["shear_modulus"] / STEEL.G - 1) < FIT_RECOVERY
    assert res.params["G_star"] == pytest.approx(G_STAR, rel=FIT_RECOVERY)
    assert res.contact.friction == res.params["friction"]
    assert list(res.to_dict())[:2] == ["displacement", "tangential_force"]


def test_cone_loop_with_fixed_friction():
    s = 0.1
    _, d = _normal(Cone(slope=s))
    u_star = MU * (STEEL.E / (1 - STEEL.nu ** 2)) * d / G_STAR

    def load(u):                                 # n = 1: F = μF_N[1 - (1 - u/u*)²]
        return MU * FN * (1 - (1 - np.minimum(u / u_star, 1)) ** 2)

    x, y = _loop(load, 0.5 * u_star)
    res = tangential_loop(x, y, FN, Cone(slope=s), sample=STEEL, free="shear_modulus",
                          friction=MU)
    assert abs(res.params["shear_modulus"] / STEEL.G - 1) < FIT_RECOVERY
    assert res.free == ("shear_modulus",)


def _lubkin(t, a, Gt):
    """Lubkin's Hertz torsion at stick ratio t = c/a: twist and torque."""
    k2 = 1 - t * t
    phi = 3 * MU * FN / (4 * np.pi * Gt * a * a) * (ellipk(k2) - ellipe(k2))
    integral = np.array([quad(lambda q: q * q * ellipe(1 - q * q), 0, tt, epsrel=1e-13)[0]
                         for tt in np.atleast_1d(t)])
    return phi, MU * FN * a * (3 * np.pi / 16 - 4 / np.pi * integral)


def test_jaeger_torsion_loop_hertz():
    a, _ = _normal(Paraboloid(R=R))
    Gt = STEEL.G
    phi0, M0 = _lubkin(np.array([0.3]), a, Gt)
    phi_v, M_v = _lubkin(np.linspace(1.0, 0.3, 250), a, Gt)    # v from 0 to phi0
    x = np.concatenate([phi0 - 2 * phi_v, (-phi0 + 2 * phi_v)[1:]])
    y = np.concatenate([M0 - 2 * M_v, (-M0 + 2 * M_v)[1:]])
    res = torsion_loop(x, y, FN, Paraboloid(R=R), sample=Elastic(E=210e9, nu=0.3))
    assert abs(res.params["friction"] / MU - 1) < FIT_RECOVERY
    assert abs(res.params["shear_modulus"] / Gt - 1) < FIT_RECOVERY
    assert 0 < res.model_error < 1e-12           # the master curve's certified error


def test_loop_jacobian_against_finite_differences():
    """The Masing loop's derivatives from the scaling L = μ l(x G/μ), for a load written
    here (power law n = 3/2 Cattaneo-Mindlin with its slope 2G*c)."""
    n = 1.5

    def load(u, mu, G):
        us = mu * 1e-6 / G * 1e11
        r = np.clip(1 - u / us, 0, None)
        return mu * FN * (1 - r ** ((n + 1) / n)), mu * FN * (n + 1) / n * r ** (1 / n) / us

    def G_of(G):
        return 2.0 * G, 2.0

    x = np.concatenate([np.linspace(4e-7, -4e-7, 60), np.linspace(-4e-7, 4e-7, 60)[1:]])
    start = {"friction": MU, "shear_modulus": 3e10}
    parts = _loop_model(x, ("friction", "shear_modulus"), 0.0, 4e-7, load, G_of, start, {})
    p = np.array([0.1, -0.2])
    _, _, der = parts(p)
    h = 1e-6
    for i, name in enumerate(("friction", "shear_modulus")):
        e = np.zeros(2)
        e[i] = h
        fd = (parts(p + e)[1] - parts(p - e)[1]) / (2 * h)
        np.testing.assert_allclose(der[name], fd, rtol=0,
                                   atol=FIT_JACOBIAN_FD * np.max(np.abs(fd)))


@pytest.mark.parametrize("kw, err, text", [
    ({"force": -1.0}, errors.ParameterError, "force=-1.0"),
    ({"free": ("friction", "E")}, errors.UnknownNameError, "'E'"),
    ({"free": ("shear_modulus",)}, errors.ParameterError, "friction=..."),
])
def test_loop_bad_input(kw, err, text):
    x = np.linspace(-1e-7, 1e-7, 50)
    args = {"force": FN, **kw}
    with pytest.raises(err, match=text):
        tangential_loop(x, np.sin(x * 1e7), args.pop("force"), Paraboloid(R=R), sample=STEEL,
                        **args)
    with pytest.raises(errors.ParameterError, match="equal length"):
        tangential_loop(x, x[:-1], FN, Paraboloid(R=R), sample=STEEL)
    with pytest.raises(errors.ParameterError, match=r"twist\[3\]=nan"):
        torsion_loop(np.r_[x[:3], np.nan, x[4:]], x, FN, Paraboloid(R=R), sample=STEEL)


def _md_loop():
    """The Mindlin-Deresiewicz loop (Hertz, friction MU, the steel's shear modulus)."""
    a, _ = _normal(Paraboloid(R=R))
    u_star = 3 * MU * FN / (4 * a * G_STAR)

    def load(u):
        return MU * FN * (1 - (1 - np.minimum(u / u_star, 1)) ** 1.5)

    return _loop(load, 0.7 * u_star)


@pytest.mark.parametrize("start", [{"shear_modulus": 1e3},
                                   {"friction": 10.0, "shear_modulus": 1e3},
                                   {"friction": 1e-8}])
def test_loop_far_start_recovers(start):
    """A start far below the truth overflowed the solver's trial steps (ZeroDivisionError):
    a step out of the model's range is now rejected, and the fit reaches Mindlin-Deresiewicz's
    values."""
    x, y = _md_loop()
    res = tangential_loop(x, y, FN, Paraboloid(R=R), sample=STEEL, start=start)
    assert abs(res.params["friction"] / MU - 1) < FIT_RECOVERY
    assert abs(res.params["shear_modulus"] / STEEL.G - 1) < FIT_RECOVERY
    assert all(np.isfinite(v) for v in res.stderr.values())


def test_loop_stuck_start_raises_convergence_error():
    """From a shear modulus 10^4 times too high the loop is the no-slip line wherever the
    solver goes: it stops where the loop does not determine the parameters, which was returned
    with infinite standard errors; now a ConvergenceError names the parameters."""
    x, y = _md_loop()
    with pytest.raises(errors.ConvergenceError, match="shear_modulus.*start=") as info:
        tangential_loop(x, y, FN, Paraboloid(R=R), sample=STEEL,
                        start={"shear_modulus": 1e15})
    assert "shear_modulus=1000000000000000.0" in str(info.value)


@pytest.mark.parametrize("start", [{"shear_modulus": 1e3}, {"shear_modulus": 1e8},
                                   {"shear_modulus": 1e15}])
def test_torsion_loop_far_start_no_zero_division(start):
    """Lubkin's Hertz torsion loop from far starts: Jäger's values, or a ConvergenceError
    naming the parameters (was ZeroDivisionError, or a ParameterError calling the slipping
    loop one that never slips)."""
    a, _ = _normal(Paraboloid(R=R))
    phi0, M0 = _lubkin(np.array([0.3]), a, STEEL.G)
    phi_v, M_v = _lubkin(np.linspace(1.0, 0.3, 120), a, STEEL.G)
    x = np.concatenate([phi0 - 2 * phi_v, (-phi0 + 2 * phi_v)[1:]])
    y = np.concatenate([M0 - 2 * M_v, (-M0 + 2 * M_v)[1:]])
    try:
        res = torsion_loop(x, y, FN, Paraboloid(R=R), sample=STEEL, start=start)
    except errors.ConvergenceError as err:      # a named failure, never ZeroDivisionError
        assert "shear_modulus=" in str(err) and "start=" in str(err)
    else:
        assert abs(res.params["friction"] / MU - 1) < FIT_RECOVERY
        assert abs(res.params["shear_modulus"] / STEEL.G - 1) < FIT_RECOVERY


@pytest.mark.parametrize("kw, err, text", [
    ({"start": {"friction": 0}}, errors.ParameterError, r"start\['friction'\]=0 is invalid"),
    ({"start": {"shear_modulus": -8e10}}, errors.ParameterError,
     r"start\['shear_modulus'\]=-80000000000.0 is invalid"),
    ({"start": {"shear_modulus": np.nan}}, errors.ParameterError, "nan is invalid"),
    ({"start": {"friction": "a"}}, errors.ParameterError, r"start\['friction'\]='a'"),
    ({"start": [0.3]}, errors.ParameterError, r"start=\[0.3\] is invalid: give a dict"),
    ({"start": {"zzz": 0.3}}, errors.UnknownNameError, r"'zzz'.*\('friction', 'shear_modulus'\)"),
    ({"free": 5}, errors.ParameterError, "free=5 is invalid"),
])
@pytest.mark.parametrize("fit", [tangential_loop, torsion_loop])
def test_loop_bad_arguments_named(fit, kw, err, text):
    """Each was a bare ZeroDivisionError/TypeError, or (an unknown name) silently ignored."""
    x, y = _md_loop()
    with pytest.raises(err, match=text):
        fit(x, y, FN, Paraboloid(R=R), sample=STEEL, **kw)
