"""Adhesive (JKR) contacts: the drivers behind :meth:`Contact.normal` (with
``work_of_adhesion > 0``), :meth:`Contact.pull_off` and :meth:`Contact.adhesion_cycle`, and their
results :class:`AdhesiveNormalState` and :class:`AdhesionCycle`.

The kernels (Heß rule, stability function, branch scan, solves on a branch) are in
:mod:`contactlab.physics.adhesion`.
"""
from __future__ import annotations

import warnings
from dataclasses import dataclass, field
from functools import cached_property
from typing import Any

import numpy as np

from ..citations import Cited, sources_for
from ..errors import OutsideTheoryError, ParameterError, ValidityWarning
from ..params import FieldsEqual, as_float_array, exactly_one
from ..physics import normal as _normal
from ..physics.adhesion import (Branches, _limit, branches, check_branch, depth_of_radius,
                                force_of_radius, phi, solve_depth, solve_force)
from ._protocol import Result, reporting
from .normal import NormalState, _scalar_or_array, warn_outside_validity
from .sizes import ADHESIVE_NORMAL_BYTES_PER_LOAD, PEAK_RADII, check_elements, check_peak

__all__ = ["AdhesiveNormalState", "AdhesionCycle", "adhesive_normal", "pull_off", "adhesion_cycle",
           "contact_flags", "contact_branches", "CYCLE_UNITS"]

#: units of the columns of an adhesion cycle (CSV headers)
CYCLE_UNITS = {"depth": "m", "force": "N", "radius": "m", "in_contact": "1"}


def contact_branches(contact) -> Branches:
    """Branch structure of an adhesive contact (scanned once per contact; the scan is
    deterministic, so the cache never changes a result)."""
    cached = contact.__dict__.get("_jkr_branches")
    if cached is None:
        cached = branches(contact.profile, contact.moduli.normal, contact.work_of_adhesion)
        contact.__dict__["_jkr_branches"] = cached
    return cached


@dataclass(frozen=True, eq=False)
class AdhesiveNormalState(NormalState):
    """State of an adhesive (JKR) normal contact.

    Same interface as :class:`~contactlab.NormalState`; ``.pressure(r)`` carries the tensile
    edge term ``(E*/π)(d - g(a))/sqrt(a² - r²)`` and ``.displacement(r)`` the matching field.

    Attributes
    ----------
    stiffness : float or ndarray
        Incremental stiffness along the equilibrium curve, ``dF/dd = 2E* a (φ-3/2)/(φ-1/2)``
        with ``φ = a g'(a)/Δl(a)``, N/m (zero at the force-controlled pull-off, infinite at the
        displacement-controlled one; ``2E* b`` when pinned at a punch wall).
    meta : dict
        Besides the usual keys: ``control``, ``branch``, ``work_of_adhesion``,
        ``stable_under_force`` and ``stable_under_displacement`` (bool arrays).
    """

    _stiff: Any = field(default=None, repr=False)

    def __repr__(self) -> str:
        return self._summary_repr()

    @property
    def stiffness(self) -> Any:
        return _scalar_or_array(self._stiff)

    @property
    def surface_energy(self) -> Any:
        """Adhesion energy of the contact area, ``-π a² Δγ``, J."""
        return _scalar_or_array(-np.pi * self._radius**2 * self.contact.work_of_adhesion)

    @cached_property
    def _edge_g(self) -> np.ndarray:
        """``g(a)`` itself: the adhesive edge term ``d - g(a) = -Δl`` is the physics here."""
        return self._g_at_radius

    @property
    def peak_pressure(self) -> Any:
        """Largest (compressive) pressure over the contact, Pa (sampled on 1024 radii).

        ``inf`` only where the edge term is compressive (an adhesive flat punch pushed in).
        """
        check_peak(self)
        rho = np.linspace(0.0, 1.0, PEAK_RADII + 1)[:-1]
        a = self._radius[..., None]
        val, _ = _normal.pressure(self.contact.profile, self.contact.moduli.normal, rho * a, a,
                                  self._depth[..., None], self._g_at_radius[..., None],
                                  self.contact.rtol)
        compressive_edge = (self._radius > 0) & (self._depth > self._g_at_radius)
        peak = np.where(compressive_edge, np.inf, np.max(val, axis=-1))
        return _scalar_or_array(np.where(self._radius > 0, peak, 0.0))


