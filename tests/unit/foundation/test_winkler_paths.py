"""The MDR foundation under load paths (contact.simulate) against independent closed forms:
normal contact (§3), Cattaneo–Mindlin and Mindlin–Deresiewicz (§5), oblique loading, and the MDR
torsion model (§6.4). Closed forms are re-implemented here, independently of the package."""
import numpy as np
import pytest

import contactlab as cl
from contactlab.errors import OutsideTheoryError, ValidityWarning
from contactlab.foundation import DEFAULT_N_SPRINGS, Winkler

from tests import tolerances as TOL
from tests.reference import hertz as hz
from tests.tolerances import (ENERGY_DRIFT, FOUNDATION_CM, FOUNDATION_NORMAL, FOUNDATION_TORSION)

MU = 0.2
STEEL = cl.Elastic(E=210e9, nu=0.3)
PMMA = cl.Elastic(E=3e9, nu=0.35)
R = 0.01
F = 100.0


def hertz(mu=MU):
    return cl.Contact(cl.profiles.Paraboloid(R=R), materials=(STEEL, STEEL), friction=mu)


def cone():
    return cl.Contact(cl.profiles.Cone(slope=0.1), materials=(STEEL, PMMA), friction=MU)


# ------------------------------------------------------------------ independent closed forms
def hertz_normal(c, d):
    """Hertz: a = sqrt(R d), F = 4E*a³/(3R) (d > 0)."""
    d = np.maximum(d, 0)
    a = np.sqrt(R * d)
    return a, 4 * c.moduli.normal * a ** 3 / (3 * R)


def cm_virgin(FN, us, n, u):
    """Cattaneo–Mindlin for f = c r^n (§5): F_x = μF_N[1-(1-u/u*)^((n+1)/n)], u* = μE* d/G*."""
    x = np.clip(np.abs(u) / us, 0, 1)
    return np.sign(u) * MU * FN * (1 - (1 - x) ** ((n + 1) / n))


def cm_loop(FN, us, n, u, u_turn):
    """Masing: after a turning point u_turn (force F_t) F = F_t - 2 F_load((u_turn - u)/2)."""
    return cm_virgin(FN, us, n, u_turn) - 2 * cm_virgin(FN, us, n, (u_turn - u) / 2)


def mdr_torsion_hertz(c, FN, a, phi):
    """theory §6.4, Hertz: φ = 3μF(1-t²)/(16 G_t a² t), M = (3/4)μFa(1-t²)(1+t²/3)."""
    Gt = c.moduli.torsional
    beta = 16 * Gt * a ** 2 * np.abs(phi) / (3 * MU * FN)
    t = np.sqrt(1 + beta ** 2 / 4) - beta / 2
    return np.sign(phi) * 0.75 * MU * FN * a * (1 - t ** 2) * (1 + t ** 2 / 3), t


# ------------------------------------------------------------------ normal
def test_normal_load_unload_equals_contact_normal_every_step():
    c = hertz()
    d_max = 2e-6
    path = cl.LoadPath().ramp(depth=d_max, steps=40).ramp(depth=0.3 * d_max, steps=30).ramp(
        force=50.0, steps=20).ramp(depth=-1e-7, steps=10)
    r = c.simulate(path, n_springs=50, method="mdr")
    a_ref, F_ref = hertz_normal(c, r.depth)
    np.testing.assert_allclose(r.radius, a_ref, rtol=FOUNDATION_NORMAL)
    np.testing.assert_allclose(r.force, F_ref, rtol=FOUNDATION_NORMAL, atol=TOL.ABS_FLOOR)
    ns = c.normal(depth=r.depth)
    np.testing.assert_allclose(r.force, ns.force, rtol=FOUNDATION_NORMAL, atol=TOL.ABS_FLOOR)
    assert r.meta["built"] == ["normal"]


