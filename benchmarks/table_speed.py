"""Cubic against linear tables, side by side in one run: every speed target of issue 12.

Run from the repository root: ``python benchmarks/table_speed.py`` (``--quick`` shortens the
exact-torsion path and skips the 10^6-point tables).

Targets, each printed with its verdict:

1. per ``normal(force=)`` call after set-up, 10^4-point table: cubic within 2x of linear;
2. 10^6-point cubic table: set-up + one ``normal(force=)`` in under 5 s (linear alongside);
   2b. the same plus no-slip torsion on randomly spaced radii within ~2x of uniform ones;
3. gait ``simulate`` (10^4 steps, force and twist vary every step) on a 200-point table: cubic
   within 2x of linear, each kind timed in fresh child processes (best of 3 runs in each of two
   children, alternated; see :func:`gait_run` for why not in one process). Timed on the
   spring foundation (``method="mdr"``, 400 springs), the route the target was set for; a
   twisted path runs the exact ring solver by default
   (``method="exact"``), which is timed too, on a shorter path (its per-step cost is dominated
   by the pressure at every ring, recomputed for every step of a changing normal load);
4. a 200-point exact torque-twist curve on a 1000-point table in under 50 ms (linear and cubic);
5. the hip-cup example study on the exact ring solver and on the MDR springs, side by side
   (no target; the exact route's ring pressures come from running sums set up once).

Times are wall-clock best-of-N with the process CPU time alongside (the machine is a shared,
noisy 2-core VM: the load average is printed before and after). The tables sample
f = r²/(2R) + c r⁴ (R = 10 mm, c = 2 m⁻³) on 0..2 mm; steel on steel, μ = 0.3.
"""
from __future__ import annotations

import os
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))
sys.path.insert(0, str(Path(__file__).resolve().parent))

import contactlab as cl  # noqa: E402
from contactlab.profiles import Tabulated  # noqa: E402
from _harness import machine  # noqa: E402

STEEL = cl.Elastic(E=210e9, nu=0.3)


def table(n: int, kind: str) -> Tabulated:
    r = np.linspace(0.0, 2e-3, n)
    return Tabulated(r, r**2 / 0.02 + 2.0 * r**4, kind)


def contact(prof: Tabulated) -> cl.Contact:
    return cl.Contact(prof, (STEEL, STEEL), friction=0.3)


def verdict(ok: bool, what: str, cpu_ok: bool | None = None) -> str:
    """Verdict on wall time; with ``cpu_ok``, also on CPU time (on a loaded machine the wall
    time of a single-threaded run is inflated by the other processes, its CPU time much less)."""
    out = f"{'OK    ' if ok else 'MISSED'} {what}"
    if cpu_ok is not None and cpu_ok != ok:
        out += f" [on CPU time: {'OK' if cpu_ok else 'MISSED'}]"
    return out


def timed(fn, min_total: float = 0.3, max_runs: int = 20) -> tuple[float, float]:
    """Best-of-N (wall, CPU) seconds of ``fn()``."""
    best_w = best_c = np.inf
    total = 0.0
    for _ in range(max_runs):
        w0, c0 = time.perf_counter(), time.process_time()
        fn()
        dw, dc = time.perf_counter() - w0, time.process_time() - c0
        best_w, best_c = min(best_w, dw), min(best_c, dc)
        total += dw
        if total >= min_total:
            break
    return best_w, best_c


def load() -> str:
    return "load %.2f %.2f %.2f" % os.getloadavg()


def gait_path(c: cl.Contact, steps: int, per_cycle: int = 200) -> cl.LoadPath:
    a = c.normal(force=100.0).radius
    phi0 = 0.5 * 3 * 0.3 * 100.0 / (16 * c.moduli.torsional * a**2)
    k = np.arange(1, steps + 1)
    return cl.LoadPath().ramp(force=75.0, steps=1).then(cl.loadpath.Table.create(
        None, {"force": 100.0 * (0.75 + 0.25 * np.sin(2 * np.pi * k / (7 * per_cycle))),
               "twist": phi0 * np.sin(2 * np.pi * k / per_cycle)}))


