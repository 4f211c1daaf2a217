"""Energy of the exact torsion path solver (``contact.simulate(method="exact")``; issue 26
item 1): superposition after a force rise at held twist, the work as ``∫ M dφ`` (against the
closed-form torque, and additive when the steps are refined), no work at held twist, and the
balance of work, elastic energy and dissipation."""
from __future__ import annotations

import itertools

import numpy as np
import pytest
from scipy.integrate import quad

import contactlab as cl
from contactlab import LoadPath
from contactlab.profiles import FlatPunch, Paraboloid
from tests.tolerances import (
    ENERGY_BALANCE,
    ENERGY_REFINEMENT,
    ENERGY_STEP_ROUNDING,
    ENERGY_SUPERPOSITION,
    ENERGY_WORK_CLOSED_FORM,
)

STEEL = cl.Elastic(E=210e9, nu=0.3)


def contact():
    return cl.Contact(Paraboloid(0.01), materials=(STEEL, STEEL), friction=0.3)


def run(force, twist, **kw):
    return contact().simulate(LoadPath.from_arrays(force=force, twist=twist), method="exact",
                              **kw)


RAMP = np.linspace(0.0, 10.0, 6)[1:]


def rise_path(twisted: bool):
    """The reproduction of the issue: twist 0 -> 1.5 mrad at 10 N, the force up to 30 N at held
    twist, then +0.4 mrad in 20 steps (``twisted=False``: no twist before the rise)."""
    f = np.concatenate([RAMP, np.full(10, 10.0), np.linspace(10, 30, 11)[1:], np.full(20, 30.0)])
    pre = 1.5e-3 if twisted else 0.0
    tw = np.concatenate([np.zeros(5), np.linspace(0, pre, 11)[1:], np.full(10, pre),
                         pre + np.linspace(0, 0.4e-3, 21)[1:]])
    return f, tw


def test_superposition_after_a_force_rise_at_held_twist():
    """Each step after the rise dissipates what a fresh contact under the same force history
    dissipates for the same increments (the stick radius stays outside the 10 N contact, where
    the old density is zero); the old code gave 354, 81, 47 ... 4.9 times that (the stored energy
    dropped the gap between the old contact radius and the new stick radius)."""
    r, r0 = run(*rise_path(True)), run(*rise_path(False))
    # the per-step values (a difference of the cumulative series rounds at its running total)
    d = r.meta["energy"]["dissipated_per_step"][-20:]
    d0 = r0.meta["energy"]["dissipated_per_step"][-20:]
    assert np.all(np.abs(d - d0) <= ENERGY_SUPERPOSITION * np.abs(d0))
    a0 = float(contact().normal(force=10.0).radius)
    assert np.all(np.asarray(r.stick_radius)[-20:] > a0)       # the premise
    # torque: the old one plus the fresh one (linear elasticity, same slip annulus)
    M = np.asarray(r.torque)[-20:]
    M0 = np.asarray(r0.torque)[-20:] + np.asarray(r.torque)[-21]
    assert np.max(np.abs(M - M0)) < 1e-9 * np.max(np.abs(M))


def test_held_twist_does_no_work():
    """The force rise at held twist (10 annulus steps) books no work and no dissipation."""
    r = run(*rise_path(True))
    e = r.meta["energy"]
    dW = np.diff(e["work"])[14:24]
    assert np.all(np.abs(dW) <= ENERGY_BALANCE * np.max(e["stored"]))
    assert np.all(np.abs(e["dissipated_per_step"][15:25]) <= ENERGY_BALANCE * np.max(e["stored"]))


def test_falling_force_at_held_twist_dissipates_the_released_energy():
    """10 N twisted to 1.5 mrad, the force down to 7 N at held twist: the contact releases its
    outer ring by slip; no work, and what the elastic energy loses is dissipated (>= 0)."""
    f = np.concatenate([RAMP, np.full(10, 10.0), np.linspace(10, 7, 7)[1:]])
    tw = np.concatenate([np.zeros(5), np.linspace(0, 1.5e-3, 11)[1:], np.full(6, 1.5e-3)])
    r = run(f, tw)
    e = r.meta["energy"]
    held = slice(15, 21)
    scale = np.max(e["stored"])
    assert np.all(np.abs(np.diff(e["work"])[held.start - 1:held.stop - 1]) <= ENERGY_BALANCE
                  * scale)
    d = e["dissipated_per_step"][held]
    assert np.all(d > 0)
    np.testing.assert_allclose(d, -np.diff(e["stored"])[14:20], rtol=1e-9)


