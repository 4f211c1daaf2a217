"""Exact torsion along load paths (``contact.simulate(path, method="exact")``): accuracy, cost, and
the error of the MDR spring model when the normal force changes (issue 18).

1. Accuracy–cost front at constant load: torque error of the ring solver against the exact
   Jäger/Masing ``twist_history`` (oscillating + irregular histories; Hertz, and a flat punch with
   and without the edge punch in the basis), per number of rings, with the time per step and the
   observed order.
2. The 180-step varying-load path (Hertz, force 10 N ± 40 % at two cycles, twist oscillating in
   partial slip at three cycles): time and torque error of ``method="exact"`` at several ring
   counts (nodes and density jumps at the path's contact radii; the nodes without the jumps; the
   uniform grid without either) and of
   ``method="mdr"`` (2000 springs), all against an exact run at ``REF_RINGS`` rings, side by
   side in one run; "ring solver alone" is the point-traction solver without the punch-density
   steps (``_run(..., annulus=False)``), "ring-solver steps" how many steps of a run fell back
   to it.
3. MDR-vs-exact error map under changing normal load (Hertz and cone; constant, sinusoidal and a
   gait-like double-hump force; for Hertz also sinusoidal forces of ±0.1 % to ±20 %): torque
   error (of the instantaneous sliding torque and of the path's), dissipated energy of the last
   twist cycle, smallest stick radius, the path's largest twist over the MDR validity twists of
   the torque and of the energy (``effects.path.mdr_path_validity``), the force's relative range
   while twisted, and which judgements of the MDR run's warning fired.

4. Long paths (``--long`` only): time per step of ``method="exact"`` on 2002-step paths (Hertz
   and cone; constant force and ±30 % at seven cycles; twist oscillating in partial slip at
   twenty cycles) at 20 and 200 rings, next to the ring solver alone and ``method="mdr"`` on the
   same paths, with the number of steps that fell back to the ring solver.

Writes ``benchmarks/results/torsion_rings.csv`` and prints the tables.
Run: ``python benchmarks/torsion_rings.py`` from the repository root (``--quick`` skips part 3;
``--map`` runs only part 3, about a minute with ``OPENBLAS_NUM_THREADS=1``, and writes
``benchmarks/results/torsion_rings_map.csv``; ``--long`` runs only part 4, a few minutes, and
writes ``benchmarks/results/torsion_rings_long.csv``).
"""
from __future__ import annotations

import sys
import time
import warnings
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

import contactlab as cl  # noqa: E402
from contactlab.effects.path import mdr_path_validity, force_variation  # noqa: E402
from contactlab.effects import path as _path  # noqa: E402
sys.path.insert(0, str(Path(__file__).resolve().parent))
from _harness import machine, write_dict_csv  # noqa: E402


def _run(c, path, outputs, n_rings, spacing, snapshots, **switches):
    """The exact ring solver with its ablation switches (``Rings.SWITCHES``), as a PathResult."""
    return _path._run(_path.METHODS["exact"], "exact", c, path, outputs, snapshots, False,
                      {"n_rings": n_rings, "spacing": spacing, **switches})

MAT = (cl.Elastic(E=210e9, nu=0.3), cl.Rigid())
MU = 0.3
#: rings of the reference run of part 2 (the punch-density steps converge at order ~2-3 at
#: constant load; the ring solver alone needed 1600 rings and ~2.8 GiB)
REF_RINGS = 800
OUT = Path(__file__).resolve().parent / "results"


def timed(fn, repeat=3):
    best, out = np.inf, None
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = fn()
        best = min(best, time.perf_counter() - t0)
    return best, out


def sliding(c, force):
    """Exact full-sliding torque per step, 2π μ ∫ p r² dr (through the exact torsion model)."""
    from contactlab.physics.torsion import METHODS
    ns = c.normal(force=np.asarray(force, float))
    a, d = np.asarray(ns._radius, float), np.asarray(ns._depth, float)
    model = METHODS["exact"](c.profile, c.moduli.normal, c.moduli.torsional, MU, c.rtol)
    return model.sliding_torque(a, d)


