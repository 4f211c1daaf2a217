"""Sweep scaling: a Dask LocalCluster with 1 and 2 workers, scheduler overhead, tiny tasks.

Run from the repository root (needs the extras dist and data):
``python benchmarks/sweep_scaling.py`` (``--quick`` for a smaller run). Prints the machine, then

1. 200 torsional loops (exact Masing history, 10 twist cycles of 100 steps each, amplitude x
   friction grid), run serially in this process and on LocalClusters side by side: 1 worker with
   Dask's default worker environment, 1 and 2 workers with ``MALLOC_TRIM_THRESHOLD_`` left unset
   (Dask's nanny sets it to 65536 by default, which makes glibc return freed memory at once and
   costs numpy-heavy studies ~20 % CPU); wall times, the 2-vs-1 speed-up, and the CPU time
   the points took on the workers (summed per point) against the serial one;
2. the scheduler's per-task overhead: 400 empty points, one point per task, on the 1-worker
   cluster and on a local process pool of 1;
3. the overhead of whole sweeps (wall and CPU time), from microsecond to millisecond points, serially in this process
   and on the 1-worker cluster without ``MALLOC_TRIM_THRESHOLD_`` (so that the figure is the
   sweep's own cost, not the allocator's): overhead = (workers x wall - C) / C, where C is the
   compute of the points, the study called at every point in a plain loop here
   (``[study(**p) for p in points]``); best of five, alternating. Each overhead is also given in
   CPU time (this process, which runs the client and the scheduler, plus the worker), which the
   load of other processes inflates far less than wall time. The torsion and design points are
   also run one point per task, to show what batching saves.

Clusters are started before the timings (their start-up is printed separately).
"""
from __future__ import annotations

import argparse
import os
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "benchmarks"))

import contactlab  # noqa: E402
from _harness import machine  # noqa: E402


def torsion_loop(amplitude, friction, cycles=10, steps_per_cycle=100):
    """One torsional fretting loop: dissipated energy and peak torque (a sweep study)."""
    contact = contactlab.Contact(contactlab.profiles.Paraboloid(R=0.01),
                                 materials=(contactlab.Elastic(E=210e9, nu=0.3),) * 2,
                                 friction=friction)
    t = np.linspace(0.0, 2 * np.pi * cycles, cycles * steps_per_cycle + 1)
    h = contact.twist_history(twist=amplitude * np.sin(t), force=100.0, method="exact")
    return {"energy": h.dissipated_energy[-1], "torque_max": np.max(np.abs(h.torque))}


def timed_loop(amplitude, friction):
    """:func:`torsion_loop` and the CPU seconds it took where it ran (column ``cpu``: process
    time, which other processes on a busy machine do not inflate as they do wall time)."""
    t0 = time.process_time()
    out = torsion_loop(amplitude, friction)
    out["cpu"] = time.process_time() - t0
    return out


def empty(i):
    return {"i": i}


def torsion_point(force):
    """Small task (milliseconds): the exact torque of a monotone twist at one preload."""
    contact = contactlab.Contact(contactlab.profiles.Paraboloid(R=0.01),
                                 materials=(contactlab.Elastic(E=210e9, nu=0.3),) * 2,
                                 friction=0.3)
    return {"torque": float(contact.torsion(force=force, twist=1e-3, method="exact").torque)}


def hertz_point(force):
    """Tiny task: the Hertz contact radius in closed form."""
    E_star = 210e9 / (2 * (1 - 0.3**2))
    return {"radius": (3 * force * 0.01 / (4 * E_star)) ** (1 / 3)}


def hertz_profile(force):
    """Small numpy task (~10 us): the Hertz pressure at 64 radii, its mean and the radius."""
    E_star = 210e9 / (2 * (1 - 0.3**2))
    a = (3 * force * 0.01 / (4 * E_star)) ** (1 / 3)
    p = 2 * E_star * a / (np.pi * 0.01) * np.sqrt(1 - np.linspace(0.0, 1.0, 64) ** 2)
    return {"radius": a, "mean_pressure": float(p.mean())}


