"""Validity limits of the MDR torsion model: the exact twist at a given stick ratio ``c/a``
[S eq. 53], ``φ = μ/(2G_t) P(c)``, at bounded cost on large tables.

The exact slip function (:func:`contactlab.physics.torsion_exact.slip_function`) integrates a
large table segment by segment: g at 8 nodes per table segment below the contact radius, each g
costing O(table nodes) (sums over the nodes below it), so O(N²) on an N-point table (hours at
N = 10^6). A validity limit needs no such resolution: it is compared with a path's largest
twist, against a threshold known to two digits (c/a = 0.83 for 1 % of torque). Tables with more
than :data:`BOUNDED_TABLE_NODES` nodes below the largest contact radius therefore take a fixed
16-point Gauss-Legendre rule over ``[c, a]`` of the same by-parts integrand

    P(c) = (E*/π) [ (g(a)-g(c)) K(k_a)/a + ∫_c^a (g(t)-g(c)) (K-E)(k_t)/(k_t² t²) dt
                    + (d - g(a)) K(k_a)/a ],   k_t² = 1 - c²/t²,

which is smooth for ``c/a`` bounded away from 0 (the kernel is ``π/4`` at ``t = c`` and
``(K-E)/k²`` of ``k² <= 1 - (c/a)²`` at ``t = a``): 17 evaluations of g per limit, whatever the
table's size. Its agreement with the exact slip function on tables of 2000 to 10^4 points (linear
and cubic, uniform and random spacing) is tested (tests/unit/physics/test_torsion_validity.py).
Every other profile, and smaller tables, take the exact slip function.
"""
from __future__ import annotations

import functools

import numpy as np

from . import torsion_exact as _exact

__all__ = ["BOUNDED_TABLE_NODES", "BOUNDED_WORK", "twist_at_stick_ratio", "slip_function_bounded",
           "uses_bounded_rule", "affordable_states", "screen_twist_at_stick_ratio"]

#: tables with more nodes than this below the largest contact radius take the bounded rule
#: (the exact route then costs ~8 N² evaluations of a node sum: 0.1 s at N = 2000)
BOUNDED_TABLE_NODES = 2000
#: node terms (evaluations of g times table nodes below them) one validity limit may cost on a
#: large table: :func:`affordable_states` caps the number of distinct normal states judged so
#: that a limit costs at most this (~0.4 s linear, ~1.5 s cubic on a 10^6-point table)
BOUNDED_WORK = 6e7
#: order of the bounded rule over ``[c, a]``
_GL_ORDER = 16
_U, _W = np.polynomial.legendre.leggauss(_GL_ORDER)
_U = 0.5 * (_U + 1.0)
_W = 0.5 * _W


def uses_bounded_rule(profile, a_max: float) -> bool:
    """Whether limits up to contact radius ``a_max`` (m) take :func:`slip_function_bounded`."""
    if not profile.has("node_table"):
        return False
    nodes = profile.table_nodes()
    return int(np.searchsorted(nodes, a_max, side="left")) > BOUNDED_TABLE_NODES


