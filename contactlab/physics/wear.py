"""Fretting wear on a radial grid: Archard's law on the 3D profile with the 3D slip.

Kernels for :func:`contactlab.effects.wear.wear` (theory and sources in docs/fretting.md). The
profile is a piecewise-linear table ``f_j`` on the uniform grid ``r_j = jΔ``; every operator
below is the exact transform of a piecewise-linear function on that grid, precomputed once as a
matrix (:func:`operators`):

* ``T``: MDR transform of the table slopes, ``g(x_i) = x_i Σ_j s_j [asin(min(r_{j+1},x_i)/x_i)
  - asin(min(r_j,x_i)/x_i)]`` [physics: piecewise-linear row of the transform table];
* ``Pm``: 3D pressure from the 1D displacement ``u = (d - g)_+``,
  ``p(r) = -(E*/π) ∫_r u'(x) dx / sqrt(x² - r²)``;
* ``A``: 3D displacement from a 1D one, ``w(r) = (2/π) ∫_0^r w_1D(x) dx / sqrt(r² - x²)``
  (tangential slip: the slip of the 3D surface is this transform of the spring slip);
* ``KP``: Jäger's slip function ``P(x) = ∫_x^a p(s) ds / sqrt(s² - x²)
  = -(E*/π) ∫_x^a u'(y) K(sqrt(1 - x²/y²)) dy / y`` (order of integration swapped; K complete
  elliptic of the first kind), which gives the slip angle ``θ_s = μP/(2G_t)`` of the exact
  torsion's Jenkins elements;
* ``B``: 3D torsional slip from the twist distribution ``Φ = (φ - θ_s)_+``,
  ``s(r) = φr - u_φ(r) = (4/(πr)) ∫_0^r Φ(t) t² dt / sqrt(r² - t²)`` (Jäger's flat-punch
  superposition for ``u_φ``, integrated by parts; docs/fretting.md);
* ``v``: volume weights, ``∫ 2πr h dr`` of the piecewise-linear ``h``.

Per cycle of a steady loop (Masing) every point slides ``4 s_load(r)``, four times its slip under
monotonic loading to the amplitude. No function here validates input (hot path).
"""
from __future__ import annotations

import numpy as np

__all__ = ["operators", "normal_depth", "contact_radius", "tangential_rate", "torsion_rate",
           "first_crossing", "tensile_fraction"]

_GL = np.polynomial.legendre.leggauss(8)


def operators(radius: float, n: int) -> dict[str, np.ndarray]:
    """Matrices of the grid ``r_j = j radius/n``, ``j = 0..n`` (see the module docstring)."""
    r = np.linspace(0.0, radius, n + 1)
    D = r[1] - r[0]
    lo, hi = r[:-1], r[1:]                          # cells
    X = r[:, None]
    # T: slopes (n cells) -> g at nodes
    with np.errstate(divide="ignore", invalid="ignore"):
        Xs = np.where(X > 0, X, 1.0)
        T = X * (np.arcsin(np.minimum(hi[None, :], X) / Xs)
                 - np.arcsin(np.minimum(lo[None, :], X) / Xs))
    T[0] = 0.0
    # Pm: slopes of u (n cells) -> p at nodes j >= 1 (without the factor -E*/π)
    with np.errstate(divide="ignore", invalid="ignore"):
        Rs = np.where(X > 0, X, 1.0)
        Pm = (np.arccosh(np.maximum(hi[None, :] / Rs, 1.0))
              - np.arccosh(np.maximum(lo[None, :] / Rs, 1.0)))
    Pm[0] = 0.0
    # A: nodal 1D values -> (2/π)∫_0^r w/sqrt(r²-x²) at nodes; cells fully below r
    A = np.zeros((n + 1, n + 1))
    Bm = np.zeros((n + 1, n + 1))
    rr = r[:, None]
    below = hi[None, :] <= rr + 0.5 * D * 1e-9
    with np.errstate(divide="ignore", invalid="ignore"):
        rsafe = np.where(rr > 0, rr, 1.0)

        def J(t):
            q = np.clip(t / rsafe, -1.0, 1.0)
            root = np.sqrt(np.maximum(rr * rr - t * t, 0.0))
            J0 = np.arcsin(q)
            J1 = -root
            J2 = 0.5 * rr * rr * J0 - 0.5 * t * root
            J3 = -rr * rr * root + root**3 / 3.0
            return J0, J1, J2, J3
        a0, a1, a2, a3 = J(hi[None, :])
        b0, b1, b2, b3 = J(lo[None, :])
    I0, I1, I2, I3 = a0 - b0, a1 - b1, a2 - b2, a3 - b3
    xl, xh = lo[None, :], hi[None, :]
    L_abel = (xh * I0 - I1) / D
    R_abel = (I1 - xl * I0) / D
    L_tor = (xh * I2 - I3) / D         # ∫ t²/sqrt(r²-t²) times the hat functions
    R_tor = (I3 - xl * I2) / D
    for M, L, R in ((A, L_abel, R_abel), (Bm, L_tor, R_tor)):
        L = np.where(below, L, 0.0)
        R = np.where(below, R, 0.0)
        M[:, :-1] += L
        M[:, 1:] += R
    A *= 2.0 / np.pi
    Bm *= 4.0 / (np.pi * np.where(r > 0, r, 1.0))[:, None]
    A[0] = 0.0
    Bm[0] = 0.0
    # KP: slopes of u -> ∫_x^... u'(y) K(1 - x²/y²)/y dy (without -E*/π), x = nodes j >= 1
    from scipy.special import ellipk    # on first use: importing scipy.special costs ~0.1 s
    u, w = _GL
    KP = np.zeros((n + 1, n))
    for j in range(1, n + 1):           # one row per node: O(n) work each, vectorised inside
        cells = np.arange(j, n)
        if cells.size == 0:
            continue
        y = lo[cells, None] + D * 0.5 * (u[None, :] + 1.0)
        m = 1.0 - (r[j] / y) ** 2
        KP[j, cells] = 0.5 * D * np.sum(w[None, :] * ellipk(m) / y, axis=1)
    # volume weights of the piecewise-linear h, and 1D trapezoid weights
    v = np.zeros(n + 1)
    v[:-1] += 2 * np.pi * D * (lo / 2 + D / 6)
    v[1:] += 2 * np.pi * D * (lo / 2 + D / 3)
    w1 = np.full(n + 1, D)
    w1[0] = w1[-1] = D / 2
    return {"r": r, "dr": D, "T": T, "Pm": Pm, "A": A, "B": Bm, "KP": KP, "v": v, "w1": w1}


