"""ContactLaw speed (issue 14): one step of normal + torsion + tangential with memory for n Hertz
contacts at constant normal load, compiled kernel (numba, extra ``fast``; serial and on numba's
threads, ``parallel=True``) and numpy path side by side in one run, and the per-step cost over n
(linear scaling).

    python benchmarks/law_speed.py            # n = 1e3 .. 1e6
    python benchmarks/law_speed.py --big      # adds n = 1e7 (about 10 GB of state and temporaries
                                              # at the default 16 springs; raises the budget)

Each step moves every contact along a smooth history (sinusoids with random phases, so reversals
and loop closures occur); the median of 10 steps after 2 warm-up steps is reported.
"""
from __future__ import annotations

import sys
import time
import warnings
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
import contactlab as cl                                     # noqa: E402
from benchmarks._harness import machine                     # noqa: E402
from contactlab.errors import ValidityWarning               # noqa: E402
from contactlab.physics import law_kernel                   # noqa: E402


def per_step(n: int, mode: str, steps: int = 10) -> float:
    rng = np.random.default_rng(0)
    law = cl.ContactLaw(cl.profiles.Paraboloid, R=rng.uniform(1e-3, 1e-2, n), E_star=1.15e11,
                        G_star=4.4e10, G_torsion=4.0e10, friction=0.3, fast=mode != "numpy",
                        parallel=mode == "threads")
    F = rng.uniform(1.0, 100.0, n)
    ph = rng.uniform(0.0, 2 * np.pi, n)
    times = []
    for k in range(steps + 2):
        tw = 2e-4 * np.sin(0.3 * k + ph)
        u = 1e-7 * np.cos(0.3 * k + ph)
        t0 = time.perf_counter()
        law.step(force=F, twist=tw, displacement=u)
        times.append(time.perf_counter() - t0)
    return float(np.median(times[2:]))


def main() -> None:
    warnings.simplefilter("ignore", ValidityWarning)    # combined shift + twist, documented
    sizes = [10**3, 10**4, 10**5, 10**6] + ([10**7] if "--big" in sys.argv else [])
    if "--big" in sys.argv:
        cl.set_memory_budget("inf")     # 1e7 contacts exceed the default 2 GiB on purpose
    print(machine())
    cl.ContactLaw(cl.profiles.Paraboloid, R=0.01, E_star=1e11, G_star=4e10, G_torsion=4e10,
                  friction=0.3).step(force=1.0, twist=1e-5, displacement=0.0)   # build + JIT
    modes = ["fast", "threads", "numpy"] if law_kernel.AVAILABLE else ["numpy"]
    for m in modes[:-1]:                                                          # JIT builds
        cl.ContactLaw(cl.profiles.Paraboloid, R=0.01, E_star=1e11, G_star=4e10, G_torsion=4e10,
                      friction=0.3, parallel=m == "threads").step(force=1.0, twist=1e-5,
                                                                   displacement=1e-9)
    print(f"{'n':>10} " + " ".join(f"{m + ' s/step':>16}" for m in modes)
          + f" {'ns/contact':>12}" + (f" {'numpy/fast':>11} {'fast/threads':>13}"
                                      if len(modes) == 3 else ""))
    for n in sizes:
        t = [per_step(n, m) for m in modes]
        line = f"{n:>10} " + " ".join(f"{v:>16.4g}" for v in t) + f" {1e9 * t[0] / n:>12.1f}"
        if len(t) == 3:
            line += f" {t[2] / t[0]:>11.2f} {t[0] / t[1]:>13.2f}"
        print(line, flush=True)


if __name__ == "__main__":
    main()
