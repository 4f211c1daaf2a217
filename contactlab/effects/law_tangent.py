"""Consistent tangent stiffness of a :class:`~contactlab.effects.law.ContactLaw` step.

Along the current branch at constant normal load the MDR gives every channel's incremental
stiffness in closed form: normal ``dF/dd = 2E* a``; tangential ``dF_x/du = 2G* c``
(Cattaneo-Mindlin, and on a Masing branch with ``c`` the stick radius of that branch, since
``F = F_r - 2F_load((u_r - u)/2)`` has slope ``F_load'``); torsional ``dM/dφ = (16/3) G_t c³``
(the stick zone turns as a rigid flat punch of radius ``c``, the slip zone's traction is
fixed; the MDR torsional springs ``8G_t Δx`` at lever ``x`` sum to the same).
"""
from __future__ import annotations

from typing import Any

import numpy as np

from ..errors import NotSupportedError

__all__ = ["tangent"]


def tangent(law: Any, res: Any, displacement: Any, twist: Any, wanted: bool = True
            ) -> dict[str, np.ndarray] | None:
    """Tangent stiffness per contact of the step ``res`` of ``law``: ``"normal"`` (N/m),
    ``"tangential"`` (N/m), ``"torsional"`` (N·m/rad); 0 for a channel not driven and for
    contacts out of contact. None when not ``wanted``.

    Raises
    ------
    NotSupportedError
        A contact is on springs (its normal load changed): the spring model's tangent is not
        available.
    """
    if not wanted:
        return None
    live = res.radius > 0
    if np.any(live & ~res.exact):
        i = int(np.argmax(live & ~res.exact))
        raise NotSupportedError(
            f"tangent=True: contact {i} is on springs (its normal load changed); the tangent "
            "of the spring model is not available yet (call law.reset(mask) to restart it at "
            "the new load).")
    a = np.where(live, res.radius, 0.0)
    ct = np.where(live, res.stick_radius, 0.0) if displacement is not None else 0.0 * a
    cm = np.where(live, res.torsion_stick_radius, 0.0) if twist is not None else 0.0 * a
    return {"normal": 2.0 * law.E_star * a, "tangential": 2.0 * law.G_star * ct,
            "torsional": 16.0 / 3.0 * law.G_torsion * cm ** 3}
