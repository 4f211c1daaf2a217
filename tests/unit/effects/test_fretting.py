"""Fretting loops and maps (issue 15) against closed forms derived in docs/fretting.md
(tests/reference/fretting.py)."""
from __future__ import annotations

import warnings

import numpy as np
import pytest

import contactlab as cl
from contactlab.errors import NotSupportedError, ParameterError, UnknownNameError, ValidityWarning
from tests.reference import fretting as ref
from tests.reference.hertz import radius_of_force
from tests.tolerances import (FRETTING_CLOSED, LOOP_TRAPEZOID, SMALL_LOOP_ENERGY, SMALL_LOOP_FLOOR,
                              TORSION_BOUNDARY, TORSION_BOUNDARY_ROOT)

STEEL = cl.Elastic(E=210e9, nu=0.3)
MU = 0.5
F = 100.0


def contact(profile=None, mu=MU):
    return cl.Contact(profile or cl.profiles.Paraboloid(R=0.01), materials=(STEEL, STEEL),
                      friction=mu)


POWER = [(1.0, cl.profiles.Cone(slope=0.05)), (2.0, cl.profiles.Paraboloid(R=0.01)),
         (4.0, cl.profiles.PowerLaw(c=1e8, n=4))]


def _C(profile, n):
    return {1.0: lambda p: p.slope, 2.0: lambda p: 0.5 / p.R, 4.0: lambda p: p.c}[n](profile)


@pytest.mark.parametrize("n,profile", POWER)
def test_onset_energy_ratio_power_law(n, profile):
    c = contact(profile)
    E, G = c.moduli.normal, c.moduli.tangential
    u_t = ref.gross_slip_amplitude(F, MU, E, G, _C(profile, n), n)
    loop = c.fretting_loop(force=F, displacement_amplitude=u_t)
    assert loop.energy_ratio == pytest.approx(ref.onset_energy_ratio(n), rel=1e-8)
    assert loop.meta["gross_slip_amplitude"] == pytest.approx(u_t, rel=1e-10)
    above = c.fretting_loop(force=F, displacement_amplitude=u_t * (1 + 1e-9))
    assert above.regime == "gross_slip"
    below = c.fretting_loop(force=F, displacement_amplitude=u_t * (1 - 1e-9))
    assert below.regime == "partial_slip"


@pytest.mark.parametrize("n,profile", POWER)
def test_gross_slip_amplitude_against_force(n, profile):
    c = contact(profile)
    forces = np.geomspace(1.0, 1e3, 7)
    m = c.fretting_map(force=forces, displacement_amplitude=[1e-7, 1e-6])
    expect = ref.gross_slip_amplitude(forces, MU, c.moduli.normal, c.moduli.tangential,
                                      _C(profile, n), n)
    np.testing.assert_allclose(m.boundary, expect, rtol=1e-10)
    slope = np.polyfit(np.log(forces), np.log(m.boundary), 1)[0]
    assert slope == pytest.approx(n / (n + 1), rel=1e-10)


@pytest.mark.parametrize("frac", [0.05, 0.3, 0.7, 0.99])
def test_hertz_tangential_energy_mindlin(frac):
    c = contact()
    u_t = ref.gross_slip_amplitude(F, MU, c.moduli.normal, c.moduli.tangential, 50.0, 2.0)
    loop = c.fretting_loop(force=F, displacement_amplitude=frac * u_t)
    a = radius_of_force(F, 0.01, c.moduli.normal)
    W = ref.mindlin_energy_of_force_amplitude(loop.peak, F, MU, a, c.moduli.tangential)
    assert loop.energy == pytest.approx(W, rel=FRETTING_CLOSED)
    Q = ref.power_virgin_force(frac * u_t, F, MU, u_t, 2.0)
    assert loop.peak == pytest.approx(Q, rel=FRETTING_CLOSED)


@pytest.mark.parametrize("ratio", [0.5, 0.3, 1e-2, 1e-3, 1e-4])
def test_small_hertz_loops_exact_against_mindlin_deresiewicz(ratio):
    """Small loops: the energy per cycle of the fretting loop and of a Masing shift history
    against Mindlin-Deresiewicz in 50-digit arithmetic, and the small-amplitude cube law
    W = T³/(9μFaG*) (Johnson 1985 eq. 7.61)."""
    c = contact()
    E, G = c.moduli.normal, c.moduli.tangential
    u_t = ref.gross_slip_amplitude(F, MU, E, G, 50.0, 2.0)
    u0 = ratio * u_t
    W, T = ref.mindlin_loop_energy_of_displacement(u0, F, MU, E, G, 0.01)
    tol = max(SMALL_LOOP_ENERGY / ratio, SMALL_LOOP_FLOOR)      # 1e-12 at ratio 1e-3
    loop = c.fretting_loop(force=F, displacement_amplitude=u0, n_points=4)
    assert loop.energy == pytest.approx(W, rel=tol)
    h = c.shift_history(force=F, displacement=u0 * np.array([1.0, -1.0, 1.0, -1.0, 1.0]))
    per_cycle = np.diff(h.dissipated_energy[::2])
    np.testing.assert_allclose(per_cycle, W, rtol=tol)
    if ratio <= 1e-3:
        a = radius_of_force(F, 0.01, E)
        cube = T**3 / (9 * MU * F * a * G)
        assert loop.energy == pytest.approx(cube, rel=3 * ratio)   # next term O(T/μF)


