"""The ring discretisation of the exact torsion solver (:mod:`contactlab.physics.torsion_rings`)
and its time loop along a load path (normal force and twist/torque changing together).

:class:`Rings` covers ``0 <= r <= radius`` (the largest contact radius of the path) with rings
``[b_j, b_{j+1}]``, one collocation point per ring (its midpoint), and holds the matrices of the
half-space's torsional influence in the point tractions: ``H`` (complementary energy) and ``g``
(torque weights). The geometry and matrices are immutable; the traction/slip state belongs to a
solver run (:meth:`Rings.new_state`).

Along a load path (:meth:`Rings.for_path`, :meth:`Rings.run`) the normal problem is solved
exactly at every step (path independent) before the loop; the torsional problem is solved with
the half-space's exact torsional influence (flat-punch superposition), Coulomb's law and memory
between steps. The state is the punch density itself; a step whose slip zone is one annulus
reaching the contact edge is taken in closed form with its stick radius solved inside its ring
(:mod:`contactlab.physics.torsion_annulus`), any other step by the box-constrained ring solver as
an increment on that density (:mod:`contactlab.physics.torsion_rings`). Flat punches (edge punch
at the wall) run on the ring solver alone; a contact without a friction limit carries rigid
punches at its contact radii. The error falls with the number of rings; see
``docs/torsion_varying_load.md``.
"""
from __future__ import annotations

import threading
import warnings
from collections import OrderedDict
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from ..citations import sources_for
from ..errors import (ContactlabError, NotSupportedError, OutsideTheoryError, ParameterError,
                      ValidityWarning)
from ..numeric.blas import serial_blas
from ..params import check_count, check_in_range, check_memory, check_time
from ..physics import normal as _normal
from ..physics import ring_pressure as _rp
from ..physics import torsion_annulus as _ta
from ..physics import torsion_energy as _te
from ..physics import torsion_point_traction as _tpt
from ..physics import torsion_rings as _tr
from .base import SERIES, Foundation, PathArrays, PathNormal

__all__ = ["Rings", "RingState", "DEFAULT_N_RINGS", "memory", "step_seconds", "rings_for_rtol",
           "RTOL_LAW", "RTOL_RANGE", "INSIDE_ALLOWANCE", "NEAR_RINGS", "inside_allowance",
           "EDGE_OFF_NODE", "COVER_OFF_NODE", "edge_off_node"]

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
#: series whose writes every step of a run (allocated without a zero fill)
_WRITES = ("twist", "torque", "stick_radius", "dissipated_energy")

#: float64 values held at the peak of an exact run (tracemalloc, rounded up; measured 7.7 per
#: ring and step of the longest leaf, 12-14 per ring squared, 390 per step on short paths; the
#: NodeTable of the annulus checks adds 4 per point and ring end, up to 8 per ring squared, and
#: its differences between neighbouring ring ends 2, up to 4)
_PER_LEAF_STEP_RING, _PER_RING2, _PER_STEP = 10, 28, 64


def memory(n_steps: int, longest_leaf: int, n_rings: int) -> float:
    """Estimated peak memory of a ring-solver run (``simulate(method="exact")``), bytes: per-step series, the
    ring arrays of a chunk of steps (the longest leaf's steps up to :data:`_BOUND_CHUNK`, x
    rings) and the dense ring matrices; checked against the memory budget before anything is
    allocated."""
    chunk = min(float(longest_leaf), float(_BOUND_CHUNK))
    return 8.0 * (_PER_STEP * float(n_steps) + _PER_LEAF_STEP_RING * chunk
                  * float(n_rings) + _PER_RING2 * float(n_rings) * float(n_rings))


@dataclass
class RingState:
    """Traction/slip state of one solver run (mutable, owned by the run).

    Attributes
    ----------
    z : ndarray
        Circumferential traction at the collocation points, Pa.
    S : ndarray
        Area-weighted slip accumulated while in contact, m³.
    active : ndarray of int, or tuple
        Active set of the last step (-1/+1 sliding backwards/forwards, 0 stuck, 2 out of contact),
        or after an annulus step its stick radius, sense and ``μ p`` at the points, from which
        :func:`contactlab.physics.torsion_rings.active_set` forms it where the ring solver
        needs it.
    twist : float
    """

    z: np.ndarray
    S: np.ndarray
    active: np.ndarray | tuple
    twist: float = 0.0


#: run time of a path on the exact rings, s per step per ring. Measured (CPU time, shared
#: 2-core VM at load ~3.5, paraboloid under a varying force with a sinusoidal twist, 200-1000
#: steps): 2.1-3.8 ms per step on 200 rings, 1.1-1.25 ms on 100 rings (10-19 µs per ring);
#: taken at about 0.45 of the smallest per ring, a lower estimate (the cost per ring grows with
#: the rings; benchmarks/time_estimates.py checks it)
STEP_SECONDS_PER_RING = 5e-6


