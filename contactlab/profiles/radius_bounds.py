"""Upper brackets of the contact radius from the gap f alone (no quadrature of g).

The depth and the reduced force of a contact radius ``a`` are Stieltjes integrals over f:

    g(a)      = ∫_0^a  a / sqrt(a² - r²)  df(r)
    F(a)/2E*  = ∫_0^a  r² / sqrt(a² - r²) df(r)

Both weights grow with r. Where f does not decrease on [0, a] (df >= 0), a left Riemann-Stieltjes
sum on any grid, ``Σ w(r_{i-1}) (f(r_i) - f(r_{i-1}))``, is therefore a lower bound of the
integral, and the first radius whose lower bound reaches the requested depth or force lies at or
above the root: an upper bracket from a few dozen values of f, without a quadrature of g. Where
f decreases between grid points the sum is no bound at all, so the callers check g (or the force)
at the bracket with one quadrature and fall back to growing the bracket on g where it falls short.

The grid is ``r_i = a sin(θ_i)``, ``θ_i = (π/2) i/m``, dense near ``r = a`` where the weights are
singular; the candidate radii are ``start · 2^(k/4)``. A candidate's bound depends only on the
profile and the candidate (never on the other requests of a batch), so one load and a batch of
loads get the same bracket, bit for bit.
"""
from __future__ import annotations

import math
from bisect import bisect_left
from functools import cache
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from .base import Profile

__all__ = ["upper_radius_from_f", "first_step_from_f", "upper_radius_one", "first_step_one",
           "BOUND_POINTS", "LADDER_STEPS", "LADDER_CHUNK"]

#: grid intervals per candidate radius (the bound is within ~10 % of g for a paraboloid)
BOUND_POINTS = 16
#: candidate radii per octave (the bracket is at most 2^(1/4) ≈ 1.19 above the first radius whose
#: bound reaches the target)
LADDER_STEPS = 4
#: candidate radii per call of f (32 octaves: 1 µm to 4 km from the usual start); at most two
#: chunks are tried
LADDER_CHUNK = 128
_MAX_CHUNKS = 2


@cache
def _grid() -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``sin θ_i`` (i = 0..m) and the left weights of g (``1/cos θ_i``) and of the force
    (``sin²θ_i / cos θ_i``, times a), i = 0..m-1; read-only."""
    th = np.arange(BOUND_POINTS + 1) * (0.5 * np.pi / BOUND_POINTS)
    s = np.sin(th)
    s[-1] = 1.0
    c = np.cos(th[:-1])
    w_g = 1.0 / c
    w_f = s[:-1] * s[:-1] / c
    for v in (s, w_g, w_f):
        v.flags.writeable = False
    return s, w_g, w_f


def _bounds(profile: Profile, radii: np.ndarray, kind: str) -> np.ndarray:
    """Lower bounds of g (``kind="depth"``) or of F/2E* (``kind="force"``) at each radius;
    -inf where f decreases between two grid points (no bound) or is not finite. (Always called
    on the same ladder of radii, whatever the targets: the same bits for one load and a batch.)"""
    s, w_g, w_f = _grid()
    r = radii[:, None] * s[None, :]
    with np.errstate(over="ignore", invalid="ignore"):
        f = np.asarray(profile._height(r), dtype=float)
        df = f[:, 1:] - f[:, :-1]
        total = (df * (w_g if kind == "depth" else w_f)).sum(axis=1)
        if kind == "force":
            total *= radii
        ok = (df >= 0).all(axis=1) & np.isfinite(total)
    return np.where(ok, total, -np.inf)


@cache
def _ladder(start: float, cap: float, chunk: int) -> np.ndarray:
    """Candidate radii ``start · 2^(k/4)`` of one chunk, those ``<= cap`` (read-only)."""
    k = np.arange(chunk * LADDER_CHUNK, (chunk + 1) * LADDER_CHUNK)
    radii = start * 2.0 ** (k / LADDER_STEPS)
    radii = radii[radii <= cap]
    radii.flags.writeable = False
    return radii


def _chunk(profile: Profile, start: float, cap: float, kind: str, chunk: int
           ) -> tuple[np.ndarray, np.ndarray]:
    """The ladder's radii of one chunk and their bounds (kept per profile, read-only)."""
    radii = _ladder(float(start), float(cap), chunk)
    key = (float(start), float(cap), kind, chunk)
    cache = profile.__dict__.get("_radius_bound_cache")
    if cache is None:
        cache = profile.__dict__["_radius_bound_cache"] = {}
    b = cache.get(key)
    if b is None:
        # (the profile's parameters are fixed: its bounds on a ladder are computed once)
        b = cache[key] = _bounds(profile, radii, kind) if radii.size else np.zeros(0)
        b.flags.writeable = False
    return radii, b


