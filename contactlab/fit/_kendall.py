"""Adhesive flat punch (Kendall 1971): the fit of a retraction curve with its pull-off.

A flat punch of radius ``b`` keeps the contact radius ``b`` while attached, so the force is
linear in the indentation, ``F = 2E* b δ + F0``, down to the detachment at
``δ_c = -sqrt(2π b Δγ/E*)`` (pull-off force ``-sqrt(8π b³ E* Δγ)``), and ``F0`` after. The
work of adhesion enters only through the detachment point: the least-squares residual does not
change with ``Δγ`` as long as no sample changes sides, so its Jacobian column is zero almost
everywhere and a least-squares fit of ``Δγ`` is ill-posed. The fit therefore separates the two:

1. ``E*``, the contact point ``z0`` and the offset ``F0`` by linear least squares on the
   model ``F = 2E* b (z - z0) [z >= z_last] + F0`` (attached samples: those at or beyond
   ``z_last``, the first sample in depth below half the smallest force, i.e. the last one
   before the jump; the model is linear in ``E*``, ``E* z0`` and ``F0``), with the usual
   covariance ``s² (JᵀJ)⁻¹`` of the exact Jacobian ``∂F/∂E* = 2b (z - z0)``, ``∂F/∂z0 = -2E* b`` (attached),
   ``∂F/∂F0 = 1``;
2. ``Δγ = E* δ_last²/(2π b)`` in closed form from the last attached sample's indentation
   ``δ_last = z_last - z0``: the detachment lies between that sample and the next one out
   (``δ_next``), so ``Δγ`` is bracketed by ``E* δ_last²/(2πb) <= Δγ < E* δ_next²/(2πb)``; the
   reported value is the lower end (the measured pull-off), its variance the propagation of the
   covariance of ``(E, z0)`` through the closed form plus the bracket's width² / 12 (the
   detachment uniform over the sampling interval).
"""
from __future__ import annotations


import numpy as np

from ..errors import ParameterError
from ._tip import covariance

__all__ = ["fit_kendall"]


