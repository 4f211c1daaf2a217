"""The result protocol: one small face shared by every result type of contactlab.

Every result (normal, tangential and torsion states, twist and shift histories, load paths,
adhesion cycles, viscoelastic histories, fretting loops and maps, wear runs, contact-law steps,
scene results) implements

* ``to_dict()``: its data by name;
* ``to_csv(path, overwrite=False)``: its per-step (per-point) columns with ``name [unit]``
  headers (SI units), preceded by metadata comment lines ``# key: value`` (``# notes: ...``,
  ``# model_error: ...``, ``# error_estimate: ...``) whenever the result carries a note or a
  model error. The CSV readers of contactlab (:func:`contactlab.loadpath.read_csv`,
  :class:`contactlab.Tabulated`) skip ``#`` lines; with pandas use
  ``pandas.read_csv(path, comment="#")``. An existing file is never replaced unless
  ``overwrite=True``;
* ``to_dataframe()``: the same columns as a :class:`pandas.DataFrame`, units, notes and errors in
  ``df.attrs``;
* ``plot(...)`` where a picture helps;
* ``cite()``: :func:`contactlab.cite` of the result;
* ``notes``: the warnings raised while it was computed (validity, model limits), as text;
* ``model_error`` beside ``error_estimate``: the measured distance of an approximate model from the
  exact solution (0.0 for exact routes), with ``model_errors`` per quantity and
  ``model_error_basis`` saying where the number comes from.

To implement it for a new result class:

1. Subclass :class:`Result` (a mixin: no fields, no ``__init__``) and set ``units``, the SI unit of
   each column (a class attribute).
2. Implement ``to_dict()``; override ``_columns()`` when the CSV columns differ from it (scalars,
   2D fields).
3. Optionally implement ``_model_errors()`` (per-quantity relative errors of an approximate
   route; computed on first access of :attr:`Result.model_error`), store ``model_errors`` and
   ``model_error_basis`` in ``meta``, or defer them with ``result._defer_model_errors(fn)``; put
   warnings into ``meta["notes"]`` or let the driver carry :func:`reporting`, which records them.
4. Add the class to :data:`contactlab.testing.RESULT_TYPES`; :class:`contactlab.testing.ResultChecks`
   then checks it.
"""
from __future__ import annotations

import csv
import functools
import io
import os
import sys
import warnings
from collections.abc import Callable
from pathlib import Path
from typing import IO, Any, ClassVar

import numpy as np

from ..errors import ContactlabWarning, ParameterError, ValidityWarning

__all__ = ["Result", "reporting", "csv_text", "write_csv", "MODEL_ERROR_WARN", "metadata_lines",
           "EXACT_BASIS"]

#: relative model error above which a result of an approximate route warns (ValidityWarning)
MODEL_ERROR_WARN = 0.01
#: ``model_error_basis`` of an exact route
EXACT_BASIS = "exact route (no model error)"


def _one_line(text: Any) -> str:
    return " ".join(str(text).split())


def _scalar_max(value: Any) -> float:
    arr = np.asarray(value, float)
    return float(np.max(arr)) if arr.size else 0.0


def metadata_lines(meta: dict[str, Any]) -> list[str]:
    """The ``# key: value`` comment lines of a CSV file for ``meta`` (``notes``: one line per
    note; other keys one line each); none when there are no notes and no model error."""
    notes = [_one_line(n) for n in meta.get("notes", ()) if str(n).strip()]
    model = meta.get("model_error", 0.0)
    if not notes and not model:
        return []
    lines = [f"# notes: {n}" for n in notes]
    for key in ("model_error", "model_error_basis", "error_estimate"):
        v = meta.get(key)
        if v is not None and v != "":
            lines.append(f"# {key}: {v if isinstance(v, str) else repr(float(v))}")
    return lines


