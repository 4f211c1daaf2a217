"""Linear viscoelastic materials, defined by their shear relaxation function ``G(t)``.

Every material here is an *incompressible* isotropic half-space (Poisson's ratio 1/2), so that
against a rigid indenter ``E*(t) = 4G(t)`` (theory §7, [H3]). All of them share the Prony
form used by the solver,

    G(t) = G_∞ + Σ_k G_k exp(-t/τ_k) + η δ(t),

with ``τ_k = η_k/G_k`` (a parallel dashpot ``η`` only for Kelvin-Voigt):

=========================  ======  ===================  ============  ======
material                   G_∞     arms (G_k, τ_k)      dashpot η     creep
=========================  ======  ===================  ============  ======
KelvinVoigt(G, eta)        G       –                    eta           closed
Maxwell(G, eta)            0       (G, eta/G)           –             closed
StandardLinearSolid(...)   G_inf   (G_1, eta_1/G_1)     –             closed
GeneralizedMaxwell(...)    G_inf   moduli, times        –             –
=========================  ======  ===================  ============  ======

References
----------
V. L. Popov, E. Willert, M. Heß, "Method of dimensionality reduction in contact mechanics and
friction: a user's handbook. III. Viscoelastic contacts", Facta Univ. Mech. Eng. 16 (2018) 99-113.
"""
from __future__ import annotations

from collections.abc import Sequence
from typing import Any, ClassVar

import numpy as np

from ..errors import ParameterError, PluginError
from ..params import MODULUS_BOUNDS, Param, as_float_array, check_bounds
from .base import Material

__all__ = ["Viscoelastic", "KelvinVoigt", "Maxwell", "StandardLinearSolid",
           "GeneralizedMaxwell"]


class Viscoelastic(Material):
    """Base class of incompressible linear viscoelastic materials (Prony form).

    To implement a subclass
    -----------------------
    1. Declare ``name`` and ``params``; validate and store the parameters in ``__init__``.
    2. Implement ``prony()`` returning ``(G_inf, moduli, times, eta)``: the long-time modulus
       (Pa, >= 0), arrays of arm moduli (Pa, > 0) and relaxation times (s, > 0), and the
       parallel dashpot viscosity (Pa·s, >= 0).
    3. Optionally implement ``creep(t)`` (shear creep compliance J(t), 1/Pa) in closed form.

    Comes free: ``relaxation(t)``, ``glassy_modulus``, ``relaxed_modulus``, ``repr``, ``==``.
    """

    is_viscoelastic: ClassVar[bool] = True
    __abstract__ = True

    def __init_subclass__(cls, **kwargs: Any) -> None:
        super().__init_subclass__(**kwargs)
        if not cls.__dict__.get("__abstract__", False) and cls.prony is Viscoelastic.prony:
            raise PluginError(f"viscoelastic material {cls.__qualname__} must implement prony() "
                              "(rule: Material contract, item 3).")

    def prony(self) -> tuple[float, np.ndarray, np.ndarray, float]:  # pragma: no cover
        raise NotImplementedError

    def relaxation(self, t: Any) -> Any:
        """Shear relaxation function ``G(t)``, Pa, for times ``t >= 0`` (s).

        The Kelvin-Voigt dashpot contributes ``η δ(t)``, which is not representable pointwise;
        it is omitted here (see :meth:`prony`).
        """
        t = as_float_array("t", t)
        if np.any(t < 0):
            raise ParameterError(f"t contains {t[t < 0].ravel()[0]!r}: times must be >= 0 s.")
        G_inf, Gk, tk, _ = self.prony()
        val = G_inf + np.sum(Gk * np.exp(-t[..., None] / tk), axis=-1)
        return float(val) if val.ndim == 0 else val

    @property
    def glassy_modulus(self) -> float:
        """Instantaneous shear modulus ``G(0+) = G_∞ + Σ G_k``, Pa (``inf`` with a dashpot)."""
        G_inf, Gk, _, eta = self.prony()
        return np.inf if eta > 0 else float(G_inf + Gk.sum())

    @property
    def relaxed_modulus(self) -> float:
        """Long-time shear modulus ``G_∞``, Pa."""
        return float(self.prony()[0])


