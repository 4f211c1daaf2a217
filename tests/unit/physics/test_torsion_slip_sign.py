"""The slip-direction test of a punch-density step by the running integral of its density change
(physics.torsion_slip_sign) against the slip increments themselves (the closed-form slip-kernel
integral, itself checked against quadrature in test_torsion_annulus.py), and its use in the
annulus step: the same results, fewer slip integrals at the points."""
from __future__ import annotations

import warnings

import numpy as np
import pytest

import contactlab as cl
from contactlab.physics import torsion_annulus as ta
from contactlab.physics import torsion_slip_sign as ss
from tests.tolerances import SLIP_SIGN_ROUNDING


def _pieces(rng, n, c=0.3):
    """``n`` abutting linear pieces of a density change on ``[c, 1]``, random values."""
    x = np.sort(np.concatenate([[c, 1.0], rng.uniform(c, 1.0, n - 1)]))
    v = rng.normal(size=(2, n))
    return x[:-1], x[1:], v[0], v[1]


def _slips(p, s, gross, r):
    """``s Δs(r)`` by the slip-kernel integral (closed form) plus the gross turn, and its scale."""
    ds = ta.slip_kernel_integral(p, r) + gross * r
    return s * ds, float(np.max(np.abs(ds)))


def test_a_true_verdict_means_the_slip_points_the_way_of_the_traction():
    rng = np.random.default_rng(28)
    r = np.linspace(0.3, 1.2, 400)[1:]
    passed = plain = 0
    for _ in range(400):
        p = _pieces(rng, int(rng.integers(1, 8)))
        # tilt towards positive changes so that both verdicts occur often
        p = (p[0], p[1], p[2] + 0.8, p[3] + 0.8)
        for s in (1.0, -1.0):
            sp = (p[0], p[1], s * p[2], s * p[3])      # the change in the sense s
            gross = s * float(rng.choice([0.0, 0.1]))
            if ss.running_turn_ok(*sp, s, gross):
                passed += 1
                plain += bool(np.all(p[2] >= 0) and np.all(p[3] >= 0))
                got, scale = _slips(sp, s, gross, r)
                assert got.min() >= -SLIP_SIGN_ROUNDING * scale
    # the test is not vacuous, and it settles changes the plain sign test cannot
    assert passed > 100 and plain < passed - 50


def test_a_change_negative_above_the_stick_radius_fails_and_slips_backwards():
    p = (np.array([0.3, 0.5]), np.array([0.5, 1.0]), np.array([-1.0, 2.0]),
         np.array([-1.0, 2.0]))
    assert not ss.running_turn_ok(*p, 1.0, 0.0)
    got, _ = _slips(p, 1.0, 0.0, np.array([0.4]))
    assert got[0] < 0                      # the slip just above c points backwards
    # the same change behind a positive band whose turn outweighs it: accepted, and right
    q = (np.array([0.3, 0.4, 0.5]), np.array([0.4, 0.5, 1.0]), np.array([3.0, -1.0, 2.0]),
         np.array([3.0, -1.0, 2.0]))
    assert ss.running_turn_ok(*q, 1.0, 0.0)
    assert not (np.all(q[2] >= 0) and np.all(q[3] >= 0))
    got, scale = _slips(q, 1.0, 0.0, np.linspace(0.31, 1.0, 300))
    assert got.min() >= -SLIP_SIGN_ROUNDING * scale


def test_interior_minimum_of_the_running_integral_counts():
    # s Δw rises through zero inside the second piece (from -1 at 1 to +1 at 3): the running
    # integral is 0.26 at both piece ends (1 and 3) but -0.24 at the zero (2)
    p = (np.array([0.0, 1.0]), np.array([1.0, 3.0]), np.array([0.26, -1.0]),
         np.array([0.26, 1.0]))
    assert not ss.running_turn_ok(*p, 1.0, 0.0)
    p_ok = (p[0], p[1], np.array([0.6, -1.0]), np.array([0.6, 1.0]))
    assert ss.running_turn_ok(*p_ok, 1.0, 0.0)


