"""The array-module backends of :class:`contactlab.effects.law.ContactLaw`: its step on a GPU
(``backend="cupy"``, extra ``gpu``) and the same code on numpy (``backend="xp-numpy"``, which
tests the GPU path on any machine).

The law's state (reference depths, both channels' turning-point stacks) and its per-contact
parameters live in the backend's array module; a step runs the constant-load law of every
contact there (:mod:`contactlab.physics.law_xp`: normal contact, Cattaneo–Mindlin and exact
torsion with Masing's rule, elementwise and masked, no loop over contacts; on a GPU the plain
step — every contact in contact and at constant load, or on its springs — is two fused
kernels, a normal kernel and a step kernel, and in the other steps each channel's Masing step
is one kernel: :mod:`contactlab.physics.law_cuda`) and returns a
:class:`DeviceLawStep` whose arrays are of that module (CuPy arrays stay on the device;
``cupy.asnumpy`` brings them to the host). Contacts whose normal load changes go onto their
MDR springs on the host (:mod:`contactlab.effects.law_device_springs`: the compiled spring
passes where numba imports, else the numpy spring path): their values are gathered from the
device and their results scattered back, a transfer of the contacts on springs only. ``law.state``,
``law.state = ...`` and ``law.reset`` work as on the other backends (the state is given as
numpy arrays). With ``backend="xp-numpy"`` every result and every state entry equals the numpy
reference law (``backend="numpy"``) to the bit.
"""
from __future__ import annotations

import warnings
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..citations import Citations
from ..errors import MemoryBudgetError, NotSupportedError, OutsideTheoryError, ParameterError
from ..errors import UnknownNameError
from ..errors import ValidityWarning
from ..params import check_memory
from ..physics import law_cuda as _cuda
from ..physics import law_xp as _xp
from ..physics import master as _master
from . import law_device_springs as _springs
from .law_checks import _per_step
from .law_step import _OUT_FIELDS, LawStep, law_sources

__all__ = ["BACKENDS", "DeviceLawStep", "array_module", "device_law_memory", "XP_STEP_BYTES",
           "resolve", "check_device", "step", "params"]

#: the backends of a law: numpy reference, compiled (numba), GPU (CuPy), and the GPU code
#: run with numpy (tests the GPU path without a GPU; slower than "numpy")
BACKENDS = ("numpy", "numba", "cupy", "xp-numpy")
#: peak memory of one step of the array-module path per contact beyond the law's state, bytes
#: (measured with tracemalloc on "xp-numpy" at 10^5 contacts, force, displacement and twist
#: with reversals and loop closures: 278 B including the step's results, which law_memory
#: counts already; rounded up for the allocator of a GPU array module, which keeps freed
#: blocks for reuse)
XP_STEP_BYTES = 320


def resolve(backend: Any, fast: bool | None, size: int, state_bytes: float
            ) -> tuple[bool | None, Any]:
    """``(fast, xp)`` of a law's ``backend`` and ``fast`` arguments: ``fast`` as the law reads
    it (None: its default choice), ``xp`` the array module of "cupy" and "xp-numpy" (None
    otherwise), checked: the name, its agreement with ``fast``, the module's presence and the
    device memory of ``size`` contacts (:func:`check_device`)."""
    if backend is None:
        return fast, None
    if not isinstance(backend, str) or backend not in BACKENDS:
        raise UnknownNameError(f"backend={backend!r} is invalid: allowed are {BACKENDS}.")
    if fast is not None and fast != (backend == "numba"):
        raise ParameterError(f"fast={fast!r} contradicts backend={backend!r}: give one of "
                             "them.")
    xp = array_module(backend) if backend in ("cupy", "xp-numpy") else None
    if xp is not None:
        check_device(xp, "ContactLaw()", size, state_bytes)
    return backend == "numba", xp


