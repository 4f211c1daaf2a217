"""One point: scene overrides by key path, outputs as scalars, errors and warnings recorded."""
from __future__ import annotations

import math
import pickle
import warnings

import numpy as np
import pytest

from contactlab.errors import ParameterError, ValidityWarning
from contactlab.scene import Scene
from contactlab.sweeps import SceneStudy, scalars
from contactlab.sweeps.study import Points, Records, evaluate, run_batch, study_id

from tests.reference.hertz import effective_modulus, radius_of_force
from tests.tolerances import CLOSED_FORM
from tests.unit.scene.helpers import base, twist_scene


def test_scalars_of_a_mapping():
    out = scalars({"torque": np.array([0.0, 2.0, 1.0]), "mu": np.float32(0.5), "n": 3,
                   "ok": True, "label": "exact", "missing": None, "one": [4.0]})
    assert out == {"torque": 1.0, "torque_min": 0.0, "torque_max": 2.0, "mu": 0.5, "n": 3.0,
                   "ok": 1.0, "label": "exact", "missing": out["missing"], "one": 4.0}
    assert math.isnan(out["missing"]) and all(type(v) in (float, str) for v in out.values())


@pytest.mark.parametrize("result, match", [({"x": object()}, "'x'=.* is invalid"),
                                           ({"x": ["a", "b"]}, "'x' is not an array"),
                                           (3.0, "result of type float")])
def test_scalars_rejects_what_is_not_a_number(result, match):
    with pytest.raises(ParameterError, match=match):
        scalars(result)


def test_scene_study_writes_values_by_key_path_hertz():
    """The swept preload reaches the contact: the final radius is Hertz's a(F)."""
    study = SceneStudy(base())
    E_star = effective_modulus(210e9, 0.3, 210e9, 0.3)
    for F in (10.0, 250.0):
        out = study(**{"load_path[0].ramp.force": F})
        assert out["force"] == pytest.approx(F, rel=CLOSED_FORM)
        assert out["radius"] == pytest.approx(float(radius_of_force(F, 0.01, E_star)),
                                              rel=CLOSED_FORM)
    assert study(**{"load_path[0].ramp.force": "50 N"})["force"] == pytest.approx(50.0, rel=CLOSED_FORM)


def test_scene_study_pickles_and_leaves_its_scene_alone():
    study = SceneStudy(Scene(twist_scene()))
    again = pickle.loads(pickle.dumps(study))
    point = {"interface.friction": 0.3}
    assert again(**point) == study(**point)
    assert study.data == Scene(twist_scene()).to_dict()
    assert study_id(again) == study_id(study) != study_id(SceneStudy(Scene(base())))


def test_scene_study_from_file_keeps_its_folder(tmp_path):
    (tmp_path / "s.toml").write_text(Scene(base()).to_toml())
    study = SceneStudy(tmp_path / "s.toml")
    assert study.base_dir == str(tmp_path.resolve())


@pytest.mark.parametrize("key, match", [
    ("interface.fricton", "grid key 'interface.fricton' is not a scene key.*did you mean 'friction'"),
    ("load_path[1].sinusoid.twst", "did you mean 'twist'"),
    ("load_path[7].ramp.force", "load_path has 2 entries"),
])
def test_check_rejects_keys_that_never_fit(key, match):
    with pytest.raises(ParameterError, match=match):
        SceneStudy(twist_scene()).check({key: 0.1})


def test_check_lets_invalid_values_through():
    SceneStudy(twist_scene()).check({"interface.friction": -0.1})     # recorded per point later


def test_study_that_is_no_study():
    with pytest.raises(ParameterError, match="study=42 is invalid"):
        SceneStudy(42)


def _warns_twice(x):
    for _ in range(2):
        warnings.warn("outside", ValidityWarning)
    warnings.warn("other", UserWarning)
    return {"y": 2 * x}


def _fails(x):
    raise ParameterError(f"x={x} is invalid: must be > 0.")


