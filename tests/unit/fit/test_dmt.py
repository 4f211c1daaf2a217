"""DMT fits recover the parameters of curves made from the DMT closed form written here (Hertz
or Sneddon's exact sphere less 2πRΔγ in contact [DMT75]); the Tabor parameter warns outside the
DMT range; tips without an apex curvature are refused by name."""
from __future__ import annotations

import warnings

import numpy as np
import pytest

from contactlab import Elastic, errors
from contactlab.fit import indentation
from contactlab.profiles import Cone, Paraboloid, PowerLaw, Sphere
from tests.tolerances import FIT_RECOVERY

E, NU, R, Z0, W = 2e6, 0.5, 5e-6, 12e-9, 0.05
ESTAR = E / (1 - NU ** 2)
SAMPLE = Elastic(E=1e6, nu=NU)
Z = np.linspace(-60e-9, 240e-9, 2000)
ALL = ("E", "contact_point", "work_of_adhesion", "force_offset")


def dmt_paraboloid(z, off=0.0):
    d = np.maximum(z - Z0, 0.0)
    return 4 / 3 * ESTAR * np.sqrt(R) * d ** 1.5 - 2 * np.pi * R * W * (z > Z0) + off


@pytest.mark.parametrize("off", [0.0, 2e-9])
def test_paraboloid_recovered(off):
    res = indentation(Z, dmt_paraboloid(Z, off), Paraboloid(R=R), sample=SAMPLE,
                      adhesion="dmt", free=ALL)
    for k, want in {"E": E, "contact_point": Z0, "work_of_adhesion": W}.items():
        assert res.params[k] == pytest.approx(want, rel=FIT_RECOVERY)
    assert res.params["force_offset"] == pytest.approx(off, abs=FIT_RECOVERY * 2 * np.pi * R * W)
    assert res.meta["apex_radius"] == R
    assert res.contact.work_of_adhesion is None          # DMT is not the contact's JKR model


def test_exact_sphere_recovered():
    a = np.linspace(0.0, 1.5e-6, 1500)[1:]
    d = a / 2 * np.log((R + a) / (R - a))
    F = ESTAR * ((a * a + R * R) / 2 * np.log((R + a) / (R - a)) - a * R) - 2 * np.pi * R * W
    before = np.linspace(-0.2 * d[-1], 0.0, 200)
    z = np.concatenate([before, d]) + Z0
    force = np.concatenate([np.zeros(200), F])
    res = indentation(z, force, Sphere(R=R), sample=SAMPLE, adhesion="dmt",
                      free=("E", "contact_point", "work_of_adhesion"))
    for k, want in {"E": E, "contact_point": Z0, "work_of_adhesion": W}.items():
        assert res.params[k] == pytest.approx(want, rel=FIT_RECOVERY)


def test_fixed_work_of_adhesion():
    res = indentation(Z, dmt_paraboloid(Z), Paraboloid(R=R), sample=SAMPLE, adhesion="dmt",
                      work_of_adhesion=W)
    assert res.params["E"] == pytest.approx(E, rel=FIT_RECOVERY)
    assert res.params["work_of_adhesion"] == W


def test_tabor_parameter_warns_outside_dmt():
    with pytest.warns(errors.ValidityWarning, match="outside the DMT limit"):
        res = indentation(Z, dmt_paraboloid(Z), Paraboloid(R=R), sample=SAMPLE, adhesion="dmt",
                          free=("E", "contact_point", "work_of_adhesion"),
                          equilibrium_distance=0.3e-9)
    mu = (R * W * W / (ESTAR ** 2 * 0.3e-9 ** 3)) ** (1 / 3)
    assert res.meta["tabor_parameter"] == pytest.approx(mu, rel=1e-6)
    # a stiff sample and a sharp tip: inside the DMT range, no warning
    Rs, Es, z0 = 10e-9, 100e9, 0.3e-9
    zz = np.linspace(-0.5e-9, 2e-9, 400)
    dd = np.maximum(zz - 0.2e-9, 0.0)
    es = Es / (1 - 0.3 ** 2)
    ff = 4 / 3 * es * np.sqrt(Rs) * dd ** 1.5 - 2 * np.pi * Rs * W * (zz > 0.2e-9)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        res = indentation(zz, ff, Paraboloid(R=Rs), sample=Elastic(E=1e9, nu=0.3),
                          adhesion="dmt", free=("E", "contact_point", "work_of_adhesion"),
                          equilibrium_distance=z0)
    assert res.meta["tabor_parameter"] < 0.1
    assert res.params["E"] == pytest.approx(Es, rel=FIT_RECOVERY)


def test_apex_radius_of_a_sum_and_refusals():
    from contactlab.fit.indentation import _apex_radius
    assert _apex_radius(Paraboloid(R=R) + PowerLaw(c=1e12, n=4.0)) == pytest.approx(R, rel=1e-15)
    assert _apex_radius(Sphere(R=R)) == R
    with pytest.raises(errors.NotSupportedError, match="apex"):
        indentation(Z, dmt_paraboloid(Z), Cone(slope=0.3), sample=SAMPLE, adhesion="dmt",
                    work_of_adhesion=W)
    with pytest.raises(errors.ParameterError, match="work of adhesion"):
        indentation(Z, dmt_paraboloid(Z), Paraboloid(R=R), sample=SAMPLE, adhesion="dmt")
    with pytest.raises(errors.ParameterError, match="adhesion='vdw'"):
        indentation(Z, dmt_paraboloid(Z), Paraboloid(R=R), sample=SAMPLE, adhesion="vdw")


@pytest.mark.slow
def test_coverage_of_the_95_percent_interval():
    """With noise, the 95 % intervals of E, the contact point and Δγ cover the truth in 90-99 %
    of 200 repetitions."""
    rng = np.random.default_rng(31)
    free = ("E", "contact_point", "work_of_adhesion")
    hits = dict.fromkeys(free, 0)
    n = 200
    clean = dmt_paraboloid(Z)
    truth = {"E": E, "contact_point": Z0, "work_of_adhesion": W}
    for _ in range(n):
        res = indentation(Z, clean + rng.normal(0.0, 3e-10, Z.size), Paraboloid(R=R),
                          sample=SAMPLE, adhesion="dmt", free=free)
        ci = res.confidence(0.95)
        for k in free:
            hits[k] += ci[k][0] <= truth[k] <= ci[k][1]
    for k, v in hits.items():
        assert 0.90 * n <= v <= 0.99 * n, (k, v)
