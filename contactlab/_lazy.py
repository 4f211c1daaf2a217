"""Names of a module resolved on first use: one helper for every lazy package face.

The pattern of scientific Python's ``lazy_loader`` (SPEC 1): a module declares which of its
public names live in which submodule, and :func:`attach` returns the module's ``__getattr__``
and ``__dir__``. Nothing is imported until a name is first looked up; the value is then stored
in the module's namespace, so later lookups are plain attribute reads. A ``.pyi`` stub next to
the module lists the same names for type checkers and IDEs (``tests/unit/test_lazy_imports.py``
checks that stub and runtime agree).

Kept in-house rather than depending on the ``lazy_loader`` package: contactlab's core
dependencies are numpy, scipy and sympy only, and this is the one function it needs (same call
shape as ``lazy_loader.attach``, so a switch is a one-line change per face).

This module is a leaf: it imports nothing from contactlab, so every layer may use it.
"""
from __future__ import annotations

import importlib
import sys
from collections.abc import Callable, Iterable, Mapping

__all__ = ["attach"]


def attach(module_name: str, submodules: Iterable[str] = (),
           submod_attrs: Mapping[str, Iterable[str]] | None = None, *,
           package: str | None = None
           ) -> tuple[Callable[[str], object], Callable[[], list[str]], list[str]]:
    """``__getattr__``, ``__dir__`` and the sorted lazy names of module ``module_name``.

    Parameters
    ----------
    module_name : str
        The module the functions serve (pass ``__name__``).
    submodules : iterable of str
        Submodules of ``module_name`` (a package) imported on first access
        (``contactlab.foundation``); importing binds each as an attribute.
    submod_attrs : mapping, optional
        Module path, relative to ``package``, -> the names it defines that ``module_name``
        offers (``{"effects.normal": ["NormalState"]}``).
    package : str, optional
        The package ``submod_attrs`` paths are relative to; default ``module_name`` (a package
        face). A plain module passes its own package (``contact.py``: ``"contactlab"``).

    Returns
    -------
    __getattr__, __dir__ : callable
        To assign to the module's own ``__getattr__`` and ``__dir__``.
    names : list of str
        Every lazily resolved name, sorted.

    Examples
    --------
    >>> getattr_, dir_, names = attach("contactlab", ["loadpath"], {"citations": ["cite"]})
    >>> names
    ['cite', 'loadpath']
    """
    base = package or module_name
    subs = frozenset(submodules)
    home = {attr: mod for mod, attrs in (submod_attrs or {}).items() for attr in attrs}
    names = sorted(subs | set(home))

    def __getattr__(name: str) -> object:
        if name in subs:                    # importing a submodule binds it as an attribute
            return importlib.import_module(f"{module_name}.{name}")
        mod = home.get(name)
        if mod is None:
            raise AttributeError(f"module {module_name!r} has no attribute {name!r}")
        value = getattr(importlib.import_module(f"{base}.{mod}"), name)
        setattr(sys.modules[module_name], name, value)   # later lookups skip __getattr__
        return value

    def __dir__() -> list[str]:
        return sorted(set(vars(sys.modules[module_name])) | set(names))

    return __getattr__, __dir__, names
