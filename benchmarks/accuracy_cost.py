"""What accuracy costs in time: normal contact (issue 7).

Run from the repository root::

    python benchmarks/accuracy_cost.py            # full ladders (~ a few minutes)
    python benchmarks/accuracy_cost.py --quick    # short ladders (< 1 min without BEM)
    python benchmarks/accuracy_cost.py --no-bem   # skip tamaas / contactmechanics
    python benchmarks/accuracy_cost.py --issue29  # only the issue-29 rows (~20 s)

Knobs (each swept over a ladder, error against an independent exact value, wall time per
evaluation, the library's own error estimate checked against the actual error):

1. ``transform quadrature rtol``: the numeric MDR route (profiles that offer only f(r) go through
   tanh-sinh quadrature for g, ∫g and the pressure), ``Contact(..., rtol=...)``.
2. ``tabulated resolution (linear|cubic)``: a tabulated profile sampled from an analytic one,
   against the analytic profile (interpolation error; no estimate is offered for it).
3. ``root-finding tolerance``: force control where a(F) needs a bracketed solve; the setting is
   the resulting root tolerance ``max(1e-15, 1e-5 rtol)``.

Side by side with the boundary-element packages ``contactmechanics`` (free, non-periodic FFT
half-space, displacement control) and ``tamaas`` (periodic, force control) for Hertz, cone and
n = 4 (both optional: skipped with a message when missing).

Writes ``benchmarks/results/accuracy_cost.csv``, ``benchmarks/results/bem_compare.csv`` and one
Pareto plot per knob (``benchmarks/results/pareto_*.png``, if matplotlib is installed).
"""
from __future__ import annotations

import argparse
import gc
import math
import random
import sys
import time
import warnings
from pathlib import Path
from typing import Any, ClassVar

import mpmath as mp
import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(Path(__file__).resolve().parent))

import contactlab as cl  # noqa: E402
from contactlab.profiles import (Cone, Paraboloid, Polynomial, PowerLaw, Profile,  # noqa: E402
                                 Tabulated, TruncatedParaboloid)
from _harness import (Knob, Row, best_time, honesty, machine, measure, pareto_plot,  # noqa: E402
                      time_to_reach, write_csv)

RESULTS = Path(__file__).resolve().parent / "results"
MATERIALS = (cl.Elastic(E=1.0, nu=0.0), cl.Rigid())        # E* = 1 Pa: errors are relative
mp.mp.dps = 30


class QuadratureOnly(Profile):
    """Exposes only f and f' of another profile: g, ∫g and p then go by quadrature."""

    name: ClassVar[str] = "quadrature_only_bench"
    params: ClassVar[tuple] = ()

    def __init__(self, base: Profile) -> None:
        self.base = base

    def _param_values(self):
        return (self.base,)

    def __repr__(self) -> str:
        return f"QuadratureOnly({self.base!r})"

    @property
    def breakpoints(self):
        return self.base.breakpoints

    @property
    def flat_radius(self):
        return self.base.flat_radius

    @property
    def max_radius(self):
        return self.base.max_radius

    def _length_scale(self):
        return self.base._length_scale()

    def _height(self, r):
        return self.base._height(r)

    def _slope(self, r):
        return self.base._slope_any(r)


# ----------------------------------------------------------------------------- exact values
def kappa(n: float) -> mp.mpf:
    n = mp.mpf(n)
    return mp.sqrt(mp.pi) * mp.gamma(n / 2 + 1) / mp.gamma(n / 2 + mp.mpf(1) / 2)


def power_pressure_ref(c: float, n: float, a: float, r: float) -> float:
    """(E*/π) ∫_0^{arccosh(a/r)} n κ_n c (r cosh u)^{n-1} du, E* = 1 (mpmath)."""
    r_, a_ = mp.mpf(r), mp.mpf(a)
    return float(mp.quad(lambda u: n * kappa(n) * c * (r_ * mp.cosh(u)) ** (n - 1),
                         [0, mp.acosh(a_ / r_)]) / mp.pi)


