"""Subsurface stresses at a snapshot of a load path (:meth:`PathResult.stress`): the driver
behind ``contact.simulate(...).stress``.

The normal part is exact: the field of the step's normal state (its indentation depth, kept in
the snapshot). The frictional parts come from the step's own surface tractions (the snapshot's
``shear_torsion`` and ``shear_tangential`` at its points ``r`` or ``x``, linear between them):

- Twist: any axisymmetric torsional traction is a superposition of twisted flat punches (Jäger
  1995), ``τ(ρ) = (4G/π) ∫_ρ^a Φ'(x) ρ / sqrt(x² - ρ²) dx``, whose density follows by Abel's
  inversion, ``Φ(x) = -(1/(2G)) ∫_x^a τ(ρ) / sqrt(ρ² - x²) dρ`` (in closed form for the
  piecewise-linear traction); the field is the 1D superposition of Reissner–Sagoci fields
  (:func:`contactlab.physics.stress.twist_kernel`).
- Shift: any traction ``q(ρ)`` along ``+x`` of axisymmetric magnitude is a superposition of
  punch-type tractions, ``q(ρ) = -(2/π) ∫_ρ^a Ψ'(x) / sqrt(x² - ρ²) dx`` with
  ``Ψ(x) = ∫_x^a ρ q(ρ) / sqrt(ρ² - x²) dρ`` (half the MDR line load of ``q``; Abel's
  inversion, in closed form for the piecewise-linear traction); the field is the superposition
  of the fields of the punch-type tractions (:func:`contactlab.physics.stress_tangential.
  shear_kernel`), the Cattaneo–Mindlin kernel.

The field is as exact as the route's traction; the estimate adds the change from halving the
density grid. A path with both a shift and a twist superposes both parts (linear elasticity);
the two tractions are those the route computed (see docs/stress.md for the decoupling).
"""
from __future__ import annotations

from typing import Any

import numpy as np

from ..errors import EffectNotPlannedError, NotSupportedError, ParameterError
from ..physics import stress as _st
from ..physics import stress_tangential as _sh
from . import stress_path_noslip as _ns
from .stress import StressField, _points, body_poisson_ratio, normal_stress
from .stress_history import _part, _quiet, _step
from .stress_tangential import (TANGENTIAL_SOURCES, _angles, _wrap, _xyz,
                                to_cartesian)

__all__ = ["path_stress", "shift_of_traction", "twist_of_traction"]

#: radii of the grid of the twist and shift profiles (the Abel integrals of the tractions),
#: interpolated linearly by the superposition (the shift's slope, exact at the nodes, too);
#: the estimate adds the change on half as many
TWIST_POINTS = 4000
SHIFT_POINTS = 4000


def _pieces(rho: np.ndarray, q: np.ndarray, xs: np.ndarray):
    """Per piece ``[lo, hi]`` of the linear interpolant ``q = α + βρ`` and per radius ``x``:
    ``α, β`` and the clipped ends ``L0, L1`` with ``S = sqrt(L² - x²)``."""
    lo, hi = rho[:-1], rho[1:]
    beta = np.diff(q) / np.diff(rho)
    alpha = q[:-1] - beta * lo
    x = xs[:, None]
    L0, L1 = np.maximum(lo, x), np.maximum(hi, x)
    S0, S1 = np.sqrt(L0 * L0 - x * x), np.sqrt(L1 * L1 - x * x)
    with np.errstate(divide="ignore", invalid="ignore"):
        log = np.where(L1 > L0, np.log((L1 + S1) / (L0 + S0)), 0.0)
    return alpha, beta, x, L0, L1, S0, S1, log


