"""Sweeps and runs that go wrong outside the physics (issue 26): Ctrl-C, a damaged checkpoint, a
store that cannot be made, a study that cannot be sent to workers, a scheduler address that is
none, an existing sweep.csv. Each is one line and a specific exit code, never a traceback; the
checkpoint of an interrupted sweep survives and resumes."""
from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import threading
import time
from pathlib import Path

import pytest

import contactlab
from contactlab.cli import main
from contactlab.errors import ParameterError

ROOT = Path(__file__).resolve().parents[2]
SCENE = ROOT / "examples" / "hertz_steel_ball.toml"
AXIS = ["--grid", "profile.R=0.005:0.02:3", "--workers", "1"]


def test_ctrl_c_in_run_is_one_line_and_exit_130(monkeypatch, capsys):
    from contactlab.scene import Scene

    def interrupted(self):
        raise KeyboardInterrupt
    monkeypatch.setattr(Scene, "run", interrupted)
    assert main(["run", str(SCENE)]) == 130
    out, err = capsys.readouterr()
    assert err == "contactlab: interrupted\n" and "Traceback" not in out
    assert main(["run", str(SCENE), "--json"]) == 130
    doc = json.loads(capsys.readouterr().out)
    assert doc == {"ok": False, "exit": 130, "error": "interrupted", "kind": "KeyboardInterrupt"}


@pytest.mark.skipif(os.name != "posix", reason="SIGINT to a process group")
def test_ctrl_c_in_a_pool_sweep_keeps_the_checkpoint(tmp_path):
    """SIGINT to the whole process group (what a terminal's Ctrl-C does) while a sweep runs on
    2 worker processes: one line, exit 130, no worker traceback; the same command resumes."""
    pytest.importorskip("pyarrow")
    out = tmp_path / "out"
    argv = [sys.executable, "-m", "contactlab", "sweep", str(SCENE), "--grid",
            "profile.R=0.005:0.02:20000", "--workers", "2", "-o", str(out)]
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    # a terminal's process starts with SIGINT at its default; a parent that ignores it (a shell's
    # background job without job control) would pass SIG_IGN on and the sweep would never see it
    proc = subprocess.Popen(argv, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                            env=env, start_new_session=True,
                            preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
    try:
        deadline = time.monotonic() + 120
        while not list((out / "sweep.parquet").glob("part-*.parquet")):
            assert proc.poll() is None and time.monotonic() < deadline, proc.stderr.read()
            time.sleep(0.05)
        os.killpg(proc.pid, signal.SIGINT)
        _, err = proc.communicate(timeout=120)
    finally:
        if proc.poll() is None:
            os.killpg(proc.pid, signal.SIGKILL)
            proc.wait()
    assert proc.returncode == 130, err
    assert "Traceback" not in err and "KeyboardInterrupt" not in err, err
    last = err.strip().splitlines()[-1]        # tqdm's bar may precede it on stderr
    assert last.startswith("contactlab: interrupted; the points finished so far are kept in")
    from contactlab.sweeps import read_store
    assert 0 < len(read_store(out / "sweep.parquet")) < 20000
    assert not (out / "sweep.csv").exists()


def test_a_damaged_checkpoint_names_the_file(tmp_path, capsys):
    pytest.importorskip("pyarrow")
    out = tmp_path / "out"
    assert main(["sweep", str(SCENE), *AXIS, "-o", str(out)]) == 0
    capsys.readouterr()
    store = out / "sweep.parquet"
    part = next(store.glob("part-*.parquet"))
    part.write_bytes(part.read_bytes()[:40])                    # cut short
    assert main(["sweep", str(SCENE), *AXIS, "-o", str(out), "--overwrite"]) == 2
    err = capsys.readouterr().err
    assert f"is damaged: {part.name} cannot be read" in err and "internal error" not in err
    with pytest.raises(ParameterError, match=f"{part.name} cannot be read"):
        contactlab.sweep(SCENE, {"profile.R": [0.005, 0.0125, 0.02]}, workers=1, store=store)
    (store / "_sweep.json").write_text("{not json")
    with pytest.raises(ParameterError, match="_sweep.json cannot be read"):
        contactlab.sweep(SCENE, {"profile.R": [0.005, 0.0125, 0.02]}, workers=1, store=store)


def test_a_store_that_cannot_be_created(tmp_path):
    pytest.importorskip("pyarrow")
    afile = tmp_path / "afile"
    afile.write_text("x")
    with pytest.raises(ParameterError, match="cannot be created or written"):
        contactlab.sweep(SCENE, {"profile.R": [0.01]}, workers=1, store=afile / "x.parquet")


def test_an_unpicklable_study_is_refused_before_any_point(tmp_path):
    calls = []

    def study(x):
        calls.append(x)
        return {"y": x}
    study.lock = threading.Lock()        # what no pickler can send
    with pytest.raises(ParameterError, match="cannot be sent to worker processes") as exc:
        contactlab.sweep(study, {"x": [1.0, 2.0, 3.0]}, workers=2, progress=False)
    assert "workers=1" in str(exc.value) and calls == []


def test_a_scheduler_address_that_is_none(capsys):
    assert main(["sweep", str(SCENE), "--grid", "profile.R=0.01", "--scheduler",
                 "not a url"]) == 2
    err = capsys.readouterr().err
    assert "--scheduler 'not a url' is invalid" in err and "internal error" not in err


def test_sweep_never_writes_over_a_file_it_did_not_write(tmp_path, capsys):
    out = tmp_path / "out"
    out.mkdir()
    (out / "sweep.csv").write_text("precious")
    assert main(["sweep", str(SCENE), *AXIS, "-o", str(out)]) == 2
    assert "--overwrite" in capsys.readouterr().err
    assert (out / "sweep.csv").read_text() == "precious"
    scene = out / "scene.toml"                       # a scene whose history is DIR/sweep.csv
    scene.write_text(SCENE.read_text().split("[[load_path]]")[0]
                     + '[[load_path]]\ntable = {file = "sweep.csv"}\n')
    (out / "sweep.csv").write_text("time,force\n0,0\n1,10\n")
    assert main(["sweep", str(scene), *AXIS, "-o", str(out), "--overwrite"]) == 2
    assert "which the scene reads" in capsys.readouterr().err
    assert (out / "sweep.csv").read_text() == "time,force\n0,0\n1,10\n"
