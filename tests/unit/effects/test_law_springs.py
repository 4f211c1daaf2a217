"""ContactLaw under a changing normal load: per-contact MDR springs against Contact.simulate at
equal spring counts and cell layout (edge spacing over the path's largest contact radius)."""
import warnings

import numpy as np
import pytest

import contactlab as cl
from contactlab.errors import OutsideTheoryError, ValidityWarning
from tests.tolerances import LAW_REGRID, LAW_SPRINGS

#: these tests compare the springs' values with simulate(); the model-error warning of twisted
#: contacts on springs (once per law, tested in test_law_model_error_warning.py) is not theirs
pytestmark = pytest.mark.filterwarnings(
    "ignore:ContactLaw. the model error:contactlab.errors.ValidityWarning")

N = 16


def _contacts(rng, n):
    R = rng.uniform(5e-3, 2e-2, n)
    mu = rng.uniform(0.2, 0.6, n)
    out = [cl.Contact(cl.profiles.Paraboloid(R=R[i]),
                      materials=(cl.Elastic(E=rng.uniform(1e11, 2e11), nu=rng.uniform(0.2, 0.35)),
                                 cl.Elastic(E=rng.uniform(1e11, 2e11), nu=rng.uniform(0.2, 0.35))),
                      friction=mu[i]) for i in range(n)]
    mod = [c.moduli for c in out]
    par = dict(R=R, friction=mu, E_star=np.array([m.normal for m in mod]),
               G_star=np.array([m.tangential for m in mod]),
               G_torsion=np.array([m.torsional for m in mod]))
    return out, par


HELD = 14      # steps at the first load (step 0 loads, then a held-load history)


def _path(F0, chan, amp):
    return (cl.LoadPath().ramp(force=F0, steps=1)
            .ramp(**{chan: amp / 2}, steps=5).ramp(**{chan: -amp / 3}, steps=5)
            .ramp(**{chan: amp / 6}, steps=3)
            .ramp(force=2 * F0, **{chan: amp}, steps=13)
            .ramp(force=0.7 * F0, **{chan: -amp / 2}, steps=17)
            .ramp(force=1.5 * F0, **{chan: amp / 3}, steps=11).hold(steps=5)
            .ramp(**{chan: -amp}, steps=9)
            .ramp(force=0.3 * F0, steps=10))


@pytest.mark.parametrize("chan, key, amp", [("twist", "torque", 3e-4),
                                            ("displacement", "tangential_force", 3e-7)])
def test_changing_load_matches_simulate(chan, key, amp):
    rng = np.random.default_rng(140)
    n = 4
    contacts, par = _contacts(rng, n)
    F0 = rng.uniform(5, 50, n)
    with warnings.catch_warnings():
        # twisted while the force changes: simulate warns that the MDR springs' dissipated energy
        # is outside their validity; this test compares two spring implementations
        warnings.filterwarnings("ignore", "MDR torsion springs outside", ValidityWarning)
        res = [c.simulate(_path(F0[i], chan, amp), n_springs=N, strategy="steps", method="mdr")
               for i, c in enumerate(contacts)]
    dep = np.stack([r.depth for r in res], 1)
    x = np.stack([getattr(r, chan) for r in res], 1)
    a = np.stack([r.radius for r in res], 1)
    # the springs must cover the path's largest radius, as the foundation of simulate does (a
    # hair more: the law's cover radius, this ratio times its own switch radius, may round an
    # ulp below the largest radius, which would then regrid the springs)
    cover = a.max(0) / np.maximum(a[HELD - 1], a[HELD]) * (1 + 1e-15)
    law = cl.ContactLaw(cl.profiles.Paraboloid, springs=N, spring_cover=cover, fast=False,
                        **par)
    out = [law.step(depth=dep[k], **{chan: x[k]}) for k in range(dep.shape[0])]
    exact = np.stack([o.exact for o in out])
    assert exact[:HELD].all() and not exact[HELD:].any()
    # from the load change on: the held-load history is carried into the springs by replaying
    # the Masing turning points, so simulate (springs throughout) is matched step by step
    y = np.stack([getattr(o, key) for o in out])[HELD:]
    ys = np.stack([getattr(r, key) for r in res], 1)[HELD:]
    np.testing.assert_allclose(y, ys, rtol=0, atol=LAW_SPRINGS * np.abs(ys).max())
    dW = np.stack([o.dissipated_energy for o in out])[HELD:]
    dWs = np.diff(np.stack([r.dissipated_energy for r in res], 1), axis=0)[HELD - 1:]
    Ws = np.stack([r.dissipated_energy for r in res], 1)
    np.testing.assert_allclose(dW, dWs, rtol=0, atol=LAW_SPRINGS * Ws.max())
    c = np.stack([o.stick_radius if chan == "displacement" else o.torsion_stick_radius
                  for o in out])[HELD:]
    cs = np.minimum(np.stack([r.stick_radius for r in res], 1), a)[HELD:]
    np.testing.assert_allclose(c, cs, rtol=LAW_SPRINGS, atol=0)


