"""Property test of the scene parser: random and malformed scenes give a SceneError (exit 2) or a
clean run without NaN; never a traceback. Runtime physics refusals (ContactlabError other than
SceneError: exit 1 with a message) are allowed, anything else is a bug."""
import math
import warnings

import numpy as np
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from contactlab.cli import main
from contactlab.errors import ContactlabError, ContactlabWarning, SceneError
from contactlab.scene import Scene
from contactlab.scene.units import UNITS
from contactlab.scene.validate import CONTROLS, EFFECTS, FIELDS, METHODS, SERIES

ALL_UNITS = sorted({u for t in UNITS.values() for u in t})

junk = st.one_of(st.none(), st.booleans(), st.text(max_size=6), st.lists(st.integers(), max_size=2),
                 st.dictionaries(st.text(max_size=4), st.integers(), max_size=2),
                 st.floats(allow_nan=True, allow_infinity=True))


def mostly(good, bad, one_in=12):
    """``good`` except once in ``one_in`` draws, so that many fuzzed scenes are valid."""
    return st.sampled_from([True] * (one_in - 1) + [False]).flatmap(
        lambda ok: good if ok else bad)


def quantity(lo, hi, units):
    num = st.floats(lo, hi)
    good = st.one_of(num, st.builds(lambda v, u: f"{v!r} {u}", num, st.sampled_from(units)))
    bad = st.one_of(junk, st.builds(lambda v, u: f"{v} {u}", st.floats(-1e3, 1e3),
                                    st.sampled_from(ALL_UNITS)))
    return mostly(good, bad)


length = quantity(1e-4, 1e-1, ["m", "mm", "um"])
small_len = quantity(1e-8, 1e-6, ["m", "um", "nm"])
modulus = quantity(1e6, 1e12, ["Pa", "MPa", "GPa"])
nu = mostly(st.floats(-0.9, 0.5), junk)
profile = mostly(st.one_of(
    st.fixed_dictionaries({"type": st.just("paraboloid"), "R": length}),
    st.fixed_dictionaries({"type": st.just("cone"), "half_angle": quantity(0.2, 1.5, ["rad"])}),
    st.fixed_dictionaries({"type": st.just("flat_punch"), "radius": length}),
    st.fixed_dictionaries({"type": st.just("truncated_paraboloid"), "radius": length, "R": length}),
    st.fixed_dictionaries({"type": st.just("power_law"), "c": st.floats(1e-3, 1e3),
                           "n": st.floats(0.6, 6)}),
    st.fixed_dictionaries({"type": st.sampled_from(["sphere", "spere", "tabulated", "cone"])},
                          optional={"R": length, "slope": junk, "file": junk})), junk)
material = mostly(st.one_of(
    st.fixed_dictionaries({"type": st.just("elastic"), "E": modulus, "nu": nu}),
    st.fixed_dictionaries({"type": st.just("elastic"), "E": modulus, "nu": nu}),
    st.fixed_dictionaries({"type": st.just("rigid")}),
    st.fixed_dictionaries({"type": st.sampled_from(["elastic", "elastc", "rigid"])},
                          optional={"E": modulus, "nu": nu, "G": modulus, "x": junk})), junk)
control = st.sampled_from(sorted(CONTROLS))
control_value = {"force": quantity(0, 50, ["N", "mN"]), "depth": small_len,
                 "twist": quantity(-1e-3, 1e-3, ["rad", "mrad"]),
                 "torque": quantity(-1e-4, 1e-4, ["N m", "mN m"]),
                 "displacement": quantity(-1e-7, 1e-7, ["m", "um"]),
                 "tangential_force": quantity(-1.0, 1.0, ["N"])}
steps = mostly(st.integers(1, 8), st.one_of(st.integers(-2, 3), junk))


@st.composite
def segment(draw, first=False):
    kind = draw(mostly(st.sampled_from(["ramp", "hold", "sinusoid"]),
                       st.sampled_from(["table", "rmp"])))
    if first:
        kind = draw(mostly(st.just("ramp"), st.just(kind), 4))
    body = {}
    if kind in ("ramp", "sinusoid", "rmp"):
        ctrls = draw(st.lists(control, min_size=0, max_size=2, unique=True))
        if first:
            ctrls = [draw(st.sampled_from(["force", "depth"]))] + [
                c for c in ctrls if c not in ("force", "depth")]
        for c in ctrls:
            body[c] = draw(control_value[c])
    if kind in ("ramp", "hold"):
        body["steps"] = draw(steps)
    if kind == "sinusoid":
        body["cycles"] = draw(mostly(st.floats(0.25, 2), junk))
        body["steps_per_cycle"] = draw(mostly(st.integers(4, 12), steps))
    if kind == "table":
        n = draw(st.integers(1, 4))
        body = {"time": sorted(draw(st.lists(st.floats(0, 10), min_size=n, max_size=n))),
                "force": draw(st.lists(st.floats(0, 50), min_size=n, max_size=n))}
    if not draw(st.sampled_from([True] * 15 + [False])):
        body[draw(st.text(max_size=5))] = draw(junk)
    return {kind: body}


