"""Kernels of the exact ring solver against direct quadratures of Jäger's punch superposition."""
import numpy as np
import pytest
from scipy.integrate import dblquad, quad

from contactlab.physics import torsion_rings as tr
from tests.tolerances import (QUADRATURE, QUADRATURE_EDGE_PUNCH, RINGS_SUPERPOSITION,
                              RINGS_TORQUE_TARGET)

G = 80e9
B = np.array([0.0, 0.3, 0.55, 0.8, 1.0]) * 1e-4


def hat(j, t):
    """Hat j (node B[j+1]) as a plain function."""
    lo, mid = B[j], B[j + 1]
    hi = B[j + 2] if j + 2 < B.size else mid
    if lo <= t <= mid:
        return (t - lo) / (mid - lo)
    if mid < t <= hi:
        return (hi - t) / (hi - mid)
    return 0.0


def traction_quad(j, r):
    f = lambda t: hat(j, t) / np.sqrt(t * t - r * r)
    pts = [p for p in B if p > r]
    val = sum(quad(f, max(lo, r), hi, limit=200)[0] for lo, hi in zip([r] + pts[:-1], pts)
              if hi > max(lo, r))
    return 4 * G / np.pi * r * val


@pytest.mark.parametrize("r", [0.1e-4, 0.42e-4, 0.79e-4, 0.95e-4])
def test_hat_traction_matches_the_punch_superposition(r):
    got = tr.hat_traction(B, np.array([r]), G)[0]
    want = np.array([traction_quad(j, r) for j in range(B.size - 1)])
    assert np.allclose(got, want, rtol=QUADRATURE * 10, atol=QUADRATURE * np.max(np.abs(want)))


def test_hat_torque_is_the_moment_of_its_traction():
    for j in range(B.size - 1):
        M = quad(lambda r: 2 * np.pi * r * r * traction_quad(j, r), 0, B[-1], limit=200,
                 points=list(B[1:-1]))[0]
        # nested adaptive quadrature of a traction with square-root kinks: ~1e-6
        assert tr.hat_torque(B, G)[j] == pytest.approx(M, rel=1e-5)


def test_energy_matrix_is_the_punch_energy():
    K = tr.energy_matrix(B, G)
    for j, k in [(0, 0), (1, 3), (2, 2), (3, 1)]:
        f = lambda s, t: hat(j, t) * hat(k, s) * 16 / 3 * G * min(t, s) ** 3
        val = 0.0
        for t0, t1 in zip(B[:-1], B[1:]):          # ring pieces; split the diagonal kink
            for s0, s1 in zip(B[:-1], B[1:]):
                if t0 == s0:
                    val += dblquad(f, t0, t1, t0, lambda t: t, epsabs=0, epsrel=1e-11)[0]
                    val += dblquad(f, t0, t1, lambda t: t, t1, epsabs=0, epsrel=1e-11)[0]
                else:
                    val += dblquad(f, t0, t1, s0, s1, epsabs=0, epsrel=1e-11)[0]
        assert K[j, k] == pytest.approx(val, rel=1e-8)


def test_box_step_single_point_sticks_then_slides():
    H = np.array([[2.0]])
    g = np.array([1.0])
    z, lam, d, _ = tr.box_step(H, g, np.zeros(1), np.array([1.0]), dphi=1.0)
    assert z[0] == pytest.approx(0.5) and lam[0] == 0.0
    z, lam, d, _ = tr.box_step(H, g, z, np.array([1.0]), dphi=2.0)
    assert z[0] == 1.0 and lam[0] == pytest.approx(1.0)      # 2·0.5 + 2 − 2·1
    z, lam, d, _ = tr.box_step(H, g, z, np.array([1.0]), torque=0.25)
    assert z[0] == pytest.approx(0.25) and d == pytest.approx(-1.5)


def test_aligned_grid_puts_every_contact_radius_on_a_node():
    rng = np.random.default_rng(3)
    b = np.linspace(0.0, 1e-4, 101)
    h = 1e-6
    radii = np.concatenate([rng.uniform(0.2e-4, 1e-4, 30), [1e-4, 0.0, 2e-4]])
    out = tr.aligned_grid(b, radii)
    assert out[0] == 0.0 and out[-1] == b[-1] and np.all(np.diff(out) >= tr.ALIGN_GAP * h)
    inside = radii[(radii > 0) & (radii <= b[-1])]
    assert np.max(np.min(np.abs(inside[:, None] - out[None, :]), axis=1)) <= 2 * tr.ALIGN_GAP * h
    assert np.max(np.diff(out)) <= (1 + 2 * tr.ALIGN_MERGE) * h * (1 + 1e-12)
    few = np.array([0.37e-4, 0.61e-4])                # radii far apart: each is a node exactly
    assert np.all(np.isin(few, tr.aligned_grid(b, few)))
    many = tr.aligned_grid(b, rng.uniform(0.2e-4, 1e-4, 3000))   # capped: the gap grows
    assert many.size - 1 <= tr.ALIGN_MAX_FACTOR * 100 and np.all(np.diff(many) > 0)


