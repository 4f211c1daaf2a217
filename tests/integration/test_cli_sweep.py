"""``contactlab sweep``: the table on disk, resumption from the store, errors and exit codes; a
sweep killed mid-way (SIGKILL) resumes computing only the points it had not stored."""
from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

pd = pytest.importorskip("pandas")

import contactlab
from contactlab.cli import main

ROOT = Path(__file__).resolve().parents[2]
SCENE = ROOT / "examples" / "steel_ball_twist.toml"
GRID = ["--grid", "interface.friction=-0.1:0.3:3", "--grid", "load_path[1].ramp.twist=1e-3:1e-2:3:log"]


def test_sweep_writes_the_table_and_a_rerun_resumes(tmp_path, capsys):
    pytest.importorskip("pyarrow")
    out = tmp_path / "out"
    assert main(["sweep", str(SCENE), *GRID, "-o", str(out), "--workers", "1"]) == 0
    assert "9 points (3 failed" in capsys.readouterr().out
    table = pd.read_csv(out / "sweep.csv", comment="#")
    # units in the headers, the same style as every result's CSV (issue 27)
    assert "torque [N*m]" in table.columns and "torque_max [N*m]" in table.columns
    table = table.rename(columns=lambda c: c.split(" [")[0])
    twists = list(dict.fromkeys(table["load_path[1].ramp.twist"]))
    np.testing.assert_allclose(twists, [1e-3, np.sqrt(1e-5), 1e-2], rtol=1e-15)
    api = contactlab.sweep(SCENE, {"interface.friction": [-0.1, 0.1, 0.3],
                                   "load_path[1].ramp.twist": twists}, workers=1)
    assert table["point"].tolist() == list(range(9))
    np.testing.assert_array_equal(table["torque"].to_numpy(), api["torque"].to_numpy())
    assert table["error"].fillna("").tolist() == ["SceneError"] * 3 + [""] * 6
    assert main(["sweep", str(SCENE), *GRID, "-o", str(out), "--json"]) == 2   # sweep.csv there
    assert "--overwrite" in json.loads(capsys.readouterr().out)["error"]
    assert main(["sweep", str(SCENE), *GRID, "-o", str(out), "--json", "--overwrite"]) == 0
    payload = json.loads(capsys.readouterr().out)
    assert payload["stats"]["resumed"] == 9 and payload["stats"]["computed"] == 0
    assert payload["failed"] == 3


def test_sweep_without_output_prints_the_table(capsys):
    assert main(["sweep", str(SCENE), "--grid", "interface.friction=0.1,0.2", "--json"]) == 0
    payload = json.loads(capsys.readouterr().out)
    assert payload["table"]["interface.friction"] == [0.1, 0.2]
    assert payload["table"]["error"] == [None, None] and payload["files"] == []


@pytest.mark.parametrize("args, message", [
    (["--grid", "interface.fricton=0.1"], "did you mean 'friction'"),
    (["--grid", "interface.friction=0.1:0.2"], "A:B:N or A:B:N:log"),
    ([], "needs at least one --grid"),
    (["--grid", "x=1", "--grid", "x=2"], "already an axis"),
])
def test_bad_sweeps_exit_2(args, message, capsys):
    assert main(["sweep", str(SCENE), *args]) == 2
    assert message in capsys.readouterr().err


def test_scheduler_and_workers_exclude_each_other(capsys):
    with pytest.raises(SystemExit) as exc:
        main(["sweep", str(SCENE), "--grid", "interface.friction=0.1", "--workers", "2",
              "--scheduler", "tcp://127.0.0.1:1"])
    assert exc.value.code == 2


# ---- a killed sweep ----------------------------------------------------------------------------
def slow(x, log):
    """A study that takes 20 ms and logs each point it computes (one line per call)."""
    time.sleep(0.02)
    with open(log, "a") as fh:
        fh.write(f"{x}\n")
    return {"y": x * x}


def _computed(log: Path) -> list[float]:
    return [float(v) for v in log.read_text().split()] if log.exists() else []


@pytest.mark.slow
def test_a_killed_sweep_resumes_computing_only_the_rest(tmp_path):
    pytest.importorskip("pyarrow")
    from contactlab.sweeps import read_store
    store, log = tmp_path / "s.parquet", tmp_path / "calls.log"
    code = ("import sys, contactlab\n"
            "from tests.integration.test_cli_sweep import slow\n"
            f"contactlab.sweep(slow, {{'x': [float(i) for i in range(250)], 'log': [{str(log)!r}]}},"
            f" workers=1, progress=False, store={str(store)!r})\n")
    proc = subprocess.Popen([sys.executable, "-c", code], cwd=ROOT)
    try:
        deadline = time.monotonic() + 120
        while not list(store.glob("part-*.parquet")) and time.monotonic() < deadline:
            assert proc.poll() is None, "the sweep ended before it could be killed"
            time.sleep(0.05)
        time.sleep(0.3)
        proc.send_signal(signal.SIGKILL)
    finally:
        proc.wait(timeout=60)
    assert proc.returncode == -signal.SIGKILL
    stored = set(read_store(store)["point"].tolist())
    first = _computed(log)
    assert 0 < len(stored) < 250 and stored <= {int(x) for x in first}
    log.unlink()
    table = contactlab.sweep(slow, {"x": [float(i) for i in range(250)], "log": [str(log)]},
                             workers=1, progress=False, store=store)
    second = sorted(int(x) for x in _computed(log))
    assert second == sorted(set(range(250)) - stored)           # only the rest, each once
    assert table["y"].tolist() == [float(i * i) for i in range(250)]
    assert table.attrs["sweep"]["stats"]["resumed"] == len(stored)


def test_sweep_over_the_time_budget_is_a_clean_error_and_resumes(tmp_path, capsys, monkeypatch):
    """Over the time budget after the timing points: a clean message (the estimate, the budget,
    how to raise it and resume), the exit code of other errors; the same command with a larger
    budget resumes from the store."""
    pytest.importorskip("pyarrow")
    out = tmp_path / "out"
    monkeypatch.setenv("CONTACTLAB_TIME_BUDGET", "1e-9")
    previous = contactlab.set_time_budget(None)
    try:
        argv = ["sweep", str(SCENE), *GRID, "-o", str(out), "--workers", "1", "--json"]
        assert main(argv) == 2
        payload = json.loads(capsys.readouterr().out)
        assert payload["ok"] is False and "Traceback" not in payload["error"]
        assert "sweep() would run for about" in payload["error"]
        assert "CONTACTLAB_TIME_BUDGET" in payload["error"] and "resume" in payload["error"]
        monkeypatch.setenv("CONTACTLAB_TIME_BUDGET", "1h")
        assert main(argv) == 0
        payload = json.loads(capsys.readouterr().out)
        assert payload["stats"]["resumed"] > 0 and payload["points"] == 9
    finally:
        contactlab.set_time_budget(previous)
