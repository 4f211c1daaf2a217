"""Accuracy of the MDR foundation against closed forms vs number of springs, and its cost.

1. Tangential (Cattaneo–Mindlin virgin curve + Mindlin–Deresiewicz unloading/reloading) and
   torsional (MDR closed form, theory §6.4, loading + Masing unloading) force error, Hertz and
   cone, for N = 50 … 4000 springs, both spacings; error = max |F - F_ref| / max |F_ref| over the
   loop; run time per step. Written to ``foundation_accuracy.csv``.
2. Energy per cycle of oscillating twist: MDR foundation vs the EXACT (Jäger/Lubkin) Hertz
   torsion hysteresis (theory §6.3, §6.5, re-implemented here with scipy), for amplitudes up to
   near full sliding; the gap is printed and written to ``torsion_energy_gap.csv``.

Run: python benchmarks/foundation_accuracy.py [output_dir]
"""
from __future__ import annotations

import csv
import os
import sys
import time

import numpy as np
from scipy.integrate import quad
from scipy.optimize import brentq
from scipy.special import ellipe, ellipk

sys.path.insert(0, os.path.join(os.path.dirname(__file__), ".."))
import contactlab as cl  # noqa: E402

MU = 0.2
F = 100.0
STEEL = cl.Elastic(E=210e9, nu=0.3)
PMMA = cl.Elastic(E=3e9, nu=0.35)


def cm(FN, us, n, u):
    x = np.clip(np.abs(u) / us, 0, 1)
    return np.sign(u) * MU * FN * (1 - (1 - x) ** ((n + 1) / n))


def tangential_case(c, FN, n, N, spacing):
    ns = c.normal(force=FN)
    us = MU * c.moduli.normal * ns.depth / c.moduli.tangential
    u0 = 0.8 * us
    path = (cl.LoadPath().ramp(force=FN, steps=5).ramp(displacement=u0, steps=200)
            .ramp(displacement=-u0, steps=400).ramp(displacement=u0, steps=400))
    t0 = time.perf_counter()
    r = c.simulate(path, n_springs=N, spacing=spacing, strategy="steps", method="mdr")
    dt = (time.perf_counter() - t0) / path.n_steps
    u = r.displacement
    ref = np.empty_like(u)
    ref[5:205] = cm(FN, us, n, u[5:205])
    ref[205:605] = cm(FN, us, n, u0) - 2 * cm(FN, us, n, (u0 - u[205:605]) / 2)
    ref[605:] = -cm(FN, us, n, u0) + 2 * cm(FN, us, n, (u0 + u[605:]) / 2)
    return np.max(np.abs(r.tangential_force[5:] - ref[5:])) / np.max(np.abs(ref[5:])), dt


def torsion_case(c, N, spacing):
    """Hertz only (the MDR torsion closed form of §6.4 is for Hertz)."""
    a = c.normal(force=F).radius
    Gt = c.moduli.torsional

    def M(phi):
        beta = 16 * Gt * a ** 2 * np.abs(phi) / (3 * MU * F)
        t = np.sqrt(1 + beta ** 2 / 4) - beta / 2
        return np.sign(phi) * 0.75 * MU * F * a * (1 - t ** 2) * (1 + t ** 2 / 3)

    p0 = 3 * MU * F * (1 - 0.25) / (16 * Gt * a ** 2 * 0.5)
    path = (cl.LoadPath().ramp(force=F, steps=4).ramp(twist=p0, steps=100)
            .ramp(twist=-p0, steps=200))
    t0 = time.perf_counter()
    r = c.simulate(path, n_springs=N, spacing=spacing, strategy="steps", method="mdr")
    dt = (time.perf_counter() - t0) / path.n_steps
    ph = r.twist[4:]
    ref = np.concatenate([M(ph[:100]), M(p0) - 2 * M((p0 - ph[100:]) / 2)])
    return np.max(np.abs(r.torque[4:] - ref)) / np.max(np.abs(ref)), dt


# ---- exact Hertz torsion (Lubkin problem via Jäger), theory §6.3, §6.5
def exact_twist(c_over_a, a, Gt):
    m = 1 - c_over_a ** 2
    return 3 * MU * F / (4 * np.pi * Gt * a ** 2) * (ellipk(m) - ellipe(m))


def exact_torque(c_over_a, a):
    integral = quad(lambda s: s * s * ellipe(1 - s * s), 0, c_over_a, epsabs=0, epsrel=1e-12)[0]
    return MU * F * a * (3 * np.pi / 16 - 4 / np.pi * integral)


