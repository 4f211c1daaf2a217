"""Fretting wear (issue 15) against closed forms derived in docs/fretting.md."""
from __future__ import annotations

import warnings

import numpy as np
import pytest

import contactlab as cl
from contactlab.errors import NotSupportedError, ParameterError
from tests.reference import fretting as ref
from tests.tolerances import (WEAR_ENERGY_IDENTITY, WEAR_GRID_ENERGY, WEAR_LIMIT_DEPTH,
                              WEAR_LIMIT_VOLUME, WEAR_MODES_SAME_LIMIT,
                              WEAR_MODES_SAME_LIMIT_VOLUME, WEAR_SAME_STICK, WEAR_SCAR_ASYMPTOTE,
                              WEAR_TORSION_SCAR_GRID)

STEEL = cl.Elastic(E=210e9, nu=0.3)
MU, F, R = 0.5, 100.0, 0.01


def contact(profile=None):
    return cl.Contact(profile or cl.profiles.Paraboloid(R=R), materials=(STEEL, STEEL),
                      friction=MU)


CASES = [
    ("hertz shift partial", None, {"displacement_amplitude": 1e-6}),
    ("hertz shift gross", None, {"displacement_amplitude": 5e-6}),
    ("hertz twist exact", None, {"twist_amplitude": 1e-2}),
    ("hertz twist mdr", None, {"twist_amplitude": 1e-3, "method": "mdr"}),
    ("cone twist", cl.profiles.Cone(slope=0.02), {"twist_amplitude": 1e-2}),
    ("n4 shift", cl.profiles.PowerLaw(c=1e12, n=4), {"displacement_amplitude": 1e-6}),
]


@pytest.mark.parametrize("name,profile,kw", CASES, ids=[c[0] for c in CASES])
def test_wear_energy_identity(name, profile, kw):
    c = contact(profile)
    k = 1e-14
    with warnings.catch_warnings():      # MDR / coarse-grid validity: the identity holds anyway
        warnings.simplefilter("ignore", cl.errors.ValidityWarning)
        w = c.wear(force=F, wear_coefficient=k, cycles=1e5, n_grid=120, checkpoints=3, **kw)
    V_table = ref.linear_table_volume(w.r, w.wear_depth[-1])
    assert w.dissipated_energy[-1] > 0
    assert V_table == pytest.approx(k / MU * w.dissipated_energy[-1], rel=WEAR_ENERGY_IDENTITY)
    assert w.volume[-1] == pytest.approx(V_table, rel=WEAR_ENERGY_IDENTITY)
    # the stored table is the unworn profile plus the wear depth (up to its datum)
    f0 = c.profile.height(w.r)
    shift = w.profile.height(w.r) - (f0 + w.wear_depth[-1])
    assert np.ptp(shift) < 1e-9 * np.max(f0)


@pytest.mark.parametrize("kw,ratio", [({"displacement_amplitude": 1e-6}, None),
                                      ({"displacement_amplitude": 5e-6}, None),
                                      ({"twist_amplitude": 1e-2}, None)])
def test_zero_wear_reproduces_loops(kw, ratio):
    c = contact()
    w = c.wear(force=F, wear_coefficient=0.0, cycles=1e6, n_grid=200, **kw)
    loop = c.fretting_loop(force=F, **kw)
    assert np.all(w.wear_depth == 0) and w.meta["steps"] == 1
    assert w.energy_per_cycle[-1] == pytest.approx(loop.energy, rel=WEAR_GRID_ENERGY)
    assert w.dissipated_energy[-1] == pytest.approx(1e6 * w.energy_per_cycle[0], rel=1e-14)
    assert w.radius[0] == pytest.approx(loop.radius, rel=WEAR_GRID_ENERGY)


@pytest.mark.parametrize("kw", [{"displacement_amplitude": 1e-6}, {"twist_amplitude": 3e-3}],
                         ids=["shift", "twist"])
def test_partial_slip_limiting_state(kw):
    c = contact()
    w = c.wear(force=F, wear_coefficient=1e-13, cycles=1e8, n_grid=200, max_radius=4e-4, **kw)
    c_end = w.stick_radius[-1]
    d_inf, a_inf, V_inf, _ = ref.hertz_limiting_state(c_end, F, c.moduli.normal, R)
    assert w.energy_per_cycle[-1] < 1e-9 * w.energy_per_cycle[0]     # wear has stopped
    assert w.depth[-1] == pytest.approx(d_inf, rel=WEAR_LIMIT_DEPTH)
    assert w.scar_radius[-1] == pytest.approx(a_inf, rel=WEAR_LIMIT_DEPTH)
    assert w.volume[-1] == pytest.approx(V_inf, rel=WEAR_LIMIT_VOLUME)
    # the stick radius drifts outward by about 1 % while the annulus wears (docs/fretting.md)
    drift = c_end / w.stick_radius[0] - 1
    assert 0 <= drift < 0.02


