"""A vectorised contact law for many contacts (DEM and multibody codes): :class:`ContactLaw`.

Every contact of a law belongs to one power-law profile family ``f = c r^n`` (``n >= 0.01``:
:class:`~contactlab.profiles.Paraboloid` with per-contact ``R``, :class:`~contactlab.profiles.Cone`
with per-contact ``slope``, :class:`~contactlab.profiles.PowerLaw` with per-contact ``c``) or
to the flat punches (:class:`~contactlab.profiles.FlatPunch`, per-contact ``radius``), with
its own moduli and friction. :meth:`ContactLaw.step` advances all contacts by one time step and
carries each contact's memory (Masing turning points) to the next.

At constant normal load the law is exact: normal contact by the closed forms, Cattaneo–Mindlin
by its closed form and exact (Jäger) torsion by the family's certified master curve
(:mod:`contactlab.physics.master`), both with Masing's rule and a turning-point stack of bounded
depth per contact (:mod:`contactlab.physics.masing_stack`). The load counts as constant while
the depth stays within ``load_rtol`` of the depth at which the contact's memory started.
"""
from __future__ import annotations

import math
import warnings
from collections.abc import Mapping
from typing import Any

import numpy as np

from ..citations import Citations
from ..errors import NotSupportedError, OutsideTheoryError, ParameterError, UnknownNameError
from ..errors import ValidityWarning
from ..numeric.cube_root import cbrt as _cbrt     # the compiled normal pass's, to the bit
from ..params import as_float_array, as_real, check_memory, exactly_one
from ..physics import law_kernel as _kernel
from ..physics import law_springs as _springs
from ..physics import master as _master
from ..physics.masing_stack import STACK_FIELDS, masing_step, new_stack
from ..profiles import Cone, FlatPunch, Paraboloid, PowerLaw
from ..symbolic.transform import kappa
from .law_checks import FixedParameter, _per_contact, _per_step, _short, checked_state_entry
from .law_checks import FixedGeometry, SlopeCheck, warn_model_error
from . import law_device as _device
from . import law_springs_numpy as _np_springs
from .law_pool import (SPRING_FIELDS, SpringPool, law_memory, law_spring_memory,
                       upgraded_state)
from .law_step import (_OUT_FIELDS, LAW_BASIS, STEP_UNITS, LawStep, law_sources,
                       springs_only_outputs)
from .law_tangent import snapshot as _tangent_snapshot
from .law_tangent import tangent as _tangent

__all__ = ["ContactLaw", "LawStep", "law_memory", "law_spring_memory", "DEFAULT_MEMORY",
           "DEFAULT_LOAD_RTOL", "DEFAULT_SPRINGS", "DEFAULT_SPRING_COVER", "STEP_UNITS", "LAW_BASIS",
           "MODEL_ERROR_WARN"]

#: turning points stored per contact and channel (four nested loops)
DEFAULT_MEMORY = 8
#: relative change of the depth up to which the normal load counts as constant
DEFAULT_LOAD_RTOL = 1e-9
#: MDR springs (cells) per contact once its normal load changes
DEFAULT_SPRINGS = 16
#: the springs of a contact cover this multiple of its contact radius (grown when exceeded)
DEFAULT_SPRING_COVER = 1.5
_NO_CONTACTS = np.zeros(0, np.int64)
#: a step's model error (:attr:`LawStep.model_error`) above this warns, once per law and quantity
MODEL_ERROR_WARN = 0.01
#: the quantities a law step carries a model error for (the causes warned about separately)
_MODEL_ERROR_CAUSES = ("tangential_force", "torque")

_NO_FLAT = np.zeros(1)
#: sources of a law step (exact normal, Cattaneo–Mindlin and Jäger torsion with Masing memory,
#: the MDR springs under a changing load)
_LAW_SOURCES = ("PH", "H1", "Sn65", "Cat38", "Min49", "MD53", "J95", "D54", "S")


