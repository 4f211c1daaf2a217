"""A profile's lengths (radii of curvature, punch radii) within [1e-30, 1e10] m: beyond them
float64 gave raw errors or overflow (a sphere of 1e-200 m: ZeroDivisionError; of 1e60 m: an
overflow warning out of the solve; a paraboloid of 1e200 m: a contact radius needed beyond
max_radius=inf). Every physical contact lies far inside. At both ends of the range the normal
solve gives the closed forms: Hertz, the sphere's exact MDR forms and Sneddon's flat punch."""
from __future__ import annotations

import math
import re

import numpy as np
import pytest

import contactlab as cl
from contactlab.errors import ParameterError
from contactlab.params import LENGTH_BOUNDS

MATERIALS = (cl.Elastic(E=1e9, nu=0.3), cl.Rigid())
E_STAR = 1e9 / (1 - 0.3**2)

MAKERS = {
    "paraboloid": (lambda L: cl.profiles.Paraboloid(R=L), "R", "radius of curvature R"),
    "sphere": (lambda L: cl.profiles.Sphere(R=L), "R", "sphere radius R"),
    "flat punch": (lambda L: cl.profiles.FlatPunch(radius=L), "radius", "punch radius"),
    "truncated paraboloid (b)": (lambda L: cl.profiles.TruncatedParaboloid(radius=L, R=1.0),
                                 "radius", "flat radius b"),
    "truncated paraboloid (R)": (lambda L: cl.profiles.TruncatedParaboloid(radius=1e-3, R=L),
                                 "R", "edge rounding radius R"),
    "truncated cone": (lambda L: cl.profiles.TruncatedCone(radius=L, slope=0.1), "radius",
                       "flat radius b"),
}


def test_the_bounds():
    assert LENGTH_BOUNDS == (1e-30, 1e10)


@pytest.mark.parametrize("name", list(MAKERS))
@pytest.mark.parametrize("length", [1e-200, 9.9e-31, 1.01e10, 1e60, 1e200])
def test_lengths_outside_the_bounds_are_refused_naming_the_parameter(name, length):
    make, key, what = MAKERS[name]
    with pytest.raises(ParameterError, match=rf"{key}={re.escape(repr(length))} is invalid: {what} must lie "
                                             r"between 1e-30 and 1e\+10 m \(check the units\)"):
        make(length)


@pytest.mark.parametrize("length", [1e-30, 1e-3, 1e10])
def test_paraboloid_and_sphere_at_the_bounds_give_their_closed_forms(length):
    """Depth d = 1e-3 R: the paraboloid to Hertz (a = sqrt(R d), F = 4/3 E* sqrt(R) d^1.5),
    the sphere to its MDR closed forms d = a/2 ln((R+a)/(R-a)), F = E*((a²+R²)/2
    ln((R+a)/(R-a)) - aR), both to 1e-12, and the force-controlled solve back to the depth."""
    R = length
    d = 1e-3 * R
    c = cl.Contact(cl.profiles.Paraboloid(R=R), MATERIALS)
    s = c.normal(depth=d)
    assert s.radius == pytest.approx(math.sqrt(R * d), rel=1e-12)
    assert s.force == pytest.approx(4 / 3 * E_STAR * math.sqrt(R) * d**1.5, rel=1e-12)
    assert c.normal(force=s.force).depth == pytest.approx(d, rel=1e-12)
    c = cl.Contact(cl.profiles.Sphere(R=R), MATERIALS)
    s = c.normal(depth=d)
    a = s.radius
    log = math.log((R + a) / (R - a))
    assert d == pytest.approx(a / 2 * log, rel=1e-12)
    assert s.force == pytest.approx(E_STAR * ((a * a + R * R) / 2 * log - a * R), rel=1e-9)
    assert c.normal(force=s.force).depth == pytest.approx(d, rel=1e-12)


@pytest.mark.parametrize("length", [1e-30, 1e-3, 1e10])
def test_flat_punch_at_the_bounds_gives_sneddon(length):
    c = cl.Contact(cl.profiles.FlatPunch(radius=length), MATERIALS)
    d = 1e-3 * length
    s = c.normal(depth=d)
    assert s.radius == length
    assert s.force == pytest.approx(2 * E_STAR * length * d, rel=1e-14)
    np.testing.assert_allclose(c.normal(force=s.force).depth, d, rtol=1e-14)
