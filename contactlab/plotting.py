"""One plot style for every figure contactlab draws (extra ``plot``: matplotlib, imported lazily).

Every ``.plot()`` of the library (:class:`~contactlab.PathResult`,
:class:`~contactlab.TwistHistory`, :class:`~contactlab.ShiftHistory`, the fretting loop and map, the
wear run, the cost report, scene results and the demo) draws through this module, so they share:

- one style (:data:`STYLE`: font sizes, grid, line widths), applied with :func:`style`;
- constrained layout, so titles, labels and legends stay inside the figure;
- at most :data:`MAX_TICKS` ticks per axis of a hysteresis loop, with the axis offset
  (``1e-6``) folded into the unit, so tick labels do not run into each other;
- ``units="si"`` (default: m, N, N·m, Pa, rad, J) or ``units="engineering"`` (µm, N, mN·m,
  MPa, mrad, µJ, µm³): only the axis numbers and labels change, never the result.

Examples
--------
>>> from contactlab.plotting import axis_label, scaled
>>> axis_label("torque", "N*m", "engineering")
'torque [mN·m]'
>>> float(scaled(2e-6, "m", "engineering"))
2.0
"""
from __future__ import annotations

import contextlib
from collections.abc import Iterator
from typing import Any

import numpy as np

from .errors import ParameterError

__all__ = ["STYLE", "UNIT_SYSTEMS", "MAX_TICKS", "pyplot", "style", "subplots", "axis_label",
           "scaled", "check_units", "loop_axes", "save", "history"]

#: unit systems accepted by every ``plot(units=...)``
UNIT_SYSTEMS = ("si", "engineering")

#: SI unit -> (label, factor) per unit system; a value in SI times the factor is the plotted number
_UNITS: dict[str, dict[str, tuple[str, float]]] = {
    "m": {"si": ("m", 1.0), "engineering": ("µm", 1e6)},
    "N": {"si": ("N", 1.0), "engineering": ("N", 1.0)},
    "N*m": {"si": ("N·m", 1.0), "engineering": ("mN·m", 1e3)},
    "Pa": {"si": ("Pa", 1.0), "engineering": ("MPa", 1e-6)},
    "rad": {"si": ("rad", 1.0), "engineering": ("mrad", 1e3)},
    "J": {"si": ("J", 1.0), "engineering": ("µJ", 1e6)},
    "m^3": {"si": ("m³", 1.0), "engineering": ("µm³", 1e18)},
    "N/m": {"si": ("N/m", 1.0), "engineering": ("N/µm", 1e-6)},
    "s": {"si": ("s", 1.0), "engineering": ("s", 1.0)},
    "1": {"si": ("", 1.0), "engineering": ("", 1.0)},
}

#: the shared matplotlib settings (``matplotlib.rcParams`` keys)
STYLE: dict[str, Any] = {
    "figure.dpi": 100,
    "savefig.dpi": 150,
    "font.size": 9.0,
    "axes.titlesize": 10.0,
    "axes.labelsize": 9.0,
    "xtick.labelsize": 8.0,
    "ytick.labelsize": 8.0,
    "legend.fontsize": 8.0,
    "legend.frameon": False,
    "lines.linewidth": 1.5,
    "axes.grid": True,
    "grid.alpha": 0.3,
    "grid.linewidth": 0.6,
    "axes.spines.top": False,
    "axes.spines.right": False,
    "axes.formatter.useoffset": False,
    "axes.formatter.limits": (-3, 4),
    "axes.formatter.use_mathtext": True,
}

#: most ticks on an axis of a loop plot (torque–twist, force–displacement)
MAX_TICKS = 5


def pyplot():
    """``matplotlib.pyplot``, or ImportError with the install hint (extra ``plot``)."""
    try:
        import matplotlib.pyplot as plt
    except ImportError as err:
        raise ImportError("plot() needs matplotlib: pip install matplotlib "
                          "(or pip install 'contactlab[plot]')") from err
    return plt


@contextlib.contextmanager
def style() -> Iterator[None]:
    """Context in which figures and artists get the shared :data:`STYLE`."""
    plt = pyplot()
    with plt.rc_context(STYLE):
        yield


def check_units(units: str) -> str:
    """Return ``units`` if it names a unit system, else raise :class:`ParameterError`."""
    if units not in UNIT_SYSTEMS:
        raise ParameterError(f"units={units!r} is invalid: give one of {list(UNIT_SYSTEMS)} "
                             "('engineering' plots µm, mN·m, MPa, mrad, µJ).")
    return units


def scaled(values: Any, si_unit: str, units: str = "si") -> np.ndarray:
    """``values`` (in ``si_unit``) converted to the plotted unit of ``units``."""
    factor = _UNITS.get(si_unit, {}).get(check_units(units), (si_unit, 1.0))[1]
    return np.asarray(values, dtype=float) * factor


def axis_label(name: str, si_unit: str, units: str = "si") -> str:
    """``"name [unit]"`` in the unit system ``units`` (no brackets for dimensionless)."""
    unit = _UNITS.get(si_unit, {}).get(check_units(units), (si_unit, 1.0))[0]
    return f"{name} [{unit}]" if unit else name


def subplots(nrows: int = 1, ncols: int = 1, *, figsize: tuple[float, float] | None = None,
             **kw: Any):
    """A styled figure with constrained layout (``plt.subplots`` arguments otherwise)."""
    plt = pyplot()
    with style():
        return plt.subplots(nrows, ncols, figsize=figsize, layout="constrained", **kw)


def loop_axes(ax: Any) -> Any:
    """Format ``ax`` for a hysteresis loop: at most :data:`MAX_TICKS` ticks per axis, symmetric
    about zero, no offset text; returns ``ax``."""
    from matplotlib.ticker import MaxNLocator
    for axis in (ax.xaxis, ax.yaxis):
        axis.set_major_locator(MaxNLocator(nbins=MAX_TICKS - 1, symmetric=True, prune=None))
    ax.axhline(0.0, color="0.6", lw=0.6, zorder=0)
    ax.axvline(0.0, color="0.6", lw=0.6, zorder=0)
    return ax


def save(fig: Any, path: Any, **kw: Any) -> None:
    """Save ``fig`` to ``path`` (format from the suffix) with the shared dpi."""
    with style():
        fig.savefig(path, **kw)


def history(x: Any, y: Any, stick_radius: Any, *, x_name: str, x_unit: str, y_name: str,
            y_unit: str, units: str = "si", axes: Any = None, title: str = "") -> Any:
    """Two panels of a history at constant normal load: the loop ``y(x)`` and the stick radius
    per step (the plot of :meth:`contactlab.TwistHistory.plot` and
    :meth:`contactlab.ShiftHistory.plot`); returns the two axes."""
    check_units(units)
    pyplot()
    with style():
        if axes is None:
            fig, axes = subplots(1, 2, figsize=(9.0, 3.6))
            if title:
                fig.suptitle(title)
        ax1, ax2 = axes
        ax1.plot(scaled(x, x_unit, units), scaled(y, y_unit, units))
        ax1.set_xlabel(axis_label(x_name, x_unit, units))
        ax1.set_ylabel(axis_label(y_name, y_unit, units))
        loop_axes(ax1)
        steps = np.arange(np.size(stick_radius))
        ax2.plot(steps, scaled(stick_radius, "m", units))
        ax2.set_xlabel("step")
        ax2.set_ylabel(axis_label("stick radius", "m", units))
        ax2.set_ylim(bottom=0.0)
    return axes
