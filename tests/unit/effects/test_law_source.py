"""ContactLaw.to_source(): the generated numpy-only module, imported from a temporary folder,
against ContactLaw on random contacts and histories (with reversals, loop closures, overflow,
separation and reset), for every family (power laws and flat punches)."""
import importlib.util
import numpy as np
import pytest

import contactlab as cl
from tests.tolerances import LAW_SOURCE

FAMILIES = [(cl.profiles.Paraboloid, "R", {}, (1e-3, 1e-2)),
            (cl.profiles.Cone, "slope", {}, (0.05, 0.2)),
            (cl.profiles.PowerLaw, "c", {"n": 4.0}, (1e5, 1e7)),
            (cl.profiles.FlatPunch, "radius", {}, (1e-4, 1e-2))]


def _import(tmp_path, src, name):
    path = tmp_path / f"{name}.py"
    path.write_text(src)
    spec = importlib.util.spec_from_file_location(name, path)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


@pytest.mark.parametrize("family, gname, extra, grange", FAMILIES)
def test_generated_law_matches_contact_law(tmp_path, family, gname, extra, grange):
    rng = np.random.default_rng(41)
    n = 60
    par = {gname: rng.uniform(*grange, n), "E_star": 10 ** rng.uniform(10, 11.3, n),
           "G_star": 10 ** rng.uniform(9.8, 10.8, n), "G_torsion": 10 ** rng.uniform(9.8, 10.8, n),
           "friction": rng.uniform(0.1, 0.8, n)}
    law = cl.ContactLaw(family, fast=False, memory=4, **extra, **par)
    src = law.to_source()
    imports = [ln.split() for ln in src.splitlines() if ln.lstrip().startswith(("import ", "from "))]
    assert {ln[1] for ln in imports} <= {"numpy", "__future__", "typing"}, imports
    mod = _import(tmp_path, src, f"vendored_law_{gname}")
    ven = mod.Law(memory=4, **par)
    F = 10 ** rng.uniform(-1, 2, n)
    d, a, _ = law.normal(force=F)
    # histories scaled by each contact's full-slip scales: partial slip, gross slip, reversals
    mu, Es = par["friction"], par["E_star"]
    phi_s = mu * Es * d / (2 * par["G_torsion"] * a)
    u_s = mu * Es * d / par["G_star"]
    steps = 120
    phi = np.cumsum(rng.standard_normal((steps, n)), axis=0) * 0.6 * phi_s
    u = np.cumsum(rng.standard_normal((steps, n)), axis=0) * 0.3 * u_s
    names = ("depth", "radius", "force", "tangential_force", "torque", "stick_radius",
             "torsion_stick_radius", "dissipated_energy")
    with pytest.warns(cl.errors.ValidityWarning):
        for k in range(steps):
            Fk = F.copy()
            if k == 70:
                Fk[:5] = 0.0                       # separation clears five contacts
            if k == 90:
                law.reset(np.arange(5, 10))
                ven.reset(np.arange(5, 10))
            if k % 2:
                dk = law.normal(force=Fk)[0]
                r1 = law.step(depth=dk, twist=phi[k], displacement=u[k])
                r2 = ven.step(depth=dk, twist=phi[k], displacement=u[k])
            else:
                r1 = law.step(force=Fk, twist=phi[k], displacement=u[k])
                r2 = ven.step(force=Fk, twist=phi[k], displacement=u[k])
            for name in names:
                x, y = getattr(r1, name), r2[name]
                np.testing.assert_allclose(y, x, rtol=LAW_SOURCE,
                                           atol=LAW_SOURCE * np.max(np.abs(x)), err_msg=name)
    st = law.state
    assert st["tor_overflow"].any() and st["tan_overflow"].any()
    assert set(ven.state) == {k for k in st if not k.startswith("spr_")}   # no spring state
    for key, v in ven.state.items():
        np.testing.assert_allclose(v, st[key], rtol=LAW_SOURCE, atol=0, err_msg=key)


def test_generated_law_refuses_a_changed_load(tmp_path):
    law = cl.ContactLaw(cl.profiles.Paraboloid, R=0.01, E_star=1e11, G_star=4e10,
                        G_torsion=4e10, friction=0.3, size=3)
    mod = _import(tmp_path, law.to_source(), "vendored_law_load")
    ven = mod.Law(R=0.01, E_star=1e11, G_star=4e10, G_torsion=4e10, friction=0.3, size=3)
    ven.step(force=[1.0, 2.0, 3.0], twist=1e-5)
    with pytest.raises(ValueError, match="contact 1"):
        ven.step(force=[1.0, 2.5, 3.0], twist=2e-5)
