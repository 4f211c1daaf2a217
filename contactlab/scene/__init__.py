"""Scenes: a whole contact study in one file (TOML) or mapping, validated, planned and run.

>>> from contactlab.scene import Scene
>>> scene = Scene.from_toml("examples/hertz_steel_ball.toml")  # doctest: +SKIP
>>> print(scene.plan())                                        # doctest: +SKIP
>>> result = scene.run()                                       # doctest: +SKIP
"""
from .cost import CostReport, scene_cost
from .model import History, Scene
from .plan import Effect, Plan, make_plan
from .run import SceneResult, run_scene
from .units import parse_quantity
from .validate import validate

__all__ = ["Scene", "History", "Effect", "Plan", "make_plan", "SceneResult", "run_scene",
           "parse_quantity", "validate", "scene_cost", "CostReport"]