def test_normal_spring_forces_integrate_to_the_normal_force():
    c = cone()
    path = cl.LoadPath().ramp(force=3.0, steps=7).ramp(twist=1e-6, steps=2)
    r = c.simulate(path, n_springs=37, spacing="uniform", snapshots=[3, -1], method="mdr")
    for step, snap in r.snapshots.items():
        assert snap["normal"].sum() == pytest.approx(r.force[step], rel=FOUNDATION_NORMAL)


# ------------------------------------------------------------------ Cattaneo–Mindlin
@pytest.mark.parametrize("kind", ["hertz", "cone"])
def test_cattaneo_mindlin_and_mindlin_deresiewicz_loop(kind):
    c = hertz() if kind == "hertz" else cone()
    n = 2.0 if kind == "hertz" else 1.0
    FN = F if kind == "hertz" else 5.0
    ns = c.normal(force=FN)
    us = MU * c.moduli.normal * ns.depth / c.moduli.tangential
    u0 = 0.8 * us
    path = (cl.LoadPath().ramp(force=FN, steps=5).ramp(displacement=u0, steps=200)
            .ramp(displacement=-u0, steps=400).ramp(displacement=u0, steps=400))
    r = c.simulate(path, method="mdr")
    assert r.meta["n_springs"] == DEFAULT_N_SPRINGS
    u, Fx = r.displacement, r.tangential_force
    load = slice(5, 205)
    unload = slice(205, 605)
    reload = slice(605, 1005)
    ref = np.empty_like(Fx)
    ref[load] = cm_virgin(FN, us, n, u[load])
    ref[unload] = cm_loop(FN, us, n, u[unload], u0)
    ref[reload] = -cm_loop(FN, us, n, -u[reload], u0)
    scale = np.max(np.abs(ref[5:]))
    err = np.abs(Fx[5:] - ref[5:]) / scale
    assert err.max() < FOUNDATION_CM
    # virgin curve: even pointwise relative (edge spacing keeps the lumped cell small)
    assert np.max(np.abs(Fx[load] / ref[load] - 1)) < 2 * FOUNDATION_CM
    # stick radius of the virgin curve within one cell
    x = np.clip(u[load] / us, 0, 1)
    c_ref = ns.radius * (1 - x) ** (1 / n)
    assert np.max(np.abs(r.stick_radius[load] - c_ref)) < 2.5 * ns.radius / DEFAULT_N_SPRINGS
    # the loop closes
    assert Fx[1004] == pytest.approx(Fx[204], rel=TOL.EXACT_ROUTES)


@pytest.mark.parametrize("spacing", ["uniform", "edge"])
def test_cattaneo_mindlin_convergence_order(spacing):
    c = hertz()
    ns = c.normal(force=F)
    us = MU * c.moduli.normal * ns.depth / c.moduli.tangential
    Ns = np.array([50, 100, 200, 400])
    errs = []
    for N in Ns:
        path = cl.LoadPath().ramp(force=F, steps=2).ramp(displacement=0.9 * us, steps=150).ramp(
            displacement=-0.9 * us, steps=150)
        r = c.simulate(path, n_springs=int(N), spacing=spacing, method="mdr")
        u = r.displacement[2:]
        ref = np.concatenate([cm_virgin(F, us, 2, u[:150]), cm_loop(F, us, 2, u[150:], 0.9 * us)])
        errs.append(np.max(np.abs(r.tangential_force[2:] - ref)) / (MU * F))
    order = -np.polyfit(np.log(Ns), np.log(errs), 1)[0]
    assert 1.8 < order < 2.3, (order, errs)


