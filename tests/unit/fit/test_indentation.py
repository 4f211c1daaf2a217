"""fit.indentation recovers the parameters of curves made from closed forms written here
(Hertz, Sneddon's exact sphere, the cone), on every tip route, with exact derivatives; its
errors for bad input name what is wrong."""
from __future__ import annotations

import numpy as np
import pytest

import contactlab as cl
from contactlab import Elastic, errors
from contactlab.fit import FitResult, indentation
from contactlab.fit._tip import TipModel
from contactlab.materials.viscoelastic import StandardLinearSolid
from contactlab.profiles import Cone, Paraboloid, Sphere, Tabulated
from tests.tolerances import FIT_JACOBIAN_FD, FIT_RECOVERY

E, NU, R, Z0 = 2e6, 0.5, 5e-6, 12e-9
ESTAR = E / (1 - NU ** 2)
SAMPLE = Elastic(E=1e6, nu=NU)
Z = np.linspace(-60e-9, 240e-9, 2000)


def hertz(z, e_star=ESTAR, z0=Z0, off=0.0):
    d = np.maximum(z - z0, 0.0)
    return 4.0 / 3.0 * e_star * np.sqrt(R) * d ** 1.5 + off


def sphere_curve(a_max, n=1500, z0=Z0):
    """Sneddon's exact sphere, parametric in the contact radius."""
    a = np.linspace(0.0, a_max, n)
    d = a / 2 * np.log((R + a) / (R - a))
    F = ESTAR * ((a * a + R * R) / 2 * np.log((R + a) / (R - a)) - a * R)
    before = np.linspace(-0.2 * d[-1], 0.0, 200, endpoint=False)
    return np.concatenate([before, d]) + z0, np.concatenate([np.zeros(200), F])


def rel(a, b):
    return abs(a / b - 1.0)


def test_hertz_recovers_modulus_and_contact_point():
    res = indentation(Z, hertz(Z), Paraboloid(R=R), sample=SAMPLE)
    assert rel(res.params["E"], E) < FIT_RECOVERY
    assert rel(res.params["contact_point"], Z0) < FIT_RECOVERY
    assert isinstance(res, FitResult) and res.free == ("E", "contact_point")
    assert res.contact.materials[1].E == res.params["E"]


def test_hertz_with_force_offset():
    res = indentation(Z, hertz(Z, off=3e-9), Paraboloid(R=R), sample=SAMPLE,
                      free=("E", "contact_point", "force_offset"))
    assert rel(res.params["E"], E) < FIT_RECOVERY
    assert rel(res.params["contact_point"], Z0) < FIT_RECOVERY
    assert rel(res.params["force_offset"], 3e-9) < FIT_RECOVERY


def test_elastic_tip_enters_through_the_effective_modulus():
    tip = Elastic(E=5e6, nu=0.3)
    e_star = 1.0 / ((1 - NU ** 2) / E + (1 - 0.3 ** 2) / 5e6)
    res = indentation(Z, hertz(Z, e_star), Paraboloid(R=R), sample=SAMPLE, tip=tip)
    assert rel(res.params["E"], E) < FIT_RECOVERY


def test_cone():
    s = 0.2                                     # F = 2E*δ²/(π s) for f = s r
    d = np.maximum(Z - Z0, 0.0)
    F = 2 * ESTAR * d * d / (np.pi * s)
    res = indentation(Z, F, Cone(slope=s), sample=SAMPLE)
    assert rel(res.params["E"], E) < FIT_RECOVERY
    assert rel(res.params["contact_point"], Z0) < FIT_RECOVERY


def test_exact_sphere_and_the_paraboloid_bias():
    z, F = sphere_curve(0.6 * R)                # deep: a/R = 0.6
    res = indentation(z, F, Sphere(R=R), sample=SAMPLE)
    assert res.meta["tip_route"] == "newton"
    assert rel(res.params["E"], E) < FIT_RECOVERY
    assert rel(res.params["contact_point"], Z0) < FIT_RECOVERY
    par = indentation(z, F, Paraboloid(R=R), sample=SAMPLE)
    assert rel(par.params["E"], E) > 0.02      # the paraboloid's bias on deep sphere data
    assert np.max(np.abs(par.residuals)) > 1e3 * np.max(np.abs(res.residuals))


