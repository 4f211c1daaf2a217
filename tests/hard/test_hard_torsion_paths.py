"""Hard cases of torsion and load paths that must stay numerically stable (issue 7).

Expected values are independent of contactlab: the mpmath reference ``tests/reference/
torsion_reference.py`` (theory §6.2-6.4 closed forms: Lubkin/Hertz table, flat-punch onset,
MDR narrow-slip formulas), moduli and Hertz radii re-derived here from theory §1/§3.
"""
from __future__ import annotations

import math
import warnings

import mpmath as mp
import numpy as np
import pytest

import contactlab as cl
from contactlab import LoadPath
from contactlab.errors import ValidityWarning
from contactlab.profiles import FlatPunch, Paraboloid
from tests import tolerances as TOL
from tests.reference import hertz as hz
from tests.reference import torsion_reference as tr
from tests.tolerances import FOUNDATION_TORSION, HARD_CLOSED, TORSION_EXACT, TORSION_TINY_STEP

MU = 0.3
EPS = np.finfo(float).eps
#: E* of two Elastic(E=1e9, nu=0.3) bodies (hertz_contact's default pair)
E_STAR_DEFAULT = hz.effective_modulus(1e9, 0.3, 1e9, 0.3)


def rel(x, y) -> float:
    return abs(float(x) / float(y) - 1.0)


def hertz_contact(R=0.01, m1=None, m2=None, mu=MU) -> cl.Contact:
    m1 = m1 or cl.Elastic(E=1e9, nu=0.3)
    m2 = m2 or cl.Elastic(E=1e9, nu=0.3)
    return cl.Contact(Paraboloid(R), materials=(m1, m2), friction=mu)


def hats(state, F, G_t, mu=MU):
    """φ̂ = φ G_t a²/(μF), M̂ = M/(μFa) (theory §6.3) with the state's own radius."""
    a = float(state.normal.radius)
    return state.twist * G_t * a * a / (mu * F), state.torque / (mu * F * a)


def ill_conditioning(t: float) -> float:
    """Relative change of φ and M (both ∝ k² = 1 - t² near full stick) per ulp of c: a result
    is exact for some c within 4 ulps of the returned one (backward-stable)."""
    return 8 * EPS / max(1.0 - t * t, EPS)


# ====================================================================== stick radius extremes
@pytest.mark.parametrize("t", [1 - 1e-9, 0.5, 1e-9])
def test_exact_stick_radius_extremes_vs_lubkin(t):
    """stick_radius= control at c/a = 1-1e-9, 0.5, 1e-9 against §6.3, and the twist-control round
    trip recovers the same stick radius and torque."""
    c = hertz_contact()
    F = 10.0
    G_t = 1e9 / (2 * 1.3) / 2                               # identical bodies: G/2 (§1)
    assert rel(c.moduli.torsional, G_t) < HARD_CLOSED
    a = float(hz.radius_of_force(F, 0.01, E_STAR_DEFAULT))     # Hertz [J85]
    s = c.torsion(force=F, stick_radius=t * a, method="exact")
    tt = mp.mpf(float(s.stick_radius)) / mp.mpf(a)
    ph, Mh = hats(s, F, G_t)
    tol = TORSION_EXACT + ill_conditioning(t)
    assert rel(ph, tr.hertz_twist_hat(tt)) < tol
    assert rel(Mh, tr.hertz_torque_hat(tt)) < tol
    assert not s.slip and np.isfinite(s.twist) and np.isfinite(s.torque)
    back = c.torsion(force=F, twist=s.twist, method="exact")
    assert abs(back.stick_radius - s.stick_radius) <= TORSION_EXACT * a
    assert rel(back.torque, s.torque) < TORSION_EXACT


def test_exact_torque_control_near_full_sliding_is_consistent():
    """At c/a = 1e-9 the torque differs from M_full by (4/(3π)) t³ μFa ~ 1e-27 relative: torque
    control cannot resolve c in double precision. It must return a consistent, finite state: the
    requested torque, a stick radius below the resolution (3π/4 · 4 eps M̂)^(1/3) ~ 1e-5 a, and
    a twist at least the one of c = 1e-9 a (φ grows as c shrinks)."""
    c = hertz_contact()
    F = 10.0
    a = float(hz.radius_of_force(F, 0.01, E_STAR_DEFAULT))     # Hertz [J85]
    s = c.torsion(force=F, stick_radius=1e-9 * a, method="exact")
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        back = c.torsion(force=F, torque=s.torque, method="exact")
    # a torque that rounds onto the full-sliding torque: unbounded twist, said by a warning
    said = [w for w in caught if issubclass(w.category, ValidityWarning)
            and "full-sliding torque" in str(w.message)]
    assert bool(said) == (back.twist == np.inf)
    assert back.torque == s.torque
    resolution = (3 * math.pi / 4 * 4 * EPS * 3 * math.pi / 16) ** (1 / 3)
    assert back.stick_radius <= resolution * a
    assert back.twist >= s.twist * (1 - TORSION_EXACT) or back.slip
    # full sliding: M = 3π/16 μFa exactly (§6.3), twist unbounded
    full = c.torsion(force=F, stick_radius=0.0, method="exact")
    assert rel(full.torque / (MU * F * a), 3 * math.pi / 16) < HARD_CLOSED
    assert full.slip and full.twist == np.inf


