"""Master curves of power-law contacts against the exact solvers, on ladders that reach
c/a -> 1 (no slip) and c/a -> 0 (full sliding); exponents below 1 (pressure singular at the
centre, algebraic decay of c/a, map power k = 4) included."""
import numpy as np
import pytest

from contactlab.physics import master, tangential, torsion_exact as ex
from contactlab.physics.torsion import Exact
from contactlab.profiles import PowerLaw
from contactlab.symbolic.transform import kappa
from tests.tolerances import CLOSED_FORM, MASTER_CURVE

STICK_LADDER = np.array([1 - 1e-10, 1 - 1e-7, 1 - 1e-4, 0.999, 0.99, 0.9, 0.7, 0.5, 0.3, 0.1,
                         1e-2, 1e-3, 1e-4, 1e-6])


#: exponents of the ladders: below 1 (k = 4 map), the cone (slowest decay for k = 1) and above
EXPONENTS = [0.01, 0.2, 0.5, 0.9, 0.99, 1.0, 2.0, 3.0]


@pytest.mark.parametrize("n", EXPONENTS)
def test_torsion_master_on_stick_ladder(n):
    """Parametrise by the stick ratio (no root solve): y = P(c)/(E*d/a), M from the torque
    integral; the master curve evaluated at that y must return c/a and M/M_full."""
    mc = master.torsion_master(n)
    assert mc.certified_error <= master.CERTIFY_TOL
    prof = PowerLaw(c=1.0, n=n)
    k = float(kappa(n))
    t = STICK_LADDER
    one = np.ones(t.size)
    P, _ = ex.slip_function(prof, 1.0, t, one, k, k, 1e-14)
    y = P / k
    phi = 0.5 * P
    T, _ = ex.torque_integral(prof, 1.0, t, one, k, k, 1e-14)
    M = ex.torque_of_stick(1.0, 1.0, t, phi, T)
    M_full = np.pi * n / (2 * (n + 2)) * k
    tt, m, q = mc(y)
    np.testing.assert_allclose(tt, t, rtol=0, atol=MASTER_CURVE)
    np.testing.assert_allclose(m, M / M_full, rtol=MASTER_CURVE, atol=0)
    D = Exact(prof, 1.0, 1.0, 1.0, 1e-14).dissipation(phi, t, one, k * one, k * one)
    # q = D/(M_full φ) is certified in absolute terms: the exact J = P T - I cancels as c -> a
    np.testing.assert_allclose(q, D / (M_full * phi), rtol=0, atol=MASTER_CURVE)


@pytest.mark.parametrize("n", EXPONENTS)
def test_torsion_master_on_twist_ladder(n):
    """Relative accuracy as y -> 0 (torque ~ y, dissipation ~ y³) and the limit y -> ∞."""
    mc = master.torsion_master(n)
    y = np.array([1e-12, 1e-9, 1e-6, 1e-3, 0.1, 1.0, 3.0, 10.0, 30.0, 1e3, 1e6])
    t_ex, m_ex, q_ex = master._exact_curves(n, y)
    t, m, q = mc(y)
    np.testing.assert_allclose(t, t_ex, rtol=0, atol=MASTER_CURVE)
    np.testing.assert_allclose(m, m_ex, rtol=MASTER_CURVE, atol=0)
    np.testing.assert_allclose(q, q_ex, rtol=0, atol=MASTER_CURVE)
    # no-slip slope: M = (16/3) G_t a³ φ  <=>  m = 16 (n+2) y / (3 π n)
    assert m[0] == pytest.approx(16 * (n + 2) * y[0] / (3 * np.pi * n), rel=MASTER_CURVE)
    if n < 1:       # algebraic decay (c/a ~ 1e-6 at y = 1e6 for n = 0.01): go further out
        t, m, _ = mc(np.array([1e30]))
    assert 0.0 <= t[-1] <= MASTER_CURVE and m[-1] == pytest.approx(1.0, abs=MASTER_CURVE)


def test_torsion_master_map_power():
    """n < 1 tables use the k = 4 map, n >= 1 the plain one (their tables are unchanged)."""
    assert master.torsion_master(0.5).power == master.MAP_POWER_BELOW_ONE == 4
    assert master.torsion_master(2.0).power == 1 and master.torsion_master(np.inf).power == 1


