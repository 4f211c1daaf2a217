"""Foundation kernels: numba against numpy, and the spring-count cliff (issue 13).

Run from the repository root: ``python benchmarks/foundation_backends.py`` (numba from the extra
``fast``; without it only numpy is timed).

1. The Jenkins update alone (``foundation._compiled.jenkins_update``) per spring-update, for
   N = 10^2 ... 10^6 springs: numba against numpy, and numpy against a minimal numpy replica
   with ``np.dot`` (what the kernel did before): no cliff means the time per spring-update stays
   within 2x over the range.
2. A gait-like ``simulate`` (force and twist change at every step, N = 2000): spring-updates per
   second with each backend (numba: the fused compiled step, one call per run of steps), side by
   side, and the numpy backend against a minimal numpy replica of the same step (target: within
   1.1x).
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


def gait_replica(fnd, d_arr, ed, twist, c_tor):
    """The gait step in the fewest numpy calls (no state objects, no checks): S, weight, slip
    limits, weighted stiffness, Jenkins update, sum, stick radius."""
    n = fnd.n_springs
    w, dG, X1, dH, K, invK, bl = fnd.w, fnd.dG, fnd.X1, fnd.dH, fnd.K_tor, fnd.invK_tor, fnd.bl
    m, S, wt, iK = np.zeros(n), np.zeros(n), np.zeros(n), np.ones(n)
    k_old, d_old, x, W = 0, 0.0, 0.0, 0.0
    ks, Ss, Ts = ed["k"].tolist(), ed["S"].tolist(), ed["T"].tolist()
    for j, d in enumerate(d_arr.tolist()):
        k = ks[j]
        Sn = d * w - dG
        Sn[k + 1:] = 0.0
        Sn[k] = Ss[j]
        lo, hi = min(k, k_old), max(k, k_old) + 1
        wt[:lo] = 1.0
        wt[hi:] = 0.0
        wt[lo:hi] = np.clip((Sn[lo:hi] - S[lo:hi]) / ((d - d_old) * w[lo:hi]), 0.0, 1.0)
        T = d * X1 - dH
        T[k + 1:] = 0.0
        T[k] = Ts[j]
        L = c_tor * T
        np.divide(invK, wt, out=iK, where=wt > 0)
        tmp = K * wt * (twist[j] - x) + m
        np.clip(tmp, -L, L, out=m)
        W += float(((tmp - m) * m * iK).sum())
        float(m.sum())
        slip = np.abs(m) >= L
        i = int(np.argmax(slip))
        float(bl[i])
        S, k_old, d_old, x = Sn, k, d, twist[j]
    return W


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
        c.simulate(path, n_springs=2000, method="mdr")
        res[b] = min(timeit.repeat(lambda: c.simulate(path, n_springs=2000, method="mdr"),
                                   number=1, repeat=3))
        print(f"  {b:6s} {res[b]:.3f} s  {2000 * 2000 / res[b]:.3g} spring-updates/s")
    if "numba" in res:
        print(f"  numpy/numba: {res['numpy'] / res['numba']:.2f}")
    from contactlab.foundation import Winkler
    from contactlab.foundation.base import path_normal_states
    nrm = path_normal_states(c.profile, c.moduli.normal, path, c.rtol)[0]
    fnd = Winkler(c.profile, c.moduli, c.friction, float(nrm["radius"].max()), n_springs=2000,
                  needs=("torsion",), rtol=c.rtol)
    ed = fnd.edge_data(nrm["depth"], nrm["radius"])
    tw = (2e-4 * np.sin(6 * np.pi * t)).tolist()
    _compiled.set_backend("numpy")
    both = [min(timeit.repeat(f, number=1, repeat=3)) for f in
            (lambda: c.simulate(path, n_springs=2000, method="mdr"),
             lambda: gait_replica(fnd, nrm["depth"], ed, tw, fnd._c_tor))]
    print(f"  numpy simulate {both[0]:.3f} s, minimal numpy replica of the step {both[1]:.3f} s: "
          f"ratio {both[0] / both[1]:.2f} (target <= 1.1)")
    _compiled.set_backend(None)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
