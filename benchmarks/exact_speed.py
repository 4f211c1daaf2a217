"""Speed of the exact torsion routes against their floors or the other route (issue 28).

Run from the repository root: ``python benchmarks/exact_speed.py [--rounds N] [--long]
[--scaling-only {all,default,rtol}] [--paths-only] [--curves-only]`` (``--scaling-only``: row 2
alone, at both ring choices or one, best of ``--rounds`` with ``--long``; ``--paths-only``: the
rows of row 1 alone, quick enough for many ``--rounds``).

Every row is measured interleaved in this one run (round-robin, the order rotated each round,
best of ``--rounds``) and reported as a ratio to its floor (a route of the same work), with a
verdict on the row's goal, so the machine's load mostly cancels; the machine and its load
average are printed. Rows and goals:

1. the 180-step varying-load twisted Hertz path, ``simulate(path, method="exact")`` (default
   rings): with BLAS set to two threads vs one (goal: within 1.2x, bit-identical), cold (ring
   matrices built) and warm (reused), against ``method="mdr"`` on the same path; goal <= 50 ms;
   and at the rings chosen for the goal's accuracy, ``simulate(path, torque_rtol=1e-3)`` (one and
   two BLAS threads), with its largest torque error against a 400-ring run, relative to the
   path's largest sliding torque (measured outside the timed rounds); the same with the punch
   densities' numpy route (``CONTACTLAB_BACKEND=numpy``'s, the reference of the stored hashes)
   against the compiled passes (numba), with their bit-identity;
2. the ring solver's cost per step against the path length: the same path shape with 10^2 and
   10^3 steps (and 10^4 with ``--long``), at the default rings and at ``torque_rtol=1e-3``, the
   exponent of time against steps fitted over all the lengths (goal <= 1.05, the issue's
   10^2..10^4 with ``--long``; the exponent between the two longest beside it; the shorter paths
   repeated within a round, every path warmed up untimed), with the ring counts, jump nodes,
   ring-solver steps and steps whose contact radius lies off a ring node; first each path on the
   rings it chooses (a longer path meets more distinct contact radii than the capped nodes can
   take, so more of its steps have their edge off a node, which cost more; at ``torque_rtol``
   a path whose contact radii would take more than 1.5x the rings as nodes is covered by the
   fewest nodes that keep each radius within 0.24 ring widths of one, a count set by the span
   of its radii, not by how many it meets), then all paths on the longest path's ring set (the
   cost per step at equal rings: whether anything grows with the history), then the shortest
   path on each path's ring set with and without its jump points (the cost per step against the
   collocation points and the nodes: the ring set's size alone);
3. ``Contact.torsion(method="mdr")`` on 10^5 forces, against ``method="no-slip"`` on the same
   forces; goal <= 0.1 s;
4. the exact torque-twist curve (200 twists, Hertz) against its floor, the closed form of the same
   curve written out with numpy (200 stick radii, no contact set-up); goal <= 2 ms;
5. the exact curve (200 twists) on a 1000-point table, against its MDR curve; goal <= 50 ms;
6. the exact curve (200 and 1000 twists) on a 1000-point linear table sampling the Hertz
   paraboloid out to 1.5 contact radii, so that 667 nodes lie in contact (the table of row 5 has
   only 94), against the closed-form exact Hertz curve of the same twists (the route of row 4 on
   the paraboloid the table samples) and against the composite route it replaced (every whole
   segment on its 8-point rule: the stick-radius solve and torque integral with
   ``panels=False``, without the call's normal solve and bookkeeping, so a little cheaper than
   the old call); goal <= 50 ms. Its torques are printed against both: the closed form differs
   by the table's interpolation error, the composite route by the panels' error.
"""
from __future__ import annotations

import argparse
import hashlib
import os
import sys
import time
import warnings
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
sys.path.insert(0, str(Path(__file__).resolve().parent))

import contactlab as cl
from contactlab.foundation import rings as _rings
from contactlab.physics import torsion_annulus as _ta
from contactlab.physics import torsion_rings as _tr
from _harness import machine

