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
    monkeypatch.delenv(TIME_BUDGET_ENV, raising=False)
    previous = cl.set_time_budget(None)
    try:
        with pytest.raises(TimeBudgetError, match="jump_rtol=1e-10"):
            C.wear(force=10.0, displacement_amplitude=1e-6, wear_coefficient=1e-13,
                   cycles=1e6, checkpoints=1000, n_grid=1000, jump_rtol=1e-10)
    finally:
        cl.set_time_budget(previous)
