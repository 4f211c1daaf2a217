"""The exact ring solver gives bit-identical results for any BLAS thread count (issue 28).

Its dense solves are a few hundred rows: a threaded BLAS splits them by thread count and adds the
parts in a different order (the torque differed in the last bits between one and two threads, and
two threads took ~3x longer). The run holds BLAS at one thread
(:func:`contactlab.numeric.blas.serial_blas`); this runs the same varying-load path in fresh
processes with ``OPENBLAS_NUM_THREADS=1`` and ``=2`` and compares the hashes of every series.
"""
from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[3]

_SCRIPT = r"""
import hashlib
import numpy as np
import contactlab as cl
c = cl.Contact(cl.profiles.Paraboloid(R=0.01), materials=(cl.Elastic(E=210e9, nu=0.3), cl.Rigid()),
               friction=0.3)
n = 180
t = np.arange(1, n + 1) / n
force = 10.0 * (1 + 0.4 * np.sin(2 * np.pi * 2 * t + 0.3))
a = float(np.max(c.normal(force=force)._radius))
s = 0.3 * 10.0 / (c.moduli.torsional * a * a)
path = cl.LoadPath.from_arrays(force=force,
                               twist=0.8 * s * np.sin(6 * np.pi * t) * np.minimum(1, 2 * t))
r = c.simulate(path, method="exact")
h = hashlib.sha256()
for k in ("torque", "dissipated_energy", "stick_radius", "twist"):
    h.update(np.ascontiguousarray(getattr(r, k)).tobytes())
print(h.hexdigest(), r.meta["fallback_steps"])
"""


def _run(threads: int, backend: str = "") -> str:
    env = dict(os.environ, OPENBLAS_NUM_THREADS=str(threads), OMP_NUM_THREADS=str(threads),
               MKL_NUM_THREADS=str(threads), PYTHONPATH=str(ROOT), CONTACTLAB_BACKEND=backend)
    out = subprocess.run([sys.executable, "-c", _SCRIPT], env=env, capture_output=True,
                         text=True, check=True, timeout=600)
    return out.stdout.strip()


def test_exact_path_is_bit_identical_for_one_and_two_blas_threads():
    pytest.importorskip("threadpoolctl")
    one, two = _run(1), _run(2)
    # the path takes both routes: annulus steps and ring-solver fallback steps
    assert int(one.split()[1]) > 0
    assert one == two


def test_exact_path_is_bit_identical_on_the_numpy_route_for_one_and_two_blas_threads():
    """The numpy route of the punch densities (the reference of the stored path hashes) and the
    compiled one (numba, when installed: the default run above) give the same bits, on one and
    two BLAS threads."""
    pytest.importorskip("threadpoolctl")
    one, two = _run(1, "numpy"), _run(2, "numpy")
    assert one == two
    assert one == _run(1)


def test_influence_matrices_are_factored_once_per_ring_set():
    """A second run on the same ring set reuses the factored matrices (read-only) and gives the
    bit-identical result; another ring set gets its own."""
    import numpy as np

    import contactlab as cl
    from contactlab.foundation import rings as fr

    c = cl.Contact(cl.profiles.Paraboloid(R=0.01),
                   materials=(cl.Elastic(E=210e9, nu=0.3), cl.Rigid()), friction=0.3)
    t = np.arange(1, 41) / 40
    path = cl.LoadPath.from_arrays(force=10.0 * (1 + 0.3 * np.sin(4 * np.pi * t)),
                                   twist=2e-4 * np.sin(6 * np.pi * t))
    fr._CACHE.clear()
    r1 = c.simulate(path, method="exact", n_rings=30)
    assert len(fr._CACHE) == 1
    mats = next(iter(fr._CACHE.values()))
    assert not mats["H"].flags.writeable and not mats["lu"][0].flags.writeable
    r2 = c.simulate(path, method="exact", n_rings=30)
    assert len(fr._CACHE) == 1 and next(iter(fr._CACHE.values())) is mats
    for k in ("torque", "dissipated_energy", "stick_radius"):
        assert np.array_equal(getattr(r1, k), getattr(r2, k))
    fr._CACHE.clear()
    r3 = c.simulate(path, method="exact", n_rings=30)     # built afresh: the same numbers
    assert np.array_equal(r1.torque, r3.torque)
    c.simulate(path, method="exact", n_rings=31)
    assert len(fr._CACHE) == 2
