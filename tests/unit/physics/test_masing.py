"""Masing bookkeeping: near-duplicate loading-curve arguments (issue 13: no rounding cliff)."""
from __future__ import annotations

import numpy as np
import pytest

import contactlab as cl
from contactlab.effects import torsion as torsion_driver
from contactlab.physics import masing
from tests.tolerances import MERGED_ARGUMENTS

STEEL = cl.Elastic(E=210e9, nu=0.3)


def test_merge_close_keeps_distinct_values_exact():
    x = np.array([0.3, 0.1, 0.2, 0.1, 0.3])
    u, inv, shift = masing.merge_close(x, 1e-12)
    assert np.array_equal(u, [0.1, 0.2, 0.3]) and np.array_equal(u[inv], x)
    assert np.array_equal(shift, np.zeros(3))


def test_merge_close_groups_rounding_jitter():
    x = np.array([1.0, 1.0 + 1e-15, 1.0 - 2e-15, 2.0, 2.0 + 4e-16, 3.0])
    u, inv, shift = masing.merge_close(x, 1e-12)
    assert u.size == 3
    assert np.all(np.abs(u[inv] - x) <= shift[inv])
    assert np.all(shift <= 1e-12 * 3) and shift[2] == 0.0


def test_merge_step_never_coarser_than_1e11():
    assert masing.merge_step(2.0, 1e-3) == pytest.approx(2e-11)
    assert masing.merge_step(2.0, 1e-13) == pytest.approx(2e-14)
    assert masing.merge_step(0.0, 1e-10) == 0.0


def _jittered(n_cycles):
    k = np.arange(20 * n_cycles)
    return np.sin(2 * np.pi * k / 20)


@pytest.mark.parametrize("method", ["exact", "mdr"])
# c/a > 0.83: the MDR torque is valid; its dissipated energy (1.9 % off) is not and says so
@pytest.mark.filterwarnings("ignore:MDR torsion model. the dissipated energy"
                            ":contactlab.errors.ValidityWarning")
def test_jittered_history_solves_per_amplitude_not_per_rounding(method, monkeypatch):
    c = cl.Contact(cl.profiles.Paraboloid(R=0.01), (STEEL, STEEL), friction=0.3)
    twist = 3e-4 * _jittered(500)      # partial slip, c/a > 0.83 (inside the MDR's validity)
    n_args = []
    real = torsion_driver.merge_close

    def counting(x, step):
        out = real(x, step)
        n_args.append((np.unique(x).size, out[0].size))
        return out

    monkeypatch.setattr(torsion_driver, "merge_close", counting)
    h = c.twist_history(force=10.0, twist=twist, method=method)
    distinct, solved = n_args[0]
    assert distinct > 1000          # the rounding makes (almost) every step distinct ...
    assert solved <= 2 * 20         # ... but the loading curve is solved per amplitude
    # against the same history with every distinct argument solved (no merging)
    monkeypatch.setattr(torsion_driver, "merge_step", lambda amp, rtol: 0.0)
    exact = c.twist_history(force=10.0, twist=twist, method=method)
    amp = np.max(np.abs(exact.torque))
    assert np.max(np.abs(h.torque - exact.torque)) <= MERGED_ARGUMENTS * amp
    assert np.all(np.abs(h.torque - exact.torque) <= h.torque_error + exact.torque_error)