def design_point(R, force):
    """A design study's point (sub-millisecond): peak pressure and radius of a ball on a flat."""
    contact = contactlab.Contact(contactlab.profiles.Paraboloid(R=R),
                                 materials=(contactlab.Elastic(E=210e9, nu=0.3),) * 2)
    state = contact.normal(force=force)
    return {"peak_pressure": state.peak_pressure, "radius": state.radius}


def timed(fn):
    t0 = time.perf_counter()
    out = fn()
    return time.perf_counter() - t0, out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="fewer loops and tiny tasks")
    args = ap.parse_args()
    import dask
    from distributed import Client, LocalCluster

    from contactlab.sweeps import make_grid

    print(machine())
    n_amp, n_mu = (10, 5) if args.quick else (20, 10)
    loops = {"amplitude": list(np.geomspace(2e-4, 4e-3, n_amp)),
             "friction": list(np.linspace(0.1, 0.5, n_mu))}
    n_loops = n_amp * n_mu

    t_serial, serial = timed(lambda: contactlab.sweep(timed_loop, loops, workers=1,
                                                      progress=False))
    rows = [("serial, this process", 1, t_serial, serial.pop("cpu").sum(), "")]
    cluster = dict(threads_per_worker=1, processes=True, dashboard_address=":0")
    # the clusters without the variable first: a nanny leaves its variables in this process's
    # environment, which later worker processes inherit
    os.environ.pop("MALLOC_TRIM_THRESHOLD_", None)
    with dask.config.set({"distributed.nanny.pre-spawn-environ.MALLOC_TRIM_THRESHOLD_": None}):
        c1n = LocalCluster(n_workers=1, **cluster)
        c2n = LocalCluster(n_workers=2, **cluster)
    with c1n, c2n, Client(c1n) as client1n, Client(c2n) as client2n, \
            LocalCluster(n_workers=1, **cluster) as c1, Client(c1) as client1:
        for name, client, w in (("LocalCluster, 1 worker", client1, 1),
                                ("1 worker, no MALLOC_TRIM", client1n, 1),
                                ("2 workers, no MALLOC_TRIM", client2n, 2)):
            contactlab.sweep(empty, {"i": [0, 1]}, client=client, progress=False)   # warm
            t, table = timed(lambda: contactlab.sweep(timed_loop, loops, client=client,
                                                      progress=False))
            cpu = table.pop("cpu").sum()
            assert table.equals(serial), "cluster table differs from the serial one"
            st = table.attrs["sweep"]["stats"]
            rows.append((name, w, t, cpu, f"batch {st['batch_size']}, {st['tasks']} tasks"))
        print(f"\n1. {n_loops} torsional loops (10 cycles x 100 steps, exact), tables identical; "
              "cpu = the points' own CPU time summed:")
        for name, w, t, cpu, note in rows:
            print(f"   {name:<26} {t:8.2f} s   {n_loops / t:7.1f} loops/s   cpu {cpu:6.2f} s"
                  f"   {note}")
        print(f"   speed-up 2 vs 1 worker (no MALLOC_TRIM): {rows[2][2] / rows[3][2]:.2f}x (ideal "
              f"2.00x); 1 worker vs serial: {rows[0][2] / rows[1][2]:.2f}x with Dask's default "
              f"environment, {rows[0][2] / rows[2][2]:.2f}x without MALLOC_TRIM_THRESHOLD_")

        n_empty = 400
        print(f"\n2. scheduler overhead per task ({n_empty} empty points, 1 point per task):")
        for name, kw in (("LocalCluster, 1 worker", {"client": client1}),
                         ("process pool, 1 worker", {"workers": 1}),):
            if "workers" in kw:
                from contactlab.sweeps.backends import Pool
                pool = Pool(empty, 1)
                pool.roundtrip()
                t0 = time.perf_counter()
                pool.submit_all([[(i, {"i": i})] for i in range(n_empty)])
                for _ in pool.completed():
                    pass
                t = time.perf_counter() - t0
                pool.close()
            else:
                t, _ = timed(lambda: contactlab.sweep(empty, {"i": list(range(n_empty))},
                                                      batch_size=1, progress=False, **kw))
            print(f"   {name:<26} {1e3 * t / n_empty:8.3f} ms per task")

        print("\n3. whole sweeps: overhead = (workers x wall - C) / C, C = the study's own calls in "
              "a plain loop here;\n   serial = workers=1 in this process, cluster = the 1-worker "
              "LocalCluster without MALLOC_TRIM_THRESHOLD_:")
        q = args.quick
        force = lambda m: {"force": list(np.linspace(1.0, 1000.0, m))}          # noqa: E731
        design = lambda m: {"R": list(np.geomspace(1e-3, 5e-2, 10)),            # noqa: E731
                            "force": list(np.linspace(1.0, 1000.0, m // 10))}
        cases = (("Hertz point", hertz_point, force(30000 if q else 30000), False),
                 ("Hertz point", hertz_point, force(100000 if q else 300000), False),
                 ("Hertz profile", hertz_profile, force(10000 if q else 30000), False),
                 ("design point", design_point, design(500 if q else 2000), True),
                 ("torsion point", torsion_point, force(100 if q else 400), True))
        print("   each overhead as wall/CPU; CPU = this process (client, scheduler) + the worker, "
              "which other sessions' load does not inflate")
        print(f"   {'study':<14} {'points':>7} {'C/point':>9} {'serial':>14} {'cluster':>14} "
              f"{'1/task':>14}   cluster plan")
        reps = 3 if q else 5
        for study_name, study, grid, one_per_task in cases:
            g = make_grid(grid)
            points = g.points
            modes = {"C": lambda: [study(**p) for p in points],
                     "serial": lambda: contactlab.sweep(study, grid, workers=1, progress=False),
                     "cluster": lambda: contactlab.sweep(study, grid, client=client1n,
                                                         progress=False)}
            if one_per_task:
                modes["1/task"] = lambda: contactlab.sweep(study, grid, client=client1n,
                                                           batch_size=1, progress=False)
            best = {k: np.inf for k in modes}
            cpu = {k: np.inf for k in modes}
            for _ in range(reps):           # alternate, best of several: the load drifts
                for k, f in modes.items():
                    on_cluster = k in ("cluster", "1/task")
                    w0 = sum(client1n.run(time.process_time).values()) if on_cluster else 0.0
                    c0 = time.process_time()
                    dt, out = timed(f)
                    c = time.process_time() - c0
                    if on_cluster:
                        c += sum(client1n.run(time.process_time).values()) - w0
                    best[k], cpu[k] = min(best[k], dt), min(cpu[k], c)
                    if k == "cluster":
                        st = out.attrs["sweep"]["stats"]
            C, n = best["C"], len(g)
            over = {k: f"{best[k] / C - 1:+7.0%}/{cpu[k] / cpu['C'] - 1:+5.0%}"
                    for k in modes if k != "C"}
            print(f"   {study_name:<14} {n:7d} {1e6 * C / n:7.2f}us {over['serial']:>14} "
                  f"{over['cluster']:>14} {over.get('1/task', '-'):>14}   {st['backend']}: "
                  f"{st['calibration_points']} timed here, {st.get('tasks', 0)} task(s) of "
                  f"{st.get('batch_size', 0)}, round trip {1e3 * st.get('roundtrip_seconds', 0):.1f}"
                  f" ms; C = {1e3 * C:.0f} ms")

    print(f"\nload average at the end: {os.getloadavg()[0]:.2f}")


if __name__ == "__main__":
    main()
