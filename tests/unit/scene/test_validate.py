"""Validation: one test per rule, every problem collected with (key path, value, allowed)."""
import pytest

from contactlab.errors import SceneError
from contactlab.scene import Scene

from tests.unit.scene.helpers import base, twist_scene


def issues_of(data, base_dir=None):
    with pytest.raises(SceneError) as e:
        Scene(data, base_dir)
    return e.value.issues


def paths(data, base_dir=None):
    return [p for p, _, _ in issues_of(data, base_dir)]


def test_valid_base_scene():
    Scene(base())


def test_all_problems_are_collected_together():
    d = base(interface={"fricton": 0.2})
    d["profile"] = {"type": "parabolid", "R": "10 mm"}
    d["materials"]["body1"]["nu"] = 0.7
    d["load_path"] = [{"ramp": {"force": "100 N", "steps": 0}},
                      {"sinusoid": {"twist": "1 m", "cycles": 2, "amplitude": 3}}]
    d["outputs"] = {"series": ["force", "torqe"]}
    got = issues_of(d)
    p = [i[0] for i in got]
    assert p == ["profile.type", "materials.body1.nu", "interface.fricton",
                 "load_path[0].ramp.steps", "load_path[1].sinusoid.amplitude",
                 "load_path[1].sinusoid.twist", "outputs.series[1]"]
    assert all(len(i) == 3 for i in got)
    allowed = dict((i[0], i[2]) for i in got)
    assert "did you mean 'paraboloid'" in allowed["profile.type"]
    assert "did you mean 'friction'" in allowed["interface.fricton"]
    assert "did you mean 'torque'" in allowed["outputs.series[1]"]


def test_message_lists_every_issue():
    d = base()
    d["profile"]["R"] = "-1 mm"
    d["materials"]["body2"]["E"] = "5 deg"
    with pytest.raises(SceneError, match=r"2 problems[\s\S]*profile.R[\s\S]*materials.body2.E"):
        Scene(d)


def test_unknown_section_did_you_mean():
    d = base(output={"series": ["force"]})
    assert issues_of(d)[0][:1] == ("output",) and "did you mean 'outputs'" in issues_of(d)[0][2]


@pytest.mark.parametrize("section", ["profile", "materials", "load_path"])
def test_required_sections(section):
    d = base()
    del d[section]
    assert section in paths(d)


def test_profile_type_required():
    assert paths(base(profile={"R": 0.01})) == ["profile.type"]


def test_profile_parameter_required():
    assert paths(base(profile={"type": "paraboloid"})) == ["profile.R"]


def test_profile_unknown_parameter():
    assert paths(base(profile={"type": "paraboloid", "R": 0.01, "radius": 1})) == ["profile.radius"]


def test_profile_domain_error_from_constructor():
    got = issues_of(base(profile={"type": "paraboloid", "R": 0}))
    assert got[0][0] == "profile.R" and got[0][1] == 0


def test_cone_slope_or_half_angle():
    Scene(base(profile={"type": "cone", "half_angle": "70.3 deg"}))
    Scene(base(profile={"type": "cone", "slope": 0.36}))
    assert paths(base(profile={"type": "cone"})) == ["profile.slope"]
    assert paths(base(profile={"type": "cone", "slope": 1, "half_angle": "60 deg"})) == [
        "profile.half_angle"]


def test_tabulated_needs_file_or_arrays(tmp_path):
    assert paths(base(profile={"type": "tabulated"})) == ["profile.file"]
    assert paths(base(profile={"type": "tabulated", "r": [0, 1e-3]})) == ["profile.f"]
    assert paths(base(profile={"type": "tabulated", "file": "missing.csv"}), tmp_path) == [
        "profile.file"]
    Scene(base(profile={"type": "tabulated", "r": [0, 1e-3, 2e-3], "f": [0, 1e-7, 4e-7]}))


def test_tabulated_bad_table_is_a_scene_issue():
    got = issues_of(base(profile={"type": "tabulated", "r": [0, 2e-3, 1e-3], "f": [0, 1e-7, 4e-7]}))
    assert got[0][0] == "profile.r" or got[0][0] == "profile"


