"""Fit of an elastic indentation curve: Young's modulus, contact point and force offset.

The model (non-adhesive, any axisymmetric profile without a wall, through the MDR):

``F(z) = E* Φ(z - z0) + F0`` for ``z > z0`` and ``F0`` before contact, with ``Φ(δ)`` the
force at unit modulus (:mod:`contactlab.fit._tip`) and ``1/E* = (1 - ν²)/E + c_tip``.

Exact Jacobian (no finite differences): ``∂F/∂E = Φ · E*² (1 - ν²)/E²``,
``∂F/∂z0 = -E* Φ'(δ) = -2E* a(δ)``, ``∂F/∂F0 = 1``. The solver is scipy's
Levenberg-Marquardt (MINPACK, as in ``least_squares(method="lm")``), in scaled variables.
"""
from __future__ import annotations

from typing import Any

import numpy as np

from ..effects._protocol import reporting
from ..errors import (
    ConvergenceError,
    NotSupportedError,
    OutsideTheoryError,
    ParameterError,
    UnknownNameError,
)
from ..materials import Elastic, Rigid
from ..materials.base import Material
from ..params.checks import check_in_range
from ..profiles.base import Profile
from ._args import (data_array, free_names, needs_adhesion, optional_positive, start_values,
                    warn_undetermined)
from .result import FitResult

__all__ = ["FREE_NAMES", "indentation"]

#: SI units of the starting values (a start given with a unit is converted)
START_UNITS = {"E": "Pa", "contact_point": "m", "force_offset": "N", "work_of_adhesion": "J/m^2"}

#: parameters ``fit.indentation`` can fit besides the sample's constructor arguments
FREE_NAMES = ("contact_point", "force_offset", "work_of_adhesion")
#: fraction of the curve (in depth order) taken as the baseline for the starting values
_BASELINE = 0.1
#: a JKR curve's snap into contact: a drop of at least this share of the descent from the
#: first sample to the force's minimum (5/9 for a paraboloid: -5/6 πwR of -3/2 πwR)
_SNAP_SHARE = 0.3
#: candidate contact points of the start search
_START_CANDIDATES = 8
#: successive parabolic steps of the JKR start search in ln E*
_JKR_PARABOLIC = 4
#: points of the first pass of a JKR fit (a subsample of the curve)
_JKR_SUBSAMPLE = 256


def _check_inputs(depth: Any, force: Any, profile: Any, sample: Any, tip: Any, free: Any,
                  adhesion: str | None = None
                  ) -> tuple[np.ndarray, np.ndarray, tuple[str, ...], Material]:
    z = data_array("depth", depth)
    F = data_array("force", force)
    if z.size != F.size:
        raise ParameterError(f"depth has {z.size} points and force has {F.size}: give curves "
                             "of equal length.")
    if not isinstance(profile, Profile):
        raise ParameterError(f"profile={profile!r} is invalid: expected a contactlab Profile "
                             "(e.g. contactlab.profiles.Sphere(R=1e-5)).")
    if not isinstance(sample, Elastic):
        raise ParameterError(f"sample={sample!r} is invalid: give an Elastic material template "
                             "(its E is the starting value when 'E' is free, else fixed).")
    tip_m = Rigid() if tip is None else tip
    if not isinstance(tip_m, Material) or tip_m.is_viscoelastic:
        raise ParameterError(f"tip={tip!r} is invalid: give None (rigid), Rigid() or an "
                             "Elastic material.")
    names = free_names(free)
    allowed = tuple(p.name for p in type(sample).params) + FREE_NAMES
    for n in names:
        if n not in allowed:
            raise UnknownNameError(f"free={n!r} is unknown: choose from {allowed}.")
    if len(set(names)) != len(names):
        raise ParameterError(f"free={names!r} names a parameter twice.")
    if "nu" in names:
        raise ParameterError("free='nu' is invalid: a normal indentation curve determines only "
                             "E/(1 - nu²); fix nu in the sample template and fit 'E'.")
    if "work_of_adhesion" in names and adhesion is None:
        raise ParameterError("free='work_of_adhesion' needs an adhesive model: give "
                             "adhesion='jkr'.")
    if not names:
        raise ParameterError("free=() is invalid: name at least one parameter to fit.")
    if z.size <= len(names):
        raise ParameterError(f"depth has {z.size} points: a fit of {len(names)} parameters "
                             f"needs more than {len(names)}.")
    return z, F, names, tip_m


def _check_work(names: tuple[str, ...], work_of_adhesion: float | None, adhesion: str) -> None:
    if "work_of_adhesion" not in names:
        if work_of_adhesion is None:
            raise ParameterError(f"adhesion={adhesion!r} needs the work of adhesion: add "
                                 "'work_of_adhesion' to free or give work_of_adhesion=... J/m².")
        if not (np.isfinite(work_of_adhesion) and work_of_adhesion > 0):
            raise ParameterError(f"work_of_adhesion={work_of_adhesion!r} is invalid: give a "
                                 "positive value, J/m².")


def _apex_radius(profile: Profile) -> float:
    """Radius of curvature of the tip's apex, ``1/f''(0)`` (m), for the Tabor parameter of a
    JKR fit: a paraboloid term ``r²/(2R)`` plus higher powers, or the exact sphere."""
    from ..profiles import Sphere
    if isinstance(profile, Sphere):
        return float(profile.R)
    terms = profile.power_terms()
    if terms is not None and profile.flat_radius == 0.0 and not np.isfinite(profile.wall_radius):
        quad = [c for c, n in terms if n == 2.0]
        if len(quad) == 1 and quad[0] > 0 and all(n >= 2.0 for _, n in terms):
            return 1.0 / (2.0 * quad[0])
    raise NotSupportedError(
        f"equilibrium_distance=... with adhesion='jkr' and profile={profile!r}: the Tabor "
        "parameter needs the tip's apex radius of curvature R (a paraboloid, the exact Sphere, "
        "or a sum of a paraboloid and higher powers); a cone or flat apex has none (R = 0 or "
        "infinite); drop equilibrium_distance.")