def _greedy_cover(ra, delta):
    """The covering of ``torsion_rings._cover_nodes`` written out as a loop: the largest radius
    a node, then from the smallest radius the largest within ``delta`` above the first one left
    uncovered."""
    rest, out, i = ra[ra < ra[-1] - delta], [], 0
    while i < rest.size:
        j = np.searchsorted(rest, rest[i] + delta, side="right") - 1
        out.append(rest[j])
        i = np.searchsorted(rest, rest[j] + delta, side="right")
    return np.array([*out, ra[-1]])


@pytest.mark.parametrize("n", [1, 2, 7, 1000, 4097])
def test_cover_nodes_are_the_greedy_covering(n):
    ra = np.unique(np.random.default_rng(n).uniform(0.3, 1.0, n))
    nodes = tr._cover_nodes(ra, 0.01)
    assert np.array_equal(nodes, _greedy_cover(ra, 0.01))
    assert nodes[-1] == ra[-1] and np.all(np.isin(nodes, ra))
    assert np.max(np.min(np.abs(ra[:, None] - nodes[None, :]), axis=1)) <= 0.01
    assert np.all(np.diff(nodes) > 0.01)


def test_aligned_grid_cover_follows_the_span_of_the_radii_not_their_number():
    b = np.linspace(0.0, 1e-4, 101)
    h = 1e-6
    few = np.random.default_rng(5).uniform(0.7e-4, 1e-4, 40)
    # a node at every radius fits ALIGN_EXACT_FACTOR: the cover changes nothing
    assert np.array_equal(tr.aligned_grid(b, few, 3.0, cover=0.24), tr.aligned_grid(b, few, 3.0))
    sizes = []
    for n in (1000, 10000, 100000):
        radii = 0.7e-4 + 0.3e-4 * (0.5 + 0.5 * np.sin(np.linspace(0.0, 20.0, n)))
        out = tr.aligned_grid(b, radii, 3.0, cover=0.24)
        inside = radii[radii > tr.ALIGN_MERGE * h]
        k = np.clip(np.searchsorted(out, inside), 1, out.size - 1)
        off = np.minimum(inside - out[k - 1], out[k] - inside)
        assert off.max() <= 0.24 * h and out[-1] == b[-1] and np.all(np.diff(out) > 0)
        sizes.append(out.size - 1)
    # 30 widths of radii at <= 0.48 widths a node, the 70 uniform rings below: ~133 rings
    # whatever the number of radii (a node at each would take up to 3x the 100 rings)
    assert max(sizes) - min(sizes) <= 2 and max(sizes) <= 100 + 30 / 0.48 + 2


def test_edge_punch_carries_the_singular_sliding_traction():
    """Full sliding of a flat punch, p ∝ 1/sqrt(a² − r²): the torque weights with the edge punch
    reproduce 2π∫ r² p dr = π²a²/2 at order > 2 (without it the square-root singularity is missed)."""
    a, errs = 1e-3, []
    for n in (50, 200):
        b = np.linspace(0.0, a, n + 1)
        r = np.append(0.5 * (b[1:] + b[:-1]), a - 0.1 * (a - b[-2]))
        g = tr.influence(b, r, G, edge_punch=True)["g"]
        assert np.all(g > 0)
        errs.append(abs(g @ (1 / np.sqrt(a * a - r * r)) / (np.pi ** 2 * a * a / 2) - 1))
    assert errs[1] < QUADRATURE_EDGE_PUNCH and errs[0] / errs[1] > 4.0 ** 2


def half_hat(j, t):
    """Falling half-hat outside node B[j] (w = (B[j+1] − t)/(B[j+1] − B[j]) on that ring)."""
    lo, hi = B[j], B[j + 1]
    return (hi - t) / (hi - lo) if lo <= t <= hi else 0.0


