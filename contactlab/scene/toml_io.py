"""Reading scenes with the standard library's :mod:`tomllib`, writing them with a minimal writer.

The writer covers what a normalised scene holds: tables, arrays of tables (``[[load_path]]``),
inline tables one level down, strings, booleans, integers, floats (incl. ``inf``/``nan``) and
arrays of those. It is not a general TOML writer.
"""
from __future__ import annotations

import math
import re
import tomllib
from collections.abc import Mapping
from pathlib import Path
from typing import Any

from ..errors import SceneError

__all__ = ["load", "loads", "dumps"]

_BARE_KEY = re.compile(r"[A-Za-z0-9_-]+")


def loads(text: str) -> dict[str, Any]:
    """Parse TOML text; a syntax error becomes a :class:`SceneError` naming line and column."""
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as err:
        raise SceneError(f"scene is not valid TOML: {err}",
                         [("<toml>", str(err), "valid TOML (https://toml.io)")]) from err


def load(path: str | Path) -> dict[str, Any]:
    """Read and parse a TOML scene file."""
    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as err:
        raise SceneError(f"scene file {str(path)!r} cannot be read: {err}",
                         [("<file>", str(path), "a readable UTF-8 TOML file")]) from err
    return loads(text)


_ESCAPES = {"\\": "\\\\", '"': '\\"', "\b": "\\b", "\t": "\\t", "\n": "\\n", "\f": "\\f",
            "\r": "\\r"}


def _string(s: str) -> str:
    """TOML basic string: escape backslash, quote and every control character."""
    out = []
    for ch in s:
        if ch in _ESCAPES:
            out.append(_ESCAPES[ch])
        elif ord(ch) < 0x20 or ord(ch) == 0x7F:
            out.append(f"\\u{ord(ch):04X}")
        else:
            out.append(ch)
    return '"' + "".join(out) + '"'


def _key(k: str) -> str:
    return k if _BARE_KEY.fullmatch(k) else _string(k)


def _value(v: Any) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        if math.isnan(v):
            return "nan"
        if math.isinf(v):
            return "inf" if v > 0 else "-inf"
        return repr(v)
    if isinstance(v, str):
        return _string(v)
    if isinstance(v, Mapping):
        return "{ " + ", ".join(f"{_key(k)} = {_value(x)}" for k, x in v.items()) + " }"
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(_value(x) for x in v) + "]"
    if hasattr(v, "tolist"):      # numpy scalars and arrays
        return _value(v.tolist())
    raise TypeError(f"cannot write {type(v).__name__} value {v!r} to TOML")


def dumps(data: Mapping[str, Any]) -> str:
    """TOML text of a scene mapping: scalars first, then ``[table]`` and ``[[array]]`` sections.

    Examples
    --------
    >>> print(dumps({"profile": {"type": "cone", "slope": 0.5},
    ...              "load_path": [{"ramp": {"depth": 1e-06, "steps": 10}}]}))
    [profile]
    type = "cone"
    slope = 0.5
    <BLANKLINE>
    [[load_path]]
    ramp = { depth = 1e-06, steps = 10 }
    <BLANKLINE>
    """
    head, blocks = [], []
    for k, v in data.items():
        if isinstance(v, Mapping):
            lines = [f"[{_key(k)}]"] + [f"{_key(kk)} = {_value(vv)}" for kk, vv in v.items()]
            blocks.append("\n".join(lines) + "\n")
        elif isinstance(v, (list, tuple)) and v and all(isinstance(x, Mapping) for x in v):
            for item in v:
                lines = [f"[[{_key(k)}]]"] + [f"{_key(kk)} = {_value(vv)}" for kk, vv in item.items()]
                blocks.append("\n".join(lines) + "\n")
        else:
            head.append(f"{_key(k)} = {_value(v)}")
    parts = (["\n".join(head) + "\n"] if head else []) + blocks
    return "\n".join(parts)
