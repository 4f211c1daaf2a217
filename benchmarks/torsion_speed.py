"""Cost of an exact torque-twist curve against the MDR model (issue 3 benchmark).

Times one 200-point twist-controlled curve (0 < φ <= 3 φ_ref, from nearly no slip to deep slip) at
rtol 1e-6 for a paraboloid and for a 10³-point linear table of the same paraboloid, with
``method="exact"`` and ``method="mdr"``; best of several repeats (one core, numpy's own
threading aside). Prints the machine, the times and the exact/MDR ratios.

Targets (issue 3): paraboloid < 50 ms, 10³-point table < 0.5 s. For scale: a 3D boundary-element
solver needs ~9 s for a 14-point curve at 2e-5 on this class of machine.

Run: ``python benchmarks/torsion_speed.py`` from the repository root.
"""
from __future__ import annotations

import sys
import time
import warnings
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

import contactlab as cl  # noqa: E402
sys.path.insert(0, str(Path(__file__).resolve().parent))
from _harness import machine  # noqa: E402  (one machine description for every benchmark)
from contactlab.errors import ValidityWarning  # noqa: E402


def best_of(fn, repeats: int) -> float:
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return min(times)


def main(repeats: int = 5) -> dict:
    mat = cl.Elastic(E=210e9, nu=0.3)
    R, a = 0.01, 2e-4
    r = np.linspace(0.0, 1.5 * a, 1000)
    profiles = {"paraboloid": cl.profiles.Paraboloid(R=R),
                "table_1000": cl.profiles.Tabulated(r, r**2 / (2 * R))}
    out = {}
    for name, prof in profiles.items():
        contact = cl.Contact(prof, (mat, mat), friction=0.3, rtol=1e-6)
        ref = contact.torsion(radius=a, stick_radius=0.0)
        phi_ref = 3 * ref.sliding_torque / (16 * contact.moduli.torsional * a**3)
        twist = np.linspace(0.0, 3.0, 201)[1:] * phi_ref
        contact.torsion(radius=a, twist=twist[:3])                  # warm-up (imports, caches)
        t_ex = best_of(lambda: contact.torsion(radius=a, twist=twist), repeats)

        def mdr():
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", ValidityWarning)
                contact.torsion(radius=a, twist=twist, method="mdr")

        mdr()
        t_md = best_of(mdr, repeats)
        out[name] = (t_ex, t_md)
    return out


if __name__ == "__main__":
    res = main()
    print(f"machine: {machine()}")
    print(f"{'profile':12s} {'exact [ms]':>11s} {'MDR [ms]':>9s} {'exact/MDR':>10s}   "
          "(200 twists, rtol 1e-6)")
    for name, (te, tm) in res.items():
        print(f"{name:12s} {te * 1e3:11.1f} {tm * 1e3:9.1f} {te / tm:10.1f}")
    tp = res["paraboloid"][0]
    tt = res["table_1000"][0]
    print(f"targets: paraboloid {tp * 1e3:.1f} ms (< 50 ms: {'met' if tp < 0.05 else 'NOT met'}), "
          f"10^3-point table {tt:.3f} s (< 0.5 s: {'met' if tt < 0.5 else 'NOT met'})")
