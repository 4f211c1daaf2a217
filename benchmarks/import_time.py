"""Start-up cost: ``import contactlab`` in a fresh interpreter (issue 13: target < 0.15 s).

Run from the repository root: ``python benchmarks/import_time.py [ROUNDS]`` (default 15).

Fresh interpreters run ``pass``, ``import numpy`` and ``import contactlab`` in turn, round after
round, so the three see the same machine load; each is timed in wall and CPU time (user + system
of the child). Reported: best and median of the rounds, contactlab's own share (contactlab minus
numpy, which it cannot avoid), the verdict on the best wall time (CPU time is no better here:
OpenBLAS's threads spin while numpy imports, so its CPU time exceeds its wall time), the optional heavy modules an import left loaded (none expected) and the
ten modules with the largest own import time from one ``-X importtime`` run. Lazy imports move cost
from the import to the first call, so the script also times, inside fresh interpreters, the first
``Contact(...).normal(force=...)`` after ``import contactlab`` (best and median of the rounds).

Children run with bytecode caching on (``PYTHONDONTWRITEBYTECODE`` removed from their
environment) after one warm-up import, as after ``pip install``: without ``.pyc`` files every
import compiles the package's sources again (~0.3 s on a 2-core VM), which says nothing about
start-up on a user's machine.
"""
from __future__ import annotations

import json
import os
import statistics
import subprocess
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _harness import machine  # noqa: E402

TARGET = 0.15
CASES = {"bare python": "pass", "import numpy": "import numpy",
         "import contactlab": "import contactlab"}
HEAVY = ("scipy.special", "scipy.integrate", "scipy.optimize", "sympy", "matplotlib", "numba",
         "pandas", "dask", "multiprocessing", "concurrent.futures")

#: the first call a user makes after the import, timed inside the child (s)
FIRST_CALL = ("import time; import contactlab as cl; t0 = time.perf_counter(); "
              "c = cl.Contact(cl.profiles.Paraboloid(R=0.01), "
              "materials=(cl.Elastic(E=210e9, nu=0.3), cl.Rigid())); "
              "c.normal(force=100.0).radius; print(time.perf_counter() - t0)")

ENV = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}


def run(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, *args], env=ENV, capture_output=True, text=True,
                          check=True)


def timed(code: str) -> tuple[float, float]:
    """Wall and CPU time (s) of one fresh interpreter running ``code``."""
    before = os.times()
    t0 = time.perf_counter()
    run("-c", code)
    wall = time.perf_counter() - t0
    after = os.times()
    cpu = (after.children_user - before.children_user) + (after.children_system - before.children_system)
    return wall, cpu


def main(rounds: int) -> None:
    print(machine())
    run("-c", "import contactlab")          # writes the bytecode caches, as an install does
    walls: dict[str, list[float]] = {k: [] for k in CASES}
    cpus: dict[str, list[float]] = {k: [] for k in CASES}
    for _ in range(rounds):
        for name, code in CASES.items():
            w, c = timed(code)
            walls[name].append(w)
            cpus[name].append(c)
    print(f"{'case':<20}{'wall best':>11}{'wall median':>13}{'CPU best':>10}{'CPU median':>12}")
    for name in CASES:
        print(f"{name:<20}{min(walls[name]):>10.3f}s{statistics.median(walls[name]):>12.3f}s"
              f"{min(cpus[name]):>9.3f}s{statistics.median(cpus[name]):>11.3f}s")
    own = min(walls["import contactlab"]) - min(walls["import numpy"])
    best = min(walls["import contactlab"])
    print(f"contactlab's own share (wall, best): {own:.3f} s; ratio import contactlab / import numpy: "
          f"{best / min(walls['import numpy']):.2f}")
    print(f"verdict: import contactlab {best:.3f} s wall (best of {rounds}) "
          f"{'meets' if best < TARGET else 'misses'} the {TARGET} s target")
    probe = ("import json, sys; import contactlab; "
             f"print(json.dumps([m for m in {list(HEAVY)!r} if m in sys.modules]))")
    loaded = json.loads(run("-c", probe).stdout)
    print(f"optional heavy modules loaded by the import: {loaded or 'none'}")
    firsts = sorted(float(run("-c", FIRST_CALL).stdout) for _ in range(rounds))
    print(f"first Contact(...).normal(force=) after the import: best {firsts[0] * 1e3:.1f} ms, "
          f"median {statistics.median(firsts) * 1e3:.1f} ms")
    err = run("-X", "importtime", "-c", "import contactlab").stderr
    rows = []
    for line in err.splitlines()[1:]:
        parts = line.split("|")
        if len(parts) == 3:
            rows.append((int(parts[0].split(":")[1]), parts[2].strip()))
    print("largest own import times (one run, µs):")
    for us, mod in sorted(rows, reverse=True)[:10]:
        print(f"  {us:>8}  {mod}")


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 15)
