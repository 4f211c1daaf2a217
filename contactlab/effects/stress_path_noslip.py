"""Frictional parts of the field at a snapshot of a load path without a friction limit (no
slip): the tractions are rebuilt from the path's own series (contact radius or depth, and the
twist or shift), not from the snapshot's samples, which cannot resolve their edge singularity.

Nothing slips, so every increment of the control (twist ``φ`` or shift ``u``) is carried by the
points in contact when it is applied, rigidly:

- The exact torsion route (the ring solver) applies the increment of a step as a rigid twisted
  flat punch of the step's contact radius; a punch wider than a later contact radius is merged
  into the punch of that radius (the points it held leave the contact traction-free). The
  increment ``Δφ_j`` of step ``j`` is then carried at step ``k`` by a punch of radius
  ``min(a_j, ..., a_k)``, and the field is the sum of the Reissner–Sagoci fields of those
  punches (:func:`contactlab.physics.stress.twist_kernel`): exact, no quadrature.
- The spring routes (MDR springs: every shift, and the torsion route ``method="mdr"``) let a
  point at radius ``x`` enter the contact when the depth passes ``g(x)`` (depth and control
  linear within a step, as the springs' contact weight does), and hold
  ``Δc(x) = c_k - c(entry)`` since then. The MDR profile of the traction is ``Δc`` times the
  springs' stiffness (``G*`` per unit length for the shift, half the MDR line load being
  ``Ψ = G* Δu/2``; the twisted-punch density ``Φ = -Δφ`` for the twist), with a jump to 0 at the
  edge: the superposition of the elementary fields over it (``Ψ'`` or ``Φ'`` as the density,
  its increments over the quadrature cells carrying the jumps where the contact shrank and grew
  again) plus the edge punch of radius ``a`` carrying ``Δc(a⁻)``, the singular edge traction.
"""
from __future__ import annotations

from typing import Any

import numpy as np

from ..errors import NotSupportedError
from ..physics import stress as _st
from ..physics import stress_tangential as _sh
from .stress import slope_route

__all__ = ["entry_history", "noslip_shift_part", "noslip_twist_part", "ring_punches"]

#: radii of the grid of the no-slip profile ``Δc(x)`` (plus the path's contact radii), linear
#: between; the estimate adds the change on half as many
NOSLIP_POINTS = 4000
#: most radii where the quadrature is split (the path's contact radii below ``a``, where
#: ``Δc`` has kinks or jumps); beyond it the jumps only
MAX_CUTS = 400
#: points per block of the punch sum (memory: points x punches values per component)
PUNCH_BLOCK = 2_000_000


def _series(result: Any, name: str, k: int) -> np.ndarray:
    data = result.data
    if name not in data:
        raise NotSupportedError(f"stress() of a no-slip path needs the series {name!r}: add it "
                                "to simulate(..., outputs=[...]).")
    return np.asarray(data[name][:k + 1], float)


def ring_punches(radius: Any, control: Any) -> tuple[np.ndarray, np.ndarray]:
    """Radii (m) and turns of the rigid punches carrying a no-slip history at its last step:
    the increment of step ``j`` (from 0 before the path) at ``min(a_j, ..., a_k)``, equal radii
    merged. Turns in the unit of ``control``."""
    a = np.asarray(radius, float)
    c = np.asarray(control, float)
    inc = np.diff(np.concatenate([[0.0], c]))
    eff = np.minimum.accumulate(a[::-1])[::-1]
    live = (eff > 0) & (inc != 0)
    t, inv = np.unique(eff[live], return_inverse=True)
    m = np.zeros(t.size)
    np.add.at(m, inv, inc[live])
    return t, m


def entry_history(g_x: Any, depth: Any, control: Any) -> np.ndarray:
    """``Δc(x) = c_k - c(entry)`` at the points of MDR profile height ``g_x`` (m) in contact at
    the last step: the control at the last entry of each point into the contact (the depth
    passing ``g(x)``, depth and control linear within each step, from 0 before the path)."""
    dd = np.concatenate([[0.0], np.asarray(depth, float)])
    cc = np.concatenate([[0.0], np.asarray(control, float)])
    sm = np.minimum.accumulate(dd[::-1])[::-1]        # the depth's lowest value from j on
    g = np.asarray(g_x, float)
    j = np.clip(np.searchsorted(sm, g, side="left") - 1, 0, dd.size - 2)
    span = dd[j + 1] - dd[j]
    with np.errstate(divide="ignore", invalid="ignore"):
        t = np.where(span > 0, (g - dd[j]) / span, 0.0)
    t = np.clip(t, 0.0, 1.0)
    return cc[-1] - (cc[j] + t * (cc[j + 1] - cc[j]))


