"""First call in a fresh process: compiled kernels with a cold and a warm on-disk cache (issue 13).

Run from the repository root: ``python benchmarks/compile_cache.py [rounds]`` (needs numba, the
extra ``fast``; default 2 rounds).

Each row is a fresh child process that imports contactlab, makes its first call and a second,
identical call (the steady cost, for scale), and reports numba's own cache statistics (compiled
signatures against signatures loaded from disk). The processes of a round run one after the
other, side by side in time, so that the machine's load is shared:

- ``cold``: an empty cache directory (``NUMBA_CACHE_DIR`` set to a fresh temporary directory):
  the first process on a machine, it compiles and writes the cache;
- ``warm``: the same directory again: every later process, it loads the machine code;
- ``no cache``: no writable cache location (what every process paid before the kernels were
  cached);
- ``numpy``: ``CONTACTLAB_BACKEND=numpy`` and ``ContactLaw(fast=False)``, the reference
  backends (nothing to compile).

Two first calls are timed in each process, one after the other: a gait-like
``simulate(method="mdr")`` (force and twist change every step, N = 2000 springs, 200 steps:
the fused Winkler kernels) and then a ``ContactLaw`` step of 1000 contacts on 16 springs each
(the contact-law kernels; "law first" is its first two steps: the second is the first on springs,
"law second" the third step). Also printed: ``python -X importtime -c "import contactlab"``
(cumulative microseconds of ``contactlab``; target < 0.15 s) and whether numba was imported by
``import contactlab`` (it must not be: numba is imported on the first compiled call).
"""
from __future__ import annotations

import json
import os
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(Path(__file__).resolve().parent))

from _harness import machine  # noqa: E402

CHILD = r"""
import json, os, sys, time
t0 = time.perf_counter()
import numpy as np
import contactlab as cl
from contactlab.loadpath import LoadPath
t_import = time.perf_counter() - t0
numba_on_import = "numba" in sys.modules

t = np.linspace(0, 1, 201)
path = LoadPath.from_arrays(time=t, force=50 + 40 * np.sin(2 * np.pi * t),
                            twist=2e-4 * np.sin(6 * np.pi * t))
c = cl.Contact(cl.profiles.Paraboloid(R=0.01), (cl.Elastic(E=210e9, nu=0.3),) * 2, friction=0.3)
out = {}
for k in ("first", "second"):
    t0 = time.perf_counter()
    r = c.simulate(path, n_springs=2000, method="mdr")
    out["simulate " + k] = time.perf_counter() - t0
rng = np.random.default_rng(0)
n = 1000
law = cl.ContactLaw(cl.profiles.Paraboloid, R=rng.uniform(1e-3, 1e-2, n), E_star=1.15e11,
                    G_star=4.4e10, G_torsion=4.0e10, friction=0.3, springs=16,
                    fast=os.environ.get("CONTACTLAB_BACKEND") != "numpy")
F = rng.uniform(1.0, 100.0, n)
ph = rng.uniform(0.0, 2 * np.pi, n)
for k, steps in (("first", (0, 1)), ("second", (2,))):   # step 1 on: every contact on springs
    t0 = time.perf_counter()
    for s in steps:
        law.step(force=F * (1.0 + 0.02 * s), twist=2e-4 * np.sin(0.3 * s + ph),
                 displacement=1e-7 * np.cos(0.3 * s + ph))
    out["law " + k] = time.perf_counter() - t0
hits = misses = 0
if "numba" in sys.modules:
    import numba.core.registry
    from contactlab.foundation import _compiled
    from contactlab.physics import law_kernel
    disp = list(_compiled._compiled_kernels.values()) + [
        v for k, kern in law_kernel._KERNELS.items()
        for v in ((kern,) if k == "load" else kern)]
    for f in disp:
        hits += sum(f.stats.cache_hits.values())
        misses += sum(f.stats.cache_misses.values())
out.update(import_s=t_import, numba_on_import=numba_on_import, hits=hits, misses=misses)
print(json.dumps(out))
"""


def child(env_extra: dict) -> dict:
    env = {k: v for k, v in os.environ.items() if not k.startswith(("NUMBA_", "CONTACTLAB_"))}
    env.update(OPENBLAS_NUM_THREADS="1", **env_extra)
    out = subprocess.run([sys.executable, "-c", CHILD], env=env, cwd=ROOT, capture_output=True,
                         text=True, check=True)
    return json.loads(out.stdout.strip().splitlines()[-1])


def import_time() -> tuple[float, bool]:
    """Cumulative import time of contactlab (s, from -X importtime) and whether numba loaded."""
    out = subprocess.run([sys.executable, "-X", "importtime", "-c",
                          "import sys, contactlab; print('numba' in sys.modules)"], cwd=ROOT,
                         capture_output=True, text=True, check=True)
    last = [ln for ln in out.stderr.splitlines() if ln.rstrip().endswith("| contactlab")][-1]
    return int(last.split("|")[1]) * 1e-6, out.stdout.strip() == "True"


def main() -> None:
    rounds = int(sys.argv[1]) if len(sys.argv) > 1 else 2
    print("Machine:", machine())
    try:
        import numba  # noqa: F401
    except ImportError:
        print("numba is not installed (extra 'fast'): nothing is compiled, nothing to cache.")
        return
    rows: dict[str, list[dict]] = {}
    with tempfile.TemporaryDirectory() as tmp:
        blocker = Path(tmp) / "not_a_directory"
        blocker.write_text("")
        for r in range(rounds):
            cache = str(Path(tmp) / f"cache{r}")
            for name, env in (("cold", {"NUMBA_CACHE_DIR": cache}),
                              ("warm", {"NUMBA_CACHE_DIR": cache}),
                              ("no cache", {"NUMBA_CACHE_DIR": str(blocker / "x"),
                                            "NUMBA_CACHE_LOCATOR_CLASSES":
                                            "UserProvidedCacheLocator"}),
                              ("numpy", {"CONTACTLAB_BACKEND": "numpy"})):
                rows.setdefault(name, []).append(child(env))
    keys = ("import_s", "simulate first", "simulate second", "law first", "law second")
    print(f"\nFresh process, median of {rounds} rounds (s); hits/misses: numba signatures loaded"
          " from disk / compiled")
    print(f"{'':>9} | " + " | ".join(f"{k:>15}" for k in keys) + " | hits/misses")
    med = {}
    for name, rs in rows.items():
        med[name] = {k: statistics.median(x[k] for x in rs) for k in keys}
        print(f"{name:>9} | " + " | ".join(f"{med[name][k]:15.3f}" for k in keys)
              + f" | {rs[-1]['hits']}/{rs[-1]['misses']}")
    first = {n: med[n]["simulate first"] + med[n]["law first"] for n in med}
    print(f"\nfirst calls (simulate + law): cold {first['cold']:.2f} s, warm {first['warm']:.2f} s,"
          f" no cache {first['no cache']:.2f} s, numpy {first['numpy']:.2f} s")
    print(f"cold / warm = {first['cold'] / first['warm']:.1f}x, no cache / warm = "
          f"{first['no cache'] / first['warm']:.1f}x")
    print(f"numba imported by import contactlab: {any(x['numba_on_import'] for rs in rows.values() for x in rs)}")
    t_imp = sorted(import_time()[0] for _ in range(5))
    print(f"python -X importtime -c 'import contactlab': {t_imp[0]:.3f} s best of 5, "
          f"median {t_imp[2]:.3f} s (target < 0.15 s)")
    print("Machine:", machine())


if __name__ == "__main__":
    main()
