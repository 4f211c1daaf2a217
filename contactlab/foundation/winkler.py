"""The Winkler (independent-spring) MDR foundation with Jenkins stick/slip elements.

Each cell ``[b_i, b_{i+1}]`` lumps the springs of ``±x`` in it [H1, PH; theory §3, §5, §6.4]:

* normal: compression ``d - g(x)``; cell force ``2E* S_i`` with ``S_i = ∫_cell (d - g)_+ dx``
  integrated exactly (so the normal force is exact at any N);
* tangential (springs ``G*Δx``): element force ``f_i``, stiffness ``2G* w_i``, slip limit
  ``μ · 2E* S_i``;
* torsional (springs ``8G_tΔx``, ``μ* = 2μ``): element torque ``m_i``, stiffness
  ``16 G_t ∫_cell x² dx``, slip limit ``4μE* ∫_cell x (d - g)_+ dx`` (the cell's share of
  ``M = (16/3) G_t a³ φ`` without slip and of ``4μE*∫x(d-g)`` at full slip).

Elements are incremental Jenkins elements: ``f ← clip(f + k_eff Δu, -L, L)``. The stiffness of a
cell is weighted by the part of it in contact during the step (``ΔS/(w Δd)``, exact when the
displacement varies linearly with the depth within the step), so springs entering contact carry
only the displacement accumulated after they touched, and springs leaving contact release theirs
(``L → 0``). The dissipated energy is ``Σ slip × limit``.
"""
from __future__ import annotations

import functools
from dataclasses import dataclass

import numpy as np

from . import _compiled
from ._compiled import jenkins_update

from ..numeric.powers import WHOLE_POWERS, power_integral
from ..numeric.quadrature import tanh_sinh
from .base import Foundation
from ..errors import OutsideTheoryError


def _check_stiffness(K: np.ndarray, radius: float) -> None:
    """Cell stiffnesses must be finite and > 0 (a contact radius of ~1e-100 m makes b³ underflow)."""
    if not (K.min() > 0 and np.isfinite(K.max())):     # (a NaN fails the first test)
        raise OutsideTheoryError(f"the path's largest contact radius {radius!r} m is outside double "
                                 "precision for the spring foundation (cell stiffnesses underflow "
                                 "to 0 or overflow): load the contact further or use the closed-form "
                                 "routes (normal(), torsion()).")

__all__ = ["Winkler", "SpringState", "xg_integral"]


def _gint(profile, x: np.ndarray) -> np.ndarray:
    x = np.asarray(x, float)
    return np.where(x > 0, profile._g_integral(np.maximum(x, 1e-300)), 0.0)


def _edge_integrals(profile, a: np.ndarray, rtol: float, tor: bool
                    ) -> tuple[np.ndarray, np.ndarray]:
    """``(∫_0^a g, ∫_0^a x g)`` of the contact radii of a run of steps (the second only with
    ``tor``, else the first again). A single power term ``c r^n`` (no wall) with every radius
    > 0 (a gait) takes ``κ_n c a^(n+1)/(n+1)`` and ``κ_n c a^(n+2)/(n+2)`` in place: the same
    operations as :func:`_gint` and :func:`xg_integral` (bit-identical), without their masks,
    error estimates and temporaries."""
    terms = profile.power_terms()
    if (terms is not None and len(terms) == 1 and not np.isfinite(profile.wall_radius)
            and a.size and float(np.min(a)) > 0):
        c, n = terms[0]
        kn = [(profile._power_kappa(n) * c, n)]
        Ga = power_integral(a, kn, 1.0)
        return Ga, (power_integral(a, kn, 2.0) if tor else Ga)
    Ga = _gint(profile, a)
    return Ga, (xg_integral(profile, a, rtol) if tor else Ga)


def _whole_power_term(profile, tor: bool) -> tuple[float, float, float] | None:
    """``(κ_n c, n + 1, n + 2)`` when the profile is one power term ``c r^n`` (no wall) whose
    edge integrals :func:`~contactlab.numeric.powers.power` takes by multiplication (``n + 1``
    and, with torsion, ``n + 2`` whole, at most 4), else None."""
    terms = profile.power_terms()
    if terms is None or len(terms) != 1 or np.isfinite(profile.wall_radius):
        return None
    c, n = (float(v) for v in terms[0])
    if n + 1.0 not in WHOLE_POWERS or (tor and n + 2.0 not in WHOLE_POWERS):
        return None
    return profile._power_kappa(n) * c, n + 1.0, n + 2.0


