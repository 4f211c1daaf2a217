"""Measured (tabulated) profiles.

``interpolation="linear"`` (default) is the piecewise-linear interpolant of the table. Its MDR
transform is exact, a sum of truncated-cone transforms (physics.md §2):

    g(x) = x [ s_k π/2 - Σ_{j=1..k} (s_j - s_{j-1}) asin(r_j/x) ],   r_k <= x < r_{k+1}

and ``∫_0^a g = Σ_i s_i ∫_{r_i}^{min(r_{i+1},a)} sqrt(a²-r²) dr`` in closed form. Each evaluation
costs O(N) for N table points; nothing is precomputed for all nodes, so tables of 10^6 points work.

``interpolation="cubic"`` uses a C² cubic spline (scipy ``CubicSpline``, not-a-knot ends); its
transform is computed by quadrature of the spline slope (no closed form is used because the
power-basis form of the spline cancels catastrophically for fine tables). The two interpolants of
the same table differ at the level of the interpolation error (~1e-4 relative for fine tables of
smooth profiles).

Heights are taken relative to the table's first value (the datum of a measurement is arbitrary),
and a table starting at ``r0 > 0`` is extended flat to the axis. Contact radii must stay inside the
table (``max_radius`` = last radius).
"""
from __future__ import annotations

import csv
from pathlib import Path
from typing import Any, ClassVar

import numpy as np

from ..errors import OutsideTheoryError, ParameterError, TabulatedDataError
from ..params import Param
from .base import Profile

__all__ = ["Tabulated"]

_CHUNK = 2_000_000   # elements per dense (x, node) block


