"""Spring-updates per second of the MDR foundation (contact.simulate), N = 1e3 springs × 1e5 steps.

Target (issue 4): >= 5e7 spring-updates/s on one core. A spring-update is one time step of one
Jenkins element (friction + memory). Prints the figures, the machine and the memory used.

Run: python benchmarks/foundation_speed.py [n_springs] [n_steps]
"""
from __future__ import annotations

import os
import resource
import sys
import time
import tracemalloc

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(__file__), ".."))
sys.path.insert(0, os.path.dirname(__file__))
import contactlab as cl  # noqa: E402
from _harness import machine  # noqa: E402  (one machine description for every benchmark)


def run(name, contact, path, n_springs, strategy):
    t0 = time.perf_counter()
    contact.simulate(path, n_springs=n_springs, strategy=strategy, method="mdr")
    dt = time.perf_counter() - t0
    steps = path.n_steps
    rate = n_springs * steps / dt
    print(f"{name:<44s} {strategy:<8s} {steps:>7d} steps {dt:7.2f} s {dt / steps * 1e6:7.2f} "
          f"µs/step {rate:9.3g} spring-updates/s ({rate / 5e7:5.2f}x target)")


def memory(contact, path, n_springs):
    """Peak Python/numpy allocation of one run (tracemalloc; a separate, untimed run)."""
    tracemalloc.start()
    contact.simulate(path, n_springs=n_springs, method="mdr")
    _, peak = tracemalloc.get_traced_memory()
    tracemalloc.stop()
    return peak / 2 ** 20


def main() -> None:
    N = int(sys.argv[1]) if len(sys.argv) > 1 else 1000
    steps = int(sys.argv[2]) if len(sys.argv) > 2 else 100_000
    print("machine:", machine())
    print(f"N = {N} springs, {steps} steps; single process (numpy may use one core)")
    steel = cl.Elastic(E=210e9, nu=0.3)
    c = cl.Contact(cl.profiles.Paraboloid(R=0.01), materials=(steel, steel), friction=0.2)
    a = c.normal(force=100.0).radius
    phi0 = 0.5 * 3 * 0.2 * 100.0 / (16 * c.moduli.torsional * a ** 2)
    u0 = 0.5 * 0.2 * c.moduli.normal * c.normal(force=100.0).depth / c.moduli.tangential
    spc = 200
    cyc = steps // spc
    k = np.arange(1, steps + 1)
    F = 100.0 * (0.75 + 0.25 * np.sin(2 * np.pi * k / (7 * spc)))
    tw = phi0 * np.sin(2 * np.pi * k / spc)
    cases = [
        ("oscillating twist, constant normal force",
         cl.LoadPath().ramp(force=100.0, steps=1)
         .sinusoid(twist=phi0, cycles=cyc, steps_per_cycle=spc)),
        ("oscillating shift, constant normal force",
         cl.LoadPath().ramp(force=100.0, steps=1)
         .sinusoid(displacement=u0, cycles=cyc, steps_per_cycle=spc)),
        ("oscillating torque (force control)",
         cl.LoadPath().ramp(force=100.0, steps=1).sinusoid(
             torque=0.5 * 0.75 * 0.2 * 100.0 * a, cycles=cyc, steps_per_cycle=spc)),
        ("gait-like: normal force varies every step",
         cl.LoadPath().ramp(force=75.0, steps=1).then(cl.loadpath.Table.create(
             None, {"force": F, "twist": tw}))),
    ]
    for name, path in cases:
        for strategy in ("segments", "steps"):
            run(name, c, path, N, strategy)
    mem = memory(c, cases[0][1], N)
    print(f"peak traced memory of one run ({steps} steps, N = {N}): {mem:.1f} MiB "
          f"(per-step result series: 11 x 8 B x {steps} = {11 * 8 * steps / 2**20:.1f} MiB; "
          f"spring state: a few arrays of N floats)")
    print(f"max RSS of the process: {resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024:.0f}"
          " MiB")


if __name__ == "__main__":
    main()
