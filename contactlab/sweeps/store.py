"""Checkpoints of a sweep: a folder of Parquet parts, written as results arrive.

``store="study.parquet"`` names a folder. ``_sweep.json`` in it says which sweep it belongs to
(the study, the grid names and a hash of every point); each ``part-NNNNNN.parquet`` holds the
rows of some finished points: the point index, the grid values, the outputs, the error, message
and warnings, and the names of the outputs the point returned (``__outputs__``, so a row reads
back exactly as it was computed). Parts are written to a temporary name and renamed, so a killed
sweep leaves only whole parts; a finished sweep is compacted into one part.
"""
from __future__ import annotations

import json
import math
import os
import time
from pathlib import Path
from typing import Any

from ..errors import ParameterError
from .grid import Grid
from .study import Records

__all__ = ["Store", "read_store"]

#: write buffered rows at most this often (s): a killed sweep loses at most this much work
FLUSH_SECONDS = 2.0
FORMAT = 1
_KEYS = "__outputs__"


def _pyarrow() -> Any:
    try:
        import pyarrow  # noqa: F401
        import pandas
    except ImportError as err:
        raise ImportError("store= needs pandas and pyarrow: pip install 'contactlab[data]'") from err
    return pandas


def _text(v: Any) -> str | None:
    if v is None or (isinstance(v, float) and math.isnan(v)):
        return None
    return str(v)


def _value(v: Any) -> Any:
    if hasattr(v, "item"):
        v = v.item()
    return v


class Store:
    """The checkpoint folder of one sweep (see the module docstring).

    Parameters
    ----------
    path : path
        The folder (created if missing).
    grid : Grid
    study : str
        :func:`~contactlab.sweeps.study.study_id` of the study.

    Raises
    ------
    ParameterError
        ``path`` is a file, or a store of another sweep.
    """

    def __init__(self, path: str | Path, grid: Grid, study: str) -> None:
        self.pd = _pyarrow()
        self.path = Path(path)
        self.grid = grid
        if self.path.exists() and not self.path.is_dir():
            raise ParameterError(f"store={str(path)!r} is a file: give a folder name (a sweep "
                                 "store is a folder of Parquet parts), e.g. 'study.parquet'.")
        self.meta = {"format": FORMAT, "study": study, "names": list(grid.names),
                     "points": len(grid), "grid": grid.fingerprint()}
        meta_file = self.path / "_sweep.json"
        if meta_file.exists():
            try:
                old = json.loads(meta_file.read_text())
                if not isinstance(old, dict):
                    raise ValueError(f"a JSON {type(old).__name__}, not an object")
            except (OSError, ValueError) as err:     # JSONDecodeError and UnicodeError included
                raise ParameterError(
                    f"store={str(path)!r} is damaged: its _sweep.json cannot be read "
                    f"({type(err).__name__}: {err}); delete the folder to start the sweep "
                    "over.") from None
            diff = [k for k in self.meta if old.get(k) != self.meta[k]]
            if diff:
                raise ParameterError(f"store={str(path)!r} holds another sweep (its "
                                     f"{', '.join(diff)} differ): give a new store or delete "
                                     "this one to start over.")
        else:
            try:
                self.path.mkdir(parents=True, exist_ok=True)
                tmp = meta_file.with_suffix(".tmp")
                tmp.write_text(json.dumps(self.meta, indent=1))
                os.replace(tmp, meta_file)
            except OSError as err:
                raise ParameterError(
                    f"store={str(path)!r} is invalid: the folder cannot be created or written "
                    f"({err.strerror or type(err).__name__}); give a writable folder.") from None
        self._buffer: list[dict[str, Any]] = []
        self._last = time.monotonic()

    def _parts(self) -> list[Path]:
        return sorted(self.path.glob("part-*.parquet"))

    def load(self) -> Records:
        """Records of the points already finished, in point order."""
        out: dict[int, dict[str, Any]] = {}
        for part in self._parts():
            df = _read_part(self.pd, self.path, part)
            try:
                for row in df.to_dict("records"):
                    i = int(row["point"])
                    if not 0 <= i < len(self.grid):
                        raise ParameterError(f"store={str(self.path)!r}: {part.name} holds point "
                                             f"{i}, outside this grid of {len(self.grid)} points.")
                    keys = json.loads(row[_KEYS])
                    out[i] = {"point": i, "outputs": {k: _value(row[k]) for k in keys},
                              "error": _text(row["error"]), "message": _text(row["message"]),
                              "warnings": _text(row["warnings"])}
            except (KeyError, TypeError, ValueError, OverflowError) as err:
                if isinstance(err, ParameterError):
                    raise
                raise _damaged(self.path, part, err) from None
        return Records.from_rows(out[i] for i in sorted(out))

    def add(self, records: Records) -> None:
        """Buffer finished records; written when :data:`FLUSH_SECONDS` passed since the last."""
        self._buffer += records.rows()
        if time.monotonic() - self._last >= FLUSH_SECONDS:
            self.flush()

    def _write(self, records: list[dict[str, Any]], name: str) -> None:
        rows = []
        for r in records:
            row = {"point": r["point"], **self.grid.point(r["point"])}
            row.update(r["outputs"])
            row.update(error=r["error"], message=r["message"], warnings=r["warnings"])
            row[_KEYS] = json.dumps(list(r["outputs"]))
            rows.append(row)
        df = self.pd.DataFrame(rows)
        for col in ("error", "message", "warnings"):
            df[col] = self.pd.Series([r[col] for r in records], index=df.index, dtype=object)
        tmp = self.path / f".{name}.tmp"
        df.to_parquet(tmp, index=False)
        os.replace(tmp, self.path / name)

    def flush(self) -> None:
        """Write the buffered records as one new part."""
        if self._buffer:
            parts = self._parts()
            n = int(parts[-1].stem.split("-")[1]) + 1 if parts else 0
            self._write(self._buffer, f"part-{n:06d}.parquet")
            self._buffer = []
        self._last = time.monotonic()

    def compact(self) -> None:
        """Rewrite every part as one (after a finished sweep)."""
        self.flush()
        parts = self._parts()
        if len(parts) > 1:
            records = self.load().rows()
            n = int(parts[-1].stem.split("-")[1]) + 1
            self._write(records, f"part-{n:06d}.parquet")
            for p in parts:
                p.unlink()


