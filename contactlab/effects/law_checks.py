"""Input checks of :class:`contactlab.effects.law.ContactLaw`: per-contact and per-step arrays
and the entries of a restored state, each refused with a ParameterError naming what is wrong."""
from __future__ import annotations

import warnings
from collections.abc import Iterator, Mapping
from typing import TYPE_CHECKING, Any

import numpy as np

from ..errors import ParameterError, ValidityWarning
from ..params import LENGTH_BOUNDS, MODULUS_BOUNDS, as_checked_array
from ..profiles.power_law import VALIDITY_SLOPE

__all__ = ["FixedGeometry", "FixedParameter", "checked_state_entry", "read_only", "SlopeCheck",
           "warn_model_error",
           "warn_outside_slope"]

#: contacts per block of :func:`warn_outside_slope` (its temporaries stay in cache)
_SLOPE_BLOCK = 1 << 15

if TYPE_CHECKING:
    from .law_step import LawStep

_UNITS = {"spring_cover": "1", "radius": "m", "R": "m", "c": "m^(1-n)", "slope": "1", "E_star": "Pa",
          "G_star": "Pa", "G_torsion": "Pa", "friction": "1"}
_BOUNDS = {"m": LENGTH_BOUNDS, "Pa": MODULUS_BOUNDS}


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
        return read_only(obj.__dict__[self.slot])

    def __set__(self, obj: Any, value: Any) -> None:
        raise ParameterError(f"ContactLaw.{self.name} is fixed when the law is built (it was "
                             f"given {_short(value)}): build a new ContactLaw for other "
                             "parameters, or one law per parameter set.")


class FixedGeometry(Mapping):
    """A law's geometry, ``{name: read-only per-contact array}``: fixed when the law is built,
    as its parameters (:class:`FixedParameter`); an entry assigned raises
    :class:`~contactlab.errors.ParameterError`."""

    def __init__(self, name: str, values: np.ndarray) -> None:
        self._items = {name: read_only(values)}

    def __getitem__(self, key: str) -> np.ndarray:
        return self._items[key]

    def __iter__(self) -> Iterator[str]:
        return iter(self._items)

    def __len__(self) -> int:
        return len(self._items)

    def __setitem__(self, key: str, value: Any) -> None:
        raise ParameterError(f"ContactLaw.geometry[{key!r}] is fixed when the law is built (it "
                             f"was given {_short(value)}): build a new ContactLaw for another "
                             "geometry.")

    def __repr__(self) -> str:
        return f"FixedGeometry({self._items!r})"


def read_only(arr: np.ndarray) -> np.ndarray:
    """A view of ``arr`` that refuses writes (``arr`` itself stays writeable)."""
    view = arr.view()
    view.flags.writeable = False
    return view


def _short(value: Any) -> str:
    """``repr(value)``, cut to 60 characters (for error messages)."""
    r = repr(value)
    return r if len(r) <= 60 else r[:57] + "..."


def _per_contact(name: str, value: Any, size: int | None) -> np.ndarray:
    """A positive finite per-contact array (scalar or 1D), errors naming the index; lengths
    and moduli within the profiles' and materials' bounds."""
    unit = _UNITS.get(name, "-")
    arr = as_checked_array(name, value, domain="positive", unit=unit, bounds=_BOUNDS.get(unit))
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
    largest errors first; in the step that warns, the first contact of the largest error from
    the start of the per-contact array up to it (:meth:`LawStep.model_error_worst_at`)."""
    peak = res.model_error_peaks_at(on)
    # (the table's 1.0e-2 at the default 16 springs is at 1 %, not above: its log-log
    # interpolation returns it one ulp high)
    todo = [q for q, e in peak.items() if q not in warned and e > limit * (1.0 + 1e-12)]
    for q in todo:      # the usual step: none, and no per-contact error array at all
        warned.add(q)
        i, value = res.model_error_worst_at(on, q, peak[q])
        text = (f"ContactLaw: the model error of the {q.replace('_', ' ')} reached "
                f"{value:.3g} at contact {i} (> {limit:.0%}): contacts "
                "whose normal load changed run on MDR springs (step.model_error per contact; "
                f"{springs} springs per contact, raise springs= to lower the spring "
                "part). Said once per law and quantity; silence it with "
                "ContactLaw(..., warn_model_error=False) or law.warn_model_error = False.")
        res.meta["notes"] = (*res.meta.get("notes", ()), text)
        warnings.warn(text, ValidityWarning, stacklevel=5)


class SlopeCheck:
    """The paraboloid law's check of ``a <= R/√3`` per contact (``R`` m, per contact), until it
    warns: a step whose largest radius is within the smallest ``R``'s limit passes after one
    reduction; otherwise :func:`warn_outside_slope` looks contact by contact."""

    def __init__(self, R: np.ndarray) -> None:
        self.R = R
        self.floor = float(R.min()) * VALIDITY_SLOPE

    def __call__(self, res: "LawStep", kc: Any = None) -> bool:
        """Whether the step ``res`` warned (``kc``: the device copy of ``1/R``, or None)."""
        if kc is None and float(res.radius.max()) <= self.floor:
            return False
        return warn_outside_slope(res, self.R, kc)


def warn_outside_slope(res: "LawStep", R: np.ndarray, kc: Any = None) -> bool:
    """A :class:`ValidityWarning` when a paraboloid contact's radius in the step ``res``
    exceeds ``R/√3`` (``R`` per contact, m), where the surface slope ``a/R`` reaches tan 30°
    and the half-space theory leaves its range (the limit
    :attr:`~contactlab.profiles.Paraboloid.validity_radius` gives a single contact). The text
    names the first such contact and also goes into ``res.meta["notes"]``.

    The host check runs in blocks of :data:`_SLOPE_BLOCK` contacts (no temporary of the law's
    size); a device step (``kc``: the device copy of ``1/R``) compares ``a·kc`` on the device.
    Returns whether it warned (the law says it once)."""
    a = res.radius
    if kc is not None:                                  # device arrays: one reduction there
        over = a * kc > VALIDITY_SLOPE
        if not bool(over.any()):
            return False
        i = int(over.argmax())
    else:
        lim = np.empty(min(_SLOPE_BLOCK, a.size))
        for s in range(0, a.size, _SLOPE_BLOCK):         # blocks, not contacts
            e = min(s + _SLOPE_BLOCK, a.size)
            np.multiply(R[s:e], VALIDITY_SLOPE, out=lim[:e - s])
            if np.any(a[s:e] > lim[:e - s]):
                i = s + int(np.argmax(a[s:e] > lim[:e - s]))
                break
        else:
            return False
    text = (f"ContactLaw: contact {i}'s radius {float(a[i])!r} m exceeds R/√3 = "
            f"{float(R[i]) * VALIDITY_SLOPE!r} m (R = {float(R[i])!r} m), where the "
            "paraboloid's surface slope reaches tan 30°: outside the range of the half-space "
            "theory, the result is the half-space solution, not that of the real body. Said "
            "once per law.")
    res.meta["notes"] = (*res.meta.get("notes", ()), text)
    warnings.warn(text, ValidityWarning, stacklevel=5)   # the caller of law.step
    return True
