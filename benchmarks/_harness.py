"""Generic accuracy-versus-cost harness for the benchmarks (issue 7).

A :class:`Knob` is one numeric setting swept over a ladder: ``run(setting)`` returns the computed
value and the library's own error estimate (relative; ``nan`` if it offers none), ``reference`` is
the independent exact value. :func:`measure` times every rung (best of several runs), computes the
actual relative error and whether the estimate covered it, and returns :class:`Row` objects;
:func:`write_csv`, :func:`time_to_reach` and :func:`pareto_plot` turn rows into the CSV, the
"time to reach 1e-3/1e-6/1e-9" table and a log-log Pareto plot (matplotlib optional).

New knobs (torsion tolerance, foundation spring count, time step, ...) only need a ``run``
callable and a reference value.
"""
from __future__ import annotations

import csv
import math
import os
import platform
import time
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Any, Callable, Iterable, Sequence

import numpy as np

__all__ = ["Knob", "Row", "measure", "write_csv", "time_to_reach", "pareto_plot", "machine",
           "best_time", "honesty", "cpu_timed", "cpu_timed_iter"]


@dataclass
class Knob:
    """One accuracy knob on one case.

    Attributes
    ----------
    name : str
        Knob name (one plot per knob), e.g. ``"quadrature rtol"``.
    case : str
        Profile / problem label, e.g. ``"paraboloid (quadrature route)"``.
    quantity : str
        What is compared: ``"force"``, ``"pressure"``, ``"radius"``, ...
    settings : sequence
        The ladder, cheapest first.
    run : callable ``setting -> (value, error_estimate)``
        ``error_estimate`` is the library's relative estimate, ``nan`` if none.
    reference : float
        Independent exact value (closed form, high-precision reference).
    error : callable ``(value, reference) -> float``, optional
        Actual error measure; default relative error.
    """

    name: str
    case: str
    quantity: str
    settings: Sequence[Any]
    run: Callable[[Any], tuple[float, float]]
    reference: float
    error: Callable[[float, float], float] | None = None
    setting_label: Callable[[Any], str] = field(
        default=lambda s: f"{s:g}" if isinstance(s, float) else str(s))


@dataclass
class Row:
    knob: str
    case: str
    quantity: str
    setting: str
    value: float
    reference: float
    error: float
    estimate: float
    honest: str          # "yes" / "no" / "n/a"
    seconds: float


def best_time(fn: Callable[[], Any], min_total: float = 0.05, max_runs: int = 50) -> tuple[float, Any]:
    """Best-of-N wall time of ``fn()`` (runs until ``min_total`` seconds or ``max_runs``)."""
    best = math.inf
    total = 0.0
    out = None
    for _ in range(max_runs):
        t0 = time.perf_counter()
        out = fn()
        dt = time.perf_counter() - t0
        best = min(best, dt)
        total += dt
        if total >= min_total:
            break
    return best, out


def cpu_timed(fn: Callable, acc: dict, key: str) -> Callable:
    """``fn`` that adds the CPU time (this process) of each call to ``acc[key]``: wrap a
    library function in place to see where a whole run spends its time."""
    def wrapper(*args: Any, **kwargs: Any) -> Any:
        c0 = time.process_time()
        try:
            return fn(*args, **kwargs)
        finally:
            acc[key] += time.process_time() - c0
    return wrapper


def cpu_timed_iter(fn: Callable, acc: dict, key: str) -> Callable:
    """:func:`cpu_timed` for a generator function: the CPU time of producing each item (not of
    the caller's work between items)."""
    def wrapper(*args: Any, **kwargs: Any) -> Any:
        it = fn(*args, **kwargs)
        while True:
            c0 = time.process_time()
            try:
                v = next(it)
            except StopIteration:
                acc[key] += time.process_time() - c0
                return
            acc[key] += time.process_time() - c0
            yield v
    return wrapper


def _rel(value: float, ref: float) -> float:
    return abs(value - ref) / abs(ref) if ref != 0 else abs(value)