def _abel(rho: np.ndarray, tau: np.ndarray, xs: np.ndarray) -> np.ndarray:
    """``∫_x^a τ(ρ)/sqrt(ρ² - x²) dρ`` at ``xs``, exact for ``τ`` linear between the samples
    ``(rho, tau)`` (increasing, from 0 to ``a``): on each piece ``τ = α + βρ`` integrates to
    ``α ln(ρ + sqrt(ρ² - x²)) + β sqrt(ρ² - x²)``."""
    alpha, beta, _, _, _, S0, S1, log = _pieces(rho, tau, xs)
    log = np.where(np.isfinite(log), log, 0.0)   # the piece at the axis: α = τ(0) = 0
    return np.sum(alpha * log + beta * (S1 - S0), axis=1)


def _abel_moment(rho: np.ndarray, q: np.ndarray, xs: np.ndarray) -> np.ndarray:
    """``∫_x^a ρ q(ρ)/sqrt(ρ² - x²) dρ`` at ``xs``, exact for ``q`` linear between the samples:
    on each piece ``q = α + βρ`` integrates to ``α S + β (ρ S + x² ln(ρ + S))/2``,
    ``S = sqrt(ρ² - x²)``."""
    alpha, beta, x, L0, L1, S0, S1, log = _pieces(rho, q, xs)
    log = np.where(x > 0, log, 0.0)              # x² ln(...) -> 0 on the axis
    return np.sum(alpha * (S1 - S0) + 0.5 * beta * (L1 * S1 - L0 * S0 + x * x * log), axis=1)


def _inside(rho: Any, q: Any, a: float, axis_value: str) -> tuple[np.ndarray, np.ndarray]:
    """The samples inside the contact, closed by ``q(a) = 0`` and a value on the axis (0 for a
    torsional traction, the first sample's for a shear traction)."""
    rho, q = np.asarray(rho, float), np.asarray(q, float)
    keep = rho < a
    rho, q = np.concatenate([rho[keep], [a]]), np.concatenate([q[keep], [0.0]])
    if rho[0] > 0:
        q0 = 0.0 if axis_value == "zero" else q[0]
        rho, q = np.concatenate([[0.0], rho]), np.concatenate([[q0], q])
    return rho, q


def twist_of_traction(rho: Any, tau: Any, a: float, G: float, x: Any) -> np.ndarray:
    """``Φ(x) = -(1/(2G)) ∫_x^a τ(ρ)/sqrt(ρ² - x²) dρ`` (rad) at the radii ``x`` (m): the
    twist profile whose increments are the density of the twisted flat punches carrying the
    traction ``tau`` (Pa, linear between the radii ``rho``, m) inside a contact of radius ``a``
    on a half-space of torsional modulus ``G`` (Pa):
    ``τ(ρ) = (4G/π) ∫_ρ^a Φ'(x) ρ/sqrt(x² - ρ²) dx``."""
    rho, tau = _inside(rho, tau, a, "zero")
    x = np.clip(np.asarray(x, float), 0.0, a)
    return -(0.5 / G) * _abel(rho, tau, x.ravel()).reshape(x.shape)


def shift_of_traction(rho: Any, q: Any, a: float, x: Any) -> np.ndarray:
    """``Ψ(x) = ∫_x^a ρ q(ρ)/sqrt(ρ² - x²) dρ`` (N/m) at the radii ``x`` (m): half the MDR line
    load of the shear traction ``q`` (Pa, along ``+x``, linear between the radii ``rho``, m,
    constant from the first one to the axis) inside a contact of radius ``a``. Its slope is the
    density of the punch-type tractions carrying ``q``:
    ``q(ρ) = -(2/π) ∫_ρ^a Ψ'(x)/sqrt(x² - ρ²) dx``, and ``Q = 4 ∫_0^a Ψ dx``."""
    rho, q = _inside(rho, q, a, "first")
    x = np.clip(np.asarray(x, float), 0.0, a)
    return _abel_moment(rho, q, x.ravel()).reshape(x.shape)


