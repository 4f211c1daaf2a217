"""Scene key paths: ``"interface.friction"``, ``"load_path[1].sinusoid.twist"``.

A key path names one value in a scene's nested tables, in the spelling scene validation uses in
its messages. :func:`parse_key_path` splits it into dict keys (str) and list indices (int);
:func:`set_key_path` writes a value into a nested mapping (a copy is the caller's business).
"""
from __future__ import annotations

import re
from collections.abc import MutableMapping
from typing import Any

from ..errors import ParameterError

__all__ = ["parse_key_path", "set_key_path"]

_PART = re.compile(r"([A-Za-z_][A-Za-z0-9_]*)((?:\[\d+\])*)$")
_EXAMPLE = "a key path like 'interface.friction' or 'load_path[1].sinusoid.twist'"


def parse_key_path(path: str) -> tuple[str | int, ...]:
    """Split a key path into dict keys and list indices.

    Parameters
    ----------
    path : str
        Dot-separated table keys, each optionally followed by ``[i]`` list indices.

    Returns
    -------
    tuple of str and int

    Raises
    ------
    ParameterError
        ``path`` is not a key path.

    Examples
    --------
    >>> parse_key_path("load_path[1].sinusoid.twist")
    ('load_path', 1, 'sinusoid', 'twist')
    """
    if not isinstance(path, str) or not path:
        raise ParameterError(f"grid key {path!r} is invalid: expected {_EXAMPLE}.")
    out: list[str | int] = []
    for part in path.split("."):
        m = _PART.match(part)
        if m is None:
            raise ParameterError(f"grid key {path!r} is invalid: {part!r} is not a table key "
                                 f"(optionally with [index]); expected {_EXAMPLE}.")
        out.append(m.group(1))
        out += [int(i) for i in re.findall(r"\[(\d+)\]", m.group(2))]
    return tuple(out)


def set_key_path(data: MutableMapping[str, Any], path: str, value: Any) -> None:
    """Set the value at key path ``path`` of nested tables ``data`` in place.

    Missing tables on the way are created; list indices must exist.

    Raises
    ------
    ParameterError
        The path does not fit the structure of ``data`` (index out of range, a value where a
        table or list is needed).

    Examples
    --------
    >>> d = {"load_path": [{"ramp": {"force": 1.0}}]}
    >>> set_key_path(d, "load_path[0].ramp.force", 2.0); d
    {'load_path': [{'ramp': {'force': 2.0}}]}
    """
    parts = parse_key_path(path)
    node: Any = data
    for depth, key in enumerate(parts):
        last = depth == len(parts) - 1
        where = _spell(parts[:depth]) or "the scene"
        if isinstance(key, int):
            if not isinstance(node, list):
                raise ParameterError(f"grid key {path!r} is invalid: {where} is not a list, so "
                                     f"[{key}] cannot index it.")
            if key >= len(node):
                raise ParameterError(f"grid key {path!r} is invalid: {where} has {len(node)} "
                                     f"entries (indices 0..{len(node) - 1}).")
        elif not isinstance(node, MutableMapping):
            raise ParameterError(f"grid key {path!r} is invalid: {where} is not a table, so it "
                                 f"has no key {key!r}.")
        elif not last and key not in node:
            node[key] = {}
        if last:
            node[key] = value
        else:
            node = node[key]


def _spell(parts: tuple[str | int, ...]) -> str:
    s = ""
    for p in parts:
        s += f"[{p}]" if isinstance(p, int) else (f".{p}" if s else p)
    return s
