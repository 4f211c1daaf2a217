"""Effect planning: the exact closed-form route whenever one exists, nothing unasked for."""
import json

import pytest

from contactlab import Contact
from contactlab.scene import Scene

from tests.unit.scene.helpers import base, twist_scene

SLIP_EFFECTS = {"tangential", "torsion", "slip"}


def plan_of(d):
    return Scene(d).plan()


def test_normal_only_plan_has_no_tangential_torsion_or_slip():
    p = plan_of(base())
    assert p.names == ("normal",)
    assert not SLIP_EFFECTS & set(p.names)
    assert p.route == "closed_form" and p.calls == ("normal",)
    assert "closed form exists, no foundation" in p["normal"].reason
    assert p.series == ("time", "depth", "force", "radius")
    assert p.method is None


def test_normal_only_with_friction_still_no_slip():
    p = plan_of(base(interface={"friction": 0.3}))
    assert p.names == ("normal",) and p.calls == ("normal",)


def test_load_unload_normal_path_is_closed_form():
    d = base(load_path=[{"ramp": {"depth": "1 um", "steps": 5}}, {"ramp": {"depth": 0, "steps": 5}},
                        {"sinusoid": {"depth": "0.1 um", "cycles": 2}}])
    p = plan_of(d)
    assert p.route == "closed_form" and p.calls == ("normal",)


def test_monotone_twist_uses_exact_torsion():
    p = plan_of(twist_scene({"ramp": {"twist": "1 mrad", "steps": 10}}))
    assert p.names == ("normal", "torsion", "slip")
    assert p.calls == ("normal", "torsion") and p.method == "exact"
    assert "monotone twist at constant normal load" in p["torsion"].reason
    assert "path has twist" in p["torsion"].reason


def test_oscillating_twist_uses_exact_history():
    p = plan_of(twist_scene())
    assert p.calls == ("normal", "twist_history")
    assert "Masing" in p["torsion"].reason
    assert "dissipated_energy" in p.series


def test_dissipation_request_uses_history_even_when_monotone():
    d = twist_scene({"ramp": {"twist": "1 mrad", "steps": 10}},
                    outputs={"series": ["torque", "dissipated_energy"]})
    assert plan_of(d).calls == ("normal", "twist_history")


def test_no_friction_means_no_slip_torsion():
    p = plan_of(twist_scene(friction=None))
    assert p.names == ("normal", "torsion") and p.method == "no-slip"
    assert p.calls == ("normal", "torsion")
    assert "linear" in p["torsion"].reason


def test_mdr_method_named_in_slip_row():
    p = plan_of(twist_scene(outputs={"method": "mdr"}))
    assert p.method == "mdr" and "MDR narrow-slip" in p["slip"].implementation


def test_varying_normal_load_while_twisted_needs_foundation():
    d = twist_scene({"ramp": {"twist": "1 mrad", "steps": 4}}, {"ramp": {"force": "200 N", "steps": 4}})
    p = plan_of(d)
    assert p.route == "foundation" and p.calls == ("simulate",)
    assert "normal load varies while twisted (step 15, load_path[2])" in p["normal"].reason
    # the exact ring solver runs such paths (issue 18), and the plan says why
    assert "exact ring solver" in p["torsion"].implementation
    assert "exact pressure per step" in p["torsion"].reason
    assert p.details["exact_torsion_path"]


def test_torque_controlled_oscillation_needs_foundation():
    d = twist_scene({"sinusoid": {"torque": "1 mN m", "cycles": 1}})
    p = plan_of(d)
    assert p.route == "foundation" and "torque-controlled" in p["normal"].reason


def test_monotone_torque_is_closed_form():
    p = plan_of(twist_scene({"ramp": {"torque": "1 mN m", "steps": 4}}))
    assert p.calls == ("normal", "torsion")


def test_shift_monotone_and_history():
    p = plan_of(twist_scene({"ramp": {"displacement": "0.1 um", "steps": 4}}))
    assert p.names == ("normal", "tangential", "slip") and p.calls == ("normal", "tangential")
    assert "Cattaneo-Mindlin" in p["slip"].implementation
    p = plan_of(twist_scene({"sinusoid": {"displacement": "0.1 um", "cycles": 1}}))
    assert p.calls == ("normal", "shift_history")


def test_requested_torsion_without_twist():
    p = plan_of(base(outputs={"effects": ["torsion"]}))
    assert p.names == ("normal", "torsion") and p.calls == ("normal",)
    assert "no call" in p["torsion"].implementation
    assert "requested in outputs.effects" in p["torsion"].reason
    assert "no twist" in p["torsion"].reason


def test_torque_series_implies_torsion():
    p = plan_of(base(outputs={"series": ["force", "torque"]}))
    assert "torsion" in p and "outputs ask for torque" in p["torsion"].reason


def test_adhesion_row():
    p = plan_of(base(interface={"work_of_adhesion": "0.05 J/m^2"}))
    assert p.names == ("normal", "adhesion") and "Heß" in p["adhesion"].implementation
    assert "JKR" in p["normal"].reason and p.route == "closed_form"


def test_fields_rows():
    p = plan_of(base(outputs={"fields": ["pressure", "surface_displacement"]}))
    assert [o.effect for o in p.outputs] == ["field:pressure", "field:surface_displacement"]
    p = plan_of(twist_scene({"ramp": {"twist": "1 mrad", "steps": 3}}, outputs={"fields": ["shear"]}))
    assert "torsion" in p and p.outputs[0].effect == "field:shear"


def test_plan_is_pure(monkeypatch):
    """Planning constructs no Contact and calls no physics."""
    def boom(*a, **k):
        raise AssertionError("physics called while planning")
    monkeypatch.setattr(Contact, "__init__", boom)
    for name in ("normal", "torsion", "twist_history", "simulate", "tangential", "shift_history"):
        monkeypatch.setattr(Contact, name, boom, raising=False)
    for d in (base(), twist_scene(), twist_scene({"ramp": {"force": 300.0, "steps": 3}},
                                                 {"sinusoid": {"twist": 1e-3, "cycles": 1}})):
        plan_of(d)


def test_print_and_json():
    p = plan_of(twist_scene())
    text = str(p)
    assert text.startswith("plan: closed form route") and "twist_history" in text
    d = json.loads(json.dumps(p.to_dict()))
    assert d["route"] == "closed_form" and d["effects"][1]["effect"] == "torsion"
    assert set(d["effects"][0]) == {"effect", "implementation", "reason"}


def test_unknown_effect_lookup():
    with pytest.raises(KeyError, match="torsion"):
        plan_of(base())["torsion"]


def test_requested_torsion_without_twist_runs_without_torsion_machinery(monkeypatch):
    monkeypatch.setattr(Contact, "torsion", None, raising=False)
    res = Scene(base(outputs={"effects": ["torsion"]})).run()
    assert res.meta["computed"] == ["normal"]
    assert list(res.series) == ["time", "depth", "force", "radius", "twist", "torque",
                                "stick_radius"]
    assert not res["torque"].any() and (res["stick_radius"] == res["radius"]).all()
