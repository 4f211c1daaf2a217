"""``contactlab fit``: a curve file with units in its header is fitted, the parameters are
printed (or given as JSON), outputs are never overwritten without --overwrite, and bad input
exits 2 with one line naming the problem."""
from __future__ import annotations

import json

import numpy as np
import pytest

from contactlab.cli import main
from tests.tolerances import FIT_RECOVERY

E, R, Z0 = 2e6, 5e-6, 10e-9


@pytest.fixture
def curve(tmp_path):
    z = np.linspace(-50.0, 200.0, 400)                  # nm
    d = np.maximum(z * 1e-9 - Z0, 0.0)
    F = 4 / 3 * E / 0.75 * np.sqrt(R) * d ** 1.5        # N
    p = tmp_path / "curve.csv"
    p.write_text("depth [nm],force [nN]\n" + "".join(
        f"{float(a)!r},{float(b) * 1e9!r}\n" for a, b in zip(z, F)))
    return p


ARGS = ["--profile", "paraboloid", "--param", f"R={R}", "--sample", "elastic:E=1e6,nu=0.5"]


def test_fit_json(curve, capsys):
    assert main(["fit", str(curve), *ARGS, "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["ok"] and out["free"] == ["E", "contact_point"]
    assert abs(out["params"]["E"] / E - 1) < FIT_RECOVERY
    assert abs(out["params"]["contact_point"] / Z0 - 1) < FIT_RECOVERY


def test_fit_text_and_output_never_overwritten(curve, tmp_path, capsys):
    out = tmp_path / "fit.csv"
    assert main(["fit", str(curve), *ARGS, "-o", str(out)]) == 0
    assert "E = 2000000 Pa" in capsys.readouterr().out
    header = next(ln for ln in out.read_text().splitlines() if not ln.startswith("#"))
    assert header == "depth [m],force [N],force_fit [N],force_residual [N]"
    assert main(["fit", str(curve), *ARGS, "-o", str(out)]) == 2
    assert "--overwrite" in capsys.readouterr().err
    assert main(["fit", str(curve), *ARGS, "-o", str(out), "--overwrite"]) == 0


def test_fit_no_output_written_when_another_is_refused(curve, tmp_path, capsys):
    """Every output path is checked before any is written: an existing --plot leaves -o's new
    file unwritten (and the existing one untouched)."""
    new, old = tmp_path / "new.csv", tmp_path / "old.png"
    old.write_text("keep")
    assert main(["fit", str(curve), *ARGS, "-o", str(new), "--plot", str(old)]) == 2
    err = capsys.readouterr().err
    assert "--plot" in err and "--overwrite" in err and "Traceback" not in err
    assert not new.exists() and old.read_text() == "keep"


def hertz_rows(header, order, z_scale=1e-9, f_scale=1e-9):
    """The Hertz curve (paraboloid R, E, nu = 0.5, contact at Z0) as CSV text: ``order`` maps
    each column of ``header`` to ``"z"``, ``"F"`` or a constant."""
    z = np.linspace(-50e-9, 200e-9, 300)
    F = 4 / 3 * E / 0.75 * np.sqrt(R) * np.maximum(z - Z0, 0.0) ** 1.5
    cols = {"z": z / z_scale, "F": F / f_scale}
    return header + "\n" + "".join(
        ",".join(repr(float(cols[c][i])) if c in cols else c for c in order) + "\n"
        for i in range(z.size))


@pytest.mark.parametrize("header, order, zs, fs", [
    ("force,depth", ("F", "z"), 1.0, 1.0),
    ("force [nN],depth [nm]", ("F", "z"), 1e-9, 1e-9),
    ("index,depth [nm],force [nN]", ("7", "z", "F"), 1e-9, 1e-9),
    ("time [ms],force [uN],comment,depth [um]", ("3", "F", "0", "z"), 1e-6, 1e-6),
])
def test_fit_reads_columns_by_name(tmp_path, capsys, header, order, zs, fs):
    """The CLI picks depth and force by their header names, in any order, other columns
    ignored (as read_curve does): Hertz's E and contact point come back."""
    p = tmp_path / "curve.csv"
    p.write_text(hertz_rows(header, order, zs, fs))
    assert main(["fit", str(p), *ARGS, "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert abs(out["params"]["E"] / E - 1) < FIT_RECOVERY
    assert abs(out["params"]["contact_point"] / Z0 - 1) < FIT_RECOVERY


@pytest.mark.parametrize("header", ["x,y", "depth,y", "z [nm],force [nN]"])
def test_fit_columns_not_named_depth_and_force_exit_2(tmp_path, capsys, header):
    p = tmp_path / "curve.csv"
    p.write_text(hertz_rows(header, ("z", "F"), 1.0, 1.0))
    assert main(["fit", str(p), *ARGS]) == 2
    err = capsys.readouterr().err
    assert "'depth' and 'force'" in err and "missing" in err and "Traceback" not in err


@pytest.mark.parametrize("extra, text", [
    (["--free", "E,radius"], "free='radius' is unknown"),
    (["--adhesion", "jkr"], "work of adhesion"),
    (["--work-of-adhesion", "0.05"], "--work-of-adhesion 0.05 is given without --adhesion"),
])
def test_fit_bad_input_exits_2(curve, capsys, extra, text):
    assert main(["fit", str(curve), *ARGS, *extra]) == 2
    err = capsys.readouterr().err
    assert text in err and "Traceback" not in err


def test_fit_missing_file(tmp_path, capsys):
    assert main(["fit", str(tmp_path / "none.csv"), *ARGS]) == 2
    assert "cannot be read" in capsys.readouterr().err


# ---------------------------------------------------------------------- viscoelastic: --time
G_INF, G_1, TAU, V = 1e4, 3e4, 0.4, 1e-6


def lee_radok_ramp(t):
    """Lee-Radok's force of a rigid paraboloid (radius R) pressed at speed V into an
    incompressible standard linear solid (G(t) = G_inf + G_1 exp(-t/τ), E*(t) = 4G(t)), contact
    at t = 0: F = 4∫G(t - s) dΦ(s) with Φ = (4/3)√R δ^(3/2), δ = V s, in closed form through
    Dawson's integral D: ∫_0^t e^(-(t-s)/τ) √s ds = τ√t - τ^(3/2) D(√(t/τ))."""
    from scipy.special import dawsn
    s = np.maximum(t, 0.0)
    return 8 * np.sqrt(R) * V ** 1.5 * (G_INF * 2 / 3 * s ** 1.5 + G_1 * (
        TAU * np.sqrt(s) - TAU ** 1.5 * dawsn(np.sqrt(s / TAU))))


@pytest.fixture
def visco_curve(tmp_path):
    t = np.linspace(-0.1, 0.5, 400)                     # s
    z = Z0 + V * t
    F = lee_radok_ramp(t)
    p = tmp_path / "visco.csv"
    p.write_text("depth [nm],force [nN],time [ms]\n" + "".join(
        f"{float(a * 1e9)!r},{float(b * 1e9)!r},{float(c * 1e3)!r}\n" for a, b, c in zip(z, F, t)))
    return p


VISCO = ["--profile", "paraboloid", "--param", f"R={R}",
         "--sample", "standard_linear_solid:G_inf=3e4,G_1=1e4,eta_1=1e4"]


def test_fit_viscoelastic_reads_the_time_column(visco_curve, capsys):
    assert main(["fit", str(visco_curve), *VISCO, "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["free"] == ["G_inf", "G_1", "eta_1", "contact_point"]
    want = {"G_inf": G_INF, "G_1": G_1, "eta_1": G_1 * TAU, "contact_point": Z0}
    for k, v in want.items():
        assert abs(out["params"][k] / v - 1) < FIT_RECOVERY, k


def test_fit_viscoelastic_time_column_named(tmp_path, visco_curve, capsys):
    renamed = tmp_path / "renamed.csv"
    renamed.write_text(visco_curve.read_text().replace("time [ms]", "t [ms]"))
    assert main(["fit", str(renamed), *VISCO, "--time", "t"]) == 0
    text = capsys.readouterr().out
    assert "G_inf = " in text and " Pa " in text and "eta_1 = " in text and "Pa s" in text


@pytest.mark.parametrize("extra, sample, text", [
    ([], "standard_linear_solid:G_inf=3e4,G_1=1e4,eta_1=1e4", "needs the sample times"),
    (["--time", "stamp"], "standard_linear_solid:G_inf=3e4,G_1=1e4,eta_1=1e4", "'stamp'"),
    (["--time", "depth"], "standard_linear_solid:G_inf=3e4,G_1=1e4,eta_1=1e4",
     "another column than 'depth' and 'force'"),
    (["--segment", "both"], "elastic:E=1e6,nu=0.5", "--segment and --index"),
])
def test_fit_time_problems_exit_2(curve, capsys, extra, sample, text):
    args = ["--profile", "paraboloid", "--param", f"R={R}", "--sample", sample]
    assert main(["fit", str(curve), *args, *extra]) == 2
    err = capsys.readouterr().err
    assert text in err and "Traceback" not in err


def test_fit_time_with_an_elastic_sample_exits_2(visco_curve, capsys):
    assert main(["fit", str(visco_curve), *ARGS, "--time", "time"]) == 2
    assert "elastic" in capsys.readouterr().err


# ---------------------------------------------------------------------- instrument files
def test_fit_reads_an_instrument_file(tmp_path, capsys):
    """An AFM file written by afmformats' own exporter (height of the cantilever's base and
    force, spring constant in its metadata) is read through read_curve and fitted."""
    afmformats = pytest.importorskip("afmformats")
    k = 50.0
    tip = np.concatenate([np.linspace(50e-9, -200e-9, 300), np.linspace(-200e-9, 50e-9, 300)])
    d = np.maximum(-tip - Z0, 0.0)
    F = 4 / 3 * E / 0.75 * np.sqrt(R) * d ** 1.5
    data = {"force": F, "height (measured)": tip - F / k, "height (piezo)": tip - F / k,
            "segment": np.r_[np.zeros(300), np.ones(300)].astype(np.uint8),
            "time": np.linspace(0.0, 1.2, 600)}
    meta = {"path": str(tmp_path / "src.tab"), "enum": 0, "spring constant": k,
            "point count": 600, "imaging mode": "force-distance"}
    out = tmp_path / "curve.tab"
    afmformats.AFMForceDistance(data, meta).export_data(str(out), fmt="tab")
    assert main(["fit", str(out), *ARGS, "--json"]) == 0
    res = json.loads(capsys.readouterr().out)
    # the exporter writes 8 significant digits: the recovery is as good as the file
    assert abs(res["params"]["E"] / E - 1) < 1e-6
    assert main(["fit", str(out), *ARGS, "--index", "2"]) == 2
    assert "index=2" in capsys.readouterr().err
    assert main(["fit", str(out), *ARGS, "--time", "time"]) == 2
    assert "instrument file" in capsys.readouterr().err
