"""contactlab.sweep in this process: tables, recorded failures, checkpoints and resumption."""
from __future__ import annotations

import math

import numpy as np
import pytest

pd = pytest.importorskip("pandas")

import contactlab
from contactlab.errors import ParameterError, SceneError
from contactlab.scene import Scene
from contactlab.sweeps import read_store, to_dataset

from tests.tolerances import TORSION_EXACT
from tests.unit.scene.helpers import twist_scene

MONOTONE = twist_scene({"ramp": {"twist": "2 mrad", "steps": 8}},
                       outputs={"method": "exact", "series": ["twist", "torque", "stick_radius"]})


def product(x, y):
    return {"sum": x + y, "prod": x * y}


def test_function_study_table():
    t = contactlab.sweep(product, {"x": [1.0, 2.0], "y": [10.0, 20.0, 30.0]}, workers=1)
    assert list(t.columns) == ["point", "x", "y", "sum", "prod", "error", "message", "warnings"]
    assert t["point"].tolist() == list(range(6))
    assert t["x"].tolist() == [1.0] * 3 + [2.0] * 3 and t["y"].tolist() == [10.0, 20.0, 30.0] * 2
    assert t["sum"].tolist() == [11.0, 21.0, 31.0, 12.0, 22.0, 32.0]
    assert t["error"].tolist() == [None] * 6
    assert t.attrs["sweep"]["stats"]["computed"] == 6


def test_scene_rows_follow_lubkins_scaling():
    """Jäger/Lubkin: the twist scales with mu (phi ~ mu F/(G a^2) [K-E]), so torque/mu depends on
    twist/mu only; rows with the same twist/mu give the same torque/mu."""
    rows = [{"interface.friction": mu, "load_path[1].ramp.twist": 0.01 * mu}
            for mu in (0.1, 0.2, 0.4)]
    t = contactlab.sweep(Scene(MONOTONE), rows, workers=1)
    ratio = (t["torque"] / t["interface.friction"]).to_numpy()
    assert t["error"].isna().all()
    np.testing.assert_allclose(ratio, ratio[0], rtol=TORSION_EXACT)
    np.testing.assert_allclose(t["stick_radius"], t["stick_radius"][0], rtol=TORSION_EXACT)


def test_invalid_points_are_recorded_and_the_rest_computed():
    grid = {"interface.friction": [-0.2, 0.1, -0.05, 0.3], "load_path[1].ramp.twist": [1e-3, 2e-3]}
    t = contactlab.sweep(Scene(MONOTONE), grid, workers=1)
    bad = t["interface.friction"] < 0
    assert len(t) == 8 and bad.sum() == 4
    assert t.loc[bad, "error"].tolist() == ["SceneError"] * 4
    assert all("interface.friction" in m for m in t.loc[bad, "message"])
    assert t.loc[bad, "torque"].isna().all()
    assert t.loc[~bad, "error"].isna().all() and (t.loc[~bad, "torque"] > 0).all()


def test_on_error_raise_raises_the_points_own_exception():
    with pytest.raises(SceneError, match="interface.friction"):
        contactlab.sweep(Scene(MONOTONE), {"interface.friction": [0.1, -0.2, 0.3]}, workers=1,
                         on_error="raise")


@pytest.mark.parametrize("kw, match", [
    ({"workers": 0}, "workers=0 is invalid"), ({"workers": 1.5}, "workers=1.5"),
    ({"workers": 2, "client": object()}, "give one"), ({"on_error": "skip"}, "on_error='skip'"),
    ({"batch_size": 0}, "batch_size=0"),
])
def test_bad_arguments(kw, match):
    with pytest.raises(ParameterError, match=match):
        contactlab.sweep(product, {"x": [1.0], "y": [2.0]}, **kw)


def test_a_grid_key_the_scene_lacks_fails_before_running():
    with pytest.raises(ParameterError, match="did you mean 'friction'"):
        contactlab.sweep(Scene(MONOTONE), {"interface.fricton": [0.1, 0.2]}, workers=1)


def echo(x):
    return {"x": 2 * x, "error": 1.0}


def test_outputs_named_like_columns_are_prefixed():
    t = contactlab.sweep(echo, {"x": [1.0, 2.0]}, workers=1)
    assert t["output.x"].tolist() == [2.0, 4.0] and t["output.error"].tolist() == [1.0, 1.0]


def test_full_grid_as_dataset():
    pytest.importorskip("xarray")
    t = contactlab.sweep(product, {"x": [3.0, 1.0], "y": [10.0, 20.0, 30.0]}, workers=1)
    ds = to_dataset(t)
    assert ds["sum"].dims == ("x", "y") and ds["x"].values.tolist() == [3.0, 1.0]
    assert ds["sum"].sel(x=1.0, y=20.0).item() == 21.0
    rows = contactlab.sweep(product, [{"x": 1.0, "y": 2.0}], workers=1)
    with pytest.raises(ParameterError, match="not a full grid"):
        to_dataset(rows)


# ---- checkpoints --------------------------------------------------------------------------------
CALLS: list[float] = []
STOP_AT: list[float] = []


