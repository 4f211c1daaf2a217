"""The hip-cup study of issue 12, end to end from the example scene. Must show the five steps
that failed before:

1. the profile CSV in mm/um and the gait CSV in ms/kN/deg are read with their units;
2. 50 nm of noise is smoothed ("auto", noise given) and the report says what smoothing did;
3. simulate runs at the default rtol on the smoothed linear table (no ConvergenceError);
4. (speed is a benchmark, not a test);
5. a ramp to the preload composes with the repeated measured gait table, and the CSV written
   has name [unit] headers.
Checks against Hertz (the r^4 wear term changes a by < 0.1 % at these loads) and the full-slip
bound of the torque.
"""
import csv
from pathlib import Path

import numpy as np

from contactlab.cli import main
from contactlab.scene import Scene
from tests.reference.hertz import radius_of_force
from tests.tolerances import HIP_CUP_RADIUS, SLIP_BOUND

EX = Path(__file__).parents[2] / "examples" / "hip_cup"


def test_hip_cup_study_end_to_end(tmp_path):
    s = Scene.from_toml(EX / "hip_cup.toml")
    prof = s.profile
    assert prof.r[-1] == 10e-3 and prof.r.size == 200                       # 1: units
    rep = prof.smoothing_report                                              # 2: smoothing
    assert rep.method == "noise" and abs(rep.noise / 50e-9 - 1) < SLIP_BOUND   # "50 nm"
    assert 0 < rep.rms_change <= 60e-9
    h = s.history()                                                          # 5: composition
    assert h.n_steps == 1 + 20 + 5 * 50
    np.testing.assert_allclose(h.values("normal")[21:71], h.values("normal")[71:121], rtol=0)
    out = tmp_path / "out"
    assert main(["run", str(EX / "hip_cup.toml"), "-o", str(out)]) == 0      # 3: simulate
    with open(out / "series.csv") as fh:
        rows = list(csv.reader(fh))
    assert rows[0] == ["time [s]", "force [N]", "radius [m]", "twist [rad]", "torque [N*m]",
                       "dissipated_energy [J]"]
    data = np.array(rows[1:], float)
    force, radius, torque = data[:, 1], data[:, 2], data[:, 4]
    E_star = 1 / ((1 - 0.3**2) / 210e9 + (1 - 0.4**2) / 1e9)
    loaded = force > 100
    a_ref = radius_of_force(force[loaded], 0.1, E_star)
    np.testing.assert_allclose(radius[loaded], a_ref, rtol=HIP_CUP_RADIUS)
    assert np.all(np.abs(torque) <= 0.75 * 0.08 * force * radius * (1 + SLIP_BOUND))


def test_hip_cup_unavailable_output_rejected_before_the_run(monkeypatch):
    """Step 5 of the study asked for ``peak_pressure``: on this route (the normal load changes
    while twisted) no per-step peak pressure is computed, and the scene says so when it is read,
    not after the run."""
    import tomllib

    import pytest

    from contactlab import Contact
    from contactlab.errors import SceneError

    def boom(*a, **k):
        raise AssertionError("computed before the outputs were checked")
    monkeypatch.setattr(Contact, "simulate", boom)
    data = tomllib.loads((EX / "hip_cup.toml").read_text())
    data["outputs"]["series"].append("peak_pressure")
    with pytest.raises(SceneError) as e:
        Scene(data, EX)
    [(path, value, allowed)] = e.value.issues
    assert (path, value) == ("outputs.series", "peak_pressure")
    assert "foundation route" in allowed and "outputs.fields = ['pressure']" in allowed


def test_hip_cup_heavier_gait_writes_the_steps_before_the_failure(tmp_path, capsys):
    """The same study with the gait forces x6 (up to 18 kN): the contact outgrows the measured
    cup (last radius 10 mm) during the first gait cycle. The run writes every step before that
    one, names it, and exits 1. The step is where Hertz's radius first passes 10 mm."""
    import json
    import shutil

    for name in ("hip_cup.toml", "hip_cup_profile.csv"):
        shutil.copy(EX / name, tmp_path / name)
    lines = (EX / "gait.csv").read_text().splitlines()
    heavy = [ln if not ln[:1].isdigit() else
             ",".join(v if j != 1 else repr(6 * float(v)) for j, v in enumerate(ln.split(",")))
             for ln in lines]
    (tmp_path / "gait.csv").write_text("\n".join(heavy) + "\n")
    scene = tmp_path / "hip_cup.toml"
    h = Scene.from_toml(scene).history()
    force = h.values("normal")
    E_star = 1 / ((1 - 0.3**2) / 210e9 + (1 - 0.4**2) / 1e9)
    a = radius_of_force(force, 0.1, E_star)
    assert np.all(np.abs(a / 10e-3 - 1) > 0.01)       # no step within 1 % of the cup's edge
    k = int(np.argmax(a > 10e-3))
    assert k == 1 + 20 + 10                            # start, preload ramp, 10 gait rows
    out = tmp_path / "out"
    assert main(["run", str(scene), "-o", str(out)]) == 1
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1
    assert (f"step {k} of {h.n_steps} failed (t = {h.time[k]:g} s, load_path[1] table, "
            f"repetition 1 of 5; steps 0-{k - 1} computed)") in err[0]
    assert "beyond the table" in err[0] and str(out / "series.csv") in err[0]
    with open(out / "series.csv") as fh:
        rows = list(csv.reader(fh))
    data = np.array(rows[1:], float)
    assert data.shape[0] == k
    loaded = data[:, 1] > 100
    np.testing.assert_allclose(data[loaded, 2], a[:k][loaded], rtol=HIP_CUP_RADIUS)
    status = json.loads((out / "status.json").read_text())
    assert status["status"] == "partial"
    assert status["failed_at"] == {"step": k, "n_steps": h.n_steps, "time": float(h.time[k]),
                                   "segment": 1, "repetition": 1}
