"""The [wear] and [fretting_map] scene tables: validation (units, every issue at once,
did-you-mean), the plan rows, the run and its outputs."""
import pickle

import numpy as np
import pytest

from contactlab.errors import SceneError, ValidityWarning
from contactlab.scene import Scene
from contactlab.scene.run import MANIFEST

from tests import tolerances as TOL
from tests.unit.scene.helpers import base, twist_scene

WEAR = {"wear_coefficient": "1e-6 mm^3/(N*m)", "cycles": 1e4, "n_grid": 160}
MAP = {"force": ["10 N", "100 N"], "twist_amplitude": {"from": "0.1 mrad", "to": "20 mrad",
                                                       "points": 4, "spacing": "log"}}


def wear_scene(**wear):
    return twist_scene(wear={**WEAR, **wear})


def issues(data):
    with pytest.raises(SceneError) as e:
        Scene(data)
    return {p: (v, a) for p, v, a in e.value.issues}


def test_units_of_the_wear_coefficient():
    for k in ("1e-6 mm^3/(N*m)", "1e-6 mm^3/(N m)", "1e-15 1/Pa", "1e-6 1/GPa", 1e-15):
        s = Scene(wear_scene(wear_coefficient=k))
        assert s.to_dict()["wear"]["wear_coefficient"] == pytest.approx(1e-15, rel=TOL.ULPS)
    got = issues(wear_scene(wear_coefficient="1e-6 mm"))
    assert "mm^3/(N*m)" in got["wear.wear_coefficient"][1]


def test_every_wear_issue_is_collected_with_did_you_mean():
    d = twist_scene(friction=None, wear={"wear_coeficient": 1e-15, "n_grid": 3,
                                         "method": "exakt", "checkpoints": [0, 5]})
    got = issues(d)
    assert "did you mean 'wear_coefficient'" in got["wear.wear_coeficient"][1]
    assert "required" in got["wear.wear_coefficient"][1] and "required" in got["wear.cycles"][1]
    assert "did you mean 'exact'" in got["wear.method"][1]
    assert "16..20000" in got["wear.n_grid"][1]
    assert "> 0" in got["wear.checkpoints"][1]
    assert "friction" in got["interface.friction"][1]


def test_wear_needs_a_fretting_segment_at_constant_force():
    got = issues(base(interface={"friction": 0.3}, wear=WEAR))
    assert "sinusoid of twist or displacement" in got["wear"][1]
    d = twist_scene({"sinusoid": {"twist": "1 mrad", "force": "10 N", "cycles": 1}}, wear=WEAR)
    assert "constant normal force" in issues(d)["load_path[1].sinusoid.force"][1]
    d = twist_scene(wear=WEAR)
    d["load_path"][0] = {"ramp": {"depth": "1 um", "steps": 5}}
    assert "force-controlled" in issues(d)["load_path"][1]
    d = twist_scene(wear=WEAR)
    d["profile"] = {"type": "flat_punch", "radius": "1 mm"}
    assert "truncated_paraboloid" in issues(d)["profile.type"][1]
    d = twist_scene(wear={**WEAR, "cycles": 10, "checkpoints": [5, 50]})
    assert "<= wear.cycles" in issues(d)["wear.checkpoints"][1]


def test_wear_force_after_repeated_segments():
    """The fretting force is read at the fretting segment's own steps, not at the step block of
    the same index (History.segment counts leaves: a repeat before the fretting segment shifts
    them): 100 N, then 200 N, both ramps repeated, then the twist at 200 N."""
    d = base(interface={"friction": 0.3}, wear=WEAR)
    d["load_path"] = [{"ramp": {"force": "100 N", "steps": 10}},
                      {"ramp": {"force": "200 N", "steps": 5}},
                      {"repeat": {"times": 2, "last": 2}},
                      {"sinusoid": {"twist": "1 mrad", "cycles": 1, "steps_per_cycle": 20}}]
    p = Scene(d).plan()
    assert p.details["wear"]["kwargs"]["force"] == 200.0
    assert p.details["wear"]["segment"] == 3


def test_every_map_issue_is_collected():
    d = twist_scene(fretting_map={"force": {"from": "1 kN", "to": "10 N", "points": 3},
                                  "twist_amplitude": ["1 mrad"], "displacement_amplitude": [1e-6],
                                  "criterion": "energy_ration", "threshold": 2})
    got = issues(d)
    assert ">= from" in got["fretting_map.force.to"][1]
    assert "exactly one of twist_amplitude" in got["fretting_map"][1]
    assert "did you mean 'energy_ratio'" in got["fretting_map.criterion"][1]
    assert "0 < threshold < 1" in got["fretting_map.threshold"][1]
    d = twist_scene(fretting_map={"force": {"from": 0, "to": "1 N", "points": 3,
                                            "spacing": "log"},
                                  "displacement_amplitude": ["1 um"], "criterion": "stick_ratio",
                                  "frce": 1})
    got = issues(d)
    assert "> 0 with spacing = 'log'" in got["fretting_map.force.from"][1]
    assert "no criterion for a tangential map" in got["fretting_map.criterion"][1]
    assert "did you mean 'force'" in got["fretting_map.frce"][1]


