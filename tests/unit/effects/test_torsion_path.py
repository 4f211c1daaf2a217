"""Exact torsion along load paths (contact.simulate(path, method="exact"), issue 18)."""
import numpy as np
import pytest

import contactlab as cl
from contactlab.foundation import rings as ring_module
from contactlab.physics.torsion import METHODS
from contactlab.errors import (NotSupportedError, ParameterError, UnknownNameError,
                               ValidityWarning)
from tests.reference import hertz
from tests.reference.torsion_rings_bruteforce import torque_history
from tests.tolerances import (RINGS_CONSTANT_LOAD, RINGS_CONSTANT_LOAD_FINE,
                              RINGS_DISSIPATION_800_STEPS, RINGS_FULL_SLIDING,
                              RINGS_FULL_SLIDING_VARYING, RINGS_FLAT_PUNCH,
                              RINGS_NO_SLIP_GROWING, RINGS_STICK_RADIUS, RINGS_VS_BRUTE_FORCE,
                              RINGS_WORK_BALANCE, RINGS_NO_SLIP,
                              RINGS_DISSIPATION_QUADRATURE, RINGS_COMPLEMENTARITY,
                              RINGS_SLIDING_PROJECTION,
                              RINGS_TORQUE_INVERSION, ENERGY_STEP_ROUNDING)

R, MU, F = 0.01, 0.3, 10.0
MAT = (cl.Elastic(E=210e9, nu=0.3), cl.Rigid())
E_STAR = hertz.effective_modulus(210e9, 0.3)


def ring_run(c, path, n_rings, **switches):
    """The ring solver with its ablation switches off (``Rings.SWITCHES``; ``simulate`` does not
    expose them), as a PathResult."""
    from contactlab.effects import path as driver
    return driver._run(driver.METHODS["exact"], "exact", c, path, None, None, False,
                       {"n_rings": n_rings, **switches})


def contact(mu=MU):
    return cl.Contact(cl.profiles.Paraboloid(R=R), materials=MAT, friction=mu)


def scales(c, force=F):
    a = hertz.radius_of_force(force, R, E_STAR)
    G = c.moduli.torsional
    return a, MU * force / (G * a * a), 3 * np.pi / 16 * MU * force * a


def histories(s):
    rng = np.random.default_rng(1)
    return {"monotone": np.linspace(0.02, 1.2, 12) * s,
            "oscillating": 0.6 * s * np.sin(np.linspace(0.2, 4 * np.pi, 24)),
            "irregular": np.cumsum(rng.normal(0, 0.25, 24)) * s}


def at_constant_load(phi):
    return (cl.LoadPath().ramp(force=F, steps=2)
            + cl.LoadPath.from_arrays(twist=phi, force=np.full(phi.size, F)))


@pytest.mark.parametrize("name", ["monotone", "oscillating", "irregular"])
def test_constant_load_reproduces_the_exact_twist_history(name):
    c = contact()
    a, s, M_full = scales(c)
    phi = histories(s)[name]
    ref = c.twist_history(twist=phi, force=F).torque
    coarse = np.max(np.abs(c.simulate(at_constant_load(phi), method="exact", n_rings=50).torque[2:]
                           - ref)) / M_full
    default = np.max(np.abs(c.simulate(at_constant_load(phi), method="exact").torque[2:] - ref))
    fine = np.max(np.abs(c.simulate(at_constant_load(phi), method="exact", n_rings=400).torque[2:]
                         - ref)) / M_full
    assert default / M_full < RINGS_CONSTANT_LOAD
    assert fine < RINGS_CONSTANT_LOAD_FINE
    # the error falls with refinement at order >= 2.3 (measured 2.6 to 2.8 from 50 to 400 rings:
    # 50, 100, 200, 400, 800 rings 1.8e-5, 2.7e-6, 3.9e-7, 5.6e-8, 9.8e-9 on the monotone one)
    assert coarse / fine > 8.0 ** 2.3


