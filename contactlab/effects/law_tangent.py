"""Consistent tangent stiffness of a :class:`~contactlab.effects.law.ContactLaw` step.

Along the current branch at constant normal load the MDR gives every channel's incremental
stiffness in closed form: normal ``dF/dd = 2E* a``; tangential ``dF_x/du = 2G* c``
(Cattaneo-Mindlin, and on a Masing branch with ``c`` the stick radius of that branch, since
``F = F_r - 2F_load((u_r - u)/2)`` has slope ``F_load'``); torsional ``dM/dφ = (16/3) G_t c³``
(the stick zone turns as a rigid flat punch of radius ``c``, the slip zone's traction is
fixed; the MDR torsional springs ``8G_t Δx`` at lever ``x`` sum to the same).

Contacts on springs (their normal load changed): each cell is a Jenkins element
``m ← clip(m + K_eff Δx, -L, L)`` with the step's effective stiffness
``K_eff = 2G* w ω`` (tangential) or ``16 G_t ∫x² ω`` (torsion), ``ω`` the part of the cell in
contact during the step, and the step's force is ``Σ m``. At the step's depth the response is
piecewise linear in the step's displacement (twist): its slope is the springs' sum
``Σ K_eff`` over the elements that stick (``|m| < L``, to 1e-9 of the limit); a sliding
element adds nothing. The
normal force stays the closed form, ``2E* a``. ``ω`` needs the depth at the start of the step,
which :func:`snapshot` keeps before the step.
"""
from __future__ import annotations

from typing import Any

import numpy as np

from ..errors import NotSupportedError
from ..physics import law_springs as _springs

__all__ = ["snapshot", "tangent"]

#: an element within this fraction of its slip limit counts as sliding
_AT_LIMIT = 1e-9


def snapshot(law: Any) -> tuple[np.ndarray, np.ndarray] | None:
    """The springs' depth (per contact) and on-flags before a step (None without springs)."""
    if not law.springs:
        return None
    return law._pool.full("spr_depth"), law._on()


def _springs_tangent(law: Any, res: Any, idx: np.ndarray, pre: tuple | None,
                     ) -> tuple[np.ndarray, np.ndarray]:
    """Tangential (N/m) and torsional (N·m/rad) springs' sums of contacts ``idx``."""
    st = law._st
    d, a = res.depth[idx], res.radius[idx]
    d_pre, on_pre = pre if pre is not None else (law._pool.full("spr_depth"), law._on())
    # the step's start: the springs' depth, or the held load a contact left in this step
    d_old = np.where(on_pre[idx], d_pre[idx], st["depth_ref"][idx])
    geo = law._geometry(idx)
    S, T, k = _springs.normal_cells(geo, d, a)
    S_old, _, k_old = _springs.normal_cells(geo, d_old, law._radius(d_old, idx))
    wgt = _springs.weights(geo, S, S_old, k, k_old, d - d_old, a)
    L_tan, L_tor = law._limits(idx, S, T)
    K_tan = 2.0 * law.G_star[idx, None] * geo["w"] * wgt
    K_tor = 16.0 * law.G_torsion[idx, None] * geo["X2"] * wgt
    # at its limit to rounding (the compiled route forms L in another order): sliding
    stick_tan = np.abs(law._spr("spr_tan", idx)) < L_tan * (1.0 - _AT_LIMIT)
    stick_tor = np.abs(law._spr("spr_tor", idx)) < L_tor * (1.0 - _AT_LIMIT)
    return (np.sum(np.where(stick_tan, K_tan, 0.0), axis=1),
            np.sum(np.where(stick_tor, K_tor, 0.0), axis=1))


def tangent(law: Any, res: Any, displacement: Any, twist: Any, wanted: bool = True,
            pre: tuple | None = None) -> dict[str, np.ndarray] | None:
    """Tangent stiffness per contact of the step ``res`` of ``law``: ``"normal"`` (N/m),
    ``"tangential"`` (N/m), ``"torsional"`` (N·m/rad); 0 for a channel not driven and for
    contacts out of contact. None when not ``wanted``. ``pre`` is :func:`snapshot` taken
    before the step.

    Raises
    ------
    NotSupportedError
        A contact whose turning-point memory overflowed (its response is approximate and not
        on a branch of the law).
    """
    if not wanted:
        return None
    live = res.radius > 0
    on = law._on() & live
    if np.any(live & ~res.exact & ~on):
        i = int(np.argmax(live & ~res.exact & ~on))
        raise NotSupportedError(
            f"tangent=True: contact {i}'s turning-point memory overflowed (its response is "
            "approximate, not on a branch); raise memory= or call law.reset(mask).")
    a = np.where(live, res.radius, 0.0)
    ct = np.where(live, res.stick_radius, 0.0) if displacement is not None else 0.0 * a
    cm = np.where(live, res.torsion_stick_radius, 0.0) if twist is not None else 0.0 * a
    out = {"normal": 2.0 * law.E_star * a, "tangential": 2.0 * law.G_star * ct,
           "torsional": 16.0 / 3.0 * law.G_torsion * cm ** 3}
    if np.any(on):
        idx = np.flatnonzero(on)
        kt, kr = _springs_tangent(law, res, idx, pre)
        out["tangential"][idx] = kt if displacement is not None else 0.0
        out["torsional"][idx] = kr if twist is not None else 0.0
    return out
