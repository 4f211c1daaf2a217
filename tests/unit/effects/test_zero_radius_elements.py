"""Elements out of contact (radius 0) beside elements in contact, on a profile with a bounded
domain: a sphere of radius ``R`` below 1 m.

The detached elements once stood in for their radius with 1.0 m while the profile was evaluated
on the whole array (the masked values were discarded), and a sphere refuses radii beyond ``R``:
``OutsideTheoryError: x=1.0 m is invalid``, a radius the user never gave. Each call is checked
against Hertz's and JKR's closed forms of the paraboloid the sphere tends to for ``a << R``, and
against the same contact's calls one element at a time.
"""
import math
import warnings

import numpy as np
import pytest

import contactlab as cl
from contactlab.profiles import Paraboloid, Sphere

R = 5e-6
SAMPLE = cl.Elastic(E=2e6, nu=0.5)
E_STAR = 2e6 / (1 - 0.5**2)
W = 0.05
#: a/R ~ 0.02 at these forces: the sphere differs from Hertz's paraboloid by O((a/R)²)
SPHERE_VS_HERTZ = 2e-3


def _contact(profile, **kw):
    return cl.Contact(profile, (cl.Rigid(), SAMPLE), **kw)


def test_adhesive_sphere_detached_depth_beside_an_attached_one():
    R = 0.05            # (adhesion spreads the contact: a/R ~ R^(-1/3), here ~0.02)
    c = _contact(Sphere(R=R), work_of_adhesion=W)
    # JKR: the displacement-controlled pull-off depth of the paraboloid (sphere for a << R)
    d_c = -0.75 * (math.pi**2 * W**2 * R / E_STAR**2) ** (1 / 3)
    d = np.array([-1e-5, 1e-7])
    assert d[0] < 2 * d_c               # far below the pull-off depth: detached
    s = c.normal(depth=d)
    assert s.force[0] == 0.0 and s.radius[0] == 0.0
    assert c.normal(depth=float(d[0])).force == 0.0
    # the attached element: as the scalar call, and JKR's paraboloid to the sphere's correction
    one = c.normal(depth=float(d[1]))
    assert s.force[1] == one.force and s.radius[1] == one.radius
    def F_jkr(a):
        return 4 * E_STAR * a**3 / (3 * R) - math.sqrt(8 * math.pi * W * E_STAR * a**3)

    a = float(s.radius[1])
    assert a / R < 0.05
    assert float(s.force[1]) == pytest.approx(F_jkr(a), rel=SPHERE_VS_HERTZ)
    # the same on the paraboloid, where 1.0 m was always a valid radius (JKR exactly)
    p = _contact(Paraboloid(R=R), work_of_adhesion=W).normal(depth=d)
    assert p.force[0] == 0.0
    assert float(p.force[1]) == pytest.approx(F_jkr(float(p.radius[1])), rel=1e-12)


def test_sphere_peak_pressure_with_an_unloaded_element():
    c = _contact(Sphere(R=R))
    F = np.array([0.0, 1e-9])
    s = c.normal(force=F)
    p0 = (6 * F[1] * E_STAR**2 / (math.pi**3 * R**2)) ** (1 / 3)     # Hertz
    peak = np.asarray(s.peak_pressure)
    assert peak[0] == 0.0
    assert peak[1] == pytest.approx(p0, rel=SPHERE_VS_HERTZ)
    p_axis = np.asarray(s.pressure([0.0]))[:, 0]
    assert p_axis[0] == 0.0 and p_axis[1] == pytest.approx(p0, rel=SPHERE_VS_HERTZ)
    assert peak[1] == c.normal(force=float(F[1])).peak_pressure


@pytest.mark.parametrize("mode", ["displacement_amplitude", "twist_amplitude"])
def test_sphere_fretting_map_with_zero_force(mode):
    c = _contact(Sphere(R=R), friction=0.3)
    amp = [1e-10, 1e-9] if mode == "displacement_amplitude" else [1e-4, 1e-3]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", cl.errors.ValidityWarning)
        m = c.fretting_map(force=[0.0, 1e-7], **{mode: amp})
        loop = c.fretting_loop(force=0.0, **{mode: amp[1]})
    names = [m.regime_names[int(r)] for r in np.asarray(m.regime)[0]]
    # out of contact nothing holds a displacement or a twist: gross slip in both modes
    assert names == ["gross_slip", "gross_slip"]
    assert loop.regime == "gross_slip"
    assert loop.energy == 0.0 and loop.peak == 0.0
