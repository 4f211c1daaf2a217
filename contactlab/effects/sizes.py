"""Peak memory of the array solves and the field methods of the states, checked against the
memory budget (:func:`contactlab.params.check_memory`) before anything of their size is made.

Each estimate is the number of elements the call computes (the broadcast size of its inputs, or
``state.size x r.size`` for a field) times bytes per element measured with :mod:`tracemalloc`
(numpy's allocations are traced) on the paraboloid, the cone, the sphere and linear and cubic
tables at 10^3-10^6 elements, rounded up to cover the largest. ``"closed"`` profiles have a
closed-form pressure shape (paraboloids, cones, power laws, flat punches); every other profile
(spheres, tables, sums, truncated profiles) goes by ``"numeric"`` quadratures or table rules.
"""
from __future__ import annotations

import math
from typing import Any

from ..params import check_memory
from ..profiles import PowerLaw

__all__ = ["NORMAL_BYTES_PER_LOAD", "ADHESIVE_NORMAL_BYTES_PER_LOAD", "FIELD_BYTES_PER_POINT",
           "PEAK_BYTES_PER_RADIUS", "PEAK_RADII", "TANGENTIAL_BYTES_PER_LOAD", "TORSION_BYTES_PER_LOAD",
           "TORSION_FIELD_BYTES_PER_POINT", "TORSION_LIGHT_BYTES_PER_LOAD",
           "torsion_bytes_per_load", "route_kind", "check_elements", "check_field",
           "check_peak"]

#: normal solve on arrays (depth, force or radius), bytes per load: measured 24-52 B on the
#: closed-form routes (paraboloid, cone; steady state from 10^5 loads on), 65-104 B on the
#: sphere, 90-391 B on linear and cubic tables (10^3-10^5 loads)
NORMAL_BYTES_PER_LOAD = {"closed": 64, "numeric": 512}
#: adhesive (JKR) normal solve on arrays, bytes per load: measured by depth and force 323-355 B
#: on the paraboloid, cone, sphere and linear and cubic tables at 10^4-10^5 loads (up to 655 B
#: at 10^3, the tables' fixed part), by radius 65-150 B (570 B on a cubic table at 10^3)
ADHESIVE_NORMAL_BYTES_PER_LOAD = 1024
#: ``NormalState.pressure`` / ``displacement`` and ``TangentialState.shear``, bytes per point of
#: ``state.shape + r.shape``: measured closed 42 B (pressure), 71-91 B (displacement), 133 B
#: (shear); numeric: sphere 1503 / 762 / 1594 B, tables 672 / 80-1480 / 763 B, and up to 3.8 KB
#: per point at 10^4 points where a table's first pressure builds its segment rules
FIELD_BYTES_PER_POINT = {"closed": 256, "numeric": 4096}
#: :attr:`NormalState.peak_pressure`: radii sampled per state
PEAK_RADII = 1024
#: ... and bytes per sampled radius: measured closed 50 B (paraboloid; cone 77-229 B per
#: state in all, its axis decides), numeric: sphere 2185 B, linear table 13-31 B, cubic table
#: 122 B (its coarse and fine passes)
PEAK_BYTES_PER_RADIUS = {"closed": 128, "numeric": 4096}
#: tangential solve on arrays, bytes per element of the broadcast of the normal load and the
#: tangential input (the normal solve, the broadcast states, the stick radii and the force):
#: measured 185-1065 B over the five profiles (displacement and force control, equal and
#: broadcast shapes, 10^3-10^4 elements)
TANGENTIAL_BYTES_PER_LOAD = 2048
#: torsion solve on arrays, bytes per element of the broadcast of the normal load and the
#: twist input, by method: measured exact 2.0-3.2 KB (paraboloid), 11 KB (cone, sphere, power
#: law n = 3), 14.2 KB (linear table); mdr 0.21 KB (paraboloid, cone), 0.83 KB (power law
#: n = 3), 1.7 KB (sphere), 7.9 KB (linear table); no-slip 147-307 B (10^3-10^5 states)
TORSION_BYTES_PER_LOAD = {"exact": 32 * 1024, "mdr": 16 * 1024, "no-slip": 512}
#: ... the same where the route is lighter: the exact model of a paraboloid (its closed forms,
#: ``"hertz"``: 2.0-2.3 KB a state at 10^4-10^5 states) and the MDR model of a profile with a
#: closed-form pressure shape (``"closed"``: 0.2-0.83 KB)
TORSION_LIGHT_BYTES_PER_LOAD = {"exact": 4 * 1024, "mdr": 1024}
#: ``TorsionState.shear`` / ``displacement``, bytes per point of ``state.shape + r.shape``, by
#: method: measured exact 82 KB / 41 KB (paraboloid, sphere; the stick zone's nested
#: quadratures), 30 KB / 93 KB (cone); mdr 0.6-1.7 KB / 0.6-1.3 KB; no-slip 83-101 B / 78-106 B
#: (10 states x 300-3000 radii)
TORSION_FIELD_BYTES_PER_POINT = {"exact": 128 * 1024, "mdr": 16 * 1024, "no-slip": 256}


def route_kind(profile: Any) -> str:
    """``"closed"`` for a profile with a closed-form pressure shape, else ``"numeric"``."""
    return "closed" if profile._has("_pressure_shape_closed_form") else "numeric"


def torsion_bytes_per_load(method: str, profile: Any) -> int:
    """Bytes per state of a torsion solve with ``method`` on ``profile``: the light routes'
    (:data:`TORSION_LIGHT_BYTES_PER_LOAD`: the exact paraboloid, the MDR model of a closed-form
    profile) or the method's bound (:data:`TORSION_BYTES_PER_LOAD`)."""
    if method == "exact" and isinstance(profile, PowerLaw) and float(profile.n) == 2.0:
        return TORSION_LIGHT_BYTES_PER_LOAD["exact"]
    if method == "mdr" and route_kind(profile) == "closed":
        return TORSION_LIGHT_BYTES_PER_LOAD["mdr"]
    return TORSION_BYTES_PER_LOAD[method]


def check_elements(what: str, n: float, per: float, detail: str) -> None:
    """:func:`~contactlab.params.check_memory` of ``n`` elements of ``per`` bytes each.

    Parameters
    ----------
    what : str
        The request (``"normal()"``).
    n : float
        Number of elements the call computes.
    per : float
        Bytes per element (one of this module's measured constants).
    detail : str
        What the elements are (``"force (1000,)"``), for the message.
    """
    check_memory(what, float(n) * per, f"{detail}: {int(n)} values x {per:g} B")


def check_field(what: str, state_shape: tuple[int, ...], r_shape: tuple[int, ...],
                per: float) -> None:
    """Check a field method's ``state_shape + r_shape`` points of ``per`` bytes each."""
    check_elements(what, math.prod(state_shape) * math.prod(r_shape), per,
                   f"state {state_shape} x r {r_shape}")


def check_peak(state: Any) -> None:
    """Check the memory of a normal state's ``peak_pressure``: :data:`PEAK_RADII` radii per
    state, at :data:`PEAK_BYTES_PER_RADIUS` of its profile's route."""
    n = math.prod(state.shape)
    check_elements("peak_pressure", n * PEAK_RADII,
                   PEAK_BYTES_PER_RADIUS[route_kind(state.contact.profile)],
                   f"{n} states x {PEAK_RADII} radii")
