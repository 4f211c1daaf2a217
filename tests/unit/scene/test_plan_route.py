"""One owner of the foundation route: the scene plan picks the model of ``contact.simulate`` with
the resolver ``simulate`` itself calls (``effects.path.resolve_path_method``), so a scene and a
direct ``contact.simulate`` call of its load path run the same model and give the same numbers:
on every example scene on the foundation route and on a seeded set of generated scenes
(with and without friction, twist, torque, shift or tangential force, the normal load held or
varying, ``outputs.method`` absent, ``"exact"``, ``"mdr"`` or ``"no-slip"``).

Before, a frictionless twisted path under a changing load ran on the MDR springs from a scene and
on the exact ring solver from ``contact.simulate``.
"""
import warnings

import numpy as np
import pytest

from contactlab.errors import ValidityWarning
from contactlab.scene import Scene

from tests.unit.scene.helpers import base, example_params

#: generated scenes
N_SCENES = 24


def _scene(i: int) -> dict:
    rng = np.random.default_rng([27, i])
    axis = ["twist", "torque", "displacement", "tangential_force"][int(rng.integers(4))]
    amp = {"twist": "1.5 mrad", "torque": "20 mN m", "displacement": "0.4 um",
           "tangential_force": "8 N"}[axis]
    varying = rng.random() < 0.75
    seg = {"sinusoid": {axis: amp, "cycles": 1.5, "steps_per_cycle": 16}}
    if varying:
        seg["sinusoid"]["force"] = "30 N"
    d = base(load_path=[{"ramp": {"force": "100 N", "steps": 4}}, seg,
                        {"ramp": {"force": "60 N", "steps": 5}}])
    friction = rng.random() < 0.6
    if friction:
        d["interface"] = {"friction": 0.2}
    methods = [None, "exact", "mdr", "no-slip"] if friction else [None, "no-slip"]
    method = methods[int(rng.integers(len(methods)))]
    if method is not None:
        d["outputs"] = {"method": method}
    return d


def _check(scene: Scene) -> None:
    plan = scene.plan()
    if plan.route != "foundation":
        pytest.skip(f"route {plan.route!r}: no contact.simulate")
    c, path = scene.contact(), scene.load_path
    # outputs.method of a twisted scene with friction in simulate's terms (the scene's
    # "no-slip" has no foundation implementation: the MDR springs); else simulate's default
    asked = None
    if plan.details["axis"] == "torsion" and scene.friction is not None:
        asked = {"exact": "exact", "mdr": "mdr", "no-slip": "mdr"}.get(scene.outputs.get("method"))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ValidityWarning)
        res = c.simulate(path, **({"method": asked} if asked else {}))
        ran = res.meta.get("method", "mdr")
        assert plan.details["path_method"] == ran
        assert plan.details["exact_torsion_path"] == (ran == "exact")
        if ran == "mdr" and "n_springs" in scene.solver:
            res = c.simulate(path, method="mdr", n_springs=scene.solver["n_springs"])
        out = scene.run()
    for k in plan.series:
        if k in res.data:
            np.testing.assert_array_equal(out.series[k], res.data[k], err_msg=k)


@pytest.mark.parametrize("path", example_params())
def test_example_scene_plan_and_simulate_agree(path):
    _check(Scene.from_toml(path))


@pytest.mark.parametrize("i", range(N_SCENES))
def test_generated_scene_plan_and_simulate_agree(i):
    _check(Scene(_scene(i)))


def test_frictionless_twist_under_changing_load_runs_the_ring_solver():
    """The case the two owners disagreed on: now the plan names the exact ring solver (its
    rigid punches at the contact radii), as contact.simulate runs it."""
    d = base(load_path=[{"ramp": {"force": "100 N", "steps": 4}},
                        {"sinusoid": {"twist": "1 mrad", "force": "30 N", "cycles": 1,
                                      "steps_per_cycle": 12}}])
    plan = Scene(d).plan()
    assert plan.route == "foundation" and plan.details["path_method"] == "exact"
    assert "exact ring solver" in plan["torsion"].implementation
    assert "rigid punches" in plan["torsion"].reason
    _check(Scene(d))
