"""Time estimates against measured runs (issue 26 item 6): each call that checks the time budget
before its work is run at a size that takes about a second, and its estimate (the same formula
the library checks) is printed beside the measured CPU time.

Run from the repository root: ``python benchmarks/time_estimates.py``.

The estimates are lower estimates (a refused call would take at least that long on an unloaded
core), so every ratio measured / estimated should be >= 1; the verdict says so per row. The
machine is named with its load: the per-step costs were calibrated on a shared 2-core VM, and a
loaded machine shows larger ratios, never smaller ones.
"""
from __future__ import annotations

import math
import sys
import time
import warnings
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(Path(__file__).resolve().parent))

import contactlab as cl  # noqa: E402
from contactlab.effects import tangential as _tan  # noqa: E402
from contactlab.effects import torsion as _tor  # noqa: E402
from contactlab.effects import wear as _wear  # noqa: E402
from contactlab.foundation import rings as _rings  # noqa: E402
from contactlab.foundation import winkler as _wink  # noqa: E402
from _harness import machine  # noqa: E402

STEEL = cl.Elastic(E=210e9, nu=0.3)
C = cl.Contact(cl.profiles.Paraboloid(R=0.01), materials=(STEEL, STEEL), friction=0.3)
CW = cl.Contact(cl.profiles.Paraboloid(R=0.01), materials=(STEEL, cl.Rigid()), friction=0.3)


def cpu(fn) -> float:
    t0 = time.process_time()
    fn()
    return time.process_time() - t0


def row(name: str, estimate: float, measured: float) -> None:
    ratio = measured / estimate
    print(f"  {name:52s} estimate {estimate:8.3g} s  measured {measured:8.3g} s  "
          f"ratio {ratio:6.2f}  {'OK (lower estimate)' if ratio >= 1 else 'UNDER: estimate too high'}")


def main() -> None:
    print(machine())
    warnings.simplefilter("ignore")
    rng = np.random.default_rng(0)
    n = 200_000
    walk = np.cumsum(rng.standard_normal(n)) * 1e-9
    row(f"shift_history, random walk of {n} steps", n * _tan.HISTORY_SECONDS_PER_STEP,
        cpu(lambda: C.shift_history(displacement=walk, force=10.0)))
    tw = np.cumsum(rng.standard_normal(n)) * 1e-6
    tw = tw[:50_000]
    for method in ("exact", "mdr"):
        # a random walk's loading-curve arguments are nearly all distinct (99.97 %)
        row(f"twist_history {method}, random walk of {tw.size} steps",
            tw.size * (_tor.HISTORY_SECONDS_PER_STEP + _tor.SOLVE_SECONDS_PER_ARGUMENT[method]),
            cpu(lambda: C.twist_history(twist=tw, force=10.0, method=method)))
    steps = 400
    path = cl.LoadPath.from_arrays(force=10 + 5 * np.sin(np.linspace(0, 20 * np.pi, steps)),
                                   twist=1e-5 * np.sin(np.linspace(0, 6 * np.pi, steps)))
    for rings in (50, 200):
        row(f"simulate exact, {steps} varying-load steps, {rings} rings",
            steps * _rings.step_seconds(rings),
            cpu(lambda: C.simulate(path, method="exact", n_rings=rings)))
    C.simulate(path, method="mdr", n_springs=100)              # compile the kernels first
    for strategy, springs in (("segments", 2000), ("steps", 20000)):
        row(f"simulate mdr {strategy}, {steps} steps, {springs} springs",
            steps * _wink.step_seconds(springs, strategy),
            cpu(lambda: C.simulate(path, method="mdr", strategy=strategy, n_springs=springs)))
    ns = CW.normal(force=10.0)
    loop = CW.fretting_loop(force=10.0, displacement_amplitude=1e-6)
    for kN in (1e-10, 1e-9):
        ratio = kN * float(np.ravel(loop.energy)[0]) / (0.3 * math.pi * ns.radius**2 * ns.depth)
        est = _wear.wear_steps_lower(1, _wear.DEFAULT_JUMP_RTOL, ratio) * \
            _wear.wear_step_seconds(_wear.DEFAULT_GRID)
        row(f"wear, Hertz shift, k N = {kN:g} (volume ratio {ratio:.3g})", est,
            cpu(lambda: CW.wear(force=10.0, displacement_amplitude=1e-6,
                                wear_coefficient=kN / 1e3, cycles=1e3,
                                max_radius=4 * ns.radius)))
    print(machine())


if __name__ == "__main__":
    main()
