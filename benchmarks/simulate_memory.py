"""Peak memory of ``contact.simulate`` against its result arrays (issue 13: within 2x).

Two 10^6-step paths, N = 2000 springs, traced with tracemalloc after a warm-up run (so that a
numba JIT compile is not counted): a held normal load with a twist sinusoid (10^4 cycles of
100 steps) and a gait-like table (force and twist change at every step), both on the spring
foundation (``method="mdr"``); then the gait table on the exact ring solver (the default of a
twisted path, ``method="exact"``) with ``exact_steps`` steps (default 10^4: the ring solver costs
~1 ms per step).

The ring solver holds dense ring-by-ring matrices (influence, its LU factors, the traction
kernels: O(rings²), ~6 MiB at the default 200 rings) whatever the path's length, as the spring
foundation holds its springs; on a path short enough to run in a benchmark they outweigh the
results. For that row the script also traces the same path a third as long (after an untraced
warm-up run) and judges what grows with the path: the peak's growth against the results' growth
between the two runs (target <= 2); peak / results is printed alongside.

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
    gait_exact = exact_path(c, phi0, exact_steps)
    short = max(exact_steps // 3, 10)
    c.simulate(exact_path(c, phi0, short), method="exact")     # warm-up (one-time set-up)
    for name, path, kw in (("held load + twist sinusoid", held, dict(n_springs=2000, method="mdr")),
                           ("gait table", gait, dict(n_springs=2000, method="mdr")),
                           ("gait table, exact rings", gait_exact, dict(method="exact"))):
        t0 = time.perf_counter()
        peak, size, n = traced(c, path, kw)
        dt = time.perf_counter() - t0
        ratio, note = peak / size, ""
        if kw["method"] == "exact":
            peak_s, size_s, _ = traced(c, exact_path(c, phi0, short), kw)
            note = (f"  [growth from {short} steps: peak +{(peak - peak_s) / 2**20:.2f} MiB, "
                    f"results +{(size - size_s) / 2**20:.2f} MiB; peak / results {ratio:.2f}]")
            ratio = (peak - peak_s) / (size - size_s)
        print(f"{name:<28s} {n:>8d} steps: peak {peak / 2**20:7.1f} MiB, result arrays "
              f"{size / 2**20:6.1f} MiB, ratio {ratio:4.2f} "
              f"{'OK' if ratio <= 2 else 'MISSED'} (target <= 2), {dt:5.1f} s" + note)


def traced(c: cl.Contact, path: cl.LoadPath, kw: dict) -> tuple[int, int, int]:
    """``(peak traced bytes, result bytes, steps)`` of one ``simulate``."""
    tracemalloc.start()
    r = c.simulate(path, **kw)
    peak = tracemalloc.get_traced_memory()[1]
    tracemalloc.stop()
    return peak, sum(v.nbytes for v in r.data.values()), len(r)


def exact_path(c: cl.Contact, phi0: float, n: int) -> cl.LoadPath:
    """The gait table of the exact-ring row, ``n`` steps."""
    ke = np.arange(1, n + 1)
    return cl.LoadPath().ramp(force=37.5, steps=1).then(cl.loadpath.Table.create(
        None, {"force": 50.0 * (0.75 + 0.25 * np.sin(2 * np.pi * ke / 700)),
               "twist": phi0 * np.sin(2 * np.pi * ke / 100)}))


if __name__ == "__main__":
    main()
