"""Viscoelastic materials and the MDR viscoelastic foundation against closed forms (theory §7)."""
from __future__ import annotations

import numpy as np
import pytest
from scipy.integrate import quad
from scipy.optimize import brentq

import contactlab as cl
from contactlab.errors import ConvergenceError, NotSupportedError, ParameterError
from contactlab.materials.viscoelastic import (GeneralizedMaxwell, KelvinVoigt, Maxwell,
                                               StandardLinearSolid)
from contactlab.profiles import FlatPunch, Paraboloid

from tests import tolerances as TOL
from tests.tolerances import VISCO_EDGE, VISCO_SPATIAL, VISCO_TIME, VISCO_TING

R = 0.01        # m
G = 1.0e6       # Pa
ETA = 1.0e4     # Pa s  (τ = η/G = 10 ms)


def contact(material, profile=None):
    return cl.Contact(profile or Paraboloid(R), materials=(material, cl.Rigid()))


def elastic_contact(G_mod, profile=None):
    # incompressible elastic body on a rigid one: E* = 4G
    return cl.Contact(profile or Paraboloid(R), materials=(cl.Elastic(E=3 * G_mod, nu=0.5),
                                                          cl.Rigid()))


# ---- materials -----------------------------------------------------------------------------
def test_relaxation_functions():
    t = np.array([0.0, 0.003, 0.05])
    np.testing.assert_allclose(Maxwell(G, ETA).relaxation(t), G * np.exp(-t * G / ETA))
    np.testing.assert_allclose(KelvinVoigt(G, ETA).relaxation(t), G)
    sls = StandardLinearSolid(1e6, 2e6, 1e4)
    np.testing.assert_allclose(sls.relaxation(t), 1e6 + 2e6 * np.exp(-t / 5e-3))
    gm = GeneralizedMaxwell(1e5, moduli=[2e5, 1e5], relaxation_times=[0.1, 10.0])
    np.testing.assert_allclose(gm.relaxation(t), 1e5 + 2e5 * np.exp(-t / 0.1)
                               + 1e5 * np.exp(-t / 10.0))
    assert sls.glassy_modulus == 3e6 and sls.relaxed_modulus == 1e6
    assert KelvinVoigt(G, ETA).glassy_modulus == np.inf


@pytest.mark.parametrize("mat", [Maxwell(G, ETA), StandardLinearSolid(1e6, 2e6, 1e4)])
def test_creep_is_the_inverse_of_relaxation(mat):
    """∫_0^t G(t-τ) dJ(τ) + G(t) J(0) = 1 for every t (Volterra identity), by quadrature."""
    h = 1e-9
    for t in (0.002, 0.01, 0.04):
        dJ = lambda tau: (mat.creep(tau + h) - mat.creep(max(tau - h, 0.0))) / (  # noqa: E731
            2 * h if tau > h else tau + h)
        val = quad(lambda tau: mat.relaxation(t - tau) * dJ(tau), 0, t, epsabs=0,
                   epsrel=1e-10, limit=200)[0]
        assert val + mat.relaxation(t) * mat.creep(0.0) == pytest.approx(1.0, rel=TOL.VISCO_IDENTITY)


def test_kelvin_voigt_creep_solves_its_ode():
    m = KelvinVoigt(G, ETA)
    t = np.array([1e-3, 1e-2, 5e-2])
    h = 1e-8
    dJ = (m.creep(t + h) - m.creep(t - h)) / (2 * h)
    np.testing.assert_allclose(G * m.creep(t) + ETA * dJ, 1.0, rtol=TOL.VISCO_IDENTITY)


@pytest.mark.parametrize("make, match", [
    (lambda: KelvinVoigt(-1.0, ETA), "G"),
    (lambda: KelvinVoigt(G, 0.0), "eta"),
    (lambda: Maxwell(G, -ETA), "eta"),
    (lambda: Maxwell(0.0, ETA), "G"),
    (lambda: StandardLinearSolid(0.0, G, ETA), "G_inf"),
    (lambda: StandardLinearSolid(G, -G, ETA), "G_1"),
    (lambda: StandardLinearSolid(G, G, float("nan")), "eta_1"),
    (lambda: GeneralizedMaxwell(-1.0, [G], [0.1]), "G_inf"),
    (lambda: GeneralizedMaxwell(G, [G, -G], [0.1, 1.0]), r"moduli\[1\]"),
    (lambda: GeneralizedMaxwell(G, [G], [0.0]), r"relaxation_times\[0\]"),
    (lambda: GeneralizedMaxwell(G, [G, G], [0.1]), "lengths"),
    (lambda: GeneralizedMaxwell(G, [], []), "moduli"),
])
def test_material_validation(make, match):
    with pytest.raises(ParameterError, match=match):
        make()


