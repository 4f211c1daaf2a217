"""ContactLaw for the flat punch family (per-contact punch radius) at constant normal load
against the single-contact exact API: Contact(FlatPunch(...)).twist_history (Jäger's exact
partial slip: no slip up to φ = μE*d/(4G_t a), then slip from the edge inwards) and
shift_history (uniform slip limit: stick until full slip), 50 random contacts."""
import numpy as np
import pytest

import contactlab as cl
from contactlab.errors import ValidityWarning
from contactlab.physics import master
from tests.tolerances import CLOSED_FORM, LAW_HISTORY, LAW_SPRINGS, MASTER_CURVE

#: these tests compare the springs' values with simulate(); the model-error warning of twisted
#: contacts on springs (once per law, tested in test_law_model_error_warning.py) is not theirs
pytestmark = pytest.mark.filterwarnings(
    "ignore:ContactLaw. the model error:contactlab.errors.ValidityWarning")


def _history(rng, steps, amp):
    inc = rng.standard_normal(steps) * amp / np.sqrt(steps) * 3
    return np.cumsum(inc)


@pytest.fixture(scope="module")
def fifty():
    rng = np.random.default_rng(1403)
    n = 50
    b = 10 ** rng.uniform(-4, -2, n)
    mats = [(cl.Elastic(E=10 ** rng.uniform(10, 11.5), nu=rng.uniform(0.0, 0.45)),
             cl.Elastic(E=10 ** rng.uniform(10, 11.5), nu=rng.uniform(0.0, 0.45)))
            for _ in range(n)]
    mu = rng.uniform(0.1, 0.8, n)
    F = 10 ** rng.uniform(-1, 3, n)
    contacts = [cl.Contact(cl.profiles.FlatPunch(radius=b[i]), materials=mats[i],
                           friction=mu[i]) for i in range(n)]
    mod = [c.moduli for c in contacts]
    Es = np.array([m.normal for m in mod])
    Gs = np.array([m.tangential for m in mod])
    Gt = np.array([m.torsional for m in mod])
    d = F / (2 * Es * b)
    phi_s = mu * Es * d / (2 * Gt * b)
    u_s = mu * Es * d / Gs
    steps = 60
    phi = np.stack([_history(rng, steps, 2 * phi_s[i]) for i in range(n)], axis=1)
    u = np.stack([_history(rng, steps, 1.5 * u_s[i]) for i in range(n)], axis=1)
    law_kw = dict(radius=b, E_star=Es, G_star=Gs, G_torsion=Gt, friction=mu, memory=64)
    return dict(contacts=contacts, F=F, phi=phi, u=u, law_kw=law_kw, b=b)


@pytest.mark.parametrize("fast", [False, True] if cl.effects.law._kernel.AVAILABLE else [False])
def test_fifty_flat_punches_twist_history(fifty, fast):
    f = fifty
    law = cl.ContactLaw(cl.profiles.FlatPunch, fast=fast, **f["law_kw"])
    out = [law.step(force=f["F"], twist=p) for p in f["phi"]]
    M = np.stack([o.torque for o in out])
    c = np.stack([o.torsion_stick_radius for o in out])
    W = np.cumsum(np.stack([o.dissipated_energy for o in out]), axis=0)
    assert np.all(np.stack([o.radius for o in out]) == f["b"])
    partial = 0
    for i, con in enumerate(f["contacts"]):
        h = con.twist_history(force=f["F"][i], twist=f["phi"][:, i], method="exact")
        amp = np.max(np.abs(h.torque))
        assert np.max(np.abs(M[:, i] - h.torque)) <= LAW_HISTORY * amp
        assert np.max(np.abs(c[:, i] - h.stick_radius)) <= LAW_HISTORY * f["b"][i]
        assert np.max(np.abs(W[:, i] - h.dissipated_energy)) <= LAW_HISTORY * h.dissipated_energy[-1]
        partial += np.count_nonzero((h.stick_radius > 0.01 * f["b"][i])
                                    & (h.stick_radius < 0.99 * f["b"][i]))
    assert partial > 100                    # the histories do visit partial slip


@pytest.mark.parametrize("fast", [False, True] if cl.effects.law._kernel.AVAILABLE else [False])
def test_fifty_flat_punches_shift_history(fifty, fast):
    f = fifty
    law = cl.ContactLaw(cl.profiles.FlatPunch, fast=fast, **f["law_kw"])
    out = [law.step(force=f["F"], displacement=u) for u in f["u"]]
    T = np.stack([o.tangential_force for o in out])
    W = np.cumsum(np.stack([o.dissipated_energy for o in out]), axis=0)
    for i, con in enumerate(f["contacts"]):
        h = con.shift_history(force=f["F"][i], displacement=f["u"][:, i])
        amp = np.max(np.abs(h.tangential_force))
        assert np.max(np.abs(T[:, i] - h.tangential_force)) <= LAW_HISTORY * amp
        assert np.max(np.abs(W[:, i] - h.dissipated_energy)) <= LAW_HISTORY * max(
            h.dissipated_energy[-1], 1e-300)


