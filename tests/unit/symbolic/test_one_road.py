"""One road to the formulas: built-ins and plugins hand over their closed forms through the same
hook (``Profile._sympy_form``), and ``symbolic/`` knows no profile class.

The expected formulas are independent closed forms (Hertz, the flat punch), or the built-in's
formulas compared with a plugin-style twin defined here that declares only the plugin shorthand.
"""
from __future__ import annotations

import ast
import dataclasses
from pathlib import Path
from typing import ClassVar

import numpy as np
import pytest
import sympy as sp

import contactlab
from contactlab.params import Param
from contactlab.profiles import (Cone, FlatPunch, Paraboloid, Polynomial, PowerLaw, Profile,
                                 Scaled, Sphere, Sum, Tabulated, TruncatedCone,
                                 TruncatedParaboloid)
from contactlab.symbolic import contact_formulas, profile_formulas
from contactlab.symbolic import formulas as formulas_module
from contactlab.symbolic.form import SympyForm, power_form, rational, symbol

SYMBOLIC = Path(contactlab.__file__).parent / "symbolic"

#: what contactlab/symbolic may import: itself and the layers below it
ALLOWED_BELOW = {"symbolic", "numeric", "params", "registry", "errors"}

BUILTINS = {
    "paraboloid": Paraboloid(R=0.01),
    "cone": Cone(slope=0.2),
    "power_law": PowerLaw(c=5e5, n=3),
    "polynomial": Polynomial({2: 50.0, 4: 1e5}),
    "sphere": Sphere(R=0.01),
    "flat_punch": FlatPunch(radius=1e-3),
    "truncated_paraboloid": TruncatedParaboloid(radius=1e-3, R=0.01),
    "truncated_cone": TruncatedCone(radius=1e-3, slope=0.1),
    "tabulated": Tabulated(np.linspace(0.0, 1e-3, 11), np.linspace(0.0, 1e-3, 11) ** 2),
    "sum": Paraboloid(R=0.01) + Sphere(R=0.02),
    "scaled": 2.0 * Sphere(R=0.01),
}

E, R, s, d, a = (symbol(n) for n in ("E_star", "R", "s", "d", "a"))


# ---------------------------------------------------------------------- plugin-style twins
class TwinParaboloid(Profile):
    """A paraboloid written as a plugin would: numeric height plus the sympy shorthand."""

    name: ClassVar[str] = "twin_paraboloid"
    params: ClassVar[tuple[Param, ...]] = (
        Param("R", "R", "m", "positive", "radius of curvature R", (1e-6, 1.0)),
    )

    def __init__(self, R: float) -> None:
        self.R = self.params[0].check(R)

    def _height(self, r: np.ndarray) -> np.ndarray:
        return r**2 / (2 * self.R)

    def _height_sympy(self, r, R):
        return r**2 / (2 * R)


class TwinCone(Profile):
    name: ClassVar[str] = "twin_cone"
    params: ClassVar[tuple[Param, ...]] = (
        Param("slope", "s", "1", "positive", "cone slope", (1e-4, 1e2)),
    )

    def __init__(self, slope: float) -> None:
        self.slope = self.params[0].check(slope)

    def _height(self, r: np.ndarray) -> np.ndarray:
        return self.slope * r

    def _height_sympy(self, r, slope):
        return slope * r


class TwinPolynomial(Profile):
    """A power sum that only lists its terms (``power_terms()``, the other plugin shorthand)."""

    name: ClassVar[str] = "twin_polynomial"
    params: ClassVar[tuple[Param, ...]] = ()

    def __init__(self, terms: tuple[tuple[float, float], ...]) -> None:
        self.terms = tuple(terms)

    def _param_values(self):
        return self.terms

    def power_terms(self) -> list[tuple[float, float]]:
        return list(self.terms)


class TransformOnly(Profile):
    """A paraboloid known to the formulas through its transform only (``_g_sympy``)."""

    name: ClassVar[str] = "transform_only"
    params: ClassVar[tuple[Param, ...]] = (
        Param("R", "R", "m", "positive", "radius of curvature R", (1e-6, 1.0)),
    )

    def __init__(self, R: float) -> None:
        self.R = self.params[0].check(R)

    def _height(self, r: np.ndarray) -> np.ndarray:
        return r**2 / (2 * self.R)

    def _g_sympy(self, x, R):
        return x**2 / R

    def _g_integral_sympy(self, a, R):
        return a**3 / (3 * R)


def assert_same_formulas(fs, ref):
    assert list(fs) == list(ref)
    for name in ref:
        assert fs[name] == ref[name], name          # structurally identical sympy trees
    assert fs.numbers == ref.numbers
    assert fs.unavailable == ref.unavailable


@pytest.mark.parametrize("twin, builtin", [
    (TwinParaboloid(R=0.01), Paraboloid(R=0.01)),
    (TwinCone(slope=0.2), Cone(slope=0.2)),
    (TwinPolynomial(((50.0, 2.0), (1e5, 4.0))), Polynomial({2: 50.0, 4: 1e5})),
], ids=["height_sympy-paraboloid", "height_sympy-cone", "power_terms-polynomial"])
def test_plugin_twin_gets_the_builtins_formulas(twin, builtin):
    assert "_sympy_form" not in type(twin).__dict__     # the twin uses the default hook
    assert_same_formulas(profile_formulas(twin), profile_formulas(builtin))
    assert_same_formulas(contact_formulas(twin), contact_formulas(builtin))


def test_plugin_twin_force_is_hertz():
    fs = contact_formulas(TwinParaboloid(R=0.01))
    hertz = sp.Rational(4, 3) * E * sp.sqrt(R) * d ** sp.Rational(3, 2)
    assert sp.simplify(fs["force_of_depth"] - hertz) == 0