def _check_t(t: Any) -> np.ndarray:
    t = as_float_array("t", t)
    if np.any(t < 0):
        raise ParameterError(f"t contains {t[t < 0].ravel()[0]!r}: times must be >= 0 s.")
    return t


def _out(v: np.ndarray) -> Any:
    return float(v) if np.ndim(v) == 0 else v


class KelvinVoigt(Viscoelastic):
    """Kelvin-Voigt solid: spring ``G`` parallel to dashpot ``eta`` (incompressible).

    Parameters
    ----------
    G : float
        Shear modulus, Pa (> 0).
    eta : float
        Shear viscosity, Pa·s (> 0).

    Notes
    -----
    ``G(t) = G + η δ(t)``; creep ``J(t) = (1 - exp(-t G/η))/G``.
    """

    name: ClassVar[str] = "kelvin_voigt"
    params: ClassVar[tuple[Param, ...]] = (
        Param("G", "G", "Pa", "positive", "shear modulus G", (1e3, 1e9), MODULUS_BOUNDS),
        Param("eta", "eta", "Pa*s", "positive", "shear viscosity eta", (1e-3, 1e9)),
    )

    def __init__(self, G: float, eta: float) -> None:
        self.G = self.params[0].check(G)
        self.eta = self.params[1].check(eta)

    def prony(self) -> tuple[float, np.ndarray, np.ndarray, float]:
        return self.G, np.zeros(0), np.zeros(0), self.eta

    def creep(self, t: Any) -> Any:
        """Shear creep compliance ``J(t) = (1 - exp(-tG/η))/G``, 1/Pa."""
        t = _check_t(t)
        return _out(-np.expm1(-t * self.G / self.eta) / self.G)


class Maxwell(Viscoelastic):
    """Maxwell fluid: spring ``G`` in series with dashpot ``eta`` (incompressible).

    Parameters
    ----------
    G : float
        Shear modulus, Pa (> 0).
    eta : float
        Shear viscosity, Pa·s (> 0).

    Notes
    -----
    ``G(t) = G exp(-t/τ)``, ``τ = η/G``; creep ``J(t) = 1/G + t/η``.
    """

    name: ClassVar[str] = "maxwell"
    params: ClassVar[tuple[Param, ...]] = KelvinVoigt.params

    def __init__(self, G: float, eta: float) -> None:
        self.G = self.params[0].check(G)
        self.eta = self.params[1].check(eta)

    def prony(self) -> tuple[float, np.ndarray, np.ndarray, float]:
        return 0.0, np.array([self.G]), np.array([self.eta / self.G]), 0.0

    def creep(self, t: Any) -> Any:
        """Shear creep compliance ``J(t) = 1/G + t/η``, 1/Pa."""
        t = _check_t(t)
        return _out(1.0 / self.G + t / self.eta)


class StandardLinearSolid(Viscoelastic):
    """Standard linear solid (Zener): ``G_inf`` parallel to (``G_1`` in series with ``eta_1``).

    Parameters
    ----------
    G_inf : float
        Long-time (relaxed) shear modulus, Pa (> 0).
    G_1 : float
        Modulus of the Maxwell arm, Pa (> 0).
    eta_1 : float
        Viscosity of the Maxwell arm, Pa·s (> 0).

    Notes
    -----
    ``G(t) = G_∞ + G_1 exp(-t/τ_1)``, ``τ_1 = η_1/G_1``. Creep:
    ``J(t) = 1/G_∞ - (1/G_∞ - 1/(G_∞+G_1)) exp(-t/τ_c)`` with
    ``τ_c = η_1 (G_∞+G_1)/(G_∞ G_1)`` (theory §7).
    """

    name: ClassVar[str] = "standard_linear_solid"
    params: ClassVar[tuple[Param, ...]] = (
        Param("G_inf", "G_inf", "Pa", "positive", "relaxed shear modulus G_inf", (1e3, 1e9), MODULUS_BOUNDS),
        Param("G_1", "G_1", "Pa", "positive", "arm shear modulus G_1", (1e3, 1e9), MODULUS_BOUNDS),
        Param("eta_1", "eta_1", "Pa*s", "positive", "arm viscosity eta_1", (1e-3, 1e9)),
    )

    def __init__(self, G_inf: float, G_1: float, eta_1: float) -> None:
        self.G_inf = self.params[0].check(G_inf)
        self.G_1 = self.params[1].check(G_1)
        self.eta_1 = self.params[2].check(eta_1)

    def prony(self) -> tuple[float, np.ndarray, np.ndarray, float]:
        return self.G_inf, np.array([self.G_1]), np.array([self.eta_1 / self.G_1]), 0.0

    @property
    def creep_time(self) -> float:
        """Retardation time ``τ_c = η_1 (G_∞+G_1)/(G_∞ G_1)``, s."""
        return self.eta_1 * (self.G_inf + self.G_1) / (self.G_inf * self.G_1)

    def creep(self, t: Any) -> Any:
        """Shear creep compliance ``J(t)``, 1/Pa (see Notes)."""
        t = _check_t(t)
        Ji, J0 = 1.0 / self.G_inf, 1.0 / (self.G_inf + self.G_1)
        return _out(Ji - (Ji - J0) * np.exp(-t / self.creep_time))


