"""Foundation kernels: numba against numpy, and the spring-count cliff (issue 13).

Run from the repository root: ``python benchmarks/foundation_backends.py [U_numba] [U_numpy]``
(numba from the extra ``fast``; without it only numpy is timed).

1. A gait-like ``simulate`` (force and twist change at every step, N = 2000): spring-updates per
   second with each backend (numba: the fused compiled step, one call per run of steps), side by
   side, and the numpy backend against a minimal numpy replica of the same step (target: within
   1.1x).
2. No cliff from N = 10^2 to 10^6 (time per spring-update within 2x across the range), measured
   in two child processes, ``OPENBLAS_NUM_THREADS=1`` and the default BLAS threads:
   a. the Jenkins update alone (``foundation._compiled.jenkins_update``) per spring-update, with
      a minimal numpy replica using ``np.dot`` (what the kernel did before) for comparison;
   b. a whole gait ``simulate(method="mdr")`` per spring-update, steps scaled so that every run
      does about U spring-updates (default U = 10^8 with numba, 10^7 with numpy: N = 10^6 then
      runs 100 / 10 steps, N = 10^2 10^6 / 10^5 steps), best of 5 (numba) / 3 (numpy) in wall
      time and in CPU time (the latter less disturbed by other processes on a loaded machine).
      This is the quantity
      a user feels; the kernel alone at N = 100 is mostly the cost of one call. The target
      applies to the numba rows (the product path with the extra ``fast``);
   c. where a whole run at N = 10^2 spends its CPU time per step (numba).
"""
from __future__ import annotations

import json
import math
import os
import subprocess
import sys
import time
import timeit
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(Path(__file__).resolve().parent))

import contactlab as cl  # noqa: E402
from contactlab.foundation import _compiled  # noqa: E402
from contactlab.loadpath import LoadPath  # noqa: E402
from _harness import cpu_timed, cpu_timed_iter, machine  # noqa: E402


def dot_replica(m, K, invK, L, nL, inc, tmp):
    np.multiply(K, inc, out=tmp)
    tmp += m
    np.minimum(tmp, L, out=m)
    np.maximum(m, nL, out=m)
    tmp -= m
    tmp *= m
    return float(np.dot(tmp, invK))


def gait_replica(fnd, d_arr, ed, twist, c_tor):
    """The gait step in the fewest numpy calls (no state objects, no checks): S, weight, slip
    limits, weighted stiffness, Jenkins update, sum, stick radius."""
    n = fnd.n_springs
    w, dG, X1, dH, K, invK, bl = fnd.w, fnd.dG, fnd.X1, fnd.dH, fnd.K_tor, fnd.invK_tor, fnd.bl
    m, S, wt, iK = np.zeros(n), np.zeros(n), np.zeros(n), np.ones(n)
    k_old, d_old, x, W = 0, 0.0, 0.0, 0.0
    ks, Ss, Ts = ed["k"].tolist(), ed["S"].tolist(), ed["T"].tolist()
    for j, d in enumerate(d_arr.tolist()):
        k = ks[j]
        Sn = d * w - dG
        Sn[k + 1:] = 0.0
        Sn[k] = Ss[j]
        lo, hi = min(k, k_old), max(k, k_old) + 1
        wt[:lo] = 1.0
        wt[hi:] = 0.0
        wt[lo:hi] = np.clip((Sn[lo:hi] - S[lo:hi]) / ((d - d_old) * w[lo:hi]), 0.0, 1.0)
        T = d * X1 - dH
        T[k + 1:] = 0.0
        T[k] = Ts[j]
        L = c_tor * T
        np.divide(invK, wt, out=iK, where=wt > 0)
        tmp = K * wt * (twist[j] - x) + m
        np.clip(tmp, -L, L, out=m)
        W += float(((tmp - m) * m * iK).sum())
        float(m.sum())
        slip = np.abs(m) >= L
        i = int(np.argmax(slip))
        float(bl[i])
        S, k_old, d_old, x = Sn, k, d, twist[j]
    return W


