"""Powers of float arrays by the cheapest accurate route (vectorised, deterministic).

numpy's ``x ** p`` for a general exponent calls a vector ``pow`` (~2.7 ns per element on a
2-core AMD EPYC VM against ~0.25 ns for a multiplication); the power-law closed forms of
contactlab raise contact radii to ``n + 1`` and ``n + 2`` at every step of a load path, and for
the common profiles (paraboloid ``n = 2``, cone ``n = 1``) those are small whole numbers.
:func:`power` then multiplies (``x·x·x`` within 2 ulp, ``(x·x)²`` within 3, against ~1 ulp of
``pow``), and :func:`root` takes the cube root by ``cbrt`` (numpy's: within 0.53 ulp measured on
an AVX-512 CPU, the C library's elsewhere within ~3 ulp), where ``x ** (1/3)`` raises to the
double nearest 1/3 and errs by up to ~12 ulp. Every closed form of a power term goes through
these, so routes that must agree bit for bit (a step's force and its edge-cell integrals, the
numpy and the compiled foundation, a scalar ``normal()`` call and a batch for ``n`` = 1, 2) do.
"""
from __future__ import annotations

import math

import numpy as np

__all__ = ["power", "root", "power_integral", "power_float", "root_float", "WHOLE_POWERS",
           "times_power", "times_power_float", "root_of_ratio", "root_of_ratio_float"]

#: exponents raised by multiplication (larger ones by ``pow``: chains would add roundings)
WHOLE_POWERS = (1.0, 2.0, 3.0, 4.0)


def power(x: np.ndarray, p: float) -> np.ndarray:
    """``x ** p`` as a new float array: whole ``p`` in :data:`WHOLE_POWERS` by multiplication
    (``x·x·x``, ``(x·x)·(x·x)``), else numpy's power."""
    p = float(p)
    if p == 3.0:
        out = np.multiply(x, x)
        out *= x
        return out
    if p == 4.0:
        out = np.multiply(x, x)
        out *= out
        return out
    if p == 2.0:
        return np.multiply(x, x)
    if p == 1.0:
        return np.array(x, dtype=float, copy=True)
    return np.power(x, p)


def root(x: np.ndarray, q: float) -> np.ndarray:
    """``x ** (1/q)`` for ``x >= 0``: ``q = 2`` by ``sqrt``, ``q = 3`` by ``cbrt``, ``q = 1`` a
    copy, else numpy's power of ``1/q``."""
    q = float(q)
    if q == 3.0:
        return np.cbrt(x)
    if q == 2.0:
        return np.sqrt(x)
    if q == 1.0:
        return np.array(x, dtype=float, copy=True)
    return np.power(x, 1.0 / q)


_TINY = float(np.finfo(float).tiny)


def _all_normal(v: np.ndarray) -> bool:
    """Whether every element of ``v`` is a normal float in ``[tiny, inf)``: two reductions (a
    NaN fails both), instead of the boolean masks of the careful branch that follows where this
    says no. Callers take their result unchanged when it says yes (the same values)."""
    if v.size == 0:
        return True
    lo = v.min()
    return bool(lo >= _TINY) and bool(v.max() < np.inf)


def _root_in_place(x: np.ndarray, q: float) -> np.ndarray:
    """:func:`root` of ``x`` written into ``x`` (the same values; no new array)."""
    q = float(q)
    if q == 3.0:
        return np.cbrt(x, out=x)
    if q == 2.0:
        return np.sqrt(x, out=x)
    if q == 1.0:
        return x
    return np.power(x, 1.0 / q, out=x)


def times_power(k: float, x: np.ndarray, p: float, whole: bool = False) -> np.ndarray:
    """``k * x**p`` (a new float array) also where ``x**p`` alone leaves the float range.

    ``x**p`` by the ``**`` operator (``whole``: by :func:`power`), times ``k``: bit-identical to
    that expression wherever the power is a normal float. Where it underflows (below the
    smallest normal float: zero or subnormal) or overflows while ``k x**p`` need not
    (``PowerLaw(c=1e294, n=100)`` at ``x = 5e-4``: ``x**100 = 8e-331``, ``k x**100 = 7e-37``),
    the product is taken in logarithms, ``exp(log k + p log x)`` (relative error ~``ε |log|``
    of the result, <= 2e-13).
    """
    x = np.asarray(x, dtype=float)
    with np.errstate(over="ignore", under="ignore"):
        pw = power(x, p) if whole else x ** p
        out = np.asarray(k * pw, dtype=float)
        if _all_normal(pw):
            return out
        bad = ((pw < _TINY) | ~np.isfinite(pw)) & (x > 0) & np.isfinite(x)
        if np.any(bad) and k > 0:
            out = np.array(out, dtype=float, ndmin=1).reshape(x.shape) if out.ndim == 0 else out
            xb = x[bad] if x.ndim else x
            out[bad] = np.exp(math.log(k) + p * np.log(xb))
    return out