def transform(ops: dict, f: np.ndarray) -> np.ndarray:
    """``g`` at the nodes of the piecewise-linear profile ``f`` (exact)."""
    return ops["T"] @ (np.diff(f) / ops["dr"])


def normal_depth(g: np.ndarray, w1: np.ndarray, E_star: float, F: float) -> float:
    """Depth ``d`` with ``2E* Σ w1 (d - g)_+ = F`` (exact for the nodal positive part)."""
    order = np.argsort(g, kind="stable")
    gs, ws = g[order], w1[order]
    # force at d = gs[k]: only nodes below it push, F_k = 2E* (gs_k W_k - S_k) with the
    # exclusive running sums W_k = Σ_{i<k} w_i, S_k = Σ_{i<k} w_i g_i (O(n log n), not O(n²))
    W = np.concatenate(([0.0], np.cumsum(ws[:-1])))
    S = np.concatenate(([0.0], np.cumsum(ws[:-1] * gs[:-1])))
    Fk = 2.0 * E_star * np.maximum(gs * W - S, 0.0)
    k = int(np.searchsorted(Fk, F))
    if k == 0:
        return float(gs[0])
    if k >= gs.size:
        raise OverflowError("normal force beyond the grid")
    slope = (Fk[k] - Fk[k - 1]) / (gs[k] - gs[k - 1]) if gs[k] > gs[k - 1] else np.inf
    return float(gs[k - 1] + (F - Fk[k - 1]) / slope)


def first_crossing(x: np.ndarray, y: np.ndarray) -> float:
    """Smallest ``x`` at which ``y`` (decreasing from >= 0) becomes negative, interpolated; 0 if
    ``y[0] < 0``, ``x[-1]`` if never."""
    neg = np.flatnonzero(y < 0)
    if neg.size == 0:
        return float(x[-1])
    k = int(neg[0])
    if k == 0:
        return 0.0
    return float(x[k - 1] + (x[k] - x[k - 1]) * y[k - 1] / (y[k - 1] - y[k]))


def contact_radius(r: np.ndarray, u: np.ndarray) -> float:
    """Outer edge of the region ``u > 0``, interpolated."""
    pos = np.flatnonzero(u > 0)           # u = d - g, not clipped
    if pos.size == 0:
        return 0.0
    k = int(pos[-1])
    if k + 1 >= u.size:
        return float(r[-1])
    return float(r[k] + (r[k + 1] - r[k]) * u[k] / (u[k] - u[k + 1]))


def tensile_fraction(ops: dict, g: np.ndarray, d: float, E_star: float) -> float:
    """Tensile load of the MDR pressure of ``u = (d - g)_+`` relative to its compressive load.

    Zero (to rounding) while ``g`` rises monotonically over the contact; a worn profile whose
    ``g`` dips (a proud, unworn island in the middle of a scar) makes the 1D contact region
    disconnected, the back-transformed pressure turns tensile, and the MDR no longer describes
    the 3D contact (docs/fretting.md, gross slip under torsion).
    """
    u = np.maximum(d - g, 0.0)
    p = -(E_star / np.pi) * (ops["Pm"] @ (np.diff(u) / ops["dr"]))
    p[0] = p[1]
    push = float(ops["v"] @ np.maximum(p, 0.0))
    return float(-(ops["v"] @ np.minimum(p, 0.0)) / push) if push > 0 else 0.0


