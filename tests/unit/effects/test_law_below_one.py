"""ContactLaw for power laws f = c r^n with 0 < n < 1 (pressure singular at the centre,
p ∝ r^(n-1)): 50 random contacts per exponent at constant normal load against the single-contact
exact API (Contact.twist_history, Jäger's exact partial slip; Contact.shift_history,
Cattaneo–Mindlin), compiled and numpy paths, the generated source, and the MDR springs against
Contact.simulate at equal spring counts under a changing load."""
import importlib.util
from contextlib import nullcontext

import numpy as np
import pytest

import contactlab as cl
from contactlab.errors import ValidityWarning
from tests.tolerances import COMPILED_VS_NUMPY, LAW_HISTORY, LAW_SOURCE, LAW_SPRINGS

#: these tests compare the springs' values with simulate(); the model-error warning of twisted
#: contacts on springs (once per law, tested in test_law_model_error_warning.py) is not theirs
pytestmark = pytest.mark.filterwarnings(
    "ignore:ContactLaw. the model error:contactlab.errors.ValidityWarning")

FAST = [False, True] if cl.effects.law._kernel.AVAILABLE else [False]


def _history(rng, steps, amp):
    inc = rng.standard_normal(steps) * amp / np.sqrt(steps) * 3
    return np.cumsum(inc)


def _fifty(n_exp, seed):
    rng = np.random.default_rng(seed)
    n = 50
    c = 10 ** rng.uniform(1, 4, n)             # m^(1-n): radii ~1e-5..1e-2 m at these loads
    mats = [(cl.Elastic(E=10 ** rng.uniform(10, 11.5), nu=rng.uniform(0.0, 0.45)),
             cl.Elastic(E=10 ** rng.uniform(10, 11.5), nu=rng.uniform(0.0, 0.45)))
            for _ in range(n)]
    mu = rng.uniform(0.1, 0.8, n)
    F = 10 ** rng.uniform(-1, 3, n)
    contacts = [cl.Contact(cl.profiles.PowerLaw(c=c[i], n=n_exp), materials=mats[i],
                           friction=mu[i]) for i in range(n)]
    mod = [k.moduli for k in contacts]
    Es = np.array([m.normal for m in mod])
    Gs = np.array([m.tangential for m in mod])
    Gt = np.array([m.torsional for m in mod])
    law_kw = dict(n=n_exp, c=c, E_star=Es, G_star=Gs, G_torsion=Gt, friction=mu, memory=64)
    d, a, _ = cl.ContactLaw(cl.profiles.PowerLaw, **law_kw).normal(force=F)
    phi_s = mu * Es * d / (2 * Gt * a)
    u_s = mu * Es * d / Gs
    steps = 60
    # twists up to ~30 phi_s: deep sliding, where c/a decays only algebraically for n < 1
    phi = np.stack([_history(rng, steps, 12 * phi_s[i]) for i in range(n)], axis=1)
    u = np.stack([_history(rng, steps, 0.7 * u_s[i]) for i in range(n)], axis=1)
    return dict(contacts=contacts, F=F, phi=phi, u=u, law_kw=law_kw, a=a)


@pytest.fixture(scope="module", params=[0.3, 0.75])
def fifty(request):
    return _fifty(request.param, 1414 + int(100 * request.param))


@pytest.mark.parametrize("fast", FAST)
def test_fifty_contacts_twist_history(fifty, fast):
    f = fifty
    law = cl.ContactLaw(cl.profiles.PowerLaw, fast=fast, **f["law_kw"])
    out = [law.step(force=f["F"], twist=p) for p in f["phi"]]
    M = np.stack([o.torque for o in out])
    c = np.stack([o.torsion_stick_radius for o in out])
    W = np.cumsum(np.stack([o.dissipated_energy for o in out]), axis=0)
    assert not law.state["tor_overflow"].any()
    deep = 0
    for i, con in enumerate(f["contacts"]):
        h = con.twist_history(force=f["F"][i], twist=f["phi"][:, i], method="exact")
        amp = np.max(np.abs(h.torque))
        assert np.max(np.abs(M[:, i] - h.torque)) <= LAW_HISTORY * amp
        assert np.max(np.abs(c[:, i] - h.stick_radius)) <= LAW_HISTORY * h.normal.radius
        assert np.max(np.abs(W[:, i] - h.dissipated_energy)) <= LAW_HISTORY * h.dissipated_energy[-1]
        deep += np.count_nonzero(h.stick_radius < 0.05 * f["a"][i])
    assert deep > 100                       # the histories reach deep sliding (c/a < 0.05)


@pytest.mark.parametrize("fast", FAST)
def test_fifty_contacts_shift_history(fifty, fast):
    f = fifty
    law = cl.ContactLaw(cl.profiles.PowerLaw, fast=fast, **f["law_kw"])
    out = [law.step(force=f["F"], displacement=u) for u in f["u"]]
    T = np.stack([o.tangential_force for o in out])
    c = np.stack([o.stick_radius for o in out])
    W = np.cumsum(np.stack([o.dissipated_energy for o in out]), axis=0)
    for i, con in enumerate(f["contacts"]):
        h = con.shift_history(force=f["F"][i], displacement=f["u"][:, i])
        amp = np.max(np.abs(h.tangential_force))
        assert np.max(np.abs(T[:, i] - h.tangential_force)) <= LAW_HISTORY * amp
        assert np.max(np.abs(c[:, i] - h.stick_radius)) <= LAW_HISTORY * h.normal.radius
        assert np.max(np.abs(W[:, i] - h.dissipated_energy)) <= LAW_HISTORY * h.dissipated_energy[-1]


