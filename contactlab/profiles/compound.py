"""Composite profiles: sums of profiles and scaled profiles (the MDR transform is linear)."""
from __future__ import annotations

from collections.abc import Iterable
from typing import Any, ClassVar, cast

import numpy as np

from ..errors import ParameterError
from ..params import Param
from ..symbolic.form import SympyForm, scaled_form, sum_form
from .base import Profile

__all__ = ["Sum", "Scaled"]


def _total(parts: Iterable[np.ndarray]) -> np.ndarray:
    """The builtin ``sum`` of a Sum's term arrays, in order (at least two terms: an array)."""
    return cast(np.ndarray, sum(parts))


class Sum(Profile):
    """Sum of profiles, ``f = Σ f_i``; every term keeps its own route (``g = Σ g_i``).

    Parameters
    ----------
    *terms : Profile
        At least two profiles. Terms stay objects: ``s.terms[1].R``.
    """

    name: ClassVar[str] = "sum"
    params: ClassVar[tuple[Param, ...]] = ()

    def __init__(self, *terms: Profile) -> None:
        flat: list[Profile] = []
        for t in terms:
            if not isinstance(t, Profile):
                raise ParameterError(f"terms contains {t!r}: every term must be a Profile.")
            flat.extend(t.terms if isinstance(t, Sum) else (t,))
        if len(flat) < 2:
            raise ParameterError("a Sum needs at least two profiles.")
        self.terms: tuple[Profile, ...] = tuple(flat)

    def _param_values(self) -> tuple[Any, ...]:
        return self.terms

    def __repr__(self) -> str:
        return " + ".join(repr(t) for t in self.terms)

    @property
    def capabilities(self) -> frozenset[str]:
        """``"terms"``: kernels that are linear in the profile take each term's own route."""
        return frozenset({"terms"})

    @property
    def max_radius(self) -> float:
        return min(t.max_radius for t in self.terms)

    @property
    def wall_radius(self) -> float:
        return min(t.wall_radius for t in self.terms)

    @property
    def flat_radius(self) -> float:
        return min(t.flat_radius for t in self.terms)

    @property
    def breakpoints(self) -> tuple[float, ...]:
        return tuple(sorted({b for t in self.terms for b in (*t.breakpoints, t.flat_radius) if b > 0}))

    def power_terms(self) -> list[tuple[float, float]] | None:
        parts = [t.power_terms() for t in self.terms]
        if any(p is None for p in parts):
            return None
        return [ct for p in parts for ct in cast("list[tuple[float, float]]", p)]

    def _sympy_form(self) -> SympyForm:
        # the MDR is linear: every term brings its own form
        return sum_form([t._sympy_form() for t in self.terms])

    def _height(self, r: np.ndarray) -> np.ndarray:
        return _total(t._height(r) for t in self.terms)

    def _slope(self, r: np.ndarray) -> np.ndarray:
        return _total(t._slope_any(r) for t in self.terms)

    def _g_closed_form(self, x: np.ndarray) -> np.ndarray:
        return _total(t._g(x) for t in self.terms)

    def _g_integral_closed_form(self, a: np.ndarray) -> np.ndarray:
        return _total(t._g_integral(a) for t in self.terms)

    # every term takes its own route at the caller's tolerance; errors add
    def _g(self, xa: np.ndarray, rtol: float | None = None) -> np.ndarray:
        return _total(t._g(xa, rtol) for t in self.terms)

    def _g_with_error(self, xa: np.ndarray, rtol: float | None = None
                      ) -> tuple[np.ndarray, np.ndarray]:
        parts = [t._g_with_error(xa, rtol) for t in self.terms]
        return _total(p[0] for p in parts), _total(p[1] for p in parts)

    def _g_integral_with_error(self, a: np.ndarray, rtol: float | None = None
                               ) -> tuple[np.ndarray, np.ndarray]:
        parts = [t._g_integral_with_error(a, rtol) for t in self.terms]
        return _total(p[0] for p in parts), _total(p[1] for p in parts)

    def _length_scale(self) -> float:
        return min(t._length_scale() for t in self.terms)


class Scaled(Profile):
    """A profile scaled by a positive factor, ``f = factor * base``."""

    name: ClassVar[str] = "scaled"
    params: ClassVar[tuple[Param, ...]] = (
        Param("factor", "k", "1", "positive", "scale factor"),
    )

    def __init__(self, base: Profile, factor: float) -> None:
        if not isinstance(base, Profile):
            raise ParameterError(f"base={base!r} is invalid: expected a Profile.")
        self.base = base
        self.factor = self.params[0].check(factor)

    def _param_values(self) -> tuple[Any, ...]:
        return (self.base, self.factor)

    def __repr__(self) -> str:
        return f"{self.factor!r} * {self.base!r}"

    @property
    def max_radius(self) -> float:
        return self.base.max_radius

    @property
    def wall_radius(self) -> float:
        return self.base.wall_radius

    @property
    def flat_radius(self) -> float:
        return self.base.flat_radius

    @property
    def breakpoints(self) -> tuple[float, ...]:
        return self.base.breakpoints

    def power_terms(self) -> list[tuple[float, float]] | None:
        p = self.base.power_terms()
        return None if p is None else [(self.factor * c, n) for c, n in p]

    def _sympy_form(self) -> SympyForm:
        return scaled_form(self.base._sympy_form(), self.factor)

    def _height(self, r: np.ndarray) -> np.ndarray:
        return self.factor * self.base._height(r)

    def _slope(self, r: np.ndarray) -> np.ndarray:
        return self.factor * self.base._slope_any(r)

    def _g_closed_form(self, x: np.ndarray) -> np.ndarray:
        return self.factor * self.base._g(x)

    def _g_integral_closed_form(self, a: np.ndarray) -> np.ndarray:
        return self.factor * self.base._g_integral(a)

    def _g(self, xa: np.ndarray, rtol: float | None = None) -> np.ndarray:
        return self.factor * self.base._g(xa, rtol)

    def _g_with_error(self, xa: np.ndarray, rtol: float | None = None
                      ) -> tuple[np.ndarray, np.ndarray]:
        val, err = self.base._g_with_error(xa, rtol)
        return self.factor * val, self.factor * err

    def _g_integral_with_error(self, a: np.ndarray, rtol: float | None = None
                               ) -> tuple[np.ndarray, np.ndarray]:
        val, err = self.base._g_integral_with_error(a, rtol)
        return self.factor * val, self.factor * err

    def _length_scale(self) -> float:
        return self.base._length_scale()
