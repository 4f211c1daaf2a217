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

Any other profile with a smooth contact edge takes the same forms with the drop integrated from
``g'`` on the annulus (:class:`ProfileEdge`, :func:`shift_any`, :func:`torsion_any`,
:func:`exact_torsion_any`), which also give the torque's and the force's slip corrections: the
no-slip value minus them is the result below a stick width of ``EDGE_FORCE_RATIO a``.

All functions are pure: arrays in, arrays out.
"""
from __future__ import annotations

import numpy as np

from ..symbolic.transform import kappa

__all__ = ["EDGE_SLIP_RATIO", "EDGE_FORCE_RATIO", "ANNULUS_RTOL",
           "power_edge", "edge_drop", "shift_dissipation",
           "ProfileEdge", "edge_of", "shift_any", "torsion_any", "exact_torsion_any",
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


# ---------------------------------------------------------------------------- any profile
# The same annulus forms for a profile that is not a single power law (exact sphere, sums,
# tables, truncated and polynomial profiles): the drop below the edge is written as
# ``g(a) − g(a − σ) = ∫_0^σ g'(a − τ) dτ`` by the Gauss–Legendre rule on ``[0, σ]``, split
# where the annulus crosses a kink of ``g`` (a table node, a breakpoint, a flat rim), with
# ``g'`` from the profile's closed form where it has one (power terms, sums, a table's node
# sums) and else from its own central differences (relative error ~1e-12). The drop keeps its
# relative accuracy at any ``σ``: so do the stick width, the dissipation and the torque and
# force corrections built from it. ``d = g(a)`` is taken as exact at a smooth contact edge
# (the normal solve's depth may differ from ``g(a)`` by a few ulps, which the stick-radius
# forms read as a punch edge of that height).

#: stick width ``σ_c/a`` below which the torque and tangential force take the annulus form
#: (no-slip value minus the annulus correction): there the stick-radius forms carry the
#: normal solve's rounding ``d − g(a)`` (a few ulps of ``d``) as a spurious edge step, an
#: absolute error ``~ε² E* d a²`` (1.7e-4 of the torque of a sphere at φ = 1e-30); above it
#: both forms agree to rounding (the annulus form also below, where the other drifts)
EDGE_FORCE_RATIO = 1e-9

#: relative error bound of the annulus corrections of any profile (stated in error estimates;
#: the correction is below ``EDGE_FORCE_RATIO`` of the result there): ``g'`` by the profile's
#: central differences errs ~1e-12, the split rule next to a linear table's node (a log-singular
#: ``g'``) converges algebraically, measured below 1e-7
ANNULUS_RTOL = 1e-6


def _g_prime_of(profile):
    """``g'`` of a profile as a callable on arrays (closed form, power terms, a table's node
    sums, the terms of a sum, else the profile's central differences)."""
    if profile._has("_g_prime_closed_form"):
        return profile._g_prime_closed_form
    terms = profile.power_terms()
    if terms is not None:
        ks = [(float(kappa(n)) * c * n, n) for c, n in terms]
        return lambda x: sum(k * x ** (n - 1.0) for k, n in ks) * np.ones_like(x)
    if profile.has("node_table"):
        return lambda x: profile.table_g_slope(x.ravel())[0].reshape(x.shape)
    if profile.has("terms"):
        parts = [_g_prime_of(t) for t in profile.terms]
        return lambda x: sum(p(x) for p in parts)
    from .adhesion import g_prime
    return lambda x: g_prime(profile, x)


def _cuts_of(profile) -> np.ndarray:
    """Radii where ``g'`` has a kink or jump: breakpoints, flat rim, a table's nodes, those of
    the terms of a sum."""
    cuts = [b for b in profile.breakpoints if 0 < b < np.inf]
    if 0 < profile.flat_radius < np.inf:
        cuts.append(profile.flat_radius)
    if profile.has("node_table") and getattr(profile, "_spline", None) is None:
        cuts.extend(float(v) for v in np.asarray(profile.r, float) if v > 0)
    if profile.has("terms"):
        for t in profile.terms:
            cuts.extend(_cuts_of(t))
    return np.unique(np.asarray(cuts, float))