def counted(x, y):
    """Records its calls; raises KeyboardInterrupt (an interrupted sweep) at x in STOP_AT."""
    if x in STOP_AT:
        raise KeyboardInterrupt
    CALLS.append(x)
    return {"v": x * y, "w": np.sin(x) if x != 5.0 else np.array([1.0, 3.0])}


@pytest.fixture
def calls():
    CALLS.clear()
    STOP_AT.clear()
    yield CALLS
    CALLS.clear()
    STOP_AT.clear()


def test_interrupted_sweep_resumes_computing_only_the_rest(tmp_path, calls, monkeypatch):
    pytest.importorskip("pyarrow")
    monkeypatch.setattr("contactlab.sweeps.store.FLUSH_SECONDS", 0.0)     # flush every batch
    grid = {"x": [float(i) for i in range(10)], "y": [1.0, -1.0]}
    full = contactlab.sweep(counted, grid, workers=1)
    calls.clear()
    store = tmp_path / "study.parquet"
    STOP_AT.append(5.0)                      # x = 5 is points 10 and 11: half the sweep
    with pytest.raises(KeyboardInterrupt):
        contactlab.sweep(counted, grid, workers=1, store=store)
    assert sorted(set(calls)) == [0.0, 1.0, 2.0, 3.0, 4.0]
    assert read_store(store)["point"].tolist() == list(range(10))
    calls.clear()
    STOP_AT.clear()
    resumed = contactlab.sweep(counted, grid, workers=1, store=store)
    assert sorted(calls) == sorted([x for x in grid["x"] if x >= 5.0] * 2)
    assert resumed.attrs["sweep"]["stats"]["resumed"] == 10
    pd.testing.assert_frame_equal(resumed, full, check_exact=True)
    assert len(list(store.glob("part-*.parquet"))) == 1            # compacted when finished
    calls.clear()
    again = contactlab.sweep(counted, grid, workers=1, store=store)   # nothing left to do
    assert calls == [] and again.equals(full)


def test_a_store_of_another_sweep_is_refused(tmp_path):
    pytest.importorskip("pyarrow")
    store = tmp_path / "s.parquet"
    contactlab.sweep(product, {"x": [1.0], "y": [2.0]}, workers=1, store=store)
    with pytest.raises(ParameterError, match="holds another sweep.*grid"):
        contactlab.sweep(product, {"x": [1.0], "y": [3.0]}, workers=1, store=store)
    with pytest.raises(ParameterError, match="holds another sweep.*study"):
        contactlab.sweep(echo, {"x": [1.0], "y": [2.0]}, workers=1, store=store)
    (tmp_path / "f").write_text("")
    with pytest.raises(ParameterError, match="is a file"):
        contactlab.sweep(product, {"x": [1.0], "y": [2.0]}, workers=1, store=tmp_path / "f")


def test_failed_points_are_stored_and_not_recomputed(tmp_path, calls):
    pytest.importorskip("pyarrow")
    grid = {"interface.friction": [-0.1, 0.2], "load_path[1].ramp.twist": [1e-3]}
    store = tmp_path / "s.parquet"
    first = contactlab.sweep(Scene(MONOTONE), grid, workers=1, store=store)
    again = contactlab.sweep(Scene(MONOTONE), grid, workers=1, store=store)
    assert again.attrs["sweep"]["stats"]["computed"] == 0
    pd.testing.assert_frame_equal(again, first, check_exact=True)
    assert again["error"].tolist() == ["SceneError", None]
    assert math.isnan(again["torque"][0])


def _study_sum(x, y):
    return {"s": x + y}


def test_sweep_stops_on_its_time_estimate_and_resumes_with_a_larger_budget(tmp_path):
    """The cost of a point is the user's function: timed on the first points, extrapolated over
    the rest and the workers, refused before running on when over the budget; the timed points
    stay in the store and a run with a larger budget resumes from them (issue 26 item 6)."""
    pytest.importorskip("pyarrow")
    from contactlab.errors import TimeBudgetError
    grid = {"x": [float(i) for i in range(40)], "y": [1.0, -1.0]}
    store = tmp_path / "study.parquet"
    previous = contactlab.set_time_budget(1e-9)
    try:
        with pytest.raises(TimeBudgetError, match=r"sweep\(\) would run for about .*points left "
                                                  r"x .* per point measured on the first \d+, "
                                                  r"over 1 worker; the \d+ points done are "
                                                  r"kept in the store .*resume") as err:
            contactlab.sweep(_study_sum, grid, workers=1, store=store, progress=False)
        done = read_store(store)["point"].tolist()
        assert 0 < len(done) < 80 and f"the {len(done)} points done" in str(err.value)
        with pytest.raises(TimeBudgetError, match=r"not kept \(no store\)"):
            contactlab.sweep(_study_sum, grid, workers=1, progress=False)
        contactlab.set_time_budget("1h")
        table = contactlab.sweep(_study_sum, grid, workers=1, store=store, progress=False)
    finally:
        contactlab.set_time_budget(previous)
    assert table.attrs["sweep"]["stats"]["resumed"] == len(done)
    assert table["s"].tolist() == [x + y for x in grid["x"] for y in grid["y"]]
