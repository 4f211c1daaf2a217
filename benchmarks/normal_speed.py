"""Normal-contact speed (issue 2 and issue 29 targets), printed with the machine.

Run from the repository root: ``python benchmarks/normal_speed.py`` (``--tables`` for the
issue-29 table rows only, ~15 s; ``--front`` for the accuracy-time front of the tables' tree
terms (rtol 1e-2 .. 1e-10, numpy and compiled routes, ~1 min); ``--issue29`` for the issue-29
rows only: each a ratio
against its floor measured interleaved in the same run, best of several rounds of the
process's CPU time (``--wall``: wall time), with a verdict against the goal).

Issue 29 rows (:func:`issue29_rows`):

* 10^6 depths / forces on a ``Paraboloid`` against the numpy closed form (goal <= 2x);
* the force rows also by the numpy route (what runs without numba: the paraboloid's numpy
  passes of :mod:`contactlab.physics.normal_fused`, the sphere's numpy Newton rounds; the
  compiled passes of :mod:`contactlab.numeric.normal_kernels` run where numba imports);
* the exact ``Sphere``, 10^5 depths / forces, against the numpy closed form of the same curve
  evaluated at the solved radii (``d = a artanh(a/R)``, ``F`` from ``∫g``; goal <= 10x), and the
  gain of batching over one scalar call per load;
* 10^3 random depths / forces on a 10^4-point linear and cubic table, per load (goal <= 20 µs),
  the tree sums beside the node-by-node sums (the route before; linear and cubic) and the
  linear table's previous Newton iteration on those, interleaved.

Targets:

* force and contact radius for 10^6 depths through the closed-form / symbolic path: < 0.1 s;
* a 10^4-point tabulated profile: transform "once" < 50 ms, then force and radius at rtol 1e-6
  in < 1 ms per depth.

A tabulated profile has no precomputation step: its transform is the exact arcsine sum, evaluated
on demand (O(N) per radius). "Transform once" is therefore measured as the first evaluation of g
on a 10^3-point grid of radii (what a plot of g needs) plus the construction of the table.
"""
from __future__ import annotations

import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(Path(__file__).resolve().parent))

import contactlab as cl  # noqa: E402
from contactlab.profiles import (Cone, Paraboloid, Polynomial, PowerLaw, Sphere,  # noqa: E402
                                 Tabulated)
from contactlab.numeric import normal_kernels  # noqa: E402
from _harness import best_time, machine  # noqa: E402

MATERIALS = (cl.Elastic(E=210e9, nu=0.3), cl.Rigid())


def verdict(value: float, target: float) -> str:
    return f"{'OK ' if value < target else 'MISSED'} (target < {target:g})"


#: the clock of the issue-29 rows: the process's CPU time (``--wall`` for wall time). On the
#: shared machine at a load of several jobs per core, a run of more than a few milliseconds is
#: descheduled for whole time slices (measured: one 1e5-element arctanh pass taking 0.4 ms or
#: 30 ms from call to call), which best-of-N wall time cannot filter out for the longer of two
#: callables; single-threaded numpy's CPU time counts only its own work
CLOCK = time.perf_counter if "--wall" in sys.argv else time.process_time


def interleaved(fns: dict, rounds: int = 7) -> dict:
    """Best time of each callable (:data:`CLOCK`), the callables run in turn in every round (so
    that a change of the machine's load hits them alike)."""
    best = {k: float("inf") for k in fns}
    for _ in range(rounds):
        for k, fn in fns.items():
            t0 = CLOCK()
            fn()
            best[k] = min(best[k], CLOCK() - t0)
    return best


def goal(ratio: float, limit: float, what: str = "x") -> str:
    return f"{'MET   ' if ratio <= limit else 'MISSED'} (goal <= {limit:g}{what})"


#: the force rows run the compiled passes where numba imports (contactlab.numeric.
#: normal_kernels); the numpy route (the reference, and what runs without numba) is timed beside
BACKEND_NOTE = f"backend of the rows above: {normal_kernels.backend()}"


def numpy_route(fn):
    """``fn`` run with the batched normal solves forced onto their numpy route."""
    def call():
        saved = normal_kernels._state["backend"]
        normal_kernels.set_backend("numpy")
        try:
            return fn()
        finally:
            normal_kernels._state["backend"] = saved
    return call