def test_full_sliding_traction_is_mu_p_and_torque_the_sliding_torque():
    c = contact()
    a, s, M_full = scales(c)
    path = cl.LoadPath().ramp(force=F, steps=2).ramp(twist=50 * s, steps=1)
    r = c.simulate(path, method="exact", snapshots=[-1])
    snap = r.snapshots[2]
    p0 = 3 * F / (2 * np.pi * a * a)
    p_ref = p0 * np.sqrt(np.clip(1 - (snap["r"] / a) ** 2, 0, None))
    assert np.allclose(snap["shear_torsion"], MU * p_ref, rtol=1e-9, atol=1e-9 * MU * p0)
    assert r.torque[-1] == pytest.approx(M_full, rel=RINGS_FULL_SLIDING)
    assert r.stick_radius[-1] == 0.0


def test_no_slip_stiffness_with_a_growing_contact():
    c = contact(mu=None)
    force = np.linspace(2.0, 10.0, 30)
    a = hertz.radius_of_force(force, R, E_STAR)
    phi = np.linspace(1e-4, 3e-3, 30)
    dphi = np.diff(np.concatenate(([0.0], phi)))
    path = cl.LoadPath.from_arrays(force=force, twist=phi)
    r = c.simulate(path, method="exact", snapshots=[29])
    assert r.meta["punches"]
    dM = np.diff(np.concatenate(([0.0], r.torque)))
    k = 16.0 / 3.0 * c.moduli.torsional
    assert np.max(np.abs(dM / dphi / (k * a ** 3) - 1)) < RINGS_NO_SLIP
    # nothing slips: the work (trapezoid in the twist) is all stored, 8 G_t ∫ x² Ψ² dx
    en = r.meta["energy"]
    assert np.max(np.abs(r.dissipated_energy)) < RINGS_NO_SLIP * en["work"][-1]
    # the traction is the Reissner–Sagoci sum of the increments (each of its radius)
    x = r.snapshots[29]["r"]
    ref = np.array([4 * c.moduli.torsional / np.pi * xi *
                    np.sum(dphi[a > xi] / np.sqrt(a[a > xi] ** 2 - xi ** 2)) for xi in x])
    assert np.allclose(r.snapshots[29]["shear_torsion"], ref, rtol=1e-12, atol=0)
    # the ring solver alone (point tractions on continuous densities) is first order here: each
    # increment is a rigid punch of an inner-node radius, whose r/sqrt(a² − r²) edge traction
    # the densities smear over the ring beyond it (measured 7.5e-3, 4.2e-3, 2.2e-3, 9.6e-4 at 100,
    # 200, 400, 800 rings, the same for a shrinking contact and already at the first step)
    err = {}
    for n in (100, 200):
        q = ring_run(c, path, n, annulus=False)
        dM = np.diff(np.concatenate(([0.0], q.torque)))
        err[n] = np.max(np.abs(dM / dphi / (k * a ** 3) - 1))
    assert err[200] < RINGS_NO_SLIP_GROWING and err[100] / err[200] > 1.5
    # without the traction-free entry (rings entering with the current rigid rotation) the
    # torque would follow (16/3) G_t a³ φ, far from this history
    assert abs(r.torque[-1] / (16 / 3 * c.moduli.torsional * a[-1] ** 3 * phi[-1]) - 1) > 0.1


def test_work_balance_and_dissipation_per_step():
    c = contact()
    a, s, M_full = scales(c)
    t = np.linspace(0, 1, 120)
    force = F * (1 + 0.3 * np.sin(2 * np.pi * 2 * t))
    phi = 0.7 * s * np.sin(2 * np.pi * 3 * t)
    r = c.simulate(cl.LoadPath.from_arrays(force=force, twist=phi), method="exact")
    en = r.meta["energy"]
    scale = np.max(np.abs(en["work"]))
    assert np.max(np.abs(en["work"] - en["stored"] - r.dissipated_energy)) < \
        RINGS_WORK_BALANCE * scale
    assert np.allclose(np.diff(np.concatenate(([0.0], r.dissipated_energy))),
                       en["dissipated_per_step"], rtol=0, atol=1e-12 * scale)
    assert r.dissipated_energy[-1] > 0


