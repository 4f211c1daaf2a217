"""The result of one :meth:`contactlab.effects.law.ContactLaw.step`: :class:`LawStep`, its
units, sources and model error (the law's time stepping lives in :mod:`contactlab.effects.law`)."""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..citations import Citations, sources_for
from ._protocol import Result

__all__ = ["LawStep", "STEP_UNITS", "LAW_BASIS", "law_sources"]

#: springs per contact of a law when its meta does not say (:data:`contactlab.effects.law.DEFAULT_SPRINGS`)
_DEFAULT_SPRINGS = 16
_OUT_FIELDS = ("depth", "radius", "force", "tangential_force", "torque", "stick_radius",
               "torsion_stick_radius", "dissipated_energy", "exact")


#: units of the columns of a law step (CSV headers)
STEP_UNITS = {"depth": "m", "radius": "m", "force": "N", "tangential_force": "N", "torque": "N*m",
              "stick_radius": "m", "torsion_stick_radius": "m", "dissipated_energy": "J",
              "exact": "1"}
#: where a law step's ``model_error`` comes from
LAW_BASIS = ("contacts on springs (exact False): the measured spring-discretisation error of the "
             "law at its springs per contact against the 2000-spring foundation (docs/dem.md), "
             "plus for twisted contacts the measured MDR-vs-exact torque map at the springs' own "
             "stick ratio (a constant-load map: under a changing load the MDR torsion error was "
             "measured larger, docs/torsion_varying_load.md); 0 where exact")


