"""The plugin registry: built-ins, decorators, entry-point discovery (fabricated and real)."""
from __future__ import annotations

import copy
import subprocess
import sys
from importlib import metadata
from pathlib import Path
from types import SimpleNamespace
from typing import ClassVar

import numpy as np
import pytest

import contactlab as cl
from contactlab.errors import ParameterError, PluginError, PluginWarning, UnknownNameError
from contactlab.materials import Material
from contactlab.params import Param
from contactlab.profiles import Cone, Paraboloid, PowerLaw, Profile
from contactlab.registry import DISABLE_ENV, Registry, register_material, register_profile, registry
from tests import tolerances as TOL
from tests.tolerances import CLOSED_FORM, HEIGHT_ONLY_PROFILE

PLUGIN_DIR = Path(__file__).resolve().parents[2] / "plugins" / "contactlab_example_plugin"
PROFILES = "contactlab.profiles"
MATERIALS = "contactlab.materials"


@pytest.fixture
def plugin_path(monkeypatch):
    """The example plugin importable from its source directory (not installed)."""
    monkeypatch.syspath_prepend(str(PLUGIN_DIR))
    yield
    for mod in [m for m in sys.modules if m.startswith("contactlab_example_plugin")]:
        del sys.modules[mod]


@pytest.fixture
def session_registry():
    """Restore the global registry's session table after a test."""
    saved = copy.deepcopy(registry._session)
    yield registry
    registry._session = saved


def ep(name, value, group=PROFILES, dist="contactlab-example-plugin"):
    e = metadata.EntryPoint(name=name, value=value, group=group)
    return e._for(SimpleNamespace(name=dist)) or e


def fresh(eps):
    reg = Registry()
    reg._iter_entry_points = lambda group: [e for e in eps if e.group == group]
    return reg


# ---------------------------------------------------------------------- built-ins
def test_builtins_registered_by_name_and_class():
    assert {"paraboloid", "cone", "power_law", "sphere", "flat_punch", "tabulated",
            "truncated_paraboloid", "truncated_cone", "polynomial"} <= set(registry.available("profile"))
    assert {"elastic", "rigid"} <= set(registry.available("material"))
    assert registry.get("profile", "paraboloid") is Paraboloid
    assert registry.get("profile", Paraboloid) is Paraboloid
    assert registry.name_of(Cone(slope=0.1)) == "cone"
    assert registry.sources("profile")["paraboloid"] == "built-in"


def test_builtins_registered_at_first_use_in_a_fresh_interpreter():
    """``import contactlab`` registers nothing (start-up time); the first lookup of a kind does,
    and a session class cannot take a built-in name even before any lookup."""
    code = ("from typing import ClassVar\n"
            "import contactlab\n"
            "from contactlab.errors import PluginError\n"
            "from contactlab.registry import register_profile, registry\n"
            "assert not registry._builtin['profile'] and not registry._builtin['material']\n"
            "class Mine(contactlab.profiles.Paraboloid):\n"
            "    name: ClassVar[str] = 'paraboloid'\n"
            "try:\n"
            "    register_profile(Mine)\n"
            "except PluginError as err:\n"
            "    assert 'cannot be shadowed' in str(err)\n"
            "else:\n"
            "    raise AssertionError('a session class shadowed a built-in')\n"
            "assert registry.get('material', 'kelvin_voigt').__name__ == 'KelvinVoigt'\n")
    subprocess.run([sys.executable, "-c", code], check=True, capture_output=True, text=True)


def test_fresh_registry_rejects_shadowing_before_any_lookup():
    reg = fresh([])

    class MyCone(Cone):
        name: ClassVar[str] = "cone"

    with pytest.raises(PluginError, match="cannot be shadowed"):
        reg.register(MyCone, "profile")
    assert reg.get("profile", "cone") is Cone