#: cuts of ``g'`` the annulus rule splits at per annulus (an annulus narrower than
#: ``EDGE_SLIP_RATIO a`` crossing more table nodes is not this form's range)
MAX_CUTS = 4
#: stick widths ``σ_c/a`` of the linearised root beyond which the forms skip a row (they are
#: used below ``EDGE_SLIP_RATIO``; the root differs from its linearisation by ``O(σ_c/a)``)
_PREFILTER = 1e-2


class ProfileEdge:
    """``g`` near a smooth contact edge of any profile, in annulus coordinates (see above)."""

    def __init__(self, profile) -> None:
        self.profile = profile
        self.prime = _g_prime_of(profile)
        self.cuts = _cuts_of(profile)

    def rule(self, a: np.ndarray, sigma: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Offsets ``τ`` below ``a`` and weights of the Gauss–Legendre rule on ``[0, σ]`` split
        at the cuts inside ``(a − σ, a)``; ``a`` and ``σ`` broadcast, the rule adds a last
        axis."""
        a, sigma = np.broadcast_arrays(np.asarray(a, float), np.asarray(sigma, float))
        first, count = self._inside(a, sigma)
        k = int(min(count.max(initial=0), MAX_CUTS))
        ends = [np.zeros(a.shape), sigma]
        for j in range(k):          # the j-th cut inside each row's annulus (else none: σ)
            b = self.cuts[np.minimum(first + j, self.cuts.size - 1)]
            ends.append(np.where(j < count, np.clip(a - b, 0.0, sigma), sigma))
        inside = k > 0
        e = np.sort(np.stack(ends, axis=-1), axis=-1)
        left, width = e[..., :-1, None], np.diff(e, axis=-1)[..., None]
        if inside:
            # g' of a linear table is inverse-square-root singular on one side of a node:
            # τ = left + width (3t² - 2t³) makes the integrand analytic in t at both ends
            t = 0.5 * (_GL_X + 1.0)
            tau = left + width * (t * t * (3.0 - 2.0 * t))
            w = width * (3.0 * t * (1.0 - t)) * _GL_W
        else:
            tau = left + 0.5 * width * (_GL_X + 1.0)
            w = 0.5 * width * _GL_W * np.ones_like(tau)
        return tau.reshape(*a.shape, -1), w.reshape(*a.shape, -1)

    def _inside(self, a: np.ndarray, sigma: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Index of the first cut inside ``(a − σ, a)`` and the number of cuts there."""
        if self.cuts.size == 0:
            return np.zeros(a.shape, int), np.zeros(a.shape, int)
        first = np.searchsorted(self.cuts, a - sigma, side="right")
        return first, np.searchsorted(self.cuts, a, side="left") - first

    def resolved(self, a: np.ndarray, sigma: np.ndarray) -> np.ndarray:
        """Where the rule on ``[0, σ]`` splits at every cut inside (at most ``MAX_CUTS``)."""
        return self._inside(a, sigma)[1] <= MAX_CUTS

    def slope(self, x: np.ndarray) -> np.ndarray:
        with np.errstate(all="ignore"):
            return np.asarray(self.prime(np.asarray(x, float)), float)

    def drop(self, a: np.ndarray, sigma: np.ndarray) -> np.ndarray:
        """``g(a) − g(a − σ)``, m, to relative accuracy (``0 <= σ < a``); broadcast."""
        tau, w = self.rule(a, sigma)
        a = np.broadcast_to(np.asarray(a, float), np.shape(tau)[:-1])
        return np.sum(w * self.slope(a[..., None] - tau), axis=-1)

    def edge_ok(self, a: np.ndarray) -> np.ndarray:
        """Where the contact edge is smooth (``a`` beyond any flat rim, inside any wall, a
        positive finite slope there): the premise ``d = g(a)`` of the annulus forms."""
        p = self.profile
        gp = self.slope(a)
        return ((a > p.flat_radius) & (a < p.wall_radius) & np.isfinite(gp) & (gp > 0))


def edge_of(profile) -> ProfileEdge | None:
    """The :class:`ProfileEdge` of a profile, ``None`` where ``g'`` is unavailable."""
    try:
        return ProfileEdge(profile)
    except (AttributeError, NotImplementedError):       # pragma: no cover - defensive
        return None


def _newton_width(edge: ProfileEdge, a: np.ndarray, F, dF, s0: np.ndarray) -> np.ndarray:
    """Width ``σ`` (m) of a root of ``F(σ)`` by Newton from ``s0`` (6 steps, clipped to
    ``[0, a/2]``): from the linearised root Newton converges to rounding where ``σ/a`` is small,
    the range of these forms."""
    s = np.clip(s0, 0.0, 0.5 * a)
    for _ in range(6):
        d = dF(s)
        s = np.clip(s - F(s) / np.where(d != 0, d, 1.0), 0.0, 0.5 * a)
    return s


def shift_any(edge: ProfileEdge, E_star: float, G_star: float, mu: float, a: np.ndarray,
              u: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Virgin-curve dissipation (J), slip correction of the force ``2G*a|u| − F`` (N) and stick
    width ``σ_c/a`` of a shift ``|u|`` for any profile, in annulus coordinates; flat arrays.
    ``σ_c`` solves ``μE*(g(a) − g(a − σ)) = G*|u|``; ``σ_c/a`` is ``inf`` off this form's
    range (not a smooth edge)."""
    a, u = np.asarray(a, float), np.abs(np.asarray(u, float))
    ok = edge.edge_ok(a)
    aa = np.where(ok, a, a[ok][0] if np.any(ok) else 1.0)     # a valid radius: g' is defined
    y = G_star * u / (mu * E_star)
    gp = np.where(ok, edge.slope(aa), 1.0)
    ok &= y / gp < _PREFILTER * aa             # far wider than EDGE_SLIP_RATIO a: not here
    y = np.where(ok, y, 0.0)
    sig = _newton_width(edge, aa, lambda s: edge.drop(aa, s) - y,
                        lambda s: edge.slope(aa - s), y / gp)
    D, C = np.zeros(a.shape), np.zeros(a.shape)
    live = ok & (sig > 0)
    if np.any(live):
        ak = aa[live]
        tau, w = edge.rule(ak[:, None], sig[live][:, None])
        tau, w = tau[:, 0], w[:, 0]
        h = mu * E_star * edge.drop(ak[:, None], tau)
        hc = G_star * u[live][:, None]
        D[live] = 2.0 / G_star * np.sum(w * h * (hc - h), axis=1)
        C[live] = 2.0 * np.sum(w * (hc - h), axis=1)
    # g' infinite at a node met by the rule, or too many nodes inside: not this form's range
    ok &= np.isfinite(D) & np.isfinite(C) & edge.resolved(aa, sig)
    return np.maximum(D, 0.0), np.maximum(C, 0.0), np.where(ok, sig / aa, np.inf)


def torsion_any(edge: ProfileEdge, E_star: float, G_t: float, mu: float, a: np.ndarray,
                phi: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """As :func:`torsion_dissipation` (MDR springs) for any profile: dissipation (J) and
    ``σ_c/a``; the width solves ``(a − σ)φ = Q (g(a) − g(a − σ))``, ``Q = μE*/(4G_t)``."""
    a, phi = np.asarray(a, float), np.abs(np.asarray(phi, float))
    ok = edge.edge_ok(a)
    aa = np.where(ok, a, a[ok][0] if np.any(ok) else 1.0)     # a valid radius: g' is defined
    Q = mu * E_star / (4.0 * G_t)
    gp = np.where(ok, edge.slope(aa), 1.0)
    ok &= phi / (phi + Q * gp) < _PREFILTER
    phi = np.where(ok, phi, 0.0)
    sig = _newton_width(edge, aa, lambda s: (aa - s) * phi - Q * edge.drop(aa, s),
                        lambda s: -phi - Q * edge.slope(aa - s), aa * phi / (phi + Q * gp))
    D = np.zeros(a.shape)
    live = ok & (sig > 0)
    if np.any(live):
        ak, pk = aa[live], phi[live]
        tau, w = edge.rule(ak[:, None], sig[live][:, None])
        tau, w = tau[:, 0], w[:, 0]
        us = Q * edge.drop(ak[:, None], tau)
        D[live] = 16.0 * G_t * np.sum(w * us * ((ak[:, None] - tau) * pk[:, None] - us), axis=1)
    ok &= np.isfinite(D) & edge.resolved(aa, sig)
    return np.maximum(D, 0.0), np.where(ok, sig / aa, np.inf)


def _slip_any(edge: ProfileEdge, E_star: float, a: np.ndarray, sigma: np.ndarray) -> np.ndarray:
    """As :func:`_slip_function` for any profile: ``P(a − σ) = (E*/π) ∫_0^σ g'(t) K(m_t)/t dτ``,
    ``t = a − τ``; broadcast, the rule adds a last axis."""
    from scipy.special import ellipk
    a, sigma = np.broadcast_arrays(np.asarray(a, float), np.asarray(sigma, float))
    tau, w = edge.rule(a, sigma)
    t = a[..., None] - tau
    m = (sigma[..., None] - tau) * (2.0 * a[..., None] - sigma[..., None] - tau) / (t * t)
    return E_star / np.pi * np.sum(w * edge.slope(t) / t * ellipk(m), axis=-1)


def exact_torsion_any(edge: ProfileEdge, E_star: float, G_t: float, mu: float, a: np.ndarray,
                      phi: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """As :func:`exact_torsion_dissipation` (Jäger's exact solution) for any profile:
    dissipation (J), the torque's slip correction ``(16/3)G_t φ a³ − M =
    8∫_c^a x² (2G_tφ − μP(x)) dx`` (N m) and ``σ_c/a``; flat arrays. ``σ_c`` solves
    ``P(σ_c) = 2G_tφ/μ`` by the fixed point ``σ ← σ P*/P(σ)`` from the edge slope
    ``P ≈ E* g'(a) σ/(2a)``."""
    a, phi = np.asarray(a, float), np.abs(np.asarray(phi, float))
    ok = edge.edge_ok(a)
    aa = np.where(ok, a, a[ok][0] if np.any(ok) else 1.0)     # a valid radius: g' is defined
    target = 2.0 * G_t * phi / mu
    slope = np.where(ok, 0.5 * E_star * edge.slope(aa) / aa, 1.0)
    ok &= target / slope < _PREFILTER * aa
    target = np.where(ok, target, 0.0)
    sig = np.minimum(target / slope, 0.5 * aa)
    for _ in range(8):
        P = _slip_any(edge, E_star, aa, sig)
        sig = np.minimum(np.where(P > 0, sig * target / np.where(P > 0, P, 1.0), 0.0), 0.5 * aa)
    D, C = np.zeros(a.shape), np.zeros(a.shape)
    live = ok & (sig > 0)
    if np.any(live):
        ak = aa[live]
        tau, w = edge.rule(ak[:, None], sig[live][:, None])
        tau, w = tau[:, 0], w[:, 0]
        P = _slip_any(edge, E_star, ak[:, None], tau)
        x = ak[:, None] - tau
        tk = target[live][:, None]
        D[live] = 4.0 * mu * mu / G_t * np.sum(w * x * x * P * (tk - P), axis=1)
        C[live] = 8.0 * mu * np.sum(w * x * x * (tk - P), axis=1)
    ok &= np.isfinite(D) & np.isfinite(C) & edge.resolved(aa, sig)
    return np.maximum(D, 0.0), np.maximum(C, 0.0), np.where(ok, sig / aa, np.inf)