def affordable_states(profile, a_max: float, wanted: int, least: int = 3) -> int:
    """How many distinct normal states (up to ``a_max``, m) a validity limit evaluates: ``wanted``,
    or on a table taking the bounded rule as many as :data:`BOUNDED_WORK` allows (at least
    ``least``)."""
    if not uses_bounded_rule(profile, a_max):
        return wanted
    below = int(np.searchsorted(profile.table_nodes(), a_max, side="left"))
    return max(least, min(wanted, int(BOUNDED_WORK // ((_GL_ORDER + 1) * below))))


def slip_function_bounded(profile, E_star: float, x: np.ndarray, a: np.ndarray, d: np.ndarray,
                          g_a: np.ndarray) -> np.ndarray:
    """Jäger's slip function ``P(x)`` (Pa) by the fixed 16-point rule over ``[x, a]`` (flat
    arrays, ``0 < x <= a``; for ``x/a`` bounded away from 0, as at a validity stick ratio)."""
    x, a, d, g_a = (np.asarray(v, float).ravel() for v in (x, a, d, g_a))
    t = x[:, None] + (a - x)[:, None] * _U
    g = profile._g(np.concatenate((x, t.ravel())))
    g_x, g_t = g[:x.size], g[x.size:].reshape(t.shape)
    Ka = _exact.K_comp((x / a) ** 2)
    val = (g_a - g_x) * Ka / a + (d - g_a) * Ka / a
    f = (g_t - g_x[:, None]) * _exact.kme_over_m((x[:, None] / t) ** 2) / (t * t)
    val += (a - x) * (f @ _W)
    return E_star / np.pi * val


def twist_at_stick_ratio(profile, E_star: float, G_t: float, mu: float, ratio: float,
                         a: np.ndarray, d: np.ndarray, g_a: np.ndarray, rtol: float) -> np.ndarray:
    """Exact twist (rad) at which the stick radius of a contact at normal state
    ``(a, d, g(a))`` (flat arrays, m) falls to ``ratio * a`` (``inf`` without contact): one slip
    function per distinct state, by the bounded rule on large tables (module docstring)."""
    out = np.full(a.shape, np.inf)
    live = a > 0
    if not np.any(live):
        return out
    keys, inv = np.unique(np.stack([a[live], d[live], g_a[live]], axis=1), axis=0,
                          return_inverse=True)
    ka, kd, kg = keys.T
    if uses_bounded_rule(profile, float(ka.max())):
        P = slip_function_bounded(profile, E_star, ratio * ka, ka, kd, kg)
    else:
        P, _ = _exact.slip_function(profile, E_star, ratio * ka, ka, kd, kg, rtol)
    out[live] = _exact.twist_of_stick(mu, G_t, P)[inv.ravel()]
    return out


#: orders of the two fixed rules of :func:`screen_twist_at_stick_ratio`
_SCREEN_ORDERS = (16, 32)
#: safety factor on the difference of the two rules (the error bound of the screen), and the
#: bound's floor (relative)
_SCREEN_SAFETY, _SCREEN_FLOOR = 100.0, 1e-8


@functools.lru_cache(maxsize=16)
def _screen_weights(ratio: float, order: int) -> tuple[np.ndarray, np.ndarray]:
    """Nodes ``τ_j`` (``t = a τ_j``) and weights ``ω_j`` of the screen's rule over ``[c, a]``,
    ``c = ratio a``: ``x/t = ratio/τ_j`` does not depend on ``a``, so the elliptic kernel is the
    same for every normal state and is folded into the weights once."""
    u, w = np.polynomial.legendre.leggauss(order)
    u, w = 0.5 * (u + 1.0), 0.5 * w
    tau = ratio + (1.0 - ratio) * u
    return tau, w * _exact.kme_over_m((ratio / tau) ** 2) * (1.0 - ratio) / (tau * tau)


def screen_twist_at_stick_ratio(profile, E_star: float, G_t: float, mu: float, ratio: float,
                                a: np.ndarray, d: np.ndarray
                                ) -> tuple[np.ndarray, np.ndarray] | None:
    """A cheap estimate of :func:`twist_at_stick_ratio` and a bound on its relative error, for
    screening many normal states; ``None`` for profiles it does not serve.

    The slip function's by-parts form (module docstring) with ``x = ratio a`` reads
    ``P = E*/(π a) [(d - g(x)) K(ratio²) + Σ_j ω_j (g(a τ_j) - g(x))]``: g at the rule's
    nodes per state, no elliptic function per state. Two Gauss-Legendre rules (16 and 32
    points); the bound is 100 times their difference (plus 1e-8), valid where g is smooth on
    ``[c, a]``: profiles without breakpoints, flat part, wall or table nodes (power laws,
    spheres, polynomials and their sums). Returns ``(twist, bound)`` (``inf`` and 0 without
    contact).
    """
    if (profile.breakpoints or profile.flat_radius > 0 or np.isfinite(profile.wall_radius)
            or profile.has("node_table") or profile.has("linear_table")):
        return None
    a = np.asarray(a, float).ravel()
    d = np.asarray(d, float).ravel()
    out = np.full(a.shape, np.inf)
    bound = np.zeros(a.shape)
    live = np.flatnonzero(a > 0)
    if not live.size:
        return out, bound
    al, dl = a[live], d[live]
    Kr = float(_exact.K_comp(np.array(ratio * ratio)))
    terms = profile.power_terms()
    vals = []
    if terms is not None and len(terms) == 1:
        # g = K x^n: P = E* K a^(n-1)/π [(δ - r^n) K(r²) + Σ ω_j (τ_j^n - r^n)], δ = d/(K a^n)
        cK, n = (float(v) for v in terms[0])
        K = profile._power_kappa(n) * cK
        Kan = K * al ** n
        delta = dl / Kan
        for order in _SCREEN_ORDERS:
            tau, om = _screen_weights(ratio, order)
            vals.append(Kan * ((delta - ratio ** n) * Kr + float((tau ** n - ratio ** n) @ om)))
    else:
        x = ratio * al
        g_x = profile._g(x)
        for order in _SCREEN_ORDERS:
            tau, om = _screen_weights(ratio, order)
            g_t = profile._g((al[:, None] * tau).ravel()).reshape(al.size, order)
            vals.append((dl - g_x) * Kr + np.sum((g_t - g_x[:, None]) * om, axis=1))
    P = E_star / np.pi * vals[1] / al
    with np.errstate(divide="ignore", invalid="ignore"):
        rel = np.abs(vals[1] - vals[0]) / np.abs(vals[1])
    out[live] = _exact.twist_of_stick(mu, G_t, P)
    bound[live] = np.where(np.isfinite(rel), _SCREEN_SAFETY * rel + _SCREEN_FLOOR, np.inf)
    return out, bound
