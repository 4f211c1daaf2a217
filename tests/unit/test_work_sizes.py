"""Every size a user controls is checked before the work it drives starts (issue 26): a sweep
grid, the steps of a twist or shift history, the points of a fretting map, the checkpoints and
the step tolerance of a wear run. Each raises a specific error naming the parameter, its value
and the limit (the memory budget and how to raise it), before anything large is built: a
sentinel in place of the first piece of work proves that none started."""
from __future__ import annotations

import numpy as np
import pytest

import contactlab as cl
from contactlab.errors import MemoryBudgetError, ParameterError

STEEL = cl.Elastic(E=210e9, nu=0.3)
F = 100.0


class WorkStarted(Exception):
    """Raised by the sentinel standing in for the first piece of real work."""


def sentinel(*args, **kwargs):
    raise WorkStarted


@pytest.fixture
def contact():
    return cl.Contact(cl.profiles.Paraboloid(R=0.01), materials=(STEEL, STEEL), friction=0.5)


@pytest.fixture
def small_budget():
    """A 1 MB memory budget: the sizes below are small, the work they would start is not."""
    previous = cl.set_memory_budget("1M")
    yield
    cl.set_memory_budget(previous)


def test_grid_axis_is_checked_before_its_values_are_made(small_budget, monkeypatch):
    from contactlab.sweeps import grid
    monkeypatch.setattr(grid.np, "linspace", sentinel)
    with pytest.raises(MemoryBudgetError, match=r"--grid 'profile.R=0.005:0.02:100000'.*"
                       r"N=100000 points.*CONTACTLAB_MEMORY_BUDGET"):
        grid.parse_axis("profile.R=0.005:0.02:100000")


def test_grid_product_is_checked_before_any_list_is_made(small_budget):
    from contactlab.sweeps.grid import make_grid
    with pytest.raises(MemoryBudgetError, match="10000000000 points = 100000 x 100000"):
        make_grid({"x": range(10**5), "y": np.arange(10**5)})
    with pytest.raises(MemoryBudgetError, match=f"{10**20} points"):
        make_grid({"x": range(10**20)})


def test_twist_history_steps_are_checked_first(contact, small_budget, monkeypatch):
    import contactlab.effects.torsion as torsion
    monkeypatch.setattr(torsion, "masing_program", sentinel)
    with pytest.raises(MemoryBudgetError, match=r"twist_history\(\).*twist: 10000 steps"):
        contact.twist_history(twist=np.zeros(10**4), force=F)


def test_twist_history_solve_is_checked_per_distinct_amplitude(contact, monkeypatch):
    """The loading-curve solve scales with the distinct amplitudes: a steady sinusoid's few
    pass, a ramp whose every step is new needs its solve's memory."""
    import contactlab.effects.torsion as torsion
    n = 2000
    steady = 1e-4 * np.sin(2 * np.pi * np.arange(n) / 200)      # 10 cycles of 200 steps
    ramp = np.linspace(1e-6, 1e-3, n)
    per = torsion.SOLVE_BYTES_PER_ARGUMENT["exact"]
    previous = cl.set_memory_budget(n * torsion.HISTORY_BYTES_PER_STEP + 400 * per)
    try:
        contact.twist_history(twist=steady, force=F)
        monkeypatch.setattr(torsion, "torsion_model",       # the solve is the work
                            lambda *a: type("Model", (), {"of_twist": sentinel})())
        with pytest.raises(MemoryBudgetError, match=rf"\d+ distinct amplitudes of the {n} steps"):
            contact.twist_history(twist=ramp, force=F)
    finally:
        cl.set_memory_budget(previous)


def test_shift_history_steps_are_checked_first(contact, small_budget, monkeypatch):
    import contactlab.effects.tangential as tangential
    monkeypatch.setattr(tangential, "masing_program", sentinel)
    with pytest.raises(MemoryBudgetError, match=r"shift_history\(\).*displacement: 10000 steps"):
        contact.shift_history(displacement=np.zeros(10**4), force=F)


def test_fretting_map_points_are_checked_before_the_normal_states(contact, small_budget,
                                                                   monkeypatch):
    import contactlab.effects.fretting as fretting
    monkeypatch.setattr(fretting, "_normal_states", sentinel)
    with pytest.raises(MemoryBudgetError, match="100 force values x 100 twist_amplitude values"):
        contact.fretting_map(force=np.linspace(1.0, 100.0, 100),
                             twist_amplitude=np.geomspace(1e-5, 1e-2, 100))


@pytest.mark.parametrize("kw, match", [
    ({"checkpoints": 10**7}, r"checkpoints=10000000 is invalid: at most 10000"),
    ({"checkpoints": np.arange(1.0, 20002.0)}, r"checkpoints=<20001 cycle numbers> is invalid"),
    ({"jump_rtol": 1e-300}, r"jump_rtol=1e-300 is invalid: .* >= 1e-10"),
    ({"jump_rtol": 9e-11}, r"jump_rtol=9e-11 is invalid"),
])
def test_wear_work_is_bounded_before_it_starts(contact, monkeypatch, kw, match):
    import contactlab.effects.wear as wear
    monkeypatch.setattr(wear, "loops", sentinel)
    with pytest.raises(ParameterError, match=match):
        contact.wear(force=F, wear_coefficient=1e-14, cycles=1e5, displacement_amplitude=1e-6,
                     **kw)


def test_wear_checkpoints_memory(contact, small_budget, monkeypatch):
    import contactlab.effects.wear as wear
    monkeypatch.setattr(wear, "loops", sentinel)
    with pytest.raises(MemoryBudgetError, match="checkpoints: 5000 stored profiles x 17 grid"):
        contact.wear(force=F, wear_coefficient=1e-14, cycles=1e5, displacement_amplitude=1e-6,
                     checkpoints=5000, n_grid=16)


def test_the_limits_pass_what_they_bound(contact):
    """The smallest allowed jump_rtol and the most checkpoints are accepted (the checks are
    limits, not a change of the defaults)."""
    import contactlab.effects.wear as wear
    from contactlab.effects.wear import _checkpoint_sizes
    _checkpoint_sizes(wear.MAX_CHECKPOINTS, 16, wear.MIN_JUMP_RTOL)
    _checkpoint_sizes(None, wear.DEFAULT_GRID, wear.DEFAULT_JUMP_RTOL)
