"""Fit of a viscoelastic approach-retract curve (Lee-Radok and Ting through the MDR).

``fit.indentation(depth, force, profile, time=t, sample=<viscoelastic template>)`` lands here.
The model and its exact derivatives are :class:`contactlab.fit._ting.TingModel`; this module
maps the sample's constructor arguments to its Prony form ``(G_∞, G_k, τ_k)`` and back, finds
starting values and runs the solver.
"""
from __future__ import annotations

import warnings

from typing import Any

import numpy as np

from ..errors import (ConvergenceError, NotSupportedError, ParameterError, UnknownNameError,
                      ValidityWarning)
from ..materials import Elastic, Rigid
from ..materials.base import Material
from ..materials.viscoelastic import GeneralizedMaxwell, Maxwell, StandardLinearSolid
from ..profiles.base import Profile
from ._args import free_names, start_values, warn_undetermined
from .result import FitResult

__all__ = ["VISCOELASTIC_MATERIALS", "fit_viscoelastic"]

#: the viscoelastic materials a fit covers (a Kelvin-Voigt dashpot has no Prony arm)
VISCOELASTIC_MATERIALS = (StandardLinearSolid, Maxwell, GeneralizedMaxwell)
_EXTRA = ("contact_point", "force_offset")


def _names(sample: Material) -> tuple[str, ...]:
    """The scalar parameter names of a material (``moduli[k]`` for sequences)."""
    out: list[str] = []
    for p in type(sample).params:
        val = getattr(sample, p.name)
        if isinstance(val, tuple):
            out += [f"{p.name}[{k}]" for k in range(len(val))]
        else:
            out.append(p.name)
    return tuple(out)


def _values(sample: Material) -> dict[str, float]:
    out: dict[str, float] = {}
    for p in type(sample).params:
        val = getattr(sample, p.name)
        if isinstance(val, tuple):
            out.update({f"{p.name}[{k}]": float(v) for k, v in enumerate(val)})
        else:
            out[p.name] = float(val)
    return out


def _prony(cls: type, v: dict[str, float]) -> tuple[float, np.ndarray, np.ndarray]:
    if cls is StandardLinearSolid:
        return v["G_inf"], np.array([v["G_1"]]), np.array([v["eta_1"] / v["G_1"]])
    if cls is Maxwell:
        return 0.0, np.array([v["G"]]), np.array([v["eta"] / v["G"]])
    K = sum(1 for n in v if n.startswith("moduli["))
    return (v["G_inf"], np.array([v[f"moduli[{k}]"] for k in range(K)]),
            np.array([v[f"relaxation_times[{k}]"] for k in range(K)]))


def _chain(cls: type, v: dict[str, float], dGi: np.ndarray, dGk: np.ndarray, dtk: np.ndarray
           ) -> dict[str, np.ndarray]:
    """Derivatives by the material's own parameters from those by ``(G_∞, G_k, τ_k)``
    (``τ = η/G`` for the standard linear solid and Maxwell)."""
    if cls is StandardLinearSolid:
        tau = v["eta_1"] / v["G_1"]
        return {"G_inf": dGi, "G_1": dGk[0] - dtk[0] * tau / v["G_1"],
                "eta_1": dtk[0] / v["G_1"]}
    if cls is Maxwell:
        tau = v["eta"] / v["G"]
        return {"G": dGk[0] - dtk[0] * tau / v["G"], "eta": dtk[0] / v["G"]}
    out = {"G_inf": dGi}
    for k in range(dGk.shape[0]):
        out[f"moduli[{k}]"] = dGk[k]
        out[f"relaxation_times[{k}]"] = dtk[k]
    return out


def _material(cls: type, v: dict[str, float]) -> Material:
    if cls is StandardLinearSolid:
        return StandardLinearSolid(v["G_inf"], v["G_1"], v["eta_1"])
    if cls is Maxwell:
        return Maxwell(v["G"], v["eta"])
    K = sum(1 for n in v if n.startswith("moduli["))
    return GeneralizedMaxwell(v["G_inf"], [v[f"moduli[{k}]"] for k in range(K)],
                              [v[f"relaxation_times[{k}]"] for k in range(K)])


