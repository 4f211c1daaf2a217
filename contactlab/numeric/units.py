"""The unit grammar of contactlab (scene files, data files and Python arguments): quantities
with explicit unit suffixes, ``"10 um"``, ``"210 GPa"``, ``"5 deg"``, ``"1e-3 m"``.

Scene files hold SI numbers or strings ``"<number> <unit>"``. The number follows the full float
grammar (sign, decimals, exponent: ``"-2.5e-3 mrad"``); the unit must belong to the dimension the
key expects, else :class:`~contactlab.errors.UnitError` names the key, the value and the units
that would be accepted (with a did-you-mean for near misses).
"""
from __future__ import annotations

import difflib
import math
import re

from ..errors import UnitError

__all__ = ["UNITS", "DIMENSION_OF_SI_UNIT", "SI_UNIT", "parse_quantity", "format_quantity",
           "dimension_of_unit", "canonical_unit", "unit_factor", "split_header", "split_number",
           "underscore_unit"]

_PRODUCT = re.compile(r"\s*[*·]\s*|\s+")


def canonical_unit(unit: str) -> str:
    """The spelling contactlab writes for ``unit``: factors joined by ``*``.

    Input may join factors by a space, ``*`` or ``·``; all mean the same product.

    >>> canonical_unit("N m"), canonical_unit(" mN·m "), canonical_unit("Pa * s")
    ('N*m', 'mN*m', 'Pa*s')
    """
    return _PRODUCT.sub("*", unit.strip())

_MICRO = ("u", "µ", "μ")  # ASCII u, micro sign U+00B5, Greek mu U+03BC


def _scaled(base: str, factors: dict[str, float]) -> dict[str, float]:
    out: dict[str, float] = {}
    for prefix, f in factors.items():
        if prefix == "u":
            for m in _MICRO:
                out[m + base] = f
        else:
            out[prefix + base] = f
    return out


_SI = {"": 1.0, "k": 1e3, "M": 1e6, "G": 1e9, "m": 1e-3, "u": 1e-6, "n": 1e-9}

#: dimension -> {unit spelling: factor to SI}. Products are spelled with ``*`` (``N*m``, ``Pa*s``),
#: the one spelling contactlab writes; input may also join factors by a space or ``·``.
UNITS: dict[str, dict[str, float]] = {
    "length": {**_scaled("m", {"": 1.0, "c": 1e-2, "m": 1e-3, "u": 1e-6, "n": 1e-9, "p": 1e-12,
                               "k": 1e3}), "micron": 1e-6, "Å": 1e-10, "angstrom": 1e-10},
    "force": _scaled("N", {"": 1.0, "k": 1e3, "M": 1e6, "m": 1e-3, "u": 1e-6, "n": 1e-9}),
    "pressure": {**_scaled("Pa", {"": 1.0, "k": 1e3, "M": 1e6, "G": 1e9, "T": 1e12}),
                 "N/m^2": 1.0, "N/mm^2": 1e6, "bar": 1e5, "psi": 6894.757293168361},
    "angle": {**_scaled("rad", {"": 1.0, "m": 1e-3, "u": 1e-6}), "deg": math.pi / 180,
              "°": math.pi / 180, "arcmin": math.pi / 10800, "arcsec": math.pi / 648000},
    "torque": {**_scaled("N*m", {"": 1.0, "k": 1e3, "m": 1e-3, "u": 1e-6}),
               "Nm": 1.0, "mNm": 1e-3, "N*mm": 1e-3},
    "time": {**_scaled("s", {"": 1.0, "m": 1e-3, "u": 1e-6, "n": 1e-9}), "min": 60.0,
             "h": 3600.0},
    "energy_per_area": {**_scaled("J/m^2", {"": 1.0, "m": 1e-3, "u": 1e-6}),
                        **_scaled("J/m2", {"": 1.0, "m": 1e-3, "u": 1e-6}),
                        **_scaled("N/m", {"": 1.0, "m": 1e-3, "u": 1e-6})},
    "energy": _scaled("J", {"": 1.0, "m": 1e-3, "u": 1e-6, "n": 1e-9}),
    "viscosity": _scaled("Pa*s", {"": 1.0, "k": 1e3, "M": 1e6, "G": 1e9, "m": 1e-3}),
    "dimensionless": {"": 1.0, "1": 1.0, "%": 1e-2},
    # Archard's wear coefficient k = K/H: worn volume per normal force and sliding distance
    "wear_coefficient": {"1/Pa": 1.0, "1/kPa": 1e-3, "1/MPa": 1e-6, "1/GPa": 1e-9,
                         "m^3/(N*m)": 1.0, "mm^3/(N*m)": 1e-9},
}

