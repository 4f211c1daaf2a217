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

#: default number of rings over the path's largest contact radius (before the nodes added at the
#: path's contact radii). Measured by benchmarks/torsion_rings.py (2-core shared VM): at constant
#: load the torque of the exact Jäger/Masing history is reproduced to 2.7e-7 of the sliding torque
#: (Hertz, punch-density steps with the stick radius solved inside its ring; order ~2.5), on a
#: 180-step path whose normal force changes every step to 1.6e-5 against 800 rings (the steps
#: with two slip zones, taken by the ring solver, dominate it)
DEFAULT_N_RINGS = 200
#: with the edge punch (contact pinned at a wall): its collocation point sits this fraction of
#: the last ring's width inside the edge (the ring's midpoint is the other point of that ring)
EDGE_POINT = 0.1
#: at a jump node (a contact radius inside the grid): the collocation point of its half-hat sits
#: this fraction of the ring outside the node (the ring's midpoint is the other point)
JUMP_POINT = 0.25


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
    ``contact_radii`` (m, optional): the contact radii of the path's steps; nodes are added at
    them (:func:`contactlab.physics.torsion_rings.aligned_grid`) so that the moving contact edge
    sits on a node; with ``jumps=True`` (default) the punch density may jump at those nodes
    (:func:`contactlab.physics.torsion_rings.jump_traction`), as a sliding contact edge needs.
    ``n_uniform`` keeps the requested ring count, ``n_springs`` the actual one; ``jumps`` holds
    the jump node indices after the build. Collocation points are sorted by radius.
    """

    def __init__(self, profile, moduli, friction, radius, *, n_springs=None, spacing="uniform",
                 needs=("torsion",), rtol=1e-10, contact_radii=None, edge_punch=False,
                 jumps=True) -> None:
        self._contact_radii = None if contact_radii is None else np.asarray(contact_radii, float)
        self.edge_punch = bool(edge_punch)
        self._with_jumps = bool(jumps)
        super().__init__(profile, moduli, friction, radius,
                         n_springs=DEFAULT_N_RINGS if n_springs is None else n_springs,
                         spacing=spacing, needs=needs, rtol=rtol)

    def _build(self) -> None:
        self.n_uniform = self.n_springs
        if self._contact_radii is not None:
            self.boundaries = _tr.aligned_grid(self.boundaries, self._contact_radii)
            self.n_springs = self.boundaries.size - 1
        b = self.boundaries
        self.jumps = (_tr.radius_nodes(b, self._contact_radii)
                      if self._with_jumps and self._contact_radii is not None
                      else np.zeros(0, np.int64))
        h = np.diff(b)
        pts = [0.5 * (b[1:] + b[:-1]), b[self.jumps] + JUMP_POINT * h[self.jumps]]
        if self.edge_punch:     # one more point, in the last ring, for the edge punch
            pts.append([b[-1] - EDGE_POINT * h[-1]])
        self.points = np.sort(np.concatenate(pts))
        mats = _tr.influence(b, self.points, self.moduli.torsional, edge_punch=self.edge_punch,
                             jumps=self.jumps)
        self.H, self.C, self.g = mats["H"], mats["C"], mats["g"]
        self.B, self.lu = mats["B"], mats["lu"]

    def new_state(self) -> RingState:
        n = self.points.size
        return RingState(np.zeros(n), np.zeros(n), np.zeros(n, int))