def fit_kendall(z: np.ndarray, F: np.ndarray, b: float, names: tuple[str, ...], E_tmpl: float,
                k_nu: float, c_tip: float, w_fixed: float | None, start: dict
                ) -> tuple[dict, dict, np.ndarray, np.ndarray, int, dict]:
    """Fit a flat punch's retraction curve with pull-off (Kendall); see the module docstring.

    Returns ``(vals, stderr, covariance, model, dof, extra)`` with ``vals`` the parameters by
    name (E Pa, contact_point m, force_offset N, work_of_adhesion J/m²) and ``extra`` the
    pull-off data for ``meta``."""
    order = np.argsort(z, kind="stable")
    zs, Fs = z[order], F[order]
    fit_e, fit_cp = "E" in names, "contact_point" in names
    fit_off, fit_w = "force_offset" in names, "work_of_adhesion" in names

    def estar(E: float) -> float:
        return 1.0 / (k_nu / E + c_tip)

    off_fixed = float(start.get("force_offset", 0.0))
    n_base = max(2, zs.size // 10)
    base = float(np.median(Fs[:n_base])) if fit_off else off_fixed
    # the last attached sample: the first one (in depth) beyond the jump, i.e. below half the
    # smallest force (near the end the attached force changes by less than the noise from
    # sample to sample, so the smallest force itself may lie a few samples deeper)
    rise = Fs - base
    i_last = int(np.argmax(rise < 0.5 * float(np.min(rise))))
    if not (rise[i_last] < 0 and 0 < i_last):
        raise ParameterError(
            "adhesion='jkr' with a flat punch: the curve has no pull-off (no force below the "
            "baseline followed by a jump back to it at smaller depth); Kendall's work of "
            "adhesion needs the detachment. Give a retraction curve through the pull-off.")
    att = np.arange(zs.size) >= i_last
    n_att = int(att.sum())
    Es_fixed = estar(float(start.get("E", E_tmpl)))
    cp_fixed = float(start.get("contact_point", 0.0))
    # ---- linear least squares in (E*, E* z0, F0) (the free ones)
    cols, rhs = [], Fs.copy()
    one = att.astype(float)
    if fit_e and fit_cp:
        cols += [2.0 * b * zs * one, -2.0 * b * one]
    elif fit_e:
        cols.append(2.0 * b * (zs - cp_fixed) * one)
    elif fit_cp:
        rhs = rhs - 2.0 * b * Es_fixed * zs * one
        cols.append(-2.0 * b * Es_fixed * one)
    else:
        rhs = rhs - 2.0 * b * Es_fixed * (zs - cp_fixed) * one
    if fit_off:
        cols.append(np.ones_like(zs))
    else:
        rhs = rhs - off_fixed
    if n_att < 2 + int(fit_e and fit_cp) or (fit_off and n_att == zs.size):
        raise ParameterError(
            f"adhesion='jkr' with a flat punch: {n_att} attached samples and "
            f"{zs.size - n_att} detached: the fit needs at least three attached ones and, with "
            "a free force offset, detached ones after the pull-off.")
    A = np.stack(cols, axis=1) if cols else np.zeros((zs.size, 0))
    norms = np.sqrt(np.einsum("ij,ij->j", A, A))
    coef = np.linalg.lstsq(A / norms, rhs, rcond=None)[0] / norms if cols else np.zeros(0)
    it = iter(coef.tolist())
    if fit_e and fit_cp:
        Es = next(it)
        cp = next(it) / Es
    elif fit_e:
        Es, cp = next(it), cp_fixed
    elif fit_cp:
        Es, cp = Es_fixed, next(it)
    else:
        Es, cp = Es_fixed, cp_fixed
    off = next(it) if fit_off else off_fixed
    if not Es > 0:
        raise ParameterError(f"adhesion='jkr' with a flat punch: the attached part's slope "
                             f"gives E* = {Es!r} Pa; check the sign of force and depth.")
    inv = 1.0 / Es - c_tip
    if not inv > 0:
        raise ParameterError(f"adhesion='jkr' with a flat punch: E* = {Es!r} Pa is stiffer "
                             "than the tip's own compliance allows.")
    E = k_nu / inv
    model = 2.0 * b * Es * (zs - cp) * one + off
    r = model - Fs
    # ---- covariance of the least-squares parameters (exact Jacobian in E, z0, F0)
    ls = [n for n in ("E", "contact_point", "force_offset") if n in names]
    J = np.empty((zs.size, len(ls)))
    for i, n in enumerate(ls):
        if n == "E":                    # ∂E*/∂E = E*² (1 - ν²)/E²
            J[:, i] = 2.0 * b * (zs - cp) * one * (Es * Es * k_nu / (E * E))
        elif n == "contact_point":
            J[:, i] = -2.0 * b * Es * one
        else:
            J[:, i] = 1.0
    p = len(ls) + int(fit_w)
    dof = zs.size - p
    s2 = float(r @ r) / max(dof, 1)
    C = covariance(J, s2) if ls else np.zeros((0, 0))
    # ---- the work of adhesion from the pull-off, in closed form
    d_last = float(zs[i_last]) - cp
    d_next = float(zs[i_last - 1]) - cp
    extra = {"pull_off_force": float(Fs[i_last] - off), "pull_off_indentation": d_last,
             "detachment_bracket": (d_next, d_last)}
    if fit_w:
        if not d_last < 0:
            raise ParameterError(
                f"adhesion='jkr' with a flat punch: the last attached sample lies at indentation "
                f"{d_last!r} m >= 0; a pull-off happens at negative indentation.")
        w = Es * d_last * d_last / (2.0 * np.pi * b)
        w_hi = Es * d_next * d_next / (2.0 * np.pi * b)
        # ∂Δγ/∂E = δ²/(2πb) ∂E*/∂E, ∂Δγ/∂z0 = -E* δ/(πb)
        g = np.array([d_last * d_last / (2.0 * np.pi * b) * Es * Es * k_nu / (E * E)
                      if n == "E" else (-Es * d_last / (np.pi * b) if n == "contact_point"
                                        else 0.0) for n in ls])
        var_w = float(g @ C @ g) + (w_hi - w) ** 2 / 12.0 if ls else (w_hi - w) ** 2 / 12.0
        cov = np.empty((p, p))
        cov[:-1, :-1] = C
        cov[:-1, -1] = cov[-1, :-1] = C @ g if ls else 0.0
        cov[-1, -1] = var_w
        extra["work_of_adhesion_bracket"] = (w, w_hi)
        names_cov = (*ls, "work_of_adhesion")
    else:
        w = float(w_fixed) if w_fixed is not None else 0.0
        cov, names_cov = C, tuple(ls)
    vals = {"E": E, "contact_point": cp, "force_offset": off, "work_of_adhesion": w}
    # the covariance in the order of names
    idx = [names_cov.index(n) for n in names]
    cov = cov[np.ix_(idx, idx)]
    stderr = {n: float(np.sqrt(cov[i, i])) for i, n in enumerate(names)}
    back = np.empty_like(model)
    back[order] = model
    return vals, stderr, cov, back, dof, extra

