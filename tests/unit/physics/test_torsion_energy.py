"""Energy of a step of the exact torsion solver (physics.torsion_energy, physics.torsion_annulus
.stored_energy): the elastic energy ``8 G_t ∫ x² Ψ² dx`` with gaps between the pieces, the
balance of work, elastic energy and dissipation, the work as ``∫ M dφ`` along the step's family
of states, and the booking of a shrinking contact (no work at held twist, continuous)."""
from __future__ import annotations

import itertools

import numpy as np
import pytest
from scipy.integrate import quad

from contactlab.physics import torsion_annulus as ta
from contactlab.physics import torsion_energy as te
from tests.tolerances import ENERGY_BALANCE, ENERGY_STEP_ROUNDING

G = 3.0e10
#: closed-form pieces against scipy quad of an independent Ψ (quad's own tolerance)
QUAD = 1e-10
#: the family's ∫ M dφ by the trapezoid rule over 4000 of its states (O(h²), measured 2e-9)
FAMILY_TRAPEZOID = 1e-7


def pieces(spec):
    """Pieces from (lo, hi, wl, wr) rows."""
    a = np.asarray(spec, float)
    return a[:, 0].copy(), a[:, 1].copy(), a[:, 2].copy(), a[:, 3].copy()


def psi_ref(spec, x):
    """Ψ(x) = ∫_x^∞ w dt of linear pieces, by hand (independent of the package)."""
    out = 0.0
    for lo, hi, wl, wr in spec:
        t0 = min(max(x, lo), hi)
        s = (wr - wl) / (hi - lo)
        # ∫_{t0}^{hi} (wl + s (t − lo)) dt
        out += wl * (hi - t0) + 0.5 * s * ((hi - lo) ** 2 - (t0 - lo) ** 2)
    return out


def energy_ref(spec):
    ends = sorted({0.0, *(p[0] for p in spec), *(p[1] for p in spec)})
    return 8 * G * sum(quad(lambda x: x * x * psi_ref(spec, x) ** 2, u, v,
                            epsabs=0, epsrel=1e-12)[0] for u, v in itertools.pairwise(ends))


GAPPED = [(0.0, 1e-4, 1.0, 0.5), (1e-4, 2e-4, 0.5, 0.2), (3e-4, 4e-4, 2.0, 1.0),
          (6e-4, 7e-4, -0.5, 0.3)]


def test_stored_energy_integrates_the_gaps_between_pieces():
    """Ψ is constant on a gap (the density of a stick radius beyond an old contact radius):
    its energy there was dropped (issue 26 item 1, 354× the dissipation of a step)."""
    ref = energy_ref(GAPPED)
    assert ta.stored_energy(pieces(GAPPED), G) == pytest.approx(ref, rel=QUAD)
    assert te.energy(pieces(GAPPED), G) == pytest.approx(ref, rel=QUAD)


def random_density(rng, n, top):
    ends = np.sort(rng.uniform(0, top, 2 * n))
    lo, hi = ends[0::2], ends[1::2]
    return lo, hi, rng.normal(size=n), rng.normal(size=n)


@pytest.mark.parametrize("seed", range(5))
def test_step_energy_balances_and_dissipation_is_the_slip_integral(seed):
    """work = E_n − E_o + D for any two densities; D against 16 G_t ∫ x² Ψ_n (Δφ − ΔΨ) dx by
    quad of the hand-written Ψ (Δφ = ΔΨ(0) + a gross turn)."""
    rng = np.random.default_rng(seed)
    old, new = random_density(rng, 4, 1e-3), random_density(rng, 5, 1.2e-3)
    gross = float(rng.normal()) * 1e-9
    out = te.step_energy(old, new, G, gross)
    scale = max(abs(out["work"]), out["stored"], out["stored_old"])
    assert abs(out["work"] - out["stored"] + out["stored_old"] - out["dissipated"]) \
        <= ENERGY_BALANCE * scale
    so, sn = list(zip(*old)), list(zip(*new))
    ends = sorted({0.0, *old[0], *old[1], *new[0], *new[1]})
    dphi = psi_ref(sn, 0.0) - psi_ref(so, 0.0) + gross
    D = 16 * G * sum(quad(lambda x: x * x * psi_ref(sn, x) * (dphi - psi_ref(sn, x)
                                                            + psi_ref(so, x)),
                          u, v, epsabs=0, epsrel=1e-12)[0] for u, v in itertools.pairwise(ends))
    assert out["dissipated"] == pytest.approx(D, rel=QUAD, abs=QUAD * scale)
    assert out["stored"] == pytest.approx(energy_ref(sn), rel=QUAD)


