"""Fretting at constant normal load: the drivers behind :meth:`Contact.fretting_loop` and
:meth:`Contact.fretting_map`, and their results :class:`FrettingLoop` and :class:`FrettingMap`.

A steady fretting loop follows Masing's rule from the monotonic loading curve of the mode:
Cattaneo–Mindlin through the MDR springs for a shift (exact, any profile), one of the torsion
models of :data:`contactlab.physics.torsion.METHODS` for a twist. The kernels (energy ratio,
loop branches, regimes, gross-slip criteria, MDR validity) are in
:mod:`contactlab.physics.fretting`; the theory is in docs/fretting.md.
"""
from __future__ import annotations

import warnings
from dataclasses import dataclass, field
from typing import Any, ClassVar

import numpy as np

from ..citations import Cited, sources_for
from ..errors import (ConvergenceError, NotSupportedError, ParameterError, UnknownNameError,
                      ValidityWarning)
from ..params import (FieldsEqual, as_float_array, as_real, check_count, check_memory,
                     check_result_finite, check_time, exactly_one)
from ..physics import fretting as _fr
from ..physics import tangential as _tan
from ._protocol import Result, reporting
from .torsion import MDR_MAP_BASIS, mdr_map_errors, resolve_method, torsion_model

__all__ = ["FrettingLoop", "FrettingMap", "fretting_loop", "fretting_map", "MODES",
           "SERIES_UNITS", "MapPlan", "plan_map", "map_block", "finish_map", "MAP_BLOCK",
           "BOUNDARY_BLOCK", "map_model_errors"]

#: Fretting modes and the name of their amplitude keyword.
MODES = {"tangential": "displacement_amplitude", "torsion": "twist_amplitude"}

#: Units of the per-point series (CSV headers).
SERIES_UNITS = {"force": "N", "displacement_amplitude": "m", "twist_amplitude": "rad",
                "tangential_force_amplitude": "N", "torque_amplitude": "N*m",
                "energy": "J", "energy_ratio": "1", "stick_ratio": "1", "regime": "1",
                "radius": "m", "stick_radius": "m"}


#: memory of fretting_loop() per loop point, floats (two branches of x and y with temporaries;
#: generous: the loop's own arrays are 4 floats per point)
LOOP_FLOATS = 64

# ---------------------------------------------------------------------------- shared checks
def _mode_and_amplitude(what: str, displacement_amplitude: Any, twist_amplitude: Any):
    key, val = exactly_one(what, {"displacement_amplitude": displacement_amplitude,
                                  "twist_amplitude": twist_amplitude})
    amp = as_float_array(key, val)
    if np.any(amp < 0):
        raise ParameterError(f"{key}={float(amp[amp < 0].ravel()[0])!r} is invalid: an amplitude "
                             "must be >= 0 (the loop runs from -amplitude to +amplitude).")
    return ("tangential" if key == "displacement_amplitude" else "torsion"), key, amp


def fretting_sources(mode: str, method: str) -> tuple[str, ...]:
    """Source tags of a fretting computation (see :mod:`contactlab.citations`)."""
    if mode == "tangential":
        return sources_for("normal", "tangential", "masing:tangential", "fretting")
    return sources_for("normal", f"torsion:{method}", "masing:torsion", "fretting")


def check_contact(contact, what: str) -> None:
    """Fretting needs friction and a non-adhesive contact."""
    if contact.friction is None:
        raise ParameterError(f"{what} needs a friction coefficient, but friction=None: give "
                             "Contact(..., friction=mu).")
    if contact.is_adhesive:
        raise NotSupportedError(f"{what} with work_of_adhesion={contact.work_of_adhesion!r}: "
                                "fretting of adhesive contacts is outside the implemented theory.")


def resolve_criterion(criterion: str, threshold: float | None) -> tuple[str, float]:
    """Validate the torsional gross-slip criterion and default its threshold."""
    if criterion not in _fr.CRITERIA:
        raise UnknownNameError(f"criterion={criterion!r} is invalid: gross-slip criteria are "
                               f"{', '.join(repr(k) for k in _fr.CRITERIA)}.")
    if threshold is None:
        return criterion, _fr.CRITERIA[criterion]
    t = as_real("threshold", threshold, f"the {criterion} threshold must be a real number with "
                                        "0 < threshold < 1")
    if not 0 < t < 1:
        raise ParameterError(f"threshold={threshold!r} is invalid: the {criterion} threshold "
                             "must satisfy 0 < threshold < 1.")
    return criterion, t


def _fresh_g(contact, a: np.ndarray, d: np.ndarray) -> np.ndarray:
    g_a = np.where(a > 0, contact.profile._g(np.maximum(a, 1e-300)), 0.0)
    if np.isfinite(contact.profile.wall_radius):
        g_a = np.where(a >= contact.profile.wall_radius, np.minimum(g_a, d), g_a)
    return g_a