def csv_text(columns: dict[str, Any], units: dict[str, str], meta: dict[str, Any] | None = None
             ) -> str:
    """CSV of equal-length columns: metadata comment lines (:func:`metadata_lines`), a header of
    ``name [unit]`` (``name`` alone for a column without a unit), one row per entry, values as
    ``repr`` of floats (they read back bit for bit)."""
    names = list(columns)
    arrs = [np.asarray(columns[n], float).ravel() for n in names]
    fh = io.StringIO(newline="")
    for line in metadata_lines(meta or {}):
        fh.write(line + "\r\n")
    w = csv.writer(fh)
    w.writerow([f"{n} [{units[n]}]" if units.get(n) else n for n in names])
    for row in zip(*arrs):
        w.writerow([repr(float(v)) for v in row])
    return fh.getvalue()


def write_csv(path: Any, text: str, overwrite: bool = False) -> Path:
    """Write ``text`` to ``path``; an existing file only with ``overwrite=True``.

    Raises
    ------
    ParameterError
        ``path`` exists and ``overwrite`` is False, or it is a folder.
    """
    p = Path(os.fspath(path))
    if p.is_dir():
        raise ParameterError(f"path={str(path)!r} is invalid: it is a folder; give a file name.")
    try:
        with open(p, "w" if overwrite else "x", newline="") as fh:
            fh.write(text)
    except FileExistsError:
        raise ParameterError(f"path={str(path)!r} exists: to_csv() never replaces a file unless "
                             "asked; pass overwrite=True or choose another name.") from None
    return p


