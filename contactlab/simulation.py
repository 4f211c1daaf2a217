"""``contact.simulate(path)``: a load path through the MDR foundation with frictional memory.

The normal problem (non-adhesive) is path independent: it is solved first for every step,
vectorised per segment, with the exact closed-form/bracketed normal solver of the contact. Then one
loop over time steps advances the tangential and torsional Jenkins elements of the
:class:`~contactlab.foundation.Winkler` foundation; every operation inside it is vectorised over
the springs. Displacement/twist-controlled steps are explicit; force/torque-controlled steps are
solved exactly (the element sum is piecewise linear and monotone in the increment); a target at or
beyond full sliding gives gross sliding (flagged, not an error).
"""
from __future__ import annotations

import warnings
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from .errors import (EffectNotPlannedError, NotSupportedError, OutsideTheoryError,
                     ParameterError, UnknownNameError, ValidityWarning)
from .foundation import Winkler
from .loadpath import LoadPath
from .loadpath.base import UNITS

__all__ = ["PathResult", "simulate", "SERIES", "PROGRESS_THRESHOLD"]

#: per-step series of a PathResult
SERIES = ("time", "depth", "force", "radius", "displacement", "tangential_force", "twist",
          "torque", "stick_radius", "dissipated_energy", "gross_sliding")
_SERIES_UNITS = dict(UNITS, radius="m", stick_radius="m", dissipated_energy="J",
                     gross_sliding="1")
#: paths with at least this many steps show a progress bar when ``progress=True``
PROGRESS_THRESHOLD = 1000


def _contact_for(profile, moduli, friction, rtol):
    """A Contact built from effective moduli (for Foundation.for_path)."""
    from .contact import Contact
    c = Contact.__new__(Contact)
    c.profile = profile
    c.materials = (None, None)
    c.friction = friction
    c.work_of_adhesion = None
    c.rtol = rtol
    c.__dict__["moduli"] = moduli
    return c


def families_needed(path: LoadPath, *, approximate: bool = False) -> tuple[str, ...]:
    """Spring families a path needs besides the normal springs.

    Raises
    ------
    OutsideTheoryError
        The path drives both a tangential shift and a twist, without ``approximate=True``.
    """
    groups = path.groups
    needs = tuple(g for g in ("tangential", "torsion") if g in groups)
    if len(needs) == 2 and not approximate:
        raise OutsideTheoryError(
            "the path drives both a tangential shift (displacement/tangential_force) and a twist "
            "(twist/torque): combined shift and twist is outside the MDR theory (the slip "
            "conditions couple). Pass approximate=True to run the two as independent spring "
            "families, each with the full friction limit (an explicit approximation).")
    return needs


def compile_normal(contact, path: LoadPath) -> list[dict[str, np.ndarray]]:
    """Normal state of every step, per leaf segment (exact; non-adhesive normal contact is path
    independent)."""
    out = []
    cur = dict.fromkeys(("depth", "force", "displacement", "tangential_force", "twist",
                         "torque"), 0.0)
    last = (np.zeros(1), np.zeros(1), np.zeros(1))
    for leaf in path.leaves():
        dt, vals = leaf.values(cur)
        n = leaf.n_steps
        if "depth" in vals:
            ns = contact.normal(depth=vals["depth"])
            d, a, F = ns._depth, ns._radius, ns._force
        elif "force" in vals:
            f = vals["force"]
            if np.any(f < 0):
                bad = f[f < 0][0]
                raise ParameterError(f"force={bad!r} N is invalid: it is below the adhesion limit "
                                     "0 N of this non-adhesive contact (use force >= 0, or a "
                                     "negative depth to separate the bodies).")
            ns = contact.normal(force=f)
            d, a, F = ns._depth, ns._radius, ns._force
        else:
            d, a, F = (np.full(n, v[-1]) for v in last)
        d, a, F = (np.asarray(v, float).reshape(n) for v in (d, a, F))
        out.append({"dt": dt, "depth": d, "radius": a, "force": F})
        last = (d, a, F)
        cur["depth"], cur["force"] = float(d[-1]), float(F[-1])
    return out