@pytest.mark.parametrize("steps", [50, 800])
def test_dissipated_energy_converges_to_the_exact_history(steps):
    """Against Masing/Jäger's exact dissipation (twist_history): each step's work is ∫ M dφ
    along the step, so the step count does not matter (the trapezoid was 1.6e-2 off at 50)."""
    c = contact()
    a, s, M_full = scales(c)
    phi = 0.6 * s * np.sin(np.linspace(0, 4 * np.pi, steps + 1)[1:])
    ref = c.twist_history(twist=phi, force=F)
    r = c.simulate(at_constant_load(phi), method="exact", n_rings=100)
    err = np.max(np.abs(r.dissipated_energy[2:] - ref.dissipated_energy))
    assert err / ref.dissipated_energy.max() < RINGS_DISSIPATION_800_STEPS


def test_torque_control_inverts_twist_control():
    c = contact()
    a, s, M_full = scales(c)
    phi = histories(s)["oscillating"][:12]
    tw = c.simulate(at_constant_load(phi), method="exact", n_rings=100)
    path = (cl.LoadPath().ramp(force=F, steps=2)
            + cl.LoadPath.from_arrays(torque=tw.torque[2:], force=np.full(phi.size, F)))
    tq = c.simulate(path, method="exact", n_rings=100)
    assert np.allclose(tq.twist[2:], phi, rtol=1e-8, atol=1e-10 * s)


def test_varying_load_against_independent_brute_force():
    c = contact()
    n = 16
    t = np.arange(1, n + 1) / n
    force = F * (1 + 0.35 * np.sin(2 * np.pi * t + 0.3))
    a = hertz.radius_of_force(force, R, E_STAR)
    a_max, s, M_full = scales(c, float(force.max()))
    phi = 0.8 * s * np.sin(2 * np.pi * 1.5 * t)
    r = c.simulate(cl.LoadPath.from_arrays(force=force, twist=phi), method="exact", n_rings=120)
    p0 = 3 * force / (2 * np.pi * a * a)

    def bound(k, rr):
        return MU * p0[k] * np.sqrt(np.clip(1 - (rr / a[k]) ** 2, 0, None))

    ref = torque_history(float(a.max()), c.moduli.torsional, bound, phi, 300)
    assert np.max(np.abs(r.torque - ref)) / M_full < RINGS_VS_BRUTE_FORCE


def test_same_call_bit_identical_and_errors():
    c = contact()
    path = cl.LoadPath.from_arrays(force=[5.0, 8.0, 6.0], twist=[1e-4, 3e-4, -2e-4])
    r1 = c.simulate(path, method="exact", n_rings=60)
    r2 = c.simulate(path, method="exact", n_rings=60)
    assert np.array_equal(r1.torque, r2.torque)
    with pytest.raises(UnknownNameError, match="method='springs'"):
        c.simulate(path, method="springs")
    shift = cl.LoadPath.from_arrays(force=[5.0, 6.0], displacement=[1e-7, 2e-7])
    with pytest.raises(NotSupportedError, match="method='mdr'"):
        c.simulate(shift, method="exact")
    # the force changes while twisted: the MDR springs' dissipated energy is outside validity
    with pytest.warns(ValidityWarning, match="dissipated energy: outside"):
        mdr = c.simulate(path, method="mdr")
    assert mdr.meta.get("method", "mdr") != "exact"


def test_error_estimate_bounds_the_error():
    c = contact()
    a, s, M_full = scales(c)
    phi = histories(s)["irregular"]
    ref = c.twist_history(twist=phi, force=F).torque
    r = c.simulate(at_constant_load(phi), method="exact", n_rings=100, error_estimate=True)
    err = np.max(np.abs(r.torque[2:] - ref)) / np.max(np.abs(r.torque))
    assert err <= r.meta["error_estimates"]["torque"]


@pytest.mark.parametrize("arg", [{"n_springs": 100}, {"spacing": "uniform"},
                                 {"strategy": "steps"}])
def test_spring_arguments_on_the_ring_solver_raise(arg):
    c = contact()
    path = cl.LoadPath.from_arrays(force=[5.0, 8.0, 6.0], twist=[1e-5, 3e-5, -2e-5])
    (name, value), = arg.items()
    for method in (None, "exact"):      # the default of a twisted path is the ring solver
        with pytest.raises(ParameterError, match=rf"{name}={value!r} applies to method='mdr'"):
            c.simulate(path, method=method, **arg)
    with pytest.warns(ValidityWarning, match="dissipated energy: outside"):  # force changes
        r = c.simulate(path, method="mdr", **arg)     # where they apply, they are used
    assert r.meta.get("method") != "exact"
    assert r.meta["spacing"] == arg.get("spacing", "edge")
    assert r.meta["n_springs"] == arg.get("n_springs", r.meta["n_springs"])