def loops(contact, mode: str, method: str, a: np.ndarray, d: np.ndarray, F_N: np.ndarray,
          amp: np.ndarray, criterion: str, threshold: float) -> dict[str, np.ndarray]:
    """Steady loops for flat arrays of states: peak, stick radius, energy, ratio, regime.

    The amplitudes ``amp`` are >= 0; ``a, d`` the normal states, ``F_N`` their forces.

    Raises
    ------
    ParameterError
        A result overflows float64 (inputs far outside any physical range).
    """
    with np.errstate(over="ignore", invalid="ignore"):
        res = _loops(contact, mode, method, a, d, F_N, amp, criterion, threshold)
    # the no-slip model never slides: its sliding torque is inf by definition, not an overflow
    sliding = {} if method == "no-slip" else {"sliding": res["sliding"]}
    check_result_finite(f"fretting ({mode})", {"force": F_N, "amplitude": amp},
                        peak=res["peak"], energy=res["energy"], energy_ratio=res["energy_ratio"],
                        stick_radius=res["stick_radius"], **sliding)
    return res


def _loops(contact, mode: str, method: str, a: np.ndarray, d: np.ndarray, F_N: np.ndarray,
           amp: np.ndarray, criterion: str, threshold: float) -> dict[str, np.ndarray]:
    prof, E, mu = contact.profile, contact.moduli.normal, contact.friction
    if mode == "tangential":
        Gs = contact.moduli.tangential
        peak, c = _tan.force_of_displacement(prof, E, Gs, mu, a, d, amp)
        W = 4.0 * _tan.virgin_dissipation(prof, E, Gs, mu, a, d, amp, contact.rtol)
        sliding = mu * F_N
        transition = _tan.full_slip_displacement(E, Gs, mu, d)   # g(0) = 0
        gross = (amp >= transition) & (amp > 0)
        A = _fr.energy_ratio(W, amp, peak)
    else:
        g_a = _fresh_g(contact, a, d)
        model = torsion_model(contact, method)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", ValidityWarning)     # judged by the caller
            sol = model.of_twist(amp, a, d, g_a)
        peak, c = sol.torque, sol.stick_radius
        W = 4.0 * model.dissipation(amp, c, a, d, g_a)
        sliding = model.sliding_torque(a, d)
        A = _fr.energy_ratio(W, amp, peak)
        value = _fr.criterion_value(criterion, A, c, a, peak, sliding)
        gross = _fr.torsional_gross_slip(criterion, threshold, value) & (amp > 0)
        # out of contact (a = 0) nothing holds a twist: gross slip, as the tangential mode's
        # zero slip displacement gives (the criterion's 0/0 would otherwise read as stick)
        gross = gross | ((a <= 0) & (amp > 0))
        if method == "no-slip":
            gross = np.zeros(amp.shape, bool)
    regime = _fr.classify(c, a, amp, gross)
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = np.where(a > 0, c / np.where(a > 0, a, 1.0), 1.0)
    return {"peak": peak, "stick_radius": c, "energy": W, "energy_ratio": A, "regime": regime,
            "sliding": sliding, "stick_ratio": ratio}


def warn_mdr(contact, amp: np.ndarray, a: np.ndarray, d: np.ndarray, quantities,
             stacklevel: int = 4) -> str | None:
    """ValidityWarning when the MDR torsion model errs by > 1 % on a requested quantity;
    returns its text (None when it does not warn)."""
    g_a = _fresh_g(contact, a, d)
    limits = _fr.mdr_validity_twists(contact.profile, contact.moduli.normal,
                                     contact.moduli.torsional, contact.friction, a, d, g_a,
                                     quantities, contact.rtol)
    bad = [(q, lim) for q, lim in limits.items() if np.any(amp > lim)]
    if bad:
        q, lim = bad[0]
        i = int(np.argmax(amp - lim))
        names = ", ".join(q for q, _ in bad)
        text = (
            f"MDR torsion model outside its validity for {names}: twist amplitude "
            f"{float(amp[i]):.4g} rad exceeds {float(lim[i]):.4g} rad, beyond which the MDR "
            f"{q.replace('_', ' ')} errs by more than 1 % against the exact solution (the exact "
            f"stick ratio falls below c/a = {_fr.MDR_VALID_STICK_RATIOS[q]}; docs/fretting.md). "
            "Use method='exact'.")
        warnings.warn(text, ValidityWarning, stacklevel=stacklevel)
        return text
    return None


def _normal_states(contact, what: str, force: Any, depth: Any):
    key, val = exactly_one(what, {"force": force, "depth": depth})
    ns = contact.normal(**{key: val})
    return ns, key