def test_oblique_loading_below_and_above_friction():
    """Preload F0, then u = λ(d - d0) while d grows (normal and tangential force rise together).

    Spring picture (§5 with the incremental rule): k = λG*/E*. Below μ nothing slips and
    ΔF_x = k ΔF_N exactly; above μ the stick zone has g(c) = d - (k/μ)(d - d0) and
    F_x = μ[F_N(a) - F_N(c)]."""
    c = hertz()
    E, Gs = c.moduli.normal, c.moduli.tangential
    d0, d1 = 1e-6, 3e-6
    for k in (0.5 * MU, 1.5 * MU):
        lam = k * E / Gs
        d = np.linspace(d0, d1, 101)
        path = cl.LoadPath().ramp(depth=d0, steps=3).then(
            cl.loadpath.Table.create(None, {"depth": d[1:], "displacement": lam * (d[1:] - d0)}))
        r = c.simulate(path, method="mdr")
        dd = r.depth[3:]
        a, FN = hertz_normal(c, dd)
        _, F0 = hertz_normal(c, d0)
        if k < MU:
            ref = k * (FN - F0)
            c_ref = a
        else:
            gc = dd - k / MU * (dd - d0)
            cc = np.sqrt(R * np.maximum(gc, 0))
            ref = MU * (FN - 4 * E * cc ** 3 / (3 * R))
            c_ref = cc
        err = np.abs(r.tangential_force[3:] - ref) / np.max(np.abs(ref))
        assert err.max() < FOUNDATION_CM
        assert np.max(np.abs(r.stick_radius[3:] - c_ref)) < 3 * a.max() / DEFAULT_N_SPRINGS
        if k > MU:  # partial slip: more than μΔF_N, less than kΔF_N
            assert np.all(r.tangential_force[3:] > MU * (FN - F0))
            assert np.all(r.tangential_force[3:] < k * (FN - F0))


def test_tangential_force_control_matches_closed_form():
    c = hertz()
    T = np.linspace(0.05, 0.95, 10) * MU * F
    path = cl.LoadPath().ramp(force=F, steps=2).then(cl.loadpath.Table.create(
        None, {"tangential_force": T}))
    r = c.simulate(path, method="mdr")
    np.testing.assert_allclose(r.tangential_force[2:], T, rtol=TOL.EXACT_ROUTES)
    s = c.tangential(force=F, tangential_force=T)
    np.testing.assert_allclose(r.displacement[2:], s.displacement, rtol=TOL.FOUNDATION_DISPLACEMENT)
    # beyond μF_N: gross sliding, flagged
    over = cl.LoadPath().ramp(force=F, steps=2).ramp(tangential_force=2 * MU * F, steps=1)
    r2 = c.simulate(over, n_springs=100, method="mdr")
    assert r2.gross_sliding[-1] and not r2.gross_sliding[:-1].any()
    assert r2.tangential_force[-1] == pytest.approx(MU * F, rel=TOL.EXACT_ROUTES)


def test_unloading_normal_releases_tangential_springs():
    c = hertz()
    ns = c.normal(force=F)
    us = MU * c.moduli.normal * ns.depth / c.moduli.tangential
    path = (cl.LoadPath().ramp(force=F, steps=5).ramp(displacement=0.5 * us, steps=20)
            .ramp(depth=-1e-9, steps=10))
    r = c.simulate(path, n_springs=200, method="mdr")
    assert r.tangential_force[-1] == 0.0
    # a force that decreases under a held shift can never exceed μ F_N
    assert np.all(np.abs(r.tangential_force) <= MU * r.force * (1 + 1e-12))


