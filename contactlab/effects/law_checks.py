"""Input checks of :class:`contactlab.effects.law.ContactLaw`: per-contact and per-step arrays
and the entries of a restored state, each refused with a ParameterError naming what is wrong."""
from __future__ import annotations

import warnings
from typing import TYPE_CHECKING, Any

import numpy as np

from ..errors import ParameterError, ValidityWarning
from ..params import as_checked_array

__all__ = ["FixedParameter", "checked_state_entry", "warn_model_error"]

if TYPE_CHECKING:
    from .law_step import LawStep

_UNITS = {"spring_cover": "1", "radius": "m", "R": "m", "c": "m^(1-n)", "slope": "1", "E_star": "Pa",
          "G_star": "Pa", "G_torsion": "Pa", "friction": "1"}


class FixedParameter:
    """A law's per-contact parameter, fixed when the law is built: read as a read-only view.

    The law derives products from its parameters once (``mu E*``, the force factor), and a
    device law copies them once, so a parameter written in place would leave those behind and
    the compiled and numpy paths would disagree without a word. Reading gives a view that
    refuses writes; assigning raises :class:`~contactlab.errors.ParameterError`. The law itself
    keeps the array under ``_<name>``.
    """

    def __set_name__(self, owner: type, name: str) -> None:
        self.name = name
        self.slot = "_" + name

    def __get__(self, obj: Any, owner: type | None = None) -> Any:
        if obj is None:
            return self
        view = obj.__dict__[self.slot].view()
        view.flags.writeable = False
        return view

    def __set__(self, obj: Any, value: Any) -> None:
        raise ParameterError(f"ContactLaw.{self.name} is fixed when the law is built (it was "
                             f"given {_short(value)}): build a new ContactLaw for other "
                             "parameters, or one law per parameter set.")


def _short(value: Any) -> str:
    """``repr(value)``, cut to 60 characters (for error messages)."""
    r = repr(value)
    return r if len(r) <= 60 else r[:57] + "..."


def _per_contact(name: str, value: Any, size: int | None) -> np.ndarray:
    """A positive finite per-contact array (scalar or 1D), errors naming the index."""
    arr = as_checked_array(name, value, domain="positive", unit=_UNITS.get(name, "-"))
    if arr.ndim > 1:
        raise ParameterError(f"{name} has shape {arr.shape}: give a scalar or one value per "
                             "contact (1D).")
    if arr.ndim == 1 and size is not None and arr.size != size:
        raise ParameterError(f"{name} has {arr.size} values but the law has {size} contacts: "
                             "give a scalar or one value per contact.")
    return arr


def _per_step(name: str, value: Any, size: int, unit: str, nonneg: bool = False) -> np.ndarray:
    """A finite (``nonneg``: and >= 0) scalar or one value per contact, broadcast to ``size``."""
    arr = as_checked_array(name, value, domain="nonnegative" if nonneg else "real", unit=unit,
                           size=size)
    return np.broadcast_to(arr, (size,))


def checked_state_entry(key: str, value: Any, like: np.ndarray, memory: int,
                        springs: int) -> np.ndarray:
    """One entry of a state being restored, as ``like``'s dtype, or ParameterError naming
    the key, the first offending entry and what is allowed (never NaN or a stray flag:
    a NaN reference depth would disable the constant-load check and report a wrong torque
    as exact)."""
    try:
        arr = np.asarray(value)
    except Exception as err:                # ragged lists and the like
        raise ParameterError(f"state[{key!r}] is invalid: it must be an array of shape "
                             f"{like.shape}.") from err
    if arr.shape != like.shape:
        raise ParameterError(f"state[{key!r}] has shape {arr.shape}; this law needs "
                             f"{like.shape}.")
    if arr.dtype.kind not in "biuf":
        raise ParameterError(f"state[{key!r}] has dtype {arr.dtype}: it must be numeric "
                             f"({like.dtype}).")
    kind = like.dtype.kind
    if kind == "f":
        ok, allowed = np.isfinite(arr), "finite"
        if key in ("depth_ref", "spr_cover", "spr_a"):
            ok, allowed = ok & (arr >= 0), "finite and >= 0 m"
    else:
        whole = np.isfinite(arr) & (arr == np.round(arr)) if arr.dtype.kind == "f" else True
        if kind == "b":
            ok, allowed = whole & ((arr == 0) | (arr == 1)), "a flag (False/True)"
        elif key.endswith("_last"):
            ok, allowed = whole & (np.abs(arr) <= 1), "-1, 0 or 1 (last direction)"
        elif key.endswith("_depth"):
            ok = whole & (arr >= 0) & (arr <= memory)
            allowed = f"an integer count of turning points in [0, memory={memory}]"
        else:                               # spr_k: the cell holding the contact edge
            ok = whole & (arr >= 0) & (arr < max(springs, 1))
            allowed = f"an integer cell index in [0, springs={springs})"
    ok = np.broadcast_to(ok, arr.shape)
    if not np.all(ok):
        i = np.unravel_index(int(np.argmin(ok)), arr.shape)
        at = ", ".join(str(int(j)) for j in i)
        raise ParameterError(f"state[{key!r}][{at}]={arr[i].item()!r} is invalid: it must "
                             f"be {allowed} (restore a state saved from law.state of a law "
                             "of the same size, memory and springs).")
    return arr.astype(like.dtype, copy=True)


def warn_model_error(res: "LawStep", on: np.ndarray, warned: set[str], springs: int,
                     limit: float) -> None:
    """A :class:`ValidityWarning` when the step ``res``'s model error exceeds ``limit`` for a
    quantity at a contact on springs (indices ``on``, or a bool mask over all contacts), once
    per quantity: ``warned`` (the law's set of quantities already said) gains it; the text
    also goes into ``res.meta["notes"]``.

    Reads the contacts on springs only (an overflowed memory warns on its own), and their
    largest errors first: the per-contact arrays are built only in the step that warns."""
    peak = res.model_error_peaks_at(on)
    todo = [q for q, e in peak.items() if q not in warned and e > limit * (1.0 + 1e-12)]
    if not todo:        # the usual step: no per-contact error array at all
        return
    on = np.flatnonzero(on) if on.dtype == bool else on
    for q, err in res.model_errors_at(on).items():
        err = np.asarray(err, float)
        # (the table's 1.0e-2 at the default 16 springs is at 1 %, not above: its log-log
        # interpolation returns it one ulp high)
        if q in warned or not np.any(err > limit * (1.0 + 1e-12)):
            continue
        warned.add(q)
        j = int(np.argmax(err))
        i = int(on[j])
        text = (f"ContactLaw: the model error of the {q.replace('_', ' ')} reached "
                f"{float(err[j]):.3g} at contact {i} (> {limit:.0%}): contacts "
                "whose normal load changed run on MDR springs (step.model_error per contact; "
                f"{springs} springs per contact, raise springs= to lower the spring "
                "part). Said once per law and quantity; silence it with "
                "ContactLaw(..., warn_model_error=False) or law.warn_model_error = False.")
        res.meta["notes"] = (*res.meta.get("notes", ()), text)
        warnings.warn(text, ValidityWarning, stacklevel=5)
