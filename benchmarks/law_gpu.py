"""ContactLaw on a GPU (issue 29, GPU part): the estimated and, where a GPU is present, the
measured time of one constant-load step of ``backend="cupy"``.

    python benchmarks/law_gpu.py            # estimate; plus the GPU rows when CuPy finds a device
    python benchmarks/law_gpu.py --n 1e6,1e7,1e8    # the GPU rows at these n (default 10^7)
    python benchmarks/law_gpu.py --changing --n 1e6,1e7    # the changing-load rows only
    python benchmarks/law_gpu.py --changing --parallel      # ... and the host springs threaded

**Estimate (no GPU needed).** The step of the array-module backend
(:mod:`contactlab.physics.law_xp`) runs as one device kernel per array operation (CuPy does
not fuse them), each reading its operands from and writing its result to device memory. This
script runs that step with numpy through a counting array type and adds up, per operation, the
bytes of its array operands and results (gathers and scatters: values and indices): the memory
traffic of one step per contact, and the number of operations (kernel launches). The estimated
step time is ``traffic / bandwidth + launches x launch_cost`` with a stated bandwidth and launch
cost (an estimate, not a measurement: real kernels reach 70-90 % of the peak bandwidth, and
CuPy's memory pool, caching and the host work of contacts on springs are not modelled).

**Measured (with CuPy and a device).** The best of six steps of ``backend="cupy"`` at
``n`` contacts, synchronised, after two warm-up steps: with the fused step (the default,
:mod:`contactlab.physics.law_cuda`: a normal kernel and a step kernel), with the fused
channel kernels only and with the array path, one after the other in the same run; at the
first ``n >= 10^7`` also a step in which 1 % of the contacts change load (they run on their
MDR springs on the host), with the compiled host spring passes and with the numpy ones.
"""
from __future__ import annotations

import functools
import os
import sys
import time
import warnings
from pathlib import Path
from typing import Any

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
import contactlab as cl                                     # noqa: E402
from contactlab.errors import ValidityWarning               # noqa: E402

#: the device the estimate is stated for: NVIDIA H200, HBM3e peak bandwidth (vendor figure)
BANDWIDTH = 4.8e12
BANDWIDTH_NAME = "H200 HBM3e peak, 4.8 TB/s"
#: cost of one kernel launch, s (a typical CUDA figure, ~5 us incl. CuPy's Python overhead)
LAUNCH = 5e-6


class _Tally:
    bytes = 0
    ops = 0


def _plain(x: Any) -> Any:
    if isinstance(x, _Counted):
        return x.view(np.ndarray)
    if isinstance(x, (tuple, list)):
        return type(x)(_plain(v) for v in x)
    return x


def _nbytes(x: Any) -> int:
    if isinstance(x, np.ndarray):
        return int(x.nbytes) if x.ndim else 0
    if isinstance(x, (tuple, list)):
        return sum(_nbytes(v) for v in x)
    return 0


def _wrap(x: Any) -> Any:
    if isinstance(x, np.ndarray) and not isinstance(x, _Counted):
        return x.view(_Counted)
    if isinstance(x, tuple):
        return tuple(_wrap(v) for v in x)
    return x


class _Counted(np.ndarray):
    """An ndarray that adds the bytes every operation on it reads and writes to _Tally."""

    def __array_ufunc__(self, ufunc, method, *inputs, **kw):
        if "out" in kw:
            kw["out"] = _plain(kw["out"])
        args = _plain(inputs)
        res = getattr(ufunc, method)(*args, **kw)
        _Tally.bytes += _nbytes(args) + _nbytes(res)
        _Tally.ops += 1
        return _wrap(res)

    def __array_function__(self, func, types, args, kwargs):
        a, k = _plain(args), {key: _plain(v) for key, v in kwargs.items()}
        res = func(*a, **k)
        if func is np.take_along_axis:      # a gather: the values taken, not the whole array
            _Tally.bytes += 2 * _nbytes(res) + _nbytes(a[1])
        else:
            _Tally.bytes += _nbytes(a) + _nbytes(tuple(k.values())) + _nbytes(res)
        _Tally.ops += 1
        return _wrap(res)

    def __getitem__(self, key):
        res = self.view(np.ndarray)[_plain(key)]
        # (the test on plain arrays: on self it would count as an operation of its own)
        if isinstance(res, np.ndarray) and not np.shares_memory(res, self.view(np.ndarray)):
            _Tally.bytes += 2 * _nbytes(res) + _nbytes(_plain(key))     # a gather
            _Tally.ops += 1
        return _wrap(res)

    def __setitem__(self, key, value):
        v = _plain(value)
        self.view(np.ndarray)[_plain(key)] = v
        _Tally.bytes += 2 * _nbytes(v) + _nbytes(_plain(key))
        _Tally.ops += 1

    def astype(self, *a, **k):
        res = self.view(np.ndarray).astype(*a, **k)
        _Tally.bytes += self.nbytes + res.nbytes
        _Tally.ops += 1
        return _wrap(res)

    def copy(self, *a, **k):
        res = self.view(np.ndarray).copy(*a, **k)
        _Tally.bytes += 2 * res.nbytes
        _Tally.ops += 1
        return _wrap(res)