def test_cover_grows_and_springs_zero_raises():
    law = cl.ContactLaw(cl.profiles.Paraboloid, R=0.01, E_star=1e11, G_star=4e10,
                        G_torsion=4e10, friction=0.3, size=2, springs=8)
    law.step(force=[1.0, 1.0], twist=1e-5)
    out = law.step(force=[1.0, 1.2], twist=2e-5)
    assert out.exact.tolist() == [True, False]
    cover = law.state["spr_cover"][1]
    assert cover == pytest.approx(1.5 * out.radius[1], rel=1e-15)
    big = law.step(force=[1.0, 10.0], twist=3e-5)      # radius beyond the cover: regrid
    assert law.state["spr_cover"][1] == pytest.approx(1.5 * big.radius[1], rel=1e-15)
    assert np.all(np.isfinite(big.torque)) and 0 < big.torque[1]
    law.reset([1])
    assert not law.state["spr_on"].any()
    strict = cl.ContactLaw(cl.profiles.Paraboloid, R=0.01, E_star=1e11, G_star=4e10,
                           G_torsion=4e10, friction=0.3, size=2, springs=0)
    strict.step(force=[1.0, 1.0], twist=1e-5)
    with pytest.raises(OutsideTheoryError, match=r"depth\[1\]"):
        strict.step(force=[1.0, 1.2], twist=1e-5)


def _random_path(rng, F0, chan, scale):
    """A held-load history (``HELD`` steps) then random load and control changes with reversals,
    ending with unloading; amplitudes around the contact's full-slip scale."""
    s = scale * rng.uniform(0.3, 2.0, 8) * rng.choice([-1.0, 1.0], 8)
    f = F0 * rng.uniform(0.3, 2.5, 4)
    return (cl.LoadPath().ramp(force=F0, steps=1)
            .ramp(**{chan: s[0]}, steps=5).ramp(**{chan: -s[1] / 2}, steps=5)
            .ramp(**{chan: s[2] / 3}, steps=3)
            .ramp(force=f[0], **{chan: s[3]}, steps=11)
            .ramp(force=f[1], **{chan: s[4]}, steps=11)
            .ramp(**{chan: s[5]}, steps=6)
            .ramp(force=f[2], **{chan: s[6]}, steps=11).hold(steps=3)
            .ramp(force=f[3], **{chan: s[7]}, steps=11)
            .ramp(force=0.2 * F0, steps=6))