def test_ring_argument_on_the_springs_raises():
    c = contact()
    twisted = cl.LoadPath.from_arrays(force=[5.0, 8.0, 6.0], twist=[1e-5, 3e-5, -2e-5])
    shifted = cl.LoadPath.from_arrays(force=[5.0, 6.0], displacement=[1e-8, 2e-8])
    for path, method in ((twisted, "mdr"), (shifted, None)):
        with pytest.raises(ParameterError, match="n_rings=50 applies to method='exact'"):
            c.simulate(path, method=method, n_rings=50)
    assert c.simulate(twisted, n_rings=50).meta["n_rings"] == 50


def flat_punch():
    return cl.Contact(cl.profiles.FlatPunch(radius=1e-3), materials=MAT, friction=MU)


@pytest.mark.parametrize("name", ["monotone", "oscillating", "irregular"])
def test_flat_punch_reproduces_the_exact_twist_history(name):
    """Singular edge pressure: the edge punch in the basis carries the square-root singular
    traction, so the error falls at order ~2 like a smooth profile (without it: order 0.5, 5 % at
    200 rings)."""
    c, a, Fp = flat_punch(), 1e-3, 100.0
    s = MU * Fp / (c.moduli.torsional * a * a)
    M_full = np.pi / 4 * MU * Fp * a                 # 2πμ∫ p r² dr, p = F/(2πa sqrt(a² − r²))
    phi = histories(s)[name]
    ref = c.twist_history(twist=phi, force=Fp).torque
    path = (cl.LoadPath().ramp(force=Fp, steps=2)
            + cl.LoadPath.from_arrays(twist=phi, force=np.full(phi.size, Fp)))
    coarse = np.max(np.abs(c.simulate(path, n_rings=50).torque[2:] - ref)) / M_full
    r = c.simulate(path)
    default = np.max(np.abs(r.torque[2:] - ref)) / M_full
    assert r.meta["edge_punch"] and default < RINGS_FLAT_PUNCH
    assert coarse / max(default, 1e-12) > 4.0 ** 1.5     # measured 4.0 ** 2.3


def test_contact_edge_on_a_node_under_a_changing_load():
    """Nodes at the path's contact radii: 3-4x below the uniform grid's error at 200 rings against
    a fine run (measured 1.4e-4 vs 4.4e-4 of the sliding torque on this path against 800 rings,
    9.8e-5 vs 4.5e-4 on its 180-step version)."""
    c = contact()
    n = 90
    t = np.arange(1, n + 1) / n
    force = F * (1 + 0.4 * np.sin(2 * np.pi * 2 * t + 0.3))
    a_max, s, M_s = scales(c, float(force.max()))
    path = cl.LoadPath.from_arrays(force=force, twist=0.8 * s * np.sin(6 * np.pi * t)
                                   * np.minimum(1, 2 * t))
    ref = c.simulate(path, n_rings=400).torque
    aligned = c.simulate(path)
    uniform = ring_run(c, path, 200, align=False)
    assert aligned.meta["aligned"] and 200 < aligned.meta["rings"] <= 300
    err_a = np.max(np.abs(aligned.torque - ref)) / M_s
    err_u = np.max(np.abs(uniform.torque - ref)) / M_s
    assert err_a < 0.5 * err_u