class GeneralizedMaxwell(Viscoelastic):
    """Generalized Maxwell solid (Prony series): ``G_inf`` parallel to Maxwell arms.

    Parameters
    ----------
    G_inf : float
        Long-time shear modulus, Pa (>= 0; 0 gives a fluid).
    moduli : sequence of float
        Arm shear moduli ``G_k``, Pa (each > 0; at least one).
    relaxation_times : sequence of float
        Arm relaxation times ``τ_k = η_k/G_k``, s (each > 0; same length as ``moduli``).

    Notes
    -----
    ``G(t) = G_∞ + Σ_k G_k exp(-t/τ_k)``.

    Examples
    --------
    >>> from contactlab.materials.viscoelastic import GeneralizedMaxwell
    >>> m = GeneralizedMaxwell(1e5, moduli=[2e5, 1e5], relaxation_times=[0.1, 10.0])
    >>> m.relaxation(0.0)
    400000.0
    """

    name: ClassVar[str] = "generalized_maxwell"
    params: ClassVar[tuple[Param, ...]] = (
        Param("G_inf", "G_inf", "Pa", "nonnegative", "long-time shear modulus G_inf", (0.0, 1e9),
              (0.0, MODULUS_BOUNDS[1])),
        Param("moduli", "G_k", "Pa", "positive", "arm shear moduli G_k", (1e3, 1e9)),
        Param("relaxation_times", "tau_k", "s", "positive", "arm relaxation times tau_k",
              (1e-6, 1e6)),
    )

    def __init__(self, G_inf: float, moduli: Sequence[float],
                 relaxation_times: Sequence[float]) -> None:
        self.G_inf = self.params[0].check(G_inf)
        Gk = self._sequence("moduli", moduli, "arm shear modulus", "Pa", MODULUS_BOUNDS)
        tk = self._sequence("relaxation_times", relaxation_times, "relaxation time", "s")
        if len(Gk) != len(tk):
            raise ParameterError(
                f"moduli and relaxation_times have lengths {len(Gk)} and {len(tk)}: give one "
                "relaxation time per arm modulus.")
        self.moduli = Gk
        self.relaxation_times = tk

    @staticmethod
    def _sequence(name: str, value: Any, what: str, unit: str,
                  bounds: tuple[float, float] | None = None) -> tuple[float, ...]:
        try:
            arr = np.atleast_1d(np.asarray(value, dtype=float))
        except (TypeError, ValueError) as err:
            raise ParameterError(f"{name}={value!r} is invalid: expected a sequence of real "
                                 f"numbers > 0 ({unit}).") from err
        if arr.ndim != 1 or arr.size == 0:
            raise ParameterError(f"{name}={value!r} is invalid: give a non-empty 1D sequence of "
                                 f"{what}s > 0 ({unit}).")
        bad = ~np.isfinite(arr) | (arr <= 0)
        if np.any(bad):
            raise ParameterError(f"{name}[{int(np.argmax(bad))}]={arr[bad][0]!r} is invalid: "
                                 f"every {what} must be finite and > 0 ({unit}).")
        if bounds is not None:
            check_bounds(name, arr, bounds, unit)
        return tuple(float(v) for v in arr)

    def prony(self) -> tuple[float, np.ndarray, np.ndarray, float]:
        return self.G_inf, np.array(self.moduli), np.array(self.relaxation_times), 0.0
