"""LoadPath.sample(): the per-step values every consumer (scene, simulate) uses, checked against
the segment formulas written out here; fractional sinusoids; one validation test per rule."""
import numpy as np
import pytest

import contactlab as cl
from contactlab.errors import ParameterError
from contactlab.loadpath import Sinusoid

from tests.tolerances import SINE_TILING


def test_ramp_hold_sinusoid_against_the_formulas():
    p = (cl.LoadPath().ramp(force=10.0, steps=4, duration=2.0).hold(steps=2, duration=1.0)
         .sinusoid(force=3.0, twist=1e-3, cycles=2, steps_per_cycle=4, period=8.0))
    s = p.sample()
    k4 = np.arange(1, 5)
    ramp_t = k4 / 4 * 2.0
    hold_t = ramp_t[-1] + np.arange(1, 3) / 2 * 1.0
    sin_t = hold_t[-1] + np.arange(1, 9) * 8.0 / 4
    np.testing.assert_array_equal(s.time, np.concatenate([ramp_t, hold_t, sin_t]))
    wave = np.array([1.0, 0.0, -1.0, 0.0] * 2)   # sin(2πk/4), exact zeros at k = 2, 4
    np.testing.assert_array_equal(s.values["force"],
                                  np.concatenate([10.0 * k4 / 4, [10.0, 10.0], 10.0 + 3.0 * wave]))
    np.testing.assert_array_equal(s.values["twist"], np.concatenate([np.zeros(6), 1e-3 * wave]))
    np.testing.assert_array_equal(s.leaf, [0] * 4 + [1] * 2 + [2] * 8)
    assert s.n_steps == p.n_steps == 14


def test_repeat_is_expanded_and_starts_from_the_state_reached():
    s = cl.LoadPath().ramp(depth=1.0, steps=2).repeat(3).sample()
    # each repetition ramps from the value reached to 1.0: only the first one moves
    np.testing.assert_array_equal(s.values["depth"], [0.5, 1.0, 1.0, 1.0, 1.0, 1.0])
    np.testing.assert_array_equal(s.leaf, [0, 0, 1, 1, 2, 2])


def test_table_times_are_relative_to_its_first_row():
    s = cl.LoadPath.from_arrays(time=[5.0, 6.0, 8.0], force=[0.0, 1.0, 2.0]).sample(
        start_time=5.0)
    np.testing.assert_array_equal(s.time, [5.0, 6.0, 8.0])
    np.testing.assert_array_equal(cl.LoadPath.from_arrays(time=[5.0, 6.0], force=[0, 1])
                                  .sample().time, [0.0, 1.0])


def test_sample_time_matches_simulate():
    p = cl.LoadPath().ramp(force=1.0, steps=3, duration=0.3).sinusoid(
        twist=1e-6, cycles=1.5, steps_per_cycle=6, period=0.7)
    c = cl.Contact(cl.profiles.Paraboloid(R=0.01), materials=(cl.Elastic(E=210e9, nu=0.3),) * 2,
                   friction=0.2)
    r = c.simulate(p, n_rings=10)
    s = p.sample()
    np.testing.assert_array_equal(r.time, s.time)
    np.testing.assert_array_equal(r.twist, s.values["twist"])


def test_every_cycle_is_bitwise_the_first_and_half_periods_are_the_mean():
    s = cl.LoadPath().sinusoid(twist=1.0, cycles=3, steps_per_cycle=10, mean={"twist": 0.5})
    v = s.sample().values["twist"].reshape(3, 10)
    assert np.array_equal(v[0], v[1]) and np.array_equal(v[0], v[2])
    assert v[0, 4] == 0.5 and v[0, 9] == 0.5


@pytest.mark.parametrize("cycles, n", [(0.25, 2), (0.5, 4), (1.5, 12), (2, 16), (0.01, 1)])
def test_fractional_cycles(cycles, n):
    seg = Sinusoid((("twist", 2.0),), cycles, 8, 4.0)
    assert seg.n_steps == n
    assert seg.duration == n * 4.0 / 8
    t, v = seg.values({"twist": 0.0})
    k = np.arange(1, n + 1)
    np.testing.assert_allclose(v["twist"], 2.0 * np.sin(2 * np.pi * k / 8), rtol=0,
                               atol=SINE_TILING * 2.0)
    np.testing.assert_array_equal(t, k * 4.0 / 8)


def test_whole_cycles_stay_integers():
    assert Sinusoid((("twist", 1.0),), 2.0).cycles == 2
    assert isinstance(Sinusoid((("twist", 1.0),), 2.0).cycles, int)


@pytest.mark.parametrize("bad", [0, -1, 0.0, -0.5, np.nan, np.inf, True, "two"])
def test_rule_cycles_positive_finite(bad):
    with pytest.raises(ParameterError, match="cycles"):
        Sinusoid((("twist", 1.0),), bad)


@pytest.mark.parametrize("bad", [0, -1, np.int64(0)])
def test_rule_whole_cycles_say_fractions_are_allowed(bad):
    # an int below 1 got the step count's message ("an integer >= 1") though 0.3 is accepted
    with pytest.raises(ParameterError, match=r"cycles=.* must be > 0 \(fractions allowed\)"):
        Sinusoid((("twist", 1.0),), bad)


def test_rule_sample_needs_one_control_per_group():
    p = cl.LoadPath().ramp(depth=1e-6, steps=2).ramp(force=1.0, steps=2)
    with pytest.raises(ParameterError, match=r"normal group.*'depth'.*'force'.*simulate"):
        p.sample()


def test_rule_start_time_finite():
    with pytest.raises(ParameterError, match="start_time"):
        cl.LoadPath().ramp(force=1.0).sample(start_time=np.nan)


def test_empty_path_samples_to_nothing():
    s = cl.LoadPath().sample()
    assert s.n_steps == 0 and s.values == {}
