"""Torsional gross-slip boundary of fretting_map() against the exact Hertz root (issue 26).

The reference is independent of the package: the Lubkin / Jäger closed forms for Hertz, solved in
20-digit arithmetic (tests/reference/fretting.py, ``hertz_torsion_boundary``). Prints the relative
error of ``fretting_map(...).boundary`` per criterion and threshold, and the time of a 50 x 50 and
an 8 x 8 (docs example) torsional map with its boundary.

Run: OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 python benchmarks/fretting_boundary.py
"""
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(Path(__file__).resolve().parent))

import contactlab as cl
from _harness import machine
from tests.reference.fretting import hertz_torsion_boundary

steel = cl.Elastic(E=210e9, nu=0.3)
MU, R = 0.5, 0.01
c = cl.Contact(cl.profiles.Paraboloid(R=R), materials=(steel, steel), friction=MU)
print(machine())
forces = np.array([1.0, 100.0])
a = np.cbrt(3.0 * forces * R / (4.0 * c.moduli.normal))
scale = MU * forces / (c.moduli.torsional * a**2)
cases = [("energy_ratio", t) for t in (0.2, 0.3, 0.5, 0.7, 0.8, 0.9)] + [
    ("torque_ratio", t) for t in (0.5, 0.9, 0.95, 0.99)] + [("stick_ratio", t) for t in (0.1, 0.5)]
print(f"{'criterion':>13} {'threshold':>9} {'c/a at root':>12} {'max |rel. error|':>17}")
for crit, thr in cases:
    phi_hat, s = hertz_torsion_boundary(crit, thr)
    m = c.fretting_map(force=forces, twist_amplitude=[1e-4], criterion=crit, threshold=thr)
    err = np.max(np.abs(m.boundary / (phi_hat * scale) - 1.0))
    print(f"{crit:>13} {thr:9.2f} {s:12.4g} {err:17.2e}")
for n in (50, 8):
    best = np.inf
    for _ in range(2):
        t = time.perf_counter()
        c.fretting_map(force=np.geomspace(1, 1000, n), twist_amplitude=np.geomspace(1e-5, 1e-1, n))
        best = min(best, time.perf_counter() - t)
    print(f"{n}x{n} torsional map (exact, with boundary): {best:.3f} s (best of 2)")