# ------------------------------------------------------------------ torsion
def test_torsion_equals_mdr_closed_form_every_step():
    c = hertz()
    ns = c.normal(force=F)
    a = hz.radius_of_force(F, R, hz.effective_modulus(210e9, 0.3, 210e9, 0.3))   # [J85]
    Gt = c.moduli.torsional
    phi_half = 3 * MU * F * (1 - 0.25) / (16 * Gt * a ** 2 * 0.5)  # t = 0.5
    path = (cl.LoadPath().ramp(force=F, steps=4).ramp(twist=phi_half, steps=100)
            .ramp(twist=-phi_half, steps=200).ramp(twist=phi_half, steps=200))
    r = c.simulate(path, method="mdr")
    assert r.meta["built"] == ["normal", "torsion"]
    ph, M = r.twist[4:], r.torque[4:]
    ref = np.empty_like(M)
    ref[:100] = mdr_torsion_hertz(c, F, a, ph[:100])[0]
    M0 = mdr_torsion_hertz(c, F, a, phi_half)[0]
    ref[100:300] = M0 - 2 * mdr_torsion_hertz(c, F, a, (phi_half - ph[100:300]) / 2)[0]
    ref[300:] = -M0 + 2 * mdr_torsion_hertz(c, F, a, (phi_half + ph[300:]) / 2)[0]
    assert np.max(np.abs(M - ref)) / np.max(np.abs(ref)) < FOUNDATION_TORSION
    t = mdr_torsion_hertz(c, F, a, ph[:100])[1]
    assert np.max(np.abs(r.stick_radius[4:104] - t * a)) < 2.5 * a / DEFAULT_N_SPRINGS


def test_torque_control_and_full_sliding():
    c = hertz()
    a = c.normal(force=F).radius
    M_full = 0.75 * MU * F * a  # MDR full slip, Hertz (§6.4)
    Ms = np.array([0.2, 0.6, 0.95]) * M_full
    path = cl.LoadPath().ramp(force=F, steps=2).then(cl.loadpath.Table.create(None,
                                                                              {"torque": Ms}))
    r = c.simulate(path, method="mdr")
    np.testing.assert_allclose(r.torque[2:], Ms, rtol=TOL.EXACT_ROUTES)
    ref = mdr_torsion_hertz(c, F, a, r.twist[2:])[0]
    np.testing.assert_allclose(ref, Ms, rtol=FOUNDATION_TORSION)
    over = c.simulate(cl.LoadPath().ramp(force=F, steps=2).ramp(torque=1.5 * M_full, steps=1),
                      n_springs=300, method="mdr")
    assert over.gross_sliding[-1]
    assert over.torque[-1] == pytest.approx(M_full, rel=TOL.QUADRATURE)


def test_history_twist_before_and_after_normal_load():
    """Spring picture: springs entering contact carry only the twist applied after they touch."""
    c = cl.Contact(cl.profiles.Paraboloid(R=R), materials=(STEEL, STEEL))  # no slip
    Gt = c.moduli.torsional
    phi = 1e-5
    F0, F1 = 10.0, 100.0
    a0, a1 = c.normal(force=F0).radius, c.normal(force=F1).radius
    before = c.simulate(cl.LoadPath().ramp(force=F0, steps=10).ramp(twist=phi, steps=5)
                        .ramp(force=F1, steps=20), method="mdr")
    after = c.simulate(cl.LoadPath().ramp(force=F1, steps=30).ramp(twist=phi, steps=5), method="mdr")
    assert before.torque[-1] == pytest.approx(16 / 3 * Gt * a0 ** 3 * phi, rel=TOL.EXACT_ROUTES)
    assert after.torque[-1] == pytest.approx(16 / 3 * Gt * a1 ** 3 * phi, rel=TOL.EXACT_ROUTES)
    assert before.torque[-1] < 0.5 * after.torque[-1]


def test_twist_without_contact_then_load_gives_no_torque():
    c = hertz()
    r = c.simulate(cl.LoadPath().ramp(force=1.0, steps=1).ramp(depth=-1e-9, steps=1)
                   .ramp(twist=1e-4, steps=3).ramp(force=F, steps=10), n_springs=100, method="mdr")
    assert np.all(r.torque[3:] == 0.0)
    assert np.all(r.dissipated_energy == 0.0)


