"""``import contactlab`` loads no heavy module it does not need at once (issue: start-up time).

scipy.special alone costs ~0.1 s of import; sympy, matplotlib, pandas and dask more. Each is
imported on first use inside the function that needs it. Run in a fresh interpreter so that
nothing this test session imported earlier can hide a regression.
"""
from __future__ import annotations

import importlib
import json
import subprocess
import sys

import numpy as np
import pytest

HEAVY = ("scipy.special", "scipy.integrate", "sympy", "matplotlib", "pandas", "pyarrow",
         "xarray", "dask", "distributed", "tqdm", "contactlab.sweeps", "multiprocessing",
         "concurrent.futures", "pint", "contactlab.numeric.units")


#: contactlab's own modules that ``import contactlab`` leaves for their first use (together
#: ~0.03 s): the effect drivers, the physics kernels, foundations, load paths, citations and the
#: viscoelastic materials (loaded when the registry registers its built-ins)
LAZY_OWN = ("contactlab.effects.normal", "contactlab.effects.adhesion",
            "contactlab.effects.tangential", "contactlab.effects.torsion",
            "contactlab.effects.viscoelastic", "contactlab.effects.path",
            "contactlab.effects.fretting", "contactlab.effects.wear", "contactlab.effects.law",
            "contactlab.physics", "contactlab.foundation", "contactlab.loadpath",
            "contactlab.citations", "contactlab.materials.viscoelastic",
            "contactlab.profiles.tabulated", "contactlab.fit")
#: standard-library modules contactlab uses only on error paths or for one debug line; checked
#: only where ``import numpy`` does not load them itself
LAZY_STDLIB = ("logging", "difflib")


def _loaded(code: str, modules: tuple[str, ...]) -> set[str]:
    """Which of ``modules`` a fresh interpreter has loaded after running ``code``."""
    probe = (f"import json, sys; {code}; "
             f"print(json.dumps([m for m in {list(modules)!r} if m in sys.modules]))")
    out = subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True, check=True)
    return set(json.loads(out.stdout.strip().splitlines()[-1]))


@pytest.fixture(scope="module")
def loaded_after_import() -> set[str]:
    return _loaded("import contactlab", HEAVY + LAZY_OWN + LAZY_STDLIB)


@pytest.mark.parametrize("module", HEAVY)
def test_heavy_module_not_imported_with_contactlab(loaded_after_import: set[str], module: str) -> None:
    assert module not in loaded_after_import, f"import contactlab loads {module}"


@pytest.mark.parametrize("module", LAZY_OWN)
def test_own_module_loaded_on_first_use_only(loaded_after_import: set[str], module: str) -> None:
    assert module not in loaded_after_import, f"import contactlab loads {module}"


@pytest.mark.parametrize("module", LAZY_STDLIB)
def test_stdlib_module_not_imported_with_contactlab(loaded_after_import: set[str],
                                                   module: str) -> None:
    if module in _loaded("import numpy", (module,)):
        pytest.skip(f"numpy itself imports {module}")
    assert module not in loaded_after_import, f"import contactlab loads {module}"


def test_first_normal_call_loads_its_driver_only() -> None:
    """Each effect driver loads on its own first use: a normal solve brings no torsion/path."""
    code = ("import contactlab as cl; c = cl.Contact(cl.profiles.Paraboloid(R=0.01), "
            "materials=(cl.Elastic(E=210e9, nu=0.3), cl.Rigid())); "
            "assert isinstance(c.normal(force=100.0), cl.NormalState)")
    loaded = _loaded(code, LAZY_OWN + ("scipy.special", "scipy"))
    assert "contactlab.effects.normal" in loaded
    assert not loaded & {"contactlab.effects.torsion", "contactlab.effects.path",
                         "contactlab.effects.fretting", "contactlab.foundation",
                         "contactlab.loadpath"}
    # κ_n of a power-law profile comes from the standard library: a first Hertz solve does not
    # wait ~0.1 s for scipy to import
    assert not loaded & {"scipy.special", "scipy"}


#: every lazily resolved top-level name -> the module that defines it (as imported eagerly before)
TOP_LEVEL_HOMES = {
    "NormalState": "contactlab.effects.normal", "AdhesiveNormalState": "contactlab.effects.adhesion",
    "AdhesionCycle": "contactlab.effects.adhesion",
    "ViscoelasticHistory": "contactlab.effects.viscoelastic",
    "TangentialState": "contactlab.effects.tangential",
    "ShiftHistory": "contactlab.effects.tangential", "PathResult": "contactlab.effects.path",
    "TorsionState": "contactlab.effects.torsion", "TwistHistory": "contactlab.effects.torsion",
    "ContactLaw": "contactlab.effects.law", "LawStep": "contactlab.effects.law",
    "LoadPath": "contactlab.loadpath.base", "cite": "contactlab.citations",
    "sweep": "contactlab.sweeps.run", "fretting_map_sweep": "contactlab.sweeps.fretting",
}
TOP_LEVEL_SUBPACKAGES = ("citations", "foundation", "loadpath")


