"""Fits of steady friction hysteresis loops at a known normal force: friction coefficient and
shear modulus.

Both loops are built by Masing's rule from the virgin (first-loading) curve ``L(x)`` of the
contact at constant normal force: on a steady loop of amplitude ``x0`` (about its centre) the
branch travelled downwards is ``X = L(x0) - 2L((x0 - x)/2)`` and the branch travelled upwards
``X = -L(x0) + 2L((x0 + x)/2)``.

* Tangential (Cattaneo-Mindlin through the MDR, exact for any profile, punch walls included):
  ``L(u) = μ [F_N - E* Φ(d - G* u/(μ E*))]`` with ``Φ`` the force at unit modulus
  (:mod:`contactlab.fit._tip`) and ``d`` the depth at the normal force; ``L'(u) = 2G* c``.
  A flat punch (radius ``b``, ``Φ = 2bδ``) has no partial slip: ``L = min(2G* b u, μ F_N)``,
  the loop a parallelogram; a profile held at its wall (``d > g(b)``) sticks fully until
  ``u = μE*(d - g(b))/G*``.
* Torsion (Jäger's exact partial slip): power-law tips ``L(φ) = M_full m(φ/φ_s)`` with the
  certified master curve ``m`` of :mod:`contactlab.physics.master`, ``M_full ∝ μ``,
  ``φ_s ∝ μ/G_t``; every other tip (punch walls included) ``L(φ) = μ m(G_t φ/μ)`` with
  ``m`` the exact torsion at unit friction and modulus (its tractions are linear in ``μ``
  when ``φ`` scales with ``μ/G_t``); both ``L'(φ) = (16/3) G_t c³``.

Both have the form ``L = μ ℓ(x G/μ)``, so the derivatives are exact in closed form from the
slope: ``∂L/∂G = L'(x) x/G`` and ``∂L/∂μ = L/μ - L'(x) x/μ``. The sample's shear modulus
``G`` enters through ``1/G* = (2 - ν)/(4G) + (tip)`` (tangential) or ``1/G_t = 1/G + (tip)``
(torsion). The normal problem (``a``, ``d`` at the normal force) uses the sample template's
Young's modulus; the fitted shear modulus is the one the loop measures.

A loop that never slips (a punch's, or a profile's held at its wall, below the amplitudes
above) is the elastic line whatever the friction: a free friction then raises
:class:`~contactlab.errors.ParameterError` (the shear modulus alone is identified).
"""
from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np

from ..effects._protocol import reporting
from ..errors import ConvergenceError, ParameterError, UnknownNameError
from ..materials import Elastic, Rigid
from ..materials.base import Material
from ..params.checks import check_in_range
from ..profiles.base import Profile
from ._args import data_array, free_names, start_values
from .result import FitResult

__all__ = ["tangential_loop", "torsion_loop"]

_LOOP_NAMES = ("friction", "shear_modulus")
#: step of ``ln μ`` and relative change of the loop below which (per unit step) the friction is
#: not identifiable: a flat punch's loop that never slides is the elastic line ``k x`` whatever
#: ``μ`` (a change at rounding, ~1e-16 of the loop), while any slip changes the loop by the
#: order of the slipped force times the step
_SLIDE_STEP = 1e-4
_SLIDE_FLOOR = 1e-10
#: residual norm, relative to the data's, above which a fit that ends on the elastic line (no
#: slip) has run away from a slipping loop (a bad start) rather than met a loop without slip
_NO_SLIP_MISFIT = 0.05


