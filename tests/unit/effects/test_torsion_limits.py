"""Torsion at the ends of its range: the full-sliding torque prescribed, no contact, a twist
near the float's range.

- ``torque=`` the full-sliding torque gives the twist that reaches it: unbounded. ``inf`` is that
  limit, and it now comes with a ValidityWarning instead of silently.
- No numpy RuntimeWarning leaks from the states out of contact (a 0/0 masked afterwards) or from
  a twist that overflows the stick-radius variable (full sliding).
"""
import math
import warnings

import numpy as np
import pytest

import contactlab as cl
from contactlab.errors import ValidityWarning
from contactlab.profiles import Cone, Paraboloid
from tests.tolerances import CLOSED_FORM

STEEL = cl.Elastic(E=210e9, nu=0.3)
MU, F = 0.2, 100.0


def _contact(profile=None):
    return cl.Contact(profile or Paraboloid(R=0.01), materials=(STEEL, STEEL), friction=MU)


def test_full_sliding_torque_gives_an_unbounded_twist_with_a_warning():
    c = _contact()
    a = c.normal(force=F).radius
    M_full = 3 * math.pi / 16 * MU * F * a          # Lubkin: full sliding of a Hertz contact
    with pytest.warns(ValidityWarning, match=r"full-sliding torque.*twist=inf at 1 state"):
        t = c.torsion(force=[F, F], torque=[M_full, 0.5 * M_full])
    assert math.isinf(t.twist[0]) and t.slip[0]
    assert np.isfinite(t.twist[1]) and not t.slip[1]
    with warnings.catch_warnings():
        warnings.simplefilter("error")              # below the limit: no warning
        c.torsion(force=F, torque=0.5 * M_full)


def test_no_runtime_warning_out_of_contact_or_at_huge_twists():
    for prof in (Paraboloid(R=0.01), Cone(half_angle=math.radians(80))):
        c = _contact(prof)
        with warnings.catch_warnings():
            warnings.simplefilter("error", RuntimeWarning)
            t = c.torsion(force=[0.0, F], torque=[0.0, 1e-5])
            assert t.twist[0] == 0.0 and t.torque[0] == 0.0 and t.twist[1] > 0
    c = _contact()
    a = c.normal(force=F).radius
    with warnings.catch_warnings():
        warnings.simplefilter("error", RuntimeWarning)
        t = c.torsion(force=F, twist=1e300)
    assert t.stick_radius == 0.0 and t.slip
    assert t.torque == pytest.approx(3 * math.pi / 16 * MU * F * a, rel=CLOSED_FORM)