def array_module(backend: str) -> Any:
    """The array namespace of ``backend`` ("cupy" or "xp-numpy").

    Raises
    ------
    NotSupportedError
        ``backend="cupy"`` without CuPy installed or without a CUDA device it can use.
    """
    if backend == "xp-numpy":
        return np
    try:
        import cupy  # type: ignore[import-not-found, unused-ignore]
    except Exception as err:            # ImportError, or a CuPy broken at import (CUDA libs)
        raise NotSupportedError(
            f"backend='cupy' is not available: CuPy does not import ({type(err).__name__}: "
            f"{err}). It needs CuPy and a CUDA GPU: pip install 'contactlab[gpu]' (or the "
            "cupy-cudaXXx wheel of your CUDA version); backend='numpy' or 'numba' run on the "
            "CPU.") from err
    try:
        count = int(cupy.cuda.runtime.getDeviceCount())
    except Exception as err:            # no driver, no device
        raise NotSupportedError(
            f"backend='cupy' is not available: CuPy finds no CUDA device ({type(err).__name__}: "
            f"{err}). It needs a CUDA GPU and its driver; backend='numpy' or 'numba' run on "
            "the CPU.") from err
    if count < 1:
        raise NotSupportedError("backend='cupy' is not available: CuPy finds no CUDA device. "
                                "It needs a CUDA GPU and its driver; backend='numpy' or "
                                "'numba' run on the CPU.")
    return cupy


def device_law_memory(size: int, state_bytes: float) -> float:
    """Device memory of a law on an array-module backend, bytes: its state and results
    (``state_bytes``, :func:`contactlab.effects.law.law_memory`), the per-contact parameters
    on the device (7 float64) and one step's temporaries (:data:`XP_STEP_BYTES`)."""
    return float(state_bytes) + float(size) * (56 + XP_STEP_BYTES)


def check_device(xp: Any, what: str, size: int, state_bytes: float) -> None:
    """Refuse (MemoryBudgetError) a law whose device memory exceeds the memory budget
    (:func:`contactlab.set_memory_budget`) or, on a GPU, the device's free memory: checked
    before anything is allocated there."""
    need = device_law_memory(size, state_bytes)
    check_memory(what, need, f"{size} contacts on backend 'cupy' or 'xp-numpy': "
                 f"{need / size:.0f} bytes per contact incl. one step's temporaries")
    if xp is not np:
        free, total = (int(v) for v in xp.cuda.runtime.memGetInfo())
        if need > free:
            raise MemoryBudgetError(
                f"{what} would need about {need / 1024**3:.3g} GiB of GPU memory ({size} "
                f"contacts, {need / size:.0f} bytes each incl. one step's temporaries), above "
                f"the {free / 1024**3:.3g} GiB free of the device's {total / 1024**3:.3g} GiB: "
                "use fewer contacts per law (several laws, one per block of contacts).")


def _host(v: Any, xp: Any = None) -> np.ndarray:
    """A numpy copy of an array of the module ``xp`` (None or numpy: a numpy array)."""
    if xp is None or xp is np:
        return np.array(v, order="C")
    return xp.asnumpy(v)


