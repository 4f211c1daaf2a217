"""What a scene file may hold: every table's keys as data, checked by :mod:`.validate`.

One :class:`Key` says what a key holds (a quantity of a dimension, an integer, a name from a list,
...), its domain and bounds, and whether it is required. The tables below list the keys of each
section; the parameters of profiles, materials and the contact come from their own
:class:`~contactlab.params.Param` specifications (:meth:`Key.from_param`), and a profile or
material class declares keys beyond its constructor in ``scene_keys`` (parsed by
:func:`key_from_text`) and alternative key groups in ``scene_one_of`` (``Tabulated``: a file,
or the r and f columns).
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from ..contact import Contact
from ..effects.wear import INTEGRATORS
from ..foundation.rings import RTOL_RANGE as _TORQUE_RTOL_RANGE
from ..loadpath.base import GROUPS, QUANTITIES
from ..loadpath.base import UNITS as PATH_UNITS
from ..numeric.units import DIMENSION_OF_SI_UNIT, canonical_unit
from ..params import Param

__all__ = ["Key", "key_from_text", "dimension_of", "SECTIONS", "SERIES", "FIELDS", "EFFECTS",
           "METHODS", "CONTROLS", "SEGMENTS", "MAX_STEPS", "MAX_FIELD_POINTS", "SCENE_KEYS",
           "INTERFACE_KEYS", "SOLVER_KEYS", "OUTPUT_KEYS", "WEAR_KEYS", "FRETTING_MAP_KEYS",
           "CRITERIA", "MAX_MAP_POINTS", "MAX_WEAR_CYCLES", "MAX_CHECKPOINTS", "AXIS_KEYS",
           "FRETTING_MAP_TABLE"]


@dataclass(frozen=True)
class Key:
    """One key of a scene table.

    Parameters
    ----------
    kind : str
        ``"quantity"`` (a number or ``"<number> <unit>"``; a list of them for sequence
        parameters), ``"integer"``, ``"choice"`` (one name of ``choices``), ``"names"`` (a list
        of distinct names of ``choices``), ``"array"`` (a non-empty list of quantities),
        ``"file"`` (a file next to the scene), ``"unit"`` (a unit name of ``dimension``),
        ``"text"``, or a kind its section checks itself (``"terms"``, ``"axis"``,
        ``"checkpoints"``).
    dimension : str
        Quantities, arrays, units, axes: a dimension of :data:`contactlab.numeric.units.UNITS`,
        or ``"number"`` for plain numbers.
    domain : {"real", "positive", "nonnegative"}
        Quantities and axes.
    low, high : float, optional
        Integers: the inclusive range. Quantities: ``high`` is an upper bound (exclusive when
        ``high_open``), ``low`` an inclusive lower bound, ``high_allowed`` the message outside
        them.
    choices : tuple of str
        Names for ``"choice"`` and ``"names"``; for a quantity, names accepted instead of a
        number (``smoothing = "auto"``).
    required : str
        What to say when the key is missing (``""``: optional).
    """

    kind: str
    dimension: str = "dimensionless"
    domain: str = "real"
    low: float | None = None
    high: float | None = None
    high_open: bool = False
    high_allowed: str = ""
    choices: tuple[str, ...] = ()
    required: str = ""

    @classmethod
    def from_param(cls, p: Param, **kw: Any) -> Key:
        """The key of a :class:`~contactlab.params.Param`: a quantity of its unit's dimension
        (plain numbers for a unit outside the grammar, ``m^(1-n)``) in its domain."""
        return cls("quantity", dimension_of(p.unit), p.domain, **kw)


def dimension_of(unit: str) -> str:
    """Dimension of an SI unit as :class:`~contactlab.params.Param` declares it; ``"number"``
    (plain numbers only) for units outside the grammar."""
    return DIMENSION_OF_SI_UNIT.get(canonical_unit(unit), "number")


def key_from_text(text: str) -> Key:
    """A :class:`Key` from the compact form classes use in ``scene_keys``:
    ``"kind[:dimension[:domain]][|name,name]"``.

    >>> key_from_text("quantity:dimensionless:nonnegative|auto")
    Key(kind='quantity', dimension='dimensionless', domain='nonnegative', low=None, high=None, \
high_open=False, high_allowed='', choices=('auto',), required='')
    >>> key_from_text("choice|linear,cubic").choices
    ('linear', 'cubic')
    """
    head, _, names = text.partition("|")
    kind, *rest = head.split(":")
    dimension = rest[0] if rest else "dimensionless"
    domain = rest[1] if len(rest) > 1 else "real"
    return Key(kind, dimension, domain, choices=tuple(n for n in names.split(",") if n))


# ---- sections and outputs -----------------------------------------------------------------------
#: top-level tables of a scene
SECTIONS = ("scene", "profile", "materials", "interface", "load_path", "outputs", "solver",
            "wear", "fretting_map")
#: per-step series a run can write -> the effect that produces it
SERIES = {"time": "normal", "depth": "normal", "force": "normal", "radius": "normal",
          "stiffness": "normal", "peak_pressure": "normal", "twist": "torsion",
          "torque": "torsion", "stick_radius": None, "dissipated_energy": "slip",
          "displacement": "tangential", "tangential_force": "tangential"}
#: field outputs (at the final step, over radius) -> the effect that produces it
FIELDS = {"pressure": "normal", "surface_displacement": "normal", "shear": "torsion"}
#: effects in dependency order
EFFECTS = ("normal", "adhesion", "viscoelastic", "tangential", "torsion", "slip")
METHODS = ("no-slip", "exact", "mdr")
#: a scene may not ask for more load steps than this (fuzzed scenes must stay cheap)
MAX_STEPS = 200_000
#: most field points
MAX_FIELD_POINTS = 100_000

#: [scene]
SCENE_KEYS = {"title": Key("text"), "description": Key("text")}
_CONTACT = {p.name: p for p in Contact.params}
#: [interface]: the contact's own parameters
INTERFACE_KEYS = {k: Key.from_param(_CONTACT[k]) for k in ("friction", "work_of_adhesion")}
#: [solver]
SOLVER_KEYS = {
    "rtol": Key.from_param(_CONTACT["rtol"], high=0.1, high_open=True,
                           high_allowed="0 < rtol < 0.1"),
    "n_springs": Key("integer", low=2, high=10_000_000),
    # rings of the exact torsion solver (varying-load twist)
    "n_rings": Key("integer", low=2, high=10_000_000),
    # or the rings chosen for a torque accuracy (Contact.simulate(torque_rtol=...)); not both
    "torque_rtol": Key("quantity", "dimensionless", "positive", low=_TORQUE_RTOL_RANGE[0],
                       high=_TORQUE_RTOL_RANGE[1],
                       high_allowed=f"a torque accuracy relative to the sliding torque, "
                                    f"{_TORQUE_RTOL_RANGE[0]:g} <= torque_rtol <= "
                                    f"{_TORQUE_RTOL_RANGE[1]:g} (the range of the measured "
                                    "error law of the ring count)"),
}
#: [outputs]
OUTPUT_KEYS = {
    "series": Key("names", choices=tuple(SERIES)),
    "fields": Key("names", choices=tuple(FIELDS)),
    "field_points": Key("integer", low=2, high=MAX_FIELD_POINTS),
    "method": Key("choice", choices=METHODS),
    "effects": Key("names", choices=EFFECTS),
}

# ---- load path ----------------------------------------------------------------------------------
#: load-path control -> (axis, dimension): the load path's own groups (normal, tangential,
#: torsion) and units, so a scene and a typed LoadPath name the axes alike
CONTROLS = {q: (GROUPS[q], DIMENSION_OF_SI_UNIT[PATH_UNITS[q]]) for q in QUANTITIES}


def _steps(kind: str, low: int = 1, required: bool = True) -> Key:
    return Key("integer", low=low, high=MAX_STEPS,
               required=f"required for a {kind} segment" if required else "")


_DURATION = Key("quantity", "time", "positive")
#: segment kind -> its options (controls come on top, except for hold and repeat)
SEGMENTS: dict[str, dict[str, Key]] = {
    "ramp": {"steps": _steps("ramp"), "duration": _DURATION},
    "hold": {"steps": _steps("hold"), "duration": _DURATION},
    "sinusoid": {"cycles": Key("quantity", "dimensionless", "positive",
                               required="required for a sinusoid segment"),
                 "steps_per_cycle": _steps("sinusoid", low=4, required=False),
                 "period": _DURATION},
    "table": {"file": Key("file"), "time": Key("array", "time")},
    "repeat": {"times": _steps("repeat"), "last": _steps("repeat", required=False)},
}

# ---- fretting: [wear] and [fretting_map] --------------------------------------------------------
#: most cycles of a scene's wear run, and most checkpoints
MAX_WEAR_CYCLES = 1e12
MAX_CHECKPOINTS = 1000
#: keys of a [wear] table
WEAR_KEYS: dict[str, Key] = {
    "wear_coefficient": Key("quantity", "wear_coefficient", "nonnegative",
                            required="Archard's coefficient k = K/H, e.g. '1e-6 mm^3/(N*m)' or "
                                     "'1e-15 1/Pa' (required)"),
    "cycles": Key("quantity", "dimensionless", "positive", high=MAX_WEAR_CYCLES,
                  high_allowed=f"at most {MAX_WEAR_CYCLES:g} cycles",
                  required="the number of fretting cycles, e.g. 1e6 (required)"),
    "checkpoints": Key("checkpoints"),
    "method": Key("choice", choices=("exact", "mdr")),
    "n_grid": Key("integer", low=16, high=20_000),
    "jump_rtol": Key("quantity", "dimensionless", "positive", high=0.1, high_open=True,
                     high_allowed="0 < jump_rtol < 0.1"),
    "max_radius": Key("quantity", "length", "positive"),
    "integrator": Key("choice", choices=INTEGRATORS),
}
#: torsional gross-slip criteria of a fretting map (docs/fretting.md, section 2)
CRITERIA = ("energy_ratio", "stick_ratio", "torque_ratio")
#: most points of a scene's fretting map (force x amplitude)
MAX_MAP_POINTS = 250_000
#: keys of a [fretting_map] table; the axes are lists or range tables (AXIS_KEYS)
FRETTING_MAP_TABLE: dict[str, Key] = {
    "force": Key("axis", "force", "positive",
                 required="the normal forces, a list ['10 N', '100 N'] or a range { from = "
                          "'10 N', to = '1 kN', points = 8, spacing = 'log' } (required)"),
    "twist_amplitude": Key("axis", "angle", "nonnegative"),
    "displacement_amplitude": Key("axis", "length", "nonnegative"),
    "method": Key("choice", choices=("exact", "mdr")),
    "criterion": Key("choice", choices=CRITERIA),
    "threshold": Key("quantity", "dimensionless", "positive", high=1.0, high_open=True,
                     high_allowed="0 < threshold < 1"),
}
FRETTING_MAP_KEYS = tuple(FRETTING_MAP_TABLE)
#: keys of a map axis given as a range table
AXIS_KEYS = {"from": Key("quantity"), "to": Key("quantity"),
             "points": Key("integer", low=1, high=10_000),
             "spacing": Key("choice", choices=("linear", "log"))}