#: the error law of the ring count on varying-load paths: the largest torque error of a path on
#: ``n`` rings, relative to the path's largest full-sliding torque, stays below ``C n^-p`` with
#: ``(C, p)`` = RTOL_LAW. An upper envelope of measured errors, not the asymptotic order: on
#: 180-step paths (Hertz, cone, a cubic table; force constant, +-30 % and +-40 % at two cycles;
#: twist at 80 % of sliding at three cycles) against 400 rings (400 vs 800 rings: 6e-6) the error
#: is 2e-3-6e-3 from 16 to 80 rings (the cone: 4.8e-3 at 60, 3.1e-3 at 80, the envelope's
#: tightest points), then falls faster than n^-2 (2e-4-3.3e-4 at 100, <= 3e-4 at 150); at
#: constant force it is 100-1000x smaller (docs/torsion_varying_load.md, "Accuracy and rings")
RTOL_LAW = (20.0, 2.0)
#: the torque accuracies ``torque_rtol`` may ask for (the law's measured range: 0.1 -> 16 rings,
#: 1e-4 -> 448 rings; finer asks need references this law was not measured against)
RTOL_RANGE = (1e-4, 0.1)
#: fewest rings an accuracy chooses (the coarsest measured count)
_RTOL_MIN_RINGS = 16


def rings_for_rtol(rtol: float) -> int:
    """Rings of the exact path solver for a torque accuracy ``rtol`` (relative to the path's
    largest full-sliding torque): the fewest for which :data:`RTOL_LAW` is below ``rtol``,
    at least 16.

    Parameters
    ----------
    rtol : float
        Requested accuracy, dimensionless, in :data:`RTOL_RANGE`.

    Returns
    -------
    int

    Raises
    ------
    ParameterError
        ``rtol`` outside :data:`RTOL_RANGE`.

    Examples
    --------
    >>> rings_for_rtol(1e-3)
    142
    """
    rtol = check_in_range("torque_rtol", rtol, RTOL_RANGE[0], RTOL_RANGE[1], low_open=False,
                          high_open=False, what="a torque accuracy relative to the sliding "
                          "torque (the range of the measured error law)")
    c, p = RTOL_LAW
    n = int(np.ceil((c / rtol) ** (1.0 / p) * (1.0 - 1e-12)))
    return max(_RTOL_MIN_RINGS, n)


#: the share of the ring count's error law (:data:`RTOL_LAW`, relative to the sliding torque)
#: by which the traction of a single-slip-annulus step may exceed the friction limit inside
#: its stick radius, weighted by the points' torque, and the step still be taken (else the
#: ring solver takes it), where every point beyond the limit lies within :data:`NEAR_RINGS`
#: uniform ring widths of the stick radius. Those exceedances are of the discretisation's
#: order: on the benchmark's path shape (Hertz, force +-40 %, twist at 80 % of sliding) at 10^4
#: steps they made 15 % of the steps ring-solver steps (4.3 % at 10^3, 3 % at 10^2), most of
#: them while the twist is ramped in, with the exceedance within a ring of the
#: stick radius (docs/torsion_varying_load.md, "Second slip zones and the step count")
INSIDE_ALLOWANCE = 0.2
#: the band inside the stick radius, in uniform ring widths, where the allowance applies: an
#: exceedance further inside is a second slip zone of the load history (the reversal phases'
#: old slip zone far inside the new stick radius) and stays with the ring solver; accepted
#: there too, the torque moved by up to 4.4x the strict solver's ring error (stored paths,
#: against 800 rings)
NEAR_RINGS = 1.0


#: the largest distance of a step's contact radius from the nearest ring node, in uniform ring
#: widths, at which a requested ``torque_rtol`` is taken to hold: the ring count's error law
#: (:data:`RTOL_LAW`) was measured on 180-step paths, whose contact radii the nodes of
#: :func:`contactlab.physics.torsion_rings.aligned_grid` all hold (within 0.065 widths at 200
#: rings). A longer path may have more distinct contact radii than the node cap lets it place;
#: the steps whose edge then lies inside a ring carry an error of the order of one ring's
#: traction: on the benchmark's varying-load Hertz path at 10^3 steps with the cap at 1.5x the
#: rings (edges up to 0.6 widths off a node) the torque error reached 2.9e-3 of the sliding
#: torque at ``torque_rtol=1e-3`` (2.1e-4 on the steps with their edge on a node), 1.6e-3 at 200
#: rings (5.7e-5 on a node). A run whose rings ``torque_rtol`` chose has the cap
#: :data:`~contactlab.physics.torsion_rings.ALIGN_MAX_FACTOR_RTOL` and warns where an edge lies
#: beyond this distance from its node (:func:`edge_off_node`); a conservative line: at 3x10^3
#: steps (edges up to 0.38 widths off) the error was 1.6e-4 of the sliding torque
EDGE_OFF_NODE = 0.25
#: a run whose rings ``torque_rtol`` chose keeps every contact radius within this many ring widths
#: of a node (``cover`` of :func:`~contactlab.physics.torsion_rings.aligned_grid`), below
#: :data:`EDGE_OFF_NODE`: never a warning (docs/torsion_varying_load.md, issue 28 row 2)
COVER_OFF_NODE = 0.24


