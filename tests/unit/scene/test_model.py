"""Scene round trips (dict, TOML, objects), the TOML writer and the sampled load path."""
import math
import tomllib

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import contactlab as cl
from contactlab.errors import SceneError
from contactlab.profiles import Cone, Paraboloid, Polynomial, Tabulated, TruncatedParaboloid
from contactlab.scene import Scene
from contactlab.scene.toml_io import dumps

from tests import tolerances as TOL
from tests.unit.scene.helpers import base, example_params, twist_scene


@pytest.mark.parametrize("path", example_params())
def test_examples_round_trip(path):
    s = Scene.from_toml(path)
    assert Scene.from_dict(s.to_dict(), base_dir=path.parent) == s
    assert Scene.loads(s.to_toml(), base_dir=path.parent) == s
    assert Scene.loads(s.to_toml(), base_dir=path.parent).to_toml() == s.to_toml()


def test_units_are_normalised_to_si():
    d = Scene(twist_scene()).to_dict()
    assert d["profile"] == {"type": "paraboloid", "R": 0.01}
    assert d["materials"]["body1"] == {"type": "elastic", "E": 210e9, "nu": 0.3}
    assert d["load_path"][1]["sinusoid"]["twist"] == pytest.approx(2e-3, rel=TOL.ULPS)


def test_save_and_load(tmp_path):
    s = Scene(twist_scene())
    s.save(tmp_path / "s.toml")
    assert Scene.from_toml(tmp_path / "s.toml") == s


def test_from_objects_equals_the_file_form():
    steel = cl.Elastic(E=210e9, nu=0.3)
    s = Scene.from_objects(Paraboloid(R=0.01), (steel, steel),
                           [{"ramp": {"force": 100.0, "steps": 10}}])
    assert s == Scene(base())
    assert s.profile == Paraboloid(R=0.01) and s.materials == (steel, steel)


@pytest.mark.parametrize("profile", [Cone(slope=0.3), TruncatedParaboloid(radius=1e-3, R=5e-3),
                                     Polynomial({2: 50.0, 4: 1e3}),
                                     Tabulated([0, 1e-3, 2e-3], [0, 1e-7, 4e-7])])
def test_from_objects_round_trip(profile):
    s = Scene.from_objects(profile, (cl.Rigid(), cl.Elastic(E=3e9, nu=0.35)),
                           [{"ramp": {"depth": 1e-7, "steps": 3}}], friction=0.3,
                           title="t", outputs={"series": ["force"]})
    assert s.profile == profile
    assert Scene.loads(s.to_toml()) == s
    assert Scene.loads(s.to_toml()).profile == profile


def test_from_objects_rejects_composites():
    with pytest.raises(SceneError, match="profile"):
        Scene.from_objects(Paraboloid(R=1.0) + Cone(slope=1.0), (cl.Rigid(), cl.Elastic(1e9, 0.3)),
                           [{"ramp": {"depth": 1e-7, "steps": 3}}])


_scalar = st.one_of(st.integers(-10**6, 10**6), st.floats(allow_nan=False), st.booleans(),
                    st.text(max_size=12))
_key = st.text(min_size=1, max_size=8)


@settings(max_examples=150, deadline=None)
@given(st.dictionaries(_key, st.one_of(
    _scalar, st.lists(st.floats(allow_nan=False), max_size=4),
    st.dictionaries(_key, st.one_of(_scalar, st.dictionaries(_key, _scalar, max_size=3)),
                    max_size=4),
    st.lists(st.dictionaries(_key, st.one_of(_scalar, st.dictionaries(_key, _scalar, max_size=3)),
                             min_size=1, max_size=3), min_size=1, max_size=3)), max_size=5))
def test_toml_writer_round_trips(data):
    assert tomllib.loads(dumps(data)) == data


def test_toml_writer_nan():
    assert math.isnan(tomllib.loads(dumps({"x": float("nan")}))["x"])


def test_history_ramp_hold_sinusoid():
    d = twist_scene({"hold": {"steps": 2, "duration": "4 s"}},
                    {"sinusoid": {"twist": "1 mrad", "cycles": 1, "steps_per_cycle": 4}})
    h = Scene(d).history()
    assert h.n_steps == 1 + 10 + 2 + 4
    np.testing.assert_allclose(h.values("normal")[:11], np.linspace(0, 100, 11), rtol=TOL.ULPS)
    np.testing.assert_allclose(h.values("normal")[11:], 100.0)
    np.testing.assert_allclose(h.values("torsion"), [0] * 13 + [1e-3, 0, -1e-3, 0], atol=TOL.ABS_ZERO_TWIST)
    np.testing.assert_allclose(h.time[:13], [*range(11), 12, 14])
    assert h.kind("normal") == "force" and h.kind("torsion") == "twist" and h.kind("tangential") is None
    assert list(h.segment[:2]) == [-1, 0] and h.segment[-1] == 2


def test_history_sinusoid_around_current_value():
    d = base(load_path=[{"ramp": {"depth": "1 um", "steps": 2}},
                        {"sinusoid": {"depth": "0.5 um", "cycles": 0.5, "steps_per_cycle": 4,
                                      "period": "2 s"}}])
    h = Scene(d).history()
    np.testing.assert_allclose(h.values("normal"), [0, 0.5e-6, 1e-6, 1.5e-6, 1e-6], rtol=TOL.SHORT_ARITHMETIC)
    np.testing.assert_allclose(h.time, [0, 1, 2, 2.5, 3.0])


def test_from_objects_with_a_loadpath():
    steel = cl.Elastic(E=210e9, nu=0.3)
    path = cl.LoadPath().ramp(force=100.0, steps=10).hold(steps=2).sinusoid(
        twist=1e-3, cycles=2, steps_per_cycle=8)
    s = Scene.from_objects(Paraboloid(R=0.01), (steel, steel), path, friction=0.2)
    assert Scene.loads(s.to_toml()) == s
    h = s.history()
    assert h.n_steps == path.n_steps + 1          # the scene history includes the unloaded start
    wave = 1e-3 * np.sin(2 * np.pi * np.arange(1, 9) / 8)
    np.testing.assert_allclose(h.values("torsion")[-8:], wave, atol=TOL.ABS_ZERO_TWIST)


def test_history_axes_are_the_load_path_groups():
    """A scene's history names its axes like the load path (normal, tangential, torsion); an
    unknown axis (the old spellings "twist"/"shift") is refused, not read as an undriven zero."""
    from contactlab.errors import UnknownNameError
    from contactlab.loadpath.base import GROUPS
    from contactlab.scene.model import AXES
    assert set(AXES) == set(GROUPS.values())
    d = {"profile": {"type": "paraboloid", "R": 0.01},
         "materials": {"body1": {"type": "elastic", "E": 2e11, "nu": 0.3},
                       "body2": {"type": "rigid"}},
         "load_path": [{"ramp": {"force": 10.0, "steps": 2}},
                       {"ramp": {"twist": 1e-3, "steps": 2}}]}
    h = Scene(d).history()
    assert h.kind("torsion") == "twist" and h.values("torsion")[-1] == 1e-3
    for old in ("twist", "shift"):
        with pytest.raises(UnknownNameError, match=f"axis='{old}'"):
            h.values(old)