# ---------------------------------------------------------------------------- single loop
@dataclass(frozen=True, eq=False)
class FrettingLoop(Result, Cited):
    """The steady fretting loop at constant normal load.

    Attributes
    ----------
    mode : {"tangential", "torsion"}
    method : str
        Torsion model (``"exact"``, ``"mdr"``, ``"no-slip"``); ``"mdr"`` for a shift (the MDR
        springs are exact for Cattaneo–Mindlin).
    amplitude : float
        ``δ*`` (m) or ``φ*`` (rad).
    peak : float
        Loop maximum ``Q*`` (N) or ``M*`` (N·m).
    energy : float
        Energy dissipated per cycle ``W``, J.
    energy_ratio : float
        Fouvry's ``A = W/(4 δ* Q*)`` (torsion: ``W/(4 φ* M*)``).
    stick_radius, radius : float
        Minimum stick radius over the cycle and contact radius, m.
    regime : str
        ``"stick"``, ``"partial_slip"`` or ``"gross_slip"``.
    sliding : float
        Full-sliding force ``μF_N`` (N) or torque (N·m) of the model.
    x, y : ndarray
        The closed loop: displacement (m) or twist (rad), and force (N) or torque (N·m).
    normal : NormalState
    meta : dict
        ``criterion``, ``threshold`` (torsion), ``gross_slip_amplitude`` (tangential: ``δ_t``).
    model_error : float
        Torsion with ``method="mdr"``: the larger relative error of the loop maximum and of the
        energy per cycle against the exact solution (:attr:`model_errors`), from the measured
        MDR-vs-exact maps at the exact stick ratio of the amplitude; 0.0 otherwise (exact).
    """

    mode: str
    method: str
    amplitude: float
    peak: float
    energy: float
    energy_ratio: float
    stick_radius: float
    radius: float
    regime: str
    sliding: float
    x: np.ndarray = field(repr=False)
    y: np.ndarray = field(repr=False)
    normal: Any = field(repr=False)
    meta: dict = field(default_factory=dict, repr=False)

    units: ClassVar[dict[str, str]] = {"displacement": "m", "tangential_force": "N", "twist": "rad",
                                       "torque": "N*m"}
    _basis = MDR_MAP_BASIS

    def _columns(self) -> dict[str, np.ndarray]:
        """The closed loop: ``displacement``/``tangential_force`` or ``twist``/``torque``."""
        xn, yn = (("displacement", "tangential_force") if self.mode == "tangential"
                  else ("twist", "torque"))
        return {xn: np.asarray(self.x, float), yn: np.asarray(self.y, float)}

    def _model_errors(self) -> dict[str, Any]:
        if self.mode != "torsion" or self.method != "mdr":
            return {}
        ct = self.normal.contact
        a = np.array([self.radius])
        d = np.array([float(self.normal._depth)])
        e = mdr_map_errors(ct, np.array([self.amplitude]), a, d, _fresh_g(ct, a, d),
                           ("torque", "energy"))
        return {"peak": float(e["torque"][0]), "energy": float(e["energy"][0])}

    def to_dict(self) -> dict[str, Any]:
        """Scalars and loop arrays by name."""
        return {k: getattr(self, k) for k in ("mode", "method", "amplitude", "peak", "energy",
                                              "energy_ratio", "stick_radius", "radius",
                                              "regime", "sliding", "x", "y")}

    def plot(self, ax: Any = None, *, units: str = "si"):
        """Draw the loop (needs matplotlib); returns the axes.

        ``units="engineering"`` labels µm or mrad and mN·m (see :mod:`contactlab.plotting`).
        """
        from .. import plotting as pl
        pl.check_units(units)
        pl.pyplot()
        xu, yu = ("m", "N") if self.mode == "tangential" else ("rad", "N*m")
        with pl.style():
            if ax is None:
                _, ax = pl.subplots(figsize=(4.8, 3.6))
            ax.plot(pl.scaled(self.x, xu, units), pl.scaled(self.y, yu, units))
            xl, yl = (("displacement", "tangential force") if self.mode == "tangential"
                      else ("twist", "torque"))
            ax.set_xlabel(pl.axis_label(xl, xu, units))
            ax.set_ylabel(pl.axis_label(yl, yu, units))
            ax.set_title(f"{self.regime.replace('_', ' ')}, A = {self.energy_ratio:.3g}")
            pl.loop_axes(ax)
        return ax

    def stress(self, x: Any, y: Any, z: Any, *, phase: float, body: int = 1,
               part: str = "total") -> Any:
        """Subsurface stress field (a ``CartesianStressField``, both modes) at ``phase`` of the
        steady loop (``control = amplitude cos 2π phase``; 0: the tip at +amplitude, 0.5: at
        -amplitude) at points ``(x, y, z)`` (m). See docs/stress.md."""
        from .stress_history import loop_stress
        return loop_stress(self, x, y, z, phase=phase, body=body, part=part)

    def fatigue(self, body: int = 1, n_phases: int = 24, points: Any = None,
                findley_k: float | None = None) -> Any:
        """Fretting-fatigue indicators over the loop (a ``FrettingFatigue``): the largest
        tensile stress at the contact edge and its range, the Smith–Watson–Topper parameter on
        the critical plane and, with ``findley_k`` (the material's normal-stress sensitivity
        ``k``, dimensionless), Findley's ``max_n [τ_a + k σ_n,max]`` (Pa). See docs/stress.md."""
        from .stress_history import fretting_fatigue
        return fretting_fatigue(self, body, n_phases, points, findley_k)