@pytest.mark.parametrize("mu", [MU, None])
def test_slip_limits_in_chunks_change_nothing(monkeypatch, mu):
    """The rings' slip limits are computed a chunk of steps at a time (memory); chunks of 3 steps
    give bit-identical series, snapshots and energies (twist, then torque control, then a hold)."""
    c = contact(mu)
    a, s, M_full = scales(c)
    t = np.arange(1, 17) / 16
    path = (cl.LoadPath.from_arrays(force=F * (1 + 0.3 * np.sin(2 * np.pi * t)),
                                    twist=0.7 * s * np.sin(3 * np.pi * t))
            .ramp(torque=0.2 * M_full, steps=7).hold(steps=4))
    runs = []
    for chunk in (ring_module._BOUND_CHUNK, 3):
        monkeypatch.setattr(ring_module, "_BOUND_CHUNK", chunk)
        runs.append(c.simulate(path, method="exact", n_rings=40, snapshots=[0, 5, 17, -1]))
    ref, small = runs
    for k in ref.data:
        assert np.array_equal(ref.data[k], small.data[k]), k
    for k in ref.meta["energy"]:
        assert np.array_equal(ref.meta["energy"][k], small.meta["energy"][k]), k
    for i in ref.snapshots:
        for q in ref.snapshots[i]:
            assert np.array_equal(ref.snapshots[i][q], small.snapshots[i][q]), (i, q)


@pytest.mark.parametrize("kind", ["linear", "cubic"])
def test_table_ring_pressures_from_running_sums(monkeypatch, kind):
    """On a table the ring pressures come from running sums over its segments, set up once
    (physics.ring_pressure): the same series as the per-step route (the profile's pressure at
    every ring and step) to RING_PRESSURE_PATH, and chunks of 3 steps give bit-identical series."""
    from contactlab.profiles import Tabulated
    from tests.tolerances import RING_PRESSURE_PATH
    r = np.linspace(0.0, 2e-3, 200)
    c = cl.Contact(Tabulated(r, r**2 / (2 * R) + 2.0 * r**4, kind), materials=MAT, friction=MU)
    a, s, M_full = scales(c)
    t = np.arange(1, 41) / 40
    path = (cl.LoadPath().ramp(force=0.7 * F, steps=2)
            + cl.LoadPath.from_arrays(force=F * (1 + 0.3 * np.sin(2 * np.pi * t)),
                                      twist=0.7 * s * np.sin(3 * np.pi * t)))
    fast = c.simulate(path, n_rings=60)
    slow = ring_run(c, path, 60, ring_table=False)
    for k in ("torque", "dissipated_energy", "stick_radius"):
        ref = np.asarray(slow.data[k])
        assert np.max(np.abs(np.asarray(fast.data[k]) - ref)) <= RING_PRESSURE_PATH * np.max(np.abs(ref)), k
    monkeypatch.setattr(ring_module, "_BOUND_CHUNK", 3)
    small = c.simulate(path, n_rings=60)
    for k in fast.data:       # node sums grouped in fixed blocks: no chunk-dependent rounding
        assert np.array_equal(fast.data[k], small.data[k]), k


def test_no_slip_with_a_shrinking_contact_is_the_rigid_punch_of_the_current_radius():
    """No slip, the twist starting at the largest contact: every point of the current contact has
    turned rigidly with the twist since, so M = (16/3) G_t a³ φ at every step (the points leaving
    the contact release their traction)."""
    c = contact(mu=None)
    force = np.linspace(10.0, 2.0, 30)
    a = hertz.radius_of_force(force, R, E_STAR)
    phi = np.linspace(1e-4, 3e-3, 30)
    path = cl.LoadPath.from_arrays(force=force, twist=phi)
    r = c.simulate(path, method="exact")
    ratio = r.torque / (16.0 / 3.0 * c.moduli.torsional * a ** 3 * phi)
    assert np.max(np.abs(ratio - 1)) < RINGS_NO_SLIP
    q = ring_run(c, path, 200, annulus=False)
    ratio = q.torque / (16.0 / 3.0 * c.moduli.torsional * a ** 3 * phi)
    assert np.max(np.abs(ratio - 1)) < RINGS_NO_SLIP_GROWING