def test_polynomial_terms():
    Scene(base(profile={"type": "polynomial", "terms": [[50.0, 2], [1e3, 4]]}))
    assert paths(base(profile={"type": "polynomial", "terms": [[50.0]]})) == ["profile.terms[0]"]
    assert paths(base(profile={"type": "polynomial", "terms": [[50.0, "2 m"]]})) == [
        "profile.terms[0][1]"]


def test_material_type_and_params():
    d = base()
    d["materials"]["body2"] = {"type": "elastc"}
    assert paths(d) == ["materials.body2.type"]
    d["materials"]["body2"] = {"type": "elastic", "E": "210 GPa"}
    assert paths(d) == ["materials.body2.nu"]


def test_elastic_from_shear_modulus():
    d = base()
    d["materials"]["body2"] = {"type": "elastic", "G": "80 GPa", "nu": 0.3}
    assert Scene(d).materials[1].E == pytest.approx(2 * 80e9 * 1.3)


def test_both_rigid_is_invalid():
    d = base(materials={"body1": {"type": "rigid"}, "body2": {"type": "rigid"}})
    assert paths(d) == ["materials"]


def test_missing_body():
    d = base()
    del d["materials"]["body2"]
    assert paths(d) == ["materials.body2"]


def test_friction_positive():
    assert paths(base(interface={"friction": 0})) == ["interface.friction"]


def test_work_of_adhesion_units():
    assert paths(base(interface={"work_of_adhesion": "5 GPa"})) == ["interface.work_of_adhesion"]


def test_load_path_nonempty_list():
    assert paths(base(load_path=[])) == ["load_path"]
    assert paths(base(load_path={"ramp": {}})) == ["load_path"]


def test_segment_kind_unknown():
    got = issues_of(base(load_path=[{"rmp": {"force": 1.0, "steps": 2}}]))
    assert got[0][0] == "load_path[0].rmp" and "did you mean 'ramp'" in got[0][2]


def test_segment_needs_control():
    assert paths(base(load_path=[{"ramp": {"steps": 2}}])) == ["load_path[0].ramp"]


def test_segment_steps_required_and_integer():
    assert paths(base(load_path=[{"ramp": {"force": 1.0}}])) == ["load_path[0].ramp.steps"]
    assert paths(base(load_path=[{"ramp": {"force": 1.0, "steps": 2.5}}])) == [
        "load_path[0].ramp.steps"]


def test_sinusoid_options():
    d = twist_scene({"sinusoid": {"twist": "1 mrad", "steps_per_cycle": 2, "cycles": 1}})
    assert paths(d) == ["load_path[1].sinusoid.steps_per_cycle"]
    d = twist_scene({"sinusoid": {"twist": "1 mrad"}})
    assert paths(d) == ["load_path[1].sinusoid.cycles"]


def test_one_control_per_axis():
    d = base(load_path=[{"ramp": {"force": 1.0, "steps": 2}}, {"ramp": {"depth": 1e-6, "steps": 2}}])
    assert paths(d) == ["load_path[1].ramp.depth"]


def test_path_needs_normal_control():
    assert paths(base(load_path=[{"ramp": {"twist": 1e-3, "steps": 2}}])) == ["load_path"]


def test_too_many_steps():
    assert paths(base(load_path=[{"ramp": {"force": 1.0, "steps": 150_000}},
                                 {"hold": {"steps": 150_000}}])) == ["load_path"]


def test_table_segment_inline_and_rules():
    Scene(base(load_path=[{"table": {"time": [0, 1, 2], "force": [0, 50, 100]}}]))
    assert paths(base(load_path=[{"table": {"time": [0, 1], "force": [0, 5, 10]}}])) == [
        "load_path[0].table"]
    assert paths(base(load_path=[{"table": {"time": [0, 2, 1], "force": [0, 5, 10]}}])) == [
        "load_path[0].table.time"]
    # a table composes with other segments (issue 12): ramp, table, repeat, hold
    s = Scene(base(load_path=[{"ramp": {"force": 5, "steps": 2}},
                              {"table": {"force": [6, 7, 5]}}, {"repeat": {"times": 3}},
                              {"hold": {"steps": 2}}]))
    assert s.history().n_steps == 1 + 2 + 3 * 3 + 2
    assert paths(base(load_path=[{"repeat": {"times": 2}},
                                 {"ramp": {"force": 1, "steps": 1}}])) == ["load_path[0].repeat.last"]


