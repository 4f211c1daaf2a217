"""Punch-density kernels of the exact torsion solver (physics.torsion_annulus) against direct
quadratures of Jäger's punch superposition and the Reissner–Sagoci displacement, and one step
from rest against the closed-form Hertz (Lubkin) solution."""
import numpy as np
import pytest
from scipy.integrate import quad
from scipy.special import ellipe, ellipk

from contactlab.physics import torsion_annulus as ta
from contactlab.physics import torsion_rings as tr
from tests.tolerances import QUADRATURE, RINGS_ANNULUS_STEP

G = 80e9          # Pa; lengths in units of the outer radius (1)
# a density with a jump inside (at 0.47) and a gap of zero density below the first piece
P = (np.array([0.2, 0.47, 0.47, 0.8]), np.array([0.47, 0.47, 0.8, 1.0]),
     np.array([3.0, 0.0, -1.5, 2.0]), np.array([5.0, 0.0, 0.5, 4.0]))
P = tuple(np.asarray(v)[[0, 2, 3]] for v in P)          # drop the zero-width piece


def w(t):
    lo, hi, wl, wr = P
    for a, b, u, v in zip(lo, hi, wl, wr):
        if a <= t < b:
            return u + (v - u) * (t - a) / (b - a)
    return 0.0


def ends():
    return sorted(set(P[0]) | set(P[1]))


def quad_pieces(f, lo, hi, epsrel=1e-12):
    pts = [x for x in ends() if lo < x < hi]
    edges = [lo] + pts + [hi]
    return sum(quad(f, u, v, limit=200, epsabs=1e-15, epsrel=epsrel)[0]
               for u, v in zip(edges, edges[1:]) if v > u)


@pytest.mark.parametrize("r", [0.1, 0.3, 0.6, 0.95])
def test_traction_matches_the_punch_superposition(r):
    pts = [x for x in ends() if x > r]
    first = quad(lambda t: w(t) / np.sqrt(t + r), r, pts[0], weight="alg", wvar=(-0.5, 0.0),
                 epsabs=0, epsrel=1e-12)[0]          # (t − r)^(-1/2) weight at the lower end
    want = 4 * G / np.pi * r * (first + quad_pieces(lambda t: w(t) / np.sqrt(t * t - r * r),
                                                    pts[0], 1.0))
    got = ta.traction(P, np.array([r]), G)[0]
    assert got == pytest.approx(want, rel=QUADRATURE * 10)


@pytest.mark.parametrize("r", [0.1, 0.3, 0.6, 0.95, 1.3])
def test_slip_kernel_is_rigid_turn_minus_reissner_sagoci(r):
    # displacement of a punch of radius t turned by 1 at r > t (Reissner–Sagoci), written out
    # independently: u = (2/π)[r arcsin(t/r) − t sqrt(1 − t²/r²)]
    def lag(t):
        return r - 2 / np.pi * (r * np.arcsin(t / r) - t * np.sqrt(1 - t * t / (r * r)))
    want = quad_pieces(lambda t: w(t) * lag(t), 0.0, min(r, 1.0))
    got = ta.slip_kernel_integral(P, np.array([r]))[0]
    assert got == pytest.approx(want, rel=QUADRATURE * 10, abs=1e-30)


def test_psi_torque_and_energy_against_quadrature():
    psi = lambda x: quad_pieces(w, x, 1.0)                      # noqa: E731
    for x in (0.0, 0.1, 0.3, 0.47, 0.9):
        assert ta.psi(P, np.array([x]))[0] == pytest.approx(psi(x), rel=QUADRATURE)
    M = 16 / 3 * G * quad_pieces(lambda t: t ** 3 * w(t), 0.0, 1.0)
    assert ta.torque(P, G) == pytest.approx(M, rel=QUADRATURE)
    assert ta.torque_below(P, np.array([0.6]), G)[0] == pytest.approx(
        16 / 3 * G * quad_pieces(lambda t: t ** 3 * w(t), 0.0, 0.6), rel=QUADRATURE)
    E = 8 * G * quad_pieces(lambda x: x * x * psi(x) ** 2, 0.0, 1.0, epsrel=1e-9)
    assert ta.stored_energy(P, G) == pytest.approx(E, rel=QUADRATURE * 10)