def xg_integral(profile, x: np.ndarray, rtol: float) -> np.ndarray:
    """``H(x) = ∫_0^x s g(s) ds``, m⁴ (closed form for power terms and tables, else tanh-sinh)."""
    x = np.asarray(x, float)
    if profile._has("_xg_integral_closed_form"):
        return np.where(x > 0, profile._xg_integral_closed_form(np.maximum(x, 0.0)), 0.0)
    terms = profile.power_terms()
    if terms is not None:
        return power_integral(x, [(profile._power_kappa(n) * c, n) for c, n in terms], 2.0)

    def integrand(s: np.ndarray, idx: np.ndarray) -> np.ndarray:
        return s * profile._g(np.maximum(s, 1e-300))

    lo = np.minimum(np.broadcast_to(profile.flat_radius, x.shape).astype(float), x)
    flat = x.ravel()
    out = np.zeros(flat.shape)
    pos = flat > lo.ravel()
    if np.any(pos):
        out[pos] = tanh_sinh(integrand, lo.ravel()[pos], flat[pos], rtol=rtol).value
    return out.reshape(x.shape)


@dataclass
class SpringState:
    """Spring state of one solver run (mutable, owned by the run).

    Attributes
    ----------
    S : ndarray
        ``∫_cell (d - g)_+ dx`` per cell, m² (normal spring state).
    tangential, torsion : ndarray or None
        Element force (N) / torque (N·m) per cell, or None when the family is not built.
    L_tan, L_tor : ndarray or None
        Current slip limits.
    depth, radius : float
    """

    S: np.ndarray
    tangential: np.ndarray | None
    torsion: np.ndarray | None
    L_tan: np.ndarray | None
    L_tor: np.ndarray | None
    depth: float = 0.0
    radius: float = 0.0
    nL_tan: np.ndarray | None = None
    nL_tor: np.ndarray | None = None
    k: int = 0


