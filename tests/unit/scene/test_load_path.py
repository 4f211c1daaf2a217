"""The scene's typed load path: step 0 is the unloaded start, then the scene's segments; the
history is the path's own sampling, checked against the segment formulas written out here."""
from pathlib import Path

import numpy as np
import pytest

from contactlab.loadpath import Hold, Ramp, Sinusoid, Table
from contactlab.scene import Scene

from tests.unit.scene.helpers import example_params, twist_scene


_FACTORS = {"s": 1.0, "ms": 1e-3, "N": 1.0, "kN": 1e3, "rad": 1.0, "deg": np.pi / 180, "m": 1.0}


def _read_history(path):
    """A CSV history with ``name [unit]`` headers, read with numpy and a small unit table."""
    lines = [ln for ln in Path(path).read_text().splitlines() if not ln.startswith("#")]
    heads = [h.strip() for h in lines[0].split(",")]
    data = np.array([[float(v) for v in ln.split(",")] for ln in lines[1:]])
    out = {}
    for i, h in enumerate(heads):
        name, _, unit = h.partition(" [")
        out[name] = data[:, i] * _FACTORS[unit.rstrip("]") or "s"]
    return out


def expected_history(segments, base_dir=None):
    """Independent sampling of scene segments (SI dicts): ramp linear in k/n, hold constant,
    sinusoid cur + A sin(2πk/spc) with one period tiled and exact zeros at half periods; a table
    at offsets from its first row after the last step; repeat copies the segments before it."""
    expanded = []
    for seg in segments:
        if "repeat" in seg:
            k = seg["repeat"].get("last", 1)
            expanded += expanded[-k:] * (seg["repeat"]["times"] - 1)
        elif "table" in seg and "file" in seg["table"]:
            expanded.append({"table": _read_history(Path(base_dir) / seg["table"]["file"])})
        else:
            expanded.append(seg)
    segments = expanded
    kinds = sorted({k for s in segments for k in next(iter(s.values()))
                    if k in ("depth", "force", "displacement", "tangential_force", "twist",
                             "torque")})
    t, cur = [0.0], dict.fromkeys(kinds, 0.0)
    vals = {k: [0.0] for k in kinds}
    for seg in segments:
        kind, body = next(iter(seg.items()))
        if kind == "table":
            n = len(next(v for k, v in body.items() if k != "time"))
            tt = np.asarray(body.get("time", np.arange(1.0, n + 1)))
            times = t[-1] + (tt - tt[0])
            new = {k: np.asarray(body[k]) if k in body else np.full(n, cur[k]) for k in kinds}
        elif kind in ("ramp", "hold"):
            n = body["steps"]
            f = np.arange(1, n + 1) / n
            times = t[-1] + f * body.get("duration", float(n))
            new = {k: cur[k] + (body[k] - cur[k]) * f if kind == "ramp" and k in body
                   else np.full(n, cur[k]) for k in kinds}
        else:
            spc = body.get("steps_per_cycle", 100)
            n = max(1, round(body["cycles"] * spc))
            one = np.sin(2 * np.pi * np.arange(1, spc + 1) / spc)
            one[[spc // 2 - 1, spc - 1] if spc % 2 == 0 else [spc - 1]] = 0.0
            wave = np.resize(one, n)
            times = t[-1] + np.arange(1, n + 1) * body.get("period", float(spc)) / spc
            new = {k: cur[k] + body.get(k, 0.0) * wave for k in kinds}
        t.extend(times)
        for k in kinds:
            vals[k].extend(new[k])
            cur[k] = float(new[k][-1])
    return np.array(t), {k: np.array(v) for k, v in vals.items()}


@pytest.mark.parametrize("path", example_params())
def test_example_history_is_the_segment_formulas_bit_for_bit(path):
    s = Scene.from_toml(path)
    t, vals = expected_history(s.to_dict()["load_path"], path.parent)
    h = s.history()
    np.testing.assert_array_equal(h.time, t)
    for axis, (kind, v) in h.controls.items():
        np.testing.assert_array_equal(v, vals[kind], err_msg=f"{path.name}: {kind}")
    assert set(vals) == {kind for kind, _ in h.controls.values()}


def test_load_path_is_typed_and_starts_unloaded():
    s = Scene(twist_scene({"hold": {"steps": 2}}, {"sinusoid": {"twist": 1e-3, "cycles": 0.5}}))
    segs = s.load_path.segments
    assert [type(x) for x in segs] == [Table, Ramp, Hold, Sinusoid]
    assert segs[0].n_steps == 1 and segs[0].time[0] == 0.0
    assert all(np.all(v == 0.0) for _, v in segs[0].columns)
    assert s.history().n_steps == s.load_path.n_steps == 1 + 10 + 2 + 50
    assert list(np.unique(s.history().segment)) == [-1, 0, 1, 2]


def test_table_scene_keeps_its_absolute_times():
    s = Scene({"profile": {"type": "paraboloid", "R": 0.01},
               "materials": {"body1": {"type": "elastic", "E": 210e9, "nu": 0.3},
                             "body2": {"type": "elastic", "E": 210e9, "nu": 0.3}},
               "load_path": [{"table": {"time": [2.0, 3.0, 5.0], "force": [0.0, 5.0, 1.0]}}]})
    assert [type(x) for x in s.load_path.segments] == [Table]
    h = s.history()
    np.testing.assert_array_equal(h.time, [2.0, 3.0, 5.0])
    np.testing.assert_array_equal(h.values("normal"), [0.0, 5.0, 1.0])
    np.testing.assert_array_equal(h.segment, [0, 0, 0])


def test_scene_sampling_lives_in_loadpath_only():
    src = (Path(__file__).parents[3] / "contactlab" / "scene" / "model.py").read_text()
    assert "np.sin" not in src and "np.arange(1" not in src
