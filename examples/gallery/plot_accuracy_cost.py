"""
What accuracy costs for your own scene
======================================

Every numeric knob of a study has a price in wall time. ``Scene.cost`` (``contactlab cost
SCENE --target 1e-6`` on the command line) runs the scene itself over a ladder of each knob that
applies to it, measures the error of every rung against the knob's tightest rung, and marks the
default (ring) and the cheapest setting that meets the target (star).

Here: the twisted steel ball of the examples, whose only knob is the tolerance ``rtol`` of the
quadratures and root solves (the exact torsion solution has no discretisation), and a tabulated
profile, whose knob is the interpolation of the table. Its integrals are exact for the
interpolant, so no rung of ``rtol`` changes its results. The report lists ``rtol`` there as
"not read" and recommends no setting for it.
"""
from pathlib import Path

from contactlab import plotting as pl
from contactlab.scene import Scene

# the example scenes live in examples/ of the repository (the docs build runs this script from
# examples/gallery/, a session may start anywhere inside the repository)
here = Path.cwd()
examples = next(p / "examples" for p in (here, *here.parents)
                if (p / "examples" / "steel_ball_twist.toml").exists())

twist = Scene.from_toml(examples / "steel_ball_twist.toml")
lens = Scene.from_toml(examples / "measured_profile.toml")

fig, axes = pl.subplots(1, 2, figsize=(10, 4.2))
for scene, ax in zip((twist, lens), axes):
    report = scene.cost(target=1e-6)
    report.plot(ax=ax)
    print(report)
