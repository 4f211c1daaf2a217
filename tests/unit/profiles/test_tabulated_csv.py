"""Measured profiles from CSV with units (issue 12). Must show:

- ``r [mm],f [um]`` headers and ``r_unit=``/``f_unit=`` arguments give the same table as SI input,
  with the unit grammar of scene files (``µm`` and ``um``; ``nm``);
- an unknown unit, a unit of another dimension, conflicting units, a one-column file, a missing
  file and a cell that is not a number each raise a contactlab error naming the problem;
- a scene reads a tabulated profile from CSV with units, smoothing and noise keys.
"""
import numpy as np
import pytest

import contactlab as cl
from contactlab.errors import TabulatedDataError, UnitError
from contactlab.profiles import Tabulated
from contactlab.scene import Scene

R_MM = np.array([0.0, 0.5, 1.0, 1.5, 2.0])
F_UM = np.array([0.0, 6.25, 25.0, 56.25, 100.0])


def write(tmp_path, text, name="p.csv"):
    p = tmp_path / name
    p.write_text(text)
    return p


def table_text(header):
    return header + "\n" + "\n".join(f"{float(a)!r},{float(b)!r}" for a, b in zip(R_MM, F_UM)) + "\n"


@pytest.mark.parametrize("header", ["r [mm],f [um]", "r [mm],f [µm]", "radius (mm), height (um)",
                                    "r [ mm ] ; f [um]".replace(";", ",")])
def test_header_units_convert_to_si(tmp_path, header):
    tab = Tabulated.from_csv(write(tmp_path, table_text(header)))
    np.testing.assert_array_equal(tab.r, R_MM * 1e-3)
    np.testing.assert_array_equal(tab.f, F_UM * 1e-6)


def test_argument_units_and_agreeing_header(tmp_path):
    plain = write(tmp_path, table_text("r,f"))
    tab = Tabulated.from_csv(plain, r_unit="mm", f_unit="um")
    np.testing.assert_array_equal(tab.r, R_MM * 1e-3)
    np.testing.assert_array_equal(tab.f, F_UM * 1e-6)
    both = write(tmp_path, table_text("r [mm],f [um]"), "b.csv")
    np.testing.assert_array_equal(Tabulated.from_csv(both, r_unit="mm").f, tab.f)
    with pytest.raises(TabulatedDataError, match="'um'.*'nm'"):
        Tabulated.from_csv(both, f_unit="nm")


def test_no_header_is_si(tmp_path):
    tab = Tabulated.from_csv(write(tmp_path, "0,0\n1e-3,1e-6\n2e-3,4e-6\n"))
    assert tab.r.tolist() == [0.0, 1e-3, 2e-3]


@pytest.mark.parametrize("text, error, match", [
    ("r [mm],f [um]\n0,0\n1,2\n".replace("[um]", "[uum]"), UnitError, "uum"),
    ("r [mm],f [N]\n0,0\n1,2\n", UnitError, "dimension force"),
    ("r [mm]\n0\n1\n2\n", TabulatedDataError, "at least 2"),
    ("r,f\n0,0\n1,abc\n", TabulatedDataError, "abc"),
    ("r,f\n0,0\n1\n", TabulatedDataError, "row 2"),
    ("r,f\n", TabulatedDataError, "no data rows"),
])
def test_bad_files_raise_contactlab_errors(tmp_path, text, error, match):
    with pytest.raises(error, match=match):
        Tabulated.from_csv(write(tmp_path, text))


def test_unknown_argument_unit(tmp_path):
    with pytest.raises(UnitError, match="furlong"):
        Tabulated.from_csv(write(tmp_path, table_text("r,f")), r_unit="furlong")


def test_missing_files_raise_contactlab_errors(tmp_path):
    with pytest.raises(TabulatedDataError, match="cannot be read"):
        Tabulated.from_csv(tmp_path / "nope.csv")
    with pytest.raises(TabulatedDataError, match="cannot be read"):
        cl.LoadPath.from_csv(tmp_path / "nope.csv")


def test_scene_reads_profile_csv_with_units_and_smoothing(tmp_path):
    write(tmp_path, table_text("r,f"), "cup.csv")
    mats = {"body1": {"type": "elastic", "E": "210 GPa", "nu": 0.3},
            "body2": {"type": "elastic", "E": "1 GPa", "nu": 0.4}}
    s = Scene({"profile": {"type": "tabulated", "file": "cup.csv", "r_unit": "mm",
                           "f_unit": "um"},
               "materials": mats, "load_path": [{"ramp": {"force": "1 N", "steps": 2}}]},
              tmp_path)
    np.testing.assert_array_equal(s.profile.f, F_UM * 1e-6)
    with pytest.raises(cl.errors.SceneError) as err:
        Scene({"profile": {"type": "tabulated", "file": "cup.csv", "r_unit": "mN"},
               "materials": mats, "load_path": [{"ramp": {"force": "1 N", "steps": 2}}]},
              tmp_path)
    assert [i[0] for i in err.value.issues] == ["profile.r_unit"]
