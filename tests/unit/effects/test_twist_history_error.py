"""Honesty of TwistHistory.torque_error / error_estimate (issue 7).

The reference is the same history at rtol = 1e-13 (a converged second run): the estimate is
about the numerical error of the Masing history against the model's exact loading curve, whose
own accuracy against the independent mpmath closed forms is tested in tests/unit/effects/test_torsion*.py.
"""
from __future__ import annotations

import warnings

import numpy as np
import pytest

import contactlab as cl
from contactlab.errors import ValidityWarning
from tests import tolerances as TOL

STEEL = cl.Elastic(E=210e9, nu=0.3)
PROFILES = {"paraboloid": cl.profiles.Paraboloid(R=0.01), "cone": cl.profiles.Cone(slope=0.05),
            "n4": cl.profiles.PowerLaw(c=1e9, n=4)}
RTOLS = (1e-3, 1e-5, 1e-7, 1e-9, 1e-11)


def _history(prof, method, rtol):
    c = cl.Contact(prof, (STEEL, STEEL), friction=0.3, rtol=rtol)
    a = c.normal(force=50.0).radius
    t = np.linspace(0, 1, 241)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ValidityWarning)       # MDR beyond its 1 % range: intended
        slide = c.torsion(force=50.0, stick_radius=0.0, method=method).sliding_torque
        phi_ref = 3 * slide / (16 * c.moduli.torsional * a**3)
        twist = phi_ref * (0.9 * np.sin(6 * np.pi * t) * (1 - 0.5 * t) + 0.1 * t)   # irregular
        return c.twist_history(force=50.0, twist=twist, method=method)


@pytest.mark.parametrize("method", ["exact", "mdr"])
def test_history_error_estimate_is_honest(method):
    outcomes = []
    for name, prof in PROFILES.items():
        ref = _history(prof, method, 1e-13)
        amp = np.max(np.abs(ref.torque))
        for rtol in RTOLS:
            h = _history(prof, method, rtol)
            actual = np.max(np.abs(h.torque - ref.torque)) / amp
            est = h.error_estimate
            assert np.all(np.isfinite(h.torque_error)) and h.torque_error.shape == h.torque.shape
            outcomes.append((est >= actual, est <= 1e4 * max(actual, 1e-14), name, rtol, est,
                             actual))
    honest = sum(o[0] for o in outcomes) / len(outcomes)
    sane = sum(o[1] for o in outcomes) / len(outcomes)
    assert honest >= 0.95, [o for o in outcomes if not o[0]]
    assert sane >= 0.95, [o for o in outcomes if not o[1]]


def test_no_slip_history_error_is_rounding_level():
    c = cl.Contact(PROFILES["paraboloid"], (STEEL, STEEL))
    h = c.twist_history(force=50.0, twist=1e-4 * np.sin(np.linspace(0, 4 * np.pi, 50)))
    # closed form: only rounding, accumulated over the Masing recursion (a few reversals)
    assert 0 <= h.error_estimate < TOL.DEFAULT_RTOL_BOUND