class ContactLaw:
    """Normal, tangential and torsional response of ``n`` contacts with memory, vectorised.

    Parameters
    ----------
    profile : Profile class or instance
        :class:`~contactlab.profiles.Paraboloid` (per-contact ``R``),
        :class:`~contactlab.profiles.Cone` (per-contact ``slope``),
        :class:`~contactlab.profiles.PowerLaw` (per-contact ``c``, one exponent ``n >= 0.01``) or
        :class:`~contactlab.profiles.FlatPunch` (per-contact ``radius``); an instance gives the
        same geometry to every contact.
    R, slope, c, radius : float or array_like, optional
        Geometry per contact (m, 1, m^(1-n), m), by the family's parameter name.
    n : float, optional
        Exponent of a :class:`~contactlab.profiles.PowerLaw` family.
    E_star, G_star, G_torsion : float or array_like, optional
        Effective normal, tangential (Cattaneo–Mindlin) and torsional moduli, Pa, per contact;
        or ``materials=(m1, m2)`` (the same pair for every contact).
    friction : float or array_like
        Coulomb coefficient per contact (> 0).
    torsion : {"exact"}
        Torsion model at constant load (Jäger's exact partial slip).
    memory : int
        Turning points stored per contact and channel. A reversal that finds a contact's stack
        full forgets the innermost open loop (see :mod:`contactlab.physics.masing_stack`): the
        contact's results are approximate from then on, ``exact`` is False for it until its
        memory is reset, and the step emits one :class:`~contactlab.errors.ValidityWarning`.
    load_rtol : float
        Relative change of the depth, from the depth at which a contact's memory started, up to
        which the normal load counts as constant.
    springs : int
        MDR springs (edge-refined cells of the Winkler foundation) per contact for contacts whose
        load changed beyond ``load_rtol``; ``0`` raises :class:`~contactlab.errors.OutsideTheoryError`
        instead (a strictly constant-load law).
    spring_cover : float or array_like
        The springs of a contact cover ``spring_cover`` times the larger of its contact radii
        before and at the change (per contact, >= 1); a contact radius beyond the cover grows it
        (the element forces are carried over by their cumulative line load, approximate).
    spring_reserve : float
        Fraction of the contacts (0 to 1) whose spring rows are allocated, and their memory
        pages faulted in, when the law is built (and by ``reset()``): ``52 + 16 springs`` bytes
        per row (308 B at 16 springs), counted against the memory budget then. A first
        changing-load step of up to that many contacts then skips that cost (measured ~0.1 µs
        CPU per row; docs/dem.md "Memory per contact"). Default 0: rows are allocated when
        contacts first switch onto their springs.
    size : int, optional
        Number of contacts when every parameter is a scalar.
    fast : bool, optional
        Use the compiled kernel (numba, extra ``fast``); default: when numba is installed and
        the environment does not force numpy (``CONTACTLAB_BACKEND=numpy``). ``False`` runs the
        numpy reference path: bit-identical at constant load; contacts on springs agree to
        ~1e-12 of the largest value (the cell integrals are summed in another order).
    parallel : bool
        Run the compiled kernel (on ``backend="cupy"``: the host's compiled spring passes) on
        numba's threads (over contacts; bit-identical to the serial kernel). Off by default: a
        threading layer inside forked worker processes can hang.
    backend : {"numpy", "numba", "cupy", "xp-numpy"}, optional
        numpy reference, compiled (``fast=True``), CUDA GPU through CuPy (extra ``gpu``, CuPy
        results: :mod:`contactlab.effects.law_device`) or the GPU code on numpy (tests).
    warn_model_error : bool
        Emit a :class:`~contactlab.errors.ValidityWarning` when a step's model error (contacts
        on springs after a load change, :attr:`LawStep.model_error`) exceeds 1 % for the
        tangential force or the torque: once per law and quantity, its text also in that step's
        ``meta["notes"]``. ``False`` (or ``law.warn_model_error = False`` later) silences it;
        the model error itself is always in the step.

    Notes
    -----
    A step with both a displacement and a twist treats the two slip problems independently,
    each with the full friction limit (their slip conditions couple in reality; outside the
    theory): a :class:`~contactlab.errors.ValidityWarning` is emitted once per law. A contact
    whose depth is <= 0 carries nothing and its memory is cleared; :meth:`reset` clears it on
    request (a DEM code recycling a contact slot). The displacement and twist are the relative
    motions accumulated since the contact's memory started.

    Examples
    --------
    >>> import numpy as np, contactlab as cl
    >>> law = cl.ContactLaw(cl.profiles.Paraboloid, R=[0.01, 0.02], E_star=1.15e11,
    ...                     G_star=4.4e10, G_torsion=4.0e10, friction=0.3)
    >>> out = law.step(force=[10.0, 20.0], twist=[1e-4, 2e-4])
    >>> out.torque.shape
    (2,)
    """

    #: per-contact parameters, fixed when the law is built: read-only views (held as ``_<name>``)
    kc, E_star, G_star, G_torsion, friction, spring_cover = (FixedParameter() for _ in range(6))

    def __init__(self, profile: Any, *, R: Any = None, slope: Any = None, c: Any = None,
                 radius: Any = None, n: float | None = None, E_star: Any = None, G_star: Any = None,
                 G_torsion: Any = None, friction: Any = None, materials: Any = None,
                 torsion: str = "exact", memory: int = DEFAULT_MEMORY,
                 load_rtol: float = DEFAULT_LOAD_RTOL, size: int | None = None,
                 fast: bool | None = None, parallel: bool = False,
                 springs: int = DEFAULT_SPRINGS,
                 spring_cover: Any = DEFAULT_SPRING_COVER, spring_reserve: float = 0.0,
                 warn_model_error: bool = True, backend: str | None = None) -> None:
        cls = profile if isinstance(profile, type) else type(profile)
        inst = None if isinstance(profile, type) else profile
        if not (isinstance(cls, type) and issubclass(cls, (PowerLaw, FlatPunch))):
            raise NotSupportedError(f"profile={profile!r} is not supported by ContactLaw: use "
                                    "Paraboloid, Cone, PowerLaw (f = c r^n, n >= "
                                    f"{_master.MIN_EXPONENT:g}) or FlatPunch.")
        if torsion not in ("exact",):
            raise UnknownNameError(f"torsion={torsion!r} is invalid: allowed are ('exact',).")
        if isinstance(memory, bool) or not isinstance(memory, (int, np.integer)) or memory < 2:
            raise ParameterError(f"memory={memory!r} is invalid: it must be an integer >= 2.")
        rtol = as_real("load_rtol", load_rtol, "it must be a real number, finite and >= 0")
        if not (np.isfinite(rtol) and rtol >= 0):
            raise ParameterError(f"load_rtol={load_rtol!r} is invalid: it must be finite and "
                                 ">= 0.")
        if size is not None and (isinstance(size, bool) or not isinstance(size, (int, np.integer))
                                 or size < 1):
            raise ParameterError(f"size={size!r} is invalid: it must be an integer >= 1.")
        if (isinstance(springs, bool) or not isinstance(springs, (int, np.integer))
                or not (springs == 0 or 2 <= springs <= 4096)):
            raise ParameterError(f"springs={springs!r} is invalid: it must be 0 (no springs) or "
                                 "an integer in [2, 4096].")
        geo = {"R": R, "slope": slope, "c": c, "radius": radius}
        if issubclass(cls, FlatPunch):
            gname, expo = "radius", np.inf
        elif cls is Paraboloid:
            gname, expo = "R", 2.0
        elif cls is Cone:
            gname, expo = "slope", 1.0
        else:
            gname = "c"
            if inst is None and n is None:
                raise ParameterError("n is missing: a PowerLaw family needs its exponent n.")
            expo = as_real("n", inst.n if inst is not None else n,
                           f"the exponent n of PowerLaw must be a real number >= "
                           f"{_master.MIN_EXPONENT:g}")
        for k, v in geo.items():
            if v is not None and k != gname:
                raise ParameterError(f"{k}= is not a parameter of {cls.__name__}: give {gname}=.")
        if inst is not None:
            if geo[gname] is not None:
                raise ParameterError(f"{gname}= given twice: by the profile instance and by "
                                     "keyword.")
            geo[gname] = getattr(inst, gname)
        if geo[gname] is None:
            raise ParameterError(f"{gname} is missing: {cls.__name__} contacts need {gname}= "
                                 "(scalar or one value per contact).")
        if not (expo >= _master.MIN_EXPONENT and (np.isfinite(expo) or gname == "radius")):
            raise NotSupportedError(
                f"n={expo!r} is not supported by ContactLaw: the exponent must satisfy n >= "
                f"{_master.MIN_EXPONENT:g} (below, the centre singularity of the pressure, "
                "p ∝ r^(n-1), approaches non-integrability and the exact solvers no longer "
                f"certify the torsion master curve to {_master.CERTIFY_TOL:g}).")
        if materials is not None:
            if any(v is not None for v in (E_star, G_star, G_torsion)):
                raise ParameterError("give either materials=(m1, m2) or E_star/G_star/G_torsion, "
                                     "not both.")
            from ..materials import effective_moduli
            mod = effective_moduli(*materials)
            E_star, G_star, G_torsion = mod.normal, mod.tangential, mod.torsional
        vals = {gname: geo[gname], "E_star": E_star, "G_star": G_star, "G_torsion": G_torsion,
                "friction": friction}
        for k, v in vals.items():
            if v is None:
                raise ParameterError(f"{k} is missing: ContactLaw needs {k}= (scalar or one "
                                     "value per contact).")
        vals = {k: _per_contact(k, v, None) for k, v in vals.items()}
        sizes = {k: v.size for k, v in vals.items() if v.ndim == 1}
        if size is None and len(set(sizes.values())) > 1:
            raise ParameterError("per-contact arrays have different lengths: "
                                 + ", ".join(f"{k} has {v}" for k, v in sizes.items())
                                 + "; give scalars or one value per contact.")
        lengths = set(sizes.values())
        if size is None:
            size = max(lengths) if lengths else 1
        reserve = as_real("spring_reserve", spring_reserve, "it must be a fraction in [0, 1]")
        if not 0.0 <= reserve <= 1.0:
            raise ParameterError(f"spring_reserve={spring_reserve!r} is invalid: it must be a "
                                 "fraction of the contacts in [0, 1].")
        self._reserve = math.ceil(reserve * size) if springs else 0
        check_memory("ContactLaw()", law_memory(size, memory, springs, self._reserve),
                     f"{size} contacts, memory={memory}, springs={springs}, spring_reserve="
                     f"{reserve:g}")
        arrs = {k: np.broadcast_to(_per_contact(k, v, size), (size,)).copy()
                for k, v in vals.items()}
        self.size = int(size)
        self.n = expo
        self.family = cls
        g = arrs[gname]
        # g(x) = kc x^n (flat punch: g = 0 inside the punch radius, kept in _flat)
        if expo == np.inf:
            self._kc = np.zeros(self.size)
        else:
            self._kc = (1.0 / g if cls is Paraboloid else float(kappa(expo)) * g)
        self.geometry: Mapping[str, np.ndarray] = FixedGeometry(gname, g)
        self._slope = SlopeCheck(g) if cls is Paraboloid else None   # a <= R/√3, until it warns
        self._E_star, self._G_star = arrs["E_star"], arrs["G_star"]
        self._G_torsion, self._friction = arrs["G_torsion"], arrs["friction"]
        self.memory = int(memory)
        self.load_rtol = float(load_rtol)
        self.springs = int(springs)
        cover = _per_contact("spring_cover", spring_cover, self.size)
        if np.any(cover < 1.0):
            i = int(np.argmax(np.broadcast_to(cover, (self.size,)) < 1.0))
            raise ParameterError(f"spring_cover[{i}]={float(np.broadcast_to(cover, (self.size,))[i])!r} "
                                 "is invalid: the springs must cover at least the contact radius "
                                 "(>= 1).")
        self._spring_cover = np.broadcast_to(cover, (self.size,)).copy()
        self._beta = _springs.unit_boundaries(max(self.springs, 2))
        self.torsion = torsion
        fast, self._xp = _device.resolve(backend, fast, self.size,
                                         law_memory(size, memory, springs))
        # the fused kernels on a GPU (None: the array path, on numpy the reference)
        self._kernels = _device.kernels(self._xp)
        if fast and not _kernel.AVAILABLE:
            raise NotSupportedError("fast=True needs numba: pip install 'contactlab[fast]'.")
        if fast is None:        # numba when it imports, unless CONTACTLAB_BACKEND=numpy (or
            # set_backend("numpy")) forces the numpy reference, as for the foundations
            from ..foundation import _compiled
            fast = _kernel.AVAILABLE and _compiled.backend() == "numba"
        self.fast = bool(fast)
        self.backend = backend if backend is not None else ("numba" if fast else "numpy")
        self.parallel = bool(parallel)
        self._master = _master.torsion_master(expo)
        self._flat = g if expo == np.inf else _NO_FLAT
        # (n + 1)/(2 n E* kc) per contact, once (n = 2: its cube root): the compiled radius
        self._factor = _kernel.force_factor(self._E_star, self._kc, expo)
        self._muE = self._friction * self._E_star         # the compiled passes' mu E* d: one product
        self._flag: np.ndarray | None = None
        self._warned = False
        #: emit the model-error ValidityWarning (once per law and quantity); settable
        self.warn_model_error = bool(warn_model_error)
        self._model_warned: set[str] = set()
        self._st = self._fresh(self.size)

    # ------------------------------------------------------------------ state
    def _fresh(self, n: int) -> dict[str, np.ndarray]:
        xp = np if self._xp is None else self._xp      # the state lives in the backend's module
        st = {"depth_ref": xp.zeros(n)}
        # both channels' stacks in one array per field (leading axis: tangential, torsion) for
        # the compiled kernel; the state names views of it
        one = new_stack(0, self.memory)         # the fields' dtypes and trailing shapes
        self._chan = {k: xp.zeros((2, n, *v.shape[1:]), v.dtype) for k, v in one.items()
                      if k not in ("X", "Y")}
        # turning points level-major (channel, level, contact): the fused pass reads the top
        # levels only (measured 8-10 % less CPU time per constant-load step at 10^6 contacts
        # than contact-major blocks); "X", "Y" and the state are (channel, contact, level)
        # views of the same memory
        for k in ("X", "Y"):
            lev = xp.zeros((2, self.memory, n), one[k].dtype)
            self._chan[k + "_levels"] = lev
            self._chan[k] = lev.transpose(0, 2, 1)
        for c, ch in enumerate(("tan", "tor")):
            for k in STACK_FIELDS:
                st[f"{ch}_{k}"] = self._chan[k][c]
        # the spring state: rows only for contacts that switch onto their springs
        self._pool = (SpringPool(n, self.springs, self._reserve, self.parallel) if self.springs
                      else None)
        return st

    def _on(self) -> np.ndarray:
        """Per contact: on its springs (a new bool array; all False without springs)."""
        return self._pool.on() if self._pool is not None else np.zeros(self.size, bool)

    def _spr(self, key: str, idx: np.ndarray) -> np.ndarray:
        """Spring field ``key`` of the contacts ``idx`` (on springs), a copy."""
        assert self._pool is not None
        return self._pool.of(key, idx)

    @property
    def state(self) -> dict[str, np.ndarray]:
        """Every contact's memory as named arrays (copies): save with ``np.savez(file,
        **law.state)``, restore with ``law.state = dict(np.load(file))``. With springs, the
        spring state is given per contact (``spr_on`` and zeros where it is False), whichever
        contacts hold rows of the law's spring pool."""
        out = {k: _device._host(v, self._xp) for k, v in self._st.items()}
        if self._pool is not None:
            out["spr_on"] = self._pool.on()
            out.update({k: self._pool.full(k) for k in SPRING_FIELDS})
        return out

    @state.setter
    def state(self, value: dict) -> None:
        # every entry is checked before any is written: a refused state leaves the law as it was
        if not isinstance(value, Mapping):
            raise ParameterError(f"state={_short(value)} is invalid: give the dict of arrays "
                                 "returned by law.state (e.g. dict(np.load(file))).")
        value = upgraded_state(value, self)     # saved before spr_a replaced spr_S
        ref = self._state_like()
        missing = sorted(set(ref) - set(value))
        extra = sorted(set(value) - set(ref))
        if missing or extra:
            raise ParameterError(f"state is invalid: missing keys {missing}, unknown keys "
                                 f"{extra} (it must come from law.state of a law of the same "
                                 "size and memory).")
        new = {k: checked_state_entry(k, value[k], v, self.memory, self.springs) for k, v in ref.items()}
        for k, v in self._st.items():           # in place: channel fields are views
            v[...] = new[k] if self._xp is None else self._xp.asarray(new[k])
        if self._pool is not None:
            self._pool.load(new["spr_on"], new)

    def _state_like(self) -> dict[str, np.ndarray]:
        """Arrays of the shapes and dtypes of :attr:`state` (views, nothing allocated)."""
        like = dict(self._st)
        if self._pool is not None:
            like["spr_on"] = np.broadcast_to(np.zeros((), bool), (self.size,))
            like.update({k: self._pool.like(k) for k in SPRING_FIELDS})
        return like

    @property
    def citations(self) -> Citations:
        """The sources the law uses (``contactlab.cite(law)``): closed-form normal contact,
        Cattaneo–Mindlin, exact torsion, Masing's rule and the MDR springs for varying loads."""
        return Citations(law_sources())

    def reset(self, mask: Any = None) -> None:
        """Clear the memory of the contacts in ``mask`` (bool array or indices; all if None)."""
        if mask is None:
            self._st = self._fresh(self.size)
            return
        try:
            m = np.asarray(mask)
        except Exception as err:                # ragged lists and the like
            raise ParameterError(f"mask={_short(mask)} is invalid: give a boolean array of one "
                                 f"value per contact ({self.size},) or integer indices.") from err
        if m.dtype == bool:
            if m.shape != (self.size,):
                raise ParameterError(f"mask has shape {m.shape}: a boolean mask needs one value "
                                     f"per contact ({self.size},).")
            idx = np.flatnonzero(m)
        else:
            # integer indices (an empty list comes as float64: whole floats are indices too)
            if m.dtype.kind not in "iuf" or (m.dtype.kind == "f" and not np.all(
                    np.isfinite(m) & (m == np.round(m)))):
                raise ParameterError(f"mask={_short(mask)} is invalid: give a boolean array of "
                                     f"one value per contact ({self.size},) or integer "
                                     "indices.")
            idx = m.astype(np.int64).ravel()
            bad = (idx < 0) | (idx >= self.size)
            if np.any(bad):
                raise ParameterError(f"mask contains index {int(idx[bad][0])}: indices must "
                                     f"satisfy 0 <= i < {self.size}.")
        self._clear(idx)

    def _clear(self, idx: np.ndarray) -> None:
        if idx.size == 0:
            return
        at = idx if self._xp is None else self._xp.asarray(idx)
        for v in self._st.values():
            v[at] = 0
        if self._pool is not None:
            self._pool.release(idx)

    def to_source(self) -> str:
        """Standalone Python source (numpy only, no contactlab import) of this law's family at
        constant normal load, for codes that vendor the law.

        Every family is covered (power laws and flat punches). The module defines
        ``Law(<geometry>, E_star, G_star, G_torsion, friction)`` with the
        same ``step`` inputs as :meth:`step` (returning a dict of arrays), ``state`` and
        ``reset``; the certified master-curve coefficients are embedded exactly, and the kernels
        are the ones of this law's numpy path, so the results agree with :meth:`step` to
        rounding. A load change beyond ``load_rtol`` raises ``ValueError`` there.

        Returns
        -------
        str
            Python source; write it to a ``.py`` file and import it.
        """
        from .law_source import law_source
        return law_source(self)

    # ------------------------------------------------------------------ normal contact
    def normal(self, *, depth: Any = None, force: Any = None) -> tuple[np.ndarray, ...]:
        """``(depth, radius, force)`` per contact for a depth (m) or a force (N >= 0)."""
        key, val = exactly_one("ContactLaw.normal()", {"depth": depth, "force": force})
        n = self.n
        if n == np.inf:                                 # flat punch: a = punch radius
            b = self._flat
            if key == "depth":
                d = _per_step("depth", val, self.size, "m")
                dp = np.maximum(d, 0.0)
                return d.copy(), np.where(dp > 0, b, 0.0), 2.0 * self._E_star * dp * b
            F = _per_step("force", val, self.size, "N", nonneg=True)
            return F / (2.0 * self._E_star * b), np.where(F > 0, b, 0.0), F.copy()
        if key == "depth":
            d = _per_step("depth", val, self.size, "m")
            dp = np.maximum(d, 0.0)
            a = (dp / self._kc) ** (1.0 / n) if n != 2.0 else np.sqrt(dp / self._kc)
            F = 2.0 * n / (n + 1.0) * self._E_star * dp * a
            return d.copy(), a, F
        F = _per_step("force", val, self.size, "N", nonneg=True)
        c = (n + 1.0) / (2.0 * n * self._E_star * self._kc)   # n = 2: cbrt(c) once, compiled
        a = _cbrt(F) * _cbrt(c) if n == 2.0 else (F * c) ** (1.0 / (n + 1.0))
        d = self._kc * a**n if n != 2.0 else self._kc * a * a
        return d, a, F.copy()

    # ------------------------------------------------------------------ the step
    def step(self, *, depth: Any = None, force: Any = None, displacement: Any = None,
             twist: Any = None, out: LawStep | None = None, tangent: bool = False
             ) -> LawStep:
        """Advance every contact by one step.

        Parameters
        ----------
        depth, force : array_like
            Exactly one: indentation depth (m) or normal force (N >= 0) per contact.
        displacement : array_like, optional
            Tangential displacement (m) since the contact's memory started (omitted: no
            tangential response).
        twist : array_like, optional
            Twist angle (rad) since the contact's memory started.
        out : LawStep, optional
            A result of an earlier step of this law whose arrays are overwritten with this
            step's results (and returned): a time loop that does not keep old results saves
            allocating (and page-faulting) nine fresh arrays per step.
        tangent : bool
            Also give the consistent tangent stiffness per contact in ``result.tangent``
            (:func:`contactlab.effects.law_tangent.tangent`).

        Returns
        -------
        LawStep

        Raises
        ------
        OutsideTheoryError
            A contact's depth left ``load_rtol`` of the depth at which its memory started (this
            law is exact at constant normal load; :meth:`reset` restarts the memory).
        NotSupportedError
            ``tangent=True`` while a contact is on springs.
        """
        if self._xp is not None:
            return self._stamp(_device.step(self, depth, force, displacement, twist, out,
                                            tangent, law_spring_memory))
        if out is not None:
            self._check_out(out)
        pre = _tangent_snapshot(self) if tangent else None     # the springs' step start
        if self.fast:
            res = self._step_fast(depth, force, displacement, twist, out)
        else:
            with np.errstate(all="ignore"):   # overflowing inputs: inf/NaN lanes, refused below
                res = self._step_numpy(depth, force, displacement, twist)
            if out is not None:
                for f in _OUT_FIELDS:
                    getattr(out, f)[...] = getattr(res, f)
                res = out
        object.__setattr__(res, "tangent", _tangent(self, res, displacement, twist, tangent,
                                                    pre))
        return self._stamp(res)

    def _stamp(self, res: LawStep) -> LawStep:
        """The law's springs and sources into the step's ``meta`` (its model error needs them);
        a reused ``out`` forgets the model errors of its previous step."""
        res.__dict__.pop("_model_errors_cache", None)
        res.meta.update(springs=self.springs, citations=_LAW_SOURCES)
        res.meta.pop("notes", None)
        if self._slope is not None and self._slope(
                res, None if self._xp is None else _device.params(self)["kc"]):
            self._slope = None
        if (self.warn_model_error and self.springs
                and len(self._model_warned) < len(_MODEL_ERROR_CAUSES)
                and self._pool is not None and self._pool.used):
            self._warn_model_error(res)
        return res

    def _warn_model_error(self, res: LawStep) -> None:
        """A :class:`ValidityWarning` when a step's model error exceeds
        :data:`MODEL_ERROR_WARN` for a quantity at a contact on springs, once per law and
        quantity (:func:`~contactlab.effects.law_checks.warn_model_error`)."""
        pool = self._pool       # many on springs: the mask; few: their indices, ascending,
        assert pool is not None  # from the rows in use (no pass over every contact)
        on = self._on() if 4 * pool.used >= self.size else np.sort(pool.owner[:pool.used])
        warn_model_error(res, on, self._model_warned, self.springs, MODEL_ERROR_WARN)

    def _check_out(self, out: Any) -> None:
        ok = isinstance(out, LawStep)
        for f in _OUT_FIELDS if ok else ():
            v = getattr(out, f)
            want = bool if f == "exact" else float
            if not (isinstance(v, np.ndarray) and v.shape == (self.size,) and v.dtype == want
                    and v.flags.writeable and v.flags.c_contiguous):
                ok = False
        if not ok:
            raise ParameterError(f"out={type(out).__name__} is invalid: give a LawStep returned "
                                 f"by an earlier step of a law with {self.size} contacts.")

    def _step_numpy(self, depth, force, displacement, twist) -> LawStep:
        d, a, F = self.normal(depth=depth, force=force)
        size = self.size
        u = None if displacement is None else _per_step("displacement", displacement, size, "m")
        phi = None if twist is None else _per_step("twist", twist, size, "rad")
        st = self._st
        live = a > 0
        if not np.all(live):
            self._clear(np.flatnonzero(~live))
        ref = st["depth_ref"]
        new = live & (ref == 0)
        ref[new] = d[new]
        off = live & (np.abs(d - ref) > self.load_rtol * ref)
        if self.springs:
            on = self._on()
            if np.any(off & ~on):
                n_spr = int(np.count_nonzero(on | off))
                check_memory("ContactLaw.step()", law_spring_memory(n_spr, self.springs),
                             f"{n_spr} contacts on {self.springs} springs each")
            _np_springs.to_springs(self, np.flatnonzero(off & ~on), d, a)
            off = np.zeros(size, bool)
        if np.any(off):
            i = int(np.argmax(off))
            raise OutsideTheoryError(
                f"depth[{i}]={float(d[i])!r} m differs from the depth {float(ref[i])!r} m at "
                f"which contact {i}'s memory started by more than load_rtol={self.load_rtol!r}: "
                "this law is exact at constant normal load. Call law.reset(mask) to restart the "
                "memory of contacts whose load changed, or raise load_rtol.")
        if u is not None and phi is not None and not self._warned and np.any(
                live & (u != 0) & (phi != 0)):
            self._warned = True
            warnings.warn("ContactLaw: displacement and twist together are treated as two "
                          "independent slip problems, each with the full friction limit "
                          "(outside the theory: the slip conditions couple).", ValidityWarning,
                          stacklevel=2)
        zero = np.zeros(size)
        was = st["tan_overflow"] | st["tor_overflow"]
        dW = zero.copy()
        Ft, ct = zero.copy(), a.copy()
        M, cm = zero.copy(), a.copy()
        safe_a = np.where(live, a, 1.0)
        safe_d = np.where(live, d, 1.0)
        FN = np.where(live, F, 0.0)
        if u is not None:
            Ft, ct, w = self._tangential(u, safe_a, safe_d, FN)
            dW += w
        if phi is not None:
            M, cm, w = self._torsion(phi, safe_a, safe_d)
            dW += w
        over = st["tan_overflow"] | st["tor_overflow"]
        exact = live & ~over
        if self.springs:                        # their (unused) stacks are not counted
            over &= ~self._on()
        n_over = int(np.count_nonzero(over & ~was & live))
        if self.springs and self._pool is not None and self._pool.used:
            idx = np.flatnonzero(self._on() & live)
            r = _np_springs.spring_step(self, idx, d[idx], a[idx], None if u is None else u[idx],
                                  None if phi is None else phi[idx])
            for arr, v in zip((Ft, ct, M, cm, dW), r):
                arr[idx] = v
            exact[idx] = False
        if not np.all(live):
            dead = ~live
            for arr in (Ft, M, dW, ct, cm):
                arr[dead] = 0.0
            self._clear(np.flatnonzero(dead))
        self._check_finite(live, d, a, F, Ft, M, ct, cm, dW)
        if n_over:
            self._warn_overflow(n_over)
        return LawStep(d, a, F, Ft, M, ct, cm, dW, exact)

    def _warn_overflow(self, count: int) -> None:
        """One ValidityWarning for the contacts whose turning-point stack overflowed in this
        step (their results are approximate from now on: ``out.exact`` is False)."""
        warnings.warn(f"ContactLaw: the turning-point memory (memory={self.memory}) of {count} "
                      "contact(s) overflowed in this step (more nested reversals than it holds): "
                      "the innermost open loop was forgotten and their results are approximate "
                      "from now on (out.exact is False, law.state['tan_overflow'] / "
                      "['tor_overflow'] flag them) until their memory is reset. Raise memory= "
                      "to keep them exact.", ValidityWarning, stacklevel=4)

    def _check_finite(self, live: np.ndarray, *outputs: np.ndarray) -> None:
        """Refuse a step whose response overflows float64 (inputs far outside any physical
        range, e.g. ``force=1e300``): the overflowing contacts are reset and an error names the
        first of them."""
        bad = np.zeros(self.size, bool)
        for arr in outputs:
            bad |= ~np.isfinite(arr)
        if np.any(bad):
            idx = np.flatnonzero(bad)
            self._clear(idx)
            i = int(idx[0])
            raise ParameterError(
                f"contact {i}: depth[{i}]={float(outputs[0][i])!r} m, force[{i}]="
                f"{float(outputs[2][i])!r} N gives a response that overflows float64 (outside any "
                "physical range): give inputs in SI units (m, N, rad). The memory of the "
                f"{idx.size} overflowing contact(s) was reset.")

    def _step_fast(self, depth, force, displacement, twist, out) -> LawStep:
        """The compiled step: a normal pass (checks, depth/radius/force, flags), one fused pass
        over both Masing channels, and the compiled spring pass for contacts on springs."""
        key, val = exactly_one("ContactLaw.step()", {"depth": depth, "force": force})
        size = self.size
        arrs: list[np.ndarray | None] = []
        for name, v, unit in ((key, val, "m" if key == "depth" else "N"),
                              ("displacement", displacement, "m"), ("twist", twist, "rad")):
            if v is None:
                arrs.append(None)
                continue
            # types and shapes here; finiteness and sign in the normal pass
            x = as_float_array(name, v, allow_nan=True)
            if x.ndim > 1 or (x.ndim == 1 and x.size != size):
                _per_step(name, v, size, unit)          # raises the error naming the input
            # one array type for the kernels (1D, C-contiguous, writeable): a scalar or a
            # read-only view would compile another specialisation on first use
            if x.ndim == 0:
                x = np.full(size, float(x))
            elif not (x.flags.c_contiguous and x.flags.writeable):
                x = np.array(x, dtype=float)
            arrs.append(x)
        v, u, phi = arrs
        st = self._st
        if self._flag is None:
            self._flag = np.empty(size, np.int8)        # scratch: reused every step
        d, a, F, flag, (bad, dead, off, both, nonfinite) = _kernel.normal_pass(
            key == "force", v, u, phi, self._kc, self._E_star, self.n, self._flat, st["depth_ref"],
            self.load_rtol, self.parallel,
            None if out is None else (out.depth, out.radius, out.force, self._flag), self._factor)
        if bad:                                         # the numpy checks name the entry
            _per_step(key, v, size, "m" if key == "depth" else "N", nonneg=key == "force")
            _per_step("displacement", u if u is not None else 0.0, size, "m")
            _per_step("twist", phi if phi is not None else 0.0, size, "rad")
        new = _NO_CONTACTS
        if dead:
            self._clear(np.flatnonzero(flag == 1))
        if off:
            offm = flag == 2
            if not self.springs:
                i = int(np.argmax(offm))
                ref = st["depth_ref"]
                raise OutsideTheoryError(
                    f"depth[{i}]={float(d[i])!r} m differs from the depth {float(ref[i])!r} m at "
                    f"which contact {i}'s memory started by more than load_rtol="
                    f"{self.load_rtol!r}: this law is exact at constant normal load. Call "
                    "law.reset(mask) to restart the memory of contacts whose load changed, or "
                    "raise load_rtol.")
            # compiled switch onto the springs after the fused pass (which leaves them out):
            # no temporaries per contact, so no memory check here
            pool = self._pool
            assert pool is not None
            offm &= pool.slot < 0                       # the contacts that switch now
            new = np.flatnonzero(offm)
            if new.size:
                pool.reserve(new.size, self.parallel)   # grown (rarely) before the kernels
        if both and not self._warned:
            self._warned = True
            warnings.warn("ContactLaw: displacement and twist together are treated as two "
                          "independent slip problems, each with the full friction limit "
                          "(outside the theory: the slip conditions couple).", ValidityWarning,
                          stacklevel=3)
        spr = None
        if self._pool is not None and self._pool.used:
            onm = self._pool.slot >= 0
            if dead:
                onm &= flag != 1
            np.copyto(flag, 3, where=onm)               # the fused pass leaves them out
            spr = np.flatnonzero(onm)
        if new.size:
            np.copyto(flag, 3, where=offm)              # (a mask: no gather of 10^6 indices)
        if new.size + (0 if spr is None else spr.size) == size:     # all on springs (or
            # switching now): no fused pass, it would only set ``exact`` False
            Ft, ct, M, cm, dW, exact, nf, n_over = springs_only_outputs(size, out)
        else:
            Ft, ct, M, cm, dW, exact, nf, n_over = _kernel.fused_pass(
                u, phi, d, a, F, flag, st["depth_ref"], self._friction, self._E_star, self._G_star,
                self._G_torsion, self.n, self._master, self._chan, self.parallel,
                None if out is None else (out.tangential_force, out.stick_radius, out.torque,
                                          out.torsion_stick_radius, out.dissipated_energy,
                                          out.exact), self._muE)
        # the switching contacts switched and stepped on their springs one at a time, the row
        # in registers between the two (one loop, on the threads), then those already on
        # springs (covers outgrown: regridded)
        regrid = lambda g: _np_springs.regrid(self, g, a[g])    # noqa: E731
        args = (self._kc, self.n, self._beta, self._friction, self._E_star, self._G_star,
                self._G_torsion)
        if new.size:
            nf += _kernel.switch_step_pass(new, d, a, u, phi, self._flat, self._spring_cover,
                                           *args, self._chan, st, self._pool,
                                           (Ft, ct, M, cm, dW), self.parallel, flag, regrid)
        if spr is not None and spr.size:
            nf += _kernel.spring_pass(spr, d, a, u, phi, *args, self._pool, (Ft, ct, M, cm, dW),
                                      self.parallel, flag, regrid)
        if nonfinite or nf:                             # overflow: refused, contacts reset
            self._check_finite(flag != 1, d, a, F, Ft, M, ct, cm, dW)
        if n_over:
            self._warn_overflow(n_over)
        return out if out is not None else LawStep(d, a, F, Ft, M, ct, cm, dW, exact)

    # ------------------------------------------------------------------ changing load: springs
    def _geometry(self, idx: np.ndarray) -> dict:
        # flat punch: kc = 0 (g = 0 inside the punch radius) with any finite exponent
        return _springs.cells(self._spr("spr_cover", idx), self._kc[idx],
                              self.n if self.n != np.inf else 1.0, self._beta)

    def _limits(self, idx, S, T):
        mu, E = self._friction[idx, None], self._E_star[idx, None]
        return 2.0 * mu * E * S, 4.0 * mu * E * T

    def _radius(self, d: np.ndarray, idx: np.ndarray) -> np.ndarray:
        """Contact radius (m) of contacts ``idx`` at depths ``d >= 0``."""
        if self.n == np.inf:
            return np.where(d > 0, self._flat[idx], 0.0)
        return (d / self._kc[idx]) ** (1.0 / self.n) if self.n != 2.0 else np.sqrt(d / self._kc[idx])

    def _channel(self, prefix: str) -> dict[str, np.ndarray]:
        return {k: self._st[f"{prefix}_{k}"] for k in STACK_FIELDS}

    def _tangential(self, u, a, d, FN):
        n = self.n
        mu, E, G = self._friction, self._E_star, self._G_star
        inv = G / (mu * E * d)          # 1/u*: the curve's argument by a multiply
        muF = mu * FN
        Dscale = 2.0 * a * (mu * E * d) ** 2 / G

        def load(arg, idx):
            if idx is None:
                t, f, w = _master.tangential_master(n, arg * inv)
                return muF * f, a * t, Dscale * w
            t, f, w = _master.tangential_master(n, arg * inv[idx])
            return muF[idx] * f, a[idx] * t, Dscale[idx] * w

        return masing_step(self._channel("tan"), u, load)

    def _torsion(self, phi, a, d):
        mc = self._master
        _, M_full = _master.torsion_scales(self.n, self._E_star, self._G_torsion, self._friction,
                                           a, d)
        inv = _master.inverse_twist_scale(self._E_star, self._G_torsion, self._friction, a, d)

        def load(arg, idx):
            if idx is None:
                t, m, q = mc(arg * inv)
                return M_full * m, a * t, M_full * arg * q
            t, m, q = mc(arg * inv[idx])
            return M_full[idx] * m, a[idx] * t, M_full[idx] * arg * q

        return masing_step(self._channel("tor"), phi, load)
