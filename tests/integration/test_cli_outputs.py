"""What a command may write (issue 26): never over a scene's own input, never over an existing file
without --overwrite, and never remove a file that no contactlab run wrote into that folder."""
from __future__ import annotations

import json

import pytest

from contactlab.cli import main
from contactlab.scene.run import MANIFEST

SCENE = """
[profile]
type = "paraboloid"
R = "10 mm"
[materials]
body1 = {type = "elastic", E = "210 GPa", nu = 0.3}
body2 = {type = "rigid"}
[[load_path]]
table = {file = "TABLE"}
"""
HISTORY = "time,force\n0,0\n1,5\n2,10\n"


def scene_reading(folder, name):
    """A scene in ``folder`` whose load history is the CSV file ``name`` beside it."""
    (folder / name).write_text(HISTORY)
    scene = folder / "scene.toml"
    scene.write_text(SCENE.replace("TABLE", name))
    return scene


@pytest.mark.parametrize("name", ["series.csv", "fields.csv", "status.json"])
def test_overwrite_never_touches_the_scenes_own_input(tmp_path, capsys, name):
    """`run scene.toml -o . --overwrite` with an input named like an output: refused before the
    run (exit 2), the input byte for byte as it was (it was replaced or deleted before)."""
    scene = scene_reading(tmp_path, name)
    assert main(["run", str(scene), "-o", str(tmp_path), "--overwrite"]) == 2
    err = capsys.readouterr().err
    assert "which the scene reads" in err and name in err
    assert (tmp_path / name).read_text() == HISTORY
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted([name, "scene.toml"])


def test_overwrite_keeps_files_no_run_wrote(tmp_path, capsys):
    """--overwrite replaces the files this run writes; a file named like another output that no
    contactlab run wrote there (a user's plot.png, wear.csv) stays."""
    scene = scene_reading(tmp_path, "history.csv")
    out = tmp_path / "out"
    out.mkdir()
    (out / "plot.png").write_text("my own picture")
    (out / "wear.csv").write_text("my own table")
    assert main(["run", str(scene), "-o", str(out), "--overwrite"]) == 0
    assert (out / "plot.png").read_text() == "my own picture"
    assert (out / "wear.csv").read_text() == "my own table"
    assert (out / "series.csv").read_text().startswith("time [s]")
    assert json.loads((out / MANIFEST).read_text())["files"].keys() == {"series.csv"}


def test_an_earlier_output_edited_since_is_kept(tmp_path, capsys):
    """An earlier run's file is removed only while it is what that run wrote."""
    scene = scene_reading(tmp_path, "history.csv")
    out = tmp_path / "out"
    assert main(["run", str(scene), "-o", str(out)]) == 0
    (out / "series.csv").write_text("edited by hand")
    assert main(["run", str(scene), "-o", str(out), "--overwrite", "--format", "json"]) == 0
    assert (out / "series.csv").read_text() == "edited by hand"
    assert main(["run", str(scene), "-o", str(out), "--overwrite"]) == 0   # written again
    assert main(["run", str(scene), "-o", str(out), "--overwrite", "--format", "json"]) == 0
    assert sorted(p.name for p in out.iterdir()) == sorted([MANIFEST, "result.json"])


def test_plot_without_output_folder_needs_overwrite(tmp_path, capsys, monkeypatch):
    """`run --plot` without -o writes ./plot.png: an existing one is replaced only with
    --overwrite (checked before the run), and never when the scene reads it."""
    monkeypatch.chdir(tmp_path)
    scene = scene_reading(tmp_path, "history.csv")
    (tmp_path / "plot.png").write_text("precious")
    assert main(["run", str(scene), "--plot"]) == 2
    assert "'plot.png' exists" in capsys.readouterr().err
    assert (tmp_path / "plot.png").read_text() == "precious"
    scene = scene_reading(tmp_path, "plot.png")
    assert main(["run", str(scene), "--plot", "--overwrite"]) == 2
    assert (tmp_path / "plot.png").read_text() == HISTORY


def test_plot_without_output_folder_replaces_with_overwrite(tmp_path, capsys, monkeypatch):
    pytest.importorskip("matplotlib")
    monkeypatch.chdir(tmp_path)
    scene = scene_reading(tmp_path, "history.csv")
    (tmp_path / "plot.png").write_text("old")
    assert main(["run", str(scene), "--plot", "--overwrite"]) == 0
    assert (tmp_path / "plot.png").read_bytes()[:4] == b"\x89PNG"


def test_cost_plot_refuses_an_existing_file(tmp_path, capsys):
    """`cost --plot f.png` with f.png there: refused before the ladders run; the scene file itself
    is refused even with --overwrite."""
    scene = scene_reading(tmp_path, "history.csv")
    target = tmp_path / "f.png"
    target.write_text("precious")
    assert main(["cost", str(scene), "--plot", str(target)]) == 2
    assert "--overwrite" in capsys.readouterr().err
    assert target.read_text() == "precious"
    for victim in (scene, tmp_path / "history.csv"):
        before = victim.read_text()
        assert main(["cost", str(scene), "--plot", str(victim), "--overwrite"]) == 2
        assert victim.read_text() == before


def test_demo_writes_into_a_new_folder(tmp_path, capsys, monkeypatch):
    """`contactlab demo` without -o never writes over a file in the current folder: each run
    makes a new folder for its picture."""
    monkeypatch.chdir(tmp_path)
    (tmp_path / "contactlab_demo.png").write_text("precious")
    (tmp_path / "contactlab-demo").mkdir()
    (tmp_path / "contactlab-demo" / "contactlab_demo.png").write_text("also precious")
    assert main(["demo", "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    assert (tmp_path / "contactlab_demo.png").read_text() == "precious"
    assert (tmp_path / "contactlab-demo" / "contactlab_demo.png").read_text() == "also precious"
    try:
        import matplotlib  # noqa: F401
    except ImportError:
        assert doc["files"] == [] and not (tmp_path / "contactlab-demo-2").exists()
    else:
        assert doc["files"] == ["contactlab-demo-2/contactlab_demo.png"]
        assert main(["demo"]) == 0
        assert "wrote contactlab-demo-3/contactlab_demo.png" in capsys.readouterr().out


def test_a_plot_the_run_wrote_is_recorded_and_removed_later(tmp_path, capsys):
    """run --plot records plot.png; a later --overwrite run without --plot removes it (an
    earlier run's file, unchanged)."""
    pytest.importorskip("matplotlib")
    scene = scene_reading(tmp_path, "history.csv")
    out = tmp_path / "out"
    assert main(["run", str(scene), "-o", str(out), "--plot"]) == 0
    assert set(json.loads((out / MANIFEST).read_text())["files"]) == {"series.csv", "plot.png"}
    assert main(["run", str(scene), "-o", str(out), "--overwrite"]) == 0
    assert sorted(p.name for p in out.iterdir()) == [MANIFEST, "series.csv"]