def test_tabulated_sphere_tip_within_its_table_error():
    z, F = sphere_curve(0.4 * R)
    r = np.linspace(0.0, 0.5 * R, 4001)
    tab = Tabulated(r, R - np.sqrt(R * R - r * r))
    res = indentation(z, F, tab, sample=SAMPLE)
    assert res.meta["tip_route"] == "table"
    # the table's own distance from the sphere: its force at unit modulus, from its exact
    # routes, against Sneddon's, over the data
    a = np.linspace(0.05 * R, 0.4 * R, 50)
    d = a / 2 * np.log((R + a) / (R - a))
    at = tab._radius_of_depth(d, 1e-12)
    phi_tab = 2 * (at * d - tab._g_integral(at, 1e-12))
    phi = (a * a + R * R) / 2 * np.log((R + a) / (R - a)) - a * R
    bound = np.max(np.abs(phi_tab / phi - 1)) + res.model_error
    assert 0 < res.model_error < 1e-5
    assert rel(res.params["E"], E) < 3 * bound


@pytest.mark.parametrize("profile", [Paraboloid(R=R), Cone(slope=0.3), Sphere(R=R),
                                     Paraboloid(R=R) + Cone(slope=0.05),
                                     Tabulated(np.linspace(0, 2e-6, 301),
                                               np.linspace(0, 2e-6, 301) ** 2 / (2 * R))])
def test_tip_slope_is_the_derivative(profile):
    m = TipModel(profile, 3e-7)
    d = np.linspace(2e-9, 2.5e-7, 40)
    h = 1e-6 * d
    fd = (m(d + h)[0] - m(d - h)[0]) / (2 * h)
    np.testing.assert_allclose(m(d)[1], fd, rtol=FIT_JACOBIAN_FD)


@pytest.mark.parametrize("profile", [Paraboloid(R=R), Sphere(R=R)])
def test_tip_slope_is_twice_the_contact_radius(profile):
    m = TipModel(profile, 3e-7)
    d = np.linspace(1e-9, 2.5e-7, 30)
    np.testing.assert_allclose(m(d)[1], 2 * profile._radius_of_depth(d, 1e-14), rtol=1e-12)


def test_noisy_fit_interval_and_errors():
    rng = np.random.default_rng(4)
    F = hertz(Z) + rng.normal(0.0, 2e-10, Z.size)
    res = indentation(Z, F, Paraboloid(R=R), sample=SAMPLE)
    lo, hi = res.confidence(0.95)["E"]
    assert lo < res.params["E"] < hi
    assert abs(res.params["E"] - E) < 5 * res.stderr["E"]
    assert res.covariance.shape == (2, 2)
    np.testing.assert_allclose(res.residuals, res.model - F, rtol=0, atol=1e-20)
    with pytest.raises(errors.ParameterError, match="level"):
        res.confidence(1.5)


def test_same_call_same_bits():
    a = indentation(Z, hertz(Z), Sphere(R=R), sample=SAMPLE)
    b = indentation(Z, hertz(Z), Sphere(R=R), sample=SAMPLE)
    assert a.params == b.params and a.stderr == b.stderr


@pytest.mark.slow
def test_coverage_of_the_95_percent_interval():
    rng = np.random.default_rng(30)
    hits = {"E": 0, "contact_point": 0}
    n = 200
    clean = hertz(Z)
    for _ in range(n):
        res = indentation(Z, clean + rng.normal(0.0, 3e-10, Z.size), Paraboloid(R=R),
                          sample=SAMPLE)
        ci = res.confidence(0.95)
        hits["E"] += ci["E"][0] <= E <= ci["E"][1]
        hits["contact_point"] += ci["contact_point"][0] <= Z0 <= ci["contact_point"][1]
    for k, v in hits.items():
        assert 0.90 * n <= v <= 0.99 * n, (k, v)


# ---------------------------------------------------------------------- bad input
@pytest.mark.parametrize("depth, force, kw, err, text", [
    (np.r_[Z[:-1], np.nan], hertz(Z), {}, errors.ParameterError, r"depth\[1999\]=nan"),
    (Z, np.r_[hertz(Z)[:-1], np.inf], {}, errors.ParameterError, r"force\[1999\]=inf"),
    (Z[:-1], hertz(Z), {}, errors.ParameterError, "equal length"),
    (Z, hertz(Z), {"free": ("E", "radius")}, errors.UnknownNameError, "radius"),
    (Z, hertz(Z), {"free": ("E", "nu")}, errors.ParameterError, "nu"),
    (Z, np.zeros_like(Z), {}, errors.ParameterError, "never reaches contact"),
    (Z, -hertz(Z), {}, errors.ParameterError, "never reaches contact"),
    (Z, hertz(Z), {"adhesion": "dmt"}, errors.ParameterError, "work of adhesion"),
    (Z, hertz(Z), {"adhesion": "jkr"}, errors.ParameterError, "work of adhesion"),
    (Z, hertz(Z), {"adhesion": "glue"}, errors.ParameterError, "adhesion='glue'"),
    (Z, hertz(Z), {"free": ("E", "work_of_adhesion")}, errors.ParameterError, "jkr"),
])
def test_bad_input_names_the_problem(depth, force, kw, err, text):
    with pytest.raises(err, match=text):
        indentation(depth, force, Paraboloid(R=R), sample=SAMPLE, **kw)