@pytest.mark.parametrize("n", [1, 3])
@pytest.mark.parametrize("flat", [False, True], ids=["paraboloid", "flat_punch"])
def test_work_of_a_twist_from_rest_is_the_integral_of_the_exact_torque(n, flat):
    """Twist from rest at 10 N in n steps: the booked work against ∫ M dφ of Jäger's
    closed-form torque (contact.torsion, method="exact") by scipy quad, whatever n (the old
    trapezoid was 18 % low at n = 1 on the paraboloid, 31 % on the flat punch, whose steps the
    ring solver alone takes)."""
    c = (cl.Contact(FlatPunch(1e-4), materials=(STEEL, STEEL), friction=0.3) if flat else
         contact())
    phi = 2e-3 if flat else 1.5e-3
    tw = np.concatenate([np.zeros(5), np.linspace(0, phi, n + 1)[1:]])
    f = np.concatenate([RAMP, np.full(n, 10.0)])
    r = c.simulate(LoadPath.from_arrays(force=f, twist=tw), method="exact")
    ref = quad(lambda p: float(c.torsion(force=10.0, twist=p, method="exact").torque), 0, phi,
               epsabs=0, epsrel=1e-12, limit=200)[0]
    assert r.meta["energy"]["work"][-1] == pytest.approx(ref, rel=ENERGY_WORK_CLOSED_FORM)


def test_work_and_dissipation_are_additive_under_step_refinement():
    """At held force a step is the continuous process of its family: twist cycles in 3 steps a
    run and in 12 give the same work and dissipation at the common steps."""
    pts = [0, 1.2e-3, -0.6e-3, 0.3e-3]

    def path(m):
        tw = np.concatenate([[0.0]] + [np.linspace(p, q, 3 * m + 1)[1:]
                                       for p, q in itertools.pairwise(pts)])
        return np.concatenate([RAMP, np.full(tw.size, 10.0)]), np.concatenate([np.zeros(5),
                                                                              tw])
    r1, r4 = run(*path(1)), run(*path(4))
    D1, D4 = np.asarray(r1.dissipated_energy)[5:], np.asarray(r4.dissipated_energy)[5:][::4]
    W1, W4 = r1.meta["energy"]["work"][5:], r4.meta["energy"]["work"][5:][::4]
    assert np.max(np.abs(D1 - D4)) <= ENERGY_REFINEMENT * D1[-1]
    assert np.max(np.abs(W1 - W4)) <= ENERGY_REFINEMENT * np.max(np.abs(W1))


def test_varying_load_steps_non_negative_and_balanced():
    """Force ±60 % and twist cycles together (steps of the ring solver among them): no step
    dissipates a negative energy; work = elastic energy + dissipation."""
    n = 80
    t = np.arange(1, n + 1) / n
    f = np.concatenate([RAMP, 10 * (1 + 0.6 * np.sin(2 * np.pi * 2 * t))])
    tw = np.concatenate([np.zeros(5), 1.5e-3 * np.sin(2 * np.pi * 3 * t)])
    r = run(f, tw, n_rings=60)
    e = r.meta["energy"]
    D = np.cumsum(e["dissipated_per_step"])
    assert np.all(e["dissipated_per_step"] >= -ENERGY_STEP_ROUNDING * D)
    scale = max(np.max(np.abs(e["work"])), np.max(e["stored"]))
    assert np.max(np.abs(e["work"] - e["stored"] - D)) <= ENERGY_BALANCE * scale


def test_without_friction_limit_a_shrinking_contact_dissipates_its_released_band():
    """No friction limit (rigid punches at the contact radii): 10 N twisted to 1 mrad, the force
    down to 5 N with the twist moving on. Growing steps dissipate nothing; a shrinking step
    dissipates the energy the band beyond the new radius held, 8 G_t ∫_a^a_old x² Ψ² dx with
    Ψ the old turn of the band (one punch per step: Ψ is the twist minus the turn inside); the
    old trapezoid booking gave negative steps here."""
    c = cl.Contact(Paraboloid(0.01), materials=(STEEL, STEEL), friction=None)
    f = np.concatenate([RAMP, np.full(4, 10.0), np.linspace(10, 5, 5)[1:]])
    tw = np.concatenate([np.zeros(5), np.linspace(0, 1e-3, 5)[1:], 1e-3 + np.linspace(0, 4e-4, 5)
                         [1:]])
    r = c.simulate(LoadPath.from_arrays(force=f, twist=tw), method="exact")
    e = r.meta["energy"]
    d = e["dissipated_per_step"]
    assert np.all(d[:9] == 0.0)
    assert np.all(d[9:] > 0)
    # step 9: before it the density is punches at a(10 N) (the twist steps at 10 N) and below;
    # the band (a(8.75 N), a(10 N)) held the twist of the punches at a(10 N): Ψ = their turn,
    # the twist 1 mrad minus the turn of the ramp's punches (there was none: twist 0 on the ramp)
    a_old, a_new = float(r.radius[8]), float(r.radius[9])
    G_t = c.moduli.torsional
    ref = 8 * G_t * 1e-3 ** 2 * (a_old ** 3 - a_new ** 3) / 3
    assert d[9] == pytest.approx(ref, rel=1e-12)
    D = np.cumsum(d)
    assert np.max(np.abs(e["work"] - e["stored"] - D)) <= ENERGY_BALANCE * np.max(e["stored"])