def test_flat_punch_closed_forms():
    """No slip (Reissner–Sagoci torque 16/3 G_t a³ φ) up to φ₁ = μE*d/(4G_t a); full sliding
    torque π/2 μE*d a² = π/4 μ F a; normal F = 2aE*d."""
    b, Es, Gt, mu, F = 2e-3, 1e11, 4e10, 0.3, 50.0
    law = cl.ContactLaw(cl.profiles.FlatPunch(radius=b), E_star=Es, G_star=4e10, G_torsion=Gt,
                        friction=mu, size=3)
    d = F / (2 * Es * b)
    phi1 = mu * Es * d / (4 * Gt * b)
    out = law.step(force=F, twist=[0.5 * phi1, phi1, 1e4 * phi1])
    assert out.depth[0] == pytest.approx(d, rel=CLOSED_FORM)
    assert out.torque[:2] == pytest.approx(16 / 3 * Gt * b**3 * np.array([0.5, 1.0]) * phi1,
                                           rel=CLOSED_FORM)
    assert out.torsion_stick_radius[:2] == pytest.approx([b, b], rel=CLOSED_FORM)
    assert out.dissipated_energy[:2] == pytest.approx([0.0, 0.0], abs=1e-300)
    assert out.torque[2] == pytest.approx(np.pi / 4 * mu * F * b, rel=MASTER_CURVE)


def test_flat_master_curve_against_closed_form_ladder():
    """Certified master curve against the closed forms on a ladder that is not the nodes,
    from just past the no-slip limit (c/a → 1) to deep sliding (c/a → 0)."""
    mc = master.torsion_master(np.inf)
    assert mc.certified_error <= master.CERTIFY_TOL
    y = 0.5 + np.concatenate([10.0 ** np.arange(-12, 3, 0.37), [0.0123, 0.7, 3.3]])
    t, m, q = mc(y)
    te, me, qe = master._flat_exact_curves(y)
    for got, exp in ((t, te), (m, me), (q, qe)):
        np.testing.assert_allclose(got, exp, rtol=0, atol=MASTER_CURVE)


@pytest.mark.parametrize("chan, key", [("twist", "torque"), ("displacement", "tangential_force")])
def test_flat_punch_changing_load_matches_simulate(chan, key):
    """Under a changing load a flat punch goes onto its springs over the punch radius
    (spring_cover=1, the layout of simulate's foundation) and matches
    Contact.simulate(method="mdr") at equal spring counts."""
    N = 16
    b, mu, F0 = 1e-3, 0.4, 20.0
    con = cl.Contact(cl.profiles.FlatPunch(radius=b), friction=mu,
                     materials=(cl.Elastic(E=2e11, nu=0.3), cl.Elastic(E=1e11, nu=0.25)))
    m = con.moduli
    d0 = F0 / (2 * m.normal * b)
    s = (mu * m.normal * d0 / (2 * m.torsional * b) if chan == "twist"
         else mu * m.normal * d0 / m.tangential)
    path = (cl.LoadPath().ramp(force=F0, steps=1).ramp(**{chan: 1.5 * s}, steps=5)
            .ramp(**{chan: -0.5 * s}, steps=5).ramp(force=2 * F0, **{chan: 2 * s}, steps=10)
            .ramp(force=0.5 * F0, **{chan: -s}, steps=10).ramp(**{chan: s}, steps=6))
    if chan == "twist":     # twisted beyond the MDR validity (c/a = 0.83), force changing
        with pytest.warns(ValidityWarning, match="outside the torque limit"):
            r = con.simulate(path, n_springs=N, strategy="steps", method="mdr")
    else:
        r = con.simulate(path, n_springs=N, strategy="steps", method="mdr")
    assert r.meta["n_springs"] == N and "Winkler" in r.meta["foundation"]
    law = cl.ContactLaw(cl.profiles.FlatPunch, radius=b, E_star=m.normal, G_star=m.tangential,
                        G_torsion=m.torsional, friction=mu, springs=N, spring_cover=1.0, size=1)
    out = [law.step(depth=r.depth[k], **{chan: getattr(r, chan)[k]})
           for k in range(len(r.depth))]
    exact = np.array([o.exact[0] for o in out])
    assert exact[:11].all() and not exact[11:].any()
    y = np.array([getattr(o, key)[0] for o in out])[~exact]
    ys = getattr(r, key)[~exact]
    np.testing.assert_allclose(y, ys, rtol=0, atol=LAW_SPRINGS * np.abs(ys).max())
