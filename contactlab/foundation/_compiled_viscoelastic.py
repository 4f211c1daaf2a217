"""Optional compiled step of the MDR viscoelastic foundation (extra ``fast``: numba).

``trial(d_new, d_old, dt, m, g, u, s, contact, ever, e, Gb, Gb_sum, visc, G_inf, Gk, tk, eta,
dx) -> (q, u_new, s_new, contact_new, stiffness, radius, force, n_contact, last)``
    The end-of-step element forces of :meth:`ViscoelasticElements.trial
    <contactlab.foundation.viscoelastic.ViscoelasticElements.trial>` for the elements ``[0, m)`` (state
    not modified): the three contact rules (in contact and compressive, entering within the
    step, force-free), the contact edge inside the outermost element's cell and the force,
    in one pass over the elements instead of ~40 numpy calls (half of a 1000-element step was
    the calls' own overhead). Plain arrays in and out, no object state.

The arithmetic per element is that of the numpy reference in the same order; the sums over
the Prony arms and over the elements in contact run sequentially (numpy sums pairwise), so the
two agree to rounding (within ``1e-12`` relative, tested on Kelvin-Voigt, Maxwell, standard
linear solid and Prony histories under depth and force control). The backend is the one of the
Winkler kernels (:func:`contactlab.foundation._compiled.backend`): numba when it imports,
``CONTACTLAB_BACKEND=numpy`` or :func:`~contactlab.foundation._compiled.set_backend` forces the
numpy reference. numba compiles the step on its first call and keeps the machine code on disk
(:mod:`contactlab.numeric.jit`): the first process on a machine compiles (seconds), later
processes load it.
"""
from __future__ import annotations

import math
import threading

import numpy as np

from . import _compiled

__all__ = ["trial_step"]

_cache: dict = {"trial": None}
_lock = threading.Lock()


def _trial(d_new, d_old, dt, m, g, u, s, was, ever, e, Gb, Gb_sum, visc, G_inf, Gk, tk, eta,
           dx):     # pragma: no cover - compiled
    K = Gk.size
    q = np.zeros(m)
    q_trial = np.empty(m)   # 4 q_a: the trial force of an element staying in contact
    u_new = np.empty(m)
    s_new = np.empty((m, K))
    con = np.zeros(m, np.bool_)
    es = np.empty(K)
    vinf = math.isinf(visc)
    # entry within the step: the whole step's loading time unless the indenter moves in
    grow = dt > 0 and d_new > d_old
    # a Kelvin-Voigt dashpot entering in zero loading time: infinite rate for all entrants
    rate_inf = False
    if eta > 0:
        for i in range(m):
            if not was[i]:
                du = (d_new - g[i]) - u[i]
                if du > 0:
                    th = 0.0
                    if grow:
                        th = min(max((u[i] + g[i] - d_old) / (d_new - d_old), 0.0), 1.0)
                    if (1.0 - th) * dt <= 0:
                        rate_inf = True
                        break
    n_in = 0
    last = -1
    for i in range(m):
        u_c = d_new - g[i]
        ui = u[i]
        du = u_c - ui
        es_sum = 0.0
        for k in range(K):
            es[k] = s[i, k] * e[k]
            es_sum += es[k]
        qa = G_inf * u_c + es_sum + Gb_sum * du + (visc * du if visc else 0.0)
        q_trial[i] = 4.0 * qa
        inside = False
        if was[i]:
            if qa >= 0:     # (A) in contact at the start: stays while compressive
                inside = True
                q[i] = qa
                u_new[i] = u_c
                for k in range(K):
                    s_new[i, k] = es[k] + Gb[k] * du
        elif du > 0:        # (B) reached by the indenter within the step
            th = 0.0
            if grow:
                th = min(max((ui + g[i] - d_old) / (d_new - d_old), 0.0), 1.0)
            h = (1.0 - th) * dt
            if eta > 0:
                rate = math.inf if rate_inf else eta * du / h
            else:
                rate = 0.0
            sb_sum = 0.0
            for k in range(K):
                z = h / tk[k]
                beta = -math.expm1(-z) / z if z > 0 else 1.0
                sb = es[k] + Gk[k] * beta * du
                s_new[i, k] = sb
                sb_sum += sb
            qb = G_inf * u_c + sb_sum + rate
            if qb >= 0:
                inside = True
                q[i] = qb
                u_new[i] = u_c
        if inside:
            con[i] = True
            n_in += 1
            last = i
        else:               # (C) force-free evolution (same integrator)
            if vinf:
                uf = ui
            else:
                uf = ((Gb_sum + visc) * ui - es_sum) / (G_inf + Gb_sum + visc)
            u_new[i] = uf
            for k in range(K):
                s_new[i, k] = es[k] + Gb[k] * (uf - ui)
    stiff = 4.0 * n_in * (G_inf + Gb_sum + (0.0 if vinf else visc))
    F_sum = 0.0
    for i in range(m):
        q[i] = 4.0 * q[i]
        if con[i]:
            F_sum += q[i]
    if last < 0:
        return q, u_new, s_new, con, stiff, 0.0, 0.0, 0, -1
    # the contact edge inside the outermost element's cell (see ViscoelasticElements._edge_and_force)
    i = last
    x_i = (i + 0.5) * dx
    j = i + 1
    a = x_i + 0.5 * dx
    if j < g.size:
        if not ever[j]:
            p_i = d_new - g[i]
            p_j = d_new - g[j]
            if p_i > 0 >= p_j:
                a = x_i + dx * p_i / (p_i - p_j)
        else:
            q_i = q[i]
            q_j = q_trial[j]    # j < m: an element ever in contact is below ``touched``
            if q_i > 0 > q_j:
                a = x_i + dx * q_i / (q_i - q_j)
    a = min(max(a, x_i), x_i + dx)
    F = 2.0 * (dx * F_sum + (a - (i + 1) * dx) * q[i])
    return q, u_new, s_new, con, stiff, a, F, n_in, last


def trial_step():
    """The compiled viscoelastic trial step (numba backend), or None with numpy (the caller then
    runs the numpy reference)."""
    if _compiled.backend() != "numba":
        return None
    kernel = _cache["trial"]
    if kernel is None:
        with _lock:
            if _cache["trial"] is None:     # compiled on its first call, cached on disk
                from ..numeric.jit import njit
                _cache["trial"] = njit(_trial, nogil=True)
            kernel = _cache["trial"]
    return kernel
