"""The :class:`Contact`: composition root of profile, materials and interface."""
from __future__ import annotations

from functools import cached_property
from typing import TYPE_CHECKING, Any

import numpy as np

from .errors import NotSupportedError, OutsideTheoryError, ParameterError
from .materials import Material, effective_moduli
from .materials.pair import EffectiveModuli
from .numeric.quadrature import DEFAULT_RTOL
from .numeric.roots import bracketed_root
from .params import Param, as_float_array
from .profiles import Profile
from .profiles.base import ROUNDING, root_rtol
from .states import NormalState

if TYPE_CHECKING:  # torsion (issue 3)
    from .torsion import TorsionState, TwistHistory

__all__ = ["Contact"]


class Contact:
    """An axisymmetric contact of a profile between two bodies.

    Parameters
    ----------
    profile : Profile
        Gap between the undeformed surfaces, ``f(r)``.
    materials : (Material, Material)
        The two bodies (one may be :class:`~contactlab.Rigid`).
    friction : float, optional
        Coulomb friction coefficient μ (> 0); ``None`` means no slip (μ → ∞).
    work_of_adhesion : float, optional
        Dupré work of adhesion Δγ, J/m² (>= 0; JKR through the MDR).
    rtol : float, optional
        Relative tolerance of every numeric route (quadratures, root finds); default 1e-10.

    Examples
    --------
    >>> import contactlab as cl
    >>> steel = cl.Elastic(E=210e9, nu=0.3)
    >>> c = cl.Contact(cl.profiles.Paraboloid(R=0.01), materials=(steel, steel))
    >>> s = c.normal(force=100.0)
    >>> round(s.radius * 1e6, 3)  # µm
    186.626
    """

    def __init__(self, profile: Profile, materials: tuple[Material, Material], *,
                 friction: float | None = None, work_of_adhesion: float | None = None,
                 rtol: float | None = None) -> None:
        if not isinstance(profile, Profile):
            raise ParameterError(f"profile={profile!r} is invalid: expected a contactlab "
                                 "Profile (e.g. contactlab.profiles.Paraboloid(R=0.01)).")
        try:
            m1, m2 = materials
        except (TypeError, ValueError) as err:
            raise ParameterError(f"materials={materials!r} is invalid: give two bodies, "
                                 "e.g. (Elastic(E=..., nu=...), Rigid()).") from err
        self.profile = profile
        self.materials = (m1, m2)
        self.friction = None if friction is None else Param(
            "friction", "mu", "1", "positive", "friction coefficient").check(friction)
        self.work_of_adhesion = None if work_of_adhesion is None else Param(
            "work_of_adhesion", "Delta_gamma", "J/m^2", "nonnegative",
            "work of adhesion").check(work_of_adhesion)
        self.rtol = DEFAULT_RTOL if rtol is None else Param(
            "rtol", "rtol", "1", "positive", "relative tolerance").check(rtol)
        if self.rtol >= 1:
            raise ParameterError(f"rtol={rtol!r} is invalid: it must satisfy 0 < rtol < 1.")
        if any(getattr(m, "is_viscoelastic", False) for m in self.materials):
            from .physics.viscoelastic import check_pair
            check_pair(m1, m2)  # only (viscoelastic, rigid) is covered (physics.md §7)
        else:
            self.moduli  # validate the pair now

    def __repr__(self) -> str:
        extra = "".join(f", {k}={v!r}" for k, v in (("friction", self.friction),
                        ("work_of_adhesion", self.work_of_adhesion)) if v is not None)
        return f"Contact({self.profile!r}, materials={self.materials!r}{extra})"

    @cached_property
    def moduli(self) -> EffectiveModuli:
        """Effective normal (E*), tangential (G*) and torsional (G_t) moduli, Pa."""
        return effective_moduli(*self.materials)

    @property
    def is_adhesive(self) -> bool:
        return bool(self.work_of_adhesion)

    # ------------------------------------------------------------------ normal contact
    def normal(self, *, depth: Any = None, force: Any = None, radius: Any = None,
               branch: str = "stable") -> NormalState:
        """Frictionless (non-adhesive) normal contact for given depth, force or contact radius.

        Exactly one of the keywords; scalars or arrays (the state has their shape).

        Parameters
        ----------
        depth : float or array_like, optional
            Indentation depth ``d``, m. ``d <= 0`` gives zero force and zero radius.
        force : float or array_like, optional
            Normal force ``F_N``, N (``<= 0`` gives the unloaded state).
        radius : float or array_like, optional
            Contact radius ``a``, m (not for a flat punch, whose radius is fixed).
        branch : {"stable", "unstable"}
            Adhesive contacts only (``work_of_adhesion > 0``): which JKR equilibrium to return
            for ``depth=``/``force=``; see :func:`contactlab.physics.adhesion.adhesive_normal`.

        Returns
        -------
        NormalState

        Raises
        ------
        OutsideTheoryError
            Contact radius beyond the profile's domain, or a ring contact (g decreasing).
        ConvergenceError
            A bracketed solve failed (never silently).
        """
        given = {k: v for k, v in (("depth", depth), ("force", force), ("radius", radius))
                 if v is not None}
        if len(given) != 1:
            raise ParameterError(f"normal() needs exactly one of depth=, force=, radius=; got "
                                 f"{sorted(given) or 'none'}.")
        if self.is_adhesive:
            from .physics.adhesion import adhesive_normal  # noqa: F401  (adhesion module)
            return adhesive_normal(self, branch=branch, **given)
        if branch != "stable":
            raise ParameterError(f"branch={branch!r} is invalid without adhesion: a non-adhesive "
                                 "contact has a single equilibrium (use branch='stable').")
        key, value = next(iter(given.items()))
        arr = as_float_array(key, value)
        prof = self.profile
        E = self.moduli.normal
        rtol = self.rtol
        if key == "depth":
            d = arr
            a = prof._radius_of_depth(d, rtol)
        elif key == "radius":
            if np.any(arr < 0):
                raise ParameterError(f"radius contains {float(arr[arr < 0].ravel()[0])!r}: contact "
                                     "radii must be >= 0 m.")
            if np.isfinite(prof.wall_radius):
                raise NotSupportedError(
                    f"radius= does not determine the state of {prof!r}: its contact radius is "
                    "fixed by the punch wall. Give depth= or force=.")
            if np.any(arr >= prof.max_radius):
                raise OutsideTheoryError(f"radius={float(np.max(arr))!r} m is invalid: it must stay below "
                                         f"max_radius={prof.max_radius!r} m of {prof!r}.")
            a = arr.copy()
            a[a < prof.flat_radius] = np.where(a[a < prof.flat_radius] > 0, prof.flat_radius, 0.0)
            g_a, g_a_err = prof._g_with_error(a, rtol)
            d = np.where(a > 0, g_a, 0.0)
            prof._check_monotone_upto(float(np.max(a, initial=0.0)), float(np.max(d, initial=0.0)))
        else:
            a, d = self._radius_depth_of_force(arr, rtol)
        pos = a > 0
        all_pos = bool(pos.all())
        g_int, g_int_err = prof._g_integral_with_error(a, rtol)
        ad = a * d
        F = ad - g_int
        F *= 2.0 * E
        # absolute force error: quadrature of ∫g, rounding of the difference, and (force control)
        # the residual of the radius solve against the requested force; errors of a enter F only
        # at second order because dF/da = 2E*(d - g(a)) = 0 at fixed depth.
        F_err = np.abs(ad)
        F_err += np.abs(g_int)
        F_err *= ROUNDING
        F_err += np.abs(g_int_err)
        F_err *= 2.0 * E
        if not all_pos:
            F = np.where(pos, F, 0.0)
            F_err = np.where(pos, F_err, 0.0)
        if key == "force":
            F_err = F_err + np.where(arr > 0, np.abs(F - arr), 0.0)
        elif key == "radius":       # the depth g(a) itself carries the error of g
            F_err = F_err + np.where(a > 0, 2.0 * E * a * np.abs(g_a_err), 0.0)
        with np.errstate(divide="ignore", invalid="ignore"):
            rel = F_err / F
        if not all_pos or rel.ndim == 0:
            rel = np.where(F > 0, rel, 0.0)
        meta = {"routes": {"g": prof.g_route}, "rtol": self.rtol, "control": key,
                "error_estimate": float(rel) if rel.ndim == 0 else rel}
        return NormalState(self, np.asarray(d, float), np.asarray(a, float), F, meta)

    def _force_of_radius(self, a: np.ndarray, rtol: float | None = None) -> np.ndarray:
        """Non-adhesive force at contact radius a: ``2E*(a g(a) - ∫_0^a g)``."""
        prof = self.profile
        rtol = self.rtol if rtol is None else rtol
        return 2.0 * self.moduli.normal * (a * prof._g(a, rtol) - prof._g_integral(a, rtol))

    def _radius_depth_of_force(self, F: np.ndarray, rtol: float | None = None
                               ) -> tuple[np.ndarray, np.ndarray]:
        rtol = self.rtol if rtol is None else rtol
        prof = self.profile
        E = self.moduli.normal
        a = np.zeros(F.shape)
        d = np.zeros(F.shape)
        pos = F > 0
        if not np.any(pos):
            return a, d
        Fp = F[pos]
        ap = np.zeros(Fp.shape)
        solve = np.ones(Fp.shape, dtype=bool)
        if np.isfinite(prof.wall_radius):
            b = prof.wall_radius
            F_wall = float(self._force_of_radius(np.array(b), rtol)) if prof.flat_radius < b else 0.0
            at_wall = Fp >= F_wall
            ap[at_wall] = b
            solve = ~at_wall
            limit = b
        else:
            limit = prof.max_radius
        if np.any(solve):
            Fs = Fp[solve]
            terms = prof.power_terms()
            fast = (prof._radius_of_reduced_force(Fs / (2 * E), rtol)
                    if hasattr(prof, "_radius_of_reduced_force") else None)
            if terms is not None and len(terms) == 1 and not np.isfinite(prof.wall_radius):
                from .symbolic.transform import kappa
                c, n = terms[0]
                ap[solve] = (Fs * (n + 1) / (2 * E * kappa(n) * c * n)) ** (1 / (n + 1))
            elif fast is not None:          # profile-specific solver (convex linear tables)
                ap[solve] = fast
            else:
                lo = np.full(Fs.shape, prof.flat_radius)
                hi = np.full(Fs.shape, prof._initial_bracket())
                for _ in range(400):
                    hi_c = np.minimum(hi, limit * (1 - 1e-15)) if np.isfinite(limit) else hi
                    short = self._force_of_radius(hi_c, rtol) < Fs
                    if not np.any(short):
                        hi = hi_c
                        break
                    at_limit = short & (hi_c >= limit * (1 - 1e-15))
                    if np.any(at_limit) and not np.isfinite(prof.wall_radius):
                        i = int(np.argmax(at_limit))
                        raise OutsideTheoryError(
                            f"force={float(Fs[i])!r} N needs a contact radius >= max_radius={limit!r} m "
                            f"of {prof!r}; reduce the force.")
                    lo = np.where(short, hi_c, lo)
                    hi = np.where(short, hi * 4.0, hi)
                ap[solve] = bracketed_root(lambda x, idx: self._force_of_radius(x, rtol), Fs, lo, hi,
                                           rtol=root_rtol(rtol), what="contact radius")
        if np.isfinite(prof.wall_radius):
            # at the wall the depth follows from F = 2E*(b d - ∫_0^b g)
            dp = np.where(ap >= prof.wall_radius, (Fp / (2 * E) + prof._g_integral(ap, rtol)) / ap,
                          prof._g(ap, rtol))
        else:
            dp = prof._g(ap, rtol)
        a[pos] = ap
        d[pos] = dp
        prof._check_monotone_upto(float(np.max(ap)), float(np.max(dp)))
        return a, d

    # ---- adhesion (issue 6)
    def pull_off(self, control: str = "force") -> NormalState:
        """State at detachment of an adhesive contact (JKR through the MDR, physics.md §4).

        Parameters
        ----------
        control : {"force", "displacement"}
            Force control: minimum of ``F(a)`` (sphere: ``-3/2 πΔγR``). Displacement control
            (fixed grips): minimum of ``d(a)`` (sphere: ``-5/6 πΔγR``).

        Returns
        -------
        AdhesiveNormalState
            ``.force``, ``.radius``, ``.depth`` at detachment.
        """
        self._require_adhesion("pull_off")
        from .physics.adhesion import pull_off
        return pull_off(self, control)

    def adhesion_cycle(self, *, depth: Any = None, force: Any = None):
        """Approach/retraction history with JKR jump-in and jump-off; see
        :func:`contactlab.physics.adhesion.adhesion_cycle`."""
        self._require_adhesion("adhesion_cycle")
        from .physics.adhesion import adhesion_cycle
        return adhesion_cycle(self, depth=depth, force=force)

    def _require_adhesion(self, what: str) -> None:
        if not self.is_adhesive:
            raise ParameterError(f"{what}() needs work_of_adhesion > 0; got "
                                 f"work_of_adhesion={self.work_of_adhesion!r}.")

    # ---- viscoelastic materials (issue 6)
    def viscoelastic_history(self, *, time: Any, depth: Any = None, force: Any = None,
                             n_springs: int | None = None, max_radius: float | None = None):
        """Normal contact history of a rigid indenter on a viscoelastic half-space (MDR, [H3]).

        See :func:`contactlab.viscoelastic.viscoelastic_history`.
        """
        from .viscoelastic import viscoelastic_history
        return viscoelastic_history(self, time=time, depth=depth, force=force,
                                    n_springs=n_springs, max_radius=max_radius)

    # ---- tangential contact, load paths, simulation (issue 4)
    def tangential(self, *, depth: Any = None, force: Any = None, radius: Any = None,
                   displacement: Any = None, tangential_force: Any = None,
                   stick_radius: Any = None):
        """Cattaneo–Mindlin tangential contact through the MDR (exact, any profile).

        One normal keyword (``depth=``, ``force=``, ``radius=``) and one tangential keyword
        (``displacement=`` m, ``tangential_force=`` N, ``stick_radius=`` m); scalars or arrays.
        Monotonic shift at constant normal load [physics.md §5]. A tangential force at or above
        ``μF_N`` is gross sliding (``state.gross_sliding``), not an error.

        Returns
        -------
        TangentialState
            ``.tangential_force .displacement .stick_radius .stiffness .shear(r)``.
        """
        from .tangential import tangential
        return tangential(self, depth=depth, force=force, radius=radius, displacement=displacement,
                          tangential_force=tangential_force, stick_radius=stick_radius)

    def shift_history(self, *, displacement: Any, depth: Any = None, force: Any = None):
        """Tangential force for an arbitrary displacement history at constant normal load.

        Exact Masing hysteresis with turning-point memory (closed loops are erased), from the
        Cattaneo–Mindlin virgin curve [physics.md §5].

        Returns
        -------
        ShiftHistory
            ``.displacement .tangential_force .stick_radius .dissipated_energy`` per step.
        """
        from .tangential import shift_history
        return shift_history(self, displacement=displacement, depth=depth, force=force)

    def simulate(self, path: Any, *, outputs: Any = None, n_springs: int | None = None,
                 spacing: str = "edge", snapshots: Any = None, progress: bool = False,
                 approximate: bool = False, strategy: str | None = None,
                 error_estimate: bool = False):
        """Run a :class:`~contactlab.LoadPath` through the MDR foundation with frictional memory.

        See :func:`contactlab.simulation.simulate` for the parameters (``error_estimate=True``
        adds ``result.meta["error_estimates"]``, the spring-discretisation error per series).

        Returns
        -------
        PathResult
        """
        from .simulation import simulate
        return simulate(self, path, outputs=outputs, n_springs=n_springs, spacing=spacing,
                        snapshots=snapshots, progress=progress, approximate=approximate,
                        strategy=strategy, error_estimate=error_estimate)

    # ---- symbolic formula export (issue 6)
    def formulas(self, substitute: bool = False):
        """Named sympy formulas of this contact (normal, torsion, JKR; physics.md §3, §4, §6).

        Parameters
        ----------
        substitute : bool
            Insert the numbers of the profile parameters, of ``E_star``/``G_t`` and, when given,
            of ``mu`` (friction) and ``Delta_gamma`` (work of adhesion). Default: symbolic, with
            the numbers in ``.numbers``.

        Returns
        -------
        contactlab.symbolic.formulas.FormulaSet
            Mapping ``name -> sympy expression``; ``.latex()``, ``.python()``, ``.callable(name)``.

        Examples
        --------
        >>> import contactlab as cl
        >>> c = cl.Contact(cl.profiles.Paraboloid(R=0.01), materials=(cl.Elastic(1e9, 0.5), cl.Rigid()))
        >>> c.formulas()["force_of_depth"]
        4*E_star*sqrt(R)*d**(3/2)/3
        """
        from .symbolic.formulas import contact_formulas
        return contact_formulas(self.profile, self.moduli, friction=self.friction,
                                work_of_adhesion=self.work_of_adhesion, substitute=substitute)

    # ---- torsion (issue 3)
    def torsion(self, *, depth: Any = None, force: Any = None, radius: Any = None,
                twist: Any = None, torque: Any = None, stick_radius: Any = None,
                method: str | None = None) -> "TorsionState":
        """Monotonic twist of the contact at constant normal load (physics.md §6).

        Give the normal preload by exactly one of ``depth=``, ``force=``, ``radius=`` and the twist
        by exactly one of ``twist=``, ``torque=``, ``stick_radius=``; scalars or arrays (the two
        broadcast together; the state has the broadcast shape).

        Parameters
        ----------
        depth, force, radius : float or array_like
            Normal preload: indentation depth (m), normal force (N) or contact radius (m).
        twist : float or array_like, optional
            Twist angle ``φ``, rad (sign gives the sense of rotation).
        torque : float or array_like, optional
            Torque ``M``, N·m; ``|M|`` must not exceed the sliding torque of the model.
        stick_radius : float or array_like, optional
            Stick radius ``c``, m, ``0 <= c <= a`` (not for ``method="no-slip"``).
        method : {"no-slip", "exact", "mdr"}, optional
            ``"no-slip"`` (Reissner-Sagoci, μ → ∞); ``"exact"`` (Jäger's partial-slip solution);
            ``"mdr"`` (MDR narrow-slip springs with μ* = 2μ: fast, exact only as ``c → a``; warns
            with :class:`~contactlab.errors.ValidityWarning` when its torque error exceeds 1 %).
            Default: ``"no-slip"`` without friction, else ``"exact"``.

        Returns
        -------
        TorsionState
            ``.twist .torque .stick_radius .slip .method .normal .shear(r) .displacement(r)``.

        Raises
        ------
        ParameterError
            ``method="exact"``/``"mdr"`` without ``friction``; stick radius outside ``[0, a]``.
        OutsideTheoryError
            A torque beyond the sliding torque.
        NotSupportedError
            ``stick_radius=`` with ``method="no-slip"``; slip with adhesion.

        Notes
        -----
        All models use the torsional modulus ``G_t`` (``1/G_t = 1/G1 + 1/G2``), not ``G*``.
        For smooth profiles full sliding is reached only asymptotically (``φ → ∞``); stick radii
        below ``1e-100 a`` are reported as 0 with ``slip=True``.

        Examples
        --------
        >>> import contactlab as cl
        >>> steel = cl.Elastic(E=210e9, nu=0.3)
        >>> c = cl.Contact(cl.profiles.Paraboloid(R=0.01), materials=(steel, steel), friction=0.3)
        >>> s = c.torsion(force=100.0, twist=1e-4)
        >>> round(s.stick_radius / s.radius, 4)
        0.9875
        """
        from .torsion import solve_torsion
        return solve_torsion(self, depth=depth, force=force, radius=radius, twist=twist,
                             torque=torque, stick_radius=stick_radius, method=method)

    def twist_history(self, *, twist: Any, depth: Any = None, force: Any = None,
                      method: str | None = None) -> "TwistHistory":
        """Torque response to an arbitrary twist history at constant normal load.

        Parameters
        ----------
        twist : array_like, 1D
            Twist per step, rad, starting from the untwisted virgin state.
        depth, force : float
            Constant normal preload (exactly one).
        method : {"exact", "mdr", "no-slip"}, optional
            Default ``"exact"`` with friction, ``"no-slip"`` without.

        Returns
        -------
        TwistHistory
            Per-step ``.twist .torque .stick_radius .dissipated_energy`` (cumulative, J).

        Notes
        -----
        Masing's rule with turning-point memory (physics.md §6.5): after each reversal the
        loading solution with doubled friction applies from the turning point; loops that close
        are forgotten. The loading curve is solved once, batched, for every step.
        """
        from .torsion import twist_history
        return twist_history(self, twist=twist, depth=depth, force=force, method=method)