def times_power_float(k: float, x: float, p: float, whole: bool = False) -> float:
    """:func:`times_power` of one float (``x**p`` by :func:`power_float` when ``whole``)."""
    try:
        pw = power_float(x, p) if whole else x ** p
    except OverflowError:
        pw = math.inf
    if (pw < _TINY or pw == math.inf) and 0.0 < x < math.inf and k > 0:
        return math.exp(math.log(k) + p * math.log(x))
    return k * pw


def root_of_ratio(num: np.ndarray, den: float, q: float, *, overwrite: bool = False
                  ) -> np.ndarray:
    """``(num/den)**(1/q)`` by :func:`root` (bit-identical to it where the quotient is a normal
    float), in logarithms where the quotient alone underflows or overflows but its root need
    not (``PowerLaw(c=1e294, n=100)`` at a depth of 1e-35 m: ``d/(κc) = 8e-331``, its 100th
    root 5e-4). ``num >= 0`` (a new float array; with ``overwrite``, a float64 ``num`` of the
    caller's own may be returned holding the result, the same values)."""
    num = np.asarray(num, dtype=float)
    if (overwrite and num.ndim and num.size and den > 0 and num.dtype == np.float64
            and num.flags.writeable):
        # the quotient's extremes are those of num divided (division by a positive constant is
        # monotone, rounding included): when they are normal floats, so is every quotient
        lo, hi = float(num.min()) / den, float(num.max()) / den
        if lo >= _TINY and hi < math.inf:
            np.divide(num, den, out=num)
            return _root_in_place(num, q)
    with np.errstate(over="ignore", under="ignore"):
        x = num / den
        if _all_normal(x):
            # the common case, in place: the quotient's own buffer takes its root
            return _root_in_place(x, q) if x.ndim else np.asarray(root(x, q), dtype=float)
        out = np.asarray(root(x, q), dtype=float)
        bad = ((x < _TINY) | ~np.isfinite(x)) & (num > 0) & np.isfinite(num)
        if np.any(bad) and den > 0:
            out = np.array(out, dtype=float, ndmin=1).reshape(num.shape) if out.ndim == 0 else out
            nb = num[bad] if num.ndim else num
            out[bad] = np.exp((np.log(nb) - math.log(den)) / q)
    return out


def root_of_ratio_float(num: float, den: float, q: float) -> float:
    """:func:`root_of_ratio` of one float (the quotient's root by :func:`root_float`)."""
    try:
        x = num / den
    except OverflowError:       # pragma: no cover - float division gives inf, not an error
        x = math.inf
    if (x < _TINY or x == math.inf) and 0.0 < num < math.inf and den > 0:
        return math.exp((math.log(num) - math.log(den)) / q)
    return root_float(x, q)


def power_integral(a: np.ndarray, terms, shift: float) -> np.ndarray:
    """``Σ k a**(n + shift) / (n + shift)`` over ``terms = [(k, n), ...]`` (a new float array of
    ``a``'s shape): the closed-form integrals of power terms (``k = κ_n c``; ``shift = 1``:
    ``∫_0^a g``, ``shift = 2``: ``∫_0^a x g``), each term as ``(power(a, p) · k) / p``."""
    a = np.asarray(a, dtype=float)
    total = None
    for k, n in terms:
        p = n + shift
        with np.errstate(over="ignore", under="ignore"):
            v = np.asarray(power(a, p), dtype=float)
        if not _all_normal(v) and (np.any((v < _TINY) & (a > 0)) or not np.all(np.isfinite(v))):
            v = times_power(k, a, p, whole=True)    # the power alone left the float range
        else:
            v *= k
        v /= p
        total = v if total is None else total + v
    return np.zeros(a.shape) if total is None else total


def power_float(x: float, p: float) -> float:
    """:func:`power` of one float: bit-identical to its array elements for the whole ``p`` of
    :data:`WHOLE_POWERS`; other ``p`` by the C library's ``pow`` (a numpy call would cost ~0.5 µs
    per scalar; the two ``pow`` agree to about an ulp)."""
    if p == 3.0:
        return x * x * x
    if p == 4.0:
        y = x * x
        return y * y
    if p == 2.0:
        return x * x
    if p == 1.0:
        return x
    return x ** p


def root_float(x: float, q: float) -> float:
    """:func:`root` of one float ``x >= 0``: bit-identical to its array elements for ``q`` = 1,
    2, 3 (numpy's ``cbrt`` for 3: within 0.53 ulp on AVX-512 CPUs, where ``math.cbrt`` errs by
    up to ~3 ulp), other ``q`` by the C library's ``pow`` as :func:`power_float`."""
    if q == 3.0:
        return float(np.cbrt(x))
    if q == 2.0:
        return math.sqrt(x)
    if q == 1.0:
        return x
    return x ** (1.0 / q)