def table_transform(r: np.ndarray, f: np.ndarray, x: float) -> tuple[float, float]:
    """Exact g(x) and ∫_0^x g of the piecewise-linear table (theory §2 row, re-implemented)."""
    s = np.diff(f) / np.diff(r)
    lo, hi = r[:-1], np.minimum(r[1:], x)
    m = lo < x
    g = x * np.sum(s[m] * (np.arcsin(hi[m] / x) - np.arcsin(lo[m] / x)))

    def prim(t):   # ∫ sqrt(x²-t²) dt
        return 0.5 * (t * np.sqrt(np.maximum(x * x - t * t, 0.0)) + x * x * np.arcsin(t / x))
    G = np.sum(s[m] * (prim(hi[m]) - prim(lo[m])))
    return float(g), float(G)


R_PAR, A = 1.0, 0.1
RHO = np.array([0.3137, 0.7071])            # pressure probes r/a (off any table node)


def cases() -> dict[str, dict[str, Any]]:
    """Exact force (at the depth of contact radius A) and pressure at RHO*A for each case."""
    out: dict[str, dict[str, Any]] = {}
    r = RHO * A
    out["paraboloid"] = dict(profile=Paraboloid(R_PAR), depth=A * A / R_PAR,
                             force=4 * A**3 / (3 * R_PAR),
                             pressure=2 / (np.pi * R_PAR) * np.sqrt(A * A - r * r))
    out["cone"] = dict(profile=Cone(0.5), depth=0.5 * np.pi * A * 0.5,
                       force=0.5 * np.pi * A * A * 0.5, pressure=0.25 * np.arccosh(A / r))
    k4 = float(kappa(4))
    out["n = 4"] = dict(profile=PowerLaw(10.0, 4.0), depth=k4 * 10.0 * A**4,
                        force=2 * k4 * 10.0 * A**5 * 4 / 5,
                        pressure=np.array([power_pressure_ref(10.0, 4.0, A, x) for x in r]))
    kh = float(kappa(0.5))      # f' ~ r^-1/2: an endpoint singularity of the transform integrand
    out["n = 0.5"] = dict(profile=PowerLaw(1.0, 0.5), depth=kh * A**0.5,
                          force=2 * kh * A**1.5 * 0.5 / 1.5,
                          pressure=np.array([power_pressure_ref(1.0, 0.5, A, x) for x in r]))
    b = A / (1 + 1e-3)          # flat punch with a rounded edge b..A = b(1+1e-3)
    d = 1e-3
    Rr = A * np.sqrt((A - b) * (A + b)) / d
    out["flat punch (rounded edge 1e-3)"] = dict(
        profile=TruncatedParaboloid(b, Rr), depth=d,
        force=2 * (A * d - ((A - b) * (A + b)) ** 1.5 / (3 * Rr)), pressure=None)
    rng = np.random.default_rng(2024)
    rt = np.linspace(0, 2 * A, 200)
    ft = rt**2 / (2 * R_PAR) * (1 + 1e-5 * rng.standard_normal(rt.size))   # g stays monotone
    ft -= ft[0]
    g_a, G_a = table_transform(rt, ft, A)
    out["tabulated, noisy (200 pts)"] = dict(profile=Tabulated(rt, ft), depth=g_a,
                                             force=2 * (A * g_a - G_a), pressure=None)
    return out