def _prepare(x: Any, y: Any, force: Any, profile: Any, sample: Any, tip: Any, free: Any,
             x_name: str, y_name: str) -> tuple:
    xs = data_array(x_name, x)
    ys = data_array(y_name, y)
    if xs.size != ys.size:
        raise ParameterError(f"{x_name} has {xs.size} points and {y_name} has {ys.size}: give "
                             "curves of equal length.")
    FN = float(np.asarray(force, float)) if np.ndim(force) == 0 else np.nan
    if not (np.isfinite(FN) and FN > 0):
        raise ParameterError(f"force={force!r} is invalid: give the loop's constant normal force "
                             "as one positive number, N.")
    if not isinstance(profile, Profile):
        raise ParameterError(f"profile={profile!r} is invalid: expected a contactlab Profile.")
    if not isinstance(sample, Elastic):
        raise ParameterError(f"sample={sample!r} is invalid: give an Elastic material template.")
    tip_m = Rigid() if tip is None else tip
    if not isinstance(tip_m, Material) or tip_m.is_viscoelastic:
        raise ParameterError(f"tip={tip!r} is invalid: give None (rigid), Rigid() or an "
                             "Elastic material.")
    names = free_names(free)
    for n in names:
        if n not in _LOOP_NAMES:
            raise UnknownNameError(f"free={n!r} is unknown: choose from {_LOOP_NAMES}.")
    if not names or len(set(names)) != len(names):
        raise ParameterError(f"free={names!r} is invalid: name each of {_LOOP_NAMES} at most "
                             "once, at least one.")
    if xs.size <= len(names):
        raise ParameterError(f"{x_name} has {xs.size} points: too few for {len(names)} "
                             "parameters.")
    lo, hi = float(np.min(xs)), float(np.max(xs))
    if not hi > lo:
        raise ParameterError(f"{x_name} never moves: a loop needs a varying {x_name}.")
    return xs, ys, FN, tip_m, names, 0.5 * (hi + lo), 0.5 * (hi - lo)


def _branches(x: np.ndarray) -> np.ndarray:
    """+1 where ``x`` travels downwards (the branch from the upper turning point), -1 upwards."""
    dx = np.gradient(x)
    s = -np.sign(dx)
    if not np.any(s != 0):
        return np.ones_like(x)
    idx = np.where(s != 0, np.arange(x.size), -1)          # turning points: nearest direction
    last = np.maximum.accumulate(idx)
    first = last.copy()
    first[last < 0] = int(np.argmax(s != 0))
    return s[first]


class _OutOfRange(ArithmeticError):
    """A trial step of the loop fit left the range where the model is defined (a value that
    overflows or vanishes in floating point); its message names the values."""


def _loop_model(x: np.ndarray, names: tuple[str, ...], centre: float, amp: float,
                load: Callable, G_of: Callable, start: dict, fixed: dict) -> Callable:
    """``parts(p) -> (values, model, {name: ∂model/∂ln(name)})`` of the Masing loop of
    ``load(x, mu, G_eff) -> (L, L')`` at ``x``; ``p`` holds ``ln(value/start)`` of ``names``."""
    xr = x - centre
    s = _branches(xr)
    v = 0.5 * (amp - s * xr)
    idx = {n: i for i, n in enumerate(names)}

    def parts(p: np.ndarray) -> tuple:
        q = dict(fixed)
        with np.errstate(over="ignore", under="ignore"):
            for n, i in idx.items():
                q[n] = float(np.exp(p[i])) * start[n]
        mu, G = q["friction"], q["shear_modulus"]
        bad = [n for n in idx if not (np.isfinite(q[n]) and q[n] > 0.0 and np.isfinite(1.0 / q[n]))]
        if bad:
            raise _OutOfRange(", ".join(f"{n}={q[n]!r}" for n in bad))
        with np.errstate(all="ignore"):
            Ge, dGe = G_of(G)
            L0, dL0 = load(np.array([amp]), mu, Ge)
            Lv, dLv = load(v, mu, Ge)
        if not (np.isfinite(Ge) and Ge > 0 and np.all(np.isfinite(Lv)) and np.all(np.isfinite(dLv))
                and np.all(np.isfinite(L0)) and np.all(np.isfinite(dL0))):
            raise _OutOfRange(", ".join(f"{n}={q[n]!r}" for n in idx))
        model = s * (L0[0] - 2.0 * Lv)
        # L = mu l(x Ge/mu): dL/dGe = L' x/Ge, dL/dmu = L/mu - L' x/mu
        d_mu = s * ((L0[0] - dL0[0] * amp) / mu - 2.0 * (Lv - dLv * v) / mu)
        d_G = s * (dL0[0] * amp - 2.0 * dLv * v) / Ge * dGe
        return q, model, {"friction": d_mu * mu, "shear_modulus": d_G * G}

    return parts


