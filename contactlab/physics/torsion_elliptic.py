"""Elliptic helpers of the exact torsion kernels (:mod:`contactlab.physics.torsion_exact`):
the complete integral ``K``, ``(K - E)/k²`` and the universal kernel
``h(v) = ∫_v^1 u² K(sqrt(1-u²)) du`` of the torque integral, each without cancellation as
``k → 0`` or ``k → 1`` (theory §6.2)."""
from __future__ import annotations

import numpy as np

__all__ = ["K_comp", "kme_over_m", "h_kernel"]


def _series_coefficients(n_terms: int) -> tuple[np.ndarray, np.ndarray]:
    n = np.arange(n_terms)
    a2 = np.ones(n_terms)
    for i in range(1, n_terms):
        a2[i] = a2[i - 1] * ((2 * i - 1) / (2 * i)) ** 2          # ((1/2)_n / n!)²
    b = np.concatenate([[0.0], np.cumsum(2.0 / ((2 * n[1:] - 1) * (2 * n[1:])))])
    return a2, b


_N_SERIES = 60
_A2, _B = _series_coefficients(_N_SERIES)


def K_comp(p: np.ndarray) -> np.ndarray:
    """Complete elliptic integral ``K(k)`` from the complementary parameter ``p = 1 - k²``.

    (scipy ``ellipkm1``: full relative precision as ``k → 1``, where ``K ~ ln(4/sqrt(p))``.)
    """
    from scipy.special import ellipkm1   # lazy: scipy.special costs ~0.1 s at import
    return ellipkm1(np.asarray(p, float))


# series of (K-E)/m = (π/2) Σ_{n>=1} a_n² 2n/(2n-1) m^(n-1), a_n = (1/2)_n/n!, for m <= 0.1
_KME_TERMS = 18


def kme_over_m(p: np.ndarray) -> np.ndarray:
    """``(K(k) - E(k))/k²`` from ``p = 1 - k²`` (``π/4`` at ``k = 0``, ``~ln(4/sqrt(p)) - 1`` as p → 0).

    Power series for ``|k²| <= 0.1`` (the difference ``K - E`` would cancel), ``ellipkm1`` and
    ``ellipe`` elsewhere. Relative error ~1e-16 (checked against Carlson's ``R_D(0, p, 1)/3``).
    ``p > 1`` (``k² < 0``) gives the analytic continuation, which the product-integration panels
    of large tables evaluate at interpolation points below the lower limit
    (:mod:`contactlab.physics.table_panels`).
    """
    p = np.asarray(p, float)
    m = 1.0 - p
    small = np.abs(m) <= 0.1
    big = ~small
    from scipy.special import ellipe, ellipkm1
    n_small = int(np.count_nonzero(small))
    if 2 * n_small < small.size:
        # mostly the special functions (the panels' points): evaluate them everywhere (the same
        # values elementwise), the few series points overwritten below, no gathers
        with np.errstate(divide="ignore", invalid="ignore"):
            out = np.asarray((ellipkm1(p) - ellipe(m)) / m, dtype=float)
    else:
        out = np.empty(p.shape)
        out[big] = (ellipkm1(p[big]) - ellipe(m[big])) / m[big]   # special functions where used
    if n_small:
        ms = m[small]
        acc = np.zeros(ms.shape)
        for n in range(_KME_TERMS, 0, -1):
            acc = acc * ms + _A2[n] * 2 * n / (2 * n - 1)
        out[small] = 0.5 * np.pi * acc
    return out


def _h_series(v: np.ndarray) -> np.ndarray:
    """``h(v) = ∫_v^1 u² K(sqrt(1-u²)) du`` by two convergent series (reference route).

    * ``v² <= 1/2``: ``K(k) = Σ a_n² u^{2n} [ln(4/u) - b_n]`` (``u = k'``) integrated term-wise,
      ``h = π²/16 - Σ a_n² v^{2n+3}/(2n+3) [ln(4/v) - b_n + 1/(2n+3)]``;
    * ``v² > 1/2``: ``K = (π/2) Σ a_n² k^{2n}``, ``h = (π/2) Σ a_n² I_n`` with
      ``I_n = ∫_v^1 u²(1-u²)^n du = (2n I_{n-1} - v³(1-v²)^n)/(2n+3)``.

    ``a_n = (1/2)_n/n!``, ``b_n = 2 Σ_{j<=n} 1/((2j-1)2j)``; 60 terms: error < 1e-17.
    """
    v = np.asarray(v, float)
    out = np.empty(v.shape)
    small = v * v <= 0.5
    if np.any(small):
        vs = v[small]
        with np.errstate(divide="ignore", invalid="ignore"):
            L = np.log(4.0 / vs)
            acc = np.zeros(vs.shape)
            vpow = vs**3
            v2 = vs * vs
            for n in range(_N_SERIES):
                q = 2 * n + 3
                acc += _A2[n] * vpow / q * (L - _B[n] + 1.0 / q)
                vpow = vpow * v2
        out[small] = np.where(vs > 0, np.pi**2 / 16 - acc, np.pi**2 / 16)
    big = ~small
    if np.any(big):
        vb = v[big]
        w = (1.0 - vb) * (1.0 + vb)
        v3 = vb**3
        In = (1.0 - v3) / 3.0
        acc = _A2[0] * In
        wn = np.ones(vb.shape)
        for n in range(1, _N_SERIES):
            wn = wn * w
            In = (2 * n * In - v3 * wn) / (2 * n + 3)
            acc += _A2[n] * In
        out[big] = 0.5 * np.pi * acc
    return out


