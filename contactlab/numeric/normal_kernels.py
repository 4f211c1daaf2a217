"""Optional compiled kernels of the batched normal solves (extra ``fast``: numba).

The batched normal solves of :func:`contactlab.physics.normal.solve` perform a dozen or more
element-wise numpy operations per array around their one or two transcendental functions; each
operation is a pass over the arrays. The kernels here run that arithmetic in one compiled pass,
around numpy's own transcendental functions (``cbrt``, ``arctanh``), which their callers take on
whole arrays: a compiled ``cbrt`` or ``atanh`` is the C library's, which may differ by an ulp
from numpy's vectorised one. Every other operation is an IEEE multiplication, division, addition,
subtraction, comparison or absolute value in the order of the numpy route (numba without
``fastmath`` contracts nothing into fused multiply-adds), so the results are bit-identical to
the numpy route (tests run both, and the kernels uncompiled).

* :func:`quotient_pass` and :func:`paraboloid_pass`: the force-controlled solve of a paraboloid
  (:mod:`contactlab.physics.normal_fused`);
* :func:`sphere_force_newton`: the Newton iteration of the exact sphere's contact radius under
  force control (:meth:`contactlab.profiles.Sphere._radius_of_reduced_force`).

numba is used when it imports, for batches of at least :data:`FUSED_FROM` elements, unless
``CONTACTLAB_BACKEND=numpy`` is set or :func:`set_backend` forces numpy. The kernels compile on
their first call (machine code cached on disk: :func:`contactlab.numeric.jit.njit`).
"""
from __future__ import annotations

import os
import threading
from collections.abc import Callable

import numpy as np

from . import jit as _jit

__all__ = ["FUSED_FROM", "FORCE_SANITY", "Q_MIN", "Q_MAX", "backend", "set_backend", "kernels",
           "quotient_pass", "paraboloid_pass", "SPHERE_SERIES", "sphere_force_pass",
           "sphere_force_newton"]

#: smallest batch the compiled passes take (below it numpy's per-call cost is small, and a
#: process that never solves a large batch never loads numba)
FUSED_FROM = 1 << 14

_state: dict = {"backend": None, "kernels": None}
_lock = threading.Lock()


def backend() -> str:
    """``"numba"`` when numba imports and nothing forces numpy, else ``"numpy"``."""
    name = _state["backend"]
    if name is None:
        forced = os.environ.get("CONTACTLAB_BACKEND", "").strip().lower()
        name = "numpy" if forced == "numpy" or not _jit.available() else "numba"
        _state["backend"] = name
    return name


def set_backend(name: str | None) -> None:
    """Force ``"numpy"`` or ``"numba"`` (``None``: the automatic choice again)."""
    from ..errors import ParameterError
    allowed = ("numpy", "numba") if _jit.available() else ("numpy",)
    if name is not None and name not in allowed:
        raise ParameterError(f"backend={name!r} is invalid: available here: "
                             f"{', '.join(allowed)} (numba comes with the extra 'fast').")
    _state["backend"] = name


#: a batched force solve whose force is further than this (relative, element by element) from
#: the request is not a solution but a numerical breakdown (overflow); the driver
#: (:mod:`contactlab.effects.normal`) raises for it
FORCE_SANITY = 1e-6
#: the quotients ``F/K`` (``F = K a³``) the compiled passes take: within these bounds the
#: quotient and the cube of its cube root (``∫g``) are normal floats by a wide margin, as the
#: numpy route's fast paths require (outside them the numpy route runs, with its logarithms)
Q_MIN, Q_MAX = 1e-290, 1e290


def quotient_pass(F: np.ndarray, K: float, q: np.ndarray) -> int:
    """``q = F/K`` (a paraboloid's ``F = K a³`` before the root:
    :meth:`~contactlab.profiles.Paraboloid._hertz_force_constants`); returns how many quotients
    lie outside ``[Q_MIN, Q_MAX]`` (a force that is not positive or NaN among them).
    Branch-free: the loop vectorises."""
    bad = 0
    for i in range(F.size):
        x = F[i] / K
        q[i] = x
        bad += (not x >= Q_MIN) | (not x <= Q_MAX)
    return bad


def paraboloid_pass(a: np.ndarray, R: float, d: np.ndarray) -> int:
    """From radii ``a``: ``d = (a·a)/R`` (``Paraboloid._g_closed_form``); returns how many
    depths are not finite. Branch-free: the loop vectorises."""
    bad = 0
    for i in range(a.size):
        ai = a[i]
        di = ai * ai
        di = di / R
        d[i] = di
        bad += not di - di == 0.0
    return bad