@pytest.mark.parametrize("r", [0.1e-4, 0.42e-4, 0.79e-4])
def test_jump_half_hat_traction_torque_and_energy_match_quadrature(r):
    """The half-hats that let the density jump at a node: traction by the punch superposition,
    torque as the moment of that traction, energy by the punch energy (16/3) G min(t, s)³."""
    jumps = np.array([1, 2])
    got = tr.jump_traction(B, np.array([r]), G, jumps)[0]
    for col, j in zip(got, jumps):
        f = lambda t: half_hat(j, t) / np.sqrt(t * t - r * r)
        want = 4 * G / np.pi * r * (quad(f, max(B[j], r), B[j + 1], limit=200)[0]
                                    if B[j + 1] > r else 0.0)
        assert col == pytest.approx(want, rel=QUADRATURE * 10, abs=QUADRATURE * abs(want))
    m = tr.jump_torque(B, G, jumps)
    for mj, j in zip(m, jumps):
        assert mj == pytest.approx(quad(lambda t: 16 / 3 * G * t ** 3 * half_hat(j, t),
                                        B[j], B[j + 1])[0], rel=1e-12)
    K = tr.energy_matrix(B, G, jumps=jumps)
    n = B.size - 1
    f = lambda s, t: half_hat(1, t) * hat(2, s) * 16 / 3 * G * min(t, s) ** 3
    val = sum(dblquad(f, B[1], B[2], s0, s1, epsabs=0, epsrel=1e-11)[0]
              for s0, s1 in zip(B[2:-1], B[3:]))
    assert K[n, 2] == pytest.approx(val, rel=1e-8) and K[2, n] == pytest.approx(K[n, 2], rel=1e-14)


def test_jump_at_an_inner_contact_edge_carries_the_sliding_traction():
    """Full sliding of a Hertz contact whose edge a is an inner node of the grid (a changing
    load): with the jump at a the torque weights reproduce 2π∫ r² p dr = π²a³/8 (p = sqrt(1 −
    r²/a²)) at order > 2; a continuous density smears the jump of w at a over the next ring."""
    a, errs, plain = 1e-3, [], []
    for n in (50, 200):
        b = np.linspace(0.0, a, n + 1)
        b = np.union1d(b * 1.3, [a])                  # grid to 1.3 a, node at a
        j = tr.radius_nodes(b, [a])
        assert b[j[0]] == a and j.size == 1
        mid = 0.5 * (b[1:] + b[:-1])
        for jumps, out in ((j, errs), (None, plain)):
            r = np.sort(np.append(mid, b[j] + 0.25 * (b[j + 1] - b[j]))) if jumps is not None \
                else mid
            g = tr.influence(b, r, G, jumps=jumps)["g"]
            p = np.sqrt(np.clip(1 - (r / a) ** 2, 0, None))
            out.append(abs(g @ p / (np.pi ** 2 * a ** 3 / 8) - 1))
    assert errs[1] < QUADRATURE_EDGE_PUNCH and errs[0] / errs[1] > 4.0 ** 2
    assert plain[1] > 10 * errs[1]


def test_gross_step_turns_by_the_smallest_increment_at_which_everything_slides():
    """``gross_step``: ``z = s μp``; every point slides the way of ``s`` (``s λ >= 0``), the
    binding point exactly at zero when the twist turns, and no smaller turn would do (the box
    step with that twist increment, less 1e-6 of it, keeps a point stuck); where the force fell
    (``μp`` scaled down from a full-sliding state) the twist is held."""
    b = np.linspace(0.0, 1.0, 21)
    r = 0.5 * (b[1:] + b[:-1])
    m = tr.influence(b, r, 1.0)
    H, g = m["H"], m["g"]
    bound = 0.3 * np.sqrt(1.0 - r * r)
    z_old, _, _, _ = tr.box_step(H, g, np.zeros(r.size), bound, dphi=0.5)   # partial slip
    z, lam, dphi = tr.gross_step(H, g, z_old, 1.2 * bound, 1.0)
    assert np.array_equal(z, 1.2 * bound) and dphi > 0
    tol = 1e-12 * np.abs(lam).max()
    assert np.all(lam >= -tol) and np.min(np.abs(lam)) <= tol
    zb, _, _, _ = tr.box_step(H, g, z_old, 1.2 * bound, dphi=dphi * (1 - 1e-6))
    assert np.any(np.abs(zb) < 1.2 * bound * (1 - 1e-12))
    _, lam2, d2 = tr.gross_step(H, g, z, 0.8 * bound, 1.0)
    assert d2 == 0.0 and np.all(lam2 >= 0.0)