scene = st.fixed_dictionaries(
    {"profile": profile, "materials": mostly(
        st.fixed_dictionaries({"body1": material, "body2": material}), junk),
     "load_path": mostly(st.builds(lambda a, b: [a, *b], segment(first=True),
                                   st.lists(segment(), max_size=2)), junk)},
    optional={
        "interface": st.fixed_dictionaries({}, optional={
            "friction": mostly(st.floats(0.05, 1), junk),
            "work_of_adhesion": mostly(st.sampled_from([0.0, 0.05, "50 mJ/m^2"]), junk)}),
        "outputs": st.fixed_dictionaries({}, optional={
            "series": st.lists(st.sampled_from([*SERIES, "torqe"]), max_size=4, unique=True),
            "fields": st.lists(st.sampled_from([*FIELDS, "presure"]), max_size=2, unique=True),
            "method": st.sampled_from([*METHODS, "exakt"]),
            "effects": st.lists(st.sampled_from([*EFFECTS, "twist"]), max_size=2, unique=True),
            "field_points": mostly(st.integers(2, 30), junk)}),
        "solver": st.fixed_dictionaries(
            {}, optional={"rtol": mostly(st.floats(1e-12, 1e-3), junk)})})


@settings(max_examples=300, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(scene)
def test_random_scenes_validate_or_run_cleanly(data):
    try:
        s = Scene(data)
    except SceneError as err:
        assert err.issues and all(len(i) == 3 and isinstance(i[0], str) for i in err.issues)
        return
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ContactlabWarning)
        try:
            res = s.run()
        except SceneError as err:          # pragma: no cover - would be a validation gap
            raise AssertionError(f"SceneError after validation: {err}") from err
        except ContactlabError:
            return                         # clean refusal, CLI exit 1 (e.g. API not merged)
    for k, v in list(res.series.items()) + list(res.fields.items()):
        assert not np.any(np.isnan(v)), k
    assert s.plan().names[0] == "normal"


toml_text = st.one_of(
    st.text(max_size=80),
    st.lists(st.sampled_from([
        "[profile]", 'type = "paraboloid"', 'R = "10 mm"', "R = -1", 'R = "1e-3 km"',
        "[materials]", 'body1 = { type = "elastic", E = "210 GPa", nu = 0.3 }',
        'body2 = { type = "rigid" }', "body2 = 3", "[[load_path]]",
        'ramp = { force = "10 N", steps = 3 }', "hold = { steps = 2 }", "[outputs]",
        'series = ["force", "torque"]', "[interface]", "friction = 0.3", "friction = nan",
        "x = [1, 2", '"', "[[profile]]"]), max_size=14).map("\n".join))


@settings(max_examples=150, deadline=None)
@given(toml_text)
def test_cli_validate_random_toml_exit_0_or_2(tmp_path_factory, text):
    path = tmp_path_factory.mktemp("fuzz") / "s.toml"
    path.write_text(text, encoding="utf-8")
    assert main(["validate", str(path), "--json"]) in (0, 2)


def test_nan_and_inf_values_are_issues():
    for bad in (math.nan, math.inf, "nan m", "-inf mm"):
        try:
            Scene({"profile": {"type": "paraboloid", "R": bad}, "materials": {
                "body1": {"type": "rigid"}, "body2": {"type": "elastic", "E": 1e9, "nu": 0.3}},
                "load_path": [{"ramp": {"force": 1.0, "steps": 1}}]})
        except SceneError as err:
            assert err.issues[0][0] == "profile.R"
        else:
            raise AssertionError(f"R={bad!r} accepted")


def test_dissipated_energy_without_tangential_drive_is_zero():
    """Regression (found by the fuzz test): friction given, only a normal ramp, and
    ``dissipated_energy`` requested used to raise KeyError; nothing slips, so it is 0 J."""
    data = {"profile": {"type": "paraboloid", "R": 0.0625},
            "materials": {"body1": {"type": "elastic", "E": 1e6, "nu": 0.0},
                          "body2": {"type": "rigid"}},
            "load_path": [{"ramp": {"force": 1.0, "steps": 3}}],
            "interface": {"friction": 1.0}, "solver": {},
            "outputs": {"series": ["time", "dissipated_energy", "depth", "twist"]}}
    res = Scene(data).run()
    assert np.all(res["dissipated_energy"] == 0.0) and np.all(res["twist"] == 0.0)
    assert np.all(np.isfinite(res["depth"]))
