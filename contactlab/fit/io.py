"""Reading measured curves for fitting: CSV files with units in the header, and AFM instrument
files through the optional package ``afmformats`` (the extra ``afm``)."""
from __future__ import annotations

import os
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..errors import NotSupportedError, ParameterError, TabulatedDataError

__all__ = ["Curve", "read_curve", "AFM_EXTENSIONS"]

#: file endings read through afmformats (everything else is read as CSV)
AFM_EXTENSIONS = (".jpk-force", ".jpk-force-map", ".jpk-qi-data", ".jpk-qi-series", ".ibw",
                  ".h5", ".tab", ".zip")
#: CSV column names and their dimensions
_CSV = {"depth": "length", "force": "force", "time": "time"}
_SEGMENTS = ("approach", "retract", "both")


@dataclass(frozen=True)
class Curve:
    """A measured indentation curve in SI units, ready for :func:`contactlab.fit.indentation`.

    Attributes
    ----------
    depth : ndarray
        Indenter (tip) position, m, increasing into the sample.
    force : ndarray
        Normal force, N.
    time : ndarray or None
        Sample times, s (None when the file has none).
    meta : dict
        ``source`` (the path), ``reader`` (``"csv"`` or ``"afmformats"``), ``segment`` and, for
        instrument files, ``depth_from`` (the column the depth came from), ``spring_constant``
        (N/m) and the instrument's metadata under ``"instrument"``.
    """

    depth: np.ndarray
    force: np.ndarray
    time: np.ndarray | None = None
    meta: dict = field(default_factory=dict)


def read_curve(path: Any, *, segment: str = "approach", index: int = 0) -> Curve:
    """Read a force-indentation curve from a CSV file or an AFM instrument file.

    Parameters
    ----------
    path : path-like
        A CSV file with the columns ``depth`` and ``force`` (and optionally ``time``), units in
        the header (``depth [nm]``, ``force [nN]``, ``time [ms]``; SI without), or an AFM file
        that ``afmformats`` reads (JPK ``.jpk-force``, Igor ``.ibw``, afmformats' own ``.tab``
        and ``.h5``, ...; see :data:`AFM_EXTENSIONS`).
    segment : {"approach", "retract", "both"}
        The part of an instrument curve to return (CSV files are returned whole).
    index : int
        Which curve of a file holding several (a force map), from 0.

    Returns
    -------
    Curve

    Raises
    ------
    ParameterError
        An unknown ``segment`` or ``index`` out of range, or a CSV file without the columns.
    TabulatedDataError
        An unreadable file or a cell that is not a number.
    NotSupportedError
        An instrument file while ``afmformats`` is not installed (``pip install
        contactlab[afm]``).

    Notes
    -----
    Instrument files give the height of the cantilever's base (up, away from the sample) and
    the force (repulsive positive). The tip's position is ``height + F/k`` with the spring
    constant ``k`` from the file (the cantilever bends up under a repulsive force); the depth
    is its negative, so it increases into the sample. A file's own ``tip position`` column is
    used when present. The contact point stays unknown: fit it (``"contact_point"``).
    """
    if segment not in _SEGMENTS:
        raise ParameterError(f"segment={segment!r} is invalid: choose one of {_SEGMENTS}.")
    name = os.fspath(path)
    if str(name).lower().endswith(AFM_EXTENSIONS):
        return _read_afm(name, segment, index)
    return _read_csv(name)


def _read_csv(path: str, time: str = "time") -> Curve:
    """The curve of a CSV file, its columns picked by name (``depth``, ``force`` and the sample
    times from the column ``time``), in any order, other columns ignored; ``meta["columns"]``
    lists the header's names. (Shared with ``contactlab fit``, whose ``--time`` names the
    time column.)"""
    from ..numeric.tables import read_columns
    if time in ("depth", "force"):
        raise ParameterError(f"time={time!r} is invalid: the column of sample times must be "
                             "another column than 'depth' and 'force'.")
    dims = {"depth": "length", "force": "force", time: "time"}

    def dimension(col: str) -> str | None:
        return dims.get(col, "ignore")
    names, cols = read_columns(path, dimension=dimension, min_columns=2,
                               known_names=tuple(dict.fromkeys((*_CSV, time))))
    missing = [c for c in ("depth", "force") if c not in cols]
    if missing:
        raise ParameterError(f"file={path!r} has the columns {names}: a curve needs 'depth' and "
                             f"'force' (missing {missing}; units in the header, e.g. "
                             "'depth [nm]').")
    return Curve(depth=cols["depth"], force=cols["force"], time=cols.get(time),
                 meta={"source": path, "reader": "csv", "segment": "whole file",
                       "columns": list(names)})


def _read_afm(path: str, segment: str, index: int) -> Curve:
    try:
        import afmformats
    except ImportError as err:
        raise NotSupportedError(
            f"file={path!r}: AFM instrument files are read through the package 'afmformats', "
            "which is not installed; install the extra: pip install 'contactlab[afm]' (or "
            "export the curve as CSV with 'depth' and 'force' columns).") from err
    try:
        data = afmformats.load_data(path)
    except (OSError, ValueError, KeyError, IndexError, afmformats.errors.AFMFileFormatError,
            afmformats.errors.MissingMetaDataError) as err:     # (BaseException subclasses)
        raise TabulatedDataError(f"file={path!r} cannot be read by afmformats: {err}") from err
    if not data:
        raise TabulatedDataError(f"file={path!r} holds no force-distance curve.")
    if not 0 <= index < len(data):
        raise ParameterError(f"index={index!r} is invalid: file={path!r} holds {len(data)} "
                             f"curves (0 to {len(data) - 1}).")
    fd = data[index]
    cols = set(fd.columns)
    force = np.asarray(fd["force"], float)
    meta_i = dict(fd.metadata)
    k = meta_i.get("spring constant")
    if "tip position" in cols:
        tip, source = np.asarray(fd["tip position"], float), "tip position"
    else:
        h_col = "height (measured)" if "height (measured)" in cols else "height (piezo)"
        if h_col not in cols:
            raise TabulatedDataError(f"file={path!r} has no height column (columns "
                                     f"{sorted(cols)}).")
        if not (k and np.isfinite(k) and k > 0):
            raise TabulatedDataError(f"file={path!r} has no spring constant: the tip position "
                                     "height + F/k cannot be computed.")
        tip = np.asarray(fd[h_col], float) + force / float(k)
        source = f"{h_col} + force/k"
    keep = np.ones(force.size, bool)
    if segment != "both" and "segment" in cols:
        keep = np.asarray(fd["segment"]) == (0 if segment == "approach" else 1)
    time = np.asarray(fd["time"], float)[keep] if "time" in cols else None
    return Curve(depth=-tip[keep], force=force[keep], time=time,
                 meta={"source": path, "reader": "afmformats", "segment": segment,
                       "depth_from": f"-({source})", "spring_constant": k,
                       "instrument": {str(a): b for a, b in meta_i.items()
                                      if isinstance(b, (int, float, str))}})