def _free(free: Any, sample: Material, adhesive: bool = False) -> tuple[str, ...]:
    if free is None:                            # every parameter of the material and z0
        free = (*tuple(p.name for p in type(sample).params), "contact_point")
    names = free_names(free)
    scalars = _names(sample)
    extra = _EXTRA + (("work_of_adhesion",) if adhesive else ())
    allowed = tuple(p.name for p in type(sample).params) + extra
    out: list[str] = []
    for n in names:
        if n in scalars or n in extra:
            out.append(n)
        elif n in allowed:                      # a sequence: every entry
            out += [s for s in scalars if s.startswith(n + "[")]
        else:
            raise UnknownNameError(f"free={n!r} is unknown for {type(sample).__name__}: choose "
                                   f"from {allowed + tuple(s for s in scalars if '[' in s)}.")
    if len(set(out)) != len(out):
        raise ParameterError(f"free={names!r} names a parameter twice.")
    if not out:
        raise ParameterError("free=() is invalid: name at least one parameter to fit.")
    return tuple(out)


#: samples of the first pass of a long curve (a subsample)
_SUBSAMPLE = 256
#: factors on the template's relaxation times tried for the start (approach, projected)
_TAU_FACTORS = np.geomspace(1.0 / 30.0, 30.0, 9)


def _project_start(cls: type, st: dict, app: Any, F: np.ndarray, cp0: float,
                   offset: bool) -> None:
    """Starting moduli and relaxation times: on the approach the force is linear in the moduli
    at fixed relaxation times and contact point (``4G_∞Φ + Σ 4G_k H_k``), so for each factor
    on the template's times the moduli (and the offset) are solved by linear least squares and
    the best positive solution is kept."""
    _, Gk0, tk0 = _prony(cls, st)
    K = Gk0.size
    best: tuple[float, np.ndarray, np.ndarray] | None = None
    # the hereditary integral of each relaxation time is computed on its own, so every factor's
    # times go through the model at once (as one longer Prony series)
    taus = np.concatenate([tk0 * c for c in _TAU_FACTORS])
    _, dGi, dGk_all, _, _ = app(1.0, np.ones(taus.size), taus, cp0)
    for i, c in enumerate(_TAU_FACTORS):
        dGk = dGk_all[i * K:(i + 1) * K]
        cols = ([] if cls is Maxwell else [dGi]) + list(dGk)
        if offset:
            cols.append(np.ones_like(F))
        A = np.stack(cols, axis=1)
        coef, *_ = np.linalg.lstsq(A, F, rcond=None)
        mod = coef[:A.shape[1] - int(offset)]
        if not np.all(mod > 0):
            continue
        rss = float(np.sum((A @ coef - F) ** 2))
        if best is None or rss < best[0]:
            best = (rss, mod, tk0 * c)
    if best is None:
        return
    _, mod, tk = best
    if cls is Maxwell:
        st.update(G=float(mod[0]), eta=float(mod[0] * tk[0]))
    elif cls is StandardLinearSolid:
        st.update(G_inf=float(mod[0]), G_1=float(mod[1]), eta_1=float(mod[1] * tk[0]))
    else:
        st["G_inf"] = float(mod[0])
        for k in range(K):
            st[f"moduli[{k}]"] = float(mod[1 + k])
            st[f"relaxation_times[{k}]"] = float(tk[k])


