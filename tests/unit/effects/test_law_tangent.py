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


def test_no_tangent_unless_asked():
    law = _law(True)
    assert law.step(depth=np.full(3, 1e-6), displacement=np.zeros(3)).tangent is None


@pytest.mark.parametrize("fast", [True, False])
@pytest.mark.parametrize("channel, out, key, amp", [
    ("displacement", "tangential_force", "tangential", 3e-7),
    ("twist", "torque", "torsional", 1e-4)])
@pytest.mark.parametrize("depth_now", [1.12, 1.08, 1.2])     # held, unloading, loading
def test_springs_tangent_is_the_derivative_under_changing_load(fast, channel, out, key, amp,
                                                                depth_now):
    """Contacts on springs (the normal load changed): the springs' sum of the sticking
    elements' stiffness equals a central difference of the law's own step response."""
    law = _law(fast)
    law.warn_model_error = False        # twisted on springs: the torque's model error warns
    d = np.full(3, 1e-6)
    for k, dk in ((0.2, 1.0), (0.4, 1.0), (0.6, 1.05), (0.8, 1.1), (1.0, 1.15), (0.3, 1.12)):
        law.step(depth=d * dk, **{channel: amp * k * SCALE})
    state = law.state

    def at(x):
        law.state = state
        return law.step(depth=d * depth_now, tangent=True, **{channel: x * SCALE})

    x = 0.25 * amp
    h = 1e-6 * x
    res = at(x)
    assert not np.any(res.exact)                    # on springs
    fd = (getattr(at(x + h), out) - getattr(at(x - h), out)) / (2 * h * SCALE)
    np.testing.assert_allclose(res.tangent[key], fd, rtol=FIT_JACOBIAN_FD)
    np.testing.assert_allclose(res.tangent["normal"],
                               2 * 115e9 * np.sqrt(0.01 * d * depth_now), rtol=1e-14)


def test_springs_tangent_on_the_step_that_leaves_the_held_load():
    """The first step after the load changes moves the contact onto springs inside the step:
    its start is the held load (depth_ref)."""
    for fast in (True, False):
        law = _law(fast)
        d = np.full(3, 1e-6)
        for k in (0.2, 0.5, 0.8):
            law.step(depth=d, displacement=3e-7 * k * SCALE)
        state = law.state

        def at(x, law=law, state=state, d=d):
            law.state = state
            return law.step(depth=1.05 * d, tangent=True, displacement=x * SCALE)
        x = 0.9 * 3e-7
        h = 1e-6 * x
        res = at(x)
        fd = (at(x + h).tangential_force - at(x - h).tangential_force) / (2 * h * SCALE)
        np.testing.assert_allclose(res.tangent["tangential"], fd, rtol=FIT_JACOBIAN_FD)


def test_overflowed_memory_refused():
    law = cl.ContactLaw(cl.profiles.Paraboloid, E_star=115e9, G_star=40e9, G_torsion=40e9,
                        friction=0.3, memory=2, springs=0, R=np.full(3, 0.01))
    d = np.full(3, 1e-6)
    with pytest.warns(errors.ValidityWarning, match="overflowed"):
        for u in (2e-7, -1.6e-7, 1.2e-7, -0.8e-7, 0.4e-7, -0.2e-7):
            law.step(depth=d, displacement=u * SCALE)
    with pytest.raises(errors.NotSupportedError, match="overflowed"):
        law.step(depth=d, displacement=-0.1e-7 * SCALE, tangent=True)
