"""Optional compiled force-controlled normal solve of a paraboloid (extra ``fast``: numba).

:func:`contactlab.physics.normal.solve` under force control on a paraboloid performs ~15
element-wise numpy operations and ~10 reductions around the one cube root (radius, depth, ``∫g``,
force, the residual against the request and the extremes the caller checks): at 10^6 forces
three times the closed form ``a = cbrt(3RF/(4E*))``, ``d = a²/R`` alone. Here the arithmetic runs
in two compiled passes around numpy's own ``cbrt`` (taken in place on the whole array, so the
root is numpy's, bit for bit: a compiled ``cbrt`` is the C library's, which may differ by an ulp
from numpy's vectorised one). Every other operation is an IEEE multiplication, division,
subtraction or absolute value in the order of the numpy route (numba without ``fastmath``
contracts nothing into fused multiply-adds), so the results are bit-identical to the numpy
route and to the scalar route (tests). Where a value leaves the range the numpy route treats
with its careful branches (a quotient or a cube outside the normal floats, a force that is not
positive), :func:`paraboloid_force` declines and the numpy route runs.

numba is used when it imports, for batches of at least :data:`FUSED_FROM` forces, unless
``CONTACTLAB_BACKEND=numpy`` is set or :func:`set_backend` forces numpy. The kernels compile on
their first call (machine code cached on disk: :func:`contactlab.numeric.jit.njit`).
"""
from __future__ import annotations

import os
import threading

import numpy as np

from ..numeric import jit as _jit

__all__ = ["FUSED_FROM", "FORCE_SANITY", "backend", "set_backend", "paraboloid_force"]

#: smallest batch the compiled passes take (below it numpy's per-call cost is small, and a
#: process that never solves a large batch never loads numba)
FUSED_FROM = 1 << 14

_TINY = float(np.finfo(float).tiny)
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
#: the quotients ``F/(2E*)·(n+1)/(κcn)`` the compiled passes take: within these bounds the
#: quotient and the cube of its cube root (``∫g``) are normal floats by a wide margin, as the
#: numpy route's fast paths require (outside them the numpy route runs, with its logarithms)
Q_MIN, Q_MAX = 1e-290, 1e290


def _quotient_pass(F: np.ndarray, two_e: float, n1: float, den: float, q: np.ndarray) -> int:
    """``q = ((F/two_e)·n1)/den`` (the operations of ``_power_radius`` and ``root_of_ratio``
    before the root); returns how many quotients lie outside ``[Q_MIN, Q_MAX]`` (a force that
    is not positive or NaN among them). Branch-free: the loop vectorises."""
    bad = 0
    for i in range(F.size):
        x = F[i] / two_e
        x = x * n1
        x = x / den
        q[i] = x
        bad += (not x >= Q_MIN) | (not x <= Q_MAX)
    return bad


def _paraboloid_pass(a: np.ndarray, F: np.ndarray, R: float, k: float, two_e: float,
                     d: np.ndarray, F_out: np.ndarray, resid: np.ndarray) -> int:
    """From radii ``a``: ``d = (a·a)/R`` (``Paraboloid._g_closed_form``), ``∫g = ((a·a)·a·k)/3``
    (``power_integral``), ``F_out = ((a·d) - ∫g)·two_e`` and ``resid = |F_out - F|`` (``solve``);
    returns how many forces are not finite or miss their request by more than
    :data:`FORCE_SANITY` (relative; NaNs count). Branch-free: the loop vectorises."""
    bad = 0
    for i in range(a.size):
        ai = a[i]
        sq = ai * ai
        di = sq / R
        g_int = sq * ai
        g_int = g_int * k
        g_int = g_int / 3.0
        fo = ai * di
        fo = fo - g_int
        fo = fo * two_e
        fi = F[i]
        r = abs(fo - fi)
        d[i] = di
        F_out[i] = fo
        resid[i] = r
        bad += (not fo - fo == 0.0) | (not r <= FORCE_SANITY * fi)
    return bad


def _kernels(compiled: bool) -> tuple:
    """``(quotient pass, paraboloid pass)``: compiled by numba (built once per process), or
    the plain Python functions (tests of the kernels' logic without numba)."""
    if not compiled:
        return _quotient_pass, _paraboloid_pass
    with _lock:
        if _state["kernels"] is None:
            _state["kernels"] = tuple(_jit.njit(f, nogil=True, error_model="numpy")
                                      for f in (_quotient_pass, _paraboloid_pass))
    return _state["kernels"]


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
    quotient, parab = _kernels(compiled)
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
