"""``contactlab sweep SCENE --grid KEY=A:B:N[:log] ... -o DIR``: the command behind the CLI.

Writes ``DIR/sweep.csv`` (the table; units in the headers, ``force [N]``, and the points'
warnings as ``# notes: ...`` lines first, read it with
``pandas.read_csv(path, comment="#")``) and keeps ``DIR/sweep.parquet`` as the checkpoint store
when pyarrow is installed, so the same command run again resumes a killed sweep.
"""
from __future__ import annotations

import re
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from ..errors import ParameterError
from .grid import parse_axis
from .run import sweep
from .table import table_csv_text

__all__ = ["sweep_command"]


def _grid(specs: Sequence[str]) -> dict[str, list[Any]]:
    if not specs:
        raise ParameterError("contactlab sweep needs at least one --grid KEY=A:B:N[:log], e.g. "
                             "--grid interface.friction=0.1:0.5:9.")
    grid: dict[str, list[Any]] = {}
    for spec in specs:
        key, values = parse_axis(spec)
        if key in grid:
            raise ParameterError(f"--grid {spec!r}: {key!r} is already an axis; give each key once.")
        grid[key] = values
    return grid


#: a Dask scheduler address: ``[protocol://]host[:port]`` (``tcp://10.0.0.5:8786``, ``localhost:8786``)
_ADDRESS = re.compile(r"^(?:[a-z][a-z0-9+.-]*://)?[^\s/:?#]+(?::\d{1,5})?/?$", re.IGNORECASE)


def _client(scheduler: str) -> Any:
    """A ``dask.distributed.Client`` of ``--scheduler``; an address that is no address, or a
    scheduler that cannot be reached, raises :class:`ParameterError` naming it."""
    if not _ADDRESS.match(scheduler.strip()):
        raise ParameterError(f"--scheduler {scheduler!r} is invalid: give a Dask scheduler "
                             "address [protocol://]host[:port], e.g. tcp://10.0.0.5:8786.")
    try:
        from distributed import Client
    except ImportError as err:
        raise ImportError("--scheduler needs dask.distributed: pip install "
                          "'contactlab[dist]'") from err
    try:
        return Client(scheduler.strip(), timeout="30s")
    except (OSError, ValueError, TypeError) as err:     # TimeoutError is an OSError
        raise ParameterError(f"--scheduler {scheduler!r}: no Dask scheduler could be reached "
                             f"there ({type(err).__name__}: {' '.join(str(err).split())}); check "
                             "the address, or run without --scheduler.") from None


def _has_pyarrow() -> bool:
    try:
        import pyarrow  # noqa: F401
    except ImportError:
        return False
    return True


def sweep_command(scene: str | Path, specs: Sequence[str], output: str | Path | None = None, *,
                  scheduler: str | None = None, workers: int | None = None,
                  progress: bool = True, on_error: str = "record",
                  allow_outside: bool = False, overwrite: bool = False
                  ) -> tuple[dict[str, Any], str]:
    """Run the sweep of the command line; returns (JSON payload, text for humans).

    ``DIR/sweep.csv`` is written at the end; an existing one is replaced only with
    ``overwrite=True`` (checked before any point runs). ``DIR/sweep.parquet`` is the checkpoint
    store: the same command run again on a killed sweep resumes from it.
    """
    grid = _grid(specs)
    outdir = Path(output) if output is not None else None
    store = None
    notes = []
    if outdir is not None:
        target = outdir / "sweep.csv"
        if not overwrite and (target.exists() or target.is_symlink()):
            raise ParameterError(f"-o {str(output)!r} is invalid: {str(target)!r} exists; choose "
                                 "another folder or pass --overwrite to replace it (a killed "
                                 "sweep resumes from sweep.parquet without it).")
        try:
            outdir.mkdir(parents=True, exist_ok=True)
        except OSError as err:
            raise ParameterError(f"-o {str(output)!r} is invalid: the folder cannot be created "
                                 f"({err.strerror or type(err).__name__}).") from None
        if _has_pyarrow():
            store = outdir / "sweep.parquet"
        else:
            notes.append("note: no checkpoint kept (pyarrow missing: pip install "
                         "'contactlab[data]'); a killed sweep starts over.")
    client = _client(scheduler) if scheduler is not None else None
    try:
        table = sweep(scene, grid, client=client, workers=workers, progress=progress,
                      on_error=on_error, store=store, allow_outside=allow_outside)
    finally:
        if client is not None:
            client.close()
    files = []
    if outdir is not None:
        from ..scene.run import atomic_write
        files.append(atomic_write(outdir / "sweep.csv", table_csv_text(table).encode()))
        if store is not None:
            files.append(store)
    stats = table.attrs["sweep"]["stats"]
    failed = int(table["error"].notna().sum())
    payload = {"ok": True, "points": len(table), "failed": failed,
               "files": [str(f) for f in files], "stats": stats, "notes": notes}
    if outdir is None:
        payload["table"] = {c: [None if v != v else v for v in table[c].tolist()]
                            for c in table.columns}
    text = [f"{scene}: {len(table)} points ({failed} failed; {stats['resumed']} from the store) "
            f"on {stats.get('backend', 'no backend')} in {stats['seconds']:.3g} s"]
    if outdir is None:
        text.append(table.drop(columns=["message", "warnings"]).to_string(index=False))
    text += [f"wrote {f}" for f in files] + notes
    return payload, "\n".join(text)
