"""Error map of the MDR torsion model against the exact (Jäger) solution.

For a paraboloid, a cone, a flat punch and a power law n = 4 this script prescribes the same twist
to both models and tabulates the relative torque error ``M_MDR/M_exact - 1`` against

* ``c/a`` of the exact solution and of the MDR model (the MDR warning uses the latter, the only
  one it knows without solving the exact problem), and
* ``φ/φ_ref`` with ``φ_ref = 3 M_full/(16 G_t a³)``, the twist at which the no-slip line reaches the
  exact full-sliding torque (a profile-independent scale; smooth profiles have no finite
  twist of full sliding).

Writes ``benchmarks/results/torsion_error_map.csv`` and, if matplotlib is installed,
``torsion_error_map.png``; prints the table and the smallest MDR ``c/a`` with error <= 1 %.

Run: ``python benchmarks/torsion_error_map.py`` from the repository root.
"""
from __future__ import annotations

import csv
import sys
import warnings
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

import contactlab as cl  # noqa: E402
sys.path.insert(0, str(Path(__file__).resolve().parent))
from _harness import machine  # noqa: E402  (one machine description for every benchmark)
from contactlab.errors import ValidityWarning  # noqa: E402

OUT = Path(__file__).resolve().parent / "results"
RATIOS = np.array([0.999, 0.995, 0.99, 0.98, 0.95, 0.92, 0.9, 0.88, 0.86, 0.85, 0.84, 0.83, 0.82,
                   0.81, 0.8,
                   0.75, 0.7, 0.6, 0.5, 0.4, 0.3, 0.2, 0.1, 0.05, 0.01, 0.001])


def cases():
    mat = cl.Elastic(E=1.0e9, nu=0.3)
    yield "paraboloid", cl.Contact(cl.profiles.Paraboloid(R=1.0), (mat, cl.Rigid()), friction=0.5), 0.01
    yield "cone", cl.Contact(cl.profiles.Cone(slope=0.1), (mat, cl.Rigid()), friction=0.5), 0.01
    yield "flat_punch", cl.Contact(cl.profiles.FlatPunch(radius=0.01), (mat, cl.Rigid()),
                                   friction=0.5), 1e-4
    yield "power_law_n4", cl.Contact(cl.profiles.PowerLaw(c=1e4, n=4), (mat, cl.Rigid()),
                                     friction=0.5), 0.01
    yield "power_law_n20", cl.Contact(cl.profiles.PowerLaw(c=1e30, n=20), (mat, cl.Rigid()),
                                      friction=0.5), 0.01
    yield "truncated_paraboloid", cl.Contact(cl.profiles.TruncatedParaboloid(radius=0.005, R=1.0),
                                             (mat, cl.Rigid()), friction=0.5), 0.01


def main() -> list[dict]:
    rows = []
    for name, contact, load in cases():
        key = "depth" if name == "flat_punch" else "radius"
        if name == "flat_punch":
            ex = contact.torsion(depth=load, stick_radius=RATIOS * contact.profile.radius)
        else:
            ex = contact.torsion(radius=load, stick_radius=RATIOS * load)
        a = ex.radius
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", ValidityWarning)
            md = contact.torsion(**{key: load}, twist=ex.twist, method="mdr")
        G = contact.moduli.torsional
        phi_ref = 3 * ex.sliding_torque / (16 * G * a**3)
        err = md.torque / ex.torque - 1
        for i, r in enumerate(RATIOS):
            rows.append({"profile": name, "c_over_a_exact": r, "c_over_a_mdr": md.stick_radius[i] / a[i],
                         "twist_over_ref": ex.twist[i] / phi_ref[i],
                         "torque_exact_over_full": ex.torque[i] / ex.sliding_torque[i],
                         "mdr_torque_error": err[i]})
    return rows


def threshold(rows: list[dict], key: str, limit: float = 0.01) -> tuple[float, str]:
    """Largest c/a (exact or MDR, by ``key``) at which some profile's error exceeds ``limit``."""
    worst, who = 0.0, ""
    for r in rows:
        if abs(r["mdr_torque_error"]) > limit and r[key] > worst:
            worst, who = r[key], r["profile"]
    return worst, who


if __name__ == "__main__":
    rows = main()
    OUT.mkdir(exist_ok=True)
    with open(OUT / "torsion_error_map.csv", "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    print(f"machine: {machine()}")
    print(f"{'profile':20s} {'c/a exact':>9s} {'c/a MDR':>9s} {'phi/phi_ref':>11s} {'M/M_full':>9s} "
          f"{'MDR error':>10s}")
    for r in rows:
        print(f"{r['profile']:20s} {r['c_over_a_exact']:9.4g} {r['c_over_a_mdr']:9.4g} "
              f"{r['twist_over_ref']:11.4g} {r['torque_exact_over_full']:9.4g} "
              f"{r['mdr_torque_error']:+10.3%}")
    t, who = threshold(rows, "c_over_a_mdr")
    te, whoe = threshold(rows, "c_over_a_exact")
    print(f"MDR torque error > 1 % first at MDR c/a = {t:.4g} ({who}), "
          f"at exact c/a = {te:.4g} ({whoe}); "
          "contactlab warns where the exact c/a < MDR_VALID_STICK_RATIO = "
          f"{cl.effects.torsion.MDR_VALID_STICK_RATIO}")
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("matplotlib not installed (pip install matplotlib): plot skipped")
    else:
        fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(10, 4))
        for name in dict.fromkeys(r["profile"] for r in rows):
            sel = [r for r in rows if r["profile"] == name]
            ax1.semilogy([r["c_over_a_mdr"] for r in sel], [abs(r["mdr_torque_error"]) for r in sel],
                         "o-", label=name)
            ax2.loglog([r["twist_over_ref"] for r in sel], [abs(r["mdr_torque_error"]) for r in sel],
                       "o-", label=name)
        for ax in (ax1, ax2):
            ax.axhline(0.01, color="k", lw=0.8, ls="--")
            ax.set_ylabel("|M_MDR / M_exact - 1| at equal twist")
            ax.legend()
        ax1.set_xlabel("c/a (MDR)")
        ax2.set_xlabel("φ / φ_ref")
        fig.tight_layout()
        fig.savefig(OUT / "torsion_error_map.png", dpi=120)
        print(f"plot: {OUT / 'torsion_error_map.png'}")
