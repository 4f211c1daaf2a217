"""The batched force-controlled normal solve of a paraboloid in few passes (numba or numpy).

A paraboloid under force control is solved in closed form on every route with one constant
per contact (:meth:`~contactlab.profiles.Paraboloid._hertz_force_constants`): ``a = cbrt(F/K)``,
``d = (a·a)/R``, ``F_out = (a·d)·c``. :func:`contactlab.physics.normal.solve` does it with the
masks, copies and reductions of its general route (and the extremes its caller checks), each
result in an array of its own. :func:`paraboloid_force` performs the same operations in the
same order, so the results are bit-identical to that route and to the scalar route (tests),
with the driver's checks made on the way and the four results (with the residual
``|F_out - F|`` the error estimate reads) in one block:

* compiled (extra ``fast``: numba): two passes (:mod:`contactlab.numeric.normal_kernels`)
  around numpy's own ``cbrt``, taken in place on the whole array, counting the values that
  fail the checks;
* numpy: the operations as ufuncs written into the block (no temporaries), chunk by chunk so
  that a chunk stays in cache between them (:data:`CHUNK`), the range and request checks
  proved from the extremes of the requests (:func:`_in_range`: every operation is monotone in
  the request), which the driver's finiteness check has already reduced.

Where a value leaves the range the general route treats with its careful branches (a quotient
or a cube outside the normal floats, a force that is not positive), :func:`paraboloid_force`
declines and the general route runs.
"""
from __future__ import annotations

import math

import numpy as np

from ..numeric.normal_kernels import FORCE_SANITY, FUSED_FROM, backend, kernels, set_backend

__all__ = ["FUSED_FROM", "FORCE_SANITY", "backend", "set_backend", "paraboloid_force"]


def paraboloid_force(profile, E_star: float, F: np.ndarray, compiled: bool | str = True,
                     extremes: tuple[float, float] | None = None
                     ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray] | None:
    """Radius, depth, force and residual ``|F_out - F|`` of requested forces ``F`` on a
    :class:`~contactlab.profiles.Paraboloid` (the caller checks the type), bit-identical to the
    general route of :func:`contactlab.physics.normal.solve`.

    ``compiled``: True the numba passes, ``"numpy"`` the numpy passes, False the numba passes'
    logic as plain Python (tests). ``extremes``: ``(min(F), max(F))`` where the caller has
    them (the driver's check that every force is finite takes them): the numpy passes then
    reduce nothing.

    Returns ``(a, d, F_out, residual)`` (arrays of ``F``'s shape) with every force finite and
    within :data:`FORCE_SANITY` of its request (the driver's checks: made on the way, or proved
    from the extremes), or None where some force is not positive, a quotient lies outside
    ``[Q_MIN, Q_MAX]`` or a force fails those checks: the general route then handles (and
    reports) them.
    """
    flat = np.ascontiguousarray(F, dtype=float).reshape(-1)
    K, c = profile._hertz_force_constants(E_star)
    # the four results in one allocation: the operating system backs a large fresh block with
    # huge pages where it can (one fault per 2 MiB instead of one per 4 KiB: four separate
    # arrays of 10^6 floats measured 2200 page faults and ~7 ms per call on a virtual machine,
    # one block ~130 and ~1.7 ms); a state keeps the block while it keeps any of the arrays
    block = np.empty((4, flat.size))
    a, d, F_out, resid = block
    if compiled == "numpy":
        if not _numpy_passes(flat, profile.R, K, c, block, extremes):
            return None
    else:
        quotient, parab = kernels(bool(compiled))[:2]
        if quotient(flat, K, a):
            return None
        np.cbrt(a, out=a)
        if parab(a, flat, profile.R, c, d, F_out, resid):
            return None
    shape = np.shape(F)
    return a.reshape(shape), d.reshape(shape), F_out.reshape(shape), resid.reshape(shape)


