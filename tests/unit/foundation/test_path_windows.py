"""simulate() on long paths works a window of steps at a time (bounded memory, issue 13): the
windows must not change the result, and a radius outside double precision is refused."""
import contextlib

import numpy as np
import pytest

import contactlab as cl
from contactlab.foundation import base as B
from contactlab.foundation import winkler_path as P
from contactlab.errors import OutsideTheoryError, ValidityWarning
from tests.tolerances import WINDOWED_PATH


def _turns_reference(v0, v):
    """Direction reversals by a plain loop (independent of the vectorised windows)."""
    out, last, prev = [], 0.0, v0
    for j, x in enumerate(v):
        s = float(np.sign(x - prev))
        if s != 0.0:
            if last != 0.0 and s != last:
                out.append(j)
            last = s
        prev = x
    return np.array(out, int)


@pytest.mark.parametrize("window", [1, 2, 7, 1 << 16])
def test_turns_windows_match_a_plain_loop(monkeypatch, window):
    rng = np.random.default_rng(3)
    v = np.repeat(rng.integers(0, 4, 60).astype(float), rng.integers(1, 4, 60))
    monkeypatch.setattr(P, "_TURN_WINDOW", window)
    np.testing.assert_array_equal(P._turns(1.0, v), _turns_reference(1.0, v))


def _paths(c):
    a = c.normal(force=50.0).radius
    phi0 = 0.5 * 3 * 0.2 * 50.0 / (16 * c.moduli.torsional * a ** 2)
    k = np.arange(1, 301)
    F = 50.0 * (0.75 + 0.25 * np.sin(2 * np.pi * k / 70))
    F[100:140] = F[99]   # a held stretch inside the gait
    tw = phi0 * np.sin(2 * np.pi * k / 20)
    gait = cl.LoadPath().ramp(force=37.5, steps=1).then(
        cl.loadpath.Table.create(None, {"force": F, "twist": tw}))
    held = cl.LoadPath().ramp(force=50.0, steps=3).sinusoid(twist=phi0, cycles=5,
                                                             steps_per_cycle=20)
    return {"gait": gait, "held": held}


@pytest.mark.parametrize("name", ["gait", "held"])
def test_small_windows_do_not_change_the_result(monkeypatch, name):
    c = cl.Contact(cl.profiles.Paraboloid(R=0.01),
                   materials=(cl.Elastic(E=210e9, nu=0.3), cl.Elastic(E=210e9, nu=0.3)),
                   friction=0.2)
    path = _paths(c)[name]
    # the gait twists beyond the MDR springs' validity while the force changes: it warns
    warns = (lambda: pytest.warns(ValidityWarning, match="method='exact'")) if name == "gait" \
        else contextlib.nullcontext
    with warns():
        ref = c.simulate(path, n_springs=200, method="mdr", snapshots=[57])
    monkeypatch.setattr(P, "_CHUNK", 5)
    monkeypatch.setattr(P, "_FUSED_WINDOW", 6)
    monkeypatch.setattr(B, "SOLVE_CHUNK", 7)
    monkeypatch.setattr(P, "_TURN_WINDOW", 3)
    with warns():
        got = c.simulate(path, n_springs=200, method="mdr", snapshots=[57])
    for k in ref.data:
        a, b = np.asarray(ref.data[k], float), np.asarray(got.data[k], float)
        scale = max(float(np.max(np.abs(a))), 1e-300)
        assert np.max(np.abs(a - b)) <= WINDOWED_PATH * scale, k
    np.testing.assert_allclose(got.snapshots[57]["torsion"], ref.snapshots[57]["torsion"],
                               rtol=0, atol=WINDOWED_PATH * np.max(np.abs(ref.snapshots[57]["torsion"])))


def test_radius_outside_double_precision_is_refused():
    c = cl.Contact(cl.profiles.Cone.from_half_angle(1.0),
                   materials=(cl.Rigid(), cl.Elastic(E=1e6, nu=0.0)), friction=0.3)
    with pytest.raises(OutsideTheoryError, match="double precision"):
        c.simulate(cl.LoadPath().ramp(force=2.3e-284, torque=7e-5, steps=1), method="mdr")