@reporting()
def fretting_loop(contact, *, force: Any = None, depth: Any = None,
                  displacement_amplitude: Any = None, twist_amplitude: Any = None,
                  method: str | None = None, criterion: str = "energy_ratio",
                  threshold: float | None = None, n_points: int = 200) -> FrettingLoop:
    """Implementation of :meth:`contactlab.Contact.fretting_loop` (see there)."""
    check_contact(contact, "fretting_loop()")
    mode, key, amp = _mode_and_amplitude("fretting_loop()", displacement_amplitude,
                                         twist_amplitude)
    if amp.ndim != 0:
        raise ParameterError(f"{key} has shape {amp.shape}: fretting_loop() takes one amplitude; "
                             "use fretting_map() for a grid.")
    n_points = check_count("n_points", n_points, 2)
    check_memory("fretting_loop()", LOOP_FLOATS * 8.0 * n_points, f"n_points={n_points}")
    criterion, threshold = resolve_criterion(criterion, threshold)
    ns, nkey = _normal_states(contact, "fretting_loop()", force, depth)
    if ns.shape != ():
        raise ParameterError(f"{nkey} must be a scalar for fretting_loop(); use fretting_map().")
    if mode == "torsion":
        method = resolve_method(contact, method)
    elif method not in (None, "mdr", "exact"):
        raise UnknownNameError(f"method={method!r} is invalid for a shift: the MDR springs are "
                               "exact for Cattaneo–Mindlin; leave method=None.")
    else:
        method = "mdr"
    a = np.atleast_1d(float(ns._radius))
    d = np.atleast_1d(float(ns._depth))
    F_N = np.atleast_1d(float(ns._force))
    x1 = np.atleast_1d(float(amp))
    res = loops(contact, mode, method, a, d, F_N, x1, criterion, threshold)
    if mode == "torsion" and method == "mdr":
        warn_mdr(contact, x1, a, d, ("torque", "energy", "stick_radius"))

    prof, E, mu = contact.profile, contact.moduli.normal, contact.friction
    if mode == "tangential":
        Gs = contact.moduli.tangential

        def curve(x: np.ndarray) -> np.ndarray:
            return _tan.force_of_displacement(prof, E, Gs, mu, a[0], d[0], x)[0]
        meta: dict[str, Any] = {"gross_slip_amplitude": float(_tan.full_slip_displacement(E, Gs, mu, d[0]))}
    else:
        model = torsion_model(contact, method)
        g_a = _fresh_g(contact, a, d)

        def curve(x: np.ndarray) -> np.ndarray:
            n = x.size
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", ValidityWarning)
                return model.of_twist(x, np.full(n, a[0]), np.full(n, d[0]),
                                      np.full(n, g_a[0])).torque
        meta = {"criterion": criterion, "threshold": threshold}
    peak = float(res["peak"][0])
    x, y = _fr.loop_branches(float(amp), peak, curve, int(n_points))
    meta.update({"rtol": contact.rtol, "load": nkey,
                 "citations": fretting_sources(mode, method)})
    return FrettingLoop(mode, method, float(amp), peak, float(res["energy"][0]),
                        float(res["energy_ratio"][0]), float(res["stick_radius"][0]),
                        float(a[0]), _fr.REGIMES[int(res["regime"][0])],
                        float(res["sliding"][0]), x, y, ns, meta)