def test_round_trip_and_plan_rows():
    s = Scene(twist_scene(wear=WEAR, fretting_map=MAP))
    assert Scene.from_dict(s.to_dict()) == s
    plan = s.plan()
    assert plan.calls[-2:] == ("wear", "fretting_map")
    w, m = plan["wear"], plan["fretting_map"]
    assert "contact.wear(force=100 N, twist_amplitude=0.002 rad" in w.implementation
    assert "method='exact'" in w.implementation and "load_path[1]" in w.reason
    assert "Jäger" in w.reason
    assert "force=<2 values>, twist_amplitude=<4 values>" in m.implementation
    assert "energy_ratio (threshold 0.2)" in m.reason
    d = plan.to_dict()
    assert [e["effect"] for e in d["effects"]][-2:] == ["wear", "fretting_map"]
    mdr = Scene(twist_scene(wear={**WEAR, "method": "mdr"})).plan()["wear"]
    assert "MDR springs" in mdr.reason and "method='mdr'" in mdr.implementation


def test_only_planned_tables_run():
    res = Scene(twist_scene()).run()
    assert res.wear is None and res.fretting_map is None
    assert "wear" not in res.meta["computed"]


def test_run_is_deterministic_and_pickles():
    s = Scene(twist_scene(wear={**WEAR, "checkpoints": 2}, fretting_map=MAP))
    a, b = s.run(), Scene(s.to_dict()).run()
    assert a == b
    assert pickle.loads(pickle.dumps(a)) == a
    assert a.meta["computed"][-2:] == ["wear", "fretting_map"]
    assert a.fretting_map.regime.shape == (2, 4)
    np.testing.assert_allclose(a.fretting_map.force, [10.0, 100.0], rtol=0)


def test_tangential_wear_scene(tmp_path):
    d = twist_scene({"sinusoid": {"displacement": "2 um", "cycles": 1}}, friction=0.5,
                    wear={**WEAR, "wear_coefficient": "1e-13 1/Pa", "cycles": 1e5})
    # c/a = 0.23: the small stick zone stands proud with a steep edge and the worn profile
    # leaves the MDR on its way to the limiting state (docs/fretting.md section 6); wear() says so
    with pytest.warns(ValidityWarning, match="left the MDR"):
        res = Scene(d).run()
    w = res.wear
    assert 1e4 < w.meta["mdr_valid_cycles"] < 1e5
    assert w.mode == "tangential"
    assert "Abel transform" in res.plan["wear"].reason
    np.testing.assert_allclose(w.volume, 1e-13 / 0.5 * w.dissipated_energy,
                               rtol=TOL.WEAR_ENERGY_IDENTITY, atol=0)
    files = sorted(p.name for p in res.write(tmp_path))
    assert files == ["series.csv", "wear.csv", "wear_profiles.csv", "worn_profile.csv"]
    lines = (tmp_path / "wear.csv").read_text().splitlines()
    # the warning and the unbounded model error lead the file as metadata lines (issue 26)
    assert lines[0].startswith("# notes: wear(): after") and "left the MDR" in lines[0]
    assert "# model_error: inf" in lines
    head = next(line for line in lines if not line.startswith("#"))
    assert head.startswith("cycles [1],depth [m],radius [m]")
    # a later run without wear removes the stale wear files (when asked to replace them)
    Scene(twist_scene()).run().write(tmp_path, overwrite=True)
    assert sorted(p.name for p in tmp_path.iterdir()) == [MANIFEST, "series.csv"]
    assert "wear (tangential, mdr) after 100000 cycles" in res.table()


def test_wear_integrator_key():
    """[wear] integrator = "implicit" runs the Rosenbrock-W route (issue 28); the plan names it,
    the run equals the direct call, and a misspelt name is caught with a suggestion."""
    s = Scene(wear_scene(integrator="implicit", cycles=1e3))
    assert Scene.from_dict(s.to_dict()) == s
    row = s.plan()["wear"]
    assert "integrator='implicit'" in row.implementation and "Rosenbrock-W" in row.reason
    assert "Heun" in Scene(wear_scene(cycles=1e3)).plan()["wear"].reason
    w = s.run().wear
    assert w.meta["integrator"] == "implicit"
    kw = s.plan().details["wear"]["kwargs"]
    assert kw["integrator"] == "implicit"
    direct = s.contact().wear(**kw)
    np.testing.assert_array_equal(w.volume, direct.volume)
    assert w.meta["steps"] == direct.meta["steps"]
    got = issues(wear_scene(integrator="implict"))
    assert "did you mean 'implicit'" in got["wear.integrator"][1]