def _jkr_model(profile: Profile, adhesion: str | None, names: tuple[str, ...],
               work_of_adhesion: float | None, delta_max: float = 0.0, rtol: float = 1e-12
               ) -> Any:
    """The JKR model of the tip, or None without adhesion: closed forms for a single power-law
    tip ``c r^n`` (n >= 1), else a Hermite table of ``g`` in the contact radius."""
    if adhesion is None:
        return None
    _check_work(names, work_of_adhesion, adhesion)
    if profile.flat_radius > 0.0 and np.isfinite(profile.wall_radius):
        raise NotSupportedError(
            f"adhesion='jkr' with profile={profile!r}: a flat centre inside a wall (other than "
            "a flat punch, fitted by Kendall's model) is not covered.")
    from ._tip import flat_radius
    b = flat_radius(profile)
    if b > 0.0:                             # a flat centre with a rising flank
        a_na = float(profile._radius_of_depth(np.array([delta_max]), rtol)[0])
        if profile.flat_radius == 0.0:      # a measured table, flat up to b
            from ._jkr_flat import JKRFlatTable
            return JKRFlatTable(profile, min(1.5 * a_na, profile.max_radius * (1.0 - 1e-6)),
                                rtol, b)
        if not (profile.g_route == "closed_form"
                and profile._g_integral_exact(np.array([profile.flat_radius])) is not None):
            raise NotSupportedError(
                f"adhesion='jkr' with profile={profile!r}: a flat centre is covered for tips "
                "whose transform g and its integral have closed forms (TruncatedCone, "
                "TruncatedParaboloid) and for measured tables with linear interpolation; this "
                "one is not.")
        from ._jkr_flat import JKRFlat
        return JKRFlat(profile, 1.5 * a_na, rtol)
    from ._jkr import JKRPower, JKRTable
    terms = profile.power_terms()
    if terms is not None and len(terms) == 1 and terms[0][1] >= 1.0:
        c, n = terms[0]
        return JKRPower(profile._power_kappa(n) * c, n)
    if terms is not None and any(n < 1.0 for _, n in terms):
        raise NotSupportedError(
            f"adhesion='jkr' with profile={profile!r}: a power term with n < 1 (a cusp at the "
            "apex) has no JKR branch end; give a tip whose terms have n >= 1.")
    a_na = float(profile._radius_of_depth(np.array([delta_max]), rtol)[0])
    a_top = 1.5 * a_na                  # adhesion widens the contact at a given indentation
    if np.isfinite(profile.max_radius):
        a_top = min(a_top, profile.max_radius * (1.0 - 1e-6))
    if np.isfinite(profile.wall_radius):    # the contact stops at the wall (the table's end)
        a_top = min(a_top, profile.wall_radius)
    return JKRTable(profile, a_top, rtol)