def front():
    c = cl.Contact(cl.profiles.Paraboloid(R=0.01), materials=MAT, friction=MU)
    F = 10.0
    a = float(c.normal(force=F)._radius)
    s = MU * F / (c.moduli.torsional * a * a)
    M_full = 3 * np.pi / 16 * MU * F * a
    rng = np.random.default_rng(1)
    hist = np.concatenate([0.6 * s * np.sin(np.linspace(0.2, 4 * np.pi, 60)),
                           np.cumsum(rng.normal(0, 0.25, 60)) * s])
    ref = c.twist_history(twist=hist, force=F).torque
    path = (cl.LoadPath().ramp(force=F, steps=2)
            + cl.LoadPath.from_arrays(twist=hist, force=np.full(hist.size, F)))
    rows = []
    for annulus in (True, False):
        for n in (25, 50, 100, 200, 400, 800):
            if n > 400 and not annulus:
                continue
            t, r = timed(lambda: _run(c, path, None, n, "uniform", None, annulus=annulus),
                         1 if n > 200 else 3)
            err = float(np.max(np.abs(r.torque[2:] - ref)) / M_full)
            rows.append({"part": "constant load",
                         "case": "hertz" + ("" if annulus else " (ring solver alone)"),
                         "method": "exact", "n": n, "steps": path.n_steps, "time_s": t,
                         "time_per_step_s": t / path.n_steps, "torque_error": err,
                         "fallback_steps": r.meta["fallback_steps"]})
    # flat punch (square-root singular edge pressure): with and without the edge punch
    c = cl.Contact(cl.profiles.FlatPunch(radius=1e-3), materials=MAT, friction=MU)
    F, a = 100.0, 1e-3
    s = MU * F / (c.moduli.torsional * a * a)
    M_full = np.pi / 4 * MU * F * a
    hist = np.concatenate([0.6 * s * np.sin(np.linspace(0.2, 4 * np.pi, 60)),
                           np.cumsum(np.random.default_rng(1).normal(0, 0.25, 60)) * s])
    ref = c.twist_history(twist=hist, force=F).torque
    path = (cl.LoadPath().ramp(force=F, steps=2)
            + cl.LoadPath.from_arrays(twist=hist, force=np.full(hist.size, F)))
    for edge in (True, False):
        for n in (25, 50, 100, 200, 400):
            t, r = timed(lambda: _run(c, path, None, n, "uniform", None, edge=edge),
                         1 if n > 200 else 3)
            rows.append({"part": "constant load", "case": "flat punch" + ("" if edge else
                                                                          " (no edge punch)"),
                         "method": "exact", "n": n, "steps": path.n_steps, "time_s": t,
                         "time_per_step_s": t / path.n_steps,
                         "torque_error": float(np.max(np.abs(r.torque[2:] - ref)) / M_full)})
    return rows


def orders(rows):
    """Observed order between successive ring counts of one case: log(e1/e2)/log(n2/n1)."""
    out = {}
    for r1, r2 in zip(rows, rows[1:]):
        if r1["case"] == r2["case"] and r1["part"] == r2["part"] and r2["n"] > r1["n"]:
            out[(r1["case"], r2["n"])] = (np.log(r1["torque_error"] / r2["torque_error"])
                                          / np.log(r2["n"] / r1["n"]))
    return out


def gait(t):
    return 0.35 + 0.65 * (np.exp(-((t % 1 - 0.15) / 0.08) ** 2)
                          + 0.8 * np.exp(-((t % 1 - 0.5) / 0.08) ** 2))


def varying_path(kind, n=180, F0=10.0, eps=0.4):
    t = np.arange(1, n + 1) / n
    if kind == "constant":
        force = np.full(n, F0)
    elif kind == "sinusoid":
        force = F0 * (1 + eps * np.sin(2 * np.pi * 2 * t + 0.3))
    else:
        force = F0 * gait(2 * t)
    return t, force


def speed():
    c = cl.Contact(cl.profiles.Paraboloid(R=0.01), materials=MAT, friction=MU)
    t, force = varying_path("sinusoid")
    a_max = float(np.max(c.normal(force=force)._radius))
    s = MU * 10.0 / (c.moduli.torsional * a_max ** 2)
    phi = 0.8 * s * np.sin(2 * np.pi * 3 * t) * np.minimum(1, 2 * t)
    path = cl.LoadPath.from_arrays(force=force, twist=phi)
    M_s = sliding(c, force)
    ref = c.simulate(path, method="exact", n_rings=REF_RINGS).torque
    rows = []
    for method, n, annulus in (("exact", 50, True), ("exact", 100, True), ("exact", 200, True),
                               ("exact", 400, True), ("exact", 100, False),
                               ("exact", 200, False), ("exact", 400, False),
                               ("mdr", None, None)):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            if method == "mdr":
                tt, r = timed(lambda: c.simulate(path, method="mdr"))
            else:
                tt, r = timed(lambda: _run(c, path, None, n, "uniform", None, annulus=annulus),
                              1 if n > 200 else 3)
        rows.append({"part": "180-step varying load",
                     "case": "hertz sinusoid" + ("" if annulus in (True, None) else
                                                 " ring solver alone"),
                     "method": method, "n": n or 2000,
                     "rings": r.meta.get("rings", n or 2000), "steps": path.n_steps,
                     "fallback_steps": r.meta.get("fallback_steps"),
                     "time_s": tt, "time_per_step_s": tt / path.n_steps,
                     "torque_error": float(np.max(np.abs(r.torque - ref)) / M_s.max())})
    return rows