def test_ring_density_round_trip_and_energy_of_the_ring_solver():
    b = np.linspace(0, 1.0, 21)
    jumps = np.array([12])
    pts = np.sort(np.concatenate([0.5 * (b[1:] + b[:-1]), [b[12] + 0.25 * (b[13] - b[12])]]))
    m = tr.influence(b, pts, G, jumps=jumps)
    z = np.random.default_rng(3).normal(size=pts.size) * 1e6
    p = ta.density(m["lu"], b, jumps, z, b[-1])
    assert np.allclose(ta.traction(p, pts, G), z, rtol=0, atol=1e-9 * np.abs(z).max())
    # a sum over random tractions of both signs: the two routes round differently (cancellation;
    # 3.3e-12 apart with AVX2 OpenBLAS kernels, closer with AVX-512 ones)
    assert ta.torque(p, G) == pytest.approx(m["g"] @ z, rel=1e-11)
    assert ta.stored_energy(p, G) == pytest.approx(0.5 * z @ m["H"] @ z, rel=1e-10)


# ---- one monotone step from rest, Hertz (a = 1, G_t = 1, p0 = 1): Lubkin's closed form
MU, F = 0.3, 2 * np.pi / 3


def hertz_twist(c):
    m = 1 - c * c
    return 3 * MU * F / (4 * np.pi) * (ellipk(m) - ellipe(m))


def hertz_torque(c):
    return MU * F * (3 * np.pi / 16 - 4 / np.pi * quad(lambda s: s * s * ellipe(1 - s * s), 0, c,
                                                       epsabs=0, epsrel=1e-13)[0])


def _hertz_rings(n):
    """``n`` uniform rings on a unit Hertz contact: boundaries, midpoints, influence matrices,
    the slip limit μp at the midpoints and its full-sliding density."""
    b = np.linspace(0, 1, n + 1)
    r = 0.5 * (b[1:] + b[:-1])
    m = tr.influence(b, r, 1.0)
    bound = MU * np.sqrt(np.clip(1 - r * r, 0, None))
    return b, r, m, bound, ta.density(m["lu"], b, np.zeros(0, int), bound, 1.0)


@pytest.mark.parametrize("c", [0.3123, 0.6789, 0.9512])
@pytest.mark.parametrize("control", ["twist", "torque"])
def test_step_from_rest_places_the_stick_radius_inside_its_ring(c, control):
    _, r, _, bound, slide = _hertz_rings(200)
    kw = ({"dphi": hertz_twist(c)} if control == "twist" else
          {"target_torque": hertz_torque(c)})
    out = ta.step(ta.empty(), slide, 1.0, 1.0, r=r, bound=bound, **kw)
    M_full = 3 * np.pi / 16 * MU * F
    assert out["ok"] and out["sense"] == 1.0 and out["gross"] == 0.0
    assert abs(out["c"] - c) < RINGS_ANNULUS_STEP * 10      # a hundredth of a ring width
    if control == "twist":
        assert abs(ta.torque(out["w"], 1.0) - hertz_torque(c)) / M_full < RINGS_ANNULUS_STEP
    else:
        assert abs(out["dpsi"] - hertz_twist(c)) / hertz_twist(c) < RINGS_ANNULUS_STEP * 10
    # slip only on the annulus, forwards; traction μp there, below inside
    assert np.all(out["slip"][r < out["c"]] == 0) and np.all(out["slip"][r > out["c"]] > 0)
    tau = ta.traction(out["w"], r, 1.0)
    assert np.allclose(tau[r > out["c"]], bound[r > out["c"]], rtol=1e-9)
    assert np.all(np.abs(tau[r < out["c"]]) < bound[r < out["c"]])


def test_kept_intermediates_give_the_results_of_fresh_densities():
    # step keeps the last twist step's piece ends and Ψ there, difference its last result and
    # the total Ψ(0) its last two, by the densities' identity: steps on the same densities with
    # other twists (and the same differences asked again) are bitwise those of fresh copies
    _, r, _, bound, slide = _hertz_rings(50)
    old = ta.step(ta.empty(), slide, 1.0, 1.0, dphi=hertz_twist(0.5), r=r, bound=bound)["w"]

    def fresh(p):
        return tuple(a.copy() for a in p)

    def same(p, q):
        return all(a.tobytes() == b.tobytes() for a, b in zip(p, q))

    for dphi in (0.3 * hertz_twist(0.5), 0.0, -0.2 * hertz_twist(0.5)):
        kept = ta.step(old, slide, 1.0, 1.0, dphi=dphi, r=r, bound=bound)
        new = ta.step(fresh(old), fresh(slide), 1.0, 1.0, dphi=dphi, r=r, bound=bound)
        assert [kept[k] for k in ("c", "dpsi", "gross", "ok")] == [
            new[k] for k in ("c", "dpsi", "gross", "ok")]
        assert same(kept["w"], new["w"]) and kept["slip"].tobytes() == new["slip"].tobytes()
        assert same(ta.difference(kept["w"], old, 0.0),
                    ta.difference(fresh(kept["w"]), fresh(old), 0.0))
    assert len({ta.step(old, slide, 1.0, 1.0, dphi=d)["c"] for d in (0.1, 0.2, 0.3)}) == 3