NS = (10**2, 10**3, 10**4, 10**5, 10**6)


def gait_path(steps: int) -> LoadPath:
    t = np.linspace(0, 1, steps + 1)
    return LoadPath.from_arrays(time=t, force=50 + 40 * np.sin(2 * np.pi * t),
                                twist=2e-4 * np.sin(6 * np.pi * t))


def gait_contact() -> cl.Contact:
    return cl.Contact(cl.profiles.Paraboloid(R=0.01), (cl.Elastic(E=210e9, nu=0.3),) * 2,
                      friction=0.3)


def kernel_sweep(backends) -> dict:
    """ns per spring-update of the Jenkins update alone, per backend and N (and np.dot)."""
    rng = np.random.default_rng(0)
    per = {b: [] for b in (*backends, "np.dot replica")}
    for n in NS:
        K = rng.uniform(0.5, 2, n)
        invK, L = 1 / K, rng.uniform(0, 1, n)
        nL, m, tmp = -L, np.zeros(n), np.empty(n)
        reps = max(20, 2 * 10**6 // n)
        for b in backends:
            _compiled.set_backend(b)
            _compiled.jenkins_update(m, K, invK, L, 0.1, tmp, nL)      # compile / warm
            t = min(timeit.repeat(lambda: _compiled.jenkins_update(m, K, invK, L, 0.01, tmp, nL),
                                  number=reps, repeat=3)) / reps / n
            per[b].append(t * 1e9)
        td = min(timeit.repeat(lambda: dot_replica(m, K, invK, L, nL, 0.01, tmp), number=reps,
                               repeat=3)) / reps / n
        per["np.dot replica"].append(td * 1e9)
    _compiled.set_backend(None)
    return per


#: runs per spring count of the whole-run sweep (best of them), per backend: a numba run of
#: 10^8 spring-updates takes ~0.1-0.15 s, so five keep the N = 100 row (whose 10^6-step runs
#: also pay the operating system for 64 MB of fresh result pages, 8-76 ms of system time per
#: run measured) from reporting one disturbed run; the numpy rows take seconds per run
WHOLE_RUN_REPEATS = {"numba": 5, "numpy": 3}


def whole_run_sweep(backends, updates: dict) -> dict:
    """ns per spring-update of a whole gait simulate (method="mdr"), ~``updates[b]`` spring-updates
    per run, best of :data:`WHOLE_RUN_REPEATS` in wall time and in CPU time of this process (the
    first run of each backend compiles)."""
    c = gait_contact()
    per = {}
    for b in backends:
        _compiled.set_backend(b)
        c.simulate(gait_path(50), n_springs=100, method="mdr")         # compile / warm
        row, cpu = [], []
        for n in NS:
            steps = max(10, int(updates[b] // n))
            path = gait_path(steps)
            best = best_cpu = math.inf
            for _ in range(WHOLE_RUN_REPEATS[b]):
                t0, c0 = time.perf_counter(), time.process_time()
                c.simulate(path, n_springs=n, method="mdr")
                best = min(best, time.perf_counter() - t0)
                best_cpu = min(best_cpu, time.process_time() - c0)
            row.append(best / (n * (steps + 1)) * 1e9)
            cpu.append(best_cpu / (n * (steps + 1)) * 1e9)
        per[b] = row
        per[b + " (CPU time)"] = cpu
    _compiled.set_backend(None)
    return per


def breakdown(n: int = 100, updates: float = 1e8) -> dict:
    """Where a whole gait run at ``n`` springs spends its CPU time (numba backend), ns per step:
    the compiled runs, the edge-cell data, the path's normal solve, the MDR validity check,
    the rest (path values, turn search, result series)."""
    from contactlab.effects import path as P
    from contactlab.foundation import winkler
    acc = dict.fromkeys(("compiled runs", "edge data", "normal solve", "validity check"), 0.0)

    saved = {(P, "iter_path_normal_states"): P.iter_path_normal_states,
             (P, "warn_mdr_path"): P.warn_mdr_path, (P, "_fused_step"): P._fused_step,
             (winkler.Winkler, "edge_data"): winkler.Winkler.edge_data}
    P.iter_path_normal_states = cpu_timed_iter(saved[(P, "iter_path_normal_states")], acc,
                                               "normal solve")
    P.warn_mdr_path = cpu_timed(saved[(P, "warn_mdr_path")], acc, "validity check")
    winkler.Winkler.edge_data = cpu_timed(saved[(winkler.Winkler, "edge_data")], acc, "edge data")
    P._fused_step = lambda fnd, chans: (
        lambda k: None if k is None else cpu_timed(k, acc, "compiled runs"))(
        saved[(P, "_fused_step")](fnd, chans))
    try:
        _compiled.set_backend("numba")
        c = gait_contact()
        steps = int(updates // n)
        path = gait_path(steps)
        c.simulate(path, n_springs=n, method="mdr")
        best = None
        for _ in range(3):
            for k in acc:
                acc[k] = 0.0
            c0 = time.process_time()
            c.simulate(path, n_springs=n, method="mdr")
            total = time.process_time() - c0
            if best is None or total < best["total"]:
                best = dict(acc, total=total)
    finally:
        for (obj, name), fn in saved.items():
            setattr(obj, name, fn)
        _compiled.set_backend(None)
    best["rest"] = best["total"] - sum(best[k] for k in acc)
    return {k: v / (steps + 1) * 1e9 for k, v in best.items()}


def child(updates: dict) -> int:
    backends = _compiled.available()
    out = {"load": os.getloadavg()[0], "kernel": kernel_sweep(backends),
           "whole": whole_run_sweep(backends, updates)}
    if "numba" in backends:
        out["breakdown"] = breakdown(NS[0], updates["numba"])
    print(json.dumps(out))
    return 0


def gait_section(backends) -> None:
    c = gait_contact()
    t = np.linspace(0, 1, 2001)
    path = gait_path(2000)
    print("\ngait-like simulate (force and twist change every step, 2000 steps, N = 2000):")
    res, cpu = {}, {}
    for b in backends:
        _compiled.set_backend(b)
        c.simulate(path, n_springs=2000, method="mdr")
        res[b] = min(timeit.repeat(lambda: c.simulate(path, n_springs=2000, method="mdr"),
                                   number=1, repeat=5))
        cpu[b] = min(timeit.repeat(lambda: c.simulate(path, n_springs=2000, method="mdr"),
                                   number=1, repeat=5, timer=time.process_time))
        print(f"  {b:6s} {res[b]:.3f} s  {2000 * 2000 / res[b]:.3g} spring-updates/s "
              f"(CPU time {cpu[b]:.3f} s, {2000 * 2000 / cpu[b]:.3g}/s)"
              + (f"  {'OK' if 2000 * 2000 / cpu[b] >= 5e8 else 'MISSED'} (target >= 5e8/s)"
                 if b == "numba" else ""))
    if "numba" in res:
        print(f"  numpy/numba: {res['numpy'] / res['numba']:.2f} (CPU time "
              f"{cpu['numpy'] / cpu['numba']:.2f})")
    from contactlab.foundation import Winkler
    from contactlab.foundation.base import path_normal_states
    nrm = path_normal_states(c.profile, c.moduli.normal, path, c.rtol)[0]
    fnd = Winkler(c.profile, c.moduli, c.friction, float(nrm["radius"].max()), n_springs=2000,
                  needs=("torsion",), rtol=c.rtol)
    ed = fnd.edge_data(nrm["depth"], nrm["radius"])
    tw = (2e-4 * np.sin(6 * np.pi * t)).tolist()
    _compiled.set_backend("numpy")
    fns = (lambda: c.simulate(path, n_springs=2000, method="mdr"),
           lambda: gait_replica(fnd, nrm["depth"], ed, tw, fnd._c_tor))
    # the two alternate run by run (best of 15 each), so that both see the same machine load;
    # wall and CPU time of the same runs
    both, both_cpu = [np.inf, np.inf], [np.inf, np.inf]
    for _ in range(15):
        for j, f in enumerate(fns):
            w0, c0 = time.perf_counter(), time.process_time()
            f()
            both[j] = min(both[j], time.perf_counter() - w0)
            both_cpu[j] = min(both_cpu[j], time.process_time() - c0)
    ratio = both[0] / both[1]
    print(f"  numpy simulate {both[0]:.3f} s, minimal numpy replica of the step {both[1]:.3f} s: "
          f"ratio {ratio:.2f} {'OK' if ratio <= 1.1 else 'MISSED'} (target <= 1.1); CPU time "
          f"{both_cpu[0]:.3f} / {both_cpu[1]:.3f} s: ratio {both_cpu[0] / both_cpu[1]:.2f} "
          "(alternating, best of 15 each)")
    _compiled.set_backend(None)


def main() -> int:
    args = [a for a in sys.argv[1:] if a != "--child"]
    updates = {"numba": float(args[0]) if args else 1e8,
               "numpy": float(args[1]) if len(args) > 1 else 1e7}
    if "--child" in sys.argv:
        return child(updates)
    print("Machine:", machine())
    backends = _compiled.available()
    print("backends:", ", ".join(backends))
    gait_section(backends)
    print(f"\nNo cliff N = 1e2..1e6 (ns per spring-update; whole runs of ~{updates['numba']:.0e} "
          f"(numba) / {updates['numpy']:.0e} (numpy) spring-updates each):")
    for threads in ("1", None):
        env = dict(os.environ)
        if threads is None:
            env.pop("OPENBLAS_NUM_THREADS", None)
        else:
            env["OPENBLAS_NUM_THREADS"] = threads
        proc = subprocess.run([sys.executable, __file__, "--child", *map(str, updates.values())],
                              env=env, capture_output=True, text=True, check=True)
        out = json.loads(proc.stdout.strip().splitlines()[-1])
        label = "OPENBLAS_NUM_THREADS=1" if threads else "default BLAS threads"
        print(f"\n  {label} (load {out['load']:.2f} at the start):")
        print(f"  {'':32s}" + "".join(f"{n:>9.0e}" for n in NS) + "   max/min")
        for what, key in (("kernel alone", "kernel"), ("whole gait simulate", "whole")):
            for b, row in out[key].items():
                targeted = key == "whole" and b.startswith("numba")
                print(f"  {what + ', ' + b:44s}" + "".join(f"{v:9.2f}" for v in row)
                      + f"   {max(row) / min(row):6.2f}"
                      + (f" {'OK' if max(row) / min(row) <= 2 else 'MISSED'} (target <= 2)"
                         if targeted else ""))
        if "breakdown" in out:
            bd = out["breakdown"]
            print(f"  whole gait run at N = {NS[0]}, numba, CPU ns per step: total "
                  f"{bd.pop('total'):.0f} = " + ", ".join(f"{k} {v:.0f}" for k, v in bd.items()))
    print("\nVerdict: the target (time per spring-update within 2x from N = 1e2 to 1e6) applies to "
          "the product path, the whole gait simulate with the extra 'fast' installed (numba; CI "
          "installs it). At N = 1e2 a step has ~100 spring-updates, so any per-step work outside "
          "the springs (the path's normal solve and the MDR validity check, both vectorised over "
          "steps; the edge-cell data; the result series) weighs as much as the springs: the "
          "breakdown above shows it. The pure-numpy backend is the reference and the fallback: "
          "its ~20 numpy calls per step cost ~1 us each whatever N, so at N = 1e2 its time per "
          "spring-update is dominated by that per-step cost (inherent; not targeted). The kernel-alone rows "
          "show the BLAS cliff the np.dot replica still has and the kernels do not.")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