# ----------------------------------------------------------------------------- knobs
def quadrature_knobs(quick: bool) -> list[Knob]:
    ladder = [1e-2, 1e-3, 1e-4, 1e-6, 1e-8, 1e-10, 1e-12] if quick else \
        [1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12, 1e-13]
    knobs = []
    for label, cs in cases().items():
        prof = QuadratureOnly(cs["profile"])

        def run_force(rtol, prof=prof, cs=cs):
            s = cl.Contact(prof, MATERIALS, rtol=rtol).normal(depth=cs["depth"])
            return s.force, s.error_estimate

        knobs.append(Knob("transform quadrature rtol", label + " [quadrature route]", "force",
                          ladder, run_force, cs["force"]))

        def run_radius(rtol, prof=prof, cs=cs):
            s = cl.Contact(prof, MATERIALS, rtol=rtol).normal(depth=cs["depth"])
            return s.radius, s.error_estimates["radius"]

        if "tabulated" not in label:        # (the table's exact radius is not A)
            knobs.append(Knob("transform quadrature rtol", label + " [quadrature route]", "radius",
                              ladder, run_radius, A))
        if cs["pressure"] is not None:
            def run_p(rtol, prof=prof, cs=cs):
                s = cl.Contact(prof, MATERIALS, rtol=rtol).normal(depth=cs["depth"])
                p, e = s.pressure(RHO * s.radius, return_error=True)
                # one number per rung: the worst probe, as the error measure below
                return p, float(np.max(e / np.abs(p)))

            ref_p = cs["pressure"]
            knobs.append(Knob("transform quadrature rtol", label + " [quadrature route]",
                              "pressure", ladder, run_p, ref_p,
                              error=lambda v, ref: float(np.max(np.abs(v / ref - 1)))))
    return knobs


def tabulated_knobs(quick: bool) -> list[Knob]:
    sizes = [11, 32, 100, 316, 1000, 3162] if quick else [11, 32, 100, 316, 1000, 3162, 10000, 31623]
    R = R_PAR
    exact = {
        "paraboloid": (lambda r: r * r / (2 * R), A * A / R, 4 * A**3 / (3 * R),
                       2 / (np.pi * R) * np.sqrt(A * A - (RHO * A) ** 2)),
        "sphere (exact)": (lambda r: R - np.sqrt(R * R - r * r),
                           A / 2 * np.log((R + A) / (R - A)),
                           (A * A + R * R) / 2 * np.log((R + A) / (R - A)) - A * R, None),
        "n = 4": (lambda r: 10.0 * r**4, float(kappa(4)) * 10 * A**4,
                  2 * float(kappa(4)) * 10 * A**5 * 4 / 5,
                  np.array([power_pressure_ref(10.0, 4.0, A, x) for x in RHO * A])),
    }
    knobs = []
    for interp in ("linear", "cubic"):
        for label, (f, d, F, p) in exact.items():
            def run_force(N, f=f, d=d, interp=interp):
                r = np.linspace(0, 2 * A, N)
                s = cl.Contact(Tabulated(r, f(r), interp), MATERIALS).normal(depth=d)
                return s.force, math.nan

            knobs.append(Knob(f"tabulated resolution ({interp})", label, "force", sizes,
                              run_force, F, setting_label=str))
            if p is not None:
                def run_p(N, f=f, d=d, interp=interp):
                    r = np.linspace(0, 2 * A, N)
                    s = cl.Contact(Tabulated(r, f(r), interp), MATERIALS).normal(depth=d)
                    return s.pressure(RHO * A), math.nan

                knobs.append(Knob(f"tabulated resolution ({interp})", label, "pressure",
                                  sizes if interp == "linear" else sizes[:5], run_p, p,
                                  error=lambda v, ref: float(np.max(np.abs(v / ref - 1))),
                                  setting_label=str))
    return knobs


def root_knobs(quick: bool) -> list[Knob]:
    ladder = [1e-2, 1e-4, 1e-6, 1e-8, 1e-10] if quick else \
        [1e-1, 1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10]
    knobs = []
    poly = Polynomial({2: 0.5, 4: 200.0})

    def F_poly(a):
        a = mp.mpf(a)
        return 2 * (0.5 * kappa(2) * a**3 * 2 / 3 + 200 * kappa(4) * a**5 * 4 / 5)

    F_target = float(F_poly(A))
    b = A / (1 + 1e-3)
    d = 1e-3
    Rr = A * np.sqrt((A - b) * (A + b)) / d
    F_punch = 2 * (A * d - ((A - b) * (A + b)) ** 1.5 / (3 * Rr))
    for label, prof, F in (("polynomial r^2 + r^4", poly, F_target),
                           ("flat punch (rounded edge 1e-3)", TruncatedParaboloid(b, Rr), F_punch)):
        def run(rtol, prof=prof, F=F):
            s = cl.Contact(prof, MATERIALS, rtol=rtol).normal(force=F)
            return s.radius, s.error_estimates["radius"]

        knobs.append(Knob("root-finding tolerance", label, "radius", ladder, run, A,
                          setting_label=lambda s: f"{max(1e-15, 1e-5 * s):g}"))
    return knobs


