"""Subsurface stresses at a snapshot of a load path (:meth:`PathResult.stress`): the driver
behind ``contact.simulate(...).stress``.

The normal part is exact: the field of the step's normal state (its indentation depth, kept in
the snapshot). The torsional part comes from the step's own surface traction ``τ(ρ)`` (the
snapshot's ``shear_torsion``, at its points ``r`` or ``x``): any axisymmetric torsional traction
is a superposition of twisted flat punches (Jäger 1995),
``τ(ρ) = (4G/π) ∫_ρ^a g(x) ρ / sqrt(x² - ρ²) dx``, whose density follows by Abel's inversion,
``g(x) = -Ψ'(x)``, ``Ψ(x) = (1/(2G)) ∫_x^a τ(ρ) / sqrt(ρ² - x²) dρ``
(in closed form for the piecewise-linear traction). The field is then the
1D superposition of Reissner–Sagoci fields (:func:`contactlab.physics.stress.twist_kernel`).
The traction between the snapshot's points is linear, so the field is as exact as the route's
traction; the estimate adds the change from halving the density grid.
"""
from __future__ import annotations

from typing import Any

import numpy as np

from ..errors import EffectNotPlannedError, NotSupportedError
from ..physics import stress as _st
from .stress import StressField, _points, body_poisson_ratio, normal_stress
from .stress_history import _part, _quiet, _step

__all__ = ["path_stress", "twist_of_traction"]

#: radii of the grid of the twist profile (the Abel integral of the traction), interpolated
#: linearly by the superposition; the estimate adds the change on half as many
TWIST_POINTS = 4000


def _abel(rho: np.ndarray, tau: np.ndarray, xs: np.ndarray) -> np.ndarray:
    """``∫_x^a τ(ρ)/sqrt(ρ² - x²) dρ`` at ``xs``, exact for ``τ`` linear between the samples
    ``(rho, tau)`` (increasing, from 0 to ``a``): on each piece ``τ = α + βρ`` integrates to
    ``α ln(ρ + sqrt(ρ² - x²)) + β sqrt(ρ² - x²)``."""
    lo, hi = rho[:-1], rho[1:]
    beta = np.diff(tau) / np.diff(rho)
    alpha = tau[:-1] - beta * lo
    x = xs[:, None]
    L0, L1 = np.maximum(lo, x), np.maximum(hi, x)
    S0, S1 = np.sqrt(L0 * L0 - x * x), np.sqrt(L1 * L1 - x * x)
    with np.errstate(divide="ignore", invalid="ignore"):
        log = np.where(L1 > L0, np.log((L1 + S1) / (L0 + S0)), 0.0)
    log = np.where(np.isfinite(log), log, 0.0)   # the piece at the axis: α = τ(0) = 0
    return np.sum(alpha * log + beta * (S1 - S0), axis=1)


def twist_of_traction(rho: Any, tau: Any, a: float, G: float, x: Any) -> np.ndarray:
    """``Φ(x) = -(1/(2G)) ∫_x^a τ(ρ)/sqrt(ρ² - x²) dρ`` (rad) at the radii ``x`` (m): the
    twist profile whose increments are the density of the twisted flat punches carrying the
    traction ``tau`` (Pa, linear between the radii ``rho``, m) inside a contact of radius ``a``
    on a half-space of torsional modulus ``G`` (Pa):
    ``τ(ρ) = (4G/π) ∫_ρ^a Φ'(x) ρ/sqrt(x² - ρ²) dx``."""
    rho, tau = np.asarray(rho, float), np.asarray(tau, float)
    keep = rho < a
    rho, tau = np.concatenate([rho[keep], [a]]), np.concatenate([tau[keep], [0.0]])
    if rho[0] > 0:
        rho, tau = np.concatenate([[0.0], rho]), np.concatenate([[0.0], tau])
    x = np.clip(np.asarray(x, float), 0.0, a)
    return -(0.5 / G) * _abel(rho, tau, x.ravel()).reshape(x.shape)


