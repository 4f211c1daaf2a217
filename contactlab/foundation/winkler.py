"""The Winkler (independent-spring) MDR foundation with Jenkins stick/slip elements.

Each cell ``[b_i, b_{i+1}]`` lumps the springs of ``±x`` in it [H1, PH; theory §3, §5, §6.4]:

* normal: compression ``d - g(x)``; cell force ``2E* S_i`` with ``S_i = ∫_cell (d - g)_+ dx``
  integrated exactly (so the normal force is exact at any N);
* tangential (springs ``G*Δx``): element force ``f_i``, stiffness ``2G* w_i``, slip limit
  ``μ · 2E* S_i``;
* torsional (springs ``8G_tΔx``, ``μ* = 2μ``): element torque ``m_i``, stiffness
  ``16 G_t ∫_cell x² dx``, slip limit ``4μE* ∫_cell x (d - g)_+ dx`` (the cell's share of
  ``M = (16/3) G_t a³ φ`` without slip and of ``4μE*∫x(d-g)`` at full slip).

Elements are incremental Jenkins elements: ``f ← clip(f + k_eff Δu, -L, L)``. The stiffness of a
cell is weighted by the part of it in contact during the step (``ΔS/(w Δd)``, exact when the
displacement varies linearly with the depth within the step), so springs entering contact carry
only the displacement accumulated after they touched, and springs leaving contact release theirs
(``L → 0``). The dissipated energy is ``Σ slip × limit``.
"""
from __future__ import annotations

import functools
import warnings
from dataclasses import dataclass
from typing import Any

import numpy as np

from . import _compiled
from . import winkler_path as _loop
from ._compiled import jenkins_update

from ..citations import sources_for
from ..errors import (ContactlabError, OutsideTheoryError, ParameterError, UnknownNameError,
                      ValidityWarning)
from ..numeric.powers import WHOLE_POWERS, power_integral
from ..numeric.quadrature import tanh_sinh
from ..params import check_count, check_memory, check_time
from .base import (DEFAULT_N_SPRINGS, SERIES, SPACINGS, Foundation, PathArrays, PathNormal,
                   families_needed)


def _check_stiffness(K: np.ndarray, radius: float) -> None:
    """Cell stiffnesses must be finite and > 0 (a contact radius of ~1e-100 m makes b³ underflow)."""
    if not (K.min() > 0 and np.isfinite(K.max())):     # (a NaN fails the first test)
        raise OutsideTheoryError(f"the path's largest contact radius {radius!r} m is outside double "
                                 "precision for the spring foundation (cell stiffnesses underflow "
                                 "to 0 or overflow): load the contact further or use the closed-form "
                                 "routes (normal(), torsion()).")

__all__ = ["Winkler", "SpringState", "xg_integral", "step_seconds"]


def _gint(profile, x: np.ndarray) -> np.ndarray:
    x = np.asarray(x, float)
    return np.where(x > 0, profile._g_integral(np.maximum(x, 1e-300)), 0.0)


def _edge_integrals(profile, a: np.ndarray, rtol: float, tor: bool
                    ) -> tuple[np.ndarray, np.ndarray]:
    """``(∫_0^a g, ∫_0^a x g)`` of the contact radii of a run of steps (the second only with
    ``tor``, else the first again). A single power term ``c r^n`` (no wall) with every radius
    > 0 (a gait) takes ``κ_n c a^(n+1)/(n+1)`` and ``κ_n c a^(n+2)/(n+2)`` in place: the same
    operations as :func:`_gint` and :func:`xg_integral` (bit-identical), without their masks,
    error estimates and temporaries."""
    terms = profile.power_terms()
    if (terms is not None and len(terms) == 1 and not np.isfinite(profile.wall_radius)
            and a.size and float(np.min(a)) > 0):
        c, n = terms[0]
        kn = [(profile._power_kappa(n) * c, n)]
        Ga = power_integral(a, kn, 1.0)
        return Ga, (power_integral(a, kn, 2.0) if tor else Ga)
    Ga = _gint(profile, a)
    return Ga, (xg_integral(profile, a, rtol) if tor else Ga)


