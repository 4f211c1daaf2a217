"""The scene checker: one value against one :class:`~contactlab.scene.schema.Key`, every problem
collected as a ``(key path, value, allowed)`` triple instead of raised.

:mod:`.validate` walks a scene's tables with it; :meth:`Checker.keys` checks a whole table against
a table of keys, so each section is data (:mod:`.schema`), not code.
"""
from __future__ import annotations

import difflib
from collections.abc import Callable, Mapping
from pathlib import Path
from typing import Any

from ..errors import ParameterError, SceneError
from .schema import Key
from .units import parse_quantity, unit_factor

__all__ = ["Checker", "Issue", "resolve_file", "summary", "short", "first_line", "join"]

Issue = tuple[str, Any, str]

_DOMAIN_TEXT = {"positive": "> 0", "nonnegative": ">= 0"}


def resolve_file(value: str | Path, base_dir: Path | None, allow_outside: bool = True) -> Path:
    """The path a scene's file reference names.

    A relative name is taken relative to ``base_dir`` (the scene's folder) and, unless
    ``allow_outside``, must stay inside it after resolving ``..`` and symbolic links; an absolute
    name is the user's explicit choice and is used as given.

    Raises
    ------
    ParameterError
        A relative name that leaves the scene's folder (``../../etc/passwd``, or a link to
        outside) while ``allow_outside`` is False. The message never shows file contents.
    """
    p = Path(value)
    if p.is_absolute() or base_dir is None:
        return p
    full = Path(base_dir) / p
    if not allow_outside:
        root = Path(base_dir).resolve()
        if not full.resolve().is_relative_to(root):
            raise ParameterError(
                f"file {str(value)!r} resolves outside the scene's folder {str(root)!r}: scene "
                "files may only refer to files in their folder or below (give an absolute "
                "path, or run with --allow-outside, to read it anyway).")
    return full


def join(path: str, key: str) -> str:
    """``"a.b"`` from a key path and a key (the top level has the empty path)."""
    return f"{path}.{key}" if path else key


def first_line(err: BaseException) -> str:
    """The first line of an exception's message (its type name if it has none)."""
    return str(err).splitlines()[0] if str(err) else type(err).__name__


def short(value: Any) -> str:
    """``repr(value)``, cut to 80 characters."""
    s = repr(value)
    return s if len(s) <= 80 else s[:77] + "..."


def summary(issues: list[Issue]) -> str:
    """The message of a :class:`~contactlab.errors.SceneError`: one line per issue."""
    lines = [f"scene is invalid ({len(issues)} problem{'s' if len(issues) > 1 else ''}):"]
    for path, value, allowed in issues:
        lines.append(f"  {path or '<scene>'} = {short(value)}: expected {allowed}")
    return "\n".join(lines)


#: a check for a key kind its section handles itself: (checker, key path, value, key) -> value
Custom = Callable[["Checker", str, Any, Key], Any]