#: Param.unit strings (the SI unit a parameter is declared in) -> dimension
DIMENSION_OF_SI_UNIT = {"m": "length", "N": "force", "Pa": "pressure", "rad": "angle",
                        "N*m": "torque", "s": "time", "J/m^2": "energy_per_area", "J": "energy",
                        "Pa*s": "viscosity", "1": "dimensionless", "-": "dimensionless",
                        "1/Pa": "wear_coefficient"}
#: dimension -> its SI unit as contactlab writes it
SI_UNIT = {"length": "m", "force": "N", "pressure": "Pa", "angle": "rad", "torque": "N*m",
           "time": "s", "energy_per_area": "J/m^2", "energy": "J", "viscosity": "Pa*s",
           "wear_coefficient": "1/Pa"}

_NUMBER = r"[+-]?(?:\d+(?:_\d+)*(?:\.\d*)?|\.\d+)(?:[eE][+-]?\d+)?"
_QUANTITY = re.compile(rf"^\s*({_NUMBER})\s*(.*?)\s*$")


def split_number(text: str) -> tuple[float | None, str]:
    """``"210 GPa"`` -> ``(210.0, "GPa")``: the number and the (normalised) unit of a quantity
    string; ``(None, "")`` when ``text`` does not start with a number.

    >>> split_number("210 GPa"), split_number("1e9"), split_number("GPa")
    ((210.0, 'GPa'), (1000000000.0, ''), (None, ''))
    """
    m = _QUANTITY.match(text)
    if not m:
        return None, ""
    return float(m.group(1).replace("_", "")), _normalise_unit(m.group(2))


def dimension_of_unit(unit: str) -> str | None:
    """Dimension a unit spelling belongs to, or None when unknown."""
    for dim, table in UNITS.items():
        if unit in table:
            return dim
    return None


def _normalise_unit(unit: str) -> str:
    return canonical_unit(unit.replace("²", "^2").replace("**", "^"))


def parse_quantity(value: object, dimension: str, key: str = "value") -> float:
    """Convert a number or a ``"<number> <unit>"`` string to a float in SI units.

    Parameters
    ----------
    value : float, int or str
        ``2000``, ``"2 kN"``, ``"1e-3 m"``, ``"0.5 mrad"``. Plain numbers are SI already.
    dimension : str
        Key of :data:`UNITS` the quantity must have (``"length"``, ``"force"``, ...) or
        ``"number"`` for parameters that accept plain numbers only.
    key : str
        Key path used in messages (``load_path[2].sinusoid.amplitude``).

    Returns
    -------
    float
        The value in SI units (may be any finite float; domain checks come later).

    Raises
    ------
    UnitError
        Not a number, a non-finite number, an unknown unit or a unit of another dimension.

    Examples
    --------
    >>> parse_quantity("210 GPa", "pressure")
    210000000000.0
    >>> parse_quantity("1e-3 m", "length")
    0.001
    >>> round(parse_quantity("5 deg", "angle"), 12)
    0.0872664626
    """
    allowed = _allowed(dimension)
    if isinstance(value, bool) or not isinstance(value, (int, float, str)):
        raise _unit_error(key, value, allowed,
                          f"{key}={value!r} is invalid: expected a number or a string "
                          f"'<number> <unit>' with unit in {allowed}.")
    if isinstance(value, (int, float)):
        v = float(value)
        if not math.isfinite(v):
            raise _unit_error(key, value, "a finite number",
                              f"{key}={value!r} is invalid: the value must be finite.")
        return v
    m = _QUANTITY.match(value)
    if not m:
        raise _unit_error(key, value, allowed,
                          f"{key}={value!r} is invalid: expected '<number> <unit>' (e.g. "
                          f"'{_example(dimension)}'), unit in {allowed}.")
    number = float(m.group(1).replace("_", ""))
    unit = _normalise_unit(m.group(2))
    if not math.isfinite(number):
        raise _unit_error(key, value, "a finite number",
                          f"{key}={value!r} is invalid: the value must be finite.")
    if dimension == "number":
        if unit in ("", "1"):
            return number
        raise _unit_error(key, value, "a plain number in SI units",
                          f"{key}={value!r} is invalid: this parameter takes a plain number in "
                          "SI units (no unit suffix).")
    table = UNITS[dimension]
    if unit in table:
        v = number * table[unit]
        if not math.isfinite(v):
            raise _unit_error(key, value, "a finite number",
                              f"{key}={value!r} overflows: the value in SI units is not finite.")
        return v
    other = dimension_of_unit(unit)
    if other is not None:
        raise _unit_error(key, value, allowed,
                          f"{key}={value!r} has unit {unit!r} of dimension {other}, but {key} is a "
                          f"{dimension.replace('_', ' ')}: use one of {allowed}.")
    close = difflib.get_close_matches(unit, list(table), n=3, cutoff=0.5)
    hint = f" Did you mean {' or '.join(repr(c) for c in close)}?" if close else ""
    raise _unit_error(key, value, allowed,
                      f"{key}={value!r} has unknown unit {unit!r}: use one of {allowed}.{hint}")