MAT = (cl.Elastic(E=210e9, nu=0.3), cl.Rigid())
MU = 0.3
#: the accuracy of the path row's goal (of the path's largest sliding torque)
RTOL = 1e-3


def _hertz() -> cl.Contact:
    return cl.Contact(cl.profiles.Paraboloid(R=0.01), materials=MAT, friction=MU)


def path_force(n: int = 180) -> np.ndarray:
    """The normal force of :func:`varying_path`, N: 10 N ± 40 % at two cycles."""
    t = np.arange(1, n + 1) / n
    return 10.0 * (1 + 0.4 * np.sin(2 * np.pi * 2 * t + 0.3))


def varying_path(c: cl.Contact, n: int = 180):
    """Force 10 N ± 40 % at two cycles, twist at 80 % of sliding at three cycles (ramped in)."""
    t = np.arange(1, n + 1) / n
    force = path_force(n)
    a_max = float(np.max(c.normal(force=force)._radius))
    s = MU * 10.0 / (c.moduli.torsional * a_max ** 2)
    phi = 0.8 * s * np.sin(2 * np.pi * 3 * t) * np.minimum(1, 2 * t)
    return cl.LoadPath.from_arrays(force=force, twist=phi)


def _digest(r) -> str:
    return hashlib.sha256(np.ascontiguousarray(r.torque).tobytes()
                          + np.ascontiguousarray(r.dissipated_energy).tobytes()).hexdigest()[:16]


def cases() -> dict:
    """name -> zero-argument callable (each returns something to keep)."""
    from threadpoolctl import threadpool_limits

    c = _hertz()
    path = varying_path(c)

    def exact_threads(n, **kw):
        def run():
            with threadpool_limits(n, user_api="blas"):
                return c.simulate(path, method="exact", **kw)
        return run

    def exact_route(compiled, **kw):
        def run():
            _ta._COMPILED["on"] = compiled
            try:
                return c.simulate(path, method="exact", **kw)
            finally:
                _ta._COMPILED["on"] = None
        return run

    def exact_cold():
        # the default rings' matrices built again; the other ring sets' kept (else the row
        # after this one, torque_rtol's rings, would time a build as well)
        saved = dict(_rings._CACHE)
        _rings._CACHE.clear()
        try:
            return c.simulate(path, method="exact")
        finally:
            _rings._CACHE.update({k: v for k, v in saved.items() if k not in _rings._CACHE})

    F = np.linspace(1.0, 100.0, 100_000)
    a10 = float(c.normal(force=10.0)._radius)
    s10 = MU * 10.0 / (c.moduli.torsional * a10 ** 2)
    twists = np.linspace(0.0, 0.95, 200) * s10
    r_tab = np.linspace(0.0, 4e-4, 1000)
    tab = cl.Contact(cl.profiles.Tabulated(r=r_tab, f=r_tab ** 2 / 0.02 + 2e3 * r_tab ** 3),
                     materials=MAT, friction=MU)
    dense = dense_table(c, a10)
    twists_1000 = np.linspace(0.0, 0.95, 1000) * s10
    return {
        "path exact, BLAS 1 thread": exact_threads(1),
        "path exact, BLAS 2 threads": exact_threads(2),
        "path exact, cold (matrices built)": exact_cold,
        "path exact rtol 1e-3, BLAS 1 thread": exact_threads(1, torque_rtol=RTOL),
        "path exact rtol 1e-3, BLAS 2 threads": exact_threads(2, torque_rtol=RTOL),
        "path exact rtol 1e-3, numpy route": exact_route(False, torque_rtol=RTOL),
        "path exact rtol 1e-3, compiled route": exact_route(True, torque_rtol=RTOL),
        "path mdr": lambda: c.simulate(path, method="mdr"),
        "torsion mdr, 1e5 forces": lambda: c.torsion(force=F, twist=2e-4, method="mdr"),
        "torsion no-slip, 1e5 forces": lambda: c.torsion(force=F, twist=2e-4, method="no-slip"),
        "curve exact, Hertz 200": lambda: c.torsion(force=10.0, twist=twists, method="exact"),
        "curve closed form (numpy), Hertz 200": lambda: hertz_floor(a10, 10.0),
        "curve mdr, Hertz 200": lambda: c.torsion(force=10.0, twist=twists, method="mdr"),
        "curve exact, table 1000": lambda: tab.torsion(force=10.0, twist=twists, method="exact"),
        "curve mdr, table 1000": lambda: tab.torsion(force=10.0, twist=twists, method="mdr"),
        "curve exact, 667 in contact, 200": lambda: dense.torsion(force=10.0, twist=twists,
                                                                  method="exact"),
        "curve exact, Hertz closed form, 200": lambda: c.torsion(force=10.0, twist=twists,
                                                                 method="exact"),
        "curve exact, 667 in contact, 1000": lambda: dense.torsion(force=10.0, twist=twists_1000,
                                                                   method="exact"),
        "curve exact, Hertz closed form, 1000": lambda: c.torsion(force=10.0, twist=twists_1000,
                                                                  method="exact"),
        "curve composite (old), 667, 200": lambda: composite_curve(dense, twists),
        "curve composite (old), 667, 1000": lambda: composite_curve(dense, twists_1000),
    }


