"""Fretting wear at constant normal force: the driver behind :meth:`Contact.wear` and its result
:class:`WearResult`.

Archard's law on the 3D profile, ``dh(r)/dN = k p(r) s(r)``, with ``s(r)`` the slip path per
cycle of the 3D surface (four times the slip under monotonic loading to the amplitude, Masing):
the Abel transform of the MDR spring slip for a shift (exact Cattaneo–Mindlin), Jäger's exact
solution for a twist (``method="exact"``) or the MDR springs' twist distribution
(``method="mdr"``, the fast approximation). The worn profile is a piecewise-linear table on a
radial grid; every transform of it is exact for that table (:mod:`contactlab.physics.wear`).

Cycle jumping: one steady loop on the current profile gives the wear rate per cycle; a step of
``ΔN`` cycles is taken with Heun's method (rates at the start and at the Euler prediction), and
``ΔN`` adapts so that the difference of the two predictions, ``ΔN/2 max|r2 - r1|``, stays below
``jump_rtol`` times the depth scale ``d + max h`` (indentation depth of the worn profile plus the
largest wear depth). The energy dissipated in a step uses the same two
rates, so worn volume = (k/μ) × dissipated energy holds to rounding for the table.
"""
from __future__ import annotations

import math

import warnings
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..citations import Cited, sources_for
from ..errors import (ConvergenceError, NotSupportedError, ParameterError, UnknownNameError,
                      ValidityWarning)
from ..params import (FieldsEqual, as_float_array, as_real, check_memory,
                     check_positive, check_time)
from ..physics import wear as _wear
from ..physics import wear_rosenbrock as _ros
from ..profiles import Tabulated
from ._protocol import Result, reporting
from .fretting import (_fresh_g, _mode_and_amplitude, check_contact, fretting_sources, loops,
                       warn_mdr)
from .torsion import MDR_MAP_BASIS, mdr_map_errors, resolve_method

__all__ = ["WearResult", "wear", "SERIES_UNITS", "DEFAULT_GRID", "DEFAULT_JUMP_RTOL",
           "INTEGRATORS", "DEFAULT_INTEGRATOR",
           "MAX_CHECKPOINTS", "MIN_JUMP_RTOL"]

#: Grid intervals of the worn-profile table (docs/fretting.md: convergence under halving).
DEFAULT_GRID = 400
#: Local error of one wear step (Euler vs Heun prediction) relative to the indentation depth.
DEFAULT_JUMP_RTOL = 1e-4
#: Relative difference of the grid's energy per cycle from the loop's (fresh contact) above which
#: wear() warns that the grid does not resolve the slip zone.
GRID_ENERGY_WARN = 0.02
#: Tensile load of the MDR pressure, relative to the compressive, above which the worn profile has
#: left the MDR (its 1D profile dips: a proud island, docs/fretting.md section 6) and wear() warns.
#: Partial-slip runs pass through about 1e-3 for a while as the stick edge steepens (measured).
MDR_TENSILE_WARN = 1e-2
#: Smallest grid the operators accept.
MIN_GRID = 16

#: Wear depth, relative to the largest, that marks the edge of the scar.
SCAR_EDGE = 1e-3

SERIES_UNITS = {"cycles": "1", "depth": "m", "radius": "m", "scar_radius": "m",
                "stick_radius": "m", "volume": "m^3",
                "max_wear_depth": "m", "dissipated_energy": "J", "energy_per_cycle": "J"}