def _previous_newton(tab):
    """The table's Newton iteration as before issue 29's change (plain start in u², stop only on
    a small step), for the side-by-side row."""
    import contactlab.profiles.tabulated._solve as solve_mod
    orig = tab._newton_on_node_interval

    def plain(*args, cusp=None, **kw):
        saved = solve_mod._NEWTON_MARGIN
        solve_mod._NEWTON_MARGIN = np.inf
        try:
            return orig(*args, **kw)
        finally:
            solve_mod._NEWTON_MARGIN = saved
    return plain


def issue29_rows() -> None:
    """The normal-solve rows of issue 29, each against its floor measured in the same run."""
    print("Issue 29: batched closed forms, ratio to the floor measured interleaved (best of 7, "
          + ("wall time" if CLOCK is time.perf_counter else "CPU time of this process; --wall "
             "for wall time") + ")")
    R = 0.01
    c = cl.Contact(Paraboloid(R), MATERIALS)
    E = c.moduli.normal
    d = np.linspace(1e-9, 1e-5, 10**6)
    F = np.linspace(1e-3, 1e3, 10**6)
    c.normal(depth=d[:10]), c.normal(force=F[:10])
    k = 4.0 / 3.0 * E * np.sqrt(R)

    def floor_depth():          # a = sqrt(R d), F = 4/3 E* sqrt(R) d^1.5
        return np.sqrt(R * d), k * d**1.5

    def floor_force():          # a = cbrt(3 R F / (4 E*)), d = a²/R
        a = np.cbrt(3.0 * R / (4.0 * E) * F)
        return a, a * a / R

    t = interleaved({"depth": lambda: c.normal(depth=d), "floor_d": floor_depth,
                     "force": lambda: c.normal(force=F), "floor_f": floor_force,
                     "force_np": numpy_route(lambda: c.normal(force=F))})
    for key, fl, label in (("depth", "floor_d", "10^6 depths -> radius, force"),
                           ("force", "floor_f", "10^6 forces -> radius, depth")):
        r = t[key] / t[fl]
        print(f"  Paraboloid {label:32s} {t[key] * 1e3:7.2f} ms, numpy closed form "
              f"{t[fl] * 1e3:6.2f} ms: {r:5.2f}x  {goal(r, 2.0)}")
    print(f"    (the forces by the numpy route, {BACKEND_NOTE}: {t['force_np'] * 1e3:.2f} ms, "
          f"{t['force_np'] / t['floor_f']:.2f}x)")

    # exact sphere: the closed form of the same curve is parametric in the contact radius
    cs = cl.Contact(Sphere(R), MATERIALS)
    a = np.linspace(1e-6, 0.45 * R, 10**5)
    st = cs.normal(radius=a)
    ds, Fs = np.asarray(st.depth), np.asarray(st.force)

    def floor_sphere():         # d = a artanh(a/R), F = 2E*(a d - ∫g), ∫g in closed form
        at = np.arctanh(a / R)
        dd = a * at
        return dd, 2 * E * (a * dd - (0.5 * (a * a - R * R) * at + 0.5 * R * a))

    t = interleaved({"depth": lambda: cs.normal(depth=ds), "force": lambda: cs.normal(force=Fs),
                     "radius": lambda: cs.normal(radius=a), "floor": floor_sphere,
                     "force_np": numpy_route(lambda: cs.normal(force=Fs))})
    for key in ("depth", "force"):
        r = t[key] / t["floor"]
        print(f"  exact Sphere, 10^5 {key + 's':6s} -> state          {t[key] * 1e3:7.2f} ms, "
              f"numpy closed form of the curve {t['floor'] * 1e3:5.2f} ms: {r:5.1f}x  "
              f"{goal(r, 10.0)}")
    print(f"    (the forces by the numpy route, {BACKEND_NOTE}: {t['force_np'] * 1e3:.2f} ms, "
          f"{t['force_np'] / t['floor']:.1f}x)")
    print(f"  (contactlab's own closed form, normal(radius=) on the same radii: "
          f"{t['radius'] * 1e3:.2f} ms)")
    few = ds[:: ds.size // 200][:200]
    t1 = interleaved({"scalar": lambda: [cs.normal(depth=float(x)) for x in few],
                      "batch": lambda: cs.normal(depth=few)}, rounds=5)
    print(f"  exact Sphere, 200 depths: scalar calls {t1['scalar'] / few.size * 1e6:.1f} µs "
          f"per depth, one batch {t1['batch'] / few.size * 1e6:.2f} µs per depth: batching gains "
          f"{t1['scalar'] / t1['batch']:.0f}x (was 3x)")

    table_rows()


def _node_by_node(tab):
    """``tab`` made to sum its nodes one by one (the route before the dyadic tree of
    contactlab.profiles.tabulated._far), for the side-by-side row."""
    tab.__dict__["_far_cache"] = (None,)
    tab.__dict__["_cubic_tree_cache"] = (None,)
    return tab


def table_rows() -> None:
    """10^3 random depths / forces on a 10^4-point table, per load, against the goal (20 µs),
    the node sums by the tree beside the node-by-node sums (linear and cubic, interleaved)."""
    # fresh random depths every round (nothing but the table's coarse node grid and the node
    # values the node search memoises is reused), linear and cubic, and the linear table with
    # its node-by-node sums and its previous Newton iteration interleaved beside it
    R = 0.01
    r = np.linspace(0, 1e-3, 10**4)
    f = R - np.sqrt(R * R - r * r)
    rng = np.random.default_rng(29)
    contacts = {}
    for key, kind in (("linear", "linear"), ("nodes", "linear"), ("previous", "linear"),
                      ("cubic", "cubic"), ("cubic_nodes", "cubic")):
        tab = Tabulated(r, f, kind)
        if key in ("nodes", "cubic_nodes"):
            _node_by_node(tab)
        if key == "previous":
            _node_by_node(tab)
            tab._newton_on_node_interval = _previous_newton(tab)
        contacts[key] = cl.Contact(tab, MATERIALS, rtol=1e-6)
        contacts[key].normal(depth=[1e-8, 2e-5])
    batches = [rng.uniform(1e-8, 2.5e-5, 10**3) for _ in range(3)]
    forces = [np.asarray(contacts["linear"].normal(depth=b).force) for b in batches]
    for b in batches:                                      # the routes agree (to rounding)
        for key, ref_key in (("linear", "nodes"), ("cubic", "cubic_nodes")):
            st, ref = contacts[key].normal(depth=b), contacts[ref_key].normal(depth=b)
            # (the tree's Taylor series are truncated for rtol 1e-6: within rtol)
            dev = float(np.max(np.abs(np.asarray(st.radius) / np.asarray(ref.radius) - 1)))
            assert dev < 1e-6, (key, dev)

    def fresh(key: str, control: str):
        it = iter(range(10**6))

        def call():
            i = next(it) % len(batches)
            vals = batches[i] if control == "depth" else forces[i]
            return contacts[key].normal(**{control: vals})
        return call

    t2 = interleaved({(k, ctl): fresh(k, ctl) for k in contacts for ctl in ("depth", "force")},
                     rounds=3)
    for ctl in ("depth", "force"):
        per = {k: t2[(k, ctl)] / 10**3 * 1e6 for k in contacts}
        print(f"  10^3 random {ctl}s on a 10^4-point linear table (rtol 1e-6) "
              f"{per['linear']:7.1f} µs per {ctl}; node-by-node sums {per['nodes']:.1f} "
              f"({per['nodes'] / per['linear']:.1f}x), and with the previous iteration "
              f"{per['previous']:.1f}  {goal(per['linear'], 20.0, ' µs')}")
        print(f"  10^3 random {ctl}s on a 10^4-point cubic table  (rtol 1e-6) "
              f"{per['cubic']:7.1f} µs per {ctl}; node-by-node sums {per['cubic_nodes']:.1f} "
              f"({per['cubic_nodes'] / per['cubic']:.1f}x)  {goal(per['cubic'], 20.0, ' µs')}")
    print()
    print()


def table_front() -> None:
    """The accuracy-time front of the far-field trees (issue 29: their Taylor terms chosen from
    rtol): 10^3 random depths / forces on a 10^4-point linear and cubic table at rtol 1e-2 ..
    1e-10, the largest true relative error of the force (depth control) and of the depth
    (force control) against the node-by-node sums at rtol 1e-12, the largest estimate relative
    to the value, µs per load by the numpy route and by the compiled one (where numba
    imports), interleaved, best of 3."""
    from contactlab.profiles.tabulated import _far
    R = 0.01
    r = np.linspace(0, 1e-3, 10**4)
    f = R - np.sqrt(R * R - r * r)
    rng = np.random.default_rng(29)
    d = rng.uniform(1e-8, 2.5e-5, 10**3)
    backends = ["numpy"] + (["numba"] if normal_kernels.backend() == "numba" else [])
    print("Issue 29, accuracy-time front of the tree's Taylor terms (10^4-point tables, 10^3 "
          "random loads, best of 3, " + ("wall time" if CLOCK is time.perf_counter
                                          else "CPU time") + ")")
    print(f"  {'table':7s} {'rtol':>6s} {'terms':>5s} {'err F(d)':>9s} {'est F':>9s} "
          f"{'err d(F)':>9s} {'est d':>9s}  " + "  ".join(
              f"{b + ' µs/depth':>15s} {b + ' µs/force':>15s}" for b in backends))
    for kind in ("linear", "cubic"):
        ref_tab = _node_by_node(Tabulated(r, f, kind))
        ref = cl.Contact(ref_tab, MATERIALS, rtol=1e-12).normal(depth=d)
        F_ref, d_ref = np.asarray(ref.force), d
        for rtol in (1e-2, 1e-3, 1e-6, 1e-8, 1e-10):
            tab = Tabulated(r, f, kind)
            c = cl.Contact(tab, MATERIALS, rtol=rtol)
            sd, sf = c.normal(depth=d), c.normal(force=F_ref)
            eF = float(np.max(np.abs(np.asarray(sd.force) / F_ref - 1)))
            ed = float(np.max(np.abs(np.asarray(sf.depth) / d_ref - 1)))
            # (the states' error estimates are relative)
            estF, estd = (float(np.max(np.asarray(e))) if e is not None else np.nan
                          for e in (sd.error_estimates["force"], sf.error_estimates["depth"]))
            with tab._tree_rtol(rtol):
                terms = tab._tree_terms()
            # at rtol 1e-6 also the code before (all 20 terms whatever rtol), interleaved
            variants = {"": c}
            if rtol == 1e-6:
                variants["all terms"] = cl.Contact(Tabulated(r, f, kind), MATERIALS, rtol=rtol)
            fns = {}
            for var, cv in variants.items():
                for b in backends:
                    for ctl, vals in (("depth", d), ("force", F_ref)):
                        def call(ctl=ctl, vals=vals, b=b, cv=cv, full=bool(var)):
                            saved = normal_kernels._state["backend"], _far.terms_from_ratios
                            normal_kernels.set_backend(b)
                            if full:
                                _far.terms_from_ratios = lambda *args: _far.TERMS
                            try:
                                return cv.normal(**{ctl: vals * rng.uniform(0.99, 1.01)})
                            finally:
                                normal_kernels._state["backend"] = saved[0]
                                _far.terms_from_ratios = saved[1]
                        fns[(var, b, ctl)] = call
            t = interleaved(fns, rounds=3)
            for var in variants:
                us = "  ".join(f"{t[(var, b, 'depth')] * 1e3:15.1f} "
                               f"{t[(var, b, 'force')] * 1e3:15.1f}" for b in backends)
                if var:
                    note = "(the code before: all terms at every rtol)"
                    print(f"  {kind:7s} {rtol:6.0e} {_far.TERMS:5d} {note:39s}  {us}")
                    continue
                print(f"  {kind:7s} {rtol:6.0e} {terms:5d} {eF:9.1e} {estF:9.1e} {ed:9.1e} "
                      f"{estd:9.1e}  {us}")
    print(f"  (terms: {_far.TERMS} at rtol <= {_far.FULL_TERMS_RTOL:g}; the estimates include "
          "the truncation bound of the tree)")
    print()


def main() -> int:
    print("Machine:", machine())
    print()
    if "--front" in sys.argv:
        table_front()
        return 0
    if "--tables" in sys.argv:
        print("Issue 29, tables (best of 3, " + ("wall time" if CLOCK is time.perf_counter
                                                  else "CPU time of this process") + ")")
        table_rows()
        return 0
    issue29_rows()
    if "--issue29" in sys.argv:
        return 0
    # ---- 10^6 depths, closed form / symbolic
    depths = np.linspace(1e-9, 1e-5, 10**6)
    rows = []
    for label, prof in (("paraboloid (closed form)", Paraboloid(0.01)),
                        ("cone (closed form)", Cone(0.2)),
                        ("power law n=4 (closed form)", PowerLaw(1e3, 4.0)),
                        ("polynomial r^2+r^4 (symbolic g, root solve)", Polynomial({2: 50.0, 4: 1e6}))):
        c = cl.Contact(prof, MATERIALS)
        c.normal(depth=depths[:10])                      # warm caches (sympy lambdify, kappa)
        t, s = best_time(lambda: c.normal(depth=depths), min_total=0.3, max_runs=5)
        assert np.all(np.isfinite(s.force)) and np.all(np.isfinite(s.radius))
        rows.append((label, t))
        print(f"10^6 depths -> force + radius, {label:45s} {t:8.4f} s  {verdict(t, 0.1)}")
    c = cl.Contact(Paraboloid(0.01), MATERIALS)
    forces = np.linspace(1e-3, 1e3, 10**6)
    t, _ = best_time(lambda: c.normal(force=forces), min_total=0.3, max_runs=5)
    print(f"10^6 forces -> depth + radius, paraboloid (closed form)            {t:8.4f} s  "
          f"{verdict(t, 0.1)}")

    # ---- 10^4-point tabulated profile
    print()
    # a sampled exact sphere: a convex table, so g is non-decreasing without the O(N²) ring-
    # contact check (noisy tables run that check once, then it is cached; see docs/accuracy.md)
    R = 0.01
    r = np.linspace(0, 1e-3, 10**4)
    f = R - np.sqrt(R * R - r * r)

    def transform_once():
        prof = Tabulated(r, f)
        return prof, prof.g(np.linspace(0, 1e-3, 1000))

    def prepare_once():
        prof = Tabulated(r, f)
        prof._coarse_nodes()        # what the depth/force solves precompute: g on 65 nodes
        return prof

    t_prep, _ = best_time(prepare_once, min_total=0.3, max_runs=10)
    print(f"10^4-point table: build + solver set-up (g memoised on 65 nodes)    {t_prep * 1e3:8.2f} ms "
          f"{verdict(t_prep * 1e3, 50)}")
    t_once, (prof, _) = best_time(transform_once, min_total=0.3, max_runs=10)
    print(f"10^4-point table: build + exact g on 10^3 radii (10^7 arcsines)    {t_once * 1e3:8.2f} ms "
          "(information: the full transform on a fine grid)")
    c = cl.Contact(prof, MATERIALS, rtol=1e-6)
    d_grid = np.linspace(1e-8, 2.5e-5, 200)
    t_scalar, _ = best_time(lambda: c.normal(depth=1.234e-5), min_total=0.3, max_runs=200)
    print(f"  force + radius at one depth (rtol 1e-6)                            {t_scalar * 1e3:8.3f} ms "
          f"{verdict(t_scalar * 1e3, 1.0)}")
    t_vec, s = best_time(lambda: c.normal(depth=d_grid), min_total=0.3, max_runs=20)
    per = t_vec / d_grid.size * 1e3
    print(f"  force + radius for 200 depths at once (rtol 1e-6), per depth      {per:8.3f} ms "
          f"{verdict(per, 1.0)}")
    t_F, _ = best_time(lambda: c.normal(force=2.0), min_total=0.3, max_runs=200)
    print(f"  depth + radius at one force (rtol 1e-6)                            {t_F * 1e3:8.3f} ms "
          f"{verdict(t_F * 1e3, 1.0)}")
    t_p, _ = best_time(lambda: c.normal(depth=1.234e-5).pressure(np.linspace(0, 1e-4, 50) * 1.0001),
                       min_total=0.3, max_runs=20)
    print(f"  pressure at 50 radii (semi-analytic truncated-cone sum)            {t_p * 1e3:8.2f} ms")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