@dataclass(frozen=True, eq=False)
class PathResult:
    """Per-step result of :meth:`Contact.simulate`.

    Attributes
    ----------
    time, depth, force, radius, displacement, tangential_force, twist, torque, stick_radius,
    dissipated_energy : ndarray
        Per-step series in SI units (s, m, N, m, m, N, rad, N·m, m, J). ``stick_radius`` is the
        outer radius of the central stick zone of the tangential springs (of the torsional
        springs for a path without shift); ``dissipated_energy`` is cumulative.
    gross_sliding : ndarray of bool
        Steps where a force/torque target reached full sliding.
    snapshots : dict
        ``{step: {"x", "depth", "radius", "normal", "tangential", "torsion", "pressure"}}``
        spring states (per cell) and the pressure at the cell midpoints, at requested steps.
    meta : dict
        ``built`` (spring families built), ``n_springs``, ``spacing``, ``foundation``, ``approximate``.
    """

    data: dict
    snapshots: dict = field(default_factory=dict)
    meta: dict = field(default_factory=dict)

    def __getattr__(self, name: str) -> Any:
        if name in SERIES:
            data = object.__getattribute__(self, "data")
            if name not in data:
                raise EffectNotPlannedError(f"{name!r} was not requested: add it to outputs= "
                                            f"(requested: {sorted(data)}).")
            return data[name]
        raise AttributeError(name)

    def __len__(self) -> int:
        return int(next(iter(self.data.values())).size)

    def to_dict(self) -> dict[str, np.ndarray]:
        """Copies of the per-step series, keyed by name."""
        return {k: np.array(v) for k, v in self.data.items()}

    def to_csv(self, path: Any) -> None:
        """Write the per-step series to CSV (``name [unit]`` headers)."""
        from .loadpath.io import write_csv
        write_csv(path, self.data, units=_SERIES_UNITS)

    def to_dataframe(self):
        """The per-step series as a :class:`pandas.DataFrame` (needs pandas)."""
        try:
            import pandas as pd
        except ImportError as err:
            raise ImportError("to_dataframe() needs pandas: pip install pandas") from err
        return pd.DataFrame(self.to_dict())

    def plot(self, quantities: Any = None, *, x: str = "time", ax: Any = None):
        """Plot series against ``x`` (needs matplotlib); returns the axes.

        ``quantities`` defaults to every driven series (force, tangential force, torque).
        """
        try:
            import matplotlib.pyplot as plt
        except ImportError as err:
            raise ImportError("plot() needs matplotlib: pip install matplotlib "
                              "(or pip install 'contactlab[plot]')") from err
        if quantities is None:
            quantities = [q for q in ("force", "tangential_force", "torque") if q in self.data
                          and np.any(self.data[q] != 0)] or ["force"]
        quantities = [quantities] if isinstance(quantities, str) else list(quantities)
        if ax is None:
            fig, axes = plt.subplots(len(quantities), 1, squeeze=False, sharex=True)
            axes = axes[:, 0]
        else:
            axes = np.atleast_1d(ax)
        for q, a in zip(quantities, axes):
            a.plot(getattr(self, x), getattr(self, q))
            a.set_ylabel(f"{q} [{_SERIES_UNITS.get(q, '')}]")
        axes[-1].set_xlabel(f"{x} [{_SERIES_UNITS.get(x, '')}]")
        return axes


def _progress(total: int, progress: bool):
    if not progress or total < PROGRESS_THRESHOLD:
        return None
    try:
        from tqdm import tqdm
    except ImportError as err:
        raise ImportError("progress=True needs tqdm: pip install tqdm "
                          "(or pip install 'contactlab[progress]')") from err
    return tqdm(total=total, unit="step", desc="simulate")


