"""Every result type follows the result protocol (issue 27): the public conformance mixin
:class:`contactlab.testing.ResultChecks` runs over one instance of each type (approximate routes
too), and a type found by :func:`contactlab.testing.result_types` without an entry here fails
``test_every_result_type_is_covered``.

The model errors of the approximate routes are checked against the exact routes in
tests/unit/effects/test_model_error.py.
"""
from __future__ import annotations

import numpy as np
import pytest

import contactlab as cl
from contactlab.effects._protocol import Result
from contactlab.materials.viscoelastic import Maxwell
from contactlab.testing import ResultChecks, result_types

STEEL = cl.Elastic(E=210e9, nu=0.3)
HERTZ = cl.Contact(cl.profiles.Paraboloid(R=0.01), materials=(STEEL, STEEL), friction=0.3)
TWIST = 2e-3 * np.sin(np.linspace(0.0, 4 * np.pi, 41))


def _path():
    return cl.LoadPath().ramp(force=100.0, steps=10).sinusoid(twist=1e-3, cycles=1,
                                                             steps_per_cycle=40)


def _law_step():
    law = cl.ContactLaw(cl.profiles.Paraboloid, R=np.full(3, 0.01), E_star=115e9,
                        G_star=40e9, G_torsion=40e9, friction=0.3)
    law.step(depth=np.full(3, 1e-6), twist=np.zeros(3))
    law.step(depth=np.full(3, 1e-6), twist=np.full(3, 1e-4))
    return law.step(depth=np.full(3, 1.2e-6), twist=np.full(3, 3e-4))   # load changes: springs


def _scene():
    from contactlab.cli import DEMO_SCENE
    from contactlab.scene import Scene
    return Scene.loads(DEMO_SCENE.replace('method = "exact"', 'method = "mdr"')).run()


class TestNormalState(ResultChecks):
    exact = True

    def make_result(self):
        return HERTZ.normal(force=[1.0, 10.0, 100.0])


class TestAdhesiveNormalState(ResultChecks):
    exact = True

    def make_result(self):
        c = cl.Contact(cl.profiles.Paraboloid(R=0.01), materials=(STEEL, STEEL),
                       work_of_adhesion=0.1)
        return c.normal(force=[0.0, 1.0])


class TestAdhesionCycle(ResultChecks):
    exact, plots = True, True

    def make_result(self):
        c = cl.Contact(cl.profiles.Paraboloid(R=0.01), materials=(STEEL, STEEL),
                       work_of_adhesion=0.1)
        d = 1e-7 * np.concatenate([np.linspace(-1, 2, 20), np.linspace(2, -3, 30)])
        return c.adhesion_cycle(depth=d)


class TestTangentialState(ResultChecks):
    exact = True

    def make_result(self):
        return HERTZ.tangential(force=100.0, displacement=[1e-7, 5e-7])


class TestStressField(ResultChecks):
    exact, plots = True, True

    def make_result(self):
        return HERTZ.normal(force=100.0).stress_field(grid=(np.linspace(0, 2e-4, 5),
                                                            np.linspace(0, 1e-4, 3)))


class TestStressMaximum(ResultChecks):
    exact = True

    def make_result(self):
        return HERTZ.normal(force=100.0).max_stress("max_shear")


class TestCartesianStressField(ResultChecks):
    exact, plots = True, True

    def make_result(self):
        s = HERTZ.tangential(force=100.0, tangential_force=10.0)
        return s.stress_field(grid=(np.linspace(-2e-4, 2e-4, 5), np.linspace(0, 1e-4, 3)))


class TestFrettingFatigue(ResultChecks):
    exact = True

    def make_result(self):
        loop = HERTZ.fretting_loop(force=100.0, displacement_amplitude=1e-7)
        return loop.fatigue(n_phases=4)


class TestShiftHistory(ResultChecks):
    exact, plots = True, True

    def make_result(self):
        return HERTZ.shift_history(force=100.0, displacement=1e-6 * np.sin(np.linspace(0, 7, 30)))


class TestTorsionStateExact(ResultChecks):
    exact = True

    def make_result(self):
        return HERTZ.torsion(force=100.0, twist=[1e-4, 1e-3])


class TestTorsionStateMDR(ResultChecks):
    exact = False

    def make_result(self):
        return HERTZ.torsion(force=100.0, twist=[1e-4, 3e-3], method="mdr")


class TestTwistHistoryExact(ResultChecks):
    exact, plots = True, True

    def make_result(self):
        return HERTZ.twist_history(force=100.0, twist=TWIST)


class TestTwistHistoryMDR(ResultChecks):
    exact, plots = False, True

    def make_result(self):
        return HERTZ.twist_history(force=100.0, twist=TWIST, method="mdr")


