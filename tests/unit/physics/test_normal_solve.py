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


@pytest.mark.parametrize("prof", [Paraboloid(0.01), Cone(0.2), PowerLaw(1e3, 4.0),
                                  PowerLaw(2e-2, 0.7)], ids=repr)
def test_all_positive_forces_shortcut_bit_identical(prof):
    """Forces all > 0 on a single power term skip the masks of the general route: the same
    radii and depths as that route (taken when one force is 0)."""
    E = cl.Contact(prof, (STEEL, STEEL)).moduli.normal
    F = np.linspace(1e-3, 300.0, 1001)
    a, d = N.radius_depth_of_force(prof, E, F, 1e-10)
    a0, d0 = N.radius_depth_of_force(prof, E, np.concatenate(([0.0], F)), 1e-10)
    assert a0[0] == 0 and d0[0] == 0
    assert np.array_equal(a, a0[1:]) and np.array_equal(d, d0[1:])
