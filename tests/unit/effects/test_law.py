"""ContactLaw at constant normal load against the single-contact API, Masing properties,
state round trip, reset and validation."""
import numpy as np
import pytest

import contactlab as cl
from contactlab.errors import NotSupportedError, OutsideTheoryError, ParameterError
from contactlab.errors import ValidityWarning
from tests.reference.hertz import radius_of_force
from tests.tolerances import CLOSED_FORM, COMPILED_VS_NUMPY, LAW_HISTORY, LOOP_AREA


def _history(rng, steps, amp):
    """Random walk with reversals, from 0."""
    inc = rng.standard_normal(steps) * amp / np.sqrt(steps) * 3
    return np.concatenate([[0.0], np.cumsum(inc)])[1:]


@pytest.fixture(scope="module")
def fifty():
    rng = np.random.default_rng(14)
    n = 50
    R = 10 ** rng.uniform(-3, -1, n)
    E1 = 10 ** rng.uniform(10, 11.5, n)
    nu1 = rng.uniform(0.0, 0.45, n)
    E2 = 10 ** rng.uniform(10, 11.5, n)
    nu2 = rng.uniform(0.0, 0.45, n)
    mu = rng.uniform(0.1, 0.8, n)
    F = 10 ** rng.uniform(-1, 3, n)
    contacts = [cl.Contact(cl.profiles.Paraboloid(R=R[i]),
                           materials=(cl.Elastic(E=E1[i], nu=nu1[i]), cl.Elastic(E=E2[i], nu=nu2[i])),
                           friction=mu[i]) for i in range(n)]
    mod = [c.moduli for c in contacts]
    Es = np.array([m.normal for m in mod])
    Gs = np.array([m.tangential for m in mod])
    Gt = np.array([m.torsional for m in mod])
    steps = 60
    # amplitudes around the full-slip scales, so that histories reach partial and gross slip
    a = np.array([radius_of_force(F[i], R[i], Es[i]) for i in range(n)])
    d = a * a / R
    phi_s = mu * Es * d / (2 * Gt * a)
    u_s = mu * Es * d / Gs
    phi = np.stack([_history(rng, steps, 2 * phi_s[i]) for i in range(n)], axis=1)
    u = np.stack([_history(rng, steps, 0.7 * u_s[i]) for i in range(n)], axis=1)
    return dict(contacts=contacts, R=R, Es=Es, Gs=Gs, Gt=Gt, mu=mu, F=F, phi=phi, u=u)


def _law(f, **kw):
    return cl.ContactLaw(cl.profiles.Paraboloid, R=f["R"], E_star=f["Es"], G_star=f["Gs"],
                         G_torsion=f["Gt"], friction=f["mu"], **kw)


def test_fifty_contacts_twist_history(fifty):
    f = fifty
    law = _law(f, memory=64)
    out = [law.step(force=f["F"], twist=p) for p in f["phi"]]
    M = np.stack([o.torque for o in out])
    c = np.stack([o.torsion_stick_radius for o in out])
    W = np.cumsum(np.stack([o.dissipated_energy for o in out]), axis=0)
    assert not law.state["tor_overflow"].any()
    for i, con in enumerate(f["contacts"]):
        h = con.twist_history(force=f["F"][i], twist=f["phi"][:, i], method="exact")
        amp = np.max(np.abs(h.torque))
        assert np.max(np.abs(M[:, i] - h.torque)) <= LAW_HISTORY * amp
        assert np.max(np.abs(c[:, i] - h.stick_radius)) <= LAW_HISTORY * h.normal.radius
        assert np.max(np.abs(W[:, i] - h.dissipated_energy)) <= LAW_HISTORY * h.dissipated_energy[-1]


def test_fifty_contacts_shift_history(fifty):
    f = fifty
    law = _law(f, memory=64)
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