@pytest.mark.parametrize("kw, err, text", [
    ({"start": {"E": 0.0}}, errors.ParameterError, r"start\['E'\]=0.0 is invalid.*> 0"),
    ({"start": {"E": -1.0}}, errors.ParameterError, r"start\['E'\]=-1.0 is invalid"),
    ({"start": {"E": np.inf}}, errors.ParameterError, r"start\['E'\]=inf is invalid"),
    ({"start": {"contact_point": np.nan}}, errors.ParameterError,
     r"start\['contact_point'\]=nan is invalid: .* finite"),
    ({"start": {"E": "x"}}, errors.ParameterError, r"start\['E'\]='x' is invalid"),
    ({"start": [1, 2]}, errors.ParameterError, r"start=\[1, 2\] is invalid: give a dict"),
    ({"start": {"Q": 1.0}}, errors.UnknownNameError, r"'Q'.*\('E', 'contact_point'\)"),
    ({"start": {"force_offset": 0.0}}, errors.UnknownNameError, "'force_offset', which is not "
     "fitted"),
    ({"free": 3}, errors.ParameterError, "free=3 is invalid: give a parameter name"),
    ({"free": ("E", None)}, errors.ParameterError, "holds None"),
    ({"adhesion": "jkr", "work_of_adhesion": "a"}, errors.ParameterError,
     "work_of_adhesion='a' is invalid"),
    ({"adhesion": "dmt", "work_of_adhesion": 0.05, "equilibrium_distance": "x"},
     errors.ParameterError, "equilibrium_distance='x' is invalid"),
    ({"adhesion": "dmt", "work_of_adhesion": 0.05, "equilibrium_distance": -3.0},
     errors.ParameterError, "equilibrium_distance=-3.0 is invalid"),
    ({"work_of_adhesion": 5.0}, errors.ParameterError,
     "work_of_adhesion=5.0 is given but adhesion=None"),
    ({"equilibrium_distance": -3.0}, errors.ParameterError,
     "equilibrium_distance=-3.0 is given but adhesion=None"),
])
def test_bad_arguments_raise_named_errors(kw, err, text):
    """Each was a bare TypeError/ValueError/ZeroDivisionError, or silently ignored."""
    with pytest.raises(err, match=text):
        indentation(Z, hertz(Z), Paraboloid(R=R), sample=SAMPLE, **kw)


def test_start_with_a_unit_and_a_valid_start_still_fit():
    res = indentation(Z, hertz(Z), Paraboloid(R=R), sample=SAMPLE,
                      start={"E": "1 MPa", "contact_point": 0.0})
    assert rel(res.params["E"], E) < FIT_RECOVERY
    assert rel(res.params["contact_point"], Z0) < FIT_RECOVERY


@pytest.mark.parametrize("level", ["high", None, 1.0, 0.0, np.nan, True])
def test_confidence_level_checked(level):
    res = indentation(Z, hertz(Z), Paraboloid(R=R), sample=SAMPLE)
    with pytest.raises(errors.ParameterError, match="level=.* is invalid: the confidence level"):
        res.confidence(level)


def test_bad_parts():
    with pytest.raises(errors.ParameterError, match="profile"):
        indentation(Z, hertz(Z), "sphere", sample=SAMPLE)
    with pytest.raises(errors.ParameterError, match="sample"):
        indentation(Z, hertz(Z), Paraboloid(R=R), sample=cl.Rigid())
    with pytest.raises(errors.NotSupportedError, match="wall"):      # Ting's rule with a wall
        indentation(Z, hertz(Z), cl.profiles.FlatPunch(radius=1e-6) + Paraboloid(R=R),
                    time=np.arange(Z.size),
                    sample=StandardLinearSolid(G_inf=1e4, G_1=1e4, eta_1=1e4))
    # a flat punch is covered (issue 30); Hertz data on it: a named error, no raw traceback
    with pytest.raises(errors.ConvergenceError, match="went to"):
        indentation(Z, hertz(Z), cl.profiles.FlatPunch(radius=1e-6), time=np.arange(Z.size),
                    sample=StandardLinearSolid(G_inf=1e4, G_1=1e4, eta_1=1e4))


def test_fit_is_reachable_lazily():
    assert cl.fit.indentation is indentation