def test_relaxation_rejects_negative_time():
    with pytest.raises(ParameterError, match="t contains"):
        Maxwell(G, ETA).relaxation(-1.0)


# ---- closed forms of theory §7 ---------------------------------------------------------
def test_kelvin_voigt_constant_rate():
    """F = (16/3) G a³/R + 8ηva with a = sqrt(R v t)."""
    v = 1e-5
    t = np.linspace(0.0, 1.0, 101)
    h = contact(KelvinVoigt(G, ETA)).viscoelastic_history(time=t, depth=v * t)
    a = np.sqrt(R * v * t)
    F = 16 / 3 * G * a**3 / R + 8 * ETA * v * a
    dx = h.meta["spacing"]
    # the dashpot edge jump 4ηv is resolved to one element; the Hertz part to O(Δx²)
    bound = 8 * ETA * v * dx + 16 * G * a * dx**2 / R + 1e-12 * F
    assert np.all(np.abs(h.force - F) <= bound)
    np.testing.assert_allclose(h.radius, a, atol=VISCO_EDGE * dx)


def test_maxwell_step_depth_relaxation():
    d0 = 1e-6
    t = np.linspace(0.0, 0.05, 51)
    h = contact(Maxwell(G, ETA)).viscoelastic_history(time=t, depth=np.full(t.shape, d0))
    a0 = np.sqrt(R * d0)
    np.testing.assert_allclose(h.force, 16 / 3 * G * a0**3 / R * np.exp(-t * G / ETA),
                               rtol=VISCO_SPATIAL)


def test_sls_step_force_creep():
    """a³(t) = 3 R F0 J(t)/16 (d = a²/R while the contact grows)."""
    m = StandardLinearSolid(1e6, 2e6, 1e4)
    F0 = 0.1
    t = np.linspace(0.0, 0.05, 401)
    h = contact(m).viscoelastic_history(time=t, force=np.full(t.shape, F0))
    a3 = 3 * R * F0 * m.creep(t) / 16
    np.testing.assert_allclose(h.force, F0, rtol=TOL.CLOSED_FORM)
    np.testing.assert_allclose(h.depth, a3 ** (2 / 3) / R, rtol=VISCO_TIME)


def test_sls_constant_rate_lee_radok():
    """Growing contact: F = (16/(3R)) ∫_0^t G(t-τ) d(a³)/dτ dτ [LR60], by quadrature."""
    m = StandardLinearSolid(1e6, 2e6, 1e4)
    v = 1e-4
    t = np.linspace(0.0, 0.03, 301)
    h = contact(m).viscoelastic_history(time=t, depth=v * t)

    def ref(tt):
        k = 1.5 * (R * v) ** 1.5
        return 16 / (3 * R) * quad(lambda s: m.relaxation(tt - s) * k * np.sqrt(s), 0, tt,
                                   epsrel=1e-12)[0]

    for i in (50, 150, 300):
        assert h.force[i] == pytest.approx(ref(t[i]), rel=VISCO_TIME)


def _ting_reference(m, v, tm, t):
    """Ting (1966) for a paraboloid under d = v t, then v(2tm - t): force and contact radius."""
    Gi, Gk, tk, _ = m.prony()

    def I(tt, lo, hi):  # ∫_lo^hi G(tt - τ) dτ
        return Gi * (hi - lo) + float(np.sum(Gk * tk * (np.exp(-(tt - hi) / tk)
                                                         - np.exp(-(tt - lo) / tk))))

    if t <= tm:
        t1 = t
    else:
        cond = lambda s: I(t, s, tm) - I(t, tm, t)   # noqa: E731  edge element force = 0
        t1 = brentq(cond, 0.0, tm, xtol=1e-15) if cond(0.0) > 0 else 0.0
    k = 1.5 * (R * v) ** 1.5
    F = 16 / (3 * R) * quad(lambda s: m.relaxation(t - s) * k * np.sqrt(s), 0, t1,
                            epsrel=1e-12)[0] if t1 > 0 else 0.0
    return F, np.sqrt(R * v * t1)