def _grid(a: float, c: float, n: int) -> np.ndarray:
    """``n`` uniform radii on ``[0, a]`` plus clusters at the stick radius ``c`` and the edge,
    where the twist profile has square-root kinks."""
    near = a * np.geomspace(1e-9, 1e-2, n // 40)
    pts = [np.linspace(0.0, a, n), a - near]
    if 0.0 < c < a:
        pts += [c - near, c + near]
    xs = np.unique(np.clip(np.concatenate(pts), 0.0, a))
    return xs


def path_stress(result: Any, r: Any, z: Any, *, step: Any, body: Any = 1,
                part: str = "total") -> StressField:
    """Implementation of :meth:`PathResult.stress` (see there)."""
    _part(part)
    contact = result.__dict__.get("_contact")
    if contact is None:
        raise NotSupportedError("stress() needs the result of contact.simulate(...) itself "
                                "(this one carries no contact, e.g. a partial result).")
    nu = body_poisson_ratio(contact, body)
    r, z = _points(r, z)
    k = _step(step, len(result))
    if k not in result.snapshots:
        raise EffectNotPlannedError(f"step {k} has no snapshot: add it to simulate(..., "
                                    f"snapshots=[...]) (stored: {sorted(result.snapshots)}).")
    snap = result.snapshots[k]
    if snap.get("shear_tangential") is not None:
        raise NotSupportedError("stress() of a path with a tangential shift is not "
                                "implemented (only the normal force and the twist may vary); "
                                "use ShiftHistory.stress or FrettingLoop.stress at a constant "
                                "normal force.")
    if contact.friction is None and snap.get("shear_torsion") is not None:
        raise NotSupportedError("stress() of a no-slip twisted path is not implemented: its "
                                "traction is singular at the contact edge, which the snapshot's "
                                "samples do not resolve; use TorsionState.stress per step.")
    a, d = float(snap["radius"]), float(snap["depth"])
    shape = r.shape
    if a > 0:
        base = normal_stress(_quiet(contact.normal, depth=d), r, z, body)
        comps = (base.srr, base.stt, base.szz, base.srz)
        err = np.array(base.error, float)
        route = base.meta["route"]
    else:
        comps = (np.zeros(shape),) * 4
        err = np.zeros(shape)
        route = "normal: none"
    if part != "total":
        comps, err = (np.zeros(shape),) * 4, np.zeros(shape)
    stz, srt = np.zeros(shape), np.zeros(shape)
    tau = snap.get("shear_torsion")
    if tau is not None and a > 0 and np.any(tau != 0):
        pts = np.asarray(snap["r"] if "r" in snap else snap["x"], float)
        G = float(contact.moduli.torsional)
        stick = result.data.get("stick_radius")
        c = float(stick[k]) if stick is not None else 0.0
        R, Z = r.ravel(), z.ravel()
        sign = 1.0 if body == 1 else -1.0

        def field(n: int) -> tuple[tuple[np.ndarray, ...], np.ndarray]:
            xs = _grid(a, c, n)
            slope = np.diff(twist_of_traction(pts, tau, a, G, xs)) / np.diff(xs)

            def dens(x: np.ndarray) -> np.ndarray:
                i = np.clip(np.searchsorted(xs, x) - 1, 0, slope.size - 1)
                return np.where((x > 0) & (x < a), slope[i], 0.0)

            return _st.superposed_field(R, Z, np.full(R.shape, a), np.zeros(R.shape), dens,
                                        0.0, nu, (c,) if 0 < c < a else (), None, None,
                                        _st.twist_kernel, 4.0 * G / np.pi)

        (tz, rt), e = field(TWIST_POINTS)
        (tzh, rth), _ = field(TWIST_POINTS // 2)
        e = e + np.maximum(np.abs(tz - tzh), np.abs(rt - rth))
        stz, srt = sign * tz.reshape(shape), sign * rt.reshape(shape)
        err = err + np.asarray(e).reshape(shape)
        route = f"{route} + torsion: twisted punches of the step's traction (Abel inversion)"
    mags = np.abs(np.stack([*comps, stz, srt]))
    fin = np.all(np.isfinite(mags), axis=0)
    top = np.max(mags[:, fin], initial=0.0)
    rel = float(np.max(err[fin], initial=0.0) / top) if top > 0 else 0.0
    return StressField(r, z, *comps, stz, srt, np.where(fin, err, np.inf),
                       {"route": route, "body": body, "nu": nu, "part": part, "step": k,
                        "error_estimate": rel, "citations": ("Sn65", "J85", "RS44")})