def test_evaluate_records_outputs_errors_and_each_warning_once():
    ok = evaluate(_warns_twice, 3, {"x": 1.5})
    assert ok["point"] == 3 and ok["outputs"] == {"y": 3.0} and ok["error"] is None
    assert ok["warnings"] == "ValidityWarning: outside\nUserWarning: other"
    # the same again: warnings are recorded per point, not once per process
    assert evaluate(_warns_twice, 4, {"x": 1.5})["warnings"] == ok["warnings"]
    bad = evaluate(_fails, 0, {"x": -1})
    assert bad["outputs"] == {} and bad["error"] == "ParameterError"
    assert bad["message"] == "x=-1 is invalid: must be > 0." and bad["warnings"] is None


def test_evaluate_lets_keyboard_interrupt_through():
    def stop(x):
        raise KeyboardInterrupt
    with pytest.raises(KeyboardInterrupt):
        evaluate(stop, 0, {"x": 1})


def _outside_scene(tmp_path):
    """A scene in tmp/a/ whose tabulated profile is ../lens.csv (outside its folder)."""
    r = np.linspace(0.0, 2e-3, 41)
    (tmp_path / "lens.csv").write_text("r,f\n" + "\n".join(f"{float(x)!r},{float(x * x / 0.02)!r}"
                                                          for x in r) + "\n")
    d = tmp_path / "a"
    d.mkdir()
    data = base()
    data["profile"] = {"type": "tabulated", "file": "../lens.csv"}
    text = Scene(base()).to_toml().replace('type = "paraboloid"', 'type = "tabulated"')
    text = text.replace('R = 0.01', 'file = "../lens.csv"')
    (d / "s.toml").write_text(text)
    return d / "s.toml", data, d


def test_allow_outside_passes_through_like_the_cli(tmp_path):
    """sweep(..., allow_outside=True) reads a file outside the scene's folder at every point,
    as `contactlab run --allow-outside` does; without it the scene is refused, as the CLI does."""
    import contactlab as cl
    from contactlab.cli import main
    from contactlab.errors import SceneError
    path, data, folder = _outside_scene(tmp_path)
    assert main(["validate", str(path)]) == 2
    assert main(["validate", str(path), "--allow-outside"]) == 0
    with pytest.raises(SceneError, match="inside the scene's folder"):
        SceneStudy(path)
    grid = {"load_path[0].ramp.force": [10.0, 20.0]}
    (folder / "inside.csv").write_text((tmp_path / "lens.csv").read_text())
    (folder / "inside.toml").write_text(path.read_text().replace("../lens.csv", "inside.csv"))
    inside = cl.sweep(folder / "inside.toml", grid, workers=1, progress=False)
    assert inside["error"].isna().all() and inside["radius"].gt(0).all()
    for study in (path, Scene.from_toml(path, allow_outside=True), data):
        kw = {} if isinstance(study, Scene) else {"allow_outside": True}
        if isinstance(study, dict):
            study = SceneStudy(study, folder, allow_outside=True)
            kw = {}
        table = cl.sweep(study, grid, workers=1, progress=False, **kw)
        assert table["error"].isna().all(), table["message"].tolist()
        assert table["radius"].tolist() == inside["radius"].tolist()
    study = SceneStudy(Scene.from_toml(path, allow_outside=True))
    assert study.allow_outside and pickle.loads(pickle.dumps(study)).allow_outside
    with pytest.raises(SceneError, match="inside the scene's folder"):
        SceneStudy(Scene.from_toml(path, allow_outside=True), allow_outside=False)
    with pytest.raises(ParameterError, match="disagrees"):
        cl.sweep(study, grid, workers=1, progress=False, allow_outside=False)
    with pytest.raises(ParameterError, match="scene studies"):
        cl.sweep(lambda x: {"x": x}, {"x": [1.0]}, workers=1, progress=False, allow_outside=True)
    with pytest.raises(ParameterError, match="allow_outside='yes'"):
        SceneStudy(path, allow_outside="yes")