# ----------------------------------------------------------------------------- BEM comparison
BEM_CASES = {
    # name: (height f(r), depth for contact radius A, exact force, exact p(A/2))
    "Hertz": (lambda r: r * r / (2 * R_PAR), A * A / R_PAR, 4 * A**3 / (3 * R_PAR),
              2 / (np.pi * R_PAR) * np.sqrt(A * A - A * A / 4)),
    "cone": (lambda r: 0.5 * r, 0.5 * np.pi * A * 0.5, 0.5 * np.pi * A * A * 0.5,
             0.25 * float(np.arccosh(2.0))),
    "n = 4": (lambda r: 10.0 * r**4, float(kappa(4)) * 10 * A**4,
              2 * float(kappa(4)) * 10 * A**5 * 4 / 5, power_pressure_ref(10.0, 4.0, A, A / 2)),
}
CL_PROFILES = {"Hertz": Paraboloid(R_PAR), "cone": Cone(0.5), "n = 4": PowerLaw(10.0, 4.0)}


def run_contactmechanics(grids: list[int]) -> list[dict]:
    try:
        from ContactMechanics import FreeFFTElasticHalfSpace, make_system
        from SurfaceTopography import Topography
    except ImportError:
        print("contactmechanics is not installed: skipped (pip install contactmechanics).")
        return []
    rows = []
    for name, (f, d, F, _) in BEM_CASES.items():
        L = 3 * A                              # free (non-periodic) half-space: domain ⊃ contact
        for n in grids:
            x = (np.arange(n) + 0.5) * L / n - L / 2
            X, Y = np.meshgrid(x, x, indexing="ij")
            h = -f(np.hypot(X, Y))

            def solve():
                with warnings.catch_warnings():
                    warnings.simplefilter("ignore")
                    sub = FreeFFTElasticHalfSpace((n, n), 1.0, (L, L))
                    system = make_system(substrate=sub, surface=Topography(h, (L, L)))
                    res = system.minimize_proxy(offset=d, pentol=1e-12 * d, maxiter=20000)
                return res, system

            try:
                t, (res, system) = best_time(solve, min_total=0.0, max_runs=1)
            except Exception as exc:
                print(f"  contactmechanics {name} {n}²: {type(exc).__name__}: {exc}")
                rows.append(dict(solver="contactmechanics", case=name, grid=n, converged=False,
                                 force_error=math.nan, radius_error=math.nan, seconds=math.nan))
                continue
            Fn = float(system.compute_normal_force())
            area = float(system.compute_contact_area())
            row = dict(solver="contactmechanics", case=name, grid=n, converged=bool(res.success),
                       force_error=abs(Fn / F - 1), radius_error=abs(math.sqrt(area / math.pi) / A - 1),
                       seconds=t)
            rows.append(row)
            print(f"  contactmechanics {name:6s} {n:5d}²  conv={row['converged']!s:5s} "
                  f"force err {row['force_error']:.2e}  radius err {row['radius_error']:.2e}  {t:.3f} s")
    return rows


