"""ContactLaw speed and memory (issues 14, 29): the law's rows of issue 29's table, each as a ratio
against its floor measured interleaved in the same run, with a verdict against the goal.

    python benchmarks/law_speed.py              # the issue-29 rows at n = 10^6 (compiled + numpy)
    python benchmarks/law_speed.py --scaling    # also the per-n table (10^3 .. 10^6) of issue 14
    python benchmarks/law_speed.py --scaling --big   # adds n = 10^7 (compiled only, ~9 GB)
    python benchmarks/law_speed.py --n 1e5      # the rows at another n (the goals stay 10^6's)
    python benchmarks/law_speed.py --passes     # only the constant-load step by parts (~15 s)
    python benchmarks/law_speed.py --changing   # the changing-load rows only (~half the time)

Rows (10^6 Hertz contacts, normal + torsion + tangential with memory, sinusoidal histories with
random phases so that reversals and loop closures occur):

* constant-load step: numpy, compiled, compiled with ``out=`` (no fresh result arrays) and the
  compiled step on numba's threads, 1 and 2 of them (``numba.set_num_threads``); goal <= 40 ms.
* changing-load step (every contact's load changes, then a tenth of them; 16 springs each): the
  FIRST such step (the switch from the exact law onto the springs, the spring rows allocated for
  the contacts that switch) and the following ones, compiled; goal <= 100 ms each. numpy's
  first changing step takes tens of seconds and ~4 GB at 10^6: ``--numpy-springs``
  adds it.
* GPU (``backend="cupy"``, 10^7 contacts): measured when CuPy finds a device, otherwise
  printed as skipped; always the estimate of ``benchmarks/law_gpu.py`` (counted traffic).
* the first changing-load step of a law built with ``spring_reserve=1.0`` (every contact's
  spring rows allocated and faulted in with the law), compiled on one thread and on the most
  threads, with the construction time of that law against a lazy one's.
* memory: tracemalloc's peak per contact of a law through constant and changing-load steps
  (and ``law_memory``, what the budget check counts); goal <= 1.5 GB at 10^6.

The constant-load rows' laws step in turn, one step each per round (the order rotated each
round), so that a change in the shared machine's speed falls on every mode alike; their five
laws are held at once (~0.5 GB each at 10^6 contacts, ~2.5 GB together, above the default memory
budget, which this benchmark lifts). Each row
prints the step's best wall time and its CPU time (this thread's; the process's on
numba's threads: a shared machine's other processes lengthen the wall time, far less the CPU
time), and two floors timed right before each of its steps (best over the row), so both see the
same machine load: one numpy pass over 10^6 floats (``np.multiply(x, 2.0, out=y)``), and the
bandwidth floor, the bytes the step must move at the least (counted per contact: ``CONST_READ``,
``CONST_WRITE``, plus the spring row read and written of a contact on springs) over the copy rate
numpy gets between two 128 MB arrays. The wall time's ratio to each floor, the minor page faults
of the best step (fresh arrays of 10^6 entries fault in their pages on the first write) and a
verdict of the wall and of the CPU time against the goal follow; the header names the machine
and its load. Each time is the best of its steps after two warm-up steps; the kernels are
compiled (or loaded from the disk cache) on a small law first.
"""
from __future__ import annotations

import os
import resource
import sys
import time
import warnings
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
import contactlab as cl                                     # noqa: E402
from benchmarks._harness import machine                     # noqa: E402
from contactlab.errors import ValidityWarning               # noqa: E402
from contactlab.effects import law_pool                     # noqa: E402
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
#: bytes one constant-load step of a Hertz contact must move at the least (both channels, by
#: force): read the three controls, five per-contact parameters (kc, E*, mu, G*, G_t), the held
#: depth, both channels' stack scalars (x, y, w 8 B each, last 1, depth 8, overflow 1) and the top
#: turning point (X, Y); write the nine outputs (8 x 8 B + exact 1 B), the stack scalars back and
#: the one-byte flag (issue 29's "bandwidth floor for the state it must touch")
CONST_READ = 3 * 8 + 5 * 8 + 8 + 2 * 34 + 2 * 16
CONST_WRITE = 8 * 8 + 1 + 2 * 34 + 1
_BW: dict[str, np.ndarray] = {}


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


def bandwidth(reps: int = 3) -> float:
    """Memory bandwidth, bytes/s (read + written): numpy copying 128 MB into another 128 MB
    array (both allocated and touched once, outside the timing: no page faults), best of
    ``reps``; far beyond the caches, so it is the DRAM rate a pass over a 10^6-contact state
    gets."""
    if not _BW:
        _BW["x"] = np.ones(16 * 2**20)
        _BW["y"] = np.zeros_like(_BW["x"])
    x, y = _BW["x"], _BW["y"]
    best = np.inf
    for _ in range(reps):
        t0 = time.perf_counter()
        np.copyto(y, x)
        best = min(best, time.perf_counter() - t0)
    return 2 * x.nbytes / best