def simulate(contact, path: LoadPath, *, outputs: Any = None, n_springs: int | None = None,
             spacing: str = "edge", snapshots: Any = None, progress: bool = False,
             approximate: bool = False) -> PathResult:
    """Run ``path`` through the MDR foundation of ``contact``.

    Parameters
    ----------
    contact : Contact
        Non-adhesive; ``friction=None`` means no slip.
    path : LoadPath
    outputs : iterable of str, optional
        Per-step series to keep (default all of :data:`SERIES`).
    n_springs : int, optional
        Cells over the path's largest contact radius (default
        :data:`~contactlab.foundation.DEFAULT_N_SPRINGS`).
    spacing : {"edge", "uniform"}
        Cell spacing (edge-refined by default).
    snapshots : iterable of int, optional
        Steps (0-based; negative counts from the end) at which spring states are stored.
    progress : bool
        Show a tqdm progress bar for paths of at least :data:`PROGRESS_THRESHOLD` steps
        (library use is quiet by default).
    approximate : bool
        Allow combined shift and twist, run as independent spring families (warns).

    Returns
    -------
    PathResult

    Raises
    ------
    OutsideTheoryError
        Combined shift and twist without ``approximate=True``.
    NotSupportedError
        Adhesive contacts.
    """
    if not isinstance(path, LoadPath):
        raise ParameterError(f"path={path!r} is invalid: expected a contactlab.LoadPath.")
    if contact.is_adhesive:
        raise NotSupportedError("simulate() supports non-adhesive contacts only "
                                "(work_of_adhesion=None).")
    needs = families_needed(path, approximate=approximate)
    if len(needs) == 2:
        warnings.warn("combined shift and twist is run as two independent spring families "
                      "(approximate=True): outside the MDR theory, the slip limits do not "
                      "interact.", ValidityWarning, stacklevel=3)
    if outputs is None:
        outputs = SERIES
    outputs = tuple(outputs)
    for o in outputs:
        if o not in SERIES:
            raise UnknownNameError(f"outputs contains {o!r}: allowed are {SERIES}.")
    normal = compile_normal(contact, path)
    n_total = path.n_steps
    snaps = set()
    for s in (snapshots or ()):
        s = int(s)
        s = s + n_total if s < 0 else s
        if not 0 <= s < n_total:
            raise ParameterError(f"snapshots contains {s!r}: steps must satisfy "
                                 f"-{n_total} <= step < {n_total}.")
        snaps.add(s)
    a_max = max(float(np.max(seg["radius"], initial=0.0)) for seg in normal)
    res = {k: np.zeros(n_total) for k in SERIES if k != "gross_sliding"}
    res["gross_sliding"] = np.zeros(n_total, bool)
    t0 = 0.0
    i0 = 0
    for seg in normal:
        n = seg["depth"].size
        res["time"][i0:i0 + n] = t0 + seg["dt"]
        for k in ("depth", "force", "radius"):
            res[k][i0:i0 + n] = seg[k]
        t0 = float(res["time"][i0 + n - 1]) if n else t0
        i0 += n
    meta = {"built": ["normal", *needs], "n_springs": None, "spacing": spacing,
            "approximate": bool(approximate), "foundation": None}
    snapshot_data: dict[int, dict] = {}
    if a_max <= 0 or not needs:
        # nothing but the (exact) normal problem: no tangential/torsional springs are built
        res["stick_radius"][:] = res["radius"]
        if needs:
            _no_contact_controls(path, needs)
        fnd = None
        if snaps and a_max > 0:
            fnd = Winkler(contact.profile, contact.moduli, contact.friction, a_max,
                          n_springs=n_springs, spacing=spacing, needs=(), rtol=contact.rtol)
            meta.update(n_springs=fnd.n_springs, foundation=repr(fnd))
        for s in sorted(snaps):
            snapshot_data[s] = _snapshot(contact, fnd, None, res, s)
        return PathResult({k: res[k] for k in outputs}, snapshot_data, meta)
    fnd = Winkler(contact.profile, contact.moduli, contact.friction, a_max, n_springs=n_springs,
                  spacing=spacing, needs=needs, rtol=contact.rtol)
    meta.update(n_springs=fnd.n_springs, foundation=repr(fnd))
    _run(contact, fnd, path, normal, res, snaps, snapshot_data, "stick_radius" in outputs,
         progress)
    return PathResult({k: res[k] for k in outputs}, snapshot_data, meta)


def _no_contact_controls(path, needs):
    """A shift/twist on a contact that never touches: only zero targets are meaningful."""
    raise ParameterError("the path prescribes " + " and ".join(needs) + " but the normal load "
                         "never brings the bodies into contact (contact radius 0 at every step).")


def _snapshot(contact, fnd, st, res, i) -> dict:
    d, a = float(res["depth"][i]), float(res["radius"][i])
    snap = {"depth": d, "radius": a}
    if fnd is not None:
        x = fnd.positions
        snap["x"] = x.copy()
        S = np.maximum(d * fnd.w - fnd.dG, 0.0)
        S[fnd.bl >= a] = 0.0
        if st is not None:
            S = st.S.copy()
            snap["tangential"] = None if st.tangential is None else st.tangential.copy()
            snap["torsion"] = None if st.torsion is None else st.torsion.copy()
        snap["normal"] = 2.0 * contact.moduli.normal * S
        snap["pressure"] = (np.asarray(contact.normal(depth=d).pressure(x), float) if a > 0
                            else np.zeros(x.size))
    return snap