def run_tamaas(grids: list[int]) -> list[dict]:
    try:
        import tamaas as tm
    except ImportError:
        print("tamaas is not installed: skipped (pip install tamaas).")
        return []
    tm.set_log_level(tm.LogLevel.error)
    rows = []
    for name, (f, d, F, p_half) in BEM_CASES.items():
        L = 8 * A                              # periodic: images at 8a
        for n in grids:
            x = np.arange(n) * L / n - L / 2   # a node on the axis and at r = A/2
            X, Y = np.meshgrid(x, x, indexing="ij")
            surf = -f(np.hypot(X, Y))

            def solve():
                model = tm.ModelFactory.createModel(tm.model_type.basic_2d, [L, L], [n, n])
                model.E, model.nu = 1.0, 0.0
                solver = tm.PolonskyKeerRey(model, surf, 1e-12)
                solver.max_iter = 20000
                solver.solve(F / L**2)
                return model

            try:
                t, model = best_time(solve, min_total=0.0, max_runs=1)
            except Exception as exc:
                print(f"  tamaas {name} {n}²: {type(exc).__name__}: {exc}")
                continue
            p = np.array(model.traction).reshape(n, n)
            area = float((p > 0).sum()) * (L / n) ** 2
            i0 = n // 2
            j_half = i0 + int(round(0.5 * A / (L / n)))
            p_err = abs(p[i0, j_half] / p_half - 1) if p_half is not None and \
                abs(x[j_half] - 0.5 * A) < 1e-12 else math.nan
            row = dict(solver="tamaas", case=name, grid=n, converged=True, force_error=p_err,
                       radius_error=abs(math.sqrt(area / math.pi) / A - 1), seconds=t)
            rows.append(row)
            print(f"  tamaas           {name:6s} {n:5d}²  p(a/2) err {p_err:.2e}  "
                  f"radius err {row['radius_error']:.2e}  {t:.3f} s")
    return rows


def contactlab_times(quad_rows: list[Row]) -> dict[str, dict[str, float]]:
    """Closed-form time (one normal() with force and radius), and quadrature-route times."""
    out = {}
    for name, prof in CL_PROFILES.items():
        d = BEM_CASES[name][1]
        c = cl.Contact(prof, MATERIALS)
        t, s = best_time(lambda: c.normal(depth=d), min_total=0.2, max_runs=2000)
        batch = np.full(10**4, d)
        tb, _ = best_time(lambda: c.normal(depth=batch), min_total=0.2, max_runs=200)
        # the exported standalone law (contact.formulas(...).python(), the code a user embeds in
        # a multibody or particle code): one force and one radius evaluation per call
        law: dict = {}
        exec(c.formulas(substitute=True).python(), law)
        force_law, radius_law = law["force_of_depth"], law["radius_of_depth"]
        te, _ = best_time(lambda: (force_law(d), radius_law(d)), min_total=0.2, max_runs=20000)
        out[name] = {"closed": t, "batch": tb / batch.size, "exported": te,
                     "exported_force_error": abs(force_law(d) / BEM_CASES[name][2] - 1),
                     "closed_force_error": abs(s.force / BEM_CASES[name][2] - 1),
                     "closed_radius_error": abs(s.radius / A - 1)}
    return out


