"""What ``contactlab list`` prints: registered profiles and materials, and the effects.

Profiles and materials come from the registry (built-ins and installed plugins alike), with each
parameter's name, unit and meaning from its :class:`~contactlab.params.Param`. Effects are the
:class:`~contactlab.Contact` methods with their inputs (SI units), models and scene outputs.
"""
from __future__ import annotations

from typing import Any

from ..loadpath.base import UNITS
from ..registry import registry
from .validate import EFFECTS, METHODS, SERIES

__all__ = ["EFFECT_TABLE", "catalog", "catalog_text"]

#: effect -> (Contact methods, inputs with SI units, models / notes)
EFFECT_TABLE: dict[str, tuple[str, str, str]] = {
    "normal": ("normal", "depth [m] | force [N] | radius [m]",
               "exact (MDR = Sneddon's solution); any profile"),
    "adhesion": ("normal, pull_off, adhesion_cycle",
                 "Contact(work_of_adhesion [J/m^2]); depth [m] | force [N]",
                 "JKR through the MDR (Heß rule), any profile"),
    "viscoelastic": ("viscoelastic_history", "time [s]; depth [m] | force [N]",
                     "MDR rheological elements; rigid indenter on a viscoelastic body"),
    "tangential": ("tangential, shift_history",
                   "force [N] | depth [m]; displacement [m] | tangential_force [N]",
                   "Cattaneo-Mindlin, exact; Masing histories"),
    "torsion": ("torsion, twist_history",
                "force [N] | depth [m]; twist [rad] | torque [N*m] | stick_radius [m]",
                f"method = {' | '.join(METHODS)}"),
    "slip": ("shift_history, twist_history, simulate", "histories of shift or twist",
             "dissipated energy [J] of frictional slip"),
    "path": ("simulate", "LoadPath (ramp, hold, sinusoid, table)",
             "MDR foundation with frictional memory; varying normal load allowed"),
    "fretting": ("fretting_loop, fretting_map",
                 "force [N]; displacement_amplitude [m] | twist_amplitude [rad]",
                 "steady loops, energy ratio, regimes"),
}


def _params(cls: Any) -> list[dict[str, str]]:
    return [{"name": p.name, "unit": p.unit, "description": p.description}
            for p in getattr(cls, "params", ())]


def catalog() -> dict[str, Any]:
    """Everything ``contactlab list`` shows, as plain data (``--json``)."""
    out: dict[str, Any] = {}
    for kind in ("profile", "material"):
        src = registry.sources(kind)
        out[kind + "s"] = [{"name": n, "class": registry.get(kind, n).__name__,
                            "source": src.get(n, "contactlab"),
                            "params": _params(registry.get(kind, n))}
                           for n in registry.available(kind)]
    out["effects"] = [{"name": e, "methods": m, "inputs": i, "models": mod,
                       "outputs": [f"{k} [{_unit(k)}]" for k, v in SERIES.items() if v == e]}
                      for e, (m, i, mod) in EFFECT_TABLE.items()]
    out["scene_effects"] = list(EFFECTS)
    return out


def _unit(series: str) -> str:
    from .run import SERIES_UNITS
    return SERIES_UNITS.get(series, UNITS.get(series, "1"))


def catalog_text(what: str = "all") -> str:
    """Human-readable tables; ``what`` is ``"profiles"``, ``"materials"``, ``"effects"`` or
    ``"all"``."""
    data = catalog()
    lines: list[str] = []
    for kind in ("profiles", "materials"):
        if what not in ("all", kind):
            continue
        lines.append(f"{kind} (registered; a scene's type = NAME, registry.create(kind, NAME)):")
        for row in data[kind]:
            ps = "; ".join(f"{p['name']} [{p['unit']}] {p['description']}" for p in row["params"])
            src = "" if row["source"] in ("contactlab", "built-in") else f"  (from {row['source']})"
            lines.append(f"  {row['name']:<22} {row['class']:<22} {ps or '(no parameters)'}{src}")
        lines.append("")
    if what in ("all", "effects"):
        lines.append("effects (Contact methods; inputs in SI units):")
        for row in data["effects"]:
            lines.append(f"  {row['name']:<13} contact.{row['methods'].replace(', ', ', contact.')}")
            lines.append(f"  {'':<13} inputs: {row['inputs']}")
            lines.append(f"  {'':<13} {row['models']}")
            if row["outputs"]:
                lines.append(f"  {'':<13} scene series: {', '.join(row['outputs'])}")
        lines.append("")
    return "\n".join(lines).rstrip() + "\n"