def test_table_segment_csv(tmp_path):
    (tmp_path / "h.csv").write_text("time,force,twist\n0,0,0\n1,100,0\n2,100,1e-3\n")
    s = Scene(base(load_path=[{"table": {"file": "h.csv"}}], interface={"friction": 0.2}), tmp_path)
    assert s.history().n_steps == 3
    (tmp_path / "bad.csv").write_text("time,forse\n0,0\n")
    got = issues_of(base(load_path=[{"table": {"file": "bad.csv"}}]), tmp_path)
    assert got[0][0] == "load_path[0].table.file[columns].forse"


def test_outputs_names():
    assert paths(base(outputs={"fields": ["presure"]})) == ["outputs.fields[0]"]
    assert paths(base(outputs={"series": ["force", "force"]})) == ["outputs.series[1]"]
    assert paths(base(outputs={"method": "exakt"})) == ["outputs.method"]
    assert paths(base(outputs={"effects": ["torsoin"]})) == ["outputs.effects[0]"]
    assert paths(base(outputs={"field_points": 1})) == ["outputs.field_points"]


def test_partial_slip_method_needs_friction():
    assert paths(base(outputs={"method": "exact"})) == ["outputs.method"]


def test_slip_and_dissipation_need_friction():
    assert paths(base(outputs={"effects": ["slip"]})) == ["outputs.effects"]
    assert "outputs.series" in paths(base(outputs={"series": ["dissipated_energy"]}))


def test_adhesion_effect_needs_work_of_adhesion():
    assert paths(base(outputs={"effects": ["adhesion"]})) == ["outputs.effects"]


def test_solver_options():
    assert paths(base(solver={"rtol": 0.5})) == ["solver.rtol"]
    assert paths(base(solver={"n_springs": 1})) == ["solver.n_springs"]
    assert paths(base(solver={"n_spring": 10})) == ["solver.n_spring"]


def test_scene_meta():
    Scene(base(scene={"title": "x", "description": "y"}))
    assert paths(base(scene={"title": 3})) == ["scene.title"]


def test_plan_conflicts_are_scene_errors():
    d = twist_scene({"ramp": {"twist": 1e-3, "displacement": 1e-7, "steps": 3}})
    assert paths(d) == ["load_path"]


def test_shear_field_needs_monotone_twist():
    d = twist_scene(outputs={"fields": ["shear"]})
    assert paths(d) == ["outputs.fields"]


def test_stick_radius_needs_twist_or_shift():
    assert paths(base(outputs={"series": ["stick_radius"]})) == ["outputs.series"]


def test_toml_syntax_error():
    with pytest.raises(SceneError, match="not valid TOML") as e:
        Scene.loads("[profile\ntype = 1")
    assert e.value.issues[0][0] == "<toml>"


def test_table_file_rows_count_against_the_step_limit(tmp_path, monkeypatch):
    """Rows of a CSV history count like inline rows, times its repeats (issue 12)."""
    import importlib
    v = importlib.import_module("contactlab.scene.validate")
    monkeypatch.setattr(v, "MAX_STEPS", 100)
    rows = "\n".join(f"{i},{i + 1}" for i in range(60))
    (tmp_path / "h.csv").write_text("time,force\n" + rows + "\n")
    Scene(base(load_path=[{"table": {"file": "h.csv"}}]), tmp_path)               # 60 rows
    Scene(base(load_path=[{"ramp": {"force": 1, "steps": 39}},
                          {"table": {"file": "h.csv"}}]), tmp_path)                # 99 steps
    got = issues_of(base(load_path=[{"ramp": {"force": 1, "steps": 41}},
                                    {"table": {"file": "h.csv"}}]), tmp_path)
    assert [(p, val) for p, val, _ in got] == [("load_path", "101 steps")]
    got = issues_of(base(load_path=[{"table": {"file": "h.csv"}}, {"repeat": {"times": 2}}]),
                    tmp_path)
    assert [(p, val) for p, val, _ in got] == [("load_path", "120 steps")]
    assert "at most 100 steps" in got[0][2]