class Tabulated(Profile):
    """Profile given by a table of radii ``r`` (m) and heights ``f`` (m).

    Parameters
    ----------
    r : array_like
        Radii, m: strictly increasing, >= 0, at least 2 points (4 for ``"cubic"``).
    f : array_like
        Heights (gap), m, same length. Need not be monotone, but the transform g must be
        non-decreasing over the contact (checked, see :meth:`radius_of_depth`).
    interpolation : {"linear", "cubic"}
        Piecewise-linear (exact transform, default) or cubic spline (quadrature transform).

    Raises
    ------
    TabulatedDataError
        Unsorted, duplicate, negative or non-finite radii; non-finite heights; length mismatch.
    """

    name: ClassVar[str] = "tabulated"
    params: ClassVar[tuple[Param, ...]] = (
        Param("r", "r_i", "m", "nonnegative", "table radii"),
        Param("f", "f_i", "m", "real", "table heights"),
        Param("interpolation", "-", "-", "real", "interpolation"),
    )

    def __init__(self, r: Any, f: Any, interpolation: str = "linear") -> None:
        if interpolation not in ("linear", "cubic"):
            raise ParameterError(f"interpolation={interpolation!r} is invalid: use 'linear' "
                                 "(exact transform) or 'cubic' (smooth spline).")
        r_arr = self._table_array("r", r)
        f_arr = self._table_array("f", f)
        if r_arr.shape != f_arr.shape:
            raise TabulatedDataError(f"r has {r_arr.size} values but f has {f_arr.size}: the "
                                     "table columns must have equal length.")
        need = 2 if interpolation == "linear" else 4
        if r_arr.size < need:
            raise TabulatedDataError(f"r has {r_arr.size} points: {interpolation} interpolation "
                                     f"needs at least {need}.")
        if r_arr[0] < 0:
            raise TabulatedDataError(f"r[0]={r_arr[0]!r} is invalid: radii must be >= 0 m.")
        steps = np.diff(r_arr)
        if np.any(steps == 0):
            i = int(np.argmax(steps == 0))
            raise TabulatedDataError(f"r[{i + 1}]={r_arr[i + 1]!r} duplicates r[{i}]: radii must "
                                     "be strictly increasing (remove or average duplicates).")
        if np.any(steps < 0):
            i = int(np.argmax(steps < 0))
            raise TabulatedDataError(f"r[{i + 1}]={r_arr[i + 1]!r} < r[{i}]={r_arr[i]!r}: radii "
                                     "must be strictly increasing (sort the table).")
        f_rel = f_arr - f_arr[0]
        if r_arr[0] > 0:        # flat extension to the axis
            r_arr = np.concatenate([[0.0], r_arr])
            f_rel = np.concatenate([[0.0], f_rel])
        self.r = r_arr
        self.f = f_rel
        self.interpolation = interpolation
        self._slopes = np.diff(f_rel) / np.diff(r_arr)
        # slope jumps Δs_j at interior nodes j = 1..N-2, and s_0 at the axis
        self._dslope = np.diff(self._slopes)
        self._monotone_f = bool(np.all(self._slopes >= 0)) if interpolation == "linear" else None
        self._spline = None
        if interpolation == "cubic":
            from scipy.interpolate import CubicSpline
            self._spline = CubicSpline(r_arr, f_rel)
            self._spline_d = self._spline.derivative()
            probe = np.linspace(0, r_arr[-1], 8 * r_arr.size)
            self._monotone_f = bool(np.all(self._spline_d(probe) >= 0))
        self._node_g: np.ndarray | None = None

    @classmethod
    def from_csv(cls, path: str | Path, interpolation: str = "linear", *,
                 delimiter: str | None = None) -> "Tabulated":
        """Read a two-column table (r [m], f [m]); a non-numeric first row is a header."""
        path = Path(path)
        try:
            text = path.read_text()
        except OSError as err:
            raise TabulatedDataError(f"file={str(path)!r} cannot be read: {err}.") from err
        dialect_delim = delimiter or (";" if text.count(";") > text.count(",") else ",")
        rows = [row for row in csv.reader(text.splitlines(), delimiter=dialect_delim)
                if row and not row[0].lstrip().startswith("#")]
        if rows:
            try:
                float(rows[0][0])
            except ValueError:
                rows = rows[1:]
        try:
            data = np.array([[float(v) for v in row[:2]] for row in rows], dtype=float)
        except (ValueError, IndexError) as err:
            raise TabulatedDataError(f"file={str(path)!r}: every row needs two numbers r, f "
                                     f"({err}).") from err
        if data.ndim != 2 or data.shape[0] == 0:
            raise TabulatedDataError(f"file={str(path)!r} holds no data rows.")
        return cls(data[:, 0], data[:, 1], interpolation=interpolation)

    @staticmethod
    def _table_array(name: str, values: Any) -> np.ndarray:
        try:
            arr = np.asarray(values, dtype=float)
        except (TypeError, ValueError) as err:
            raise TabulatedDataError(f"{name} is invalid: expected a 1D array of numbers.") from err
        if arr.ndim != 1:
            raise TabulatedDataError(f"{name} has shape {arr.shape}: expected a 1D array.")
        if not np.all(np.isfinite(arr)):
            i = int(np.argmax(~np.isfinite(arr)))
            raise TabulatedDataError(f"{name}[{i}]={arr[i]!r} is invalid: table values must be "
                                     "finite (drop or fill missing points).")
        return arr

    # identity: arrays compare by value
    def _param_values(self) -> tuple[Any, ...]:
        return (self.r.tobytes(), self.f.tobytes(), self.interpolation)

    def __repr__(self) -> str:
        return (f"Tabulated(<{self.r.size} points, r in [0, {self.r[-1]:.4g}] m>, "
                f"interpolation={self.interpolation!r})")

    @property
    def max_radius(self) -> float:
        return float(self.r[-1])

    def _length_scale(self) -> float:
        return float(np.min(np.diff(self.r)))

    def _initial_bracket(self) -> float:
        return float(self.r[-1]) * (1 - 1e-12)

    # ------------------------------------------------------------------ geometry
    def _guard(self, r: np.ndarray, name: str) -> None:
        if np.any(r > self.r[-1]):
            raise OutsideTheoryError(
                f"{name}={np.max(r)!r} m lies beyond the table (last radius {self.r[-1]!r} m): "
                "extend the measured profile or reduce the load.")

    def _height(self, r: np.ndarray) -> np.ndarray:
        self._guard(r, "r")
        if self._spline is not None:
            return self._spline(r)
        return np.interp(r, self.r, self.f)

    def _slope(self, r: np.ndarray) -> np.ndarray:
        self._guard(r, "r")
        if self._spline is not None:
            return self._spline_d(r)
        k = np.clip(np.searchsorted(self.r, r, side="right") - 1, 0, self._slopes.size - 1)
        return self._slopes[k]

    def available_strategies(self) -> tuple[str, ...]:
        return ("closed_form", "quadrature") if self._spline is None else ("quadrature",)

    def _g_closed_form(self, x: np.ndarray) -> np.ndarray:
        """Exact transform of the piecewise-linear interpolant (sum of arcsines), chunked."""
        self._guard(x, "x")
        x = np.asarray(x, dtype=float)
        flat = x.ravel()
        out = np.zeros(flat.size)
        nodes = self.r[1:-1]
        ds = self._dslope
        chunk = max(1, _CHUNK // max(nodes.size, 1))
        k_all = np.clip(np.searchsorted(self.r, flat, side="right") - 1, 0, self._slopes.size - 1)
        for start in range(0, flat.size, chunk):
            xs = flat[start:start + chunk]
            pos = xs > 0
            val = np.zeros(xs.size)
            if np.any(pos):
                xp = xs[pos][:, None]
                q = np.minimum(nodes[None, :] / xp, 1.0)
                contrib = np.where(nodes[None, :] < xp, ds[None, :] * np.arcsin(q), 0.0)
                val[pos] = xs[pos] * (0.5 * np.pi * self._slopes[k_all[start:start + chunk][pos]]
                                      - contrib.sum(axis=1))
            out[start:start + chunk] = val
        return out.reshape(x.shape)

    def _g_integral_closed_form(self, a: np.ndarray) -> np.ndarray:
        if self._spline is not None:
            return self._g_integral_quadrature(a)[0]
        self._guard(a, "a")
        a = np.asarray(a, dtype=float)
        flat = a.ravel()
        out = np.zeros(flat.size)
        lo_n, hi_n, s = self.r[:-1], self.r[1:], self._slopes
        chunk = max(1, _CHUNK // s.size)
        for start in range(0, flat.size, chunk):
            aa = flat[start:start + chunk][:, None]
            lo = np.minimum(lo_n[None, :], aa)
            hi = np.minimum(hi_n[None, :], aa)

            def prim(t: np.ndarray) -> np.ndarray:
                # ∫ sqrt(a²-r²) dr = (r sqrt(a²-r²) + a² asin(r/a))/2
                with np.errstate(divide="ignore", invalid="ignore"):
                    q = np.where(aa > 0, t / np.where(aa > 0, aa, 1.0), 0.0)
                return 0.5 * (t * np.sqrt(np.maximum((aa - t) * (aa + t), 0.0))
                              + aa**2 * np.arcsin(np.minimum(q, 1.0)))

            out[start:start + chunk] = (s[None, :] * (prim(hi) - prim(lo))).sum(axis=1)
        return out.reshape(a.shape)

    def _g_integral_with_error(self, a: np.ndarray, rtol: float | None = None
                               ) -> tuple[np.ndarray, np.ndarray]:
        if self._spline is not None:
            return self._g_integral_quadrature(a, rtol)
        return super()._g_integral_with_error(a, rtol)

    # ------------------------------------------------------------------ contact radius
    def _check_monotone_upto(self, a_max: float, d_for_message: float) -> None:
        if self._monotone_f:
            return
        # g at all nodes up to a_max (and midpoints), cached for the largest range asked so far
        grid = np.union1d(self.r[self.r <= a_max], 0.5 * (self.r[1:] + self.r[:-1])[self.r[1:] <= a_max])
        grid = np.append(grid, a_max)
        g = self._g(grid)
        dg = np.diff(g)
        scale = max(float(np.max(np.abs(g))), 1e-300)
        bad = np.flatnonzero(dg < -1e-12 * scale)
        if bad.size:
            i = int(bad[0])
            raise OutsideTheoryError(
                f"depth={d_for_message!r} m: the transformed profile g(x) decreases at x="
                f"{grid[i]:.6g} m (g={g[i]:.6g} m, then {g[i + 1]:.6g} m), so beyond depth "
                f"{g[i]:.6g} m the contact is an annulus, outside the MDR. Smooth the measured "
                "profile or limit the load.")
