"""Measured load histories with units, composed with synthetic segments (issue 12). Must show:

- ``time [ms],force [kN],twist [deg]`` headers read to SI;
- a ``table`` segment composes with ramp, hold, sinusoid and repeat in Python, and the sampled
  history equals the segments laid end to end (independent concatenation);
- the same path in a scene (``table`` + ``repeat``) samples to the same history.
"""
import numpy as np

import contactlab as cl
from contactlab.scene import Scene


def gait_csv(tmp_path):
    p = tmp_path / "gait.csv"
    p.write_text("time [ms],force [kN],twist [deg]\n0,0.3,0\n250,3.0,1\n500,0.3,0\n750,1.5,-1\n")
    return p


def test_header_units(tmp_path):
    seg, = cl.LoadPath.from_csv(gait_csv(tmp_path)).segments
    np.testing.assert_allclose(seg.time, [0.0, 0.25, 0.5, 0.75], rtol=1e-15)
    cols = dict(seg.columns)
    np.testing.assert_allclose(cols["force"], [300.0, 3000.0, 300.0, 1500.0], rtol=1e-15)
    np.testing.assert_allclose(cols["twist"], np.radians([0, 1, 0, -1]), rtol=1e-15)


def test_table_composes_in_python(tmp_path):
    gait = cl.LoadPath.from_csv(gait_csv(tmp_path))
    path = (cl.LoadPath().ramp(force=300.0, steps=3, duration=0.3) + gait).repeat(3, last=1)
    path = path.hold(steps=2).sinusoid(twist=1e-3, cycles=1, steps_per_cycle=4)
    smp = path.sample()
    force = np.concatenate([[100.0, 200.0, 300.0], np.tile([300.0, 3000.0, 300.0, 1500.0], 3),
                            [1500.0] * 2, [1500.0] * 4])
    np.testing.assert_allclose(smp.values["force"], force, rtol=1e-15)
    # table times: offsets from its first row, after the previous segment's last step
    np.testing.assert_allclose(smp.time[3:7], 0.3 + np.array([0.0, 0.25, 0.5, 0.75]), rtol=1e-14)
    np.testing.assert_allclose(smp.time[7:11], 1.05 + np.array([0.0, 0.25, 0.5, 0.75]),
                               rtol=1e-14)


def test_table_composes_in_scenes(tmp_path):
    gait_csv(tmp_path)
    s = Scene({"profile": {"type": "paraboloid", "R": "20 mm"},
               "materials": {"body1": {"type": "elastic", "E": "210 GPa", "nu": 0.3},
                             "body2": {"type": "elastic", "E": "1 GPa", "nu": 0.4}},
               "interface": {"friction": 0.1},
               "load_path": [{"ramp": {"force": "300 N", "steps": 3, "duration": "0.3 s"}},
                             {"table": {"file": "gait.csv"}}, {"repeat": {"times": 3}}]},
              tmp_path)
    h = s.history()
    assert h.n_steps == 1 + 3 + 12
    np.testing.assert_allclose(h.values("normal")[4:], np.tile([300.0, 3000.0, 300.0, 1500.0], 3),
                               rtol=1e-15)
    np.testing.assert_allclose(h.values("torsion")[4:8], np.radians([0, 1, 0, -1]), rtol=1e-15)
