"""ContactLaw.step(..., tangent=True): the tangent stiffness of every channel equals a central
finite difference of the law's own response along the current (Masing) branch, away from
reversals, on the compiled and the numpy route."""
from __future__ import annotations

import numpy as np
import pytest

import contactlab as cl
from contactlab import errors
from tests.tolerances import FIT_JACOBIAN_FD

SCALE = np.array([1.0, 0.5, 0.2])


def _law(fast, profile=cl.profiles.Paraboloid, torsion="exact", **geo):
    geo = geo or {"R": np.full(3, 0.01)}
    return cl.ContactLaw(profile, E_star=115e9, G_star=40e9, G_torsion=40e9, friction=0.3,
                         fast=fast, torsion=torsion, **geo)


@pytest.mark.parametrize("fast, torsion", [(True, "exact"), (False, "exact")])
@pytest.mark.parametrize("channel, out, key, amp", [
    ("displacement", "tangential_force", "tangential", 3e-7),
    ("twist", "torque", "torsional", 1e-4)])
@pytest.mark.parametrize("profile, geo", [(cl.profiles.Paraboloid, {"R": np.full(3, 0.01)}),
                                          (cl.profiles.Cone, {"slope": np.full(3, 0.05)})])
def test_tangent_is_the_derivative_on_a_masing_branch(fast, torsion, channel, out, key, amp,
                                                      profile, geo):
    law = _law(fast, profile, torsion, **geo)
    depth = np.full(3, 1e-6)
    for k in (0.2, 0.4, 0.6, 0.8, 1.0, 0.3):        # loading, then a reversal
        law.step(depth=depth, **{channel: amp * k * SCALE})
    state = law.state

    def at(x):
        law.state = state
        return law.step(depth=depth, tangent=True, **{channel: x * SCALE})

    x = 0.25 * amp                                  # on the unloading branch
    h = 1e-6 * x
    res = at(x)
    fd = (getattr(at(x + h), out) - getattr(at(x - h), out)) / (2 * h * SCALE)
    np.testing.assert_allclose(res.tangent[key], fd, rtol=FIT_JACOBIAN_FD)
    dn = (law.normal(depth=depth * (1 + 1e-7))[2] - law.normal(depth=depth * (1 - 1e-7))[2])
    np.testing.assert_allclose(res.tangent["normal"], dn / (2e-7 * depth), rtol=FIT_JACOBIAN_FD)
    other = "torsional" if key == "tangential" else "tangential"
    assert np.all(res.tangent[other] == 0.0)


def test_no_tangent_unless_asked_and_springs_refused():
    law = _law(True)
    assert law.step(depth=np.full(3, 1e-6), displacement=np.zeros(3)).tangent is None
    law = _law(True)                                # default: springs after a load change
    law.step(depth=np.full(3, 1e-6), displacement=np.full(3, 1e-8))
    with pytest.raises(errors.NotSupportedError, match="springs"):
        law.step(depth=np.full(3, 1.6e-6), displacement=np.full(3, 2e-8), tangent=True)