@pytest.mark.parametrize("fast", [False, True] if cl.effects.law._kernel.AVAILABLE else [False])
@pytest.mark.parametrize("chan, key", [("twist", "torque"), ("displacement", "tangential_force")])
def test_fifty_random_contacts_changing_load_match_simulate(chan, key, fast):
    """Issue 14's must-show: 50 random contacts (radius, moduli, friction, load) on random
    changing-load paths, the law with N springs against Contact.simulate(method="mdr") with N
    springs (the spring foundation, not the exact ring solver), step by step to 1e-12."""
    rng = np.random.default_rng(1450)
    n = 50
    contacts, par = _contacts(rng, n)
    F0 = 10 ** rng.uniform(0, 2.5, n)
    mu, Es, Gs, Gt = par["friction"], par["E_star"], par["G_star"], par["G_torsion"]
    a0 = (3 * F0 * par["R"] / (4 * Es)) ** (1 / 3)
    d0 = a0 * a0 / par["R"]
    scale = mu * Es * d0 / (2 * Gt * a0) if chan == "twist" else mu * Es * d0 / Gs
    res = []
    for i, c in enumerate(contacts):
        # the twisted paths go beyond the MDR springs' validity (ValidityWarning, only that):
        # this test compares two implementations of the same MDR model
        with warnings.catch_warnings(record=True) as rec:
            warnings.simplefilter("always")
            r = c.simulate(_random_path(rng, F0[i], chan, scale[i]), n_springs=N,
                           strategy="steps", method="mdr")
        assert all(issubclass(w.category, ValidityWarning) for w in rec)
        assert r.meta["n_springs"] == N and "Winkler" in r.meta["foundation"]   # springs ran
        res.append(r)
    steps = min(len(r.depth) for r in res)
    dep = np.stack([r.depth[:steps] for r in res], 1)
    x = np.stack([getattr(r, chan)[:steps] for r in res], 1)
    a_all = [r.radius for r in res]
    a = np.stack([ra[:steps] for ra in a_all], 1)
    # the law's cover (spring_cover x the larger radius at the switch) must reach the path's
    # largest radius, as simulate's foundation does: a few ulps more so that rounding does not
    # trigger a regrid (a different cell layout, tested separately)
    cover = np.array([ra.max() for ra in a_all]) / np.maximum(a[HELD - 1], a[HELD]) * (1 + 1e-15)
    law = cl.ContactLaw(cl.profiles.Paraboloid, springs=N, spring_cover=cover, fast=fast,
                        **par)
    out = [law.step(depth=dep[k], **{chan: x[k]}) for k in range(steps)]
    exact = np.stack([o.exact for o in out])
    assert exact[:HELD].all() and not exact[HELD:].any()
    y = np.stack([getattr(o, key) for o in out])[HELD:]
    ys = np.stack([getattr(r, key)[:steps] for r in res], 1)[HELD:]
    peak = np.abs(ys).max(0)
    assert np.all(peak > 0)
    np.testing.assert_allclose(y / peak, ys / peak, rtol=0, atol=LAW_SPRINGS)
    dW = np.stack([o.dissipated_energy for o in out])[HELD:]
    Ws = np.stack([r.dissipated_energy[:steps] for r in res], 1)
    dWs = np.diff(Ws, axis=0)[HELD - 1:]
    np.testing.assert_allclose(dW / Ws.max(0), dWs / Ws.max(0), rtol=0, atol=LAW_SPRINGS)
    c = np.stack([o.stick_radius if chan == "displacement" else o.torsion_stick_radius
                  for o in out])[HELD:]
    cs = np.minimum(np.stack([r.stick_radius[:steps] for r in res], 1), a)[HELD:]
    np.testing.assert_allclose(c, cs, rtol=LAW_SPRINGS, atol=0)