def bem_compare(quick: bool, quad_rows: list[Row]) -> list[dict]:
    grids = [16, 32, 64, 128] if quick else [16, 32, 64, 128, 256, 512]
    print(f"\nBEM comparison, grids {grids} (same contact radius a = {A} m, E* = 1 Pa)")
    rows = run_contactmechanics(grids) + run_tamaas(grids)
    if not rows:
        return rows
    cl_t = contactlab_times(quad_rows)
    ttr = time_to_reach(quad_rows, (1e-3, 1e-6))
    map_case = {"Hertz": "paraboloid", "cone": "cone", "n = 4": "n = 4"}
    print("\nTime to reach a target (s); ratio = BEM time / contactlab time. contactlab closed "
          "form: one normal(depth=) giving force and radius; 'quad' = the generic quadrature "
          "route forced (profile given only as f(r)).")
    header = (f"{'case':7s} {'target':22s} {'contactmech.':>12s} {'tamaas':>10s} "
              f"{'cl closed':>10s} {'cl quad':>10s} {'CM/cl':>9s} {'tamaas/cl':>9s}")
    print(header)
    for name in BEM_CASES:
        for target_name, key, tol in (("force err 1e-3", "force_error", 1e-3),
                                      ("force err 1e-6", "force_error", 1e-6),
                                      ("radius err 1e-3", "radius_error", 1e-3)):
            def reach(solver):
                ok = [r["seconds"] for r in rows if r["solver"] == solver and r["case"] == name
                      and r["converged"] and r[key] <= tol]
                return min(ok) if ok else math.nan
            tcm, ttm = reach("contactmechanics"), reach("tamaas")
            tcl = cl_t[name]["closed"]
            quad_key = ("transform quadrature rtol", map_case[name] + " [quadrature route]",
                        "force" if key == "force_error" else "radius")
            tq = ttr.get(quad_key, {}).get(tol, math.nan)

            def fmt(v):
                return f"{v:10.3g}" if math.isfinite(v) else f"{'not reached':>10s}"
            print(f"{name:7s} {target_name:22s} {fmt(tcm):>12s} {fmt(ttm)} {fmt(tcl)} {fmt(tq)} "
                  f"{fmt(tcm / tcl):>9s} {fmt(ttm / tcl):>9s}")
    print("(tamaas is force-controlled and periodic: its 'force err' column is the error of "
          "p(a/2); contactmechanics is displacement-controlled on a free half-space.)")
    for name in BEM_CASES:
        ct = cl_t[name]
        cm = [r["seconds"] for r in rows if r["solver"] == "contactmechanics" and r["case"] == name
              and r["converged"] and r["force_error"] <= 1e-3]
        ratio = f"{min(cm) / ct['batch']:.2g}" if cm else "n/a"
        ratio_law = f"{min(cm) / ct['exported']:.2g}" if cm else "n/a"
        print(f"contactlab {name}: force error {ct['closed_force_error']:.1e}, radius error "
              f"{ct['closed_radius_error']:.1e}; {ct['closed'] * 1e6:.0f} µs per call, "
              f"{ct['batch'] * 1e9:.0f} ns per depth in a batch of 10^4 (contactmechanics 1e-3 "
              f"force time / batch time per depth = {ratio}); exported force law "
              f"(formulas().python()): {ct['exported'] * 1e6:.2f} µs per force + radius, force "
              f"error {ct['exported_force_error']:.1e} (contactmechanics 1e-3 / exported = "
              f"{ratio_law})")
    return rows


# ----------------------------------------------------------------------------- main
#: Tamaas (PolonskyKeerRey, N = 8 grid) reaching a 1e-2 answer, as issue 29 recorded it on the
#: 2-core VM; used, labelled "recorded", when tamaas is not installed
TAMAAS_N8_RECORDED = 0.35e-3


def _tamaas_n8(name: str):
    """A callable running tamaas on an 8² grid for BEM_CASES[name] (None without tamaas)."""
    try:
        import tamaas as tm
    except ImportError:
        return None
    tm.set_log_level(tm.LogLevel.error)
    f, _, F, _ = BEM_CASES[name]
    n, L = 8, 8 * A
    x = np.arange(n) * L / n - L / 2
    X, Y = np.meshgrid(x, x, indexing="ij")
    surf = -f(np.hypot(X, Y))

    def solve():
        model = tm.ModelFactory.createModel(tm.model_type.basic_2d, [L, L], [n, n])
        model.E, model.nu = 1.0, 0.0
        solver = tm.PolonskyKeerRey(model, surf, 1e-12)
        solver.max_iter = 20000
        solver.solve(F / L**2)
        return model
    return solve


def _interleaved(fns: dict, rounds: int = 15) -> dict:
    """Best time of each callable, run in turn every round in a new (seeded) order, the garbage
    collector off during each call; the process's CPU time (``--wall``:
    wall time), so that time slices lost to other jobs on a loaded machine do not count (tamaas
    runs in this process: its threads' CPU time counts too)."""
    clock = time.perf_counter if "--wall" in sys.argv else time.process_time
    best = {k: math.inf for k in fns}
    order = list(fns)
    rng = random.Random(29)
    for _ in range(rounds):
        # a new order every round: a short call right after a long one (a 12 ms tight-rtol solve)
        # runs ~1.5x slower (cold caches), and a fixed order charged that to the same callables
        rng.shuffle(order)
        for k in order:
            fn = fns[k]
            # the garbage collector off while a callable runs, as timeit does: a collection
            # triggered by the previous callable's allocations (a 12 ms tight-rtol solve before a
            # 0.4 ms table call) would be charged to the next one in every round (an explicit
            # collection before each call instead leaves every call with cold caches)
            gc.disable()
            try:
                t0 = clock()
                fn()
                best[k] = min(best[k], clock() - t0)
            finally:
                gc.enable()
    return best


