"""Optional compiled force-controlled normal solve of a paraboloid (extra ``fast``: numba).

:func:`contactlab.physics.normal.solve` under force control on a paraboloid performs ~15
element-wise numpy operations and ~10 reductions around the one cube root (radius, depth, ``∫g``,
force, the residual against the request and the extremes the caller checks): at 10^6 forces
three times the closed form ``a = cbrt(3RF/(4E*))``, ``d = a²/R`` alone. Here the arithmetic runs
in two compiled passes (:mod:`contactlab.numeric.normal_kernels`) around numpy's own ``cbrt``,
taken in place on the whole array, so the results are bit-identical to the numpy route and to
the scalar route (tests). Where a value leaves the range the numpy route treats with its careful
branches (a quotient or a cube outside the normal floats, a force that is not positive),
:func:`paraboloid_force` declines and the numpy route runs.
"""
from __future__ import annotations

import numpy as np

from ..numeric.normal_kernels import (FORCE_SANITY, FUSED_FROM, backend, kernels,
                                      set_backend)

__all__ = ["FUSED_FROM", "FORCE_SANITY", "backend", "set_backend", "paraboloid_force"]


def paraboloid_force(profile, E_star: float, F: np.ndarray, compiled: bool = True
                     ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray] | None:
    """Radius, depth, force and residual ``|F_out - F|`` of requested forces ``F`` on a
    :class:`~contactlab.profiles.Paraboloid` (the caller checks the type), bit-identical to the
    numpy route of :func:`contactlab.physics.normal.solve`.

    Returns ``(a, d, F_out, residual)`` (arrays of ``F``'s shape) with every force finite and
    within :data:`FORCE_SANITY` of its request (the driver's checks, made on the way), or None
    where some force is not positive, a quotient lies outside ``[Q_MIN, Q_MAX]`` or a force
    fails those checks: the numpy route then handles (and reports) them.
    """
    quotient, parab = kernels(compiled)[:2]
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
    if quotient(flat, two_e, n + 1.0, kap * c * n, a):
        return None
    np.cbrt(a, out=a)
    if parab(a, flat, profile.R, kap * c, two_e, d, F_out, resid):
        return None
    shape = np.shape(F)
    return a.reshape(shape), d.reshape(shape), F_out.reshape(shape), resid.reshape(shape)