def test_cli_sweep_allow_outside(tmp_path, capsys):
    pytest.importorskip("pandas")
    from contactlab.cli import main
    path, _, _ = _outside_scene(tmp_path)
    argv = ["sweep", str(path), "--grid", "load_path[0].ramp.force=10,20", "--workers", "1",
            "--json"]
    assert main(argv) == 2
    capsys.readouterr()
    assert main(argv + ["--allow-outside"]) == 0
    out = capsys.readouterr().out
    assert '"ok": true' in out


# ---- batches: columns out, columns back --------------------------------------------------------
def _silences_then_warns(x):
    if x == 1.0:
        warnings.simplefilter("ignore")          # a study that changes the filters for good
    warnings.warn("outside", ValidityWarning)
    return {"y": 2 * x} if x != 2.0 else {"z": x, "y": 1.0}


def test_a_batch_records_each_points_own_warnings_like_single_points():
    batch = Points.of([{"x": float(x)} for x in range(4)], [0, 1, 2, 3], ("x",))
    rec = run_batch(_silences_then_warns, batch)
    alone = [evaluate(_silences_then_warns, i, p) for i, p in batch]
    assert rec.rows() == _untimed(alone)
    w = "ValidityWarning: outside"
    assert rec.warnings == [w, None, w, w]        # point 1 silenced itself, not the next ones
    # a point that did not return a name has None in that column
    assert rec.outputs == {"y": [0.0, 2.0, 1.0, 6.0], "z": [None, None, 2.0, None]}


def test_points_and_records_pickle_as_columns():
    pts = Points.of([{"a": 1, "b": "x"}, {"a": 2, "b": "y"}, {"a": 3, "b": "z"}], [2, 0], ("a", "b"))
    assert list(pts) == [(2, {"a": 3, "b": "z"}), (0, {"a": 1, "b": "x"})]
    back = pickle.loads(pickle.dumps(pts))
    assert list(back) == list(pts) and back.columns == [[3, 1], ["z", "x"]]
    rec = run_batch(_fails, Points([5], ("x",), [[-1]]))
    rec.extend(run_batch(_warns_twice, Points([7], ("x",), [[1.5]])))
    assert rec.outputs == {"y": [None, 3.0]} and rec.error == ["ParameterError", None]
    again = pickle.loads(pickle.dumps(rec))
    assert again.rows() == rec.rows()
    assert Records.from_rows(rec.rows()).rows() == rec.rows()


def _untimed(rows):
    return [{k: v for k, v in r.items() if k != "seconds"} for r in rows]


def _double(x):
    return {"y": 2 * x}


def test_columns_travel_compactly_and_come_back_exactly():
    floats = [0.1, -0.0, float("nan"), float("inf"), 1e-310, 2.0 / 3.0]
    ints_then_floats = [1, 2.5, 3, 4.0, 5, 6.0]
    pts = Points(list(range(10, 16)), ("a", "b", "c"),
                 [floats, ints_then_floats, ["x", None, "y", "z", "w", "v"]])
    back = pickle.loads(pickle.dumps(pts))
    assert back.index == pts.index
    for mine, theirs in zip(pts.columns, back.columns):
        assert [type(v) for v in theirs] == [type(v) for v in mine]
        assert [repr(v) for v in theirs] == [repr(v) for v in mine]
    assert np.array(back.columns[0]).tobytes() == np.array(floats).tobytes()   # bit for bit
    scattered = Points([3, 1, 7], ("a",), [[1.0, 2.0, 3.0]])
    assert pickle.loads(pickle.dumps(scattered)).index == [3, 1, 7]
    rec = run_batch(_warns_twice, Points(list(range(5)), ("x",), [[0.5, 1.0, 1.5, 2.0, 2.5]]))
    again = pickle.loads(pickle.dumps(rec))
    assert again.rows() == rec.rows() and again.error == [None] * 5
    assert [type(v) for v in again.outputs["y"]] == [float] * 5
    big = run_batch(_double, Points(list(range(3000)), ("x",), [[1.5] * 3000]))
    # y as float64 (8 bytes a value), the indices as a range, no error: one marker, no times
    assert len(pickle.dumps(big)) < 3000 * 8 + 1000


