"""Quantities with units in the Python API (issue 27, item 4): what scene files accept, Python
accepts too, converted once at the boundary (``contactlab.params.to_si``).

Expected SI values are written out by hand (``"210 GPa"`` is ``210e9`` Pa): a unit string or a pint
quantity must give the bit-identical float a caller would have typed in SI, and the result of a
call must be bit-identical to the call with SI numbers.
"""
from __future__ import annotations

import math

import numpy as np
import pytest

import contactlab as cl
from contactlab.errors import ParameterError, SceneError, UnitError
from contactlab.params import QUANTITY_UNITS, to_si
from contactlab.profiles import Cone, FlatPunch, Paraboloid, Sphere


@pytest.fixture
def contact():
    return cl.Contact(Paraboloid(R=0.01), materials=(cl.Elastic(E=210e9, nu=0.3), cl.Rigid()),
                      friction=0.2)


# ---------------------------------------------------------------------------- constructors
@pytest.mark.parametrize("make, si", [
    (lambda: cl.Elastic(E="210 GPa", nu=0.3), cl.Elastic(E=210e9, nu=0.3)),
    (lambda: cl.Elastic(E="2.1e5 MPa", nu=0.3), cl.Elastic(E=2.1e11, nu=0.3)),
    (lambda: Paraboloid(R="10 mm"), Paraboloid(R=0.01)),
    (lambda: Sphere(R="2 cm"), Sphere(R=0.02)),
    (lambda: FlatPunch(radius="500 um"), FlatPunch(radius=500 * 1e-6)),
    (lambda: cl.Elastic.from_shear_modulus("80 GPa", 0.3), cl.Elastic.from_shear_modulus(80e9, 0.3)),
])
def test_constructor_accepts_unit_strings(make, si):
    assert make() == si


def test_contact_parameters_accept_units():
    c = cl.Contact(Paraboloid(R=0.01), materials=(cl.Elastic(E=210e9, nu=0.3), cl.Rigid()),
                   work_of_adhesion="50 mJ/m^2")
    assert c.work_of_adhesion == 50 * 1e-3


# ---------------------------------------------------------------------------- contact methods
def test_normal_with_units_is_bit_identical(contact):
    a, b = contact.normal(force="2 kN"), contact.normal(force=2000.0)
    assert (a.depth, a.radius, a.force) == (b.depth, b.radius, b.force)
    a, b = contact.normal(depth="3 um"), contact.normal(depth=3 * 1e-6)
    assert (a.depth, a.force) == (b.depth, b.force)


def test_torsion_and_tangential_with_units(contact):
    a = contact.torsion(force="1 kN", twist="1 mrad")
    b = contact.torsion(force=1000.0, twist=1e-3)
    assert a.torque == b.torque
    a = contact.tangential(force="1 kN", displacement="100 nm")
    b = contact.tangential(force=1000.0, displacement=100 * 1e-9)
    assert a.tangential_force == b.tangential_force


def test_load_path_targets_accept_units():
    p = cl.LoadPath().ramp(force="2 kN", steps=3).sinusoid(twist="5 mrad", cycles=1)
    q = cl.LoadPath().ramp(force=2000.0, steps=3).sinusoid(twist=5e-3, cycles=1)
    assert p == q


# ---------------------------------------------------------------------------- refusals
@pytest.mark.parametrize("make, match", [
    (lambda c: cl.Elastic(E="210 mm", nu=0.3), r"E='210 mm' has unit 'mm' of dimension length.*GPa"),
    (lambda c: Paraboloid(R="10 N"), r"R='10 N' has unit 'N' of dimension force.*\bmm\b"),
    (lambda c: c.normal(force="3 mm"), r"force='3 mm' has unit 'mm'.*kN"),
    (lambda c: c.torsion(force=1.0, twist="1 N*m"), r"twist='1 N\*m'.*rad"),
    (lambda c: Paraboloid(R="1 furlong"), r"R='1 furlong' has unknown unit 'furlong'"),
])
def test_wrong_dimension_names_parameter_value_and_units(contact, make, match):
    with pytest.raises(UnitError, match=match) as e:
        make(contact)
    assert isinstance(e.value, ParameterError) and isinstance(e.value, SceneError)


@pytest.mark.parametrize("make, match", [
    (lambda: cl.Elastic(E="210e9", nu=0.3), r"E='210e9' is invalid.*string with a unit"),
    (lambda: cl.Elastic(E=210e9, nu="0.3"), r"nu='0.3' is invalid"),
    (lambda: Paraboloid(R="ten mm"), r"R='ten mm' is invalid"),
])
def test_strings_without_a_unit_are_not_numbers(make, match):
    with pytest.raises(ParameterError, match=match):
        make()


def test_to_si_leaves_plain_values_alone():
    arr = np.array([1.0, 2.0])
    assert to_si("force", arr) is arr and to_si("force", 2.0) == 2.0
    assert to_si("n_springs", "2 kN") == "2 kN"      # a name without a unit: nothing converted
    assert set(QUANTITY_UNITS) >= {"depth", "force", "twist", "torque", "displacement"}


# ---------------------------------------------------------------------------- Cone
def test_cone_half_angle_keyword():
    alpha = math.radians(70.0)
    assert Cone(half_angle=alpha) == Cone.from_half_angle(alpha) == Cone(slope=1.0 / math.tan(alpha))
    assert Cone(half_angle="70 deg").slope == 1.0 / math.tan(70 * math.pi / 180)


@pytest.mark.parametrize("kw, match", [({}, "exactly one"), ({"slope": 1.0, "half_angle": 0.5},
                                                              "exactly one"),
                                       ({"half_angle": "90 deg"}, "half_angle="),
                                       ({"half_angle": "1 m"}, "dimension length")])
def test_cone_needs_one_valid_parameter(kw, match):
    with pytest.raises(ParameterError, match=match):
        Cone(**kw)


def test_registry_create_from_the_package_face():
    assert cl.registry.create("profile", "paraboloid", R="10 mm") == Paraboloid(R=0.01)
    assert cl.registry.get("profile", "cone") is Cone
    assert "cone" in cl.registry.available("profile")


# ---------------------------------------------------------------------------- pint
def test_pint_quantities():
    pint = pytest.importorskip("pint")
    u = pint.UnitRegistry()
    assert cl.Elastic(E=u.Quantity(210, "GPa"), nu=0.3) == cl.Elastic(E=210e9, nu=0.3)
    c = cl.Contact(Paraboloid(R=u.Quantity(1, "cm")),
                   materials=(cl.Elastic(E=210e9, nu=0.3), cl.Rigid()))
    got = c.normal(depth=u.Quantity([1.0, 2.0], "um")).force
    np.testing.assert_array_equal(got, c.normal(depth=np.array([1.0, 2.0]) * 1e-6).force)
    with pytest.raises(UnitError, match=r"E=.*wrong dimension: E is a pressure in Pa"):
        cl.Elastic(E=u.Quantity(3, "m"), nu=0.3)
    with pytest.raises(UnitError, match=r"force=.*wrong dimension"):
        c.normal(force=u.Quantity(3, "mm"))