@pytest.mark.parametrize("profile,kw,single", [
    (cl.profiles.Paraboloid, {"R": [0.01, 0.002]}, lambda i: cl.profiles.Paraboloid(R=[0.01, 0.002][i])),
    (cl.profiles.Cone, {"slope": [0.1, 0.3]}, lambda i: cl.profiles.Cone(slope=[0.1, 0.3][i])),
    (cl.profiles.PowerLaw, {"c": [3.0, 50.0], "n": 3.0},
     lambda i: cl.profiles.PowerLaw(c=[3.0, 50.0][i], n=3.0)),
])
def test_normal_and_families(profile, kw, single):
    steel = cl.Elastic(E=210e9, nu=0.3)
    law = cl.ContactLaw(profile, materials=(steel, steel), friction=0.3, **kw)
    F = np.array([5.0, 50.0])
    d, a, FF = law.normal(force=F)
    phi = np.array([1e-4, -3e-4])
    out = law.step(force=F, twist=phi)
    for i in range(2):
        con = cl.Contact(single(i), materials=(steel, steel), friction=0.3)
        ns = con.normal(force=F[i])
        assert d[i] == pytest.approx(ns.depth, rel=CLOSED_FORM)
        assert a[i] == pytest.approx(ns.radius, rel=CLOSED_FORM)
        d2, a2, F2 = law.normal(depth=np.full(2, ns.depth))
        assert F2[i] == pytest.approx(F[i], rel=CLOSED_FORM)
        ts = con.torsion(force=F[i], twist=phi[i], method="exact")
        assert out.torque[i] == pytest.approx(ts.torque, rel=LAW_HISTORY)
        assert out.torsion_stick_radius[i] == pytest.approx(ts.stick_radius, rel=LAW_HISTORY)


def _hertz_law(memory=8):
    return cl.ContactLaw(cl.profiles.Paraboloid, R=0.01, E_star=1.15e11, G_star=4.4e10,
                         G_torsion=4.0e10, friction=0.3, memory=memory, size=1)


def _run(law, phi, F=100.0):
    return np.array([law.step(force=F, twist=p).torque[0] for p in phi]), law


def test_masing_symmetry_and_erasure():
    """M(-φ) = -M(φ); an inner loop that closes is forgotten: the response afterwards equals the
    one of the history without the inner loop."""
    up = np.linspace(0, 4e-4, 41)[1:]
    down = np.linspace(4e-4, -2e-4, 61)[1:]
    inner = np.concatenate([np.linspace(-2e-4, 1e-4, 31)[1:], np.linspace(1e-4, -2e-4, 31)[1:]])
    after = np.linspace(-2e-4, -4e-4, 21)[1:]
    with_loop = np.concatenate([up, down, inner, after])
    without = np.concatenate([up, down, after])
    M1, _ = _run(_hertz_law(), with_loop)
    M2, _ = _run(_hertz_law(), without)
    Mneg, _ = _run(_hertz_law(), -with_loop)
    np.testing.assert_array_equal(Mneg, -M1)
    k = up.size + down.size + inner.size
    np.testing.assert_allclose(M1[k:], M2[up.size + down.size:], rtol=1e-13, atol=0)
    # the inner loop returned exactly to its start point
    assert M1[k - 1] == pytest.approx(M1[up.size + down.size - 1], rel=1e-13)
    # Masing: the unloading branch reaches -M_max at -φ_max and rejoins the virgin curve
    cyc = np.concatenate([up, np.linspace(4e-4, -4e-4, 81)[1:], np.linspace(-4e-4, -6e-4, 21)[1:]])
    Mc, _ = _run(_hertz_law(), cyc)
    Mv, _ = _run(_hertz_law(), -np.linspace(0, 6e-4, 61)[1:])
    assert Mc[up.size + 79] == pytest.approx(-Mc[up.size - 1], rel=1e-13)
    assert Mc[-1] == pytest.approx(Mv[-1], rel=1e-12)


