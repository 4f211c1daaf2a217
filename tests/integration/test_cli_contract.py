"""The CLI contract (issue 11): every failure exits 2 (invalid input) or 1 (numerical) with one
human line on stderr, or with --json one JSON error object on stdout, never a traceback; outputs
are written atomically, never through a planted symbolic link; a non-empty output folder is
refused without --overwrite; scene file references stay inside the scene's folder."""
from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

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
ramp = {force = "10 N", steps = 5}
"""


@pytest.fixture
def scene(tmp_path):
    p = tmp_path / "scene" / "s.toml"
    p.parent.mkdir()
    p.write_text(SCENE)
    return p


def code_of(argv):
    """main's return value, or the code of the SystemExit argparse raises on usage errors."""
    try:
        return main(argv)
    except SystemExit as exc:
        return exc.code


def failure(argv, capsys, code):
    """Run ``argv`` plain and with --json: the exit code, one stderr line, one JSON object."""
    assert code_of(argv) == code
    out, err = capsys.readouterr()
    assert "Traceback" not in err + out
    lines = err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("contactlab"), err
    assert code_of(argv + ["--json"]) == code
    out, err = capsys.readouterr()
    doc = json.loads(out)
    assert doc["ok"] is False and doc["exit"] == code and doc["error"]
    return lines[0], doc


def test_output_folder_is_a_file(scene, tmp_path, capsys):
    f = tmp_path / "afile"
    f.write_text("x")
    line, doc = failure(["run", str(scene), "-o", str(f)], capsys, 2)
    assert "is a file" in line and doc["kind"] == "ParameterError"
    line, _ = failure(["run", str(scene), "-o", str(f / "sub")], capsys, 2)
    assert "cannot be created" in line
    line, _ = failure(["demo", "-o", str(f / "missing" / "dir")], capsys, 2)
    assert "cannot be created" in line


@pytest.mark.skipif(os.name != "posix" or os.geteuid() == 0,
                    reason="permissions do not bind the super-user")
def test_output_folder_read_only(scene, tmp_path, capsys):
    ro = tmp_path / "ro"
    ro.mkdir()
    ro.chmod(0o555)
    try:
        line, _ = failure(["run", str(scene), "-o", str(ro)], capsys, 2)
        assert "not writable" in line
        failure(["run", str(scene), "-o", str(ro / "sub")], capsys, 2)
    finally:
        ro.chmod(0o755)


def test_usage_errors_and_missing_scene(scene, tmp_path, capsys):
    failure(["run", str(scene), "--bogus"], capsys, 2)
    failure(["run", str(tmp_path / "missing.toml")], capsys, 2)


def test_numerical_failure_exits_1(tmp_path, capsys):
    """A force beyond what a sphere can carry (a would reach R) is a run failure, exit 1."""
    p = tmp_path / "s.toml"
    p.write_text(SCENE.replace('type = "paraboloid"', 'type = "sphere"')
                 .replace('"10 N"', '"1e15 N"'))
    line, doc = failure(["run", str(p)], capsys, 1)
    assert doc["kind"] == "OutsideTheoryError"


def test_non_empty_folder_needs_overwrite_and_json_leaves_no_stale_csv(scene, tmp_path, capsys):
    out = tmp_path / "out"
    assert main(["run", str(scene), "-o", str(out)]) == 0
    assert (out / "series.csv").is_file()
    capsys.readouterr()
    line, _ = failure(["run", str(scene), "-o", str(out), "--format", "json"], capsys, 2)
    assert "--overwrite" in line
    assert main(["run", str(scene), "-o", str(out), "--format", "json", "--overwrite"]) == 0
    assert sorted(p.name for p in out.iterdir()) == [MANIFEST, "result.json"]   # no stale csv


def test_planted_symlink_is_replaced_not_followed(scene, tmp_path):
    out = tmp_path / "out"
    out.mkdir()
    victim = tmp_path / "victim.txt"
    victim.write_text("precious")
    (out / "series.csv").symlink_to(victim)
    assert main(["run", str(scene), "-o", str(out), "--overwrite"]) == 0
    assert victim.read_text() == "precious"
    assert not (out / "series.csv").is_symlink()
    assert (out / "series.csv").read_text().startswith("time")
    assert not [p for p in out.iterdir() if p.name.endswith(".tmp")]     # no temp file left