@dataclass(frozen=True, eq=False)
class DeviceLawStep(LawStep):
    """A :class:`~contactlab.effects.law_step.LawStep` whose arrays belong to the law's array
    module (CuPy arrays on a GPU); its model errors and citations are computed on the host."""

    xp: Any = field(default=None, repr=False)      # the arrays' module (None: numpy)

    def _host_step(self, idx: np.ndarray | None = None) -> LawStep:
        """The fields the model errors read (of the contacts ``idx``; all for None), on the
        host, as a :class:`LawStep`."""
        pick = {}
        for f in ("exact", "radius", "torsion_stick_radius", "torque"):
            v = getattr(self, f)
            pick[f] = _host(v if idx is None else v[_to(self.xp or np, idx)], self.xp)
        zero = np.zeros(pick["radius"].shape)
        return LawStep(zero, pick["radius"], zero, zero, pick["torque"], zero,
                       pick["torsion_stick_radius"], zero, pick["exact"], meta=self.meta)

    def model_errors_at(self, idx: np.ndarray | None) -> dict[str, Any]:
        return self._host_step(idx).model_errors_at(None)

    def model_error_peaks_at(self, idx: np.ndarray) -> dict[str, float]:
        # (the law's warning, in its changing-load steps: the four fields of the contacts on
        # springs gathered on the device and copied to the host; the peaks are a maximum and
        # a minimum over them, whatever their order: the same bits. Measured on a GPU at 10^7
        # contacts, 1 % on springs: the whole fields' copies took 93 ms of a 144 ms step)
        ix = _indices(idx)
        return self._host_step(ix).model_error_peaks_at(np.arange(ix.size))

    def model_error_worst_at(self, on: np.ndarray, quantity: str,
                             peak: float) -> tuple[int, float]:
        ix = _indices(on)           # ascending: the first largest entry is the same contact's
        j, value = self._host_step(ix).model_error_worst_at(np.arange(ix.size), quantity, peak)
        return int(ix[j]), value

    @property
    def citations(self) -> Citations:
        return Citations(law_sources(springs=not bool(self.exact.all())))

    def _columns(self) -> dict[str, Any]:
        """The columns of ``to_csv`` and ``to_dataframe``, on the host."""
        return {k: _host(v, self.xp) for k, v in self.to_dict().items()}


def _indices(on: np.ndarray) -> np.ndarray:
    """Contact indices (ascending) of ``on``: indices, or a bool mask over all contacts."""
    on = np.asarray(on)
    return np.flatnonzero(on) if on.dtype == bool else on


def _to(xp: Any, idx: np.ndarray) -> Any:
    """Host indices as an index array of the module ``xp``."""
    return idx if xp is np else xp.asarray(idx)


def params(law: Any) -> dict[str, Any]:
    """The law's per-contact parameters and torsion master-curve table in its array module
    (copied to the device once, on the first step)."""
    got = law.__dict__.get("_xp_params")
    if got is None:
        xp = law._xp
        got = {"kc": law._kc, "E": law._E_star, "G": law._G_star, "Gt": law._G_torsion,
               "mu": law._friction, "flat": law._flat, "coef": law._master.coef}
        if xp is not np:        # contiguous (a scalar parameter is a broadcast view)
            got = {k: xp.ascontiguousarray(xp.asarray(v)) for k, v in got.items()}
        law.__dict__["_xp_params"] = got
    return got


def _input(law: Any, xp: Any, name: str, value: Any, unit: str, nonneg: bool = False) -> Any:
    """A per-step input as a float64 array of ``xp`` of one value per contact: host values
    through the numpy checks (the same errors as the numpy law), device arrays checked on the
    device (an offending entry is named by the same checks on the host)."""
    size = law.size
    if xp is np or not isinstance(value, xp.ndarray):
        return xp.asarray(_per_step(name, value, size, unit, nonneg=nonneg))
    if value.ndim > 1 or (value.ndim == 1 and value.size != size) or value.dtype.kind not in "iuf":
        _per_step(name, _host(value, xp), size, unit, nonneg=nonneg)        # raises, naming it
        raise ParameterError(f"{name} is invalid: give a float array of one value per contact "
                             f"({size},) or a scalar.")
    x = xp.broadcast_to(value.astype(np.float64, copy=False), (size,))
    ok = xp.isfinite(x)
    if nonneg:
        ok &= x >= 0
    if not bool(ok.all()):
        _per_step(name, _host(x, xp), size, unit, nonneg=nonneg)            # raises, naming it
    return x