@dataclass(frozen=True, eq=False)
class AdhesionCycle(FieldsEqual, Result, Cited):
    """An approach/retraction history of an adhesive contact (JKR hysteresis).

    Attributes
    ----------
    control : str
        ``"depth"`` or ``"force"``.
    depth, force, radius : ndarray
        Per step, m, N, m (out of contact: force and radius 0; under force control the depth
        out of contact is reported as 0).
    in_contact : ndarray of bool
        Contact flag per step.
    jumps : ndarray of int
        Steps at which contact was made or lost (the state changes discontinuously there).
    pull_off_value : float
        Depth (m) or force (N) below which contact is lost.
    model_error : float
        0.0: exact in the JKR limit [Heß11] (large Tabor parameter).
    """

    control: str
    depth: np.ndarray
    force: np.ndarray
    radius: np.ndarray
    in_contact: np.ndarray
    jumps: np.ndarray
    pull_off_value: float
    meta: dict = field(default_factory=dict, repr=False)

    units = CYCLE_UNITS

    def to_dict(self) -> dict[str, Any]:
        """Per-step arrays as a dict (for pandas/CSV)."""
        return {"depth": self.depth, "force": self.force, "radius": self.radius,
                "in_contact": self.in_contact}

    def plot(self, axes: Any = None, *, units: str = "si"):
        """Force against depth (the JKR hysteresis, jumps marked) and the contact radius per
        step (needs matplotlib); returns the two axes. ``units="engineering"`` labels µm and mN
        (see :mod:`contactlab.plotting`)."""
        from .. import plotting as pl
        pl.check_units(units)
        pl.pyplot()
        with pl.style():
            if axes is None:
                fig, axes = pl.subplots(1, 2, figsize=(9.0, 3.6))
                fig.suptitle(f"adhesion cycle ({self.control} control)")
            ax1, ax2 = axes
            ax1.plot(pl.scaled(self.depth, "m", units), pl.scaled(self.force, "N", units))
            if self.jumps.size:
                ax1.plot(pl.scaled(self.depth[self.jumps], "m", units),
                         pl.scaled(self.force[self.jumps], "N", units), "o", label="jumps")
                ax1.legend()
            ax1.set_xlabel(pl.axis_label("depth", "m", units))
            ax1.set_ylabel(pl.axis_label("force", "N", units))
            ax2.plot(np.arange(self.radius.size), pl.scaled(self.radius, "m", units))
            ax2.set_xlabel("step")
            ax2.set_ylabel(pl.axis_label("contact radius", "m", units))
            ax2.set_ylim(bottom=0.0)
        return axes


# ---------------------------------------------------------------------------- drivers
def adhesion_sources(profile: Any) -> tuple[str, ...]:
    """Source tags of an adhesive computation on ``profile`` (see :mod:`contactlab.citations`)."""
    punch = ("adhesion:flat_punch",) if getattr(profile, "name", "") == "flat_punch" else ()
    return sources_for("normal", "adhesion", *punch)


def _state(contact, d: np.ndarray, a: np.ndarray, pinned: np.ndarray, control: str,
           branch: str, F: np.ndarray | None = None):
    prof, E, w = contact.profile, contact.moduli.normal, contact.work_of_adhesion
    if F is None:
        F = force_of_radius(prof, E, w, a, d)
    F = np.where(a > 0, F, 0.0)
    warn_outside_validity(prof, a, stacklevel=5)
    if np.any(a > 0):
        prof._check_monotone_upto(float(np.max(a)), float(np.max(np.where(a > 0, d, -np.inf))))
    # stiffness dF/dd along the equilibrium curve; 2E*b when pinned at a wall, 0 when detached
    with np.errstate(invalid="ignore", divide="ignore"):
        ph = np.where(a > 0, phi(prof, E, w, np.maximum(a, 1e-300)), 0.0)
        k = 2 * E * a * (ph - 1.5) / (ph - 0.5)
    k = np.where(pinned, 2 * E * a, np.where(a > 0, k, 0.0))
    k = np.where(np.isnan(k), 2 * E * a, k)     # φ = ∞ (slope jump at a flat rim)
    k = np.where(np.abs(ph - 0.5) < 1e-9, np.inf, k)   # at the fixed-grip pull-off
    br = contact.__dict__.get("_jkr_branches")
    meta = {"routes": {"g": prof.g_route}, "rtol": contact.rtol, "control": control,
            "branch": branch, "work_of_adhesion": w, "citations": adhesion_sources(prof)}
    if br is not None:
        meta["stable_under_force"] = (a >= br.a_force * (1 - 1e-9)) & (a > 0)
        meta["stable_under_displacement"] = (a >= br.a_disp * (1 - 1e-9)) & (a > 0)
    return AdhesiveNormalState(contact, np.asarray(d, float), np.asarray(a, float),
                               np.asarray(F, float), meta, np.asarray(k, float))