def test_scene_file_references_are_contained(tmp_path, capsys):
    secret = tmp_path / "secret.csv"
    secret.write_text("root:x:0:0:root:/root:/bin/bash\nTOPSECRET,1\n")
    d = tmp_path / "a" / "b"
    d.mkdir(parents=True)
    scene = d / "s.toml"
    scene.write_text(SCENE.replace('ramp = {force = "10 N", steps = 5}',
                                   'table = {file = "../../secret.csv"}'))
    assert main(["validate", str(scene)]) == 2
    out, err = capsys.readouterr()
    assert "inside the scene's folder" in err and "root:x" not in err + out
    # opting out reads the file, but the error never shows its contents
    for argv in (["validate", str(scene), "--allow-outside"],
                 ["validate", str(scene), "--allow-outside", "--json"]):
        assert main(argv) == 2
        out, err = capsys.readouterr()
        assert "readable CSV" in err + out
        assert "root:x" not in err + out and "TOPSECRET" not in err + out
    # a link inside the folder that points outside is outside too
    (d / "link.csv").symlink_to(secret)
    scene.write_text(SCENE.replace('ramp = {force = "10 N", steps = 5}',
                                   'table = {file = "link.csv"}'))
    assert main(["validate", str(scene)]) == 2
    assert "inside the scene's folder" in capsys.readouterr().err


def test_absolute_reference_is_an_explicit_opt_out(tmp_path, capsys):
    hist = tmp_path / "h.csv"
    hist.write_text("time,force\n0,0\n1,5\n2,10\n")
    d = tmp_path / "s"
    d.mkdir()
    scene = d / "s.toml"
    scene.write_text(SCENE.replace('ramp = {force = "10 N", steps = 5}',
                                   f'table = {{file = "{hist.as_posix()}"}}'))
    assert main(["validate", str(scene)]) == 0


def test_inline_table_obeys_the_step_limit(tmp_path, capsys):
    from contactlab.scene.validate import MAX_STEPS
    n = MAX_STEPS + 1
    scene = tmp_path / "s.toml"
    scene.write_text(SCENE.replace('ramp = {force = "10 N", steps = 5}',
                                   "table = {force = [" + ", ".join(["1.0"] * n) + "]}"))
    assert main(["validate", str(scene)]) == 2
    assert f"at most {MAX_STEPS} steps" in capsys.readouterr().err


def test_real_process_prints_no_traceback(tmp_path):
    f = tmp_path / "afile"
    f.write_text("x")
    r = subprocess.run([sys.executable, "-m", "contactlab", "demo", "-o", str(f / "x")],
                       capture_output=True, text=True, cwd=tmp_path,
                       env={**os.environ, "PYTHONPATH": str(Path(__file__).parents[2])})
    assert r.returncode == 2 and "Traceback" not in r.stderr
    assert len(r.stderr.strip().splitlines()) == 1


def test_scene_problems_are_one_stderr_line_and_listed_in_json(tmp_path, capsys):
    p = tmp_path / "bad.toml"
    p.write_text(SCENE.replace('R = "10 mm"', 'R = "-10 mm"')
                 .replace('nu = 0.3', 'nu = 0.7').replace("steps = 5", "steps = 0"))
    line, doc = failure(["validate", str(p)], capsys, 2)
    assert line.startswith("contactlab: bad.toml: 3 problems: ")
    for key in ("profile.R = '-10 mm'", "materials.body1.nu = 0.7", "load_path[0].ramp.steps = 0"):
        assert key in line
    assert line.count(";") == 2
    assert doc["kind"] == "SceneError" and doc["error"] == line.removeprefix("contactlab: ")
    assert [i["path"] for i in doc["issues"]] == ["profile.R", "materials.body1.nu",
                                                 "load_path[0].ramp.steps"]
    failure(["run", str(p)], capsys, 2)


def test_warnings_are_one_line_each(tmp_path):
    """A ValidityWarning during a run is one stderr line (class and message, no source echo)."""
    p = tmp_path / "s.toml"
    p.write_text(SCENE.replace('type = "paraboloid"', 'type = "sphere"')
                 .replace('E = "210 GPa"', 'E = "1 GPa"').replace('"10 N"', '"1e5 N"'))
    r = subprocess.run([sys.executable, "-m", "contactlab", "run", str(p)],
                       capture_output=True, text=True, cwd=tmp_path,
                       env={**os.environ, "PYTHONPATH": str(Path(__file__).parents[2])})
    assert r.returncode == 0, r.stderr
    lines = r.stderr.strip().splitlines()
    assert lines and all(ln.startswith("contactlab: ValidityWarning: ") for ln in lines), lines