def map_row(c, pname, kind, t, force, amp, s, eps=None):
    phi = amp * s * np.sin(2 * np.pi * 3 * t) * np.minimum(1, 2 * t)
    path = cl.LoadPath.from_arrays(force=force, twist=phi)
    M_s = sliding(c, force)
    ex = c.simulate(path, method="exact", n_rings=400)
    with warnings.catch_warnings(record=True) as rec:
        warnings.simplefilter("always")
        md = c.simulate(path, method="mdr")
    warned = [str(w.message) for w in rec if issubclass(w.category, cl.errors.ValidityWarning)]
    ratio = mdr_path_validity(c, ex.twist, ex.radius, ex.depth)[0]
    e_ratio = mdr_path_validity(c, ex.twist, ex.radius, ex.depth, "energy")[0]
    last = t > 2 / 3
    W_ex = ex.dissipated_energy[-1] - ex.dissipated_energy[~last][-1]
    W_md = md.dissipated_energy[-1] - md.dissipated_energy[~last][-1]
    inside = ex.torque != 0
    return {
        "part": "mdr error map",
        "case": f"{pname} {kind}" + ("" if eps is None else f" ±{100 * eps:g}%") + f" amp={amp}",
        "method": "mdr vs exact", "n": 400, "steps": t.size,
        "torque_error": float(np.max(np.abs(md.torque - ex.torque)) / M_s.max()),
        "torque_error_inst": float(np.max(np.abs(md.torque - ex.torque)[inside] / M_s[inside])),
        "energy_error_last_cycle": float(W_md / W_ex - 1) if W_ex > 0 else np.nan,
        "min_stick_exact": float(np.min(ex.stick_radius / ex.radius)),
        "min_stick_mdr": float(np.min(md.stick_radius / md.radius)),
        "validity_ratio": float(ratio), "energy_validity_ratio": float(e_ratio),
        "force_variation": force_variation(ex.twist, ex.radius, ex.force),
        "mdr_warns": bool(warned),
        "warns_torque": any("outside the torque limit" in m for m in warned),
        "warns_energy": any("dissipated energy: outside" in m for m in warned)}


def error_map():
    rows = []
    profiles = {"hertz": cl.profiles.Paraboloid(R=0.01),
                "cone": cl.profiles.Cone(slope=0.02) if hasattr(cl.profiles, "Cone") else None}
    for pname, prof in profiles.items():
        if prof is None:
            continue
        c = cl.Contact(prof, materials=MAT, friction=MU)
        a_ref = float(c.normal(force=10.0)._radius)
        s = MU * 10.0 / (c.moduli.torsional * a_ref ** 2)
        for kind in ("constant", "sinusoid", "gait"):
            t, force = varying_path(kind)
            for amp in (0.005, 0.02, 0.04, 0.06, 0.08, 0.3, 0.8):
                rows.append(map_row(c, pname, kind, t, force, amp, s))
        if pname == "hertz":
            # the energy judgement: how small a force change keeps the MDR energy within 1 %
            for eps in (0.001, 0.003, 0.01, 0.02, 0.05, 0.1, 0.2):
                t, force = varying_path("sinusoid", eps=eps)
                for amp in (0.005, 0.01, 0.02, 0.04):
                    rows.append(map_row(c, pname, "sinusoid", t, force, amp, s, eps))
    return rows


def print_map(em):
    print("\n3. MDR vs exact under changing normal load (180 steps)")
    for r in em:
        print(f"  {r['case']:32s} torque {r['torque_error']:.3f} (inst {r['torque_error_inst']:.3f})"
              f"  energy/cycle {r['energy_error_last_cycle']:+.3f}"
              f"  c/a min exact {r['min_stick_exact']:.3f} mdr {r['min_stick_mdr']:.3f}"
              f"  twist/validity torque {r['validity_ratio']:.2f} energy "
              f"{r['energy_validity_ratio']:.2f}  dF/F {r['force_variation']:.1e}"
              f"  warns torque {r['warns_torque']} energy {r['warns_energy']}")


