"""The time budget (issue 26 item 6): work whose run time a user's sizes set is estimated from a
calibrated cost per unit and refused before it starts when the estimate exceeds the budget."""
from __future__ import annotations

import math

import numpy as np
import pytest

import contactlab as cl
from contactlab.errors import ParameterError, TimeBudgetError
from contactlab.params import DEFAULT_TIME_BUDGET, TIME_BUDGET_ENV

C = cl.Contact(cl.profiles.Paraboloid(R=0.01), materials=(cl.Elastic(E=210e9, nu=0.3),
                                                          cl.Rigid()), friction=0.3)


@pytest.fixture
def tiny_budget():
    previous = cl.set_time_budget(1e-9)
    try:
        yield
    finally:
        cl.set_time_budget(previous)


def test_budget_settings(monkeypatch):
    monkeypatch.delenv(TIME_BUDGET_ENV, raising=False)
    assert cl.time_budget() == DEFAULT_TIME_BUDGET
    monkeypatch.setenv(TIME_BUDGET_ENV, "2h")
    assert cl.time_budget() == 7200.0
    previous = cl.set_time_budget("10min")
    try:
        assert cl.time_budget() == 600.0
        cl.set_time_budget("inf")
        assert math.isinf(cl.time_budget())
        for bad in (0, -1, "soon", float("nan")):
            with pytest.raises(ParameterError, match="time budget"):
                cl.set_time_budget(bad)
    finally:
        cl.set_time_budget(previous)


@pytest.mark.parametrize("kw", [dict(twist_amplitude=np.linspace(1e-5, 1e-3, 5), method="exact"),
                                dict(twist_amplitude=np.linspace(1e-5, 1e-3, 5), method="mdr"),
                                dict(displacement_amplitude=np.linspace(1e-8, 1e-6, 5))])
def test_fretting_map_refused_before_work(tiny_budget, kw):
    with pytest.raises(TimeBudgetError, match=r"fretting_map\(\) would run for about .* time "
                                              r"budget of .*set_time_budget"):
        C.fretting_map(force=[5.0, 10.0], **kw)


def test_exact_map_of_two_million_points_refused_at_the_default(monkeypatch):
    """The run found to take ~20 minutes (2000 forces x 1000 twists, exact) is refused at the
    default budget, naming the points and how to raise the budget."""
    monkeypatch.delenv(TIME_BUDGET_ENV, raising=False)
    previous = cl.set_time_budget(None)
    try:
        with pytest.raises(TimeBudgetError, match="2000000 points on the exact route"):
            C.fretting_map(force=np.linspace(1.0, 10.0, 2000),
                           twist_amplitude=np.linspace(1e-5, 1e-3, 1000), method="exact")
    finally:
        cl.set_time_budget(previous)


def test_wear_refused_before_work(tiny_budget):
    with pytest.raises(TimeBudgetError, match=r"wear\(\) would run .*checkpoints"):
        C.wear(force=10.0, displacement_amplitude=1e-6, wear_coefficient=1e-13, cycles=1e5,
               checkpoints=50)


def test_wear_of_many_steps_refused_at_the_default(monkeypatch):
    """9e4 steps from the tolerance on a 1501-node grid (measured 43 ms per step at 1001 nodes
    on short runs; estimated 16 ms): refused at the default budget."""
    monkeypatch.delenv(TIME_BUDGET_ENV, raising=False)
    previous = cl.set_time_budget(None)
    try:
        with pytest.raises(TimeBudgetError, match="jump_rtol=1e-10"):
            C.wear(force=10.0, displacement_amplitude=1e-6, wear_coefficient=1e-13,
                   cycles=1e6, checkpoints=1000, n_grid=1500, jump_rtol=1e-10)
    finally:
        cl.set_time_budget(previous)


# ---- histories and paths: steps x a calibrated per-step cost, refused before any work ---------
def _no_work(*args, **kwargs):
    raise AssertionError("work started before the time budget was checked")


def test_twist_history_refused_before_work(tiny_budget, monkeypatch):
    monkeypatch.setattr("contactlab.effects.torsion.masing_program", _no_work)
    monkeypatch.setattr("contactlab.effects.torsion.torsion_model", _no_work)
    for method in ("exact", "mdr"):
        with pytest.raises(TimeBudgetError, match=r"twist_history\(\) would run for about .*"
                                                  r"1000 steps x .*time budget of .*"
                                                  r"set_time_budget"):
            C.twist_history(twist=np.linspace(0.0, 1e-4, 1000), force=10.0, method=method)


def test_twist_history_distinct_amplitudes_checked_before_the_solve(monkeypatch):
    """The second check, after the distinct amplitudes are known, names them; the loading-curve
    solve has not run."""
    class NoSolve:
        of_twist = staticmethod(_no_work)

    monkeypatch.setattr("contactlab.effects.torsion.HISTORY_SECONDS_PER_STEP", 0.0)
    monkeypatch.setattr("contactlab.effects.torsion.torsion_model", lambda *a: NoSolve())
    previous = cl.set_time_budget(1e-9)
    try:
        with pytest.raises(TimeBudgetError, match=r"501 steps x 0 us of bookkeeping and \d+ distinct amplitudes"):
            C.twist_history(twist=np.r_[np.linspace(0.0, 1e-4, 500), np.zeros(1)], force=10.0,
                            method="exact")
    finally:
        cl.set_time_budget(previous)