# ---------------------------------------------------------------------------- maps
@dataclass(frozen=True, eq=False)
class FrettingMap(FieldsEqual, Result, Cited):
    """Running-condition map over normal forces x amplitudes.

    Attributes
    ----------
    mode, method, criterion : str
    threshold : float
    force : ndarray, shape (nF,)
        Normal forces, N.
    amplitude : ndarray, shape (nA,)
        Amplitudes ``δ*`` (m) or ``φ*`` (rad).
    regime : ndarray of int8, shape (nF, nA)
        Codes into :attr:`regime_names` (0 stick, 1 partial slip, 2 gross slip).
    energy_ratio, energy, stick_ratio, peak : ndarray, shape (nF, nA)
        Fouvry's ``A``, energy per cycle (J), minimum ``c/a``, loop maximum (N or N·m).
    boundary : ndarray, shape (nF,)
        Gross-slip amplitude per force: tangential ``δ_t = μE*d/G*`` (exact); torsion the
        amplitude where the criterion is met (root on the loading curve, see
        :func:`torsional_boundary`).
    model_error : ndarray or float
        Torsion with ``method="mdr"``: per grid point, shape (nF, nA), the larger relative error
        of the loop maximum and of the energy per cycle against the exact solution, from the
        measured MDR-vs-exact maps (:attr:`model_errors`); 0.0 otherwise (exact).
    """

    mode: str
    method: str
    criterion: str
    threshold: float
    force: np.ndarray = field(repr=False)
    amplitude: np.ndarray = field(repr=False)
    regime: np.ndarray = field(repr=False)
    energy_ratio: np.ndarray = field(repr=False)
    energy: np.ndarray = field(repr=False)
    stick_ratio: np.ndarray = field(repr=False)
    peak: np.ndarray = field(repr=False)
    boundary: np.ndarray = field(repr=False)
    meta: dict = field(default_factory=dict, repr=False)

    regime_names = _fr.REGIMES
    units = SERIES_UNITS
    _basis = MDR_MAP_BASIS

    @property
    def amplitude_name(self) -> str:
        return MODES[self.mode]

    def to_dict(self) -> dict[str, np.ndarray]:
        """One row per grid point (force-major), as flat arrays."""
        F, X = np.meshgrid(self.force, self.amplitude, indexing="ij")
        peak = "tangential_force_amplitude" if self.mode == "tangential" else "torque_amplitude"
        return {"force": F.ravel(), self.amplitude_name: X.ravel(),
                "regime": self.regime.ravel().astype(float),
                "energy_ratio": self.energy_ratio.ravel(), "energy": self.energy.ravel(),
                "stick_ratio": self.stick_ratio.ravel(), peak: self.peak.ravel()}

    def to_dataframe(self):
        """The grid as a :class:`pandas.DataFrame` (needs pandas), regimes as names; units,
        notes and errors in ``df.attrs`` (see :class:`~contactlab.effects._protocol.Result`)."""
        df = Result.to_dataframe(self)
        df["regime"] = [self.regime_names[int(r)] for r in self.regime.ravel()]
        return df

    def plot(self, ax: Any = None, *, boundary: bool = True, units: str = "si"):
        """The running-condition map: regimes over amplitude (x) and normal force (y), with the
        analytic gross-slip boundary drawn on top (needs matplotlib); returns the axes.

        ``units="engineering"`` labels the amplitude in µm or mrad (see
        :mod:`contactlab.plotting`).
        """
        from .. import plotting as pl
        pl.check_units(units)
        pl.pyplot()
        from matplotlib.colors import ListedColormap
        from matplotlib.patches import Patch
        xu = "m" if self.mode == "tangential" else "rad"
        amp = pl.scaled(self.amplitude, xu, units)
        with pl.style():
            if ax is None:
                _, ax = pl.subplots(figsize=(5.6, 4.0))
            colors = ["#4c72b0", "#dd8452", "#c44e52"]
            ax.pcolormesh(amp, self.force, self.regime, cmap=ListedColormap(colors),
                          vmin=-0.5, vmax=2.5, shading="nearest")
            ax.grid(False)
            handles = [Patch(color=c, label=n.replace("_", " "))
                       for c, n in zip(colors, self.regime_names)]
            if boundary and np.any(np.isfinite(self.boundary)):
                handles += ax.plot(pl.scaled(self.boundary, xu, units), self.force, "k-", lw=2,
                                   label="gross-slip boundary")
            ax.set_xlim(amp.min(), amp.max())
            if self.amplitude.min() > 0 and self.amplitude.max() > 10 * self.amplitude.min():
                ax.set_xscale("log")
            if self.force.min() > 0 and self.force.max() > 10 * self.force.min():
                ax.set_yscale("log")
            ax.set_xlabel(pl.axis_label("displacement amplitude" if self.mode == "tangential"
                                        else "twist amplitude", xu, units))
            ax.set_ylabel(pl.axis_label("normal force", "N", units))
            ax.legend(handles=handles, loc="upper center", bbox_to_anchor=(0.5, -0.18),
                      ncol=2, frameon=False)
            title = "running-condition map"
            if self.mode == "torsion":
                title += f" ({self.criterion.replace('_', ' ')} {self.threshold:g})"
            ax.set_title(title)
        return ax


