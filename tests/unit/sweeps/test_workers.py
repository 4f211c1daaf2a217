"""A local pool whose worker process dies: the sweep restarts the pool and sends the unfinished
batches again; a worker that dies every time ends the sweep with a WorkerError naming the points,
never a raw BrokenProcessPool. The deaths are real (SIGKILL of the worker process)."""
from __future__ import annotations

import os
import signal
import time
from pathlib import Path

import pytest

pd = pytest.importorskip("pandas")

import contactlab
from contactlab.errors import ContactlabError, WorkerError
from contactlab.sweeps import backends


class DiesOnce:
    """``{"y": 2 x}``; the first worker process to reach ``x == at`` kills itself (SIGKILL, as
    the out-of-memory killer or a stray ``kill`` would), leaving a marker file so that the
    retry succeeds. Never dies in the process that created it (the sweep's own process)."""

    def __init__(self, marker: Path, at: float, seconds: float = 0.0) -> None:
        self.marker = str(marker)
        self.at = at
        self.seconds = seconds
        self.parent = os.getpid()

    def __call__(self, x):
        time.sleep(self.seconds)
        if x == self.at and os.getpid() != self.parent and not os.path.exists(self.marker):
            Path(self.marker).touch()
            os.kill(os.getpid(), signal.SIGKILL)
        return {"y": 2 * x}


class AlwaysDies(DiesOnce):
    """Kills every worker process that reaches ``x == at``."""

    def __call__(self, x):
        if x == self.at and os.getpid() != self.parent:
            os.kill(os.getpid(), signal.SIGKILL)
        return {"y": 2 * x}


GRID = {"x": [float(i) for i in range(12)]}


def test_a_killed_worker_is_replaced_and_its_batches_sent_again(tmp_path):
    serial = contactlab.sweep(DiesOnce(tmp_path / "m0", at=7.0), GRID, workers=1)
    table = contactlab.sweep(DiesOnce(tmp_path / "m", at=7.0), GRID, workers=2, batch_size=2)
    assert (tmp_path / "m").exists()                      # a worker did die
    assert table.attrs["sweep"]["stats"]["restarts"] == 1
    pd.testing.assert_frame_equal(table, serial, check_exact=True)   # every point, once


def test_a_worker_dying_every_time_is_a_worker_error(tmp_path, monkeypatch):
    monkeypatch.setattr(backends, "POOL_RESTARTS", 0)         # one pool start, not three
    with pytest.raises(WorkerError, match=r"died 1 time\(s\).*points.*7.*workers=1") as err:
        contactlab.sweep(AlwaysDies(tmp_path / "m", at=7.0), GRID, workers=2, batch_size=2)
    assert isinstance(err.value, ContactlabError)


@pytest.mark.slow
def test_a_killed_worker_in_run_tasks_is_replaced(tmp_path):
    from contactlab.sweeps import run_tasks
    # 10 ms an item: more work than a round trip to the pool, so it runs there
    out = run_tasks(DiesOnce(tmp_path / "m", at=5.0, seconds=0.01), [float(i) for i in range(8)],
                    workers=2)
    assert out == [{"y": 2.0 * i} for i in range(8)] and (tmp_path / "m").exists()
