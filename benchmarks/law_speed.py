"""ContactLaw speed and memory (issues 14, 29): the law's rows of issue 29's table, each as a ratio
against its floor measured interleaved in the same run, with a verdict against the goal.

    python benchmarks/law_speed.py              # the issue-29 rows at n = 10^6 (compiled + numpy)
    python benchmarks/law_speed.py --scaling    # also the per-n table (10^3 .. 10^6) of issue 14
    python benchmarks/law_speed.py --scaling --big   # adds n = 10^7 (compiled only, ~9 GB)
    python benchmarks/law_speed.py --n 1e5      # the rows at another n (the goals stay 10^6's)

Rows (10^6 Hertz contacts, normal + torsion + tangential with memory, sinusoidal histories with
random phases so that reversals and loop closures occur):

* constant-load step: numpy, compiled, compiled with ``out=`` (no fresh result arrays) and the
  compiled step on numba's threads; goal <= 40 ms.
* changing-load step (every contact's load changes, then a tenth of them; 16 springs each): the
  FIRST such step (the switch from the exact law onto the springs, the spring rows allocated for
  the contacts that switch) and the following ones, compiled; goal <= 100 ms each. numpy's
  first changing step takes tens of seconds and ~4 GB at 10^6: ``--numpy-springs``
  adds it.
* GPU (``backend="cupy"``, 10^7 contacts): measured when CuPy finds a device, otherwise
  printed as skipped; always the estimate of ``benchmarks/law_gpu.py`` (counted traffic).
* memory: tracemalloc's peak per contact of a law through constant and changing-load steps
  (and ``law_memory``, what the budget check counts); goal <= 1.5 GB at 10^6.

The floor is one numpy pass over 10^6 floats (``np.multiply(x, 2.0, out=y)``), timed right before
each measured step (best of its repetitions), so both see the same machine load. Each time is the
best of its steps after two warm-up steps (each row also prints the step's CPU time, which a
shared machine's load disturbs far less than the wall time); the kernels are compiled (or
loaded from the disk cache) on a small law first.
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
        t = {m: (per_spring_step(n, m) if n < 10**6 or m != "numpy"
                 or "--numpy-springs" in sys.argv else float("nan")) for m in modes}
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


FLOOR_N = 10**6


def floor_pass(reps: int = 5) -> float:
    """One numpy pass over 10^6 floats (read one array, write another), best of ``reps``."""
    x = np.random.default_rng(1).uniform(size=FLOOR_N)
    y = np.empty_like(x)
    best = np.inf
    for _ in range(reps):
        t0 = time.perf_counter()
        np.multiply(x, 2.0, out=y)
        best = min(best, time.perf_counter() - t0)
    return best


def _law(n: int, mode: str, **kw) -> cl.ContactLaw:
    rng = np.random.default_rng(0)
    return cl.ContactLaw(cl.profiles.Paraboloid, R=rng.uniform(1e-3, 1e-2, n), E_star=1.15e11,
                         G_star=4.4e10, G_torsion=4.0e10, friction=0.3, fast=mode != "numpy",
                         parallel=mode == "threads", **kw)


def _controls(n: int, k: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    rng = np.random.default_rng(0)
    F = rng.uniform(1.0, 100.0, n)
    ph = rng.uniform(0.0, 2 * np.pi, n)
    return F, 2e-4 * np.sin(0.3 * k + ph), 1e-7 * np.cos(0.3 * k + ph)


def constant_row(n: int, mode: str, steps: int = 6) -> tuple[float, float, float]:
    """(best step time, the floor measured right before it, best step CPU time of this
    thread) at constant load. On a shared machine the CPU time varies far less than the wall
    time (other processes' load); with ``threads`` it counts the calling thread only."""
    law = _law(n, mode)
    F = _controls(n, 0)[0]
    best, floor, cpu, out = np.inf, np.inf, np.inf, None
    for k in range(steps + 2):
        _, tw, u = _controls(n, k)
        fl = floor_pass()
        c0 = time.thread_time()
        t0 = time.perf_counter()
        res = law.step(force=F, twist=tw, displacement=u, out=out)
        t = time.perf_counter() - t0
        c = time.thread_time() - c0
        if mode == "fast+out":
            out = res
        if k >= 2:
            best, floor, cpu = min(best, t), min(floor, fl), min(cpu, c)
    return best, floor, cpu


def changing_row(n: int, mode: str, steps: int = 4, frac: float = 1.0
                 ) -> tuple[float, float, float, float, float]:
    """(first changing-load step, best later changing-load step, floor, and the CPU times of
    this thread of the first and the best later step): the force of every contact (``frac``: of
    that fraction of the contacts, the rest held) changes from step 2 on."""
    law = _law(n, mode)
    F = _controls(n, 0)[0]
    m = round(frac * n)
    times, cpus, floor = [], [], np.inf
    for k in range(steps + 2):
        _, tw, u = _controls(n, k)
        fl = floor_pass()
        Fk = F.copy()
        if k >= 2:
            Fk[:m] *= 1.0 + 0.02 * np.sin(0.5 * k)
        c0 = time.thread_time()
        t0 = time.perf_counter()
        law.step(force=Fk, twist=tw, displacement=u)
        times.append(time.perf_counter() - t0)
        cpus.append(time.thread_time() - c0)
        floor = min(floor, fl)
    return times[2], min(times[3:]), floor, cpus[2], min(cpus[3:])


def memory_row(n: int, frac: float = 1.0) -> tuple[float, float, float]:
    """tracemalloc peaks per contact (bytes): the law and constant-load steps, then the first
    changing-load steps (every contact, or the fraction ``frac`` of them, onto its springs); and
    law_memory per contact (its spring rows for those contacts included)."""
    import tracemalloc
    from contactlab.effects.law import DEFAULT_MEMORY, DEFAULT_SPRINGS, law_memory
    F, tw, u = _controls(n, 0)
    tracemalloc.start()
    try:
        law = _law(n, "fast")
        out = None
        for k in range(3):
            out = law.step(force=F, twist=tw * (1 - 0.1 * k), displacement=u, out=out)
        const = tracemalloc.get_traced_memory()[1]
        m = round(frac * n)
        for k in range(3):
            Fk = F.copy()
            Fk[:m] *= 1.01 + 0.01 * k
            out = law.step(force=Fk, twist=tw, displacement=u, out=out)
        changing = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    return const / n, changing / n, law_memory(n, DEFAULT_MEMORY, DEFAULT_SPRINGS, m) / n


def _verdict(ok: bool) -> str:
    return "meets the goal" if ok else "MISSES the goal"


def issue_rows() -> None:
    n = int(float(sys.argv[sys.argv.index("--n") + 1])) if "--n" in sys.argv else 10**6
    fast = law_kernel.AVAILABLE
    print(f"\nissue 29, ContactLaw rows at n = {n} (floor: one numpy pass over 10^6 floats, "
          "timed before each step)")
    for m in (["numpy", "fast", "fast+out", "threads"] if fast else ["numpy"]):    # build + JIT
        w = _law(64, m)
        w.step(force=1.0, twist=1e-5, displacement=1e-9)
        w.step(force=2.0, twist=1e-5, displacement=1e-9)                    # switch + springs
    print(f"{'row':<44} {'time':>10} {'floor':>9} {'ratio':>8}  goal     verdict")
    for m in (["numpy", "fast", "fast+out", "threads"] if fast else ["numpy"]):
        t, fl, cpu = constant_row(n, m)
        print(f"{'constant-load step, ' + m:<44} {1e3 * t:>8.1f}ms {1e3 * fl:>7.2f}ms "
              f"{t / fl:>7.0f}x  <= 40 ms {_verdict(t <= 0.040)}   "
              f"(CPU {1e3 * cpu:.1f} ms; load {os.getloadavg()[0]:.1f})", flush=True)
    modes = (["fast", "threads"] if fast else []) + (
        ["numpy"] if "--numpy-springs" in sys.argv or not fast else [])
    # every contact's load changes, or a tenth of them (a packing where few contacts switch:
    # the spring rows are allocated for those only)
    for frac in (1.0, 0.1):
        for m in modes:
            first, later, fl, c_first, c_later = changing_row(n, m, frac=frac)
            for name, t, c in (("FIRST changing-load step", first, c_first),
                               ("later changing-load step", later, c_later)):
                print(f"{f'{name}, {m}, {frac:.0%}':<44} {1e3 * t:>8.1f}ms {1e3 * fl:>7.2f}ms "
                      f"{t / fl:>7.0f}x  <= 100 ms {_verdict(t <= 0.100)}   "
                      f"(CPU {1e3 * c:.1f} ms; load {os.getloadavg()[0]:.1f})", flush=True)
    if fast:
        for frac in (1.0, 0.1):
            const, changing, counted = memory_row(n, frac)
            for name, b in (("memory, law + constant-load steps", const),
                            (f"memory, law + changing-load steps, {frac:.0%}", changing)):
                print(f"{name:<44} {b * n / 1e9:>8.2f}GB {'':>9} {b:>6.0f}B/contact  <= 1.5 GB "
                      f"{_verdict(b * n <= 1.5e9)}")
            print(f"{f'memory counted (law_memory), {frac:.0%}':<44} {counted * n / 1e9:>8.2f}GB "
                  f"{'':>9} {counted:>6.0f}B/contact")


def scaling() -> None:
    sizes = [10**3, 10**4, 10**5, 10**6] + ([10**7] if "--big" in sys.argv else [])
    modes = (["numpy", "fast", "fast+out", "threads"] if law_kernel.AVAILABLE else ["numpy"])
    print(f"\n{'n':>10} " + " ".join(f"{m + ' s':>12}" for m in modes)
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


def main() -> None:
    warnings.simplefilter("ignore", ValidityWarning)    # combined shift + twist, documented
    # 10^6 contacts on numpy springs and 10^7 contacts exceed the default budget on purpose
    cl.set_memory_budget("inf")
    print(machine(), f"load average {os.getloadavg()[0]:.1f}")
    issue_rows()
    # the GPU row (backend="cupy", 10^7 contacts): measured where CuPy finds a device, else
    # a line saying it was skipped; and the estimate from the counted memory traffic
    from benchmarks.law_gpu import estimate, gpu_rows
    print("\nGPU (ContactLaw(..., backend='cupy')):")
    estimate()
    gpu_rows(10**7)
    if "--scaling" in sys.argv:
        scaling()


if __name__ == "__main__":
    main()
