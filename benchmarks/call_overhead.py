"""Per-call cost of single normal solves and the rounding cliff of histories (issue 13).

Run from the repository root: ``python benchmarks/call_overhead.py``.

Every figure is measured side by side in this one run and reported also as a ratio to the same
closed form written in plain ``math`` (Hertz: ``a = sqrt(R d)``, ``F = 4E* a³/(3R)``), so the
machine's load cancels. Targets: ``normal(depth=)`` <= 5 µs and ``normal(force=)`` <= 8 µs on
closed-form profiles; root-solved profiles (sphere, polynomial, truncated paraboloid) <= 100 µs;
a 10^3-cycle twist history whose amplitudes differ by rounding within 1.5x of the tiled one.
"""
from __future__ import annotations

import math
import sys
import time
import timeit
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(Path(__file__).resolve().parent))

import contactlab as cl  # noqa: E402
from contactlab.profiles import (Cone, FlatPunch, Paraboloid, Polynomial, PowerLaw,  # noqa: E402
                                 Sphere, Tabulated, TruncatedParaboloid)
from _harness import machine  # noqa: E402

STEEL = cl.Elastic(E=210e9, nu=0.3)


def per_call(fn, number: int = 2000) -> float:
    return min(timeit.repeat(fn, number=number, repeat=5)) / number


def main() -> int:
    print("Machine:", machine())
    E, R = 115e9, 0.01

    def plain_hertz(d=1e-6):
        a = math.sqrt(R * d)
        return a, 4 * E * a**3 / (3 * R)

    t_plain = per_call(plain_hertz, 20000)
    print(f"\nplain-math Hertz (a, F from d): {t_plain * 1e6:.3f} µs\n")
    print(f"{'profile':48s} {'depth µs':>9s} {'force µs':>9s} {'d/plain':>8s} {'F/plain':>8s}"
          "  target")
    for prof, target in ((Paraboloid(R), (5, 8)), (Cone(0.2), (5, 8)), (PowerLaw(1e3, 4.0), (5, 8)),
                         (FlatPunch(1e-3), (5, 8)), (Sphere(R), (100, 100)),
                         (Polynomial({2: 50.0, 4: 1e6}), (100, 100)),
                         (TruncatedParaboloid(1e-4, R), (100, 100)),
                         # scaled single power terms and punches stay closed forms; sums are
                         # root-solved (Newton on the summed closed-form g')
                         (2.0 * Paraboloid(R), (5, 8)), (3.0 * FlatPunch(1e-3), (5, 8)),
                         (2.0 * Sphere(R), (100, 100)), (Paraboloid(R) + Cone(0.2), (100, 100)),
                         (Sphere(R) + PowerLaw(1e3, 4.0), (100, 100))):
        c = cl.Contact(prof, (STEEL, STEEL))
        c.normal(depth=1e-6), c.normal(force=10.0)         # warm: scalar forms, kappa, imports
        td = per_call(lambda: c.normal(depth=1e-6))
        tf = per_call(lambda: c.normal(force=10.0))
        ok = "OK" if td * 1e6 <= target[0] and tf * 1e6 <= target[1] else "MISSED"
        print(f"{prof!r:48s} {td * 1e6:9.2f} {tf * 1e6:9.2f} {td / t_plain:8.0f} {tf / t_plain:8.0f}"
              f"  <= {target[0]}/{target[1]} µs {ok}")

    print("\n10^3-cycle twist/shift histories, force 10 N, friction 0.3 (best of 5, jittered and "
          "tiled runs interleaved):")
    k = np.arange(20 * 1000)
    jit = np.sin(2 * np.pi * k / 20)                       # rounding: ~10^4 distinct values
    til = np.tile(np.sin(2 * np.pi * np.arange(20) / 20), 1000)
    r = np.linspace(0, 1e-3, 200)
    for prof in (Paraboloid(R), Tabulated(r, R - np.sqrt(R * R - r * r))):
        c = cl.Contact(prof, (STEEL, STEEL), friction=0.3)
        for x in (jit, til):                                                     # warm
            c.twist_history(twist=3e-4 * x, force=10.0).dissipated_energy
            c.shift_history(displacement=1e-6 * x, force=10.0)
        runs = {"twist": lambda x: c.twist_history(twist=3e-4 * x, force=10.0).dissipated_energy,
                "shift": lambda x: c.shift_history(displacement=1e-6 * x, force=10.0)}
        best = {(w, lab): math.inf for w in runs for lab in ("jittered", "tiled")}
        for _ in range(5):
            for w, fn in runs.items():
                for lab, x in (("jittered", jit), ("tiled", til)):
                    t0 = time.perf_counter()
                    fn(x)
                    best[w, lab] = min(best[w, lab], time.perf_counter() - t0)
        tw = {lab: best["twist", lab] for lab in ("jittered", "tiled")}
        sh = {lab: best["shift", lab] for lab in ("jittered", "tiled")}
        name = type(prof).__name__
        for what, t in (("twist_history", tw), ("shift_history", sh)):
            ratio = t["jittered"] / t["tiled"]
            print(f"  {name:11s} {what}: jittered {t['jittered'] * 1e3:7.1f} ms, tiled "
                  f"{t['tiled'] * 1e3:7.1f} ms, ratio {ratio:.2f} "
                  f"{'OK' if ratio <= 1.5 else 'MISSED'} (target <= 1.5)")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
