"""The :class:`Contact`: composition root of profile, materials and interface.

A contact validates its parts once, at construction; every method is a one-line delegation to the
driver of its effect in :mod:`contactlab.effects` (which never imports this module).
"""
from __future__ import annotations

import importlib
from functools import cached_property
from typing import TYPE_CHECKING, Any, ClassVar

from . import effects
from ._lazy import attach
from .errors import ParameterError
from .materials import Material, effective_moduli
from .materials.pair import EffectiveModuli, viscoelastic_body
from .numeric.quadrature import DEFAULT_RTOL
from .params import without_caches
from .params import PLAIN_TYPES, Param, to_si_values
from .profiles import Profile

if TYPE_CHECKING:   # result types of the annotations; the drivers load on first use (_Drivers)
    from .effects.adhesion import AdhesionCycle
    from .effects.fretting import FrettingLoop, FrettingMap
    from .effects.normal import NormalState
    from .effects.path import PathResult
    from .effects.tangential import ShiftHistory, TangentialState
    from .effects.torsion import TorsionState, TwistHistory
    from .effects.viscoelastic import ViscoelasticHistory
    from .effects.wear import WearResult

__all__ = ["Contact"]

#: result classes this module used to import eagerly, still importable from here
_RESULTS = {"AdhesionCycle": "adhesion", "FrettingLoop": "fretting", "FrettingMap": "fretting",
            "NormalState": "normal", "PathResult": "path", "ShiftHistory": "tangential",
            "TangentialState": "tangential", "TorsionState": "torsion",
            "TwistHistory": "torsion", "ViscoelasticHistory": "viscoelastic",
            "WearResult": "wear"}


class _Drivers:
    """The effect drivers (modules of :mod:`contactlab.effects`), each imported on first use.

    ``import contactlab`` loads none of them (together ~20 ms of start-up); once imported, a
    driver is a plain instance attribute, so a call pays one attribute lookup, as it paid one
    global lookup when the modules were imported at the top of this file.
    """

    _NAMES = frozenset({"adhesion", "fretting", "normal", "path", "tangential", "torsion",
                        "viscoelastic", "wear"})

    def __getattr__(self, name: str) -> Any:
        if name not in self._NAMES:
            raise AttributeError(f"contactlab.effects has no driver {name!r}")
        module = importlib.import_module(f"{effects.__name__}.{name}")
        setattr(self, name, module)
        return module


_drivers = _Drivers()


