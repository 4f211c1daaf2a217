"""Execution of a planned scene: call exactly the ``Contact`` methods the plan names.

``result.meta["computed"]`` lists the calls actually made, in order, so tests (and users) can
check that an effect the plan left out was never computed.
"""
from __future__ import annotations

import io
import json
import os
import tempfile
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any, cast

import numpy as np

from ..citations import Cited, sources_for
from ..errors import (ConvergenceError, ContactlabError, EffectNotPlannedError,
                      NotSupportedError, ParameterError, failed_part_way)
from ..numeric.prefix import solved_prefix
from ..params import FieldsEqual
from ..loadpath import UNITS
from ..effects._protocol import Result, csv_text
from ..effects.fretting import SERIES_UNITS as MAP_UNITS
from ..effects.wear import SERIES_UNITS as WEAR_UNITS
from .validate import SERIES

if TYPE_CHECKING:  # pragma: no cover
    from .model import Scene
    from .plan import Plan

__all__ = ["SceneResult", "run_scene", "SERIES_UNITS", "FIELD_UNITS", "OUTPUT_FILES",
           "MANIFEST", "atomic_write", "record_outputs"]

#: every file a run may write into its output folder (series/fields CSV, JSON, plot; wear series,
#: worn profiles and the final worn profile; fretting map and its gross-slip boundary; the status
#: of a partial run)
OUTPUT_FILES = ("series.csv", "fields.csv", "result.json", "plot.png", "wear.csv",
                "wear_profiles.csv", "worn_profile.csv", "fretting_map.csv",
                "fretting_boundary.csv", "status.json")
#: the record, in an output folder, of the files the last run wrote there (name -> SHA-256 of
#: the contents): a later run removes an earlier run's file only if this record lists it and the
#: file is unchanged, so a file the user put there (or edited) is never removed
MANIFEST = ".contactlab-outputs.json"


def atomic_write(path: str | Path, data: bytes) -> Path:
    """Write ``data`` to ``path`` through a fresh temporary file in the same folder and a rename.

    The temporary file is created exclusively (``O_EXCL``), and the rename replaces whatever
    ``path`` was, a symbolic link included, without following it: a link planted in the output
    folder is never written through, and readers see the old file or the complete new one.
    """
    path = Path(path)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp", dir=path.parent)
    try:
        with os.fdopen(fd, "wb") as fh:
            fh.write(data)
        os.replace(tmp, path)
    except BaseException:
        try:
            os.unlink(tmp)
        except OSError:
            pass
        raise
    return path


def _digest(path: Path) -> str | None:
    """SHA-256 of a regular file's contents (None for a link, a folder or a missing file)."""
    import hashlib
    try:
        if path.is_symlink() or not path.is_file():
            return None
        return hashlib.sha256(path.read_bytes()).hexdigest()
    except OSError:
        return None


def _manifest(directory: Path) -> dict[str, str]:
    """The files :data:`MANIFEST` in ``directory`` records (empty when missing or unreadable)."""
    try:
        data = json.loads((directory / MANIFEST).read_text())
        files = data["files"]
        return {str(k): str(v) for k, v in files.items() if k in OUTPUT_FILES}
    except (OSError, ValueError, KeyError, TypeError, AttributeError):
        return {}


def record_outputs(directory: str | Path, paths: list[Path], *, keep: bool = True) -> None:
    """Record ``paths`` (files just written into ``directory``) in its :data:`MANIFEST`.

    ``keep=True`` adds them to what the record lists already (a plot written after the data
    files); ``keep=False`` replaces the record.
    """
    d = Path(directory)
    files = _manifest(d) if keep else {}
    for p in paths:
        digest = _digest(Path(p))
        if digest is not None and Path(p).name in OUTPUT_FILES:
            files[Path(p).name] = digest
    atomic_write(d / MANIFEST, json.dumps({"format": 1, "files": files}, indent=1).encode())


