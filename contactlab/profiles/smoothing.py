"""Smoothing of measured (noisy) profile tables and the nearest MDR-admissible table.

Kernels only (arrays in, arrays out); :class:`~contactlab.profiles.tabulated.Tabulated` calls
them at construction.

Smoothing is a cubic smoothing spline of the table (natural ends; the minimiser scipy's
``make_smoothing_spline`` computes, in Reinsch's banded form so each λ costs O(N)). It
minimises
``Σ (f_i - s(r_i))² + λ ∫ s''(ρ)² dρ`` with ``ρ = r / r_max`` (``λ`` dimensionless). ``λ``
is

* given (``smoothing=<float>``),
* chosen so that the RMS change of the table equals a known measurement noise
  (``smoothing="auto", noise=σ``; the discrepancy principle), or
* chosen by generalised cross-validation, ``GCV(λ) = N RSS / (N - tr S_λ)²``
  (``smoothing="auto"``; λ that keep more than 80 % of the points' degrees of freedom
  are excluded, GCV's spurious minimum at interpolation), with ``tr S_λ`` exact up to 1000
  points and estimated from 32 fixed Rademacher probes (Hutchinson) beyond, so the choice is
  the same on every run.

On the axis the spline is even (``axis="even"``, the default): the table is mirrored,
``f(-r) = f(r)``, and the smoother acts on the mirrored table, so the smoothed surface has
``f'(0) = 0`` like every body of revolution that is smooth on its axis. Natural ends there left
a slope of the noise's size on the axis, a cone tip whose pressure is infinite. A measured cone
(a real tip) is smoothed with ``axis="free"``: natural ends at both ends, a tip rounded by the
mirroring would triple a noisy cone's force error.

The uncertainty the smoothing leaves is estimated once: the noise level ``σ`` (given, or from the
residuals, ``RSS / (N - tr S)``), the spread of the smoothed table over 16 re-smoothed copies
with fresh noise of that level (fixed seed), and the smoothing bias, estimated as the change a
second smoothing makes (``s - S s``). :class:`Tabulated` turns these into error bands of ``g``
and ``∫g``.

The MDR needs ``g`` non-decreasing; for the piecewise-linear interpolant of a table that holds
when ``r f'(r)`` is non-decreasing, i.e. the slopes ``s_k`` are >= 0 and non-decreasing (a slope
drop at ``r_j`` makes ``g`` fall just beyond ``r_j``). :func:`nearest_admissible` returns the
table with those slopes that is nearest in the slope norm ``Σ h_k (s_k - ŝ_k)²`` (weighted
isotonic regression), integrated back from the axis value.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import ParameterError, TabulatedDataError
from ..params import as_real

__all__ = ["SmoothingReport", "smooth_table", "nearest_admissible", "slope_violations"]

#: random probes for the GCV trace and the noise re-smoothings (fixed seed: deterministic)
N_PROBES = 32
#: tables up to this many points get the exact trace of the smoother (GCV)
EXACT_TRACE_LIMIT = 1000
_LOG_LAM = np.linspace(-14.0, 4.0, 37)


@dataclass(frozen=True)
class SmoothingReport:
    """What smoothing did to a table.

    Attributes
    ----------
    method : str
        ``"given"`` (λ from the caller), ``"noise"`` (λ matched to ``noise``), ``"gcv"``
        (generalised cross-validation) or ``"admissible"`` (no smoothing, projection only).
    lam : float
        Smoothing parameter λ (dimensionless: radii scaled by the last radius).
    max_change, rms_change : float
        Largest and RMS change of the heights, m.
    noise : float
        Noise level used for the error estimate, m (given, or estimated from the residuals).
    dof : float
        Effective degrees of freedom of the smoothed table (``tr S``).
    admissible_change : float
        Largest change of the heights made by ``admissible="nearest"``, m (0 if not asked).
    """

    method: str
    lam: float
    max_change: float
    rms_change: float
    noise: float
    dof: float
    admissible_change: float = 0.0


class _Smoother:
    """Reinsch form of the cubic smoothing spline (Green & Silverman, 1994, §2.3): the smoothed
    values at the abscissae are ``y - λ Q γ`` with ``(R + λ QᵀQ) γ = Qᵀ y`` (``Q`` the
    second-difference matrix, ``R`` the tridiagonal Gram matrix of the natural spline). The
    band matrices are built once; each λ costs one banded Cholesky solve, O(N), for any number
    of columns. This is the minimiser scipy's ``make_smoothing_spline`` computes (same λ)."""

    def __init__(self, r: np.ndarray, f: np.ndarray, even: bool = False) -> None:
        from scipy import sparse
        self.r, self.f = r, f
        self.n = r.size
        # even: the smoother of the mirrored table (the axis node once), restricted to r >= 0
        self._skip = (1 if r[0] == 0 else 0) if even else None
        # (_skip is None exactly when not even)
        full = np.concatenate([-r[::-1][:r.size - self._skip], r]) if self._skip is not None else r
        self.x = full / r[-1]
        h = np.diff(self.x)
        m = self.x.size
        k = np.arange(m - 2)
        Q = sparse.csc_matrix((np.concatenate([1 / h[:-1], -1 / h[:-1] - 1 / h[1:], 1 / h[1:]]),
                               (np.concatenate([k, k + 1, k + 2]), np.concatenate([k, k, k]))),
                              shape=(m, m - 2))
        R = sparse.diags([h[1:-1] / 6, (h[:-1] + h[1:]) / 3, h[1:-1] / 6], [-1, 0, 1])
        QtQ = (Q.T @ Q).todia()
        self.Q = Q
        self._R = np.zeros((3, m - 2))
        self._R[2] = (h[:-1] + h[1:]) / 3
        self._R[1, 1:] = h[1:-1] / 6
        self._QQ = np.zeros((3, m - 2))
        for off, row in zip(QtQ.offsets, QtQ.data):
            if 0 <= off <= 2:    # upper bands, dia layout: data[j] sits in column j
                self._QQ[2 - off, off:] = row[off:]
        del R
        rng = np.random.default_rng(12)
        self.z = rng.choice([-1.0, 1.0], size=(self.n, N_PROBES))

    def _solve(self, y: np.ndarray, lam: float) -> np.ndarray:
        from scipy.linalg import solveh_banded
        if self._skip is not None:          # mirror, smooth, keep the half r >= 0
            y = np.concatenate([y[::-1][:self.n - self._skip], y])
        gamma = solveh_banded(self._R + lam * self._QQ, self.Q.T @ y)
        out = y - lam * (self.Q @ gamma)
        return out[-self.n:] if self._skip is not None else out

    def apply(self, values: np.ndarray, lam: float) -> np.ndarray:
        """The smoother ``S_λ`` applied to table values (1-D or columns)."""
        return self._solve(values, lam)

    def trace(self, lam: float) -> float:
        """``tr S_λ``: exact (unit columns) up to :data:`EXACT_TRACE_LIMIT` points, else the
        Hutchinson estimate from the fixed probes."""
        if self.n <= EXACT_TRACE_LIMIT:
            total = 0.0
            for j0 in range(0, self.n, 512):        # blocks of unit columns
                cols = np.zeros((self.n, min(512, self.n - j0)))
                idx = np.arange(cols.shape[1])
                cols[j0 + idx, idx] = 1.0
                total += float(np.sum(self.apply(cols, lam)[j0 + idx, idx]))
            return total
        return float(np.mean(np.sum(self.z * self.apply(self.z, lam), axis=0)))

    def rss(self, lam: float) -> tuple[float, np.ndarray]:
        s = self.apply(self.f, lam)
        return float(np.sum((s - self.f) ** 2)), s

    def gcv(self, lam: float) -> float:
        rss, _ = self.rss(lam)
        dof = self.trace(lam)
        if dof > 0.8 * self.n:      # near-interpolation: GCV's spurious minimum at λ -> 0
            return np.inf
        return self.n * rss / (self.n - dof) ** 2


