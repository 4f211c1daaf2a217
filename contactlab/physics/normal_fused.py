"""The batched force-controlled normal solve of a paraboloid in few passes (numba or numpy).

:func:`contactlab.physics.normal.solve` under force control runs the general power-term route:
~15 element-wise numpy operations and ~10 reductions around the one cube root (radius, depth,
``∫g``, force, the residual against the request and the extremes the caller checks), each
result in an array of its own. At 10^6 forces that is three times the closed form
``a = cbrt(3RF/(4E*))``, ``d = a²/R`` alone. :func:`paraboloid_force` performs the same
operations in the same order, so the results are bit-identical to that route and to the scalar
route (tests), with the driver's checks made on the way and the four results in one block:

* compiled (extra ``fast``: numba): two passes (:mod:`contactlab.numeric.normal_kernels`)
  around numpy's own ``cbrt``, taken in place on the whole array;
* numpy: the operations as ufuncs written into the block (no temporaries), chunk by chunk so
  that a chunk stays in cache between them (:data:`CHUNK`), the range checks decided by the
  extremes of the chunk's requests (two reductions: the quotient is a monotone function of
  the force) and the request check by one reduction of the chunk's residual.

Where a value leaves the range the general route treats with its careful branches (a quotient
or a cube outside the normal floats, a force that is not positive), :func:`paraboloid_force`
declines and the general route runs.
"""
from __future__ import annotations

import numpy as np

from ..numeric.normal_kernels import (FORCE_SANITY, FUSED_FROM, Q_MAX, Q_MIN, backend, kernels,
                                      set_backend)

__all__ = ["FUSED_FROM", "FORCE_SANITY", "backend", "set_backend", "paraboloid_force"]


def paraboloid_force(profile, E_star: float, F: np.ndarray, compiled: bool | str = True
                     ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray] | None:
    """Radius, depth, force and residual ``|F_out - F|`` of requested forces ``F`` on a
    :class:`~contactlab.profiles.Paraboloid` (the caller checks the type), bit-identical to the
    general route of :func:`contactlab.physics.normal.solve`.

    ``compiled``: True the numba passes, ``"numpy"`` the numpy passes, False the numba passes'
    logic as plain Python (tests).

    Returns ``(a, d, F_out, residual)`` (arrays of ``F``'s shape) with every force finite and
    within :data:`FORCE_SANITY` of its request (the driver's checks, made on the way), or None
    where some force is not positive, a quotient lies outside ``[Q_MIN, Q_MAX]`` or a force
    fails those checks: the general route then handles (and reports) them.
    """
    flat = np.ascontiguousarray(F, dtype=float).reshape(-1)
    (c, n), = profile.power_terms()
    kap = profile._power_kappa(n)
    two_e = 2.0 * E_star
    # the four results in one allocation: the operating system backs a large fresh block with
    # huge pages where it can (one fault per 2 MiB instead of one per 4 KiB: four separate
    # arrays of 10^6 floats measured 2200 page faults and ~7 ms per call on a virtual machine,
    # one block ~130 and ~1.7 ms); a state keeps the block while it keeps any of the arrays
    block = np.empty((4, flat.size))
    a, d, F_out, resid = block
    if compiled == "numpy":
        if not _numpy_passes(flat, profile.R, n + 1.0, kap * c * n, kap * c, two_e, block):
            return None
    else:
        quotient, parab = kernels(bool(compiled))[:2]
        if quotient(flat, two_e, n + 1.0, kap * c * n, a):
            return None
        np.cbrt(a, out=a)
        if parab(a, flat, profile.R, kap * c, two_e, d, F_out, resid):
            return None
    shape = np.shape(F)
    return a.reshape(shape), d.reshape(shape), F_out.reshape(shape), resid.reshape(shape)


#: elements per chunk of the numpy passes: the dozen ufuncs run chunk by chunk, so that a
#: chunk's request and its four result rows (5 x 1 MiB) stay in the processor's cache between
#: the operations instead of streaming five arrays of the batch's size through memory a dozen
#: times (measured at 10^6 forces on the shared 2-core VM, interleaved best of 25: 5.13 ms
#: whole arrays, 4.75-4.82 ms in chunks of 2^17-2^18; 2^15 loses to the per-call cost)
CHUNK = 1 << 17


def _numpy_passes(F: np.ndarray, R: float, n1: float, den: float, k: float, two_e: float,
                  block: np.ndarray) -> bool:
    """The operations of the compiled passes (``quotient_pass``, numpy's ``cbrt``,
    ``paraboloid_pass``) as numpy ufuncs written into the rows ``a, d, F_out, resid`` of
    ``block``, chunk by chunk (:data:`CHUNK`: every element sees the same operations, so the
    bits do not depend on the chunking); False where those passes would decline (nothing is
    then to be read).

    The quotient ``((F/two_e)·n1)/den`` is a monotone function of ``F`` (each operation is a
    correctly rounded product or quotient by a positive constant), so its extremes over a chunk
    are those of the extremes of the chunk's forces, evaluated as floats in the same order: two
    reductions (of a chunk in cache) decide the range check. The request check (every force
    finite and within ``FORCE_SANITY`` of its request, the compiled pass's count) by the largest
    residual of each chunk against its smallest request (one more reduction; a NaN fails the
    comparison), element by element only where that fails."""
    if F.size == 0:
        return False
    fits = True
    for start in range(0, F.size, CHUNK):
        sl = slice(start, start + CHUNK)
        Fc = F[sl]
        lo, hi = float(Fc.min()), float(Fc.max())
        if not (lo > 0 and ((lo / two_e) * n1) / den >= Q_MIN
                and ((hi / two_e) * n1) / den <= Q_MAX):
            return False
        a, d, F_out, resid = block[0, sl], block[1, sl], block[2, sl], block[3, sl]
        np.divide(Fc, two_e, out=a)
        a *= n1
        a /= den
        np.cbrt(a, out=a)
        sq = np.multiply(a, a, out=resid)       # a·a: the depth's and ∫g's first product
        np.divide(sq, R, out=d)                 # d = (a·a)/R
        g_int = np.multiply(sq, a, out=resid)   # ∫g = (((a·a)·a)·k)/3
        g_int *= k
        g_int /= 3.0
        np.multiply(a, d, out=F_out)            # F_out = ((a·d) - ∫g)·two_e
        F_out -= g_int
        F_out *= two_e
        np.subtract(F_out, Fc, out=resid)       # resid = |F_out - F|
        np.abs(resid, out=resid)
        fits = fits and bool(resid.max() <= FORCE_SANITY * lo)
    if fits:
        return True
    # (requests over many decades: each residual against its own request; a NaN fails)
    return bool(np.all(block[3] <= FORCE_SANITY * F))