def _check_out(law: Any, xp: Any, out: Any) -> None:
    ok = isinstance(out, LawStep)
    for f in _OUT_FIELDS if ok else ():
        v = getattr(out, f)
        want = np.bool_ if f == "exact" else np.float64
        if not (isinstance(v, xp.ndarray) and v.shape == (law.size,) and v.dtype == want
                and v.flags.c_contiguous):
            ok = False
    if not ok:
        raise ParameterError(f"out={type(out).__name__} is invalid: give a LawStep returned "
                             f"by an earlier step of this law ({law.size} contacts, backend "
                             f"{law.backend!r}).")


def step(law: Any, depth: Any, force: Any, displacement: Any, twist: Any, out: Any,
         tangent: bool, spring_memory: Callable[[int, int], float]) -> DeviceLawStep:
    """One step of ``law`` on its array-module backend (see the module docstring): the
    arithmetic and bookkeeping of the numpy law's step, in the law's array module
    (``spring_memory``: :func:`contactlab.effects.law.law_spring_memory`, checked before a
    switch onto the springs)."""
    from ..params import exactly_one
    xp = law._xp
    if tangent:
        raise NotSupportedError(f"tangent=True is not supported on backend={law.backend!r}: "
                                "use backend='numpy' or 'numba' for the consistent tangent.")
    if out is not None:
        _check_out(law, xp, out)
    key, val = exactly_one("ContactLaw.step()", {"depth": depth, "force": force})
    P = params(law)
    size = law.size
    n = law.n
    kern = law._kernels
    if kern is not None and kern.normal is not None:
        springs = _on_springs(law, xp)
        first = _plain_normal(law, xp, kern, key == "force", val, displacement, twist,
                              None if springs is None else springs[1])
        if first is not None:           # the plain case: two kernels (+ the host's springs)
            if first[-1] and not law._warned:
                law._warned = True
                warnings.warn(_BOTH, ValidityWarning, stacklevel=3)
            outs, n_over = _plain_rest(law, xp, kern, first[:-1], springs)
            if n_over:
                law._warn_overflow(n_over)
            return _result(xp, out, outs)
    with np.errstate(all="ignore"):     # masked lanes may overflow; results are checked below
        v = _input(law, xp, key, val, "m" if key == "depth" else "N", nonneg=key == "force")
        d, a, F = _xp.normal(xp, key == "force", v, P["kc"], P["E"], n, P["flat"])
        u = None if displacement is None else _input(law, xp, "displacement", displacement,
                                                      "m")
        phi = None if twist is None else _input(law, xp, "twist", twist, "rad")
        st = law._st
        live = a > 0
        all_live = bool(live.all())
        if not all_live:
            law._clear(_host(xp.flatnonzero(~live), xp))
        ref = st["depth_ref"]
        ref[...] = xp.where(live & (ref == 0), d, ref)
        off = live & (xp.abs(d - ref) > law.load_rtol * ref)
        if law.springs:
            off_idx = _host(xp.flatnonzero(off), xp)
            switch = off_idx[law._pool.slot[off_idx] < 0]      # not on springs yet
            if switch.size:
                n_spr = law._pool.used + int(switch.size)
                check_memory("ContactLaw.step()", spring_memory(n_spr, law.springs),
                             f"{n_spr} contacts on {law.springs} springs each")
                _springs.to_springs(law, xp, switch, d, a)
        elif bool(off.any()):
            i = int(xp.argmax(off))
            raise OutsideTheoryError(
                f"depth[{i}]={float(d[i])!r} m differs from the depth {float(ref[i])!r} m at "
                f"which contact {i}'s memory started by more than load_rtol={law.load_rtol!r}: "
                "this law is exact at constant normal load. Call law.reset(mask) to restart the "
                "memory of contacts whose load changed, or raise load_rtol.")
        if (u is not None and phi is not None and not law._warned
                and bool(xp.any(live & (u != 0) & (phi != 0)))):
            law._warned = True
            warnings.warn(_BOTH, ValidityWarning, stacklevel=3)
        zero = xp.zeros(size)
        was = st["tan_overflow"] | st["tor_overflow"]
        dW = zero.copy()
        Ft, ct = zero.copy(), a.copy()
        M, cm = zero.copy(), a.copy()
        safe_a = xp.where(live, a, 1.0)
        safe_d = xp.where(live, d, 1.0)
        kernel = None if kern is None else kern.channel
        if u is not None:
            FN = xp.where(live, F, 0.0)
            Ft, ct, w = (_tangential(law, xp, P, u, safe_a, safe_d, FN) if kernel is None else
                         _fused(law, xp, kernel, _cuda.TANGENTIAL, P, u, safe_a, safe_d, FN))
            dW = dW + w
        if phi is not None:
            M, cm, w = (_torsion(law, xp, P, phi, safe_a, safe_d) if kernel is None else
                        _fused(law, xp, kernel, _cuda.TORSION, P, phi, safe_a, safe_d, zero))
            dW = dW + w
        over = st["tan_overflow"] | st["tor_overflow"]
        exact = live & ~over
        springs = _on_springs(law, xp)          # (all live: the others were cleared)
        if springs is not None:
            over &= ~springs[1]                 # their (unused) stacks are not counted
        n_over = int(xp.count_nonzero(over & ~was & live))
        if springs is not None:
            _spring_outputs(law, xp, springs[0], d, a, u, phi, (Ft, ct, M, cm, dW))
            exact[_to(xp, springs[0])] = False
        if not all_live:
            dead = ~live
            Ft, M, dW, ct, cm = (xp.where(dead, 0.0, arr) for arr in (Ft, M, dW, ct, cm))
            law._clear(_host(xp.flatnonzero(dead), xp))
        outs = (d, a, F, Ft, M, ct, cm, dW)
        # one test of their sum (as the compiled step; 9 operations instead of 25): not finite
        # when an output is not; a sum of finite outputs that overflows only sends the step to
        # the exact check below, which finds nothing
        tot = d + a
        for arr in outs[2:]:
            tot += arr
        if not bool(xp.isfinite(tot).all()):
            law._check_finite(_host(live, xp), *(_host(arr, xp) for arr in outs))
    if n_over:
        law._warn_overflow(n_over)
    return _result(xp, out, (d, a, F, Ft, M, ct, cm, dW, exact))