def test_step_reports_a_failed_check():
    # the twist held while the friction limit drops a hundredfold: no annulus reaching the edge
    # is needed by the twist, but the old traction inside is far beyond the new limit
    b, r, m, bound, slide = _hertz_rings(50)
    old = ta.step(ta.empty(), slide, 1.0, 1.0, dphi=hertz_twist(0.5), r=r, bound=bound)["w"]
    weak = ta.density(m["lu"], b, np.zeros(0, int), bound / 100, 1.0)
    out = ta.step(old, weak, 1.0, 1.0, dphi=0.0, r=r, bound=bound / 100)
    assert not out["ok"] and "friction limit" in out["why"]



def test_step_without_increments_checks_the_traction_first(monkeypatch):
    # a step with a second slip zone (the ring solver's) fails the traction check; without the
    # increments wanted it is found before the slip check's difference and integrals are formed
    # (a failed attempt at a third of the cost), with the verdict and density of the full check
    b, r, m, bound, slide = _hertz_rings(50)
    old = ta.step(ta.empty(), slide, 1.0, 1.0, dphi=hertz_twist(0.5), r=r, bound=bound)["w"]
    weak = ta.density(m["lu"], b, np.zeros(0, int), bound / 100, 1.0)
    full = ta.step(old, weak, 1.0, 1.0, dphi=0.0, r=r, bound=bound / 100, slip=True)

    def formed(*args):
        raise AssertionError("the slip check was formed")

    monkeypatch.setattr(ta, "difference", formed)
    quick = ta.step(old, weak, 1.0, 1.0, dphi=0.0, r=r, bound=bound / 100, slip=False)
    assert not full["ok"] and not quick["ok"] and quick["why"] == full["why"]
    assert quick["c"] == full["c"] and all(np.array_equal(u, v) for u, v in
                                           zip(quick["w"], full["w"]))
    monkeypatch.undo()
    # a step that passes: the same verdict and density either way
    for kw in ({"dphi": 0.1 * hertz_twist(0.5)}, {"dphi": -hertz_twist(0.3)}):
        a = ta.step(old, slide, 1.0, 1.0, r=r, bound=bound, slip=True, **kw)
        q = ta.step(old, slide, 1.0, 1.0, r=r, bound=bound, slip=False, **kw)
        assert a["ok"] and q["ok"] and a["c"] == q["c"]
        assert all(np.array_equal(u, v) for u, v in zip(a["w"], q["w"]))

def test_rigid_punches_energy_and_a_shrinking_contact():
    t = np.array([0.3, 0.55, 0.8, 1.0])
    m = np.array([2.0, -1.0, 0.5, 1.5])
    psi = lambda x: float(np.sum(m[t > x]))                 # noqa: E731
    edges = [0.0, *t]
    E = 8 * G * sum(quad(lambda x: x * x * psi(x) ** 2, u, v, epsabs=0, epsrel=1e-13)[0]
                    for u, v in zip(edges, edges[1:]))
    assert ta.punch_energy(t, m, G) == pytest.approx(E, rel=1e-12)
    # the contact shrinks to 0.6 with the twist held: the punches beyond leave, and the points
    # inside keep their rigid turn Ψ(0) (no slip), now carried by a punch of radius 0.6
    t2, m2, d = ta.punch_step(t, m, 0.6, G, dphi=0.0)
    assert d == 0.0 and np.sum(m2) == pytest.approx(np.sum(m), rel=1e-15)
    assert np.all(t2 <= 0.6) and ta.punch_traction(t2, m2, np.array([0.7]), G)[0] == 0.0
    # a torque target instead: the same state back from its torque
    t3, m3, d3 = ta.punch_step(t, m, 0.6, G, target_torque=ta.punch_torque(t2, m2, G))
    assert d3 == pytest.approx(0.0, abs=1e-14) and np.allclose(m3, m2, rtol=1e-14)