def test_full_sliding_at_every_step_of_a_changing_load():
    """Twist increments far beyond full sliding, with the force changing every step and the twist
    reversing halfway: τ = ±μp at every point and M = ±(3π/16) μ F a (Hertz) at every step; the
    contact edge is an inner node of the rings at most steps (the jump of the density there)."""
    c = contact()
    n = 20
    t = np.arange(1, n + 1) / n
    force = F * (1 + 0.4 * np.sin(2 * np.pi * t + 0.3))
    a = hertz.radius_of_force(force, R, E_STAR)
    s = MU * F / (c.moduli.torsional * a.min() ** 2)
    phi = np.concatenate([50 * s * np.arange(1, 11), 50 * s * (10 - 2 * np.arange(1, 11))])
    r = c.simulate(cl.LoadPath.from_arrays(force=force, twist=phi), method="exact",
                   snapshots=list(range(n)))
    sense = np.where(np.arange(n) < 10, 1.0, -1.0)
    M_s = 3 * np.pi / 16 * MU * force * a
    assert np.max(np.abs(r.torque / (sense * M_s) - 1)) < RINGS_FULL_SLIDING_VARYING
    assert r.meta["jump_nodes"] > 0
    for k in range(n):
        snap = r.snapshots[k]
        p0 = 3 * force[k] / (2 * np.pi * a[k] ** 2)
        p = p0 * np.sqrt(np.clip(1 - (snap["r"] / a[k]) ** 2, 0, None))
        assert np.allclose(snap["shear_torsion"], sense[k] * MU * p, rtol=0, atol=1e-9 * MU * p0)


def test_stick_radius_follows_the_exact_twist_history():
    """Stick radius at constant load against Jäger/Masing's (twist_history), within a ring."""
    c = contact()
    a, s, _ = scales(c)
    for name, phi in histories(s).items():
        ref = c.twist_history(twist=phi, force=F).stick_radius
        r = c.simulate(at_constant_load(phi), method="exact")
        assert np.max(np.abs(r.stick_radius[2:] - ref)) < RINGS_STICK_RADIUS * a / 200, name


def varying_load_with_snapshots(n_rings):
    c = contact()
    a, s, M_full = scales(c)
    n = 60
    t = np.arange(1, n + 1) / n
    path = cl.LoadPath.from_arrays(force=F * (1 + 0.3 * np.sin(2 * np.pi * t + 0.3)),
                                   twist=0.8 * s * np.sin(2 * np.pi * 2 * t))
    return c, c.simulate(path, method="exact", n_rings=n_rings, snapshots=list(range(n)))


def test_dissipation_from_the_returned_fields_by_independent_quadrature():
    """Per step, ∫ 2πr τ_new Δs dr from the returned fields (point tractions and slip
    increments at the snapshots: the end traction times the slip, the dissipation of a step),
    integrated by scipy's adaptive quadrature on a monotone cubic interpolant, against the
    solver's dissipation, on the steps whose contact does not shrink (a shrinking contact's
    step also releases the outer density, booked as a release at the held twist: see
    ``docs/torsion_varying_load.md``, how energy is booked)."""
    from scipy.integrate import quad
    from scipy.interpolate import PchipInterpolator
    _, r = varying_load_with_snapshots(100)
    per_step = r.meta["energy"]["dissipated_per_step"]
    total = per_step.sum()
    q = np.zeros(per_step.size)
    rest = {"radius": 0.0, "shear_torsion": 0.0}
    grows = np.zeros(per_step.size, bool)
    for k in range(per_step.size):
        old, new = r.snapshots[k - 1] if k else rest, r.snapshots[k]
        grows[k] = new["radius"] >= old["radius"]
        x = new["r"]
        reach = max(old["radius"], new["radius"])
        f = 2 * np.pi * x * new["shear_torsion"] * new["slip_increment"]
        m = x < reach
        xx = np.concatenate([[0.0], x[m], [reach]])
        ff = np.concatenate([[0.0], f[m], [0.0]])
        q[k] = quad(PchipInterpolator(xx, ff), 0.0, reach, points=xx[1:-1], limit=4000)[0]
    assert grows.sum() >= per_step.size // 3
    assert np.max(np.abs(q - per_step)[grows]) < RINGS_DISSIPATION_QUADRATURE * total
    assert np.all(per_step >= -ENERGY_STEP_ROUNDING * np.cumsum(per_step))
    assert r.dissipated_energy[-1] == pytest.approx(total, rel=1e-12)