@dataclass(frozen=True, eq=False)
class WearResult(FieldsEqual, Cited, Result):
    """Fretting-wear run: worn profiles at checkpoints and series per wear step.

    Attributes
    ----------
    mode, method : str
        ``"tangential"`` or ``"torsion"``; ``"exact"`` or ``"mdr"`` (shift: ``"mdr"``, exact).
    cycles, depth, radius, scar_radius, stick_radius, volume, max_wear_depth,
    dissipated_energy, energy_per_cycle : ndarray
        Per accepted step (the first entry is the fresh contact): cycle count, indentation depth
        relative to the unworn surface (m), contact radius (m; the region that carries load),
        scar radius (m; outermost radius worn by more than 1e-3 of the largest wear depth),
        stick radius (m), worn volume
        (m³), largest wear depth (m), cumulative energy dissipated by friction (J) and energy
        per cycle (J).
    checkpoints : ndarray
        Cycle counts of the stored profiles (0 first).
    profiles : list of Tabulated
        Worn profile at each checkpoint (heights relative to the table's first value).
    wear_depth : ndarray, shape (n_checkpoints, n_grid + 1)
        Wear depth ``h(r)`` at the grid radii :attr:`r` at each checkpoint, m.
    r : ndarray
        Grid radii, m.
    meta : dict
        ``wear_coefficient``, ``amplitude``, ``force``, ``n_grid``, ``grid_radius``,
        ``jump_rtol``, ``integrator``, ``steps``, ``rejected``, ``rates`` (evaluations),
        ``jacobians`` and ``factorisations`` (implicit route), ``error_estimates`` (relative
        error of the cycle jumps per quantity at the end of the run: ``volume``,
        ``dissipated_energy``, ``max_wear_depth``, ``scar_radius``; not the grid's) and
        ``error_estimate`` (their largest),
        ``mdr_valid_cycles`` (last cycle count at which the worn profile was still a simply
        connected MDR contact; inf when it stayed one, otherwise wear() warned) and
        ``tensile_fraction`` (largest tensile share of the MDR pressure over the run),
        ``citations`` (the sources: ``contactlab.cite(result)``).
    model_error : float
        Largest relative model error of the run (:attr:`model_errors`): a twist with
        ``method="mdr"`` carries the measured MDR-vs-exact error of the energy per cycle at the
        fresh contact's exact stick ratio (the worn volume is the energy times k/μ); a run whose
        worn profile left the MDR (``meta["mdr_valid_cycles"]`` finite) has no error bound
        (``inf``). 0.0 otherwise (a shift, or the exact torsion, on a simply connected contact).
    """

    mode: str
    method: str
    cycles: np.ndarray = field(repr=False)
    depth: np.ndarray = field(repr=False)
    radius: np.ndarray = field(repr=False)
    scar_radius: np.ndarray = field(repr=False)
    stick_radius: np.ndarray = field(repr=False)
    volume: np.ndarray = field(repr=False)
    max_wear_depth: np.ndarray = field(repr=False)
    dissipated_energy: np.ndarray = field(repr=False)
    energy_per_cycle: np.ndarray = field(repr=False)
    checkpoints: np.ndarray = field(repr=False)
    profiles: list = field(repr=False)
    wear_depth: np.ndarray = field(repr=False)
    r: np.ndarray = field(repr=False)
    meta: dict = field(default_factory=dict, repr=False)

    units = SERIES_UNITS
    _basis = MDR_MAP_BASIS

    @property
    def profile(self) -> Tabulated:
        """The worn profile at the last checkpoint."""
        return self.profiles[-1]

    def to_dict(self) -> dict[str, np.ndarray]:
        """Per-step series by name."""
        return {k: getattr(self, k) for k in SERIES_UNITS}

    def plot(self, axes: Any = None, *, units: str = "si"):
        """Profile evolution, scar radius and worn volume against cycles (needs matplotlib).

        ``units="engineering"`` labels µm and µm³ instead of m and m³ (see
        :mod:`contactlab.plotting`); returns the three axes.
        """
        from .. import plotting as pl
        pl.check_units(units)
        pl.pyplot()
        with pl.style():
            if axes is None:
                _, axes = pl.subplots(1, 3, figsize=(11.0, 3.6))
            ax0, ax1, ax2 = axes
            rmax = 1.2 * float(np.max(self.radius))
            keep = self.r <= rmax
            r = pl.scaled(self.r[keep], "m", units)
            for N, prof in zip(self.checkpoints, self.profiles):
                ax0.plot(r, pl.scaled(prof.height(self.r[keep]), "m", units),
                         label=f"N = {N:.3g}")
            ax0.set_xlabel(pl.axis_label("r", "m", units))
            ax0.set_ylabel(pl.axis_label("worn profile f(r)", "m", units))
            ax0.set_title("profile")
            ax0.legend()
            N = np.maximum(self.cycles, 1.0)
            ax1.loglog(N[1:], pl.scaled(self.radius[1:], "m", units), label="contact radius")
            ax1.loglog(N[1:], pl.scaled(np.maximum(self.scar_radius[1:], 1e-300), "m", units),
                       label="scar radius")
            ax1.legend()
            ax1.set_xlabel("cycles")
            ax1.set_ylabel(pl.axis_label("radius", "m", units))
            ax1.set_title("radii")
            ax2.loglog(N[1:], pl.scaled(np.maximum(self.volume[1:], 1e-300), "m^3", units))
            ax2.set_xlabel("cycles")
            ax2.set_ylabel(pl.axis_label("worn volume", "m^3", units))
            ax2.set_title("worn volume")
        return axes


#: peak memory of wear() in floats per (n_grid+1)^2 (its dense grid operators): 23.2 measured
#: with tracemalloc for n_grid = 200..800, shift and twist; rounded up. The same 23.2 peak with
#: integrator="implicit" (n_grid 200 and 400, shift, exact and MDR twist): its Jacobian operators,
#: Jacobian, products and LU factors (about 16 per node pair) are built after the grid
#: operators' temporaries are freed
GRID_FLOATS = 24


#: safety factor of the run's error estimates over the accumulated local errors: on the ladder of
#: tests/unit/effects/test_wear_implicit.py the scar radius of a twist at 0.3 of the twist scale
#: (measured table) differed from the tenfold tighter run by 1.01 times the plain sum
ERROR_SAFETY = 2.0
#: the implicit route's safety factor: on 10^6-cycle gross-slip runs (Hertz, 10x and 20x full
#: sliding, shift and twist, n_grid = 120) the worn volume differed from the tenfold tighter run
#: by 0.98-1.01 times ERROR_SAFETY times the plain sum (the steps that cross a grid node carry a
#: kink the embedded estimate sees only in part); 3 leaves a margin of 1.5
IMPLICIT_ERROR_SAFETY = 3.0