@pytest.mark.parametrize("t", [1 - 1e-9, 0.9])
def test_mdr_stick_radius_near_full_stick_vs_closed_form(t):
    """MDR §6.4: φ̂ = 3(1-t²)/(16t), M̂ = (3/4)(1-t²)(1+t²/3); round trip through twist and torque."""
    c = hertz_contact()
    F = 10.0
    G_t = c.moduli.torsional
    a = float(hz.radius_of_force(F, 0.01, E_STAR_DEFAULT))     # Hertz [J85]
    s = c.torsion(force=F, stick_radius=t * a, method="mdr")
    tt = mp.mpf(float(s.stick_radius)) / mp.mpf(a)
    ph_ref, M_ref = tr.hertz_mdr_hat(tt)
    ph, Mh = hats(s, F, G_t)
    tol = TORSION_EXACT + ill_conditioning(t)
    assert rel(ph, ph_ref) < tol and rel(Mh, M_ref) < tol
    for kw in ({"twist": s.twist}, {"torque": s.torque}):
        back = c.torsion(force=F, method="mdr", **kw)
        assert abs(back.stick_radius - s.stick_radius) <= TORSION_EXACT * a
        assert rel(back.torque, s.torque) < TORSION_EXACT and rel(back.twist, s.twist) < tol


def test_mdr_stick_radius_near_full_sliding_warns_and_matches():
    """c/a = 1e-9 in the MDR model: the documented ValidityWarning, and φ̂ = 3/(16t) (1-t²) ≈ 1.9e8
    and M̂ → 3/4 (§6.4) without overflow."""
    c = hertz_contact()
    F = 10.0
    a = float(hz.radius_of_force(F, 0.01, E_STAR_DEFAULT))     # Hertz [J85]
    with pytest.warns(ValidityWarning, match="outside its validity"):
        s = c.torsion(force=F, stick_radius=1e-9 * a, method="mdr")
    tt = mp.mpf(float(s.stick_radius)) / mp.mpf(a)
    ph_ref, M_ref = tr.hertz_mdr_hat(tt)
    ph, Mh = hats(s, F, c.moduli.torsional)
    assert rel(ph, ph_ref) < TORSION_EXACT and rel(Mh, M_ref) < TORSION_EXACT
    with pytest.warns(ValidityWarning):
        back = c.torsion(force=F, twist=s.twist, method="mdr")
    assert rel(back.stick_radius, s.stick_radius) < TORSION_EXACT
    with pytest.warns(ValidityWarning):
        full = c.torsion(force=F, stick_radius=0.0, method="mdr")
    assert rel(full.torque / (MU * F * a), 0.75) < HARD_CLOSED       # 4/π × exact (§6.4)
    assert rel(full.sliding_torque / c.torsion(force=F, stick_radius=0.0).sliding_torque,
               4 / math.pi) < HARD_CLOSED


# ====================================================================== sliding limit
def flat_contact():
    b = 1e-3
    c = cl.Contact(FlatPunch(b), materials=(cl.Elastic(E=1e9, nu=0.3), cl.Rigid()), friction=MU)
    E_star = 1e9 / (1 - 0.09)
    G_t = 1e9 / 2.6
    return c, b, E_star, G_t


def test_flat_punch_exactly_at_no_slip_limit():
    """§6.2.7: no slip up to φ_0 = μE*d/(4G_t a) with M_0 = (4/3)μE*da². Exactly at φ_0 (and one
    ulp either side) c = a, M = M_0; stick_radius=a and torque=M_0 give back φ_0."""
    c, b, E_star, G_t = flat_contact()
    d = 1e-6
    phi0, M0 = (float(v) for v in tr.flat_onset(E_star, d, b, MU, G_t))
    for phi in (phi0, np.nextafter(phi0, 0), np.nextafter(phi0, 1)):
        s = c.torsion(depth=d, twist=phi)
        assert rel(s.stick_radius, b) < HARD_CLOSED
        assert rel(s.torque, M0 * phi / phi0) < HARD_CLOSED and not s.slip
    assert rel(c.torsion(depth=d, torque=M0).twist, phi0) < HARD_CLOSED
    s = c.torsion(depth=d, stick_radius=b)
    assert rel(s.twist, phi0) < HARD_CLOSED and rel(s.torque, M0) < HARD_CLOSED


