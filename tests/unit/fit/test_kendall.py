"""JKR fit of a flat punch (Kendall 1971): E, the contact point and the offset by linear least
squares on the attached part, the work of adhesion from the measured pull-off in closed form,
on retraction curves made here from Kendall's closed form: F = 2E*bδ while attached, detachment
at δ_c = -sqrt(2πbΔγ/E*) (pull-off force -sqrt(8πb³E*Δγ)), the offset after."""
from __future__ import annotations

import numpy as np
import pytest

from contactlab import Elastic, errors
from contactlab.fit import indentation
from contactlab.profiles import FlatPunch
from tests.tolerances import FIT_CLOSED_FORM_ROUNDING, FIT_RECOVERY

E, NU, Z0, W, B = 2e6, 0.5, 12e-9, 0.05, 1e-6
ESTAR = E / (1 - NU ** 2)
SAMPLE = Elastic(E=1e6, nu=NU)
DC = -np.sqrt(2 * np.pi * B * W / ESTAR)
ALL = ("E", "contact_point", "work_of_adhesion", "force_offset")


def kendall(dd, off=3e-10):
    return np.where(dd >= DC, 2 * ESTAR * B * dd, 0.0) + off


def test_pull_off_force_is_kendalls():
    assert 2 * ESTAR * B * DC == pytest.approx(-np.sqrt(8 * np.pi * B ** 3 * ESTAR * W),
                                               rel=FIT_CLOSED_FORM_ROUNDING)


def test_recovered_with_a_sample_at_the_detachment():
    dd = np.concatenate([np.linspace(DC - 60e-9, DC, 400, endpoint=False),
                         np.linspace(DC, 200e-9, 1600)])
    z, F = (dd + Z0)[::-1], kendall(dd)[::-1]            # a retraction: decreasing depth
    res = indentation(z, F, FlatPunch(radius=B), sample=SAMPLE, adhesion="jkr", free=ALL)
    for k, want in {"E": E, "contact_point": Z0, "work_of_adhesion": W,
                    "force_offset": 3e-10}.items():
        assert res.params[k] == pytest.approx(want, rel=FIT_RECOVERY), k
    assert res.meta["pull_off_force"] == pytest.approx(
        -np.sqrt(8 * np.pi * B ** 3 * ESTAR * W), rel=FIT_RECOVERY)
    assert res.contact.work_of_adhesion == res.params["work_of_adhesion"]
    assert np.max(np.abs(res.residuals)) < 1e-12 * np.max(np.abs(F))


def test_work_of_adhesion_within_the_sampling_bracket():
    """A grid without a sample at the detachment: Δγ from the last attached sample is the
    bracket's lower end; the truth lies inside, and the standard error holds the bracket's
    width/sqrt(12)."""
    dd = np.linspace(DC - 61.3e-9, 200e-9, 2000)
    res = indentation(dd + Z0, kendall(dd, 0.0), FlatPunch(radius=B), sample=SAMPLE,
                      adhesion="jkr", free=("E", "contact_point", "work_of_adhesion"))
    lo, hi = res.meta["work_of_adhesion_bracket"]
    assert lo <= W < hi
    assert res.params["work_of_adhesion"] == lo
    assert res.stderr["work_of_adhesion"] >= (hi - lo) / np.sqrt(12) * (1 - 1e-12)
    assert res.params["E"] == pytest.approx(E, rel=FIT_RECOVERY)
    assert res.params["contact_point"] == pytest.approx(Z0, rel=FIT_RECOVERY)


def test_last_attached_sample_is_the_jump_not_the_smallest_force():
    """Near the pull-off the attached force changes by less than the noise per sample: a sample
    a few steps deeper can hold the smallest force. The samples between it and the jump are
    still attached (regression: they were taken as detached, biasing the contact point)."""
    dd = np.concatenate([np.linspace(DC - 60e-9, DC, 400, endpoint=False),
                         np.linspace(DC, 200e-9, 1600)])
    F = kendall(dd, 0.0)
    F[403] -= 1e-8                  # 3 samples deeper than the end (1.8e-9 N per sample)
    res = indentation(dd + Z0, F, FlatPunch(radius=B), sample=SAMPLE, adhesion="jkr",
                      free=ALL)
    assert res.meta["pull_off_indentation"] == pytest.approx(DC, rel=FIT_RECOVERY)
    assert res.params["contact_point"] == pytest.approx(Z0, rel=FIT_RECOVERY)


def test_noisy_interval_of_the_modulus():
    rng = np.random.default_rng(3)
    dd = np.linspace(DC - 60e-9, 200e-9, 2000)
    F = kendall(dd) + rng.normal(0.0, 2e-9, dd.size)
    res = indentation(dd + Z0, F, FlatPunch(radius=B), sample=SAMPLE, adhesion="jkr",
                      free=ALL)
    assert res.covariance.shape == (4, 4)
    assert all(v > 0 for v in res.stderr.values())
    assert abs(res.params["E"] - E) < 5 * res.stderr["E"]
    assert abs(res.params["work_of_adhesion"] - W) < 5 * res.stderr["work_of_adhesion"]


def test_fixed_work_and_refusals():
    dd = np.linspace(DC - 60e-9, 200e-9, 2000)
    res = indentation(dd + Z0, kendall(dd, 0.0), FlatPunch(radius=B), sample=SAMPLE,
                      adhesion="jkr", work_of_adhesion=W)
    assert res.params["E"] == pytest.approx(E, rel=FIT_RECOVERY)
    assert res.params["work_of_adhesion"] == W
    with pytest.raises(errors.ParameterError, match="no pull-off"):
        indentation(dd + Z0, np.maximum(kendall(dd, 0.0), 0.0), FlatPunch(radius=B),
                    sample=SAMPLE, adhesion="jkr", free=ALL)


@pytest.mark.slow
def test_coverage_of_the_95_percent_interval():
    """With noise larger than the attached force's change from one sample to the next near the
    pull-off, the 95 % intervals of E and the contact point cover the truth in 90-99 % of 200
    repetitions; Δγ's (its sampling bracket included) in at least 90 %."""
    rng = np.random.default_rng(7)
    dd = np.linspace(DC - 60e-9, 200e-9, 2000)
    clean = kendall(dd, 0.0)
    truth = {"E": E, "contact_point": Z0, "work_of_adhesion": W}
    hits = dict.fromkeys(truth, 0)
    n = 200
    for _ in range(n):
        res = indentation(dd + Z0, clean + rng.normal(0.0, 2e-9, dd.size), FlatPunch(radius=B),
                          sample=SAMPLE, adhesion="jkr", free=ALL)
        ci = res.confidence(0.95)
        for k in truth:
            hits[k] += ci[k][0] <= truth[k] <= ci[k][1]
    for k in ("E", "contact_point"):
        assert 0.90 * n <= hits[k] <= 0.99 * n, (k, hits[k])
    assert hits["work_of_adhesion"] >= 0.90 * n


def test_tabor_parameter_is_undefined_for_a_punch_and_says_why():
    dd = np.concatenate([np.linspace(DC - 60e-9, DC, 400, endpoint=False),
                         np.linspace(DC, 200e-9, 1600)])
    res = indentation((dd + Z0)[::-1], kendall(dd)[::-1], FlatPunch(radius=B), sample=SAMPLE,
                      adhesion="jkr", free=ALL)
    assert res.meta["tabor_parameter"] is None and "wall" in res.meta["tabor_note"]