#: an explicit step whose rate changed by more than this fraction of the largest rate over the
#: step (``max|r2 - r1| > STIFF_RATIO max|r1|``, a lower estimate of dN times the stiffest
#: eigenvalue z) adds ``v·|e|`` to the volume's error estimate: Heun damps a real mode by
#: ``1 - z + z²/2``, most at z = 1 and not at all at z = 2. Measured (docs/fretting.md section
#: 8): 1.0 covers the 10^5-cycle Hertz runs 2.8-145 times, 1.5 misses them (0.015-0.27)
STIFF_RATIO = 1.0

#: the cycle-jump integrators: Rosenbrock-W steps (default) and the explicit Heun steps
INTEGRATORS = ("implicit", "explicit")
DEFAULT_INTEGRATOR = "explicit"
#: accepted steps a Jacobian serves before it is computed again (it is also recomputed after a
#: rejected step): a W-method keeps its order with any matrix, a stale one only costs larger
#: error estimates; one Jacobian costs about as much as ten rate evaluations
JACOBIAN_REUSE = 10
#: grid nodes beyond the contact edge that the Jacobian treats as touching
#: (:func:`contactlab.physics.wear_rosenbrock.rate_jacobian`)
JACOBIAN_EDGE = 3
#: a step keeps the LU factors of an earlier step while its length is within this factor of
#: theirs (:func:`contactlab.physics.wear_rosenbrock.rosenbrock_step`)
LU_REUSE = 2.0
#: floor of the implicit steps' error scale (the largest wear depth after the step), relative to
#: the indentation depth: a run that starts unworn is controlled by its wear, not by the depth
IMPLICIT_FLOOR = 1e-6
#: an implicit step ends this fraction past the predicted moment the next grid node beyond the
#: contact edge touches (:func:`_edge_crossing`): the kink of the positive parts then falls at
#: the step's end (0 switches the event off)
EDGE_EVENT = 0.1
#: a rejected step whose error estimate exceeds this many tolerances recomputes a kept Jacobian
JACOBIAN_RETRY = 10.0

#: most checkpoints a run takes: each costs at least one wear step (two rate evaluations on the
#: dense grid) and a stored profile, so their count sets the run time whatever the tolerance
MAX_CHECKPOINTS = 10_000
#: memory per checkpoint per grid node, floats: the wear depth kept for ``wear_depth`` and the
#: stored profile table (radii, heights and its lazily built transform), rounded up
CHECKPOINT_FLOATS = 8
#: smallest ``jump_rtol``: the number of wear steps grows as ``jump_rtol**-0.5`` (28 steps at
#: 1e-3, 3540 at 1e-8 measured on a Hertz shift), while the jump error it controls is already
#: 1e-4 relative at the default and far below the grid's discretisation error (4e-2 at
#: n_grid = 100, docs/fretting.md); below this the steps run into millions for nothing, and at
#: 1e-300 the step floor (1e-9 of the cycle count) makes them unbounded
MIN_JUMP_RTOL = 1e-10


def _checkpoint_sizes(checkpoints: Any, n_grid: int, jump_rtol: float) -> None:
    """Work and memory a run's checkpoints and step tolerance imply, checked before any work."""
    if isinstance(checkpoints, (int, np.integer)) and not isinstance(checkpoints, bool):
        n_ck, shown = int(checkpoints), f"{checkpoints!r}"
    else:
        n_ck = 1 if checkpoints is None else int(np.size(checkpoints))
        shown = f"<{n_ck} cycle numbers>"
    if n_ck > MAX_CHECKPOINTS:
        raise ParameterError(f"checkpoints={shown} is invalid: at most {MAX_CHECKPOINTS} "
                             "checkpoints (each is at least one wear step on the dense grid and a "
                             "stored profile); give fewer, e.g. checkpoints=20.")
    check_memory("wear()", 8.0 * CHECKPOINT_FLOATS * (int(n_grid) + 1) * n_ck,
                 f"checkpoints: {n_ck} stored profiles x {int(n_grid) + 1} grid nodes")
    if jump_rtol < MIN_JUMP_RTOL:
        raise ParameterError(f"jump_rtol={jump_rtol!r} is invalid: the wear-step tolerance must be "
                             f">= {MIN_JUMP_RTOL:g} (the steps grow as jump_rtol**-0.5 while the "
                             "grid's error stays); e.g. jump_rtol=1e-6.")
    steps = wear_steps_lower(n_ck, jump_rtol)
    check_time("wear()", steps * wear_step_seconds(int(n_grid)),
               f"at least {steps:.3g} wear steps ({n_ck} checkpoints, jump_rtol={jump_rtol:g}) on "
               f"the {int(n_grid) + 1}-node grid")