def _law(n: int, mode: str, **kw) -> cl.ContactLaw:
    rng = np.random.default_rng(0)
    return cl.ContactLaw(cl.profiles.Paraboloid, R=rng.uniform(1e-3, 1e-2, n), E_star=1.15e11,
                         G_star=4.4e10, G_torsion=4.0e10, friction=0.3, fast=mode != "numpy",
                         parallel=mode.startswith("threads"), **kw)


def _controls(n: int, k: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    rng = np.random.default_rng(0)
    F = rng.uniform(1.0, 100.0, n)
    ph = rng.uniform(0.0, 2 * np.pi, n)
    return F, 2e-4 * np.sin(0.3 * k + ph), 1e-7 * np.cos(0.3 * k + ph)


def _cpu(mode: str) -> float:
    """CPU seconds: of this thread (serial modes), of the process (numba's threads)."""
    return time.process_time() if mode.startswith("threads") else time.thread_time()


def _faults() -> int:
    return resource.getrusage(resource.RUSAGE_SELF).ru_minflt


class Row:
    """Best wall and CPU time of a row's steps, the floors measured right before each step
    (best of the row), and the minor page faults of the best-wall step."""

    def __init__(self) -> None:
        self.t = self.cpu = self.floor = np.inf
        self.bw = 0.0
        self.faults = 0
        self.built = 0.0            # wall time of the law's construction (changing rows)

    def floors(self) -> None:
        self.floor = min(self.floor, floor_pass())
        self.bw = max(self.bw, bandwidth())

    def add(self, t: float, cpu: float, faults: int) -> None:
        if t < self.t:
            self.faults = faults
        self.t, self.cpu = min(self.t, t), min(self.cpu, cpu)


def _timed(mode: str, law: cl.ContactLaw, **kw) -> tuple[object, float, float, int]:
    """``law.step(**kw)``: (its result, wall time, CPU time, minor page faults)."""
    f0 = _faults()
    c0 = _cpu(mode)
    t0 = time.perf_counter()
    res = law.step(**kw)
    t = time.perf_counter() - t0
    return res, t, _cpu(mode) - c0, _faults() - f0


def constant_rows(n: int, modes: list[str], steps: int = 6) -> dict[str, Row]:
    """Best constant-load step (wall, CPU) of each mode after two warm-up steps, floors
    interleaved. The modes' laws step in turn (round-robin, the order rotated each step): this
    shared machine's speed changes within minutes (the same compiled step measured at ~60 and
    ~88 ms in consecutive processes, the serial and the threaded build alike when alternated in
    one), and such a change then falls on every mode alike instead of on the rows that ran
    during it."""
    laws = {m: _law(n, m) for m in modes}
    F = _controls(n, 0)[0]
    rows = {m: Row() for m in modes}
    outs: dict[str, object] = dict.fromkeys(modes)
    for k in range(steps + 2):
        _, tw, u = _controls(n, k)
        for m in modes[k % len(modes):] + modes[:k % len(modes)]:
            _threads(m)
            rows[m].floors()
            res, t, c, f = _timed(m, laws[m], force=F, twist=tw, displacement=u, out=outs[m])
            if m == "fast+out":
                outs[m] = res
            if k >= 2:
                rows[m].add(t, c, f)
    return rows


def changing_row(n: int, mode: str, steps: int = 4, frac: float = 1.0,
                 reserve: float = 0.0) -> tuple[Row, Row]:
    """(the first changing-load step, the best later one): the force of every contact
    (``frac``: of that fraction of the contacts, the rest held) changes from step 2 on;
    ``reserve``: the law's ``spring_reserve`` (its construction timed as the rows' ``t0``)."""
    t0 = time.perf_counter()
    law = _law(n, mode, spring_reserve=reserve)
    built = time.perf_counter() - t0
    F = _controls(n, 0)[0]
    m = round(frac * n)
    first, later = Row(), Row()
    for k in range(steps + 2):
        _, tw, u = _controls(n, k)
        Fk = F.copy()
        if k >= 2:
            Fk[:m] *= 1.0 + 0.02 * np.sin(0.5 * k)
        row = first if k == 2 else later
        row.floors()
        _, t, c, f = _timed(mode, law, force=Fk, twist=tw, displacement=u)
        if k >= 2:
            row.add(t, c, f)
    first.built = later.built = built
    return first, later


def memory_row(n: int, frac: float = 1.0) -> tuple[float, float, float]:
    """tracemalloc peaks per contact (bytes): the law and constant-load steps, then the first
    changing-load steps (every contact, or the fraction ``frac`` of them, onto its springs; plus
    the spring pool's memory-mapped arrays, which tracemalloc does not count); and
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
    # the pool's large arrays are memory maps of their own (law_pool._mapped), which
    # tracemalloc does not see: their bytes are added
    pool = law._pool
    changing += sum(v.nbytes for v in (pool.owner, *pool.rows.values())
                    if v.nbytes >= law_pool._MAP_BYTES)
    return const / n, changing / n, law_memory(n, DEFAULT_MEMORY, DEFAULT_SPRINGS, m) / n


def _verdict(ok: bool) -> str:
    return "meets the goal" if ok else "MISSES the goal"


def _print(name: str, row: Row, traffic: float, goal: float) -> None:
    """One row: wall and CPU time, the numpy pass and the bandwidth floor of ``traffic`` bytes
    with the wall time's ratio to each, the verdict of the wall time against ``goal`` and of the
    CPU time (the step's own work, without the shared machine's other processes)."""
    bw_floor = traffic / row.bw
    print(f"{name:<40} {1e3 * row.t:>7.1f} {1e3 * row.cpu:>7.1f} {1e3 * row.floor:>6.2f} "
          f"{row.t / row.floor:>6.0f}x {1e3 * bw_floor:>6.1f} {row.t / bw_floor:>5.1f}x "
          f"{row.faults:>7d}  <= {1e3 * goal:.0f} ms: wall {_verdict(row.t <= goal)}, "
          f"CPU {_verdict(row.cpu <= goal)}  (load {os.getloadavg()[0]:.1f})", flush=True)


def _modes(fast: bool) -> list[str]:
    """numpy, compiled (fresh outputs / out=), compiled on numba's threads (1 and 2)."""
    if not fast:
        return ["numpy"]
    import numba
    return ["numpy", "fast", "fast+out"] + [f"threads x{k}" for k in (1, 2)
                                             if k <= numba.get_num_threads()]


def _threads(mode: str) -> None:
    if mode.startswith("threads"):
        import numba
        numba.set_num_threads(int(mode.split("x")[1]))


def issue_rows() -> None:
    from contactlab.effects.law import DEFAULT_SPRINGS
    from contactlab.effects.law_pool import pool_row_bytes
    n = int(float(sys.argv[sys.argv.index("--n") + 1])) if "--n" in sys.argv else 10**6
    fast = law_kernel.AVAILABLE
    modes = _modes(fast)
    print(f"\nissue 29, ContactLaw rows at n = {n}: best wall and CPU time of the step (CPU of "
          "this thread; of the process on numba's threads), the numpy pass over 10^6 floats "
          "('pass') and the bandwidth floor of the bytes the step must move ('bw floor': bytes "
          "per contact x n / the measured copy rate), both timed before each step, the wall "
          "time's ratio to each, minor page faults of the best step")
    for m in modes:                                 # build + JIT
        w = _law(64, m)
        w.step(force=1.0, twist=1e-5, displacement=1e-9)
        w.step(force=2.0, twist=1e-5, displacement=1e-9)                    # switch + springs
    const_b = CONST_READ + CONST_WRITE
    print(f"constant-load step: {const_b} B per contact moved at the least "
          f"({CONST_READ} read, {CONST_WRITE} written)")
    print(f"{'row':<40} {'wall':>7} {'CPU':>7} {'pass':>6} {'ratio':>7} {'bw fl':>6} "
          f"{'ratio':>6} {'faults':>7}  goal")
    changing_only = "--changing" in sys.argv
    if not changing_only:
        for m, row in constant_rows(n, modes).items():
            _print(f"constant-load step, {m}", row, const_b * n, 0.040)
    # a contact on its springs also reads and writes its spring row (3 floats per spring and
    # the row's scalars)
    spr_b = 2 * pool_row_bytes(DEFAULT_SPRINGS)
    print(f"changing-load step: + {spr_b} B per contact on springs (its spring row read and "
          "written)")
    # every contact's load changes, or a tenth of them (a packing where few contacts switch:
    # the spring rows are allocated for those only)
    for frac in (1.0, 0.1):
        for m in modes:
            if m == "fast+out" or (m == "numpy" and "--numpy-springs" not in sys.argv):
                continue
            _threads(m)
            first, later = changing_row(n, m, frac=frac)
            for name, row in (("FIRST changing step", first), ("later changing step", later)):
                _print(f"{name}, {m}, {frac:.0%}", row, (const_b + frac * spr_b) * n, 0.100)
    # the opt-in reservation: every contact's spring rows allocated and faulted in with the law
    # (ContactLaw(..., spring_reserve=1.0)); its construction time, then its first step
    for m in modes:
        if m != "fast" and not (m == modes[-1] and m.startswith("threads")):   # most threads
            continue
        _threads(m)
        lazy = time.perf_counter()
        _law(n, m)
        lazy = time.perf_counter() - lazy
        first, _ = changing_row(n, m, steps=1, reserve=1.0)
        print(f"spring_reserve=1.0, {m}: the law built in {1e3 * first.built:.0f} ms (lazy: "
              f"{1e3 * lazy:.0f} ms), {pool_row_bytes(DEFAULT_SPRINGS) * n / 1e9:.2f} GB of "
              "rows held from the start")
        _print(f"FIRST step reserved, {m}, 100%", first, (const_b + spr_b) * n,
               0.100)
    if fast and not changing_only:
        for frac in (1.0, 0.1):
            const, changing, counted = memory_row(n, frac)
            for name, b in (("memory, law + constant-load steps", const),
                            (f"memory, law + changing-load steps, {frac:.0%}", changing)):
                print(f"{name:<44} {b * n / 1e9:>8.2f}GB {b:>6.0f}B/contact  <= 1.5 GB "
                      f"{_verdict(b * n <= 1.5e9)}")
            print(f"{f'memory counted (law_memory), {frac:.0%}':<44} {counted * n / 1e9:>8.2f}GB "
                  f"{counted:>6.0f}B/contact")


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


def passes(n: int = 10**6, steps: int = 8) -> None:
    """``--passes``: where one compiled constant-load step goes, on one thread with ``out=``:
    CPU time of this thread per part (best of ``steps`` after two warm-up steps), the kernels
    wrapped by timers: the normal pass (numpy's powers, the compiled cube-root loop and the
    compiled loop), the kernel loop and the cube-root loop alone, the tangential and the
    torsion pass, the whole step and what is left of it (the step's Python and numpy around
    the passes)."""
    law = _law(n, "fast")
    times: dict[str, list[float]] = {}

    def timed(name: str, f):
        def g(*a, **k):
            t0 = time.thread_time()
            r = f(*a, **k)
            times.setdefault(name, []).append(time.thread_time() - t0)
            return r
        return g

    kernels = list(law_kernel._kernels(False))
    kernels[0] = timed("normal pass, compiled loop", kernels[0])
    kernels[9] = timed("normal pass, compiled loop", kernels[9])
    kernels[10] = timed("normal pass, its cube-root loop", kernels[10])
    kernels[1] = timed("tangential pass", kernels[1])
    kernels[7] = timed("tangential pass", kernels[7])      # (its n = 2 build)
    kernels[5] = timed("torsion pass (and dW, exact)", kernels[5])
    kernels[8] = timed("torsion pass (and dW, exact)", kernels[8])
    saved = law_kernel._KERNELS[False], law_kernel.normal_pass
    law_kernel._KERNELS[False] = tuple(kernels)
    law_kernel.normal_pass = timed("normal pass (numpy powers + loop)", law_kernel.normal_pass)
    try:
        out = None
        for k in range(steps + 2):
            F, tw, u = _controls(n, k)
            t0 = time.thread_time()
            out = law.step(force=F, twist=tw, displacement=u, out=out)
            times.setdefault("the step", []).append(time.thread_time() - t0)
    finally:
        law_kernel._KERNELS[False], law_kernel.normal_pass = saved
    best = {name: 1e3 * min(v[2:]) for name, v in times.items()}
    print(f"\nthe compiled constant-load step by parts, {n} Hertz contacts, one thread, out=, "
          f"CPU ms, best of {steps} (load {os.getloadavg()[0]:.1f})")
    for name in ("normal pass (numpy powers + loop)", "normal pass, compiled loop",
                 "normal pass, its cube-root loop", "tangential pass",
                 "torsion pass (and dW, exact)", "the step"):
        print(f"  {name:<36} {best[name]:7.2f}")
    rest = best["the step"] - sum(best[k] for k in ("normal pass (numpy powers + loop)",
                                                     "tangential pass",
                                                     "torsion pass (and dW, exact)"))
    print(f"  {'the rest (Python, checks, numpy)':<36} {rest:7.2f}", flush=True)


def main() -> None:
    warnings.simplefilter("ignore", ValidityWarning)    # combined shift + twist, documented
    if "--passes" in sys.argv:
        cl.set_memory_budget("inf")
        print(machine(), f"load average {os.getloadavg()[0]:.1f}")
        passes(int(float(sys.argv[sys.argv.index("--n") + 1])) if "--n" in sys.argv else 10**6)
        return
    # 10^6 contacts on numpy springs and 10^7 contacts exceed the default budget on purpose
    cl.set_memory_budget("inf")
    print(machine(), f"load average {os.getloadavg()[0]:.1f}")
    issue_rows()
    if "--changing" in sys.argv:
        return
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
