"""One registry of named types: profiles, materials (and later other kinds).

Built-in types are registered through :meth:`Registry.register` at the registry's first use of
their kind (so a source checkout works without installed metadata, and ``import contactlab`` does
not pay for checking them). Third-party types arrive through Python
entry points, discovered lazily (at the first unknown name or :meth:`Registry.available`) and
cached until :meth:`Registry.refresh`::

    [project.entry-points."contactlab.profiles"]
    hyperbolic = "my_package.profiles:Hyperbolic"

Every class passes the same checks: it subclasses the kind's base class (whose
``__init_subclass__`` checks the contract), declares ``name`` matching ``[a-z][a-z0-9_]*`` (equal
to the entry-point name), and has an explicit ``__init__`` signature (no ``*args``/``**kwargs``)
naming every declared ``Param``. A broken or clashing plugin is skipped with a
:class:`~contactlab.errors.PluginWarning`; it never breaks ``import contactlab``. Built-in names
cannot be shadowed; among plugins the first distribution (by name) wins.
``CONTACTLAB_DISABLE_PLUGINS=a,b`` blocks entry points (or distributions) by name.

For a notebook session, :func:`register_profile` / :func:`register_material` register a class
for the running session only.

Examples
--------
>>> from contactlab.registry import registry
>>> registry.get("profile", "paraboloid").__name__
'Paraboloid'
>>> registry.create("profile", "paraboloid", R=0.01)
Paraboloid(R=0.01)

The module offers the same calls on the process-wide registry (``contactlab.registry`` is this
module):

>>> import contactlab as cl
>>> cl.registry.create("profile", "paraboloid", R="10 mm")
Paraboloid(R=0.01)
"""
from __future__ import annotations

import importlib
import inspect
import os
import re
import threading
import warnings
from collections.abc import Iterable
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:   # importlib.metadata costs ~15 ms at import: loaded on first discovery
    from importlib import metadata

from .errors import ParameterError, PluginError, PluginWarning, UnknownNameError

__all__ = ["Registry", "KindSpec", "registry", "register_profile", "register_material",
           "NAME_PATTERN", "DISABLE_ENV", "available", "get", "create"]

#: registry keys: lowercase snake case
NAME_PATTERN = re.compile(r"[a-z][a-z0-9_]*\Z")
#: environment variable with comma-separated entry-point or distribution names to skip
DISABLE_ENV = "CONTACTLAB_DISABLE_PLUGINS"


@dataclass(frozen=True)
class KindSpec:
    """A kind of registered type: its base class (``module:Class``), entry-point group and the
    function (``module:function``, called with the registry) that registers the built-ins; the
    subpackage also calls it for the global registry when it is imported."""

    base: str
    group: str
    builtins: str

    def base_class(self) -> type:
        mod, _, cls = self.base.partition(":")
        return getattr(importlib.import_module(mod), cls)


@dataclass(frozen=True)
class _Entry:
    cls: type
    source: str          # "built-in", "session" or the distribution name
    origin: str          # entry point text or module:qualname