#: run time of one wear step, s: a fixed part, one per dense-grid entry (n_grid + 1)² (the
#: operators' products) and one per (n_grid + 1)³ (the implicit steps' Jacobians and LU
#: factors, kept over several steps). Measured (CPU time, shared 2-core VM at load ~3.5, Hertz
#: shifts): 1.13 ms per accepted step at n_grid = 100 (454 steps), 0.68 ms at 400 (1146 steps),
#: 36 and 43 ms at 700 and 1000 on short runs (32-37 steps, the factorisations not spread);
#: 0.39-0.45 ms at 400 on runs of 4 000-9 000 steps. The formula lies below each (0.21, 0.62,
#: 2.1, 5.2 ms): a lower estimate; benchmarks/time_estimates.py checks it
WEAR_STEP_SECONDS, WEAR_STEP_SECONDS_PER_ENTRY, WEAR_STEP_SECONDS_PER_CUBE = 2e-4, 1e-9, 4e-12
#: wear steps against the worn-volume ratio ``ρ = k N W / (μ π a² d)`` (the volume the fresh
#: contact's wear rate removes in the run, over the contact's volume scale; ``W`` the energy of
#: the fresh loop): at least ``WEAR_STEPS_FACTOR ρ**WEAR_STEPS_POWER`` at the default
#: ``jump_rtol``. Measured (default integrator, n_grid = 100) 26, 209, 1146, 3993 steps at
#: ρ = 0.049-19.7 on a Hertz shift, 65-9144 at ρ = 0.14-55 on an n = 3 power-law shift and
#: 1-243 at ρ = 3e-4-0.12 on a Hertz twist; ``200 ρ^0.8`` lies below every one (by 1.2-6.7)
WEAR_STEPS_FACTOR, WEAR_STEPS_POWER = 200.0, 0.8


def wear_step_seconds(n_grid: int) -> float:
    """Estimated run time (s) of one wear step on the ``n_grid`` grid."""
    n = n_grid + 1.0
    return WEAR_STEP_SECONDS + WEAR_STEP_SECONDS_PER_ENTRY * n**2 + WEAR_STEP_SECONDS_PER_CUBE * n**3


def wear_steps_lower(n_checkpoints: int, jump_rtol: float, wear_ratio: float = 0.0) -> float:
    """A lower bound of a run's wear steps: one per checkpoint at least, the steps the jump
    tolerance asks for (``0.9 jump_rtol**-0.5``: 28 at 1e-3, 3540 at 1e-8 measured on a Hertz
    shift, more on others), and those the amount of wear asks for, growing with the cycles:
    ``WEAR_STEPS_FACTOR wear_ratio**WEAR_STEPS_POWER`` (``wear_ratio``: the worn-volume ratio
    ``k N W / (μ π a² d)``, see :data:`WEAR_STEPS_FACTOR`), fewer in proportion to
    ``jump_rtol**-0.5`` above the default tolerance (never more below it: a lower bound)."""
    by_wear = WEAR_STEPS_FACTOR * max(wear_ratio, 0.0) ** WEAR_STEPS_POWER
    by_wear *= min(1.0, math.sqrt(DEFAULT_JUMP_RTOL / jump_rtol))
    return max(float(n_checkpoints), 0.9 / math.sqrt(jump_rtol), by_wear)


def _error_estimates(r: np.ndarray, h: np.ndarray, v: np.ndarray, err_h: np.ndarray,
                     err_V: float, f0: np.ndarray | None = None,
                     safety: float = ERROR_SAFETY, threshold: bool = False,
                     err_V_stiff: float = 0.0) -> dict[str, float]:
    """Relative error estimates of the cycle jumps at the end of the run from the accumulated
    local error estimates: ``err_h`` per node (``Σ|e_n|``) and ``err_V`` of the volume
    (``Σ|v·e_n|``). The wear equation damps a perturbation of the worn depth (a locally deeper
    wear unloads that spot), so the global error stays near the sum of the local ones; the scar
    radius moves by what ``h ± err_h`` moves it. Each is taken ``safety`` times: the
    moving contact edge is not damped, and there the sum alone fell short (see the constant).

    The outermost worn node takes at least the accumulated error of its inner neighbour (the
    grid's edge term): it wears from the moment the contact edge reaches it, and that moment is
    set by the depths inside it, which its own small local errors (its rate is small) do not
    see. The scar radius sits on that node, ``SCAR_EDGE`` of the largest depth, so its depth
    error is a large part of its depth (docs/fretting.md section 8).

    In gross slip the scar is a worn cap of the profile ``f0``, and its edge is where the load
    puts the contact edge: a volume error ``δV`` moves it by ``δV/(π s² f0'(s))`` (the cap of
    radius ``s`` grows by ``π s² f0'(s)`` per unit radius), whatever the local errors at the
    edge.

    ``threshold=True`` adds the threshold term (the implicit route): the wear equation spreads
    local errors over the cap, so every worn node carries the cap's depth error
    ``δh = δV/(π s²)`` besides its own sum, and the scar moves by where the 10^-3 crossing of
    ``h ± (e + δh)`` lands. Between the outermost worn node and the first unworn one the slope
    of the interpolated depth is ``h_m/Δr``, far below ``f0'(s)`` when that node is just above
    the threshold. The scar radius takes the largest of the terms (docs/fretting.md section
    8).

    ``err_V_stiff`` (explicit route) is ``Σ v·|e_n|`` over the steps at Heun's stability limit
    (``STIFF_RATIO``): there the node errors alternate in sign and cancel in ``v·e_n``, but
    the never-negative wear rate turns them into volume. It is added to the volume's and the
    energy's sums only (docs/fretting.md section 8, the stability-limit term)."""
    V = float(v @ h)
    hm = float(np.max(h))
    if hm <= 0:
        return {"volume": 0.0, "dissipated_energy": 0.0, "max_wear_depth": 0.0,
                "scar_radius": 0.0}

    def scar(y: np.ndarray) -> float:
        ym = float(np.max(y))
        return _wear.contact_radius(r, y - SCAR_EDGE * ym) if ym > 0 else 0.0

    s0 = scar(h)
    e = err_h.copy()
    m = int(np.flatnonzero(h > 0)[-1])
    if m > 0:
        e[m] = max(e[m], e[m - 1])
    e *= safety
    ds = max(abs(scar(h + e) - s0), abs(scar(h - e) - s0))
    if f0 is not None and s0 > 0:
        j = min(int(s0 / r[1]), r.size - 2)
        slope = float(f0[j + 1] - f0[j]) / float(r[1])
        if slope > 0:
            # the cap's depth error: the volume error spread over the cap
            dh = safety * err_V / (math.pi * s0 * s0)
            ds = max(ds, dh / slope)
            if threshold:
                # the same depth error on every worn node moves the interpolated crossing
                # by dh over the slope of the grid segment it lies on
                ec = e + np.where(h > 0, dh, 0.0)
                ds = max(ds, abs(scar(h + ec) - s0), abs(scar(h - ec) - s0))
    eV = safety * (err_V + err_V_stiff) / V
    return {"volume": eV, "dissipated_energy": eV,
            "max_wear_depth": float(np.max(e)) / hm,
            "scar_radius": ds / s0 if s0 > 0 else 0.0}


