"""physics.normal.solve without its force error estimate (issue 13): the per-step normal states
of a load path discard the estimate, so they skip its arithmetic; depth, radius and force are
bit-identical to the full solve."""
from __future__ import annotations

import numpy as np
import pytest

import contactlab as cl
from contactlab.physics import normal as N
from contactlab.profiles import Cone, FlatPunch, Paraboloid, PowerLaw, Sphere, Tabulated

STEEL = cl.Elastic(E=210e9, nu=0.3)
_r = np.linspace(0.0, 3e-4, 400)
PROFILES = [Paraboloid(0.01), Cone(0.2), PowerLaw(1e3, 4.0), Sphere(0.01), FlatPunch(1e-3),
            Paraboloid(0.01) + Cone(0.1), Tabulated(_r, _r**2 / 0.02),
            Tabulated(_r, _r**2 / 0.02, "cubic")]
VALUES = {"depth": np.array([-1e-6, 0.0, 1e-9, 3e-7, 2e-6]),
          "force": np.array([0.0, 1e-3, 10.0, 30.0, 0.0])}


@pytest.mark.parametrize("prof", PROFILES, ids=repr)
@pytest.mark.parametrize("control", ["depth", "force"])
def test_without_error_estimate_bit_identical(prof, control):
    E = cl.Contact(prof, (STEEL, STEEL)).moduli.normal
    x = VALUES[control]
    full = N.solve(prof, E, control, x.copy(), 1e-10)
    bare = N.solve(prof, E, control, x.copy(), 1e-10, error_estimate=False)
    assert bare[3] is None and full[3] is not None
    for u, v in zip(full[:3], bare[:3]):
        assert u.shape == v.shape and np.array_equal(u, v)
    # all in contact (the branch without masking)
    pos = x[x > 0]
    full = N.solve(prof, E, control, pos, 1e-10)
    bare = N.solve(prof, E, control, pos, 1e-10, error_estimate=False)
    for u, v in zip(full[:3], bare[:3]):
        assert np.array_equal(u, v)