def fit_viscoelastic(z: np.ndarray, F: np.ndarray, time: Any, profile: Profile,
                     sample: Material, tip: Material | None, free: Any,
                     start: dict | None, rtol: float, adhesion: str | None = None,
                     work_of_adhesion: float | None = None,
                     equilibrium_distance: float | None = None) -> FitResult:
    """The viscoelastic branch of :func:`contactlab.fit.indentation` (checked ``z``, ``F``).

    ``adhesion="dmt"``: the force less ``2πΔγ ρ(a(t))`` in contact, with Ting's contact radius
    ``a(t)`` (:mod:`contactlab.fit._dmt`); the derivatives through the contact radius's own
    (``TingModel.contact``). The Tabor parameter is reported at the instantaneous modulus
    ``E* = 4(G_∞ + Σ G_k)`` (``meta["tabor_parameter"]``, warns above 0.1; without
    ``equilibrium_distance`` at 0.3 nm, warning only when it is above 0.1 over 0.2-0.5 nm) and,
    with ``equilibrium_distance``, at the relaxed one ``4G_∞``
    (``meta["tabor_parameter_relaxed"]``)."""
    from ._args import data_array
    from .indentation import START_UNITS, _check_work, indentation
    if not isinstance(sample, VISCOELASTIC_MATERIALS):
        raise NotSupportedError(
            f"sample={sample!r} with time=...: viscoelastic fits cover "
            f"{', '.join(c.__name__ for c in VISCOELASTIC_MATERIALS)} (a Kelvin-Voigt dashpot "
            "has no relaxation arm for Ting's rule); give one of these.")
    if tip is not None and not isinstance(tip, Rigid):
        raise NotSupportedError(f"tip={tip!r} with a viscoelastic sample: the theory covers a "
                                "rigid tip on an incompressible half-space; give tip=None.")
    t = data_array("time", time)
    if t.size != z.size:
        raise ParameterError(f"time has {t.size} points and depth has {z.size}: give curves "
                             "of equal length.")
    cls = type(sample)
    names = _free(free, sample, adhesion == "dmt")
    # moduli, viscosities, times and Δγ are fitted through their logarithms: positive
    start = start_values(start, names, tuple(n for n in names if n not in _EXTRA),
                         START_UNITS)
    if adhesion == "dmt":
        _check_work(names, work_of_adhesion, adhesion)
        from ._dmt import check_wall
        check_wall(profile)
    # a flat punch (contact radius b from the first touch): Φ = 2bδ, Ting's t1 then gives the
    # constant-radius hereditary integral up to the force's zero (see _ting)
    punch = profile.is_flat_punch
    if np.isfinite(profile.wall_radius) and not punch:
        raise NotSupportedError(
            f"profile={profile!r} with time=...: a profile rising up to a punch wall is not "
            "covered by the viscoelastic fits (its contact radius stalls at the wall and moves "
            "again on the retract); give a flat punch or a profile without a wall.")
    if z.size <= len(names):
        raise ParameterError(f"depth has {z.size} points: a fit of {len(names)} parameters "
                             f"needs more than {len(names)}.")
    fixed = _values(sample)
    fixed.update({"contact_point": 0.0, "force_offset": 0.0,
                  "work_of_adhesion": float(work_of_adhesion or 0.0)})
    extra = _EXTRA + (("work_of_adhesion",) if adhesion == "dmt" else ())
    fit_cp = "contact_point" in names
    im = int(z.size - 1 - np.argmax(z[::-1]))
    # ---- starting values: an elastic fit of the approach gives the contact point and the
    # apparent modulus E* = 4G; the template's moduli are scaled to it at the approach's time
    st = dict(start or {})
    app = slice(0, im + 1)
    el_free = ("E", *tuple(n for n in extra if n in names))
    try:
        # (a start only: its validity notes, e.g. the Tabor parameter at a unit modulus, are
        # not the fit's; the fit reports its own below)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", ValidityWarning)
            el = indentation(z[app], F[app], profile, sample=Elastic(E=1.0, nu=0.5),
                             free=el_free, rtol=rtol, adhesion=adhesion,
                             work_of_adhesion=work_of_adhesion,
                             start={k: st[k] for k in extra if k in st})
    except ConvergenceError as err:
        raise ConvergenceError(f"fit.indentation (viscoelastic): the elastic fit of the "
                               f"approach, which gives the starting values, failed: {err}") \
            from err
    for n in extra:
        if n in names and n not in st:
            st[n] = el.params[n]
    cp0 = float(st.get("contact_point", fixed["contact_point"]))
    G_app = el.params["E"] / 3.0
    in_c = z[app] > cp0
    t_eff = 0.5 * float(t[im] - t[app][in_c][0]) if np.any(in_c) else 0.0
    G_inf, Gk, tk = _prony(cls, fixed)
    scale = G_app / (G_inf + float(np.sum(Gk * np.exp(-t_eff / tk))))
    for n in names:
        if n not in st and n not in extra:
            st[n] = fixed[n] * (scale if (n.startswith(("G", "moduli")) or n == "eta_1"
                                          or n == "eta") else 1.0)
    # ---- the model over the depths the contact point allows
    span = float(np.max(z) - np.min(z))
    from ._tip import ROUNDING, TipModel, covariance, levenberg_marquardt
    d_max = (float(np.max(z)) - (float(np.min(z)) - span if fit_cp else cp0)) * 1.0001
    if np.isfinite(profile.max_radius) and not punch:
        reach = float(profile._g(np.array([profile.max_radius * (1.0 - 1e-6)]), rtol)[0])
        d_max = min(d_max, reach)
    from ._ting import TingModel
    tipm = TipModel(profile, d_max, rtol, allow_wall=punch)
    model = TingModel(t, z, tipm)
    dmt = None
    if adhesion == "dmt":
        from ._dmt import DMTModel
        dmt = DMTModel(profile, tipm)
    own = _names(sample)
    if all(n in names and n not in (start or {}) for n in own) and im > 0:
        F_app = F[app]
        if dmt is not None:             # the approach without the adhesive force
            F_app = F_app + 2.0 * np.pi * float(st.get("work_of_adhesion", fixed[
                "work_of_adhesion"])) * dmt(z[app] - cp0)[0]
        _project_start(cls, st, TingModel(t[app], z[app], tipm), F_app, cp0,
                       "force_offset" in names)
    top = float(np.max(np.abs(F))) or 1.0
    scales = {n: (max(span, 1e-300) if n == "contact_point" else top if n == "force_offset"
                  else float(st[n])) for n in names}
    logs = tuple(n for n in names if n not in _EXTRA)   # moduli, viscosities, times, Δγ > 0
    idx = {n: i for i, n in enumerate(names)}

    def unpack(x: np.ndarray) -> dict[str, float]:
        v = dict(fixed)
        for n, i in idx.items():
            v[n] = (float(np.exp(x[i])) if n in logs else float(x[i])) * scales[n]
        return v

    cache: dict = {}

    def evaluate(x: np.ndarray) -> tuple:
        key = x.tobytes()
        if key not in cache:
            cache.clear()
            v = unpack(x)
            gone = [n for n in logs if not 0.0 < v[n] < np.inf]
            if gone:                    # a log-parameter under- or overflowed: the data do
                raise ConvergenceError(   # not determine it (a model far from the curve)
                    f"fit.indentation (viscoelastic) did not converge: {gone[0]} went to "
                    f"{v[gone[0]]!r} (the curve does not determine it with this tip and "
                    "material; check the profile, the template and the time axis).")
            Gi, Gk_, tk_ = _prony(cls, v)
            f, dGi, dGk, dtk, dz0 = model(Gi, Gk_, tk_, v["contact_point"])
            if dmt is not None:         # - 2πΔγ ρ(a(t)), through δ(t1) on the retract
                c_d, c_Gi, c_Gk, c_tk = model.contact
                rho, rho_d = dmt(c_d)
                w2 = 2.0 * np.pi * v["work_of_adhesion"]
                f = f - w2 * rho
                dGi = dGi - w2 * rho_d * c_Gi
                dGk = dGk - w2 * rho_d * c_Gk
                dtk = dtk - w2 * rho_d * c_tk
                dz0 = dz0 + w2 * rho_d * (c_d > 0)
            d = _chain(cls, v, dGi, dGk, dtk)
            d["contact_point"] = dz0
            if dmt is not None:
                d["work_of_adhesion"] = -2.0 * np.pi * rho
            cache[key] = (v, f, d)
        return cache[key]

    def residual(x: np.ndarray) -> np.ndarray:
        v, f, _ = evaluate(x)
        return f + v["force_offset"] - F

    def jacobian(x: np.ndarray) -> np.ndarray:
        v, _, d = evaluate(x)
        J = np.empty((z.size, len(idx)))
        for n, i in idx.items():
            if n == "force_offset":
                J[:, i] = scales[n]
            elif n in logs:                     # ∂F/∂ln p = p ∂F/∂p
                J[:, i] = d[n] * v[n]
            else:
                J[:, i] = d[n] * scales[n]
        return J

    x0 = np.array([np.log(st[n] / scales[n]) if n in logs else st[n] / scales[n]
                   for n in names])
    model_all, z_all, F_all = model, z, F
    if dmt is not None and dmt.rho0 > 0 and im > len(names):
        # the adhesive force jumps where the contact starts and ends; the end on the retract
        # moves with the moduli, and from a rough start a jump on the wrong side of a sample
        # sends the solver astray: a first pass on the approach and the retract up to its
        # first sample below half the jump 2πΔγρ0 (the end's neighbourhood and the samples
        # apart left out), then the whole curve
        jump = 2.0 * np.pi * dmt.rho0 * float(st.get("work_of_adhesion",
                                                     fixed["work_of_adhesion"]))
        low = np.flatnonzero(F[im + 1:] - float(st.get("force_offset", 0.0)) < -0.5 * jump)
        n_keep = im + 1 + (int(low[0]) if low.size else z.size - im - 1)
        keep = np.arange(n_keep)
        model, z, F = TingModel(t[keep], z_all[keep], tipm), z_all[keep], F_all[keep]
        x_app, _, ok, _ = levenberg_marquardt(residual, jacobian, x0,
                                              floor=(ROUNDING ** 2) * float(F @ F))
        cache.clear()
        model, z, F = model_all, z_all, F_all
        if ok:
            x0 = x_app
    sub = z.size // _SUBSAMPLE
    if sub > 1:
        # a first pass on every sub-th sample (the turning point kept): most of the walk from
        # the start costs a fraction of a full evaluation; the full curve follows from there
        keep = np.union1d(np.arange(0, z.size, sub), [model.im, z.size - 1])
        model, z, F = TingModel(t[keep], z_all[keep], tipm), z_all[keep], F_all[keep]
        x_sub, _, ok, _ = levenberg_marquardt(residual, jacobian, x0,
                                              floor=(ROUNDING ** 2) * float(F @ F))
        cache.clear()
        model, z, F = model_all, z_all, F_all
        if ok:
            x0 = x_sub
    x_sol, nfev, ok, msg = levenberg_marquardt(residual, jacobian, x0,
                                                floor=(ROUNDING ** 2) * float(F @ F))
    if not ok:
        raise ConvergenceError(f"fit.indentation (viscoelastic) did not converge: {msg}")
    vals = unpack(x_sol)
    r = residual(x_sol)
    J = jacobian(x_sol) / np.array([vals[n] if n in logs else scales[n] for n in names])
    dof = z.size - len(names)
    cov = covariance(J, float(r @ r) / dof)
    stderr = {n: float(np.sqrt(cov[i, i])) for n, i in idx.items()}
    warn_undetermined(stderr)
    from ..contact import Contact
    contact = Contact(profile, (Rigid(), _material(cls, vals)))
    params = {n: vals[n] for n in _names(sample) + extra}
    meta: dict = {"citations": ("PH", "H3", "LR60", "T66") + (("DMT75",) if dmt else ()),
                  "x_name": "time", "y_name": "force",
                  "tip_route": model.tip.route, "depth": z, "largest_depth_index": im}
    if model.tip.route == "table":
        meta["tip_model_errors"] = {"force": model.tip.error}
    if dmt is not None:
        meta["dmt_route"] = dmt.route
        meta["effective_radius"] = float(dmt(np.array([float(np.max(z)) - vals[
            "contact_point"]]))[0][0])
        if dmt.route == "table":
            meta.setdefault("tip_model_errors", {})["dmt_radius"] = dmt.error
        from .indentation import report_tabor
        Gi, Gk_, _ = _prony(cls, vals)
        rho, w = meta["effective_radius"], vals["work_of_adhesion"]
        report_tabor(meta, w, 4.0 * (Gi + float(np.sum(Gk_))), equilibrium_distance, "dmt",
                     rho)
        z0 = meta.get("equilibrium_distance")
        if z0 is not None and meta["tabor_parameter"] is not None:
            meta["tabor_parameter_relaxed"] = (float((rho * w * w / ((4.0 * Gi) ** 2 * float(
                z0) ** 3)) ** (1.0 / 3.0)) if Gi > 0 else float("inf"))
    return FitResult(params=params, free=names, stderr=stderr, covariance=cov, x=t, y=F,
                     model=r + F, residuals=r, contact=contact, dof=dof, nfev=nfev, meta=meta)