def hertz_slide(a, n=40):
    """A full-sliding density of a paraboloid: W ∝ −P'(t) ∝ t sqrt(a² − t²)-like, here
    piecewise linear on n rings (any positive density serves the identities)."""
    b = np.linspace(0, a, n + 1)
    v = b * np.sqrt(np.maximum(a * a - b * b, 0.0)) / a ** 2 * 1e3
    return ta.from_nodes(b, v[:-1], v[1:])


def test_family_work_is_the_integral_of_torque_over_twist():
    """The work of an annulus step equals ∫ M dφ along its family w(c') = splice(w_o, s W, c'),
    c' from the contact edge to c (trapezoid over 4000 states), and its D is >= 0."""
    a0, a = 0.6e-4, 1e-4
    old = hertz_slide(a0, 17)
    slide = hertz_slide(a)
    out = ta.step(old, slide, a, G, dphi=2e-3)
    c = out["c"]
    assert a0 < c < a or 0 < c < a0
    cs = np.linspace(a, c, 4001)
    M = np.array([ta.torque(ta.splice(old, slide, x), G) for x in cs])
    phi = np.array([ta.psi(ta.splice(old, slide, x), np.zeros(1))[0] for x in cs])
    W = float(np.sum(0.5 * (M[1:] + M[:-1]) * np.diff(phi)))
    en = te.annulus_energy(old, out["w"], slide, a, out["sense"], G, out["dpsi"])
    assert en["work"] == pytest.approx(W, rel=FAMILY_TRAPEZOID, abs=0)
    assert en["stored"] - en["stored_old"] + en["dissipated"] == pytest.approx(
        en["work"], rel=ENERGY_BALANCE)
    assert en["dissipated"] > 0
    # the trapezoid over the step alone (the old booking) is far off
    trap = 0.5 * (M[0] + M[-1]) * (phi[-1] - phi[0])
    assert abs(trap / W - 1) > 100 * FAMILY_TRAPEZOID


def shrinking():
    """A density reaching 1e-4 (a contact twisted in near-stick: a tenth of a full-sliding
    density), the contact shrunk to 0.8e-4 with its full-sliding density above the old one on
    the annulus (the slip of the step points the way of its traction)."""
    def linear(a, scale):
        b = np.linspace(0, a, 33)
        return ta.from_nodes(b, scale * b[:-1] / a, scale * b[1:] / a)
    return linear(1e-4, 100.0), linear(0.8e-4, 1e3), 0.8e-4


def annulus_valid(old, out):
    """The slip of the step points the way of its sense: s Δw >= 0 on the annulus."""
    d = ta.difference(out["w"], old, out["c"])
    inside = d[0] < 0.8e-4
    return np.all(out["sense"] * d[2][inside] >= 0) and np.all(out["sense"] * d[3][inside] >= 0)


def test_held_twist_release_does_no_work_and_dissipates_the_released_energy():
    old, slide, a = shrinking()
    out = ta.step(old, slide, a, G, dphi=0.0)
    assert annulus_valid(old, out)
    en = te.annulus_energy(old, out["w"], slide, a, out["sense"], G, out["dpsi"])
    assert out["dpsi"] == pytest.approx(0.0, abs=1e-14)
    assert abs(en["work"]) <= ENERGY_BALANCE * en["stored_old"]
    assert en["dissipated"] == pytest.approx(en["stored_old"] - en["stored"], rel=1e-10)
    assert en["dissipated"] > 0


@pytest.mark.parametrize("where", ["zero", "release"])
def test_booking_of_a_shrinking_contact_is_continuous(where):
    """Across Δφ = 0 (split into release + family / family + release) and across Δφ = −G (the
    family turns monotonically beyond it) the work and dissipation are continuous."""
    old, slide, a = shrinking()
    G_rel = float(ta.psi(old, np.array([a]))[0])
    base = 0.0 if where == "zero" else -G_rel
    vals = []
    for eps in (-1e-9, 1e-9):
        dphi = base + eps * G_rel
        out = ta.step(old, slide, a, G, dphi=dphi)
        assert annulus_valid(old, out)
        en = te.annulus_energy(old, out["w"], slide, a, out["sense"], G, out["dpsi"])
        # (at Δφ = −G nothing slides: 0 to rounding)
        assert en["dissipated"] >= -ENERGY_STEP_ROUNDING * en["stored_old"]
        vals.append((en["work"], en["dissipated"]))
    (w0, d0), (w1, d1) = vals
    scale = te.energy(old, G)
    assert abs(w1 - w0) < 1e-6 * scale
    assert abs(d1 - d0) < 1e-6 * scale