def torsional_boundary(contact, method: str, a: np.ndarray, d: np.ndarray, F_N: np.ndarray,
                       criterion: str, threshold: float) -> np.ndarray:
    """Twist amplitude at which the torsional gross-slip criterion is met, per normal state.

    The root of the criterion along the loading curve, certified to
    ``rtol = min(BOUNDARY_RTOL, contact.rtol)`` relative in the twist
    (:func:`contactlab.physics.fretting.torsional_boundary`), then certified once more on the
    route the map's points take (:func:`loops`, twist given): the returned amplitude is gross slip
    there and ``(1 - rtol)`` times it is not (:func:`_certify_boundary`). ``inf`` where the
    criterion is never met.
    """
    if method == "no-slip":
        return np.full(a.shape, np.inf)
    rtol = min(_fr.BOUNDARY_RTOL, contact.rtol)
    phi = _fr.torsional_boundary(torsion_model(contact, method), a, d, _fresh_g(contact, a, d),
                                 criterion, threshold, rtol)
    return _certify_boundary(contact, method, a, d, F_N, criterion, threshold, phi, rtol)


#: Widest relative offset :func:`_certify_boundary` searches, in units of the contact's ``rtol``
#: (the two routes agree to about the quadrature tolerance; measured <= 2e-10 at the default
#: 1e-10), and never below :data:`_CERTIFY_FLOOR`
_CERTIFY_SPAN = 1e3
_CERTIFY_FLOOR = 1e-6


def _certify_boundary(contact, method: str, a: np.ndarray, d: np.ndarray, F_N: np.ndarray,
                      criterion: str, threshold: float, phi: np.ndarray, rtol: float
                      ) -> np.ndarray:
    """Move each finite boundary ``phi`` onto the classification of :func:`loops`.

    The loading-curve root and a loop at that twist evaluate the criterion by different routes
    (stick radius given, twist given), which agree to about the quadrature tolerance. A bracket
    ``[lo, hi]`` with ``hi`` gross slip and ``lo`` not, on the loops' own route, is found around
    ``phi`` (widened 4x per step where needed) and bisected to ``hi/lo - 1 <= rtol``; ``hi`` is
    returned. So a map point at or beyond the drawn line is gross slip and a point more than
    ``rtol`` below it is not, as :meth:`Contact.fretting_loop` reports.

    Raises
    ------
    ConvergenceError
        The two routes disagree by more than ``max(1e3 contact.rtol, 1e-6)`` relative (never
        seen; a defect, not an input).
    """
    out = phi.copy()
    idx = np.flatnonzero(np.isfinite(phi) & (phi > 0))
    if idx.size == 0:
        return out
    p0 = phi[idx]
    span = max(_CERTIFY_SPAN * contact.rtol, _CERTIFY_FLOOR)

    def gross(x: np.ndarray, k: np.ndarray) -> np.ndarray:
        i = idx[k]
        r = loops(contact, "torsion", method, a[i], d[i], F_N[i], x, criterion, threshold)
        return r["regime"] == _fr.GROSS_SLIP

    all_k = np.arange(idx.size)
    lo, hi = p0 * (1.0 - rtol), p0.copy()
    g = gross(np.concatenate([hi, lo]), np.concatenate([all_k, all_k]))
    ok_hi, ok_lo = g[:idx.size], ~g[idx.size:]
    off = rtol
    while True:
        up = np.flatnonzero(~ok_hi)                      # hi not gross: the root lies above
        down = np.flatnonzero(ok_hi & ~ok_lo)            # lo gross already: the root lies below
        if up.size + down.size == 0:
            break
        off *= 4.0
        if off > span:
            raise ConvergenceError(
                f"torsional gross-slip boundary: the loop at the loading-curve root and the "
                f"root itself disagree on the {criterion} criterion by more than {span:.2g} "
                "relative.")
        lo[up], hi[down] = hi[up], lo[down]              # the old end is on the right side
        ok_lo[up], ok_hi[down] = True, True
        hi[up], lo[down] = p0[up] * (1.0 + off), p0[down] * (1.0 - off)
        g = gross(np.concatenate([hi[up], lo[down]]), np.concatenate([up, down]))
        ok_hi[up], ok_lo[down] = g[:up.size], ~g[up.size:]
    wide = np.flatnonzero(hi > lo * (1.0 + rtol))
    while wide.size:
        mid = 0.5 * (lo[wide] + hi[wide])
        g = gross(mid, wide)
        hi[wide] = np.where(g, mid, hi[wide])
        lo[wide] = np.where(g, lo[wide], mid)
        wide = wide[hi[wide] > lo[wide] * (1.0 + rtol)]
    out[idx] = hi
    return out


#: grid points per block of a map: a large map is computed block by block, here or on workers
#: (the blocks are the same either way, so the map is the same bit for bit)
MAP_BLOCK = 1024
#: normal states per block of the torsional gross-slip boundary (a root search per state)
BOUNDARY_BLOCK = 16