@pytest.mark.parametrize("segments", [
    # a CSV history's rows count, also under a repeat (each row is one step)
    ['table = {{file = "h.csv"}}', 'repeat = {{times = {big}}}'],
    ['table = {{file = "h.csv"}}', 'ramp = {{force = "5 N", steps = {rest}}}'],
    ['ramp = {{force = "5 N", steps = {rest}}}', 'table = {{file = "h.csv"}}'],
    # every other kind counts as well
    ['ramp = {{force = "5 N", steps = {half}}}', 'hold = {{steps = {half}}}',
     'table = {{force = [1.0, 2.0]}}'],
    ['ramp = {{force = "5 N", steps = 10}}',
     'sinusoid = {{force = "1 N", cycles = {quarter}, steps_per_cycle = 4}}',
     'hold = {{steps = 3}}'],
    ['ramp = {{force = "5 N", steps = 10}}', 'hold = {{steps = 10}}',
     'repeat = {{times = {big20}, last = 2}}'],
])
def test_every_segment_kind_and_history_file_counts_toward_the_step_limit(tmp_path, capsys,
                                                                         segments):
    from contactlab.scene.validate import MAX_STEPS
    rows = 100
    (tmp_path / "h.csv").write_text("time,force\n" + "".join(f"{i},{1.0 + i % 3}\n"
                                                            for i in range(rows)))
    fmt = {"big": MAX_STEPS // rows + 1, "rest": MAX_STEPS - rows + 1, "half": MAX_STEPS // 2,
           "quarter": MAX_STEPS // 4, "big20": MAX_STEPS // 20 + 1}
    body = "".join(f"[[load_path]]\n{s.format(**fmt)}\n" for s in segments)
    scene = tmp_path / "s.toml"
    scene.write_text(SCENE.split("[[load_path]]")[0] + body)
    assert main(["validate", str(scene)]) == 2
    assert f"at most {MAX_STEPS} steps in total" in capsys.readouterr().err
    # one step fewer is accepted (the limit is exact), for the history-file cases
    if "rest" in segments[-1] or "rest" in segments[0]:
        fmt["rest"] -= 1
        body = "".join(f"[[load_path]]\n{s.format(**fmt)}\n" for s in segments)
        scene.write_text(SCENE.split("[[load_path]]")[0] + body)
        assert main(["validate", str(scene)]) == 0, capsys.readouterr().err


@pytest.mark.parametrize("text", ["root:x:0:0:root:/root:/bin/bash\nTOPSECRET,1\n",
                                  "r,f\n0,0\n1e-3,TOPSECRET\n",
                                  "r [TOPSECRET],f\n0,0\n1e-3,1e-9\n2e-3,4e-9\n",
                                  "r,f\n0,0\n1e-3,1e-9,TOPSECRET\n"])
def test_profile_file_errors_never_show_the_file(tmp_path, capsys, text):
    """A tabulated profile named outside the scene's folder (read with --allow-outside) that is
    not a valid table: the error names rows and columns by position, never the contents."""
    (tmp_path / "secret.csv").write_text(text)
    d = tmp_path / "a" / "b"
    d.mkdir(parents=True)
    scene = d / "s.toml"
    scene.write_text(SCENE.replace('type = "paraboloid"\nR = "10 mm"',
                                   'type = "tabulated"\nfile = "../../secret.csv"'))
    for argv in (["validate", str(scene), "--allow-outside"],
                 ["validate", str(scene), "--allow-outside", "--json"]):
        assert main(argv) == 2
        out, err = capsys.readouterr()
        assert "secret.csv" in out + err
        assert "TOPSECRET" not in out + err and "root:x" not in out + err


def test_broken_pipe_is_no_traceback(scene):
    r = subprocess.run(f"{sys.executable} -m contactlab validate {scene} --json | head -c 1",
                       shell=True, capture_output=True, text=True,
                       env={**os.environ, "PYTHONPATH": str(Path(__file__).parents[2])})
    assert "Traceback" not in r.stderr