def test_concurrent_first_lookup_sees_every_builtin(tmp_path, monkeypatch):
    """The built-ins of a kind register under a lock: a lookup that starts while another thread
    is registering them waits for the whole table instead of reading half of it."""
    import threading
    import time
    from contactlab.registry import KindSpec
    (tmp_path / "slow_builtins.py").write_text(
        "import time\n"
        "from typing import ClassVar\n"
        "from contactlab.profiles import Paraboloid\n"
        "class First(Paraboloid):\n"
        "    name: ClassVar[str] = 'first'\n"
        "class Second(Paraboloid):\n"
        "    name: ClassVar[str] = 'second'\n"
        "def register(reg):\n"
        "    reg.register(First, 'extra', builtin=True)\n"
        "    time.sleep(0.3)\n"
        "    reg.register(Second, 'extra', builtin=True)\n")
    monkeypatch.syspath_prepend(str(tmp_path))
    reg = fresh([])
    reg.add_kind("extra", KindSpec("contactlab.profiles.base:Profile", "contactlab.extra",
                                   "slow_builtins:register"))
    first = threading.Thread(target=reg.get, args=("extra", "first"))
    first.start()
    time.sleep(0.1)                      # the first thread is inside the registration now
    try:
        assert reg.get("extra", "second").__name__ == "Second"
    finally:
        first.join()
        sys.modules.pop("slow_builtins", None)


def test_create_builds_and_validates():
    assert registry.create("profile", "paraboloid", R=0.01) == Paraboloid(R=0.01)
    assert registry.create("material", "elastic", E=1e9, nu=0.3) == cl.Elastic(E=1e9, nu=0.3)
    with pytest.raises(ParameterError, match="Did you mean 'R'"):
        registry.create("profile", "paraboloid", r=0.01)
    with pytest.raises(ParameterError, match="needs R"):
        registry.create("profile", "paraboloid")
    with pytest.raises(ParameterError, match="R=-1"):
        registry.create("profile", "paraboloid", R=-1)


def test_unknown_name_lists_available_and_close_matches():
    with pytest.raises(UnknownNameError, match=r"Did you mean 'paraboloid'.*Available: .*cone"):
        registry.get("profile", "parabolid")
    with pytest.raises(UnknownNameError, match="kind='profil'.*'profile'"):
        registry.get("profil", "cone")

    class Unregistered(Paraboloid):
        name: ClassVar[str] = "unregistered"

    with pytest.raises(UnknownNameError, match="not a registered profile"):
        registry.get("profile", Unregistered)
    with pytest.raises(UnknownNameError, match="name 3 is invalid"):
        registry.get("profile", 3)


def test_import_contactlab_scans_no_plugins_and_no_sympy():
    code = ("import sys, contactlab; from contactlab.registry import registry; "
            "assert registry._plugins is None; assert 'sympy' not in sys.modules; print('ok')")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         cwd=Path(cl.__file__).parents[1], check=False)
    assert out.stdout.strip() == "ok", out.stderr


# ---------------------------------------------------------------------- validation rules
def test_rule_subclass_of_kind_base(session_registry):
    class NotAProfile:
        name = "not_a_profile"

    with pytest.raises(PluginError, match="subclass"):
        registry.register(NotAProfile, "profile")


def test_rule_name_pattern(session_registry):
    class BadName(Paraboloid):
        name: ClassVar[str] = "Bad-Name"

    with pytest.raises(PluginError, match=r"name pattern"):
        register_profile(BadName)


def test_rule_explicit_signature(session_registry):
    class Variadic(Paraboloid):
        name: ClassVar[str] = "variadic"

        def __init__(self, *args, **kwargs):
            super().__init__(*args, **kwargs)

    with pytest.raises(PluginError, match=r"no \*args/\*\*kwargs"):
        register_profile(Variadic)


def test_rule_params_in_signature(session_registry):
    class Hidden(Paraboloid):
        name: ClassVar[str] = "hidden"

        def __init__(self) -> None:
            super().__init__(R=1.0)

    with pytest.raises(PluginError, match="declares params R"):
        register_profile(Hidden)


def test_rule_profile_contract_checked_at_class_definition():
    with pytest.raises(PluginError, match="must implement one of"):
        class NoHooks(Profile):
            name: ClassVar[str] = "no_hooks"


# ---------------------------------------------------------------------- decorators
def test_decorators_register_for_the_session(session_registry):
    @register_profile
    class Bump(Profile):
        """f = h r⁶ (session-only example)."""

        name: ClassVar[str] = "bump"
        params: ClassVar[tuple[Param, ...]] = (Param("h", "h", "m^-5", "positive", "h"),)

        def __init__(self, h: float) -> None:
            self.h = self.params[0].check(h)

        def power_terms(self):
            return [(self.h, 6.0)]

    @register_material
    class Stiff(Material):
        name: ClassVar[str] = "stiff"
        params: ClassVar[tuple[Param, ...]] = ()

        def _compliances(self):
            return (1e-12, 1e-12, 1e-12)

    assert registry.get("profile", "bump") is Bump
    assert registry.sources("profile")["bump"] == "session"
    assert registry.create("profile", "bump", h=2.0).g(1.0) == pytest.approx(2 * 1.0 * 16 / 5, rel=TOL.SHORT_ARITHMETIC)
    assert registry.get("material", "stiff") is Stiff
    registry.unregister("profile", "bump")
    with pytest.raises(UnknownNameError):
        registry.get("profile", "bump")


