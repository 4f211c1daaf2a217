"""Every registered profile and material type (built-in and the example plugin's) passes the
public conformance mixins of :mod:`contactlab.testing`.

A type gets its instance from the table below when its parameters are not scalars with a
typical range (tables, term lists, Prony series), otherwise from ``typical_instance`` (the
centre of each ``Param.typical``). A newly registered type without either fails
``test_every_registered_type_is_covered``.
"""
from __future__ import annotations

import importlib.util

import numpy as np
import pytest

import contactlab as cl
from contactlab.materials.viscoelastic import GeneralizedMaxwell
from contactlab.profiles import Paraboloid, Polynomial, Tabulated
from contactlab.registry import registry
from contactlab.testing import MaterialChecks, ProfileChecks, typical_instance

_R_TAB = np.linspace(0.0, 2e-4, 401)

#: hand-written typical instances (non-scalar parameters)
PROFILE_TABLE = {
    "polynomial": Polynomial({1.5: 3.0, 2: 50.0, 4: 1e6}),
    # samples of a paraboloid R = 1 mm: the cubic spline is smooth, the linear table has kinks
    # at every node (declared as breakpoints, so the independent quadrature splits there)
    "tabulated": Tabulated(_R_TAB, Paraboloid(R=1e-3).height(_R_TAB), interpolation="cubic"),
}
MATERIAL_TABLE = {
    "generalized_maxwell": GeneralizedMaxwell(G_inf=1e5, moduli=[2e5, 3e5],
                                              relaxation_times=[0.1, 2.0]),
}
#: extra instances beyond one per type
EXTRA_PROFILES = {
    "tabulated_linear": Tabulated(_R_TAB, Paraboloid(R=1e-3).height(_R_TAB)),
}


def _instance(kind, name, table):
    return table[name] if name in table else typical_instance(registry.get(kind, name))


PROFILES = {n: _instance("profile", n, PROFILE_TABLE) for n in registry.available("profile")}
PROFILES.update(EXTRA_PROFILES)
MATERIALS = {n: _instance("material", n, MATERIAL_TABLE) for n in registry.available("material")}


def test_every_registered_type_is_covered():
    assert set(registry.available("profile")) <= set(PROFILES)
    assert set(registry.available("material")) <= set(MATERIALS)


@pytest.mark.skipif(importlib.util.find_spec("contactlab_example_plugin") is None,
                    reason="install with: pip install ./tests/plugins/contactlab_example_plugin")
def test_the_example_plugin_takes_part():
    assert {"quartic", "rounded_cone"} <= set(PROFILES) and "incompressible" in MATERIALS


@pytest.fixture(params=sorted(PROFILES), ids=str)
def _profile_name(request):
    return request.param


class TestRegisteredProfiles(ProfileChecks):
    """The mixin run once per registered profile type (parametrised through ``make_profile``)."""

    @pytest.fixture(autouse=True)
    def _select(self, _profile_name):
        self._name = _profile_name

    def make_profile(self):
        return PROFILES[self._name]


@pytest.fixture(params=sorted(MATERIALS), ids=str)
def _material_name(request):
    return request.param


class TestRegisteredMaterials(MaterialChecks):
    """The mixin run once per registered material type."""

    @pytest.fixture(autouse=True)
    def _select(self, _material_name):
        self._name = _material_name

    def make_material(self):
        return MATERIALS[self._name]


# ---- the mixins can fail: a broken profile and a broken material are caught
class _Dented(Paraboloid):
    """A paraboloid whose g is off by 1e-6 (what a wrong transform hook would give)."""

    def _g_closed_form(self, x):
        return super()._g_closed_form(x) * (1 + 1e-6)


@pytest.mark.parametrize("check", ["test_g_matches_independent_quadrature",
                                   "test_inverse_transform_round_trip"])
def test_profile_checks_catch_a_wrong_transform(check):
    class Broken(ProfileChecks):
        profile = _Dented(R=1e-3)

    with pytest.raises(AssertionError):
        getattr(Broken(), check)()


def test_material_checks_catch_an_unchecked_parameter():
    class Lax(cl.Elastic):
        def __init__(self, E, nu):
            self.E, self.nu = E, nu          # no validation

    class Broken(MaterialChecks):
        material = Lax(E=1e9, nu=0.3)

    with pytest.raises(AssertionError, match="did not raise ParameterError"):
        Broken().test_bad_parameters_raise()