def _golden(fun, lo: float, hi: float, iters: int = 30) -> float:
    phi = 0.5 * (np.sqrt(5.0) - 1.0)
    a, b = lo, hi
    c, d = b - phi * (b - a), a + phi * (b - a)
    fc, fd = fun(c), fun(d)
    for _ in range(iters):
        if fc < fd:
            b, d, fd = d, c, fc
            c = b - phi * (b - a)
            fc = fun(c)
        else:
            a, c, fc = c, d, fd
            d = a + phi * (b - a)
            fd = fun(d)
    return 0.5 * (a + b)


def smooth_table(r: np.ndarray, f: np.ndarray, smoothing: object, noise: float | None,
                 axis: str = "even"
                 ) -> tuple[np.ndarray, SmoothingReport, dict[str, np.ndarray]]:
    """Smoothed heights at the table radii, the report, and the error ingredients.

    ``axis="even"`` smooths the table mirrored about the axis (``f'(0) = 0``), ``"free"``
    with natural ends at both ends (see the module docstring).

    Returns
    -------
    f_smooth : ndarray
    report : SmoothingReport
    parts : dict
        ``"bias"`` (estimated smoothing bias at the nodes, m) and ``"spread"`` (N × 16 array of
        re-smoothed noise copies minus the smoothed table, m).
    """
    if r.size < 5:
        raise TabulatedDataError(f"r has {r.size} points: smoothing needs at least 5.")
    sm = _Smoother(r, f, even=axis == "even")
    if isinstance(smoothing, str):
        if smoothing != "auto":
            raise ParameterError(f"smoothing={smoothing!r} is invalid: use None, 'auto' or a "
                                 "number >= 0 (the spline's dimensionless λ).")
        if noise is not None:
            target = float(noise) * float(noise) * r.size     # inf for absurd noise: no overflow error

            def excess(log_lam: float) -> float:
                return np.log(max(sm.rss(10.0 ** log_lam)[0], 1e-300)) - np.log(target)
            vals = np.array([excess(v) for v in _LOG_LAM])
            if vals[-1] <= 0:
                log_lam, method = float(_LOG_LAM[-1]), "noise"
            elif vals[0] >= 0:
                log_lam, method = float(_LOG_LAM[0]), "noise"
            else:
                k = int(np.argmax(vals > 0))
                from scipy.optimize import brentq
                log_lam = brentq(excess, _LOG_LAM[k - 1], _LOG_LAM[k], xtol=1e-6)
                method = "noise"
        else:
            scores = np.array([sm.gcv(10.0 ** v) for v in _LOG_LAM])
            k = int(np.argmin(scores))
            lo, hi = _LOG_LAM[max(k - 1, 0)], _LOG_LAM[min(k + 1, _LOG_LAM.size - 1)]
            log_lam = _golden(lambda v: sm.gcv(10.0 ** v), lo, hi)
            method = "gcv"
        lam = 10.0 ** log_lam
    else:
        lam = as_real("smoothing", smoothing, "use None, 'auto' or a number >= 0 (the "
                                              "spline's dimensionless λ)")
        if not np.isfinite(lam) or lam < 0:
            raise ParameterError(f"smoothing={smoothing!r} is invalid: λ must be a finite "
                                 "number >= 0.")
        method = "given"
    rss, s = sm.rss(lam)
    dof = sm.trace(lam)
    if noise is not None:
        sigma = float(noise)
    else:
        sigma = float(np.sqrt(rss / max(r.size - dof, 1.0)))
    rng = np.random.default_rng(7)
    eps = sigma * rng.standard_normal((r.size, N_PROBES))
    spread = sm.apply(eps, lam)                      # S ε: the smoothed noise (S is linear)
    bias = s - sm.apply(s, lam)                      # a second smoothing's change ≈ bias
    change = s - f
    report = SmoothingReport(method, float(lam), float(np.max(np.abs(change))),
                             float(np.sqrt(np.mean(change ** 2))), sigma, float(dof))
    return s, report, {"bias": bias, "spread": spread}