#: elements per chunk of the numpy passes: the ufuncs run chunk by chunk, so that a chunk's
#: request and its four result rows (5 x 1 MiB) stay in the processor's cache between the
#: operations instead of streaming five arrays of the batch's size through memory for each
#: (measured at 10^6 forces on the shared 2-core VM, interleaved best of 25: 5.13 ms whole
#: arrays, 4.75-4.82 ms in chunks of 2^17-2^18 with the dozen operations before the one
#: constant of ``_hertz_force_constants``; 2^15 loses to the per-call cost)
CHUNK = 1 << 17

#: the bounds every intermediate value of the numpy passes keeps at the extremes of the
#: requests (a factor 1e18 inside the normal floats): then, the operations being monotone, it
#: keeps them for every request (see :func:`_in_range`)
_LOW, _HIGH = 1e-290, 1e290


def _in_range(lo: float, hi: float, R: float, K: float, c: float) -> bool:
    """Whether the numpy passes' values for requests in ``[lo, hi]`` are normal floats and meet
    the driver's checks (every force finite, within :data:`FORCE_SANITY` of its request),
    decided from the extremes alone.

    Every operation of the passes is a correctly rounded product or quotient of positive
    operands, each non-decreasing in the request (the quotient ``F/K``, ``a·a``, ``(a·a)/R``,
    ``a·d``, ``(a·d)·c``), and numpy's ``cbrt`` is within an ulp of the monotone cube root: so
    every intermediate value of a request in ``[lo, hi]`` lies between those of ``lo`` and
    ``hi`` (to an ulp; the bounds :data:`_LOW`, :data:`_HIGH` leave a factor 1e18). With all of
    them normal, ``F_out = F·(4E*/(3R))/K·(1 + δ)`` where ``K = 4E*/(3R)`` up to its two
    roundings and ``δ`` sums the other roundings (the quotient, the root to 0.53 ulp tripled by
    the cube, ``a·a``, ``/R``, ``a·d``, ``·c``, ``c`` itself): ``|F_out/F - 1| < 12 ulp``,
    far within :data:`FORCE_SANITY` (1e-6)."""
    if not (lo > 0 and math.isfinite(hi)):
        return False
    for x, ok in ((lo, lambda v: v >= _LOW), (hi, lambda v: v <= _HIGH)):
        q = x / K
        a = float(np.cbrt(q))
        sq = a * a
        d = sq / R
        ad = a * d
        if not all(ok(v) for v in (q, a, sq, d, ad, ad * c)):
            return False
    return True


def _numpy_passes(F: np.ndarray, R: float, K: float, c: float, block: np.ndarray,
                  extremes: tuple[float, float] | None) -> bool:
    """The operations of the compiled passes (``quotient_pass``, numpy's ``cbrt``,
    ``paraboloid_pass``) as numpy ufuncs written into the rows ``a, d, F_out, resid`` of
    ``block``, chunk by chunk (:data:`CHUNK`: every element sees the same operations, so the
    bits do not depend on the chunking); False where the requests' extremes leave the range of
    :func:`_in_range` (nothing is then to be read). The range and the request checks are
    proved from the extremes (two reductions, none where the caller gives ``extremes``)."""
    if F.size == 0:
        return False
    lo, hi = extremes if extremes is not None else (float(F.min()), float(F.max()))
    if not _in_range(lo, hi, R, K, c):
        return False
    for start in range(0, F.size, CHUNK):
        sl = slice(start, start + CHUNK)
        Fc = F[sl]
        a, d, F_out, resid = block[0, sl], block[1, sl], block[2, sl], block[3, sl]
        np.divide(Fc, K, out=a)                 # a = cbrt(F/K)
        np.cbrt(a, out=a)
        np.multiply(a, a, out=d)                # d = (a·a)/R
        d /= R
        np.multiply(a, d, out=F_out)            # F_out = (a·d)·c
        F_out *= c
        np.subtract(F_out, Fc, out=resid)       # resid = |F_out - F|
        np.abs(resid, out=resid)
    return True