__getattr__, __dir__, _LAZY = attach(__name__, package=effects.__name__,
                                     submod_attrs={mod: [n for n, m in _RESULTS.items() if m == mod]
                                                   for mod in set(_RESULTS.values())})


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

    #: the contact's own parameters (scene files take them from their [interface] and
    #: [solver] tables)
    params: ClassVar[tuple[Param, ...]] = (
        Param("friction", "mu", "1", "positive", "friction coefficient"),
        Param("work_of_adhesion", "Delta_gamma", "J/m^2", "nonnegative", "work of adhesion"),
        Param("rtol", "rtol", "1", "positive", "relative tolerance"),
    )

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
        p_friction, p_adhesion, p_rtol = self.params
        self.friction = None if friction is None else p_friction.check(friction)
        self.work_of_adhesion = (None if work_of_adhesion is None
                                 else p_adhesion.check(work_of_adhesion))
        self.rtol = DEFAULT_RTOL if rtol is None else p_rtol.check(rtol)
        if self.rtol >= 1:
            raise ParameterError(f"rtol={rtol!r} is invalid: it must satisfy 0 < rtol < 1.")
        if any(getattr(m, "is_viscoelastic", False) for m in self.materials):
            viscoelastic_body(m1, m2)  # only (viscoelastic, rigid) is covered
        else:
            _ = self.moduli  # validate the pair now (and cache it)

    def __getstate__(self) -> dict[str, Any]:
        # per-contact caches stay behind (rebuilt on first use): a used contact pickles like a
        # fresh one, for process pools and distributed sweeps
        return without_caches(self.__dict__)

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
        """True when the contact has a work of adhesion ``Δγ > 0`` J/m² (JKR states)."""
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
            for ``depth=``/``force=``; see :func:`contactlab.effects.adhesion.adhesive_normal`.

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
        if not (type(force) in PLAIN_TYPES and type(depth) in PLAIN_TYPES
                and type(radius) in PLAIN_TYPES):       # a value with a unit ("100 N")
            depth, force, radius = to_si_values(depth=depth, force=force, radius=radius)
        solve = _drivers.adhesion.adhesive_normal if self.is_adhesive else _drivers.normal.normal
        return solve(self, depth=depth, force=force, radius=radius, branch=branch)

    # ---- adhesion (issue 6)
    def pull_off(self, control: str = "force") -> NormalState:
        """State at detachment of an adhesive contact (JKR through the MDR, theory §4).

        Parameters
        ----------
        control : {"force", "displacement"}
            Force control: minimum of ``F(a)`` (sphere: ``-3/2 πΔγR``). Displacement control
            (fixed grips): minimum of ``d(a)`` (sphere: ``-5/6 πΔγR``).

        Returns
        -------
        AdhesiveNormalState
            ``.force`` (N), ``.radius`` (m), ``.depth`` (m) at detachment.
        """
        self._require_adhesion("pull_off")
        return _drivers.adhesion.pull_off(self, control)

    def adhesion_cycle(self, *, depth: Any = None, force: Any = None) -> AdhesionCycle:
        """Approach/retraction history with JKR jump-in and jump-off.

        Parameters
        ----------
        depth : array_like, 1D
            Depth history, m (exactly one of ``depth``/``force``).
        force : array_like, 1D
            Force history, N.

        Returns
        -------
        AdhesionCycle
            Per-step depth (m), force (N), radius (m) and contact flag; see
            :func:`contactlab.effects.adhesion.adhesion_cycle`.
        """
        self._require_adhesion("adhesion_cycle")
        depth, force = to_si_values(depth=depth, force=force)
        return _drivers.adhesion.adhesion_cycle(self, depth=depth, force=force)

    def _require_adhesion(self, what: str) -> None:
        if not self.is_adhesive:
            raise ParameterError(f"{what}() needs work_of_adhesion > 0; got "
                                 f"work_of_adhesion={self.work_of_adhesion!r}.")

    # ---- viscoelastic materials (issue 6)
    def viscoelastic_history(self, *, time: Any, depth: Any = None, force: Any = None,
                             n_springs: int | None = None, max_radius: float | None = None
                             ) -> ViscoelasticHistory:
        """Normal contact history of a rigid indenter on a viscoelastic half-space (MDR, [H3]).

        Parameters
        ----------
        time : array_like, 1D
            Times, s (increasing).
        depth, force : array_like, 1D
            Depth history (m) or force history (N); exactly one.
        n_springs : int, optional
            Foundation elements; ``max_radius`` (m) bounds the foundation.

        Returns
        -------
        ViscoelasticHistory
            See :func:`contactlab.effects.viscoelastic.viscoelastic_history`.
        """
        time, depth, force, max_radius = to_si_values(time=time, depth=depth, force=force,
                                                      max_radius=max_radius)
        return _drivers.viscoelastic.viscoelastic_history(self, time=time, depth=depth, force=force,
                                                          n_springs=n_springs, max_radius=max_radius)

    # ---- tangential contact, load paths, simulation (issue 4)
    def tangential(self, *, depth: Any = None, force: Any = None, radius: Any = None,
                   displacement: Any = None, tangential_force: Any = None,
                   stick_radius: Any = None) -> TangentialState:
        """Cattaneo–Mindlin tangential contact through the MDR (exact, any profile).

        One normal keyword (``depth=``, ``force=``, ``radius=``) and one tangential keyword
        (``displacement=`` m, ``tangential_force=`` N, ``stick_radius=`` m); scalars or arrays.
        Monotonic shift at constant normal load [theory §5]. A tangential force at or above
        ``μF_N`` is gross sliding (``state.gross_sliding``), not an error.

        Returns
        -------
        TangentialState
            ``.tangential_force .displacement .stick_radius .stiffness .shear(r)``.
        """
        depth, force, radius, displacement, tangential_force, stick_radius = to_si_values(
            depth=depth, force=force, radius=radius, displacement=displacement,
            tangential_force=tangential_force, stick_radius=stick_radius)
        return _drivers.tangential.tangential(self, depth=depth, force=force, radius=radius,
                                              displacement=displacement,
                                              tangential_force=tangential_force,
                                              stick_radius=stick_radius)

    def shift_history(self, *, displacement: Any, depth: Any = None, force: Any = None
                      ) -> ShiftHistory:
        """Tangential force for an arbitrary displacement history at constant normal load.

        Exact Masing hysteresis with turning-point memory (closed loops are erased), from the
        Cattaneo–Mindlin virgin curve [theory §5].

        Parameters
        ----------
        displacement : array_like, 1D
            Tangential displacement history, m.
        depth, force : float
            Constant normal preload, m or N (exactly one).

        Returns
        -------
        ShiftHistory
            Per step: ``.displacement`` (m), ``.tangential_force`` (N), ``.stick_radius`` (m),
            ``.dissipated_energy`` (J, cumulative).
        """
        displacement, depth, force = to_si_values(displacement=displacement, depth=depth,
                                                  force=force)
        return _drivers.tangential.shift_history(self, displacement=displacement, depth=depth,
                                                 force=force)

    def simulate(self, path: Any, *, outputs: Any = None, n_springs: int | None = None,
                 spacing: str | None = None, snapshots: Any = None, progress: bool = False,
                 approximate: bool = False, strategy: str | None = None,
                 error_estimate: bool = False, method: str | None = None,
                 n_rings: int | None = None,
                 torque_rtol: float | None = None) -> PathResult:
        """Run a :class:`~contactlab.LoadPath` through the MDR foundation with frictional memory.

        See :func:`contactlab.effects.path.simulate` for the parameters (``error_estimate=True``
        adds ``result.meta["error_estimates"]``, the discretisation error per series). A path with
        twist or torque runs the exact torsion solver by default (``method="exact"``, ``n_rings``
        rings, or as many as ``torque_rtol``, the torque's accuracy relative to the sliding torque,
        needs); ``method="mdr"`` keeps the MDR spring model.

        Parameters
        ----------
        path : LoadPath
            The load path; its quantities are SI (m, N, rad, N*m, s).

        Returns
        -------
        PathResult
            Per-step series in SI units (the units are in the ``to_csv`` headers). On the
            spring foundation (``method="mdr"``, and paths without twist or torque) the float
            series asked for are rows of one array (one allocation, cheaper to fault in on long
            paths): ``result.torque.copy()`` holds one series without the others.
        """
        return _drivers.path.simulate(self, path, outputs=outputs, n_springs=n_springs,
                                      spacing=spacing, snapshots=snapshots, progress=progress,
                                      approximate=approximate, strategy=strategy,
                                      error_estimate=error_estimate, method=method, n_rings=n_rings,
                                      torque_rtol=torque_rtol)

    # ---- symbolic formula export (issue 6)
    def formulas(self, substitute: bool = False):
        """Named sympy formulas of this contact (normal, torsion, JKR; theory §3, §4, §6).

        Parameters
        ----------
        substitute : bool
            Insert the numbers of the profile parameters, of ``E_star``/``G_t`` and, when given,
            of ``mu`` (friction) and ``Delta_gamma`` (work of adhesion). Default: symbolic, with
            the numbers in ``.numbers``.

        Returns
        -------
        contactlab.symbolic.formulas.FormulaSet
            Formulas in SI units (lengths m, forces N, moduli Pa, angles rad).
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
                method: str | None = None) -> TorsionState:
        """Monotonic twist of the contact at constant normal load (theory §6).

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
        depth, force, radius, twist, torque, stick_radius = to_si_values(
            depth=depth, force=force, radius=radius, twist=twist, torque=torque,
            stick_radius=stick_radius)
        return _drivers.torsion.solve_torsion(self, depth=depth, force=force, radius=radius,
                                              twist=twist, torque=torque, stick_radius=stick_radius,
                                              method=method)

    def twist_history(self, *, twist: Any, depth: Any = None, force: Any = None,
                      method: str | None = None) -> TwistHistory:
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
        Masing's rule with turning-point memory (theory §6.5): after each reversal the
        loading solution with doubled friction applies from the turning point; loops that close
        are forgotten. The loading curve is solved once, batched, for every step.
        """
        twist, depth, force = to_si_values(twist=twist, depth=depth, force=force)
        return _drivers.torsion.twist_history(self, twist=twist, depth=depth, force=force,
                                              method=method)

    # ---- fretting (issue 15)
    def fretting_loop(self, *, force: Any = None, depth: Any = None,
                      displacement_amplitude: Any = None, twist_amplitude: Any = None,
                      method: str | None = None, criterion: str = "energy_ratio",
                      threshold: float | None = None, n_points: int = 200) -> FrettingLoop:
        """The steady fretting loop under a shift or twist amplitude at constant normal load.

        Parameters
        ----------
        force, depth : float
            Constant normal preload, N or m (exactly one).
        displacement_amplitude : float, optional
            Tangential amplitude ``δ*``, m (Cattaneo–Mindlin through the MDR springs, exact).
        twist_amplitude : float, optional
            Torsional amplitude ``φ*``, rad (exactly one of the two amplitudes).
        method : {"exact", "mdr", "no-slip"}, optional
            Torsion model (default ``"exact"``); the MDR model warns
            (:class:`~contactlab.errors.ValidityWarning`) when its torque, energy per cycle or
            stick radius errs by more than 1 %.
        criterion : {"energy_ratio", "stick_ratio", "torque_ratio"}
            Torsional gross-slip criterion (smooth profiles reach full sliding only as
            ``φ* → ∞``); ``threshold`` defaults to 0.2, 0.1 and 0.95 respectively.
        n_points : int
            Points per loop branch.

        Returns
        -------
        FrettingLoop
            ``.energy .energy_ratio .peak .stick_radius .regime .x .y``; see
            :mod:`contactlab.effects.fretting` and docs/fretting.md.

        Examples
        --------
        >>> import contactlab as cl
        >>> steel = cl.Elastic(E=210e9, nu=0.3)
        >>> c = cl.Contact(cl.profiles.Paraboloid(R=0.01), materials=(steel, steel), friction=0.5)
        >>> loop = c.fretting_loop(force=100.0, displacement_amplitude=10e-6)
        >>> loop.regime, round(loop.energy_ratio, 3)
        ('gross_slip', 0.831)
        """
        force, depth, displacement_amplitude, twist_amplitude = to_si_values(
            force=force, depth=depth, displacement_amplitude=displacement_amplitude,
            twist_amplitude=twist_amplitude)
        return _drivers.fretting.fretting_loop(self, force=force, depth=depth,
                                               displacement_amplitude=displacement_amplitude,
                                               twist_amplitude=twist_amplitude, method=method,
                                               criterion=criterion, threshold=threshold,
                                               n_points=n_points)

    def fretting_map(self, *, force: Any = None, depth: Any = None,
                     displacement_amplitude: Any = None, twist_amplitude: Any = None,
                     method: str | None = None, criterion: str = "energy_ratio",
                     threshold: float | None = None, boundary: bool = True) -> FrettingMap:
        """Fretting regime map over 1D arrays of normal loads and amplitudes.

        Same keywords as :meth:`fretting_loop` with 1D arrays (normal forces in N, amplitudes in
        m or rad); ``boundary=False`` skips the
        torsional boundary root. Returns a :class:`~contactlab.effects.fretting.FrettingMap`
        (``.regime .energy_ratio .energy .stick_ratio .boundary``, ``.plot()``,
        ``.to_dataframe()``, ``.to_csv()``). A large map is computed in blocks of 1024 grid
        points; ``contactlab.fretting_map_sweep`` runs the same blocks on every core or a Dask
        cluster and returns the same map.
        """
        force, depth, displacement_amplitude, twist_amplitude = to_si_values(
            force=force, depth=depth, displacement_amplitude=displacement_amplitude,
            twist_amplitude=twist_amplitude)
        return _drivers.fretting.fretting_map(self, force=force, depth=depth,
                                              displacement_amplitude=displacement_amplitude,
                                              twist_amplitude=twist_amplitude, method=method,
                                              criterion=criterion, threshold=threshold,
                                              boundary=boundary)

    def wear(self, *, force: Any, displacement_amplitude: Any = None, twist_amplitude: Any = None,
             wear_coefficient: Any, cycles: Any, method: str | None = None,
             checkpoints: Any = None, n_grid: int = 400, max_radius: Any = None,
             jump_rtol: float = 1e-4, integrator: str = "explicit") -> WearResult:
        """Fretting wear at constant normal force (Archard's law on the 3D profile).

        Parameters
        ----------
        force : float
            Normal force, N.
        displacement_amplitude, twist_amplitude : float
            Shift amplitude ``δ*`` (m) or twist amplitude ``φ*`` (rad); exactly one.
        wear_coefficient : float
            Archard's ``k = K/H``, 1/Pa (worn depth per unit pressure and slip); 0 gives the
            wear-free loops.
        cycles : float
            Number of cycles.
        method : {"exact", "mdr"}, optional
            Torsion: Jäger's exact slip (default) or the MDR springs (fast approximation; warns
            when its worn volume or stick radius errs by more than 1 %).
        checkpoints : int or array_like, optional
            Cycle counts at which the worn profile is stored (an int: that many, log-spaced);
            the last is always ``cycles``.
        n_grid : int
            Intervals of the worn-profile table.
        max_radius : float, optional
            Grid radius, m (default: estimated from the fresh loop and a wear-volume bound).
        jump_rtol : float
            Local error of one cycle jump relative to the indentation depth plus the largest
            wear depth (explicit: Euler vs Heun; implicit: the embedded order-2 solution).
        integrator : {"explicit", "implicit"}
            Cycle jumps: ``"explicit"`` Heun steps (the reference; their length is bounded by
            the stiffness of the wear equation, about one cycle per step in long gross-slip
            runs at large ``k``) or ``"implicit"`` Rosenbrock-W steps with the rate's Jacobian
            (ROS34PW2, L-stable: the length is bounded by the accuracy). Both report
            ``meta["error_estimates"]`` (relative, per quantity, from the accumulated local
            errors); docs/fretting.md section 8.

        Returns
        -------
        WearResult
            ``.profiles`` (:class:`~contactlab.profiles.Tabulated` at the checkpoints),
            ``.profile``, series ``.cycles .depth .radius .stick_radius .volume
            .max_wear_depth .dissipated_energy``, ``.plot()``; docs/fretting.md.
        """
        force, displacement_amplitude, twist_amplitude, wear_coefficient, max_radius = to_si_values(
            force=force, displacement_amplitude=displacement_amplitude,
            twist_amplitude=twist_amplitude, wear_coefficient=wear_coefficient,
            max_radius=max_radius)
        return _drivers.wear.wear(self, force=force, displacement_amplitude=displacement_amplitude,
                                  twist_amplitude=twist_amplitude, wear_coefficient=wear_coefficient,
                                  cycles=cycles, method=method, checkpoints=checkpoints,
                                  n_grid=n_grid, max_radius=max_radius, jump_rtol=jump_rtol,
                                  integrator=integrator)