@reporting()
def indentation(depth: Any, force: Any, profile: Profile, *, sample: Elastic,
                tip: Material | None = None, free: Any = None,
                adhesion: str | None = None, work_of_adhesion: float | None = None,
                equilibrium_distance: float | None = None, time: Any = None,
                start: dict | None = None, rtol: float = 1e-12) -> FitResult:
    """Fit an elastic indentation curve: the sample's Young's modulus, the contact point and
    the force offset, with exact derivatives.

    Parameters
    ----------
    depth : array_like
        Indenter position, m (increasing into the sample); the contact point is unknown unless
        ``"contact_point"`` is not free (then ``depth`` is the indentation itself).
    force : array_like
        Measured normal force, N, same length.
    profile : Profile
        The tip's shape: closed forms, the exact ``Sphere``, ``Cone``, a measured
        ``Tabulated`` tip, sums, a punch wall (``FlatPunch``, a rounded end inside a wall;
        not with ``"dmt"``).
    sample : Elastic
        Material template of the sample: its ``nu`` is used, its ``E`` is the fixed value (or
        the fallback start when ``"E"`` is free; the start is computed from the data).
    tip : Material or None
        The tip's material (``None``: rigid).
    free : sequence of str
        Names to fit: ``"E"``, ``"contact_point"``, ``"force_offset"`` and, with
        ``adhesion="jkr"``, ``"work_of_adhesion"``. The others are fixed
        (``contact_point`` 0 m, ``force_offset`` 0 N, ``E`` the template's).
    adhesion : None or "jkr"
        ``"jkr"``: adhesive contact by Heß's rule through the MDR (the JKR limit): power laws
        ``c r^n`` with ``n >= 1`` in closed form, others by a table (a rounded end inside a
        wall: the radius stops at the wall), flat-centred tips with a rising flank exactly;
        the curve is the retraction
        branch under fixed grips (zero force once the surfaces have come apart). A flat
        punch (``FlatPunch``): Kendall's model, ``F = 2E* b δ`` while attached, detachment at
        ``δ_c = -sqrt(2π b Δγ/E*)``; ``E``, the contact point and the offset by linear least
        squares, ``Δγ`` from the measured pull-off in closed form (its sampling bracket in
        ``meta["work_of_adhesion_bracket"]``, see the fitting docs).
        ``"dmt"``: the non-adhesive MDR force less the Derjaguin force of a short-range
        attraction on the rigid gap beyond the contact edge, ``2πΔγ ρ(a)`` with the effective
        radius ``ρ(a) = a/f'(a)`` (``R`` for a paraboloid, ``sqrt(R² - a²)`` for the exact
        sphere, ``a/s`` for a cone of slope ``s``), for any tip without a wall whose gap opens
        beyond the contact edge; ``meta["effective_radius"]`` is ``ρ`` at the deepest point.
    work_of_adhesion : float, optional
        ``Δγ``, J/m²: the fixed value when ``"work_of_adhesion"`` is not free.
    equilibrium_distance : float, optional
        ``z0`` of the Tabor parameter ``μ_T = (R Δγ²/(E*² z0³))^(1/3)``, m: the fit reports
        ``μ_T`` in ``meta["tabor_parameter"]`` and warns (ValidityWarning) when ``μ_T < 5``
        with JKR or ``μ_T > 0.1`` with DMT (outside the model's limit). ``R``: the apex radius
        (JKR, rounded tips); with DMT, and for JKR tips without one, the effective radius
        ``a/f'(a)`` at the deepest point; none for a flat punch. Every adhesive fit reports
        ``μ_T``: without ``equilibrium_distance`` at an assumed 0.3 nm, with
        ``meta["tabor_parameter_range"]`` over 0.2-0.5 nm, warning only when the whole range
        is outside the model's limit.
    time : array_like, optional
        Sample times, s, for a viscoelastic sample (Lee-Radok on the approach, Ting on the
        retract); with ``adhesion="dmt"`` the adhesive force follows Ting's contact radius
        (``adhesion="jkr"`` is refused: the crack at the edge is rate dependent).
    start : dict, optional
        Starting values by name (override the automatic ones): fitted names only, finite
        numbers, positive for ``"E"`` and ``"work_of_adhesion"``.
    rtol : float
        Tolerance of the profile's routes when a tip table is built.

    Returns
    -------
    FitResult

    Raises
    ------
    ParameterError
        Non-finite values, unequal lengths, too few points, a curve that never reaches contact,
        a non-elastic sample; ``free`` not a name or names; ``start`` not a mapping or a start
        value not a finite number (positive for ``E`` and the work of adhesion);
        ``work_of_adhesion`` or ``equilibrium_distance`` not a positive number, or given
        without ``adhesion``.
    UnknownNameError
        An unknown name in ``free``, a name in ``start`` that is not fitted.
    NotSupportedError
        ``adhesion`` with ``time``, a profile rising up to a wall with ``time`` (a flat punch
        is covered), DMT on a tip flat at the contact's
        onset (``f'(a)/a -> 0``).
    ConvergenceError
        The solver did not converge.

    Examples
    --------
    >>> import numpy as np
    >>> from contactlab import Elastic, fit
    >>> from contactlab.profiles import Paraboloid
    >>> z = np.linspace(-50e-9, 200e-9, 300)
    >>> d = np.maximum(z - 10e-9, 0.0)
    >>> F = 4/3 * 2e6/(1 - 0.25) * np.sqrt(5e-6) * d**1.5
    >>> res = fit.indentation(z, F, Paraboloid(R=5e-6), sample=Elastic(E=1e6, nu=0.5))
    >>> round(res.params["E"] / 2e6, 9), round(res.params["contact_point"] * 1e9, 6)
    (1.0, 10.0)
    """
    if adhesion not in (None, "jkr", "dmt"):
        raise ParameterError(f"adhesion={adhesion!r} is invalid: choose None, 'jkr' or 'dmt'.")
    needs_adhesion(adhesion, work_of_adhesion=work_of_adhesion,
                   equilibrium_distance=equilibrium_distance)
    rtol = check_in_range("rtol", rtol, 0.0, 1.0, low_open=True, high_open=True,
                          what="the model's relative tolerance")
    work_of_adhesion = optional_positive("work_of_adhesion", work_of_adhesion,
                                         "the work of adhesion", "J/m^2")
    equilibrium_distance = optional_positive("equilibrium_distance", equilibrium_distance,
                                             "the equilibrium distance", "m")
    if time is not None:
        if adhesion == "jkr":
            raise NotSupportedError(
                "adhesion='jkr' with time=...: on a viscoelastic sample the JKR crack at the "
                "contact edge grows and heals at rates that depend on the crack speed (the "
                "work of adhesion is rate dependent, with a hysteresis between approach and "
                "retract), which Ting's rules do not describe; fit adhesion='dmt' (an "
                "attraction beyond the contact edge, through Ting's contact radius) or an "
                "elastic JKR fit of the retract.")
        if not isinstance(profile, Profile):
            raise ParameterError(f"profile={profile!r} is invalid: expected a contactlab "
                                 "Profile (e.g. contactlab.profiles.Sphere(R=1e-5)).")
        z, F = data_array("depth", depth), data_array("force", force)
        if z.size != F.size:
            raise ParameterError(f"depth has {z.size} points and force has {F.size}: give "
                                 "curves of equal length.")
        from .viscoelastic import fit_viscoelastic
        return fit_viscoelastic(z, F, time, profile, sample, tip, free, start, rtol,
                                adhesion, work_of_adhesion, equilibrium_distance)
    if isinstance(sample, Material) and sample.is_viscoelastic:
        raise ParameterError(f"sample={sample!r} is viscoelastic: give the sample times as "
                             "time=... (s) to fit it with Ting's rules.")
    if free is None:
        free = ("E", "contact_point")
    z, F, names, tip_m = _check_inputs(depth, force, profile, sample, tip, free, adhesion)
    start = start_values(start, names, ("E", "work_of_adhesion"), START_UNITS)
    if adhesion == "jkr":
        if profile.is_flat_punch:
            _check_work(names, work_of_adhesion, adhesion)
            return _kendall_result(z, F, profile, sample, tip_m, names, work_of_adhesion,
                                   dict(start))
    jkr = None
    dmt = None
    if adhesion == "dmt":
        _check_work(names, work_of_adhesion, adhesion)
        from ._dmt import check_wall
        check_wall(profile)
    c_tip = tip_m._compliances()[0]
    k_nu = 1.0 - sample.nu ** 2
    order = np.argsort(z, kind="stable")
    zs, Fs = z[order], F[order]
    span = float(zs[-1] - zs[0])
    fit_cp = "contact_point" in names
    fit_off = "force_offset" in names
    # ---- the tip model over every indentation the bounds allow
    if fit_cp:
        if span <= 0:
            raise ParameterError("depth has a single value: a contact point cannot be fitted.")
        cp_lo = float(zs[0]) - span
        delta_max = (float(zs[-1]) - cp_lo) * 1.0001
    else:
        cp_lo = 0.0
        delta_max = float(zs[-1]) * 1.0001
        if delta_max <= 0:
            raise ParameterError(f"depth <= 0 everywhere (max {delta_max!r} m) with the contact "
                                 "point fixed at 0: the curve never reaches contact.")
    if np.isfinite(profile.max_radius):     # a finite tip (a table, the sphere): its reach
        reach = float(profile._g(np.array([profile.max_radius * (1.0 - 1e-6)]), rtol)[0])
        if delta_max > reach:
            delta_max = reach
            cp_lo = float(zs[-1]) - reach
            if not fit_cp:
                raise OutsideTheoryError(
                    f"depth={float(zs[-1])!r} m exceeds the depth {reach!r} m that {profile!r} "
                    "reaches at its max_radius; use a larger tip or drop the deep points.")
    from ._tip import TipModel
    tipm = TipModel(profile, delta_max, rtol, allow_wall=True)
    if adhesion == "dmt":
        from ._dmt import DMTModel
        dmt = DMTModel(profile, tipm)
    if adhesion == "jkr":
        jkr = _jkr_model(profile, adhesion, names, work_of_adhesion, delta_max, rtol)
    # ---- starting values
    user_start = dict(start or {})
    start = dict(user_start)
    n_base = max(2, int(_BASELINE * zs.size))
    if jkr is not None:
        # JKR: the detached samples end at the snap into contact, the largest drop before the
        # force's minimum; a first tenth that runs past them into the attached branch set the
        # offset start far below the baseline (and the fit converged there)
        i_min = int(np.argmin(Fs))
        drops = np.diff(Fs[:i_min + 1])
        if drops.size:
            i_snap = int(np.argmin(drops)) + 1
            if i_snap >= 2 and -float(drops[i_snap - 1]) > _SNAP_SHARE * float(Fs[0] - Fs[i_min]):
                n_base = min(n_base, i_snap)
    base = Fs[:n_base]
    off0 = float(np.median(base)) if fit_off else 0.0
    rise = Fs - off0
    top = float(np.max(np.abs(rise) if dmt is not None else rise))   # DMT: the drop counts
    noise = float(np.median(np.abs(base - np.median(base)))) * 1.4826 if fit_off else 0.0
    thr = max(5.0 * noise, 0.02 * top)
    if top <= 0 or not np.any((np.abs(rise) if dmt is not None else rise) > thr):
        raise ParameterError(
            f"force never rises above its baseline (largest rise {top!r} N over an offset of "
            f"{off0!r} N): the curve never reaches contact; check the sign of force and depth.")
    zc, Fc, proj_off = zs, Fs, fit_off
    if dmt is not None and dmt.rho0 == 0.0:
        # a pointed tip: no step at the contact point; the force is linear in E*, Δγ and the
        # offset at a given contact point, which a search over candidates projects out
        from ._dmt import dmt_start
        dmt_start(dmt, tipm, start, names, zs, Fs, rise, cp_lo, fit_off,
                  float(work_of_adhesion or 0.0), k_nu, c_tip, float(sample.E))
    if dmt is not None:             # DMT: the force drops by 2πΔγ ρ0 at the contact point
        i_min = int(np.argmin(rise))
        if fit_cp and "contact_point" not in start:
            start["contact_point"] = 0.5 * (float(zs[max(i_min - 1, 0)]) + float(zs[i_min]))
        if "work_of_adhesion" in names and "work_of_adhesion" not in start:
            start["work_of_adhesion"] = max(-float(rise[i_min]), 1e-6 * top) / (
                2.0 * np.pi * dmt.rho0)
        if fit_off and "force_offset" not in start:
            start["force_offset"] = off0
        w0 = float(start.get("work_of_adhesion", work_of_adhesion or 0.0))
        rho_s = dmt(zs - float(start.get("contact_point", 0.0)))[0]
        Fc = Fs + 2.0 * np.pi * rho_s * w0
    if jkr is not None:             # the start from the part above the baseline after pull-off
        keep = (np.arange(zs.size) > int(np.argmin(rise))) & (rise > 0)
        zc, Fc, proj_off = zs[keep], rise[keep], False
    if fit_cp and "contact_point" not in start:
        z_thr = float(zs[int(np.argmax(rise > thr))])
        cands = np.linspace(max(cp_lo, z_thr - 0.5 * (float(zs[-1]) - z_thr)), z_thr,
                            _START_CANDIDATES)
        best = (np.inf, z_thr)
        n_f = float(Fc.size)
        sF, sFF = float(Fc.sum()), float(Fc @ Fc)
        for c in cands:                 # the linear parameters projected out at each candidate
            phi, _ = tipm(zc - c)
            sp, spp, spF = float(phi.sum()), float(phi @ phi), float(phi @ Fc)
            if proj_off:                # 2x2 normal equations of F = e·phi + o
                det = n_f * spp - sp * sp
                if det <= 0:
                    continue
                e = (n_f * spF - sp * sF) / det
                o = (sF - e * sp) / n_f
                rss = sFF - e * spF - o * sF
            else:
                e = spF / spp if spp > 0 else 0.0
                rss = sFF - e * spF
            if rss < best[0] and e > 0:
                best = (rss, float(c))
        start["contact_point"] = best[1]
    cp0 = float(start.get("contact_point", 0.0))
    phi0, _ = tipm(zc - cp0)
    if jkr is not None and fit_off and "force_offset" not in start:
        start["force_offset"] = off0
    if fit_off and "force_offset" not in start:
        A = np.stack([phi0, np.ones_like(phi0)], axis=1)
        coef, *_ = np.linalg.lstsq(A, Fs, rcond=None)
        start["force_offset"] = float(coef[1])
    off0 = float(start.get("force_offset", 0.0))
    if "E" in names and "E" not in start:
        es = float(phi0 @ (Fc - (0.0 if jkr is not None else off0))) / max(
            float(phi0 @ phi0), 1e-300)
        if not es > 0:
            es = float(sample.E) / k_nu
        inv = 1.0 / es - c_tip
        start["E"] = k_nu / inv if inv > 0 else float(sample.E)
    def estar(E: float) -> float:
        return 1.0 / (k_nu / E + c_tip)

    fixed = {"E": float(sample.E), "contact_point": 0.0, "force_offset": 0.0,
             "work_of_adhesion": float(work_of_adhesion or 0.0)}
    if jkr is not None:
        es0 = _jkr_start(jkr, start, names, estar(float(start.get("E", sample.E))), zs, rise,
                         fixed["work_of_adhesion"], set(user_start))
        if "E" in names and "E" not in user_start:
            inv = 1.0 / es0 - c_tip
            start["E"] = k_nu / inv if inv > 0 else float(sample.E)
    # ---- scaled problem (E and the work of adhesion through their logarithms)
    scales = {"E": float(start.get("E", sample.E)), "contact_point": max(span, 1e-300),
              "force_offset": max(top, 1e-300),
              "work_of_adhesion": float(start.get("work_of_adhesion", 1.0))}
    logs = ("E", "work_of_adhesion")
    idx = {n: i for i, n in enumerate(names)}

    def unpack(x: np.ndarray) -> dict[str, float]:
        vals = dict(fixed)
        vals.update({n: float(start[n]) for n in names if n not in idx and n in start})
        for n, i in idx.items():     # E as exp(x) · scale: positive without bounds
            vals[n] = (float(np.exp(x[i])) if n in logs else float(x[i])) * scales[n]
        return vals

    cache: dict = {}

    def evaluate(x: np.ndarray) -> tuple:
        key = x.tobytes()
        if key not in cache:
            cache.clear()
            v = unpack(x)
            Es = estar(v["E"])
            if jkr is None:             # F = E*Φ: ∂F/∂E* = Φ, ∂F/∂δ = E*Φ' = 2E*a
                phi, dphi = tipm(z - v["contact_point"])
                f, f_d, f_e, f_w = Es * phi, Es * dphi, phi, None
                if dmt is not None:     # DMT: - 2πΔγ ρ in contact, ∂F/∂Δγ = -2πρ there
                    delta = z - v["contact_point"]
                    rho, rho_d = dmt(delta)
                    f_w = np.where(delta > 0, -2.0 * np.pi * rho, 0.0)
                    f = f + f_w * v["work_of_adhesion"]
                    if dmt.route != "constant":     # ∂F/∂δ: - 2πΔγ dρ/dδ
                        f_d = f_d - (2.0 * np.pi * v["work_of_adhesion"]) * rho_d
            else:
                f, f_d, f_e, f_w = jkr.force(z - v["contact_point"], Es, v["work_of_adhesion"])
            cache[key] = (v, Es, f, f_d, f_e, f_w)
        return cache[key]

    def residual(x: np.ndarray) -> np.ndarray:
        v, _, f, *_ = evaluate(x)
        return f + v["force_offset"] - F

    def jacobian(x: np.ndarray) -> np.ndarray:
        v, Es, _, f_d, f_e, f_w = evaluate(x)
        J = np.empty((z.size, len(idx)))
        for n, i in idx.items():
            if n == "E":                # ∂F/∂ln E = ∂F/∂E* · E*²(1 - ν²)/E
                J[:, i] = f_e * (Es * Es * k_nu / v["E"])
            elif n == "contact_point":
                J[:, i] = -f_d * scales[n]
            elif n == "work_of_adhesion":
                J[:, i] = f_w * v[n]
            else:
                J[:, i] = scales[n]
        return J

    from ._tip import ROUNDING, covariance, levenberg_marquardt
    floor = (ROUNDING ** 2) * float(F @ F)
    stages = [names]
    if jkr is not None and fit_off and len(names) > 1:
        # the offset shifts the detached points and the branch end together: fitted last,
        # from the solution with the baseline's offset (Levenberg-Marquardt otherwise wanders
        # along the discontinuity at the branch end)
        stages.insert(0, tuple(n for n in names if n != "force_offset"))
    z_all, F_all = z, F
    sub = max(1, z.size // _JKR_SUBSAMPLE)
    if jkr is not None and sub > 1:
        # a first pass on every sub-th point: most of the walk from the start (whose Δγ is
        # high under fixed grips) costs a fraction of a full evaluation
        stages.insert(0, stages[0])
    for k_stage, stage in enumerate(stages):
        z, F = (z_all[::sub], F_all[::sub]) if (k_stage == 0 and len(stages) > 1
                                                 and jkr is not None and sub > 1) \
            else (z_all, F_all)
        idx.clear()
        idx.update({n: i for i, n in enumerate(stage)})
        cache.clear()
        x0 = np.empty(len(stage))
        for n, i in idx.items():
            v0 = float(start.get(n, fixed[n])) / scales[n]
            x0[i] = np.log(v0) if n in logs else v0
        # Levenberg-Marquardt (MINPACK): no bounds are needed (E > 0 through ln E; the tip
        # model is defined for every contact point) and its gradient test is scale-free
        x_sol, nfev, ok, msg = levenberg_marquardt(
            residual, jacobian, x0, floor=floor * z.size / z_all.size,
            stall=0.1 / (z.size - len(stage)))
        if not ok:
            raise ConvergenceError(f"fit.indentation did not converge: {msg}")
        start.update({n: v for n, v in unpack(x_sol).items() if n in idx})
    vals = unpack(x_sol)
    if fit_cp and not cp_lo <= vals["contact_point"] < float(zs[-1]):
        raise ConvergenceError(
            f"fit.indentation: the contact point went to {vals['contact_point']!r} m, outside "
            f"[{cp_lo!r}, {float(zs[-1])!r}) m (one depth span before the data to its end); "
            "give start={'contact_point': ...} or check the curve.")
    r = residual(x_sol)
    J = jacobian(x_sol) / np.array([vals[n] if n in logs else scales[n] for n in names])
    dof = z.size - len(names)
    s2 = float(r @ r) / dof
    cov = covariance(J, s2)
    stderr = {n: float(np.sqrt(cov[i, i])) for n, i in idx.items()}
    warn_undetermined(stderr)
    from ..contact import Contact
    fitted = Elastic(E=vals["E"], nu=sample.nu)
    w_fit = vals["work_of_adhesion"] if adhesion is not None else None
    # the fitted contact carries the work of adhesion only for JKR (the contact's own adhesion
    # model); a DMT fit reports it in params
    contact = Contact(profile, (tip_m, fitted), work_of_adhesion=w_fit if jkr else None)
    meta: dict = {"citations": ("PH", "H1", "Sn65") + (("JKR71", "Heß11") if jkr else ())
                  + (("DMT75", "M92") if dmt is not None else ()),
                  "x_name": "depth", "y_name": "force",
                  "tip_route": "jkr" if jkr is not None else tipm.route}
    dmt_R = None
    if dmt is not None:             # the effective radius a/f'(a) at the deepest point
        dmt_R = float(dmt(np.array([float(zs[-1]) - vals["contact_point"]]))[0][0])
        meta["effective_radius"] = dmt_R
        meta["dmt_route"] = dmt.route
    if jkr is not None and hasattr(jkr, "error"):
        meta["tip_model_errors"] = {"g": jkr.error}
        meta["model_error_basis"] = ("cubic Hermite table of the tip's transform g in the "
                                     "contact radius, measured at the interval midpoints")
    if adhesion is not None:
        assert w_fit is not None        # fitted or fixed with an adhesion model
        radius = dmt_R if dmt_R is not None else tabor_radius(
            profile, float(zs[-1]) - vals["contact_point"])
        report_tabor(meta, w_fit, contact.moduli.normal, equilibrium_distance, adhesion,
                     radius)
    if tipm.route == "table" and jkr is None:
        meta["tip_model_errors"] = {"force": tipm.error}
        meta["model_error_basis"] = ("cubic Hermite table of the tip's force at unit modulus, "
                                     "measured at the interval midpoints")
    if dmt is not None and dmt.route == "table":
        meta.setdefault("tip_model_errors", {})["dmt_radius"] = dmt.error
        meta["model_error_basis"] = (meta.get("model_error_basis", "") + "; " if
                                     "model_error_basis" in meta else "") + (
            "cubic spline of the DMT effective radius a/f'(a) in the contact radius (relative "
            "to its largest value), measured at the interval midpoints")
    params = {k: vals[k] for k in ("E", "contact_point", "force_offset")}
    if adhesion is not None:
        params["work_of_adhesion"] = vals["work_of_adhesion"]
    params["nu"] = float(sample.nu)
    return FitResult(params=params, free=names, stderr=stderr, covariance=cov, x=z, y=F,
                     model=r + F, residuals=r, contact=contact, dof=dof, nfev=nfev,
                     meta=meta)


def _kendall_result(z: np.ndarray, F: np.ndarray, profile: Profile, sample: Elastic,
                    tip_m: Material, names: tuple[str, ...], work_of_adhesion: float | None,
                    start: dict) -> FitResult:
    """A flat punch's JKR (Kendall) fit: :mod:`contactlab.fit._kendall`."""
    from ..contact import Contact
    from ._kendall import fit_kendall
    k_nu = 1.0 - sample.nu ** 2
    vals, stderr, cov, model, dof, extra = fit_kendall(
        z, F, float(profile.wall_radius), names, float(sample.E), k_nu,
        tip_m._compliances()[0], work_of_adhesion, start)
    fitted = Elastic(E=vals["E"], nu=sample.nu)
    contact = Contact(profile, (tip_m, fitted), work_of_adhesion=vals["work_of_adhesion"])
    meta: dict = {"citations": ("PH", "K71"), "x_name": "depth", "y_name": "force",
                  "tip_route": "kendall", **extra}
    report_tabor(meta, vals["work_of_adhesion"], contact.moduli.normal, None, "jkr", None)
    params = {k: vals[k] for k in ("E", "contact_point", "force_offset", "work_of_adhesion")}
    params["nu"] = float(sample.nu)
    r = model - F
    return FitResult(params=params, free=names, stderr=stderr, covariance=cov, x=z, y=F,
                     model=model, residuals=r, contact=contact, dof=dof, nfev=1, meta=meta)


def _jkr_start(jkr: Any, start: dict, names: tuple[str, ...], E_star0: float, zs: np.ndarray,
               rise: np.ndarray, w_fixed: float, given: set) -> float:
    """Starting values of a JKR fit; returns the starting ``E*``.

    The smallest force of the data is read as the end of the branch: for each candidate ``E*``
    (a factor 1/3..3 around the non-adhesive estimate ``E_star0``, then successive parabolic
    steps in ``ln E*``) the work of adhesion follows from that force (it is a power of ``Δγ``)
    and the contact point from its depth; the candidate with the smallest residual of (a
    subsample of) the data wins. (Under fixed grips the data's smallest force is the branch's
    minimum, ``9/5`` of the branch end's for a paraboloid, so ``Δγ`` starts high; reading it
    as that minimum instead started closer on noise-free curves but led noisy fits into local
    minima at the branch end's jump more often.)"""
    i_pull = int(np.argmin(rise))
    if getattr(jkr, "end_at_jump", False) and rise[i_pull] < 0:
        # the branch end is the jump: the first sample (in depth) below a quarter of the
        # smallest force (the end's force is more than half of it on these tips: 5/9 in the
        # paraboloid's limit b -> 0, all of it on a steep flank)
        i_pull = int(np.argmax(rise < 0.25 * rise[i_pull]))
    f_pull, z_pull = float(rise[i_pull]), float(zs[i_pull])
    step = max(1, zs.size // 256)           # the candidates are judged on a subsample
    zs, rise = zs[::step], rise[::step]
    # the force of c r^n grows as Δγ^((n+1)/(2n-1)) at a fixed point of the branch (a table:
    # the paraboloid's 1, iterated)
    n = getattr(jkr, "n", 2.0)
    p = getattr(jkr, "work_power", (2.0 * n - 1.0) / (n + 1.0))

    def work(E_star: float, point: Any) -> float:
        if "work_of_adhesion" not in names or "work_of_adhesion" in given:
            return float(start.get("work_of_adhesion", w_fixed))
        if not f_pull < 0:
            return 1e-9 * E_star * float(np.max(np.abs(zs)))
        w = float((f_pull / point(E_star, 1.0)[0]) ** p)
        if not hasattr(jkr, "n"):
            for _ in range(4):
                w *= float((f_pull / point(E_star, w)[0]) ** p)
        return w

    def trial(es: float, point: Any) -> tuple[float, float, float, float]:
        w = work(es, point)
        cp = (z_pull - point(es, w)[1] if "contact_point" not in given
              and "contact_point" in names else float(start.get("contact_point", 0.0)))
        f = jkr.force(zs - cp, es, w)[0]
        return float(np.sum((f - rise) ** 2)), float(es), w, cp

    best = (np.inf, E_star0, work(E_star0, jkr.branch_end),
            float(start.get("contact_point", 0.0)))
    h = np.log(3.0) / 4.0                       # the grid's step in ln E*
    grid = E_star0 * np.exp(h * np.arange(-4, 5))
    for point in (jkr.branch_end,):
        if hasattr(jkr, "forces"):          # a power-law tip: all candidates in one evaluation
            ws = np.array([work(float(es), point) for es in grid])
            cps = np.array([z_pull - point(float(es), float(w))[1] for es, w in zip(grid, ws)]
                           if "contact_point" not in given and "contact_point" in names
                           else [float(start.get("contact_point", 0.0))] * grid.size)
            f = jkr.forces(zs[None, :] - cps[:, None], grid, ws)
            rss = np.sum((f - rise) ** 2, axis=1)
            rows = [(float(r), float(es), float(w), float(c))
                    for r, es, w, c in zip(rss, grid, ws, cps)]
        else:
            rows = [trial(float(es), point) for es in grid]
        i = int(np.argmin([r[0] for r in rows]))
        if rows[i][0] < best[0]:
            best = rows[i]
        if 0 < i < grid.size - 1 and "E" in names and "E" not in given:
            # successive parabolic steps in ln E* from the best point and its neighbours
            pts = [(float(np.log(r[1])), r) for r in rows[i - 1:i + 2]]
            for _ in range(_JKR_PARABOLIC):
                (u0, q0), (u1, q1), (u2, q2) = sorted(pts, key=lambda p: p[0])
                r0, r1, r2 = q0[0], q1[0], q2[0]
                den = (u1 - u0) * (r1 - r2) - (u1 - u2) * (r1 - r0)
                if not den != 0:
                    break
                u = u1 - 0.5 * ((u1 - u0) ** 2 * (r1 - r2) - (u1 - u2) ** 2 * (r1 - r0)) / den
                if not u0 < u < u2 or min(abs(u - u0), abs(u - u1), abs(u - u2)) < 1e-9:
                    break
                row = trial(float(np.exp(u)), point)
                # keep the three best points
                pts = sorted([*pts, (u, row)], key=lambda p: p[1][0])[:3]
                if row[0] < best[0]:
                    best = row
    start["work_of_adhesion"] = best[2]
    if "contact_point" in names:
        start["contact_point"] = best[3]
    return best[1]


#: equilibrium distance ``z0`` of the Tabor parameter when the user gives none, m, and the
#: range of typical interatomic distances a warning must hold over (Tabor 1977; Johnson and
#: Greenwood 1997 use 0.2-0.5 nm)
TABOR_Z0_DEFAULT = 0.3e-9
TABOR_Z0_RANGE = (0.2e-9, 0.5e-9)
#: limits of the two models in the Tabor parameter (Johnson and Greenwood 1997)
TABOR_JKR_MIN, TABOR_DMT_MAX = 5.0, 0.1


def tabor_radius(profile: Profile, delta: float) -> float | None:
    """Length ``R`` of the Tabor parameter of a tip (m): its apex radius of curvature where it
    has one (paraboloid, exact sphere, a paraboloid plus higher powers), else the effective
    radius ``a/f'(a)`` at the non-adhesive contact radius of the indentation ``delta`` (a cone,
    a power law, a truncated or measured tip); None where neither is finite and positive (a
    flat punch, whose adhesion is Kendall's)."""
    try:
        return _apex_radius(profile)
    except NotSupportedError:
        pass
    if not (np.isfinite(delta) and delta > 0.0):
        return None
    a = float(profile._radius_of_depth(np.array([delta]), 1e-10)[0])
    if np.isfinite(profile.wall_radius) and a >= profile.wall_radius:
        return None                     # the edge is at the wall: f' is infinite there
    slope = float(np.asarray(profile.derivative(a)))
    rho = a / slope if slope > 0.0 else float("inf")
    return rho if np.isfinite(rho) and rho > 0.0 else None


def report_tabor(meta: dict, w: float, E_star: float, z0: float | None, adhesion: str,
                 radius: float | None) -> None:
    """Write the Tabor parameter of an adhesive fit into ``meta`` and warn (ValidityWarning)
    where the chosen model is outside its limit.

    With ``z0`` given: ``meta["tabor_parameter"]`` at it, warning below 5 (JKR) or above 0.1
    (DMT). Without: the value at :data:`TABOR_Z0_DEFAULT` and ``meta["tabor_parameter_range"]``
    over :data:`TABOR_Z0_RANGE`; the warning is raised only where the whole range lies outside
    the model's limit (the result does not depend on the unknown ``z0`` then)."""
    if radius is None:
        meta["tabor_parameter"] = None
        meta["tabor_note"] = ("undefined: the tip has no curvature radius at the contact edge "
                              "(a punch wall); Kendall's adhesion acts through the pull-off")
        return
    if z0 is not None:
        meta["tabor_parameter"] = _tabor(w, E_star, z0, adhesion, radius, stacklevel=5)
        meta["equilibrium_distance"] = float(z0)
        return
    mu = _tabor_value(radius, w, E_star, TABOR_Z0_DEFAULT)
    lo = _tabor_value(radius, w, E_star, TABOR_Z0_RANGE[1])
    hi = _tabor_value(radius, w, E_star, TABOR_Z0_RANGE[0])
    meta["tabor_parameter"] = mu
    meta["tabor_parameter_range"] = (lo, hi)
    meta["equilibrium_distance"] = TABOR_Z0_DEFAULT
    meta["tabor_note"] = ("equilibrium distance assumed (0.3 nm; the range is over 0.2-0.5 nm): "
                          "give equilibrium_distance= to set it")
    _tabor_warn(adhesion, hi if adhesion == "jkr" else lo,
                " for every equilibrium distance in 0.2-0.5 nm (give equilibrium_distance= "
                "to set it)", stacklevel=4)


def _tabor_value(radius: float, w: float, E_star: float, z0: float) -> float:
    return float((radius * w * w / (E_star * E_star * z0 ** 3)) ** (1.0 / 3.0))


def _tabor_warn(adhesion: str, mu: float, where: str = "", stacklevel: int = 4) -> None:
    import warnings

    from ..errors import ValidityWarning
    if adhesion == "jkr" and mu < TABOR_JKR_MIN:
        warnings.warn(f"Tabor parameter {mu:.3g} < 5{where}: the contact is outside the JKR "
                      "limit (short-range adhesion, compliant bodies); the fitted work of "
                      "adhesion is biased (DMT applies below ~0.1).", ValidityWarning,
                      stacklevel=stacklevel)
    if adhesion == "dmt" and mu > TABOR_DMT_MAX:
        warnings.warn(f"Tabor parameter {mu:.3g} > 0.1{where}: the contact is outside the DMT "
                      "limit (long-range adhesion, stiff bodies); the fitted work of adhesion "
                      "is biased (JKR applies above ~5).", ValidityWarning,
                      stacklevel=stacklevel)


def _tabor(w: float, E_star: float, z0: float, adhesion: str, radius: float,
           stacklevel: int = 4) -> float:
    """Tabor parameter ``(R Δγ²/(E*² z0³))^(1/3)`` for the length ``radius``; warns outside
    the model's range: below 5 for JKR, above 0.1 for DMT."""
    if not (np.isfinite(z0) and z0 > 0):
        raise ParameterError(f"equilibrium_distance={z0!r} is invalid: give a positive "
                             "distance, m (typically 0.2-0.5e-9).")
    mu = _tabor_value(radius, w, E_star, z0)
    _tabor_warn(adhesion, mu, stacklevel=stacklevel)
    return mu