def _whole_power_term(profile, tor: bool) -> tuple[float, float, float] | None:
    """``(κ_n c, n + 1, n + 2)`` when the profile is one power term ``c r^n`` (no wall) whose
    edge integrals :func:`~contactlab.numeric.powers.power` takes by multiplication (``n + 1``
    and, with torsion, ``n + 2`` whole, at most 4), else None."""
    terms = profile.power_terms()
    if terms is None or len(terms) != 1 or np.isfinite(profile.wall_radius):
        return None
    c, n = (float(v) for v in terms[0])
    if n + 1.0 not in WHOLE_POWERS or (tor and n + 2.0 not in WHOLE_POWERS):
        return None
    return profile._power_kappa(n) * c, n + 1.0, n + 2.0


def xg_integral(profile, x: np.ndarray, rtol: float) -> np.ndarray:
    """``H(x) = ∫_0^x s g(s) ds``, m⁴ (closed form for power terms and tables, else tanh-sinh)."""
    x = np.asarray(x, float)
    if profile._has("_xg_integral_closed_form"):
        return np.where(x > 0, profile._xg_integral_closed_form(np.maximum(x, 0.0)), 0.0)
    terms = profile.power_terms()
    if terms is not None:
        return power_integral(x, [(profile._power_kappa(n) * c, n) for c, n in terms], 2.0)

    def integrand(s: np.ndarray, idx: np.ndarray) -> np.ndarray:
        return s * profile._g(np.maximum(s, 1e-300))

    lo = np.minimum(np.broadcast_to(profile.flat_radius, x.shape).astype(float), x)
    flat = x.ravel()
    out = np.zeros(flat.shape)
    pos = flat > lo.ravel()
    if np.any(pos):
        out[pos] = tanh_sinh(integrand, lo.ravel()[pos], flat[pos], rtol=rtol).value
    return out.reshape(x.shape)


@dataclass
class SpringState:
    """Spring state of one solver run (mutable, owned by the run).

    Attributes
    ----------
    S : ndarray
        ``∫_cell (d - g)_+ dx`` per cell, m² (normal spring state).
    tangential, torsion : ndarray or None
        Element force (N) / torque (N·m) per cell, or None when the family is not built.
    L_tan, L_tor : ndarray or None
        Current slip limits.
    depth, radius : float
    """

    S: np.ndarray
    tangential: np.ndarray | None
    torsion: np.ndarray | None
    L_tan: np.ndarray | None
    L_tor: np.ndarray | None
    depth: float = 0.0
    radius: float = 0.0
    nL_tan: np.ndarray | None = None
    nL_tor: np.ndarray | None = None
    k: int = 0


#: the routes of the time loop (``strategy=``; :func:`contactlab.foundation.winkler_path.time_loop`)
STRATEGIES = ("segments", "steps")


#: run time of a path on the MDR springs, s per step: a fixed part, and with
#: ``strategy="steps"`` one per spring and step. Measured (CPU time, shared 2-core VM at load
#: ~3.5, paraboloid, numba kernels): "segments" 0.26 µs per step on a held-force twist ramp of
#: 10^5 steps (closed form per run of steps), 3.4-7.5 µs on sinusoids and varying forces at 2 000
#: springs; "steps" 4.1-13 µs per step at 2 000 springs and 21-35 µs at 20 000 (~1 ns per spring
#: and step). Taken at about 0.4 of the smallest, and "segments" without a per-spring part: a
#: lower estimate (numpy without numba is slower; benchmarks/time_estimates.py checks it)
STEP_SECONDS, STEP_SECONDS_PER_SPRING = 1e-7, 4e-10


def step_seconds(n_springs: int, strategy: str) -> float:
    """Estimated run time (s) of one path step on ``n_springs`` springs with ``strategy``."""
    return STEP_SECONDS + (STEP_SECONDS_PER_SPRING * n_springs if strategy == "steps" else 0.0)