def exact_cycle_energy(phi0, a, Gt):
    """W = 4 φ0 M0 - 8 ∫_0^{M0} φ dM = 4φ0M0 - 8∫_{c0}^{a} φ(c) (-dM/dc) dc."""
    t0 = brentq(lambda t: exact_twist(t, a, Gt) - phi0, 1e-14, 1 - 1e-15, xtol=1e-15)
    M0 = exact_torque(t0, a)
    # dM/dt = -(4/π) μFa t² E(sqrt(1-t²))
    integ = quad(lambda t: exact_twist(t, a, Gt) * 4 / np.pi * MU * F * a * t * t
                 * ellipe(1 - t * t), t0, 1, epsabs=0, epsrel=1e-11, limit=200)[0]
    return 4 * phi0 * M0 - 8 * integ, t0


def main() -> None:
    outdir = sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(os.path.abspath(__file__))
    hertz = cl.Contact(cl.profiles.Paraboloid(R=0.01), materials=(STEEL, STEEL), friction=MU)
    cone = cl.Contact(cl.profiles.Cone(slope=0.1), materials=(STEEL, PMMA), friction=MU)
    rows = []
    print(f"{'N':>5} {'spacing':>8} {'tan Hertz':>10} {'tan cone':>10} {'torsion':>10} "
          f"{'µs/step (tan)':>14}")
    for N in (50, 100, 200, 400, 1000, 2000, 4000):
        for spacing in ("uniform", "edge"):
            eh, th = tangential_case(hertz, F, 2.0, N, spacing)
            ec, _ = tangential_case(cone, 5.0, 1.0, N, spacing)
            et, tt = torsion_case(hertz, N, spacing)
            rows.append({"n_springs": N, "spacing": spacing, "tangential_error_hertz": eh,
                         "tangential_error_cone": ec, "torsional_error_hertz": et,
                         "seconds_per_step_tangential": th, "seconds_per_step_torsion": tt})
            print(f"{N:5d} {spacing:>8} {eh:10.3e} {ec:10.3e} {et:10.3e} {th * 1e6:14.1f}")
    for spacing in ("uniform", "edge"):
        Ns = np.array([r["n_springs"] for r in rows if r["spacing"] == spacing])
        for key in ("tangential_error_hertz", "tangential_error_cone", "torsional_error_hertz"):
            e = np.array([r[key] for r in rows if r["spacing"] == spacing])
            order = -np.polyfit(np.log(Ns), np.log(e), 1)[0]
            print(f"fitted order, {spacing:>7}, {key}: {order:.2f}")
    path = os.path.join(outdir, "foundation_accuracy.csv")
    with open(path, "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    print("wrote", path)

    # ---- energy per cycle: MDR foundation vs exact torsion hysteresis
    a = hertz.normal(force=F).radius
    Gt = hertz.moduli.torsional
    print(f"\n{'c0/a exact':>10} {'phi0 [rad]':>11} {'W exact [J]':>12} {'W MDR [J]':>12} "
          f"{'MDR/exact-1':>12} {'M0 MDR/exact-1':>14}")
    erows = []
    for t_target in (0.999, 0.99, 0.95, 0.9, 0.7, 0.5, 0.3, 0.1, 0.03):
        phi0 = exact_twist(t_target, a, Gt)
        W_ex, t0 = exact_cycle_energy(phi0, a, Gt)
        spc = 400
        p = (cl.LoadPath().ramp(force=F, steps=2)
             .sinusoid(twist=phi0, cycles=2, steps_per_cycle=spc))
        r = hertz.simulate(p, n_springs=2000, method="mdr")
        W_mdr = r.dissipated_energy[2 + 2 * spc - 1] - r.dissipated_energy[2 + spc - 1]
        M0_mdr = np.max(r.torque[2 + spc:])
        M0_ex = exact_torque(t0, a)
        erows.append({"stick_ratio_exact": t0, "twist_amplitude": phi0, "W_exact": W_ex,
                      "W_mdr_foundation": W_mdr, "W_rel_gap": W_mdr / W_ex - 1,
                      "M0_rel_gap": M0_mdr / M0_ex - 1})
        print(f"{t0:10.4f} {phi0:11.4e} {W_ex:12.5e} {W_mdr:12.5e} {W_mdr / W_ex - 1:12.4e} "
              f"{M0_mdr / M0_ex - 1:14.4e}")
    path = os.path.join(outdir, "torsion_energy_gap.csv")
    with open(path, "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=list(erows[0]))
        w.writeheader()
        w.writerows(erows)
    print("wrote", path)


if __name__ == "__main__":
    main()