def slope_violations(r: np.ndarray, f: np.ndarray) -> np.ndarray:
    """Indices ``j`` of the nodes where the linear interpolant's slope drops (``s_j < s_{j-1}``,
    ``r f'`` falls) and, as ``0``, a negative first slope."""
    s = np.diff(f) / np.diff(r)
    bad = list(np.flatnonzero(np.diff(s) < 0) + 1)
    return np.array(([0] if s[0] < 0 else []) + bad, dtype=np.intp)


def nearest_admissible(r: np.ndarray, f: np.ndarray) -> np.ndarray:
    """Heights of the nearest table whose slopes are >= 0 and non-decreasing.

    Nearest in ``Σ h_k (s_k - ŝ_k)²`` (``h_k`` the interval lengths): weighted isotonic
    regression of the slopes (scipy ``isotonic_regression``), clipped at 0, integrated from ``f[0]``.

    Examples
    --------
    >>> nearest_admissible(np.array([0.0, 1.0, 2.0, 3.0]), np.array([0.0, 2.0, 3.0, 6.0])).tolist()
    [0.0, 1.5, 3.0, 6.0]
    """
    h = np.diff(r)
    s = np.diff(f) / h
    from scipy.optimize import isotonic_regression
    s_hat = np.maximum(isotonic_regression(s, weights=h, increasing=True).x, 0.0)
    return f[0] + np.concatenate([[0.0], np.cumsum(s_hat * h)])