class _CountingXP:
    """numpy as an array module whose arrays count their traffic."""
    ndarray = _Counted

    @staticmethod
    def asnumpy(v: Any) -> np.ndarray:          # to the host: not device traffic
        return np.array(_plain(v), order="C")

    def __getattr__(self, name: str) -> Any:
        f = getattr(np, name)
        if name in ("zeros", "asarray", "ascontiguousarray", "arange", "full", "empty"):
            return lambda *a, **k: _wrap(np.asarray(f(*_plain(a), **k)))
        return f


def _law(n: int, backend: str, parallel: bool = False) -> cl.ContactLaw:
    rng = np.random.default_rng(0)
    return cl.ContactLaw(cl.profiles.Paraboloid, R=rng.uniform(1e-3, 1e-2, n), E_star=1.15e11,
                         G_star=4.4e10, G_torsion=4.0e10, friction=0.3, backend=backend,
                         parallel=parallel)


@functools.lru_cache(maxsize=32)
def _controls(n: int, k: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Force, twist and displacement of step ``k`` (cached: the same for every mode)."""
    rng = np.random.default_rng(0)
    F = rng.uniform(1.0, 100.0, n)
    ph = rng.uniform(0.0, 2 * np.pi, n)
    return F, 2e-4 * np.sin(0.3 * k + ph), 1e-7 * np.cos(0.3 * k + ph)


def counted_traffic(n: int = 10**4, steps: int = 8) -> tuple[float, int, float, int]:
    """(bytes per contact, operations) of the largest and of the smallest of ``steps - 2``
    constant-load steps of the array-module path (normal + tangential + torsion; sinusoidal
    controls with random phases: reversals and loop closures in some steps, not in others)."""
    law = _law(n, "xp-numpy")
    law._xp = _CountingXP()
    law.reset()                         # the state in counting arrays
    law.__dict__.pop("_xp_params", None)
    seen = []
    for k in range(steps):
        F, tw, u = _controls(n, k)
        _Tally.bytes = _Tally.ops = 0
        law.step(force=F, twist=tw, displacement=u)
        if k >= 2:
            seen.append((_Tally.bytes / n, _Tally.ops))
    return (*max(seen), *min(seen))


def estimate() -> tuple[float, int]:
    per, ops, per_lo, ops_lo = counted_traffic()
    print(f"array-module step (normal + tangential + torsion, constant load): {per_lo:.0f}-"
          f"{per:.0f} bytes of device memory traffic per contact, {ops_lo}-{ops} operations "
          "(kernel launches) per step (counted: numpy with a counting array type, 10^4 "
          "contacts, 6 steps)")
    print(f"ESTIMATED GPU step time, the larger count ({BANDWIDTH_NAME}, {1e6 * LAUNCH:.0f} us "
          "per launch; an estimate, not a measurement):")
    for n in (10**6, 10**7, 10**8):
        t = per * n / BANDWIDTH + ops * LAUNCH
        print(f"  n = {n:>9.0e}: {1e3 * t:8.2f} ms per step, {n / t / 1e9:6.2f} x 10^9 "
              "contact-steps per second")
    return per, ops


def _device() -> Any:
    """CuPy when it finds a CUDA device, else None (and a line saying why)."""
    try:
        import cupy  # type: ignore[import-not-found, unused-ignore]
        if cupy.cuda.runtime.getDeviceCount() < 1:
            raise RuntimeError("no CUDA device")
    except Exception as err:
        print(f"GPU rows SKIPPED: CuPy with a CUDA device is not available here "
              f"({type(err).__name__}: {err}); install the extra 'gpu' on a machine with a GPU.")
        return None
    return cupy


def _best_step(cupy: Any, law: cl.ContactLaw, n: int, F: Any, steps: int = 8,
               changing: float = 0.0) -> float:
    """The best of ``steps - 2`` synchronised steps (two warm-ups), inputs on the device;
    ``changing``: the fraction of contacts whose force changes in every step (onto their
    springs on the host)."""
    best = np.inf
    m = int(changing * n)
    for k in range(steps):
        _, tw_h, u_h = _controls(n, k)
        tw, u = cupy.asarray(tw_h), cupy.asarray(u_h)
        if m:
            F[:m] *= 1.0 + 0.02 * (-1) ** k
        cupy.cuda.Device().synchronize()
        t0 = time.perf_counter()
        law.step(force=F, twist=tw, displacement=u)
        cupy.cuda.Device().synchronize()
        if k >= 2:
            best = min(best, time.perf_counter() - t0)
    return best


def changing_rows(cupy: Any, name: str, n: int) -> None:
    """Steps in which 1 % of ``n`` contacts change their load (onto their springs, which run
    on the host): the compiled host spring passes (where numba imports; with ``--parallel``
    also on numba's threads) and the numpy reference, one law each, side by side."""
    from contactlab.effects import law_device_springs
    from contactlab.foundation import _compiled
    routes = ["compiled", "numpy"] if law_device_springs.compiled(cupy) else ["numpy"]
    if "--parallel" in sys.argv and routes[0] == "compiled":
        import numba
        routes.insert(1, f"compiled, {numba.get_num_threads()} threads")
    times = {}
    for route in routes:
        _compiled.set_backend("numpy" if route == "numpy" else None)
        try:
            law = _law(n, "cupy", parallel="threads" in route)
            F = cupy.asarray(_controls(n, 0)[0])
            times[route] = best = _best_step(cupy, law, n, F, changing=0.01)
        finally:
            _compiled.set_backend(None)
        print(f"MEASURED on {name}: n = {n:.0e}, a step with 1 % of the contacts changing load "
              f"(on their springs, on the host, {route} spring passes): {1e3 * best:.2f} ms",
              flush=True)
        del law, F
        cupy.get_default_memory_pool().free_all_blocks()
    if len(times) == 2:
        print(f"  numpy / compiled host springs {times['numpy'] / times['compiled']:.2f}",
              flush=True)


def gpu_rows(sizes: list[int] | int) -> None:
    """The measured rows at each of ``sizes`` contacts, or a line saying why they were
    skipped: the constant-load step, and at the first size of 10^7 or more (else the last)
    a step in which 1 % of the contacts change their load (onto their springs on the host)."""
    cupy = _device()
    if cupy is None:
        return
    sizes = [sizes] if isinstance(sizes, int) else sizes
    cl.set_memory_budget("inf")
    name = cupy.cuda.runtime.getDeviceProperties(0)["name"].decode()
    from contactlab.physics.law_cuda import Kernels
    what = {"step": "fused step (normal + step kernels)", "channels": "fused channel kernels",
            "array": "array path"}
    for n in sizes:
        times = {}
        for mode in what:                   # one law at a time (10^8 contacts: ~90 GB each)
            law = _law(n, "cupy")
            kernels = law._kernels
            assert kernels is not None             # CuPy's build of the fused kernels
            if mode != "step":
                law._kernels = Kernels(kernels.channel) if mode == "channels" else None
            F = cupy.asarray(_controls(n, 0)[0])
            times[mode] = best = _best_step(cupy, law, n, F)
            print(f"MEASURED on {name}: n = {n:.0e}, constant-load step, {what[mode]}: "
                  f"{1e3 * best:.2f} ms ({n / best / 1e9:.2f} x 10^9 contact-steps per second; "
                  "inputs on the device)", flush=True)
            if mode == "step" and n == next((s for s in sizes if s >= 10**7), sizes[-1]):
                changing_rows(cupy, name, n)
            del law, F
            cupy.get_default_memory_pool().free_all_blocks()
        print(f"  array path / fused step {times['array'] / times['step']:.2f}, channel "
              f"kernels / fused step {times['channels'] / times['step']:.2f}", flush=True)


def main() -> None:
    warnings.simplefilter("ignore", ValidityWarning)    # combined shift + twist, documented
    arg = sys.argv[sys.argv.index("--n") + 1] if "--n" in sys.argv else "1e7"
    print(f"load average {os.getloadavg()[0]:.1f}")
    sizes = [int(float(v)) for v in arg.split(",")]
    if "--changing" in sys.argv:        # the changing-load rows only
        cupy = _device()
        if cupy is not None:
            cl.set_memory_budget("inf")
            name = cupy.cuda.runtime.getDeviceProperties(0)["name"].decode()
            for n in sizes:
                changing_rows(cupy, name, n)
        return
    estimate()
    gpu_rows(sizes)


if __name__ == "__main__":
    main()
