"""The ring discretisation of the exact torsion solver (:mod:`contactlab.physics.torsion_rings`).

:class:`Rings` covers ``0 <= r <= radius`` (the largest contact radius of the path) with rings
``[b_j, b_{j+1}]``, one collocation point per ring (its midpoint), and holds the matrices of the
half-space's torsional influence in the point tractions: ``H`` (complementary energy) and ``g``
(torque weights). The geometry and matrices are immutable; the traction/slip state belongs to a
solver run (:meth:`Rings.new_state`).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..physics import torsion_rings as _tr
from .base import Foundation

__all__ = ["Rings", "RingState", "DEFAULT_N_RINGS"]

#: default number of rings over the path's largest contact radius. Measured by
#: benchmarks/torsion_rings.py (Hertz, 2-core VM): at constant load the torque of the exact
#: Jäger/Masing history is reproduced to <= 2e-6 of the sliding torque (monotone, oscillating,
#: irregular), on a 180-step path whose normal force changes every step to ~6e-4 of the sliding
#: torque against a 4x finer run, in ~0.5 s.
DEFAULT_N_RINGS = 200


@dataclass
class RingState:
    """Traction/slip state of one solver run (mutable, owned by the run).

    Attributes
    ----------
    z : ndarray
        Circumferential traction at the collocation points, Pa.
    S : ndarray
        Area-weighted slip accumulated while in contact, m³.
    active : ndarray of int
        Active set of the last step (-1/+1 sliding backwards/forwards, 0 stuck, 2 out of contact).
    twist : float
    """

    z: np.ndarray
    S: np.ndarray
    active: np.ndarray
    twist: float = 0.0


class Rings(Foundation):
    """Rings with the exact torsional influence matrices (see the module docstring).

    Parameters are those of :class:`~contactlab.foundation.Foundation`; ``n_springs`` is the
    number of rings and ``spacing`` defaults to ``"uniform"`` (measured more accurate here than
    the edge-refined spacing, whose fine cells sit at the largest radius only).
    """

    def __init__(self, profile, moduli, friction, radius, *, n_springs=None, spacing="uniform",
                 needs=("torsion",), rtol=1e-10) -> None:
        super().__init__(profile, moduli, friction, radius,
                         n_springs=DEFAULT_N_RINGS if n_springs is None else n_springs,
                         spacing=spacing, needs=needs, rtol=rtol)

    def _build(self) -> None:
        b = self.boundaries
        self.points = 0.5 * (b[1:] + b[:-1])
        mats = _tr.influence(b, self.points, self.moduli.torsional)
        self.H, self.C, self.g = mats["H"], mats["C"], mats["g"]
        self.B, self.lu = mats["B"], mats["lu"]

    def new_state(self) -> RingState:
        n = self.n_springs
        return RingState(np.zeros(n), np.zeros(n), np.zeros(n, int))