def _profile_grid(contact: Any, result: Any, k: int, control: str, n: int
                  ) -> tuple[np.ndarray, np.ndarray, float, tuple[float, ...]]:
    """Grid ``xs`` on ``[0, a]`` (uniform plus the path's contact radii below ``a``, each also
    just inside), ``Δc`` there (left limit at ``a``) and the radii where ``Δc`` jumps (where the
    contact grew again after shrinking)."""
    radii = _series(result, "radius", k)
    a = float(radii[-1])
    inner = np.unique(radii[(radii > 0) & (radii < a)])
    lo, hi = inner * (1.0 - 1e-12), inner * (1.0 + 1e-12)
    xs = np.unique(np.clip(np.concatenate([np.linspace(0.0, a, n), lo, hi]), 0.0, a))
    g = np.asarray(contact.profile.g(xs), float)
    dc = entry_history(np.minimum(g, float(_series(result, "depth", k)[-1])),
                       _series(result, "depth", k), _series(result, control, k))
    if inner.size <= MAX_CUTS:          # every kink (and jump) of Δc
        cuts = tuple(inner)
    else:                               # the jumps only: the kinks are left to the estimate
        jump = np.abs(np.interp(hi, xs, dc) - np.interp(lo, xs, dc))
        cuts = tuple(inner[jump > 1e-9 * np.max(np.abs(dc), initial=0.0)][:MAX_CUTS])
    return xs, dc, a, cuts


def _superpose(xs: np.ndarray, prof: np.ndarray, a: float, edge: float, cuts: tuple,
               R: np.ndarray, Z: np.ndarray, nu: float, kernel: Any, scale: float
               ) -> tuple[tuple[np.ndarray, ...], np.ndarray]:
    slope = np.diff(prof) / np.diff(xs)

    def dens(x: np.ndarray) -> np.ndarray:
        i = np.clip(np.searchsorted(xs, x) - 1, 0, slope.size - 1)
        return np.where((x > 0) & (x < a), slope[i], 0.0)

    def vals(x: np.ndarray) -> np.ndarray:
        return np.interp(x, xs, prof)

    return _st.superposed_field(R, Z, np.full(R.shape, a), np.full(R.shape, edge), dens, 0.0,
                                nu, cuts, None, vals, kernel, scale)


