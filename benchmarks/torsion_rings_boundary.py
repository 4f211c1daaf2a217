"""The stick–slip boundary inside a ring: what limits the ring solver at constant load (issue 18).

At constant normal force the exact punch density of a twisted Hertz contact is ``W(t)`` on the
slip annulus ``c < t < a`` and zero inside the stick radius ``c``: it jumps at ``c``. The solver's
hats are continuous, so the ring holding ``c`` smears that jump, and its points switch between
stick and slip one whole ring at a time. This study takes one monotone twist step from rest
(normalised Hertz contact, a = 1, G_t = 1, p0 = 1, μ = 0.3) to the twist of a given stick radius
``c`` (23 values, c/a = 0.30 … 0.97) and compares the torque with the exact
``M(c) = μFa [3π/16 − (4/π) ∫_0^{c/a} s² E(sqrt(1 − s²)) ds]`` for

1. the solver's basis (uniform hats, midpoints);
2. a node at the exact ``c`` where the density may jump (``torsion_rings.influence(jumps=...)``)
   and a collocation point on ``c``, the active set found by the solver;
3. the same basis with the active set fixed at the exact one (points at or beyond ``c`` at μp).

4. the solver's punch-density step (``physics.torsion_annulus.step``): the stick radius solved
   inside its ring, the density jumping there, the full-sliding density from the hats.

Row 3 is what placing the boundary inside its ring would buy; row 2 shows that the basis alone is
not enough (the discrete boundary still lands a point or two off); row 4 is what the solver does
since (it needs no exact ``c``). Max error over ``c`` of the
sliding torque per ring count. Run: ``python benchmarks/torsion_rings_boundary.py``.
"""
from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
from scipy.integrate import quad
from scipy.special import ellipe, ellipk

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from contactlab.physics import torsion_annulus as ta  # noqa: E402
from contactlab.physics import torsion_rings as tr  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _harness import machine  # noqa: E402

G, MU, P0 = 1.0, 0.3, 1.0
F = 2 * np.pi * P0 / 3
M_FULL = 3 * np.pi / 16 * MU * F
RATIOS = np.linspace(0.3, 0.97, 23) + 0.0012345      # off the ring midpoints


def twist(c):
    m = 1 - c * c
    return 3 * MU * F / (4 * np.pi * G) * (ellipk(m) - ellipe(m))


def torque(c):
    return MU * F * (3 * np.pi / 16 - 4 / np.pi * quad(lambda s: s * s * ellipe(1 - s * s), 0, c,
                                                       epsabs=0, epsrel=1e-13)[0])


def bound(r):
    return MU * P0 * np.sqrt(np.clip(1 - r * r, 0, None))


def step(n, c, variant):
    b = np.linspace(0.0, 1.0, n + 1)
    if variant == "annulus":
        r = 0.5 * (b[1:] + b[:-1])
        m = tr.influence(b, r, G)
        slide = ta.density(m["lu"], b, np.zeros(0, int), bound(r), 1.0)
        w = ta.step(ta.empty(), slide, 1.0, G, dphi=twist(c), r=r, bound=bound(r))["w"]
        return abs(ta.torque(w, G) - torque(c)) / M_FULL
    if variant == "hats":
        r = 0.5 * (b[1:] + b[:-1])
        m = tr.influence(b, r, G)
    else:
        b = np.union1d(b, [c])
        r = np.sort(np.append(0.5 * (b[1:] + b[:-1]), c))
        m = tr.influence(b, r, G, jumps=tr.radius_nodes(b, [c]))
    H, g = m["H"], m["g"]
    if variant != "fixed":
        z = tr.box_step(H, g, np.zeros(r.size), bound(r), dphi=twist(c), C=m["C"])[0]
    else:
        A = r >= c
        z = np.where(A, bound(r), 0.0)
        z[~A] = np.linalg.solve(H[np.ix_(~A, ~A)], twist(c) * g[~A] - H[np.ix_(~A, A)] @ z[A])
    return abs(g @ z - torque(c)) / M_FULL


def main():
    print(machine())
    print("one monotone step from rest, max torque error over c/a = 0.30..0.97 (of M_full)")
    print(f"  {'rings':>5s}  {'hats':>9s}  {'jump at c':>9s}  {'jump at c, exact active set':>27s}"
          f"  {'punch-density step':>18s}")
    for n in (25, 50, 100, 200):
        e = [max(step(n, c, v) for c in RATIOS) for v in ("hats", "jump", "fixed", "annulus")]
        print(f"  {n:5d}  {e[0]:9.2e}  {e[1]:9.2e}  {e[2]:27.2e}  {e[3]:18.2e}")


if __name__ == "__main__":
    main()
