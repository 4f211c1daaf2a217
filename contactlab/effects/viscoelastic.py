"""Viscoelastic normal contact histories: the driver behind :meth:`Contact.viscoelastic_history`
and its result :class:`ViscoelasticHistory`.

The time stepping is that of the MDR viscoelastic foundation,
:class:`contactlab.foundation.viscoelastic.ViscoelasticElements` (theory §7).
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..citations import Cited, sources_for
from ..errors import ConvergenceError, NotSupportedError, ParameterError
from ..foundation import viscoelastic as _ve
from ..foundation.base import DEFAULT_N_SPRINGS    # elements over the largest contact radius
from ..materials import Elastic, Rigid, effective_moduli
from ..materials.pair import viscoelastic_body
from ..params import FieldsEqual, as_float_array, check_count, check_memory, exactly_one
from ..physics.normal import radius_depth_of_force
from ._protocol import Result, reporting

__all__ = ["ViscoelasticHistory", "viscoelastic_history", "DEFAULT_N_SPRINGS", "history_memory",
           "HISTORY_UNITS"]

#: units of the columns of a viscoelastic history (CSV headers)
HISTORY_UNITS = {"time": "s", "depth": "m", "force": "N", "radius": "m"}



def history_memory(n_steps: int, n_springs: int, n_terms: int) -> float:
    """Estimated peak memory of :func:`viscoelastic_history`, bytes (float64 values: 16 per
    step, ``8 (n_terms + 4)`` per spring for the element states and their trial copies)."""
    return 8.0 * (16.0 * n_steps + 8.0 * (n_terms + 4) * float(n_springs))


@dataclass(frozen=True, eq=False)
class ViscoelasticHistory(FieldsEqual, Result, Cited):
    """Per-step result of a viscoelastic normal-contact history.

    Attributes
    ----------
    time : ndarray
        Times, s.
    depth : ndarray
        Indentation depth, m (under force control, the solved depth; after release, the depth at
        which the indenter just touches the surface).
    force : ndarray
        Normal force, N (never tensile: no adhesion).
    radius : ndarray
        Contact radius, m, interpolated inside the outermost element's cell (growth front:
        ``d = g(a)``; shrinking contact: zero element force).
    meta : dict
        ``control``, ``n_springs``, ``spacing`` (m), ``material``, ``foundation_radius`` (m).
    model_error : float
        0.0: the MDR rules of viscoelastic contact are exact [H3]; the discretisation in space
        and time is numerical error.
    """

    time: np.ndarray
    depth: np.ndarray
    force: np.ndarray
    radius: np.ndarray
    meta: dict = field(default_factory=dict)

    units = HISTORY_UNITS

    def to_dict(self) -> dict[str, np.ndarray]:
        """Per-step arrays (``time``, ``depth``, ``force``, ``radius``)."""
        return {"time": self.time, "depth": self.depth, "force": self.force,
                "radius": self.radius}

    def plot(self, axes: Any = None, *, units: str = "si"):
        """Force against depth and the contact radius against time (needs matplotlib); returns
        the two axes. ``units="engineering"`` labels µm and mN (see :mod:`contactlab.plotting`)."""
        from .. import plotting as pl
        pl.check_units(units)
        pl.pyplot()
        with pl.style():
            if axes is None:
                fig, axes = pl.subplots(1, 2, figsize=(9.0, 3.6))
                fig.suptitle("viscoelastic history")
            ax1, ax2 = axes
            ax1.plot(pl.scaled(self.depth, "m", units), pl.scaled(self.force, "N", units))
            ax1.set_xlabel(pl.axis_label("depth", "m", units))
            ax1.set_ylabel(pl.axis_label("force", "N", units))
            ax2.plot(self.time, pl.scaled(self.radius, "m", units))
            ax2.set_xlabel("time [s]")
            ax2.set_ylabel(pl.axis_label("contact radius", "m", units))
            ax2.set_ylim(bottom=0.0)
        return axes


@reporting()
def viscoelastic_history(contact, *, time: Any, depth: Any = None, force: Any = None,
                         n_springs: int | None = None, max_radius: float | None = None
                         ) -> ViscoelasticHistory:
    """Normal contact of a rigid indenter on a viscoelastic half-space under a load history.

    Parameters
    ----------
    contact : Contact
        ``materials = (viscoelastic, Rigid())`` (either order); no adhesion.
    time : array_like
        Non-decreasing times, s (1D). The first state is reached from the virgin, unloaded
        half-space by a jump (glassy response); repeated times are jumps.
    depth, force : array_like, exactly one
        Prescribed indentation depth (m) or normal force (N), same length as ``time``.
    n_springs : int, optional
        Number of foundation elements (default 2000) over the foundation radius.
    max_radius : float, optional
        Foundation radius, m. Default: the geometric radius at the largest depth (depth
        control) or the elastic radius at the largest force with the relaxed-at-the-end modulus
        ``G(t_end)`` (force control; an upper bound since ``J(t) G(t) <= 1``), plus 10 %.

    Returns
    -------
    ViscoelasticHistory

    Raises
    ------
    NotSupportedError
        Materials other than (viscoelastic, rigid), or adhesion.
    ConvergenceError
        The contact reached the edge of the foundation (give a larger ``max_radius``).
    """
    m1, m2 = contact.materials
    mat = viscoelastic_body(m1, m2)
    if contact.is_adhesive:
        raise NotSupportedError("work_of_adhesion > 0 with a viscoelastic material is not covered "
                                "by theory §7 (adhesion-free unloading only).")
    key, value = exactly_one("viscoelastic_history()", {"depth": depth, "force": force})
    t = as_float_array("time", time)
    load = as_float_array(key, value)
    if t.ndim != 1 or t.size == 0:
        raise ParameterError(f"time must be a non-empty 1D array; got shape {t.shape}.")
    if load.shape != t.shape:
        raise ParameterError(f"{key} has shape {load.shape} but time has shape {t.shape}: give one "
                             "value per time.")
    if np.any(np.diff(t) < 0):
        i = int(np.argmax(np.diff(t) < 0)) + 1
        raise ParameterError(f"time[{i}]={t[i]!r} s is invalid: times must be non-decreasing.")
    n_springs = DEFAULT_N_SPRINGS if n_springs is None else check_count("n_springs", n_springs, 2)
    prof = contact.profile
    G_inf, Gk, tk, eta = mat.prony()
    check_memory("viscoelastic_history()", history_memory(t.size, n_springs, Gk.size),
                 f"{t.size} steps, {n_springs} springs, {Gk.size} Prony terms")
    if max_radius is None:
        if key == "depth":
            d_max = float(np.max(load))
            a_max = float(prof._radius_of_depth(np.array(d_max))) if d_max > 0 else 0.0
        else:
            F_max = float(np.max(load))
            G_end = float(mat.relaxation(t[-1] - t[0])) if (G_inf > 0 or Gk.size) else 0.0
            if G_end <= 0:
                G_end = G_inf
            # the elastic radius with the relaxed modulus (incompressible: E = 3G)
            E_end = effective_moduli(Elastic(E=3.0 * G_end, nu=0.5), Rigid()).normal
            a_end, _ = radius_depth_of_force(prof, E_end, np.array(max(F_max, 0.0)), contact.rtol)
            a_max = float(a_end)
        if a_max <= 0:
            a_max = 1.0 if not np.isfinite(prof.max_radius) else 0.5 * prof.max_radius
        L = 1.1 * a_max
    else:
        L = float(as_float_array("max_radius", max_radius))
        if not L > 0:
            raise ParameterError(f"max_radius={max_radius!r} is invalid: it must be > 0 m.")
    L = min(L, prof.wall_radius, prof.max_radius * (1 - 1e-12))
    dx = L / n_springs
    x = (np.arange(n_springs) + 0.5) * dx
    g_x = prof._g(x)
    scale = float(prof._g(np.array(L))) if np.isfinite(prof._g(np.array(L))) else L * 1e-3
    res = _ve.solve_history(g_x, dx, (G_inf, Gk, tk, eta), t,
                            depth=load if key == "depth" else None,
                            force=load if key == "force" else None,
                            depth_scale=max(scale * 1e-3, 1e-300))
    if np.any(res["edge_reached"]) and not np.isfinite(prof.wall_radius):
        i = int(np.argmax(res["edge_reached"]))
        raise ConvergenceError(
            f"the contact reached the edge of the foundation (radius {L:.6g} m) at step {i}: "
            "pass a larger max_radius=.")
    meta = {"control": key, "n_springs": n_springs, "spacing": dx, "material": mat,
            "foundation_radius": L, "citations": sources_for("mdr", "viscoelastic")}
    return ViscoelasticHistory(t, res["depth"], res["force"], res["radius"], meta)