def test_torsion_master_below_one_decays_algebraically():
    """Independent of the solvers' quadrature: deep in sliding, c/a ∝ y^(-1/(1-n)) (the slip
    function P(c) ∝ c^(n-1) of the centre singularity p ∝ r^(n-1)); the local log-slope of the
    master curve tends to -1/(1-n)."""
    for n in (0.2, 0.5):
        mc = master.torsion_master(n)
        y = np.array([1e6, 1e6 * 1.01])
        t, _, _ = mc(y)
        slope = np.log(t[1] / t[0]) / np.log(1.01)
        assert slope == pytest.approx(-1 / (1 - n), rel=1e-2)


def test_torsion_master_rejects_n_below_minimum():
    with pytest.raises(master.NotSupportedError, match=r"n=0.005.*n >= 0.01.*singularity"):
        master.torsion_master(0.005)


@pytest.mark.parametrize("n", [1.0, 2.0, 3.0, 1.7])
def test_tangential_master_against_kernels(n):
    prof = PowerLaw(c=2.0, n=n)
    E, G, mu, a = 1.3e11, 5e10, 0.4, 1e-4
    d = float(prof._g(np.array(a)))
    u_star = mu * E * d / G
    x = np.array([1e-6, 1e-3, 0.1, 0.5, 0.9, 0.999, 1.0, 1.5])
    u = x * u_star
    t, f, w = master.tangential_master(n, x)
    F, c = tangential.force_of_displacement(prof, E, G, mu, a, d, u)
    FN = 2 * E * d * a * n / (n + 1)
    mpmath = pytest.importorskip("mpmath")
    mpmath.mp.dps = 30
    f_ref = [float(1 - (1 - mpmath.mpf(v)) ** (mpmath.mpf(n + 1) / n)) if v < 1 else 1.0
             for v in x]
    np.testing.assert_allclose(f, f_ref, rtol=1e-14)
    # the spring-sum kernel cancels at small x (2G*cu + 2μE*∫(d - g) - ...): absolute comparison
    np.testing.assert_allclose(f * mu * FN, F, rtol=0, atol=1e-12 * mu * FN)
    np.testing.assert_allclose(t * a, c, rtol=0, atol=CLOSED_FORM * a)
    D = tangential.virgin_dissipation(prof, E, G, mu, a, d, u, 1e-12)
    np.testing.assert_allclose(2 * a * (mu * E * d) ** 2 / G * w, D, rtol=1e-9,
                               atol=1e-12 * D.max())


@pytest.mark.parametrize("n", [0.3, 0.75])
def test_torsion_master_below_one_against_independent_reference(n):
    """n < 1 against the independent mpmath reference (tests/reference/torsion_reference.py:
    the slip function integrated directly from the closed-form pressure, singular at the centre
    as r^(n-1), and the torque by its swapped single integral), parametrised by the stick
    ratio; M_full = π n/(2(n+2)) μE*d a² in closed form."""
    ref = pytest.importorskip("tests.reference.torsion_reference")
    mc = master.torsion_master(n)
    k = float(kappa(n))                     # unit contact: c = a = E* = G_t = μ = 1, d = κ
    M_full = np.pi * n / (2 * (n + 2)) * k
    p = lambda r: ref.pressure_power(r, 1, 1, 1, n)  # noqa: E731
    for t in (0.99, 0.5, 1e-3):
        phi, M = ref.torque_general(t, 1, p, 1, 1)
        tt, m, _ = mc(np.array([2 * float(phi) / k]))
        assert tt[0] == pytest.approx(t, rel=MASTER_CURVE, abs=MASTER_CURVE)
        assert m[0] == pytest.approx(float(M) / M_full, rel=MASTER_CURVE)


class _IndexWatch:
    """numpy as an array module for :func:`master.evaluate`, counting the entries of the panel
    index (the integer array it clips) that lay below the table (negative) before the clip."""

    def __init__(self):
        self.clips = 0
        self.below = 0

    def clip(self, a, lo, hi):
        if np.asarray(a).dtype.kind == "i":
            self.clips += 1
            self.below += int(np.count_nonzero(np.asarray(a) < lo))
        return np.clip(a, lo, hi)

    def __getattr__(self, name):
        return getattr(np, name)


def _bits(v):
    return np.ascontiguousarray(v, float).view(np.uint64)