def remove_earlier_outputs(directory: str | Path, keep: list[Path]) -> list[Path]:
    """Remove the files an earlier run wrote into ``directory`` that are not in ``keep``.

    Only files its :data:`MANIFEST` lists, and only while their contents are what that run wrote
    (same SHA-256): any other file, a scene's own input included, is left alone. Returns the
    removed paths.
    """
    d = Path(directory)
    names = {Path(p).name for p in keep}
    removed = []
    for name, digest in _manifest(d).items():
        path = d / name
        if name not in names and _digest(path) == digest:
            path.unlink()
            removed.append(path)
    return removed

#: unit of each series: the load-path quantities' units plus the response quantities
SERIES_UNITS = {**UNITS, "radius": "m", "stiffness": "N/m", "peak_pressure": "Pa",
                "stick_radius": "m", "dissipated_energy": "J"}
FIELD_UNITS = {"r": "m", "pressure": "Pa", "surface_displacement": "m", "shear": "Pa"}
#: fields are sampled on r in [0, FIELD_EXTENT * a_final]
FIELD_EXTENT = 1.5


def _sources(computed: list[str], method: str | None, contact: Any) -> tuple[str, ...]:
    """Source tags of the calls a scene made (see :mod:`contactlab.citations`)."""
    names = {"normal": ("normal", *(("adhesion",) if contact.is_adhesive else ())),
             "torsion": ("normal", f"torsion:{method or 'exact'}"),
             "twist_history": ("normal", f"torsion:{method or 'exact'}", "masing:torsion"),
             "tangential": ("normal", "tangential"),
             "shift_history": ("normal", "tangential", "masing:tangential"),
             "simulate": ("normal", "foundation"),
             "viscoelastic_history": ("mdr", "viscoelastic"),
             "wear": ("normal", "fretting", "wear"), "fretting_map": ("normal", "fretting")}
    return sources_for(*(n for c in computed for n in names.get(c, ())))


def _collect(meta: dict[str, Any], calls: list[tuple[str, Any]]) -> None:
    """Notes and model errors of the results a scene computed, into its ``meta``: ``notes``
    (the warnings, in order, each once), ``model_errors`` (``"<call>.<quantity>"``: largest
    relative error), ``model_error`` (their largest, 0.0 when every route was exact) and
    ``model_error_basis``."""
    notes: list[str] = []
    errs: dict[str, float] = {}
    bases: list[str] = []
    for name, res in calls:
        if res is None:
            continue
        notes += [n for n in getattr(res, "notes", ()) if n not in notes]
        if isinstance(res, Result):
            for q, v in res.model_errors.items():
                errs[f"{name}.{q}"] = float(np.max(np.asarray(v, float)))
            if res.model_errors and res.model_error_basis not in bases:
                bases.append(res.model_error_basis)
    meta["notes"] = notes
    meta["model_errors"] = {k: _finite(v) for k, v in errs.items()}
    meta["model_error"] = _finite(max(errs.values(), default=0.0))
    meta["model_error_basis"] = "; ".join(bases) if bases else "exact routes (no model error)"


def _finite(v: float) -> Any:
    """A float for JSON: ``inf`` as the string ``"inf"`` (no bound known)."""
    return v if np.isfinite(v) else "inf"


