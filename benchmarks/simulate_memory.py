"""Peak memory of ``contact.simulate`` against its result arrays (issue 13: within 2x).

Two 10^6-step paths, N = 2000 springs, traced with tracemalloc after a warm-up run (so that a
numba JIT compile is not counted): a held normal load with a twist sinusoid (10^4 cycles of
100 steps) and a gait-like table (force and twist change at every step), both on the spring
foundation (``method="mdr"``); then the gait table on the exact ring solver (the default of a
twisted path, ``method="exact"``) with ``exact_steps`` steps (default 10^4: the ring solver costs
~1 ms per step).

Run from the repository root: ``python benchmarks/simulate_memory.py [steps] [exact_steps]``
"""
from __future__ import annotations

import sys
import time
import tracemalloc
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))
sys.path.insert(0, str(Path(__file__).resolve().parent))
import contactlab as cl  # noqa: E402
from _harness import machine  # noqa: E402


def main() -> None:
    steps = int(sys.argv[1]) if len(sys.argv) > 1 else 10 ** 6
    exact_steps = int(sys.argv[2]) if len(sys.argv) > 2 else 10 ** 4
    print("machine:", machine())
    steel = cl.Elastic(E=210e9, nu=0.3)
    c = cl.Contact(cl.profiles.Paraboloid(R=0.01), materials=(steel, steel), friction=0.2)
    a = c.normal(force=50.0).radius
    phi0 = 0.5 * 3 * 0.2 * 50.0 / (16 * c.moduli.torsional * a ** 2)
    held = cl.LoadPath().ramp(force=50.0, steps=1).sinusoid(twist=phi0, cycles=steps // 100,
                                                            steps_per_cycle=100)
    k = np.arange(1, steps + 1)
    F = 50.0 * (0.75 + 0.25 * np.sin(2 * np.pi * k / 1400))
    tw = phi0 * np.sin(2 * np.pi * k / 200)
    gait = cl.LoadPath().ramp(force=37.5, steps=1).then(
        cl.loadpath.Table.create(None, {"force": F, "twist": tw}))
    del F, tw, k
    c.simulate(cl.LoadPath().ramp(force=50.0, steps=3).ramp(force=40.0, twist=phi0, steps=20),
               n_springs=100, method="mdr")   # warm-up (JIT)
    ke = np.arange(1, exact_steps + 1)
    gait_exact = cl.LoadPath().ramp(force=37.5, steps=1).then(cl.loadpath.Table.create(
        None, {"force": 50.0 * (0.75 + 0.25 * np.sin(2 * np.pi * ke / 700)),
               "twist": phi0 * np.sin(2 * np.pi * ke / 100)}))
    for name, path, kw in (("held load + twist sinusoid", held, dict(n_springs=2000, method="mdr")),
                           ("gait table", gait, dict(n_springs=2000, method="mdr")),
                           ("gait table, exact rings", gait_exact, dict(method="exact"))):
        tracemalloc.start()
        t0 = time.perf_counter()
        r = c.simulate(path, **kw)
        dt = time.perf_counter() - t0
        peak = tracemalloc.get_traced_memory()[1]
        tracemalloc.stop()
        size = sum(v.nbytes for v in r.data.values())
        print(f"{name:<28s} {len(r):>8d} steps: peak {peak / 2**20:7.1f} MiB, result arrays "
              f"{size / 2**20:6.1f} MiB, ratio {peak / size:4.2f} (target <= 2), {dt:5.1f} s")
        del r


if __name__ == "__main__":
    main()