@dataclass(frozen=True, eq=False)
class MapPlan:
    """A validated fretting map before it is computed: its settings, normal states and blocks.

    Plain data (pickles): :func:`map_block` computes one of :meth:`blocks` from it and the
    contact, :func:`finish_map` assembles the blocks' results into the :class:`FrettingMap`.
    """

    mode: str
    method: str
    criterion: str
    threshold: float
    load_key: str
    loads: np.ndarray
    amplitude: np.ndarray
    radius: np.ndarray
    depth: np.ndarray
    boundary: bool

    def blocks(self) -> list[tuple[str, int, int]]:
        """``("loops", start, stop)`` over the force-major grid points (:data:`MAP_BLOCK` each),
        then ``("boundary", start, stop)`` over the forces (:data:`BOUNDARY_BLOCK` each) when a
        torsional boundary is asked for."""
        n, nF = self.loads.size * self.amplitude.size, self.loads.size
        out = [("loops", s, min(s + MAP_BLOCK, n)) for s in range(0, n, MAP_BLOCK)]
        if self.mode == "torsion" and self.boundary:
            out += [("boundary", s, min(s + BOUNDARY_BLOCK, nF))
                    for s in range(0, nF, BOUNDARY_BLOCK)]
        return out


#: peak memory of a map per grid point, bytes (its result arrays, their assembly, the validity
#: check; a block's working memory is bounded by MAP_BLOCK): up to 919 B measured with
#: tracemalloc for 50 x 1000 maps (shift, twist exact and mdr), rounded up; checked before the
#: normal states are solved
MAP_POINT_BYTES = 1024


#: run time per map point (one loop) and per boundary force, s, by route: measured on the shared
#: 2-core VM at load ~9 (exact torsion 0.74 ms per point, 0.29 s per boundary force; MDR
#: torsion 0.05 ms and 5 ms; shift 1 us per point, boundaries in closed form) and taken at
#: about 0.4 of that, a lower estimate for an unloaded core
MAP_POINT_SECONDS = {"exact": 3e-4, "mdr": 2e-5, "tangential": 5e-7}
MAP_BOUNDARY_SECONDS = {"exact": 0.1, "mdr": 2e-3, "tangential": 0.0}


def map_time(mode: str, method: str, n_loads: int, n_amplitudes: int, boundary: bool) -> float:
    """Estimated run time (s) of a map: :data:`MAP_POINT_SECONDS` per point plus, for a
    torsional boundary, :data:`MAP_BOUNDARY_SECONDS` per force."""
    key = "tangential" if mode != "torsion" else ("exact" if method == "exact" else "mdr")
    t = MAP_POINT_SECONDS[key] * float(n_loads) * float(n_amplitudes)
    if mode == "torsion" and boundary:
        t += MAP_BOUNDARY_SECONDS[key] * float(n_loads)
    return t


def plan_map(contact, *, force: Any = None, depth: Any = None,
             displacement_amplitude: Any = None, twist_amplitude: Any = None,
             method: str | None = None, criterion: str = "energy_ratio",
             threshold: float | None = None, boundary: bool = True) -> MapPlan:
    """Validate a map's arguments and solve its normal states (see :func:`fretting_map`)."""
    check_contact(contact, "fretting_map()")
    mode, key, amp = _mode_and_amplitude("fretting_map()", displacement_amplitude,
                                         twist_amplitude)
    n_loads = int(np.size(force if force is not None else depth))      # size check first
    check_memory("fretting_map()", MAP_POINT_BYTES * float(n_loads) * float(amp.size),
                 f"{n_loads} {'force' if force is not None else 'depth'} values x {amp.size} {key} "
                 f"values = {n_loads * amp.size} points x {MAP_POINT_BYTES} B")
    criterion, threshold = resolve_criterion(criterion, threshold)
    ns, nkey = _normal_states(contact, "fretting_map()", force, depth)
    # the forces as given (the solved state's force differs from them by rounding)
    loads = np.atleast_1d(np.asarray(ns._force if force is None else force, float))
    if loads.ndim != 1 or amp.ndim > 1:
        raise ParameterError(f"fretting_map() takes 1D arrays of {nkey} and {key}; got shapes "
                             f"{np.shape(ns._force)} and {amp.shape}.")
    amp = np.atleast_1d(amp)
    if mode == "torsion":
        method = resolve_method(contact, method)
    elif method not in (None, "mdr", "exact"):
        raise UnknownNameError(f"method={method!r} is invalid for a shift: leave method=None.")
    else:
        method = "mdr"
    est = map_time(mode, method, loads.size, amp.size, bool(boundary))
    check_time("fretting_map()", est,
               f"{loads.size} x {amp.size} = {loads.size * amp.size} points on the "
               f"{'exact' if method == 'exact' and mode == 'torsion' else method} route"
               + (f" and {loads.size} boundary solves" if mode == "torsion" and boundary else ""))
    return MapPlan(mode, method, criterion, threshold, nkey, loads, amp,
                   np.atleast_1d(np.asarray(ns._radius, float)),
                   np.atleast_1d(np.asarray(ns._depth, float)), bool(boundary))