def _fit_loop(x: np.ndarray, y: np.ndarray, names: tuple[str, ...], centre: float, amp: float,
              load: Callable, G_of: Callable, start: dict, fixed: dict) -> tuple:
    """Least squares of the Masing loop of ``load(x, mu, G_eff) -> (L, L')``."""
    parts = _loop_model(x, names, centre, amp, load, G_of, start, fixed)
    idx = {n: i for i, n in enumerate(names)}

    # a trial step that leaves the model's range gets a residual far above any other, so that
    # the solver rejects it and shortens its step (finite: its sum of squares must not overflow)
    rejected = np.full(y.size, 1e100 / np.sqrt(y.size))
    last_bad = [""]

    def residual(p: np.ndarray) -> np.ndarray:
        try:
            r = parts(p)[1] - y
        except _OutOfRange as err:
            last_bad[0] = str(err)
            return rejected
        if not float(np.max(np.abs(r))) < rejected[0]:     # (NaN too)
            last_bad[0] = ", ".join(f"{n}={float(np.exp(p[i])) * start[n]!r}"
                                    for i, n in enumerate(names))
            return rejected
        return r

    def jacobian(p: np.ndarray) -> np.ndarray:
        _, _, d = parts(p)
        return np.stack([d[n] for n in names], axis=1)

    starts = ", ".join(f"{n}={start[n]!r}" for n in names)

    def failed(what: str) -> ConvergenceError:
        return ConvergenceError(
            f"the loop fit of {names} did not converge from start ({starts}): {what}; give "
            "start={...} closer to the loop's values (friction of the order of the largest "
            "force over the normal force, the shear modulus of the material).")

    from ._tip import covariance, levenberg_marquardt
    try:
        x_sol, nfev, ok, msg = levenberg_marquardt(residual, jacobian, np.zeros(len(names)))
        q, model, d = parts(x_sol)
    except _OutOfRange as err:
        raise failed(f"it reached values where the model is undefined ({err})") from None
    if not ok:
        raise failed(str(msg))
    if not np.all(np.isfinite(model - y)) or float((model - y) @ (model - y)) >= float(
            rejected @ rejected):
        raise failed(f"every step left the model's range (last: {last_bad[0]})")
    r = model - y
    if "friction" in idx:
        # identifiable only if a larger friction changes the loop: a flat punch's loop that
        # never slides is the elastic line whatever the friction (any larger value fits as
        # well; at the threshold the derivative is one-sided)
        up = x_sol.copy()
        up[idx["friction"]] += _SLIDE_STEP
        change = float(np.linalg.norm(parts(up)[1] - model))
        if not change > _SLIDE_FLOOR * _SLIDE_STEP * float(np.linalg.norm(model)):
            misfit = float(np.linalg.norm(r)) / max(float(np.linalg.norm(y)), 1e-300)
            if misfit > _NO_SLIP_MISFIT:
                # the data are not the elastic line the fit stopped at: a start from which the
                # solver ran to a loop without slip, not a loop that never slips
                raise failed(f"it stopped at {', '.join(f'{n}={q[n]!r}' for n in names)}, "
                             "where the model loop never slips (the elastic line), "
                             f"{misfit:.2g} of the data's norm away from the data")
            raise ParameterError(
                f"free='friction' is not identifiable from this loop: at the fitted values "
                f"(friction={q['friction']!r}) it never slides, and every larger friction gives "
                "the same loop (the elastic line of a contact held at a punch wall); fit "
                "free=('shear_modulus',) with friction=... given, or a loop of larger amplitude.")
    J = np.stack([d[n] / q[n] for n in names], axis=1)
    dof = x.size - len(names)
    s2 = float(r @ r) / dof
    cov = covariance(J, s2)
    stderr = {n: float(np.sqrt(cov[i, i])) for n, i in idx.items()}
    undefined = [n for n in names if not np.isfinite(stderr[n])]
    if undefined:
        # a singular Jacobian: the loop does not change with these parameters at the values
        # reached (a loop fully sliding at a tiny or huge modulus), so they are not determined
        raise failed(f"it stopped at {', '.join(f'{n}={q[n]!r}' for n in names)}, where the "
                     f"loop does not determine {undefined} (singular Jacobian: their standard "
                     "errors are undefined)")
    return q, model, r, cov, stderr, dof, nfev


