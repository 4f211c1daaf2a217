"""Timing of formula export: derivation (first call, cached), lambdified callables vs the solver.

Run: ``python benchmarks/formulas.py``. Prints ratios; no assertions.
"""
from __future__ import annotations

import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
sys.path.insert(0, str(Path(__file__).resolve().parent))
import contactlab as cl  # noqa: E402
from _harness import machine  # noqa: E402  (one machine description for every benchmark)
from contactlab.profiles import Cone, Paraboloid, Polynomial, PowerLaw, Sphere, TruncatedCone  # noqa: E402
from contactlab.symbolic import formulas as _f  # noqa: E402


def best(fn, repeat=5):
    out = []
    for _ in range(repeat):
        t = time.perf_counter()
        fn()
        out.append(time.perf_counter() - t)
    return min(out)


def main() -> None:
    print(f"machine: {machine()}")
    mats = (cl.Elastic(E=210e9, nu=0.3), cl.Rigid())
    print(f"{'profile':<42} {'formulas() first [s]':>20} {'cached [us]':>12}")
    for prof in (Paraboloid(R=0.01), Cone(slope=0.2), PowerLaw(c=5e5, n=3), PowerLaw(c=30.0, n=1.5),
                 Polynomial({2: 50.0, 4: 1e5}), Sphere(R=0.01), TruncatedCone(radius=1e-3, slope=0.1)):
        _f._contact_formulas_cached.cache_clear()
        _f._profile_formulas_cached.cache_clear()
        c = cl.Contact(prof, materials=mats)
        t0 = time.perf_counter()
        c.formulas()
        first = time.perf_counter() - t0
        cached = best(c.formulas, 20)
        print(f"{prof!r:<42} {first:20.3f} {cached * 1e6:12.1f}")

    c = cl.Contact(Paraboloid(R=0.01), materials=mats)
    fs = c.formulas()
    d = np.linspace(1e-8, 1e-6, 100_000)
    F = fs.callable("force_of_depth")
    t_callable = best(lambda: F(d))
    t_solver = best(lambda: c.normal(depth=d).force)
    print(f"Hertz F(d), 1e5 depths: callable {t_callable * 1e3:.2f} ms, contact.normal "
          f"{t_solver * 1e3:.2f} ms, ratio solver/callable {t_solver / t_callable:.1f}")
    c = cl.Contact(Sphere(R=0.01), materials=mats)
    fs = c.formulas()
    a = np.linspace(1e-5, 1e-3, 100_000)
    F = fs.callable("force_of_radius")
    t_callable = best(lambda: F(a))
    t_solver = best(lambda: c.normal(radius=a).force)
    print(f"sphere F(a), 1e5 radii: callable {t_callable * 1e3:.2f} ms, contact.normal "
          f"{t_solver * 1e3:.2f} ms, ratio solver/callable {t_solver / t_callable:.1f}")


if __name__ == "__main__":
    main()
