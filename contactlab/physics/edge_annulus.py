"""Monotone dissipation of a thin slip annulus at the contact edge, in annulus coordinates.

Under a small tangential shift ``u`` or twist ``φ`` the slip zone of the MDR springs is a thin
annulus ``c < x < a`` at the contact edge. Its dissipation is an integral over that annulus of
``h (slip)``, ``h(x) = μE*(d − g(x))`` the spring's friction limit:

* shift (Cattaneo–Mindlin): ``D = 2∫_c^a h (u − h/G*) dx`` with ``h(c) = G* u``;
* MDR torsion springs: ``D = 16 G_t ∫_c^a u_s (xφ − u_s) dx``, ``u_s = h/(4 G_t)``, with
  ``cφ = u_s(c)``.

Written at the stick radius ``c`` these lose the annulus to rounding once its width
``σ_c = a − c`` nears the float spacing of ``a``: ``c`` is a float near ``a``, ``d − g(x)`` a
difference of two numbers of the size of ``d``, so the relative error is ``~ε a/σ_c`` (``D = 0``
at amplitudes of one ulp, 1e-3 at ``σ_c/a ~ 1e-13``). Here the annulus is its own coordinate: for
a single power law ``g = K x^n`` (paraboloid, cone, power law; ``d = g(a)``) the drop below the
edge is ``g(a) − g(a − σ) = K aⁿ (−expm1(n log1p(−σ/a)))`` (relative rounding), the stick width
``σ_c`` solves its equation in ``σ`` (closed form for the shift, Newton for the twist from the
linearised root) and the integral is a 16-point Gauss–Legendre rule on ``[0, σ_c]``, where the
integrand is smooth (its nearest singularity, ``x = 0``, lies ``~a`` away). Every factor keeps
its relative accuracy: the result is accurate to rounding at any amplitude, and ``>= 0``.

All functions are pure: arrays in, arrays out.
"""
from __future__ import annotations

import numpy as np

from ..symbolic.transform import kappa

__all__ = ["EDGE_SLIP_RATIO", "power_edge", "edge_drop", "shift_dissipation",
           "torsion_dissipation", "exact_torsion_dissipation"]

#: stick width ``σ_c/a`` below which the histories take the annulus form: the stick-radius form
#: errs by a few ``ε a/σ_c`` (measured 4e-14 at ``σ_c/a = 5e-3``), below 1e-12 above this
EDGE_SLIP_RATIO = 1e-3

_GL_X, _GL_W = np.polynomial.legendre.leggauss(16)


def power_edge(profile) -> tuple[float, float] | None:
    """``(K, n)`` with ``g = K x^n`` (``K > 0``, ``n > 0``) for a single power-law profile without
    flat or wall (the annulus form's premise), else ``None``."""
    terms = profile.power_terms()
    if terms is None or len(terms) != 1:
        return None
    c, n = (float(v) for v in terms[0])
    if not (c > 0 and n > 0) or np.isfinite(profile.wall_radius) or profile.flat_radius > 0:
        return None
    return float(kappa(n)) * c, n


def _edge_depth(K: float, n: float, a: np.ndarray) -> np.ndarray:
    """``g(a) = K aⁿ``, m; ``nan`` where it leaves the float range (not this form's range: the
    stick-radius form answers there)."""
    with np.errstate(over="ignore", under="ignore", divide="ignore", invalid="ignore"):
        g = np.exp(np.log(K) + n * np.log(a))
    return np.where(np.isfinite(g) & (g > 0), g, np.nan)


def edge_drop(K: float, n: float, a: np.ndarray, sigma: np.ndarray) -> np.ndarray:
    """``g(a) − g(a − σ)`` for ``g = K x^n``, m, to relative rounding (``0 <= σ <= a``)."""
    return _edge_depth(K, n, a) * -np.expm1(n * np.log1p(-sigma / a))


