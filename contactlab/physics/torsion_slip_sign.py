"""Whether a punch-density step's slip points the way of its traction, from the density alone.

A single-slip-annulus step (:mod:`contactlab.physics.torsion_annulus`) changes the punch density
by ``Δw`` above its stick radius ``c`` and may turn the contact as a whole by ``g`` (gross
sliding); the slip increment at ``r > c`` is

    Δs(r) = ∫_c^r Δw(t) K(r, t) dt + g r,   K(r, t) = (2/π)[r arccos(t/r) + t sqrt(1 − t²/r²)],

and the step is the exact one when ``s Δs >= 0`` on the annulus (``s = ±1`` the sense of its
traction). The kernel is non-negative and falls with ``t`` on ``[0, r]``:
``∂K/∂t = −(4/π) u²/sqrt(1 − u²)`` with ``u = t/r``, and ``K(r, r) = 0``. Writing
``D(x) = ∫_c^x s Δw dt`` (the turn the change of density gives the stick zone's side of ``x``,
counted from ``c``), integration by parts gives

    s ∫_c^r Δw K dt = D(r) K(r, r) − ∫_c^r D(t) ∂K/∂t dt = ∫_c^r D(t) |∂K/∂t| dt,

so ``D >= 0`` on ``[c, r]`` is enough for ``s Δs(r) >= s g r``: the slip points the way of the
traction at every radius when the running integral of ``s Δw`` from ``c`` outwards never falls
below zero and ``s g >= 0`` (the second mean value theorem, Abel's form). The plain test
``s Δw >= 0`` everywhere is the special case of a running integral that only grows. Where the
full-sliding density ends inside a ring (a contact radius off a ring node) it has a band near the
edge where its collocated form dips and was cut
(:func:`~contactlab.physics.torsion_annulus.nonnegative_psi`), and ``s Δw`` changes sign there
while its running integral stays positive: this test settles those steps without the slip
integrals at the points (a product of the points by the ring ends per step).

Pure functions: arrays in, a verdict out. With numba (extra ``fast``) the compiled route of
the annulus step takes the same test as one compiled pass (:func:`running_turn_ok_compiled`:
the same sums in the same order, so the same verdicts).
"""
from __future__ import annotations

import threading

import numpy as np

from ..numeric import jit as _jit

__all__ = ["running_turn_ok", "running_turn_ok_compiled", "MARGIN"]

#: the running integral must stay above this share of the running sum of the pieces' absolute
#: integrals (the rounding of the sums it is made of, many times over): a step near the line
#: goes to the slip integrals at the points, the test that decides it there
MARGIN = 1e-12


def running_turn_ok(lo: np.ndarray, hi: np.ndarray, wl: np.ndarray, wr: np.ndarray,
                    s: float, gross: float) -> bool:
    """Whether the change of density ``Δw`` (pieces ``[lo_k, hi_k]``, linear from ``wl_k`` to
    ``wr_k``, ascending, from the stick radius outwards) and the whole-contact turn ``gross``
    (rad) make the slip point the way of ``s`` at every radius (module docstring): ``s gross
    >= 0`` and the running integral of ``s Δw`` at every piece end and at every zero inside a
    piece where ``s Δw`` turns from negative to positive (its minima) at least :data:`MARGIN`
    times the running sum of the pieces' absolute integrals. ``False`` for a nan.

    Parameters
    ----------
    lo, hi : ndarray
        Piece ends, m (pieces in ascending order, not overlapping).
    wl, wr : ndarray
        ``Δw`` at the pieces' ends, rad/m.
    s : float
        Sense of the traction on the slip annulus, ``±1``.
    gross : float
        Turn of the contact as a whole, rad.

    Returns
    -------
    bool

    Examples
    --------
    A density change that is negative just above ``c`` but whose running integral stays
    positive passes, the plain sign test would not:

    >>> import numpy as np
    >>> running_turn_ok(np.array([0.0, 1.0]), np.array([1.0, 2.0]), np.array([2.0, -0.5]),
    ...                 np.array([2.0, -0.5]), 1.0, 0.0)
    True
    >>> running_turn_ok(np.array([0.0, 1.0]), np.array([1.0, 2.0]), np.array([-0.5, 2.0]),
    ...                 np.array([-0.5, 2.0]), 1.0, 0.0)
    False
    """
    if not s * gross >= 0:
        return False
    if lo.size == 0:
        return True
    a, b = s * wl, s * wr
    h = hi - lo
    seg = 0.5 * h * (a + b)
    end = np.cumsum(seg)                    # (sums one after the other)
    tot = np.cumsum(np.abs(seg))
    if not bool(np.all(end >= MARGIN * tot)):      # (False for a nan)
        return False
    # a piece whose s Δw rises through zero has the running integral's minimum at that zero:
    # D(start) + ½ a x at x = −a h / (b − a) inside it
    turn = (a < 0) & (b > 0)
    if not turn.any():
        return True
    start = np.concatenate([[0.0], end[:-1]])[turn]
    below = np.concatenate([[0.0], tot[:-1]])[turn]
    at = start + 0.5 * a[turn] * (-a[turn] * h[turn] / (b[turn] - a[turn]))
    return bool(np.all(at >= MARGIN * below))


def _running_turn_pass(lo, hi, wl, wr, s, gross, margin):
    """:func:`running_turn_ok` written out as one loop (numba): the running sums in the order of
    ``np.cumsum`` (one after the other), the same arithmetic per piece."""
    if not s * gross >= 0:
        return False
    end = 0.0
    tot = 0.0
    for j in range(lo.size):
        a = s * wl[j]
        b = s * wr[j]
        h = hi[j] - lo[j]
        seg = 0.5 * h * (a + b)
        start, below = end, tot
        end += seg
        tot += abs(seg)
        if not end >= margin * tot:
            return False
        if a < 0 and b > 0 and not start + 0.5 * a * (-a * h / (b - a)) >= margin * below:
            return False
    return True


_STATE: dict = {"pass": None}
_LOCK = threading.Lock()


def running_turn_ok_compiled(lo: np.ndarray, hi: np.ndarray, wl: np.ndarray, wr: np.ndarray,
                             s: float, gross: float) -> bool:
    """:func:`running_turn_ok` by a compiled pass (numba, built once per process; the plain loop
    without numba): the same verdict (tested on random densities)."""
    fn = _STATE["pass"]
    if fn is None:
        with _LOCK:
            if _STATE["pass"] is None:
                _STATE["pass"] = (_jit.njit(_running_turn_pass, nogil=True, error_model="numpy")
                                  if _jit.available() else _running_turn_pass)
            fn = _STATE["pass"]
    return bool(fn(lo, hi, wl, wr, float(s), float(gross), MARGIN))