def format_quantity(value: float, dimension: str) -> str:
    """Human string of an SI value with its SI unit (``"0.01 m"``); plain repr when dimensionless."""
    unit = SI_UNIT.get(dimension)
    return f"{value!r} {unit}" if unit else repr(value)


def _allowed(dimension: str) -> str:
    if dimension == "number":
        return "a plain number (SI)"
    units = [u for u in UNITS[dimension] if u and not u.startswith(("µ", "μ"))]
    return "{" + ", ".join(units) + "}"


def _example(dimension: str) -> str:
    return {"length": "10 um", "force": "2 kN", "pressure": "210 GPa", "angle": "5 deg",
            "torque": "0.1 N*m", "time": "2 s", "energy_per_area": "0.05 J/m^2", "energy": "1 mJ",
            "viscosity": "1 MPa*s", "dimensionless": "0.3", "number": "1.5",
            "wear_coefficient": "1e-6 mm^3/(N*m)"}[dimension]


def _unit_error(key: str, value: object, allowed: str, message: str) -> UnitError:
    return UnitError(message, issues=[(key, value, allowed)])


def unit_factor(unit: str, dimension: str, key: str = "unit") -> float:
    """Factor that converts a value given in ``unit`` to SI, for a quantity of ``dimension``.

    The same grammar as :func:`parse_quantity` (``"mm"``, ``"um"``, ``"µm"``, ``"kN"``,
    ``"deg"``, ``"N m"``); an empty unit means SI.

    Raises
    ------
    UnitError
        The unit is unknown or belongs to another dimension; the message names ``key``.

    Examples
    --------
    >>> unit_factor("mm", "length"), unit_factor("kN", "force")
    (0.001, 1000.0)
    """
    if not isinstance(unit, str):
        raise _unit_error(key, unit, _allowed(dimension),
                          f"{key}={unit!r} is invalid: expected a unit string from "
                          f"{_allowed(dimension)}.")
    return parse_quantity(f"1 {unit}", dimension, key)


def split_header(name: str, known_names: tuple[str, ...] | frozenset[str] | None = None
                 ) -> tuple[str, str | None]:
    """A CSV column header -> ``(name, unit or None)``.

    Accepted spellings: ``r [mm]``, ``r (mm)``, ``r/mm`` and ``r_mm``. The ``_`` form is read as
    a unit only when the part after the last ``_`` is a known unit spelling, or when the part
    before it is one of ``known_names`` (then an unknown unit is reported, not read as part of
    the name); a header that is itself one of ``known_names`` (``tangential_force``) is a name.

    >>> split_header(" twist [deg] "), split_header("time"), split_header("r/mm")
    (('twist', 'deg'), ('time', None), ('r', 'mm'))
    >>> split_header("f_um"), split_header("force_lbf", ("force",)), split_header("f_i")
    (('f', 'um'), ('force', 'lbf'), ('f_i', None))
    """
    name = name.strip()
    m = re.match(r"^(.*?)\s*[\[(]\s*(.*?)\s*[\])]\s*$", name)
    if m is not None:
        return m.group(1).strip(), m.group(2)
    if known_names is not None and name in known_names:
        return name, None
    if "/" in name:
        base, unit = (part.strip() for part in name.split("/", 1))
        if base and unit:
            return base, unit
    if "_" in name:
        base, suffix = name.rsplit("_", 1)
        if base and suffix and (dimension_of_unit(_normalise_unit(suffix)) is not None
                                or (known_names is not None and base in known_names)):
            return base, suffix
    return name, None


def underscore_unit(name: str) -> str | None:
    """The part after the last ``_`` of a header that :func:`split_header` left whole
    (``"r_furlong"`` -> ``"furlong"``), or None: readers of columns with a dimension refuse it
    as an unknown unit rather than take the column as SI."""
    if "_" not in name:
        return None
    base, suffix = name.rsplit("_", 1)
    return suffix if base and re.fullmatch(r"[^\W\d_][\w^°µμÅ]*", suffix) else None
