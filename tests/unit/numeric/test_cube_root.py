"""numeric.cube_root: glibc's double ``cbrt`` in arithmetic and bit operations, compiled and numpy.

The compiled scalar (:func:`cbrt_one` in a numba loop), the plain Python scalar and the numpy
twin (:func:`cbrt`) give the same bits everywhere (by construction: the same operations); on a
host whose numpy ``cbrt`` is glibc's (probed: the C library is glibc and numpy agrees with its
``cbrt`` called through ctypes) they equal numpy's ``cbrt`` bit for bit; and they are within
3 ulp of the 40-digit cube root (mpmath; glibc's algorithm, not correctly rounded).
"""
from __future__ import annotations

import ctypes
import ctypes.util

import numpy as np
import pytest

from contactlab.numeric import jit
from contactlab.numeric.cube_root import cbrt, cbrt_one

needs_numba = pytest.mark.skipif(not jit.available(), reason="numba (extra 'fast') not installed")

TINY = 2.2250738585072014e-308
SPECIAL = np.array([0.0, -0.0, np.inf, -np.inf, np.nan, 5e-324, -5e-324, TINY, -TINY,
                    np.nextafter(TINY, 0.0), 1.7976931348623157e308, -1.7976931348623157e308,
                    1.0, -1.0, 8.0, 27.0, -27.0, 0.5, 2.0, 4.0, 1e-300, 1e300])


def sample(m: int, seed: int = 29) -> np.ndarray:
    """``m`` float64 over the whole range, both signs: exp(uniform(-700, 700)), 10^(±300) in
    decades, subnormals (mantissa bits and exponents at random), the specials."""
    rng = np.random.default_rng(seed)
    k = m // 4
    parts = [np.exp(rng.uniform(-700.0, 700.0, k)),
             rng.uniform(0.5, 1.0, k) * 10.0 ** rng.integers(-307, 308, k),
             rng.integers(1, 1 << 52, k, dtype=np.int64).view(np.float64),     # subnormals
             rng.integers(0, 0x7FF0_0000_0000_0000, m - 3 * k, dtype=np.int64).view(np.float64)]
    x = np.concatenate(parts)
    x *= rng.choice([-1.0, 1.0], x.size)
    return np.concatenate([SPECIAL, x])


def bits(a: np.ndarray) -> np.ndarray:
    """The bits of float64 values, every NaN as one pattern (NaN payloads are not compared)."""
    a = np.where(np.isnan(a), np.nan, a)
    return a.view(np.int64)


def _glibc_cbrt():
    """The C library's ``cbrt`` through ctypes when the C library is glibc, else None."""
    try:
        libc = ctypes.CDLL(ctypes.util.find_library("c"))
        libc.gnu_get_libc_version.restype = ctypes.c_char_p
        libc.gnu_get_libc_version()
        libm = ctypes.CDLL(ctypes.util.find_library("m"))
    except (OSError, AttributeError, TypeError):
        return None
    f = libm.cbrt
    f.restype, f.argtypes = ctypes.c_double, [ctypes.c_double]
    return f


def _numpy_is_glibc() -> str | None:
    """None when numpy's ``cbrt`` is glibc's (probed on 4000 values against the C library's
    ``cbrt`` called through ctypes), else the reason it is not."""
    f = _glibc_cbrt()
    if f is None:
        return "the C library is not glibc (no gnu_get_libc_version)"
    x = sample(4000, seed=7)
    ref = np.array([f(float(v)) for v in x])
    if not np.array_equal(bits(np.cbrt(x)), bits(ref)):
        return "numpy's cbrt is not the C library's here (a SIMD cbrt, e.g. numpy's AVX-512 build)"
    return None


def test_numpy_twin_equals_numpy_cbrt_on_glibc():
    """On a glibc host whose numpy calls glibc's cbrt: the same bits on 10^6 values over the
    whole range, subnormals, zeros, infinities (NaN: NaN), and glibc's cbrt called directly."""
    why = _numpy_is_glibc()
    if why is not None:
        pytest.skip(why)
    x = sample(10**6)
    assert np.array_equal(bits(cbrt(x)), bits(np.cbrt(x)))
    f = _glibc_cbrt()
    assert np.array_equal(bits(cbrt(SPECIAL)), bits(np.array([f(float(v)) for v in SPECIAL])))


def test_specials():
    """Zeros keep their sign, infinities stay, NaN gives NaN; exact cubes of small whole numbers
    are exact where glibc's are (cbrt(0.125) is one ulp below 0.5, as glibc's)."""
    y = cbrt(np.array([0.0, -0.0, np.inf, -np.inf, np.nan, 8.0, -8.0, 1.0, 0.125]))
    assert y[8] == np.nextafter(0.5, 0.0)       # glibc's too: within its 1 ulp
    assert y[:4].tolist() == [0.0, 0.0, np.inf, -np.inf]
    assert np.signbit(y[:4]).tolist() == [False, True, False, True]
    assert np.isnan(y[4])
    assert y[5:8].tolist() == [2.0, -2.0, 1.0]
    assert cbrt_one(-0.0) == 0.0 and np.signbit(cbrt_one(-0.0))
    assert np.isnan(cbrt_one(float("nan"))) and cbrt_one(float("-inf")) == float("-inf")


def test_plain_scalar_equals_numpy_twin():
    """The plain Python scalar (what the uncompiled kernels run) and the numpy twin: the same bits."""
    x = sample(4000, seed=3)
    y = np.array([cbrt_one(float(v)) for v in x])
    assert np.array_equal(bits(y), bits(cbrt(x)))


@needs_numba
def test_compiled_scalar_equals_numpy_twin():
    """The scalar compiled as the law's normal pass compiles it (inlined into a numba loop with
    numpy's error model, vectorised) and the numpy twin: the same bits on 10^6 values."""
    import numba
    one = numba.njit(cbrt_one, inline="always")

    @numba.njit(error_model="numpy")
    def compiled(x, out):
        for i in range(x.size):
            out[i] = one(x[i])

    x = sample(10**6, seed=11)
    y = np.empty_like(x)
    compiled(x, y)
    assert np.array_equal(bits(y), bits(cbrt(x)))


def test_within_three_ulp_of_the_cube_root():
    """Against the 40-digit cube root (mpmath) on 3000 values over the whole range, subnormals
    included: within 3 ulp (of the result) of the exact root, glibc's algorithm's error (measured
    2.86 ulp the most on 2 x 10^4 values, half of them within 0.6)."""
    import mpmath as mp
    x = sample(3000, seed=5)
    x = x[np.isfinite(x) & (x != 0.0)]
    y = cbrt(x)
    with mp.workdps(40):
        ref = [mp.sign(float(v)) * mp.cbrt(abs(mp.mpf(float(v)))) for v in x]
        err = [abs((mp.mpf(float(a)) - r) / mp.mpf(float(np.spacing(abs(float(a))))))
               for a, r in zip(y, ref)]
    assert float(max(err)) <= 3.0


def test_shapes_and_out():
    """Any shape (0-d included) and ``out`` (in place too): the same values as the flat call."""
    x = sample(600, seed=9)[:600].reshape(20, 30)
    want = cbrt(x.ravel())
    assert np.array_equal(bits(cbrt(x).ravel()), bits(want))
    assert cbrt(np.float64(8.0)).shape == () and float(cbrt(np.float64(8.0))) == 2.0
    y = x.copy()
    assert cbrt(y, out=y) is y and np.array_equal(bits(y.ravel()), bits(want))