def test_transform_only_plugin_gets_hertz_force_of_radius():
    fs = contact_formulas(TransformOnly(R=0.01))
    # F(a) = 2E*(a g(a) - ∫_0^a g) = 4 E* a³/(3R) (Hertz)
    assert sp.simplify(fs["force_of_radius"] - sp.Rational(4, 3) * E * a**3 / R) == 0
    assert "height" not in fs and "_g_sympy" in fs.unavailable["height"]


# ---------------------------------------------------------------------- built-ins use the hook
@pytest.mark.parametrize("cls", [Paraboloid, Cone, PowerLaw, Polynomial, Sphere, FlatPunch,
                                 TruncatedParaboloid, TruncatedCone, Tabulated, Sum, Scaled])
def test_every_builtin_declares_its_own_form(cls):
    assert "_sympy_form" in cls.__dict__


@pytest.mark.parametrize("key", sorted(BUILTINS))
def test_builtin_formulas_come_from_the_hook(key, monkeypatch):
    """Replace the hook of the profile's class by a spy: the formulas must be built from it."""
    profile = BUILTINS[key]
    cls = type(profile)
    original = cls._sympy_form
    calls = []

    def spy(self):
        calls.append(self)
        return original(self)

    monkeypatch.setattr(cls, "_sympy_form", spy)
    formulas_module._profile_formulas_cached.cache_clear()
    formulas_module._contact_formulas_cached.cache_clear()
    try:
        profile_formulas(profile)
        contact_formulas(profile)
    finally:
        formulas_module._profile_formulas_cached.cache_clear()
        formulas_module._contact_formulas_cached.cache_clear()
    assert calls and calls[0] is profile


def test_subclass_of_builtin_overrides_the_form():
    """A plugin subclassing a built-in changes its formulas through the same hook."""

    class ShallowSphere(Sphere):
        name: ClassVar[str] = "shallow_sphere"

        def _sympy_form(self) -> SympyForm:
            return dataclasses.replace(super()._sympy_form(), reason="declared by the subclass")

    fs = ShallowSphere(R=0.01).formulas()
    assert fs["g"] == Sphere(R=0.01).formulas()["g"]
    assert fs.unavailable["radius_of_depth"] == "declared by the subclass"


def test_symbolic_needs_only_the_hook():
    """Any object answering _sympy_form gets formulas: symbolic/ checks no class."""

    class Bare:
        def _sympy_form(self) -> SympyForm:
            return power_form([(1 / (2 * R), rational(2.0))], {R: 0.01})

    assert_same_formulas(contact_formulas(Bare()), contact_formulas(Paraboloid(R=0.01)))


def test_flat_punch_form_gives_boussinesq():
    fs = contact_formulas(FlatPunch(radius=1e-3))
    b = symbol("b")
    assert sp.simplify(fs["force_of_depth"] - 2 * E * b * d) == 0


def test_sum_reasons_follow_the_terms():
    """Reasons of a sum are joined in term order (not set order, which varies per process)."""
    sphere, cone = Sphere(R=0.01), TruncatedCone(radius=1e-3, slope=0.1)
    why = (sphere + cone).formulas().unavailable["radius_of_depth"]
    why_reversed = (cone + sphere).formulas().unavailable["radius_of_depth"]
    assert why.startswith("the exact sphere") and "truncated cone" in why
    assert why_reversed.startswith("a truncated cone") and "exact sphere" in why_reversed


# ---------------------------------------------------------------------- layering
def _imported_modules(path: Path) -> list[tuple[int, str]]:
    """``(line, absolute module)`` of every import in ``path``, at any depth (lazy ones too)."""
    package = ["contactlab", "symbolic"]
    tree = ast.parse(path.read_text(encoding="utf-8"), filename=str(path))
    out = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            out += [(node.lineno, alias.name) for alias in node.names]
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package[: len(package) - node.level + 1]
                mod = ".".join(base + ([node.module] if node.module else []))
                # "from .. import x" names submodules of the base package
                names = [mod] if node.module else [f"{mod}.{al.name}" for al in node.names]
                out += [(node.lineno, m) for m in names]
            else:
                out.append((node.lineno, node.module or ""))
        elif isinstance(node, ast.Call):
            fn = node.func
            called = fn.attr if isinstance(fn, ast.Attribute) else getattr(fn, "id", "")
            if called in ("import_module", "__import__"):
                out.append((node.lineno, "<dynamic import>"))
    return out


def test_symbolic_imports_nothing_above_it():
    files = sorted(SYMBOLIC.glob("*.py"))
    assert {f.name for f in files} >= {"formulas.py", "form.py", "transform.py", "export.py"}
    bad = []
    for f in files:
        for line, mod in _imported_modules(f):
            parts = mod.split(".")
            if mod == "<dynamic import>" or mod == "contactlab" or (
                    parts[0] == "contactlab" and parts[1] not in ALLOWED_BELOW):
                bad.append(f"{f.name}:{line} imports {mod}")
    assert not bad, bad


def test_import_walker_sees_lazy_and_relative_imports(tmp_path):
    """The walker must catch what the layering forbids (a check that cannot fail is no check)."""
    src = tmp_path / "probe.py"
    src.write_text("def f():\n    from ..profiles import Cone\n    from .. import materials\n"
                   "    import contactlab.contact\n    from . import form\n", encoding="utf-8")
    mods = [m for _, m in _imported_modules(src)]
    assert mods == ["contactlab.profiles", "contactlab.materials", "contactlab.contact",
                    "contactlab.symbolic.form"]
