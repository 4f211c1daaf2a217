"""``simulate(path, torque_rtol=...)``: the exact ring solver's rings chosen from a requested torque
accuracy (:func:`contactlab.foundation.rings.rings_for_rtol`, issue 28).

The error law (:data:`contactlab.foundation.rings.RTOL_LAW`) is checked where it is used: on a
ladder of 180-step twisted paths (Hertz, cone, a cubic table; force constant, ±30 % and ±40 %),
the largest torque error of the run at the chosen ring count, against a converged run at 400 rings
computed here, relative to the path's largest full-sliding torque ``2π μ ∫ p r² dr`` (the exact
torsion model's closed form), must be below the request less the reference's own error.
"""
from __future__ import annotations

import warnings

import numpy as np
import pytest

import contactlab as cl
from contactlab.errors import ParameterError
from contactlab.foundation import rings as _rings
from contactlab.physics.torsion import METHODS as TORSION_METHODS
from tests.tolerances import RINGS_RTOL_REFERENCE

MAT = (cl.Elastic(E=210e9, nu=0.3), cl.Rigid())
MU = 0.3
REF_RINGS = 400
_R_TAB = np.linspace(0.0, 4e-4, 300)
PROFILES = {
    "hertz": lambda: cl.profiles.Paraboloid(R=0.01),
    "cone": lambda: cl.profiles.Cone(0.01),
    "table": lambda: cl.profiles.Tabulated(r=_R_TAB, f=_R_TAB ** 2 / 0.02 + 2e3 * _R_TAB ** 3),
}


def _path(c, eps, n=180):
    """Force 10 N (1 + eps sin(4πt + 0.3)), twist 80 % of sliding at three cycles, ramped in."""
    t = np.arange(1, n + 1) / n
    force = 10.0 * (1 + eps * np.sin(2 * np.pi * 2 * t + 0.3))
    a_max = float(np.max(c.normal(force=force)._radius))
    s = MU * 10.0 / (c.moduli.torsional * a_max ** 2)
    phi = 0.8 * s * np.sin(2 * np.pi * 3 * t) * np.minimum(1, 2 * t)
    return cl.LoadPath.from_arrays(force=force, twist=phi), force


def _sliding(c, force):
    ns = c.normal(force=force)
    model = TORSION_METHODS["exact"](c.profile, c.moduli.normal, c.moduli.torsional, MU, c.rtol)
    return model.sliding_torque(np.asarray(ns._radius, float), np.asarray(ns._depth, float))


LADDER = [("hertz", 0.4), ("hertz", 0.0), ("cone", 0.3), ("table", 0.3), ("table", 0.0)]


@pytest.mark.parametrize("name,eps", LADDER)
def test_chosen_rings_meet_the_requested_torque_accuracy(name, eps):
    c = cl.Contact(PROFILES[name](), materials=MAT, friction=MU)
    path, force = _path(c, eps)
    scale = float(np.max(_sliding(c, force)))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        ref = c.simulate(path, method="exact", n_rings=REF_RINGS).torque
        for rtol in (1e-2, 3e-3, 1e-3):
            r = c.simulate(path, method="exact", torque_rtol=rtol)
            assert r.meta["n_rings"] == _rings.rings_for_rtol(rtol)
            err = float(np.max(np.abs(r.torque - ref))) / scale
            assert err < rtol - RINGS_RTOL_REFERENCE, (name, eps, rtol, err)


def test_rings_for_rtol_follows_the_stated_law():
    C, p = _rings.RTOL_LAW
    for rtol in (1e-4, 3e-4, 1e-3, 3e-3, 1e-2):
        n = _rings.rings_for_rtol(rtol)
        assert C * n ** -p <= rtol < C * (n - 1) ** -p
    assert _rings.rings_for_rtol(_rings.RTOL_RANGE[1]) == 16   # the coarsest measured count


@pytest.mark.parametrize("bad", [0.0, -1e-3, 0.5, 1e-6, float("nan"), float("inf"), "1e-3"])
def test_bad_torque_rtol_raises(bad):
    with pytest.raises(ParameterError, match="torque_rtol"):
        _rings.rings_for_rtol(bad)


def test_torque_rtol_with_n_rings_or_on_mdr_raises():
    c = cl.Contact(PROFILES["hertz"](), materials=MAT, friction=MU)
    path, _ = _path(c, 0.4, n=6)
    with pytest.raises(ParameterError, match="both given"):
        c.simulate(path, method="exact", torque_rtol=1e-3, n_rings=50)
    with pytest.raises(ParameterError, match="torque_rtol"):
        c.simulate(path, method="mdr", torque_rtol=1e-3)


def test_default_rings_unchanged_without_torque_rtol():
    c = cl.Contact(PROFILES["hertz"](), materials=MAT, friction=MU)
    path, _ = _path(c, 0.4, n=6)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        r = c.simulate(path)
    assert r.meta["n_rings"] == _rings.DEFAULT_N_RINGS


def test_error_estimate_with_torque_rtol_halves_the_chosen_rings():
    """Regression: the coarse run of ``error_estimate=True`` kept ``torque_rtol`` beside its
    halved ``n_rings`` and raised "both given"."""
    c = cl.Contact(PROFILES["hertz"](), materials=MAT, friction=MU)
    path, _ = _path(c, 0.4, n=12)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        r = c.simulate(path, torque_rtol=1e-2, error_estimate=True)
        half = c.simulate(path, method="exact", n_rings=_rings.rings_for_rtol(1e-2) // 2)
    full = r.torque
    expected = float(np.max(np.abs(full - half.torque))) / float(np.max(np.abs(full)))
    assert r.meta["n_rings"] == 45
    assert r.meta["error_estimates"]["torque"] == expected