def _chunk_lists(profile: Profile, start: float, cap: float, kind: str
                 ) -> tuple[list[float], list[float], bool]:
    """The first chunk's radii and bounds as lists and whether the bounds never decrease (for
    the one-load functions below; kept per profile)."""
    cache = profile.__dict__.get("_radius_bound_cache")
    key = (float(start), float(cap), kind, "lists")
    got = cache.get(key) if cache is not None else None
    if got is None:
        radii, b = _chunk(profile, start, cap, kind, 0)
        mono = bool(radii.size >= 2 and np.all(b[1:] >= b[:-1]) and b[0] > -np.inf)
        got = (radii.tolist(), b.tolist(), mono)
        profile.__dict__["_radius_bound_cache"][key] = got
    return got


def upper_radius_one(profile: Profile, target: float, start: float, cap: float,
                     kind: str) -> float:
    """:func:`upper_radius_from_f` of one target in floats (the same radius)."""
    if math.isfinite(start) and start > 0 and target == target:
        radii, b, mono = _chunk_lists(profile, start, cap, kind)
        if mono:
            k = bisect_left(b, target)          # (the first bound >= target, as argmax there)
            if k < len(radii):
                return radii[k]
    return float(upper_radius_from_f(profile, np.array([target]), start, cap, kind)[0])


def upper_radius_from_f(profile: Profile, target: np.ndarray, start: float, cap: float,
                        kind: str) -> np.ndarray:
    """Per target (depth in m, or ``F/2E*`` in N/Pa), the first candidate radius
    ``start · 2^(k/4) <= cap`` whose lower bound from f reaches it, or NaN where none does.

    Only a bracket candidate: the bound holds where f does not decrease on [0, radius], which
    the callers verify with one evaluation of g (or the force) there.
    """
    t = np.asarray(target, dtype=float)
    out = np.full(t.shape, np.nan)
    if not (np.isfinite(start) and start > 0):
        return out
    todo = np.ones(t.shape, dtype=bool)
    for chunk in range(_MAX_CHUNKS):
        radii, b = _chunk(profile, start, cap, kind, chunk)
        if radii.size == 0:
            break
        reach = b[None, :] >= t[todo][:, None]
        hit = reach.any(axis=1)
        out[todo] = np.where(hit, radii[reach.argmax(axis=1)], np.nan)
        todo[todo] = ~hit
        if not todo.any() or radii.size < LADDER_CHUNK:
            break
    return out


#: the first step of the root's iteration stays this far inside the bracket (as a fraction)
_STEP_MARGIN = 1.0 / 64.0


def _log_slopes(profile: Profile, start: float, cap: float, kind: str) -> np.ndarray:
    """Per interval of the first chunk's ladder, the power ``m`` of its bounds,
    ``ln(b_k/b_{k-1}) / ln(r_k/r_{k-1})`` (element ``k``; element 0 and intervals without a
    positive finite power: NaN). Kept per profile, read-only: one load and a batch read the same
    values."""
    cache = profile.__dict__["_radius_bound_cache"]     # (filled by _chunk before)
    key = (float(start), float(cap), kind, "slopes")
    m = cache.get(key)
    if m is None:
        radii, b = _chunk(profile, start, cap, kind, 0)
        m = np.full(radii.size, np.nan)
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            p = np.log(b[1:] / b[:-1]) / np.log(radii[1:] / radii[:-1])
        m[1:] = np.where(np.isfinite(p) & (p > 0), p, np.nan)
        m.flags.writeable = False
        cache[key] = m
    return m


def _slope_lists(profile: Profile, start: float, cap: float, kind: str) -> list[float]:
    """:func:`_log_slopes` as a list (for :func:`first_step_one`; kept per profile)."""
    cache = profile.__dict__["_radius_bound_cache"]
    key = (float(start), float(cap), kind, "slope lists")
    got = cache.get(key)
    if got is None:
        got = cache[key] = _log_slopes(profile, start, cap, kind).tolist()
    return got