def _edge_crossing(ops: dict, f: np.ndarray, d: float, rate: np.ndarray,
                   overshoot: float) -> float:
    """Cycles until the first grid node beyond the contact edge touches, predicted from the
    current rates and taken ``1 + overshoot`` times (inf when the edge does not advance).

    The gap of a node is ``u = d - g`` with ``g = G f``; under the rates ``R`` it changes at
    ``du/dN = c·R - (G R)_j``, where ``c·R`` is the depth's rate from the force balance on the
    contact set ``C`` (``Σ_C w1 (G R) / Σ_C w1``). A step that ends just past the crossing keeps
    the kink of the positive parts at its very end, where it costs the least accuracy."""
    g = _wear.transform(ops, f)
    inside = d - g > 0
    if not np.any(inside) or inside[-1]:
        return math.inf
    j = int(np.flatnonzero(inside)[-1]) + 1
    dg = _wear.transform(ops, rate)
    w = np.where(inside, ops["w1"], 0.0)
    du = float(w @ dg) / float(np.sum(w)) - float(dg[j])
    if du <= 0:
        return math.inf
    return (1.0 + overshoot) * (g[j] - d) / du


def _checkpoints(cycles: float, checkpoints: Any) -> np.ndarray:
    if checkpoints is None:
        return np.array([cycles])
    if isinstance(checkpoints, (int, np.integer)) and not isinstance(checkpoints, bool):
        if checkpoints < 1:
            raise ParameterError(f"checkpoints={checkpoints!r} is invalid: give a count >= 1 or "
                                 "an array of cycle numbers.")
        pts = np.geomspace(min(1.0, cycles), cycles, int(checkpoints))
        return np.unique(pts)
    pts = as_float_array("checkpoints", checkpoints).ravel()
    if np.any(pts <= 0) or np.any(pts > cycles):
        raise ParameterError(f"checkpoints={checkpoints!r} is invalid: every checkpoint must "
                             f"satisfy 0 < checkpoint <= cycles={cycles!r}.")
    return np.unique(np.append(pts, cycles))


def _grid_radius(contact, mode: str, F: float, amp: float, k: float, cycles: float,
                 fresh: dict, a0: float, d0: float) -> float:
    """Grid extent: partial slip, twice the radius where g reaches the limiting depth; gross
    slip, the cap whose volume bounds the worn volume (every point sliding the amplitude)."""
    prof = contact.profile
    c0 = float(fresh["stick_radius"][0])
    gross = int(fresh["regime"][0]) == 2
    if not gross and c0 > 0:
        gc = float(prof._g(np.array(c0)))
        gint = float(prof._g_integral(np.array(c0)))
        d_lim = (F / (2 * contact.moduli.normal) + gint) / c0
        r_lim = float(prof._radius_of_depth(np.array(d_lim))) if d_lim > gc else a0
        return 2.0 * max(r_lim, a0)

    def cap(R: float) -> float:
        rr = np.linspace(0.0, R, 401)
        y = 2 * np.pi * rr * (prof.height(np.array(R)) - prof.height(rr))
        return float(np.sum((y[1:] + y[:-1]) * np.diff(rr)) / 2)

    lo, hi = a0, a0
    def bound(R: float) -> float:
        L = amp if mode == "tangential" else amp * R
        return 4.0 * k * F * L * cycles
    limit = min(prof.max_radius, 1e6 * a0)
    while cap(hi) < bound(hi) and hi < limit:
        lo, hi = hi, min(2 * hi, limit)
    for _ in range(40):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if cap(mid) < bound(mid) else (lo, mid)
    return 1.3 * max(hi, 1.25 * a0)


