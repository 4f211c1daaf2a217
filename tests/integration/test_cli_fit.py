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
    assert "overwrite=True" in capsys.readouterr().err
    assert main(["fit", str(curve), *ARGS, "-o", str(out), "--overwrite"]) == 0


@pytest.mark.parametrize("extra, text", [
    (["--free", "E,radius"], "free='radius' is unknown"),
    (["--adhesion", "jkr"], "work of adhesion"),
])
def test_fit_bad_input_exits_2(curve, capsys, extra, text):
    assert main(["fit", str(curve), *ARGS, *extra]) == 2
    err = capsys.readouterr().err
    assert text in err and "Traceback" not in err


def test_fit_missing_file(tmp_path, capsys):
    assert main(["fit", str(tmp_path / "none.csv"), *ARGS]) == 2
    assert "cannot be read" in capsys.readouterr().err