@pytest.mark.parametrize("chan, key", [("twist", "torque"), ("displacement", "tangential_force")])
def test_regrid_against_simulate(chan, key):
    """The load grows twelvefold after the switch, so the radius leaves the springs' cover (1.5
    times the radius at the switch) and the law re-lays its cells (cover grown, element forces
    carried over by their cumulative line load). simulate's foundation instead covers the
    path's largest radius from the start, so the two differ by the re-layout: to LAW_REGRID of
    the peak against simulate at equal spring counts, and against the 2000-spring foundation
    within twice the error of simulate's own 16 springs (measured 1.3e-2; 1.4x twist, 1.2x
    shift)."""
    rng = np.random.default_rng(77)
    contacts, par = _contacts(rng, 2)
    F0 = 10 ** rng.uniform(0, 2, 2)
    for i, c in enumerate(contacts):
        p = {k: v[i] for k, v in par.items()}
        a0 = (3 * F0[i] * p["R"] / (4 * p["E_star"])) ** (1 / 3)
        d0 = a0 * a0 / p["R"]
        s = (p["friction"] * p["E_star"] * d0 / (2 * p["G_torsion"] * a0) if chan == "twist"
             else p["friction"] * p["E_star"] * d0 / p["G_star"])
        path = (cl.LoadPath().ramp(force=F0[i], steps=1).ramp(**{chan: s}, steps=5)
                .ramp(**{chan: -0.5 * s}, steps=5)
                .ramp(force=8 * F0[i], **{chan: 3 * s}, steps=20).ramp(**{chan: -2 * s}, steps=10)
                .ramp(force=3 * F0[i], **{chan: 2 * s}, steps=10).ramp(force=12 * F0[i], steps=8)
                .ramp(**{chan: -3 * s}, steps=10))
        # beyond the MDR springs' validity on the twisted path (ValidityWarning, only that): the
        # test compares two implementations of the same MDR model
        with warnings.catch_warnings(record=True) as rec:
            warnings.simplefilter("always")
            r16 = c.simulate(path, n_springs=N, strategy="steps", method="mdr")
            ref = c.simulate(path, n_springs=2000, strategy="steps", method="mdr")
        assert all(issubclass(w.category, ValidityWarning) for w in rec)
        law = cl.ContactLaw(cl.profiles.Paraboloid, springs=N, size=1, **p)
        out = [law.step(depth=r16.depth[k], **{chan: getattr(r16, chan)[k]})
               for k in range(len(r16.depth))]
        assert law.state["spr_cover"][0] > 1.5 * r16.radius[11] * 1.01      # it did re-lay
        on = ~np.array([o.exact[0] for o in out])
        y = np.array([getattr(o, key)[0] for o in out])[on]
        y16, yr = getattr(r16, key)[on], getattr(ref, key)[on]
        peak = np.abs(yr).max()
        assert np.abs(y - y16).max() <= LAW_REGRID * peak
        assert np.abs(y - yr).max() <= 2.0 * np.abs(y16 - yr).max()


def test_springs_do_not_return_to_the_exact_law():
    """Documented: once on springs a contact stays there at constant load (its element state
    after a load change is not a Masing history at one load), until it separates or is reset;
    then it starts again on the exact law and matches twist_history from a virgin state."""
    law = cl.ContactLaw(cl.profiles.Paraboloid, R=0.01, E_star=1.15e11, G_star=4.4e10,
                        G_torsion=4.0e10, friction=0.3, size=2)
    law.step(force=[10.0, 10.0], twist=1e-5)
    law.step(force=[10.0, 12.0], twist=2e-5)                # contact 1 leaves the constant load
    held = [law.step(force=[10.0, 12.0], twist=t) for t in np.linspace(2e-5, -3e-5, 12)]
    assert all(o.exact.tolist() == [True, False] for o in held)
    back = law.step(force=[10.0, 10.0], twist=-3e-5)         # even at its first load again
    assert back.exact.tolist() == [True, False]
    law.step(force=[10.0, 0.0], twist=-3e-5)                 # separates: memory cleared
    assert not law.state["spr_on"][1]
    hist = 1e-4 * np.sin(np.linspace(0, 3 * np.pi, 40))
    outs = [law.step(force=[10.0, 7.0], twist=[0.0, t]) for t in hist]
    assert all(o.exact[1] for o in outs)
    ref = cl.ContactLaw(cl.profiles.Paraboloid, R=0.01, E_star=1.15e11, G_star=4.4e10,
                        G_torsion=4.0e10, friction=0.3, size=1)
    M_ref = [ref.step(force=7.0, twist=t).torque[0] for t in hist]
    np.testing.assert_array_equal([o.torque[1] for o in outs], M_ref)