def hip_cup() -> None:
    """The example study (200-point smoothed linear table, ramp + 5 gait cycles, 270 steps):
    ``simulate`` on the exact ring solver (default) and on the MDR springs, side by side."""
    import warnings

    from contactlab.scene import Scene
    scene = Scene.from_toml(Path(__file__).resolve().parent.parent / "examples" / "hip_cup"
                            / "hip_cup.toml")
    c, path = scene.contact(), scene.load_path
    times = {}
    for method in ("exact", "mdr"):
        with warnings.catch_warnings():     # the springs warn beyond their validity twist
            warnings.simplefilter("ignore")
            times[method] = timed(lambda: c.simulate(path, method=method), min_total=0,
                                  max_runs=2)
    ratio = times["exact"][0] / times["mdr"][0]
    print(f"5. hip-cup study ({path.n_steps} steps): exact ring solver {times['exact'][0]:.2f} s "
          f"(cpu {times['exact'][1]:.2f}), MDR springs {times['mdr'][0]:.2f} s (cpu "
          f"{times['mdr'][1]:.2f}), exact/MDR {ratio:.2f}")


GAIT_STEPS = 10_000


def gait_run(kind: str) -> None:
    """Child process of item 3: best-of-3 (wall, CPU) seconds of the gait ``simulate`` on a
    200-point ``kind`` table, printed as ``wall cpu``.

    A child per kind: the run allocates arrays of 10^4 x (nodes in contact) doubles per
    transform call, and whether such an array costs fresh pages (page faults, counted in the
    process's CPU time) depends on how the allocator's heap grew in earlier runs of the same
    process; measured in one process, the kind timed second inherits the first's heap (a
    linear run after a cubic one took half its time alone). The first spring-foundation run of
    a process compiles or loads its numba kernels: a 50-step run does that before timing."""
    import warnings
    with warnings.catch_warnings():     # the springs warn beyond their validity twist
        warnings.simplefilter("ignore")
        contact(table(200, "linear")).simulate(gait_path(contact(table(200, "linear")), 50),
                                               n_springs=400, method="mdr")
        path = gait_path(contact(table(200, "linear")), GAIT_STEPS)
        c = contact(table(200, kind))
        w, cpu = timed(lambda: c.simulate(path, n_springs=400, method="mdr"), min_total=0,
                       max_runs=3)
    print(w, cpu)


def gait_child(kind: str) -> tuple[float, float]:
    """Run :func:`gait_run` in a fresh interpreter (same environment): ``(wall, cpu)``."""
    import subprocess
    out = subprocess.run([sys.executable, __file__, "--gait-child", kind], capture_output=True,
                         text=True, check=True)
    w, cpu = out.stdout.split()[-2:]
    return float(w), float(cpu)


