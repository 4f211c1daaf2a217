"""Compiled kernels cached on disk (issue 13): a later process loads the machine code the first
one compiled, two processes compiling at once compile once, no writable cache directory means an
in-memory compile with the same results and no warning. Timing-free: numba's own per-dispatcher
cache statistics (hits and misses per signature) and the cache's index files are the signals."""
import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from contactlab.numeric import jit

pytestmark = pytest.mark.skipif(not jit.available(), reason="numba (extra 'fast') not installed")

ROOT = Path(__file__).resolve().parents[3]

# One small call of a kernel of each compiled module (small signatures: the compile of each is
# short), printing numba's cache statistics and the results as exact hex floats.
SCRIPT = r"""
import json, sys
import numpy as np
from contactlab.foundation import _compiled
from contactlab.physics import law_kernel

assert "numba" not in sys.modules            # imported on the first compiled call only
rng = np.random.default_rng(3)
n = 257
K = rng.uniform(0.5, 2.0, n); L = rng.uniform(0.0, 1.0, n)
m = np.clip(rng.normal(0, 0.5, n), -L, L)
w = [_compiled.jenkins_update(m, K, 1 / K, L, inc) for inc in (0.3, -1.1, 0.05)]
kc = rng.uniform(1.0, 2.0, 9); E = rng.uniform(1e9, 2e9, 9); val = rng.uniform(0.0, 1e-6, 9)
d, a, F, flag, counts = law_kernel.normal_pass(False, val, None, None, kc, E, 2.0,
                                               np.zeros(9), np.zeros(9), 1e-9)
k = _compiled._build()
# (n = 2: the normal pass's build for the paraboloid, the last of the passes)
disp = {"jenkins": k["_jenkins"], "normal_pass": law_kernel._kernels(False)[9]}
print(json.dumps({
    "results": [x.hex() for x in w] + [float(x).hex() for x in np.concatenate([m, d, a, F])],
    "hits": {n: sum(f.stats.cache_hits.values()) for n, f in disp.items()},
    "misses": {n: sum(f.stats.cache_misses.values()) for n, f in disp.items()},
    "cached": {n: f.stats.cache_path is not None for n, f in disp.items()},
}))
"""


def _env(**extra):
    env = {k: v for k, v in os.environ.items() if not k.startswith("NUMBA_")}
    env.update(CONTACTLAB_BACKEND="numba", PYTHONPATH=str(ROOT), **extra)
    return env