def test_energy_per_cycle_is_loop_area():
    """Dissipation per steady cycle = ∮ M dφ (trapezoid over a fine cycle, a second method)."""
    law = _hertz_law()
    amp = 5e-4
    n = 4000
    first = np.linspace(0, amp, n // 4 + 1)[1:]
    cyc = amp * np.cos(np.linspace(0, 2 * np.pi, n + 1)[1:])
    for p in first:
        law.step(force=100.0, twist=p)
    M = np.empty(n)
    W = 0.0
    for i, p in enumerate(cyc):
        o = law.step(force=100.0, twist=p)
        M[i] = o.torque[0]
        W += o.dissipated_energy[0]
    phi = np.concatenate([[amp], cyc])
    Mc = np.concatenate([[M[-1]], M])
    area = np.sum(0.5 * (Mc[1:] + Mc[:-1]) * np.diff(phi))   # work done on the contact
    assert W == pytest.approx(area, rel=LOOP_AREA)


@pytest.mark.parametrize("t0", [0.7, 0.2])
def test_energy_per_cycle_matches_twist_history_and_closed_form(t0):
    """Steady cycles ±φ0: the law's energy per cycle equals Contact.twist_history's (exact
    Masing hysteresis of the single-contact API) and the closed form of Hertz torsion
    (independent mpmath reference: W = 8∫_0^φ0 M dφ - 4φ0 M0 with Lubkin's M(φ))."""
    ref = pytest.importorskip("tests.reference.torsion_reference")
    steel = cl.Elastic(E=210e9, nu=0.3)
    R, F, mu = 0.01, 100.0, 0.3
    con = cl.Contact(cl.profiles.Paraboloid(R=R), materials=(steel, steel), friction=mu)
    a, G = con.normal(force=F).radius, con.moduli.torsional
    phi0 = float(ref.hertz_twist_hat(t0)) * mu * F / (G * a * a)
    steps, cycles = 40, 4
    k = np.arange(1, steps * cycles + 1)
    hist = np.concatenate([np.linspace(0, phi0, 11)[1:], phi0 * np.cos(2 * np.pi * k / steps)])
    law = cl.ContactLaw(cl.profiles.Paraboloid, R=R, materials=(steel, steel), friction=mu,
                        size=1)
    W = np.cumsum([law.step(force=F, twist=p).dissipated_energy[0] for p in hist])
    h = con.twist_history(force=F, twist=hist, method="exact")
    ends = 10 - 1 + steps * np.arange(cycles + 1)          # after the ramp, after each cycle
    per_law = np.diff(W[ends])
    per_hist = np.diff(h.dissipated_energy[ends])
    closed = float(ref.hertz_loop_energy_hat(t0)) * (mu * F) ** 2 / (G * a)
    np.testing.assert_allclose(per_law, per_hist, rtol=LAW_HISTORY)
    np.testing.assert_allclose(per_law, closed, rtol=LAW_HISTORY)


def test_state_round_trip_and_reset(tmp_path):
    rng = np.random.default_rng(3)
    phi = np.cumsum(rng.standard_normal((40, 5)), axis=0) * 1e-4
    u = np.cumsum(rng.standard_normal((40, 5)), axis=0) * 1e-7
    F = np.linspace(10, 50, 5)

    def make():
        return cl.ContactLaw(cl.profiles.Paraboloid, R=np.linspace(0.005, 0.02, 5),
                             E_star=1.15e11, G_star=4.4e10, G_torsion=4e10, friction=0.3)

    ref = make()
    full = [ref.step(force=F, twist=phi[i]) for i in range(40)]
    law = make()
    for i in range(20):
        law.step(force=F, twist=phi[i])
    np.savez(tmp_path / "s.npz", **law.state)
    other = make()
    other.state = dict(np.load(tmp_path / "s.npz"))
    for i in range(20, 40):
        o = other.step(force=F, twist=phi[i])
        np.testing.assert_array_equal(o.torque, full[i].torque)
        np.testing.assert_array_equal(o.dissipated_energy, full[i].dissipated_energy)
    # reset: contact 2 starts afresh, the others keep their memory
    other.reset(np.arange(5) == 2)
    fresh = make()
    o = other.step(force=F, twist=phi[0])
    f0 = fresh.step(force=F, twist=phi[0])
    assert o.torque[2] == f0.torque[2]
    assert o.torque[0] != f0.torque[0]
    # separation clears the memory too
    d, a, _ = other.normal(force=F)
    o = other.step(depth=np.where(np.arange(5) == 1, -1e-9, d), displacement=u[0])
    assert o.force[1] == 0 and o.tangential_force[1] == 0 and not o.exact[1]
    assert other.state["tor_depth"][1] == 0


def test_overflow_flag():
    """Beyond `memory` nested reversals the contact is flagged; the response stays the exact one
    until a forgotten loop would have closed, and differs by less than the loop size after."""
    ring = 4e-4 * np.sin(np.linspace(0, 6 * np.pi, 301)) * np.exp(-np.linspace(0, 1, 301))
    hist = np.concatenate([ring, np.linspace(ring[-1], 6e-4, 101)[1:]])
    M_big, big = _run(_hertz_law(memory=64), hist)
    with pytest.warns(ValidityWarning, match="memory=2"):
        M_small, small = _run(_hertz_law(memory=2), hist)
    assert small.state["tor_overflow"][0] and not big.state["tor_overflow"][0]
    diff = np.flatnonzero(np.abs(M_small - M_big) > 1e-12 * np.max(np.abs(M_big)))
    assert diff.size and diff[0] >= ring.size
    assert np.max(np.abs(M_small - M_big)) < 0.1 * np.max(np.abs(M_big))
    assert M_small[-1] == pytest.approx(M_big[-1], rel=1e-12)   # back on the virgin curve


def test_combined_shift_and_twist_warns():
    law = _hertz_law()
    with pytest.warns(ValidityWarning, match="independent"):
        law.step(force=100.0, twist=1e-4, displacement=1e-7)


@pytest.mark.parametrize("kw,exc,match", [
    ({"R": [0.01, np.nan, 0.02]}, ParameterError, r"R\[1\]=nan"),
    ({"R": 0.01, "E_star": [1e11, -1.0, 1e11]}, ParameterError, r"E_star\[1\]=-1.0"),
    ({"R": [0.01, 0.02], "friction": [0.3, 0.3, 0.3]}, ParameterError, "R has 2, friction has 3"),
    ({"R": [[0.01]]}, ParameterError, "R has shape"),
    ({"slope": 0.1}, ParameterError, "slope= is not a parameter"),
    ({"R": 0.01, "memory": 1}, ParameterError, "memory=1"),
    ({"R": 0.01, "torsion": "mdr"}, cl.errors.UnknownNameError, "torsion='mdr'"),
])
def test_validation(kw, exc, match):
    base = dict(E_star=1e11, G_star=4e10, G_torsion=4e10, friction=0.3)
    base.update(kw)
    with pytest.raises(exc, match=match):
        cl.ContactLaw(cl.profiles.Paraboloid, **base)


def test_validation_profiles_and_steps():
    with pytest.raises(NotSupportedError, match="Sphere"):
        cl.ContactLaw(cl.profiles.Sphere, R=0.01, E_star=1e11, G_star=4e10, G_torsion=4e10,
                      friction=0.3)
    with pytest.raises(NotSupportedError, match=r"n=0.005.*n >= 0.01.*singularity"):
        cl.ContactLaw(cl.profiles.PowerLaw, c=1.0, n=0.005, E_star=1e11, G_star=4e10,
                      G_torsion=4e10, friction=0.3)
    law = cl.ContactLaw(cl.profiles.Paraboloid, R=[0.01] * 4, E_star=1e11, G_star=4e10,
                        G_torsion=4e10, friction=0.3, springs=0)
    with pytest.raises(ParameterError, match=r"twist\[2\]=nan"):
        law.step(force=1.0, twist=[0, 0, np.nan, 0])
    with pytest.raises(ParameterError, match=r"force\[3\]=-1.0"):
        law.step(force=[1.0, 1.0, 1.0, -1.0])
    with pytest.raises(ParameterError, match="exactly one"):
        law.step(twist=0.0)
    law.step(force=[1.0, 2.0, 3.0, 4.0], twist=1e-5)
    with pytest.raises(OutsideTheoryError, match=r"depth\[2\]"):
        law.step(force=[1.0, 2.0, 3.5, 4.0], twist=1e-5)
    with pytest.raises(ParameterError, match="state is invalid"):
        law.state = {"depth_ref": np.zeros(4)}


@pytest.mark.skipif(not cl.effects.law._kernel.AVAILABLE, reason="numba (extra 'fast') not installed")
@pytest.mark.parametrize("by", ["force", "depth"])
def test_compiled_kernel_matches_numpy(by):
    """The compiled step (normal pass + fused channels + spring pass) against the numpy path,
    incl. stack overflow, separation, a load change onto the springs, a regrid and a reset.
    Depth control: the same arithmetic at constant load, bit-identical (the spring pass
    reorders the cell integrals: to COMPILED_VS_NUMPY). Force control: the compiled radius a = (...)^(1/(n+1)) may differ
    by an ulp from numpy's power; responses then agree to COMPILED_VS_NUMPY of their largest
    value, the per-step dissipation (a difference of branch dissipations, conditioned as 1/x for
    small slip) to COMPILED_VS_NUMPY of the cumulative dissipation."""
    rng = np.random.default_rng(5)
    n = 200
    kw = dict(R=rng.uniform(1e-3, 1e-2, n), E_star=1.15e11, G_star=4.4e10, G_torsion=4e10,
              friction=rng.uniform(0.1, 0.5, n), memory=4)
    fast = cl.ContactLaw(cl.profiles.Paraboloid, fast=True, **kw)
    slow = cl.ContactLaw(cl.profiles.Paraboloid, fast=False, **kw)
    load = rng.uniform(1, 100, n) if by == "force" else rng.uniform(1e-7, 1e-6, n)
    phi = np.cumsum(rng.standard_normal((80, n)), axis=0) * 1e-4
    u = np.cumsum(rng.standard_normal((80, n)), axis=0) * 3e-8
    W = np.zeros(n)
    with pytest.warns(ValidityWarning):
        for k in range(80):
            L = load.copy()
            if k >= 20:
                L[:5] = 0.0                                   # separated
            if k >= 40:
                L[5:10] *= 1.0 + 0.01 * (k - 39)              # load change: springs
            if k >= 50:
                L[9] *= 4.0                                   # radius beyond the cover: regrid
            if k == 60:
                fast.reset(np.arange(10, 15))
                slow.reset(np.arange(10, 15))
            a = fast.step(**{by: L}, twist=phi[k], displacement=u[k])
            b = slow.step(**{by: L}, twist=phi[k], displacement=u[k])
            W += b.dissipated_energy
            np.testing.assert_array_equal(a.exact, b.exact)
            for name in ("depth", "radius", "force", "torque", "tangential_force",
                         "stick_radius", "torsion_stick_radius", "dissipated_energy"):
                x, y = getattr(a, name), getattr(b, name)
                if by == "depth":        # same arithmetic at constant load; springs: reordered
                    np.testing.assert_array_equal(x[a.exact], y[a.exact], err_msg=name)
                scale = W.max() if name == "dissipated_energy" else np.max(np.abs(y))
                np.testing.assert_allclose(x, y, rtol=0, atol=COMPILED_VS_NUMPY * scale,
                                           err_msg=name)
    assert fast.state["tor_overflow"].any()      # the overflow path is exercised too
    assert fast.state["spr_on"][5:10].all() and not fast.state["spr_on"][10:].any()
    on = fast.state["spr_on"]
    for k, v in fast.state.items():
        ref = slow.state[k]
        if k.startswith(("tan_", "tor_")):
            # a contact on springs never returns to the Masing stacks: the compiled step leaves
            # them as they were at the switch, the numpy step keeps advancing them (unused)
            v, ref = v[~on], ref[~on]
        if v.dtype != float or (by == "depth" and not k.startswith("spr_")):
            np.testing.assert_array_equal(v, ref, err_msg=k)
        else:
            np.testing.assert_allclose(v, ref, rtol=0, atol=COMPILED_VS_NUMPY
                                       * np.max(np.abs(ref), initial=0.0), err_msg=k)


@pytest.mark.skipif(not cl.effects.law._kernel.AVAILABLE, reason="numba (extra 'fast') not installed")
def test_threaded_kernel_is_bit_identical():
    rng = np.random.default_rng(6)
    n = 3000
    kw = dict(R=rng.uniform(1e-3, 1e-2, n), E_star=1.15e11, G_star=4.4e10, G_torsion=4e10,
              friction=rng.uniform(0.1, 0.5, n), memory=4)
    par = cl.ContactLaw(cl.profiles.Paraboloid, fast=True, parallel=True, **kw)
    ser = cl.ContactLaw(cl.profiles.Paraboloid, fast=True, **kw)
    F = rng.uniform(1, 100, n)
    with pytest.warns(ValidityWarning):
        for k in range(30):
            phi = np.sin(0.7 * k + np.arange(n)) * 3e-4
            u = np.cos(0.5 * k + np.arange(n)) * 1e-7
            a = par.step(force=F, twist=phi, displacement=u)
            b = ser.step(force=F, twist=phi, displacement=u)
            for name in ("torque", "tangential_force", "stick_radius", "torsion_stick_radius",
                         "dissipated_energy"):
                assert np.array_equal(getattr(a, name), getattr(b, name)), name


@pytest.mark.parametrize("fast", [False, True] if cl.effects.law._kernel.AVAILABLE else [False])
def test_step_into_out_arrays(fast):
    """step(out=earlier) overwrites the earlier result's arrays with exactly the results of a
    step without out; a foreign or mis-shaped out is refused."""
    rng = np.random.default_rng(11)
    n = 50
    kw = dict(R=rng.uniform(1e-3, 1e-2, n), E_star=1.15e11, G_star=4.4e10, G_torsion=4e10,
              friction=0.3, fast=fast)
    a, b = _plain_law(**kw), _plain_law(**kw)
    F = rng.uniform(1, 100, n)
    buf = a.step(force=F, twist=0.0)
    b.step(force=F, twist=0.0)
    for k in range(1, 20):
        tw = 3e-4 * np.sin(0.4 * k + np.arange(n))
        got = a.step(force=F, twist=tw, out=buf)
        ref = b.step(force=F, twist=tw)
        assert got is buf
        for f in ("depth", "radius", "force", "torque", "torsion_stick_radius",
                  "dissipated_energy", "exact"):
            np.testing.assert_array_equal(getattr(got, f), getattr(ref, f), err_msg=f)
    other = _plain_law(R=[0.01] * 3, E_star=1e11, G_star=4e10, G_torsion=4e10, friction=0.3)
    with pytest.raises(ParameterError, match="out=LawStep is invalid"):
        a.step(force=F, twist=0.0, out=other.step(force=1.0, twist=0.0))
    with pytest.raises(ParameterError, match="out=dict is invalid"):
        a.step(force=F, twist=0.0, out={})


def _plain_law(**kw):
    return cl.ContactLaw(cl.profiles.Paraboloid, **kw)
