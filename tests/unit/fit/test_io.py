"""read_curve: CSV files with units in the header (written here) and AFM files written by
afmformats' own exporter (skipped without afmformats); the missing extra is named."""
from __future__ import annotations

import builtins

import numpy as np
import pytest

from contactlab import Elastic, errors
from contactlab.fit import Curve, indentation, read_curve
from contactlab.profiles import Paraboloid
from tests.tolerances import FIT_RECOVERY

E, NU, R, Z0 = 2e6, 0.5, 5e-6, 12e-9
ESTAR = E / (1 - NU ** 2)


def hertz(depth):
    return 4 / 3 * ESTAR * np.sqrt(R) * np.maximum(depth - Z0, 0.0) ** 1.5


def test_csv_with_units_in_the_header(tmp_path):
    z = np.linspace(-60e-9, 240e-9, 500)
    F = hertz(z)
    path = tmp_path / "curve.csv"
    rows = "\n".join(f"{float(a) * 1e9!r},{float(b) * 1e9!r},{float(c) * 1e3!r}"
                     for a, b, c in zip(z, F, np.arange(z.size) * 1e-3))
    path.write_text("# a measured curve\ndepth [nm],force [nN],time [ms]\n" + rows + "\n")
    c = read_curve(path)
    assert isinstance(c, Curve) and c.meta["reader"] == "csv"
    np.testing.assert_allclose(c.depth, z, rtol=1e-15, atol=0)
    np.testing.assert_allclose(c.force, F, rtol=1e-15, atol=0)
    np.testing.assert_allclose(c.time, np.arange(z.size) * 1e-3, rtol=1e-15, atol=0)
    res = indentation(c.depth, c.force, Paraboloid(R=R), sample=Elastic(E=1e6, nu=NU))
    assert res.params["E"] == pytest.approx(E, rel=FIT_RECOVERY)


def test_csv_errors_name_the_problem(tmp_path):
    path = tmp_path / "bad.csv"
    path.write_text("height [nm],force [nN]\n1,2\n3,4\n")
    with pytest.raises(errors.ParameterError, match="'depth'"):
        read_curve(path)
    with pytest.raises(errors.TabulatedDataError, match="cannot be read"):
        read_curve(tmp_path / "none.csv")
    with pytest.raises(errors.ParameterError, match="segment='down'"):
        read_curve(path, segment="down")


def test_missing_extra_is_named(monkeypatch, tmp_path):
    real = builtins.__import__

    def no_afm(name, *args, **kwargs):
        if name == "afmformats":
            raise ImportError("No module named 'afmformats'")
        return real(name, *args, **kwargs)
    monkeypatch.setattr(builtins, "__import__", no_afm)
    with pytest.raises(errors.NotSupportedError, match=r"contactlab\[afm\]"):
        read_curve(tmp_path / "curve.jpk-force")


def test_afmformats_tab_file(tmp_path):
    """A curve written by afmformats' own exporter: height of the base (up) and force; the
    depth read back is -(height + F/k)."""
    afmformats = pytest.importorskip("afmformats")
    k = 50.0                  # a stiff cantilever: F/k stays small beside the 8 digits written
    tip = np.concatenate([np.linspace(60e-9, -240e-9, 300), np.linspace(-240e-9, 60e-9, 300)])
    depth = -tip
    F = hertz(depth)
    height = tip - F / k
    seg = np.r_[np.zeros(300), np.ones(300)].astype(np.uint8)
    data = {"force": F, "height (measured)": height, "height (piezo)": height,
            "segment": seg, "time": np.linspace(0.0, 1.2, 600)}
    meta = {"path": str(tmp_path / "src.tab"), "enum": 0, "spring constant": k,
            "point count": 600, "imaging mode": "force-distance"}
    out = tmp_path / "curve.tab"
    afmformats.AFMForceDistance(data, meta).export_data(str(out), fmt="tab")
    c = read_curve(out, segment="approach")
    assert c.meta["reader"] == "afmformats" and c.meta["spring_constant"] == k
    # the exporter writes 8 significant digits
    np.testing.assert_allclose(c.depth, depth[:300], rtol=0, atol=1e-7 * np.max(depth))
    both = read_curve(out, segment="both")
    assert both.depth.size == 600 and both.time is not None
    res = indentation(c.depth, c.force, Paraboloid(R=R), sample=Elastic(E=1e6, nu=NU))
    # the exporter writes 8 significant digits: the recovery is as good as the file
    assert res.params["E"] == pytest.approx(E, rel=1e-6)
    with pytest.raises(errors.ParameterError, match="index=3"):
        read_curve(out, index=3)
