"""Pressure of measured tables: ``peak_pressure`` and ``pressure(r)`` against one ``normal()``.

Run from the repository root: ``python benchmarks/table_pressure_speed.py`` (``--skip-old``
leaves out the profile's own route, which takes seconds per call).

Target (issue 26, item 3): on a 300-point table, ``peak_pressure`` (1024 radii) and
``pressure(r)`` (101 radii) in <= 10 ms after the first call (which sets up the per-segment
rules, cached per table). Each is printed as a time and as a ratio to one ``normal(force=)`` on
the same table, measured side by side in this run (the machine is a shared, noisy VM: the
ratio is the portable number). The per-segment route is checked against the profile's own
route (tanh-sinh per radius and node) and against Hertz, the closed form the table samples.

Also a linear table whose first segment is flat (a finite axis pressure: the full 1024-radius
pass), ``peak_pressure`` by the numpy route and the compiled pass (numba, extra ``fast``),
alternating in one process.

Also the hip-cup example (examples/hip_cup/, 200 measured radii in mm/um with 50 nm noise,
``smoothing="auto"``): ``normal(force=3000).peak_pressure`` with its time, linear and cubic.
"""
from __future__ import annotations

import math
import sys
import time
import warnings
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(Path(__file__).resolve().parent))

import contactlab as cl  # noqa: E402
from contactlab.errors import ValidityWarning  # noqa: E402
from contactlab.physics import normal as _normal  # noqa: E402
from contactlab.profiles import Tabulated  # noqa: E402
from _harness import machine  # noqa: E402

STEEL = cl.Elastic(E=210e9, nu=0.3)
E_STAR = 210e9 / (2 * (1 - 0.3**2))
R = 0.01
TARGET = 10e-3


def best_time(fn, min_total: float = 0.3, max_runs: int = 60):
    """``(best wall time, best CPU time), last value`` of ``fn()`` over repeated runs (the VM is
    shared: a single-threaded call's CPU time is the number an idle machine would show)."""
    walls, cpus, total, out = [], [], 0.0, None
    for _ in range(max_runs):
        t0, c0 = time.perf_counter(), time.process_time()
        out = fn()
        walls.append(time.perf_counter() - t0)
        cpus.append(time.process_time() - c0)
        total += walls[-1]
        if total >= min_total and len(walls) >= 5:
            break
    return (min(walls), min(cpus)), out


def paraboloid_table(kind: str, n: int = 300) -> Tabulated:
    r = np.linspace(0.0, 2e-3, n)
    return Tabulated(r, r**2 / (2 * R), kind)


def table_case(kind: str, skip_old: bool) -> None:
    tab = paraboloid_table(kind)
    c = cl.Contact(tab, materials=(STEEL, STEEL))
    F = 50.0
    t_first0 = time.perf_counter()
    s = c.normal(force=F)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ValidityWarning)     # linear: the cone tip, said
        peak = s.peak_pressure
    t_first = time.perf_counter() - t_first0
    radii = np.linspace(0.0, s.radius, 101)[1:-1]
    (t_normal, c_normal), _ = best_time(lambda: c.normal(force=F))

    def peak_call():
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", ValidityWarning)
            return c.normal(force=F).peak_pressure

    (t_peak, c_peak), _ = best_time(peak_call)
    t_peak -= t_normal                                  # the peak alone (a fresh state)
    c_peak -= c_normal
    (t_field, c_field), p = best_time(lambda: s.pressure(radii))
    a = s.radius
    hertz = 2 * E_STAR / (math.pi * R) * np.sqrt(a * a - radii**2)
    far = radii > 0.1 * a           # (a linear table's cone tip adds a log term near the axis)
    dev = float(np.max(np.abs(p - hertz)[far]) / hertz[0])
    h = 2e-3 / 299
    print(f"  {kind:6s} normal {t_normal * 1e3:6.2f} ms (CPU {c_normal * 1e3:5.2f}) | first "
          f"normal+peak {t_first * 1e3:7.1f} ms")
    print(f"         peak_pressure {t_peak * 1e3:6.2f} ms (CPU {c_peak * 1e3:5.2f} ms, "
          f"{c_peak / c_normal:5.1f} x normal) | pressure(99 radii) {t_field * 1e3:6.2f} ms (CPU "
          f"{c_field * 1e3:5.2f} ms, {c_field / c_normal:5.1f} x normal)")
    print(f"         peak {peak:.6g} Pa, Hertz p0 {2 * E_STAR * a / (math.pi * R):.6g} Pa; "
          f"pressure vs Hertz (r > a/10) max {dev:.2e} of p0 (table resolution 3 (h/a)^2 = "
          f"{3 * (h / a) ** 2:.1e})")
    for name, t, cpu in (("peak_pressure", t_peak, c_peak), ("pressure(r)", t_field, c_field)):
        print(f"         {'OK    ' if t <= TARGET else 'MISSED'} {name} <= {TARGET * 1e3:.0f} ms "
              f"wall [on CPU time: {'OK' if cpu <= TARGET else 'MISSED'}]")
    if not skip_old:
        rr = np.linspace(0.0, 1.0, 1025)[:-1] * a
        t0 = time.perf_counter()
        old, _ = _normal.pressure_shape(tab, rr, a, c.rtol, table_rules=False)
        t_old = time.perf_counter() - t0
        new, est = _normal.pressure_shape(tab, rr, a, c.rtol)
        ok = np.isfinite(old) & np.isfinite(new) & (rr > 0)
        print(f"         profile's own route on the 1024 peak radii: {t_old:.2f} s; largest "
              f"difference {np.max(np.abs(new - old)[ok]) / np.max(np.abs(old[ok])):.1e} of max S "
              f"(estimate {np.max(est[ok]) / np.max(np.abs(old[ok])):.1e})")