class TestViscoelasticHistory(ResultChecks):
    exact, plots = True, True

    def make_result(self):
        c = cl.Contact(cl.profiles.Paraboloid(R=0.01),
                       materials=(cl.Rigid(), Maxwell(1e6, 1e4)))
        t = np.linspace(0.0, 0.01, 8)
        return c.viscoelastic_history(time=t, depth=np.linspace(0, 1e-6, 8), n_springs=200)


class TestPathResultExact(ResultChecks):
    exact, plots = True, True

    def make_result(self):
        return HERTZ.simulate(_path(), n_rings=32)


class TestPathResultMDR(ResultChecks):
    exact, plots = False, True

    def make_result(self):
        return HERTZ.simulate(_path(), method="mdr", n_springs=200)


class TestFrettingLoop(ResultChecks):
    exact, plots = True, True

    def make_result(self):
        return HERTZ.fretting_loop(force=100.0, displacement_amplitude=5e-7, n_points=20)


class TestFrettingLoopMDR(ResultChecks):
    exact, plots = False, True

    def make_result(self):
        return HERTZ.fretting_loop(force=100.0, twist_amplitude=2e-3, method="mdr", n_points=20)


class TestFrettingMap(ResultChecks):
    exact, plots = True, True

    def make_result(self):
        return HERTZ.fretting_map(force=[10.0, 100.0], displacement_amplitude=[1e-7, 1e-5])


class TestFrettingMapMDR(ResultChecks):
    exact, plots = False, True

    def make_result(self):
        return HERTZ.fretting_map(force=[10.0, 100.0], twist_amplitude=[1e-4, 3e-3],
                                  method="mdr", boundary=False)


class TestWearResult(ResultChecks):
    exact, plots = False, True

    def make_result(self):
        return HERTZ.wear(force=100.0, twist_amplitude=2e-3, wear_coefficient=1e-16,
                          cycles=1e3, method="mdr", n_grid=64)


class TestLawStep(ResultChecks):
    exact = False

    def make_result(self):
        return _law_step()


class TestSceneResult(ResultChecks):
    exact, plots = False, True

    def make_result(self):
        return _scene()


def _hertz_curve():
    z = np.linspace(-20e-9, 100e-9, 200)
    d = np.maximum(z - 5e-9, 0.0)
    return z, 4.0 / 3.0 * 2e6 / 0.75 * np.sqrt(5e-6) * d ** 1.5


class TestFitResult(ResultChecks):
    exact, plots = True, True

    def make_result(self):
        z, F = _hertz_curve()
        return cl.fit.indentation(z, F + 1e-11 * np.sin(z * 1e9), cl.profiles.Paraboloid(R=5e-6),
                                  sample=cl.Elastic(E=1e6, nu=0.5))


class TestFitResultTable(ResultChecks):
    exact, plots = False, False

    def make_result(self):
        z, F = _hertz_curve()
        r = np.linspace(0.0, 2e-6, 101)
        tip = cl.profiles.Tabulated(r, r * r / 1e-5)
        return cl.fit.indentation(z, F, tip, sample=cl.Elastic(E=1e6, nu=0.5))


class TestFitResultLoop(ResultChecks):
    exact, plots = True, True

    def make_result(self):
        u = np.concatenate([np.linspace(1e-7, -1e-7, 40), np.linspace(-1e-7, 1e-7, 40)[1:]])
        F = 5.0 * np.tanh(u * 1e7)
        return cl.fit.tangential_loop(u, F, 100.0, cl.profiles.Paraboloid(R=0.01),
                                      sample=STEEL)


def _checked_types() -> set[type]:
    import warnings
    out = set()
    for t in globals().values():
        if isinstance(t, type) and issubclass(t, ResultChecks) and t is not ResultChecks:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                out.add(type(t()._result()))
    return out


def test_every_result_type_is_covered():
    found = set(result_types())
    assert len(found) >= 14
    assert all(issubclass(t, Result) for t in found), \
        [t.__name__ for t in found if not issubclass(t, Result)]
    missing = found - _checked_types()
    assert not missing, f"result types without a ResultChecks test: {missing}"


def test_a_new_result_type_without_the_protocol_is_found(monkeypatch):
    """The enumeration finds any dataclass with a ``meta`` field in a result module, so a new
    result type that forgets the protocol fails the test above."""
    from dataclasses import dataclass, field

    import contactlab.effects.tangential as mod

    @dataclass(frozen=True)
    class Forgotten:
        meta: dict = field(default_factory=dict)

    Forgotten.__module__ = mod.__name__
    monkeypatch.setattr(mod, "Forgotten", Forgotten, raising=False)
    assert Forgotten in result_types() and not issubclass(Forgotten, Result)


@pytest.mark.parametrize("bad", [True, "yes"])
def test_to_csv_overwrite_flag_is_a_keyword(tmp_path, bad):
    s = HERTZ.normal(force=1.0)
    with pytest.raises(TypeError):
        s.to_csv(tmp_path / "x.csv", bad)          # positional: refused
