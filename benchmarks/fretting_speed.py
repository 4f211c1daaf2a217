"""Fretting speed targets (issue 15): a 50 x 50 torsional fretting map and a 10^6-cycle torsional
wear run on a Hertz contact, each under 10 s on one core.

Run: OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 python benchmarks/fretting_speed.py
"""
import time
import warnings

import numpy as np

import contactlab as cl
from _harness import machine

steel = cl.Elastic(E=210e9, nu=0.3)
c = cl.Contact(cl.profiles.Paraboloid(R=0.01), materials=(steel, steel), friction=0.5)
print(machine())
t = time.perf_counter()
m = c.fretting_map(force=np.geomspace(1, 1000, 50), twist_amplitude=np.geomspace(1e-5, 1e-1, 50))
print(f"50x50 torsional map (exact, with boundary): {time.perf_counter() - t:.2f} s")
t = time.perf_counter()
m = c.fretting_map(force=np.geomspace(1, 1000, 50),
                   displacement_amplitude=np.geomspace(1e-8, 1e-4, 50))
print(f"50x50 tangential map: {time.perf_counter() - t:.2f} s")
for phi, n in ((1e-2, 200), (1e-2, 400), (0.05, 200)):
    t = time.perf_counter()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        w = c.wear(force=100.0, twist_amplitude=phi, wear_coefficient=1e-15, cycles=1e6,
                   n_grid=n)
    print(f"1e6-cycle torsional wear, phi={phi}, n_grid={n}: {time.perf_counter() - t:.2f} s "
          f"({w.meta['steps']} steps, {w.meta['rejected']} rejected)")
# method="mdr" against the exact torsion, side by side (docs/fretting.md section 4)
for phi in (1e-3, 1e-2):
    for n in (200, 400):
        row = {}
        for method in ("exact", "mdr"):
            best = np.inf
            for _ in range(2):
                t = time.perf_counter()
                with warnings.catch_warnings():
                    warnings.simplefilter("ignore")
                    w = c.wear(force=100.0, twist_amplitude=phi, wear_coefficient=1e-15,
                               cycles=1e6, n_grid=n, method=method)
                best = min(best, time.perf_counter() - t)
            row[method] = (best, w.volume[-1])
        print(f"wear phi={phi}, n_grid={n}: exact {row['exact'][0]:.3f} s, mdr "
              f"{row['mdr'][0]:.3f} s, speed-up {row['exact'][0] / row['mdr'][0]:.2f}, "
              f"volume mdr/exact - 1 = {row['mdr'][1] / row['exact'][1] - 1:+.3f}")
