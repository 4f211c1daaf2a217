"""Shared state of a :class:`~contactlab.profiles.tabulated.Tabulated` table.

The attributes every part of the table reads (set by ``Tabulated.__init__``), the guard that keeps
radii inside the table, and the closed-form node integrals the linear and the cubic transforms
share. Private: the public class is :class:`~contactlab.profiles.tabulated.Tabulated`.
"""
from __future__ import annotations

import contextlib
import threading
from collections.abc import Iterator
from typing import TYPE_CHECKING, Any, cast

import numpy as np

from ...errors import OutsideTheoryError
from ..base import Profile
from . import _far

#: elements per dense (x, node) block of the node sums
_CHUNK = 2_000_000

#: points per dense (point, node) block at most: with the points sorted, a block's nodes are
#: those below its largest point, so short blocks waste few terms (a triangle, not a rectangle)
_ROWS = 64


def _rows_per_chunk(n_nodes: int) -> int:
    return max(1, min(_ROWS, _CHUNK // max(n_nodes, 1)))


def _sorted(x: np.ndarray) -> tuple[np.ndarray, np.ndarray | None]:
    """The points flattened and sorted (``order``, or None when already sorted). A point's node
    sums do not depend on the other points of its block (fixed_sums), so sorting changes no
    bit; it keeps every block's nodes to those below its own points."""
    flat = x.ravel()
    if flat.size < 2 or bool(np.all(flat[1:] >= flat[:-1])):
        return flat, None
    order = np.argsort(flat, kind="stable")
    return flat[order], order


def _unsorted(vals: np.ndarray, order: np.ndarray | None, shape: tuple[int, ...]) -> np.ndarray:
    if order is None:
        return vals.reshape(shape)
    out = np.empty_like(vals)
    out[order] = vals
    return out.reshape(shape)


def _clip_index(k: np.ndarray, lo: int, hi: int) -> np.ndarray:
    """``np.clip`` of an index array from ``searchsorted`` (the same ``min(max(k, lo), hi)``,
    the same dtype), without ``np.clip``'s wrapper and integer-limit look-ups, which cost more
    than the clip on the few points of one load."""
    return np.minimum(np.maximum(k, lo), hi)


#: per thread: ``id(table) -> Taylor terms`` of the table's call in progress
#: (:meth:`_TableBase._tree_rtol`); a thread's setting is never seen by another thread's call
_CALL_TERMS = threading.local()


def _call_terms() -> dict[int, int]:
    terms = getattr(_CALL_TERMS, "terms", None)
    if terms is None:
        terms = _CALL_TERMS.terms = {}
    return cast("dict[int, int]", terms)


class _TableBase(Profile):
    """The table's attributes and shared helpers; no hook of :class:`Profile` is overridden."""

    def _tree_terms(self) -> int:
        """Taylor terms per block of the far-field trees in the current call (set from the
        call's rtol by :meth:`_tree_rtol`; all :data:`._far.TERMS` outside one)."""
        return int(_call_terms().get(id(self), _far.TERMS))

    def _tree_excess(self) -> np.ndarray:
        """``ratios[T]``, T = 0 .. :data:`._far.TERMS`: the largest truncation bound of the
        trees after T terms relative to ``|g|`` on 64 radii spread geometrically up to the
        table's end (g with all terms; inf where g vanishes there, zeros without a tree), set up
        once: :func:`._far.terms_from_ratios` picks the terms of an rtol from them (a table
        whose weights cancel inside blocks less takes more terms)."""
        cached = self.__dict__.get("_far_excess")
        if cached is None:
            x = float(self.r[-1]) * np.geomspace(2.0**-12, 1.0, 64)
            counts = np.arange(_far.TERMS + 1)
            cubic = self._spline is not None
            tree = self._cubic_tree() if cubic else self._far_tree()
            cached = np.zeros(counts.size)
            if tree is not None:
                bound = (self._cubic_truncation(x, "g", counts) if cubic
                         else self._far_truncation(x, "g", counts))
                g = np.abs(self._g_closed_form(x))
                cached = (np.max(bound / g, axis=1) if bool(np.all(g > 0))
                          else np.full(counts.size, np.inf))
            self.__dict__["_far_excess"] = cached
        return cast(np.ndarray, cached)

    @contextlib.contextmanager
    def _tree_rtol(self, rtol: float | None) -> Iterator[None]:
        """Inside: the far-field trees take the Taylor terms of ``rtol``
        (:func:`._far.terms_from_ratios`), and the results' error estimates carry their truncation
        bound. ``rtol=None`` keeps the setting of an enclosing call (the table's :attr:`rtol`
        outside one); on exit the enclosing setting is back. The setting belongs to the calling
        thread: another thread's call on the same table keeps its own."""
        calls, key = _call_terms(), id(self)
        prev = calls.get(key)
        if rtol is None and prev is not None:
            yield
            return
        rtol = self.rtol if rtol is None else rtol
        terms = _far.TERMS
        if rtol > _far.FULL_TERMS_RTOL:
            if prev is not None:
                del calls[key]
            try:
                terms = _far.terms_from_ratios(rtol, self._tree_excess())
            finally:
                if prev is not None:
                    calls[key] = prev
        calls[key] = terms
        try:
            yield
        finally:
            if prev is None:
                calls.pop(key, None)
            else:
                calls[key] = prev

    r: np.ndarray
    f: np.ndarray
    interpolation: str
    axis: str
    _slopes: np.ndarray
    _dslope: np.ndarray
    _monotone_f: bool | None
    _verified_upto: float
    _spline: Any
    _spline_d: Any
    _node_g: np.ndarray | None
    _cubic_base: tuple[float, float, float]
    _cubic_nodes: np.ndarray
    _cubic_jumps: np.ndarray
    _cubic_local_lo: np.ndarray
    _cubic_local_hi: np.ndarray
    _cubic_local_d: np.ndarray
    _cubic_local_mom: np.ndarray

    if TYPE_CHECKING:
        # the dispatching hooks of Tabulated, which the parts call (declared for type checkers)
        def _g_and_slope(self, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]: ...

        def _g_integral_closed_form(self, a: np.ndarray) -> np.ndarray: ...

        def _g_closed_form(self, x: np.ndarray) -> np.ndarray: ...

        def _cubic_tree(self) -> Any: ...

        def _far_tree(self) -> Any: ...

        def _cubic_truncation(self, x: np.ndarray, kind: str,
                              terms: np.ndarray | None = None) -> np.ndarray: ...

        def _far_truncation(self, x: np.ndarray, kind: str, terms: np.ndarray | None = None
                            ) -> np.ndarray: ...

        def _g_slope_integral(self, x: np.ndarray
                              ) -> tuple[np.ndarray, np.ndarray, np.ndarray]: ...

        def _height(self, r: np.ndarray) -> np.ndarray: ...

        def _cubic_g_slope_integral(self, x: np.ndarray
                                    ) -> tuple[np.ndarray, np.ndarray, np.ndarray]: ...

        def _cubic_shared_pass(self) -> contextlib.AbstractContextManager[None]: ...

        def _cubic_tree(self) -> Any: ...

        def _cubic_signed_pass(self, x: np.ndarray
                               ) -> tuple[np.ndarray, np.ndarray, np.ndarray] | None: ...

        def _cubic_prime(self, a: np.ndarray) -> np.ndarray: ...

        def _far_prime(self, a: np.ndarray) -> None: ...

    def _guard(self, r: np.ndarray, name: str) -> None:
        if np.any(r > self.r[-1]):
            raise OutsideTheoryError(
                f"{name}={float(np.max(r))!r} m lies beyond the table (last radius {self.r[-1]!r} m): "
                "extend the measured profile or reduce the load.")

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
