"""Pressure of a table at fixed ring radii from running sums over its segments
(``physics.ring_pressure``) against closed forms and against the profile's own route."""
import numpy as np
import pytest

from contactlab.physics import normal, ring_pressure as rp
from contactlab.profiles import Paraboloid, Tabulated
from tests.reference.tabulated import spline_pressure_shape_quad, table_pressure_shape_quad
from tests.reference.torsion_reference import pressure_cone, pressure_power
from tests.tolerances import RING_PRESSURE_CLOSED, RING_PRESSURE_SECOND

E = 1.0            # pressures below are E*/π S with E* = 1 Pa
RTOL = 1e-10


def radii(seed: int, a_max: float, n: int = 60) -> tuple[np.ndarray, np.ndarray]:
    """Ring radii (uniform midpoints) and contact radii (random, some on the ring radii)."""
    rings = (np.arange(n) + 0.5) / n * a_max
    a = np.random.default_rng(seed).uniform(0.05 * a_max, a_max, 12)
    return rings, np.concatenate([a, rings[[3, n // 2, n - 1]], [a_max]])


def shape(prof, rings, a_max, a):
    tab = rp.fixed_radii_shape(prof, rings, a_max, RTOL)
    assert tab is not None
    return tab, rp.shape_at(prof, tab, a)


def scale(prof, a):
    return (prof.g(a) / a)[:, None]


@pytest.mark.parametrize("spacing", ["uniform", "random"])
def test_linear_table_of_a_cone_is_the_cone(spacing):
    """The linear interpolant of a cone is the cone: S = s (π/2) arccosh(a/r) (Sneddon)."""
    s = 0.05
    n = 60
    r = (np.linspace(0, 2e-3, n) if spacing == "uniform" else
         2e-3 * np.sort(np.r_[0.0, np.random.default_rng(3).random(n - 2), 1.0]))
    prof = Tabulated(r, s * r)
    rings, a = radii(1, 1.2e-3)
    tab, (S, err) = shape(prof, rings, 1.2e-3, a)
    ref = np.array([[float(pressure_cone(ri, ai, np.pi, s)) if ri < ai else 0.0 for ri in rings]
                    for ai in a])
    assert np.all(np.abs(S - ref) <= RING_PRESSURE_CLOSED * (np.abs(ref) + scale(prof, a)))
    assert np.all(S[rings[None, :] >= a[:, None]] == 0)


@pytest.mark.parametrize("spacing", ["uniform", "random"])
def test_cubic_table_of_a_cubic_is_the_cubic(spacing):
    """The not-a-knot spline of f = r²/(2R) + c r³ is f itself: S is the sum of the power laws'
    closed forms (Popov-Heß, ₂F₁), at every node and between."""
    R, c = 0.01, 3.0
    n = 80
    r = (np.linspace(0, 2e-3, n) if spacing == "uniform" else
         2e-3 * np.sort(np.r_[0.0, np.random.default_rng(5).random(n - 2), 1.0]))
    prof = Tabulated(r, r**2 / (2 * R) + c * r**3, "cubic")
    rings, a = radii(2, 1.5e-3)
    tab, (S, err) = shape(prof, rings, 1.5e-3, a)
    ref = np.array([[float(pressure_power(ri, ai, np.pi, 1 / (2 * R), 2)
                           + pressure_power(ri, ai, np.pi, c, 3)) if ri < ai else 0.0
                     for ri in rings] for ai in a])
    assert np.all(np.abs(S - ref) <= RING_PRESSURE_CLOSED * (np.abs(ref) + scale(prof, a)))


def tables():
    rng = np.random.default_rng(11)
    uni = np.linspace(0.0, 2e-3, 200)
    rnd = 2e-3 * np.sort(np.r_[0.0, rng.random(198), 1.0])
    # pairs of nodes 1e-9 of the table apart: nearly singular segments next to wide ones
    pairs = np.sort(np.r_[uni, uni[1:-1:7] + 2e-12])
    for name, r in (("uniform", uni), ("random", rnd), ("clustered", pairs)):
        f = r**2 / 0.02 + 2.0 * r**4
        for kind in ("linear", "cubic"):
                    yield pytest.param(r, f, kind, id=f"{kind}-{name}")


@pytest.mark.parametrize("r, f, kind", list(tables()))
def test_tables_match_the_profiles_own_route(r, f, kind):
    """Against the per-(ring, node) quadratures of ``normal.pressure_shape`` (a second method)
    everywhere, and against scipy's quad of the definition at a few points (independent).

    On the cubic spline with node pairs 1e-9 of the table apart the profile's by-parts route is
    off by up to 2e-10 (about 27x its own estimate; measured against the independent quad, which
    the running sums match to 6e-16): there the independent quad alone is the reference."""
    prof = Tabulated(r, f, kind)
    a_max = 0.6e-3
    rings, a = radii(7, a_max)
    tab, (S, err) = shape(prof, rings, a_max, a)
    ref, ref_err = normal.pressure_shape(prof, rings[None, :], a[:, None], RTOL)
    tol = RING_PRESSURE_SECOND * (np.abs(ref) + scale(prof, a))
    clustered = np.min(np.diff(r)) < 1e-9 * r[-1]
    if not (clustered and kind == "cubic"):
        assert np.all(np.abs(S - ref) <= tol)
    # the error estimate is an estimate, not a guess: small where the values agree
    assert np.all(err <= tol)
    quad = table_pressure_shape_quad if kind == "linear" else spline_pressure_shape_quad
    picks = ((15, 0.94),) if kind == "cubic" else ((0, 0.1), (4, 0.5), (10, 0.97))
    if kind == "linear" and clustered:
        picks = ()      # the by-parts quad cannot resolve 1e-12 m intervals (the route above can)
    for i, frac in picks:
        j = max(int(np.searchsorted(rings, frac * a[i])) - 1, 0)      # a ring below frac a
        assert rings[j] < a[i]
        q = quad(r, f, rings[j], a[i])
        assert abs(S[i, j] - q) <= RING_PRESSURE_SECOND * (abs(q) + scale(prof, a)[i, 0])


def test_ring_on_a_node_of_a_linear_table_is_infinite_as_the_profiles_route():
    """At a slope jump the pressure is logarithmically infinite; the running sums hand such
    rings to the profile's route, which says so (inf)."""
    r = np.linspace(0.0, 2e-3, 41)
    prof = Tabulated(r, r**2 / 0.02)
    rings = np.array([r[5], 0.5 * (r[7] + r[8]), r[12]])
    a = np.array([r[14] + 1e-6, 0.9 * r[14]])
    tab, (S, _) = shape(prof, rings, r[15], a)
    ref, _ = normal.pressure_shape(prof, rings[None, :], a[:, None], RTOL)
    assert np.isinf(S[0, 0]) and np.isinf(S[0, 2]) and np.isfinite(S[0, 1])
    np.testing.assert_array_equal(np.isinf(S), np.isinf(ref))
    fin = np.isfinite(ref)
    assert np.all(np.abs(S[fin] - ref[fin]) <= RING_PRESSURE_SECOND * np.abs(ref[fin]))


def test_declines_what_it_cannot_set_up(monkeypatch):
    """Not a table, a radius on the axis, or more rings x knots than MAX_ENTRIES: None (the
    caller takes the profile's own route)."""
    r = np.linspace(0.0, 2e-3, 101)
    prof = Tabulated(r, r**2 / 0.02)
    rings = np.linspace(1e-5, 1e-3, 50)
    assert rp.fixed_radii_shape(Paraboloid(R=0.01), rings, 1e-3, RTOL) is None
    assert rp.fixed_radii_shape(prof, np.r_[0.0, rings], 1e-3, RTOL) is None
    assert rp.fixed_radii_shape(prof, rings, 1e-3, RTOL) is not None
    monkeypatch.setattr(rp, "MAX_ENTRIES", 50 * 49 - 1)   # 49 nodes below 1 mm
    assert rp.fixed_radii_shape(prof, rings, 1e-3, RTOL) is None


def test_pressure_at_adds_the_edge_term():
    """``pressure_at`` is ``normal.pressure`` at the ring radii: S plus (d - g(a))/sqrt(a² - r²)."""
    r = np.linspace(0.0, 2e-3, 101)
    prof = Tabulated(r, r**2 / 0.02 + 2.0 * r**4)
    rings, a = radii(3, 1e-3)
    d = prof.g(a) * (1 + np.linspace(-0.1, 0.1, a.size))
    tab = rp.fixed_radii_shape(prof, rings, 1e-3, RTOL)
    p, _ = rp.pressure_at(prof, 2e9, tab, a, d, prof.g(a))
    ref, _ = normal.pressure(prof, 2e9, rings[None, :], a[:, None], d[:, None],
                             prof.g(a)[:, None], RTOL)
    sc = 2e9 / np.pi * (np.abs(normal.pressure_shape(prof, rings[None, :], a[:, None], RTOL)[0])
                        + scale(prof, a) + np.abs(d - prof.g(a))[:, None]
                        / np.sqrt(np.maximum(a[:, None]**2 - rings**2, 1e-300)))
    fin = np.isfinite(ref)
    np.testing.assert_array_equal(p[~fin], ref[~fin])      # ±inf at r = a (edge term)
    assert np.sum(~fin) >= 2
    assert np.all(np.abs(p[fin] - ref[fin]) <= RING_PRESSURE_SECOND * sc[fin])


def test_pressure_without_edge_term_is_the_rows_of_a_call_with_one():
    """``pressure_from_shape`` where ``d = g(a)`` on every row (no edge term: its short route)
    gives the same bits as those rows of a call in which one row has an edge term (the whole
    formula, elementwise): Hertz's closed form ``(2E*/πR) sqrt(a² − r²)`` within rounding."""
    R, E_star = 0.01, 2e9
    prof = Paraboloid(R=R)
    rings, a = radii(5, 1e-3)
    rows = np.r_[a, 0.5e-3]
    d = prof.g(rows)
    d[-1] *= 1.01                                  # the last row: an edge term
    shape = normal.pressure_shape(prof, rings[None, :], rows[:, None], RTOL)
    args = (rings[None, :], rows[:, None], d[:, None], prof.g(rows)[:, None])
    whole = normal.pressure_from_shape(E_star, *shape, *args)
    short = normal.pressure_from_shape(E_star, shape[0][:-1], shape[1][:-1],
                                       *(x[:-1] if x.shape[0] > 1 else x for x in args))
    assert whole[0][:-1].tobytes() == short[0].tobytes()
    assert whole[1][:-1].tobytes() == short[1].tobytes()
    hertz = 2 * E_star / (np.pi * R) * np.sqrt(np.maximum(a[:, None]**2 - rings**2, 0.0))
    assert np.all(np.abs(short[0] - hertz) <= RING_PRESSURE_CLOSED * np.max(hertz))
    assert np.all(short[0][rings[None, :] >= a[:, None]] == 0.0)
    # the edge row took its term: above the same row without one, inside the contact
    g_last = prof.g(rows[-1:])[:, None]
    plain = normal.pressure_from_shape(E_star, shape[0][-1:], shape[1][-1:], rings[None, :],
                                       rows[-1:, None], g_last, g_last)[0]
    inside = rings < rows[-1]
    assert np.all(whole[0][-1][inside] > plain[0][inside])


def test_contact_inside_the_first_segment():
    """No table node below the largest contact radius (a coarse table): every ring takes its own
    piece from r to a, a cone's closed form on a linear table's first segment."""
    r = np.linspace(0.0, 2e-3, 10)
    prof = Tabulated(r, 0.05 * r)
    rings, a = radii(4, 0.8 * r[1])
    tab, (S, _) = shape(prof, rings, 0.8 * r[1], a)
    assert tab.knots.size == 0
    ref = np.array([[float(pressure_cone(ri, ai, np.pi, 0.05)) if ri < ai else 0.0 for ri in rings]
                    for ai in a])
    assert np.all(np.abs(S - ref) <= RING_PRESSURE_CLOSED * (np.abs(ref) + scale(prof, a)))
