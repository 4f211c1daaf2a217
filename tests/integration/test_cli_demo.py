"""The console entry point: `contactlab demo` prints Hertz numbers that match the closed form."""
from __future__ import annotations

import numpy as np

from contactlab.cli import main
from tests import tolerances as TOL


def test_demo_prints_hertz_table(capsys, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)        # `demo` without -o makes a new folder in the cwd
    assert main(["demo"]) == 0
    out = capsys.readouterr().out
    E_star = 210e9 / (2 * (1 - 0.3**2))
    R = 0.01
    rows = [line.split() for line in out.splitlines() if line.strip()[:1].isdigit()]
    assert len(rows) >= 3
    for d_um, f, a_um, p in (map(float, row[:4]) for row in rows):
        d = d_um * 1e-6
        assert np.isclose(f, 4 / 3 * E_star * np.sqrt(R) * d**1.5, rtol=TOL.PRINTED_5_DIGITS)
        assert np.isclose(a_um * 1e-6, np.sqrt(R * d), rtol=TOL.PRINTED_5_DIGITS)
        assert np.isclose(p * 1e6, 2 * E_star * np.sqrt(R * d) / (np.pi * R), rtol=TOL.PRINTED_5_DIGITS)


def test_version(capsys):
    import pytest
    with pytest.raises(SystemExit) as exc:
        main(["--version"])
    assert exc.value.code == 0
    assert "contactlab" in capsys.readouterr().out