def _starts(y: np.ndarray, x: np.ndarray, centre: float, amp: float, FN: float, slope0: float,
            names: tuple[str, ...], start: dict | None, sample: Elastic, G_of: Callable,
            scale: float, plateau: bool = False) -> dict:
    """Starting values: the friction from the loop's largest value over its full-slip value
    (``scale`` = the full-slip value at friction 1; 5 % above it, or the value itself for a
    ``plateau`` loop that reaches full slip, a flat punch's, so that the start slides where the
    data do), the modulus from the slope of the branches
    leaving the turning points (the loop starts each branch with the no-slip stiffness)."""
    out = start_values(start, names, names, {"shear_modulus": "Pa"})
    if "friction" not in out:
        out["friction"] = max(float(np.max(np.abs(y))) / scale, 1e-6) * (1.0 if plateau
                                                                         else 1.05)
    if "shear_modulus" not in out:
        xr = x - centre
        # the branches leaving the turning points (a punch's loop is elastic there and flat
        # on the branch arriving at them)
        top = (np.abs(np.abs(xr) - amp) < 0.1 * amp) & (_branches(xr) * xr > 0)
        k = 0.0
        if np.count_nonzero(top) > 2:
            # the lower turning point's branch folded onto the upper's (x, y) -> (-x, -y): one
            # line, one intercept
            sg = np.sign(xr[top])
            k = abs(float(np.polyfit(sg * xr[top], sg * y[top], 1)[0]))
        G0 = float(sample.G)
        if k > 0 and slope0 > 0:
            # no-slip stiffness slope0 * G_eff: invert G_eff(G) by one secant on the template
            ge0, _ = G_of(G0)
            G0 = G0 * (k / slope0) / ge0 * 1.0
        out["shear_modulus"] = max(G0, 1e-6 * float(sample.G))
    return out