@pytest.mark.parametrize("control", ["twist", "torque"])
def test_box_step_memo_reuses_the_last_factor_with_the_same_bits(control, monkeypatch):
    # a run of box steps each starting from the last one's active set (the ring solver's steps
    # during a second slip zone): with a memo, a pivot on the same stuck/active set as the
    # previous solve skips the Cholesky factorisation, and every result is bit-identical
    b = np.linspace(0.0, 1.0, 61)
    r = 0.5 * (b[1:] + b[:-1])
    m = tr.influence(b, r, 1.0)
    H, C, g = m["H"], m["C"], m["g"]
    p = np.sqrt(np.clip(1 - (r / 0.9) ** 2, 0, None))
    factored = []
    potrf = tr._potrf
    monkeypatch.setattr(tr, "_potrf", lambda *a, **k: factored.append(1) or potrf(*a, **k))

    def run(memo):
        z, act, out = np.zeros(r.size), None, []
        for k in range(40):
            bound = 0.3 * p * (1 - 0.004 * k)          # the limit falls: slip from the edge
            kw = ({"dphi": 2e-3 if k < 20 else -1e-3} if control == "twist" else
                  {"torque": float(g @ z) + (2e-4 if k < 20 else -1e-4)})
            z, lam, d, _ = tr.box_step(H, g, z, bound, guess=act, C=C, memo=memo, **kw)
            act = np.where(bound == 0, 2, np.where(lam == 0, 0, np.sign(z))).astype(int)
            out.append((z, lam, d))
        return out

    plain = run(None)
    n_plain = len(factored)
    memo_run = run({})
    assert len(factored) - n_plain < 0.7 * n_plain           # factors reused
    for (z0, l0, d0), (z1, l1, d1) in zip(plain, memo_run):
        assert np.array_equal(z0, z1) and np.array_equal(l0, l1) and d0 == d1


@pytest.mark.parametrize("share", [0.9, 0.5, 0.0, -0.6])
@pytest.mark.parametrize("sense", [1.0, -1.0])
def test_box_step_torque_below_sliding_from_full_sliding(share, sense):
    """Regression (issue 28, a stored sphere path at steps 99-101): from a full-sliding state
    (every point at ``-s μp``) a torque target of smaller magnitude was accepted with every
    point still at its bound and no twist increment: the torque stayed ``-s M_sliding``.

    Reference: the discrete problem's own superposition (Jäger/Ciavarella for torsion) at a
    fixed limit: unloading from ``z_o = -s b`` to the torque ``T`` is ``z = -s b + 2y``, where
    ``y`` is the loading from zero to the torque ``(T + s M_s)/2`` (``M_s = g·b``) with the same
    limits, and the twist increment is twice the loading's (``λ = 2 λ_y``: same complementarity).
    The loading solve starts from no point at a bound, another branch of the solver."""
    b = np.linspace(0.0, 1.0, 41)
    r = 0.5 * (b[1:] + b[:-1])
    m = tr.influence(b, r, 1.0)
    H, C, g = m["H"], m["C"], m["g"]
    bound = 0.3 * np.sqrt(np.clip(1.0 - (r / 0.9) ** 2, 0.0, None))
    Ms = float(g @ bound)
    z_old = -sense * bound
    target = -sense * share * Ms
    for kw in ({}, {"C": C}):
        z, _, d, _ = tr.box_step(H, g, z_old, bound, torque=target,
                                   guess=np.where(bound == 0, 2, -int(sense)), **kw)
        assert abs(float(g @ z) - target) <= RINGS_TORQUE_TARGET * Ms
        y, _, dy, _ = tr.box_step(H, g, np.zeros(r.size), bound,
                                  torque=0.5 * (target + sense * Ms) * sense, **kw)
        y = sense * y
        assert np.max(np.abs(z - (z_old + 2.0 * y))) <= RINGS_SUPERPOSITION * bound.max()
        assert abs(d - 2.0 * sense * dy) <= RINGS_SUPERPOSITION * abs(2.0 * dy)


def test_box_step_torque_beyond_sliding_the_other_way_is_gross():
    # from full sliding one way, a target beyond the sliding torque the other way: no state
    # within the limits carries it (nan: the caller's gross step)
    b = np.linspace(0.0, 1.0, 21)
    r = 0.5 * (b[1:] + b[:-1])
    m = tr.influence(b, r, 1.0)
    bound = 0.3 * np.sqrt(1.0 - r * r)
    Ms = float(m["g"] @ bound)
    _, _, d, _ = tr.box_step(m["H"], m["g"], -bound, bound, torque=1.01 * Ms,
                             guess=-np.ones(r.size, int))
    assert np.isnan(d)


def test_active_set_of_an_annulus_step():
    """An annulus step's active set, kept as its stick radius, sense and μp: the sense beyond
    the stick radius (the radius itself included), stuck inside, 2 where μp is 0; an array is
    its own active set."""
    r = np.array([0.1, 0.3, 0.5, 0.7, 0.9, 1.1])
    bound = np.array([2.0, 1.5, 1.0, 0.5, 0.0, 0.0])
    for s, beyond in ((1.0, 1), (-1.0, -1)):
        act = tr.active_set((0.5, s, bound), r)
        assert act.tolist() == [0, 0, beyond, beyond, 2, 2]
        assert act.dtype.kind == "i"
    given = np.array([0, 1, -1, 2, 2, 0])
    assert tr.active_set(given, r) is given