def test_compiled_matches_numpy_below_one(fifty):
    if not cl.effects.law._kernel.AVAILABLE:
        pytest.skip("numba not installed")
    f = fifty
    laws = [cl.ContactLaw(cl.profiles.PowerLaw, fast=fast, **{**f["law_kw"], "memory": 4})
            for fast in (False, True)]
    with pytest.warns(ValidityWarning, match="memory=4"):      # the overflow path too
        for k in range(f["phi"].shape[0]):
            r = [law.step(force=f["F"], twist=f["phi"][k]) for law in laws]
            np.testing.assert_array_equal(r[0].exact, r[1].exact)
            for name in ("torque", "torsion_stick_radius", "dissipated_energy"):
                x, y = getattr(r[0], name), getattr(r[1], name)
                np.testing.assert_allclose(y, x, rtol=COMPILED_VS_NUMPY,
                                           atol=COMPILED_VS_NUMPY * np.max(np.abs(x)),
                                           err_msg=name)
    assert laws[0].state["tor_overflow"].any()


def test_generated_source_below_one(tmp_path, fifty):
    f = fifty
    law = cl.ContactLaw(cl.profiles.PowerLaw, fast=False, **f["law_kw"])
    path = tmp_path / "law_below_one.py"
    path.write_text(law.to_source())
    spec = importlib.util.spec_from_file_location("law_below_one", path)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    kw = {k: v for k, v in f["law_kw"].items() if k != "n"}
    ven = mod.Law(**kw)
    for k in range(f["phi"].shape[0]):
        r1 = law.step(force=f["F"], twist=f["phi"][k])
        r2 = ven.step(force=f["F"], twist=f["phi"][k])
        for name in ("torque", "torsion_stick_radius", "dissipated_energy"):
            x = getattr(r1, name)
            np.testing.assert_allclose(r2[name], x, rtol=LAW_SOURCE,
                                       atol=LAW_SOURCE * np.max(np.abs(x)), err_msg=name)


@pytest.mark.parametrize("chan, key", [("twist", "torque"), ("displacement", "tangential_force")])
def test_changing_load_matches_simulate_below_one(chan, key):
    """MDR springs of an n = 0.5 contact (cell integrals with x^(n+1), x^(n+2)) against
    Contact.simulate(method="mdr") at equal spring counts, cells over the path's largest
    radius."""
    N, n_exp, c0, mu, F0 = 16, 0.5, 300.0, 0.4, 20.0
    con = cl.Contact(cl.profiles.PowerLaw(c=c0, n=n_exp), friction=mu,
                     materials=(cl.Elastic(E=2e11, nu=0.3), cl.Elastic(E=1e11, nu=0.25)))
    m = con.moduli
    law0 = cl.ContactLaw(cl.profiles.PowerLaw, c=c0, n=n_exp, materials=(
        cl.Elastic(E=2e11, nu=0.3), cl.Elastic(E=1e11, nu=0.25)), friction=mu, size=1)
    d0, a0, _ = law0.normal(force=F0)
    s = (mu * m.normal * d0[0] / (2 * m.torsional * a0[0]) if chan == "twist"
         else mu * m.normal * d0[0] / m.tangential)
    path = (cl.LoadPath().ramp(force=F0, steps=1).ramp(**{chan: 1.5 * s}, steps=5)
            .ramp(**{chan: -0.5 * s}, steps=5).ramp(force=2 * F0, **{chan: 2 * s}, steps=10)
            .ramp(force=0.5 * F0, **{chan: -s}, steps=10).ramp(**{chan: s}, steps=6))
    # the twisted path changes the load beyond the MDR validity twist: simulate says so
    with (pytest.warns(cl.errors.ValidityWarning, match="exact") if chan == "twist"
          else nullcontext()):
        r = con.simulate(path, n_springs=N, strategy="steps", method="mdr")
    cover = r.radius.max() / max(r.radius[10], r.radius[11])      # cover x radius at the switch
    law = cl.ContactLaw(cl.profiles.PowerLaw, c=c0, n=n_exp, E_star=m.normal,
                        G_star=m.tangential, G_torsion=m.torsional, friction=mu, springs=N,
                        spring_cover=cover, size=1)
    out = [law.step(depth=r.depth[k], **{chan: getattr(r, chan)[k]})
           for k in range(len(r.depth))]
    exact = np.array([o.exact[0] for o in out])
    assert exact[:11].all() and not exact[11:].any()
    y = np.array([getattr(o, key)[0] for o in out])[~exact]
    ys = getattr(r, key)[~exact]
    np.testing.assert_allclose(y, ys, rtol=0, atol=LAW_SPRINGS * np.abs(ys).max())
