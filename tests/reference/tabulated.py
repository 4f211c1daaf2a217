"""The MDR transform of piecewise-linear tables from its definition (independent re-implementation).

g(x) = |x| ∫_0^|x| f'(r)/sqrt(x²-r²) dr summed in closed form per interval (f' constant there) and,
separately, by scipy quad; the pressure shape and the outside displacement by quad of the MDR
formulas. Source: V. L. Popov, M. Heß, MDR, Springer 2015, eqs. (3.7), (3.12), (3.13) [PH].
Nothing here imports contactlab.
"""
from __future__ import annotations

import numpy as np
from scipy import integrate

def table_g_sum(r: np.ndarray, f: np.ndarray, x: np.ndarray) -> np.ndarray:
    """theory §2 table row: g(x) = x Σ_i s_i [asin(min(r_{i+1},x)/x) - asin(r_i/x)], r_i < x.

    ``r`` must start at 0 (prepend the flat extension before calling). Vectorised over ``x``.
    """
    s = np.diff(f) / np.diff(r)
    x = np.atleast_1d(np.asarray(x, float))
    out = np.empty(x.size)
    for j, xj in enumerate(x):          # a loop over a handful of reference points only
        lo, hi = r[:-1], np.minimum(r[1:], xj)
        m = lo < xj
        out[j] = xj * np.sum(s[m] * (np.arcsin(hi[m] / xj) - np.arcsin(lo[m] / xj)))
    return out


def table_g_quad(r: np.ndarray, f: np.ndarray, x: float) -> float:
    """g(x) = x ∫_0^{π/2} f'(x sinθ) dθ by scipy quad, split at θ_i = asin(r_i/x)."""
    s = np.diff(f) / np.diff(r)
    cuts = [0.0] + [float(np.arcsin(ri / x)) for ri in r[1:-1] if ri < x] + [0.5 * np.pi]
    total = 0.0
    for t0, t1 in zip(cuts[:-1], cuts[1:]):
        k = min(int(np.searchsorted(r, x * np.sin(0.5 * (t0 + t1)), side="right") - 1), s.size - 1)
        total += s[k] * (t1 - t0)        # f' is constant on each θ piece
    # and the independent quad check of the same integral (piecewise-constant integrand)
    q, _ = integrate.quad(lambda th: s[min(int(np.searchsorted(r, x * np.sin(th), side="right") - 1),
                                           s.size - 1)],
                          0.0, 0.5 * np.pi, points=cuts[1:-1] or None, limit=500, epsabs=0,
                          epsrel=1e-13)
    assert abs(q - total) <= 1e-10 * abs(total)
    return x * total


def table_g_integral_quad(r: np.ndarray, f: np.ndarray, a: float) -> float:
    """∫_0^a g dx = ∫_0^a f'(t) sqrt(a²-t²) dt by scipy quad on each table interval."""
    s = np.diff(f) / np.diff(r)
    total = 0.0
    for i in range(s.size):
        lo, hi = r[i], min(r[i + 1], a)
        if lo >= a:
            break
        total += s[i] * integrate.quad(lambda t: np.sqrt(a * a - t * t), lo, hi, epsabs=0,
                                       epsrel=1e-13)[0]
    return total


def table_pressure_shape_quad(r: np.ndarray, f: np.ndarray, rr: float, a: float) -> float:
    """S(r, a) = ∫_r^a g'(x)/sqrt(x²-r²) dx of the table, by parts so only g is needed:
    S = (g(a)-g(r))/sqrt(a²-r²) + ∫_r^a (g(x)-g(r)) x/(x²-r²)^{3/2} dx (scipy quad, split at
    the nodes; the integrand is bounded at x = r because g is smooth just above r off-node)."""
    g_r = table_g_sum(r, f, np.array([rr]))[0]
    g_a = table_g_sum(r, f, np.array([a]))[0]
    pts = [float(x) for x in r if rr < x < a]

    def integrand(x):
        return (table_g_sum(r, f, np.array([x]))[0] - g_r) * x / (x * x - rr * rr) ** 1.5

    # substitute x = r + t² near the lower end to tame the (x-r)^{-1/2} behaviour
    def sub(t):
        x = rr + t * t
        return integrand(x) * 2 * t
    edges = [0.0] + [np.sqrt(p - rr) for p in pts] + [np.sqrt(a - rr)]
    total = sum(integrate.quad(sub, e0, e1, epsabs=0, epsrel=1e-12, limit=200)[0]
                for e0, e1 in zip(edges[:-1], edges[1:]))
    return (g_a - g_r) / np.sqrt(a * a - rr * rr) + total


def table_abel_outside_quad(r: np.ndarray, f: np.ndarray, rr: float, a: float) -> float:
    """(2/π) ∫_0^a g(x)/sqrt(r²-x²) dx for r > a (scipy quad split at the nodes)."""
    pts = [0.0] + [float(x) for x in r if 0 < x < a] + [a]
    total = sum(integrate.quad(lambda x: table_g_sum(r, f, np.array([x]))[0] / np.sqrt(rr * rr - x * x),
                               e0, e1, epsabs=0, epsrel=1e-12, limit=200)[0]
                for e0, e1 in zip(pts[:-1], pts[1:]))
    return 2 / np.pi * total


def spline_pressure_shape_quad(r: np.ndarray, f: np.ndarray, rr: float, a: float,
                               axis: str = "even") -> float:
    """S(r, a) = ∫_r^a g'(x)/sqrt(x²-r²) dx of the cubic spline of the table (scipy
    ``CubicSpline``; ``axis="even"``: f'(0) = 0 on the axis and not-a-knot at the outer end, as
    ``Tabulated``'s default; ``"free"``: not-a-knot at both ends), by nested scipy quad: ``g'(x) = ∫_0^{π/2} [f'(t) + t f''(t)]_{t = x sinθ}
    dθ`` (from g = x ∫_0^{π/2} f'(x sinθ) dθ), split at the nodes in θ, and S in ``u =
    arccosh(x/r)``, split at the nodes."""
    from scipy.interpolate import CubicSpline
    sp = CubicSpline(r, f - f[0], bc_type=((1, 0.0), "not-a-knot") if axis == "even"
                     else "not-a-knot")
    d1, d2 = sp.derivative(1), sp.derivative(2)

    def g_prime(x: float) -> float:
        cuts = [0.0] + [float(np.arcsin(b / x)) for b in r if 0 < b < x] + [np.pi / 2]

        def h(t: float) -> float:
            y = x * np.sin(t)
            return float(d1(y) + y * d2(y))
        return sum(integrate.quad(h, p0, p1, epsabs=0, epsrel=1e-13)[0]
                   for p0, p1 in zip(cuts[:-1], cuts[1:]) if p1 > p0)

    us = [0.0] + [float(np.arccosh(b / rr)) for b in r if rr < b < a] + [float(np.arccosh(a / rr))]
    return sum(integrate.quad(lambda u: g_prime(rr * np.cosh(u)), u0, u1, epsabs=0,
                              epsrel=1e-12)[0] for u0, u1 in zip(us[:-1], us[1:]))