class Result:
    """Mixin of every result type: the protocol of :mod:`contactlab.effects._protocol`.

    Attributes
    ----------
    units : dict
        SI unit of each column of :meth:`to_csv` (class attribute).
    """

    units: ClassVar[dict[str, str]] = {}
    #: ``model_error_basis`` when the class computes no model error (an exact route)
    _basis: ClassVar[str] = EXACT_BASIS

    # ------------------------------------------------------------------ data
    def to_dict(self) -> dict[str, Any]:  # pragma: no cover - every result defines it
        raise NotImplementedError

    def _columns(self) -> dict[str, Any]:
        """The columns of :meth:`to_csv` and :meth:`to_dataframe` (default :meth:`to_dict`)."""
        return {k: np.ravel(v) for k, v in self.to_dict().items()}

    def _meta(self) -> dict:
        meta = getattr(self, "meta", None)
        return meta if isinstance(meta, dict) else {}

    # ------------------------------------------------------------------ notes and errors
    @property
    def notes(self) -> tuple[str, ...]:
        """Warnings raised while this result was computed (validity, model limits), as text."""
        return tuple(self._meta().get("notes", ()))

    def _model_errors(self) -> dict[str, Any]:
        """Per-quantity relative model errors (empty for an exact route)."""
        return {}

    @property
    def model_errors(self) -> dict[str, Any]:
        """Relative model error of each quantity of an approximate route (``{}`` for an exact
        route): the measured distance of the model from the exact solution (see
        :attr:`model_error_basis`), computed on first access."""
        # computed once, kept beside the fields (not in ``meta``: a result equals its recomputed
        # copy whether or not its model error was read)
        got = self.__dict__.get("_model_errors_cache")
        if got is None:
            pending = self.__dict__.get("_model_errors_fn")
            got = pending() if pending is not None else self._meta().get("model_errors")
            if got is None:
                got = self._model_errors()
            object.__setattr__(self, "_model_errors_cache", got)
        return dict(got)

    def __getstate__(self) -> dict[str, Any]:
        """Pickled state: a deferred model error is computed first, so that the pickle does not
        carry the contact it was deferred with (which may hold unpicklable callables)."""
        state = dict(self.__dict__)
        fn = state.pop("_model_errors_fn", None)
        if fn is not None and "_model_errors_cache" not in state:
            state["_model_errors_cache"] = fn()
        return state

    def _defer_model_errors(self, fn: Callable[[], dict[str, Any]]) -> None:
        """Compute :attr:`model_errors` by ``fn()`` on first access (a picklable callable)."""
        object.__setattr__(self, "_model_errors_fn", fn)
        self.__dict__.pop("_model_errors_cache", None)

    @property
    def model_error(self) -> Any:
        """Largest relative model error over the quantities of :attr:`model_errors` (0.0 for an
        exact route; per state for arrays of states). Numerical error is
        :attr:`error_estimate`'s; this is the approximate model's own, from measured maps of
        the model against the exact solution or from a coarse exact check
        (:attr:`model_error_basis` says which)."""
        errs = self.model_errors
        if not errs:
            return 0.0
        vals = [np.asarray(v, float) for v in errs.values()]
        out = functools.reduce(np.maximum, vals)
        return float(out) if out.ndim == 0 else out

    @property
    def model_error_basis(self) -> str:
        """Where :attr:`model_error` comes from (a measured map, a coarse exact check, or an exact
        route)."""
        if not self.model_errors:
            return EXACT_BASIS
        return self._meta().get("model_error_basis", self._basis)

    def metadata(self) -> dict[str, Any]:
        """JSON-ready metadata: ``type``, ``notes``, ``model_error`` (largest), ``model_errors``,
        ``model_error_basis``, ``error_estimate`` (largest; None where not estimated) and
        ``citations`` (tags)."""
        est = getattr(self, "error_estimate", None)
        tags: list[str] = []
        try:
            from ..citations import _citations_of
            tags = list(_citations_of(self).tags)
        except Exception:           # noqa: BLE001 - a result whose citations are not recorded
            tags = []
        return {"type": type(self).__name__, "notes": list(self.notes),
                "model_error": _json_float(_scalar_max(self.model_error)),
                "model_errors": {k: _json_float(_scalar_max(v))
                                 for k, v in self.model_errors.items()},
                "model_error_basis": self.model_error_basis,
                "error_estimate": None if est is None else _json_float(_scalar_max(est)),
                "citations": tags}

    # ------------------------------------------------------------------ output
    def to_csv(self, path: Any, *, overwrite: bool = False) -> Path:
        """Write :meth:`_columns` to CSV (``name [unit]`` headers; ``# notes: ...`` and the model
        error as comment lines first when there are any); returns the path.

        Raises
        ------
        ParameterError
            ``path`` exists and ``overwrite`` is False.
        """
        meta = self.metadata()
        return write_csv(path, csv_text(self._columns(), type(self).units, meta), overwrite)

    def to_dataframe(self) -> Any:
        """The columns of :meth:`to_csv` as a :class:`pandas.DataFrame` (needs pandas); units,
        notes, model and numerical errors in ``df.attrs`` (``"units"``, ``"notes"``,
        ``"model_error"``, ``"model_error_basis"``, ``"error_estimate"``)."""
        try:
            import pandas as pd
        except ImportError as err:
            raise ImportError("to_dataframe() needs pandas: pip install pandas "
                              "(or pip install 'contactlab[data]')") from err
        cols = self._columns()
        df = pd.DataFrame(cols)
        meta = self.metadata()
        df.attrs.update(units={k: type(self).units.get(k, "") for k in cols},
                        notes=meta["notes"], model_error=meta["model_error"],
                        model_errors=meta["model_errors"],
                        model_error_basis=meta["model_error_basis"],
                        error_estimate=meta["error_estimate"])
        return df

    def _summary_repr(self, **lead: Any) -> str:
        """``Name(key=value unit, ...)`` of :meth:`to_dict` after the items ``lead`` (their
        ``repr``): a scalar by its value (6 significant digits), an array by its shape and range
        (for the repr of a state whose dataclass fields hide the numbers)."""
        units = type(self).units
        parts = [f"{k}={v!r}" for k, v in lead.items()]
        for key, value in self.to_dict().items():
            unit = units.get(key, "")
            unit = "" if unit in ("", "1") else f" {unit}"
            arr = np.asarray(value)
            if arr.ndim == 0:
                v = arr.item()
                parts.append(f"{key}={v!r}" if isinstance(v, bool) else f"{key}={v:.6g}{unit}")
            elif arr.size and arr.dtype.kind == "f":
                parts.append(f"{key}=<{'x'.join(map(str, arr.shape))}: {np.min(arr):.4g} .. "
                             f"{np.max(arr):.4g}{unit}>")
            else:
                parts.append(f"{key}=<{'x'.join(map(str, arr.shape))}>")
        return f"{type(self).__name__}({', '.join(parts)})"

    def cite(self, *, format: str = "both", file: IO[str] | None = sys.stdout) -> str:
        """:func:`contactlab.cite` of this result: print (and return) its sources."""
        from ..citations import cite
        return cite(self, format=format, file=file)