# ---- the speed routes (issue 28): each against the route it replaces --------------------------
def _densities(rng):
    """Abutting densities on a grid with a few off-grid nodes (stick radii), one with a gap."""
    b = np.linspace(0.0, 1.0, 41)
    out = []
    for extra in ([], [0.3137], [0.11, 0.5551, 0.77]):
        nodes = np.unique(np.concatenate([b[b <= 0.9], extra]))
        n = nodes.size - 1
        out.append((nodes[:-1], nodes[1:], rng.normal(size=n), rng.normal(size=n)))
    return b, out


def test_node_table_traction_and_slip_equal_the_piece_by_piece_sums():
    from tests.tolerances import RINGS_NODE_TABLE
    rng = np.random.default_rng(7)
    b, dens = _densities(rng)
    r = 0.5 * (b[1:] + b[:-1])
    table = ta.NodeTable(r, b)
    for p in dens:
        for sel in (slice(None), slice(0, 17), slice(9, 30)):
            want = ta.traction(p, r[sel], G)
            got = ta.traction(p, r[sel], G, table)
            assert np.max(np.abs(got - want)) <= RINGS_NODE_TABLE * np.max(np.abs(want))
            want = ta.slip_kernel_integral(p, r[sel])
            got = ta.slip_kernel_integral(p, r[sel], table)
            assert np.max(np.abs(got - want)) <= RINGS_NODE_TABLE * np.max(np.abs(want))
    # radii that are not rows of the table: the direct route, bit for bit
    rr = np.array([0.123, 0.456])
    assert np.array_equal(ta.traction(dens[1], rr, G, table), ta.traction(dens[1], rr, G))
    assert np.array_equal(ta.slip_kernel_integral(dens[1], rr, table),
                          ta.slip_kernel_integral(dens[1], rr))


def test_node_table_rows_of_its_own_radii_are_the_searched_rows():
    """The table's own radii (the same array, a copy, with equal radii repeated) get the rows a
    search of its radii finds; other radii are still searched (a subset, one off the table:
    None); the columns of its own radii are C-ordered, the same values as computed."""
    b = np.linspace(0.0, 1.0, 12)
    for r in (0.5 * (b[1:] + b[:-1]), np.array([0.1, 0.2, 0.2, 0.2, 0.7])):
        table = ta.NodeTable(r, b)
        search = np.searchsorted(table.r, table.r)
        for x in (table.r, r.copy()):
            assert table.same_radii(x)
            assert np.array_equal(table.rows(x), search)
        assert not table.same_radii(r[:-1]) and not table.same_radii(r + 1e-3)
        assert np.array_equal(table.rows(r[1:]), search[1:])
        assert table.rows(np.r_[r[:2], 0.123456]) is None
        nodes = np.r_[b[2:7], 0.61, b[9]]       # one node off the table
        A, S = table.columns(r.copy(), nodes)
        A0, S0 = ta._antiderivatives(table.r, nodes)
        assert A.flags.c_contiguous and S.flags.c_contiguous
        assert A.tobytes() == A0.tobytes() and S.tobytes() == S0.tobytes()


def test_node_table_slip_is_exact_zero_beyond_the_nodes_and_small_near_the_axis():
    # a density far outside the point: its lag there is 0 (K vanishes for t > r), and at a
    # point near the axis with every node beyond it no constant residue is left by the sums
    from tests.tolerances import RINGS_NODE_TABLE
    b = np.linspace(0.0, 1.0, 41)
    r = 0.5 * (b[1:] + b[:-1])
    table = ta.NodeTable(r, b)
    p = (b[20:-1], b[21:], np.ones(20), 2.0 * np.ones(20))
    got = ta.slip_kernel_integral(p, r[:20], table)
    assert np.array_equal(got, np.zeros(20))
    p = (b[:-1], b[1:], np.linspace(1, 2, 40), np.linspace(1.5, 2.5, 40))
    want = ta.slip_kernel_integral(p, r[:1])
    got = ta.slip_kernel_integral(p, r[:1], table)
    assert abs(got[0] - want[0]) <= RINGS_NODE_TABLE * abs(want[0])


def test_difference_with_one_lookup_equals_the_four_evaluations():
    # difference() takes both interval ends of each density with one search (_ends): the same
    # values, bit for bit, as w(x+) and w(x-) taken one by one (_values)
    rng = np.random.default_rng(3)
    _, dens = _densities(rng)
    gap = (np.array([0.0, 0.5]), np.array([0.2, 0.9]), np.array([1.0, -2.0]),
           np.array([3.0, 4.0]))
    for new, old in [(dens[0], dens[1]), (dens[2], gap), (gap, dens[1]), (dens[1], ta.empty())]:
        for start in (0.0, 0.3137, 0.6):
            got = ta.difference(new, old, start)
            xs = np.unique(np.concatenate([new[0], new[1], old[0], old[1], [start]]))
            xs = xs[xs >= start]
            lo, hi = xs[:-1], xs[1:]
            want = (lo, hi, ta._values(new, lo, 1) - ta._values(old, lo, 1),
                    ta._values(new, hi, -1) - ta._values(old, hi, -1))
            for u, v in zip(got, want):
                assert np.array_equal(u, v)