_BOTH = ("ContactLaw: displacement and twist together are treated as two independent slip "
         "problems, each with the full friction limit (outside the theory: the slip "
         "conditions couple).")


def _result(xp: Any, out: Any, outs: tuple) -> Any:
    """The step's :class:`DeviceLawStep` of the arrays ``outs`` (``out``'s arrays written
    and ``out`` returned when given)."""
    d, a, F, Ft, M, ct, cm, dW, exact = outs
    res = DeviceLawStep(d, a, F, Ft, M, ct, cm, dW, exact, xp=xp)
    if out is None:
        return res
    for f in _OUT_FIELDS:
        getattr(out, f)[...] = getattr(res, f)
    return out


def _direct(xp: Any, value: Any, size: int) -> Any:
    """``value`` itself when it is a device array the kernels can read as it is (float64,
    one C-contiguous value per contact; checked by the normal kernel), else None."""
    if (xp is not np and isinstance(value, xp.ndarray) and value.dtype == np.float64
            and value.shape == (size,) and value.flags.c_contiguous):
        return value
    return None


def _spring_outputs(law: Any, xp: Any, idx: np.ndarray, d: Any, a: Any, u: Any, phi: Any,
                    outs: tuple) -> bool:
    """The spring step of the contacts ``idx`` (every contact on springs) on the host
    (:mod:`contactlab.effects.law_device_springs`), their values gathered from the step's
    device arrays ``d``, ``a``, ``u``, ``phi`` and their results scattered into ``outs``
    (``Ft, ct, M, cm, dW``); returns whether those results are all finite."""
    di = _to(xp, idx)
    r = _springs.spring_step(law, xp, idx, _host(d[di], xp), _host(a[di], xp),
                             None if u is None else _host(u[di], xp),
                             None if phi is None else _host(phi[di], xp))
    for arr, v in zip(outs, r):
        arr[di] = xp.asarray(v)
    return all(bool(np.isfinite(v).all()) for v in r)


