"""The DMT adhesive force of any tip without a wall, with its exact derivatives, for fitting.

Derjaguin's approximation with a rigid gap beyond the contact edge: outside the contact radius
``a`` the surfaces are separated by the undeformed gap ``h(r) = f(r) - f(a)``, and a
short-range attraction of work ``Δγ = ∫_0^∞ σ(h) dh`` pulls on that annulus. With
``dh = f'(r) dr``, ``2π r dr = 2π (r/f'(r)) dh``; when the range is short against the length
over which ``r/f'(r)`` changes, the attraction sums to

``F_adh = 2π Δγ ρ(a)``, with the *effective radius* ``ρ(a) = a/f'(a)`` (m).

Paraboloid ``r²/(2R)``: ``ρ = R`` for every ``a`` (the classic ``2πRΔγ``; exact for any
range, since ``r/f'(r)`` is constant); exact sphere ``ρ = sqrt(R² - a²)``; cone ``f = s r``:
``ρ = a/s``; power law ``c r^n``: ``ρ = a^(2-n)/(n c)``. A wall (``f' = ∞``) gives ``ρ = 0``:
no DMT force, and a flat apex (``f'(a)/a → 0`` at the contact's onset) gives an infinite one;
both are refused.

The fitted force is ``F = E* Φ(δ) - 2πΔγ ρ(a(δ)) + F0`` in contact (``δ > 0``), ``F0`` apart;
``∂F/∂Δγ = -2π ρ``, ``∂F/∂δ = 2E* a - 2πΔγ ρ'(a) da/dδ`` with the tip model's own ``a(δ)``
and ``da/dδ`` (:meth:`contactlab.fit._tip.TipModel.radius`).

Routes for ``ρ``: ``"constant"`` (one paraboloid term: ``R``, no radius needed), ``"power"``
(sums of powers, closed form), ``"sphere"`` (closed form), ``"table"`` (any other profile: a
cubic spline of ``a/f'(a)`` in ``a`` on graded nodes, its error measured at the interval
midpoints against the profile's own slope and reported; the Jacobian uses the spline's own
derivative, so it is exact for the model being fitted).
"""
from __future__ import annotations

from typing import Any

import numpy as np

from ..errors import NotSupportedError

__all__ = ["DMT_NODES", "DMT_TABLE_WARN", "DMTModel", "check_wall", "dmt_start"]

#: nodes of the ``"table"`` route's spline of ``a/f'(a)``
DMT_NODES = 2049
#: error of that spline (relative to the largest ``a/f'(a)``) above which a fit warns
DMT_TABLE_WARN = 1e-3


def check_wall(profile: Any) -> None:
    """Refuse a tip with a punch wall (NotSupportedError): the DMT force beyond it is zero."""
    if np.isfinite(profile.wall_radius):
        raise NotSupportedError(
            f"adhesion='dmt' with profile={profile!r}: beyond a punch wall the gap opens "
            "vertically (f' infinite), so the DMT (Derjaguin) force 2πΔγ a/f'(a) is zero and "
            "DMT adds nothing to the non-adhesive fit; the adhesion of a flat punch is "
            "Kendall's (JKR-type: it acts through the pull-off, not the attached curve).")