@reporting()
def tangential_loop(displacement: Any, tangential_force: Any, force: float, profile: Profile, *,
                    sample: Elastic, tip: Material | None = None,
                    free: Any = ("friction", "shear_modulus"), friction: float | None = None,
                    start: dict | None = None, rtol: float = 1e-12) -> FitResult:
    """Fit a steady tangential (fretting) loop at a known normal force: friction coefficient
    and the sample's shear modulus (Cattaneo-Mindlin with Masing's rule, exact through the MDR
    for any profile, punch walls included).

    Parameters
    ----------
    displacement : array_like
        Tangential displacement, m (a steady loop, in time order; its centre is removed).
    tangential_force : array_like
        Tangential force, N, same length.
    force : float
        The constant normal force, N (> 0).
    profile : Profile
        The tip's shape: any, a punch wall included (a flat punch has no partial slip: the
        loop is a parallelogram, ``Q = 2G* b u`` up to ``μF``; its friction comes from the
        plateau, the modulus from the elastic branches).
    sample : Elastic
        The sample template: its ``E`` and ``nu`` set the normal problem, its ``G`` is the
        fallback start (or fixed value) of ``"shear_modulus"``.
    tip : Material or None
        The tip (None: rigid).
    free : sequence of str
        ``"friction"``, ``"shear_modulus"``.
    friction : float, optional
        Fixed friction coefficient when ``"friction"`` is not free.
    start : dict, optional
        Starting values by name: fitted names only, positive finite numbers.
    rtol : float
        Tolerance of the profile's routes.

    Returns
    -------
    FitResult
        ``params``: ``friction``, ``shear_modulus`` (Pa), ``G_star`` (Pa).

    Raises
    ------
    ParameterError
        Bad input; or ``"friction"`` free on a loop that never slips at the fitted values (a
        flat punch below ``|Q| = μF``): every larger friction gives the same loop.
    UnknownNameError
        An unknown name in ``free``.
    ConvergenceError
        The solver did not converge, or stopped where the loop does not determine the
        parameters (a singular Jacobian; a start far from the loop): the message names the
        start and the values reached.
    """
    rtol = check_in_range("rtol", rtol, 0.0, 1.0, low_open=True, high_open=True,
                          what="the model's relative tolerance")
    x, y, FN, tip_m, names, centre, amp = _prepare(
        displacement, tangential_force, force, profile, sample, tip, free, "displacement",
        "tangential_force")
    from ..contact import Contact
    from ._tip import TipModel
    contact = Contact(profile, (tip_m, sample), friction=friction)
    E_star = contact.moduli.normal
    st = contact.normal(force=FN)
    d, a = float(st.depth), float(st.radius)
    tipm = TipModel(profile, d * 1.0001, rtol, allow_wall=True)
    c_tip = tip_m._compliances()[1]
    k_nu = (2.0 - sample.nu) / 4.0

    def G_of(G: float) -> tuple[float, float]:
        ge = 1.0 / (k_nu / G + c_tip)
        return ge, ge * ge * k_nu / (G * G)

    def load(u: np.ndarray, mu: float, Ge: float) -> tuple[np.ndarray, np.ndarray]:
        phi, dphi = tipm(d - Ge * u / (mu * E_star))
        return mu * (FN - E_star * phi), Ge * dphi

    fixed = {"friction": float(friction or 0.0), "shear_modulus": float(sample.G)}
    if "friction" not in names and friction is None:
        raise ParameterError("friction is fixed (not in free): give friction=... .")
    st0 = _starts(y, x, centre, amp, FN, 2.0 * a, names, start, sample, G_of, FN,
                  plateau=tipm.route == "punch")
    st0.update({n: fixed[n] for n in _LOOP_NAMES if n not in names})
    q, model, r, cov, stderr, dof, nfev = _fit_loop(x, y, names, centre, amp, load, G_of,
                                                      st0, fixed)
    params = {"friction": q["friction"], "shear_modulus": q["shear_modulus"],
              "G_star": G_of(q["shear_modulus"])[0]}
    meta: dict[str, Any] = {"citations": ("PH", "H1", "MD53"), "x_name": "displacement",
            "y_name": "tangential_force", "tip_route": tipm.route}
    if tipm.route == "table":
        meta["tip_model_errors"] = {"tangential_force": tipm.error}
    return FitResult(params=params, free=names, stderr=stderr, covariance=cov, x=x, y=y,
                     model=model, residuals=r, contact=Contact(profile, (tip_m, sample),
                                                               friction=q["friction"]),
                     dof=dof, nfev=nfev, meta=meta)


