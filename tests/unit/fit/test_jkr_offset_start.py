"""A JKR fit with a free force offset on a curve with few detached samples.

The offset's start was the median of the first tenth of the samples by depth. When fewer than a
tenth are detached, that tenth runs into the attached branch (forces down to the pull-off force),
the start lies far below the baseline, and the fit converged to a wrong answer (E 7.7 % low,
the work of adhesion 78 % low, with relative errors of ~1 % reported). The baseline now ends at
the snap into contact.
"""
import numpy as np
import pytest

import contactlab as cl
from contactlab.profiles import Paraboloid

E, W, R, Z0 = 2e6, 0.05, 5e-6, 30e-9
FREE = ("E", "contact_point", "work_of_adhesion", "force_offset")
#: noise-free synthetic data from the forward model: the fit's own tolerance
RECOVER = 1e-8


def _curve(lo: float, n: int = 500):
    ct = cl.Contact(Paraboloid(R=R), (cl.Rigid(), cl.Elastic(E=E, nu=0.5)), work_of_adhesion=W)
    d = np.linspace(lo, 0.4e-6, n)
    return d + Z0, np.asarray(ct.normal(depth=d).force)


@pytest.mark.parametrize("lo", [-0.2e-6, -0.21e-6, -0.25e-6])
def test_jkr_fit_recovers_with_few_detached_samples(lo):
    z, F = _curve(lo)
    detached = int(np.sum(F == 0.0))
    assert 2 <= detached < 50          # fewer than the first tenth (50 samples)
    r = cl.fit.indentation(z, F, Paraboloid(R=R), sample=cl.Elastic(E=1e6, nu=0.5),
                           adhesion="jkr", free=FREE)
    assert r.params["E"] == pytest.approx(E, rel=RECOVER)
    assert r.params["work_of_adhesion"] == pytest.approx(W, rel=RECOVER)
    assert r.params["contact_point"] == pytest.approx(Z0, abs=RECOVER * Z0)
    # JKR's pull-off force (force control) scales the offset's tolerance
    assert abs(r.params["force_offset"]) < RECOVER * 1.5 * np.pi * W * R


def test_noisy_jkr_fit_with_few_detached_samples_is_within_its_errors():
    z, F = _curve(-0.21e-6)
    sigma = 1e-3 * 1.5 * np.pi * W * R
    Fn = F + np.random.default_rng(3).normal(0.0, sigma, F.size) + 2e-9
    r = cl.fit.indentation(z, Fn, Paraboloid(R=R), sample=cl.Elastic(E=1e6, nu=0.5),
                           adhesion="jkr", free=FREE)
    for name, true in (("E", E), ("work_of_adhesion", W), ("contact_point", Z0),
                       ("force_offset", 2e-9)):
        assert abs(r.params[name] - true) < 5 * r.stderr[name], name


@pytest.mark.parametrize("bad", [-1.0, 0.0, 1.0, np.nan, np.inf, "x", True])
def test_fit_rtol_is_checked(bad):
    from contactlab.errors import ParameterError
    z, F = _curve(-0.25e-6, n=100)
    with pytest.raises(ParameterError, match=r"rtol=.* is invalid: the model's relative tol"):
        cl.fit.indentation(z, F, Paraboloid(R=R), sample=cl.Elastic(E=1e6, nu=0.5),
                           adhesion="jkr", free=FREE, rtol=bad)
    u = np.sin(np.linspace(0.0, 2 * np.pi, 50)) * 1e-7
    with pytest.raises(ParameterError, match=r"rtol=.* is invalid"):
        cl.fit.tangential_loop(u, 1e-3 * u, 1.0, Paraboloid(R=R),
                               sample=cl.Elastic(E=E, nu=0.5), rtol=bad)


def test_undetermined_parameters_warn_instead_of_infinite_errors_silently():
    # a flat punch entirely in contact: F = 2 E* b (z - cp) + offset is linear in z, so the
    # contact point and the offset cannot be told apart (the covariance is singular)
    from contactlab.errors import ValidityWarning
    from contactlab.profiles import FlatPunch
    b, E_s = 1e-6, 2e6 / 0.75
    z = np.linspace(10e-9, 200e-9, 100)
    F = 2 * E_s * b * (z - 5e-9) + 1e-9
    with pytest.warns(ValidityWarning, match=r"do not determine .*'contact_point'"):
        r = cl.fit.indentation(z, F, FlatPunch(radius=b), sample=cl.Elastic(E=1e6, nu=0.5),
                               free=("E", "contact_point", "force_offset"))
    assert not np.isfinite(r.stderr["contact_point"])
    # the slope still fixes E (Sneddon's flat punch: dF/dz = 2 E* b)
    assert r.params["E"] == pytest.approx(2e6, rel=1e-9)
    np.testing.assert_allclose(r.model, F, rtol=1e-9)
