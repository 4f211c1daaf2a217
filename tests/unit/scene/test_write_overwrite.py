"""SceneResult.write never replaces or removes a file unless overwrite=True (issue 26 item 6),
the rule of the results' to_csv; the CLI checks its own targets (-o, --overwrite) first."""
from __future__ import annotations

import json

import pytest

from contactlab.errors import ParameterError
from contactlab.scene import Scene
from contactlab.scene.run import MANIFEST

from tests.unit.scene.helpers import base


@pytest.fixture(scope="module")
def result():
    return Scene(base()).run()


def test_second_write_refuses_and_keeps_the_files(result, tmp_path):
    first = result.write(tmp_path)
    before = {p.name: p.read_bytes() for p in tmp_path.iterdir()}
    with pytest.raises(ParameterError, match=r"series\.csv.*overwrite=True"):
        result.write(tmp_path)
    assert {p.name: p.read_bytes() for p in tmp_path.iterdir()} == before
    assert [p.name for p in result.write(tmp_path, overwrite=True)] == [p.name for p in first]


def test_a_users_file_of_an_output_name_is_never_replaced(result, tmp_path):
    mine = tmp_path / "series.csv"
    mine.write_text("my own data\n")
    with pytest.raises(ParameterError, match="overwrite=True"):
        result.write(tmp_path)
    assert mine.read_text() == "my own data\n"
    assert not (tmp_path / MANIFEST).exists()


def test_removing_an_earlier_output_needs_overwrite(result, tmp_path):
    """A JSON write beside an earlier CSV write would remove series.csv: refused without
    overwrite=True; with it the folder holds one consistent result."""
    result.write(tmp_path)
    with pytest.raises(ParameterError, match=r"series\.csv"):
        result.write(tmp_path, "json")
    assert (tmp_path / "series.csv").exists() and not (tmp_path / "result.json").exists()
    result.write(tmp_path, "json", overwrite=True)
    assert sorted(p.name for p in tmp_path.iterdir()) == [MANIFEST, "result.json"]
    assert json.loads((tmp_path / MANIFEST).read_text())["files"].keys() == {"result.json"}


def test_a_file_as_directory_is_refused(result, tmp_path):
    f = tmp_path / "f"
    f.write_text("x")
    with pytest.raises(ParameterError, match="not a folder"):
        result.write(f)