def _on_springs(law: Any, xp: Any) -> tuple[np.ndarray, Any] | None:
    """``(contacts on springs, ascending, from the pool's rows in use (no pass over every
    contact); their mask on the device, bool: one byte each, as the kernels read it)``, or
    None when no contact is on springs."""
    pool = law._pool
    if pool is None or not pool.used:
        return None
    idx = np.sort(pool.owner[:pool.used])
    mask = xp.zeros(law.size, bool)
    mask[_to(xp, idx)] = True
    return idx, mask


def _plain_normal(law: Any, xp: Any, kern: _cuda.Kernels, by_force: bool, val: Any,
                  displacement: Any, twist: Any, spring: Any = None) -> tuple | None:
    """The normal kernel: ``(u, phi, d, a, F, flags, both)`` when the step is the plain
    case (every input finite, every contact in contact, no depth beyond ``load_rtol`` of its
    reference but those of contacts on springs, ``spring``: their mask, or None), else None
    (the array path takes the step, from the start: nothing was written)."""
    size = law.size
    P = params(law)
    c = xp.ascontiguousarray
    got: list[Any] = []
    for name, value, unit, nonneg in ((("force" if by_force else "depth"), val,
                                       "N" if by_force else "m", by_force),
                                      ("displacement", displacement, "m", False),
                                      ("twist", twist, "rad", False)):
        if value is None:
            got.append(None)
            continue
        arr = _direct(xp, value, size)
        got.append(c(_input(law, xp, name, value, unit, nonneg=nonneg)) if arr is None
                   else arr)
    v, u, phi = got
    flags = xp.zeros(6, np.uint64)
    d, a, F = xp.empty(size), xp.empty(size), xp.empty(size)
    assert kern.normal is not None
    kern.normal(_cuda.normal_args(by_force, v, u, phi, c(P["kc"]), c(P["E"]), c(P["flat"]),
                                  law.n, law.load_rtol, law._st["depth_ref"], (d, a, F),
                                  flags, spring))
    f = _host(flags[:4], xp)
    if f[_cuda.FLAG_BAD] or f[_cuda.FLAG_SEPARATED] or f[_cuda.FLAG_OFF]:
        return None
    return u, phi, d, a, F, flags, bool(f[_cuda.FLAG_BOTH] and u is not None and
                                        phi is not None)


def _plain_rest(law: Any, xp: Any, kern: _cuda.Kernels, normal: tuple,
                springs: tuple | None) -> tuple[tuple, int]:
    """The step kernel after :func:`_plain_normal` (``normal``: its ``(u, phi, d, a, F,
    flags)``): ``(outputs, first overflows)``; ``springs``: :func:`_on_springs` (those
    contacts left out by the kernel, stepped on the host as in the array path); a step whose
    outputs are not finite is refused as on the array path (after the springs' step, as
    there)."""
    u, phi, d, a, F, flags = normal
    size = law.size
    P = params(law)
    c = xp.ascontiguousarray
    outs = (*(xp.empty(size) for _ in range(5)), xp.empty(size, bool))
    assert kern.step is not None
    kern.step(_cuda.step_args(u, phi, d, a, F, c(P["mu"]), c(P["E"]), c(P["G"]), c(P["Gt"]),
                              law.n, law._master, c(P["coef"]), law._st["depth_ref"],
                              law._chan, outs, flags, None if springs is None else springs[1]))
    g = _host(flags, xp)
    Ft, ct, M, cm, dW, exact = outs
    finite = (True if springs is None
              else _spring_outputs(law, xp, springs[0], d, a, u, phi, (Ft, ct, M, cm, dW)))
    if g[_cuda.FLAG_NONFINITE] or not finite:
        law._check_finite(np.ones(size, bool),
                          *(_host(arr, xp) for arr in (d, a, F, Ft, M, ct, cm, dW)))
    return (d, a, F, Ft, M, ct, cm, dW, exact), int(g[_cuda.COUNT_OVERFLOW])