def issue29_rows() -> None:
    """The accuracy-buys-speed rows of issue 29: the quadrature route and a 7-point linear table
    at rtol 1e-2 and 1e-3 against tamaas on an 8² grid, timed interleaved in this run (or the
    issue's recorded tamaas time, labelled, when tamaas is not installed); and whether the time
    falls as rtol loosens (rtol 1e-2 against 1e-10)."""
    have_tamaas = _tamaas_n8("Hertz") is not None
    print("\nIssue 29: accuracy that buys speed (best of 15, interleaved, CPU time of this "
          "process unless --wall); peer: tamaas "
          + ("2D BEM on an 8² grid, measured in this run" if have_tamaas else
             f"NOT INSTALLED: the issue's recorded {TAMAAS_N8_RECORDED * 1e3:.2f} ms (recorded, "
             "not measured here)"))
    cs = cases()
    for name, key in (("Hertz", "paraboloid"), ("cone", "cone"), ("n = 4", "n = 4")):
        prof = QuadratureOnly(cs[key]["profile"])
        d, F_ref = cs[key]["depth"], cs[key]["force"]
        r7 = np.linspace(0, 2 * A, 7)
        tab = Tabulated(r7, BEM_CASES[name][0](r7))

        def quad(rtol, prof=prof, d=d):
            return cl.Contact(prof, MATERIALS, rtol=rtol).normal(depth=d)

        def quad_force(rtol, prof=prof, F=F_ref):
            return cl.Contact(prof, MATERIALS, rtol=rtol).normal(force=F)

        def table(rtol, tab=tab, d=d):
            return cl.Contact(tab, MATERIALS, rtol=rtol).normal(depth=d)
        fns = {f"quad {rt:g}": (lambda rt=rt: quad(rt)) for rt in (1e-2, 1e-3, 1e-10)}
        fns.update({f"quadF {rt:g}": (lambda rt=rt: quad_force(rt)) for rt in (1e-2, 1e-3, 1e-10)})
        fns.update({f"table7 {rt:g}": (lambda rt=rt: table(rt)) for rt in (1e-2, 1e-3)})
        peer = _tamaas_n8(name)
        if peer is not None:
            fns["tamaas"] = peer
        t = _interleaved(fns)
        t_peer = t.get("tamaas", TAMAAS_N8_RECORDED)
        label = "measured" if peer is not None else "recorded"
        for rt in (1e-2, 1e-3):
            s = quad(rt)
            err = abs(s.force / F_ref - 1)
            ok = err <= s.error_estimate
            r = t[f"quad {rt:g}"] / t_peer
            print(f"  {name:6s} quadrature route rtol {rt:g}: {t[f'quad {rt:g}'] * 1e3:6.2f} ms "
                  f"(force err {err:.1e}, estimate {s.error_estimate:.1e}, covers: {ok}); tamaas "
                  f"N=8 {t_peer * 1e3:.2f} ms ({label}): {r:5.2f}x  "
                  f"{'MET   ' if r < 1 else 'MISSED'} (goal < 1x)")
            sf = quad_force(rt)
            errf = abs(sf.depth / d - 1)
            rf = t[f"quadF {rt:g}"] / t_peer
            print(f"  {name:6s} quadrature route, force control, rtol {rt:g}: "
                  f"{t[f'quadF {rt:g}'] * 1e3:6.2f} ms (depth err {errf:.1e}, force estimate "
                  f"{sf.error_estimate:.1e}); {rf:5.2f}x tamaas  "
                  f"{'MET   ' if rf < 1 else 'MISSED'} (goal < 1x)")
            rt7 = t[f"table7 {rt:g}"] / t_peer
            print(f"  {name:6s} 7-point linear table, rtol {rt:g}: {t[f'table7 {rt:g}'] * 1e3:6.2f} ms"
                  f"; {rt7:5.2f}x tamaas  {'MET   ' if rt7 < 1 else 'MISSED'} (goal < 1x)")
        for tag, what in (("quad", "depth"), ("quadF", "force")):
            fall = t[f"{tag} 0.01"] / t[f"{tag} 1e-10"]
            fall3 = t[f"{tag} 0.001"] / t[f"{tag} 1e-10"]
            print(f"  {name:6s} quadrature route ({what} control): time at rtol 1e-2 / 1e-3 / "
                  f"1e-10 = {t[f'{tag} 0.01'] * 1e3:.2f} / {t[f'{tag} 0.001'] * 1e3:.2f} / "
                  f"{t[f'{tag} 1e-10'] * 1e3:.2f} ms: 1e-2 / 1e-10 = {fall:.2f}, 1e-3 / 1e-10 = "
                  f"{fall3:.2f}  {'MET   ' if max(fall, fall3) < 0.8 else 'MISSED'} (goal: the "
                  "time falls as rtol loosens)")


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="short ladders, small BEM grids")
    ap.add_argument("--no-bem", action="store_true", help="skip tamaas / contactmechanics")
    ap.add_argument("--wall", action="store_true", help="issue-29 rows in wall time, not CPU time")
    ap.add_argument("--issue29", action="store_true",
                    help="only the issue-29 rows (quadrature route and tables against tamaas)")
    args = ap.parse_args(argv)
    t_start = time.perf_counter()
    print("Machine:", machine())
    issue29_rows()
    if args.issue29:
        return 0
    min_total = 0.02 if args.quick else 0.1
    print("\nKnob ladders (error = actual relative error against the exact value; est = the "
          "library's own estimate)")
    rows = measure(quadrature_knobs(args.quick) + root_knobs(args.quick), min_total=min_total)
    quad_rows = list(rows)
    rows += measure(tabulated_knobs(args.quick), min_total=min_total)
    RESULTS.mkdir(parents=True, exist_ok=True)
    suffix = "_quick" if args.quick else ""
    print("\nwrote", write_csv(rows, RESULTS / f"accuracy_cost{suffix}.csv"))
    for p in pareto_plot(rows, RESULTS, prefix=f"pareto{suffix}"):
        print("wrote", p)
    ok, n = honesty(rows)
    print(f"\nError estimate honest (estimate >= actual error) on {ok} of {n} rungs "
          f"({100.0 * ok / max(n, 1):.1f} %); tabulated resolution rungs carry no estimate.")
    for r in rows:
        if r.honest == "no":
            print(f"  under-estimate: {r.knob} | {r.case} | {r.quantity} | {r.setting}: "
                  f"err {r.error:.2e} > est {r.estimate:.2e}")
    print("\nTime to reach a relative error (s per evaluation; '-' = not reached on the ladder)")
    print(f"{'knob':32s} {'case':40s} {'quantity':9s} {'1e-3':>10s} {'1e-6':>10s} {'1e-9':>10s}")
    for (knob, case, q), tt in time_to_reach(rows).items():
        cells = " ".join(f"{v:10.3g}" if math.isfinite(v) else f"{'-':>10s}" for v in tt.values())
        print(f"{knob:32s} {case:40s} {q:9s} {cells}")
    if not args.no_bem:
        bem_rows = bem_compare(args.quick, quad_rows)
        if bem_rows:
            import csv
            path = RESULTS / f"bem_compare{suffix}.csv"
            with path.open("w", newline="") as fh:
                w = csv.DictWriter(fh, fieldnames=list(bem_rows[0]))
                w.writeheader()
                w.writerows(bem_rows)
            print("wrote", path)
    print(f"\ntotal benchmark time {time.perf_counter() - t_start:.1f} s")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
