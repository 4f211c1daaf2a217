"""``contactlab list``: registered profiles, materials (with parameter units) and the effects."""
from __future__ import annotations

import json

import pytest

from contactlab.cli import main
from contactlab.registry import registry


def test_list_text_names_every_registered_type_with_units(capsys):
    assert main(["list"]) == 0
    out = capsys.readouterr().out
    for kind in ("profile", "material"):
        for name in registry.available(kind):
            assert f"  {name} " in out
    assert "R [m] radius of curvature R" in out and "E [Pa]" in out and "eta [Pa*s]" in out
    for effect in ("normal", "adhesion", "tangential", "torsion", "viscoelastic", "fretting"):
        assert f"  {effect} " in out
    assert "twist [rad]" in out and "torque [N*m]" in out


def test_list_json_and_filter(capsys):
    assert main(["list", "materials", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["ok"] and set(data) == {"ok", "materials"}
    elastic = next(m for m in data["materials"] if m["name"] == "elastic")
    assert {"name": "nu", "unit": "1", "description": "Poisson's ratio"} in elastic["params"]


def test_list_plugin_profile_is_listed(capsys):
    """Session-registered types are listed like the built-ins."""
    from typing import ClassVar

    from contactlab.params import Param
    from contactlab.profiles import Profile

    class Bump(Profile):
        """f = c r^2 (test profile)."""
        name: ClassVar[str] = "bump_for_list"
        params: ClassVar[tuple] = (Param("c", "c", "1/m", "positive", "bump curvature c"),)

        def __init__(self, c: float) -> None:
            super().__init__(c=c)

        def _height(self, r, c):
            return c * r ** 2

    registry.register(Bump, "profile")
    try:
        assert main(["list", "profiles"]) == 0
        assert "bump_for_list" in capsys.readouterr().out
    finally:
        registry.unregister("profile", "bump_for_list")


def test_list_bad_choice_exits_2(capsys):
    with pytest.raises(SystemExit) as e:
        main(["list", "springs"])
    assert e.value.code == 2