class Winkler(Foundation):
    """Independent springs with stick/slip memory (see the module docstring)."""

    def _build(self) -> None:
        # few full-length passes and temporaries: at 10^6 springs building costs as much as ~40
        # steps of the compiled run (left edges are views of the boundary arrays, b³ is b²·b)
        b = self.boundaries
        prof = self.profile
        self.bl = b[:-1]
        self.w = np.diff(b)
        # 1/w and the weight buffer of the step-by-step route are made on first use (a fused
        # compiled run needs neither: at 10^6 springs two 8 MB arrays fewer per simulate)
        Gb = _gint(prof, b)
        self.dG = np.diff(Gb)
        self.G_left = Gb[:-1]
        E = self.moduli.normal
        mu = self.friction
        self._c_tan = 2.0 * mu * E if mu is not None else np.inf
        self._c_tor = 4.0 * mu * E if mu is not None else np.inf
        if "tangential" in self.needs:
            self.K_tan = 2.0 * self.moduli.tangential * self.w
            _check_stiffness(self.K_tan, self.radius)
            self.invK_tan = 1.0 / self.K_tan
        if "torsion" in self.needs:
            b2 = b * b
            self.X1 = np.diff(b2)
            self.X1 /= 2.0
            b2 *= b                                     # b³
            K = np.diff(b2)
            del b2
            K *= 16.0 * self.moduli.torsional
            K /= 3.0
            self.K_tor = K
            _check_stiffness(self.K_tor, self.radius)
            self.invK_tor = 1.0 / self.K_tor
            Hb = xg_integral(prof, b, self.rtol)
            self.dH = np.diff(Hb)
            self.H_left = Hb[:-1]

    # ------------------------------------------------------------------ per-step precomputation
    def edge_data(self, d: np.ndarray, a: np.ndarray) -> dict[str, np.ndarray]:
        """Vectorised over steps: index of the cell holding the contact edge and its exact
        partial integrals (``S`` and, with torsion, ``∫ x (d-g)``)."""
        d = np.asarray(d, float)
        a = np.asarray(a, float)
        tor = "torsion" in self.needs
        kernel = _compiled.edge_cells() if d.ndim == 1 and d.shape == a.shape else None
        if kernel is not None:   # compiled: the search and arithmetic below in one pass
            spec = _whole_power_term(self.profile, tor)
            if spec is None:
                a = np.minimum(a, self.radius)
                Ga, Ha = _edge_integrals(self.profile, a, self.rtol, tor)
                spec = (0.0, 0.0, 0.0)
            else:       # the integrals in the kernel's pass
                Ga = Ha = a
            out = {"k": np.empty(d.size, np.int64), "S": np.empty(d.size)}
            out["T"] = np.empty(d.size) if tor else out["S"]
            kernel(d, a, Ga, Ha, self.boundaries, self.G_left, self.H_left if tor else self.G_left,
                   out["k"], out["S"], out["T"], tor, float(self.radius), *spec)
            if not tor:
                del out["T"]
            return out
        a = np.minimum(a, self.radius)
        k = np.clip(np.searchsorted(self.boundaries, a, side="left") - 1, 0, self.n_springs - 1)
        bl = self.bl[k]
        S = np.where(a > bl, d * (a - bl) - (_gint(self.profile, a) - self.G_left[k]), 0.0)
        out = {"k": k, "S": np.maximum(S, 0.0)}
        if "torsion" in self.needs:
            Ha = xg_integral(self.profile, a, self.rtol)
            out["T"] = np.maximum(np.where(a > bl, d * (a * a - bl * bl) / 2.0
                                           - (Ha - self.H_left[k]), 0.0), 0.0)
        return out

    def new_state(self) -> SpringState:
        n = self.n_springs
        tan = np.zeros(n) if "tangential" in self.needs else None
        tor = np.zeros(n) if "torsion" in self.needs else None
        return SpringState(np.zeros(n), tan, tor,
                           np.zeros(n) if tan is not None else None,
                           np.zeros(n) if tor is not None else None,
                           nL_tan=np.zeros(n) if tan is not None else None,
                           nL_tor=np.zeros(n) if tor is not None else None)

    def set_normal(self, st: SpringState, d: float, a: float, k: int, S_edge: float,
                   T_edge: float | None) -> np.ndarray | None:
        """Move the normal springs to depth ``d`` (radius ``a``, edge cell ``k``); update the slip
        limits of the built families.

        Returns the contact weight of each cell over the step (``ΔS/(w Δd)``: 1 for cells in
        contact before and after, 0 for cells out of contact throughout, the exact average for
        the cells the edge crossed), by which the stiffness of the tangential/torsional elements is
        scaled for this step; ``None`` when the depth did not change (then the weight is the
        contact fraction, :meth:`fraction`).
        """
        dd = d - st.depth
        k_old = st.k
        S_old = st.S
        S = d * self.w
        S -= self.dG  # cells left of k are fully in contact, so S > 0 there (d >= g(a))
        S[k + 1:] = 0.0
        S[k] = S_edge
        weight = None
        if dd != 0.0:
            lo, hi = min(k, k_old), max(k, k_old) + 1
            weight = self.__dict__.get("_wbuf")
            if weight is None:
                weight = self._wbuf = np.zeros(self.n_springs)
            weight[:lo] = 1.0
            weight[hi:] = 0.0
            ws = (S[lo:hi] - S_old[lo:hi]) / (dd * self.w[lo:hi])
            np.clip(ws, 0.0, 1.0, out=weight[lo:hi])
        st.S, st.depth, st.radius, st.k = S, d, a, k
        inf_mu = self.friction is None
        if st.L_tan is not None:
            st.L_tan = np.where(S > 0, np.inf, 0.0) if inf_mu else self._c_tan * S
            st.nL_tan = -st.L_tan
        if st.L_tor is not None:
            T = d * self.X1
            T -= self.dH
            T[k + 1:] = 0.0
            T[k] = T_edge
            st.L_tor = np.where(T > 0, np.inf, 0.0) if inf_mu else self._c_tor * T
            st.nL_tor = -st.L_tor
        return weight

    @functools.cached_property
    def inv_w(self) -> np.ndarray:
        """``1 / w`` per cell, 1/m."""
        return 1.0 / self.w

    def fraction(self, a: float) -> np.ndarray:
        """Fraction of each cell inside the contact radius ``a``."""
        return np.clip((a - self.bl) * self.inv_w, 0.0, 1.0)

    # ------------------------------------------------------------------ Jenkins elements
    @staticmethod
    def jenkins(m: np.ndarray, K: np.ndarray, invK: np.ndarray, L: np.ndarray, nL: np.ndarray,
                inc: float, tmp: np.ndarray) -> float:
        """Advance elements in place by displacement ``inc``; return the dissipated energy, J.

        ``m ← clip(m + K inc, -L, L)`` (``nL = -L``); dissipation
        ``Σ |slip| L = Σ (trial - m) m / K``.
        """
        return jenkins_update(m, K, invK, L, inc, tmp, nL)   # compiled when numba is installed

    @staticmethod
    def solve(m: np.ndarray, K: np.ndarray, L: np.ndarray, target: float) -> tuple[float, bool]:
        """Increment ``s`` with ``Σ clip(m + K s, -L, L) = target`` (exact, piecewise linear).

        The sum is monotone non-decreasing in ``s``. A target at or beyond the full-sliding value
        ``±ΣL`` returns the smallest increment that reaches full sliding and ``gross=True``.
        """
        m0 = np.clip(m, -L, L)
        F0 = float(m0.sum())
        if target == F0:
            return 0.0, False
        sgn = 1.0 if target > F0 else -1.0
        act = K > 0
        Ka = K[act]
        room = (L[act] - sgn * m0[act]) / Ka  # >= 0; inf without friction
        need = sgn * (target - F0)
        fin = np.isfinite(room)
        k_inf = float(Ka[~fin].sum())
        r = room[fin]
        kf = Ka[fin]
        order = np.argsort(r)
        r = r[order]
        kf = kf[order]
        # gain at breakpoint j: sum_{i<j} k_i r_i + r_j (sum_{i>=j} k_i + k_inf)
        kr = np.concatenate(([0.0], np.cumsum(kf * r)))
        k_rest = (kf[::-1].cumsum()[::-1]) + k_inf
        gain = kr[:-1] + r * k_rest
        j = int(np.searchsorted(gain, need, side="left"))
        if j < r.size:
            slope = k_rest[j]
            s = (need - kr[j]) / slope
            return sgn * float(s), False
        if k_inf > 0:
            return sgn * float((need - kr[-1]) / k_inf), False
        return sgn * float(r[-1] if r.size else 0.0), True

    @staticmethod
    def stick_radius(m: np.ndarray, L: np.ndarray, bl: np.ndarray, radius: float) -> float:
        """Outer radius of the central stick zone: the left edge of the first element at its
        slip limit (cells out of contact count as slipping), or ``radius``."""
        slip = np.abs(m) >= L
        i = int(np.argmax(slip))
        return float(bl[i]) if slip[i] else radius