def _json_float(v: float) -> Any:
    return v if np.isfinite(v) else ("inf" if v > 0 else "-inf")


# ---------------------------------------------------------------------- recording warnings
#: per-file warning registries of re-emitted warnings (the "default" action shows a warning once
#: per location, as for a warning raised directly)
_REGISTRIES: dict[str, dict] = {}
_THIS_FILE = __file__


def _reemit(caught: list, here: tuple, there: tuple) -> None:
    for w in caught:
        loc = (w.filename, w.lineno)
        # the decorator is one frame more on the stack: a warning that lands on it belongs one
        # frame further out (the driver's caller), one that lands there one further still
        if loc[0] == _THIS_FILE:
            loc = here
        elif loc == here:
            loc = there
        warnings.warn_explicit(w.message, w.category, loc[0], loc[1],
                               registry=_REGISTRIES.setdefault(loc[0], {}))


def reporting(assess: Callable[..., list[str]] | None = None) -> Callable:
    """Decorator of a driver ``f(contact, ...) -> result``: the warnings it raises are recorded
    as text in ``result.meta["notes"]`` (``ContactlabWarning`` and subclasses) and raised as
    before (same category, message and location; a location that pointed at the driver's caller,
    the :class:`~contactlab.Contact` method, is moved to that method's caller, where the warning
    pointed without this decorator).

    ``assess(result, notes, contact, *args, **kwargs)``, if given, runs after the driver (with
    the notes recorded so far) and returns further warning texts (model errors above
    :data:`MODEL_ERROR_WARN` that no recorded warning states yet): they are recorded and raised
    as :class:`~contactlab.errors.ValidityWarning` at the user's call.
    """
    def wrap(func: Callable) -> Callable:
        @functools.wraps(func)
        def driver(*args: Any, **kwargs: Any) -> Any:
            f = sys._getframe(1)
            here = (f.f_code.co_filename, f.f_lineno)
            g = f.f_back
            there = (g.f_code.co_filename, g.f_lineno) if g is not None else here
            caught: list = []
            extra: list[str] = []
            try:
                with warnings.catch_warnings(record=True) as caught:
                    warnings.simplefilter("always")
                    res = func(*args, **kwargs)
                    if assess is not None:
                        seen = [_one_line(w.message) for w in caught
                                if issubclass(w.category, ContactlabWarning)]
                        extra = [_one_line(t) for t in assess(res, seen, *args, **kwargs)]
                notes = [_one_line(w.message) for w in caught
                         if issubclass(w.category, ContactlabWarning)] + extra
                meta = getattr(res, "meta", None)
                if notes and isinstance(meta, dict):
                    old = list(meta.get("notes", ()))
                    meta["notes"] = tuple(old + [n for n in notes if n not in old])
            finally:
                _reemit(list(caught), here, there)
            for text in extra:
                warnings.warn_explicit(text, ValidityWarning, there[0], there[1],
                                       registry=_REGISTRIES.setdefault(there[0], {}))
            return res
        return driver
    return wrap
