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