@dataclass(eq=False)
class SceneResult(FieldsEqual, Result, Cited):
    """Outputs of a scene run.

    Attributes
    ----------
    series : dict of ndarray
        Per-step outputs (SI units, see :data:`SERIES_UNITS`), in the plan's order.
    fields : dict of ndarray
        ``r`` and the requested fields at the final step (empty when none were asked for).
    plan : Plan
    meta : dict
        ``computed`` (Contact methods called, in order), ``route``, ``version``, ``title``;
        ``wear`` and ``fretting_map`` headline numbers when those tables were planned;
        ``notes`` (the warnings of the run, as text), ``model_errors``, ``model_error`` and
        ``model_error_basis`` (of the approximate routes the run took; 0.0 when all were exact).
        The notes and the model error are also the ``# notes: ...`` and ``# model_error: ...``
        comment lines at the top of every CSV file :meth:`write` writes (when there are any).
    wear : WearResult or None
        The fretting-wear run of a ``[wear]`` table (:meth:`contactlab.Contact.wear`).
    fretting_map : FrettingMap or None
        The map of a ``[fretting_map]`` table (:meth:`contactlab.Contact.fretting_map`).
    """

    series: dict[str, np.ndarray]
    fields: dict[str, np.ndarray]
    plan: "Plan"
    meta: dict[str, Any] = field(default_factory=dict)
    wear: Any = None
    fretting_map: Any = None

    units = SERIES_UNITS

    def _columns(self) -> dict[str, np.ndarray]:
        return dict(self.series)

    def _model_errors(self) -> dict[str, Any]:
        return {k: (float("inf") if v == "inf" else v)
                for k, v in self.meta.get("model_errors", {}).items()}

    def metadata(self) -> dict[str, Any]:
        out = Result.metadata(self)
        if self.meta.get("model_error_basis"):
            out["model_error_basis"] = self.meta["model_error_basis"]
        return out

    def __getitem__(self, name: str) -> np.ndarray:
        if name in self.series:
            return self.series[name]
        if name in self.fields:
            return self.fields[name]
        if name in SERIES:
            eff = SERIES[name] or "torsion"
            raise EffectNotPlannedError(
                f"{name!r} was not computed: the plan has {list(self.plan.names)}; add {eff!r} to "
                f"outputs.effects or {name!r} to outputs.series.")
        raise KeyError(f"{name!r} is not an output; series are {list(self.series)}")

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready: plan, series and fields as lists, units, meta."""
        out = {"title": self.meta.get("title"), "plan": self.plan.to_dict(),
               "units": {k: SERIES_UNITS[k] for k in self.series},
               "series": {k: _jsonable(v) for k, v in self.series.items()},
               "fields": {k: _jsonable(v) for k, v in self.fields.items()},
               "meta": {k: v for k, v in self.meta.items() if k != "title"}}
        if self.wear is not None:
            w = self.wear
            out["wear"] = {"units": dict(WEAR_UNITS),
                           "series": {k: _jsonable(v) for k, v in w.to_dict().items()},
                           "checkpoints": _jsonable(w.checkpoints), "r": _jsonable(w.r),
                           "profiles": [_jsonable(p.f) for p in w.profiles]}
        if self.fretting_map is not None:
            out["fretting_map"] = {"units": {k: MAP_UNITS[k] for k in
                                             self.fretting_map.to_dict()},
                                   "points": {k: _jsonable(v) for k, v in
                                              self.fretting_map.to_dict().items()},
                                   "boundary": _jsonable(self.fretting_map.boundary)}
        return out

    def write(self, directory: str | Path, fmt: str = "csv", *,
              overwrite: bool = False) -> list[Path]:
        """Write ``series.csv`` (+ ``fields.csv``) or ``result.json`` into ``directory``.

        A partial result (``meta["status"] == "partial"``, the ``err.partial`` of a run that failed
        part-way) writes the steps it holds and, beside the CSV files, ``status.json`` (status,
        where it failed, the error); ``result.json`` carries the same in ``meta``.

        Every file is written atomically (:func:`atomic_write`) and recorded in the folder's
        :data:`MANIFEST`. Files an earlier run wrote that this run does not write (``series.csv``
        beside a new ``result.json``, an old ``plot.png``, ...) are removed, so the folder holds
        one consistent result; only files that record lists, unchanged since that run wrote
        them, are removed: a file this package did not write is never removed.

        Parameters
        ----------
        directory : str or Path
            Output folder (created if missing).
        fmt : {"csv", "json"}
        overwrite : bool
            Replace existing files of the same names and remove an earlier run's outputs
            (default ``False``: the same rule as the results' ``to_csv``).

        Raises
        ------
        ParameterError
            Without ``overwrite=True``, a file this call would replace or remove exists (checked
            before anything is written).
        """
        d = Path(directory)
        if d.exists() and not d.is_dir():
            raise ParameterError(f"directory={str(directory)!r} is invalid: it is a file, not a "
                                 "folder; give a folder name (created if missing).")
        files = self._file_bytes(fmt)
        if not overwrite and d.is_dir():
            names = {n for n, _ in files}
            stale = [n for n in _manifest(d) if n not in names]
            for name in [*names, *stale]:
                path = d / name
                if path.exists() or path.is_symlink():
                    raise ParameterError(
                        f"path={str(path)!r} exists: SceneResult.write() never replaces or "
                        "removes a file unless asked; pass overwrite=True or choose another "
                        "folder.")
        d.mkdir(parents=True, exist_ok=True)
        paths = [atomic_write(d / name, data) for name, data in files]
        remove_earlier_outputs(d, paths)
        record_outputs(d, paths, keep=False)
        return paths

    def _file_bytes(self, fmt: str) -> list[tuple[str, bytes]]:
        """The files :meth:`write` writes: (name, contents)."""
        if fmt == "json":
            return [("result.json", json.dumps(self.to_dict(), indent=1).encode())]
        info = self.metadata()
        out = [("series.csv", _csv_bytes(self.series, SERIES_UNITS, info))]
        if self.fields:
            out.append(("fields.csv", _csv_bytes(self.fields, FIELD_UNITS, info)))
        out += self._fretting_bytes(info)
        if self.meta.get("status") == "partial":     # the CSV files cannot say so
            status = {k: self.meta.get(k) for k in ("status", "failed_at", "error", "title",
                                                    "computed", "route", "version")}
            out.append(("status.json", json.dumps(status, indent=1).encode()))
        return out

    def _fretting_bytes(self, info: dict) -> list[tuple[str, bytes]]:
        """CSV files of the wear run and the fretting map (``name [unit]`` headers)."""
        out = []
        if self.wear is not None:
            w = self.wear
            out.append(("wear.csv", _csv_bytes(w.to_dict(), WEAR_UNITS, info)))
            cols = {"r": w.r}
            for N, prof in zip(w.checkpoints, w.profiles):
                cols[f"profile@{N:.6g}"] = prof.f
            units = {k: "m" for k in cols}
            out.append(("wear_profiles.csv", _csv_bytes(cols, units, info)))
            out.append(("worn_profile.csv", _csv_bytes({"r": w.r, "f": w.profile.f},
                                                       {"r": "m", "f": "m"}, info)))
        if self.fretting_map is not None:
            m = self.fretting_map
            out.append(("fretting_map.csv", _csv_bytes(m.to_dict(), MAP_UNITS, info)))
            amp = m.amplitude_name
            out.append(("fretting_boundary.csv", _csv_bytes(
                {"force": m.force, amp: m.boundary}, MAP_UNITS, info)))
        return out

    def figure(self, *, units: str = "si") -> Any:
        """The figure :meth:`plot` saves (needs matplotlib): one row per series against time, the
        loops, the fields, and, when the scene had them, a row with the wear run (profile
        evolution, radii and worn volume against cycles, :meth:`WearResult.plot`) and a row with
        the fretting map (:meth:`FrettingMap.plot`). ``units`` applies to the wear and map rows
        (``"engineering"``: µm, mrad, ...)."""
        from .. import plotting as pl
        pl.check_units(units)
        plt = pl.pyplot()
        names = [k for k in self.series if k != "time"]
        x = self.series.get("time", np.arange(len(next(iter(self.series.values())))))
        pairs = [("twist", "torque"), ("displacement", "tangential_force")]
        loops = [(a, b) for a, b in pairs if a in self.series and b in self.series]
        n = len(names) + len(loops) + (1 if self.fields else 0)
        extra = [h for h, on in ((2.6, self.wear is not None),
                                 (3.4, self.fretting_map is not None)) if on]
        width = 11.0 if self.wear is not None else 6.0
        with pl.style():
            fig = plt.figure(figsize=(width, 0.6 + 2.0 * n + sum(extra)), layout="constrained")
            gs = fig.add_gridspec(n + len(extra), 3, height_ratios=[2.0] * n + extra)
            rows = [fig.add_subplot(gs[i, :]) for i in range(n)]
            for ax, k in zip(rows, names):
                ax.plot(x, self.series[k])
                ax.set_ylabel(f"{k} [{SERIES_UNITS[k]}]")
                ax.set_xlabel("time [s]")
            for ax, (a, b) in zip(rows[len(names):], loops):
                ax.plot(self.series[a], self.series[b])
                ax.set_xlabel(f"{a} [{SERIES_UNITS[a]}]")
                ax.set_ylabel(f"{b} [{SERIES_UNITS[b]}]")
                pl.loop_axes(ax)
            if self.fields:
                ax = rows[-1]
                for k, v in self.fields.items():
                    if k != "r":
                        ax.plot(self.fields["r"], v, label=f"{k} [{FIELD_UNITS[k]}]")
                ax.set_xlabel("r [m]")
                ax.legend()
            row = n
            if self.wear is not None:
                self.wear.plot([fig.add_subplot(gs[row, j]) for j in range(3)], units=units)
                row += 1
            if self.fretting_map is not None:
                self.fretting_map.plot(fig.add_subplot(gs[row, :]), units=units)
            fig.suptitle(str(self.meta.get("title", "")))
        return fig

    def plot(self, path: str | Path, *, units: str = "si") -> Path:
        """Save :meth:`figure` to ``path`` (format from the suffix; needs matplotlib)."""
        try:
            import matplotlib
            matplotlib.use("Agg")
            import matplotlib.pyplot as plt
        except ImportError as err:
            raise ImportError("plotting needs matplotlib: pip install 'contactlab[plot]'") from err
        from .. import plotting as pl
        fig = self.figure(units=units)
        buf = io.BytesIO()
        pl.save(fig, buf, format=Path(path).suffix.lstrip(".") or "png")
        plt.close(fig)
        return atomic_write(path, buf.getvalue())

    def table(self, rows: int = 10) -> str:
        """A short human table of the series (``rows`` steps, evenly spread, last included)."""
        n = len(next(iter(self.series.values())))
        idx = np.unique(np.linspace(0, n - 1, min(rows, n)).round().astype(int))
        names = list(self.series)
        head = " ".join(f"{f'{k} [{SERIES_UNITS[k]}]':>16}" for k in names)
        lines = [head]
        for i in idx:
            lines.append(" ".join(f"{self.series[k][i]:16.6g}" for k in names))
        lines += _fretting_lines(self)
        return "\n".join(lines)


def _fretting_lines(res: SceneResult) -> list[str]:
    """Headline lines of the wear run and the fretting map for :meth:`SceneResult.table`."""
    lines = []
    if res.wear is not None:
        w = res.meta["wear"]
        lines += [f"wear ({res.wear.mode}, {res.wear.method}) after {w['cycles']:.6g} cycles: "
                  f"worn volume {w['volume']:.4g} m^3, max wear depth {w['max_wear_depth']:.4g} "
                  f"m, scar radius {w['scar_radius']:.4g} m, contact radius {w['radius']:.4g} m, "
                  f"stick radius {w['stick_radius']:.4g} m, energy dissipated "
                  f"{w['dissipated_energy']:.4g} J ({w['steps']} wear steps)"]
    if res.fretting_map is not None:
        m = res.meta["fretting_map"]
        counts = ", ".join(f"{k} {v}" for k, v in m["regimes"].items())
        lines += [f"fretting map ({res.fretting_map.mode}, {m['points']} points): {counts}"]
    return lines


def _jsonable(v: np.ndarray) -> list:
    return [None if not np.isfinite(x) else float(x) for x in np.asarray(v, float).ravel()] \
        if np.any(~np.isfinite(v)) else np.asarray(v, float).tolist()


def _csv_bytes(cols: dict[str, np.ndarray], units: dict[str, str],
               meta: dict[str, Any] | None = None) -> bytes:
    """CSV of equal-length columns in the result protocol's style
    (:func:`contactlab.effects._protocol.csv_text`): ``# notes: ...`` metadata lines when there
    are notes or a model error, ``name [unit]`` headers."""
    return csv_text(cols, units, meta).encode()


def _get(obj: Any, name: str, n: int) -> np.ndarray:
    if not hasattr(obj, name):
        raise NotSupportedError(f"{type(obj).__name__} has no {name!r}: cannot fill that series.")
    v = np.asarray(getattr(obj, name), dtype=float)
    return np.broadcast_to(v, (n,)).copy() if v.ndim == 0 else v.reshape(-1)


def _closed_form(contact: Any, plan: "Plan", h: Any, m: int, results: list | None = None
                 ) -> tuple[dict[str, np.ndarray], Any, list[str]]:
    """Series of the closed-form route for the first ``m`` steps (``m = n``: the whole path);
    the result objects computed are appended to ``results`` as (call, result)."""
    n_kind = h.kind("normal")
    N = h.values("normal")[:m]
    out: dict[str, np.ndarray] = {"time": h.time[:m].copy()}
    computed = ["normal"]
    normal_state = contact.normal(**{n_kind: N})
    for k in ("depth", "force", "radius", "stiffness", "peak_pressure"):
        if k in plan.series:
            out[k] = _get(normal_state, k, m)
    axis = plan.details["axis"]
    call = next((c for c in plan.calls if c in ("torsion", "twist_history", "tangential",
                                                 "shift_history")), None)
    start = min(plan.details["start"], m)
    radius = np.asarray(normal_state.radius, float).reshape(-1)
    if call is not None and m > start:
        ctrl = h.kind(axis) or ("twist" if axis == "torsion" else "displacement")
        drive = h.values(axis)[:m]
        kw = {n_kind: float(N[start]), ctrl: drive[start:]}
        if call in ("torsion", "twist_history"):
            kw["method"] = plan.method
        res = getattr(contact, call)(**kw)
        computed.append(call)
        if results is not None:
            results.append((call, res))
        pre = {"twist": 0.0, "torque": 0.0, "displacement": 0.0, "tangential_force": 0.0,
               "dissipated_energy": 0.0}
        for k in ("twist", "torque", "displacement", "tangential_force", "stick_radius",
                  "dissipated_energy"):
            if k not in plan.series:
                continue
            col = np.empty(m)
            col[:start] = radius[:start] if k == "stick_radius" else pre[k]
            col[start:] = _get(res, k, m - start)
            out[k] = col
    else:
        for k in ("twist", "torque", "stick_radius", "displacement", "tangential_force",
                  "dissipated_energy"):
            if k in plan.series:   # requested effect with nothing driving it (yet)
                out[k] = np.zeros(m) if k != "stick_radius" else _get(normal_state, "radius", m)
    return out, normal_state, computed


def _step_failure(scene: "Scene", plan: "Plan", h: Any, err: ContactlabError, k: int,
                  series: dict[str, np.ndarray], computed: list[str]) -> ContactlabError:
    """``err`` at step ``k`` of the scene's path, named by step, time and scene segment, with the
    :class:`SceneResult` of steps ``0 .. k-1`` as ``err.partial``."""
    from .model import leaf_segments
    n = h.n_steps
    leaf = int(h.segment[min(k, n - 1)])
    segs = scene.to_dict()["load_path"]
    owners = leaf_segments(segs)
    seg, rep, times = owners[leaf] if 0 <= leaf < len(owners) else (leaf, 0, 1)
    what = ("the unloaded start" if seg < 0 else f"load_path[{seg}] {next(iter(segs[seg]))}"
            + (f", repetition {rep + 1} of {times}" if times > 1 else ""))
    t = float(h.time[min(k, n - 1)])
    where = (f"step {k} of {n} failed (t = {t:.6g} s, {what}; "
             + (f"steps 0-{k - 1} computed)" if k else "no step computed)"))
    info = {"step": k, "n_steps": n, "time": t, "segment": seg,
            **({"repetition": rep + 1} if times > 1 else {})}
    part = _partial_result(scene, plan, series, {}, computed, info)
    failed_part_way(err, where, part, **info)
    part.meta["error"] = f"{type(err).__name__}: {err}"
    return err


def _partial_result(scene: "Scene", plan: "Plan", series: dict, fields: dict, computed: list,
                    info: dict, **results: Any) -> SceneResult:
    from .._version import __version__
    meta = {"computed": list(computed), "route": plan.route, "version": __version__,
            "title": scene.title, "status": "partial", "failed_at": dict(info),
            "citations": _sources(computed, plan.method, scene.contact())}
    return SceneResult({k: np.asarray(v) for k, v in series.items()}, dict(fields), plan, meta,
                       results.get("wear"), results.get("fretting_map"))


def run_scene(scene: "Scene") -> SceneResult:
    """Run a validated scene along its plan.

    A run that fails part-way raises its error (same type) naming the step (index, time, scene
    segment) or the stage after the path (fields, wear, fretting map), with what was computed
    before it as ``err.partial`` (a :class:`SceneResult` with ``meta["status"] == "partial"``)
    and the place as ``err.failed_at``.

    Raises
    ------
    NotSupportedError
        A planned series that the chosen route does not produce.
    ConvergenceError
        A series came out NaN (never returned silently).
    """
    from .._version import __version__
    plan = scene.plan()
    h = scene.history()
    contact = scene.contact()
    computed: list[str] = []
    n = h.n_steps
    n_kind = cast(str, h.kind("normal"))       # a validated scene's path drives the normal axis
    N = h.values("normal")
    out: dict[str, np.ndarray] = {"time": h.time.copy()}
    normal_state = None
    results: list[tuple[str, Any]] = []

    if plan.route == "viscoelastic":
        kw = {"n_springs": scene.solver["n_springs"]} if "n_springs" in scene.solver else {}

        def visco(m: int) -> Any:
            return contact.viscoelastic_history(time=h.time[:m], **{n_kind: N[:m]}, **kw)
        try:
            res = visco(n)
        except ContactlabError as err:
            m, got = solved_prefix(visco, n)
            raise _step_failure(scene, plan, h, err, m, {} if got is None else {
                k: (h.time[:m] if k == "time" else _get(got, k, m)) for k in plan.series},
                ["viscoelastic_history"] if got is not None else []) from None
        computed.append("viscoelastic_history")
        results.append(("viscoelastic_history", res))
        for k in plan.series:
            if k != "time":
                out[k] = _get(res, k, n)
    elif plan.route == "foundation":
        kw = {"n_springs": scene.solver["n_springs"]} if "n_springs" in scene.solver else {}
        # the model the plan resolved (effects.path.resolve_path_method, as simulate does)
        method = plan.details.get("path_method") or "mdr"
        if method == "exact":
            # the exact ring solver: it reads n_rings (or torque_rtol), not n_springs
            kw = {"method": "exact"}
            for key in ("n_rings", "torque_rtol"):
                if key in scene.solver:
                    kw[key] = scene.solver[key]
        else:                              # the plan chose the MDR springs
            kw = {**kw, "method": method}
        try:
            res = contact.simulate(scene.load_path, **kw)
        except ContactlabError as err:
            part, at = err.partial, err.failed_at or {}
            if not hasattr(part, "data") or "step" not in at:
                raise
            raise _step_failure(scene, plan, h, err, int(at["step"]),
                                {k: part.data[k] for k in plan.series if k in part.data},
                                ["simulate"]) from None
        computed.append("simulate")
        results.append(("simulate", res))
        for k in plan.series:
            if k != "time":
                out[k] = _get(res, k, n)
    else:
        try:
            out, normal_state, computed = _closed_form(contact, plan, h, n, results)
            results.insert(0, ("normal", normal_state))
        except ContactlabError as err:
            m, got = solved_prefix(lambda m: _closed_form(contact, plan, h, m), n)
            raise _step_failure(scene, plan, h, err, m, got[0] if got else {},
                                got[2] if got else []) from None

    series = {k: out[k] for k in plan.series}
    nan_at = [int(np.argmax(np.isnan(v))) for v in series.values() if np.any(np.isnan(v))]
    if nan_at:
        k = min(nan_at)
        name = next(key for key, v in series.items() if np.isnan(v[k]))
        nan_err = ConvergenceError(f"{name}[{k}] is NaN: the computation failed at that step "
                                   f"({scene.title!r}).")
        raise _step_failure(scene, plan, h, nan_err, k, {key: v[:k] for key, v in series.items()},
                            computed)

    fields: dict[str, np.ndarray] = {}
    stage = "fields"
    wear_res = fmap = None
    meta_extra: dict[str, Any] = {}
    try:
        if plan.fields:
            if normal_state is None:   # fields from the decoupled normal problem
                normal_state = contact.normal(depth=float(out["depth"][-1]) if "depth" in out
                                              else float(np.asarray(res.depth)[-1]))
                computed.append("normal")
            st = normal_state
            a_end = float(np.asarray(st.radius, float).reshape(-1)[-1])
            d_end = float(np.asarray(st.depth, float).reshape(-1)[-1])
            pts = int(scene.outputs.get("field_points", 101))
            r = np.linspace(0.0, FIELD_EXTENT * a_end, pts)
            fields["r"] = r
            last = contact.normal(depth=d_end) if st.shape else st
            for f in plan.fields:
                if f == "pressure":
                    fields[f] = np.asarray(last.pressure(r), float)
                elif f == "surface_displacement":
                    fields[f] = np.asarray(last.displacement(r), float)
                elif f == "shear":   # the exact torsion state at the final (monotone) twist
                    start = plan.details["start"]
                    ctrl = h.kind("torsion") or "twist"
                    ts = contact.torsion(**{n_kind: float(N[start]),
                                            ctrl: float(h.values("torsion")[-1]),
                                            "method": plan.method})
                    fields[f] = np.asarray(ts.shear(r), float).reshape(-1)
                    results.append(("torsion", ts))
            for k, v in fields.items():
                if np.any(np.isnan(v)):
                    raise ConvergenceError(f"field {k}[{int(np.argmax(np.isnan(v)))}] is NaN "
                                           f"({scene.title!r}).")
        if "wear" in plan.calls:
            stage = "wear"
            wear_res = contact.wear(**plan.details["wear"]["kwargs"])
            computed.append("wear")
            results.append(("wear", wear_res))
            meta_extra["wear"] = {**{k: float(v[-1]) for k, v in wear_res.to_dict().items()},
                                  "steps": int(wear_res.meta["steps"]),
                                  "mode": wear_res.mode, "method": wear_res.method}
        if "fretting_map" in plan.calls:
            stage = "fretting_map"
            fmap = contact.fretting_map(**plan.details["fretting_map"]["kwargs"])
            computed.append("fretting_map")
            results.append(("fretting_map", fmap))
            meta_extra["fretting_map"] = {
                "points": int(fmap.regime.size),
                "regimes": {name: int(np.sum(fmap.regime == i))
                            for i, name in enumerate(fmap.regime_names)}}
    except ContactlabError as err:
        info = {"stage": stage, "step": n, "n_steps": n}
        part = _partial_result(scene, plan, series, fields if stage != "fields" else {},
                               computed, info, wear=wear_res)
        part.meta.update(meta_extra)
        failed_part_way(err, f"the {stage.replace('_', ' ')} stage after the load path "
                        f"failed (all {n} steps computed)", part, **info)
        part.meta["error"] = f"{type(err).__name__}: {err}"
        raise err from None

    meta = {"computed": computed, "route": plan.route, "version": __version__,
            "title": scene.title, "citations": _sources(computed, plan.method, contact),
            **meta_extra}
    _collect(meta, results)
    return SceneResult(series, fields, plan, meta, wear_res, fmap)
