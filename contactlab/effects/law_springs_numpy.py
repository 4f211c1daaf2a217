"""The numpy reference path of :class:`contactlab.effects.law.ContactLaw` on its MDR springs:
the switch of contacts from the exact constant-load law onto their springs, the growth of a
contact's spring cover and one spring step (the compiled path:
:mod:`contactlab.physics.law_kernel`). The spring rows live in the law's
:class:`~contactlab.effects.law_pool.SpringPool`."""
from __future__ import annotations

from typing import Any

import numpy as np

from ..physics import law_springs as _springs

__all__ = ["to_springs", "regrid", "spring_step"]


def to_springs(law: Any, idx: np.ndarray, d: np.ndarray, a: np.ndarray) -> None:
    """Switch contacts ``idx`` from the exact constant-load law to MDR springs: the cells
    take the state of the held load the contact leaves (its Masing turning points replayed
    through the elements at that load)."""
    if idx.size == 0:
        return
    st = law._st
    pool = law._pool
    assert pool is not None
    P = pool.rows
    s = pool.assign(idx)
    d0 = st["depth_ref"][idx]
    a0 = law._radius(d0, idx)
    P["spr_cover"][s] = law.spring_cover[idx] * np.maximum(a0, a[idx])
    geo = law._geometry(idx)
    S, T, k = _springs.normal_cells(geo, d0, a0)
    frac = _springs.weights(geo, S, S, k, k, np.zeros(idx.size), a0)
    L_tan, L_tor = law._limits(idx, S, T)
    K_tan = 2.0 * law.G_star[idx, None] * geo["w"]
    K_tor = 16.0 * law.G_torsion[idx, None] * geo["X2"]
    for ch, K, L in (("tan", K_tan, L_tan), ("tor", K_tor, L_tor)):
        P[f"spr_{ch}"][s] = _springs.replay(st[f"{ch}_X"][idx], st[f"{ch}_depth"][idx],
                                            st[f"{ch}_x"][idx], K * frac, L)
        P[f"spr_x_{ch}"][s] = st[f"{ch}_x"][idx]
    P["spr_a"][s], P["spr_k"][s], P["spr_depth"][s] = a0, k, d0


def regrid(law: Any, idx: np.ndarray, a_new: np.ndarray) -> None:
    """Grow the cover of contacts ``idx`` to ``spring_cover × a_new``; element forces are
    carried over by their cumulative line load (approximate)."""
    assert law._pool is not None
    P, s = law._pool.rows, law._pool.slot[idx]
    old = law._geometry(idx)
    P["spr_cover"][s] = law.spring_cover[idx] * a_new
    new = law._geometry(idx)
    for ch in ("tan", "tor"):
        m = P[f"spr_{ch}"][s]
        cum = np.concatenate([np.zeros((idx.size, 1)), np.cumsum(m, axis=1)], axis=1)
        P[f"spr_{ch}"][s] = np.diff(_springs.interp_rows(new["b"], old["b"], cum), axis=1)
    d0 = P["spr_depth"][s]
    a0 = law._radius(d0, idx)
    P["spr_a"][s], P["spr_k"][s] = a0, _springs.normal_cells(new, d0, a0)[2]


def spring_step(law: Any, idx, d, a, u, phi):
    """One MDR spring step of the contacts ``idx`` (on springs: all of them) at depth ``d``,
    radius ``a`` and controls ``u``, ``phi`` (theirs, or None): ``(Ft, ct, M, cm, dW)`` of
    those contacts. A driven channel's elements beyond the edge cell are +0 after the step:
    written up to the last step's edge cell (every one where the channel is
    :attr:`~contactlab.effects.law_pool.SpringPool.stale`), the others (+0 already) kept as
    they are; the clip before gives the dissipation (a zero there)."""
    pool = law._pool
    assert pool is not None
    grow = a > law._spr("spr_cover", idx)
    if np.any(grow):
        regrid(law, idx[grow], a[grow])
    P, s = pool.rows, pool.slot[idx]
    geo = law._geometry(idx)
    S, T, k = _springs.normal_cells(geo, d, a)
    d_old = P["spr_depth"][s]
    k_old = P["spr_k"][s]
    dd = d - d_old
    # the last step's cell integrals, recomputed from its depth and radius (not stored): the
    # same call on the same cells as the one that formed them, so the same bits
    S_old = _springs.normal_cells(geo, d_old, P["spr_a"][s])[0]
    wgt = _springs.weights(geo, S, S_old, k, k_old, dd, a)
    L_tan, L_tor = law._limits(idx, S, T)
    j = np.arange(S.shape[1])[None, :]
    beyond = j > k[:, None]
    untouched = j > np.maximum(k, k_old)[:, None]       # beyond both edges
    zero = np.zeros(idx.size)
    Ft, ct, M, cm, dW = zero, a.copy(), zero, a.copy(), zero.copy()
    for ch, x, K, L in (("tan", u, 2.0 * law.G_star[idx, None] * geo["w"], L_tan),
                        ("tor", phi, 16.0 * law.G_torsion[idx, None] * geo["X2"], L_tor)):
        if x is None:
            continue
        m0 = P[f"spr_{ch}"][s]
        m = m0.copy()
        dW += _springs.jenkins_rows(m, K * wgt, L, x - P[f"spr_x_{ch}"][s])
        keep = untouched & (not pool.stale[ch])
        m = np.where(beyond, np.where(keep, m0, 0.0), m)
        P[f"spr_{ch}"][s], P[f"spr_x_{ch}"][s] = m, x
        if ch == "tan":
            Ft, ct = m.sum(axis=1), _springs.stick_radius(m, L, geo["bl"], a)
        else:
            M, cm = m.sum(axis=1), _springs.stick_radius(m, L, geo["bl"], a)
    pool.stale["tan"], pool.stale["tor"] = u is None, phi is None
    P["spr_a"][s], P["spr_k"][s], P["spr_depth"][s] = a, k, d
    return Ft, ct, M, cm, dW