@reporting()
def torsion_loop(twist: Any, torque: Any, force: float, profile: Profile, *, sample: Elastic,
                 tip: Material | None = None, free: Any = ("friction", "shear_modulus"),
                 friction: float | None = None, start: dict | None = None,
                 route: str = "auto") -> FitResult:
    """Fit a steady torsion loop at a known normal force: friction coefficient and the sample's
    shear modulus (Jäger's exact partial slip with Masing's rule; any tip, punch walls
    included).

    Parameters
    ----------
    twist : array_like
        Twist angle, rad (a steady loop, in time order; its centre is removed).
    torque : array_like
        Torque, N·m, same length.
    force : float
        The constant normal force, N (> 0).
    profile : Profile
        The tip's shape: power laws ``c r^n`` (Paraboloid, Cone, PowerLaw) take the certified
        master curve, every other shape (exact ``Sphere``, sums, ``Tabulated``,
        ``TruncatedCone``, a ``FlatPunch``, a profile rising to a wall, ...) the library's
        exact torsion. A flat punch sticks fully up to the twist ``μF/(8 G_t b²)`` (slip then
        starts at the edge) and slides fully at the torque ``μF πb/4``.
    sample, tip, free, friction, start
        As for :func:`tangential_loop`; the shear modulus enters through ``1/G_t = 1/G + 1/G_tip``.
    route : {"auto", "exact"}
        ``"auto"``: the master curve for a single power law, else the exact torsion;
        ``"exact"``: the exact torsion for every tip (the same model as the master curve on a
        power law, slower).

    Returns
    -------
    FitResult
        ``params``: ``friction``, ``shear_modulus`` (Pa), ``G_torsion`` (Pa). ``meta["route"]``
        is ``"master"`` or ``"exact"``; the model error is the master curve's certified error
        or the exact torsion's estimated error (relative to the torque) at the fitted values.

    Raises
    ------
    ParameterError
        Bad input; or ``"friction"`` free on a loop that never slips at the fitted values (a
        flat punch below the twist above): every larger friction gives the same loop.
    UnknownNameError, ConvergenceError
        As for :func:`tangential_loop`.

    Notes
    -----
    At a fixed normal state Jäger's tractions are linear in ``μ`` when the twist scales with
    ``μ/G_t``, so the first-loading torque is ``L(φ) = μ m(G_t φ/μ)`` with ``m`` the torque at
    unit friction and unit torsional modulus; its slope is ``(16/3) G_t c³`` with ``c`` the
    stick radius (an increment of twist adds a rigidly twisted punch of radius ``c``).
    """
    x, y, FN, tip_m, names, centre, amp = _prepare(twist, torque, force, profile, sample, tip,
                                                   free, "twist", "torque")
    if route not in ("auto", "exact"):
        raise ParameterError(f"route={route!r} is invalid: choose 'auto' or 'exact'.")
    terms = profile.power_terms()
    if (route == "auto" and terms is not None and len(terms) == 1
            and not np.isfinite(profile.wall_radius)):
        return _torsion_master(x, y, FN, profile, sample, tip_m, names, centre, amp, friction,
                               start, float(terms[0][1]))
    return _torsion_exact(x, y, FN, profile, sample, tip_m, names, centre, amp, friction, start)


def _torsion_G_of(tip_m: Material) -> Callable:
    c_tip = tip_m._compliances()[2]

    def G_of(G: float) -> tuple[float, float]:
        ge = 1.0 / (1.0 / G + c_tip)
        return ge, ge * ge / (G * G)

    return G_of


def _torsion_result(x, y, profile, sample, tip_m, names, q, model, r, cov, stderr, dof, nfev,
                    G_of, meta) -> FitResult:
    from ..contact import Contact
    params = {"friction": q["friction"], "shear_modulus": q["shear_modulus"],
              "G_torsion": G_of(q["shear_modulus"])[0]}
    return FitResult(params=params, free=names, stderr=stderr, covariance=cov, x=x, y=y,
                     model=model, residuals=r, contact=Contact(profile, (tip_m, sample),
                                                               friction=q["friction"]),
                     dof=dof, nfev=nfev, meta=meta)


def _torsion_master(x, y, FN, profile, sample, tip_m, names, centre, amp, friction, start,
                    n) -> FitResult:
    """The power-law route: Jäger's torsion from the certified master curve."""
    from ..contact import Contact
    from ..physics import master as _master
    contact = Contact(profile, (tip_m, sample), friction=friction)
    E_star = contact.moduli.normal
    st = contact.normal(force=FN)
    d, a = float(st.depth), float(st.radius)
    mc = _master.torsion_master(n)
    G_of = _torsion_G_of(tip_m)

    def load(phi: np.ndarray, mu: float, Gt: float) -> tuple[np.ndarray, np.ndarray]:
        phi_s, M_full = _master.torsion_scales(n, E_star, Gt, mu, a, d)
        t, m, _ = mc(phi / phi_s)
        c = a * t
        return M_full * m, 16.0 / 3.0 * Gt * c ** 3

    fixed = {"friction": float(friction or 0.0), "shear_modulus": float(sample.G)}
    if "friction" not in names and friction is None:
        raise ParameterError("friction is fixed (not in free): give friction=... .")
    M_unit = _master.torsion_scales(n, E_star, 1.0, 1.0, a, d)[1]
    st0 = _starts(y, x, centre, amp, FN, 16.0 / 3.0 * a ** 3, names, start, sample, G_of,
                  M_unit)
    st0.update({k: fixed[k] for k in _LOOP_NAMES if k not in names})
    q, model, r, cov, stderr, dof, nfev = _fit_loop(x, y, names, centre, amp, load, G_of,
                                                      st0, fixed)
    meta = {"citations": ("PH", "J95"), "x_name": "twist", "y_name": "torque",
            "tip_model_errors": {"torque": float(mc.certified_error)},
            "model_error_basis": "certified error of the exact torsion master curve",
            "route": "master"}
    return _torsion_result(x, y, profile, sample, tip_m, names, q, model, r, cov, stderr, dof,
                           nfev, G_of, meta)