def composite_curve(c: cl.Contact, phi: np.ndarray, force: float = 10.0) -> np.ndarray:
    """Torques of the exact curve by the composite route the panels replaced (whole segments on
    the 8-point rule): root of μP(c)/(2G_t) = φ, then M = (16/3) G_t φ c³ + 8μT(c)."""
    from contactlab.physics import torsion_exact as te
    n = c.normal(force=force)
    a, d = float(n._radius), float(n._depth)
    A, D = np.full(phi.shape, a), np.full(phi.shape, d)
    G = np.full(phi.shape, float(c.profile._g(np.array(a))))
    E, G_t = c.moduli.normal, c.moduli.torsional
    cc = te.solve_stick_of_twist(c.profile, E, G_t, MU, phi, A, D, G, c.rtol, panels=False)
    T, _ = te.torque_integral(c.profile, E, cc, A, D, G, c.rtol, panels=False)
    return np.where(cc < a, 16.0 / 3.0 * G_t * phi * cc**3 + 8.0 * MU * T, 0.0)


def dense_table(c: cl.Contact, a: float) -> cl.Contact:
    """A 1000-point linear table of the paraboloid of ``c`` out to ``1.5 a``: at the force of
    contact radius ``a`` two thirds of its nodes (667) lie in contact."""
    r = np.linspace(0.0, 1.5 * a, 1000)
    prof = cl.profiles.Tabulated(r=r, f=r**2 / (2 * float(c.profile.R)))
    return cl.Contact(prof, materials=MAT, friction=MU)


_GL = np.polynomial.legendre.leggauss(32)


def hertz_floor(a: float, force: float, n: int = 200):
    """The floor of the Hertz curve: Lubkin's closed form at ``n`` stick radii written out with
    numpy/scipy (twist ``3μF/(4πG_t a²) (K − E)``, torque ``μFa (4/π) ∫_t^1 s² E ds`` by one
    32-point Gauss rule), no contact, normal solve or error estimate."""
    from scipy.special import ellipe, ellipk
    G_t = _hertz().moduli.torsional
    t = np.linspace(1e-3, 1.0, n)
    m = 1.0 - t * t
    phi = 3 * MU * force / (4 * np.pi * G_t * a * a) * (ellipk(m) - ellipe(m))
    s = t[:, None] + (1.0 - t[:, None]) * 0.5 * (_GL[0][None, :] + 1.0)
    M = MU * force * a * 4 / np.pi * (1.0 - t) * 0.5 * ((s * s * ellipe(1.0 - s * s)) @ _GL[1])
    return phi, M