def _pressure(ops: dict, u: np.ndarray, E_star: float) -> np.ndarray:
    return np.maximum(-(E_star / np.pi) * (ops["Pm"] @ (np.diff(u) / ops["dr"])), 0.0)


def _extrapolate_axis(q: np.ndarray) -> np.ndarray:
    """``q(0)`` from the even extension (the axis node carries a log singularity of the
    discrete pressure): ``q_0 = (4 q_1 - q_2)/3``, clipped at 0."""
    q = q.copy()
    q[0] = max((4.0 * q[1] - q[2]) / 3.0, 0.0) if q.size > 2 else q[1]
    return q


def _window(ops: dict, g: np.ndarray, d: float) -> dict:
    """The operators on the leading nodes ``0..L-1`` that hold the contact and two nodes beyond
    its edge: every rate beyond is zero, and the operators that map the contact's ``u`` to the
    rates inside need no node beyond (``A``, ``B`` act on nodes below the radius, ``Pm``, ``KP``
    on the slopes of ``u``, zero beyond). Same values as the full grid up to rounding."""
    inside = np.flatnonzero(d - g > 0)
    n1 = ops["r"].size
    L = n1 if inside.size == 0 else min(n1, int(inside[-1]) + 3)
    if L >= n1:
        return ops
    out = {"r": ops["r"][:L], "dr": ops["dr"], "Pm": ops["Pm"][:L, :L - 1],
           "KP": ops["KP"][:L, :L - 1], "A": ops["A"][:L, :L], "B": ops["B"][:L, :L]}
    return out


def _embed(q: np.ndarray, n1: int) -> np.ndarray:
    if q.size == n1:
        return q
    out = np.zeros(n1)
    out[:q.size] = q
    return out


def tangential_rate(ops: dict, g: np.ndarray, d: float, E_star: float, G_star: float,
                    mu: float, delta: float, window: bool = False
                    ) -> tuple[np.ndarray, float, float]:
    """``q = p s_load`` at the nodes (Pa·m), stick radius and contact radius, m.

    Springs slide ``(δ - μE* u/G*)_+`` (independent Jenkins elements, Cattaneo–Mindlin through
    the MDR); the 3D slip is its Abel transform ``A``. ``window=True`` works on the nodes the
    contact covers only (:func:`_window`: the same values up to rounding, not the same bits).
    """
    r_all = ops["r"]
    a = contact_radius(r_all, d - g)
    if window:
        ops = _window(ops, g, d)
        g = g[:ops["r"].size]
    u = np.maximum(d - g, 0.0)
    p = _pressure(ops, u, E_star)
    s1 = np.maximum(delta - mu * E_star * u / G_star, 0.0)
    s3 = np.maximum(ops["A"] @ s1, 0.0)
    r = ops["r"]
    c = first_crossing(r, mu * E_star * u - G_star * delta)
    return _embed(_extrapolate_axis(p * s3), r_all.size), c, a


def torsion_rate(ops: dict, g: np.ndarray, d: float, E_star: float, G_t: float, mu: float,
                 phi: float, method: str, window: bool = False
                 ) -> tuple[np.ndarray, float, float]:
    """``q = p s_load`` at the nodes (Pa·m), stick radius and contact radius, m.

    ``method="exact"``: Jäger's Jenkins elements, slip angle ``θ_s = μP(x)/(2G_t)``;
    ``"mdr"``: the MDR springs, ``θ_s = μE* u(x)/(4G_t x)``. The twist distribution
    ``Φ = (φ - θ_s)_+`` gives the 3D slip through ``B``. ``window``: as in
    :func:`tangential_rate`.
    """
    r_all = ops["r"]
    a = contact_radius(r_all, d - g)
    if window:
        ops = _window(ops, g, d)
        g = g[:ops["r"].size]
    u = np.maximum(d - g, 0.0)
    p = _pressure(ops, u, E_star)
    r = ops["r"]
    theta = np.full(r.shape, np.inf)
    if method == "exact":
        P = -(E_star / np.pi) * (ops["KP"] @ (np.diff(u) / ops["dr"]))
        theta[1:] = mu * P[1:] / (2.0 * G_t)
    else:
        theta[1:] = mu * E_star * u[1:] / (4.0 * G_t * r[1:])
    Phi = np.maximum(phi - theta, 0.0)
    s3 = np.maximum(ops["B"] @ Phi, 0.0)
    c = first_crossing(r, np.where(np.isfinite(theta), theta - phi, 1.0))
    return _embed(_extrapolate_axis(p * s3), r_all.size), c, a