class Registry:
    """Named types by kind, from built-ins, the session and entry points.

    Parameters
    ----------
    kinds : dict, optional
        ``kind -> KindSpec``; default ``profile`` and ``material``.
    """

    def __init__(self, kinds: dict[str, KindSpec] | None = None) -> None:
        self.kinds: dict[str, KindSpec] = dict(kinds or {
            "profile": KindSpec("contactlab.profiles.base:Profile", "contactlab.profiles",
                                "contactlab.profiles:_register_builtins"),
            "material": KindSpec("contactlab.materials.base:Material", "contactlab.materials",
                                 "contactlab.materials:_register_builtins"),
        })
        self._builtin: dict[str, dict[str, _Entry]] = {k: {} for k in self.kinds}
        self._session: dict[str, dict[str, _Entry]] = {k: {} for k in self.kinds}
        self._plugins: dict[str, dict[str, _Entry]] | None = None
        self._builtins_done: set[str] = set()       # kinds whose built-ins are registered
        self._builtins_lock = threading.RLock()

    # ------------------------------------------------------------------ kinds
    def add_kind(self, kind: str, spec: KindSpec) -> None:
        """Declare a new kind (e.g. ``"effect"``) with its base class and entry-point group."""
        self._check_kind_name(kind)
        self.kinds[kind] = spec
        self._builtin.setdefault(kind, {})
        self._session.setdefault(kind, {})
        self._plugins = None

    def _kind(self, kind: str) -> KindSpec:
        if kind not in self.kinds:
            import difflib      # error paths only: ~2 ms of import
            close = difflib.get_close_matches(str(kind), list(self.kinds), n=3)
            hint = f" Did you mean {', '.join(map(repr, close))}?" if close else ""
            raise UnknownNameError(f"kind={kind!r} is unknown.{hint} Known kinds: "
                                   f"{', '.join(self.kinds)}.")
        return self.kinds[kind]

    @staticmethod
    def _check_kind_name(kind: str) -> None:
        if not isinstance(kind, str) or not NAME_PATTERN.match(kind):
            raise ParameterError(f"kind={kind!r} is invalid: kinds are lowercase snake case.")

    def _kind_of(self, cls: type) -> str:
        for kind, spec in self.kinds.items():
            if isinstance(cls, type) and issubclass(cls, spec.base_class()):
                return kind
        raise PluginError(f"{cls!r} is not a subclass of any registered kind's base class "
                          f"({', '.join(s.base for s in self.kinds.values())}) "
                          "(rule: subclass of the kind's base class).")

    # ------------------------------------------------------------------ validation
    def validate(self, cls: Any, kind: str, origin: str = "") -> str:
        """Check ``cls`` against the rules for ``kind``; return its name.

        Raises
        ------
        PluginError
            Naming the origin (entry point), the class and the rule broken.
        """
        where = f" (from {origin})" if origin else ""
        spec = self._kind(kind)
        base = spec.base_class()
        label = getattr(cls, "__qualname__", repr(cls))
        if not (isinstance(cls, type) and issubclass(cls, base)):
            raise PluginError(f"{label}{where} is not a subclass of {base.__qualname__} "
                              f"(rule: a {kind} must subclass {spec.base.replace(':', '.')}).")
        if inspect.isabstract(cls):
            raise PluginError(f"{label}{where} is abstract: it leaves "
                              f"{', '.join(sorted(getattr(cls, '__abstractmethods__', ())))} unimplemented "
                              "(rule: contract of the base class).")
        name = getattr(cls, "name", None)
        if not isinstance(name, str) or not NAME_PATTERN.match(name):
            raise PluginError(f"{label}{where} has name={name!r}: a registered {kind} needs a "
                              "class attribute `name` matching [a-z][a-z0-9_]* "
                              "(rule: name pattern).")
        try:
            sig = inspect.signature(cls)
        except (TypeError, ValueError) as err:  # pragma: no cover - builtins without signature
            raise PluginError(f"{label}{where}: __init__ has no inspectable signature "
                              "(rule: explicit signature).") from err
        variadic = [p.name for p in sig.parameters.values()
                    if p.kind in (p.VAR_POSITIONAL, p.VAR_KEYWORD)]
        if variadic:
            raise PluginError(f"{label}{where}: __init__ takes *{variadic[0]}; a registered {kind} "
                              "needs an explicit signature naming each parameter "
                              "(rule: explicit signature, no *args/**kwargs).")
        declared = [p.name for p in getattr(cls, "params", ())]
        missing = [p for p in declared if p not in sig.parameters]
        if missing:
            raise PluginError(f"{label}{where}: declares params {', '.join(missing)} that "
                              "__init__ does not accept (rule: explicit signature).")
        return name

    # ------------------------------------------------------------------ registration
    def register(self, cls: type, kind: str | None = None, *, builtin: bool = False) -> type:
        """Register ``cls`` (validated) for this session; returns ``cls`` (usable as decorator).

        Parameters
        ----------
        cls : type
        kind : str, optional
            ``"profile"``, ``"material"``…; inferred from the base class when omitted.
        builtin : bool
            Used by contactlab's own subpackages only.

        Raises
        ------
        PluginError
            The class breaks a rule, or its name is a built-in name (built-ins cannot be
            shadowed).
        """
        kind = kind or self._kind_of(cls)
        origin = f"{cls.__module__}:{cls.__qualname__}"
        name = self.validate(cls, kind, origin)
        table = self._builtin[kind] if builtin else self._session[kind]
        if not builtin:
            self._ensure_builtins(kind)         # a session class must not shadow a built-in
            if name in self._builtin[kind]:
                raise PluginError(
                    f"{origin} has name={name!r}, the name of the built-in "
                    f"{self._builtin[kind][name].cls.__qualname__}; built-in names cannot be "
                    "shadowed: choose another name.")
            old = table.get(name)
            if old is not None and old.origin != origin:
                warnings.warn(f"{kind} name {name!r}: {origin} clashes with {old.origin} "
                              "registered earlier in this session; the first is kept.",
                              PluginWarning, stacklevel=2)
                return cls
        table[name] = _Entry(cls, "built-in" if builtin else "session", origin)
        return cls

    def unregister(self, kind: str, name: str) -> None:
        """Remove a session registration (built-ins and entry points stay)."""
        self._kind(kind)
        if self._session[kind].pop(name, None) is None:
            raise UnknownNameError(f"{kind} {name!r} was not registered in this session.")

    # ------------------------------------------------------------------ entry points
    def refresh(self) -> None:
        """Forget discovered entry points; the next lookup scans them again."""
        self._plugins = None

    def _iter_entry_points(self, group: str) -> Iterable["metadata.EntryPoint"]:
        """Installed entry points of ``group`` (override or monkeypatch in tests)."""
        from importlib import metadata
        return metadata.entry_points(group=group)

    def _discover(self) -> dict[str, dict[str, _Entry]]:
        if self._plugins is not None:
            return self._plugins
        disabled = {s.strip() for s in os.environ.get(DISABLE_ENV, "").split(",") if s.strip()}
        found: dict[str, dict[str, _Entry]] = {}
        for kind, spec in self.kinds.items():
            self._ensure_builtins(kind)
            try:
                eps = list(self._iter_entry_points(spec.group))
            except Exception as err:  # noqa: BLE001 - broken metadata must not break contactlab
                warnings.warn(f"could not list entry points of group {spec.group!r}: {err}",
                              PluginWarning, stacklevel=3)
                eps = []
            found[kind] = self._load_entry_points(kind, eps, disabled)
        self._plugins = found
        return found

    @staticmethod
    def _dist_name(ep: "metadata.EntryPoint") -> str:
        dist = getattr(ep, "dist", None)
        return getattr(dist, "name", None) or getattr(dist, "metadata", {}).get("Name", "") or "?"

    def _load_entry_points(self, kind: str, eps: Iterable["metadata.EntryPoint"],
                           disabled: set[str]) -> dict[str, _Entry]:
        """Load, validate and de-duplicate entry points of one kind (first distribution wins)."""
        out: dict[str, _Entry] = {}
        for ep in sorted(eps, key=lambda e: (self._dist_name(e), e.name)):
            dist = self._dist_name(ep)
            text = f"entry point {ep.name} = {ep.value!r} (group {ep.group!r}, distribution {dist!r})"
            if ep.name in disabled or dist in disabled:
                continue
            try:
                cls = ep.load()
                name = self.validate(cls, kind, text)
            except Exception as err:  # noqa: BLE001 - any plugin failure is skipped
                warnings.warn(f"{text} skipped: {type(err).__name__}: {err}", PluginWarning,
                              stacklevel=4)
                continue
            if name != ep.name:
                warnings.warn(f"{text} skipped: the class name attribute {name!r} differs from "
                              f"the entry-point name {ep.name!r}; they must be equal.",
                              PluginWarning, stacklevel=4)
                continue
            if name in self._builtin[kind]:
                warnings.warn(f"{text} skipped: {name!r} is a built-in {kind} name and cannot be "
                              "shadowed.", PluginWarning, stacklevel=4)
                continue
            if name in out:
                warnings.warn(f"{text} skipped: {kind} {name!r} is already provided by "
                              f"{out[name].origin}; the first distribution wins.", PluginWarning,
                              stacklevel=4)
                continue
            out[name] = _Entry(cls, dist, text)
        return out

    # ------------------------------------------------------------------ lookup
    def _ensure_builtins(self, kind: str) -> None:
        """Register the built-ins of ``kind`` (``KindSpec.builtins``) at the kind's first use.

        Deferred from import time (the contract checks of ~15 classes cost ~3 ms of start-up);
        under a lock, so that a concurrent first lookup never sees half of the table.
        """
        if kind in self._builtins_done:
            return
        spec = self._kind(kind)
        with self._builtins_lock:
            if kind in self._builtins_done:
                return
            mod, _, func = spec.builtins.partition(":")
            module = importlib.import_module(mod)
            if func:
                getattr(module, func)(self)
            self._builtins_done.add(kind)

    def _tables(self, kind: str, discover: bool) -> list[dict[str, _Entry]]:
        self._ensure_builtins(kind)
        tables = [self._builtin[kind], self._session[kind]]
        if discover:
            tables.append(self._discover().get(kind, {}))
        return tables

    def available(self, kind: str) -> tuple[str, ...]:
        """Every registered name of ``kind`` (built-ins, session, plugins), sorted."""
        return tuple(sorted({n for t in self._tables(kind, True) for n in t}))

    def sources(self, kind: str) -> dict[str, str]:
        """``name -> source`` ("built-in", "session" or the plugin's distribution name)."""
        out: dict[str, str] = {}
        for t in self._tables(kind, True):
            for n, e in t.items():
                out.setdefault(n, e.source)
        return dict(sorted(out.items()))

    def get(self, kind: str, name: str | type) -> type:
        """The class registered as ``name`` (or check that class ``name`` is registered).

        Raises
        ------
        UnknownNameError
            Listing the available names and close matches.
        """
        if isinstance(name, type):
            for t in self._tables(kind, True):
                for e in t.values():
                    if e.cls is name:
                        return name
            raise UnknownNameError(f"class {name.__qualname__} is not a registered {kind}; "
                                   f"register it with registry.register({name.__qualname__}).")
        if not isinstance(name, str):
            raise UnknownNameError(f"{kind} name {name!r} is invalid: give a registered name "
                                   f"(str) or class; available: {', '.join(self.available(kind))}.")
        for t in self._tables(kind, False):      # no plugin scan for known names
            if name in t:
                return t[name].cls
        plugins = self._discover().get(kind, {})
        if name in plugins:
            return plugins[name].cls
        srcs = self.sources(kind)
        import difflib
        close = difflib.get_close_matches(str(name), list(srcs), n=3)
        hint = f" Did you mean {', '.join(map(repr, close))}?" if close else ""
        listing = ", ".join(n if s in ("built-in", "session") else f"{n} [{s}]"
                            for n, s in srcs.items())
        raise UnknownNameError(f"{kind} {name!r} is unknown.{hint} Available: {listing}.")

    def name_of(self, cls_or_obj: Any, kind: str | None = None) -> str:
        """Registry name of a class or instance (checked to be registered)."""
        cls: Any = cls_or_obj if isinstance(cls_or_obj, type) else type(cls_or_obj)
        kind = kind or self._kind_of(cls)
        self.get(kind, cls)
        return cls.name

    def create(self, kind: str, name: str | type, /, **params: Any) -> Any:
        """Build the ``kind`` registered as ``name`` from keyword parameters.

        The keywords are checked against the constructor before the call: unknown ones (with
        close matches) and missing ones raise :class:`~contactlab.errors.ParameterError`; values
        are checked by the class itself.
        """
        cls: Any = self.get(kind, name)
        sig = inspect.signature(cls)
        accepted = [p for p in sig.parameters]
        unknown = [k for k in params if k not in sig.parameters]
        if unknown:
            import difflib
            close = ([a for a in accepted if a.lower() == unknown[0].lower()]
                     or difflib.get_close_matches(unknown[0], accepted, n=1))
            hint = f" Did you mean {close[0]!r}?" if close else ""
            raise ParameterError(f"{unknown[0]}={params[unknown[0]]!r} is not a parameter of "
                                 f"{kind} {cls.name!r}.{hint} Allowed: {', '.join(accepted)}.")
        missing = [p.name for p in sig.parameters.values()
                   if p.default is p.empty and p.name not in params]
        if missing:
            raise ParameterError(f"{kind} {cls.name!r} needs {', '.join(missing)}; got "
                                 f"{', '.join(params) or 'no parameters'}.")
        return cls(**params)


#: the process-wide registry
registry = Registry()


# module-level shortcuts to the process-wide registry: ``contactlab.registry.create(...)``
def available(kind: str) -> tuple[str, ...]:
    """Names registered for ``kind`` (built-ins, session and plugins): :meth:`Registry.available`
    of the process-wide :data:`registry`."""
    return registry.available(kind)


def get(kind: str, name: str | type) -> type:
    """The class registered for ``kind`` as ``name``: :meth:`Registry.get` of :data:`registry`."""
    return registry.get(kind, name)


def create(kind: str, name: str | type, /, **params: Any) -> Any:
    """Build the ``kind`` registered as ``name``: :meth:`Registry.create` of :data:`registry`.

    Examples
    --------
    >>> import contactlab as cl
    >>> cl.registry.create("profile", "cone", half_angle="70 deg") == cl.profiles.Cone(
    ...     half_angle="70 deg")
    True
    """
    return registry.create(kind, name, **params)


def register_profile(cls: type) -> type:
    """Class decorator: register a :class:`~contactlab.profiles.Profile` for this session."""
    return registry.register(cls, "profile")


def register_material(cls: type) -> type:
    """Class decorator: register a :class:`~contactlab.materials.Material` for this session."""
    return registry.register(cls, "material")
