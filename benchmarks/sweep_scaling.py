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
3. small tasks (one exact torsion point, milliseconds) and tiny ones (a closed-form Hertz point,
   microseconds): one point per task versus the automatic batch size (Hertz: on 10x as many points),
   on the 1-worker cluster (Dask defaults); overhead = cluster wall / serial wall - 1 (the serial
   sweep evaluates and tabulates the same points in this process; best of three, alternating).

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

    print(machine())
    n_amp, n_mu = (10, 5) if args.quick else (20, 10)
    loops = {"amplitude": list(np.geomspace(2e-4, 4e-3, n_amp)),
             "friction": list(np.linspace(0.1, 0.5, n_mu))}
    n_loops = n_amp * n_mu
    n_tiny = 1000 if args.quick else 3000
    tiny = {"force": list(np.linspace(1.0, 1000.0, n_tiny))}

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

        print(f"\n3. small and tiny tasks on the 1-worker cluster, one point per task versus the "
              "automatic batches;\n   overhead = cluster wall / serial wall (same points, this "
              "process) - 1:")
        q = args.quick
        cases = (("torsion point", torsion_point, 300 if q else 1000, 300 if q else 1000),
                 ("Hertz point", hertz_point, 1000 if q else 3000, 10000 if q else 30000))
        for study_name, study, n_one, n_auto in cases:
            for label, bs, m in (("1 point per task", 1, n_one), ("automatic batches", None, n_auto)):
                grid = {"force": list(np.linspace(1.0, 1000.0, m))}
                t_ser = t = np.inf
                for _ in range(3):          # alternate, best of three: the load drifts
                    t_ser = min(t_ser, timed(lambda: contactlab.sweep(
                        study, grid, workers=1, progress=False))[0])
                    dt, table = timed(lambda: contactlab.sweep(
                        study, grid, client=client1, batch_size=bs, progress=False))
                    t = min(t, dt)
                st = table.attrs["sweep"]["stats"]
                print(f"   {study_name:<14} {label:<18} {m:6d} points, {1e6 * t_ser / m:7.1f} us "
                      f"each; {st.get('calibration_points', 0):5d} timed here, batch "
                      f"{st.get('batch_size', 0):5d}, {st.get('tasks', 0):5d} tasks: {t:7.2f} s vs "
                      f"{t_ser:6.2f} s serial, overhead {t / t_ser - 1:7.1%}")

    print(f"\nload average at the end: {os.getloadavg()[0]:.2f}")


if __name__ == "__main__":
    main()
