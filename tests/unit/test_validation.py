"""Bad input: one clear contactlab exception per validation rule, naming parameter and value."""
from __future__ import annotations

import numpy as np
import pytest

import contactlab as cl
from contactlab import profiles as P
from contactlab.errors import (NotSupportedError, OutsideTheoryError, ParameterError,
                               TabulatedDataError)

STEEL = cl.Elastic(E=210e9, nu=0.3)


@pytest.mark.parametrize("E", [-1.0, 0.0, np.nan, np.inf, "abc"])
def test_elastic_modulus_must_be_positive_finite(E):
    with pytest.raises(ParameterError, match="E="):
        cl.Elastic(E=E, nu=0.3)


@pytest.mark.parametrize("nu", [-1.0, 0.5000001, 0.7, np.nan])
def test_poisson_ratio_range(nu):
    with pytest.raises(ParameterError, match=r"nu=.*-1 < nu <= 0.5"):
        cl.Elastic(E=1e9, nu=nu)


def test_poisson_limits_accepted():
    assert cl.Elastic(E=1e9, nu=0.5).nu == 0.5
    assert cl.Elastic(E=1e9, nu=-0.999).nu == -0.999


def test_two_rigid_bodies_rejected():
    with pytest.raises(ParameterError, match="Rigid"):
        cl.Contact(P.Paraboloid(R=1.0), materials=(cl.Rigid(), cl.Rigid()))


def test_materials_must_be_materials():
    with pytest.raises(ParameterError, match="materials"):
        cl.Contact(P.Paraboloid(R=1.0), materials=(STEEL, 210e9))
    with pytest.raises(ParameterError, match="materials"):
        cl.Contact(P.Paraboloid(R=1.0), materials=STEEL)


def test_profile_must_be_profile():
    with pytest.raises(ParameterError, match="profile"):
        cl.Contact("ball", materials=(STEEL, STEEL))


@pytest.mark.parametrize("factory,match", [
    (lambda: P.Paraboloid(R=0.0), "R="),
    (lambda: P.Paraboloid(R=-1e-3), "R="),
    (lambda: P.Sphere(R=-1.0), "R="),
    (lambda: P.PowerLaw(c=1.0, n=0.0), "n="),
    (lambda: P.PowerLaw(c=1.0, n=-2.0), "n="),
    (lambda: P.PowerLaw(c=0.0, n=2.0), "c="),
    (lambda: P.Cone(slope=-0.1), "slope="),
    (lambda: P.Cone.from_half_angle(np.pi / 2), "half_angle="),
    (lambda: P.FlatPunch(radius=0.0), "radius="),
    (lambda: P.TruncatedParaboloid(radius=1e-3, R=0.0), "R="),
    (lambda: P.TruncatedCone(radius=-1e-3, slope=0.1), "radius="),
    (lambda: P.Polynomial({2: -1.0}), r"terms\[0\].c="),
    (lambda: P.Polynomial([]), "terms="),
])
def test_profile_parameters(factory, match):
    with pytest.raises(ParameterError, match=match):
        factory()


@pytest.mark.parametrize("r,f,match", [
    ([0.0, 2e-3, 1e-3], [0, 1e-6, 2e-6], r"r\[2\]=.*strictly increasing"),
    ([0.0, 1e-3, 1e-3], [0, 1e-6, 2e-6], r"r\[2\]=.*duplicates"),
    ([0.0, np.nan, 2e-3], [0, 1e-6, 2e-6], r"r\[1\]=nan"),
    ([0.0, 1e-3, 2e-3], [0, np.inf, 2e-6], r"f\[1\]=inf"),
    ([-1e-3, 1e-3, 2e-3], [0, 1e-6, 2e-6], r"r\[0\]="),
    ([0.0, 1e-3], [0, 1e-6, 2e-6], "equal length"),
    ([0.0], [0.0], "at least 2"),
])
def test_tabulated_data_checks(r, f, match):
    with pytest.raises(TabulatedDataError, match=match):
        P.Tabulated(r=r, f=f)


def test_tabulated_bad_interpolation():
    with pytest.raises(ParameterError, match="interpolation='spline'"):
        P.Tabulated(r=[0, 1e-3], f=[0, 1e-6], interpolation="spline")


def test_ring_contact_is_outside_theory_with_depth():
    # a raised rim: f rises then falls far enough that g decreases -> annular contact
    r = np.linspace(0, 1e-3, 200)
    f = 1e-6 * np.sin(np.pi * r / 1e-3 * 1.5) ** 2
    tab = P.Tabulated(r=r, f=f)
    c = cl.Contact(tab, materials=(STEEL, STEEL))
    c.normal(depth=1e-8)        # small depths: fine while g rises
    with pytest.raises(OutsideTheoryError, match="annulus"):
        c.normal(depth=float(np.max(tab.g(r))) * 0.999999)


def test_sphere_contact_radius_below_R():
    c = cl.Contact(P.Sphere(R=1e-3), materials=(STEEL, STEEL))
    with pytest.raises(OutsideTheoryError, match="max_radius"):
        c.normal(depth=1.0)
    with pytest.raises(OutsideTheoryError, match="radius="):
        c.normal(radius=1e-3)
    with pytest.raises(OutsideTheoryError, match="max_radius"):
        c.normal(force=1e12)


def test_contact_beyond_table_is_outside_theory():
    c = cl.Contact(P.Tabulated(r=[0, 1e-3], f=[0, 1e-6]), materials=(STEEL, STEEL))
    with pytest.raises(OutsideTheoryError, match="max_radius"):
        c.normal(depth=1e-3)


def test_normal_needs_exactly_one_control():
    c = cl.Contact(P.Paraboloid(R=1.0), materials=(STEEL, STEEL))
    with pytest.raises(ParameterError, match="exactly one"):
        c.normal(depth=1e-6, force=1.0)
    with pytest.raises(ParameterError, match="exactly one"):
        c.normal()
    with pytest.raises(ParameterError, match="depth contains nan"):
        c.normal(depth=[1e-6, np.nan])
    with pytest.raises(ParameterError, match="radius contains"):
        c.normal(radius=-1e-6)


def test_flat_punch_radius_control_not_supported():
    c = cl.Contact(P.FlatPunch(radius=1e-3), materials=(STEEL, STEEL))
    with pytest.raises(NotSupportedError, match="radius="):
        c.normal(radius=1e-3)


def test_contact_options():
    with pytest.raises(ParameterError, match="friction="):
        cl.Contact(P.Paraboloid(R=1.0), materials=(STEEL, STEEL), friction=-0.1)
    with pytest.raises(ParameterError, match="work_of_adhesion="):
        cl.Contact(P.Paraboloid(R=1.0), materials=(STEEL, STEEL), work_of_adhesion=-1.0)
    with pytest.raises(ParameterError, match="rtol="):
        cl.Contact(P.Paraboloid(R=1.0), materials=(STEEL, STEEL), rtol=2.0)


def test_negative_radius_in_field_methods():
    s = cl.Contact(P.Paraboloid(R=1.0), materials=(STEEL, STEEL)).normal(depth=1e-6)
    with pytest.raises(ParameterError, match="r contains"):
        s.pressure(-1.0)
