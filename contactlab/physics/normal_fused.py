"""The batched force-controlled normal solve of a paraboloid in few passes (numba or numpy).

A paraboloid under force control is solved in closed form on every route with one constant
per contact (:meth:`~contactlab.profiles.Paraboloid._hertz_force_constants`): ``a = cbrt(F/K)``,
``d = (a·a)/R``, and the state's force is the request itself; the estimate of its error carries
the residual ``|F(a, d) - F|``, ``F(a, d) = (a·d)·c``, computed when it is read.
:func:`contactlab.physics.normal.solve` does it with the masks and reductions of its general
route; :func:`paraboloid_force` performs the same operations, so the results are bit-identical
to that route and to the scalar route (tests), the three results in one block:

* the range and request checks are proved from the extremes of the requests
  (:func:`_in_range`: every operation is monotone in the request), which the driver's
  finiteness check has already reduced;
* compiled (extra ``fast``: numba): two passes (:mod:`contactlab.numeric.normal_kernels`)
  around numpy's own ``cbrt``, taken in place on the whole array, counting the values that
  leave the range (belt and braces);
* numpy: the four operations as ufuncs written into the block (no temporaries).

Where a value leaves the range the general route treats with its careful branches (a quotient
or a depth outside the normal floats, a force that is not positive), :func:`paraboloid_force`
declines and the general route runs.
"""
from __future__ import annotations

import math

import numpy as np

from ..numeric.normal_kernels import FORCE_SANITY, FUSED_FROM, backend, kernels, set_backend

__all__ = ["FUSED_FROM", "FORCE_SANITY", "backend", "set_backend", "paraboloid_force"]


def paraboloid_force(profile, E_star: float, F: np.ndarray, compiled: bool | str = True,
                     extremes: tuple[float, float] | None = None
                     ) -> tuple[np.ndarray, np.ndarray, np.ndarray] | None:
    """Radius, depth and force (a copy of the request: the state's force) of requested forces
    ``F`` on a :class:`~contactlab.profiles.Paraboloid` (the caller checks the type),
    bit-identical to the general route of :func:`contactlab.physics.normal.solve`.

    ``compiled``: True the numba pass, ``"numpy"`` the numpy passes, False the numba pass's
    logic as plain Python (tests). ``extremes``: ``(min(F), max(F))`` where the caller has
    them (the driver's check that every force is finite takes them): the range check then
    reduces nothing.

    Returns ``(a, d, F_out)`` (arrays of ``F``'s shape) with every radius and depth a finite
    float whose force ``(a·d)·c`` meets the request to :data:`FORCE_SANITY` (the driver's
    checks, proved from the extremes: :func:`_in_range`), or None where some force is not
    positive or an intermediate value leaves the range of that proof (the compiled passes also
    count quotients outside ``[Q_MIN, Q_MAX]`` and depths that are not finite): the general
    route then handles (and reports) them.
    """
    flat = np.ascontiguousarray(F, dtype=float).reshape(-1)
    K = profile._hertz_force_constants(E_star)[0]
    if flat.size == 0:
        return None
    lo, hi = extremes if extremes is not None else (float(flat.min()), float(flat.max()))
    if not _in_range(lo, hi, profile.R, K):
        return None
    # the three results in one allocation (a state keeps the block while it keeps any of them)
    block = np.empty((3, flat.size))
    a, d, F_out = block
    if compiled == "numpy":
        _numpy_passes(flat, profile.R, K, block)
    else:
        quotient, parab = kernels(bool(compiled))[:2]
        if quotient(flat, K, a):
            return None
        np.cbrt(a, out=a)
        if parab(a, profile.R, d):
            return None
        F_out[...] = flat
    shape = np.shape(F)
    return a.reshape(shape), d.reshape(shape), F_out.reshape(shape)


#: the bounds every intermediate value of the numpy passes keeps at the extremes of the
#: requests (a factor 1e18 inside the normal floats): then, the operations being monotone, it
#: keeps them for every request (see :func:`_in_range`)
_LOW, _HIGH = 1e-290, 1e290


def _in_range(lo: float, hi: float, R: float, K: float) -> bool:
    """Whether the numpy passes' values for requests in ``[lo, hi]`` are normal floats that
    meet the driver's checks (radius and depth finite, ``F(a, d)`` within
    :data:`FORCE_SANITY` of the request), decided from the extremes alone.

    Every operation of the passes is a correctly rounded quotient or product of positive
    operands, each non-decreasing in the request (``F/K``, ``a·a``, ``(a·a)/R``), and numpy's
    ``cbrt`` is within an ulp of the monotone cube root: so every intermediate value of a
    request in ``[lo, hi]`` lies between those of ``lo`` and ``hi`` (to an ulp; the bounds
    :data:`_LOW`, :data:`_HIGH` leave a factor 1e18). With all of them normal,
    ``F(a, d) = (a·d)·c = F·(1 + δ)``, ``δ`` the sum of the roundings (``K``'s two, the
    quotient, the root's 0.53 ulp tripled by the cube, ``a·a``, ``/R``, ``a·d``, ``·c`` and
    ``c``'s own): ``|δ| < 12 ulp``, far within :data:`FORCE_SANITY` (1e-6)."""
    if not (lo > 0 and math.isfinite(hi)):
        return False
    for x, ok in ((lo, lambda v: v >= _LOW), (hi, lambda v: v <= _HIGH)):
        q = x / K
        a = float(np.cbrt(q))
        sq = a * a
        if not all(ok(v) for v in (q, a, sq, sq / R)):
            return False
    return True


def _numpy_passes(F: np.ndarray, R: float, K: float, block: np.ndarray) -> None:
    """The operations of the compiled pass (``quotient_pass``, numpy's ``cbrt``,
    ``paraboloid_pass``) as numpy ufuncs written into the rows ``a, d, F_out`` of ``block``
    (``F_out`` a copy of the request), for requests :func:`_in_range` accepted."""
    a, d, F_out = block
    np.divide(F, K, out=a)                      # a = cbrt(F/K)
    np.cbrt(a, out=a)
    np.multiply(a, a, out=d)                    # d = (a·a)/R
    d /= R
    F_out[...] = F
