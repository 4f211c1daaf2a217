"""ContactLaw speed (issue 14): one step of normal + torsion + tangential with memory for n Hertz
contacts at constant normal load, side by side in one run: the numpy path, the compiled step
(numba, extra ``fast``: a normal pass and one fused pass over both Masing channels), the same
writing into the arrays of the previous result (``step(out=...)``: no fresh output arrays), and
the compiled step on numba's threads (``parallel=True``); plus the per-step cost over n and a
linear fit ``t = t0 + c n`` of it (fixed cost, cost per contact, largest deviation); then
one changing-load step with every contact on its 16 MDR springs, numpy and compiled.

    python benchmarks/law_speed.py            # n = 1e3 .. 1e6
    python benchmarks/law_speed.py --big      # adds n = 1e7 (compiled modes only; ~6 GB used,
                                              # the memory budget is raised)

Each step moves every contact along a smooth history (sinusoids with random phases, so reversals
and loop closures occur); the median of 10 steps after 2 warm-up steps is reported. The modes
alternate per n so that the machine's load is shared between them.
"""
from __future__ import annotations

import os
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
    out = None
    for k in range(steps + 2):
        tw = 2e-4 * np.sin(0.3 * k + ph)
        u = 1e-7 * np.cos(0.3 * k + ph)
        t0 = time.perf_counter()
        res = law.step(force=F, twist=tw, displacement=u, out=out)
        times.append(time.perf_counter() - t0)
        if mode == "fast+out":
            out = res
    return float(np.median(times[2:]))


def per_spring_step(n: int, mode: str, springs: int = 16, steps: int = 6) -> float:
    """One changing-load step (every contact on its springs) of normal + torsion + tangential."""
    rng = np.random.default_rng(0)
    law = cl.ContactLaw(cl.profiles.Paraboloid, R=rng.uniform(1e-3, 1e-2, n), E_star=1.15e11,
                        G_star=4.4e10, G_torsion=4.0e10, friction=0.3, fast=mode != "numpy",
                        springs=springs)
    F = rng.uniform(1.0, 100.0, n)
    ph = rng.uniform(0.0, 2 * np.pi, n)
    times = []
    for k in range(steps + 2):
        tw = 2e-4 * np.sin(0.3 * k + ph)
        u = 1e-7 * np.cos(0.3 * k + ph)
        t0 = time.perf_counter()
        law.step(force=F * (1.0 + 0.02 * np.sin(0.5 * k)), twist=tw, displacement=u)
        times.append(time.perf_counter() - t0)
    return float(np.median(times[2:]))      # from step 2 on every contact is on springs


def springs_table() -> None:
    modes = ["numpy", "fast"] if law_kernel.AVAILABLE else ["numpy"]
    print(f"\nchanging load, 16 springs per contact\n{'n':>10} "
          + " ".join(f"{m + ' s':>12}" for m in modes) + f" {'ns/contact':>11}"
          + (f" {'numpy/fast':>11}" if len(modes) == 2 else ""))
    for n in [10**4, 10**5, 10**6]:
        t = {m: per_spring_step(n, m) for m in modes}
        line = (f"{n:>10} " + " ".join(f"{t[m]:>12.4g}" for m in modes)
                + f" {1e9 * t[modes[-1]] / n:>11.1f}")
        if len(modes) == 2:
            line += f" {t['numpy'] / t['fast']:>11.2f}"
        print(line + f"   (load {os.getloadavg()[0]:.1f})", flush=True)


def linearity(best_of: dict[int, float]) -> None:
    """Fit ``t = t0 + c n`` (relative least squares) to the fastest mode's step times and print
    the fixed cost, the cost per contact and the largest relative deviation from the fit: the
    per-step cost is linear in n when the deviation is of the order of the timing noise."""
    n = np.array(sorted(best_of), float)
    t = np.array([best_of[k] for k in sorted(best_of)])
    A = np.stack([np.ones_like(n), n], axis=1) / t[:, None]
    (t0, c), *_ = np.linalg.lstsq(A, np.ones_like(t), rcond=None)
    if t0 < 0:                          # noise at small n: no fixed cost, cost per contact only
        t0, c = 0.0, float(np.sum(n / t) / np.sum((n / t) ** 2))
    dev = np.max(np.abs((t0 + c * n) / t - 1.0))
    print(f"linear fit over n = {int(n[0])}..{int(n[-1])}: t = {1e6 * t0:.1f} us + "
          f"{1e9 * c:.1f} ns x n, largest deviation {100 * dev:.0f} %", flush=True)


def main() -> None:
    warnings.simplefilter("ignore", ValidityWarning)    # combined shift + twist, documented
    sizes = [10**3, 10**4, 10**5, 10**6] + ([10**7] if "--big" in sys.argv else [])
    # 1e7 contacts (--big) and 1e6 contacts on numpy springs exceed the default budget on purpose
    cl.set_memory_budget("inf")
    print(machine(), f"load average {os.getloadavg()[0]:.1f}")
    modes = (["numpy", "fast", "fast+out", "threads"] if law_kernel.AVAILABLE else ["numpy"])
    for m in modes:                                                         # build + JIT
        cl.ContactLaw(cl.profiles.Paraboloid, R=0.01, E_star=1e11, G_star=4e10, G_torsion=4e10,
                      friction=0.3, fast=m != "numpy", parallel=m == "threads").step(
            force=1.0, twist=1e-5, displacement=1e-9)
    print(f"{'n':>10} " + " ".join(f"{m + ' s':>12}" for m in modes)
          + f" {'ns/contact':>11}" + (f" {'numpy/fast':>11} {'fast/out':>9} {'fast/thr':>9}"
                                      if len(modes) == 4 else ""))
    best_of = {}
    for n in sizes:
        t = {m: (per_step(n, m) if (n < 10**7 or m != "numpy") else float("nan"))
             for m in modes}
        best = t.get("fast+out", t["numpy"])
        best_of[n] = best
        line = f"{n:>10} " + " ".join(f"{t[m]:>12.4g}" for m in modes) + f" {1e9 * best / n:>11.1f}"
        if len(modes) == 4:
            line += (f" {t['numpy'] / t['fast']:>11.2f} {t['fast'] / t['fast+out']:>9.2f}"
                     f" {t['fast'] / t['threads']:>9.2f}")
        print(line + f"   (load {os.getloadavg()[0]:.1f})", flush=True)
    linearity(best_of)
    springs_table()


if __name__ == "__main__":
    main()