class DMTModel:
    """Effective radius ``ρ(a(δ)) = a/f'(a)`` (m) of a tip and its slope in the indentation.

    Parameters
    ----------
    profile : Profile
        The tip; no wall, and a finite ``ρ`` at the contact's onset.
    tipm : TipModel
        The fit's tip model (its contact radius ``a(δ)`` and ``da/dδ``).
    """

    def __init__(self, profile: Any, tipm: Any) -> None:
        from ..profiles import Sphere
        check_wall(profile)
        self.profile, self.tipm = profile, tipm
        self.error = 0.0
        terms = profile.power_terms()
        b = profile.flat_radius
        if isinstance(profile, Sphere):
            self.route = "sphere"
            self._R = float(profile.R)
        elif terms is not None and b == 0.0:
            self.route = "power"
            if len(terms) == 1 and terms[0][1] == 2.0:
                self.route = "constant"
                self._R = 1.0 / (2.0 * terms[0][0])
            self._terms = [(float(c), float(n)) for c, n in terms]
        else:
            self.route = "table"
            self._build(float(tipm.radius(np.array([tipm.delta_max]))[0][0]))
            if self.error > DMT_TABLE_WARN:
                import warnings

                from ..errors import ValidityWarning
                warnings.warn(
                    f"adhesion='dmt' with profile={profile!r}: the effective radius a/f'(a) "
                    f"of the tip is not smooth (its spline is off by {self.error:.2g} of its "
                    "largest value between nodes; a linear table's slope is constant on each "
                    "interval); the fitted work of adhesion carries that error. Use "
                    "interpolation='cubic' for a measured tip.", ValidityWarning, stacklevel=4)
        rho0 = float(self.rho_of_radius(np.array([b]))[0][0])
        if not (np.isfinite(rho0) and rho0 >= 0.0):
            raise NotSupportedError(
                f"adhesion='dmt' with profile={profile!r}: the tip is flat at the contact's "
                f"onset (f'(a)/a -> 0 at a = {b!r} m), where the DMT force 2πΔγ a/f'(a) of a "
                "rigid gap is unbounded; the model needs a gap that opens beyond the contact "
                "edge (a rounded or pointed apex, or a flat centre with a rising flank); use "
                "adhesion='jkr'.")
        #: ``ρ`` at the contact's onset (m): the force step at the contact point is ``2πΔγ ρ0``
        self.rho0 = rho0

    # ------------------------------------------------------------------ table route
    def _build(self, a_top: float) -> None:
        from scipy.interpolate import CubicSpline
        p = self.profile
        key = ("dmt", DMT_NODES, a_top)
        cache = p.__dict__.setdefault("_fit_tip_tables", {})
        if key not in cache:
            b = p.flat_radius
            top = min(a_top * 1.02, p.max_radius)
            a = b + (top - b) * np.linspace(0.0, 1.0, DMT_NODES) ** 2
            rho = self._rho_slope(a[1:])
            if b > 0:
                rho0 = self._rho_slope(np.array([b * (1.0 + 1e-12)]))[0]
            else:       # a/f'(a) at a = 0: quadratic extrapolation of the first nodes
                x, y = a[1:4], rho[:3]
                rho0 = (y[0] * x[1] * x[2] / ((x[0] - x[1]) * (x[0] - x[2]))
                        + y[1] * x[0] * x[2] / ((x[1] - x[0]) * (x[1] - x[2]))
                        + y[2] * x[0] * x[1] / ((x[2] - x[0]) * (x[2] - x[1])))
                if rho0 <= 1e-9 * float(np.max(rho)):     # a pointed apex: 0, not rounding
                    rho0 = 0.0
            vals = np.concatenate([[rho0], rho])
            spline = CubicSpline(a, vals)
            am = 0.5 * (a[2:] + a[1:-1])
            exact = self._rho_slope(am)
            scale = max(float(np.max(np.abs(vals))), 1e-300)
            err = float(np.max(np.abs(spline(am) - exact))) / scale
            cache[key] = (spline, spline.derivative(), err)
        self._spline, self._dspline, self.error = cache[key]

    def _rho_slope(self, a: np.ndarray) -> np.ndarray:
        s = np.asarray(self.profile._slope_any(a), float)
        with np.errstate(divide="ignore", invalid="ignore"):
            return np.where(s > 0, a / np.where(s > 0, s, 1.0), np.inf)

    # ------------------------------------------------------------------ evaluation
    def rho_of_radius(self, a: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """``ρ(a)`` (m) and ``dρ/da`` (dimensionless) at contact radii ``a`` (m)."""
        if self.route == "constant":
            return np.full(a.shape, self._R), np.zeros(a.shape)
        if self.route == "sphere":
            rho = np.sqrt(np.maximum(self._R * self._R - a * a, 0.0))
            return rho, np.where(rho > 0, -a / np.where(rho > 0, rho, 1.0), 0.0)
        if self.route == "power":
            # ρ = 1/S, S = Σ n c a^(n-2); dρ/da = -S'/S², S' = Σ n (n-2) c a^(n-3)
            with np.errstate(divide="ignore", invalid="ignore"):
                S = sum(n * c * a ** (n - 2.0) for c, n in self._terms)
                dS = sum(n * (n - 2.0) * c * a ** (n - 3.0) for c, n in self._terms
                         if n != 2.0)
                rho = np.where(np.isinf(S), 0.0, 1.0 / S)
                drho = -dS * rho * rho
            return rho, np.where(np.isfinite(drho), drho, 0.0) * np.ones(a.shape)
        return self._spline(a), self._dspline(a)

    def __call__(self, delta: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """``ρ(a(δ))`` (m) and ``dρ/dδ`` (dimensionless) at indentations ``δ`` (m); 0 where
        ``δ <= 0`` (apart)."""
        pos = delta > 0
        if self.route == "constant":
            return np.where(pos, self._R, 0.0), np.zeros(delta.shape)
        a, a_d = self.tipm.radius(delta)
        rho, rho_a = self.rho_of_radius(a)
        return np.where(pos, rho, 0.0), np.where(pos, rho_a * a_d, 0.0)


#: candidate contact points of a pointed tip's start search (a second, finer pass follows)
_START_CANDIDATES = 32


def dmt_start(dmt: DMTModel, tipm: Any, start: dict, names: tuple[str, ...], zs: np.ndarray,
              Fs: np.ndarray, rise: np.ndarray, cp_lo: float, fit_off: bool, w_fixed: float,
              k_nu: float, c_tip: float, E_fixed: float) -> None:
    """Starting values of a DMT fit on a pointed tip (``ρ0 = 0``: no step at the contact
    point): at each candidate contact point the force ``E* Φ - 2πΔγ ρ + F0`` is linear in the
    free ones of ``E*``, ``Δγ`` and ``F0``, solved by linear least squares; the candidate with
    the smallest residual (and ``E*``, ``Δγ`` positive) wins, on a grid from the start of the
    data (or one span before it) to the force's minimum, then on a finer grid around it; the
    candidates are judged on a subsample of about 256 points.
    Fills ``start`` for the names it does not hold."""
    fit_cp = "contact_point" in names and "contact_point" not in start
    step = max(1, zs.size // 256)               # the candidates are judged on a subsample
    z_min = float(zs[int(np.argmin(rise))])
    zs, Fs = zs[::step], Fs[::step]
    free_e = "E" in names and "E" not in start
    free_w = "work_of_adhesion" in names and "work_of_adhesion" not in start
    free_o = fit_off and "force_offset" not in start
    es_fixed = 1.0 / (k_nu / float(start.get("E", E_fixed)) + c_tip)
    w_fix = float(start.get("work_of_adhesion", w_fixed))
    o_fix = float(start.get("force_offset", 0.0))

    def solve(cp: float) -> tuple[float, float, float, float]:
        phi = tipm(zs - cp)[0]
        rho = dmt(zs - cp)[0]
        cols, rhs = [], Fs.copy()
        for free, col, val in ((free_e, phi, es_fixed), (free_w, -2.0 * np.pi * rho, w_fix),
                               (free_o, np.ones_like(phi), o_fix)):
            if free:
                cols.append(col)
            else:
                rhs = rhs - val * col
        coef: Any = []
        if cols:                        # columns of unit length: their scales differ widely
            A = np.stack(cols, axis=1)
            norms = np.sqrt(np.einsum("ij,ij->j", A, A))
            norms[norms == 0] = 1.0
            coef = np.linalg.lstsq(A / norms, rhs, rcond=None)[0] / norms
        it = iter(coef)
        e = float(next(it)) if free_e else es_fixed
        w = float(next(it)) if free_w else w_fix
        o = float(next(it)) if free_o else o_fix
        r = e * phi - 2.0 * np.pi * w * rho + o - Fs
        ok = e > 0 and w > 0
        return (float(r @ r) if ok else np.inf), e, w, o

    cp0 = float(start.get("contact_point", 0.0))
    if fit_cp:
        lo = max(cp_lo, float(zs[0]))
        grid = np.linspace(lo, z_min, _START_CANDIDATES)
        rows = [(*solve(float(c)), float(c)) for c in grid]
        i = int(np.argmin([r[0] for r in rows]))
        dz = float(grid[1] - grid[0]) if grid.size > 1 else 0.0
        fine = np.linspace(max(lo, rows[i][4] - dz), min(z_min, rows[i][4] + dz),
                           _START_CANDIDATES // 2)
        rows += [(*solve(float(c)), float(c)) for c in fine]
        best = min(rows, key=lambda r: r[0])
        cp0 = best[4] if np.isfinite(best[0]) else z_min
        start["contact_point"] = cp0
    _, e, w, o = solve(cp0)
    if free_e and e > 0:
        inv = 1.0 / e - c_tip
        start["E"] = k_nu / inv if inv > 0 else E_fixed
    if free_w:
        start["work_of_adhesion"] = w if w > 0 else 1e-3
    if free_o:
        start["force_offset"] = o