def test_release_stops_at_the_new_radius_when_the_booked_turn_rounds_beyond_it():
    """Regression (issue 26 item 1): a contact regrowing at held twist with an old density
    that reaches beyond the new radius ``a`` with ``Ψ_o(a) = 2e-25`` rad, and a ``Ψ_o`` that
    dips below zero inside ``a`` (bands of both senses). The booked turn of the step is a
    difference of two totals ``Ψ(0) ≈ 4e-3`` rad: one ulp of it (~1e-18 rad) exceeds ``Ψ_o(a)``.
    The release stage of the booking went down to ``Ψ_o = 1e-18`` rad, deep inside ``a``, and
    the held stage after it regrew that density: a large negative dissipation. The step is at
    held twist: no work, and it dissipates the energy it releases, ``E_o − E_n >= 0``."""
    a, top, p = 1e-4, 1.2e-4, 0.5e-4
    old = pieces([(0.0, p, 0.0, 200.0), (p, a, -20.0, -20.0), (a, top, 1e-20, 1e-20)])
    slide = hertz_slide(a)
    out = ta.step(old, slide, a, G, dphi=0.0)
    assert out["sense"] == 1.0
    for turn in (-1e-18, out["dpsi"], 0.0, 1e-18):
        en = te.annulus_energy(old, out["w"], slide, a, out["sense"], G, turn)
        E_o = te.energy(old, G)
        assert abs(en["work"]) <= ENERGY_BALANCE * E_o
        assert en["dissipated"] >= -ENERGY_STEP_ROUNDING * E_o
        assert en["dissipated"] == pytest.approx(E_o - te.energy(out["w"], G),
                                                 abs=ENERGY_BALANCE * E_o)


def test_release_of_a_band_whose_twist_is_not_monotone():
    """The band beyond the new radius ``a`` carries a density of both signs (``-u`` at its
    inner end, ``+u`` at ``top``): ``Ψ_o`` rises from ``top`` inwards to its maximum ``G`` at
    ``a`` and falls again below it, so both ends of that piece lie below ``Ψ_o = −Δφ = G/2`` and
    the release radius was searched (and found) inside the new contact. The release stops at
    the outer root (between ``a`` and ``top``): its work is ∫ M dφ along the release (the twist
    monotone there; trapezoid over 4000 states), the step dissipates >= 0 and balances."""
    a, top, p0, u = 0.79e-4, 1e-4, 0.6e-4, 50.0
    old = pieces([(0.0, p0, 40.0, 40.0), (p0, top, -u, u)])
    slide = hertz_slide(a)
    # by hand: w = −u + 2u ξ/L on (p0, top), ξ = t − p0, L = top − p0: Ψ_o = u ξ (1 − ξ/L)
    L = top - p0
    G_rel = float(ta.psi(old, np.array([a]))[0])
    assert G_rel == pytest.approx(u * (a - p0) * (1 - (a - p0) / L), rel=QUAD, abs=0)
    dphi = -0.5 * G_rel
    out = ta.step(old, slide, a, G, dphi=dphi)
    assert out["sense"] == 1.0 and out["c"] < a
    d = ta.difference(out["w"], old, out["c"])       # s Δw >= 0 on the annulus: a valid step
    assert np.all(d[2][d[0] < a] >= 0) and np.all(d[3][d[0] < a] >= 0)
    en = te.annulus_energy(old, out["w"], slide, a, out["sense"], G, out["dpsi"])
    assert en["stored"] - en["stored_old"] + en["dissipated"] == pytest.approx(
        en["work"], rel=ENERGY_BALANCE, abs=0)
    assert en["dissipated"] >= 0
    # the release from top down to the outer root x1 of Ψ_o(x1) = −Δφ (the inner one is
    # below a, and Ψ_o(p0) = Ψ_o(top) = 0)
    x1 = p0 + L / 2 + np.sqrt(L * L / 4 + dphi * L / u)
    assert p0 + L / 2 - np.sqrt(L * L / 4 + dphi * L / u) < a
    assert a < x1 < top
    assert psi_ref([(0.0, p0, 40.0, 40.0), (p0, top, -u, u)], x1) == pytest.approx(
        -dphi, rel=QUAD, abs=0)
    xs = np.linspace(top, x1, 4001)
    M = np.array([ta.torque(ta.splice(old, ta.empty(), x), G) for x in xs])
    phi = np.array([-ta.psi(old, np.array([x]))[0] for x in xs])
    W = float(np.sum(0.5 * (M[1:] + M[:-1]) * np.diff(phi)))
    assert en["work"] == pytest.approx(W, rel=FAMILY_TRAPEZOID, abs=0)
