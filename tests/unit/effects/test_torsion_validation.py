"""Bad input to contact.torsion / contact.twist_history: one test per validation rule."""
from __future__ import annotations

import numpy as np
import pytest

import contactlab as cl
from contactlab.errors import NotSupportedError, OutsideTheoryError, ParameterError, UnknownNameError

MAT = (cl.Elastic(E=210e9, nu=0.3), cl.Rigid())


@pytest.fixture
def frictional():
    return cl.Contact(cl.profiles.Paraboloid(R=0.01), MAT, friction=0.3)


@pytest.fixture
def frictionless():
    return cl.Contact(cl.profiles.Paraboloid(R=0.01), MAT)


@pytest.mark.parametrize("method", ["exact", "mdr"])
def test_slip_methods_need_friction(frictionless, method):
    with pytest.raises(ParameterError, match="friction"):
        frictionless.torsion(force=1.0, twist=1e-4, method=method)
    with pytest.raises(ParameterError, match="friction"):
        frictionless.twist_history(twist=[0.0, 1e-4], force=1.0, method=method)


def test_default_method_follows_friction(frictional, frictionless):
    assert frictionless.torsion(force=1.0, twist=1e-4).method == "no-slip"
    assert frictional.torsion(force=1.0, twist=1e-4).method == "exact"


def test_unknown_method(frictional):
    with pytest.raises(UnknownNameError, match="method='exat'.*'exact'"):
        frictional.torsion(force=1.0, twist=1e-4, method="exat")


def test_exactly_one_normal_load(frictional):
    with pytest.raises(ParameterError, match="depth=, force=, radius="):
        frictional.torsion(force=1.0, depth=1e-6, twist=1e-4)


def test_exactly_one_twist_control(frictional):
    with pytest.raises(ParameterError, match="twist=, torque=, stick_radius="):
        frictional.torsion(force=1.0, twist=1e-4, torque=1e-3)
    with pytest.raises(ParameterError, match="twist=, torque=, stick_radius="):
        frictional.torsion(force=1.0)


def test_twist_must_be_finite(frictional):
    with pytest.raises(ParameterError, match="twist"):
        frictional.torsion(force=1.0, twist=np.nan)


def test_torque_beyond_sliding(frictional):
    M_full = frictional.torsion(force=1.0, twist=0.0).sliding_torque
    with pytest.raises(OutsideTheoryError, match="torque="):
        frictional.torsion(force=1.0, torque=1.01 * M_full)


def test_torque_without_contact(frictional):
    with pytest.raises(OutsideTheoryError, match="torque="):
        frictional.torsion(depth=-1e-6, torque=1e-3)


def test_stick_radius_range(frictional):
    a = frictional.normal(force=1.0).radius
    with pytest.raises(ParameterError, match="stick_radius"):
        frictional.torsion(force=1.0, stick_radius=1.1 * a)
    with pytest.raises(ParameterError, match="stick_radius"):
        frictional.torsion(force=1.0, stick_radius=-1e-9)


def test_stick_radius_needs_slip_model(frictionless):
    with pytest.raises(NotSupportedError, match="stick_radius"):
        frictionless.torsion(force=1.0, stick_radius=1e-5)


def test_slip_with_adhesion_not_supported():
    c = cl.Contact(cl.profiles.Paraboloid(R=0.01), MAT, friction=0.3, work_of_adhesion=0.1)
    with pytest.raises(NotSupportedError, match="work_of_adhesion"):
        c.torsion(force=1.0, twist=1e-4, method="exact")


def test_history_twist_must_be_1d(frictional):
    with pytest.raises(ParameterError, match="twist"):
        frictional.twist_history(twist=np.zeros((2, 3)), force=1.0)


def test_history_load_must_be_scalar(frictional):
    with pytest.raises(ParameterError, match="force"):
        frictional.twist_history(twist=[0.0, 1e-4], force=[1.0, 2.0])


def test_history_exactly_one_load(frictional):
    with pytest.raises(ParameterError, match="depth=, force="):
        frictional.twist_history(twist=[0.0, 1e-4])


def test_field_radii_non_negative(frictional):
    s = frictional.torsion(force=1.0, twist=1e-4)
    with pytest.raises(ParameterError, match="r contains"):
        s.shear(-1.0)


def test_no_contact_gives_zero_torque(frictional):
    s = frictional.torsion(depth=-1e-6, twist=1e-4)
    assert s.torque == 0.0 and s.slip


def test_state_is_immutable(frictional):
    s = frictional.torsion(force=1.0, twist=1e-4)
    with pytest.raises(AttributeError):
        s.method = "mdr"