def _annulus_rule(sig_c: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Nodes ``σ`` (rows) and weights of the Gauss–Legendre rule on ``[0, σ_c]``."""
    half = 0.5 * sig_c[:, None]
    return half * (_GL_X[None, :] + 1.0), half * _GL_W[None, :]


def shift_dissipation(K: float, n: float, E_star: float, G_star: float, mu: float,
                      a: np.ndarray, u: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Virgin-curve dissipation ``2∫_c^a h (u − h/G*) dx`` (J) of a shift ``|u|`` and the stick
    width ``σ_c/a``, in annulus coordinates (module docstring); flat arrays. ``σ_c/a`` is
    ``inf`` where the drop ``h(c)`` exceeds half of ``μE* g(a)`` (not this form's range)."""
    a, u = np.asarray(a, float), np.abs(np.asarray(u, float))
    hc = G_star * u                                         # h(c) = G* u
    y = hc / (mu * E_star * _edge_depth(K, n, a))           # drop at c relative to g(a)
    # (beyond y = 1/2 the slip reaches far inside: not this form's range; nan: g(a) overflows)
    y = np.where(np.isfinite(y), y, np.inf)
    s_c = np.where(y <= 0.5, -np.expm1(np.log1p(-np.minimum(y, 0.5)) / n), np.inf)
    out = np.zeros(a.shape)
    ok = np.isfinite(s_c) & (s_c > 0)
    if np.any(ok):
        ak = a[ok]
        sig, w = _annulus_rule(s_c[ok] * ak)
        h = mu * E_star * edge_drop(K, n, ak[:, None], sig)
        out[ok] = 2.0 / G_star * np.sum(w * h * (hc[ok][:, None] - h), axis=1)
    return np.maximum(out, 0.0), s_c


def torsion_dissipation(K: float, n: float, E_star: float, G_t: float, mu: float,
                        a: np.ndarray, phi: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Dissipation ``16 G_t ∫_c^a u_s (xφ − u_s) dx`` (J) of the MDR torsion springs twisted
    monotonically to ``|φ|`` and the stick width ``σ_c/a``, in annulus coordinates; flat
    arrays. The width solves ``(1 − s) aφ = Q (1 − (1 − s)^n)``, ``Q = μE* K aⁿ/(4 G_t)``, by
    Newton from the root of its linearisation ``s₀ = aφ/(aφ + nQ)`` (the left side falls and the
    right rises in ``s``: one root; from ``s₀`` Newton converges to rounding in a few steps where
    ``s`` is small, the range of this form)."""
    a, phi = np.asarray(a, float), np.abs(np.asarray(phi, float))
    Q = mu * E_star * _edge_depth(K, n, a) / (4.0 * G_t)
    keep = np.isfinite(Q)                                   # else: not this form's range
    Q = np.where(keep, Q, 1.0)
    A = a * phi
    s = A / (A + n * Q)
    for _ in range(6):
        F = (1.0 - s) * A + Q * np.expm1(n * np.log1p(-s))
        dF = -A - n * Q * np.exp((n - 1.0) * np.log1p(-s))
        s = np.clip(s - F / dF, 0.0, 0.5)
    s = np.where(keep, s, np.inf)
    out = np.zeros(a.shape)
    ok = np.isfinite(s) & (s > 0)
    if np.any(ok):
        ak, pk = a[ok], phi[ok]
        sig, w = _annulus_rule(s[ok] * ak)
        us = mu * E_star * edge_drop(K, n, ak[:, None], sig) / (4.0 * G_t)
        out[ok] = 16.0 * G_t * np.sum(w * us * ((ak[:, None] - sig) * pk[:, None] - us), axis=1)
    return np.maximum(out, 0.0), s


def _slip_function(K: float, n: float, E_star: float, a: np.ndarray,
                   sigma: np.ndarray) -> np.ndarray:
    """Jäger's slip function ``P(x) = ∫_x^a p(s)/sqrt(s² − x²) ds`` at ``x = a − σ`` (Pa) for
    ``g = K x^n``, ``d = g(a)``: with the pressure ``p = (E*/π) ∫_r^a g'(t)/sqrt(t² − r²) dt``
    the inner integral is ``K(m)/t``, so ``P = (E*/π) ∫_x^a g'(t) K(m_t)/t dt`` with
    ``m_t = 1 − x²/t² = (σ − τ)(2a − σ − τ)/(a − τ)²`` at ``t = a − τ``: exact differences, an
    integrand smooth in ``τ`` (``K`` analytic at ``m = 0``), 16-point Gauss–Legendre on
    ``[0, σ]``. ``a`` and ``σ`` broadcast (any shape); the rule adds a last axis."""
    from scipy.special import ellipk
    half = 0.5 * sigma[..., None]
    tau = half * (_GL_X + 1.0)
    t = a[..., None] - tau
    m = (sigma[..., None] - tau) * (2.0 * a[..., None] - sigma[..., None] - tau) / (t * t)
    f = n * _edge_depth(K, n, t) / (t * t) * ellipk(m)
    return E_star / np.pi * np.sum(half * _GL_W * f, axis=-1)


def exact_torsion_dissipation(K: float, n: float, E_star: float, G_t: float, mu: float,
                              a: np.ndarray, phi: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Dissipation ``(4μ²/G_t) ∫_c^a x² P(x) (P(c) − P(x)) dx`` (J) of Jäger's exact solution
    twisted monotonically to ``|φ|`` and the stick width ``σ_c/a``, in annulus coordinates;
    flat arrays. ``σ_c`` solves ``P(σ_c) = 2 G_t φ/μ`` from the edge slope
    ``P ≈ (E*/2) g'(a) σ`` by the fixed point ``σ ← σ P*/P(σ)`` (``P(σ)/σ`` varies by
    ``O(σ/a)``: it contracts by that factor per step, to rounding in 8 steps where ``σ/a`` is
    small, the range of this form)."""
    a, phi = np.asarray(a, float), np.abs(np.asarray(phi, float))
    target = 2.0 * G_t * phi / mu
    slope = 0.5 * E_star * n * _edge_depth(K, n, a) / a     # P ≈ (E*/2) g'(a) σ
    keep = np.isfinite(slope)                               # else: not this form's range
    sig = np.minimum(target / np.where(keep, slope, 1.0), 0.5 * a)
    for _ in range(8):
        P = _slip_function(K, n, E_star, a, sig)
        sig = np.minimum(np.where(P > 0, sig * target / np.where(P > 0, P, 1.0), 0.0), 0.5 * a)
    s = np.where(keep, sig / a, np.inf)
    out = np.zeros(a.shape)
    ok = keep & (sig > 0)
    if np.any(ok):
        ak = a[ok]
        nodes, w = _annulus_rule(sig[ok])
        P = _slip_function(K, n, E_star, ak[:, None], nodes)
        x = ak[:, None] - nodes
        out[ok] = 4.0 * mu * mu / G_t * np.sum(w * x * x * P * (target[ok][:, None] - P),
                                                axis=1)
    return np.maximum(out, 0.0), s