#: (row, floor row, goal on the row's time in s or None, goal on the ratio or None)
ROWS = [
    ("path exact, BLAS 2 threads", "path exact, BLAS 1 thread", None, 1.2),
    ("path exact, BLAS 1 thread", "path mdr", 0.05, None),
    ("path exact, cold (matrices built)", "path exact, BLAS 1 thread", None, None),
    ("path exact rtol 1e-3, BLAS 1 thread", "path mdr", 0.05, None),
    ("path exact rtol 1e-3, BLAS 2 threads", "path exact rtol 1e-3, BLAS 1 thread", None, 1.2),
    ("path exact rtol 1e-3, numpy route", "path mdr", 0.05, None),
    ("path exact rtol 1e-3, compiled route", "path exact rtol 1e-3, numpy route", 0.05, None),
    ("torsion mdr, 1e5 forces", "torsion no-slip, 1e5 forces", 0.1, None),
    ("curve exact, Hertz 200", "curve closed form (numpy), Hertz 200", 0.002, None),
    ("curve exact, table 1000", "curve mdr, table 1000", 0.05, None),
    ("curve exact, 667 in contact, 200", "curve exact, Hertz closed form, 200", 0.05, None),
    ("curve exact, 667 in contact, 1000", "curve exact, Hertz closed form, 1000", 0.05, None),
    ("curve exact, 667 in contact, 200", "curve composite (old), 667, 200", None, None),
    ("curve exact, 667 in contact, 1000", "curve composite (old), 667, 1000", None, None),
]


def path_error(r) -> float:
    """Largest torque error of the run ``r`` of the path row against 400 rings, relative to the
    path's largest full-sliding torque ``2π μ ∫ p r² dr`` (the exact torsion model)."""
    from contactlab.physics.torsion import METHODS
    c = _hertz()
    path = varying_path(c)
    ref = c.simulate(path, method="exact", n_rings=400).torque
    ns = c.normal(force=path_force(180))   # varying_path's
    model = METHODS["exact"](c.profile, c.moduli.normal, c.moduli.torsional, MU, c.rtol)
    M = model.sliding_torque(np.asarray(ns._radius, float), np.asarray(ns._depth, float))
    return float(np.max(np.abs(r.torque - ref)) / np.max(M))


def verdict(t: float, ratio: float, goal_t: float | None, goal_r: float | None) -> str:
    """The row's goals and whether this run met them."""
    parts = []
    if goal_t is not None:
        parts.append(f"time <= {goal_t * 1e3:g} ms " + ("met" if t <= goal_t else "NOT met"))
    if goal_r is not None:
        parts.append(f"ratio <= {goal_r:g} " + ("met" if ratio <= goal_r else "NOT met"))
    return "; ".join(parts) or "(reported)"


class _RingSets:
    """Records the ring set each run builds (``Rings.for_path``) and, while ``fixed`` holds one,
    hands that set to every run instead (the benchmark's paths of 10^2, 10^3 and 10^4 steps
    sample the same shape at nested instants, so the longest path's ring set covers every
    contact radius of the shorter ones)."""

    def __init__(self):
        self.orig = _rings.Rings.__dict__["for_path"]
        self.last = None
        self.fixed = None

    def __enter__(self):
        rec = self

        def for_path(cls, *a, **k):
            fnd = rec.fixed if rec.fixed is not None else rec.orig.__func__(cls, *a, **k)
            rec.last = fnd
            return fnd
        _rings.Rings.for_path = classmethod(for_path)
        return self

    def __exit__(self, *exc):
        _rings.Rings.for_path = self.orig


def _off_node(fnd, radii) -> int:
    """Steps whose contact radius is not a ring node (inside the aligned range)."""
    b = fnd.boundaries
    h = float(b[-1]) / fnd.n_uniform
    a = np.asarray(radii, float)
    a = a[(a > _tr.ALIGN_MERGE * h) & (a <= b[-1])]
    return int(np.count_nonzero(~np.isin(a, b)))


