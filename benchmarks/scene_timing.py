"""Scene timing: a normal-only scene versus the same scene with torsion requested.

Run from the repository root: ``python benchmarks/scene_timing.py``. Prints the machine, the best
of several repeats for: parsing + validation + planning, the normal-only run, the same run with
``outputs.effects = ["torsion"]`` (torsion at zero twist) and with a monotone twist segment, and
the ratios. Scenes needing an API this build lacks are reported as "n/a".
"""
from __future__ import annotations

import copy
import sys
import timeit
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from contactlab.errors import NotSupportedError  # noqa: E402
sys.path.insert(0, str(Path(__file__).resolve().parent))
from _harness import machine  # noqa: E402  (one machine description for every benchmark)
from contactlab.scene import Scene  # noqa: E402

STEEL = {"type": "elastic", "E": "210 GPa", "nu": 0.3}
NORMAL = {
    "profile": {"type": "paraboloid", "R": "10 mm"},
    "materials": {"body1": STEEL, "body2": STEEL},
    "interface": {"friction": 0.2},
    "load_path": [{"ramp": {"force": "100 N", "steps": 200}}],
}


def variant(**changes):
    d = copy.deepcopy(NORMAL)
    for k, v in changes.items():
        if k == "extra_segments":
            d["load_path"] += v
        else:
            d[k] = v
    return d


SCENES = {
    "normal only": NORMAL,
    "+ torsion requested (zero twist)": variant(outputs={"effects": ["torsion"]}),
    "+ monotone twist (exact torsion)": variant(
        extra_segments=[{"ramp": {"twist": "3 mrad", "steps": 200}}]),
    "+ oscillating twist (exact history)": variant(
        extra_segments=[{"sinusoid": {"twist": "3 mrad", "cycles": 2, "steps_per_cycle": 100}}]),
}


def best(fn, repeat=7):
    n, _ = timeit.Timer(fn).autorange()
    return min(timeit.Timer(fn).repeat(repeat=repeat, number=n)) / n


def main() -> None:
    print(f"machine: {machine()}")
    t_build = best(lambda: Scene(NORMAL).plan())
    print(f"parse+validate+plan (normal only, 201 steps): {t_build * 1e3:8.3f} ms")
    base = None
    for name, d in SCENES.items():
        scene = Scene(d)
        try:
            scene.run()
        except NotSupportedError as err:
            print(f"{name:40s}     n/a   ({str(err).split(',')[0]})")
            continue
        t = best(lambda: scene.run())
        calls = ", ".join(scene.run().meta["computed"])
        base = base or t
        print(f"{name:40s} {t * 1e3:8.3f} ms  x{t / base:6.2f}   computed: {calls}")


if __name__ == "__main__":
    main()
