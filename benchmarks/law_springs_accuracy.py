"""ContactLaw under a changing normal load (issue 14): error of the per-contact MDR springs
against the full foundation (Contact.simulate with its default 2000 edge-refined springs over the
path's largest radius), as a function of the springs per contact.

    python benchmarks/law_springs_accuracy.py

Twenty random Hertz contacts (R, moduli, friction, preload), each on a path that first twists
(or shifts) at a held load (exact Masing regime), then changes load and twist together in both
directions with reversals (spring regime, the held-load memory replayed into the springs). The
law runs as a DEM code would: springs over ``spring_cover = 1.5`` times the radius at the load
change, grown when the radius exceeds it. Reported: the largest torque (force) error over the
spring steps relative to the largest value of the path, and the error of the energy dissipated
since the load change relative to its final value.
"""
from __future__ import annotations

import sys
import warnings
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
import contactlab as cl                                     # noqa: E402
from benchmarks._harness import machine                     # noqa: E402

HELD = 14


def path(F0, chan, amp):
    return (cl.LoadPath().ramp(force=F0, steps=1)
            .ramp(**{chan: amp / 2}, steps=5).ramp(**{chan: -amp / 3}, steps=5)
            .ramp(**{chan: amp / 6}, steps=3)
            .ramp(force=2 * F0, **{chan: amp}, steps=40)
            .ramp(force=0.7 * F0, **{chan: -amp / 2}, steps=50)
            .ramp(force=1.5 * F0, **{chan: amp / 3}, steps=30).hold(steps=5)
            .ramp(**{chan: -amp}, steps=30)
            .ramp(force=0.3 * F0, steps=30))


def main() -> None:
    warnings.simplefilter("ignore")
    print(machine())
    rng = np.random.default_rng(7)
    n = 20
    R = rng.uniform(5e-3, 2e-2, n)
    mu = rng.uniform(0.2, 0.6, n)
    cons = [cl.Contact(cl.profiles.Paraboloid(R=R[i]),
                       materials=(cl.Elastic(E=rng.uniform(1e11, 2e11), nu=0.3),
                                  cl.Elastic(E=rng.uniform(1e11, 2e11), nu=0.25)),
                       friction=mu[i]) for i in range(n)]
    par = dict(R=R, friction=mu, E_star=np.array([c.moduli.normal for c in cons]),
               G_star=np.array([c.moduli.tangential for c in cons]),
               G_torsion=np.array([c.moduli.torsional for c in cons]))
    F0 = rng.uniform(5, 50, n)
    print(f"{'channel':>13} {'springs':>8} {'max |dy|/max|y|':>16} {'max |dW|/W':>15}")
    for chan, key in (("twist", "torque"), ("displacement", "tangential_force")):
        # amplitudes of about the full-slip scale at the preload: partial and gross slip
        d0 = np.array([c.normal(force=F0[i]).depth for i, c in enumerate(cons)])
        a0 = np.sqrt(R * d0)
        scale = (mu * par["E_star"] * d0 / (2 * par["G_torsion"] * a0) if chan == "twist"
                 else mu * par["E_star"] * d0 / par["G_star"])
        ref = [c.simulate(path(F0[i], chan, 1.5 * scale[i]), method="mdr") for i, c in enumerate(cons)]
        dep = np.stack([r.depth for r in ref], 1)
        x = np.stack([getattr(r, chan) for r in ref], 1)
        y_ref = np.stack([getattr(r, key) for r in ref], 1)
        W_ref = np.stack([r.dissipated_energy for r in ref], 1)
        for N in (8, 16, 32, 64):
            law = cl.ContactLaw(cl.profiles.Paraboloid, springs=N, **par)
            out = [law.step(depth=dep[k], **{chan: x[k]}) for k in range(dep.shape[0])]
            y = np.stack([getattr(o, key) for o in out])
            W = np.cumsum(np.stack([o.dissipated_energy for o in out]), 0)
            ey = np.max(np.abs(y - y_ref)[HELD:] / np.abs(y_ref).max(0))
            # energy dissipated since the load change (before it the law is exact and the
            # foundation is the MDR torsion model: a model difference, not a spring count one)
            dw, dw_ref = W[HELD:] - W[HELD - 1], W_ref[HELD:] - W_ref[HELD - 1]
            ew = np.max(np.abs(dw - dw_ref) / dw_ref.max(0))
            print(f"{chan:>13} {N:>8} {ey:>16.3g} {ew:>15.3g}", flush=True)


if __name__ == "__main__":
    main()