_MIXED = [{"a": 1.0, "b": 2.0},                      # first point: converted, columns made
          {"a": 3.0, "b": 4.0},                      # same names, floats: straight in
          {"b": 6.0, "a": 5.0},                      # same names, another order
          {"a": 7.0, "b": np.float64(8.0)},          # a numpy float after a float: converted
          {"a": 9.0, "b": None},                     # None is NaN, not "not returned"
          {"a": 10.0, "b": 3},                       # an int
          {"a": 11.0, "b": np.array([1.0, 2.0])},    # an array: final value, _min, _max
          {"a": 12.0, "b": object()},                # an invalid output: a recorded error
          {"a": 13.0, "b": 14.0},
          {"a": 15.0},                               # a name missing
          {"a": 16.0, "b": 17.0, "c": "text"}]       # a new name


def _mixed(x):
    return _MIXED[int(x)]


def test_a_batch_converts_every_point_as_a_single_point_would():
    """The batch loop's shortcut for floats under known names agrees, point for point and
    column for column, with each point evaluated alone (which always converts)."""
    n = len(_MIXED)
    rec = run_batch(_mixed, Points(list(range(n)), ("x",), [[float(i) for i in range(n)]]))
    alone = [evaluate(_mixed, i, {"x": float(i)}) for i in range(n)]
    got = rec.rows()
    for mine, ref in zip(got, _untimed(alone)):
        assert mine["point"] == ref["point"] and mine["error"] == ref["error"]
        assert mine["outputs"].keys() == ref["outputs"].keys(), mine["point"]
        for k, v in ref["outputs"].items():
            assert repr(mine["outputs"][k]) == repr(v) and type(mine["outputs"][k]) is type(v)
    assert list(rec.outputs) == ["a", "b", "b_min", "b_max", "c"]
    assert rec.error[7] == "ParameterError" and rec.outputs["a"][7] is None
    assert math.isnan(rec.outputs["b"][4]) and rec.outputs["b"][9] is None
    assert all(len(col) == n for col in rec.outputs.values())


class _Stop:
    """Returns floats, raises KeyboardInterrupt at point ``at``."""

    def __init__(self, at):
        self.at = at

    def __call__(self, x):
        if x == self.at:
            raise KeyboardInterrupt
        return {"y": 2 * x}


def test_an_interrupted_batch_keeps_the_points_before_the_interrupt():
    out = Records()
    with pytest.raises(KeyboardInterrupt):
        run_batch(_Stop(3.0), Points(list(range(10, 16)), ("x",), [[0.0, 1.0, 2.0, 3.0, 4.0, 5.0]]),
                  out)
    assert out.point == [10, 11, 12] and out.outputs == {"y": [0.0, 2.0, 4.0]}
    assert out.error == out.message == out.warnings == [None] * 3


def _ordered(b, a, c=10.0):
    return {"v": 100 * a + b + c}


def _kwonly(*, a, b):
    return {"v": 100 * a + b}


def _posonly(a, b, /):
    return {"v": 100 * a + b}


def test_plain_functions_are_called_positionally_with_the_same_binding():
    """``study(*values)`` in parameter order binds as ``study(**point)`` does; anything that is
    not a plain function taking the grid names as its leading parameters is called by keyword."""
    from contactlab.sweeps.study import _leading
    assert _leading(_ordered, ("a", "b")) == [1, 0]
    assert _leading(_ordered, ("a", "c")) is None            # c is not a leading parameter
    assert _leading(_kwonly, ("a", "b")) is None
    assert _leading(_posonly, ("a", "b")) is None
    assert _leading(lambda **kw: kw, ("a",)) is None
    pts = Points(list(range(3)), ("a", "b"), [[1.0, 2.0, 3.0], [0.5, 0.25, 0.125]])
    for fn in (_ordered, _kwonly):
        assert run_batch(fn, pts).outputs["v"] == [fn(**p)["v"] for _, p in pts]
    assert run_batch(_posonly, pts).error == ["TypeError"] * 3   # by keyword, as documented
