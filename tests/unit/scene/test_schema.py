"""The scene schema is data: keys come from the classes' Param specifications and their declared
``scene_keys``/``scene_one_of``, not from per-type code in the validator (issue 27)."""
from typing import ClassVar

import pytest

from contactlab.errors import SceneError
from contactlab.params import Param
from contactlab.profiles import Cone, Polynomial, Profile, Tabulated
from contactlab.registry import registry
from contactlab.scene import Scene
from contactlab.scene.schema import INTERFACE_KEYS, Key, key_from_text
from contactlab.scene.validate import object_keys

from tests.unit.scene.helpers import base


def issues_of(data):
    with pytest.raises(SceneError) as e:
        Scene(data)
    return e.value.issues


def test_key_from_text():
    assert key_from_text("array:length") == Key("array", "length")
    assert key_from_text("choice|linear,cubic") == Key("choice", choices=("linear", "cubic"))
    assert key_from_text("quantity:dimensionless:nonnegative|auto") == Key(
        "quantity", "dimensionless", "nonnegative", choices=("auto",))


def test_object_keys_follow_the_param_units():
    keys, required, groups = object_keys(registry.get("profile", "flat_punch"))
    assert keys["radius"] == Key("quantity", "length") and required == {"radius"}
    keys, required, groups = object_keys(registry.get("material", "elastic"))
    assert keys["E"].dimension == keys["G"].dimension == "pressure"
    assert groups == (("E",), ("G",)) and required == {"E", "nu"}


def test_class_declared_keys():
    keys, _, groups = object_keys(Tabulated)
    assert set(Tabulated.scene_keys) <= set(keys) and groups == (("file",), ("r", "f"))
    assert keys["r_unit"] == Key("unit", "length") and keys["r"] == Key("array", "length")
    keys, _, groups = object_keys(Cone)
    assert keys["half_angle"].dimension == "angle" and groups == (("slope",), ("half_angle",))
    assert object_keys(Polynomial)[0]["terms"].kind == "terms"


def test_interface_keys_are_the_contact_params():
    from contactlab import Contact
    p = {q.name: q for q in Contact.params}
    assert INTERFACE_KEYS["friction"] == Key.from_param(p["friction"])
    assert INTERFACE_KEYS["work_of_adhesion"] == Key("quantity", "energy_per_area", "nonnegative")


def test_cone_alternatives_messages():
    got = issues_of(base(profile={"type": "cone"}))
    assert got == [("profile.slope", None, "required for type 'cone': give 'slope' or 'half_angle'")]
    got = issues_of(base(profile={"type": "cone", "slope": 1, "half_angle": "60 deg"}))
    assert got == [("profile.half_angle", "60 deg", "either 'slope' or 'half_angle', not both")]
    assert Scene(base(profile={"type": "cone", "half_angle": "60 deg"})).profile == Cone(
        half_angle="60 deg")


def test_a_session_class_gets_its_scene_table_from_its_params():
    """A registered class needs no validator code: its Param units give the key dimensions, its
    scene_keys add keys, its scene_one_of alternative groups."""

    class Bump(Profile):
        name: ClassVar[str] = "bump_schema_test"
        params: ClassVar[tuple[Param, ...]] = (Param("R", "R", "m", "positive", "radius"),)
        scene_keys: ClassVar[dict[str, str]] = {"curvature": "quantity:number"}
        scene_one_of: ClassVar[tuple[tuple[str, ...], ...]] = (("R",), ("curvature",))

        def __init__(self, R: float | None = None, curvature: float | None = None) -> None:
            self.R = self.params[0].check(R if R is not None else 1.0 / curvature)

        def _height(self, r):
            return r * r / (2 * self.R)

    registry.register(Bump, "profile")
    try:
        assert Scene(base(profile={"type": "bump_schema_test", "R": "10 mm"})).profile.R == 0.01
        assert Scene(base(profile={"type": "bump_schema_test", "curvature": 100})).profile.R == 0.01
        got = issues_of(base(profile={"type": "bump_schema_test", "R": "10 N"}))
        assert got == [("profile.R", "10 N", "{m, cm, mm, um, nm, pm, km, micron, Å, angstrom}")]
        got = issues_of(base(profile={"type": "bump_schema_test"}))
        assert got[0][:2] == ("profile.R", None) and "'curvature'" in got[0][2]
    finally:
        registry.unregister("profile", "bump_schema_test")
