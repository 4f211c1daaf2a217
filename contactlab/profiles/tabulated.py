"""Measured (tabulated) profiles.

``interpolation="linear"`` (default) is the piecewise-linear interpolant of the table. Its MDR
transform is exact, a sum of truncated-cone transforms (theory §2):

    g(x) = x [ s_k π/2 - Σ_{j=1..k} (s_j - s_{j-1}) asin(r_j/x) ],   r_k <= x < r_{k+1}

(the node r_k = x itself is included, so g is continuous at the nodes)

and ``∫_0^a g = Σ_i s_i ∫_{r_i}^{min(r_{i+1},a)} sqrt(a²-r²) dr`` in closed form. Each evaluation
costs O(N) for N table points; nothing is precomputed for all nodes, so tables of 10^6 points work.

``interpolation="cubic"`` uses a C² cubic spline (scipy ``CubicSpline``, not-a-knot ends). Its
transform is set up once as node sums: the spline's slope written as jumps at the nodes, each
node contributing elementary terms (``Tabulated._cubic_sums``), O(nodes below x) per point.
Pieces between nearly coincident nodes (random spacing: 1e-15 of the radius apart at 10^6
points), whose cubic coefficient is data rounding divided by h³, are kept local: integrated over
the piece only instead of extrapolated over the table, where their huge jumps would cancel
(``Tabulated._setup_cubic_jumps``). Points whose sums still carry a rounding estimate above
:data:`CUBIC_SUM_RTOL` fall back to a Gauss-Legendre rule per table interval in θ (12 nodes,
error estimate from 8). Every sum over the nodes is grouped in fixed blocks
(:mod:`contactlab.numeric.fixed_sums`), so a point's value does not depend on the other points
of its call.

The two interpolants of the same table differ at the level of the linear interpolation error:
for a table sampled from a smooth profile the linear one is off by ~0.35 (Δr/a)² in force and
~2.4 (Δr/a)² in contact radius, the cubic one by ~1e-12 at 1000 points (tests/unit/profiles/test_transform.py).

Heights are taken relative to the table's first value (the datum of a measurement is arbitrary),
and a table starting at ``r0 > 0`` is extended flat to the axis. Contact radii must stay inside the
table (``max_radius`` = last radius).
"""
from __future__ import annotations

from pathlib import Path
from typing import Any, ClassVar

import numpy as np

from ..errors import OutsideTheoryError, ParameterError, TabulatedDataError
from ..numeric.fixed_sums import row_sums, weighted_row_sums
from ..params import Param, as_real
from ..symbolic.form import SympyForm
from .base import Profile

__all__ = ["Tabulated"]

