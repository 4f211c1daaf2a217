"""The MDR springs of an array-module :class:`contactlab.effects.law.ContactLaw` (a GPU law,
``backend="cupy"``, or its code on numpy, ``backend="xp-numpy"``): run on the host, where the
law's spring pool and per-contact parameters live.

The contacts that switch onto their springs, and those on them, are a part of the law's
contacts (in a packing most contacts keep their load). Their values are gathered from the
device into arrays of their own (entry ``j`` for the ``j``-th of them), the host spring passes
run on those, and the step's results are scattered back: a transfer of the contacts on springs
only. On a device the passes are the compiled ones of the numba law
(:mod:`contactlab.physics.law_kernel`, extra ``fast``) where numba imports, else the numpy
reference (:mod:`contactlab.effects.law_springs_numpy`); ``CONTACTLAB_BACKEND=numpy`` (or
``contactlab.foundation._compiled.set_backend("numpy")``) forces the reference. The two agree
within 1e-11 of each field's largest value (the compiled passes form a cell's integrals in
another order), as the numba and numpy laws do. ``backend="xp-numpy"``, which
exists to test the device code against the numpy law to the bit, always runs the reference.

The compiled passes index every per-contact array by the contact; here they are given the
gathered arrays with the indices ``0 .. m-1`` and, as the pool's row of entry ``j``, a gathered
copy of the pool's slots: after a switch the pool's own slots and owners are set to the
contacts' indices.
"""
from __future__ import annotations

from typing import Any

import numpy as np

from ..physics import law_kernel as _kernel
from . import law_springs_numpy as _np_springs

__all__ = ["compiled", "to_springs", "spring_step"]


def _host(v: Any, xp: Any) -> np.ndarray:
    return v if xp is np else xp.asnumpy(v)


def compiled(xp: Any) -> bool:
    """The host spring passes of a law on the array module ``xp`` are the compiled ones: on a
    device, where numba imports and the numpy reference is not forced; on numpy
    (``backend="xp-numpy"``, which tests the device code against the numpy law to the bit)
    never."""
    if xp is np or not _kernel.AVAILABLE:
        return False
    from ..foundation import _compiled
    return _compiled.backend() == "numba"


def _gather(xp: Any, v: Any, idx: np.ndarray, axis: int = 0) -> np.ndarray:
    """``v`` at the contacts ``idx`` along ``axis``, on the host."""
    ix = idx if xp is np else xp.asarray(idx)
    return np.ascontiguousarray(_host(xp.take(v, ix, axis=axis), xp))


class _Gather:
    """``v[idx]`` of an array of the module ``xp``, on the host, for host indices ``idx``."""

    def __init__(self, v: Any, xp: Any) -> None:
        self.v = v
        self.xp = xp

    def __getitem__(self, idx: np.ndarray) -> np.ndarray:
        return _gather(self.xp, self.v, idx)


class _HostView:
    """The law as the numpy spring path sees it on a device: its state read through gathers
    at the contacts it reads, everything else the law's own (parameters and spring pool live
    on the host)."""

    def __init__(self, law: Any) -> None:
        self._law = law
        self._st = {k: _Gather(v, law._xp) for k, v in law._st.items()}

    def __getattr__(self, name: str) -> Any:
        return getattr(self._law, name)


def to_springs(law: Any, xp: Any, idx: np.ndarray, d: Any, a: Any) -> None:
    """Switch the contacts ``idx`` (host indices, not on springs) onto their springs: their
    Masing turning points replayed through the elements at the held load (``d``, ``a``: the
    step's depths and radii of all contacts, arrays of ``xp``)."""
    if idx.size == 0:
        return
    if not compiled(xp):
        if xp is np:
            _np_springs.to_springs(law, idx, d, a)
        else:       # the state, depths and radii gathered at the contacts the path reads
            at: Any = (_Gather(d, xp), _Gather(a, xp))
            _np_springs.to_springs(_HostView(law), idx, *at)
        return
    pool = law._pool
    m = idx.size
    pool.reserve(m, law.parallel)
    is_flat = law.n == np.inf
    nn = 1.0 if is_flat else float(law.n)
    bG = law._beta ** (nn + 1.0) / (nn + 1.0)
    bH = law._beta ** (nn + 2.0) / (nn + 2.0)
    chan = law._chan
    # turning points level-major, as the law's own (the kernels' argument types)
    X = _gather(xp, chan["X_levels"], idx, axis=2).transpose(0, 2, 1)
    slot = np.empty(m, np.int32)
    base = pool.used
    P = pool.rows
    _kernel._kernels(law.parallel)[3](
        np.arange(m), _gather(xp, law._st["depth_ref"], idx), _gather(xp, a, idx),
        law._flat[idx] if is_flat else law._flat, is_flat, law._spring_cover[idx],
        law._kc[idx], nn, law._beta, bG, bH, law._friction[idx], law._E_star[idx],
        law._G_star[idx], law._G_torsion[idx], X, _gather(xp, chan["depth"], idx, axis=1),
        _gather(xp, chan["x"], idx, axis=1), slot, pool.owner, base, P["spr_cover"],
        P["spr_a"], P["spr_k"], P["spr_depth"], P["spr_tan"], P["spr_tor"], P["spr_x_tan"],
        P["spr_x_tor"])
    # the kernel wrote the entries' positions as owners: the contacts' indices instead
    pool.owner[base:base + m] = idx
    pool.slot[idx] = slot
    pool.take(m)


def spring_step(law: Any, xp: Any, idx: np.ndarray, d: np.ndarray, a: np.ndarray,
                u: np.ndarray | None, phi: np.ndarray | None) -> tuple[np.ndarray, ...]:
    """One spring step of the contacts ``idx`` (every contact on springs) at their depths
    ``d``, radii ``a`` and controls ``u``, ``phi`` (host arrays, entry ``j`` for contact
    ``idx[j]``; a control None: not driven): ``(Ft, ct, M, cm, dW)`` of those contacts."""
    if not compiled(xp):
        return _np_springs.spring_step(law, idx, d, a, u, phi)
    m = idx.size
    out = tuple(np.empty(m) for _ in range(5))
    gathered = _GatheredPool(law._pool, idx)
    regrid = lambda g: _np_springs.regrid(law, idx[g], a[g])     # noqa: E731
    _kernel.spring_pass(np.arange(m), d, a, u, phi, law._kc[idx], law.n, law._beta,
                        law._friction[idx], law._E_star[idx], law._G_star[idx],
                        law._G_torsion[idx], gathered, out, law.parallel,
                        np.zeros(m, np.int8), regrid)
    return out


class _GatheredPool:
    """The law's spring pool as :func:`contactlab.physics.law_kernel.spring_pass` reads it
    for gathered arrays: the slot of entry ``j`` is the row of contact ``idx[j]``; the rows and
    the channels' staleness are the pool's own."""

    def __init__(self, pool: Any, idx: np.ndarray) -> None:
        self.rows = pool.rows
        self.stale = pool.stale
        self.slot = pool.slot[idx]
        self.size = idx.size
