"""Every public name has a numpydoc docstring that states units, and is in the API reference.

The API reference (docs/conf.py) is generated from ``contactlab.__all__`` and the public members of
:class:`~contactlab.Contact`; this test holds those names to the docstring standard: a summary line,
and for anything that takes or returns quantities, the SI unit of at least one of them (or an
explicit "dimensionless"/"SI" statement).
"""
from __future__ import annotations

import inspect
import re

import pytest

import contactlab as cl

UNIT = re.compile(r"(?<![A-Za-z_])(m|N|Pa|rad|J|s|N\*m|N·m|N/m|J/m\^?2|J/m²|Pa\*s|1/Pa)"
                  r"(?![A-Za-z_(])|dimensionless|\bSI\b|[µμ]m|\b[Bb]ytes\b")
MODULES = {"profiles", "materials", "errors", "foundation", "loadpath", "registry", "citations"}
#: names that take no physical quantity: plugin registration takes classes; a sweep takes a study
#: and a grid whose units are those of the study (scene keys carry their own units)
NO_QUANTITIES = {"register_profile", "register_material", "sweep", "cite"}


def _public():
    names = [n for n in cl.__all__ if not n.startswith("__")]
    out = [(n, getattr(cl, n)) for n in names]
    out += [(f"Contact.{n}", getattr(cl.Contact, n)) for n, _ in
            inspect.getmembers(cl.Contact) if not n.startswith("_")]
    return out


@pytest.mark.parametrize("name, obj", _public(), ids=[n for n, _ in _public()])
def test_public_name_has_a_docstring_with_units(name, obj):
    doc = inspect.getdoc(obj.fget if isinstance(obj, property) else obj) or ""
    assert doc.strip(), f"contactlab.{name} has no docstring"
    if (name in MODULES | NO_QUANTITIES
            or inspect.isclass(obj) and issubclass(obj, BaseException)):
        return
    assert UNIT.search(doc), f"contactlab.{name}: the docstring states no SI unit"