def edge_off_node(nodes: np.ndarray, radii: np.ndarray, n_uniform: int) -> tuple[float, int]:
    """How far the contact radii ``radii`` (m) lie from the nearest of the ring nodes ``nodes``
    (sorted, ``0`` first, m): the largest distance in uniform ring widths (``nodes[-1] /
    n_uniform``) and the number of radii beyond :data:`EDGE_OFF_NODE` widths. Radii the
    alignment ignores (within ``ALIGN_MERGE`` widths of the centre, or beyond the last node)
    are not counted.

    Examples
    --------
    >>> edge_off_node(np.array([0.0, 1.0, 2.0, 2.5, 4.0]), np.array([2.5, 3.0, 3.9]), 4)
    (0.5, 1)
    """
    b = np.asarray(nodes, float)
    h = float(b[-1]) / int(n_uniform)
    a = np.asarray(radii, float)
    a = a[(a > _tr.ALIGN_MERGE * h) & (a <= b[-1])]
    if a.size == 0:
        return 0.0, 0
    k = np.clip(np.searchsorted(b, a), 1, b.size - 1)
    d = np.minimum(a - b[k - 1], b[k] - a) / h
    return float(d.max()), int(np.count_nonzero(d > EDGE_OFF_NODE))


def inside_allowance(n_rings: int) -> float:
    """Allowed torque of the traction beyond the friction limit inside the stick radius of a
    single-slip-annulus step, relative to the step's sliding torque: :data:`INSIDE_ALLOWANCE`
    times :data:`RTOL_LAW` at ``n_rings`` (the rings before the nodes at the contact radii).

    Examples
    --------
    >>> inside_allowance(200)
    0.0001
    """
    c, p = RTOL_LAW
    return INSIDE_ALLOWANCE * c * float(n_rings) ** -p


