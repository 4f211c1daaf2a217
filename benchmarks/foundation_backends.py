"""Foundation kernels: numba against numpy, and the spring-count cliff (issue 13).

Run from the repository root: ``python benchmarks/foundation_backends.py`` (numba from the extra
``fast``; without it only numpy is timed).

1. The Jenkins update alone (``foundation._compiled.jenkins_update``) per spring-update, for
   N = 10^2 ... 10^6 springs: numba against numpy, and numpy against a minimal numpy replica
   with ``np.dot`` (what the kernel did before): no cliff means the time per spring-update stays
   within 2x over the range.
2. A gait-like ``simulate`` (force and twist change at every step, N = 2000): spring-updates per
   second with each backend, side by side.
"""
from __future__ import annotations

import sys
import timeit
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(Path(__file__).resolve().parent))

import contactlab as cl  # noqa: E402
from contactlab.foundation import _compiled  # noqa: E402
from contactlab.loadpath import LoadPath  # noqa: E402
from _harness import machine  # noqa: E402


def dot_replica(m, K, invK, L, nL, inc, tmp):
    np.multiply(K, inc, out=tmp)
    tmp += m
    np.minimum(tmp, L, out=m)
    np.maximum(m, nL, out=m)
    tmp -= m
    tmp *= m
    return float(np.dot(tmp, invK))


def main() -> int:
    print("Machine:", machine())
    backends = _compiled.available()
    print("backends:", ", ".join(backends))
    rng = np.random.default_rng(0)
    print(f"\n{'N':>8s} " + " ".join(f"{b + ' ns/upd':>14s}" for b in backends)
          + f" {'np.dot ns/upd':>14s}")
    per = {b: [] for b in backends}
    for n in (10**2, 10**3, 10**4, 10**5, 10**6):
        K = rng.uniform(0.5, 2, n)
        invK, L = 1 / K, rng.uniform(0, 1, n)
        nL, m, tmp = -L, np.zeros(n), np.empty(n)
        reps = max(20, 2 * 10**6 // n)
        row = []
        for b in backends:
            _compiled.set_backend(b)
            _compiled.jenkins_update(m, K, invK, L, 0.1, tmp, nL)      # compile / warm
            t = min(timeit.repeat(lambda: _compiled.jenkins_update(m, K, invK, L, 0.01, tmp, nL),
                                  number=reps, repeat=3)) / reps / n
            per[b].append(t)
            row.append(t)
        td = min(timeit.repeat(lambda: dot_replica(m, K, invK, L, nL, 0.01, tmp), number=reps,
                               repeat=3)) / reps / n
        print(f"{n:8d} " + " ".join(f"{t * 1e9:14.3f}" for t in row) + f" {td * 1e9:14.3f}")
    for b in backends:
        print(f"{b}: max/min time per spring-update over N = 1e2..1e6: "
              f"{max(per[b]) / min(per[b]):.2f} (target <= 2; includes the per-call overhead at "
              "N = 100)")

    c = cl.Contact(cl.profiles.Paraboloid(R=0.01), (cl.Elastic(E=210e9, nu=0.3),) * 2,
                   friction=0.3)
    t = np.linspace(0, 1, 2001)
    path = LoadPath.from_arrays(time=t, force=50 + 40 * np.sin(2 * np.pi * t),
                                twist=2e-4 * np.sin(6 * np.pi * t))
    print("\ngait-like simulate (force and twist change every step, 2000 steps, N = 2000):")
    res = {}
    for b in backends:
        _compiled.set_backend(b)
        c.simulate(path)
        res[b] = min(timeit.repeat(lambda: c.simulate(path), number=1, repeat=3))
        print(f"  {b:6s} {res[b]:.3f} s  {2000 * 2000 / res[b]:.3g} spring-updates/s")
    if "numba" in res:
        print(f"  numpy/numba: {res['numpy'] / res['numba']:.2f}")
    _compiled.set_backend(None)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