@reporting()
def wear(contact, *, force: Any, displacement_amplitude: Any = None, twist_amplitude: Any = None,
         wear_coefficient: Any, cycles: Any, method: str | None = None, checkpoints: Any = None,
         n_grid: int = DEFAULT_GRID, max_radius: Any = None,
         jump_rtol: float = DEFAULT_JUMP_RTOL,
         integrator: str = DEFAULT_INTEGRATOR) -> WearResult:
    """Implementation of :meth:`contactlab.Contact.wear` (see there)."""
    if not isinstance(integrator, str) or integrator not in INTEGRATORS:
        raise UnknownNameError(f"integrator={integrator!r} is invalid: choose one of "
                               f"{', '.join(map(repr, INTEGRATORS))} (implicit: Rosenbrock steps "
                               "limited by accuracy; explicit: Heun steps, the reference).")
    check_contact(contact, "wear()")
    mode, key, amp_arr = _mode_and_amplitude("wear()", displacement_amplitude, twist_amplitude)
    if amp_arr.ndim != 0:
        raise ParameterError(f"{key} has shape {amp_arr.shape}: wear() takes one amplitude.")
    amp = float(amp_arr)
    F = check_positive("force", force, "the normal force", "N")
    k = as_real("wear_coefficient", wear_coefficient,
                "Archard's coefficient k = K/H must be a real number >= 0 1/Pa")
    if not (k >= 0 and np.isfinite(k)):
        raise ParameterError(f"wear_coefficient={wear_coefficient!r} is invalid: Archard's "
                             "coefficient k = K/H must be >= 0 1/Pa.")
    N_end = check_positive("cycles", cycles, "the number of cycles")
    jump_rtol = check_positive("jump_rtol", jump_rtol, "the wear-step tolerance")
    if not isinstance(n_grid, (int, np.integer)) or isinstance(n_grid, bool) or n_grid < MIN_GRID:
        raise ParameterError(f"n_grid={n_grid!r} is invalid: give an integer >= {MIN_GRID}.")
    check_memory("wear()", GRID_FLOATS * 8.0 * (int(n_grid) + 1) ** 2,
                 f"n_grid={int(n_grid)}: dense (n_grid+1)^2 grid operators")
    _checkpoint_sizes(checkpoints, int(n_grid), jump_rtol)
    if np.isfinite(contact.profile.wall_radius):
        raise NotSupportedError(f"wear() of {contact.profile!r}: a profile with a wall (flat "
                                "punch) cannot be worn into a table; use a rounded punch "
                                "(TruncatedParaboloid) instead.")
    if mode == "torsion":
        method = resolve_method(contact, method)
        if method == "no-slip":
            raise NotSupportedError("wear() with method='no-slip': nothing slips, nothing wears.")
    elif method not in (None, "mdr", "exact"):
        raise UnknownNameError(f"method={method!r} is invalid for a shift: leave method=None.")
    else:
        method = "mdr"
    ck = _checkpoints(N_end, checkpoints)
    E, mu = contact.moduli.normal, contact.friction
    ns = contact.normal(force=F)
    a0, d0 = float(ns._radius), float(ns._depth)
    one = lambda v: np.atleast_1d(float(v))                     # noqa: E731
    fresh = loops(contact, mode, method, one(a0), one(d0), one(F), one(amp), "energy_ratio", 0.2)
    if mode == "torsion" and method == "mdr":
        warn_mdr(contact, one(amp), one(a0), one(d0), ("worn_volume", "stick_radius"))
    # the wear the run removes sets its steps, which grow with the cycles: checked now that the
    # fresh loop's energy is known, before the grid and the wear steps
    W_fresh = float(fresh["energy"][0])
    ratio = (k * N_end * W_fresh / (mu * math.pi * a0 * a0 * d0)
             if a0 > 0 and d0 > 0 and mu and np.isfinite(W_fresh) else 0.0)
    n_ck = 1 if checkpoints is None else (int(checkpoints) if isinstance(
        checkpoints, (int, np.integer)) else int(np.size(checkpoints)))
    # the implicit steps do not grow with the wear (2040 steps at ratio ~2e3, where the explicit
    # law gives ~9e4): only the checkpoints and the tolerance bound them from below
    steps_est = wear_steps_lower(n_ck, jump_rtol, ratio if integrator == "explicit" else 0.0)
    check_time("wear()", steps_est * wear_step_seconds(int(n_grid)),
               f"at least {steps_est:.3g} wear steps: {N_end:.4g} cycles remove {ratio:.3g} times "
               f"the contact's volume scale pi a^2 d at the fresh wear rate (k={k:g} 1/Pa), on "
               f"the {int(n_grid) + 1}-node grid")
    R = (float(check_positive("max_radius", max_radius, "the grid radius", "m"))
         if max_radius is not None else _grid_radius(contact, mode, F, amp, k, N_end, fresh,
                                                      a0, d0))
    R = min(R, 0.999 * contact.profile.max_radius)
    if R <= a0:
        raise ParameterError(f"max_radius={R!r} m is invalid: the grid must extend beyond the "
                             f"contact radius {a0!r} m.")
    ops = _wear.operators(R, int(n_grid))
    r = ops["r"]
    f0 = np.asarray(contact.profile.height(r), float)
    v = ops["v"]
    edge = 0.9 * R

    implicit = integrator == "implicit"

    def state(h: np.ndarray):
        g = _wear.transform(ops, f0 + h)
        try:
            d = _wear.normal_depth(g, ops["w1"], E, F)
        except OverflowError:
            d = np.inf
        if not np.isfinite(d):
            raise ConvergenceError(f"wear(): the contact outgrew the grid (radius {R!r} m); give "
                                   "a larger max_radius=.")
        if mode == "tangential":
            q, c, a = _wear.tangential_rate(ops, g, d, E, contact.moduli.tangential, mu, amp,
                                            implicit)
        else:
            q, c, a = _wear.torsion_rate(ops, g, d, E, contact.moduli.torsional, mu, amp, method,
                                         implicit)
        if a > edge:
            raise ConvergenceError(f"wear(): the contact radius {a!r} m reached 90 % of the grid "
                                   f"radius {R!r} m after some wear; give a larger max_radius=.")
        return q, d, c, a

    q1, d, c, a = state(np.zeros(r.shape))
    W_grid = 4.0 * mu * float(v @ q1)
    W_loop = float(fresh["energy"][0])
    grid_error = W_grid / W_loop - 1.0 if W_loop > 0 else 0.0
    if method != "mdr" or mode == "tangential":
        if abs(grid_error) > GRID_ENERGY_WARN:
            warnings.warn(f"wear(): the grid of n_grid={n_grid} intervals over {R:.4g} m resolves "
                          f"the slip zone (width {a - c:.3g} m) poorly: its energy per cycle "
                          f"differs from the loop's by {grid_error:+.2%}. Increase n_grid or "
                          "give a smaller max_radius=.", ValidityWarning, stacklevel=3)
    h = np.zeros(r.shape)
    N = 0.0
    energy = 0.0
    series: dict[str, list[Any]] = {kk: [] for kk in SERIES_UNITS}

    def record(N, d, a, c, h, energy, q):
        series["cycles"].append(N)
        series["depth"].append(d + h[0])
        series["radius"].append(a)
        series["stick_radius"].append(c)
        hm = float(np.max(h))
        series["scar_radius"].append(_wear.contact_radius(r, h - SCAR_EDGE * hm) if hm > 0
                                     else 0.0)
        series["volume"].append(float(v @ h))
        series["max_wear_depth"].append(float(np.max(h)))
        series["dissipated_energy"].append(energy)
        series["energy_per_cycle"].append(4.0 * mu * float(v @ q))

    record(N, d, a, c, h, energy, q1)
    tensile = [_wear.tensile_fraction(ops, _wear.transform(ops, f0), d, E)]
    valid_until = np.inf                 # last accepted cycle count the MDR still describes
    profiles = [Tabulated(r, f0)]
    depths = [h.copy()]
    stops = list(ck)
    rate_max = 4.0 * k * float(np.max(q1))
    dN = N_end if rate_max == 0 else min(N_end, 0.01 * d / rate_max)
    steps = rejected = evals = jacobians = 0
    rejected_last = False
    G_mod = contact.moduli.tangential if mode == "tangential" else contact.moduli.torsional
    jops = _ros.jacobian_operators(ops, E) if implicit else {}
    J: np.ndarray | None = None
    J_fresh = False                      # J was computed on the current profile
    lu: tuple | None = None              # factors of I - γ dN_lu J
    dN_lu = 0.0
    factorisations = 0
    J_age = 0                            # accepted steps since J was computed
    J_edge = -1                          # contact edge (grid cell of a) when J was computed
    err_h = np.zeros(r.shape)            # accumulated |local error| per node (error estimate)
    err_V = 0.0                          # accumulated |local error| of the volume
    err_Vs = 0.0                         # explicit steps at the stability limit: Σ v·|e_n|

    last: list[Any] = [None, None]           # the implicit step's last state: (y, state(y))
    n_rate = [0]

    def rate(y: np.ndarray) -> np.ndarray:
        st = state(y)
        last[0], last[1] = y, st
        n_rate[0] += 1
        return 4.0 * k * st[0]

    while stops:
        target = stops[0]
        dN = min(dN, target - N)
        r1 = 4.0 * k * q1
        evals += 1
        tol = jump_rtol * (d + float(np.max(h)))
        edge_cell = int(a / ops["dr"])
        if implicit and (J is None or J_age >= JACOBIAN_REUSE or (rejected_last and not J_fresh)
                         or edge_cell != J_edge):
            J = 4.0 * k * _ros.rate_jacobian(ops, jops, _wear.transform(ops, f0 + h), d, E, G_mod,
                                             mu, amp, mode, method, JACOBIAN_EDGE)
            jacobians += 1
            J_fresh, J_age, lu, J_edge = True, 0, None, edge_cell
        if implicit and EDGE_EVENT > 0:
            dN = min(dN, _edge_crossing(ops, f0 + h, d, r1, EDGE_EVENT))
        if implicit and (lu is None or not 1.0 / LU_REUSE <= dN / dN_lu <= LU_REUSE):
            assert J is not None
            lu, dN_lu = _ros.factor(J, dN), dN
            factorisations += 1
        try:
            if implicit:
                assert J is not None and lu is not None
                h_new, e_vec, _ = _ros.rosenbrock_step(rate, h, r1, dN, J, lu, dN_lu)
                err = float(np.max(np.abs(e_vec)))
                # relative to the wear itself: the depth scale d hides errors of a shallow scar
                tol = jump_rtol * max(float(np.max(h_new)), IMPLICIT_FLOOR * d)
            else:
                q2, *_ = state(h + dN * r1)
        except ConvergenceError:        # a stage or prediction left the grid: a smaller jump
            if dN <= 1e-9 * max(N, 1.0):
                raise
            rejected += 1
            rejected_last = True
            dN *= 0.25
            continue
        if not implicit:
            r2 = 4.0 * k * q2
            err = 0.5 * dN * float(np.max(np.abs(r2 - r1)))
            e_vec = 0.5 * dN * (r2 - r1)
        if err <= tol or dN <= 1e-9 * max(N, 1.0):
            if implicit:
                dE = ((mu / k) * float(v @ (h_new - h)) if k > 0
                      else dN * 4.0 * mu * float(v @ q1))
                h = h_new
                energy += dE
                J_fresh = False
                J_age += 1
            else:
                h = h + 0.5 * dN * (r1 + r2)
                energy += 0.5 * dN * 4.0 * mu * float(v @ (q1 + q2))
                if float(np.max(np.abs(r2 - r1))) > STIFF_RATIO * float(np.max(np.abs(r1))):
                    # dN times the stiffest rate's eigenvalue near Heun's limit: the node
                    # errors alternate in sign, cancel in v·e, and wear only adds depth
                    err_Vs += float(v @ np.abs(e_vec))
            err_h += np.abs(e_vec)
            err_V += abs(float(v @ e_vec))
            N = target if target - (N + dN) <= 1e-12 * target else N + dN
            if implicit and last[0] is h:
                q1, d, c, a = last[1]           # the step evaluated its end state
            else:
                q1, d, c, a = state(h)
                evals += 1
            steps += 1
            rejected_last = False
            record(N, d, a, c, h, energy, q1)
            tensile.append(_wear.tensile_fraction(ops, _wear.transform(ops, f0 + h), d, E))
            if tensile[-1] > MDR_TENSILE_WARN and np.isinf(valid_until):
                valid_until = series["cycles"][-2]
            if N >= target:
                stops.pop(0)
                profiles.append(Tabulated(r, f0 + h))
                depths.append(h.copy())
        else:
            rejected += 1
            # a rejection far beyond the tolerance is a stiff mode the kept Jacobian missed;
            # one near it is the step size (a node crossing the contact edge)
            rejected_last = err > JACOBIAN_RETRY * tol
        if implicit:
            grow = 4.0 if err == 0 else min(4.0, max(0.2, 0.9 * (tol / err) ** (1.0 / 3.0)))
        else:
            grow = 4.0 if err == 0 else min(4.0, max(0.2, 0.9 * np.sqrt(tol / err)))
        dN = max(dN * grow, 1e-9 * max(N, 1.0))
    estimates = _error_estimates(r, h, v, err_h, err_V, f0,
                                 IMPLICIT_ERROR_SAFETY if implicit else ERROR_SAFETY, implicit,
                                 err_Vs)
    meta = {"wear_coefficient": k, "amplitude": amp, "force": F, "n_grid": int(n_grid),
            "grid_radius": R, "jump_rtol": jump_rtol, "integrator": integrator, "steps": steps,
            "rejected": rejected, "rates": evals + n_rate[0] + 1, "jacobians": jacobians,
            "factorisations": factorisations,
            "error_estimate": max(estimates.values()), "error_estimates": estimates,
            "fresh_energy_per_cycle": float(fresh["energy"][0]),
            "friction": mu, "fresh_grid_energy_error": grid_error,
            "mdr_valid_cycles": float(valid_until), "tensile_fraction": float(max(tensile)),
            "citations": fretting_sources(mode, method) + sources_for("wear")}
    if np.isfinite(valid_until):
        warnings.warn(f"wear(): after {valid_until:.4g} cycles the worn profile left the MDR: its "
                      "1D profile dips (a proud unworn stick zone with a steep edge: torsion at "
                      "large twist, or a small stick zone in partial slip), so the contact is no "
                      "longer simply connected and the MDR "
                      f"pressure turns tensile ({max(tensile):.2g} of the load). Results beyond "
                      "that cycle count are not reliable (meta['mdr_valid_cycles']).",
                      ValidityWarning, stacklevel=3)
    errs = {}
    if mode == "torsion" and method == "mdr":
        e = mdr_map_errors(contact, one(amp), one(a0), one(d0), _fresh_g(contact, one(a0),
                                                                         one(d0)), ("energy",))
        errs = {"volume": float(e["energy"][0]), "dissipated_energy": float(e["energy"][0])}
        meta["model_error_basis"] = MDR_MAP_BASIS + " (energy per cycle of the fresh contact)"
    if np.isfinite(valid_until):
        errs = {k: float("inf") for k in ("volume", "dissipated_energy", "max_wear_depth")}
        meta["model_error_basis"] = (f"the worn profile left the MDR after {valid_until:.4g} "
                                     "cycles (meta['mdr_valid_cycles']): no error bound beyond")
    if errs:
        meta["model_errors"] = errs
    arr = {kk: np.asarray(vv, float) for kk, vv in series.items()}
    return WearResult(mode, method, arr["cycles"], arr["depth"], arr["radius"],
                      arr["scar_radius"], arr["stick_radius"], arr["volume"], arr["max_wear_depth"],
                      arr["dissipated_energy"], arr["energy_per_cycle"],
                      np.concatenate([[0.0], ck]), profiles, np.array(depths), r.copy(), meta)