_CHUNK = 2_000_000   # elements per dense (x, node) block
_GL_HI = np.polynomial.legendre.leggauss(12)
_GL_LO = np.polynomial.legendre.leggauss(8)
#: local corrections of cubic tables (tiny pieces): 2 points, error estimate from the midpoint
_GL_LOC_HI = np.polynomial.legendre.leggauss(2)
_GL_LOC_LO = np.polynomial.legendre.leggauss(1)
#: local pieces nearer x than this many piece widths are integrated in θ, farther ones by the
#: two-term Taylor form (relative error ~ (width / distance)² / 8 of a rounding-level term)
_LOCAL_NEAR = 300.0
#: tables up to this many points declare their nodes as breakpoints (quadratures split there)
BREAKPOINT_LIMIT = 2000
#: cubic tables: points whose closed-form node sum carries a worst-case rounding estimate (8 eps
#: times the sum of |terms|, pessimistic by 5-50x) above this fraction
#: of the value are recomputed by the per-interval Gauss rule
CUBIC_SUM_RTOL = 1e-6
#: cubic tables: pieces whose cubic coefficient d satisfies |d| r_max² > this times the largest
#: slope are local (see :meth:`Tabulated._setup_cubic_jumps`). On a uniform 10^6-point table
#: (rounding noise alone) |d| r_max² reaches ~300 times the slope, on a random one 1e14 times;
#: with 300, 29 % of a random 10^6-point table's pieces are local and its node sums are
#: accurate to ~5e-10 (rounding estimate < 4e-7; 1e3: 18 % local, 1.3e-9; 1e4: 6 %, 7e-9)
CUBIC_LOCAL_RATIO = 300.0


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
        Piecewise-linear (exact transform, default) or cubic spline.
    smoothing : None, "auto" or float
        Noisy data: replace the heights by a smoothing spline of the table (see
        :mod:`contactlab.profiles.smoothing`). ``"auto"`` picks the smoothing from the data
        (generalised cross-validation, or matched to ``noise`` when given); a float is the
        spline's dimensionless λ. :attr:`smoothing_report` says what it did, and the error
        estimates of every result include the uncertainty it leaves (noise and bias).
    noise : float, optional
        Standard deviation of the measurement noise of ``f``, m (used by ``smoothing="auto"``
        and by the error estimate).
    axis : {"even", "free"}
        The surface on the axis. ``"even"`` (default): smooth there, ``f'(0) = 0`` (the table's
        even extension ``f(-r) = f(r)``): the smoothing spline of ``smoothing=`` and the cubic
        spline of ``interpolation="cubic"`` are made even, so their pressure is finite on the
        axis. ``"free"``: keep the slope the data give on the axis (a measured cone or
        pointed tip; smoothing then has natural ends, the cubic spline not-a-knot ends). The
        linear interpolant keeps its first segment either way: if that segment is not flat the
        table is a cone tip, whose pressure is logarithmically infinite on the axis (said by a
        :class:`~contactlab.errors.ValidityWarning` when a peak pressure meets it).
    admissible : None or "nearest"
        ``"nearest"`` replaces the (smoothed) table by the nearest one whose linear
        interpolant has ``r f'(r)`` non-decreasing (slopes >= 0 and non-decreasing), so ``g`` is
        monotone at every load; :attr:`smoothing_report` gives the largest change. Without it, a
        table whose ``g`` decreases is reported (radius and depth) when a load reaches there.

    Raises
    ------
    TabulatedDataError
        Unsorted, duplicate, negative or non-finite radii; non-finite heights; length mismatch.
    ParameterError
        An invalid ``smoothing``, ``noise`` or ``admissible``.

    Examples
    --------
    >>> import numpy as np
    >>> r = np.linspace(0.0, 1e-3, 200)
    >>> f = r**2 / 0.02 + 5e-9 * np.random.default_rng(1).standard_normal(r.size)
    >>> tab = Tabulated(r, f, smoothing="auto", noise=5e-9)
    >>> tab.smoothing_report.method, tab.smoothing_report.rms_change < 1e-8
    ('noise', True)
    """

    name: ClassVar[str] = "tabulated"
    params: ClassVar[tuple[Param, ...]] = (
        Param("r", "r_i", "m", "nonnegative", "table radii"),
        Param("f", "f_i", "m", "real", "table heights"),
        Param("interpolation", "-", "-", "real", "interpolation"),
    )
    #: a scene's [profile] table of this type: keys besides the constructor's parameters, as
    #: ``"kind[:dimension[:domain]][|names]"`` (contactlab.scene.schema.key_from_text), and the
    #: key groups of which it gives exactly one (a CSV file, or the two columns inline)
    scene_keys: ClassVar[dict[str, str]] = {
        "file": "file", "r": "array:length", "f": "array:length",
        "interpolation": "choice|linear,cubic", "r_unit": "unit:length", "f_unit": "unit:length",
        "smoothing": "quantity:dimensionless:nonnegative|auto", "noise": "quantity:length",
        "admissible": "choice|nearest", "axis": "choice|even,free"}
    scene_one_of: ClassVar[tuple[tuple[str, ...], ...]] = (("file",), ("r", "f"))

    def __init__(self, r: Any, f: Any, interpolation: str = "linear", *,
                 smoothing: Any = None, noise: float | None = None,
                 admissible: str | None = None, axis: str = "even") -> None:
        if interpolation not in ("linear", "cubic"):
            raise ParameterError(f"interpolation={interpolation!r} is invalid: use 'linear' "
                                 "(exact transform) or 'cubic' (smooth spline).")
        if axis not in ("even", "free"):
            raise ParameterError(f"axis={axis!r} is invalid: use 'even' (a surface smooth on "
                                 "its axis, f'(0) = 0) or 'free' (keep the slope the data give "
                                 "there, e.g. a cone tip).")
        self.axis = axis
        if admissible not in (None, "nearest"):
            raise ParameterError(f"admissible={admissible!r} is invalid: use None (report a "
                                 "non-monotone g when a load reaches it) or 'nearest'.")
        if noise is not None:
            noise = as_real("noise", noise, "expected a number >= 0 (m)")
            if not np.isfinite(noise) or noise < 0:
                raise ParameterError(f"noise={noise!r} m is invalid: it must be finite and "
                                     ">= 0.")
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
            raise TabulatedDataError(f"r[0]={float(r_arr[0])!r} is invalid: radii must be >= 0 m.")
        steps = np.diff(r_arr)
        if np.any(steps == 0):
            i = int(np.argmax(steps == 0))
            raise TabulatedDataError(f"r[{i + 1}]={float(r_arr[i + 1])!r} duplicates r[{i}]: radii must "
                                     "be strictly increasing (remove or average duplicates).")
        if np.any(steps < 0):
            i = int(np.argmax(steps < 0))
            raise TabulatedDataError(
                f"r[{i + 1}]={float(r_arr[i + 1])!r} < r[{i}]={float(r_arr[i])!r}: radii must be "
                "strictly increasing (sort the table).")
        self.smoothing_report = None
        self._band = None
        if smoothing is not None or admissible is not None:
            f_arr = self._smooth(r_arr, f_arr, smoothing, noise, admissible, axis)
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
        # g is non-decreasing when r f'(r) is (g'(x) = ∫_0^{π/2} (r f')'(x sinθ) dθ): for the
        # linear interpolant s_0 >= 0 and no negative slope jump. A monotone f is NOT enough (a
        # slope that drops, e.g. a ramp then a plateau, makes g decrease: a ring contact).
        # Slope jumps within the rounding of the slopes count as 0 here: a table sampled from a
        # convex surface at nodes 1e-15 of its radius apart (random spacing, 10^6 points) has
        # slopes rounded by eps |f| / Δr, far beyond their true jumps; the exact first-crossing
        # solve it would otherwise take costs O(N²) (hours at 10^6 points) for a dip of g
        # below the rounding of the data.
        ds_tol = self._slope_rounding(r_arr, f_rel, float(np.max(np.abs(f_arr))))
        self._monotone_f = (bool(self._slopes[0] >= -ds_tol[0]
                                 and np.all(self._dslope >= -(ds_tol[1:] + ds_tol[:-1])))
                            if interpolation == "linear" else None)
        self._verified_upto = 0.0
        self._spline = None
        if interpolation == "cubic":
            from scipy.interpolate import CubicSpline
            # even: clamped f'(0) = 0 on the axis (the even extension of the table), so the
            # surface has no cone tip there; free: not-a-knot at both ends
            self._spline = CubicSpline(r_arr, f_rel, bc_type=(((1, 0.0), "not-a-knot")
                                                              if axis == "even" else "not-a-knot"))
            self._spline_d = self._spline.derivative()
            probe = np.linspace(0, r_arr[-1], 8 * r_arr.size)
            fp = self._spline_d(probe)
            rfp = probe * fp                                # r f'(r) non-decreasing
            # up to the rounding of the spline's slopes: eps |f| / h from the data, amplified by
            # the spline's solve and spread over a few neighbouring intervals (its influence
            # decays by 2 - sqrt(3) per interval); a random 10^6-point table of a convex profile
            # (nodes 5e-15 m apart) wiggles by up to 175 x 8 eps |f| / h here
            tol = self._spline_rounding(r_arr, float(np.max(np.abs(f_arr))), probe)
            self._monotone_f = bool(np.all(fp >= -tol)
                                    and np.all(np.diff(rfp) >= -(probe[1:] * tol[1:]
                                                                 + probe[:-1] * tol[:-1])))
            # transform once: the spline's slope as node jumps (see _setup_cubic_jumps)
            self._setup_cubic_jumps(r_arr)
        self._node_g: np.ndarray | None = None

    def _setup_cubic_jumps(self, r: np.ndarray) -> None:
        """Node-jump form of the spline's slope, with clustered pieces kept local.

        ``f'(r) = P_0(r) + Σ_j ΔP_j(r) [r > r_j]``, ``P_k`` the slope polynomial of piece k and
        ``ΔP_j = α_j + β_j (r - r_j) + γ_j (r - r_j)²`` its change at node j. For a C² spline only
        ``γ_j = 3 Δd_j`` is nonzero in exact arithmetic; the rounding-level α, β are kept so the sum
        telescopes to every piece exactly (without them the node terms, extrapolated over the whole
        table, drift by ~1e-9 at 10^4 points).

        Pieces whose cubic coefficient is huge (:data:`CUBIC_LOCAL_RATIO`: nearly coincident
        nodes, whose third derivative is rounding noise of the data divided by h³) are *local*:
        their jumps, extrapolated over the whole table, would be ~1e13 times the slope and
        cancel between neighbours, leaving rounding errors of 1e-7 of g in every sum (random
        10^6-point tables). A run of local pieces is instead represented by the regular piece
        before it, continued across the run (one merged, modest jump at the run's end), plus a
        local correction ``D_k = P_k - P_prev`` integrated over each local piece only
        (:meth:`_cubic_local`)."""
        c = self._spline.c
        f_scale = max(float(np.max(np.abs(c[2]))), np.finfo(float).tiny)
        local = np.abs(c[0]) * float(r[-1]) ** 2 > CUBIC_LOCAL_RATIO * f_scale
        local[0] = False                    # piece 0 is the base polynomial
        reg = np.flatnonzero(~local)

        def jumps(prev: np.ndarray, k: np.ndarray) -> np.ndarray:
            """(α, β, γ) of P_k - P_prev at r_k, in powers of (r - r_k)."""
            H = r[k] - r[prev]
            return np.stack([c[2, k] - (c[2, prev] + (2.0 * c[1, prev] + 3.0 * c[0, prev] * H) * H),
                             2.0 * c[1, k] - (2.0 * c[1, prev] + 6.0 * c[0, prev] * H),
                             3.0 * (c[0, k] - c[0, prev])])

        self._cubic_base = (float(c[2, 0]), float(c[1, 0]), float(c[0, 0]))
        prev, nxt = reg[:-1], reg[1:]
        jmp = jumps(prev, nxt)
        keep = np.any(jmp != 0, axis=0)
        self._cubic_nodes = np.ascontiguousarray(r[nxt][keep])
        self._cubic_jumps = np.ascontiguousarray(jmp[:, keep])
        loc = np.flatnonzero(local)
        base = reg[np.searchsorted(reg, loc) - 1]
        # per local piece: its ends and the coefficients of D_k in powers of (r - r_k)
        self._cubic_local_lo = np.ascontiguousarray(r[loc])
        self._cubic_local_hi = np.ascontiguousarray(r[loc + 1])
        self._cubic_local_d = d = np.ascontiguousarray(jumps(base, loc))
        # moments of D over each piece about its midpoint, and the bound of the next Taylor term
        h = self._cubic_local_hi - self._cubic_local_lo
        mu0 = h * (d[0] + h * (0.5 * d[1] + h * d[2] / 3.0))
        mu1 = h ** 3 * (d[1] + h * d[2]) / 12.0
        q2 = (np.abs(d[0]) + h * (np.abs(d[1]) + h * np.abs(d[2]))) * h ** 3 / 24.0
        nu0 = h * (d[1] + h * d[2])
        nu1 = h ** 3 * d[2] / 6.0
        self._cubic_local_mom = np.ascontiguousarray(np.stack(
            [0.5 * (self._cubic_local_lo + self._cubic_local_hi), mu0, mu1, q2, nu0, nu1]))

    def _slope_rounding(self, r: np.ndarray, f: np.ndarray, f_scale: float) -> np.ndarray:
        """Rounding bound of each segment's slope, 1: ``4 eps (|f_i| + |f_{i+1}| + max|f| +
        |s_i| (r_i + r_{i+1})) / Δr_i`` (the heights as given, their datum shift and the radii
        each rounded by eps)."""
        eps = np.finfo(float).eps
        return 4.0 * eps * (np.abs(f[:-1]) + np.abs(f[1:]) + f_scale + np.abs(self._slopes)
                            * (r[:-1] + r[1:])) / np.diff(r)

    @staticmethod
    def _spline_rounding(r: np.ndarray, f_scale: float, x: np.ndarray) -> np.ndarray:
        """Rounding bound of the cubic spline's slope at ``x``, 1: ``4096 eps max|f| / h``,
        ``h`` the narrowest interval within 8 of the one holding ``x`` (2-sqrt(3))^8 = 3e-5)."""
        from scipy.ndimage import minimum_filter1d
        h = minimum_filter1d(np.diff(r), size=17, mode="nearest")
        k = np.clip(np.searchsorted(r, x, side="right") - 1, 0, h.size - 1)
        return 4096.0 * np.finfo(float).eps * f_scale / h[k]

    def _smooth(self, r: np.ndarray, f: np.ndarray, smoothing: Any, noise: float | None,
                admissible: str | None, axis: str = "even") -> np.ndarray:
        """Smoothed and/or projected heights; sets :attr:`smoothing_report` and the error band."""
        from dataclasses import replace

        from .smoothing import SmoothingReport, nearest_admissible, slope_violations, smooth_table
        parts = None
        if smoothing is not None:
            f_new, report, parts = smooth_table(r, f, smoothing, noise, axis)
        else:
            f_new = f.copy()
            report = SmoothingReport("admissible", 0.0, 0.0, 0.0, float(noise or 0.0), r.size)
        project = admissible == "nearest"
        if not project and smoothing == "auto" and slope_violations(r, f_new).size:
            # a projection smaller than the noise is not a change the data can tell apart
            f_adm = nearest_admissible(r, f_new)
            project = bool(np.max(np.abs(f_adm - f_new)) <= 3.0 * report.noise)
        if project:
            f_adm = nearest_admissible(r, f_new)
            report = replace(report, admissible_change=float(np.max(np.abs(f_adm - f_new))))
            if parts is not None:
                parts["bias"] = parts["bias"] + (f_adm - f_new)
            else:
                parts = {"bias": f_adm - f_new, "spread": None}
            f_new = f_adm
            change = f_new - f
            report = replace(report, max_change=float(np.max(np.abs(change))),
                             rms_change=float(np.sqrt(np.mean(change ** 2))))
        self.smoothing_report = report
        self._band_parts = (r, parts)
        return f_new

    def _smoothing_band(self) -> tuple[np.ndarray, np.ndarray, np.ndarray] | None:
        """``(x grid, |δg|, |δ∫g|)``: error bands the smoothing leaves (bias + 3 σ of the
        re-smoothed noise copies), on 65 radii, as envelopes (computed on first use)."""
        if self._band is not None or getattr(self, "_band_parts", None) is None:
            return self._band
        r, parts = self._band_parts
        grid = np.linspace(0.0, float(self.r[-1]), 65)

        def transforms(v: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
            t = Tabulated(r, v)
            return np.abs(t._g_closed_form(grid)), np.abs(t._g_integral_closed_form(grid))

        bg, bi = transforms(parts["bias"])
        sg = np.zeros(grid.size)
        si = np.zeros(grid.size)
        if parts.get("spread") is not None:
            # signed copies: the RMS over the probes is the standard deviation
            def signed(v: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
                t = Tabulated(r, v)
                return t._g_closed_form(grid), t._g_integral_closed_form(grid)
            cols = [signed(parts["spread"][:, k]) for k in range(parts["spread"].shape[1])]
            sg = np.sqrt(np.mean([c[0] ** 2 for c in cols], axis=0))
            si = np.sqrt(np.mean([c[1] ** 2 for c in cols], axis=0))
        eg, ei = bg + 3.0 * sg, bi + 3.0 * si
        # envelope: the larger of the neighbouring grid values, so interpolation never dips
        eg = np.maximum(eg, np.maximum(np.r_[eg[1:], eg[-1]], np.r_[eg[0], eg[:-1]]))
        ei = np.maximum(ei, np.maximum(np.r_[ei[1:], ei[-1]], np.r_[ei[0], ei[:-1]]))
        self._band = (grid, eg, ei)
        return self._band

    def _g_with_error(self, xa: np.ndarray, rtol: float | None = None
                      ) -> tuple[np.ndarray, np.ndarray]:
        if self._spline is not None and self.g_route == "closed_form":
            val, err, _ = self._cubic_value(xa, "g")
        else:
            val, err = super()._g_with_error(xa, rtol)
        band = self._smoothing_band()
        if band is not None:
            err = err + np.interp(xa, band[0], band[1])
        return val, err

    @classmethod
    def from_csv(cls, path: str | Path, interpolation: str = "linear", *,
                 r_unit: str | None = None, f_unit: str | None = None,
                 delimiter: str | None = None, smoothing: Any = None,
                 noise: float | None = None, admissible: str | None = None,
                 axis: str = "even", quote_contents: bool = True) -> "Tabulated":
        """Read a table: two columns r, f (further columns are ignored).

        Parameters
        ----------
        path : path-like
            CSV file. An optional header names the columns with their units, in the unit
            grammar of scene files: ``r [mm],f [um]`` (also ``r (mm)``, ``r_mm``, ``r/mm``; an
            unknown unit is an error). Lines starting with ``#`` are comments; columns are
            separated by ``,``, ``;`` (if the file holds more of them than commas), tabs or
            whitespace; a UTF-8 byte-order mark is skipped.
        interpolation : {"linear", "cubic"}
            See :class:`Tabulated`.
        r_unit, f_unit : str, optional
            Units of the columns when the header gives none (``"mm"``, ``"um"``, ``"nm"``);
            default m. A unit in the header and a different one here is an error.
        delimiter : str, optional
            Column separator (default: detected).
        smoothing, noise, admissible, axis
            See :class:`Tabulated` (``noise`` in m, whatever the file's units).
        quote_contents : bool
            Quote the file in error messages (the bad cell, the header). False names rows and
            columns by position only (scene files: a file is never shown).

        Raises
        ------
        TabulatedDataError
            Unreadable file, fewer than two columns, a cell that is not a number, conflicting
            units, and every check of :class:`Tabulated`.
        UnitError
            A unit that is unknown or not a length.

        Examples
        --------
        >>> import pathlib, tempfile
        >>> p = pathlib.Path(tempfile.mkdtemp()) / "cup.csv"
        >>> _ = p.write_text("r [mm],f [um]\\n0,0\\n1,25\\n2,100\\n")
        >>> Tabulated.from_csv(p).f * 1e6
        array([  0.,  25., 100.])
        """
        from ..numeric.tables import read_columns
        units = {k: v for k, v in ((0, r_unit), (1, f_unit)) if v is not None}
        names, cols = read_columns(path, names=("r", "f"), units=units, delimiter=delimiter,
                                   min_columns=2, quote=bool(quote_contents),
                                   dimension=("length", "length"))
        for extra in names[2:]:
            cols.pop(extra, None)
        r_name, f_name = names[0], names[1]
        return cls(cols[r_name], cols[f_name], interpolation=interpolation, smoothing=smoothing,
                   noise=noise, admissible=admissible, axis=axis)

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
            raise TabulatedDataError(f"{name}[{i}]={float(arr[i])!r} is invalid: table values must be "
                                     "finite (drop or fill missing points).")
        return arr

    # identity: arrays compare by value
    def _param_values(self) -> tuple[Any, ...]:
        # (the axis condition changes the cubic spline only)
        return (self.r.tobytes(), self.f.tobytes(), self.interpolation,
                *((self.axis,) if self.interpolation == "cubic" else ()))

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

    # ------------------------------------------------------------------ symbolic
    def _sympy_form(self) -> SympyForm:
        return SympyForm(reason="a tabulated (measured) profile has no symbolic form; use the "
                                "numeric routes (contact.normal(...))")

    # ------------------------------------------------------------------ geometry
    def _guard(self, r: np.ndarray, name: str) -> None:
        if np.any(r > self.r[-1]):
            raise OutsideTheoryError(
                f"{name}={float(np.max(r))!r} m lies beyond the table (last radius {self.r[-1]!r} m): "
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
        return ("closed_form", "quadrature")

    def _g_closed_form(self, x: np.ndarray) -> np.ndarray:
        """Exact transform of the interpolant (sum of arcsines, or of the spline's node terms),
        chunked."""
        if self._spline is not None:
            return self._cubic_value(x, "g")[0]
        return self._arcsine_sums(x, with_slope=False)[0]

    def _cubic_value(self, x: np.ndarray, kind: str, with_slope: bool = False
                     ) -> tuple[np.ndarray, np.ndarray, np.ndarray | None]:
        """``(value, error)`` of the spline's transform (``kind`` "g" or "int"): the closed-form
        node sums, and the per-interval Gauss rule at the points where their rounding estimate
        exceeds :data:`CUBIC_SUM_RTOL` (tables with nearly coincident nodes, whose spline has
        huge third-derivative jumps that cancel in the sums)."""
        val, err, slope = self._cubic_sums(x, kind, with_slope)
        bad = err > CUBIC_SUM_RTOL * np.abs(val)
        if np.any(bad):
            xb = np.asarray(x, dtype=float)[bad]
            weight, p = {"g": (0, 1), "int": (2, 2), "xg": ("xg", 3)}[kind]
            v, e = self._spline_theta_sum(xb, weight)
            val[bad], err[bad] = v * xb**p, e * xb**p
        return val, err, slope

    def _g_and_slope(self, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """``(g, g')`` of the interpolant in one pass over the nodes."""
        if self._spline is not None:
            g, _, gp = self._cubic_value(x, "g", with_slope=True)
            return g, gp
        return self._arcsine_sums(x, with_slope=True)

    def _cubic_sums(self, x: np.ndarray, kind: str, with_slope: bool = False
                    ) -> tuple[np.ndarray, np.ndarray, np.ndarray | None]:
        """Closed-form transform of the cubic spline: ``(value, rounding estimate, g')``.

        With ``f'(r) = b0 + 2c0 r + 3d0 r² + Σ_j [α_j + β_j (r - r_j) + J_j (r - r_j)²]_+`` (set
        up once; α, β are rounding-level, their terms ``α acos + β (sqrt - r_j acos)`` and
        ``α K0 + β (s³/3 - r_j K0)``, ``K0 = (a²θ - r_j s)/2``, are included below):

        * ``kind="g"``: ``g = x [b0 π/2 + 2c0 x + 3d0 πx²/4 + Σ_{r_j<x} J_j S_j]``,
          ``S_j = (x²/2 + r_j²) acos(r_j/x) - 1.5 r_j sqrt(x² - r_j²)``, and
          ``g' = g/x + x [2c0 + 3d0 πx/2 + Σ J_j (x acos(r_j/x) - (r_j/x) sqrt(x² - r_j²))]``;
        * ``kind="int"``: ``∫_0^a g = b0 πa²/4 + 2c0 a³/3 + 3d0 πa⁴/16 + Σ_{r_j<a} J_j T_j``,
          ``T_j = θ (a⁴/8 + a² r_j²/2) - r_j s (13a²/24 + r_j²/12)``, ``θ = acos(r_j/a)``,
          ``s = sqrt(a² - r_j²)``.

        * ``kind="xg"``: ``∫_0^a x g dx`` with the node integrals of
          :meth:`_xg_integral_closed_form`.

        O(nodes below x) per point, no quadrature; the rounding estimate is 8 eps times the sum
        of the absolute values of every part of every term before they cancel (conservative also
        for nearly coincident nodes, whose huge jumps cancel between neighbours and inside each
        term as r_j -> x).
        """
        self._guard(x, "x" if kind == "g" else "a")
        x = np.asarray(x, dtype=float)
        flat = x.ravel()
        out = np.zeros(flat.size)
        err = np.zeros(flat.size)
        slope = np.zeros(flat.size) if with_slope else None
        b0, c0, d0 = self._cubic_base
        nodes_all, jump_all = self._cubic_nodes, self._cubic_jumps
        total = nodes_all.size
        chunk = max(1, _CHUNK // max(total, 1))
        eps = np.finfo(float).eps
        for start in range(0, flat.size, chunk):
            xs = flat[start:start + chunk]
            pos = xs > 0
            if not np.any(pos):
                continue
            xv = xs[pos]
            xp = xv[:, None]
            # the nodes below the chunk's largest point; row_sums groups every point's sums the
            # same whatever else is in its chunk (fixed_sums)
            m = int(np.searchsorted(nodes_all, xv.max(), side="left"))
            nodes = nodes_all[:m][None, :]
            al, be, jmp = (jump_all[k, :m][None, :] for k in range(3))
            below = nodes < xp
            root = np.sqrt(np.maximum((xp - nodes) * (xp + nodes), 0.0))
            theta = np.arctan2(root, nodes)                       # acos(r_j/x), accurate near x

            # each node term is a difference of parts that cancel as r_j -> x (the J term by
            # (root/x)^2 and more): its rounding is eps times the parts' magnitudes, not its value.
            # g and ∫g: the node terms are θ, root (and root³) times per-node coefficients and
            # powers of x, so their sums (and the parts' magnitudes) are contractions with
            # coefficient columns set up once (θ = root = 0 at nodes >= x: no mask needed)
            if kind in ("g", "int"):
                c_th, c_rt, c_r3 = self._cubic_columns(kind)
                # one padded product buffer and one blocked sum per term array (weighted_row_sums)
                T = weighted_row_sums(theta, c_th, total)
                S = weighted_row_sums(root, c_rt if kind == "int" or with_slope else c_rt[:2],
                                      total)
                xv2 = xv * xv
            loc_val, loc_mag, loc_slope = self._cubic_local(xv, kind, with_slope)
            if kind == "g":
                total_nodes = T[0] + 0.5 * xv2 * T[1] + S[0]
                mag_nodes = T[2] + 0.5 * xv2 * T[3] + S[1]
                head = (b0 * 0.5 * np.pi, 2.0 * c0 * xv, 0.75 * np.pi * d0 * xv2)
                total_g = head[0] + head[1] + head[2] + total_nodes + loc_val
                size = abs(head[0]) + np.abs(head[1]) + np.abs(head[2]) + mag_nodes
                out[start:start + chunk][pos] = xv * total_g
                err[start:start + chunk][pos] = 8 * eps * xv * size + xv * loc_mag
                if with_slope:
                    # (the rounding-level α term, a cusp, is left out of the Newton slope)
                    dnodes = (S[2] - S[3]) / xv + xv * T[1]
                    slope[start:start + chunk][pos] = total_g + xv * (
                        2.0 * c0 + 1.5 * np.pi * d0 * xv + dnodes + loc_slope)
                continue
            if kind == "int":
                R3 = weighted_row_sums(root ** 3 / 3.0, c_r3, total)
                c13 = 13.0 / 24.0 * xv2
                out[start:start + chunk][pos] = (
                    0.25 * np.pi * b0 * xv2 + 2.0 / 3.0 * c0 * xv2 * xv
                    + 0.1875 * np.pi * d0 * xv2 * xv2
                    + 0.5 * xv2 * T[0] + 0.125 * xv2 * xv2 * T[1] + S[0]
                    - c13 * S[1] + R3[0] + xv2 * loc_val)
                err[start:start + chunk][pos] = 8 * eps * (
                    np.abs(0.25 * np.pi * b0 * xv2) + np.abs(2.0 / 3.0 * c0 * xv2 * xv)
                    + np.abs(0.1875 * np.pi * d0 * xv2 * xv2)
                    + 0.5 * xv2 * T[2] + 0.125 * xv2 * xv2 * T[3] + S[2]
                    + c13 * S[3] + R3[1]) + xv2 * loc_mag
                continue
            # "xg": ∫_0^a x g dx
            P2, Q2, P4, (m2, mq, m4) = self._node_moments(xp, nodes)
            b2 = nodes * nodes
            terms = np.where(below, al * P2 + be * (Q2 - nodes * P2)
                             + jmp * (0.5 * P4 + b2 * P2 - 1.5 * nodes * Q2), 0.0)
            mags = np.where(below, np.abs(al) * m2 + np.abs(be) * (mq + nodes * m2)
                            + np.abs(jmp) * (0.5 * m4 + b2 * m2 + 1.5 * nodes * mq), 0.0)
            av2 = xv * xv
            head = (np.pi / 6.0 * b0 * av2 * xv, 0.5 * c0 * av2 * av2,
                    0.15 * np.pi * d0 * av2 * av2 * xv)
            out[start:start + chunk][pos] = (head[0] + head[1] + head[2]
                                             + row_sums(terms, total) + av2 * xv * loc_val)
            err[start:start + chunk][pos] = 8 * eps * (
                np.abs(head[0]) + np.abs(head[1]) + np.abs(head[2]) + row_sums(mags, total)) \
                + av2 * xv * loc_mag
        return (out.reshape(x.shape), err.reshape(x.shape),
                None if slope is None else slope.reshape(x.shape))

    def _cubic_local(self, xv: np.ndarray, kind: str, with_slope: bool
                     ) -> tuple[np.ndarray, np.ndarray, np.ndarray | None]:
        """Local corrections of :meth:`_cubic_sums` at ``xv > 0``: ``∫ D_k(r) w(r, x) dr`` over
        every local piece k below x (``D_k = P_k - P_prev``, see :meth:`_setup_cubic_jumps`), in
        the units of the node sums of ``kind`` (``w = 1/s``; ``s/x²``; ``(x s + r² L)/(2x³)``,
        ``s = sqrt(x² - r²)``, ``L = acosh(x/r)``): ``(value, error, slope term)``, the slope
        term ``∫ D'(x sinθ) sinθ dθ`` (``kind="g"``: the derivative at fixed θ-limits; the
        moving limits give cusp terms that cancel the merged jumps' α cusps, which the Newton
        slope of :meth:`_cubic_sums` leaves out too).

        The pieces are tiny (nearly coincident nodes). A piece more than
        :data:`_LOCAL_NEAR` widths below x contributes ``w(r_m) μ0 + w'(r_m) μ1`` (``r_m`` its
        midpoint, ``μ0 = ∫D``, ``μ1 = ∫D (r - r_m)``; ``ν0, ν1``
        likewise of ``D'`` for the slope term; set up once), with the next Taylor term as
        its error; a piece nearer x (or holding it) is integrated in θ by a 2-point Gauss rule,
        its error the difference to the midpoint rule. Both add 8 eps times the magnitudes.
        The corrections are at the rounding level of the data (~1e-10 of g); they make the sum
        the exact transform of the spline all the same."""
        rows = xv.size
        lo_all = self._cubic_local_lo
        total = lo_all.size
        zero = np.zeros(rows)
        m = int(np.searchsorted(lo_all, xv.max(), side="left")) if total else 0
        if m == 0:
            return zero, zero, (zero if with_slope else None)
        eps = np.finfo(float).eps
        xp = xv[:, None]
        lo, hi = lo_all[None, :m], self._cubic_local_hi[None, :m]
        rm, mu0, mu1, q2 = (self._cubic_local_mom[k, None, :m] for k in range(4))
        below = lo < xp
        near = below & ((xp - hi) < _LOCAL_NEAR * (hi - lo))
        far = below & ~near
        s = np.sqrt(np.where(far, (xp - rm) * (xp + rm), 1.0))
        slope = None
        if kind == "g":
            s3 = s * s * s
            vals = mu0 / s + mu1 * rm / s3
            mags = np.abs(mu0) / s + np.abs(mu1) * rm / s3
            w2 = (1.0 + 3.0 * rm * rm / (s * s)) / s3
            if with_slope:
                nu0, nu1 = (self._cubic_local_mom[k, None, :m] for k in (4, 5))
                dvals = (nu0 * rm / s + nu1 * xp * xp / s3) / xp
        elif kind == "int":
            vals = (mu0 * s - mu1 * rm / s) / (xp * xp)
            mags = (np.abs(mu0) * s + np.abs(mu1) * rm / s) / (xp * xp)
            w2 = xp / (s * s * s)
        else:
            L = np.arccosh(np.maximum(xp / np.where(far, rm, xp), 1.0))
            x3 = xp * xp * xp
            w0 = 0.5 * (xp * s + rm * rm * L)
            w1 = rm * L - xp * rm / s
            vals = (mu0 * w0 + mu1 * w1) / x3
            mags = (np.abs(mu0) * w0 + np.abs(mu1) * np.abs(w1)) / x3
            w2 = (L + xp / s + x3 / (s * s * s)) / x3
        vals = np.where(far, vals, 0.0)
        errs = np.where(far, q2 * w2 + 8 * eps * mags, 0.0)
        if with_slope:
            dvals = np.where(far, dvals, 0.0)
        ri, ki = np.nonzero(near)
        if ri.size:
            nv, ne, nd = self._cubic_local_gauss(xv[ri], ki, kind, with_slope)
            vals[ri, ki], errs[ri, ki] = nv, ne
            if with_slope:
                dvals[ri, ki] = nd
        if with_slope:
            slope = row_sums(dvals, total)
        return row_sums(vals, total), row_sums(errs, total), slope

    def _cubic_local_gauss(self, x: np.ndarray, k: np.ndarray, kind: str, with_slope: bool
                           ) -> tuple[np.ndarray, np.ndarray, np.ndarray | None]:
        """:meth:`_cubic_local` for local pieces ``k`` near ``x`` (1-D, paired): a 2-point Gauss
        rule in θ over the piece's part below x, error from the midpoint rule."""
        lo, hi = self._cubic_local_lo[k], self._cubic_local_hi[k]
        d0, d1, d2 = (self._cubic_local_d[j, k][:, None] for j in range(3))
        xc = x[:, None]
        th_lo = np.arcsin(np.minimum(lo / x, 1.0))[:, None]
        half = 0.5 * (np.arcsin(np.minimum(hi / x, 1.0))[:, None] - th_lo)
        res = []
        for u, wts in (_GL_LOC_HI, _GL_LOC_LO):
            dth = half * (u + 1.0)
            th = th_lo + dth
            # r - r_k = x (sinθ - sinθ_k), without cancelling
            t = 2.0 * xc * np.sin(0.5 * dth) * np.cos(th_lo + 0.5 * dth)
            D = d0 + t * (d1 + t * d2)
            if kind == "g":
                w = np.ones_like(th)
            elif kind == "int":
                w = np.cos(th) ** 2
            else:
                co, si = np.cos(th), np.sin(th)
                w = 0.5 * co * (co + si * si * np.arcsinh(co / si))
            res.append(np.sum(D * w * wts, axis=-1) * half[:, 0])
            if len(res) == 1:
                mag = np.sum(np.abs(D * w) * wts, axis=-1) * half[:, 0]
                dv = (np.sum((d1 + 2.0 * d2 * t) * np.sin(th) * wts, axis=-1) * half[:, 0]
                      if with_slope else None)
        err = np.abs(res[0] - res[1]) + 8 * np.finfo(float).eps * mag
        return res[0], err, dv

    def _cubic_columns(self, kind: str) -> tuple[np.ndarray, np.ndarray, np.ndarray | None]:
        """Per-node coefficient columns of the node sums of :meth:`_cubic_sums` (set up once).

        ``kind="g"``: θ-columns ``[α - bβ + b²J, J, |α| + b|β| + b²|J|, |J|]``, root-columns
        ``[β - 1.5bJ, |β| + 1.5b|J|, β, bJ]``; ``kind="int"``: θ-columns as for g, root-columns
        ``[-bα/2 + b²β/2 - b³J/12, bJ, b|α|/2 + b²|β|/2 + b³|J|/12, b|J|]``, root³/3-columns
        ``[β, |β|]`` (b = r_j; the signed columns give the value, the absolute ones the parts'
        magnitudes for the rounding estimate). Each is returned as a contiguous (columns, nodes)
        array, one row per column.
        """
        cache = self.__dict__.setdefault("_cubic_cols", {})
        if kind not in cache:
            b = self._cubic_nodes
            al, be, J = self._cubic_jumps
            aa, ab, aJ = np.abs(al), np.abs(be), np.abs(J)
            th = np.stack([al - b * be + b * b * J, J, aa + b * ab + b * b * aJ, aJ], axis=1)
            if kind == "g":
                rt = np.stack([be - 1.5 * b * J, ab + 1.5 * b * aJ, be, b * J], axis=1)
                r3 = None
            else:
                rt = np.stack([-0.5 * b * al + 0.5 * b * b * be - b**3 * J / 12.0, b * J,
                               0.5 * b * aa + 0.5 * b * b * ab + b**3 * aJ / 12.0, b * aJ], axis=1)
                r3 = np.stack([be, ab], axis=1)
            cache[kind] = tuple(None if v is None else np.ascontiguousarray(v.T)
                                for v in (th, rt, r3))
        return cache[kind]

    def _arcsine_sums(self, x: np.ndarray, with_slope: bool
                      ) -> tuple[np.ndarray, np.ndarray | None]:
        """g(x) and, if asked, g'(x) of the linear interpolant in one pass over the nodes.

        ``g = x [s_k π/2 − Σ Δs_j asin(r_j/x)]`` and
        ``g' = s_k π/2 − Σ Δs_j [asin(r_j/x) − r_j/sqrt(x² − r_j²)]`` (nodes r_j <= x; g' is
        infinite exactly at a node with a slope jump, the square-root cusp).
        """
        self._guard(x, "x")
        x = np.asarray(x, dtype=float)
        flat = x.ravel()
        out = np.zeros(flat.size)
        slope = np.zeros(flat.size) if with_slope else None
        # only nodes with a slope jump contribute, and only those below the largest x
        jump = self._dslope != 0
        nodes_all = self.r[1:-1][jump]
        ds_all = self._dslope[jump]
        chunk = max(1, _CHUNK // max(nodes_all.size, 1))
        k_all = np.clip(np.searchsorted(self.r, flat, side="right") - 1, 0, self._slopes.size - 1)
        for start in range(0, flat.size, chunk):
            xs = flat[start:start + chunk]
            pos = xs > 0
            if not np.any(pos):
                continue
            xp = xs[pos][:, None]
            m = int(np.searchsorted(nodes_all, xp.max(), side="right"))
            nodes, ds = nodes_all[:m], ds_all[:m]
            below = nodes[None, :] <= xp
            # nodes above x give 1 (masked below); dividing by max(x, node) keeps a tiny x
            # (radius floors of 1e-300) from overflowing node / x
            q = nodes[None, :] / np.maximum(xp, nodes[None, :])
            # a node at x itself contributes asin(1) (x exactly on a node: k includes its slope)
            asin_sum = row_sums(np.where(below, ds[None, :] * np.arcsin(q), 0.0), nodes_all.size)
            base = 0.5 * np.pi * self._slopes[k_all[start:start + chunk][pos]] - asin_sum
            out[start:start + chunk][pos] = xs[pos] * base
            if with_slope:
                with np.errstate(divide="ignore", invalid="ignore"):
                    cusp = np.where(below, ds[None, :] * nodes[None, :]
                                    / np.sqrt((xp - nodes[None, :]) * (xp + nodes[None, :])), 0.0)
                slope[start:start + chunk][pos] = base + row_sums(cusp, nodes_all.size)
        return out.reshape(x.shape), None if slope is None else slope.reshape(x.shape)

    # ------------------------------------------------------------------ cubic: per-interval Gauss
    def _spline_theta_sum(self, x: np.ndarray, weight_power: int | str
                          ) -> tuple[np.ndarray, np.ndarray]:
        """``∫_0^{π/2} f'(x sinθ) w(θ) dθ`` for the spline, one Gauss-Legendre rule per table
        interval in θ (the integrand is analytic inside each interval, so 12 nodes reach rounding
        level; the 8-node rule gives the error estimate).

        ``w = cos^p θ`` for ``weight_power = p`` (``g/x``: p = 0, ``∫g / a²``: p = 2), or
        ``w = cosθ (cosθ + sin²θ asinh(cotθ))/2`` for ``"xg"`` (``∫_0^a x g dx / a³``, from
        ``∫_0^a x g = ∫_0^a f'(r) ∫_r^a x²/sqrt(x² - r²) dx dr``)."""
        flat = np.asarray(x, dtype=float).ravel()
        val = np.zeros(flat.size)
        err = np.zeros(flat.size)
        lo_n, hi_n = self.r[:-1], self.r[1:]
        chunk = max(1, _CHUNK // (lo_n.size * _GL_HI[0].size))
        for start in range(0, flat.size, chunk):
            xs = flat[start:start + chunk]
            pos = xs > 0
            if not np.any(pos):
                continue
            xp = xs[pos][:, None]
            # min(node / x, 1) without overflow for tiny x (node / max(x, node))
            t_lo = np.arcsin(lo_n[None, :] / np.maximum(xp, lo_n[None, :]))
            t_hi = np.arcsin(hi_n[None, :] / np.maximum(xp, hi_n[None, :]))
            half = 0.5 * (t_hi - t_lo)
            mid = 0.5 * (t_hi + t_lo)
            sums = []
            for nodes, weights in (_GL_HI, _GL_LO):
                th = mid[..., None] + half[..., None] * nodes
                vals = self._spline_d(np.minimum(xp[..., None] * np.sin(th), self.r[-1]))
                if weight_power == "xg":
                    co, si = np.cos(th), np.sin(th)
                    vals = vals * 0.5 * co * (co + si * si * np.arcsinh(co / si))
                elif weight_power:
                    vals = vals * np.cos(th) ** weight_power
                # plain sums (not BLAS): a point's rounding does not depend on its batch
                sums.append((np.sum(vals * weights, axis=-1) * half).sum(axis=1))
            val[start:start + chunk][pos] = sums[0]
            err[start:start + chunk][pos] = np.abs(sums[0] - sums[1])
        return val.reshape(np.shape(x)), err.reshape(np.shape(x))

    def _g_quadrature(self, xa: np.ndarray, rtol: float | None = None
                      ) -> tuple[np.ndarray, np.ndarray]:
        if self._spline is None:
            return super()._g_quadrature(xa, rtol)
        self._guard(np.asarray(xa), "x")
        v, e = self._spline_theta_sum(xa, 0)
        return v * xa, e * xa

    def _g_integral_quadrature(self, a: np.ndarray, rtol: float | None = None
                               ) -> tuple[np.ndarray, np.ndarray]:
        if self._spline is None:
            return super()._g_integral_quadrature(a, rtol)
        self._guard(np.asarray(a), "a")
        v, e = self._spline_theta_sum(a, 2)
        return v * a**2, e * a**2

    def _g_integral_closed_form(self, a: np.ndarray) -> np.ndarray:
        if self._spline is not None:
            return self._cubic_value(a, "int")[0]
        self._guard(a, "a")
        a = np.asarray(a, dtype=float)
        flat = a.ravel()
        out = np.zeros(flat.size)
        # summation by parts of Σ_i s_i ∫_{r_i}^{min(r_{i+1},a)} sqrt(a²-r²) dr: with
        # P_a(r) = (r sqrt(a²-r²) + a² asin(r/a))/2 and P_a(a) = πa²/4,
        # ∫_0^a g = s_k πa²/4 − Σ_{r_j <= a} Δs_j P_a(r_j) (only nodes with a slope jump)
        jump = self._dslope != 0
        nodes_all = self.r[1:-1][jump]
        ds_all = self._dslope[jump]
        k_all = np.clip(np.searchsorted(self.r, flat, side="right") - 1, 0, self._slopes.size - 1)
        chunk = max(1, _CHUNK // max(nodes_all.size, 1))
        for start in range(0, flat.size, chunk):
            aa = flat[start:start + chunk]
            pos = aa > 0
            if not np.any(pos):
                continue
            ap = aa[pos][:, None]
            m = int(np.searchsorted(nodes_all, ap.max(), side="right"))
            nodes, ds = nodes_all[:m][None, :], ds_all[:m][None, :]
            below = nodes <= ap
            q = np.minimum(nodes / ap, 1.0)
            P = 0.5 * (nodes * np.sqrt(np.maximum((ap - nodes) * (ap + nodes), 0.0))
                       + ap**2 * np.arcsin(q))
            out[start:start + chunk][pos] = (
                self._slopes[k_all[start:start + chunk][pos]] * 0.25 * np.pi * aa[pos] ** 2
                - row_sums(np.where(below, ds * P, 0.0), nodes_all.size))
        return out.reshape(a.shape)

    def _xg_integral_closed_form(self, a: np.ndarray) -> np.ndarray:
        """``∫_0^a x g(x) dx`` (m³) of the interpolant in closed form, O(nodes below a) per point.

        With ``g = x [s_0 π/2 + Σ_{r_j<x} Δs_j acos(r_j/x)]`` (linear; the spline's node terms
        likewise, see :meth:`_cubic_sums`) every node contributes elementary integrals
        (``b = r_j``, ``s = sqrt(a² - b²)``, ``θ = acos(b/a)``, ``L = asinh(s/b)``):

        * ``P2 = ∫_b^a x² acos(b/x) dx = a³θ/3 - (b/6)(a s + b² L)``,
        * ``Q2 = ∫_b^a x² sqrt(x² - b²) dx = a(2a² - b²) s/8 - b⁴ L/8``,
        * ``P4 = ∫_b^a x⁴ acos(b/x) dx = a⁵θ/5 - (b/5)(a³ s/4 + 3b² (a s + b² L)/8)``.

        The quadratures this replaces (torsion's sliding torque, the spring foundation's
        ``∫_0^x s g(s) ds``) could not converge across thousands of square-root cusps.
        """
        self._guard(np.asarray(a), "a")
        if self._spline is not None:
            return self._cubic_value(a, "xg")[0]
        a = np.asarray(a, dtype=float)
        flat = a.ravel()
        out = np.zeros(flat.size)
        jump = self._dslope != 0
        nodes_all = self.r[1:-1][jump]
        ds_all = self._dslope[jump]
        chunk = max(1, _CHUNK // max(nodes_all.size, 1))
        for start in range(0, flat.size, chunk):
            aa = flat[start:start + chunk]
            pos = aa > 0
            if not np.any(pos):
                continue
            av = aa[pos]
            m = int(np.searchsorted(nodes_all, av.max(), side="left"))
            ap = av[:, None]
            b, ds = nodes_all[:m][None, :], ds_all[:m][None, :]
            P2 = self._node_moments(ap, b)[0]
            out[start:start + chunk][pos] = (np.pi / 6.0 * self._slopes[0] * av**3
                                             + row_sums(np.where(b < ap, ds * P2, 0.0),
                                                        nodes_all.size))
        return out.reshape(a.shape)

    @staticmethod
    def _node_moments(ap: np.ndarray, b: np.ndarray
                      ) -> tuple[np.ndarray, np.ndarray, np.ndarray, tuple[np.ndarray, ...]]:
        """``(P2, Q2, P4, magnitudes)`` of :meth:`_xg_integral_closed_form` for ``b < a``
        (entries with ``b >= a`` are 0); ``magnitudes`` are the sums of the absolute values of
        each formula's parts (before they cancel), for rounding estimates."""
        with np.errstate(invalid="ignore", divide="ignore"):
            s = np.sqrt(np.maximum((ap - b) * (ap + b), 0.0))
            theta = np.arctan2(s, b)
            L = np.where(s > 0, np.arcsinh(s / np.where(b > 0, b, 1.0)), 0.0)
        a2, a3, b2 = ap * ap, ap * ap * ap, b * b
        ks = b / 6.0 * (ap * s + b2 * L)
        P2 = a3 * theta / 3.0 - ks
        q1, q2 = ap * (2.0 * a2 - b2) * s / 8.0, b2 * b2 * L / 8.0
        Q2 = q1 - q2
        p4a = a3 * a2 * theta / 5.0
        p4b = b / 5.0 * (a3 * s / 4.0 + 3.0 * b2 / 8.0 * (ap * s + b2 * L))
        P4 = p4a - p4b
        mags = (a3 * theta / 3.0 + ks, np.abs(q1) + q2, p4a + p4b)
        return P2, Q2, P4, mags

    @property
    def capabilities(self) -> frozenset[str]:
        """Semi-analytic pressure, Abel transform and force solves; ``"node_table"`` (g analytic
        between the nodes: composite quadrature rules per segment) and, for linear
        interpolation, ``"linear_table"`` (nodes where g has square-root cusps)."""
        caps = {"semi_analytic_pressure_shape", "semi_analytic_abel_g", "reduced_force_solver",
                "node_table"}
        if self.interpolation == "linear":
            caps.add("linear_table")
        return frozenset(caps)

    def table_nodes(self) -> np.ndarray:
        """Radii of the table nodes, m (the axis included)."""
        return self.r

    def table_g_first(self, t: np.ndarray) -> np.ndarray:
        """g on the first table segment ``0 <= t <= r_1`` in closed form, m: ``(π/2) s_0 t``
        (linear) or ``t (b0 π/2 + 2 c0 t + 3 d0 π t²/4)`` (the spline's first piece, which no
        node term reaches below ``r_1``)."""
        t = np.asarray(t, dtype=float)
        if self._spline is None:
            return 0.5 * np.pi * self._slopes[0] * t
        b0, c0, d0 = self._cubic_base
        return t * (0.5 * np.pi * b0 + t * (2.0 * c0 + 0.75 * np.pi * d0 * t))

    def table_g_slope(self, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """``(g'(x), rounding estimate)`` of the interpolant's transform (dimensionless), O(nodes
        below x) per point, for ``x`` between the nodes (at a node of a linear table g' is
        infinite).

        Linear: the arcsine node sums (:meth:`_arcsine_sums`), estimate ``8 eps`` times the sum of
        the node terms' magnitudes; cubic: the spline's closed-form node sums
        (:meth:`_cubic_sums`), estimate the rounding estimate of ``g`` there divided by ``x``
        (points whose sums cancel badly, nearly coincident nodes, carry a large estimate)."""
        x = np.asarray(x, dtype=float)
        eps = np.finfo(float).eps
        if self._spline is not None:
            g, err, slope = self._cubic_sums(x, "g", with_slope=True)
            with np.errstate(divide="ignore", invalid="ignore"):
                est = np.where(x > 0, err / np.where(x > 0, x, 1.0), 0.0)
            return slope, est + 8 * eps * np.abs(slope)
        _, slope = self._arcsine_sums(x, with_slope=True)
        return slope, 8 * eps * (np.abs(slope) + 0.5 * np.pi * float(np.max(np.abs(self._slopes)))
                                 + np.abs(self._dslope).sum())

    def table_axis_slope(self) -> float:
        """Slope of the interpolant on the axis, ``f'(0+)`` (1): the first segment's slope
        (linear) or the spline's (cubic; exactly 0 with ``axis="even"``). Nonzero means a cone
        tip, whose pressure is logarithmically infinite on the axis."""
        return float(self._slopes[0] if self._spline is None else self._cubic_base[0])

    def table_slopes(self) -> np.ndarray:
        """Slope of the interpolant on each table segment (linear interpolation)."""
        return self._slopes

    def _pressure_shape_semi_analytic(self, r: np.ndarray, a: np.ndarray, rtol: float
                                      ) -> tuple[np.ndarray, np.ndarray] | None:
        """``S(r, a) = ∫_r^a g'(x)/sqrt(x²-r²) dx`` of the linear interpolant, term by term.

        The interpolant is a cone of slope ``s_0`` plus truncated cones ``Δs_j (r - r_j)_+`` at the
        interior nodes, so ``S = s_0 (π/2) arccosh(a/r) + Σ_j Δs_j S_j`` with
        ``h_j'(x) = arccos(r_j/x) + r_j/sqrt(x²-r_j²)`` and

        * ``r > r_j``: ``S_j = ∫_0^{arccosh(a/r)} h_j'(r cosh u) du``,
        * ``r < r_j``: ``S_j = ∫_0^{arccosh(a/r_j)} r_j (1 + sinh v gd(v)) / sqrt(r_j² cosh²v - r²) dv``,

        both with bounded, smooth integrands (one batched tanh-sinh quadrature). At a node
        (``r = r_j``, a slope jump) the pressure is logarithmically infinite: ``±inf``. Cost
        O(number of nodes below ``a``) per radius. Returns ``None`` for the cubic spline (which
        takes the generic route).
        """
        if self._spline is not None:
            return None
        from ..numeric.quadrature import tanh_sinh
        r, a = np.broadcast_arrays(np.asarray(r, float), np.asarray(a, float))
        out = np.zeros(r.shape)
        err = np.zeros(r.shape)
        inside = r < a
        if not np.any(inside):
            return out, err
        self._guard(a[inside], "a")
        rr, aa = r[inside], a[inside]
        s0 = self._slopes[0]
        if s0 != 0:             # (a flat first segment has no tip term, also on the axis)
            with np.errstate(divide="ignore"):
                val = s0 * 0.5 * np.pi * np.arccosh(aa / np.where(rr > 0, rr, 0.0))
        else:
            val = np.zeros(rr.shape)
        er = np.zeros(rr.shape)
        keep = self._dslope != 0
        nodes, ds = self.r[1:-1][keep], self._dslope[keep]
        chunk = max(1, 200_000 // max(nodes.size, 1))
        for start in range(0, rr.size, chunk):
            rc, ac = rr[start:start + chunk], aa[start:start + chunk]
            ip, jn = np.nonzero(nodes[None, :] < ac[:, None])
            if ip.size == 0:
                continue
            rp, ap, b, w = rc[ip], ac[ip], nodes[jn], ds[jn]
            hit = rp == b
            above = rp > b
            with np.errstate(divide="ignore", invalid="ignore"):
                hi = np.where(above, np.arccosh(ap / np.where(above, rp, 1.0)),
                              np.arccosh(ap / b))
            hi = np.where(hit, 0.0, hi)

            def integrand(t: np.ndarray, idx: np.ndarray) -> np.ndarray:
                rv, bv = rp[idx][:, None], b[idx][:, None]
                up = above[idx][:, None]
                ch, sh = np.cosh(t), np.sinh(t)
                x = rv * ch
                with np.errstate(divide="ignore", invalid="ignore"):
                    root = np.sqrt(np.maximum((x - bv) * (x + bv), 0.0))
                    f_above = np.arctan2(root, bv) + bv / root
                    q = np.sqrt(np.maximum((bv * ch - rv) * (bv * ch + rv), 0.0))
                    f_below = bv * (1.0 + sh * np.arctan(sh)) / q
                return np.where(up, f_above, f_below)

            res = tanh_sinh(integrand, np.zeros_like(hi), hi, rtol=rtol, raise_on_failure=False)
            terms = w * res.value
            terms = np.where(hit, np.sign(w) * np.inf, terms)
            part = np.zeros(rc.size)
            np.add.at(part, ip, terms)
            e = np.zeros(rc.size)
            np.add.at(e, ip, np.abs(w) * res.error)
            val[start:start + chunk] += part
            er[start:start + chunk] += e
        out[inside] = val
        err[inside] = er
        return out, err

    def _quadrature_floor(self, x: np.ndarray, value: np.ndarray) -> np.ndarray | float:
        """A table that declares no breakpoints (too fine, or a spline) leaves a kink of g at
        every node inside one θ quadrature: it is accepted to the table's own resolution,
        ``|value| (h/x)²`` with ``h`` the largest node spacing below ``x`` (the interpolant of data
        sampled from a smooth surface is known to that relative accuracy)."""
        if self.breakpoints:
            return 0.0
        gaps = np.maximum.accumulate(np.diff(self.r))
        k = np.clip(np.searchsorted(self.r, x, side="left") - 1, 0, gaps.size - 1)
        with np.errstate(divide="ignore", invalid="ignore"):
            rel = np.where(x > 0, np.minimum((gaps[k] / np.where(x > 0, x, 1.0)) ** 2, 1.0), 0.0)
        return np.abs(value) * rel

    @property
    def breakpoints(self) -> tuple[float, ...]:
        """Interior nodes where the linear interpolant's slope jumps, for tables up to
        :data:`BREAKPOINT_LIMIT` points; finer tables and the cubic spline declare none (their
        kinks are weak and splitting at every node would cost O(N²))."""
        if self.r.size > BREAKPOINT_LIMIT or self._spline is not None:
            # the spline's transform is C² (its third-derivative jumps leave (x - r_j)^(5/2)
            # kinks): quadratures need no split there, and splitting at every node made an exact
            # torque-twist curve on 1000 points 14x slower for a 6e-14 change
            return ()
        return tuple(self.r[1:-1][self._dslope != 0].tolist())

    def _abel_g_semi_analytic(self, r: np.ndarray, a: np.ndarray, rtol: float
                              ) -> tuple[np.ndarray, np.ndarray] | None:
        """``A(r, a) = (2/π) ∫_0^{asin(min(1,a/r))} g(r sinθ) dθ`` of the linear interpolant.

        Inside the contact ``A = f(r)``. Outside, term by term over the cone plus truncated cones
        (``h_j(x) = x arccos(r_j/x)`` for ``x > r_j``), with ``θ_a = asin(a/r)``:
        ``A = s_0 r (1 - cos θ_a) + (2/π) Σ_j Δs_j ∫_{θ_j}^{θ_a} r sinθ arccos(r_j/(r sinθ)) dθ``,
        ``θ_j = asin(r_j/r)``. Each integrand is smooth inside its interval (the kink of ``h_j``
        sits at the lower end): one batched tanh-sinh quadrature. Returns ``None`` for the cubic
        spline.
        """
        if self._spline is not None:
            return None
        from ..numeric.quadrature import tanh_sinh
        r, a = np.broadcast_arrays(np.asarray(r, float), np.asarray(a, float))
        out = np.zeros(r.shape)
        err = np.zeros(r.shape)
        inside = (r <= a) & (r > 0)
        if np.any(inside):
            out[inside] = self._height(r[inside])
        outside = r > a
        if not np.any(outside):
            return out, err
        self._guard(a[outside], "a")
        ro, ao = r[outside], a[outside]
        th_a = np.arcsin(ao / ro)
        cone = self._slopes[0] * ro * (1.0 - np.cos(th_a))
        val = np.zeros(ro.shape)
        er = np.zeros(ro.shape)
        keep = self._dslope != 0
        nodes, ds = self.r[1:-1][keep], self._dslope[keep]
        chunk = max(1, 200_000 // max(nodes.size, 1))
        for start in range(0, ro.size, chunk):
            rc, ac, tc = ro[start:start + chunk], ao[start:start + chunk], th_a[start:start + chunk]
            ip, jn = np.nonzero(nodes[None, :] < ac[:, None])
            if ip.size == 0:
                continue
            rp, b, w = rc[ip], nodes[jn], ds[jn]
            lo = np.arcsin(b / rp)

            def integrand(th: np.ndarray, idx: np.ndarray) -> np.ndarray:
                x = rp[idx][:, None] * np.sin(th)
                bv = b[idx][:, None]
                root = np.sqrt(np.maximum((x - bv) * (x + bv), 0.0))
                return x * np.arctan2(root, bv)

            res = tanh_sinh(integrand, lo, tc[ip], rtol=rtol, raise_on_failure=False)
            part = np.zeros(rc.size)
            np.add.at(part, ip, w * res.value)
            e = np.zeros(rc.size)
            np.add.at(e, ip, np.abs(w) * res.error)
            val[start:start + chunk] += part
            er[start:start + chunk] += e
        out[outside] = cone + 2.0 / np.pi * val
        err[outside] = 2.0 / np.pi * er
        return out, err

    def _g_integral_with_error(self, a: np.ndarray, rtol: float | None = None
                               ) -> tuple[np.ndarray, np.ndarray]:
        if self._spline is not None:
            val, err, _ = self._cubic_value(a, "int")
        else:
            val, err = super()._g_integral_with_error(a, rtol)
        band = self._smoothing_band()
        if band is not None:
            err = err + np.interp(a, band[0], band[2])
        return val, err

    # ------------------------------------------------------------------ contact radius
    def _grid_g(self) -> tuple[np.ndarray, np.ndarray]:
        """g on the nodes and interval midpoints (cached; O(N²), built only for tables whose
        interpolant is not monotone, where the first crossing g = d must be located)."""
        cached = self.__dict__.get("_grid_cache")
        if cached is None:
            grid = np.sort(np.concatenate([self.r, 0.5 * (self.r[1:] + self.r[:-1])]))
            cached = (grid, self._g(grid))
            self.__dict__["_grid_cache"] = cached
        return cached

    def _solve_radius_first_crossing(self, d: np.ndarray, rtol: float) -> np.ndarray:
        """Smallest ``a`` with ``g(a) = d`` for tables whose g may decrease somewhere: bisection
        could land beyond a dip that lies outside the true contact, so the first crossing is
        located on the cached node/midpoint grid (the one the ring-contact check needs anyway)."""
        from .base import root_rtol
        grid, g = self._grid_g()
        running = np.maximum.accumulate(g)
        i = np.searchsorted(running, d, side="left")
        if np.any(i >= grid.size):
            k = int(np.argmax(i >= grid.size))
            raise OutsideTheoryError(
                f"depth={float(d.ravel()[k])!r} m needs a contact radius beyond the table (last "
                f"radius {self.r[-1]!r} m); extend the measured profile or reduce the load.")
        i = np.maximum(i, 1)
        from ..numeric.roots import bracketed_root
        return bracketed_root(lambda x, idx: self._g(x), d, grid[i - 1], grid[i],
                              rtol=root_rtol(rtol), what="contact radius")

    def _solve_radius(self, d: np.ndarray, limit: float, rtol: float | None = None) -> np.ndarray:
        """g(a) = d for the linear interpolant: a search over the nodes, then a smooth solve.

        The node interval holding ``a`` is found by safeguarded interpolation search (g is nearly
        linear across many nodes; each step tests the two nodes around the guess in one call and
        alternates with bisection when the bracket does not halve), typically 2-3 calls instead
        of ``log2(N)`` bisections. Between two nodes g is analytic except for the
        ``sqrt(x - r_k)`` kink at the left node, which ``x = r_k + (r_{k+1} - r_k) u²`` removes,
        so the bracketed solve in ``u`` (started with the memoised node values) converges
        superlinearly. The cubic spline takes the generic route.
        """
        if not self._monotone_f:
            return self._solve_radius_first_crossing(d, self.rtol if rtol is None else rtol)
        from ..errors import OutsideTheoryError
        from .base import root_rtol
        rtol = self.rtol if rtol is None else rtol
        flat = np.asarray(d, dtype=float).ravel()
        coarse = self._coarse_nodes()               # includes the last node
        g_end = float(self._node_g[-1])
        if np.any(flat > g_end):
            i = int(np.argmax(flat > g_end))
            raise OutsideTheoryError(
                f"depth={flat[i]!r} m needs a contact radius >= max_radius={limit!r} m of "
                f"{self!r}; reduce the depth/force.")
        # bracket from the cached coarse node grid (65 nodes, computed once per table)
        j = np.clip(np.searchsorted(self._node_g[coarse], flat, side="left"), 1, coarse.size - 1)
        lo, hi = coarse[j - 1], coarse[j]
        g_lo, g_hi = self._node_g[lo].copy(), self._node_g[hi].copy()
        lo, hi = self._node_search(self._g_at_nodes, flat, lo, hi, g_lo, g_hi)
        return self._newton_on_node_interval(
            flat, lo, hi, self._g_at_nodes(lo), self._g_at_nodes(hi), 0.5 * root_rtol(rtol),
            self._g_and_slope, self._g).reshape(np.shape(d))

    @staticmethod
    def _node_search(at_nodes, target: np.ndarray, lo: np.ndarray, hi: np.ndarray,
                     v_lo: np.ndarray, v_hi: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Narrow node brackets ``[lo, hi]`` of an increasing node function to adjacent nodes.

        Safeguarded interpolation search: guess the node from the bracket values, test the two
        nodes around the guess in one call of ``at_nodes`` (memoised), alternate with a bisection
        step whenever the bracket did not halve.
        """
        interpolate = True
        while True:
            open_ = np.flatnonzero(hi - lo > 1)
            if open_.size == 0:
                break
            lo_o, hi_o = lo[open_], hi[open_]
            if interpolate:
                # the function is nearly linear across a coarse bracket: guess the node interval
                # from the bracket values and test both of its nodes in one call
                with np.errstate(divide="ignore", invalid="ignore"):
                    frac = (target[open_] - v_lo[open_]) / (v_hi[open_] - v_lo[open_])
                frac = np.where(np.isfinite(frac), frac, 0.5)
                k = lo_o + np.floor(frac * (hi_o - lo_o)).astype(np.intp)
                k = np.clip(k, lo_o, hi_o - 1)
                pair = at_nodes(np.concatenate([k, k + 1])).reshape(2, -1)
                below_k = pair[0] < target[open_]
                below_k1 = pair[1] < target[open_]
                # keep the tighter of the two tested nodes on each side of the target
                new_lo = np.where(below_k1, k + 1, np.where(below_k, k, lo_o))
                new_hi = np.where(~below_k, k, np.where(~below_k1, k + 1, hi_o))
                v_lo[open_] = np.where(below_k1, pair[1], np.where(below_k, pair[0], v_lo[open_]))
                v_hi[open_] = np.where(~below_k, pair[0], np.where(~below_k1, pair[1], v_hi[open_]))
                shrunk = (new_hi - new_lo) <= 0.5 * (hi_o - lo_o)
                lo[open_], hi[open_] = new_lo, new_hi
                interpolate = bool(np.all(shrunk))   # else alternate with a bisection step
            else:
                mid = (lo_o + hi_o) // 2
                v_mid = at_nodes(mid)
                below = v_mid < target[open_]
                lo[open_] = np.where(below, mid, lo_o)
                hi[open_] = np.where(below, hi_o, mid)
                v_lo[open_] = np.where(below, v_mid, v_lo[open_])
                v_hi[open_] = np.where(below, v_hi[open_], v_mid)
                interpolate = True
        return lo, hi

    def _reduced_force_at_nodes(self, idx: np.ndarray) -> np.ndarray:
        """``H = a g(a) - ∫_0^a g`` (force / 2E*) at table nodes, memoised like g."""
        cache = self.__dict__.get("_node_H")
        if cache is None:
            cache = np.full(self.r.size, np.nan)
            self.__dict__["_node_H"] = cache
        vals = cache[idx]
        missing = np.isnan(vals)
        if np.any(missing):
            new = np.unique(idx[missing])
            x = self.r[new]
            cache[new] = x * self._g_at_nodes(new) - self._g_integral_closed_form(x)
            vals = cache[idx]
        return vals

    def _radius_of_reduced_force(self, target: np.ndarray, rtol: float) -> np.ndarray | None:
        """Contact radius with ``a g(a) - ∫_0^a g = target`` (= F/(2E*)), or None (generic route).

        The same scheme as :meth:`_solve_radius`: node search on the memoised values, then Newton
        in ``u`` with ``dH/da = a g'(a)``; used for convex linear tables only.
        """
        if not self._monotone_f:
            return None
        from ..errors import OutsideTheoryError
        from .base import root_rtol
        r = self.r
        flat = np.asarray(target, dtype=float).ravel()
        coarse = self._coarse_nodes()
        H_c = self._reduced_force_at_nodes(coarse)
        if np.any(flat > H_c[-1]):
            i = int(np.argmax(flat > H_c[-1]))
            raise OutsideTheoryError(
                f"force/E* = {2 * float(flat[i]):.6g} m² needs a contact radius beyond the table "
                f"(last radius {float(r[-1])!r} m, which carries force/E* = "
                f"{2 * float(H_c[-1]):.6g} m²); extend the measured profile or reduce the force.")
        j = np.clip(np.searchsorted(H_c, flat, side="left"), 1, coarse.size - 1)
        lo, hi = coarse[j - 1], coarse[j]
        lo, hi = self._node_search(self._reduced_force_at_nodes, flat, lo, hi,
                                   H_c[j - 1].copy(), H_c[j].copy())

        def value_and_slope(x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
            g, gp = self._g_and_slope(x)
            return x * g - self._g_integral_closed_form(x), x * gp      # dH/da = a g'(a)

        return self._newton_on_node_interval(
            flat, lo, hi, self._reduced_force_at_nodes(lo), self._reduced_force_at_nodes(hi),
            0.5 * root_rtol(rtol), value_and_slope,
            lambda x: x * self._g(x) - self._g_integral_closed_form(x)).reshape(np.shape(target))

    def _newton_on_node_interval(self, target: np.ndarray, lo: np.ndarray, hi: np.ndarray,
                                 v0: np.ndarray, v1: np.ndarray, tol: float, value_and_slope,
                                 value) -> np.ndarray:
        """Solve ``v(x) = target`` inside node intervals ``[r[lo], r[hi]]`` (``v`` increasing).

        Newton in ``u`` with ``x = r_lo + h u²`` (removes the square-root cusp of g at the left
        node), started from linear interpolation of ``v`` in ``x`` (dense tables: the smooth part
        dominates); each step costs one pass over the nodes for ``v`` and ``dv/dx`` together, and
        three to four steps reach ``tol``. Elements that leave ``[0, 1]`` or do not converge go to
        the bracketed solver on the same interval (``value`` only, end values known).
        """
        from ..numeric.roots import bracketed_root
        x0, h = self.r[lo], self.r[hi] - self.r[lo]
        with np.errstate(divide="ignore", invalid="ignore"):
            u = np.sqrt(np.clip(np.where(v1 > v0, (target - v0) / (v1 - v0), 0.25), 1e-12, 1.0))
        done = np.zeros(target.size, dtype=bool)
        for _ in range(6):
            act = np.flatnonzero(~done)
            if act.size == 0:
                break
            x = x0[act] + h[act] * u[act] ** 2
            v, dv = value_and_slope(x)
            step = (v - target[act]) / (dv * 2 * h[act] * u[act])
            u_new = u[act] - step
            ok = np.isfinite(u_new) & (u_new > 0) & (u_new <= 1)
            u[act] = np.where(ok, u_new, u[act])
            conv = ok & (np.abs(step) * 2 * h[act] * u[act]
                         <= tol * (x0[act] + h[act] * u[act] ** 2))
            done[act[conv]] = True
        rest = np.flatnonzero(~done)
        if rest.size:
            def func(uu: np.ndarray, idx: np.ndarray) -> np.ndarray:
                return value(x0[rest][idx] + h[rest][idx] * uu * uu)

            u[rest] = bracketed_root(func, target[rest], np.zeros(rest.size), np.ones(rest.size),
                                     rtol=tol, what="contact radius", f_lo=v0[rest],
                                     f_hi=v1[rest])
        return x0 + h * u * u

    def _coarse_nodes(self) -> np.ndarray:
        """Indices of 65 evenly spaced nodes whose g is memoised once (the search's first bracket)."""
        idx = self.__dict__.get("_coarse_idx")
        if idx is None:
            idx = np.unique(np.linspace(0, self.r.size - 1, 65).round().astype(np.intp))
            self._g_at_nodes(idx)
            self.__dict__["_coarse_idx"] = idx
        return idx

    def _g_at_nodes(self, idx: np.ndarray) -> np.ndarray:
        """g at table nodes ``r[idx]``, memoised per node (the bisection revisits the same
        nodes for every depth; the table is immutable, so the cache never goes stale)."""
        if self._node_g is None:
            self._node_g = np.full(self.r.size, np.nan)
        vals = self._node_g[idx]
        missing = np.isnan(vals)
        if np.any(missing):
            new = np.unique(idx[missing])
            self._node_g[new] = self._g(self.r[new])
            vals = self._node_g[idx]
        return vals

    def _check_monotone_upto(self, a_max: float, d_for_message: float) -> None:
        if self._monotone_f or a_max <= self._verified_upto:
            return
        grid, g = self._grid_g()
        upto = grid < a_max
        gg = np.append(g[upto], float(self._g(np.array(a_max))))
        xx = np.append(grid[upto], a_max)
        dg = np.diff(gg)
        scale = max(float(np.max(np.abs(gg))), 1e-300)
        bad = np.flatnonzero(dg < -1e-12 * scale)
        if not bad.size:
            self._verified_upto = a_max
        if bad.size:
            i = int(bad[0])
            raise OutsideTheoryError(
                f"depth={d_for_message!r} m: the transformed profile g(x) decreases at x="
                f"{xx[i]:.6g} m (g={gg[i]:.6g} m, then {gg[i + 1]:.6g} m), so beyond depth "
                f"{gg[i]:.6g} m the contact is an annulus, outside the MDR. Smooth the measured "
                "profile (Tabulated(..., smoothing='auto')), take the nearest admissible table "
                "(admissible='nearest', slopes made non-decreasing) or limit the load.")