def test_builtin_names_cannot_be_shadowed(session_registry):
    class MyParaboloid(Paraboloid):
        name: ClassVar[str] = "paraboloid"

    with pytest.raises(PluginError, match="cannot be shadowed"):
        register_profile(MyParaboloid)


def test_duplicate_session_name_warns_first_wins(session_registry):
    def make():
        class Twin(Paraboloid):
            name: ClassVar[str] = "twin"
        return Twin

    first, second = make(), make()
    second.__qualname__ = "OtherTwin"
    register_profile(first)
    with pytest.warns(PluginWarning, match="first is kept"):
        register_profile(second)
    assert registry.get("profile", "twin") is first


# ---------------------------------------------------------------------- entry points (fabricated)
def test_discovery_of_fabricated_entry_points(plugin_path):
    reg = fresh([ep("quartic", "contactlab_example_plugin:Quartic"),
                 ep("rounded_cone", "contactlab_example_plugin:RoundedCone"),
                 ep("incompressible", "contactlab_example_plugin:Incompressible", MATERIALS)])
    assert {"quartic", "rounded_cone"} <= set(reg.available("profile"))
    assert "incompressible" in reg.available("material")
    assert reg.sources("profile")["quartic"] == "contactlab-example-plugin"
    q = reg.create("profile", "quartic", c=1e9)
    assert type(q).__name__ == "Quartic"
    with pytest.raises(UnknownNameError, match=r"quartic \[contactlab-example-plugin\]"):
        reg.get("profile", "quartc")


def test_discovery_is_lazy_and_cached(plugin_path):
    calls = []
    reg = Registry()

    def it(group):
        calls.append(group)
        return [ep("quartic", "contactlab_example_plugin:Quartic")] if group == PROFILES else []

    reg._iter_entry_points = it
    assert reg.get("profile", "paraboloid") is Paraboloid      # known name: no scan
    assert calls == []
    reg.get("profile", "quartic")
    reg.get("profile", "quartic")
    reg.available("profile")
    assert calls.count(PROFILES) == 1
    reg.refresh()
    reg.available("profile")
    assert calls.count(PROFILES) == 2


def test_broken_entry_point_warns_and_is_skipped(plugin_path):
    reg = fresh([ep("missing", "no_such_module_xyz:Thing"),
                 ep("quartic", "contactlab_example_plugin:Quartic")])
    with pytest.warns(PluginWarning, match=r"missing.*no_such_module_xyz.*ModuleNotFoundError"):
        names = reg.available("profile")
    assert "quartic" in names and "missing" not in names


def test_entry_point_breaking_a_rule_warns(plugin_path):
    reg = fresh([ep("incompressible", "contactlab_example_plugin:Incompressible")])  # wrong kind
    with pytest.warns(PluginWarning, match="not a subclass of Profile"):
        assert "incompressible" not in reg.available("profile")


def test_entry_point_name_must_match_class_name(plugin_path):
    reg = fresh([ep("quart", "contactlab_example_plugin:Quartic")])
    with pytest.warns(PluginWarning, match="differs from the entry-point name"):
        assert "quart" not in reg.available("profile")


def test_entry_point_cannot_shadow_builtin(plugin_path):
    reg = fresh([ep("paraboloid", "contactlab.profiles:Paraboloid", dist="evil")])
    with pytest.warns(PluginWarning, match="built-in profile name"):
        reg.available("profile")
    assert reg.get("profile", "paraboloid") is Paraboloid


def test_duplicate_entry_points_first_distribution_wins(plugin_path):
    import contactlab_example_plugin as plug

    class OtherQuartic(plug.Quartic):
        pass

    plug.OtherQuartic = OtherQuartic
    reg = fresh([ep("quartic", "contactlab_example_plugin:OtherQuartic", dist="zz-late"),
                 ep("quartic", "contactlab_example_plugin:Quartic", dist="aa-early")])
    with pytest.warns(PluginWarning, match="already provided.*aa-early"):
        assert reg.get("profile", "quartic") is plug.Quartic


