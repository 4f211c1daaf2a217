"""Unit spellings, byte-order marks and delimiters of every CSV reader (issue 26, item 6).

``r_mm,f_mm`` and ``r/mm,f/mm`` were read as metres (1000x off); a UTF-8 BOM in a load-path CSV
and tab-separated profiles were refused. Every reader (profiles, load paths, scene histories)
now accepts ``r [mm]``, ``r (mm)``, ``r_mm``, ``r/mm``, a BOM and ``,`` ``;`` tab or
whitespace separators, and refuses an unknown unit naming the column and the unit.
"""
import numpy as np
import pytest

import contactlab as cl
from contactlab.errors import TabulatedDataError, UnitError
from contactlab.loadpath.io import read_history
from contactlab.profiles import Tabulated
from contactlab.scene.validate import read_table

R_MM = [0.0, 0.5, 1.0, 1.5, 2.0]
F_UM = [0.0, 6.25, 25.0, 56.25, 100.0]


def _write(tmp_path, text, name="t.csv", bom=False):
    p = tmp_path / name
    p.write_bytes((b"\xef\xbb\xbf" if bom else b"") + text.encode("utf-8"))
    return p


def _profile_text(header, sep):
    rows = [sep.join((repr(a), repr(b))) for a, b in zip(R_MM, F_UM)]
    return "# a comment line\n" + header + "\n" + "\n".join(rows) + "\n"


@pytest.mark.parametrize("header", ["r [mm]{s}f [um]", "r (mm){s}f (um)", "r_mm{s}f_um",
                                    "r/mm{s}f/um", "radius_mm{s}height_µm"])
@pytest.mark.parametrize("sep", [",", ";", "\t", "   "])
@pytest.mark.parametrize("bom", [False, True])
def test_profile_units_delimiters_bom(tmp_path, header, sep, bom):
    tab = Tabulated.from_csv(_write(tmp_path, _profile_text(header.format(s=sep), sep), bom=bom))
    np.testing.assert_array_equal(tab.r, np.array(R_MM) * 1e-3)
    np.testing.assert_array_equal(tab.f, np.array(F_UM) * 1e-6)


@pytest.mark.parametrize("header, column, unit", [("r_furlong,f_um", "r_furlong", "furlong"),
                                                  ("r/mm,f/parsec", "f", "parsec"),
                                                  ("r [mm],f [inch]", "f", "inch")])
def test_profile_unknown_unit_names_column_and_unit(tmp_path, header, column, unit):
    with pytest.raises(UnitError, match=f"column '{column}' has unit '{unit}'"):
        Tabulated.from_csv(_write(tmp_path, _profile_text(header, ",")))


def test_profile_unit_of_wrong_dimension(tmp_path):
    with pytest.raises(UnitError, match="dimension force"):
        Tabulated.from_csv(_write(tmp_path, _profile_text("r_mm,f_kN", ",")))


@pytest.mark.parametrize("header", ["time [ms]{s}force [kN]", "time_ms{s}force_kN",
                                    "time/ms{s}force/kN", "time (ms){s}force (kN)"])
@pytest.mark.parametrize("sep", [",", ";", "\t", " "])
@pytest.mark.parametrize("bom", [False, True])
def test_load_path_units_delimiters_bom(tmp_path, header, sep, bom):
    text = header.format(s=sep) + "\n" + "\n".join(
        sep.join((repr(t), repr(f))) for t, f in ((0.0, 0.3), (10.0, 1.5), (20.0, 3.0))) + "\n"
    p = _write(tmp_path, text, bom=bom)
    for cols in (read_history(p), read_table(p)):
        np.testing.assert_allclose(cols["time"], [0.0, 0.01, 0.02], rtol=1e-15)
        np.testing.assert_allclose(cols["force"], [300.0, 1500.0, 3000.0], rtol=1e-15)
    path = cl.LoadPath.from_csv(p)
    np.testing.assert_allclose(path.sample().values["force"], [300.0, 1500.0, 3000.0], rtol=1e-15)


def test_load_path_tangential_force_is_a_name_and_unknown_unit_is_refused(tmp_path):
    ok = _write(tmp_path, "time_s,force_N,tangential_force\n0,1,0\n1,2,0.5\n", "ok.csv")
    cols = read_history(ok)
    assert sorted(cols) == ["force", "tangential_force", "time"]
    bad = _write(tmp_path, "time,force_lbf\n0,1\n1,2\n", "bad.csv")
    with pytest.raises(UnitError, match="column 'force' has unit 'lbf'"):
        read_history(bad)
    with pytest.raises(UnitError):
        read_table(bad)


def test_scene_history_never_quotes_the_file(tmp_path):
    bad = _write(tmp_path, "time,force\n0,secret\n", "bad.csv")
    with pytest.raises(TabulatedDataError) as info:
        read_table(bad)
    assert "secret" not in str(info.value)
