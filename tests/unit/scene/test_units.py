"""Unit-suffix parsing: full float grammar, every dimension, clear UnitErrors."""
import math

import pytest

from contactlab.errors import SceneError, UnitError
from contactlab.scene.units import UNITS, parse_quantity
from tests import tolerances as TOL


@pytest.mark.parametrize("text, dim, expected", [
    ("10 um", "length", 10e-6),
    ("10 µm", "length", 10e-6),      # micro sign
    ("10 μm", "length", 10e-6),      # Greek mu
    ("10um", "length", 10e-6),       # no space
    ("1e-3 m", "length", 1e-3),
    ("1E+2 nm", "length", 1e-7),
    ("-2.5e-3 mrad", "angle", -2.5e-6),
    (".5 mm", "length", 5e-4),
    ("5. mm", "length", 5e-3),
    ("+3 kN", "force", 3000.0),
    ("210 GPa", "pressure", 210e9),
    ("2 N/mm^2", "pressure", 2e6),
    ("0.5 mrad", "angle", 0.5e-3),
    ("5 deg", "angle", 5 * math.pi / 180),
    ("90 °", "angle", math.pi / 2),
    ("0.1 N m", "torque", 0.1),
    ("3 mN m", "torque", 3e-3),
    ("2 ms", "time", 2e-3),
    ("0.05 J/m^2", "energy_per_area", 0.05),
    ("50 mJ/m²", "energy_per_area", 0.05),
    ("72 mN/m", "energy_per_area", 0.072),
    ("0.3", "dimensionless", 0.3),
    ("30 %", "dimensionless", 0.3),
    ("1_000 N", "force", 1000.0),
])
def test_parse_quantity(text, dim, expected):
    assert parse_quantity(text, dim) == pytest.approx(expected, rel=TOL.ULPS)


def test_plain_numbers_are_si():
    assert parse_quantity(2000, "force") == 2000.0
    assert parse_quantity(1.5e-6, "length") == 1.5e-6


def test_every_table_entry_parses():
    for dim, table in UNITS.items():
        for unit, factor in table.items():
            assert parse_quantity(f"2 {unit}", dim) == pytest.approx(2 * factor, rel=TOL.ULPS)


def test_unknown_unit_names_key_value_and_suggests():
    with pytest.raises(UnitError, match=r"R='10 mmm' has unknown unit 'mmm'.*Did you mean 'mm'") as e:
        parse_quantity("10 mmm", "length", "R")
    assert e.value.issues[0][0] == "R"
    assert isinstance(e.value, SceneError)


def test_wrong_dimension():
    with pytest.raises(UnitError, match=r"twist='1e-3 m' has unit 'm' of dimension length.*angle"):
        parse_quantity("1e-3 m", "angle", "twist")


def test_not_a_number():
    with pytest.raises(UnitError, match=r"E='GPa' is invalid: expected '<number> <unit>'"):
        parse_quantity("GPa", "pressure", "E")


@pytest.mark.parametrize("bad", [float("inf"), float("nan"), "inf m", "1e400 m"])
def test_non_finite(bad):
    with pytest.raises(UnitError, match="finite|<number> <unit>"):
        parse_quantity(bad, "length", "R")


@pytest.mark.parametrize("bad", [True, None, [1.0], {"a": 1}])
def test_wrong_type(bad):
    with pytest.raises(UnitError, match="expected a number or a string"):
        parse_quantity(bad, "length", "R")


def test_number_only_parameters_refuse_units():
    assert parse_quantity("1.5", "number") == 1.5
    with pytest.raises(UnitError, match="plain number"):
        parse_quantity("1.5 m", "number", "c")