def _run(env, n=1):
    """Run SCRIPT in ``n`` fresh processes at once (warnings are errors there too)."""
    procs = [subprocess.Popen([sys.executable, "-W", "error", "-c", SCRIPT], env=env, cwd=ROOT,
                              stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
             for _ in range(n)]
    out = []
    for p in procs:
        so, se = p.communicate(timeout=900)
        assert p.returncode == 0, se
        out.append(json.loads(so.strip().splitlines()[-1]))
    return out


def test_a_second_process_loads_the_compiled_kernels_from_disk(tmp_path):
    """Two processes start cold at once on an empty cache: with the compile lock each kernel is
    compiled once in all (the other process loads it); a third process compiles nothing. The
    results are bit-identical whichever process compiled and whichever loaded."""
    env = _env(NUMBA_CACHE_DIR=str(tmp_path / "cache"))
    cold = _run(env, n=2)
    index = sorted(p.name for p in (tmp_path / "cache").rglob("*.nbi"))
    assert any(name.startswith("_compiled._jenkins-") for name in index), index
    assert any(name.startswith("law_kernel._normal_pass_hertz-") for name in index), index
    for name in ("jenkins", "normal_pass"):
        assert all(r["cached"][name] for r in cold)
        assert sum(r["misses"][name] for r in cold) == 1, cold     # compiled once in all
        assert sum(r["hits"][name] for r in cold) == 1, cold       # ... and loaded once
    (warm,) = _run(env)
    assert all(warm["misses"][name] == 0 and warm["hits"][name] == 1 for name in warm["hits"])
    assert cold[0]["results"] == cold[1]["results"] == warm["results"]


def test_no_writable_cache_directory_compiles_in_memory_quietly(tmp_path):
    """Every cache location unusable (numba's only allowed locator points below a file): the
    kernels compile in memory, without a warning (the processes run with ``-W error``), with the
    results of a cached run."""
    import numba.core.config as cfg
    if not hasattr(cfg, "CACHE_LOCATOR_CLASSES"):
        pytest.skip("this numba cannot restrict its cache locators")
    blocker = tmp_path / "a_file"
    blocker.write_text("")
    (nocache,) = _run(_env(NUMBA_CACHE_DIR=str(blocker / "cache"),
                           NUMBA_CACHE_LOCATOR_CLASSES="UserProvidedCacheLocator"))
    assert not any(nocache["cached"].values())
    assert all(v == 0 for v in nocache["hits"].values())
    (cached,) = _run(_env(NUMBA_CACHE_DIR=str(tmp_path / "cache")))
    assert all(cached["cached"].values())
    assert nocache["results"] == cached["results"]


def test_every_kernel_is_cached_under_its_own_name():
    """All compiled kernels get an on-disk cache (nothing is compiled here), the serial and the
    threaded build of a law pass under two names (numba's cache key ignores ``parallel``)."""
    from contactlab.foundation import _compiled, _compiled_viscoelastic
    from contactlab.physics import law_kernel
    if _compiled.backend() != "numba":
        pytest.skip("numpy backend forced")
    disp = dict(_compiled._build())
    disp["trial"] = _compiled_viscoelastic.trial_step()
    for par in (False, True):
        for f in law_kernel._kernels(par):
            disp[f.py_func.__qualname__] = f
    disp["_load"] = law_kernel._KERNELS["load"]
    assert {"_normal_pass", "_normal_pass_parallel", "_fused_torsion", "_fused_tangential",
            "_fused_torsion_parallel", "_fused_tangential_parallel", "_spring_pass_parallel",
            "_switch_pass", "_switch_pass_parallel", "_switch_step_pass",
            "_switch_step_pass_parallel", "_first_pass", "_first_pass_parallel",
            "_fused_tangential_hertz", "_fused_tangential_hertz_parallel",
            "_fused_torsion_hertz", "_fused_torsion_hertz_parallel", "_normal_pass_hertz",
            "_normal_pass_hertz_parallel", "_cbrt_pass", "_cbrt_pass_parallel"} <= disp.keys()
    if any(f.stats.cache_path is None for f in disp.values()):
        pytest.skip("no writable cache directory in this environment")
    index = [f._cache._cache_file._index_name for f in disp.values()]
    # 8 Winkler kernels (one step loop for one block or many since issue 13; the whole-power
    # helper of the edge-cell pass), the viscoelastic step, 22 law passes (serial and threaded:
    # normal, fused torsion, spring, switch onto the springs, switch-and-step in blocks, fused
    # tangential, switch-and-step per contact, fused tangential, torsion and normal for n = 2,
    # the force's cube root) and the law loader
    assert len(set(index)) == len(index) == 32, index


def test_import_contactlab_does_not_import_numba():
    code = "import sys, contactlab; print('numba' in sys.modules)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True,
                         env=_env(), cwd=ROOT)
    assert out.stdout.strip() == "False"


def test_a_numba_that_does_not_import_means_numpy(tmp_path):
    """numba installed but refusing to import (as a numba too old for the installed numpy does):
    the foundations and the contact law choose their numpy paths instead of failing."""
    (tmp_path / "numba").mkdir()
    (tmp_path / "numba" / "__init__.py").write_text(
        "raise ImportError('Numba needs NumPy 2.0 or less')\n")
    code = ("import contactlab as cl\n"
            "from contactlab.foundation import _compiled\n"
            "law = cl.ContactLaw(cl.profiles.Paraboloid, R=0.01, E_star=1e11, G_star=4e10,\n"
            "                    G_torsion=4e10, friction=0.3)\n"
            "print(_compiled.backend(), law.fast, cl.effects.law._kernel.AVAILABLE)")
    env = _env()
    env["PYTHONPATH"] = os.pathsep.join([str(tmp_path), str(ROOT)])
    out = subprocess.run([sys.executable, "-W", "error", "-c", code], capture_output=True,
                         text=True, env=env, cwd=ROOT)
    assert out.returncode == 0, out.stderr
    assert out.stdout.split() == ["numpy", "False", "False"]
