"""The MDR viscoelastic foundation: independent rheological elements [H3] (theory §7).

Rigid indenter on an incompressible linear viscoelastic half-space, ``E*(t) = 4G(t)``. The
half-space becomes a row of independent 1D rheological elements at ``x_i`` (spacing ``Δx``), each a
copy of the material's element with every parameter scaled by ``4Δx``. For the Prony form
``G(t) = G_∞ + Σ_k G_k e^{-t/τ_k} + η δ(t)`` the line load of element i is

    q_i = 4 [G_∞ u_i + Σ_k s_ik + η du_i/dt],    ds_ik/dt + s_ik/τ_k = G_k du_i/dt,

with ``u_i`` its surface displacement (``d - g(x_i)`` while in contact). ``F = 2∫_0^a q dx``, with
the edge ``a`` interpolated inside the outermost element's cell (see :meth:`ViscoelasticElements.trial`).

Time integration (exact for displacements linear within a step): the arm stresses advance by
the exponential integrator

    s_ik ← e^{-Δt/τ_k} s_ik + G_k β_k Δu_i,     β_k = τ_k (1 - e^{-Δt/τ_k}) / Δt,

vectorised over springs and arms. Contact rules per element:

* in contact at the start of a step: it stays in contact while its force is compressive; if the
  trial force is tensile it separates (no adhesion) and evolves force-free. The contact edge is
  therefore where the element force vanishes, which reproduces Ting's solution for shrinking
  contacts (``d = g(a)`` is *not* used on unloading);
* out of contact: it evolves force-free (``q = 0``: creep recovery, solved in closed form for the
  same integrator) until the indenter reaches its surface, ``d - g(x_i) > u_i``. Within the step the
  entry time is interpolated (fraction θ), and the loading part of the step uses ``(1-θ)Δt``: this
  makes the Kelvin-Voigt edge jump ``4ηḋ`` exact.

Force control solves ``F(d) = F_target`` per step by a bracketed root (``F`` is non-decreasing in
the end-of-step depth). A zero-length step is a jump (glassy response ``G_∞ + Σ G_k``); it is not
allowed with a Kelvin-Voigt dashpot.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import ConvergenceError, ParameterError
from . import _compiled_viscoelastic
from ..numeric.roots import bracketed_root

__all__ = ["ViscoelasticElements", "solve_history"]


def _beta(h: np.ndarray, tau: np.ndarray) -> np.ndarray:
    """``τ(1 - e^{-h/τ})/h`` (→ 1 as h → 0), elementwise."""
    z = h / tau
    with np.errstate(invalid="ignore", divide="ignore"):
        out = -np.expm1(-z) / z
    return np.where(z > 0, out, 1.0)


@dataclass
class _Trial:
    m: int                 # elements [0, m) were updated; the rest are virgin and unchanged
    q: np.ndarray
    u: np.ndarray
    s: np.ndarray
    contact: np.ndarray
    stiffness: float = 0.0   # dq_sum/dd of the elements in contact (for Newton predictions)
    radius: float = 0.0      # contact edge, m (sub-element, see ViscoelasticElements.trial)
    total: float = 0.0       # normal force, N
    n_contact: int = 0       # elements in contact
    last: int = -1           # the outermost element in contact (-1: none)


class ViscoelasticElements:
    """The MDR viscoelastic foundation: element state and the per-step update (half line x > 0).

    Parameters
    ----------
    g_x : ndarray
        Transformed profile at the element centres (non-decreasing), m.
    dx : float
        Element spacing, m.
    G_inf, moduli, times, eta
        Prony form of the material (Pa, Pa, s, Pa·s).

    Notes
    -----
    Only the elements ``[0, m)`` that were ever touched or can be reached at the trial depth are
    updated; the rest are virgin (``u = s = 0``) and stay so under force-free evolution.
    """

    def __init__(self, g_x: np.ndarray, dx: float, G_inf: float, moduli: np.ndarray,
                 times: np.ndarray, eta: float) -> None:
        self.g = np.asarray(g_x, float)
        self.dx = float(dx)
        self.G_inf = float(G_inf)
        self.Gk = np.asarray(moduli, float)
        self.tk = np.asarray(times, float)
        self.eta = float(eta)
        n = self.g.size
        self.u = np.zeros(n)
        self.s = np.zeros((n, self.Gk.size))
        self.contact = np.zeros(n, bool)
        self.touched = 0           # elements [0, touched) may differ from the virgin state
        self.ever = np.zeros(n, bool)   # element has been in contact at some step
        self._dt_cache: tuple = (None, None)

    def _coefficients(self, dt: float) -> tuple:
        if self._dt_cache[0] == dt:
            return self._dt_cache[1]
        z = dt / self.tk
        e = np.exp(-z)
        beta = np.ones(z.shape)     # _beta without its error-state context (a step's cost)
        pos = z > 0
        beta[pos] = -np.expm1(-z[pos]) / z[pos]
        Gb = self.Gk * beta
        if dt > 0:
            visc = self.eta / dt
        else:
            visc = np.inf if self.eta > 0 else 0.0
        coef = (e, Gb, float(Gb.sum()), visc)
        self._dt_cache = (dt, coef)
        return coef

    def trial(self, d_new: float, d_old: float, dt: float) -> _Trial:
        """End-of-step element forces for indenter depth ``d_new`` (state not modified).

        Compiled (numba, extra ``fast``) when available, else the numpy reference
        (:mod:`contactlab.foundation._compiled_viscoelastic`; the backend switch is the one of
        the Winkler kernels)."""
        m = max(self.touched, int(np.searchsorted(self.g, d_new, side="right")))
        m = min(m, self.g.size)
        e, Gb, Gb_sum, visc = self._coefficients(dt)
        kernel = _compiled_viscoelastic.trial_step()
        if kernel is not None:      # numba: the same step in one compiled pass
            out = kernel(float(d_new), float(d_old), float(dt), m, self.g, self.u[:m],
                         self.s[:m], self.contact[:m], self.ever, e, Gb, Gb_sum, float(visc),
                         self.G_inf, self.Gk, self.tk, self.eta, self.dx)
            return _Trial(m, *out)
        return self._trial_numpy(d_new, d_old, dt, m, e, Gb, Gb_sum, visc)

    def _trial_numpy(self, d_new: float, d_old: float, dt: float, m: int, e: np.ndarray,
                     Gb: np.ndarray, Gb_sum: float, visc: float) -> _Trial:
        """The reference numpy implementation of :meth:`trial`."""
        g = self.g[:m]
        u, s, was = self.u[:m], self.s[:m], self.contact[:m]
        u_c = d_new - g
        du = u_c - u
        es = s * e                                  # (m, K)
        es_sum = es.sum(axis=1)
        q = np.zeros(m)
        u_new = u.copy()
        s_new = np.empty_like(s)
        # (A) in contact at the start of the step: stays while compressive
        with np.errstate(invalid="ignore"):
            q_a = self.G_inf * u_c + es_sum + Gb_sum * du + (visc * du if visc else 0.0)
        in_a = was & (q_a >= 0)
        # (B) free at the start, reached by the indenter within the step (entry fraction θ)
        cand = np.flatnonzero(~was & (du > 0))
        in_b = np.zeros(m, bool)
        if cand.size:
            if dt > 0 and d_new > d_old:
                theta = np.clip((u[cand] + g[cand] - d_old) / (d_new - d_old), 0.0, 1.0)
            else:
                theta = np.zeros(cand.size)
            h = (1.0 - theta) * dt                  # loading part of the step
            duc = du[cand]
            rate: float | np.ndarray
            if self.eta > 0:
                if np.any(h <= 0):
                    rate = np.full(cand.size, np.inf)
                else:
                    rate = self.eta * duc / h
            else:
                rate = 0.0
            s_b = es[cand] + self.Gk * _beta(h[:, None], self.tk[None, :]) * duc[:, None]
            q_b = self.G_inf * u_c[cand] + s_b.sum(axis=1) + rate
            ok = q_b >= 0
            sel = cand[ok]
            in_b[sel] = True
            q[sel] = q_b[ok]
            u_new[sel] = u_c[sel]
            s_new[sel] = s_b[ok]
        q[in_a] = q_a[in_a]
        u_new[in_a] = u_c[in_a]
        s_new[in_a] = es[in_a] + Gb * du[in_a, None]
        # (C) force-free evolution (same integrator): G_∞u' + Σ(e s + G_k β_k (u'-u)) + η(u'-u)/Δt = 0
        free = ~(in_a | in_b)
        if np.any(free):
            uf, esf = u[free], es_sum[free]
            if np.isinf(visc):
                u_f = uf.copy()
            else:
                u_f = ((Gb_sum + visc) * uf - esf) / (self.G_inf + Gb_sum + visc)
            u_new[free] = u_f
            s_new[free] = es[free] + Gb * (u_f - uf)[:, None]
        contact = in_a | in_b
        n_in = int(np.count_nonzero(contact))
        k = 4.0 * n_in * (self.G_inf + Gb_sum + (visc if np.isfinite(visc) else 0.0))
        q = 4.0 * q
        a, F, last = self._edge_and_force(d_new, q, 4.0 * q_a, contact)
        return _Trial(m, q, u_new, s_new, contact, k, a, F, n_in, last)

    def _edge_and_force(self, d: float, q: np.ndarray, q_trial: np.ndarray,
                        contact: np.ndarray) -> tuple[float, float, int]:
        """Contact edge inside the outermost element's cell, and ``F = 2∫_0^a q dx``.

        Growth front (the next element never touched): the edge is where the indenter meets the
        undisturbed surface, ``d = g(a)``, interpolated between the two element centres.
        Elsewhere (shrinking contact, Ting): where the element force vanishes, interpolated
        between the outermost element's force and the neighbour's trial contact force.
        The outermost element i then carries the length ``a - iΔx`` (interior ones ``Δx``), so
        the force is continuous as elements enter or leave.
        """
        idx = np.flatnonzero(contact)
        if idx.size == 0:
            return 0.0, 0.0, -1
        dx = self.dx
        i = int(idx[-1])
        x_i = (i + 0.5) * dx
        j = i + 1
        a = x_i + 0.5 * dx
        if j < self.g.size:
            if not self.ever[j]:
                p_i, p_j = d - self.g[i], d - self.g[j]
                if p_i > 0 >= p_j:
                    a = x_i + dx * p_i / (p_i - p_j)
            else:
                q_i, q_j = q[i], q_trial[j]
                if q_i > 0 > q_j:
                    a = x_i + dx * q_i / (q_i - q_j)
        a = min(max(a, x_i), x_i + dx)
        F = 2.0 * (dx * float(q[idx].sum()) + (a - (i + 1) * dx) * float(q[i]))
        return a, F, i

    def commit(self, t: _Trial) -> None:
        m = t.m
        self.u[:m], self.s[:m], self.contact[:m] = t.u, t.s, t.contact
        if t.last >= 0:
            self.touched = max(self.touched, t.last + 1)
            self.ever[:t.last + 1] |= t.contact[:t.last + 1]

    def force(self, t: _Trial) -> float:
        """``F = 2∫_0^a q dx`` (both halves of the 1D foundation), N."""
        return t.total

    def touching_depth(self) -> float:
        """Smallest depth at which the indenter touches the (free) surface, m: 0 on a surface
        never touched (the tip, ``g(0) = 0``; the first element's centre would give
        ``g(Δx/2) > 0``, a depth into a surface nothing has pressed)."""
        if self.touched == 0:
            return 0.0
        m = self.touched
        return float(np.min(self.g[:m] + self.u[:m]))


def solve_history(g_x: np.ndarray, dx: float, prony: tuple, time: np.ndarray,
                  depth: np.ndarray | None = None, force: np.ndarray | None = None,
                  depth_scale: float = 1e-9) -> dict[str, np.ndarray]:
    """Run the foundation through a depth or force history.

    Parameters
    ----------
    g_x : ndarray
        ``g`` at the element centres ``x_i = (i + 1/2) Δx``, m.
    dx : float
        Element spacing, m.
    prony : (G_inf, moduli, times, eta)
        Material in Prony form.
    time : ndarray
        Non-decreasing times, s. The state at ``time[0]`` is reached from the virgin, unloaded
        half-space by a jump.
    depth, force : ndarray, exactly one
        Prescribed history (m or N), same length as ``time``.
    depth_scale : float
        A typical depth, m (initial bracket width of force-controlled steps).

    Returns
    -------
    dict
        ``depth``, ``force``, ``radius`` (edge interpolated inside the outermost element's cell),
        ``n_contact`` and
        ``edge_reached`` (contact touched the last element) arrays per step.
    """
    G_inf, Gk, tk, eta = prony
    fd = ViscoelasticElements(g_x, dx, G_inf, Gk, tk, eta)
    n = time.size
    out_d = np.zeros(n)
    out_F = np.zeros(n)
    out_a = np.zeros(n)
    out_n = np.zeros(n, int)
    edge = np.zeros(n, bool)
    t_prev, d_prev = float(time[0]), 0.0
    last_step = 0.0
    for i in range(n):
        dt = float(time[i]) - t_prev
        if depth is not None:
            d_new = float(depth[i])
            if dt == 0 and eta > 0 and d_new != d_prev and (
                    np.any(fd.contact) or d_new > float(np.min(g_x + fd.u))):
                raise ParameterError(
                    f"depth[{i}]={d_new!r} m jumps (zero time step) on a Kelvin-Voigt material: its "
                    "dashpot cannot follow a jump. Start the history at depth 0 and ramp it.")
            trial = fd.trial(d_new, d_prev, dt)
        else:
            assert force is not None   # exactly one of depth, force is given
            target = float(force[i])
            if target <= 0:
                # pulled off (no adhesion): the largest depth at which no element carries force
                d_new = _release_depth(fd, d_prev, dt, depth_scale, i)
                trial = fd.trial(d_new, d_prev, dt)
            else:
                if dt == 0 and eta > 0:
                    raise ParameterError(
                        f"force[{i}]={target!r} N is applied in a zero time step on a "
                        "Kelvin-Voigt material: its dashpot cannot follow a jump. Start the "
                        "history at force 0 and ramp it.")
                d_new = _solve_force(fd, target, d_prev, dt, depth_scale, i, last_step)
                trial = fd.trial(d_new, d_prev, dt)
        fd.commit(trial)
        out_d[i] = d_new
        out_F[i] = fd.force(trial)
        out_a[i] = trial.radius
        out_n[i] = trial.n_contact      # elements beyond trial.m are virgin, out of contact
        edge[i] = trial.last == g_x.size - 1
        last_step = d_new - d_prev
        t_prev, d_prev = float(time[i]), d_new
    return {"depth": out_d, "force": out_F, "radius": out_a, "n_contact": out_n,
            "edge_reached": edge}


def _release_depth(fd: ViscoelasticElements, d_old: float, dt: float, scale: float, step: int) -> float:
    """Largest end-of-step depth at which no element carries force (bisection on F > 0)."""

    def F(d: float) -> float:
        return fd.force(fd.trial(d, d_old, dt))

    hi = fd.touching_depth()
    if F(hi) <= 0:
        return hi
    span = max(abs(hi), scale)
    lo = hi - span
    for _ in range(200):
        if F(lo) <= 0:
            break
        span *= 2.0
        lo = hi - span
    else:
        raise ConvergenceError(f"step {step}: the indenter could not be released.")
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if F(mid) > 0:
            hi = mid
        else:
            lo = mid
        if hi - lo <= 1e-13 * max(abs(lo), scale):
            break
    return lo


def _solve_force(fd: ViscoelasticElements, target: float, d_old: float, dt: float, scale: float,
                 step: int, guess_step: float = 0.0) -> float:
    """Depth at the end of a step such that the foundation force equals ``target``."""

    def F(d: float) -> float:
        return fd.force(fd.trial(d, d_old, dt))

    # Newton predictions with the tangent stiffness (F is piecewise linear in d between contact
    # changes), keeping the evaluated points as a bracket; bracketed solve if they stall
    tol = 1e-13 * abs(target)
    d = d_old + guess_step
    lo_pts: list[float] = []
    hi_pts: list[float] = []
    for _ in range(6):
        tr = fd.trial(d, d_old, dt)
        Fd = fd.force(tr)
        if abs(Fd - target) <= tol:
            return float(d)
        (lo_pts if Fd < target else hi_pts).append(d)
        k = 2.0 * fd.dx * tr.stiffness
        if k <= 0:
            break
        d = d + (target - Fd) / k
    if lo_pts and hi_pts:
        lo, hi = max(lo_pts), min(hi_pts)
        return float(bracketed_root(lambda x, idx: np.array([F(float(v)) for v in x]), target,
                                    lo, hi, rtol=1e-13, ftol=1e-13, what=f"depth at step {step}"))
    # bracket around the previous depth, widening geometrically (F is non-decreasing in d)
    base = d_old if d_old > fd.touching_depth() or np.any(fd.contact) else fd.touching_depth()
    step0 = max(abs(guess_step), scale)
    lo, hi = base, base
    F_lo = F_hi = F(base)
    span = step0
    for _ in range(200):
        if F_lo <= target:
            break
        hi, F_hi = lo, F_lo
        lo -= span
        span *= 4.0
        F_lo = F(lo)
    else:
        raise ConvergenceError(f"step {step}: no lower depth bracket for force={target!r} N.")
    span = step0
    for _ in range(200):
        if F_hi >= target:
            break
        lo, F_lo = hi, F_hi
        hi += span
        span *= 4.0
        F_hi = F(hi)
    else:
        raise ConvergenceError(f"step {step}: no upper depth bracket for force={target!r} N.")
    if F_lo == target:
        return float(lo)
    if F_hi == target:
        return float(hi)

    def func(x: np.ndarray, idx: np.ndarray) -> np.ndarray:
        return np.array([F(float(v)) for v in x])

    root = bracketed_root(func, target, lo, hi, rtol=1e-13, ftol=1e-13,
                          what=f"depth at step {step}")
    return float(root)