def test_oscillating_twist_no_drift_over_1e4_cycles():
    c = hertz()
    a = c.normal(force=F).radius
    phi0 = 3 * MU * F * (1 - 0.49) / (16 * c.moduli.torsional * a ** 2 * 0.7)
    spc = 8
    cycles = 10_000
    path = (cl.LoadPath().ramp(force=F, steps=2)
            .sinusoid(twist=phi0, cycles=cycles, steps_per_cycle=spc))
    r = c.simulate(path, n_springs=100, outputs=["torque", "dissipated_energy", "twist"], method="mdr")
    W = r.dissipated_energy[2 + spc - 1::spc]  # end of each cycle
    per = np.diff(W)[1:]
    assert per[0] > 0
    assert np.max(np.abs(per / per[0] - 1)) < ENERGY_DRIFT
    M = r.torque[2:].reshape(cycles, spc)
    assert np.max(np.abs(M[-1] - M[1])) <= ENERGY_DRIFT * np.max(np.abs(M))


def test_jaeger_loop_comparison():
    c = hertz()
    a = c.normal(force=F).radius
    phi = 1e-3 * 3 * MU * F / (16 * c.moduli.torsional * a ** 2)  # very narrow slip annulus
    r = c.simulate(cl.LoadPath().ramp(force=F, steps=2).ramp(twist=phi, steps=20), method="mdr")
    exact = c.torsion(force=F, twist=phi, method="exact").torque
    assert r.torque[-1] == pytest.approx(exact, rel=TOL.NARROW_SLIP_FOUNDATION)


# ------------------------------------------------------------------ planning / errors
def test_only_needed_foundations_are_built():
    c = hertz()
    shift = c.simulate(cl.LoadPath().ramp(force=F, steps=2).ramp(displacement=1e-8, steps=2),
                       n_springs=20, method="mdr")
    assert shift.meta["built"] == ["normal", "tangential"]
    twist = c.simulate(cl.LoadPath().ramp(force=F, steps=2).ramp(twist=1e-6, steps=2),
                       n_springs=20, method="mdr")
    assert twist.meta["built"] == ["normal", "torsion"]
    f = Winkler.for_path(c.profile, c.moduli, MU, cl.LoadPath().ramp(force=F, steps=3),
                         n_springs=10)
    assert f.built == ["normal"] and not hasattr(f, "K_tor") and not hasattr(f, "K_tan")
    assert f.radius == pytest.approx(c.normal(force=F).radius, rel=TOL.SHORT_ARITHMETIC)


def test_combined_shift_and_twist_needs_opt_in():
    c = hertz()
    path = cl.LoadPath().ramp(force=F, steps=2).ramp(displacement=1e-8, twist=1e-6, steps=2)
    with pytest.raises(OutsideTheoryError, match="approximate=True"):
        c.simulate(path, method="mdr")
    with pytest.warns(ValidityWarning, match="independent"):
        r = c.simulate(path, approximate=True, n_springs=20, method="mdr")
    assert r.meta["built"] == ["normal", "tangential", "torsion"]


def test_outputs_selection_and_unplanned_output():
    c = hertz()
    r = c.simulate(cl.LoadPath().ramp(force=F, steps=3), outputs=["force"], method="mdr")
    with pytest.raises(cl.errors.EffectNotPlannedError, match="torque"):
        r.torque
    with pytest.raises(cl.errors.UnknownNameError, match="outputs"):
        c.simulate(cl.LoadPath().ramp(force=F, steps=3), outputs=["forse"], method="mdr")