#: series coefficients of the exact sphere's reduced force ``h(q)/(R² q³)`` in ``q²``,
#: ``2m/((2m-1)(2m+1))``, m = 1..9 (``q < 0.1``: the tenth term is below 1e-18 of the first;
#: :mod:`contactlab.profiles.sphere` evaluates them in the same order)
SPHERE_SERIES = tuple(2 * m / ((2 * m - 1) * (2 * m + 1)) for m in range(1, 10))
_S1, _S2, _S3, _S4, _S5, _S6, _S7, _S8, _S9 = SPHERE_SERIES


def sphere_force_pass(x: np.ndarray, at: np.ndarray, eta: np.ndarray, live: np.ndarray,
                      noise: float, rtol: float) -> int:
    """One Newton round of :meth:`contactlab.profiles.Sphere._radius_of_reduced_force` on the
    live elements of ``x`` (``at = artanh x``, from numpy): the operations of its ``step_of``
    and of :func:`contactlab.numeric.roots.convex_newton_fused`, element by element; an element
    that stops leaves ``live``. Returns how many are still live. Branch-free (both forms of
    the residual are evaluated and one is selected): the loop vectorises."""
    left = 0
    for i in range(x.size):
        lv = live[i]
        q = x[i]
        a_t = at[i]
        f = eta[i]
        p = q * q
        p = p + 1.0
        p = p * a_t                     # (q² + 1) artanh q
        h = p - q
        h = h * 0.5
        # the series of _series_of_small (Horner in q²), taken below q = 0.1
        xx = q * q
        acc = _S9 * xx
        acc = acc + _S8
        acc = acc * xx
        acc = acc + _S7
        acc = acc * xx
        acc = acc + _S6
        acc = acc * xx
        acc = acc + _S5
        acc = acc * xx
        acc = acc + _S4
        acc = acc * xx
        acc = acc + _S3
        acc = acc * xx
        acc = acc + _S2
        acc = acc * xx
        acc = acc + _S1
        acc = acc * (xx * q)
        small = q < 0.1
        h = acc if small else h
        h = h - f                       # the residual
        w = p + q
        w = w * 0.5
        w = f if small else w
        w = w * noise
        quiet = abs(h) <= w
        w = 1.0 - q
        s = 1.0 + q
        w = w * s
        w = q / w
        w = w + a_t
        w = w * q
        s = h / w                       # the Newton step
        new = q - s
        new = q if quiet else new
        x[i] = new if lv else q
        go = lv and not (abs(s) <= abs(new) * rtol or quiet)
        live[i] = go
        left += go
    return left


def sphere_force_newton(x: np.ndarray, eta: np.ndarray, noise: float, rtol: float,
                        maxiter: int, compiled: bool = True,
                        work: np.ndarray | None = None) -> float | None:
    """Newton rounds of :func:`sphere_force_pass` on the flat float array ``x`` in place, each
    after numpy's ``arctanh`` of ``x`` (every element, as the numpy route's ``step_of``): None
    once every element has stopped; after ``maxiter`` rounds the first element still iterating
    (the caller raises, as :func:`~contactlab.numeric.roots.convex_newton_fused` does).
    ``work``: a float array of ``x``'s size the caller no longer needs, to hold ``artanh x``."""
    step = kernels(compiled)[2]
    at = np.empty_like(x) if work is None else work
    live = np.ones(x.shape, dtype=bool)
    for _ in range(maxiter):
        with np.errstate(divide="ignore", invalid="ignore"):
            np.arctanh(x, out=at)
        if step(x, at, eta, live, noise, rtol) == 0:
            return None
    return float(x[np.argmax(live)])


def kernels(compiled: bool = True) -> tuple[Callable, ...]:
    """``(quotient_pass, paraboloid_pass, sphere_force_pass)``: compiled by numba (built once
    per process), or the plain Python functions (``compiled=False``: the kernels' logic
    without numba, for tests)."""
    if not compiled:
        return quotient_pass, paraboloid_pass, sphere_force_pass
    with _lock:
        if _state["kernels"] is None:
            _state["kernels"] = tuple(_jit.njit(f, nogil=True, error_model="numpy")
                                      for f in (quotient_pass, paraboloid_pass,
                                                sphere_force_pass))
    return _state["kernels"]