def _halved(field: Any) -> tuple[tuple[np.ndarray, ...], np.ndarray]:
    comps, e = field(NOSLIP_POINTS)
    half, _ = field(NOSLIP_POINTS // 2)
    return comps, e + np.maximum.reduce([np.abs(u - v) for u, v in zip(comps, half)])


def _slope_part(contact: Any, result: Any, k: int, control: str, alpha: float,
                R: np.ndarray, Z: np.ndarray, nu: float, kernel: Any, scale: float
                ) -> tuple[tuple[np.ndarray, ...], np.ndarray] | None:
    """The superposition over the profile ``P = alpha Δc`` with its exact slope: between the
    path's contact radii ``Δc`` follows the depth, ``P' = -alpha rate_j g'(x)`` (``rate_j`` the
    control's change per depth over the entry step ``j``), each jump of ``Δc`` at a radius
    ``s`` a punch of radius ``s`` and the drop to 0 at ``a`` the edge punch. ``None`` for a
    linear table (its slope is not pointwise: the grid route takes it)."""
    radii, depth = _series(result, "radius", k), _series(result, "depth", k)
    ctrl = _series(result, control, k)
    a = float(radii[-1])
    gp, gp_err, g_vals, pcuts, _ = slope_route(contact.profile, a, contact.rtol)
    if g_vals is not None:
        return None
    dd = np.concatenate([[0.0], depth])
    cc = np.concatenate([[0.0], ctrl])
    sm = np.minimum.accumulate(dd[::-1])[::-1]
    with np.errstate(divide="ignore", invalid="ignore"):
        rate = np.where(np.diff(dd) != 0, np.diff(cc) / np.diff(dd), 0.0)
    d_k = float(depth[-1])

    def g_of(x: np.ndarray) -> np.ndarray:
        return np.minimum(np.asarray(contact.profile.g(x), float), d_k)

    def dens(x: np.ndarray) -> np.ndarray:
        j = np.clip(np.searchsorted(sm, g_of(x), side="left") - 1, 0, rate.size - 1)
        return np.where((x > 0) & (x < a), -alpha * rate[j] * gp(x), 0.0)

    dens_err = None
    if gp_err is not None:
        def dens_err(x: np.ndarray) -> np.ndarray:
            j = np.clip(np.searchsorted(sm, g_of(x), side="left") - 1, 0, rate.size - 1)
            return np.abs(alpha * rate[j]) * gp_err(x)

    inner = np.unique(radii[(radii > 0) & (radii < a)])
    lo, hi = inner * (1.0 - 1e-12), inner * (1.0 + 1e-12)
    both = entry_history(g_of(np.concatenate([lo, hi, [a]])), depth, ctrl)
    jump = alpha * (both[inner.size:2 * inner.size] - both[:inner.size])
    edge = -alpha * float(both[-1])
    cuts = tuple(sorted({*inner[:MAX_CUTS], *pcuts}))
    P, err = _st.superposed_field(R, Z, np.full(R.shape, a), np.full(R.shape, edge), dens,
                                  0.0, nu, cuts, dens_err, None, kernel, scale)
    live = np.abs(jump) > 1e-12 * np.max(np.abs(both), initial=0.0) * max(abs(alpha), 1e-300)
    if np.any(live):
        s, J = inner[live], jump[live]
        step = max(1, PUNCH_BLOCK // s.size)
        P = tuple(np.array(p) for p in P)
        for lo_i in range(0, R.size, step):
            sl = slice(lo_i, lo_i + step)
            K = kernel(R[sl, None], Z[sl, None], s[None, :])
            for p, c in zip(P, K):
                with np.errstate(invalid="ignore"):
                    p[sl] += scale * (c @ J)
    return P, err


def noslip_shift_part(contact: Any, result: Any, k: int, R: np.ndarray, Z: np.ndarray,
                      nu: float) -> tuple[tuple[np.ndarray, ...], np.ndarray]:
    """Radial functions of :func:`~contactlab.physics.stress_tangential.shear_kernel` (body 1,
    ``σ_xz = q`` on the surface) of the no-slip shift traction at step ``k`` and their error."""
    Gs = float(contact.moduli.tangential)

    def kernel(rr, zz, xx, offset=None):
        return _sh.shear_kernel(rr, zz, xx, nu, offset)

    # q = -(2/π)∫Ψ'/sqrt(x² - ρ²) + (2/π)Ψ(a⁻)/sqrt(a² - ρ²), Ψ = G* Δu/2; the kernel's σ_xz
    # is -1/sqrt, so the field is (2/π)[∫Ψ' K - Ψ(a⁻) K(a)]
    exact = _slope_part(contact, result, k, "displacement", 0.5 * Gs, R, Z, nu, kernel,
                        2.0 / np.pi)
    if exact is not None:
        return exact

    def field(n: int) -> tuple[tuple[np.ndarray, ...], np.ndarray]:
        xs, du, a, cuts = _profile_grid(contact, result, k, "displacement", n)
        psi = 0.5 * Gs * du
        return _superpose(xs, psi, a, -float(psi[-1]), cuts, R, Z, nu, kernel, 2.0 / np.pi)

    return _halved(field)


def noslip_twist_part(contact: Any, result: Any, k: int, R: np.ndarray, Z: np.ndarray,
                      nu: float, rings: bool) -> tuple[tuple[np.ndarray, ...], np.ndarray]:
    """``(σ_θz, σ_rθ)`` (body 1) of the no-slip torsional traction at step ``k`` and their
    error: the ring solver's punches (``rings``) or the springs' entry history."""
    G = float(contact.moduli.torsional)
    if rings:
        t, m = ring_punches(_series(result, "radius", k), _series(result, "twist", k))
        out = [np.zeros(R.shape), np.zeros(R.shape)]
        step = max(1, PUNCH_BLOCK // max(t.size, 1))
        for lo in range(0, R.size, step):
            sl = slice(lo, lo + step)
            tz, rt = _st.twist_kernel(R[sl, None], Z[sl, None], t[None, :])
            with np.errstate(invalid="ignore"):
                out[0][sl] = (4.0 * G / np.pi) * (tz @ m)
                out[1][sl] = (4.0 * G / np.pi) * (rt @ m)
        scale = np.maximum(np.abs(out[0]), np.abs(out[1]))
        return (out[0], out[1]), 1e-14 * max(t.size, 1) * scale

    exact = _slope_part(contact, result, k, "twist", -1.0, R, Z, nu, _st.twist_kernel,
                        4.0 * G / np.pi)
    if exact is not None:
        return exact

    def field(n: int) -> tuple[tuple[np.ndarray, ...], np.ndarray]:
        xs, dphi, a, cuts = _profile_grid(contact, result, k, "twist", n)
        return _superpose(xs, -dphi, a, float(dphi[-1]), cuts, R, Z, nu, _st.twist_kernel,
                          4.0 * G / np.pi)

    return _halved(field)