def test_segment_and_step_strategies_agree():
    """The closed-form run advance equals step-by-step spring updates (varying normal force,
    reversals, force and torque control, holds)."""
    c = hertz()
    k = np.arange(1, 301)
    path = (cl.LoadPath().ramp(force=F, steps=5)
            .sinusoid(twist=2e-4, cycles=2, steps_per_cycle=40)
            .then(cl.loadpath.Table.create(None, {"force": F * (0.8 + 0.2 * np.cos(k / 20)),
                                                  "twist": 1e-4 * np.sin(k / 15)}))
            .hold(steps=20).ramp(torque=0.5 * 0.75 * MU * F * c.normal(force=F).radius, steps=30)
            .ramp(torque=-0.3 * 0.75 * MU * F * c.normal(force=F).radius, steps=30))
    with pytest.warns(ValidityWarning, match="method='exact'"):     # beyond the MDR validity
        a = c.simulate(path, n_springs=300, strategy="segments", method="mdr")
    with pytest.warns(ValidityWarning, match="method='exact'"):
        b = c.simulate(path, n_springs=300, strategy="steps", method="mdr")
    for q in ("torque", "twist", "dissipated_energy", "stick_radius"):
        scale = np.max(np.abs(getattr(b, q)))
        np.testing.assert_allclose(getattr(a, q), getattr(b, q), rtol=0, atol=TOL.STRATEGY_AGREEMENT * scale)
    ns = c.normal(force=F)
    us = MU * c.moduli.normal * ns.depth / c.moduli.tangential
    path = (cl.LoadPath().ramp(force=F, steps=5)
            .sinusoid(displacement=0.7 * us, cycles=2, steps_per_cycle=60)
            .ramp(tangential_force=0.5 * MU * F, steps=25).ramp(force=0.5 * F, steps=20)
            .ramp(tangential_force=-0.4 * MU * F, steps=25))
    a = c.simulate(path, n_springs=300, strategy="segments", method="mdr")
    b = c.simulate(path, n_springs=300, strategy="steps", method="mdr")
    for q in ("tangential_force", "displacement", "dissipated_energy", "stick_radius"):
        scale = np.max(np.abs(getattr(b, q)))
        np.testing.assert_allclose(getattr(a, q), getattr(b, q), rtol=0, atol=TOL.STRATEGY_AGREEMENT * scale)


def test_snapshot_tractions_match_closed_forms():
    """Tractions reconstructed from the springs: Cattaneo–Mindlin τ = μ(p_a - p_c) (Hertz, §5),
    and the no-slip torsion traction τ = (4G_tφ/π) r/sqrt(a²-r²) (§6.1)."""
    c = hertz()
    ns = c.normal(force=F)
    a = ns.radius     # field checked at the solver's own edge: sqrt(a²-x²) amplifies ulps of a
    us = MU * c.moduli.normal * ns.depth / c.moduli.tangential
    u = 0.5 * us
    r = c.simulate(cl.LoadPath().ramp(force=F, steps=3).ramp(displacement=u, steps=20),
                   snapshots=[-1], method="mdr")
    snap = r.snapshots[22]
    x = snap["x"]
    cc = a * np.sqrt(1 - u / us)
    p0 = 3 * F / (2 * np.pi * a ** 2)
    sel = (x < 0.95 * a) & (np.abs(x - cc) > 0.02 * a)
    ref = MU * p0 * (np.sqrt(1 - (x / a) ** 2) - np.where(x < cc, cc / a * np.sqrt(
        np.clip(1 - (x / cc) ** 2, 0, None)), 0))
    assert np.max(np.abs(snap["shear_tangential"][sel] - ref[sel])) < TOL.SNAPSHOT_TRACTION * MU * p0
    np.testing.assert_allclose(snap["pressure"], 2 * c.moduli.normal / (np.pi * R) * np.sqrt(
        np.clip(a * a - x * x, 0, None)), rtol=TOL.QUADRATURE)
    c0 = cl.Contact(cl.profiles.Paraboloid(R=R), materials=(STEEL, STEEL))
    phi = 1e-5
    t = c0.simulate(cl.LoadPath().ramp(force=F, steps=3).ramp(twist=phi, steps=2), snapshots=[4], method="mdr")
    x = t.snapshots[4]["x"]
    sel = x < 0.9 * a
    ref = 4 * c0.moduli.torsional * phi / np.pi * x / np.sqrt(a * a - x * x)
    np.testing.assert_allclose(t.snapshots[4]["shear_torsion"][sel], ref[sel], rtol=TOL.SNAPSHOT_TRACTION)
