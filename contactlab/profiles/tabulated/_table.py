"""The :class:`Tabulated` profile: reading and checking a table, and the hooks of the Profile contract.

The table's transform kernels live beside it (``_linear``: linear interpolation, ``_cubic``: the
cubic spline, ``_solve``: contact-radius solves); this class reads and checks the table, smooths
it when asked, and implements the :class:`~contactlab.profiles.base.Profile` hooks by
dispatching to them. Overview and formulas: :mod:`contactlab.profiles.tabulated`.
"""
from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Any, ClassVar, cast

import numpy as np

from ...errors import ParameterError, TabulatedDataError
from ...params import LENGTH_BOUNDS, Param, as_real
from ...symbolic.form import SympyForm
from ._base import _clip_index
from ._cubic import _CubicTransform
from ._linear import _LinearTransform
from ._solve import _TableSolver

if TYPE_CHECKING:
    from ..smoothing import SmoothingReport

__all__ = ["Tabulated", "BREAKPOINT_LIMIT"]

#: tables up to this many points declare their nodes as breakpoints (quadratures split there)
BREAKPOINT_LIMIT = 2000
#: the largest radius of a table, m (and the largest height's magnitude: the upper bound)
_SCALE_RANGE = LENGTH_BOUNDS


class Tabulated(_TableSolver, _CubicTransform, _LinearTransform):
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
        Unsorted, duplicate, negative or non-finite radii; non-finite heights; length mismatch;
        a largest radius outside ``[1e-30, 1e10]`` m or a height beyond ``1e10`` m of 0.
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
        self._check_scale(r_arr, f_arr)
        self.smoothing_report: SmoothingReport | None = None
        self._band: tuple[np.ndarray, np.ndarray, np.ndarray] | None = None
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

    @staticmethod
    def _check_scale(r: np.ndarray, f: np.ndarray) -> None:
        """The table's largest radius within ``[1e-30, 1e10]`` m and its heights within
        ``1e10`` m of 0, the range in which both interpolations are checked against Hertz's
        closed form. Beyond it results left float64 or went wrong: a linear table of 1e-200 m
        radii gave a zero contact radius for a positive depth, a cubic one of 1e20 m radii
        called its ``g`` decreasing, one of 1e30 m gave a contact radius 4e10 times too small,
        one of 1e300 m failed inside scipy's spline. Every physical table lies far inside (an
        atom is 1e-10 m across, the Earth's radius 6.4e6 m)."""
        lo, hi = _SCALE_RANGE
        if not lo <= float(r[-1]) <= hi:
            raise TabulatedDataError(
                f"r[-1]={float(r[-1])!r} m is invalid: the largest radius of a table must lie "
                f"between {lo:g} and {hi:g} m (check the units of r).")
        big = float(np.max(np.abs(f)))
        if big > hi:
            i = int(np.argmax(np.abs(f)))
            raise TabulatedDataError(
                f"f[{i}]={float(f[i])!r} m is invalid: the heights of a table must lie within "
                f"{hi:g} m of 0 (check the units of f).")

    def _slope_rounding(self, r: np.ndarray, f: np.ndarray, f_scale: float) -> np.ndarray:
        """Rounding bound of each segment's slope, 1: ``4 eps (|f_i| + |f_{i+1}| + max|f| +
        |s_i| (r_i + r_{i+1})) / Δr_i`` (the heights as given, their datum shift and the radii
        each rounded by eps)."""
        eps = np.finfo(float).eps
        return 4.0 * eps * (np.abs(f[:-1]) + np.abs(f[1:]) + f_scale + np.abs(self._slopes)
                            * (r[:-1] + r[1:])) / np.diff(r)

    def _smooth(self, r: np.ndarray, f: np.ndarray, smoothing: Any, noise: float | None,
                admissible: str | None, axis: str = "even") -> np.ndarray:
        """Smoothed and/or projected heights; sets :attr:`smoothing_report` and the error band."""
        from dataclasses import replace

        from ..smoothing import SmoothingReport, nearest_admissible, slope_violations, smooth_table
        parts: Any = None
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

    def _g(self, xa: np.ndarray, rtol: float | None = None) -> np.ndarray:
        # the far-field trees take the Taylor terms of rtol
        with self._tree_rtol(rtol):
            return super()._g(xa, rtol)

    def _g_with_error(self, xa: np.ndarray, rtol: float | None = None
                      ) -> tuple[np.ndarray, np.ndarray]:
        # the far-field trees take the Taylor terms of rtol; their truncation bound enters
        # the estimate (zero with all terms: the default rtol keeps its bits)
        with self._tree_rtol(rtol):
            if self._spline is not None and self.g_route == "closed_form":
                val, err, _ = self._cubic_value(xa, "g")
                err = err + self._cubic_truncation(xa, "g")
            else:
                val, err = super()._g_with_error(xa, rtol)
                if self._spline is None:
                    err = err + self._far_truncation(xa, "g")
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
        from ...numeric.tables import read_columns
        # (columns named by position: read_columns takes int keys as well as names)
        units: dict[Any, str | None] = {k: v for k, v in ((0, r_unit), (1, f_unit))
                                        if v is not None}
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

    def _sympy_form(self) -> SympyForm:
        return SympyForm(reason="a tabulated (measured) profile has no symbolic form; use the "
                                "numeric routes (contact.normal(...))")

    def _height(self, r: np.ndarray) -> np.ndarray:
        self._guard(r, "r")
        if self._spline is not None:
            return self._spline(r)
        return np.interp(r, self.r, self.f)

    def _slope(self, r: np.ndarray) -> np.ndarray:
        self._guard(r, "r")
        if self._spline is not None:
            return self._spline_d(r)
        k = _clip_index(np.searchsorted(self.r, r, side="right") - 1, 0, self._slopes.size - 1)
        return self._slopes[k]

    def available_strategies(self) -> tuple[str, ...]:
        return ("closed_form", "quadrature")

    def _g_closed_form(self, x: np.ndarray) -> np.ndarray:
        """Exact transform of the interpolant (sum of arcsines, or of the spline's node terms),
        chunked."""
        if self._spline is not None:
            return self._cubic_value(x, "g")[0]
        return self._arcsine_sums(x, with_slope=False)[0]

    def _g_and_slope(self, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """``(g, g')`` of the interpolant in one pass over the nodes."""
        if self._spline is not None:
            g, _, gp = self._cubic_value(x, "g", with_slope=True)
            return g, cast(np.ndarray, gp)
        g, gp = self._arcsine_sums(x, with_slope=True)
        return g, cast(np.ndarray, gp)

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
        return self._linear_g_integral(a)

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
        return self._linear_xg_integral(a)

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
            _, err, c_slope = self._cubic_sums(x, "g", with_slope=True)
            slope = cast(np.ndarray, c_slope)
            with np.errstate(divide="ignore", invalid="ignore"):
                est = np.where(x > 0, err / np.where(x > 0, x, 1.0), 0.0)
            return slope, est + 8 * eps * np.abs(slope)
        slope = cast(np.ndarray, self._arcsine_sums(x, with_slope=True)[1])
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
        """``S(r, a) = ∫_r^a g'(x)/sqrt(x²-r²) dx`` of the linear interpolant, term by term
        (:meth:`_linear_pressure_shape`); ``None`` for the cubic spline (the generic route)."""
        if self._spline is not None:
            return None
        return self._linear_pressure_shape(r, a, rtol)

    def _quadrature_floor(self, x: np.ndarray, value: np.ndarray) -> np.ndarray | float:
        """A table that declares no breakpoints (too fine, or a spline) leaves a kink of g at
        every node inside one θ quadrature: it is accepted to the table's own resolution,
        ``|value| (h/x)²`` with ``h`` the largest node spacing below ``x`` (the interpolant of data
        sampled from a smooth surface is known to that relative accuracy)."""
        if self.breakpoints:
            return 0.0
        gaps = np.maximum.accumulate(np.diff(self.r))
        k = _clip_index(np.searchsorted(self.r, x, side="left") - 1, 0, gaps.size - 1)
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
        """``A(r, a) = (2/π) ∫_0^{asin(min(1,a/r))} g(r sinθ) dθ`` of the linear interpolant, term
        by term (:meth:`_linear_abel_g`); ``None`` for the cubic spline."""
        if self._spline is not None:
            return None
        return self._linear_abel_g(r, a, rtol)

    def _g_integral_with_error(self, a: np.ndarray, rtol: float | None = None
                               ) -> tuple[np.ndarray, np.ndarray]:
        with self._tree_rtol(rtol):
            if self._spline is not None:
                val, err, _ = self._cubic_value(a, "int")
                err = err + self._cubic_truncation(a, "int")
            else:
                val, err = super()._g_integral_with_error(a, rtol)
                err = err + self._far_truncation(a, "int")
        band = self._smoothing_band()
        if band is not None:
            err = err + np.interp(a, band[0], band[2])
        return val, err

    def _solve_radius(self, d: np.ndarray, limit: float, rtol: float | None = None) -> np.ndarray:
        """g(a) = d: node search, then a smooth solve (:meth:`_solve_table_radius`), the
        far-field trees with the Taylor terms of ``rtol``."""
        with self._tree_rtol(rtol):
            return self._solve_table_radius(d, limit, rtol)

    def _radius_of_reduced_force(self, target: np.ndarray, rtol: float) -> np.ndarray | None:
        """Contact radius with ``a g(a) - ∫_0^a g = target`` (= F/(2E*)), or None (generic route):
        :meth:`_table_radius_of_reduced_force` (the far-field trees with the Taylor terms of
        ``rtol``)."""
        with self._tree_rtol(rtol):
            return self._table_radius_of_reduced_force(target, rtol)

    def _check_monotone_upto(self, a_max: float, d_for_message: float) -> None:
        self._check_table_monotone(a_max, d_for_message)