def test_disable_plugins_by_name(plugin_path, monkeypatch):
    monkeypatch.setenv(DISABLE_ENV, "quartic, other")
    reg = fresh([ep("quartic", "contactlab_example_plugin:Quartic"),
                 ep("rounded_cone", "contactlab_example_plugin:RoundedCone")])
    assert "quartic" not in reg.available("profile")
    assert "rounded_cone" in reg.available("profile")
    monkeypatch.setenv(DISABLE_ENV, "contactlab-example-plugin")    # or by distribution
    reg.refresh()
    assert "rounded_cone" not in reg.available("profile")


def test_entry_point_listing_failure_never_breaks(monkeypatch):
    reg = Registry()

    def boom(group):
        raise RuntimeError("corrupt metadata")

    reg._iter_entry_points = boom
    with pytest.warns(PluginWarning, match="corrupt metadata"):
        assert "paraboloid" in reg.available("profile")


# ---------------------------------------------------------------------- plugin behaviour
def test_height_only_plugin_gets_normal_contact_for_free(plugin_path):
    from contactlab_example_plugin import Quartic
    mats = (cl.Elastic(E=1e9, nu=0.3), cl.Rigid())
    plug, ref = cl.Contact(Quartic(c=1e9), mats), cl.Contact(PowerLaw(c=1e9, n=4), mats)
    assert plug.profile.available_strategies() == ("quadrature",)
    d = np.array([1e-8, 1e-7, 1e-6])
    s1, s2 = plug.normal(depth=d), ref.normal(depth=d)
    np.testing.assert_allclose(s1.radius, s2.radius, rtol=HEIGHT_ONLY_PROFILE)
    np.testing.assert_allclose(s1.force, s2.force, rtol=HEIGHT_ONLY_PROFILE)
    r = np.array([0.1, 0.5, 0.9]) * float(s2.radius[-1])
    np.testing.assert_allclose(s1.pressure(r)[-1], s2.pressure(r)[-1], rtol=HEIGHT_ONLY_PROFILE)
    f1 = plug.normal(force=s2.force)
    np.testing.assert_allclose(f1.depth, d, rtol=HEIGHT_ONLY_PROFILE)
    with pytest.raises(Exception, match="no symbolic form"):
        Quartic(c=1e9).formulas()["g"]


def test_symbolic_plugin_gets_formulas(plugin_path):
    from contactlab_example_plugin import RoundedCone
    prof = RoundedCone(slope=0.1, R=0.01)
    assert prof.g_route == "symbolic"
    ref = Paraboloid(R=0.01) + Cone(slope=0.1)
    x = np.array([1e-5, 1e-4, 1e-3])
    np.testing.assert_allclose(prof.g(x), ref.g(x), rtol=CLOSED_FORM)
    fs = prof.formulas()
    assert {str(s) for s in fs["g"].free_symbols} == {"x", "s", "R"}
    mats = (cl.Elastic(E=1e9, nu=0.3), cl.Rigid())
    c = cl.Contact(prof, mats)
    a = np.array([1e-4, 5e-4])
    np.testing.assert_allclose(c.formulas().callable("force_of_radius")(a),
                               cl.Contact(ref, mats).normal(radius=a).force, rtol=CLOSED_FORM)


def test_plugin_material(plugin_path):
    from contactlab_example_plugin import Incompressible
    m = Incompressible(G=1e6)
    ref = cl.Elastic(E=3e6, nu=0.5)
    got, want = cl.effective_moduli(m, cl.Rigid()), cl.effective_moduli(ref, cl.Rigid())
    assert got.normal == pytest.approx(4e6, rel=TOL.ULPS) == want.normal
    assert got.torsional == pytest.approx(want.torsional, rel=TOL.ULPS)
    assert got.tangential == pytest.approx(want.tangential, rel=TOL.ULPS)


# ---------------------------------------------------------------------- installed plugin
def test_installed_example_plugin_through_real_entry_points():
    try:
        metadata.distribution("contactlab-example-plugin")
    except metadata.PackageNotFoundError:
        pytest.skip("install with: pip install ./tests/plugins/contactlab_example_plugin")
    reg = Registry()
    assert reg.sources("profile")["quartic"] == "contactlab-example-plugin"
    assert reg.create("profile", "rounded_cone", slope=0.1, R=0.01).g_route == "symbolic"
    assert "incompressible" in reg.available("material")