# ---- the full-sliding density held to Ψ >= 0 (nonnegative_psi) ------------------------------
#: a density whose Ψ dips below zero inside (0.45..0.6: w changes sign twice) and at the outer
#: end (w < 0 on the last piece), with a gap of zero density
Q = (np.array([0.1, 0.3, 0.45, 0.6, 0.85]), np.array([0.3, 0.45, 0.6, 0.85, 1.0]),
     np.array([1.0, -2.0, -6.0, 4.0, 2.0]), np.array([-1.0, -6.0, 8.0, 3.0, -9.0]))


def _psi_by_quadrature(p, x):
    lo, hi, wl, wr = p
    tot = 0.0
    for a, b, u, v in zip(lo, hi, wl, wr):
        if b > x:
            s = max(a, x)        # a linear piece: its trapezoid is exact
            tot += 0.5 * (b - s) * (u + (v - u) * (s - a) / (b - a) + v)
    return tot


def test_nonnegative_psi_is_the_positive_part_of_psi():
    """The projected density's Ψ is ``max(Ψ, 0)`` (Ψ of the original density summed piece by
    piece), its elastic energy that of ``max(Ψ, 0)`` (quadrature), and it is the density
    itself, the same arrays, where Ψ never dips below zero."""
    x = np.linspace(0.0, 1.0, 2001)
    want = np.array([max(_psi_by_quadrature(Q, v), 0.0) for v in x])
    assert np.min(ta.psi(Q, x)) < -0.05                      # the case has negative bands
    out = ta.nonnegative_psi(Q)
    got = ta.psi(out, x)
    assert np.all(got >= 0.0)
    assert np.max(np.abs(got - want)) <= QUADRATURE * np.max(np.abs(want))
    E = 8 * G * quad(lambda v: v * v * max(_psi_by_quadrature(Q, v), 0.0) ** 2, 0.0, 1.0,
                     points=[0.3, 0.45, 0.6, 0.85], limit=200, epsabs=0, epsrel=1e-11)[0]
    assert ta.stored_energy(out, G) == pytest.approx(E, rel=QUADRATURE * 10)
    # Ψ >= 0 everywhere: nothing to remove
    assert ta.psi(P, x).min() >= 0.0 and ta.nonnegative_psi(P) is P
    assert ta.nonnegative_psi(ta.empty())[0].size == 0


def test_sliding_density_of_an_edge_short_of_its_node_is_held_to_non_negative_psi():
    """A Hertz contact of radius 0.97 on 24 rings whose contact-radius node sits at 1.0 (an edge
    that shares a node of the aligned grid lies up to a fraction of a ring inside it): the
    collocated full-sliding density ends negative and its Ψ dips below zero near the edge (so
    a slip annulus there would book a negative dissipation); the projection has Ψ >= 0 and
    moves the torque by less than the collocated density's own error against the closed form
    ``μ π² a³ p₀/8`` (p₀ = 1, G_t = 1)."""
    a = 0.97
    b = tr.aligned_grid(np.linspace(0.0, 1.2, 25), np.array([1.0, 1.2]))
    jumps = tr.radius_nodes(b, np.array([1.0, 1.2]))
    h = np.diff(b)
    pts = np.sort(np.concatenate([0.5 * (b[1:] + b[:-1]), b[jumps] + 0.25 * h[jumps]]))
    m = tr.influence(b, pts, 1.0, jumps=jumps)
    bound = MU * np.sqrt(np.clip(1 - (pts / a) ** 2, 0, None))
    W = ta.density(m["lu"], b, jumps, bound, 1.0)
    x = np.linspace(0.0, 1.0, 20001)
    assert W[3][-1] < 0 and ta.psi(W, x).min() < -1e-3 * ta.psi(W, x).max()
    Wp = ta.nonnegative_psi(W)
    assert ta.psi(Wp, x).min() >= 0.0
    M = MU * np.pi ** 2 * a ** 3 / 8
    err = abs(ta.torque(W, 1.0) - M)
    assert abs(ta.torque(Wp, 1.0) - ta.torque(W, 1.0)) < err
    assert abs(ta.torque(Wp, 1.0) - M) < err