def monotone_block(m: np.ndarray, K: np.ndarray, L: np.ndarray, bl: np.ndarray, radius: float,
                   s: float, du: np.ndarray | None = None, target: np.ndarray | None = None,
                   want_stick: bool = True) -> dict[str, np.ndarray]:
    """Advance Jenkins elements over a run of steps with fixed ``K``, ``L`` and monotone input.

    Exact closed form of ``T`` successive updates ``m ← clip(m + K Δ, -L, L)`` when every
    increment has the sign ``s``: element ``i`` sticks until the accumulated displacement
    ``x`` reaches its room ``r_i = (L_i - s m_i)/K_i`` and slides after that. With the rooms
    sorted, the force ``Σ clip(m + s K x, -L, L)``, the dissipation ``Σ_{r_i < x} L_i (x - r_i)``
    and the stick radius (first element, from the centre, whose room is reached) follow from
    cumulative sums and a binary search per step: ``O(N log N + T log N)`` instead of ``O(N T)``.

    Parameters
    ----------
    m : ndarray
        Element forces, updated in place to the state after the last step.
    K, L : ndarray
        Stiffness and slip limit of each element (``K = 0``: out of contact).
    bl : ndarray
        Left cell boundaries (for the stick radius); ``radius`` is the contact radius.
    s : {+1, -1}
        Direction of the run.
    du : ndarray, optional
        Accumulated displacement ``x_t >= 0`` (``s``-directed) at each step of the run, or
    target : ndarray, optional
        Total force at each step (force control); ``x_t`` is solved exactly.

    Returns
    -------
    dict
        ``force`` (total per step), ``dissipation`` (cumulative within the run), ``x``
        (accumulated displacement), ``gross`` (target at/over full sliding) and, if asked,
        ``stick``.
    """
    act = K > 0
    sm = s * m
    F0 = float(m.sum())
    Ka = K[act]
    room = (L[act] - sm[act]) / Ka
    order = np.argsort(room, kind="stable")
    r = room[order]
    k = Ka[order]
    lim = L[act][order]
    fin = np.isfinite(r)
    kr = np.where(fin, k * r, 0.0)
    ckr = np.concatenate(([0.0], np.cumsum(kr)))
    ck = np.concatenate(([0.0], np.cumsum(k)))
    Ktot = ck[-1]
    gross = None
    if target is not None:
        G = s * (np.asarray(target, float) - F0)
        gb = ckr[:-1] + np.where(fin, r, np.inf) * (Ktot - ck[:-1])
        j = np.searchsorted(gb, G, side="left")
        over = j >= r.size
        jj = np.minimum(j, max(r.size - 1, 0))
        slope = Ktot - ck[jj]
        with np.errstate(divide="ignore", invalid="ignore"):
            x = np.where(over, r[-1] if r.size else 0.0, (G - ckr[jj]) / slope)
        x = np.maximum(x, 0.0)
        gross = over
    else:
        x = np.asarray(du, float)
    idx = np.searchsorted(r, x, side="right")  # elements whose room is used up
    gain = ckr[idx] + x * (Ktot - ck[idx])
    force = F0 + s * gain
    if gross is not None:
        force = np.where(gross, s * float(L[act].sum()), force)
    lr = np.where(fin, lim * r, 0.0)
    cl = np.concatenate(([0.0], np.cumsum(np.where(fin, lim, 0.0))))
    clr = np.concatenate(([0.0], np.cumsum(lr)))
    diss = x * cl[idx] - clr[idx]
    out = {"force": force, "dissipation": np.maximum(diss, 0.0), "x": x,
           "gross": np.zeros(x.size, bool) if gross is None else gross}
    if want_stick:
        rs = np.zeros(m.size)
        rs[act] = room
        pm = np.minimum.accumulate(rs)
        first = np.searchsorted(-pm, -x, side="left")
        out["stick"] = np.where(first < m.size, bl[np.minimum(first, m.size - 1)], radius)
    xe = float(x[-1])
    np.minimum(sm + K * xe, L, out=sm)
    np.multiply(sm, s, out=m)
    return out


