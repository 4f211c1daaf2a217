"""One unit spelling on output (products with *: N*m, Pa*s); every spelling accepted on input."""
import json

import numpy as np
import pytest

import contactlab as cl
from contactlab.registry import registry
from contactlab.loadpath import UNITS, read_csv, write_csv
from contactlab.loadpath.base import canonical_unit
from contactlab.scene import Scene
from contactlab.scene.run import FIELD_UNITS, SERIES_UNITS
from contactlab.scene.units import DIMENSION_OF_SI_UNIT, SI_UNIT, UNITS as SCENE_UNITS
from contactlab.scene.units import format_quantity, parse_quantity

from tests.unit.scene.helpers import twist_scene


def written_units():
    units = [*UNITS.values(), *SERIES_UNITS.values(), *FIELD_UNITS.values(), *SI_UNIT.values(),
             *DIMENSION_OF_SI_UNIT]
    for kind in ("profile", "material"):
        for name in registry.available(kind):
            units += [p.unit for p in getattr(registry.get(kind, name), "params", ())]
    return units


def test_every_written_unit_is_canonical():
    bad = sorted({u for u in written_units() if canonical_unit(u) != u})
    assert not bad, f"units not in the one written spelling: {bad}"
    assert UNITS["torque"] == SERIES_UNITS["torque"] == SI_UNIT["torque"] == "N*m"


def test_scene_unit_tables_hold_only_canonical_spellings():
    for dim, table in SCENE_UNITS.items():
        assert all(canonical_unit(u) == u for u in table), dim


@pytest.mark.parametrize("dim, spellings", [
    ("torque", ["2 mN*m", "2 mN m", "2 mN·m", "2 mN * m", "2  mN   m"]),
    ("viscosity", ["2 kPa*s", "2 kPa s", "2 kPa·s"]),
])
def test_every_spelling_parses_to_the_same_value(dim, spellings):
    values = {parse_quantity(s, dim) for s in spellings}
    assert values == {2.0 * SCENE_UNITS[dim][spellings[0].split(" ", 1)[1]]}


def test_formatted_quantities_use_the_written_spelling():
    assert format_quantity(0.5, "torque") == "0.5 N*m"
    assert format_quantity(2.0, "viscosity") == "2.0 Pa*s"


@pytest.mark.parametrize("header", ["torque [N*m]", "torque [N m]", "torque [N·m]"])
def test_csv_reader_accepts_every_spelling(tmp_path, header):
    f = tmp_path / "h.csv"
    f.write_text(f"time [s],force [N],{header}\n1,1.0,0.0\n2,1.0,0.5\n")
    seg, = read_csv(f).segments
    np.testing.assert_array_equal(dict(seg.columns)["torque"], [0.0, 0.5])


def test_csv_reader_converts_units_and_rejects_another_dimension(tmp_path):
    f = tmp_path / "h.csv"
    f.write_text("force [N],torque [N*mm]\n1.0,2.0\n")
    seg, = read_csv(f).segments
    assert dict(seg.columns)["torque"].tolist() == [2e-3]
    f.write_text("force [N],torque [mm]\n1.0,0.0\n")
    with pytest.raises(cl.errors.UnitError, match=r"dimension length"):
        read_csv(f)


def test_csv_writer_and_scene_outputs_write_n_star_m(tmp_path):
    write_csv(tmp_path / "p.csv", {"torque": np.zeros(2)})
    assert (tmp_path / "p.csv").read_text().splitlines()[0] == "torque [N*m]"
    res = Scene(twist_scene({"ramp": {"twist": "1 mrad", "steps": 2}})).run()
    assert json.loads(json.dumps(res.to_dict()))["units"]["torque"] == "N*m"
    assert "torque [N*m]" in res.table()