def measure(knobs: Iterable[Knob], *, min_total: float = 0.05, verbose: bool = True) -> list[Row]:
    """Run and time every rung of every knob."""
    rows: list[Row] = []
    for k in knobs:
        for s in k.settings:
            try:
                t, (val, est) = best_time(lambda: k.run(s), min_total=min_total)
            except Exception as exc:            # a rung that fails is recorded, not fatal
                if verbose:
                    print(f"  {k.name} | {k.case} | {k.quantity} | {k.setting_label(s)}: "
                          f"{type(exc).__name__}: {exc}")
                continue
            err = (k.error or _rel)(val, k.reference)
            honest = "n/a" if not math.isfinite(est) else ("yes" if err <= max(est, 1e-15) else "no")
            # array results (fields at several probes): record the worst probe
            v, ref = np.ravel(np.asarray(val, float)), np.ravel(np.asarray(k.reference, float))
            i = int(np.argmax(np.abs(v / ref - 1))) if v.size > 1 else 0
            rows.append(Row(k.name, k.case, k.quantity, k.setting_label(s), float(v[i]),
                            float(ref[min(i, ref.size - 1)]), float(err), float(est), honest, t))
            if verbose:
                print(f"  {k.name:24s} {k.case:38s} {k.quantity:8s} {k.setting_label(s):>8s}  "
                      f"err {err:9.2e}  est {est:9.2e}  {t * 1e3:9.3f} ms")
    return rows


def honesty(rows: Sequence[Row]) -> tuple[int, int]:
    """(rungs where estimate >= actual error, rungs with an estimate)."""
    checked = [r for r in rows if r.honest != "n/a"]
    return sum(r.honest == "yes" for r in checked), len(checked)


def write_csv(rows: Sequence[Row], path: str | Path) -> Path:
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    with path.open("w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=list(Row.__dataclass_fields__))
        w.writeheader()
        for r in rows:
            w.writerow(asdict(r))
    return path


def write_dict_csv(rows: Sequence[dict], path: str | Path) -> Path:
    """Write plain dict rows (columns: every key of any row, sorted; missing cells empty)."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    with path.open("w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=sorted({k for r in rows for k in r}))
        w.writeheader()
        w.writerows(rows)
    return path


def time_to_reach(rows: Sequence[Row], targets: Sequence[float] = (1e-3, 1e-6, 1e-9)
                  ) -> dict[tuple[str, str, str], dict[float, float]]:
    """Cheapest measured time whose actual error is ``<= target``, per (knob, case, quantity).

    ``nan`` when no rung of the ladder reaches the target.
    """
    out: dict[tuple[str, str, str], dict[float, float]] = {}
    for r in rows:
        key = (r.knob, r.case, r.quantity)
        out.setdefault(key, {t: math.nan for t in targets})
        for t in targets:
            if r.error <= t and not (r.seconds >= out[key][t]):
                out[key][t] = r.seconds
    return out


def pareto_plot(rows: Sequence[Row], directory: str | Path, prefix: str = "pareto") -> list[Path]:
    """One log-log plot (error vs time) per knob; returns the files written ([] without matplotlib)."""
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("matplotlib is not installed: no plots (pip install matplotlib).")
        return []
    directory = Path(directory)
    directory.mkdir(parents=True, exist_ok=True)
    files = []
    for knob in dict.fromkeys(r.knob for r in rows):
        fig, ax = plt.subplots(figsize=(6.4, 4.4))
        sel = [r for r in rows if r.knob == knob]
        for key in dict.fromkeys((r.case, r.quantity) for r in sel):
            pts = [r for r in sel if (r.case, r.quantity) == key]
            ax.loglog([r.seconds for r in pts], [max(r.error, 1e-17) for r in pts], "o-",
                      ms=3, label=f"{key[0]} - {key[1]}")
        ax.set_xlabel("wall time per evaluation [s]")
        ax.set_ylabel("relative error")
        ax.set_title(knob)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=6)
        fig.tight_layout()
        name = directory / f"{prefix}_{knob.replace(' ', '_').replace('/', '_')}.png"
        fig.savefig(name, dpi=110)
        plt.close(fig)
        files.append(name)
    return files


def machine() -> str:
    """One line naming the machine (platform, CPU, cores, load average, Python, numpy); every
    benchmark prints it."""
    cpu = platform.processor() or ""
    try:
        with open("/proc/cpuinfo") as fh:
            for line in fh:
                if line.startswith("model name"):
                    cpu = line.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    load = f"{os.getloadavg()[0]:.2f}" if hasattr(os, "getloadavg") else "n/a"
    return (f"{platform.platform()} | CPU: {cpu or 'unknown'} | {os.cpu_count()} cores | "
            f"load {load} | Python {platform.python_version()} | numpy {np.__version__}"
            f"{_simd()}")


def _simd() -> str:
    """numpy's SIMD level on this CPU (its highest dispatch target found, e.g. ``X86_V3``, or
    ``X86_V4``: AVX-512), as `` (SIMD ...)``: some of numpy's vectorised functions (``cbrt``
    among them) are 10-15x faster with AVX-512 than the scalar libm loop numpy falls back to
    without it; empty where numpy does not say (:func:`contactlab.numeric.simd.simd_level`)."""
    from contactlab.numeric.simd import simd_level
    level = simd_level()
    return "" if level is None else f" (SIMD {level})"