_MAP_FIELDS = ("regime", "energy_ratio", "energy", "stick_ratio", "peak")


def map_block(contact, plan: MapPlan, block: tuple[str, int, int]) -> dict[str, np.ndarray]:
    """The results of one block of :meth:`MapPlan.blocks` (flat arrays)."""
    kind, start, stop = block
    if kind == "boundary":
        sl = slice(start, stop)
        return {"boundary": torsional_boundary(contact, plan.method, plan.radius[sl],
                                               plan.depth[sl], plan.loads[sl], plan.criterion,
                                               plan.threshold)}
    k = np.arange(start, stop)
    rows, cols = k // plan.amplitude.size, k % plan.amplitude.size
    res = loops(contact, plan.mode, plan.method, plan.radius[rows], plan.depth[rows],
                plan.loads[rows], plan.amplitude[cols], plan.criterion, plan.threshold)
    return {f: res[f] for f in _MAP_FIELDS}


def finish_map(contact, plan: MapPlan, results: list[dict[str, np.ndarray]],
               stacklevel: int = 5) -> FrettingMap:
    """The :class:`FrettingMap` from the results of every block, in :meth:`MapPlan.blocks`
    order (with the MDR validity warning where it applies, ``stacklevel`` pointing at the
    user's call)."""
    nF, nA = plan.loads.size, plan.amplitude.size
    parts = [r for r in results if "boundary" not in r]
    res = {f: np.concatenate([r[f] for r in parts]) for f in _MAP_FIELDS}
    note = None
    if plan.mode == "torsion" and plan.method == "mdr":
        note = warn_mdr(contact, np.tile(plan.amplitude, nF), np.repeat(plan.radius, nA),
                        np.repeat(plan.depth, nA), ("torque", "energy", "stick_radius"),
                        stacklevel=stacklevel)
    if plan.mode == "tangential":
        bnd = _tan.full_slip_displacement(contact.moduli.normal, contact.moduli.tangential,
                                          contact.friction, plan.depth)
    elif plan.boundary:
        bnd = np.concatenate([r["boundary"] for r in results if "boundary" in r])
    else:
        bnd = np.full(nF, np.nan)
    shp = (nF, nA)
    meta = {"rtol": contact.rtol, "load": plan.load_key,
            "citations": fretting_sources(plan.mode, plan.method)}
    if note is not None:
        meta["notes"] = (" ".join(note.split()),)
    mdr = plan.mode == "torsion" and plan.method == "mdr"
    if mdr:
        meta["model_error_basis"] = MDR_MAP_BASIS
    fmap = FrettingMap(plan.mode, plan.method, plan.criterion, plan.threshold, plan.loads.copy(),
                       plan.amplitude.copy(), res["regime"].reshape(shp),
                       res["energy_ratio"].reshape(shp), res["energy"].reshape(shp),
                       res["stick_ratio"].reshape(shp), res["peak"].reshape(shp),
                       np.asarray(bnd, float), meta)
    if mdr:
        from functools import partial
        fmap._defer_model_errors(partial(map_model_errors, contact, plan.amplitude.copy(),
                                         plan.radius.copy(), plan.depth.copy()))
    return fmap


def map_model_errors(contact, amplitude: np.ndarray, radius: np.ndarray, depth: np.ndarray
                     ) -> dict[str, np.ndarray]:
    """``model_errors`` of an MDR torsional fretting map, shape (forces, amplitudes): loop
    maximum and energy per cycle from the measured maps (computed on first access)."""
    nF, nA = radius.size, amplitude.size
    a, d = np.repeat(radius, nA), np.repeat(depth, nA)
    e = mdr_map_errors(contact, np.tile(amplitude, nF), a, d, _fresh_g(contact, a, d),
                       ("torque", "energy"))
    return {"peak": e["torque"].reshape(nF, nA), "energy": e["energy"].reshape(nF, nA)}


@reporting()
def fretting_map(contact, *, force: Any = None, depth: Any = None,
                 displacement_amplitude: Any = None, twist_amplitude: Any = None,
                 method: str | None = None, criterion: str = "energy_ratio",
                 threshold: float | None = None, boundary: bool = True) -> FrettingMap:
    """Implementation of :meth:`contactlab.Contact.fretting_map` (see there): plan, every
    block here, finish (``contactlab.fretting_map_sweep`` runs the same blocks on workers)."""
    plan = plan_map(contact, force=force, depth=depth,
                    displacement_amplitude=displacement_amplitude,
                    twist_amplitude=twist_amplitude, method=method, criterion=criterion,
                    threshold=threshold, boundary=boundary)
    return finish_map(contact, plan, [map_block(contact, plan, b) for b in plan.blocks()])
