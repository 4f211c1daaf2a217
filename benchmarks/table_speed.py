"""Cubic against linear tables, side by side in one run (issue 12 targets).

Run from the repository root: ``python benchmarks/table_speed.py``.

Targets:

* per ``normal(force=)`` call after set-up, 10^4-point table: cubic within 2x of linear;
* 10^6-point cubic table: set-up + one ``normal(force=)`` in under 5 s;
* gait ``simulate`` (10^4 steps, force and twist vary every step) on a 200-point table: cubic
  within 2x of linear;
* a 200-point exact torque-twist curve on a 1000-point table in under 50 ms.

The tables sample f = r²/(2R) + c r⁴ (R = 10 mm, c = 2 m⁻³) on 0..2 mm; steel on steel.
"""
from __future__ import annotations

import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))
sys.path.insert(0, str(Path(__file__).resolve().parent))

import contactlab as cl  # noqa: E402
from contactlab.profiles import Tabulated  # noqa: E402
from _harness import best_time, machine  # noqa: E402

STEEL = cl.Elastic(E=210e9, nu=0.3)


def table(n: int, kind: str) -> Tabulated:
    r = np.linspace(0.0, 2e-3, n)
    return Tabulated(r, r**2 / 0.02 + 2.0 * r**4, kind)


def contact(prof: Tabulated) -> cl.Contact:
    return cl.Contact(prof, (STEEL, STEEL), friction=0.3)


def verdict(ok: bool, what: str) -> str:
    return f"{'OK    ' if ok else 'MISSED'} {what}"


def main() -> int:
    print("Machine:", machine())
    # ---- per call, 10^4 points
    forces = iter(np.linspace(50.0, 150.0, 10_000))
    per = {}
    for kind in ("linear", "cubic"):
        c = contact(table(10_000, kind))
        c.normal(force=100.0)                                   # set-up (memoised node values)
        per[kind], _ = best_time(lambda: c.normal(force=float(next(forces))), min_total=0.5)
    ratio = per["cubic"] / per["linear"]
    print(f"normal(force=) per call, 10^4 points: linear {per['linear'] * 1e3:.2f} ms, cubic "
          f"{per['cubic'] * 1e3:.2f} ms, ratio {ratio:.2f}  "
          + verdict(ratio < 2, "(cubic within 2x)"))
    # ---- 10^6-point cubic: set-up + one force
    r = np.linspace(0.0, 2e-3, 1_000_000)
    f = r**2 / 0.02 + 2.0 * r**4
    t0 = time.perf_counter()
    contact(Tabulated(r, f, "cubic")).normal(force=100.0)
    dt = time.perf_counter() - t0
    t0 = time.perf_counter()
    contact(Tabulated(r, f, "linear")).normal(force=100.0)
    dl = time.perf_counter() - t0
    print(f"10^6 points, set-up + one force: cubic {dt:.2f} s, linear {dl:.2f} s  "
          + verdict(dt < 5, "(cubic < 5 s)"))
    # ---- gait simulate, 200-point tables
    steps, spc = 10_000, 200
    k = np.arange(1, steps + 1)
    probe = contact(table(200, "linear"))
    a = probe.normal(force=100.0).radius
    phi0 = 0.5 * 3 * 0.3 * 100.0 / (16 * probe.moduli.torsional * a**2)
    path = cl.LoadPath().ramp(force=75.0, steps=1).then(cl.loadpath.Table.create(
        None, {"force": 100.0 * (0.75 + 0.25 * np.sin(2 * np.pi * k / (7 * spc))),
               "twist": phi0 * np.sin(2 * np.pi * k / spc)}))
    sim = {}
    for kind in ("linear", "cubic"):
        c = contact(table(200, kind))
        t0 = time.perf_counter()
        c.simulate(path, n_springs=400, method="mdr")
        sim[kind] = time.perf_counter() - t0
    ratio = sim["cubic"] / sim["linear"]
    print(f"gait simulate 10^4 steps, 200 points: linear {sim['linear']:.2f} s, cubic "
          f"{sim['cubic']:.2f} s, ratio {ratio:.2f}  " + verdict(ratio < 2, "(cubic within 2x)"))
    # ---- exact torque-twist curve, 1000-point tables
    for kind in ("linear", "cubic"):
        c = contact(table(1000, kind))
        a = c.normal(force=100.0).radius
        twist = np.linspace(0.0, 2 * phi0, 201)[1:]
        c.torsion(radius=a, twist=twist[:3], method="exact")      # warm-up
        dt, _ = best_time(lambda: c.torsion(radius=a, twist=twist, method="exact"),
                          min_total=0.2, max_runs=5)
        print(f"exact torque-twist, 200 twists, 1000-point {kind}: {dt * 1e3:.1f} ms  "
              + verdict(dt < 0.05, "(< 50 ms)"))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
