"""Effective moduli (theory §1) against the formulas written out independently."""
from __future__ import annotations

import re

import pytest

import contactlab as cl
from contactlab.materials import effective_moduli
from contactlab.materials.viscoelastic import GeneralizedMaxwell, KelvinVoigt, StandardLinearSolid

from tests.tolerances import CLOSED_FORM


def test_steel_on_steel():
    E, nu = 210e9, 0.3
    G = E / (2 * (1 + nu))
    m = effective_moduli(cl.Elastic(E=E, nu=nu), cl.Elastic(E=E, nu=nu))
    assert m.normal == pytest.approx(E / (2 * (1 - nu**2)), rel=CLOSED_FORM)
    assert m.tangential == pytest.approx(2 * G / (2 - nu), rel=CLOSED_FORM)
    assert m.torsional == pytest.approx(G / 2, rel=CLOSED_FORM)     # identical bodies: G_t = G/2
    assert m.elastically_similar
    # theory §1: G*/G_t = 2.35 for steel on steel
    assert m.tangential / m.torsional == pytest.approx(4 / (2 - nu) / 1, rel=CLOSED_FORM)
    assert round(m.tangential / m.torsional, 2) == 2.35


def test_incompressible_on_rigid():
    G = 1e6
    rubber = cl.Elastic.from_shear_modulus(G, 0.5)
    m = effective_moduli(rubber, cl.Rigid())
    assert m.normal == pytest.approx(4 * G, rel=CLOSED_FORM)     # E* = 4E/3 = 4G
    assert m.torsional == pytest.approx(G, rel=CLOSED_FORM)
    assert m.tangential == pytest.approx(4 * G / 1.5, rel=CLOSED_FORM)
    assert m.elastically_similar


def test_dissimilar_pair_compliances_add():
    a, b = cl.Elastic(E=200e9, nu=0.3), cl.Elastic(E=1e9, nu=0.46)
    m = a.pair(b)
    assert 1 / m.torsional == pytest.approx(1 / a.G + 1 / b.G, rel=CLOSED_FORM)
    assert 1 / m.normal == pytest.approx((1 - 0.09) / 200e9 + (1 - 0.46**2) / 1e9, rel=CLOSED_FORM)
    assert not m.elastically_similar


def test_identity():
    assert cl.Elastic(E=1.0, nu=0.2) == cl.Elastic(E=1.0, nu=0.2)
    assert len({cl.Elastic(E=1.0, nu=0.2), cl.Elastic(E=1.0, nu=0.2)}) == 1
    assert repr(cl.Rigid()) == "Rigid()"


def test_viscoelastic_materials_arrive_through_the_registry():
    reg = cl.registry.registry
    for name in ("kelvin_voigt", "maxwell", "standard_linear_solid", "generalized_maxwell"):
        assert name in reg.available("material")
    assert reg.get("material", "kelvin_voigt") is KelvinVoigt
    sls = reg.create("material", "standard_linear_solid", G_inf=1e6, G_1=2e6, eta_1=1e3)
    assert isinstance(sls, StandardLinearSolid) and sls.is_viscoelastic


@pytest.mark.parametrize("make, name, value", [
    (lambda v: cl.Elastic(E=v, nu=0.3), "E", 1e-300),
    (lambda v: cl.Elastic(E=v, nu=0.3), "E", 1e300),
    (lambda v: cl.Elastic.from_shear_modulus(G=v, nu=0.3), "G", 1e25),
    (lambda v: KelvinVoigt(G=v, eta=1.0), "G", 1e-20),
    (lambda v: StandardLinearSolid(G_inf=1e6, G_1=v, eta_1=1.0), "G_1", 1e21),
    (lambda v: GeneralizedMaxwell(G_inf=1e6, moduli=[1e6, v], relaxation_times=[1.0, 2.0]),
     "moduli[1]", 1e-12),
    (lambda v: GeneralizedMaxwell(G_inf=v, moduli=[1e6], relaxation_times=[1.0]), "G_inf",
     1e30),
])
def test_moduli_outside_the_bounds_are_refused(make, name, value):
    """A modulus outside [1e-10, 1e20] Pa (contactlab.params.MODULUS_BOUNDS; a generalized
    Maxwell material's long-time modulus, which may be 0: [0, 1e20] Pa) is refused,
    naming it and asking to check the units: E = 1e-300 Pa on a rigid flat gave a subnormal
    Hertz force with five of its digits lost, E = 1e300 Pa a depth of 4e-200 m for 1 N."""
    with pytest.raises(cl.errors.ParameterError,
                       match=re.escape(f"{name}={value!r} is invalid: ") + r".* must lie "
                             r"between (1e-10|0) and 1e\+20 Pa \(check the units\)"):
        make(value)


@pytest.mark.parametrize("E", [1e-10, 1e20])
def test_moduli_at_the_bounds_follow_hertz(E):
    """At both ends of the bounds a sphere on a rigid flat is Hertz's contact,
    F = 4/3 E* R^(1/2) d^(3/2), E* = E/(1 - ν²), to rounding."""
    nu, R, d = 0.3, 0.01, 1e-6
    c = cl.Contact(cl.profiles.Paraboloid(R=R), (cl.Elastic(E=E, nu=nu), cl.materials.Rigid()))
    F = 4.0 / 3.0 * E / (1.0 - nu**2) * R**0.5 * d**1.5
    assert c.normal(depth=d).force == pytest.approx(F, rel=CLOSED_FORM)