@pytest.mark.slow
def test_tangential_gross_slip_scar_asymptote():
    c = contact()
    delta, k = 50e-6, 1e-15
    w = c.wear(force=F, wear_coefficient=k, cycles=1e6, n_grid=200, displacement_amplitude=delta)
    asym = ref.hertz_gross_slip_scar(k, R, F, delta, w.cycles[-1])
    assert w.scar_radius[-1] == pytest.approx(asym, rel=WEAR_SCAR_ASYMPTOTE)
    i = np.searchsorted(w.cycles, 1e4)
    assert w.scar_radius[i] / ref.hertz_gross_slip_scar(k, R, F, delta, w.cycles[i]) > 1.05


def test_torsional_gross_slip_scar_law_with_its_pillar_and_validity():
    """Large twist: the scar follows (6kRFφN/π)^(1/3) inside the bracket of its two leading
    corrections, the elastic excess (a0/a)³ above and the unworn pillar's load share below
    (docs/fretting.md section 6), until the proud pillar makes the MDR profile dip; wear() says
    when."""
    c = contact()
    phi, k = 0.2, 1e-15
    E = c.moduli.normal
    with pytest.warns(cl.errors.ValidityWarning, match="left the MDR"):
        w = c.wear(force=F, wear_coefficient=k, cycles=8e5, twist_amplitude=phi, n_grid=150,
                   max_radius=0.9e-3, checkpoints=[3e4, 1e5, 3e5])
    N_valid = w.meta["mdr_valid_cycles"]
    assert 3e5 < N_valid < 8e5 and w.meta["tensile_fraction"] > 1e-2
    a0 = w.radius[0]
    assert a0 == pytest.approx((3 * F * R / (4 * E)) ** (1 / 3), rel=WEAR_GRID_ENERGY)
    ok = (w.cycles >= 3e4) & (w.cycles <= N_valid)
    N, a = w.cycles[ok], w.scar_radius[ok]
    law = ref.hertz_torsion_gross_slip_scar(k, R, F, phi, N)
    b = np.max(w.stick_radius[w.cycles <= N_valid])            # the pillar is the stick zone
    psi = ref.pillar_load_share(b, a, a0, E, R, F)
    upper = 1 + (a0 / a) ** 3
    lower = (1 - psi) ** (1 / 3)
    assert np.all(a / law <= upper + WEAR_TORSION_SCAR_GRID), (N, a / law, upper)
    assert np.all(a / law >= lower - WEAR_TORSION_SCAR_GRID), (N, a / law, lower)
    # at 3e5 cycles the corrections (+5.5 %, -9 % here) largely cancel: the law itself holds to
    # 3 % (measured 1.2-1.8 % over grid cells of 6, 3, 1.5 µm)
    i = np.flatnonzero(N == 3e5)[0]
    assert upper[i] - 1 < 0.06 and 1 - lower[i] < 0.1
    assert abs(a[i] / law[i] - 1) < 0.03
    # the stick zone survives the whole run (never wears): an island at every twist
    assert np.all(w.stick_radius > 0)
    # pure sliding bound: no point slides more than 4φr per cycle, so dV/dN <= 4kφF a(N)
    dV = np.diff(w.volume) / np.diff(w.cycles)
    assert np.all(dV <= 4 * k * phi * F * w.radius[1:] * (1 + 1e-9))


def test_convergence_under_halving():
    c = contact()
    kw = dict(force=F, wear_coefficient=1e-14, cycles=1e5, displacement_amplitude=1e-6,
              max_radius=4e-4)
    base = c.wear(n_grid=100, jump_rtol=2e-4, **kw)
    half_jump = c.wear(n_grid=100, jump_rtol=1e-4, **kw)
    half_grid = c.wear(n_grid=200, jump_rtol=2e-4, **kw)
    dj = abs(half_jump.volume[-1] / base.volume[-1] - 1)
    dg = abs(half_grid.volume[-1] / base.volume[-1] - 1)
    # measured (docs/fretting.md): jump 1e-4 relative, grid 4e-2 relative at 100 -> 200 intervals
    assert dj < 1e-3
    assert dg < 0.1


def test_mdr_twist_warns_and_differs():
    c = contact()
    with pytest.warns(cl.errors.ValidityWarning, match="worn volume"):
        mdr = c.wear(force=F, wear_coefficient=1e-14, cycles=1e4, twist_amplitude=1e-2,
                     method="mdr", n_grid=120)
    exact = c.wear(force=F, wear_coefficient=1e-14, cycles=1e4, twist_amplitude=1e-2,
                   n_grid=120)
    assert abs(mdr.volume[-1] / exact.volume[-1] - 1) > 0.01