def kernels(xp: Any) -> _cuda.Kernels | None:
    """The fused kernels of the array module ``xp`` (:mod:`contactlab.physics.law_cuda`):
    CuPy's build of them on a GPU, None on numpy (the array path, the reference)."""
    if xp is None or xp is np:
        return None
    got = _KERNELS.get(xp)
    if got is None:
        got = _KERNELS[xp] = _cuda.cupy_kernels(xp)
    return got


_KERNELS: dict[Any, _cuda.Kernels] = {}         # per array module


def _fused(law: Any, xp: Any, kernel: Callable[[tuple], None], kind: int, P: dict, x: Any,
           a: Any, d: Any, FN: Any) -> tuple:
    """One channel's Masing step of every contact in one kernel launch (``_tangential`` or
    ``_torsion`` fused): ``(y, aux, dW)``."""
    size = law.size
    out = (xp.empty(size), xp.empty(size), xp.empty(size))
    G = P["G"] if kind == _cuda.TANGENTIAL else P["Gt"]
    c = xp.ascontiguousarray
    kernel(_cuda.channel_args(kind, c(x), a, d, FN, c(P["mu"]), c(P["E"]), c(G), law.n,
                              law._master, c(P["coef"]), law._chan,
                              0 if kind == _cuda.TANGENTIAL else 1, out))
    return out


def _channel(st: dict, prefix: str) -> dict[str, Any]:
    from ..physics.masing_stack import STACK_FIELDS
    return {k: st[f"{prefix}_{k}"] for k in STACK_FIELDS}


def _tangential(law: Any, xp: Any, P: dict, u: Any, a: Any, d: Any, FN: Any) -> tuple:
    """Cattaneo–Mindlin with Masing's rule (``ContactLaw._tangential``, elementwise)."""
    n = law.n
    mu, E, G = P["mu"], P["E"], P["G"]
    inv = G / (mu * E * d)
    muF = mu * FN
    Dscale = 2.0 * a * (mu * E * d) ** 2 / G

    def load(arg: Any, idx: Any) -> tuple:
        if idx is None:
            t, f, w = _xp.tangential_curve(xp, n, arg * inv)
            return muF * f, a * t, Dscale * w
        t, f, w = _xp.tangential_curve(xp, n, arg * inv[idx])
        return muF[idx] * f, a[idx] * t, Dscale[idx] * w

    return _xp.masing_step(xp, _channel(law._st, "tan"), u, load)


def _torsion(law: Any, xp: Any, P: dict, phi: Any, a: Any, d: Any) -> tuple:
    """Exact (Jäger) torsion with Masing's rule (``ContactLaw._torsion``, elementwise)."""
    mc = law._master
    _, M_full = _master.torsion_scales(law.n, P["E"], P["Gt"], P["mu"], a, d)
    inv_s = _master.inverse_twist_scale(P["E"], P["Gt"], P["mu"], a, d)

    def load(arg: Any, idx: Any) -> tuple:
        if idx is None:
            t, m, q = _xp.torsion_curves(xp, P["coef"], mc.y_scale, arg * inv_s, mc.y0, mc.m0,
                                         mc.scaled, mc.power)
            return M_full * m, a * t, M_full * arg * q
        t, m, q = _xp.torsion_curves(xp, P["coef"], mc.y_scale, arg * inv_s[idx], mc.y0,
                                     mc.m0, mc.scaled, mc.power)
        return M_full[idx] * m, a[idx] * t, M_full[idx] * arg * q

    return _xp.masing_step(xp, _channel(law._st, "tor"), phi, load)