def test_gross_turn_against_the_sense_or_a_nan_is_not_settled():
    p = (np.array([0.3]), np.array([1.0]), np.array([1.0]), np.array([1.0]))
    assert ss.running_turn_ok(*p, 1.0, 0.0) and ss.running_turn_ok(*p, 1.0, 0.2)
    assert not ss.running_turn_ok(*p, 1.0, -0.2)
    assert not ss.running_turn_ok(*p, -1.0, 0.0)
    assert not ss.running_turn_ok(*p, 1.0, float("nan"))
    bad = (p[0], p[1], np.array([np.nan]), p[3])
    assert not ss.running_turn_ok(*bad, 1.0, 0.0)
    empty = (np.zeros(0),) * 4
    assert ss.running_turn_ok(*empty, 1.0, 0.0)


def test_the_compiled_pass_gives_the_same_verdicts():
    rng = np.random.default_rng(7)
    seen = set()
    for _ in range(300):
        p = _pieces(rng, int(rng.integers(1, 10)))
        p = (p[0], p[1], p[2] + rng.uniform(0.0, 1.5), p[3] + rng.uniform(0.0, 1.5))
        for s in (1.0, -1.0):
            for gross in (0.0, s * 0.1, -s * 0.1):
                want = ss.running_turn_ok(*p, s, gross)
                assert ss.running_turn_ok_compiled(*p, s, gross) is want
                assert bool(ss._running_turn_pass(*p, s, gross, ss.MARGIN)) is want
                seen.add(want)
    assert seen == {True, False}
    nan = (np.array([0.0]), np.array([1.0]), np.array([np.nan]), np.array([1.0]))
    assert not ss.running_turn_ok_compiled(*nan, 1.0, 0.0)


def _path(n: int):
    """benchmarks/exact_speed.py ``varying_path``: force 10 N +- 40 % at two cycles, twist at 80 %
    of sliding at three cycles (ramped in), Hertz."""
    c = cl.Contact(cl.profiles.Paraboloid(R=0.01),
                   materials=(cl.Elastic(E=210e9, nu=0.3), cl.Rigid()), friction=0.3)
    t = np.arange(1, n + 1) / n
    force = 10.0 * (1 + 0.4 * np.sin(2 * np.pi * 2 * t + 0.3))
    a_max = float(np.max(c.normal(force=force)._radius))
    s = 0.3 * 10.0 / (c.moduli.torsional * a_max ** 2)
    phi = 0.8 * s * np.sin(2 * np.pi * 3 * t) * np.minimum(1, 2 * t)
    return c, cl.LoadPath.from_arrays(force=force, twist=phi)


@pytest.mark.parametrize("compiled", [False, True])
def test_annulus_steps_give_the_same_bits_with_fewer_slip_integrals(compiled, monkeypatch):
    c, path = _path(100)
    calls = {"n": 0}
    inner = ta.slip_kernel_integral

    def counted(*a, **k):
        calls["n"] += 1
        return inner(*a, **k)

    monkeypatch.setattr(ta, "slip_kernel_integral", counted)
    monkeypatch.setitem(ta._COMPILED, "on", compiled)
    runs = {}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for used in (False, True):
            if not used:        # the step before the running-integral test
                monkeypatch.setattr(ss, "running_turn_ok", lambda *a: False)
                monkeypatch.setattr(ss, "running_turn_ok_compiled", lambda *a: False)
            else:
                monkeypatch.undo()
                monkeypatch.setattr(ta, "slip_kernel_integral", counted)
                monkeypatch.setitem(ta._COMPILED, "on", compiled)
            calls["n"] = 0
            r = c.simulate(path, method="exact")
            runs[used] = (np.asarray(r.torque), np.asarray(r.dissipated_energy), calls["n"])
    assert np.array_equal(runs[True][0], runs[False][0])
    assert np.array_equal(runs[True][1], runs[False][1])
    # measured: 45 of the 100 steps needed the slip integrals before, 1 after
    assert runs[True][2] <= runs[False][2] // 4