def first_step_from_f(profile: Profile, target: np.ndarray, lo: np.ndarray, hi: np.ndarray,
                      value_hi: np.ndarray, start: float, cap: float, kind: str) -> np.ndarray:
    """A first point for the root's iteration in ``[lo, hi]``, as a fraction from ``lo``
    (0.5, a bisection, where no guess applies).

    ``value_hi`` is g (or F/2E*) at ``hi``. The ratio of g to its lower bound from f is the same
    at every radius for a power-law gap (both scale as ``a^n``) and varies slowly otherwise; so
    the guess is the radius where the bound, scaled by the ratio found at ``hi``, meets the
    target, both read off the bounds of the first ladder chunk by power-law interpolation
    between two ladder radii (``b ∝ r^m`` on the interval, ``m`` from its two bounds: exact for
    a power-law gap, whose guess is then the root itself up to the quadrature's error), linear
    where an interval has no positive power. Elementwise arithmetic and numpy's ``power`` per
    element: one load and a batch get the same bits.
    """
    t = np.asarray(target, dtype=float)
    out = np.full(t.shape, 0.5)
    if not (np.isfinite(start) and start > 0):
        return out
    radii, b = _chunk(profile, start, cap, kind, 0)
    if not _chunk_lists(profile, start, cap, kind)[2]:
        return out
    m = _log_slopes(profile, start, cap, kind)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        # the bound at hi (interpolated between the ladder's radii), then the ratio of value
        # to bound
        j = np.clip(np.searchsorted(radii, hi), 1, radii.size - 1)
        r0, r1, b0, b1, mj = radii[j - 1], radii[j], b[j - 1], b[j], m[j]
        pj = np.isfinite(mj)
        b_hi = np.where(pj, b0 * np.power(hi / r0, np.where(pj, mj, 1.0)),
                        b0 + (hi - r0) * ((b1 - b0) / (r1 - r0)))
        tau = t * (b_hi / value_hi)
        # the radius where the bound reaches tau (interpolated between the ladder's bounds)
        k = np.clip(np.searchsorted(b, tau), 1, radii.size - 1)
        r0, r1, b0, b1, mk = radii[k - 1], radii[k], b[k - 1], b[k], m[k]
        pk = np.isfinite(mk)
        x0 = np.where(pk, r0 * np.power(tau / b0, np.where(pk, 1.0 / mk, 1.0)),
                      r0 + (tau - b0) * ((r1 - r0) / (b1 - b0)))
        frac = (x0 - lo) / (hi - lo)
        ok = (np.isfinite(frac) & (hi >= radii[0]) & (hi <= radii[-1]) & (value_hi > 0)
              & (b_hi > 0) & (tau >= b[0]) & (tau <= b[-1]))
    return np.where(ok, np.clip(frac, _STEP_MARGIN, 1.0 - _STEP_MARGIN), out)


def _power_one(x: float, p: float) -> float:
    """numpy's ``power`` of one element, as on an array (its vector loop, not the C
    library's ``pow``, which may differ in the last bit). The floating-point state switch
    (a few µs, more than the power) only where the power could overflow or be invalid."""
    if 0.0 < x < math.inf and abs(p) < 1e300 and abs(p * math.log(x)) < 700.0:
        return float(np.power(np.array([x]), np.array([p]))[0])
    with np.errstate(over="ignore", invalid="ignore", divide="ignore", under="ignore"):
        return float(np.power(np.array([x]), np.array([p]))[0])


def first_step_one(profile: Profile, target: float, lo: float, hi: float, value_hi: float,
                   start: float, cap: float, kind: str) -> float:
    """:func:`first_step_from_f` of one element in floats (the same operations: the same
    fraction, bit for bit)."""
    if not (math.isfinite(start) and start > 0):
        return 0.5
    radii, b, mono = _chunk_lists(profile, start, cap, kind)
    if not mono:
        return 0.5
    m = _slope_lists(profile, start, cap, kind)
    n = len(radii)
    try:
        j = min(max(bisect_left(radii, hi), 1), n - 1)
        r0, r1, b0, b1, mj = radii[j - 1], radii[j], b[j - 1], b[j], m[j]
        if math.isfinite(mj):
            b_hi = b0 * _power_one(hi / r0, mj)
        else:
            b_hi = b0 + (hi - r0) * ((b1 - b0) / (r1 - r0))
        tau = target * (b_hi / value_hi)
        k = min(max(bisect_left(b, tau), 1), n - 1)
        r0, r1, b0, b1, mk = radii[k - 1], radii[k], b[k - 1], b[k], m[k]
        if math.isfinite(mk):
            x0 = r0 * _power_one(tau / b0, 1.0 / mk)
        else:
            x0 = r0 + (tau - b0) * ((r1 - r0) / (b1 - b0))
        frac = (x0 - lo) / (hi - lo)
    except (ZeroDivisionError, OverflowError):
        return 0.5
    ok = (math.isfinite(frac) and radii[0] <= hi <= radii[-1] and value_hi > 0 and b_hi > 0
          and b[0] <= tau <= b[-1])
    return min(max(frac, _STEP_MARGIN), 1.0 - _STEP_MARGIN) if ok else 0.5
