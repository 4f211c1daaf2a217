"""Benchmark of the MDR viscoelastic foundation (contactlab.foundation.viscoelastic).

1. Time per step against the number of foundation elements, for a depth-controlled triangle
   history (Ting unloading) and a force-controlled creep history, generalized Maxwell material
   with 1 and 4 arms; each backend of the foundation step side by side (numba: the compiled
   trial step of the extra ``fast``; numpy: the reference) and their ratio.
2. Accuracy against the time step: SLS creep under a step force on a paraboloid against the
   closed form a³(t) = 3RF0 J(t)/16 (theory §7), and SLS constant-rate indentation against the
   Lee-Radok hereditary integral; fitted order.

Writes ``viscoelastic_speed.csv`` and ``viscoelastic_accuracy.csv`` next to this script (or to
the directory given as the first argument) and prints a summary with the machine name.

Run: ``python benchmarks/viscoelastic_speed.py [outdir]`` from the repository root.
"""
from __future__ import annotations

import csv
import os
import sys
import time

import numpy as np
from scipy.integrate import quad

sys.path.insert(0, os.path.join(os.path.dirname(__file__), ".."))

import contactlab as cl  # noqa: E402
sys.path.insert(0, os.path.dirname(__file__))
from _harness import machine  # noqa: E402  (one machine description for every benchmark)
from contactlab.materials.viscoelastic import GeneralizedMaxwell, StandardLinearSolid  # noqa: E402
from contactlab.profiles import Paraboloid  # noqa: E402
from contactlab.foundation import _compiled  # noqa: E402

R = 0.01


def _contact(mat):
    return cl.Contact(Paraboloid(R), materials=(mat, cl.Rigid()))


def speed(outdir: str) -> None:
    """Time per step of both foundation backends side by side (numba: the compiled trial step,
    extra ``fast``; numpy: the reference), and their ratio."""
    backends = _compiled.available()
    rows = []
    mats = {1: GeneralizedMaxwell(1e6, [2e6], [5e-3]),
            4: GeneralizedMaxwell(1e6, [2e6, 1e6, 5e5, 2e5], [1e-3, 5e-3, 2e-2, 1e-1])}
    steps = 400
    t = np.linspace(0.0, 0.04, steps)
    d = 1e-4 * np.where(t <= 0.02, t, 0.04 - t)
    for b in backends:      # compile / warm
        _compiled.set_backend(b)
        _contact(mats[1]).viscoelastic_history(time=t[:5], depth=d[:5], n_springs=20)
    print("time per step (best of 2), backends side by side:")
    for arms, mat in mats.items():
        c = _contact(mat)
        for n in (250, 1000, 4000, 16000):
            per = {}
            for b in backends:
                _compiled.set_backend(b)
                dep = frc = np.inf
                for _ in range(2):
                    t0 = time.perf_counter()
                    c.viscoelastic_history(time=t, depth=d, n_springs=n)
                    dep = min(dep, (time.perf_counter() - t0) / steps)
                    t0 = time.perf_counter()
                    c.viscoelastic_history(time=t[:100], force=np.full(100, 0.1), n_springs=n)
                    frc = min(frc, (time.perf_counter() - t0) / 100)
                per[b] = (dep, frc)
                rows.append((b, arms, n, dep, frc))
            line = "  ".join(f"{b}: depth {per[b][0] * 1e6:8.1f} us, force {per[b][1] * 1e6:8.1f} us"
                             for b in backends)
            if "numba" in per:
                line += (f"  numpy/numba: depth {per['numpy'][0] / per['numba'][0]:.1f}x, "
                         f"force {per['numpy'][1] / per['numba'][1]:.1f}x")
            print(f"arms={arms} n_springs={n:6d}: {line}")
    _compiled.set_backend(None)
    with open(os.path.join(outdir, "viscoelastic_speed.csv"), "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(["backend", "arms", "n_springs", "depth_control_s_per_step",
                    "force_control_s_per_step"])
        w.writerows(rows)
    for b in backends:
        base = {r[1]: r[3] for r in rows if r[0] == b and r[2] == 250}
        for bb, arms, n, dep, frc in rows:
            if bb == b and n == 16000:
                print(f"{b}, arms={arms}: 64x the elements costs {dep / base[arms]:.1f}x per "
                      "depth step")


def accuracy(outdir: str) -> None:
    m = StandardLinearSolid(1e6, 2e6, 1e4)
    c = _contact(m)
    F0, T = 0.1, 0.05
    v = 1e-4
    rows = []
    for n in (11, 21, 41, 81, 161, 321, 641):
        t = np.linspace(0.0, T, n)
        h = c.viscoelastic_history(time=t, force=np.full(n, F0), n_springs=1000)
        ref = (3 * R * F0 * m.creep(t) / 16) ** (2 / 3) / R
        e_creep = float(np.max(np.abs(h.depth / ref - 1)))
        tt = np.linspace(0.0, 0.03, n)
        hd = c.viscoelastic_history(time=tt, depth=v * tt, n_springs=4000)
        k = 1.5 * (R * v) ** 1.5
        ref_F = 16 / (3 * R) * quad(lambda s: m.relaxation(tt[-1] - s) * k * np.sqrt(s), 0,
                                    tt[-1], epsrel=1e-12)[0]
        e_rate = abs(hd.force[-1] / ref_F - 1)
        rows.append((t[1], e_creep, tt[1], e_rate))
        print(f"dt={t[1]:.3e} s: creep depth error {e_creep:.3e}; dt={tt[1]:.3e} s: "
              f"constant-rate force error {e_rate:.3e}")
    r = np.array(rows)
    o1 = np.polyfit(np.log(r[:, 0]), np.log(r[:, 1]), 1)[0]
    print(f"fitted order in dt: creep {o1:.2f}; constant-rate error is dominated by the "
          "element spacing (Δx) once dt is small")
    with open(os.path.join(outdir, "viscoelastic_accuracy.csv"), "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(["dt_creep_s", "creep_depth_rel_error", "dt_rate_s", "rate_force_rel_error"])
        w.writerows(rows)


if __name__ == "__main__":
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(os.path.abspath(__file__))
    os.makedirs(out, exist_ok=True)
    print(f"machine: {machine()}")
    speed(out)
    accuracy(out)
