"""``[solver] torque_rtol``: the scene key of ``Contact.simulate(path, torque_rtol=...)`` (issue 28).

The key chooses the rings of the exact ring solver from a torque accuracy, in the range of the
measured error law (``foundation.rings.RTOL_RANGE``); a scene refuses it together with ``n_rings``,
as ``simulate`` does, and otherwise gives the same numbers as the Python call.
"""
import numpy as np
import pytest

from contactlab import Contact
from contactlab.errors import ParameterError, SceneError
from contactlab.foundation.rings import RTOL_RANGE
from contactlab.scene import Scene
from contactlab.scene.cost import default_ladders, with_setting

from tests.unit.scene.helpers import twist_scene

#: twist while the normal force changes: the plan runs the exact ring solver
SEG = {"sinusoid": {"twist": "1 mrad", "force": "50 N", "cycles": 1, "steps_per_cycle": 12}}


def issues(data):
    with pytest.raises(SceneError) as e:
        Scene(data)
    return e.value.issues


def test_scene_torque_rtol_gives_the_python_call():
    s = Scene(twist_scene(SEG, solver={"torque_rtol": 0.05}))
    res = s.run()
    assert res.meta["computed"] == ["simulate"]
    ref = s.contact().simulate(s.load_path, method="exact", torque_rtol=0.05)
    # the same call: bit-identical (same rings, same steps)
    np.testing.assert_array_equal(res["torque"], ref.torque)
    np.testing.assert_array_equal(res["dissipated_energy"], ref.dissipated_energy)
    # and not the default rings' result (the key is read, not dropped)
    dflt = s.contact().simulate(s.load_path, method="exact")
    assert ref.meta["n_rings"] != dflt.meta["n_rings"]
    assert not np.array_equal(res["torque"], dflt.torque)


def test_scene_torque_rtol_is_passed_to_simulate(monkeypatch):
    seen = {}
    real = Contact.simulate

    def simulate(self, path, **kw):
        seen.update(kw)
        return real(self, path, **kw)
    monkeypatch.setattr(Contact, "simulate", simulate)
    Scene(twist_scene(SEG, solver={"torque_rtol": "0.1"})).run()
    assert seen == {"method": "exact", "torque_rtol": 0.1}


@pytest.mark.parametrize("value", [0.5, 0.1000001, 9.9e-5, 1e-6])
def test_torque_rtol_outside_the_measured_range(value):
    (path, got, allowed), = issues(twist_scene(SEG, solver={"torque_rtol": value}))
    assert path == "solver.torque_rtol" and got == value
    assert f"{RTOL_RANGE[0]:g} <= torque_rtol <= {RTOL_RANGE[1]:g}" in allowed


@pytest.mark.parametrize("value", [RTOL_RANGE[0], RTOL_RANGE[1]])
def test_torque_rtol_range_is_inclusive(value):
    assert Scene(twist_scene(SEG, solver={"torque_rtol": value})).solver["torque_rtol"] == value


@pytest.mark.parametrize("value", [0.0, -1e-3, "abc", True, [1e-3]])
def test_torque_rtol_not_a_positive_number(value):
    got = issues(twist_scene(SEG, solver={"torque_rtol": value}))
    assert [p for p, _, _ in got] == ["solver.torque_rtol"]


def test_torque_rtol_and_n_rings_are_refused_together():
    (path, got, allowed), = issues(twist_scene(SEG, solver={"torque_rtol": 1e-3,
                                                            "n_rings": 100}))
    assert path == "solver.torque_rtol" and got == 1e-3
    assert "not both" in allowed and "n_rings = 100" in allowed
    # as the Python call refuses them
    s = Scene(twist_scene(SEG))
    with pytest.raises(ParameterError, match=r"n_rings=100 and torque_rtol=0\.001"):
        s.contact().simulate(s.load_path, method="exact", n_rings=100, torque_rtol=1e-3)


def test_cost_ladder_centres_on_the_rings_torque_rtol_chooses():
    from contactlab.foundation.rings import rings_for_rtol
    s = Scene(twist_scene(SEG, solver={"torque_rtol": 1e-3}))
    n0 = rings_for_rtol(1e-3)
    assert n0 in default_ladders(s)["n_rings"]
    rung = with_setting(s, "n_rings", 60)
    assert rung.solver == {"n_rings": 60}          # the rung's rings replace the accuracy