def scaling(steps: list[int], rounds: int, **kw) -> None:
    """Ring-solver time per step against the path length (same path shape, CPU time, best of
    ``rounds``, a path of ``n`` steps run ``steps[-1] // (5 n)`` times a round), the fitted
    exponent of time against steps (goal <= 1.05), and what grows with the length: rings (nodes
    added at the contact radii met, at most 1.5x the rings by default; at ``torque_rtol`` beyond
    1.5x the fewest that keep every contact radius within 0.24 ring widths of one, up to 3x),
    jump nodes, ring-solver steps and the steps whose contact radius is off a node (more
    distinct contact radii than the cap allows nodes for). Then the same paths on one fixed
    ring set (the longest path's): the per-step cost at equal rings."""
    c = _hertz()
    paths = {n: varying_path(c, n) for n in steps}
    radii = {n: c.normal(force=path_force(n))._radius for n in steps}
    label = ", ".join(f"{k}={v:g}" for k, v in kw.items()) or "default rings"
    own: dict = {}
    own_info: dict = {}
    own_sets: dict = {}
    with warnings.catch_warnings(), _RingSets() as sets:
        warnings.simplefilter("ignore")
        for fixed in (False, True):
            if fixed:       # the last run above was the longest path's
                sets.fixed = sets.last
            best = dict.fromkeys(steps, np.inf)
            info = {}
            for n in steps:         # untimed: the ring set's build (its matrices are cached)
                c.simulate(paths[n], method="exact", **kw)
            for _ in range(rounds):
                for n in steps:
                    # the shorter paths repeated within the round (best of all: a 10^2-step run
                    # takes ~20 ms, where one hiccup of the machine moved the fit by 0.05)
                    for _ in range(max(1, steps[-1] // (5 * n))):
                        t0 = time.process_time()
                        r = c.simulate(paths[n], method="exact", **kw)
                        best[n] = min(best[n], time.process_time() - t0)
                    info[n] = (r.meta["rings"], r.meta["jump_nodes"], r.meta["fallback_steps"],
                               _off_node(sets.last, radii[n]))
                    if not fixed:
                        own_sets[n] = sets.last
            head = (f"{label}, fixed ring set (the {steps[-1]}-step path's)" if fixed
                    else f"{label}, each path's own ring set")
            print(f"\n{head}:")
            print(f"{'steps':>7s} {'ms/step':>8s} {'rings':>6s} {'jumps':>6s} "
                  f"{'ring-solver steps':>18s} {'edge off node':>14s}")
            for n in steps:
                print(f"{n:7d} {best[n] / n * 1e3:8.3f} {info[n][0]:6d} {info[n][1]:6d} "
                      f"{info[n][2]:18d} {info[n][3]:14d}")
            x = np.log(np.array(steps, float))
            y = np.log(np.array([best[n] for n in steps]))
            k = float(np.polyfit(x, y, 1)[0])
            # the verdict is the issue's: the exponent fitted over all the lengths (10^2..10^4
            # with --long); the exponent between the two longest paths is printed beside it
            # (every path warmed up untimed: none pays its ring set's build in the rounds)
            tail = float((y[-1] - y[-2]) / (x[-1] - x[-2]))
            print(f"exponent of time against steps, fit {steps[0]}..{steps[-1]}: {k:.3f} "
                  "(goal <= 1.05: " + ("met" if k <= 1.05 else "NOT met") + "); "
                  f"between {steps[-2]} and {steps[-1]}: {tail:.3f}")
            if not fixed:
                own, own_info = best, info
        n0 = steps[0]
        cap = _tr.ALIGN_MAX_FACTOR_RTOL if "torque_rtol" in kw else _tr.ALIGN_MAX_FACTOR
        more = (f" and it runs on {info[n0][0]} rings, not {own_info[n0][0]} (nodes at the "
                f"contact radii met, up to {cap:g}x the rings"
                + (f"; beyond {_tr.ALIGN_EXACT_FACTOR:g}x the fewest that keep every contact "
                   f"radius within {_rings.COVER_OFF_NODE:g} ring widths of one)"
                   if "torque_rtol" in kw else ")")
                if info[n0][0] != own_info[n0][0] else "")
        print(f"the {n0}-step path on its own rings vs the {steps[-1]}-step path's: "
              f"{own[n0] / n0 * 1e3:.3f} vs {best[n0] / n0 * 1e3:.3f} ms/step: on the longer "
              f"path's rings {info[n0][3]} of its steps, not {own_info[n0][3]}, have their "
              f"contact radius off a node{more}; a step with its edge off a node costs more "
              "(its full-sliding density has a negative band to remove, and more steps take "
              "the ring solver). What grows with the path at its own rings is the ring set "
              "(from the distinct contact radii it meets), not the history")
        ring_set_sweep(c, paths, own_sets, sets, rounds, **kw)


def ring_set_sweep(c: cl.Contact, paths: dict, own_sets: dict, sets: "_RingSets", rounds: int,
                   **kw) -> None:
    """The shortest path on the ring set of each path (``own_sets``), and on the same nodes
    without the jump points (one collocation point per contact-radius node fewer): its cost per
    step against the collocation points and nodes, the ring set's size alone (CPU time, best of
    ``rounds`` + 1, interleaved). Most of a step's work is products and solves of the points by
    the nodes (the full-sliding density's LU solve, the traction check inside the stick radius,
    the table sums), so the cost grows faster than the nodes where the jump points grow faster
    than the nodes."""
    n0 = min(paths)
    n_rings = _rings.rings_for_rtol(kw["torque_rtol"]) if "torque_rtol" in kw else None
    factor = _tr.ALIGN_MAX_FACTOR_RTOL if "torque_rtol" in kw else _tr.ALIGN_MAX_FACTOR
    cover = _rings.COVER_OFF_NODE if "torque_rtol" in kw else None
    cases = {}
    for n, fnd in own_sets.items():
        cases[n, True] = fnd
        bare = _rings.Rings(c.profile, c.moduli, MU, fnd.radius, n_springs=fnd.n_uniform,
                            contact_radii=c.normal(force=path_force(n))._radius, jumps=False,
                            align_factor=factor, align_cover=cover)
        bare.switches = dict(getattr(fnd, "switches", {}), jumps=False)
        cases[n, False] = bare
    best = dict.fromkeys(cases, np.inf)
    for _ in range(rounds + 1):
        for key, fnd in cases.items():
            sets.fixed = fnd
            t0 = time.process_time()
            c.simulate(paths[n0], method="exact", n_rings=n_rings)
            best[key] = min(best[key], time.process_time() - t0)
    sets.fixed = None
    print(f"the {n0}-step path on each path's ring set, with and without the jump points:")
    print(f"{'ring set of':>12s} {'nodes':>6s} {'points':>7s} {'ms/step':>8s} "
          f"{'points (no jumps)':>18s} {'ms/step':>8s}")
    for n in own_sets:
        a, b = cases[n, True], cases[n, False]
        print(f"{n:7d} steps {a.n_springs:6d} {a.points.size:7d} {best[n, True] / n0 * 1e3:8.3f} "
              f"{b.points.size:18d} {best[n, False] / n0 * 1e3:8.3f}")


def path_summary(best: dict, keep: dict) -> None:
    """The path rows' BLAS-thread ratio, bit-identity and accuracy at ``torque_rtol``."""
    same = _digest(keep["path exact, BLAS 1 thread"]) == _digest(keep["path exact, BLAS 2 threads"])
    ratio = best["path exact, BLAS 2 threads"] / best["path exact, BLAS 1 thread"]
    print(f"\nBLAS 2 vs 1 thread: ratio {ratio:.2f} (goal <= 1.2), results bit-identical: {same}")
    r1, r2 = keep["path exact rtol 1e-3, BLAS 1 thread"], keep["path exact rtol 1e-3, BLAS 2 threads"]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        err = path_error(r1)
    print(f"torque_rtol={RTOL:g}: {r1.meta['n_rings']} rings ({r1.meta['rings']} with the nodes at "
          f"the contact radii), torque error {err:.2e} of the sliding torque (goal <= {RTOL:g}: "
          + ("met" if err <= RTOL else "NOT met") + "), BLAS 1 vs 2 threads bit-identical: "
          f"{_digest(r1) == _digest(r2)}")


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--long", action="store_true", help="scaling up to 10^4 steps (~2 min)")
    ap.add_argument("--scaling-only", choices=("all", "default", "rtol"),
                    help="only row 2 (the cost per step against the path length): at both ring "
                    "choices, the default rings or torque_rtol's")
    ap.add_argument("--paths-only", action="store_true",
                    help="only the row-1 path rows (quick: compare two checkouts with many "
                    "--rounds), no curves or scaling")
    ap.add_argument("--curves-only", action="store_true",
                    help="only the torque-twist curve rows (4-6), no path rows or scaling")
    args = ap.parse_args()
    print("Machine:", machine())
    print("load average (1, 5, 15 min):", os.getloadavg())
    if args.scaling_only:
        _scaling_rows(args, {"all": ({}, {"torque_rtol": RTOL}), "default": ({},),
                             "rtol": ({"torque_rtol": RTOL},)}[args.scaling_only])
        print("load average after:", os.getloadavg())
        return 0
    fns = cases()
    if args.curves_only:
        fns = {k: v for k, v in fns.items() if k.startswith("curve")}
    if args.paths_only:
        fns = {k: v for k, v in fns.items() if k.startswith("path")}
    best = dict.fromkeys(fns, np.inf)
    keep: dict = {}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        names = list(fns)
        for k in range(args.rounds):
            # the order rotated each round: no row always runs right after the same one (the
            # row after the cold row's matrix build ran 5 % slower in every round, its caches
            # flushed: 50.9 ms against 48.2 ms for the same run in a later row)
            shift = k * len(names) // max(args.rounds, 1)
            for name in names[shift:] + names[:shift]:
                t0 = time.perf_counter()
                keep[name] = fns[name]()
                best[name] = min(best[name], time.perf_counter() - t0)
    print(f"\n{'row':38s} {'time':>10s} {'floor':38s} {'its time':>10s} {'ratio':>7s}  "
          "goal: verdict")
    for row, ref, goal_t, goal_r in ROWS:
        if row not in best:
            continue
        ratio = best[row] / best[ref]
        print(f"{row:38s} {best[row] * 1e3:8.2f}ms {ref:38s} {best[ref] * 1e3:8.2f}ms "
              f"{ratio:7.3f}  "
              + verdict(best[row], ratio, goal_t, goal_r))
    if not args.curves_only:
        path_summary(best, keep)
    for n in (() if args.paths_only else (200, 1000)):
        tab, ref = keep[f"curve exact, 667 in contact, {n}"], keep[f"curve exact, Hertz closed form, {n}"]
        nodes = int(np.sum(tab.contact.profile.table_nodes() < float(tab.normal.radius)))
        err = float(np.max(np.abs(tab.torque - ref.torque)) / np.max(np.abs(ref.torque)))
        old = keep[f"curve composite (old), 667, {n}"]
        err_old = float(np.max(np.abs(tab.torque - old)) / np.max(np.abs(old)))
        print(f"table curve, {n} twists: {nodes} nodes in contact; torque against the sampled "
              f"paraboloid's closed form {err:.2e} of the largest torque (the table's "
              f"interpolation error), against the composite route {err_old:.1e}")
    if args.curves_only:
        print("load average after:", os.getloadavg())
        return 0
    same = _digest(keep["path exact rtol 1e-3, numpy route"]) == _digest(
        keep["path exact rtol 1e-3, compiled route"])
    ratio = best["path exact rtol 1e-3, numpy route"] / best["path exact rtol 1e-3, compiled route"]
    print(f"compiled passes (numba available: {_ta._ring_kernels._jit.available()}): "
          f"{ratio:.2f}x faster than the numpy route, bit-identical: {same}")
    if not args.paths_only:
        _scaling_rows(args, ({}, {"torque_rtol": RTOL}))
    print("load average after:", os.getloadavg())
    return 0


def _scaling_rows(args, choices) -> None:
    """Row 2 at each ring choice of ``choices`` (keywords of ``simulate``)."""
    for kw in choices:
        scaling([100, 1000, 10000] if args.long else [100, 1000], args.rounds if args.long
                and args.scaling_only else (1 if args.long else 2), **kw)


if __name__ == "__main__":
    raise SystemExit(main())