def main_map():
    """Part 3 only (``--map``): writes ``benchmarks/results/torsion_rings_map.csv``."""
    print(machine())
    em = error_map()
    print_map(em)
    write_dict_csv(em, OUT / "torsion_rings_map.csv")


def long_path(c, n=2000, varying=False):
    """A ramp to 10 N, then ``n`` steps of a twist oscillating in partial slip (20 cycles) under
    a constant force or one of ±30 % at seven cycles."""
    t = np.arange(1, n + 1) / n
    force = (10.0 * (1 + 0.3 * np.sin(2 * np.pi * 7 * t + 0.3)) if varying
             else np.full(n, 10.0))
    a = float(c.normal(force=10.0)._radius)
    s = MU * 10.0 / (c.moduli.torsional * a * a)
    phi = 0.6 * s * np.sin(2 * np.pi * 20 * t) * np.minimum(1, 5 * t)
    return (cl.LoadPath().ramp(force=10.0, steps=2)
            + cl.LoadPath.from_arrays(force=force, twist=phi))


def long_paths():
    rows = []
    profiles = {"hertz": cl.profiles.Paraboloid(R=0.01), "cone": cl.profiles.Cone(slope=0.02)}
    for pname, prof in profiles.items():
        c = cl.Contact(prof, materials=MAT, friction=MU)
        for varying in (False, True):
            path = long_path(c, varying=varying)
            case = f"{pname} {'force ±30%' if varying else 'constant force'}"
            for label, n, fn in (
                    ("exact", 20, lambda: _run(c, path, None, 20, "uniform", None)),
                    ("exact", 200, lambda: _run(c, path, None, 200, "uniform", None)),
                    ("ring solver alone", 20,
                     lambda: _run(c, path, None, 20, "uniform", None, annulus=False)),
                    ("ring solver alone", 200,
                     lambda: _run(c, path, None, 200, "uniform", None, annulus=False)),
                    ("mdr", 2000, lambda: c.simulate(path, method="mdr"))):
                with warnings.catch_warnings():
                    warnings.simplefilter("ignore")
                    tt, r = timed(fn, 1)
                rows.append({"part": "long path", "case": case, "method": label, "n": n,
                             "steps": path.n_steps, "time_s": tt,
                             "time_per_step_s": tt / path.n_steps,
                             "fallback_steps": r.meta.get("fallback_steps")})
    return rows


def main_long():
    """Part 4 only (``--long``): writes ``benchmarks/results/torsion_rings_long.csv``."""
    print(machine())
    rows = long_paths()
    print("\n4. long paths: time per step")
    for r in rows:
        fb = r["fallback_steps"]
        print(f"  {r['case']:22s} {r['method']:18s} N={r['n']:5d}  {r['steps']} steps"
              f"  {r['time_s']:.2f} s  {1e3 * r['time_per_step_s']:.3f} ms/step"
              + (f"  ring-solver steps {fb}" if fb is not None else ""))
    write_dict_csv(rows, OUT / "torsion_rings_long.csv")


def main():
    if "--map" in sys.argv:
        return main_map()
    if "--long" in sys.argv:
        return main_long()
    # the reference run at 800 rings (~2400 unknowns with the nodes and jumps at the contact
    # radii) may need more than the default memory budget
    cl.set_memory_budget("inf")
    print(machine())
    rows = front()
    od = orders(rows)
    print("\n1. constant load, error vs twist_history (of the sliding torque), time per step")
    for r in rows:
        o = od.get((r["case"], r["n"]))
        print(f"  {r['case']:36s} N={r['n']:4d}  error {r['torque_error']:.2e}"
              f"  {1e3 * r['time_per_step_s']:.2f} ms/step"
              + (f"  order {o:.2f}" if o is not None else ""))
    sp = speed()
    od = orders([r for r in sp if r["method"] == "exact"])
    print(f"\n2. 180-step varying-load path (error of the max sliding torque vs exact "
          f"N={REF_RINGS})")
    for r in sp:
        o = od.get((r["case"], r["n"]))
        print(f"  {r['method']:5s} {r['case']:32s} N={r['n']:5d} rings {r['rings']:5d}"
              f"  {r['time_s']:.3f} s  error {r['torque_error']:.2e}"
              f"  ring-solver steps {r['fallback_steps']}"
              + (f"  order {o:.2f}" if o is not None else ""))
    rows += sp
    if "--quick" not in sys.argv:
        em = error_map()
        print_map(em)
        rows += em
    write_dict_csv(rows, OUT / "torsion_rings.csv")


if __name__ == "__main__":
    main()