def _h_chebyshev():
    """Chebyshev coefficients of the smooth parts of h (built once from the series).

    ``v² <= 1/2``: ``h = π²/16 - v³ [ln(4/v) A(z) + B(z)]``, ``z = v²``, with
    ``A = Σ a_n² z^n/(2n+3)`` and ``B = Σ a_n² z^n (1/(2n+3) - b_n)/(2n+3)`` analytic for ``|z| < 1``
    (Chebyshev on ``z ∈ [0, 1/2]``, 24 terms); ``v² > 1/2``: ``h/(1-v)`` is analytic in ``v`` on
    ``[1/√2, 1]`` (nearest singularity at 0; 20 terms). Both to ~1e-16.
    """
    from numpy.polynomial import chebyshev as C
    n = np.arange(_N_SERIES)
    q = 2 * n + 3
    alpha = _A2 / q
    beta = _A2 * (1.0 / q - _B) / q
    x = np.cos(np.pi * (np.arange(64) + 0.5) / 64)
    z = 0.25 * (x + 1.0)                                      # [0, 1/2]
    zp = z[:, None] ** n[None, :]
    cA = C.chebfit(x, zp @ alpha, 23)
    cB = C.chebfit(x, zp @ beta, 23)
    v0 = np.sqrt(0.5)
    vv = v0 + (1.0 - v0) * 0.5 * (x + 1.0)
    cH = C.chebfit(x, _h_series(vv) / (1.0 - vv), 19)        # h/(1-v): relative accuracy at v → 1
    return cA, cB, cH, v0


_H_CHEB = _h_chebyshev()


def h_kernel(v: np.ndarray) -> np.ndarray:
    """``h(v) = ∫_v^1 u² K(sqrt(1-u²)) du`` for ``0 <= v <= 1`` (``h(0) = π²/16``, ``h(1) = 0``).

    The universal kernel of the swapped torque integral. Evaluated from Chebyshev expansions of the
    analytic parts of the convergent series of :func:`_h_series` (module docstring); relative
    error ~1e-15 (tested against mpmath).
    """
    from numpy.polynomial.chebyshev import chebval
    cA, cB, cH, v0 = _H_CHEB
    v = np.asarray(v, float)
    out = np.empty(v.shape)
    over = v > 1.0
    if np.any(over):
        vo = v[over]
        out[over] = np.where(vo <= 2.0, (1.0 - vo) * chebval(2.0 * vo - 3.0, _h_over_cheb()),
                             _h_over_one(vo))
    small = v <= v0
    if np.any(small):
        vs = v[small]
        x = 4.0 * vs * vs - 1.0
        with np.errstate(divide="ignore", invalid="ignore"):
            L = np.where(vs > 0, np.log(4.0 / np.where(vs > 0, vs, 1.0)), 0.0)
        out[small] = np.pi**2 / 16 - vs**3 * (L * chebval(x, cA) + chebval(x, cB))
    big = ~small & ~over
    if np.any(big):
        x = 2.0 * (v[big] - v0) / (1.0 - v0) - 1.0
        out[big] = (1.0 - v[big]) * chebval(x, cH)
    return out


_GL16 = np.polynomial.legendre.leggauss(16)


def _h_over_one(v: np.ndarray) -> np.ndarray:
    """Analytic continuation of :func:`h_kernel` to ``1 < v <= 2``:
    ``h(v) = -∫_1^v u² K(u) du`` with ``K(u) = ellipkm1(u²)`` (``k² = 1 - u² < 0``), analytic
    there, by a 16-point Gauss-Legendre rule (to rounding for ``v <= 2``). Only the panels of
    :mod:`contactlab.physics.table_panels` evaluate it, at interpolation points below the lower
    limit of their integrals."""
    from scipy.special import ellipkm1
    x, w = _GL16
    half = 0.5 * (v - 1.0)
    u = 1.0 + half[..., None] * (x + 1.0)
    return -half * np.sum(w * u * u * ellipkm1(u * u), axis=-1)


_H_OVER: list = []


def _h_over_cheb() -> np.ndarray:
    """Chebyshev coefficients of ``h(v)/(1 - v)`` on ``[1, 2]`` from :func:`_h_over_one` (built
    once: analytic there, relative accuracy kept at the simple zero ``v = 1``; the nearest
    singularity ``v = 0`` gives ``ρ = 3 + 2√2``, so 26 terms reach ~1e-17 of its scale)."""
    if not _H_OVER:
        from numpy.polynomial import chebyshev as C
        x = np.cos(np.pi * (np.arange(40) + 0.5) / 40)
        v = 1.5 + 0.5 * x
        _H_OVER.append(C.chebfit(x, _h_over_one(v) / (1.0 - v), 25))
    return _H_OVER[0]