def abel_traction(x: np.ndarray, q: np.ndarray, a: float, q_edge: float,
                  r: np.ndarray) -> np.ndarray:
    """``-(1/π) ∫_r^a q'(x)/sqrt(x² - r²) dx + q_edge/(π sqrt(a² - r²))`` for ``r < a``.

    ``q`` is the piecewise-linear interpolant through ``(x_i, q_i)``, constant on ``[0, x_0]`` and
    linear from the last node to ``(a, q_edge)``; ``q_edge`` is the value at ``a⁻`` (a jump to 0
    at ``a`` gives the edge term). MDR inverse of a line load [H1; theory §3]. Returns 0 for
    ``r >= a``.
    """
    r = np.asarray(r, float)
    xn = np.concatenate((x, [a]))
    qn = np.concatenate((q, [q_edge]))
    x0, x1 = xn[:-1], xn[1:]
    slope = np.diff(qn) / np.diff(xn)
    rr = np.maximum(r, 1e-300)[..., None]
    lo = np.maximum(x0, rr)
    hi = np.maximum(x1, rr)
    with np.errstate(divide="ignore", invalid="ignore"):
        seg = np.arccosh(hi / rr) - np.arccosh(lo / rr)
        tau = -(slope * seg).sum(axis=-1) / np.pi
        tau = tau + np.where(r < a, q_edge / (np.pi * np.sqrt(np.maximum(a * a - r * r, 0))), 0.0)
    return np.where(r < a, tau, 0.0)


def snapshot_shear(fnd: "Winkler", st: SpringState, r: np.ndarray) -> dict[str, np.ndarray]:
    """3D tractions from the spring states at radii ``r`` (MDR inverse of the line loads).

    Tangential: line load ``q_x = f_i/(2 w_i)`` (both sides lumped in ``f_i``),
    ``τ_x = -(1/π)∫ q_x'/sqrt(x²-r²)``. Torsion: cell rotation ``ψ_i = m_i/K_i`` (``u_y = xψ``),
    ``τ = (4G_t r/π)[-∫ ψ'/sqrt(x²-r²) + ψ(a)/sqrt(a²-r²)]`` (theory §8, item 1).
    A cell at its slip limit next to the edge means ``u(a) = 0``; otherwise the edge cell's value
    holds up to ``a`` (no slip).
    """
    a = st.radius
    inside = fnd.bl < a
    x = fnd.positions[inside]
    out = {}
    if x.size == 0:
        return out
    last = int(np.flatnonzero(inside)[-1])
    if st.tangential is not None:
        q = st.tangential[inside] / (2.0 * fnd.w[inside])
        slipping = np.abs(st.tangential[last]) >= st.L_tan[last]
        out["shear_tangential"] = abel_traction(x, q, a, 0.0 if slipping else q[-1], r)
    if st.torsion is not None:
        psi = st.torsion[inside] / fnd.K_tor[inside]
        slipping = np.abs(st.torsion[last]) >= st.L_tor[last]
        out["shear_torsion"] = 4.0 * fnd.moduli.torsional * np.asarray(r, float) * abel_traction(
            x, psi, a, 0.0 if slipping else psi[-1], r)
    return out