def _exact_virgin(contact: Any, d: float, Gt0: float) -> Callable:
    """``load(phi, mu, G_t) -> (L, L')`` of the first-loading torsion from the exact solver of
    ``contact`` (friction 1, torsional modulus ``Gt0``) at depth ``d``: ``L = μ m(G_t φ/μ)``
    with ``m(s)`` its torque at twist ``s/Gt0``, ``L' = (16/3) G_t c³``."""

    def load(phi: np.ndarray, mu: float, Gt: float) -> tuple[np.ndarray, np.ndarray]:
        psi, inv = np.unique(Gt / (mu * Gt0) * np.asarray(phi, float), return_inverse=True)
        st = contact.torsion(depth=d, twist=psi, method="exact")
        M = np.asarray(st.torque, float).reshape(-1)[inv]
        c = np.asarray(st.stick_radius, float).reshape(-1)[inv]
        return mu * M, 16.0 / 3.0 * Gt * c ** 3

    return load


def _torsion_exact(x, y, FN, profile, sample, tip_m, names, centre, amp, friction,
                   start) -> FitResult:
    """Any tip other than a single power law (walls included): the virgin curve at unit
    friction from the library's exact torsion, scaled by ``L = μ m(G_t φ/μ)``; the slope from
    the stick radius."""
    from ..contact import Contact
    from ..physics.torsion_exact import sliding_torque
    contact = Contact(profile, (tip_m, sample), friction=1.0)
    E_star, Gt0 = contact.moduli.normal, contact.moduli.torsional
    st = contact.normal(force=FN)
    d, a = float(st.depth), float(st.radius)
    G_of = _torsion_G_of(tip_m)
    load = _exact_virgin(contact, d, Gt0)
    fixed = {"friction": float(friction or 0.0), "shear_modulus": float(sample.G)}
    if "friction" not in names and friction is None:
        raise ParameterError("friction is fixed (not in free): give friction=... .")
    M_unit = float(sliding_torque(profile, E_star, 1.0, np.array([a]), np.array([d]),
                                  contact.rtol)[0])
    st0 = _starts(y, x, centre, amp, FN, 16.0 / 3.0 * a ** 3, names, start, sample, G_of,
                  M_unit)
    st0.update({k: fixed[k] for k in _LOOP_NAMES if k not in names})
    q, model, r, cov, stderr, dof, nfev = _fit_loop(x, y, names, centre, amp, load, G_of,
                                                      st0, fixed)
    Gt = G_of(q["shear_modulus"])[0]
    fin = contact.torsion(depth=d, twist=Gt / (q["friction"] * Gt0) * np.array([amp]),
                          method="exact")
    err = float(np.max(np.atleast_1d(np.asarray(fin.error_estimate, float))))
    meta = {"citations": ("PH", "J95"), "x_name": "twist", "y_name": "torque",
            "tip_model_errors": {"torque": err},
            "model_error_basis": "estimated error of the exact torsion at the loop's amplitude",
            "route": "exact"}
    return _torsion_result(x, y, profile, sample, tip_m, names, q, model, r, cov, stderr, dof,
                           nfev, G_of, meta)