def main(argv: list[str]) -> int:
    if argv[:1] == ["--gait-child"]:
        gait_run(argv[1])
        return 0
    quick = "--quick" in argv
    print("Machine:", machine())
    print("Start:", load())
    # ---- 1. per call, 10^4 points
    per = {}
    for kind in ("linear", "cubic"):
        c = contact(table(10_000, kind))
        c.normal(force=100.0)                                   # set-up (memoised node values)
        forces = iter(np.linspace(50.0, 150.0, 100_000))
        per[kind] = timed(lambda: c.normal(force=float(next(forces))), min_total=0.5, max_runs=200)
    ratio = per["cubic"][0] / per["linear"][0]
    print(f"1. normal(force=) per call, 10^4 points: linear {per['linear'][0] * 1e3:.2f} ms "
          f"(cpu {per['linear'][1] * 1e3:.2f}), cubic {per['cubic'][0] * 1e3:.2f} ms "
          f"(cpu {per['cubic'][1] * 1e3:.2f}), ratio {ratio:.2f}  "
          + verdict(ratio <= 2, "(cubic within 2x)"))
    # ---- 2. 10^6-point cubic: set-up + one force
    if not quick:
        r = np.linspace(0.0, 2e-3, 1_000_000)
        f = r**2 / 0.02 + 2.0 * r**4
        big = {}
        for kind in ("linear", "cubic"):
            w0, c0 = time.perf_counter(), time.process_time()
            contact(Tabulated(r, f, kind)).normal(force=100.0)
            big[kind] = (time.perf_counter() - w0, time.process_time() - c0)
        print(f"2. 10^6 points, set-up + one force: cubic {big['cubic'][0]:.2f} s (cpu "
              f"{big['cubic'][1]:.2f}), linear {big['linear'][0]:.2f} s (cpu "
              f"{big['linear'][1]:.2f})  "
              + verdict(big["cubic"][0] < 5, "(cubic < 5 s)", big["cubic"][1] < 5))
        # randomly spaced radii (nearest nodes ~1e-15 of the radius apart): set-up + one force
        # + no-slip torsion, against the same on the uniform table, within ~2x
        rr = 2e-3 * np.sort(np.r_[0.0, np.random.default_rng(1).random(999_998), 1.0])
        spaced = {}
        for name, radii in (("uniform", r), ("random", rr)):
            w0, c0 = time.perf_counter(), time.process_time()
            c = contact(Tabulated(radii, radii**2 / 0.02 + 2.0 * radii**4, "cubic"))
            c.normal(force=100.0)
            c.torsion(force=100.0, twist=np.array([1e-5, 1e-3]), method="no-slip")
            spaced[name] = (time.perf_counter() - w0, time.process_time() - c0)
        ratio = spaced["random"][0] / spaced["uniform"][0]
        print(f"2b. 10^6-point cubic, set-up + one force + no-slip torsion: uniform "
              f"{spaced['uniform'][0]:.2f} s (cpu {spaced['uniform'][1]:.2f}), random "
              f"{spaced['random'][0]:.2f} s (cpu {spaced['random'][1]:.2f}), ratio {ratio:.2f}  "
              + verdict(ratio <= 2, "(random within ~2x of uniform)",
                        spaced["random"][1] <= 2 * spaced["uniform"][1]))
    # ---- 3. gait simulate, 200-point tables: each kind in its own child processes
    sim = {kind: (np.inf, np.inf) for kind in ("linear", "cubic")}
    for _ in range(2):                                  # alternated: both see the same load
        for kind in sim:
            w, c = gait_child(kind)
            sim[kind] = (min(sim[kind][0], w), min(sim[kind][1], c))
    ratio = sim["cubic"][0] / sim["linear"][0]
    print(f"3. gait simulate 10^4 steps, 200 points, spring foundation (method='mdr', 400 "
          f"springs): linear {sim['linear'][0]:.3f} s (cpu {sim['linear'][1]:.3f}), cubic "
          f"{sim['cubic'][0]:.3f} s (cpu {sim['cubic'][1]:.3f}), ratio {ratio:.2f}  "
          + verdict(ratio <= 2, "(cubic within 2x)",
                    sim["cubic"][1] <= 2 * sim["linear"][1]))
    steps = 100 if quick else 1000
    path = gait_path(contact(table(200, "linear")), steps)
    ex = {}
    for kind in ("linear", "cubic"):
        c = contact(table(200, kind))
        ex[kind] = timed(lambda: c.simulate(path, method="exact"), min_total=0, max_runs=1)
    ratio = ex["cubic"][0] / ex["linear"][0]
    print(f"3b. same gait, {steps} steps, exact ring solver (method='exact', the default for "
          f"twisted paths): linear {ex['linear'][0]:.2f} s (cpu {ex['linear'][1]:.2f}), cubic "
          f"{ex['cubic'][0]:.2f} s (cpu {ex['cubic'][1]:.2f}), ratio {ratio:.2f}  "
          + verdict(ratio <= 2, "(cubic within 2x)"))
    # ---- 4. exact torque-twist curve, 1000-point tables
    for kind in ("linear", "cubic"):
        c = contact(table(1000, kind))
        a = c.normal(force=100.0).radius
        phi0 = 0.5 * 3 * 0.3 * 100.0 / (16 * c.moduli.torsional * a**2)
        twist = np.linspace(0.0, 2 * phi0, 201)[1:]
        c.torsion(radius=a, twist=twist[:3], method="exact")    # set-up (rule below a)
        dt = timed(lambda: c.torsion(radius=a, twist=twist, method="exact"), min_total=0.3,
                   max_runs=10)
        print(f"4. exact torque-twist, 200 twists, 1000-point {kind}: {dt[0] * 1e3:.1f} ms "
              f"(cpu {dt[1] * 1e3:.1f})  " + verdict(dt[0] < 0.05, "(< 50 ms)", dt[1] < 0.05))
    # ---- 5. the hip-cup study (examples/hip_cup): exact ring solver against the MDR springs
    hip_cup()
    print("End:", load())
    return 0


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