def adhesive_normal(contact, *, depth: Any = None, force: Any = None, radius: Any = None,
                    branch: str = "stable"):
    """JKR normal contact through the MDR (Heß rule) for given depth, force or contact radius.

    Parameters
    ----------
    contact : Contact
        With ``work_of_adhesion > 0``.
    depth : float or array_like, optional
        Indentation depth ``d``, m (may be negative). Depths below the displacement-controlled
        pull-off depth give the detached state (radius 0, force 0).
    force : float or array_like, optional
        Normal force, N (negative = tensile). Forces below the force-controlled pull-off force
        raise :class:`~contactlab.errors.OutsideTheoryError` (no equilibrium exists).
    radius : float or array_like, optional
        Contact radius ``a``, m (direct; every ``a > 0`` is an equilibrium, stable or not).
    branch : {"stable", "unstable"}
        For ``depth=``/``force=``: ``"stable"`` (default) is the equilibrium stable under that
        control, the solution with the largest radius; ``"unstable"`` the smaller-radius solution
        that exists between the pull-off point and ``a → 0`` (a ``ParameterError`` names the
        reachable range otherwise).

    Returns
    -------
    AdhesiveNormalState
        ``meta["stable_under_force"]`` and ``meta["stable_under_displacement"]`` flag each state.

    Notes
    -----
    ``d(a) = g(a) - sqrt(2π a Δγ/E*)`` and ``F(a) = 2E*(a d - ∫_0^a g)`` [Heß11; theory §4].
    The state returned for a depth between the pull-off depth and 0 is the one reached on
    retraction; on approach the bodies stay apart until ``d = 0`` (see
    :meth:`Contact.adhesion_cycle`).
    """
    check_branch(branch)
    key, value = exactly_one("normal()", {"depth": depth, "force": force, "radius": radius})
    arr = as_float_array(key, value)
    check_elements("normal()", arr.size, ADHESIVE_NORMAL_BYTES_PER_LOAD,
                   f"{key} {arr.shape}, adhesive")
    prof, E, w = contact.profile, contact.moduli.normal, contact.work_of_adhesion
    if key == "radius":
        if np.any(arr < 0):
            raise ParameterError(f"radius contains {arr[arr < 0].ravel()[0]!r}: contact radii "
                                 "must be >= 0 m.")
        lim = _limit(prof)
        if np.any(arr > prof.wall_radius) or np.any(arr >= prof.max_radius):
            raise OutsideTheoryError(f"radius={np.max(arr)!r} m is invalid: it must stay below "
                                     f"{lim!r} m for {prof!r}.")
        a = arr.copy()
        d = depth_of_radius(prof, E, w, a)
        prof._check_monotone_upto(float(np.max(a, initial=0.0)), float(np.max(d, initial=0.0)))
        try:
            contact_branches(contact)
        except OutsideTheoryError:
            pass
        return _state(contact, d, a, np.zeros(a.shape, bool), "radius", "n/a")
    if key == "depth":
        a, pinned = solve_depth(prof, E, w, contact_branches(contact), arr, branch)
        d = arr.copy()
        F = None
        if np.any(pinned):
            F = force_of_radius(prof, E, w, a, d)
        return _state(contact, d, a, pinned, "depth", branch, F)
    a, d, pinned = solve_force(prof, E, w, contact_branches(contact), arr, branch)
    return _state(contact, d, a, pinned, "force", branch, np.where(a > 0, arr, 0.0))


def contact_flags(history: np.ndarray, pull_off_value: float) -> np.ndarray:
    """In contact at each step of a 1D load history: a relay with memory. The bodies touch at
    ``v >= 0`` and come apart at ``v < pull_off_value`` (< 0: JKR's pull-off depth or force is
    negative); in between each step keeps the state of the last step that decided it (apart
    before any). One pass: the index of the last deciding step by a running maximum.

    Parameters
    ----------
    history : numpy.ndarray
        Depths (m) or forces (N), 1D.
    pull_off_value : float
        The pull-off depth (m) or force (N) of the history's control, below 0.

    Returns
    -------
    numpy.ndarray
        bool per step.
    """
    touch = history >= 0.0
    decided = touch | (history < pull_off_value)
    last = np.maximum.accumulate(np.where(decided, np.arange(history.size), -1))
    return np.where(last >= 0, touch[np.maximum(last, 0)], False)