@pytest.mark.parametrize("t", [1 - 1e-6, 0.5, 1e-6])
def test_flat_punch_beyond_limit_vs_elliptic(t):
    """φ = μE*d/(2πG_t a) K(k_c), k_c² = 1 - t² (§6.2.7) from just beyond φ_0 to near sliding."""
    c, b, E_star, G_t = flat_contact()
    d = 1e-6
    phi = float(tr.flat_twist(t, E_star, d, b, MU, G_t))
    s = c.torsion(depth=d, twist=phi)
    # K(k) is flat near k = 0: dK/K = k²/4 ... so c is ill-conditioned there, check φ(c) instead
    tt = mp.mpf(float(s.stick_radius)) / b
    assert rel(phi, tr.flat_twist(tt, E_star, d, b, MU, G_t)) < TORSION_EXACT
    if t < 0.9:
        assert rel(s.stick_radius, t * b) < TORSION_EXACT


def test_full_sliding_torque_exact_and_mdr_limits():
    """Twist far beyond the sliding limit: exact → 3π/16 μFa, MDR → 3/4 μFa (ratio 4/π, §6.4)."""
    c = hertz_contact()
    F = 10.0
    a = float(hz.radius_of_force(F, 0.01, E_STAR_DEFAULT))     # Hertz [J85]
    ex = c.torsion(force=F, twist=1e6)
    assert rel(ex.torque / (MU * F * a), 3 * math.pi / 16) < HARD_CLOSED and ex.slip
    with pytest.warns(ValidityWarning):
        md = c.torsion(force=F, twist=1e6, method="mdr")
    t = float(md.stick_radius) / a          # MDR: t ≈ 1/β, §6.4
    assert rel(md.torque / (MU * F * a), float(tr.hertz_mdr_hat(t)[1])) < HARD_CLOSED
    for m in ("exact", "mdr"):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", ValidityWarning)
            Mf = c.torsion(force=F, stick_radius=0.0, method=m).torque
            s = c.torsion(force=F, torque=Mf, method=m)
        assert s.slip and s.twist == np.inf and s.stick_radius == 0.0


# ====================================================================== extreme scales
SCALES = {
    "R=1nm, E=1TPa": (1e-9, (cl.Elastic(E=1e12, nu=0.3), cl.Elastic(E=1e12, nu=0.3))),
    "R=10m, E=1kPa": (10.0, (cl.Elastic(E=1e3, nu=0.3), cl.Elastic(E=1e3, nu=0.3))),
    "nu=0.5 on rigid": (0.01, (cl.Elastic(E=1e6, nu=0.5), cl.Rigid())),
    "rigid first": (0.01, (cl.Rigid(), cl.Elastic(E=2e11, nu=0.29))),
    "moduli ratio 1e6": (0.01, (cl.Elastic(E=2e11, nu=0.3), cl.Elastic(E=2e5, nu=0.45))),
}


def moduli_by_hand(mats):
    """theory §1: 1/E* = Σ(1-ν²)/E, 1/G_t = Σ 1/G (rigid: 0)."""
    inv_e = sum((1 - m.nu**2) / m.E for m in mats if isinstance(m, cl.Elastic))
    inv_g = sum(2 * (1 + m.nu) / m.E for m in mats if isinstance(m, cl.Elastic))
    return 1 / inv_e, 1 / inv_g