def test_gross_slip_energy_linear_in_amplitude():
    # beyond u_t every spring slides: W grows by 4 μF per unit amplitude
    c = contact()
    u_t = c.fretting_loop(force=F, displacement_amplitude=1e-9).meta["gross_slip_amplitude"]
    W1 = c.fretting_loop(force=F, displacement_amplitude=2 * u_t).energy
    W2 = c.fretting_loop(force=F, displacement_amplitude=3 * u_t).energy
    assert W2 - W1 == pytest.approx(4 * MU * F * u_t, rel=FRETTING_CLOSED)
    assert W1 == pytest.approx(4 * MU * F * (2 * u_t) - 4 * MU * F * u_t * 0.8, rel=FRETTING_CLOSED)


@pytest.mark.parametrize("kw", [{"displacement_amplitude": 1.2e-6}, {"twist_amplitude": 2e-3}])
def test_loop_area_equals_energy(kw):
    c = contact()
    loop = c.fretting_loop(force=F, n_points=2000, **kw)
    area = -np.trapezoid(loop.y, loop.x) if hasattr(np, "trapezoid") else -np.trapz(loop.y, loop.x)
    assert abs(area) == pytest.approx(loop.energy, rel=LOOP_TRAPEZOID)
    assert loop.x[0] == loop.amplitude and loop.y[0] == loop.peak
    assert loop.y[len(loop.y) // 2] == pytest.approx(-loop.peak, rel=1e-14)


def test_torsion_small_amplitude_cube_law():
    c = contact()
    a = radius_of_force(F, 0.01, c.moduli.normal)
    G = c.moduli.torsional
    devs = []
    for ratio in (0.9999, 0.9998, 0.9996):
        phi0 = float(ref.hertz_twist_of_stick_ratio(ratio, F, MU, a, G))
        loop = c.fretting_loop(force=F, twist_amplitude=phi0)
        assert loop.stick_radius / a == pytest.approx(ratio, abs=1e-9)
        W0 = ref.hertz_torsion_small_energy(phi0, F, MU, a, G)
        devs.append(loop.energy / W0 - 1)
        # the same law in the torque amplitude (3 M0³/(16 μF G_t a⁴)) to leading order
        assert loop.energy == pytest.approx(3 * loop.peak**3 / (16 * MU * F * G * a**4),
                                            rel=10 * (1 - ratio))
    devs = np.array(devs)
    assert abs(devs[0]) < 1e-3 and np.all(np.sign(devs) == np.sign(devs[0]))
    # first-order approach to the law: the deviation doubles with 1 - c/a
    assert devs[1] / devs[0] == pytest.approx(2.0, rel=0.02)
    assert devs[2] / devs[1] == pytest.approx(2.0, rel=0.02)


def test_torsion_regimes_and_criteria():
    c = contact()
    a = radius_of_force(F, 0.01, c.moduli.normal)
    G = c.moduli.torsional
    phi_t = float(ref.hertz_twist_of_stick_ratio(0.1, F, MU, a, G))
    m = c.fretting_map(force=[F], twist_amplitude=[0.5 * phi_t, 2 * phi_t],
                       criterion="stick_ratio")
    assert m.boundary[0] == pytest.approx(phi_t, rel=TORSION_BOUNDARY)
    assert [m.regime_names[r] for r in m.regime[0]] == ["partial_slip", "gross_slip"]
    # energy-ratio boundary: the loop there has A = 0.2
    m2 = c.fretting_map(force=[F], twist_amplitude=[1e-4])
    loop = c.fretting_loop(force=F, twist_amplitude=float(m2.boundary[0]))
    assert loop.energy_ratio == pytest.approx(0.2, rel=TORSION_BOUNDARY_ROOT)
    m3 = c.fretting_map(force=[F], twist_amplitude=[1e-4], criterion="torque_ratio",
                        threshold=0.9)
    loop = c.fretting_loop(force=F, twist_amplitude=float(m3.boundary[0]))
    assert loop.peak / loop.sliding == pytest.approx(0.9, rel=TORSION_BOUNDARY_ROOT)
    # a stricter criterion moves the boundary to larger amplitudes
    assert m2.boundary[0] < c.fretting_map(force=[F], twist_amplitude=[1e-4],
                                           threshold=0.3).boundary[0]


def test_torsion_boundary_scales_hertz():
    # Hertz: φ_t ∝ μF/(G_t a²) ∝ F^(1/3) for a fixed criterion (self-similarity)
    c = contact()
    forces = np.geomspace(1, 1e3, 4)
    m = c.fretting_map(force=forces, twist_amplitude=[1e-4])
    slope = np.polyfit(np.log(forces), np.log(m.boundary), 1)[0]
    assert slope == pytest.approx(1 / 3, rel=TORSION_BOUNDARY_ROOT)


def test_flat_punch_tangential_sticks_then_slides():
    c = contact(cl.profiles.FlatPunch(radius=1e-4))
    d = 1e-7
    u_t = MU * c.moduli.normal * d / c.moduli.tangential
    assert c.fretting_loop(depth=d, displacement_amplitude=0.5 * u_t).regime == "stick"
    assert c.fretting_loop(depth=d, displacement_amplitude=0.5 * u_t).energy == 0.0
    onset = c.fretting_loop(depth=d, displacement_amplitude=u_t)
    assert onset.regime == "gross_slip" and onset.energy_ratio == pytest.approx(0.0, abs=1e-12)


def test_mdr_warns_on_energy_where_torque_is_fine():
    c = contact()
    a = radius_of_force(F, 0.01, c.moduli.normal)
    phi = float(ref.hertz_twist_of_stick_ratio(0.9, F, MU, a, c.moduli.torsional))
    with pytest.warns(ValidityWarning, match="energy"):
        mdr = c.fretting_loop(force=F, twist_amplitude=phi, method="mdr")
    exact = c.fretting_loop(force=F, twist_amplitude=phi)
    assert abs(mdr.energy / exact.energy - 1) > 0.01            # the warning is deserved
    assert abs(mdr.peak / exact.peak - 1) < 0.01               # the torque alone is fine
    small = float(ref.hertz_twist_of_stick_ratio(0.99, F, MU, a, c.moduli.torsional))
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        mdr = c.fretting_loop(force=F, twist_amplitude=small, method="mdr")
    exact = c.fretting_loop(force=F, twist_amplitude=small)
    assert abs(mdr.energy / exact.energy - 1) < 0.01


def test_map_outputs(tmp_path):
    c = contact()
    m = c.fretting_map(force=[10.0, 100.0, 1000.0], displacement_amplitude=[1e-7, 1e-6, 1e-5])
    assert m.regime.shape == (3, 3) and m.energy.shape == (3, 3)
    loop = c.fretting_loop(force=100.0, displacement_amplitude=1e-6)
    assert m.energy[1, 1] == loop.energy and m.energy_ratio[1, 1] == loop.energy_ratio
    p = tmp_path / "map.csv"
    m.to_csv(p)
    rows = p.read_text().splitlines()
    assert rows[0].startswith("force [N],displacement_amplitude [m],regime [1]")
    assert len(rows) == 10
    df = m.to_dataframe()
    assert set(df["regime"]) <= {"stick", "partial_slip", "gross_slip"}
    assert df.shape[0] == 9


def test_map_plot():
    pytest.importorskip("matplotlib")
    import matplotlib
    matplotlib.use("Agg")
    c = contact()
    m = c.fretting_map(force=np.geomspace(1, 100, 4), twist_amplitude=np.geomspace(1e-5, 1e-2, 5))
    ax = m.plot()
    assert ax.get_xlabel().startswith("twist amplitude")
    assert len(ax.lines) == 1
    c.fretting_loop(force=1.0, twist_amplitude=1e-3).plot()
    import matplotlib.pyplot as plt
    plt.close("all")


def test_bad_input():
    c = contact()
    with pytest.raises(ParameterError, match="displacement_amplitude="):
        c.fretting_loop(force=F)
    with pytest.raises(ParameterError, match="displacement_amplitude"):
        c.fretting_loop(force=F, displacement_amplitude=-1e-6)
    with pytest.raises(ParameterError, match="fretting_map"):
        c.fretting_loop(force=F, displacement_amplitude=[1e-6, 2e-6])
    with pytest.raises(UnknownNameError, match="criterion"):
        c.fretting_loop(force=F, twist_amplitude=1e-3, criterion="ratio")
    with pytest.raises(ParameterError, match="threshold"):
        c.fretting_loop(force=F, twist_amplitude=1e-3, threshold=1.5)
    with pytest.raises(ParameterError, match="friction"):
        cl.Contact(cl.profiles.Paraboloid(R=0.01), materials=(STEEL, STEEL)).fretting_loop(
            force=F, twist_amplitude=1e-3)
    with pytest.raises(NotSupportedError, match="adhesi"):
        cl.Contact(cl.profiles.Paraboloid(R=0.01), materials=(STEEL, STEEL), friction=0.3,
                   work_of_adhesion=0.1).fretting_loop(force=F, twist_amplitude=1e-3)
    with pytest.raises(UnknownNameError, match="method"):
        c.fretting_loop(force=F, displacement_amplitude=1e-6, method="no-slip")
    with pytest.raises(ParameterError, match="n_points"):
        c.fretting_loop(force=F, displacement_amplitude=1e-6, n_points=1)
    with pytest.raises(ParameterError, match="force"):
        c.fretting_map(force=[[1.0, 2.0]], displacement_amplitude=[1e-6])