def test_returned_fields_obey_coulomb_at_every_step():
    """|τ| <= μp at every point, slip along τ where it slides, and no slip where the traction is
    below μp (the fields of the punch-density steps and of the ring steps alike) except where
    the full-sliding density was held to Ψ >= 0: there the band of the edge ring it removes
    carries less than μp while it slides, and the points inside see that band's traction
    (RINGS_SLIDING_PROJECTION beyond the edge ring; docs/torsion_varying_load.md)."""
    _, r = varying_load_with_snapshots(100)
    for k, snap in r.snapshots.items():
        tau, lim, ds = snap["shear_torsion"], MU * snap["pressure"], snap["slip_increment"]
        x = snap["r"]
        inside = x < snap["radius"]
        scale = lim.max()
        assert np.all(np.abs(tau[inside]) <= lim[inside] + RINGS_COMPLEMENTARITY * scale), k
        edge_ring = x >= snap["radius"] - np.max(np.diff(x[inside]), initial=0.0)
        below = inside & (np.abs(tau) < lim - np.where(edge_ring, np.inf,
                                                         RINGS_SLIDING_PROJECTION) * scale)
        assert np.all(ds[below] == 0), k
        sliding = inside & (ds != 0)
        assert np.all(np.sign(ds[sliding]) * tau[sliding] >= 0), k
        assert np.all(np.sign(ds[sliding & ~edge_ring]) == np.sign(tau[sliding & ~edge_ring])), k


def test_torque_control_fallback_steps_reach_the_torque():
    """Torque control on a cone with the force changing ±30 %: the steps with two slip zones go to
    the ring solver, whose own torque measure (g·z) of the old tractions differs from the exact
    torque of the density. Twist control along the twist the torque run returns must give back
    the prescribed torque at every step, fallback steps included."""
    c = cl.Contact(cl.profiles.Cone(slope=0.02), materials=MAT, friction=MU)
    n = 180
    t = np.arange(1, n + 1) / n
    force = F * (1 + 0.3 * np.sin(2 * np.pi * 2 * t + 0.3))
    ns = c.normal(force=F)
    M_sl = float(METHODS["exact"](c.profile, c.moduli.normal, c.moduli.torsional, MU, c.rtol)
                 .sliding_torque(np.array([float(ns._radius)]), np.array([float(ns._depth)]))[0])
    torque = 0.6 * M_sl * np.sin(2 * np.pi * 3 * t) * np.minimum(1, 2 * t)
    tq = c.simulate(cl.LoadPath.from_arrays(force=force, torque=torque), method="exact",
                    n_rings=100)
    assert tq.meta["fallback_steps"] > 0
    tw = c.simulate(cl.LoadPath.from_arrays(force=force, twist=tq.twist), method="exact",
                    n_rings=100)
    assert np.max(np.abs(tw.torque - torque)) / np.max(np.abs(torque)) < RINGS_TORQUE_INVERSION


def test_torque_control_out_of_contact_without_friction_limit():
    """A frictionless torque-controlled path opening at zero load (as a scene's path does: its
    start step) ran into a division by the contact radius 0 (ZeroDivisionError). Out of contact
    no punch carries a torque: the twist is held, and a torque target other than 0 is gross
    sliding. The rest of the path is that of the path without the start step."""
    from tests.tolerances import ZERO_LOAD_START
    c = contact(mu=None)
    t = np.arange(1, 41) / 40
    rest = (cl.LoadPath().ramp(force=F, steps=4)
            + cl.LoadPath.from_arrays(force=F * (1 + 0.3 * np.sin(2 * np.pi * t)),
                                      torque=2e-4 * np.sin(3 * np.pi * t)))
    ref = c.simulate(rest)
    got = c.simulate(cl.LoadPath.from_arrays(force=[0.0], torque=[0.0]) + rest)
    assert got.meta["method"] == "exact" and got.meta["punches"]
    assert got.torque[0] == 0.0 and got.twist[0] == 0.0 and not got.gross_sliding.any()
    for k in ("torque", "twist", "stick_radius", "dissipated_energy"):
        a, b = getattr(got, k)[1:], getattr(ref, k)
        assert np.max(np.abs(a - b)) <= ZERO_LOAD_START * np.max(np.abs(b)), k
    pushed = c.simulate(cl.LoadPath.from_arrays(force=[0.0], torque=[1e-4]) + rest)
    assert pushed.gross_sliding[0] and pushed.twist[0] == 0.0 and pushed.torque[0] == 0.0