def _run(contact, fnd: Winkler, path, normal, res, snaps, snapshot_data, want_stick, progress):
    st = fnd.new_state()
    has_tan = st.tangential is not None
    has_tor = st.torsion is not None
    n = fnd.n_springs
    tmp = np.empty(n)
    cur = dict.fromkeys(("depth", "force", "displacement", "tangential_force", "twist",
                         "torque"), 0.0)
    ctrl_tan, ctrl_tor = "displacement", "twist"
    u = phi = 0.0
    W = 0.0
    Keff_tan = np.zeros(n) if has_tan else None
    Keff_tor = np.zeros(n) if has_tor else None
    bar = _progress(res["time"].size, progress)
    i = 0
    first = True
    keff_is_frac = False
    for leaf, nrm in zip(path.leaves(), normal):
        cur["depth"], cur["force"] = (float(res["depth"][i - 1]), float(res["force"][i - 1])) \
            if i else (0.0, 0.0)
        _, vals = leaf.values(cur)
        m = leaf.n_steps
        if "displacement" in vals or "tangential_force" in vals:
            ctrl_tan = "displacement" if "displacement" in vals else "tangential_force"
            tv = vals[ctrl_tan]
        else:
            tv = np.full(m, cur[ctrl_tan])
        if "twist" in vals or "torque" in vals:
            ctrl_tor = "twist" if "twist" in vals else "torque"
            rv = vals[ctrl_tor]
        else:
            rv = np.full(m, cur[ctrl_tor])
        d_arr, a_arr = nrm["depth"], nrm["radius"]
        ed = fnd.edge_data(d_arr, a_arr)
        ek, eS = ed["k"], ed["S"]
        eT = ed.get("T")
        for j in range(m):
            d = d_arr[j]
            a = a_arr[j]
            changed = first or d != st.depth or a != st.radius
            if changed:
                first = False
                weight = fnd.set_normal(st, d, a, int(ek[j]), eS[j], None if eT is None else eT[j])
                if has_tan:
                    np.multiply(fnd.K_tan, weight, out=Keff_tan)
                    W += fnd.jenkins(st.tangential, Keff_tan, fnd.invK_tan, st.L_tan, 0.0, tmp)
                if has_tor:
                    np.multiply(fnd.K_tor, weight, out=Keff_tor)
                    W += fnd.jenkins(st.torsion, Keff_tor, fnd.invK_tor, st.L_tor, 0.0, tmp)
                keff_is_frac = weight is st.frac
            elif not keff_is_frac:  # normal held: cells weigh by their contact fraction
                if has_tan:
                    np.multiply(fnd.K_tan, st.frac, out=Keff_tan)
                if has_tor:
                    np.multiply(fnd.K_tor, st.frac, out=Keff_tor)
                keff_is_frac = True
            if has_tan:
                if ctrl_tan == "displacement":
                    inc = tv[j] - u
                else:
                    inc, gross = fnd.solve(st.tangential, Keff_tan, st.L_tan, tv[j])
                    res["gross_sliding"][i] |= gross
                if inc != 0.0:
                    W += fnd.jenkins(st.tangential, Keff_tan, fnd.invK_tan, st.L_tan, inc, tmp)
                    u += inc
                if ctrl_tan == "displacement":
                    u = tv[j]  # no round-off drift of the prescribed displacement
                res["displacement"][i] = u
                res["tangential_force"][i] = st.tangential.sum()
            if has_tor:
                if ctrl_tor == "twist":
                    inc = rv[j] - phi
                else:
                    inc, gross = fnd.solve(st.torsion, Keff_tor, st.L_tor, rv[j])
                    res["gross_sliding"][i] |= gross
                if inc != 0.0:
                    W += fnd.jenkins(st.torsion, Keff_tor, fnd.invK_tor, st.L_tor, inc, tmp)
                    phi += inc
                if ctrl_tor == "twist":
                    phi = rv[j]
                res["twist"][i] = phi
                res["torque"][i] = st.torsion.sum()
            res["dissipated_energy"][i] = W
            if want_stick:
                if has_tan:
                    res["stick_radius"][i] = fnd.stick_radius(st.tangential, st.L_tan, fnd.bl, a)
                else:
                    res["stick_radius"][i] = fnd.stick_radius(st.torsion, st.L_tor, fnd.bl, a)
            if i in snaps:
                snapshot_data[i] = _snapshot(contact, fnd, st, res, i)
            i += 1
        cur["displacement"], cur["tangential_force"] = (res["displacement"][i - 1],
                                                        res["tangential_force"][i - 1])
        cur["twist"], cur["torque"] = res["twist"][i - 1], res["torque"][i - 1]
        if bar is not None:
            bar.update(m)
    if bar is not None:
        bar.close()