def test_bad_input():
    c = contact()
    with pytest.raises(ParameterError, match="wear_coefficient"):
        c.wear(force=F, wear_coefficient=-1.0, cycles=10, displacement_amplitude=1e-6)
    with pytest.raises(ParameterError, match="cycles"):
        c.wear(force=F, wear_coefficient=1e-15, cycles=0, displacement_amplitude=1e-6)
    with pytest.raises(ParameterError, match="n_grid"):
        c.wear(force=F, wear_coefficient=1e-15, cycles=10, displacement_amplitude=1e-6, n_grid=3)
    with pytest.raises(ParameterError, match="checkpoints"):
        c.wear(force=F, wear_coefficient=1e-15, cycles=10, displacement_amplitude=1e-6,
               checkpoints=[20])
    with pytest.raises(NotSupportedError, match="wall"):
        contact(cl.profiles.FlatPunch(radius=1e-4)).wear(
            force=F, wear_coefficient=1e-15, cycles=10, displacement_amplitude=1e-6)
    with pytest.raises(ParameterError, match="force"):
        c.wear(force=-1.0, wear_coefficient=1e-15, cycles=10, displacement_amplitude=1e-6)


def test_outputs(tmp_path):
    pytest.importorskip("matplotlib")
    import matplotlib
    matplotlib.use("Agg")
    c = contact()
    w = c.wear(force=F, wear_coefficient=1e-14, cycles=1e4, displacement_amplitude=1e-6,
               checkpoints=3, n_grid=150)
    assert len(w.profiles) == len(w.checkpoints) == 4
    assert isinstance(w.profile, cl.profiles.Tabulated)
    w.to_csv(tmp_path / "w.csv")
    assert (tmp_path / "w.csv").read_text().startswith("cycles [1],depth [m]")
    assert w.to_dataframe().shape[0] == w.cycles.size
    w.plot()
    import matplotlib.pyplot as plt
    plt.close("all")


def test_tangential_and_torsional_limits_agree_at_the_same_permanent_stick_radius():
    """Dmitriev et al. (2016): the limiting worn shape depends only on the permanent stick radius
    and the depth (here: the force). A shift run and a twist run whose amplitude is tuned (secant
    on the twist) so that their final stick radii agree end in the same worn profile, compared
    with each other, not with the closed form. With equal *fresh* stick radii they do not: the
    stick radius drifts by +0.6 % under the shift and +2 % under the twist (docs/fretting.md)."""
    c = contact()
    kw = dict(force=F, wear_coefficient=1e-13, cycles=1e8, n_grid=200, max_radius=4e-4)
    shift = c.wear(displacement_amplitude=1e-6, **kw)
    target = shift.stick_radius[-1]
    a = float(c.normal(force=F).radius)
    s0 = shift.stick_radius[0] / a

    def final_c(phi):
        return c.wear(twist_amplitude=phi, **kw)

    # same fresh stick radius (Lubkin closed form): the final stick radii differ by the drift
    p0 = float(ref.hertz_twist_of_stick_ratio(s0, F, MU, a, c.moduli.torsional))
    w0 = final_c(p0)
    assert w0.stick_radius[0] == pytest.approx(shift.stick_radius[0], rel=WEAR_GRID_ENERGY)
    assert w0.stick_radius[-1] / target - 1 > 0.005
    p1 = float(ref.hertz_twist_of_stick_ratio(s0 * target / w0.stick_radius[-1], F, MU, a,
                                              c.moduli.torsional))
    w1 = final_c(p1)
    for _ in range(6):                       # secant on the twist amplitude
        if abs(w1.stick_radius[-1] / target - 1) < WEAR_SAME_STICK:
            break
        p0, w0, p1 = p1, w1, p1 + (target - w1.stick_radius[-1]) * (p1 - p0) / (
            w1.stick_radius[-1] - w0.stick_radius[-1])
        w1 = final_c(p1)
    assert abs(w1.stick_radius[-1] / target - 1) < WEAR_SAME_STICK
    assert w1.energy_per_cycle[-1] == 0 == shift.energy_per_cycle[-1]       # both have stopped
    assert w1.depth[-1] == pytest.approx(shift.depth[-1], rel=WEAR_MODES_SAME_LIMIT)
    assert w1.scar_radius[-1] == pytest.approx(shift.scar_radius[-1], rel=WEAR_MODES_SAME_LIMIT)
    assert w1.max_wear_depth[-1] == pytest.approx(shift.max_wear_depth[-1],
                                                  rel=WEAR_MODES_SAME_LIMIT)
    assert w1.volume[-1] == pytest.approx(shift.volume[-1], rel=WEAR_MODES_SAME_LIMIT_VOLUME)
    dh = np.abs(w1.wear_depth[-1] - shift.wear_depth[-1])
    away = np.abs(shift.r - target) > 3 * (shift.r[1] - shift.r[0])   # the stick edge's cells
    assert np.max(dh[away]) <= WEAR_MODES_SAME_LIMIT_VOLUME * shift.max_wear_depth[-1]
