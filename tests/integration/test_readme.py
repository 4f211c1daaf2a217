"""The README quick start runs as written (and its Hertz numbers are the closed form)."""
from __future__ import annotations

import re
from pathlib import Path

import numpy as np
from tests import tolerances as TOL

README = Path(__file__).resolve().parents[2] / "README.md"


def test_quick_start_runs(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)        # it writes run.csv
    block = re.findall(r"```python\n(.*?)```", README.read_text(), re.S)[0]
    env: dict = {}
    exec(compile(block, "README.md quick start", "exec"), env)
    s = env["s"]
    E_star = 210e9 / (2 * (1 - 0.3**2))
    a = (3 * 100.0 * 0.01 / (4 * E_star)) ** (1 / 3)            # Hertz, Johnson (1985) eq. 4.22
    assert np.isclose(s.radius, a, rtol=TOL.HARD_CLOSED)
    assert (tmp_path / "run.csv").exists()
    assert env["h"].dissipated_energy[-1] > 0