@pytest.mark.parametrize("name", list(SCALES))
@pytest.mark.parametrize("method", ["exact", "mdr"])
def test_extreme_scales_match_dimensionless_table(name, method):
    """Dimensionless φ̂, M̂ at c/a = 0.99, 0.9 (and 0.5 exact) match §6.3 for every scale and
    material pair; the twist round trip returns the stick radius."""
    R, mats = SCALES[name]
    E_star, G_t = moduli_by_hand(mats)
    c = cl.Contact(Paraboloid(R), materials=mats, friction=MU)
    assert rel(c.moduli.normal, E_star) < HARD_CLOSED
    assert rel(c.moduli.torsional, G_t) < HARD_CLOSED
    d = 1e-3 * R                                        # a = sqrt(R d), F = (4/3)E* a³/R (§3)
    a = math.sqrt(R * d)
    F = 4 / 3 * E_star * a**3 / R
    ts = [0.99, 0.9] + ([0.5] if method == "exact" else [])
    s = c.torsion(depth=d, stick_radius=np.array(ts) * a, method=method)
    assert rel(s.normal.radius, a) < HARD_CLOSED and rel(s.normal.force, F) < HARD_CLOSED
    ph = s.twist * G_t * a * a / (MU * F)
    Mh = s.torque / (MU * F * a)
    for i, t in enumerate(ts):
        if method == "exact":
            ref = (tr.hertz_twist_hat(t), tr.hertz_torque_hat(t))
        else:
            ref = tr.hertz_mdr_hat(t)
        assert rel(ph[i], ref[0]) < TORSION_EXACT and rel(Mh[i], ref[1]) < TORSION_EXACT
    back = c.torsion(depth=d, twist=s.twist, method=method)
    np.testing.assert_allclose(back.stick_radius, np.array(ts) * a, rtol=TORSION_EXACT)
    assert np.all(np.isfinite(back.torque))


# ====================================================================== long and tiny load paths
def mdr_hertz_torque(phi, F, a, G_t, mu=MU):
    """Virgin MDR torque (§6.4): β = 16G_t a²φ/(3μF), t = sqrt(1+β²/4) - β/2."""
    beta = 16 * G_t * a * a * np.abs(phi) / (3 * mu * F)
    t = np.sqrt(1 + beta**2 / 4) - beta / 2
    return np.sign(phi) * 0.75 * mu * F * a * (1 - t * t) * (1 + t * t / 3)


def test_million_step_oscillating_twist_simulate():
    """10^6 steps of ±φ_0 twist at constant force through contact.simulate: finite, the torque at
    the last peak and trough is the Masing value of the MDR closed form (§6.4/6.5), energy per
    cycle is constant (periodic Jenkins states) and the loop closes. ~1.2 s with N = 2000."""
    c = hertz_contact()
    F = 10.0
    a = float(hz.radius_of_force(F, 0.01, E_STAR_DEFAULT))     # Hertz [J85]
    G_t = c.moduli.torsional
    phi0 = float(tr.hertz_mdr_hat(0.95)[0]) * MU * F / (G_t * a * a)
    cycles, spc = 1000, 1000
    path = LoadPath().ramp(force=F, steps=4).sinusoid(twist=phi0, cycles=cycles,
                                                      steps_per_cycle=spc)
    # exact c/a ≈ 0.95 < 0.97: the MDR energy per cycle errs by more than 1 % (warned)
    with pytest.warns(ValidityWarning, match="dissipated energy: outside"):
        r = c.simulate(path, method="mdr")
    assert r.torque.shape == (4 + cycles * spc,)
    for arr in (r.torque, r.stick_radius, r.dissipated_energy, r.twist):
        assert np.all(np.isfinite(arr))
    M0 = mdr_hertz_torque(phi0, F, a, G_t)
    peak = 4 + (cycles - 1) * spc + spc // 4 - 1           # last maximum (sin = 1)
    trough = peak + spc // 2
    assert abs(r.twist[peak] - phi0) < TOL.ULPS * phi0
    assert abs(r.torque[peak] - M0) < FOUNDATION_TORSION * M0
    assert abs(r.torque[trough] + M0) < FOUNDATION_TORSION * M0
    ends = 4 + np.arange(1, cycles + 1) * spc - 1
    per_cycle = np.diff(r.dissipated_energy[ends])
    assert np.all(np.abs(per_cycle / per_cycle[0] - 1) < TOL.ENERGY_PER_CYCLE)
    assert abs(r.torque[ends[-1]] - r.torque[ends[-2]]) < TOL.EXACT_ROUTES * M0


def tiny_step_path(F, phi1, n_tiny, delta):
    """Force ramp, twist ramp to φ1, then n_tiny steps of +delta, n_tiny of -delta, n_tiny of +delta."""
    steps = np.concatenate([np.full(n_tiny, delta), np.full(n_tiny, -delta),
                            np.full(n_tiny, delta)])
    twist = np.concatenate([[0.0, 0.0, 0.5 * phi1, phi1], phi1 + np.cumsum(steps)])
    force = np.concatenate([[0.5 * F], np.full(twist.size - 1, F)])
    return LoadPath.from_arrays(force=force, twist=twist), twist