def _damaged(store: Path, part: Path, err: BaseException) -> ParameterError:
    return ParameterError(
        f"store={str(store)!r} is damaged: {part.name} cannot be read ({type(err).__name__}: "
        f"{' '.join(str(err).split())[:200]}); delete that file (its points are computed again) "
        "or the whole folder to start over.")


def _read_part(pd: Any, store: Path, part: Path) -> Any:
    """One part as a DataFrame; a file that is not a whole Parquet table of a sweep (cut short,
    overwritten) raises :class:`ParameterError` naming it, never pyarrow's own error."""
    try:
        df = pd.read_parquet(part)
    except Exception as err:         # noqa: BLE001 - pyarrow raises ArrowInvalid, OSError, ...
        raise _damaged(store, part, err) from None
    missing = [c for c in ("point", "error", "message", "warnings", _KEYS) if c not in df.columns]
    if missing:
        raise _damaged(store, part, KeyError(f"no column(s) {missing}"))
    return df


def read_store(path: str | Path) -> Any:
    """The rows a store holds so far, as a DataFrame sorted by point (a quick look at a sweep
    that is still running or was killed)."""
    pd = _pyarrow()
    parts = sorted(Path(path).glob("part-*.parquet"))
    if not parts:
        raise ParameterError(f"store={str(path)!r} holds no results (no part-*.parquet files).")
    df = pd.concat([_read_part(pd, Path(path), p) for p in parts], ignore_index=True)
    return df.drop(columns=[_KEYS]).sort_values("point").reset_index(drop=True)
