"""A load path that fails part-way (issue 12): ``contact.simulate`` raises the error of the failing
step, with its type, naming the step (index, time, segment), and ``err.partial`` holds the steps
before it, equal to the first steps of the same run without the failure.

Failures are injected at a known step: a kernel of the spring foundation or of the exact ring
solver that raises there, or a measured table whose last radius the contact passes at a step known
from Hertz (``a = (3 F R / (4 E*))^(1/3)``), which the normal solve of every route meets.
"""
import numpy as np
import pytest

import contactlab as cl
import contactlab.foundation.winkler_path as winkler_path
import contactlab.physics.torsion_annulus as annulus
from contactlab.errors import ConvergenceError, OutsideTheoryError
from contactlab.foundation import Winkler
from tests.reference import hertz
from tests.tolerances import PARTIAL_PREFIX_NORMAL

R = 0.01
MAT = (cl.Elastic(E=210e9, nu=0.3), cl.Elastic(E=210e9, nu=0.3))
E_STAR = hertz.effective_modulus(210e9, 0.3, 210e9, 0.3)
#: 10 steps to 100 N, then 20 steps to 300 N while twisting, then 2 twist cycles (110 steps)
PATH = (cl.LoadPath().ramp(force=100.0, steps=10).ramp(force=300.0, twist=1e-3, steps=20)
        .sinusoid(twist=1e-3, cycles=2, steps_per_cycle=40))


def contact(profile=None):
    return cl.Contact(profile or cl.profiles.Paraboloid(R=R), materials=MAT, friction=0.2)


def check_partial(err, full, k, segment):
    part = err.partial
    assert err.failed_at["step"] == k and err.failed_at["segment"] == segment
    assert err.failed_at["time"] == full.time[k] and err.failed_at["n_steps"] == len(full)
    assert f"step {k} of {len(full)} failed" in str(err) and "injected" in str(err)
    assert len(part) == k and part.meta["status"] == "partial"
    assert part.meta["failed_at"]["step"] == k and "ConvergenceError" in part.meta["error"]
    for name, v in part.data.items():          # the same steps as the run without the failure
        np.testing.assert_array_equal(v, full.data[name][:k], err_msg=name)


# the MDR springs warn beyond their validity twist: not the subject here
@pytest.mark.filterwarnings("ignore::contactlab.errors.ValidityWarning")
def test_spring_route_step_by_step(monkeypatch):
    """A step of the MDR springs (numpy step-by-step route) fails at step 17."""
    monkeypatch.setattr(winkler_path, "_fused_step", lambda fnd, chans: None)
    full = contact().simulate(PATH, method="mdr")
    d_fail = full.depth[17]
    orig = Winkler.set_normal

    def set_normal(self, st, d, *a, **k):
        if d >= d_fail:
            raise ConvergenceError("injected")
        return orig(self, st, d, *a, **k)
    monkeypatch.setattr(Winkler, "set_normal", set_normal)
    with pytest.raises(ConvergenceError) as e:
        contact().simulate(PATH, method="mdr")
    check_partial(e.value, full, 17, 1)


# the MDR springs warn beyond their validity twist: not the subject here
@pytest.mark.filterwarnings("ignore::contactlab.errors.ValidityWarning")
def test_spring_route_block(monkeypatch):
    """The closed-form block of a held-load twist run fails: the steps before the block stay."""
    full = contact().simulate(PATH, method="mdr")
    calls = []
    orig = winkler_path.monotone_block

    def block(*a, **k):
        calls.append(1)
        if len(calls) == 2:
            raise ConvergenceError("injected")
        return orig(*a, **k)
    monkeypatch.setattr(winkler_path, "monotone_block", block)
    with pytest.raises(ConvergenceError) as e:
        contact().simulate(PATH, method="mdr")
    k = e.value.failed_at["step"]
    # the first block is the first quarter cycle (steps 30-39), the second starts at step 40
    assert k == 40
    check_partial(e.value, full, k, 2)


def test_exact_ring_route(monkeypatch):
    """The exact solver's step (one punch-density step call per step) fails at step 39."""
    full = contact().simulate(PATH, snapshots=[5, 50])
    assert full.meta["method"] == "exact"
    calls = []
    orig = annulus.step

    def box_step(*a, **k):
        calls.append(1)
        if len(calls) == 40:
            raise ConvergenceError("injected")
        return orig(*a, **k)
    monkeypatch.setattr(annulus, "step", box_step)
    with pytest.raises(ConvergenceError) as e:
        contact().simulate(PATH, snapshots=[5, 50])
    check_partial(e.value, full, 39, 2)
    assert sorted(e.value.partial.snapshots) == [5]     # the snapshot at step 50 never came


def short_table(n=200, r_last=2e-4):
    r = np.linspace(0.0, r_last, n)
    return cl.profiles.Tabulated(r, r**2 / (2 * R))


def first_step_beyond(forces, r_last):
    """First step whose Hertz radius leaves the table (none within 0.5 % of its end: the
    200-node interpolant moves radii by ~1e-5)."""
    a = hertz.radius_of_force(forces, R, E_STAR)
    assert np.all(np.abs(a / r_last - 1) > 0.005)
    return int(np.argmax(a > r_last))


@pytest.mark.parametrize("method", ["mdr", "exact"])
def test_normal_solve_leaves_the_table(method):
    """The contact passes the table's last radius at step 12 (120 N -> 130 N): the normal solve
    (vectorised per segment) names that step; the partial result holds the normal series of the
    steps before it (the tangential time loop had not started)."""
    c = contact(short_table())
    path = cl.LoadPath().ramp(force=100.0, steps=10).ramp(force=300.0, twist=1e-3, steps=20)
    forces = np.concatenate((np.linspace(10, 100, 10), np.linspace(110, 300, 20)))
    k = first_step_beyond(forces, 2e-4)
    assert k == 12
    with pytest.raises(OutsideTheoryError) as e:
        c.simulate(path, method=method)
    err = e.value
    assert err.failed_at["step"] == k and err.failed_at["segment"] == 1
    assert err.failed_at["time"] == k + 1.0         # unit time steps; step 0 ends at t = 1 s
    assert f"step {k} of 30 failed" in str(err) and "beyond the table" in str(err)
    part = err.partial
    assert set(part.data) == {"time", "depth", "force", "radius"} and len(part) == k
    ref = c.normal(force=forces[:k])
    np.testing.assert_allclose(part.force, forces[:k], rtol=PARTIAL_PREFIX_NORMAL)
    np.testing.assert_allclose(part.radius, ref.radius, rtol=PARTIAL_PREFIX_NORMAL)
    np.testing.assert_allclose(part.depth, ref.depth, rtol=PARTIAL_PREFIX_NORMAL)