@pytest.mark.parametrize("mat", [StandardLinearSolid(1e6, 2e6, 1e4), Maxwell(G, ETA)])
def test_ting_unloading_shrinking_contact(mat):
    v, tm = 1e-4, 0.02
    t = np.linspace(0.0, 2 * tm, 801)
    d = np.where(t <= tm, v * t, v * (2 * tm - t))
    h = contact(mat).viscoelastic_history(time=t, depth=d)
    refs = np.array([_ting_reference(mat, v, tm, tt) for tt in t[::40]])
    F_peak = np.max(refs[:, 0])
    np.testing.assert_allclose(h.force[::40], refs[:, 0], atol=VISCO_TING * F_peak)
    np.testing.assert_allclose(h.radius[::40], refs[:, 1], atol=VISCO_EDGE * h.meta["spacing"])
    # the surface recovers slowly, so the indenter leaves it: the contact is smaller than the
    # geometric rule d = g(a) would give (the two agree to first order in t - tm, so compare from
    # a quarter of the unloading on)
    late = (t > 1.25 * tm) & (h.force > 0)
    assert np.all(h.radius[late] < np.sqrt(R * np.maximum(d[late], 0)) - h.meta["spacing"])
    assert np.all(h.force >= 0)                       # no adhesion: never tensile
    if isinstance(mat, Maxwell):
        # the Maxwell body separates before the indenter is back at d = 0
        lost = np.flatnonzero((t > tm) & (h.force == 0))
        assert lost.size and d[lost[0]] > 0


def test_elastic_limits_recover_contact_normal():
    t = np.linspace(0.0, 1.0, 101)
    d = 2e-6 * np.where(t <= 0.5, t, 1.0 - t)
    for mat, G_el in ((KelvinVoigt(G, 1e-9), G), (StandardLinearSolid(G, 1e-6, 1e-9), G)):
        h = contact(mat).viscoelastic_history(time=t, depth=d)
        ref = elastic_contact(G_el).normal(depth=d)
        np.testing.assert_allclose(h.force, ref.force, rtol=VISCO_SPATIAL,
                                   atol=VISCO_SPATIAL * np.max(ref.force))
        np.testing.assert_allclose(h.radius, ref.radius, atol=VISCO_EDGE * h.meta["spacing"])


def test_elastic_limit_force_control():
    t = np.linspace(0.0, 1.0, 21)
    F = 0.05 * np.sin(np.pi * t)
    h = contact(StandardLinearSolid(G, 1e-6, 1e-9)).viscoelastic_history(time=t, force=F)
    ref = elastic_contact(G).normal(force=F)
    np.testing.assert_allclose(h.depth, ref.depth, rtol=VISCO_SPATIAL,
                               atol=VISCO_SPATIAL * np.max(ref.depth))


def test_flat_punch_maxwell_relaxation():
    b = 1e-3
    t = np.linspace(0.0, 0.05, 11)
    h = contact(Maxwell(G, ETA), FlatPunch(b)).viscoelastic_history(time=t,
                                                                    depth=np.full(t.shape, 1e-6))
    np.testing.assert_allclose(h.force, 8 * G * b * 1e-6 * np.exp(-t * G / ETA), rtol=TOL.EXACT_ROUTES)


def test_time_step_convergence_order():
    """SLS creep: fitted order of the depth error over a Δt ladder (exponential integrator)."""
    m = StandardLinearSolid(1e6, 2e6, 1e4)
    F0 = 0.1
    errs, dts = [], []
    for n in (26, 51, 101, 201):
        t = np.linspace(0.0, 0.05, n)
        h = contact(m).viscoelastic_history(time=t, force=np.full(t.shape, F0), n_springs=500)
        ref = (3 * R * F0 * m.creep(t) / 16) ** (2 / 3) / R
        errs.append(np.max(np.abs(h.depth / ref - 1)))
        dts.append(t[1])
    order = np.polyfit(np.log(dts), np.log(errs), 1)[0]
    assert order > 1.8


# ---- unsupported combinations and validation -----------------------------------------------
def test_viscoelastic_with_elastic_partner_not_supported():
    with pytest.raises(NotSupportedError, match="rigid indenter"):
        cl.Contact(Paraboloid(R), materials=(Maxwell(G, ETA), cl.Elastic(E=1e9, nu=0.3)))


def test_two_viscoelastic_bodies_not_supported():
    with pytest.raises(NotSupportedError, match="rigid indenter"):
        cl.Contact(Paraboloid(R), materials=(Maxwell(G, ETA), Maxwell(G, ETA)))


def test_elastic_solvers_and_torsion_not_covered():
    c = contact(Maxwell(G, ETA))
    with pytest.raises(NotSupportedError, match="not covered by the theory in docs/theory"):
        c.normal(depth=1e-6)
    # torsion (issue 3) and tangential solvers go through the same effective moduli
    with pytest.raises(NotSupportedError, match="torsion"):
        c.moduli.torsional