@reporting()
def pull_off(contact, control: str = "force"):
    """State at detachment: minimum of ``F(a)`` (force control) or of ``d(a)`` (fixed grips).

    Parameters
    ----------
    contact : Contact
        With ``work_of_adhesion > 0``.
    control : {"force", "displacement"}
        Loading device. Force control: the contact follows the stable branch while the tensile
        force grows and jumps off at the minimum of ``F(a)`` (``dF/da = 0``). Displacement control:
        it follows the branch further, to the minimum of ``d(a)`` (``dd/da = 0``).

    Returns
    -------
    AdhesiveNormalState
        ``.force``, ``.radius``, ``.depth`` at detachment.

    Raises
    ------
    OutsideTheoryError
        No interior minimum (power laws with ``n <= 1/2``, theory §4).

    Warns
    -----
    ValidityWarning
        When ``φ`` crosses the critical value more than once (e.g. a flat punch with a gently
        rounded edge): the returned state ends the stable branch connected to large contacts, but
        the contact may then jump onto a lower stable branch rather than separate.
    """
    controls = ("force", "displacement")
    if control not in controls:
        raise ParameterError(f"control={control!r} is invalid: choose one of {controls}.")
    br = contact_branches(contact)
    prof, E, w = contact.profile, contact.moduli.normal, contact.work_of_adhesion
    a_c = br.a_force if control == "force" else br.a_disp
    if a_c <= 0:
        raise OutsideTheoryError(
            f"{control}-controlled pull-off of {prof!r}: the stable branch reaches a -> 0 without "
            "an interior minimum, so the contact carries no tensile force at detachment.")
    low = br.a_force_low if control == "force" else br.a_disp_low
    if low > 0:
        warnings.warn(
            f"{control}-controlled pull-off of {prof!r}: the stability function crosses its "
            f"critical value more than once, so another stable branch exists below "
            f"a = {low:.6g} m. The state returned ends the stable branch connected to large "
            "contacts; the contact may jump onto the lower branch instead of separating.",
            ValidityWarning, stacklevel=3)
    a = np.array(a_c)
    d = depth_of_radius(prof, E, w, a)
    pinned = np.array(br.pinned_force if control == "force" else br.pinned_disp)
    return _state(contact, d, a, pinned, f"pull_off:{control}", "stable")


@reporting()
def adhesion_cycle(contact, *, depth: Any = None, force: Any = None):
    """Walk an approach/retraction history with JKR jump-in and jump-off (hysteresis).

    Parameters
    ----------
    depth, force : array_like (1D), exactly one
        The load history, m or N.

    Returns
    -------
    AdhesionCycle
        Per-step ``depth``, ``force``, ``radius``, ``in_contact`` and the step indices of the
        jumps.

    Notes
    -----
    Rules (quasi-static, short-range adhesion):

    * Out of contact the bodies stay apart (zero force) until the surfaces touch: under depth
      control at ``d >= 0``, under force control at ``F >= 0``. They then jump onto the stable
      branch (JKR jump-in: for a paraboloid under fixed grips ``a³ = 2πΔγR²/E*`` at ``d = 0``).
    * In contact the state follows the stable branch; there is no other memory.
    * Contact is lost below the pull-off depth (depth control, ``dd/da = 0``) or the pull-off
      force (force control, ``dF/da = 0``); the bodies jump apart.
    """
    key, value = exactly_one("adhesion_cycle()", {"depth": depth, "force": force})
    arr = as_float_array(key, value)
    if arr.ndim != 1 or arr.size == 0:
        raise ParameterError(f"{key} must be a non-empty 1D history; got shape {arr.shape}.")
    br = contact_branches(contact)
    prof, E, w = contact.profile, contact.moduli.normal, contact.work_of_adhesion
    if key == "depth":
        a_c = br.a_disp
        lim = float(depth_of_radius(prof, E, w, np.array(a_c)))
    else:
        a_c = br.a_force
        lim = float(force_of_radius(prof, E, w, np.array(a_c)))
    in_contact = contact_flags(arr, lim)
    radius = np.zeros(arr.shape)
    depth_out = arr.copy() if key == "depth" else np.zeros(arr.shape)
    force_out = np.zeros(arr.shape) if key == "depth" else np.where(in_contact, arr, 0.0)
    if np.any(in_contact):
        given: dict[str, Any] = {key: arr[in_contact]}
        s = adhesive_normal(contact, **given)
        radius[in_contact] = s._radius
        depth_out[in_contact] = s._depth
        force_out[in_contact] = s._force
    if key == "force":
        # out of contact under force control the gap is undefined; report the touching depth 0
        depth_out[~in_contact] = 0.0
    jumps = np.flatnonzero(np.diff(in_contact.astype(int)) != 0) + 1
    return AdhesionCycle(control=key, depth=depth_out, force=force_out, radius=radius,
                         in_contact=in_contact, jumps=jumps, pull_off_value=lim,
                         meta={"citations": adhesion_sources(prof)})