def shift_slope(rho: Any, q: Any, a: float, x: Any) -> np.ndarray:
    """``Ψ'(x) = x ∫_x^a q'(ρ)/sqrt(ρ² - x²) dρ`` (Pa) of :func:`shift_of_traction` (``q``
    vanishes at ``a``), exact for the piecewise-linear ``q``: ``x Σ β ln((L1 + S1)/(L0 + S0))``
    over its pieces of slope ``β``. Continuous (logarithmic kinks at the samples)."""
    rho, q = _inside(rho, q, a, "first")
    x = np.clip(np.asarray(x, float), 0.0, a)
    _, beta, xx, _, _, _, _, log = _pieces(rho, q, x.ravel())
    log = np.where(np.isfinite(log), log, 0.0)   # the axis piece: β = 0
    return (xx[:, 0] * np.sum(beta * log, axis=1)).reshape(x.shape)


def _grid(a: float, c: float, n: int) -> np.ndarray:
    """``n`` uniform radii on ``[0, a]`` plus clusters at the stick radius ``c`` and the edge,
    where the profiles have square-root kinks."""
    near = a * np.geomspace(1e-9, 1e-2, n // 40)
    pts = [np.linspace(0.0, a, n), a - near]
    if 0.0 < c < a:
        pts += [c - near, c + near]
    xs = np.unique(np.clip(np.concatenate(pts), 0.0, a))
    return xs


def _density(xs: np.ndarray, prof: np.ndarray, a: float):
    """The slope of the piecewise-linear profile through ``(xs, prof)`` as a function (0 outside
    ``(0, a)``)."""
    slope = np.diff(prof) / np.diff(xs)

    def dens(x: np.ndarray) -> np.ndarray:
        i = np.clip(np.searchsorted(xs, x) - 1, 0, slope.size - 1)
        return np.where((x > 0) & (x < a), slope[i], 0.0)

    return dens


def _halved(field, n: int):
    """``field(n)`` with its estimate plus the change from ``field(n // 2)``."""
    comps, e = field(n)
    half, _ = field(n // 2)
    e = e + np.maximum.reduce([np.abs(u - v) for u, v in zip(comps, half)])
    return comps, e


def _twist_part(snap: dict, tau: np.ndarray, a: float, c: float, G: float, R: np.ndarray,
                Z: np.ndarray, nu: float) -> tuple[tuple[np.ndarray, ...], np.ndarray]:
    pts = np.asarray(snap["r"] if "r" in snap else snap["x"], float)
    cuts = (c,) if 0 < c < a else ()

    def field(n: int) -> tuple[tuple[np.ndarray, ...], np.ndarray]:
        xs = _grid(a, c, n)
        dens = _density(xs, twist_of_traction(pts, tau, a, G, xs), a)
        return _st.superposed_field(R, Z, np.full(R.shape, a), np.zeros(R.shape), dens,
                                    0.0, nu, cuts, None, None, _st.twist_kernel, 4.0 * G / np.pi)

    return _halved(field, TWIST_POINTS)


def _shift_part(snap: dict, q: np.ndarray, a: float, c: float, R: np.ndarray, Z: np.ndarray,
                nu: float) -> tuple[tuple[np.ndarray, ...], np.ndarray]:
    """Radial functions of :func:`~contactlab.physics.stress_tangential.shear_kernel` of the
    field of the shear traction ``q`` (``σ_xz = q`` on the surface) and their error."""
    pts = np.asarray(snap["r"] if "r" in snap else snap["x"], float)
    cuts = (c,) if 0 < c < a else ()

    def kernel(rr, zz, xx, offset=None):
        return _sh.shear_kernel(rr, zz, xx, nu, offset)

    def field(n: int) -> tuple[tuple[np.ndarray, ...], np.ndarray]:
        xs = _grid(a, c, n)
        slope = shift_slope(pts, q, a, xs)
        prof = shift_of_traction(pts, q, a, xs)

        def dens(x: np.ndarray) -> np.ndarray:
            return np.where((x > 0) & (x < a), np.interp(x, xs, slope), 0.0)

        def vals(x: np.ndarray) -> np.ndarray:
            return np.interp(x, xs, prof)

        # the kernel's traction is -1/sqrt(x² - ρ²) in σ_xz: q = +(2/π)∫Ψ'·(-K); the
        # increments of Ψ over the rule's cells (Riemann–Stieltjes) carry its steep turn at the
        # stick radius, which the sampled traction spreads over a few samples
        return _st.superposed_field(R, Z, np.full(R.shape, a), np.zeros(R.shape), dens,
                                    0.0, nu, cuts, None, vals, kernel, 2.0 / np.pi)

    return _halved(field, SHIFT_POINTS)


def _stick_of_traction(snap: dict, tau: np.ndarray, a: float) -> float:
    """Where a sampled traction turns most sharply inside ``0.98 a`` (the square-root kink at
    the stick radius of a partial-slip traction): the sample of the largest change of slope."""
    pts = np.asarray(snap["r"] if "r" in snap else snap["x"], float)
    inside = pts < 0.98 * a
    x, t = pts[inside], np.asarray(tau, float)[inside]
    if x.size < 3:
        return 0.0
    turn = np.abs(np.diff(np.diff(t) / np.diff(x)))
    return float(x[int(np.argmax(turn)) + 1])


def _punch_shift_part(Q: float, a: float, R: np.ndarray, Z: np.ndarray, nu: float
                      ) -> tuple[tuple[np.ndarray, ...], np.ndarray]:
    """Radial functions of the shift traction of a flat punch at the tangential force ``Q``.

    Every spring of a flat punch carries the same normal force and the same shift, so they
    stick or slide together at every step of any history: the traction keeps the shape of the
    punch's own pressure, ``q = Q/(2π a sqrt(a² - r²))`` (sticking or sliding alike), the
    single punch-type traction of radius ``a`` (its kernel's ``σ_xz`` is ``-1/sqrt(a² - r²)``).
    """
    amp = -Q / (2.0 * np.pi * a)
    P = tuple(amp * p for p in _sh.shear_kernel(R, Z, a, nu))
    return P, 4e-15 * np.maximum.reduce([np.abs(p) for p in P])


def _sticking_edge(contact: Any, snap: dict, family: str) -> bool:
    """Whether the snapshot's outermost spring of ``family`` sticks with a load on it: its 3D
    traction then has an edge singularity ``∝ 1/sqrt(a² - ρ²)`` the samples do not resolve."""
    spring = snap.get(family)
    if spring is None or np.size(spring) == 0:
        return False
    f = float(np.ravel(spring)[-1])
    if f == 0.0:
        return False
    if contact.friction is None:
        return True
    limit = contact.friction * float(np.ravel(snap["normal"])[-1])
    if family == "torsion":
        return False      # the torsional slip limit needs the cell's lever: left to the caller
    return abs(f) < limit * (1.0 - 1e-9)


def path_stress(result: Any, a: Any, b: Any, c: Any = None, *, step: Any, body: Any = 1,
                part: str = "total") -> Any:
    """Implementation of :meth:`PathResult.stress` (see there)."""
    _part(part)
    contact = result.__dict__.get("_contact")
    if contact is None:
        raise NotSupportedError("stress() needs the result of contact.simulate(...) itself "
                                "(this one carries no contact, e.g. a partial result).")
    nu = body_poisson_ratio(contact, body)
    k = _step(step, len(result))
    if k not in result.snapshots:
        raise EffectNotPlannedError(f"step {k} has no snapshot: add it to simulate(..., "
                                    f"snapshots=[...]) (stored: {sorted(result.snapshots)}).")
    snap = result.snapshots[k]
    q = snap.get("shear_tangential")
    if q is not None and c is None:
        raise ParameterError("stress() of a path with a tangential shift takes points "
                             "(x, y, z) (m), x along the shift, as ShiftHistory.stress.")
    punch = q is not None and contact.friction is not None and contact.profile.is_flat_punch
    if (q is not None and contact.friction is not None and not punch
            and _sticking_edge(contact, snap, "tangential")):
        raise NotSupportedError(
            f"stress() at step {k}: the shift's traction sticks at the contact edge below "
            "the slip limit there (a profile with an edge, e.g. a flat punch), where it is "
            "singular, 1/sqrt(a² - r²), which the snapshot's samples do not resolve; use "
            "TangentialState.stress or ShiftHistory.stress at a constant normal force.")
    if c is None:
        r, z = _points(a, b)
        return _cylindrical(result, contact, snap, k, r, z, body, part, nu)
    x, y, z = _xyz(a, b, c)
    rho, cos, sin = _angles(x, y)
    f = _cylindrical(result, contact, snap, k, rho, z, body, part, nu)
    comps = list(to_cartesian(f, x, y))
    err = np.array(f.error, float)
    route = f.meta["route"]
    rad = float(snap["radius"])
    if q is not None and rad > 0 and (contact.friction is None or np.any(q != 0)):
        if contact.friction is None:
            P, e = _ns.noslip_shift_part(contact, result, k, rho.ravel(), z.ravel(), nu)
        elif punch:
            P, e = _punch_shift_part(float(result.tangential_force[k]), rad, rho.ravel(),
                                     z.ravel(), nu)
        else:
            stick = result.data.get("stick_radius")
            cs = float(stick[k]) if stick is not None else 0.0
            P, e = _shift_part(snap, q, rad, cs, rho.ravel(), z.ravel(), nu)
        sign = 1.0 if body == 1 else -1.0
        tc = _sh.shear_components(tuple(sign * p.reshape(x.shape) for p in P), cos, sin)
        comps = [u + v for u, v in zip(comps, tc)]
        err = err + e.reshape(x.shape)
        route = f"{route} + shift: " + ("no-slip punch-type shear tractions of the path's "
                                         "history" if contact.friction is None else
                                         "the step's tangential force on the shifted punch"
                                         if punch else
                                         "punch-type shear tractions of the step's traction "
                                         "(Abel inversion)")
    return _wrap(x, y, z, comps, err, {"route": route, "body": body, "nu": nu, "part": part,
                                       "step": k, "citations": (*TANGENTIAL_SOURCES, "RS44")})


def _cylindrical(result: Any, contact: Any, snap: dict, k: int, r: np.ndarray, z: np.ndarray,
                 body: int, part: str, nu: float) -> StressField:
    """The axisymmetric parts (normal and torsional) of the field at snapshot ``k``."""
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
    noslip = contact.friction is None and tau is not None and a > 0
    if noslip:
        rings = str(result.meta.get("foundation", "")).startswith("Rings")
        (tz, rt), e = _ns.noslip_twist_part(contact, result, k, r.ravel(), z.ravel(), nu, rings)
        route = (f"{route} + torsion: no-slip twisted punches of the path's history "
                 f"({'the ring solver' if rings else 'springs'})")
    elif tau is not None and a > 0 and np.any(tau != 0):
        stick = result.data.get("stick_radius")
        if snap.get("shear_tangential") is not None:   # the series is the shift's
            c = _stick_of_traction(snap, tau, a)
        else:
            c = float(stick[k]) if stick is not None else 0.0
        (tz, rt), e = _twist_part(snap, tau, a, c, float(contact.moduli.torsional), r.ravel(),
                                  z.ravel(), nu)
        route = f"{route} + torsion: twisted punches of the step's traction (Abel inversion)"
    if noslip or (tau is not None and a > 0 and np.any(tau != 0)):
        sign = 1.0 if body == 1 else -1.0
        stz, srt = sign * tz.reshape(shape), sign * rt.reshape(shape)
        err = err + np.asarray(e).reshape(shape)
    mags = np.abs(np.stack([*comps, stz, srt]))
    fin = np.all(np.isfinite(mags), axis=0)
    top = np.max(mags[:, fin], initial=0.0)
    rel = float(np.max(err[fin], initial=0.0) / top) if top > 0 else 0.0
    return StressField(r, z, *comps, stz, srt, np.where(fin, err, np.inf),
                       {"route": route, "body": body, "nu": nu, "part": part, "step": k,
                        "error_estimate": rel, "citations": ("Sn65", "J85", "RS44")})