def _master_twists(mc, rng):
    """Finite twists y >= -0.0: 8 random points in every panel of the map, its edges, the
    ends (0, -0.0, the smallest subnormal, 1e-300, 1e300) and, for the flat punch, y0 and
    its neighbours; for k = 1 also tiny negatives (s rounds into (-1/N, 0])."""
    N, k = mc.panels, mc.power
    s = np.concatenate([((np.arange(N)[:, None] + rng.random((N, 8))) / N).ravel(),
                        np.arange(N) / N])
    y = mc.y0 + mc.y_scale * (s / (1.0 - s)) ** k
    ends = [0.0, -0.0, 5e-324, 1e-300, 1e300]
    if mc.y0 > 0:
        ends += [mc.y0, np.nextafter(mc.y0, 0.0), np.nextafter(mc.y0, 1.0), 0.5 * mc.y0]
    if k == 1:
        ends += [-5e-324, -1e-300, -0.5 * mc.y_scale / (N + 1)]
    return np.concatenate([y, ends])


@pytest.mark.parametrize("n", [0.5, 2.0, np.inf], ids=["k4", "k1", "flat"])
def test_evaluate_on_any_array_module_to_the_bit(n):
    """``evaluate`` through an array module (numpy wrapped to count the panel indices its
    clip moves up to 0) and through the device step's entry point
    (``law_xp.torsion_curves``) equals the numpy route bit for bit on every panel, the ends
    and the flat punch's stick branch; for every finite ``y >= -0.0`` (and tiny negatives
    with k = 1) no panel index is negative, so the clip changes no bit there. ``inf`` and NaN
    (s = inf/inf) give NaN curves: the index is clipped into the table, where it was once
    read at -2^63 (IndexError)."""
    from contactlab.physics import law_xp
    mc = master.torsion_master(n)
    y = _master_twists(mc, np.random.default_rng(11))
    args = (mc.coef, mc.y_scale, y, mc.y0, mc.m0, mc.scaled, mc.power)
    ref = master.evaluate(*args)
    watch = _IndexWatch()
    for got in (master.evaluate(*args, xp=watch), law_xp.torsion_curves(np, *args), mc(y)):
        for a, b in zip(got, ref):
            np.testing.assert_array_equal(_bits(a), _bits(b))
    assert watch.clips == 1 and watch.below == 0
    assert all(np.all(np.isfinite(v)) for v in ref)
    # inf, NaN, the largest float (y/y_s overflows for k = 4; m0 y for the flat punch) and,
    # for k = 4, a tiny negative (a fractional power of it is NaN)
    edge = np.array([np.inf, np.nan, np.finfo(float).max] + ([-1e-300] if mc.power != 1 else []))
    edge_args = (mc.coef, mc.y_scale, edge, mc.y0, mc.m0, mc.scaled, mc.power)
    with np.errstate(invalid="ignore", over="ignore"):     # inf/inf, NaN cast to an index
        ref = master.evaluate(*edge_args)
        watch = _IndexWatch()
        got = master.evaluate(*edge_args, xp=watch)
    for a, b in zip(got, ref):
        np.testing.assert_array_equal(_bits(a), _bits(b))
        assert np.all(np.isnan(b[:2]))
    assert watch.below == np.count_nonzero(np.isnan(ref[0])) >= 2


def test_evaluate_degree_seven_by_estrin_other_degrees_by_horner():
    """The order of operations the compiled law reproduces (issue 29): a degree-7 table is
    evaluated by Estrin's scheme (pairs, then u², then u⁴), any other degree by Horner's rule,
    bit for bit; on the certification points the two orders of a degree-7 table agree to
    MASTER_CURVE (both are rounding-level evaluations of the same polynomial)."""
    rng = np.random.default_rng(3)
    coef = rng.standard_normal((3, 5, 8))
    y = rng.uniform(0.0, 20.0, 400)
    t, m, q = master.evaluate(coef, 1.0, y, scaled=False)
    s = y / (y + 1.0)
    z = s * 5
    j = np.clip(z.astype(np.intp), 0, 4)
    u = 2.0 * (z - j) - 1.0
    u2, u4 = u * u, (u * u) * (u * u)
    for k, got in enumerate((t, m, q)):
        c = coef[k][j].T
        est = ((c[0] + c[1] * u) + (c[2] + c[3] * u) * u2) + ((c[4] + c[5] * u)
                                                              + (c[6] + c[7] * u) * u2) * u4
        hor = c[7]
        for p in range(6, -1, -1):
            hor = hor * u + c[p]
        np.testing.assert_array_equal(got, np.clip(est, 0.0, 1.0) if k == 0 else est)
        np.testing.assert_allclose(est, hor, rtol=0, atol=MASTER_CURVE * np.max(np.abs(hor)))
    six = master.evaluate(coef[:, :, :7], 1.0, y, scaled=False)[1]
    hor = coef[1][j, 6]
    for p in range(5, -1, -1):
        hor = hor * u + coef[1][j, p]
    np.testing.assert_array_equal(six, hor)