def test_history_needs_viscoelastic_material():
    with pytest.raises(NotSupportedError, match="viscoelastic body"):
        elastic_contact(G).viscoelastic_history(time=[0.0, 1.0], depth=[0.0, 1e-6])


def test_adhesion_with_viscoelastic_not_supported():
    c = cl.Contact(Paraboloid(R), materials=(Maxwell(G, ETA), cl.Rigid()), work_of_adhesion=0.1)
    with pytest.raises(NotSupportedError, match="work_of_adhesion"):
        c.viscoelastic_history(time=[0.0, 1.0], depth=[0.0, 1e-6])


def test_time_must_be_non_decreasing():
    with pytest.raises(ParameterError, match="time"):
        contact(Maxwell(G, ETA)).viscoelastic_history(time=[0.0, 1.0, 0.5], depth=[0, 1e-6, 0])


def test_history_shapes_must_match():
    with pytest.raises(ParameterError, match="depth has shape"):
        contact(Maxwell(G, ETA)).viscoelastic_history(time=[0.0, 1.0], depth=[0.0])


def test_n_springs_validation():
    with pytest.raises(ParameterError, match="n_springs"):
        contact(Maxwell(G, ETA)).viscoelastic_history(time=[0.0, 1.0], depth=[0, 1e-6],
                                                      n_springs=1)


def test_exactly_one_load():
    with pytest.raises(ParameterError, match="exactly one"):
        contact(Maxwell(G, ETA)).viscoelastic_history(time=[0.0, 1.0])


def test_kelvin_voigt_cannot_jump():
    with pytest.raises(ParameterError, match="Kelvin-Voigt"):
        contact(KelvinVoigt(G, ETA)).viscoelastic_history(time=[0.0, 1.0], depth=[1e-6, 1e-6])


def test_foundation_too_small():
    with pytest.raises(ConvergenceError, match="max_radius"):
        contact(Maxwell(G, ETA)).viscoelastic_history(time=[0.0, 1.0], depth=[1e-6, 1e-6],
                                                      max_radius=1e-5)


def test_csv_round_trip(tmp_path):
    t = np.linspace(0.0, 0.01, 5)
    h = contact(Maxwell(G, ETA)).viscoelastic_history(time=t, depth=np.full(5, 1e-6))
    p = tmp_path / "h.csv"
    h.to_csv(str(p))
    data = np.loadtxt(p, delimiter=",", skiprows=1)
    np.testing.assert_array_equal(data[:, 2], h.force)


def test_generalized_maxwell_constant_rate_lee_radok():
    m = GeneralizedMaxwell(2e5, moduli=[1e6, 5e5, 2e5], relaxation_times=[1e-3, 1e-2, 1e-1])
    v = 1e-4
    t = np.linspace(0.0, 0.03, 61)
    h = contact(m).viscoelastic_history(time=t, depth=v * t)
    k = 1.5 * (R * v) ** 1.5
    for i in (20, 60):
        ref = 16 / (3 * R) * quad(lambda s: m.relaxation(t[i] - s) * k * np.sqrt(s), 0, t[i],
                                  epsrel=1e-12)[0]
        assert h.force[i] == pytest.approx(ref, rel=VISCO_TIME)


@pytest.mark.parametrize("m", [StandardLinearSolid(1e6, 2e6, 1e4), KelvinVoigt(G, ETA)])
def test_force_and_depth_control_are_inverse(m):
    """Force-controlled load/unload/hold; replaying its depth history reproduces the forces."""
    t = np.linspace(0.0, 0.06, 121)
    F = np.clip(0.1 * np.sin(np.pi * t / 0.04), 0.0, None) * (t <= 0.04)
    c = contact(m)
    hf = c.viscoelastic_history(time=t, force=F)
    np.testing.assert_allclose(hf.force, F, rtol=TOL.CLOSED_FORM, atol=TOL.ABS_FLOOR_TINY)
    hd = c.viscoelastic_history(time=t, depth=hf.depth, max_radius=hf.meta["foundation_radius"])
    np.testing.assert_allclose(hd.force, F, rtol=TOL.VISCO_FORCE_CONTROL, atol=TOL.CLOSED_FORM * F.max())
    # after release the free surface recovers (SLS): the touching depth decreases towards 0
    after = t > 0.045
    assert np.all(np.diff(hf.depth[after]) < 0) and np.all(hf.depth[after] > 0)