@pytest.mark.parametrize("rel_step", [1e-13, 1e-15])
def test_steps_below_1e12_of_amplitude_simulate(rel_step):
    """Twist steps of 1e-13 and 1e-15 of the amplitude: no NaN, torque increments equal the
    incremental stiffness of the springs stuck at that moment (forward: stick zone 16G_t∫_0^c x²,
    §6.4; after the reversal every spring sticks: (16/3)G_t a³) to rounding of M, no drift after
    returning, and no dissipation during the tiny steps after the reversal."""
    c = hertz_contact()
    F = 10.0
    a = float(hz.radius_of_force(F, 0.01, E_STAR_DEFAULT))     # Hertz [J85]
    G_t = c.moduli.torsional
    phi1 = float(tr.hertz_mdr_hat(0.9)[0]) * MU * F / (G_t * a * a)
    n = 50
    delta = rel_step * phi1
    path, twist = tiny_step_path(F, phi1, n, delta)
    # exact c/a ≈ 0.9 < 0.97: the MDR energy per cycle errs by more than 1 % (warned)
    with pytest.warns(ValidityWarning, match="dissipated energy: outside"):
        r = c.simulate(path, method="mdr")
    assert np.all(np.isfinite(r.torque)) and np.all(np.isfinite(r.dissipated_energy))
    M1 = r.torque[3]
    assert abs(M1 - mdr_hertz_torque(phi1, F, a, G_t)) < FOUNDATION_TORSION * M1
    dphi = np.diff(r.twist[3:])
    dM = np.diff(r.torque[3:])
    k_full = 16 / 3 * G_t * a**3
    back = slice(n, 2 * n)                                  # after the reversal: all stuck
    noise = TORSION_TINY_STEP * abs(M1)                     # rounding of the torque sum
    assert np.all(np.abs(dM[back] - k_full * dphi[back]) <= 1e-6 * k_full * abs(delta) + noise)
    # forward steps: stiffness between stick-zone (16/3)G_t c³ and full stick
    c1 = 0.9 * a                                           # MDR stick radius at φ1
    k_stick = 16 / 3 * G_t * c1**3
    fwd = dM[:n] / delta                 # the cell holding c is lumped: ~0.3 % at N = 2000
    assert np.all(np.abs(fwd - k_stick) <= 1e-2 * k_stick + noise / delta)
    # back at φ1 + n δ after down-and-up: same torque (elastic inner loop), no drift
    assert abs(r.torque[3 + n] - r.torque[3 + 3 * n]) <= 2 * noise + 1e-6 * k_full * n * delta
    assert np.all(np.abs(np.diff(r.dissipated_energy[3 + n:])) <= TORSION_TINY_STEP
                  * abs(r.dissipated_energy[3 + n]) + 1e-30)


@pytest.mark.parametrize("method", ["exact", "mdr"])
# c/a = 0.9: the MDR torque is valid, its dissipated energy (2.4 % off) is not and says so
@pytest.mark.filterwarnings("ignore:MDR torsion model. the dissipated energy"
                            ":contactlab.errors.ValidityWarning")
def test_tiny_steps_twist_history(method):
    """twist_history with steps of 1e-13 of the amplitude after a reversal: Masing branch starts
    with the full-stick stiffness (16/3)G_t a³ (§6.5), increments match it to the rounding of M."""
    c = hertz_contact()
    F = 10.0
    a = float(hz.radius_of_force(F, 0.01, E_STAR_DEFAULT))     # Hertz [J85]
    G_t = c.moduli.torsional
    phi1 = float(tr.hertz_twist_hat(0.9)) * MU * F / (G_t * a * a)
    delta = 1e-13 * phi1
    tw = np.concatenate([[0.0, phi1], phi1 - delta * np.arange(1, 41),
                         phi1 - 40 * delta + delta * np.arange(1, 41)])
    h = c.twist_history(force=F, twist=tw, method=method)
    assert np.all(np.isfinite(h.torque)) and np.all(np.isfinite(h.dissipated_energy))
    k_full = 16 / 3 * G_t * a**3
    dM = np.diff(h.torque[1:])
    dphi = np.diff(tw[1:])
    noise = TORSION_TINY_STEP * abs(h.torque[1])
    assert np.all(np.abs(dM - k_full * dphi) <= 1e-6 * k_full * delta + noise)
    assert abs(h.torque[-1] - h.torque[1]) <= noise            # back at φ1: Masing closure
    assert abs(h.dissipated_energy[-1] - h.dissipated_energy[1]) <= noise * delta + \
        TORSION_TINY_STEP * h.dissipated_energy[1]
