"""Speed of the exact torsion routes against their floors or the other route (issue 28).

Run from the repository root: ``python benchmarks/exact_speed.py [--rounds N]``.

Every row is measured interleaved in this one run (round-robin, best of ``--rounds``) and reported
as a ratio to a route of the same work, so the machine's load mostly cancels; the machine and its
load average are printed. Rows and goals:

1. the 180-step varying-load twisted Hertz path, ``simulate(path, method="exact")`` (default
   rings): with BLAS set to two threads vs one (goal: within 1.2x, bit-identical), cold (ring
   matrices built) and warm (reused), against ``method="mdr"`` on the same path; goal <= 50 ms;
2. ``Contact.torsion(method="mdr")`` on 10^5 forces (closed-form kernels of the paraboloid and
   the screened validity check, no per-force work beyond array arithmetic), reported as the
   ratio to ``method="no-slip"`` on the same forces (the floor: one closed form per force);
   goal <= 0.1 s;
3. the exact torque-twist curve (200 twists, Hertz) against the MDR curve of the same twists;
   goal <= 2 ms;
4. the exact curve (200 twists) on a 1000-point table, against its MDR curve; goal <= 50 ms.
"""
from __future__ import annotations

import argparse
import hashlib
import os
import sys
import time
import warnings
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
sys.path.insert(0, str(Path(__file__).resolve().parent))

import contactlab as cl
from contactlab.foundation import rings as _rings
from _harness import machine

MAT = (cl.Elastic(E=210e9, nu=0.3), cl.Rigid())
MU = 0.3


def _hertz() -> cl.Contact:
    return cl.Contact(cl.profiles.Paraboloid(R=0.01), materials=MAT, friction=MU)


def varying_path(c: cl.Contact, n: int = 180):
    """Force 10 N ± 40 % at two cycles, twist at 80 % of sliding at three cycles (ramped in)."""
    t = np.arange(1, n + 1) / n
    force = 10.0 * (1 + 0.4 * np.sin(2 * np.pi * 2 * t + 0.3))
    a_max = float(np.max(c.normal(force=force)._radius))
    s = MU * 10.0 / (c.moduli.torsional * a_max ** 2)
    phi = 0.8 * s * np.sin(2 * np.pi * 3 * t) * np.minimum(1, 2 * t)
    return cl.LoadPath.from_arrays(force=force, twist=phi)


def _digest(r) -> str:
    return hashlib.sha256(np.ascontiguousarray(r.torque).tobytes()
                          + np.ascontiguousarray(r.dissipated_energy).tobytes()).hexdigest()[:16]


def cases() -> dict:
    """name -> zero-argument callable (each returns something to keep)."""
    from threadpoolctl import threadpool_limits

    c = _hertz()
    path = varying_path(c)

    def exact_threads(n):
        def run():
            with threadpool_limits(n, user_api="blas"):
                return c.simulate(path, method="exact")
        return run

    def exact_cold():
        _rings._CACHE.clear()
        return c.simulate(path, method="exact")

    F = np.linspace(1.0, 100.0, 100_000)
    a10 = float(c.normal(force=10.0)._radius)
    s10 = MU * 10.0 / (c.moduli.torsional * a10 ** 2)
    twists = np.linspace(0.0, 0.95, 200) * s10
    r_tab = np.linspace(0.0, 4e-4, 1000)
    tab = cl.Contact(cl.profiles.Tabulated(r=r_tab, f=r_tab ** 2 / 0.02 + 2e3 * r_tab ** 3),
                     materials=MAT, friction=MU)
    return {
        "path exact, BLAS 1 thread": exact_threads(1),
        "path exact, BLAS 2 threads": exact_threads(2),
        "path exact, cold (matrices built)": exact_cold,
        "path mdr": lambda: c.simulate(path, method="mdr"),
        "torsion mdr, 1e5 forces": lambda: c.torsion(force=F, twist=2e-4, method="mdr"),
        "torsion no-slip, 1e5 forces": lambda: c.torsion(force=F, twist=2e-4, method="no-slip"),
        "curve exact, Hertz 200": lambda: c.torsion(force=10.0, twist=twists, method="exact"),
        "curve mdr, Hertz 200": lambda: c.torsion(force=10.0, twist=twists, method="mdr"),
        "curve exact, table 1000": lambda: tab.torsion(force=10.0, twist=twists, method="exact"),
        "curve mdr, table 1000": lambda: tab.torsion(force=10.0, twist=twists, method="mdr"),
    }


#: (row, reference row, goal on the row's time in s or None)
ROWS = [
    ("path exact, BLAS 2 threads", "path exact, BLAS 1 thread", None),
    ("path exact, BLAS 1 thread", "path mdr", 0.05),
    ("path exact, cold (matrices built)", "path exact, BLAS 1 thread", None),
    ("torsion mdr, 1e5 forces", "torsion no-slip, 1e5 forces", 0.1),
    ("curve exact, Hertz 200", "curve mdr, Hertz 200", 0.002),
    ("curve exact, table 1000", "curve mdr, table 1000", 0.05),
]


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--rounds", type=int, default=3)
    args = ap.parse_args()
    print("Machine:", machine())
    print("load average (1, 5, 15 min):", os.getloadavg())
    fns = cases()
    best = dict.fromkeys(fns, np.inf)
    keep: dict = {}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for _ in range(args.rounds):
            for name, fn in fns.items():
                t0 = time.perf_counter()
                keep[name] = fn()
                best[name] = min(best[name], time.perf_counter() - t0)
    same = _digest(keep["path exact, BLAS 1 thread"]) == _digest(keep["path exact, BLAS 2 threads"])
    print(f"\n{'row':38s} {'time':>10s} {'reference':38s} {'ratio':>7s}  goal")
    for row, ref, goal in ROWS:
        g = "" if goal is None else (f"<= {goal * 1e3:g} ms: "
                                     + ("met" if best[row] <= goal else "NOT met"))
        print(f"{row:38s} {best[row] * 1e3:8.2f}ms {ref:38s} {best[row] / best[ref]:7.2f}  {g}")
    ratio = best["path exact, BLAS 2 threads"] / best["path exact, BLAS 1 thread"]
    print(f"\nBLAS 2 vs 1 thread: ratio {ratio:.2f} (goal <= 1.2), results bit-identical: {same}")
    print("load average after:", os.getloadavg())
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