@dataclass(frozen=True, eq=False)
class LawStep(Result):
    """Result of one :meth:`ContactLaw.step`: one value per contact (SI units).

    Attributes
    ----------
    depth, radius, force : ndarray
        Indentation depth (m), contact radius (m), normal force (N).
    tangential_force, torque : ndarray
        Tangential force (N) along the given displacement, torque (N·m) about the normal.
    stick_radius, torsion_stick_radius : ndarray
        Stick radius of the tangential (Cattaneo–Mindlin) and of the torsional slip problem, m
        (the contact radius without slip; of the active Masing branch).
    dissipated_energy : ndarray
        Energy dissipated by friction in this step, J (both channels).
    exact : ndarray of bool
        True where the result is exact: constant normal load, and the contact's turning-point
        memory never overflowed (see ``memory`` of :class:`ContactLaw`).
    meta : dict
        ``springs`` (springs per contact of the law), ``citations``.
    model_error : ndarray
        Per contact: 0 where exact, else the measured error of the spring model
        (:data:`LAW_BASIS`), computed on first access.
    """

    depth: np.ndarray
    radius: np.ndarray
    force: np.ndarray
    tangential_force: np.ndarray
    torque: np.ndarray
    stick_radius: np.ndarray
    torsion_stick_radius: np.ndarray
    dissipated_energy: np.ndarray
    exact: np.ndarray
    meta: dict = field(default_factory=dict, repr=False)
    tangent: dict | None = field(default=None, repr=False)   # step(..., tangent=True)

    units = STEP_UNITS
    _basis = LAW_BASIS

    def to_dict(self) -> dict[str, np.ndarray]:
        """One array per quantity, one value per contact."""
        return {k: getattr(self, k) for k in _OUT_FIELDS}

    def _model_errors(self) -> dict[str, Any]:
        return self.model_errors_at(None)

    def model_errors_at(self, idx: np.ndarray | None) -> dict[str, Any]:
        """:attr:`model_errors` of the contacts ``idx`` only (all for None; ``{}`` when none
        of them is off the exact law), entry by entry the same numbers: the law's model-error
        warning looks at the contacts on springs without a pass over every contact."""
        from ..physics import model_error as _maps
        exact, radius = np.asarray(self.exact, bool), np.asarray(self.radius)
        cm, torque = self.torsion_stick_radius, self.torque
        if idx is not None:
            exact, radius, cm, torque = exact[idx], radius[idx], cm[idx], torque[idx]
        off = ~exact & (radius > 0)
        if not np.any(off):
            return {}
        spring = _maps.law_spring_error(self.meta.get("springs", _DEFAULT_SPRINGS))
        with np.errstate(divide="ignore", invalid="ignore"):
            ratio = np.where(off, cm / np.where(off, radius, 1.0), 1.0)
        twisted = off & (torque != 0)
        mdr = np.where(twisted, _maps.mdr_ratio_error(None, "torque", ratio), 0.0)
        return {"tangential_force": np.where(off, spring, 0.0),
                "torque": np.where(off, spring + mdr, 0.0)}

    def model_error_peaks_at(self, idx: np.ndarray) -> dict[str, float]:
        """The largest entry of each array of :meth:`model_errors_at` ``(idx)`` (``idx``:
        contact indices, or a bool mask over all contacts; ``{}`` when
        none of the contacts is off the exact law), to the bit, without those arrays: the
        spring part is one number for every contact off the exact law, and the torque's MDR
        part falls as the stick ratio rises (a step function of it), so its largest value is
        the one at the smallest stick ratio of a twisted contact. The law's model-error warning
        checks these first, so that a changing-load step builds no per-contact error array
        unless it warns (measured ~50 ms of a changing-load step at 10^6 contacts)."""
        from ..physics import model_error as _maps
        exact, radius = np.asarray(self.exact, bool), np.asarray(self.radius)
        torque, cm = np.asarray(self.torque), np.asarray(self.torsion_stick_radius)
        idx = np.asarray(idx)
        if idx.dtype == bool:   # a mask over all contacts (the law's: no index array built)
            off = idx & ~exact
            off &= radius > 0
        elif 4 * idx.size < exact.size:         # a few contacts: gathers at idx
            exact, radius, torque, cm = exact[idx], radius[idx], torque[idx], cm[idx]
            off = ~exact & (radius > 0)
        else:       # many: masks over all contacts, the same quotients and minimum (measured
            off = np.zeros(exact.size, bool)    # 16.5 -> 7 ms at 10^6 of 10^6 contacts)
            off[idx] = True
            off &= ~exact
            off &= radius > 0
        if not np.any(off):
            return {}
        spring = _maps.law_spring_error(self.meta.get("springs", _DEFAULT_SPRINGS))
        twisted = off & (torque != 0)
        mdr = 0.0
        if np.any(twisted):
            with np.errstate(divide="ignore", invalid="ignore"):
                q = np.divide(cm, radius, where=twisted, out=np.empty(radius.shape))
            low = np.min(q, where=twisted, initial=np.inf)
            mdr = float(_maps.mdr_ratio_error(None, "torque", np.array([low]))[0])
        return {"tangential_force": spring, "torque": spring + mdr}

    def model_error_worst_at(self, on: np.ndarray, quantity: str,
                             peak: float) -> tuple[int, float]:
        """The contact of the first largest entry of :meth:`model_errors_at` ``(on)`` for
        ``quantity`` (``on``: ascending contact indices, or a bool mask over all contacts;
        ``peak``: that largest entry, :meth:`model_error_peaks_at`), and the entry: the
        contact and value ``np.argmax`` of the whole array names, to the bit, with the array
        built in blocks of :data:`_WORST_BLOCK` contacts from the start, up to the block that
        holds the peak (the law's model-error warning: in the step that warns, the whole
        arrays cost ~35 ms at 10^6 contacts on springs)."""
        from ..physics import model_error as _maps
        exact, radius = np.asarray(self.exact, bool), np.asarray(self.radius)
        torque, cm = np.asarray(self.torque), np.asarray(self.torsion_stick_radius)
        on = np.asarray(on)
        idx = None if on.dtype == bool else on
        if idx is not None:
            exact, radius, torque, cm = exact[idx], radius[idx], torque[idx], cm[idx]
        spring = _maps.law_spring_error(self.meta.get("springs", _DEFAULT_SPRINGS))
        for s in range(0, exact.size, _WORST_BLOCK):
            e = slice(s, s + _WORST_BLOCK)
            off = ~exact[e] & (radius[e] > 0)
            if idx is None:
                off &= on[e]
            if quantity == "torque":
                with np.errstate(divide="ignore", invalid="ignore"):
                    ratio = np.where(off, cm[e] / np.where(off, radius[e], 1.0), 1.0)
                twisted = off & (torque[e] != 0)
                mdr = np.where(twisted, _maps.mdr_ratio_error(None, "torque", ratio), 0.0)
                err = np.where(off, spring + mdr, 0.0)
            else:
                err = np.where(off, spring, 0.0)
            hit = np.flatnonzero(err == peak)
            if hit.size:
                j = s + int(hit[0])
                return (j if idx is None else int(idx[j])), float(err[hit[0]])
        raise AssertionError(f"no entry of {quantity} equals its peak {peak!r}")  # pragma: no cover

    @property
    def citations(self) -> Citations:
        """The sources of this step (``contactlab.cite(step)``): the law's closed forms, and the
        MDR springs when some contact was not exact (its normal load changed)."""
        return Citations(law_sources(springs=not bool(np.all(self.exact))))


#: contacts per block of :meth:`LawStep.model_error_worst_at`
_WORST_BLOCK = 1 << 14


def law_sources(springs: bool = True) -> tuple[str, ...]:
    """Source tags of :class:`ContactLaw`: closed-form normal contact, Cattaneo–Mindlin and
    exact (Jäger) torsion with Masing's rule; ``springs``: also the MDR springs that carry a
    contact whose normal load changes."""
    tags = sources_for("normal", "tangential", "masing:tangential", "torsion:exact",
                       "masing:torsion")
    return tags + tuple(t for t in sources_for("foundation", "foundation:torsion")
                        if springs and t not in tags)




def springs_only_outputs(size: int, out: LawStep | None) -> tuple:
    """The fused pass's ``(Ft, ct, M, cm, dW, exact, nonfinite, n_over)`` when every contact is
    on springs (it would only set ``exact`` False and leave the rest to the spring pass): the
    outputs (``out``'s arrays, or new ones), ``exact`` False, no pass over the contacts."""
    if out is None:
        return (*(np.empty(size) for _ in range(5)), np.zeros(size, bool), 0, 0)
    out.exact[...] = False
    return (out.tangential_force, out.stick_radius, out.torque, out.torsion_stick_radius,
            out.dissipated_energy, out.exact, 0, 0)
