"""MDR torsion validity check and ``simulate(method="mdr")`` on 10^6-point tables (issues 12, 13).

Run from the repository root: ``python benchmarks/large_tables_mdr.py [--whole] [N]``
(default N = 10^6 table points; uniform tables of a paraboloid, R = 10 mm, over 0.2 mm).

1. The validity check of a twisted path run on the MDR springs
   (``effects.path.mdr_path_validity``, torque and energy criteria) on a 10^4-step gait whose
   contact radius sweeps 30-170 µm, linear and cubic table: it takes the bounded rule of
   ``physics.torsion_validity`` (17 evaluations of g per limit, as many limits as its budget
   allows) instead of the exact slip function, whose composite table rule costs O(N²) (g at 8
   nodes per table segment, each g a sum over the nodes below it). The limits are compared with
   Jäger's closed form for Hertz contact at the same radius.
2. ``--whole``: a 200-step gait ``simulate(method="mdr", n_springs=200)`` on the same tables,
   CPU time per stage (normal states of the path, foundation build, time loop, validity check).
"""
from __future__ import annotations

import sys
import time
import warnings
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(Path(__file__).resolve().parent))

import contactlab as cl  # noqa: E402
from contactlab.effects import path as P  # noqa: E402
from contactlab.physics import torsion_validity as V  # noqa: E402
from _harness import cpu_timed, machine  # noqa: E402
from scipy.special import ellipe, ellipkm1  # noqa: E402

R, MU = 0.01, 0.3


def contact(n: int, interpolation: str) -> cl.Contact:
    r = np.linspace(0.0, 2e-4, n)
    return cl.Contact(cl.profiles.Tabulated(r, r * r / (2 * R), interpolation),
                      (cl.Elastic(E=210e9, nu=0.3),) * 2, friction=MU)


def hertz_twist(ratio: float, a: float, c: cl.Contact) -> float:
    """Jäger's twist at stick ratio c/a for Hertz contact of radius a."""
    F = 4 * c.moduli.normal * a**3 / (3 * R)
    return 3 * MU * F / (4 * np.pi * c.moduli.torsional * a * a) * (ellipkm1(ratio**2)
                                                                    - ellipe(1 - ratio**2))


def validity_section(n: int) -> None:
    print(f"\n1. validity check, 10^4-step gait, radius 30-170 um, {n:.0e}-point tables "
          f"(bounded rule above {V.BOUNDED_TABLE_NODES} nodes; CPU s):")
    steps = 10**4
    t = np.linspace(0.0, 1.0, steps)
    # 257 distinct radii (their depths g(a) computed once, outside the timing)
    grid = np.linspace(3e-5, 1.7e-4, 257)
    idx = np.rint((0.5 + 0.5 * np.sin(2 * np.pi * t)) * 256).astype(int)
    radius = grid[idx]
    twist = 2e-4 * np.sin(6 * np.pi * t)
    for interp in ("linear", "cubic"):
        c = contact(n, interp)
        t0 = time.process_time()
        c.profile._g(radius[:1])                # table set-up outside the timing
        setup = time.process_time() - t0
        depth = c.profile._g(grid)[idx]
        states = V.affordable_states(c.profile, float(radius.max()), P._VALIDITY_RADII)
        for q, ratio in (("torque", 0.83), ("energy", 0.97)):
            t0 = time.process_time()
            _, _, lim, a = P.mdr_path_validity(c, twist, radius, depth, q)
            dt = time.process_time() - t0
            ref = hertz_twist(ratio, a, c)
            print(f"  {interp:6s} {q:6s} {dt:6.2f} s ({states} radii; table set-up {setup:.2f} s)"
                  f"  limit {lim:.6g} rad at a = {a:.4g} m, Hertz {ref:.6g}: "
                  f"{abs(lim / ref - 1):.1e} relative")


def whole_section(n: int) -> None:
    print(f"\n2. 200-step gait simulate(method='mdr', n_springs=200), {n:.0e}-point tables, CPU s "
          "per stage:")
    from contactlab.foundation import winkler
    steps = 200
    t = np.linspace(0.0, 1.0, steps + 1)
    path = cl.LoadPath.from_arrays(time=t, force=5 + 4 * np.sin(2 * np.pi * t),
                                   twist=2e-4 * np.sin(6 * np.pi * t))
    warm = cl.Contact(cl.profiles.Paraboloid(R=R), (cl.Elastic(E=210e9, nu=0.3),) * 2,
                      friction=MU)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        warm.simulate(path, n_springs=200, method="mdr")        # compile outside the timing
    for interp in ("linear", "cubic"):
        c = contact(n, interp)
        acc = dict.fromkeys(("normal states", "foundation build", "validity check"), 0.0)
        saved = (P.iter_path_normal_states, winkler.Winkler._build, P.warn_mdr_path)

        # the whole normal solve at the call (a list), not leaf by leaf inside the time loop
        P.iter_path_normal_states = cpu_timed(lambda *a, **k: iter(list(saved[0](*a, **k))),
                                              acc, "normal states")
        winkler.Winkler._build = cpu_timed(saved[1], acc, "foundation build")
        P.warn_mdr_path = cpu_timed(saved[2], acc, "validity check")
        try:
            c0 = time.process_time()
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                c.simulate(path, n_springs=200, method="mdr")
            total = time.process_time() - c0
        finally:
            P.iter_path_normal_states, winkler.Winkler._build, P.warn_mdr_path = saved
        rest = total - sum(acc.values())
        parts = ", ".join(f"{k} {v:.1f}" for k, v in acc.items())
        print(f"  {interp:6s} total {total:7.1f} s = {parts}, time loop and rest {rest:.1f}")


def main() -> int:
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    n = int(float(args[0])) if args else 10**6
    print("Machine:", machine())
    validity_section(n)
    if "--whole" in sys.argv:
        whole_section(n)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
