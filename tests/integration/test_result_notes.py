"""A scene run on an approximate route writes its warnings and its model error where a machine
reads them (issue 26, item 4): ``contactlab run --json`` ``notes``, ``result.json`` ``meta``, and
``# notes: ...`` / ``# model_error: ...`` lines at the top of every CSV file of the run, which the
package's own CSV reader still reads."""
from __future__ import annotations

import json

import pytest

from contactlab.cli import DEMO_SCENE, main
from contactlab.numeric.tables import read_columns

MDR = DEMO_SCENE.replace('method = "exact"', 'method = "mdr"')
#: the command line shows warnings (one line each on stderr) instead of raising them
SHOWN = pytest.mark.filterwarnings("always::contactlab.errors.ValidityWarning")


@SHOWN
def test_run_json_carries_the_validity_warning(tmp_path, capsys):
    scene = tmp_path / "mdr.toml"
    scene.write_text(MDR)
    assert main(["run", str(scene), "--json"]) == 0
    out = capsys.readouterr()
    payload = json.loads(out.out)
    assert "dissipated energy of this twist history" in payload["notes"]
    assert "ValidityWarning" in out.err               # the console still shows it
    meta = payload["meta"]
    assert meta["model_error"] > 0.01 and meta["model_errors"]
    assert "map" in meta["model_error_basis"]
    assert any("dissipated energy" in n for n in meta["notes"])


@SHOWN
def test_run_csv_and_json_files_carry_notes_and_model_error(tmp_path, capsys):
    scene = tmp_path / "mdr.toml"
    scene.write_text(MDR)
    assert main(["run", str(scene), "-o", str(tmp_path / "csv")]) == 0
    lines = (tmp_path / "csv" / "series.csv").read_text().splitlines()
    assert lines[0].startswith("# notes: ")
    assert any(line.startswith("# model_error: ") for line in lines)
    names, cols = read_columns(tmp_path / "csv" / "series.csv", dimension=lambda n: "ignore")
    assert names[0] == "time" and cols["time"].size == 221
    assert main(["run", str(scene), "-o", str(tmp_path / "js"), "--format", "json"]) == 0
    data = json.loads((tmp_path / "js" / "result.json").read_text())
    assert data["meta"]["notes"] and data["meta"]["model_error"] > 0.01


def test_exact_run_writes_plain_csv(tmp_path, capsys):
    scene = tmp_path / "exact.toml"
    scene.write_text(DEMO_SCENE)
    assert main(["run", str(scene), "-o", str(tmp_path / "out"), "--json"]) == 0
    payload = json.loads(capsys.readouterr().out)
    assert payload["notes"] == "" and payload["meta"]["model_error"] == 0.0
    assert (tmp_path / "out" / "series.csv").read_text().startswith("time [s],")