def hip_cup(kind: str) -> None:
    steel, pe = cl.Elastic(E=210e9, nu=0.3), cl.Elastic(E=1e9, nu=0.4)
    path = ROOT / "examples" / "hip_cup" / "hip_cup_profile.csv"
    tab = Tabulated.from_csv(path, kind, smoothing="auto", noise=50e-9)
    c = cl.Contact(tab, materials=(steel, pe))
    t0 = time.perf_counter()
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", ValidityWarning)
        peak = c.normal(force=3000.0).peak_pressure
    t_first = time.perf_counter() - t0

    def again():
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", ValidityWarning)
            return c.normal(force=3000.0).peak_pressure

    (t_again, c_again), _ = best_time(again)
    note = " [ValidityWarning: first segment not flat, a cone tip]" if caught else ""
    print(f"  hip cup {kind:6s} normal(force=3000).peak_pressure = {peak:.6g} Pa, first call "
          f"{t_first:.2f} s, again {t_again * 1e3:.1f} ms (CPU {c_again * 1e3:.1f} ms){note}")


def flat_first_case(rounds: int = 15) -> None:
    """The linear table whose first segment is flat (finite axis pressure: the full 1024-radius
    pass): ``peak_pressure`` by the numpy route and by the compiled pass (numba, extra
    ``fast``), alternating in this process, best CPU time of each."""
    from contactlab.numeric import jit, normal_kernels

    r = np.linspace(0.0, 2e-3, 300)
    f = r**2 / (2 * R)
    f[1] = 0.0
    c = cl.Contact(Tabulated(r, f, "linear"), materials=(STEEL, STEEL))
    _ = c.normal(force=50.0).peak_pressure              # sets up the per-segment rules
    routes = ("numpy", "numba") if jit.available() else ("numpy",)
    best = dict.fromkeys(routes, math.inf)
    peaks = {}
    try:
        for _ in range(rounds):
            for route in routes:
                normal_kernels.set_backend(route)
                c0 = time.process_time()
                peaks[route] = c.normal(force=50.0).peak_pressure
                best[route] = min(best[route], time.process_time() - c0)
    finally:
        normal_kernels.set_backend(None)
    times = ", ".join(f"{k} route {v * 1e3:.2f} ms CPU" for k, v in best.items())
    same = "same bits" if len(set(peaks.values())) == 1 else "DIFFERENT"
    print(f"  linear, flat first segment: normal+peak_pressure (best of {rounds}, alternating) "
          f"{times}; peak {peaks['numpy']:.6g} Pa ({same})")


def main() -> None:
    skip_old = "--skip-old" in sys.argv
    print(machine())
    print("300-point table of f = r²/(2R), R = 10 mm, r <= 2 mm; steel on steel, F = 50 N")
    for kind in ("linear", "cubic"):
        table_case(kind, skip_old)
    flat_first_case()
    for kind in ("linear", "cubic"):
        hip_cup(kind)
    print(machine())


if __name__ == "__main__":
    main()