class Checker:
    """Collects the issues of one scene (``issues``) while checking its values."""

    def __init__(self, base_dir: Path | None, allow_outside: bool = False) -> None:
        self.allow_outside = allow_outside
        self.issues: list[Issue] = []
        self.base_dir = base_dir
        self.file_steps: dict[str, int] = {}     # load_path[i] -> rows of its CSV history

    def add(self, path: str, value: Any, allowed: str) -> None:
        self.issues.append((path, value, allowed))

    # ---- tables
    def table(self, path: str, value: Any) -> dict | None:
        if not isinstance(value, Mapping):
            self.add(path, value, "a table (mapping of keys to values)")
            return None
        bad = [k for k in value if not isinstance(k, str)]
        for k in bad:
            self.add(f"{path}.{k!r}", k, "string keys")
        return {k: v for k, v in value.items() if isinstance(k, str)}

    def unknown_keys(self, path: str, table: Mapping, allowed: Any) -> None:
        allowed = list(allowed)
        for k in table:
            if k not in allowed:
                close = difflib.get_close_matches(k, allowed, n=1, cutoff=0.6)
                hint = f"; did you mean {close[0]!r}?" if close else ""
                self.add(join(path, k), table[k], f"a key from {sorted(allowed)}{hint}")

    def keys(self, path: str, table: Mapping[str, Any], spec: Mapping[str, Key],
             custom: Mapping[str, Custom] | None = None) -> dict[str, Any]:
        """The checked values of ``table``'s keys in the order of ``spec``; a missing required
        key is an issue. Kinds in ``custom`` are checked by their function."""
        out: dict[str, Any] = {}
        for k, key in spec.items():
            kp = join(path, k)
            if k not in table:
                if key.required:
                    self.add(kp, None, key.required)
                continue
            check = (custom or {}).get(key.kind)
            v = check(self, kp, table[k], key) if check else self.key(kp, table[k], key)
            if v is not None:
                out[k] = v
        return out

    # ---- values
    def key(self, path: str, value: Any, key: Key) -> Any:
        """``value`` checked against ``key``: the normalised value, or None after an issue."""
        kind = key.kind
        if kind == "quantity":
            if key.choices and isinstance(value, str):     # a name instead of a number
                return self.choice(path, value, key.choices)
            v = self.quantity(path, value, key.dimension, key.domain)
            if v is not None and key.high is not None and (
                    v >= key.high if key.high_open else v > key.high):
                self.add(path, value, key.high_allowed)
                return None
            if v is not None and key.low is not None and v < key.low:
                self.add(path, value, key.high_allowed)
                return None
            return v
        if kind == "integer":
            return self.integer(path, value, int(key.low or 0), int(key.high or 0))
        if kind == "choice":
            return self.choice(path, value, key.choices)
        if kind == "names":
            return self.string_list(path, value, key.choices)
        if kind == "array":
            return self.array(path, value, key.dimension)
        if kind == "file":
            return self.file(path, value)
        if kind == "unit":                   # a unit name (the columns of a CSV file)
            try:
                unit_factor(value, key.dimension, path)
            except SceneError as err:
                self.issues.extend(err.issues)
                return None
            return value
        if kind == "text":
            if not isinstance(value, str):
                self.add(path, value, "a string")
                return None
            return value
        raise ValueError(f"{path}: no check for a key of kind {kind!r}")

    def quantity(self, path: str, value: Any, dim: str, domain: str = "real") -> float | None:
        try:
            v = parse_quantity(value, dim, path)
        except SceneError as err:
            self.issues.extend(err.issues)
            return None
        ok = {"real": True, "positive": v > 0, "nonnegative": v >= 0}[domain]
        if not ok:
            self.add(path, value, _DOMAIN_TEXT[domain])
            return None
        return v

    def integer(self, path: str, value: Any, low: int, high: int) -> int | None:
        if isinstance(value, bool) or not isinstance(value, int):
            if isinstance(value, float) and value.is_integer() and low <= value <= high:
                return int(value)
            self.add(path, value, f"an integer {low}..{high}")
            return None
        if not low <= value <= high:
            self.add(path, value, f"an integer {low}..{high}")
            return None
        return value

    def choice(self, path: str, value: Any, allowed: Any) -> Any:
        allowed = list(allowed)
        if not isinstance(value, str) or value not in allowed:
            close = (difflib.get_close_matches(value, allowed, n=1, cutoff=0.6)
                     if isinstance(value, str) else [])
            hint = f"; did you mean {close[0]!r}?" if close else ""
            self.add(path, value, f"one of {allowed}{hint}")
            return None
        return value

    def string_list(self, path: str, value: Any, allowed: Any) -> list[str] | None:
        if not isinstance(value, list):
            self.add(path, value, f"a list of names from {sorted(allowed)}")
            return None
        out: list[str] = []
        for i, v in enumerate(value):
            c = self.choice(f"{path}[{i}]", v, allowed)
            if c is not None:
                if c in out:
                    self.add(f"{path}[{i}]", v, "each name once")
                else:
                    out.append(c)
        return out

    def array(self, path: str, value: Any, dim: str) -> list[float] | None:
        if not isinstance(value, list) or len(value) == 0:
            self.add(path, value, "a non-empty list of numbers")
            return None
        out = []
        for i, v in enumerate(value):
            q = self.quantity(f"{path}[{i}]", v, dim)
            if q is None:
                return None
            out.append(q)
        return out

    def file(self, path: str, value: Any) -> str | None:
        if not isinstance(value, str) or not value:
            self.add(path, value, "a file name (relative to the scene file)")
            return None
        try:
            p = resolve_file(value, self.base_dir, self.allow_outside)
        except ParameterError:
            self.add(path, value, "a file inside the scene's folder (an absolute path or "
                     "--allow-outside reads files elsewhere)")
            return None
        if not p.is_file():
            self.add(path, value, f"an existing file (looked for {str(p)!r})")
            return None
        return value