def step_seconds(n_rings: int) -> float:
    """Estimated run time (s) of one path step on ``n_rings`` rings."""
    return STEP_SECONDS_PER_RING * n_rings


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
                 jumps=True, align_factor=_tr.ALIGN_MAX_FACTOR, align_cover=None) -> None:
        self.align_factor = float(align_factor)
        self.align_cover = None if align_cover is None else float(align_cover)
        self._contact_radii = None if contact_radii is None else np.asarray(contact_radii, float)
        self.edge_punch = bool(edge_punch)
        self._with_jumps = bool(jumps)
        super().__init__(profile, moduli, friction, radius,
                         n_springs=DEFAULT_N_RINGS if n_springs is None else n_springs,
                         spacing=spacing, needs=needs, rtol=rtol)

    def _build(self) -> None:
        self.n_uniform = self.n_springs
        if self._contact_radii is not None:
            self.boundaries = _tr.aligned_grid(self.boundaries, self._contact_radii,
                                               self.align_factor, self.align_cover)
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
        mats = _influence(b, self.points, self.moduli.torsional, self.edge_punch, self.jumps)
        self.H, self.C, self.g = mats["H"], mats["C"], mats["g"]
        self.B, self.lu = mats["B"], mats["lu"]
        #: the traction's and slip's antiderivatives at the points and ring ends (the checks of
        #: the annulus steps)
        self.table, self.table_diffs = mats["table"], mats["diffs"]

    def new_state(self) -> RingState:
        n = self.points.size
        return RingState(np.zeros(n), np.zeros(n), np.zeros(n, int))

    # ------------------------------------------------------------------ along a load path
    #: series whose discretisation error an error estimate reports
    ESTIMATED = ("torque", "twist", "stick_radius", "dissipated_energy")
    #: the ablation switches of a run (all on by default; tests and benchmarks turn them off):
    #: nodes at the contact radii, the edge punch at a wall, jumps of the punch density at those
    #: nodes, the tables' pressure at the fixed ring radii, the single-slip-annulus step
    SWITCHES = ("align", "edge", "jumps", "ring_table", "annulus")

    if TYPE_CHECKING:
        # set on the instances a run builds (declared for type checkers only: no field)
        switches: dict[str, bool]

    @classmethod
    # a ring model counts rings: its keyword is n_rings where the base class has n_springs
    def check_path(cls, path: Any, snapshots: Any = (), *,  # type: ignore[override]
                   n_rings: int | None = None, torque_rtol: float | None = None,
                   spacing: str = "uniform", approximate: bool = False,
                   **switches: bool) -> dict[str, Any]:
        """Check a run along ``path``: twist or torque without shift, ``n_rings`` (default
        :data:`DEFAULT_N_RINGS`) or ``torque_rtol`` (:func:`rings_for_rtol`), the memory
        budget. ``approximate`` has no meaning here (one family) and is ignored; ``switches``:
        :data:`SWITCHES`."""
        if "tangential" in path.groups:
            raise NotSupportedError("method='exact' solves torsion paths (twist/torque); this "
                                    "path drives a tangential shift: use method='mdr'.")
        bad = sorted(set(switches) - set(cls.SWITCHES))
        if bad:
            raise ParameterError(f"{bad[0]}= is not an option of the ring solver: allowed are "
                                 f"{cls.SWITCHES}.")
        sw = {k: bool(switches.get(k, True)) for k in cls.SWITCHES}
        if torque_rtol is not None:
            if n_rings is not None:
                raise ParameterError(f"n_rings={n_rings!r} and torque_rtol={torque_rtol!r} were "
                                     "both given: pass one (torque_rtol chooses the rings).")
            n_rings = rings_for_rtol(torque_rtol)
        n_rings = DEFAULT_N_RINGS if n_rings is None else check_count("n_rings", n_rings)
        n_total = path.n_steps
        longest = max((_longest_leaf(s) for s in path.segments), default=0)
        # nodes at the contact radii: up to ALIGN_MAX_FACTOR times the rings (..._RTOL where a
        # torque accuracy chose them), and a jump point per contact-radius node (at most one per
        # ring); the edge punch 1
        factor = _tr.ALIGN_MAX_FACTOR if torque_rtol is None else _tr.ALIGN_MAX_FACTOR_RTOL
        n_max = (int(np.ceil(2 * factor * n_rings)) + 1 if sw["align"]
                 else n_rings + 1)
        check_memory("simulate(method='exact')", memory(n_total, longest, n_max),
                     f"{n_total} steps, longest segment {longest} steps, {n_rings} rings "
                     f"(up to {n_max} with the nodes at the contact radii)")
        per = step_seconds(n_rings)
        check_time("simulate(method='exact')", n_total * per,
                   f"{n_total} steps x {per * 1e3:.3g} ms on {n_rings} rings")
        out = {"n_rings": n_rings, "spacing": spacing, **sw}
        if torque_rtol is not None:
            out["torque_rtol"] = torque_rtol
        return out

    @classmethod
    def writes(cls, path: Any, outputs: Any, **options: Any) -> tuple[str, ...]:
        return _WRITES

    @classmethod
    def coarser(cls, options: dict, meta: dict) -> dict | None:
        """Half the rings (the torque error falls at least as fast as ``N^-1`` on varying-load
        paths, so the difference bounds the error of the ``N``-ring run from above)."""
        # the coarse run halves the rings the run used (those of torque_rtol when it chose them)
        coarse = {k: v for k, v in options.items() if k != "torque_rtol"}
        return dict(coarse, n_rings=max(4, meta["n_rings"] // 2))

    @classmethod
    def for_path(cls, profile: Any, moduli: Any, friction: float | None, path: Any, *,
                 normal: PathNormal | None = None, n_springs: int | None = None,
                 spacing: str = "uniform", rtol: float = 1e-10, approximate: bool = False,
                 n_rings: int | None = None, torque_rtol: float | None = None,
                 **switches: bool) -> "Rings":
        """The rings of a twist/torque path: over its largest contact radius, with nodes at its
        contact radii (``align``) and the edge punch where the contact reaches a wall
        (``edge``); ``n_rings`` (or ``n_springs``) rings before those nodes. ``torque_rtol``
        (set where the requested accuracy chose ``n_rings``, :meth:`check_path`): beyond
        :data:`~contactlab.physics.torsion_rings.ALIGN_EXACT_FACTOR` times the rings the fewest
        nodes within :data:`COVER_OFF_NODE` widths of every contact radius, up to
        :data:`~contactlab.physics.torsion_rings.ALIGN_MAX_FACTOR_RTOL` times the rings, and a
        :class:`~contactlab.errors.ValidityWarning` where a contact radius still lies more than
        :data:`EDGE_OFF_NODE` ring widths from its node (:func:`edge_off_node`).

        Raises
        ------
        ParameterError
            The normal load never brings the bodies into contact.
        """
        sw = {k: bool(switches.get(k, True)) for k in cls.SWITCHES}
        if normal is None:
            from .base import path_normal_series
            normal = path_normal_series(profile, moduli.normal, path, rtol)
        a_max = normal.max_radius
        if a_max <= 0:
            raise ParameterError("the path prescribes a twist or torque but the normal load "
                                 "never brings the bodies into contact (contact radius 0 at "
                                 "every step).")
        if not _RADIUS_RANGE[0] <= a_max <= _RADIUS_RANGE[1]:
            F_max = float(np.max(np.abs(normal.series["force"]), initial=0.0))
            raise OutsideTheoryError(
                f"the exact ring solver cannot take this path: its largest contact radius "
                f"{a_max!r} m (normal force up to {F_max!r} N on {profile!r}) lies outside "
                f"[{_RADIUS_RANGE[0]!r}, {_RADIUS_RANGE[1]!r}] m, where its torque integrals "
                "(fifth powers of the radius) keep double precision. Check the units of the "
                "profile parameters, moduli and loads (SI: m, Pa, N), or rescale the problem.")
        radii = normal.series["radius"] if sw["align"] else None
        wall = profile.wall_radius
        edge_punch = bool(sw["edge"] and np.isfinite(wall) and a_max >= wall * (1.0 - 1e-12))
        fnd = cls(profile, moduli, friction, a_max,
                  n_springs=n_rings if n_rings is not None else n_springs, spacing=spacing,
                  rtol=rtol, contact_radii=radii, edge_punch=edge_punch, jumps=sw["jumps"],
                  align_factor=(_tr.ALIGN_MAX_FACTOR if torque_rtol is None
                                else _tr.ALIGN_MAX_FACTOR_RTOL),
                  align_cover=None if torque_rtol is None else COVER_OFF_NODE)
        fnd.switches = sw
        rtol_asked = torque_rtol
        if rtol_asked is not None and radii is not None:
            off, count = edge_off_node(fnd.boundaries, radii, fnd.n_uniform)
            if count:
                warnings.warn(
                    f"torque_rtol={rtol_asked!r} may not be met on this path: {count} of its "
                    f"{np.size(radii)} steps have their contact radius up to {off:.2f} ring widths "
                    f"off a ring node (more distinct contact radii than the {fnd.n_uniform} rings "
                    f"may add nodes for: at most {fnd.align_factor:g} x the rings), beyond "
                    f"the {EDGE_OFF_NODE:g} widths where the ring count's error law was measured "
                    "(with 1.5 x the rings, edges up to 0.6 widths off gave 2.9x the requested "
                    "torque_rtol=1e-3 on 10^3 steps of a varying-load Hertz path). Pass "
                    "error_estimate=True (half the rings again: its estimate covered the "
                    "measured error on such paths), n_rings= for more rings, or fewer "
"steps.", ValidityWarning, stacklevel=2)
        return fnd

    def run(self, leaves: Any, normal: PathNormal, outputs: Any, snapshots: Any,
            progress: Any = None) -> PathArrays:
        """The exact torsion steps along the path (see the module docstring). The snapshots
        hold ``r`` (the collocation points), ``depth``, ``radius``, ``shear_torsion``,
        ``pressure`` (Pa), ``slip`` and ``slip_increment`` (m); ``meta``: the ring counts, the
        switches, ``iterations``, ``fallback_steps`` (steps not taken by the annulus step),
        ``energy`` (``work``, ``stored``, ``dissipated_per_step`` per step, J). The steps'
        small dense solves run on one BLAS thread (:func:`contactlab.numeric.blas.serial_blas`):
        the same result for any thread setting, and no thread start-up per solve."""
        with serial_blas():
            return self._run(leaves, normal, outputs, snapshots, progress)

    def _run(self, leaves: Any, normal: PathNormal, outputs: Any, snapshots: Any,
             progress: Any = None) -> PathArrays:
        """:meth:`run` inside :func:`~contactlab.numeric.blas.serial_blas`."""
        sw = getattr(self, "switches", None) or dict.fromkeys(self.SWITCHES, True)
        align, ring_table, annulus = sw["align"], sw["ring_table"], sw["annulus"]
        rings, edge_punch, spacing = self, self.edge_punch, self.spacing
        res = normal.series
        n_total = res["time"].size
        for key in SERIES:
            if key not in res:
                res[key] = np.zeros(n_total, bool if key == "gross_sliding" else float)
        snaps = set(snapshots)
        work = np.zeros(n_total)
        stored = np.zeros(n_total)
        step_diss = np.zeros(n_total)
        st = self.new_state()
        r, H, g = self.points, self.H, self.g
        mu = self.friction
        prof, E = self.profile, self.moduli.normal
        # tables: the pressure shape at the (fixed) ring radii as running sums over the table
        # segments, set up once (physics.ring_pressure); other profiles: their own route per step
        table = (_rp.fixed_radii_shape(prof, r, self.radius, self.rtol)
                 if ring_table and mu is not None else None)
        cur = dict.fromkeys(("depth", "force", "twist", "torque"), 0.0)
        ctrl = "twist"
        M_old, W_in, W_d = 0.0, 0.0, 0.0
        G_t = self.moduli.torsional
        # the punch density as the state, each step with one slip annulus (stick radius inside
        # its ring) where that is the exact step; without friction limit rigid punches at the
        # contact radii; the flat punch's edge punch keeps the point tractions
        use_annulus = bool(annulus and mu is not None and not edge_punch)
        use_punches = bool(annulus and mu is None and not edge_punch)
        pt, pm = np.zeros(0), np.zeros(0)   # the rigid punches of a run without friction limit
        w = _ta.empty()
        slip = np.zeros(r.size)
        fallback = 0
        # the annulus step's accepted excess beyond μp inside its stick radius: torque weights,
        # the share of the step's sliding torque (inside_allowance) and the band it may lie in
        g_abs = np.abs(g)
        allowance = inside_allowance(self.n_uniform) if use_annulus else 0.0
        near = NEAR_RINGS * float(self.boundaries[-1]) / self.n_uniform
        # the ring solver's last Cholesky factor (torsion_rings.box_step's memo): its steps come
        # in runs whose next step mostly starts from the last one's stuck set
        factors: dict = {}
        ring_E: tuple = (None, 0.0)     # (density, its energy) of the last ring step
        slide_key = None        # (radius, μp) of the last full-sliding density computed
        snap_data: dict[int, dict] = {}
        i = 0
        iters = 0
        done = 0        # steps complete (the partial result of a failure)
        try:
            for leaf in leaves:
                # read-only columns where the segment has them (a table's own, no copies)
                _, vals = getattr(leaf, "values_readonly", leaf.values)(cur)
                n = leaf.n_steps
                d_arr, a_arr = res["depth"][i:i + n], res["radius"][i:i + n]
                if "twist" in vals or "torque" in vals:
                    ctrl = "twist" if "twist" in vals else "torque"
                    target = np.asarray(vals[ctrl], float)
                else:
                    target = np.full(n, cur[ctrl])
                g_a = np.where(a_arr > 0, prof._g(np.maximum(a_arr, 1e-300)), 0.0)
                if np.isfinite(prof.wall_radius):
                    g_a = np.where(a_arr >= prof.wall_radius, np.minimum(g_a, d_arr), g_a)
                for c0 in range(0, n, _BOUND_CHUNK):
                    # slip limits of the rings a chunk of steps at a time (a steps x rings array for a
                    # whole leaf would outgrow the result series many times over)
                    c1 = min(n, c0 + _BOUND_CHUNK)
                    ac, dc = a_arr[c0:c1], d_arr[c0:c1]
                    if mu is None:
                        bound = np.where(r[None, :] < ac[:, None], np.inf, 0.0)
                        p = None
                    elif table is not None:
                        p = _rp.pressure_at(prof, E, table, ac, dc, g_a[c0:c1])[0]
                    else:
                        p = _normal.pressure(prof, E, r[None, :], ac[:, None], dc[:, None],
                                             g_a[c0:c1, None], self.rtol)[0]
                    if mu is not None:
                        assert p is not None   # a pressure is computed whenever mu is given
                        bound = mu * np.where(r[None, :] < ac[:, None], np.maximum(p, 0.0), 0.0)
                    if use_annulus:
                        # the density ends at the node of the contact radius (a radius within
                        # ALIGN_GAP ring widths of another shares its node): the chunk's at once
                        bnd = rings.boundaries
                        edges = bnd[np.minimum(np.searchsorted(bnd, ac * (1 - 1e-12)),
                                               bnd.size - 1)].tolist()
                        # the full-sliding densities' coefficients of the chunk: one LAPACK call
                        coefs = _ta.coefficients(rings.lu, bound)
                    for j in range(c0, c1):
                        k = i + j
                        bj, aj = bound[j - c0], float(a_arr[j])
                        if use_annulus:
                            edge_j = edges[j - c0]
                            # (the same shape every step: an elementwise test is array_equal)
                            if slide_key is None or not (slide_key[0] == edge_j and
                                                         bool((slide_key[1] == bj).all())):
                                slide = _ta.nonnegative_psi(_ta.from_coefficients(
                                    bnd, coefs[j - c0], rings.jumps, edge_j))
                                slide_key = (edge_j, bj)
                            out = _annulus_step(rings, w, bj, edge_j, G_t, ctrl, float(target[j]),
                                                st.twist, st.active, slip=bool(snaps), slide=slide,
                                                memo=factors,
                                                allow=(g_abs, allowance * float(g_abs @ bj),
                                                       near))
                            w_o = w
                            w, z, lam_slip, dphi, gross, c_stick, st.active, it, book = out
                            M = _ta.torque(w, G_t)
                            # the step's work, elastic energy and dissipation
                            # (physics.torsion_energy)
                            if "ring" in book:
                                fallback += 1
                                # a run of ring steps: the old density's energy is the last
                                # one's new (the same density, the same bits)
                                en = _te.ring_step_energy(w_o, w, G_t, book["ring"],
                                                          ring_E[1] if ring_E[0] is w_o else None)
                                ring_E = (w, en["stored"])
                            elif book["turn"] is None:     # gross sliding, twist held
                                en = _te.step_energy(w_o, w, G_t, gross=None)
                            else:
                                en = _te.annulus_energy(w_o, w, slide, edge_j, book["sense"], G_t,
                                                        book["turn"], book["gross"])
                            E_st, dW = en["stored"], en["dissipated"]
                            W_in += en["work"]
                            slip += lam_slip
                        elif use_punches:
                            # no friction limit: rigid punches at the contact radii, exact
                            # out of contact no punch carries a torque: a torque target holds
                            # the twist (gross sliding unless the target is 0)
                            kw = ({"dphi": float(target[j]) - st.twist} if ctrl == "twist" else
                                  {"target_torque": float(target[j])} if aj > 0 else
                                  {"dphi": 0.0})
                            pt_o, pm_o = pt, pm
                            pt, pm, dphi = _ta.punch_step(pt, pm, aj, G_t, **kw)
                            gross = bool(ctrl == "torque" and aj == 0 and float(target[j]) != 0)
                            z, it, c_stick = None, 1, aj
                            lam_slip = np.zeros(r.size)
                            M = _ta.punch_torque(pt, pm, G_t)
                            # a release at the held twist, then a rigid punch
                            # (physics.torsion_energy)
                            en = _te.punch_step_energy(pt_o, pm_o, pt, pm, aj, G_t, dphi)
                            E_st, dW = en["stored"], en["dissipated"]
                            W_in += en["work"]
                        else:
                            z_old = st.z
                            if ctrl == "twist":
                                z, lam, dphi, it = _tr.box_step(H, g, z_old, bj,
                                                                dphi=target[j] - st.twist,
                                                                guess=_tr.active_set(st.active, r),
                                                                C=rings.C, memo=factors)
                            else:
                                z, lam, dphi, it = _tr.box_step(H, g, z_old, bj,
                                                                torque=float(target[j]),
                                                                guess=_tr.active_set(st.active, r),
                                                                C=rings.C, memo=factors)
                            gross = not np.isfinite(dphi)
                            if gross:       # torque beyond full sliding: gross sliding, the
                                # twist turned by the smallest increment at which all slides
                                # (held while the force falls: no work at a held twist)
                                z, lam, dphi = _tr.gross_step(H, g, z_old, bj,
                                                              float(np.sign(target[j])))
                            M = float(g @ z)
                            # the end traction times the slip (+ the release at a held twist),
                            # in the ring solver's energy; the work balances it
                            # (physics.torsion_energy)
                            dW = _te.ring_dissipation(H, z_old, z, lam, held=dphi == 0.0)
                            E_st = 0.5 * float(z @ (H @ z))
                            W_in += E_st - 0.5 * float(z_old @ (H @ z_old)) + dW
                            lam = np.where(bj > 0, lam, 0.0)
                            st.S = st.S + lam
                            slip += _tr.slip_density(lam, r, g)
                            st.z = z
                            st.active = np.where(bj == 0, 2, np.where(lam == 0, 0,
                                                                      np.sign(z))).astype(int)
                            c_stick = None
                        res["gross_sliding"][k] = gross
                        iters += it
                        W_d += dW
                        st.twist = float(target[j]) if ctrl == "twist" else st.twist + dphi
                        M_old = M
                        if progress is not None:
                            progress(1)
                        res["twist"][k] = st.twist
                        res["torque"][k] = M if ctrl == "twist" else (float(target[j]) if not
                                                                      res["gross_sliding"][k] else M)
                        res["dissipated_energy"][k] = W_d
                        if z is None and use_punches and k in snaps:
                            z = _ta.punch_traction(pt, pm, r, G_t)
                        if c_stick is None:
                            if z is None:
                                z = _tpt.traction_at_points(w, r, G_t, rings.table, rings.table_diffs)
                            c_stick = _tr.stick_radius(r, z, bj, aj)
                        res["stick_radius"][k] = c_stick
                        work[k], step_diss[k] = W_in, dW
                        stored[k] = E_st
                        done = k + 1
                        if k in snaps:
                            if z is None:
                                z = _tpt.traction_at_points(w, r, G_t, rings.table, rings.table_diffs)
                            snap_data[k] = {"r": r.copy(), "depth": float(d_arr[j]),
                                            "radius": aj, "shear_torsion": z.copy(),
                                            "pressure": (np.zeros(r.size) if p is None else
                                                         np.where(r < aj, p[j - c0], 0.0)),
                                            "slip": slip.copy(),
                                            "slip_increment": lam_slip.copy()
                                            if use_annulus or use_punches
                                            else _tr.slip_density(lam, r, g)}
                i += n
                cur.update(depth=float(d_arr[-1]) if n else cur["depth"],
                           force=float(res["force"][i - 1]) if n else cur["force"],
                           twist=st.twist, torque=M_old)
        except ContactlabError as err:
            meta = {"built": ["normal", "torsion"], "method": "exact", "n_rings": rings.n_uniform,
                    "rings": rings.n_springs, "aligned": bool(align), "edge_punch": edge_punch,
                    "jump_nodes": int(rings.jumps.size),
                    "n_springs": None, "spacing": spacing, "foundation": repr(rings),
                    "approximate": False, "iterations": iters, "annulus": use_annulus,
                    "fallback_steps": int(fallback)}
            err.partial = PathArrays(res, {s: v for s, v in snap_data.items() if s < done}, meta,
                                     done)
            raise
        meta = {"built": ["normal", "torsion"], "method": "exact", "n_rings": rings.n_uniform,
                "rings": rings.n_springs, "aligned": bool(align), "edge_punch": edge_punch,
                "jump_nodes": int(rings.jumps.size),
                "n_springs": None, "spacing": spacing, "foundation": repr(rings),
                "approximate": False, "iterations": iters,
                "annulus": use_annulus, "punches": use_punches, "fallback_steps": int(fallback),
                "energy": {"work": work, "stored": stored, "dissipated_per_step": step_diss},
                "citations": sources_for("normal", "torsion:exact")}
        return PathArrays(res, snap_data, meta, n_total)


#: influence matrices kept for reuse (:func:`_influence`): at most this many ring sets, and
#: none whose matrices take more than :data:`_CACHE_MAX_BYTES`
_CACHE_SIZE, _CACHE_MAX_BYTES = 4, 32 * 2 ** 20
_CACHE: OrderedDict[tuple, dict[str, Any]] = OrderedDict()
_CACHE_LOCK = threading.Lock()


def _influence(b: np.ndarray, points: np.ndarray, G_t: float, edge_punch: bool,
               jumps: np.ndarray) -> dict[str, Any]:
    """:func:`contactlab.physics.torsion_rings.influence` of one ring set, factored once: the
    matrices depend on the nodes, the points, ``G_t``, the edge punch and the jump nodes only,
    so a run along the same path (or any path with the same contact radii) reuses them (arrays
    read-only; least recently used of :data:`_CACHE_SIZE` sets dropped). Built on one BLAS
    thread: bit-identical for any thread setting."""
    key = (b.tobytes(), points.tobytes(), float(G_t), bool(edge_punch),
           np.asarray(jumps, np.int64).tobytes())
    with _CACHE_LOCK:
        hit = _CACHE.get(key)
        if hit is not None:
            _CACHE.move_to_end(key)
            return hit
    with serial_blas():
        mats: dict[str, Any] = dict(_tr.influence(b, points, G_t, edge_punch=edge_punch,
                                                  jumps=jumps))
    table = _ta.NodeTable(points, b)
    mats["table"], mats["diffs"] = table, _tpt.differences(table)
    arrays = [mats["H"], mats["C"], mats["g"], mats["B"], *mats["lu"], *mats["diffs"],
              *(a for pair in table.arrays.values() for a in pair)]
    for a in arrays:
        a.flags.writeable = False
    if sum(a.nbytes for a in arrays) <= _CACHE_MAX_BYTES:
        with _CACHE_LOCK:
            _CACHE[key] = mats
            while len(_CACHE) > _CACHE_SIZE:
                _CACHE.popitem(last=False)
    return mats


#: contact radii (m) the ring solver takes: its punch-density torques carry ``a⁵`` (and its
#: energies ``a⁵ G_t φ²``), which below 1e-58 m fall into the subnormal range and lose digits
#: (measured: scaled Hertz paths exact to 5e-15 down to a = 3e-58 m, 7e-12 at 3e-63 m, 0.6
#: wrong at 7e-66 m); above 1e50 m a⁵ G_t approaches overflow
_RADIUS_RANGE = (1e-58, 1e50)


#: steps whose ring slip limits are held at once (memory: chunk x rings floats)
_BOUND_CHUNK = 128


def _longest_leaf(seg) -> int:
    """Steps of the longest leaf segment (a repeat's leaves are its own segments' leaves)."""
    inner = getattr(seg, "segments", None)
    if inner is None:
        return int(seg.n_steps)
    return max((_longest_leaf(s) for s in inner), default=0)


def _annulus_step(rings, w, bound, radius, G_t, ctrl, target, twist, active, slip=True,
                  slide=None, memo=None, allow=None):
    """One step on the punch density: the single-slip-annulus step of
    :mod:`contactlab.physics.torsion_annulus` when its checks hold, else the ring solver's
    box-constrained step from the point tractions of ``w`` (its result turned back into a
    density). Returns the new density, the point tractions (or ``None``), the slip increments at
    the points (m), the twist increment, gross sliding, the stick radius (``None``: from the
    tractions), the active set, pivots and what the step's energy needs: the sense of the
    annulus step and the turn of its density (``sense``, ``turn``), or where the ring solver took
    the step its dissipation (``ring``). ``slip=False``
    skips the slip increments where the checks do not need them; ``slide`` is the step's
    full-sliding density when known; ``memo`` the ring solver's factor memo (its ``box_step``);
    ``allow`` the accepted excess beyond ``μ p`` inside the stick radius
    (:func:`contactlab.physics.torsion_annulus.step`)."""
    r, b, jumps = rings.points, rings.boundaries, rings.jumps
    if slide is None:
        slide = _ta.nonnegative_psi(_ta.density(rings.lu, b, jumps, bound, radius))
    if ctrl == "twist":
        out = _ta.step(w, slide, radius, G_t, dphi=target - twist, r=r, bound=bound, slip=slip,
                       table=rings.table, allow=allow)
    else:
        out = _ta.step(w, slide, radius, G_t, target_torque=target, r=r, bound=bound, slip=slip,
                       table=rings.table, allow=allow)
    if out["ok"]:
        s, c, extra = out["sense"], out["c"], out["gross"]
        gross = bool(extra != extra)    # (nan: a torque beyond the sliding torque)
        w_new = out["w"]
        ds = out["slip"]
        # the energy of the step from the twist its density carries (plus a gross turn), not
        # the target (they differ by the root's rounding)
        book = {"sense": s, "turn": out["dpsi"] + (0.0 if gross else float(extra)),
                "gross": 0.0 if gross else float(extra)}
        if gross:
            # torque beyond the sliding torque: the contact slides as a whole onto s·W and its
            # twist is whatever the slip makes it; it turns by the smallest increment at which
            # all of it slides (the rule of the spring routes): the turn of its density where
            # that points the way of the slip (the force rose), else none (the force fell: the
            # twist is held, the step releases energy at no work; a held stage)
            turn = float(out["dpsi"])
            act = np.where(bound == 0, 2, int(s))       # (int arrays already: no astype)
            if s * turn >= 0:
                return (w_new, None, ds, turn, True, 0.0, act, 1,
                        {"sense": s, "turn": turn, "gross": 0.0})
            return (w_new, None, ds, 0.0, True, 0.0, act, 1,
                    {"sense": s, "turn": None, "gross": 0.0})
        dphi = target - twist if ctrl == "twist" else out["dpsi"]
        # the active set as the stick radius, sense and μp (formed if a ring step follows)
        return (w_new, None, ds, dphi, False, c if c < radius else None, (c, s, bound), 1, book)
    # the ring solver's step is incremental: the increment of the point tractions is a hat
    # density added to the exact old density (its jumps at earlier stick radii kept)
    H, g = rings.H, rings.g
    z_old = _tpt.traction_at_points(w, r, G_t, rings.table, rings.table_diffs)
    if ctrl == "twist":
        z, lam, dphi, it = _tr.box_step(H, g, z_old, bound, dphi=target - twist,
                                        guess=_tr.active_set(active, r), C=rings.C, memo=memo)
    else:
        # the ring solver's torque g·z of the old tractions differs from the density's exact
        # torque by its discretisation error: aim its step at the increment of the torque, not
        # at the target in its own measure (near full sliding the difference turns into a
        # large twist error)
        M_w = _ta.torque(w, G_t)
        z, lam, dphi, it = _tr.box_step(H, g, z_old, bound,
                                        torque=target + float(g @ z_old) - M_w,
                                        guess=_tr.active_set(active, r), C=rings.C, memo=memo)
    gross = not np.isfinite(dphi)
    if gross:       # all slides: the smallest turn at which it does (held while the force falls)
        z, lam, dphi = _tr.gross_step(H, g, z_old, bound, float(np.sign(target)))
    lam = np.where(bound > 0, lam, 0.0)
    act = np.where(bound == 0, 2, np.where(lam == 0, 0, np.sign(z))).astype(int)
    w_new = _ta.add(w, _ta.density(rings.lu, b, jumps, z - z_old, b[-1]))
    # its dissipation in its own measure: the sliding traction times the slip, >= 0
    return (w_new, z, _tr.slip_density(lam, r, g), dphi, gross, None, act, it,
            {"ring": _te.ring_dissipation(H, z_old, z, lam, held=dphi == 0.0)})