class Winkler(Foundation):
    """Independent springs with stick/slip memory (see the module docstring).

    Along a load path (:meth:`for_path`, :meth:`run`; the time loop is
    :func:`contactlab.foundation.winkler_path.time_loop`) its options are ``n_springs``,
    ``spacing``, ``strategy`` (``"segments"``: runs of steps at a held normal load and a
    monotone control in closed form, the default; ``"steps"``: every step one by one, the same
    results up to rounding) and ``approximate`` (combined shift and twist as two independent
    spring families, with a :class:`~contactlab.errors.ValidityWarning`).
    """

    #: series whose discretisation error an error estimate reports (the normal ones are exact
    #: at any N, the cells integrating their springs exactly)
    ESTIMATED = ("tangential_force", "torque", "stick_radius", "dissipated_energy")
    #: the time loop's route (set by :meth:`for_path`)
    strategy = "segments"
    approximate = False

    @classmethod
    def check_path(cls, path: Any, snapshots: Any = (), *, n_springs: int | None = None,
                   spacing: str | None = None, strategy: str | None = None,
                   approximate: bool = False) -> dict[str, Any]:
        strategy = "segments" if strategy is None else strategy
        if strategy not in STRATEGIES:
            raise UnknownNameError(f"strategy={strategy!r} is invalid: allowed are "
                                   f"{STRATEGIES}.")
        spacing = "edge" if spacing is None else spacing
        if spacing not in SPACINGS:
            raise UnknownNameError(f"spacing={spacing!r} is invalid: allowed are {SPACINGS}.")
        needs = families_needed(path, approximate=approximate)
        if len(needs) == 2:
            warnings.warn("combined shift and twist is run as two independent spring families "
                          "(approximate=True): outside the MDR theory, the slip limits do not "
                          "interact.", ValidityWarning, stacklevel=6)
        n_total = path.n_steps
        n_springs = DEFAULT_N_SPRINGS if n_springs is None else check_count("n_springs", n_springs)
        n_snap = len(snapshots)
        check_memory("simulate()", _loop.memory(n_total, n_springs, n_snap),
                     f"{n_total} steps, {n_springs} springs, {n_snap} snapshots")
        per = step_seconds(n_springs, strategy)
        check_time("simulate()", n_total * per,
                   f"{n_total} steps x {per * 1e6:.3g} us on the MDR springs (strategy="
                   f"{strategy!r}" + (f", {n_springs} springs per step)" if strategy == "steps"
                                      else ")"))
        return {"n_springs": n_springs, "spacing": spacing, "strategy": strategy,
                "approximate": bool(approximate)}

    @classmethod
    def writes(cls, path: Any, outputs: Any, *, approximate: bool = False,
               **options: Any) -> tuple:
        needs = families_needed(path, approximate=approximate)
        return _loop.run_writes(needs, tuple(outputs)) if needs else ()

    @classmethod
    def coarser(cls, options: dict, meta: dict) -> dict | None:
        """Half the springs (the spring error falls as 1/N², so the difference is about three
        times the error of the N-spring run); none for a run that built no springs."""
        if not meta.get("n_springs"):
            return None
        return dict(options, n_springs=max(2, meta["n_springs"] // 2))

    @classmethod
    def for_path(cls, profile: Any, moduli: Any, friction: float | None, path: Any, *,
                 normal: PathNormal | None = None, n_springs: int | None = None,
                 spacing: str = "edge", rtol: float = 1e-10, approximate: bool = False,
                 strategy: str = "segments", **options: Any) -> "Winkler":
        """The springs of ``path`` (see :meth:`Foundation.for_path`): over the largest contact
        radius, the families the path loads. A path that never brings the bodies into contact
        gets a foundation without cells (nothing to discretise), or raises
        :class:`~contactlab.errors.ParameterError` when it prescribes a shift or twist."""
        needs = families_needed(path, approximate=approximate)
        if normal is None:
            from .base import path_normal_series
            normal = path_normal_series(profile, moduli.normal, path, rtol)
        a_max = normal.max_radius
        if a_max > 0:
            fnd = cls(profile, moduli, friction, a_max, n_springs=n_springs, spacing=spacing,
                      needs=needs, rtol=rtol, **options)
        elif needs:
            raise ParameterError("the path prescribes " + " and ".join(needs) + " but the normal "
                                 "load never brings the bodies into contact (contact radius 0 "
                                 "at every step).")
        else:           # never in contact: no cells
            fnd = cls.__new__(cls)
            fnd.profile, fnd.moduli, fnd.friction, fnd.rtol = profile, moduli, friction, rtol
            fnd.radius, fnd.n_springs, fnd.spacing, fnd.needs = 0.0, 0, spacing, ()
        fnd.strategy, fnd.approximate = strategy, bool(approximate)
        return fnd

    def run(self, leaves: Any, normal: PathNormal, outputs: Any, snapshots: Any,
            progress: Any = None) -> PathArrays:
        """The time loop along the path (:func:`~contactlab.foundation.winkler_path.time_loop`).
        The snapshots hold ``depth``, ``radius``, the cell midpoints ``x`` and the spring states
        ``normal``, ``tangential``, ``torsion`` (N, N·m) and the tractions
        ``shear_tangential``, ``shear_torsion`` (Pa); the 3D pressure is left to the caller.
        ``meta``: ``built``, ``n_springs`` (``None`` when no springs were needed), ``spacing``,
        ``approximate``, ``foundation``, ``citations``."""
        res = normal.series
        needs = self.needs
        n_total = res["time"].size
        outputs = tuple(outputs)
        snaps = set(snapshots)
        meta: dict[str, Any] = {"built": ["normal", *needs], "n_springs": None, "spacing": self.spacing,
                "approximate": self.approximate, "foundation": None,
                "citations": sources_for("normal", "foundation",
                                         *(("tangential",) if "tangential" in needs else ()),
                                         *(("foundation:torsion",) if "torsion" in needs
                                           else ()))}
        runs = self.radius > 0 and bool(needs)
        written = _loop.run_writes(needs, outputs) if runs else ()
        for k in SERIES:
            if k not in res:
                res[k] = (np.empty(n_total) if k in written else
                          np.zeros(n_total, bool if k == "gross_sliding" else float))
        snapshot_data: dict[int, dict] = {}
        if not runs:
            # nothing but the (exact) normal problem: no tangential/torsional springs
            res["stick_radius"][:] = res["radius"]
            fnd = self if snaps and self.radius > 0 else None
            if fnd is not None:
                meta.update(n_springs=self.n_springs, foundation=repr(self))
            for s in sorted(snaps):
                snapshot_data[s] = _loop.snapshot(fnd, None, res, s)
            return PathArrays(res, snapshot_data, meta, n_total)
        meta.update(n_springs=self.n_springs, foundation=repr(self))
        track: dict[str, Any] = {"done": 0}
        try:
            _loop.time_loop(self, leaves, normal.leaves, res, snaps, snapshot_data,
                            "stick_radius" in outputs, progress, self.strategy, track)
        except ContactlabError as err:
            done = track["done"]
            err.partial = PathArrays(res, {s: v for s, v in snapshot_data.items() if s < done},
                                     meta, done)
            raise
        return PathArrays(res, snapshot_data, meta, n_total)

    def _build(self) -> None:
        # few full-length passes and temporaries: at 10^6 springs building costs as much as ~40
        # steps of the compiled run (left edges are views of the boundary arrays, b³ is b²·b)
        b = self.boundaries
        prof = self.profile
        self.bl = b[:-1]
        self.w = np.diff(b)
        # 1/w and the weight buffer of the step-by-step route are made on first use (a fused
        # compiled run needs neither: at 10^6 springs two 8 MB arrays fewer per simulate)
        Gb = _gint(prof, b)
        self.dG = np.diff(Gb)
        self.G_left = Gb[:-1]
        E = self.moduli.normal
        mu = self.friction
        self._c_tan = 2.0 * mu * E if mu is not None else np.inf
        self._c_tor = 4.0 * mu * E if mu is not None else np.inf
        if "tangential" in self.needs:
            self.K_tan = 2.0 * self.moduli.tangential * self.w
            _check_stiffness(self.K_tan, self.radius)
            self.invK_tan = 1.0 / self.K_tan
        if "torsion" in self.needs:
            b2 = b * b
            self.X1 = np.diff(b2)
            self.X1 /= 2.0
            b2 *= b                                     # b³
            K = np.diff(b2)
            del b2
            K *= 16.0 * self.moduli.torsional
            K /= 3.0
            self.K_tor = K
            _check_stiffness(self.K_tor, self.radius)
            self.invK_tor = 1.0 / self.K_tor
            Hb = xg_integral(prof, b, self.rtol)
            self.dH = np.diff(Hb)
            self.H_left = Hb[:-1]

    # ------------------------------------------------------------------ per-step precomputation
    def edge_data(self, d: np.ndarray, a: np.ndarray) -> dict[str, np.ndarray]:
        """Vectorised over steps: index of the cell holding the contact edge and its exact
        partial integrals (``S`` and, with torsion, ``∫ x (d-g)``)."""
        d = np.asarray(d, float)
        a = np.asarray(a, float)
        tor = "torsion" in self.needs
        kernel = _compiled.edge_cells() if d.ndim == 1 and d.shape == a.shape else None
        if kernel is not None:   # compiled: the search and arithmetic below in one pass
            spec = _whole_power_term(self.profile, tor)
            if spec is None:
                a = np.minimum(a, self.radius)
                Ga, Ha = _edge_integrals(self.profile, a, self.rtol, tor)
                spec = (0.0, 0.0, 0.0)
            else:       # the integrals in the kernel's pass
                Ga = Ha = a
            out = {"k": np.empty(d.size, np.int64), "S": np.empty(d.size)}
            out["T"] = np.empty(d.size) if tor else out["S"]
            kernel(d, a, Ga, Ha, self.boundaries, self.G_left, self.H_left if tor else self.G_left,
                   out["k"], out["S"], out["T"], tor, float(self.radius), *spec)
            if not tor:
                del out["T"]
            return out
        a = np.minimum(a, self.radius)
        k = np.clip(np.searchsorted(self.boundaries, a, side="left") - 1, 0, self.n_springs - 1)
        bl = self.bl[k]
        S = np.where(a > bl, d * (a - bl) - (_gint(self.profile, a) - self.G_left[k]), 0.0)
        out = {"k": k, "S": np.maximum(S, 0.0)}
        if "torsion" in self.needs:
            Ha = xg_integral(self.profile, a, self.rtol)
            out["T"] = np.maximum(np.where(a > bl, d * (a * a - bl * bl) / 2.0
                                           - (Ha - self.H_left[k]), 0.0), 0.0)
        return out

    def new_state(self) -> SpringState:
        n = self.n_springs
        tan = np.zeros(n) if "tangential" in self.needs else None
        tor = np.zeros(n) if "torsion" in self.needs else None
        return SpringState(np.zeros(n), tan, tor,
                           np.zeros(n) if tan is not None else None,
                           np.zeros(n) if tor is not None else None,
                           nL_tan=np.zeros(n) if tan is not None else None,
                           nL_tor=np.zeros(n) if tor is not None else None)

    def set_normal(self, st: SpringState, d: float, a: float, k: int, S_edge: float,
                   T_edge: float | None) -> np.ndarray | None:
        """Move the normal springs to depth ``d`` (radius ``a``, edge cell ``k``); update the slip
        limits of the built families.

        Returns the contact weight of each cell over the step (``ΔS/(w Δd)``: 1 for cells in
        contact before and after, 0 for cells out of contact throughout, the exact average for
        the cells the edge crossed), by which the stiffness of the tangential/torsional elements is
        scaled for this step; ``None`` when the depth did not change (then the weight is the
        contact fraction, :meth:`fraction`).
        """
        dd = d - st.depth
        k_old = st.k
        S_old = st.S
        S = d * self.w
        S -= self.dG  # cells left of k are fully in contact, so S > 0 there (d >= g(a))
        S[k + 1:] = 0.0
        S[k] = S_edge
        weight = None
        if dd != 0.0:
            lo, hi = min(k, k_old), max(k, k_old) + 1
            weight = self.__dict__.get("_wbuf")
            if weight is None:
                weight = self._wbuf = np.zeros(self.n_springs)
            weight[:lo] = 1.0
            weight[hi:] = 0.0
            ws = (S[lo:hi] - S_old[lo:hi]) / (dd * self.w[lo:hi])
            np.clip(ws, 0.0, 1.0, out=weight[lo:hi])
        st.S, st.depth, st.radius, st.k = S, d, a, k
        inf_mu = self.friction is None
        if st.L_tan is not None:
            st.L_tan = np.where(S > 0, np.inf, 0.0) if inf_mu else self._c_tan * S
            st.nL_tan = -st.L_tan
        if st.L_tor is not None:
            T = d * self.X1
            T -= self.dH
            T[k + 1:] = 0.0
            T[k] = T_edge
            st.L_tor = np.where(T > 0, np.inf, 0.0) if inf_mu else self._c_tor * T
            st.nL_tor = -st.L_tor
        return weight

    @functools.cached_property
    def inv_w(self) -> np.ndarray:
        """``1 / w`` per cell, 1/m."""
        return 1.0 / self.w

    def fraction(self, a: float) -> np.ndarray:
        """Fraction of each cell inside the contact radius ``a``."""
        return np.clip((a - self.bl) * self.inv_w, 0.0, 1.0)

    # ------------------------------------------------------------------ Jenkins elements
    @staticmethod
    def jenkins(m: np.ndarray, K: np.ndarray, invK: np.ndarray, L: np.ndarray, nL: np.ndarray,
                inc: float, tmp: np.ndarray) -> float:
        """Advance elements in place by displacement ``inc``; return the dissipated energy, J.

        ``m ← clip(m + K inc, -L, L)`` (``nL = -L``); dissipation
        ``Σ |slip| L = Σ (trial - m) m / K``.
        """
        return jenkins_update(m, K, invK, L, inc, tmp, nL)   # compiled when numba is installed

    @staticmethod
    def solve(m: np.ndarray, K: np.ndarray, L: np.ndarray, target: float) -> tuple[float, bool]:
        """Increment ``s`` with ``Σ clip(m + K s, -L, L) = target`` (exact, piecewise linear).

        The sum is monotone non-decreasing in ``s``. A target at or beyond the full-sliding value
        ``±ΣL`` returns the smallest increment that reaches full sliding and ``gross=True``.
        """
        m0 = np.clip(m, -L, L)
        F0 = float(m0.sum())
        if target == F0:
            return 0.0, False
        sgn = 1.0 if target > F0 else -1.0
        act = K > 0
        Ka = K[act]
        room = (L[act] - sgn * m0[act]) / Ka  # >= 0; inf without friction
        need = sgn * (target - F0)
        fin = np.isfinite(room)
        k_inf = float(Ka[~fin].sum())
        r = room[fin]
        kf = Ka[fin]
        order = np.argsort(r)
        r = r[order]
        kf = kf[order]
        # gain at breakpoint j: sum_{i<j} k_i r_i + r_j (sum_{i>=j} k_i + k_inf)
        kr = np.concatenate(([0.0], np.cumsum(kf * r)))
        k_rest = (kf[::-1].cumsum()[::-1]) + k_inf
        gain = kr[:-1] + r * k_rest
        j = int(np.searchsorted(gain, need, side="left"))
        if j < r.size:
            slope = k_rest[j]
            s = (need - kr[j]) / slope
            return sgn * float(s), False
        if k_inf > 0:
            return sgn * float((need - kr[-1]) / k_inf), False
        return sgn * float(r[-1] if r.size else 0.0), True

    @staticmethod
    def stick_radius(m: np.ndarray, L: np.ndarray, bl: np.ndarray, radius: float) -> float:
        """Outer radius of the central stick zone: the left edge of the first element at its
        slip limit (cells out of contact count as slipping), or ``radius``."""
        slip = np.abs(m) >= L
        i = int(np.argmax(slip))
        return float(bl[i]) if slip[i] else radius