def test_shift_history_refused_before_work(tiny_budget, monkeypatch):
    monkeypatch.setattr("contactlab.effects.tangential.masing_program", _no_work)
    with pytest.raises(TimeBudgetError, match=r"shift_history\(\) would run .*displacement: "
                                              r"1000 steps"):
        C.shift_history(displacement=np.linspace(0.0, 1e-7, 1000), force=10.0)


@pytest.mark.parametrize("kw, name", [(dict(method="exact", n_rings=50), "50 rings"),
                                      (dict(method="mdr"), "strategy='segments'"),
                                      (dict(method="mdr", strategy="steps", n_springs=300),
                                       "300 springs per step")])
def test_simulate_refused_before_work(tiny_budget, monkeypatch, kw, name):
    monkeypatch.setattr("contactlab.foundation.base.path_normal_series", _no_work)
    path = cl.LoadPath().ramp(force=10.0, steps=5).ramp(twist=1e-4, steps=20)
    with pytest.raises(TimeBudgetError, match=rf"simulate\(.*\) would run .*25 steps x .*{name}"):
        C.simulate(path, **kw)


def test_exact_path_of_a_million_steps_refused_at_the_default(monkeypatch):
    """10^6 steps on the default 200 rings: about 17 min estimated (measured 2-4 ms per step),
    refused at the default budget before the normal problem is solved."""
    monkeypatch.delenv(TIME_BUDGET_ENV, raising=False)
    monkeypatch.setattr("contactlab.foundation.base.path_normal_series", _no_work)
    previous = cl.set_time_budget(None), cl.set_memory_budget("inf")
    try:
        path = cl.LoadPath().ramp(force=10.0, steps=10).ramp(twist=1e-4, steps=10**6)
        with pytest.raises(TimeBudgetError, match="1000010 steps x .* on 200 rings"):
            C.simulate(path, method="exact")
    finally:
        cl.set_time_budget(previous[0])
        cl.set_memory_budget(previous[1])


def test_a_budget_raise_lets_the_same_calls_run(monkeypatch):
    path = cl.LoadPath().ramp(force=10.0, steps=5).ramp(twist=1e-6, steps=20)
    calls = [lambda: C.twist_history(twist=np.linspace(0.0, 1e-4, 50), force=10.0),
             lambda: C.shift_history(displacement=np.linspace(0.0, 1e-7, 50), force=10.0),
             lambda: C.simulate(path, method="exact", n_rings=16),
             lambda: C.simulate(path, method="mdr", n_springs=64),
             lambda: C.wear(force=10.0, displacement_amplitude=1e-6, wear_coefficient=1e-13,
                            cycles=100.0, n_grid=100)]
    previous = cl.set_time_budget(1e-9)
    try:
        for call in calls:
            with pytest.raises(TimeBudgetError):
                call()
        cl.set_time_budget("1h")
        for call in calls:
            call()
    finally:
        cl.set_time_budget(previous)


# ---- wear: the steps grow with the wear the cycles remove ------------------------------------
def test_wear_step_bound_grows_with_the_worn_volume():
    """At the default tolerance: 90 steps from the tolerance alone, then 200 ρ^0.8 (ρ the
    worn-volume ratio, linear in the cycles); a looser tolerance lowers the wear part as
    jump_rtol^-0.5, a tighter one does not raise it (the bound stays a lower bound)."""
    from contactlab.effects.wear import wear_steps_lower
    low = [wear_steps_lower(1, 1e-4, ratio) for ratio in (0.0, 1.0, 1e2, 1e4)]
    np.testing.assert_allclose(low, [90.0, 200.0, 200.0 * 1e2**0.8, 200.0 * 1e4**0.8],
                               rtol=1e-12)
    assert wear_steps_lower(1, 1e-2, 1e4) == pytest.approx(0.1 * low[3], rel=1e-12)
    assert wear_steps_lower(1, 1e-6, 1e4) == pytest.approx(low[3], rel=1e-12)
    assert wear_steps_lower(10**6, 1e-4, 1.0) == 10**6          # one per checkpoint at least


def test_wear_of_many_cycles_refused_at_the_default_before_the_steps(monkeypatch):
    """10^7 cycles at k = 1e-11 1/Pa remove ~5e5 times the contact's volume scale: millions of
    wear steps. The old bound (one per checkpoint, 90 from the tolerance) let it start; it is
    refused now, naming the cycles, before the grid is built."""
    monkeypatch.delenv(TIME_BUDGET_ENV, raising=False)
    monkeypatch.setattr("contactlab.effects.wear._wear.operators", _no_work)
    previous = cl.set_time_budget(None)
    try:
        with pytest.raises(TimeBudgetError, match=r"wear\(\) would run .*1e\+07 cycles remove"):
            C.wear(force=10.0, displacement_amplitude=1e-6, wear_coefficient=1e-11, cycles=1e7)
    finally:
        cl.set_time_budget(previous)


def test_implicit_wear_is_not_refused_by_the_explicit_step_law(monkeypatch):
    """The implicit cycle jumps do not grow with the worn volume (issue 28: 2040 steps for 10^6
    gross-slip cycles whose worn-volume ratio ~2e3 gives the explicit law ~9e4): the same
    request that the explicit route is refused for reaches the grid."""
    monkeypatch.delenv(TIME_BUDGET_ENV, raising=False)
    monkeypatch.setattr("contactlab.effects.wear._wear.operators", _no_work)
    previous = cl.set_time_budget(None)
    try:
        with pytest.raises(AssertionError, match="work started"):
            C.wear(force=10.0, displacement_amplitude=1e-6, wear_coefficient=1e-11, cycles=1e7,
                   integrator="implicit")
    finally:
        cl.set_time_budget(previous)