@pytest.mark.parametrize("name", sorted(TOP_LEVEL_HOMES))
def test_lazy_top_level_name_is_the_defining_modules_object(name: str) -> None:
    import contactlab
    home = importlib.import_module(TOP_LEVEL_HOMES[name])
    assert getattr(contactlab, name) is getattr(home, name)
    assert name in dir(contactlab) and name in contactlab.__all__


@pytest.mark.parametrize("name", TOP_LEVEL_SUBPACKAGES)
def test_lazy_subpackage_is_the_module(name: str) -> None:
    import contactlab
    assert getattr(contactlab, name) is importlib.import_module(f"contactlab.{name}")
    assert name in dir(contactlab) and name in contactlab.__all__


def test_every_public_name_resolves_in_a_fresh_interpreter() -> None:
    """``from contactlab import *`` (every name of ``__all__``) works before anything else ran."""
    code = ("import contactlab; from contactlab import *; "
            "missing = [n for n in contactlab.__all__ if n not in globals()]; "
            "assert not missing, missing; assert set(contactlab.__all__) <= set(dir(contactlab))")
    subprocess.run([sys.executable, "-c", code], check=True, capture_output=True)


def test_tabulated_profile_resolves_lazily() -> None:
    from contactlab import profiles
    from contactlab.profiles.tabulated import Tabulated
    assert profiles.Tabulated is Tabulated and "Tabulated" in profiles.__all__
    assert "Tabulated" in dir(profiles)
    from contactlab.registry import registry
    assert registry.get("profile", "tabulated") is Tabulated
    with pytest.raises(AttributeError, match="no_such_name"):
        profiles.no_such_name


def test_effects_package_names_are_the_defining_modules_objects() -> None:
    from contactlab import effects
    for name in effects.__all__:
        value = getattr(effects, name)
        assert value is getattr(importlib.import_module(value.__module__), name)
        assert value.__module__.startswith("contactlab.effects.") and name in dir(effects)
    with pytest.raises(AttributeError, match="no_such_name"):
        effects.no_such_name


def test_contact_module_still_exports_its_result_classes() -> None:
    """Names ``contactlab.contact`` imported eagerly before stay importable from it."""
    from contactlab import contact
    from contactlab.effects.normal import NormalState
    from contactlab.effects.wear import WearResult
    assert contact.NormalState is NormalState and contact.WearResult is WearResult
    from contactlab.contact import FrettingMap, TwistHistory    # noqa: F401 (import works)
    with pytest.raises(AttributeError, match="no_such_name"):
        contact.no_such_name


def test_lazy_top_level_names_resolve() -> None:
    import contactlab
    from contactlab import sweeps
    assert contactlab.sweep is sweeps.sweep
    assert contactlab.fretting_map_sweep is sweeps.fretting_map_sweep
    assert {"sweep", "fretting_map_sweep"} <= set(dir(contactlab))
    with pytest.raises(AttributeError, match="no_such_name"):
        contactlab.no_such_name


def test_wear_operators_import_scipy_special_on_first_use() -> None:
    """The lazily imported ``ellipk`` still serves the wear operators (not a stubbed import)."""
    from contactlab.physics import wear
    ops = wear.operators(1e-3, 8)
    assert ops and all(np.all(np.isfinite(np.asarray(v, float))) for v in ops.values())


#: package faces that resolve names lazily and ship a ``.pyi`` stub listing them
STUBBED = ("contactlab", "contactlab.effects", "contactlab.profiles")


def _stub_names(module: str) -> tuple[set[str], list[str]]:
    """Names a package's ``__init__.pyi`` binds (imports, defs) and its ``__all__``."""
    import ast
    from pathlib import Path
    mod = importlib.import_module(module)
    tree = ast.parse((Path(mod.__file__).parent / "__init__.pyi").read_text(encoding="utf-8"))
    bound: set[str] = set()
    all_: list[str] = []
    for node in tree.body:
        if isinstance(node, ast.ImportFrom):
            bound |= {a.asname or a.name for a in node.names}
        elif isinstance(node, ast.FunctionDef):
            bound.add(node.name)
        elif isinstance(node, ast.Assign) and node.targets[0].id == "__all__":  # type: ignore[attr-defined]
            all_ = ast.literal_eval(node.value)
    return bound, all_


@pytest.mark.parametrize("module", STUBBED)
def test_stub_lists_the_runtime_names(module: str) -> None:
    """The ``.pyi`` stub (what type checkers and IDEs see) and the lazy runtime agree: the same
    ``__all__``, every name the stub binds resolves at run time, and every lazily resolved name
    is in the stub."""
    mod = importlib.import_module(module)
    bound, all_ = _stub_names(module)
    assert all_ == list(mod.__all__)
    assert set(mod.__all__) <= bound
    assert set(mod._LAZY) <= bound, sorted(set(mod._LAZY) - bound)
    for name in sorted(bound):
        assert getattr(mod, name) is not None, name
