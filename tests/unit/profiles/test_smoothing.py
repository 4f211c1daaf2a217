"""Noisy measured profiles (issue 12). Must show:

- tables sampled from analytic profiles (paraboloid, cone, n = 4; 200 and 2000 points; noise
  0.1 % and 2 % of the largest height) with ``smoothing="auto"``: force and contact radius at
  a contact radius of half the table within NOISY_TABLE_FORCE / NOISY_TABLE_RADIUS of the
  noise-free closed form (measured worst: 6 % / 2.5 % at 2 % noise on 200 points);
- the reported error estimates (which include the smoothing) cover the true error in at least
  95 % of a ladder of seeds;
- the smoothing report says what smoothing did, and matches a given noise level;
- the even default (issue 26): the smoothed surface has f'(0) = 0 (the even extension), the
  same as smoothing the mirrored table by scipy's make_smoothing_spline; a cone keeps its tip
  with axis="free";
- the Reinsch smoother is the minimiser scipy's make_smoothing_spline computes (second method);
- a table that stays non-monotone is diagnosed with radius and depth, and
  ``admissible="nearest"`` gives the nearest table with non-decreasing slopes (isotonic
  regression, checked against a brute-force projection).
"""
import numpy as np
import pytest

import contactlab as cl
from contactlab.errors import OutsideTheoryError, ParameterError
from contactlab.profiles import Cone, Paraboloid, PowerLaw, Tabulated
from contactlab.profiles.smoothing import _Smoother, nearest_admissible
from tests.tolerances import NOISY_TABLE_FORCE, NOISY_TABLE_RADIUS, SMOOTHER_SECOND_METHOD
from tests.tolerances import INTEGRATED_SLOPES

E = cl.Elastic(E=210e9, nu=0.3)
R_MAX = 1e-3
CASES = {"paraboloid": (lambda r: r**2 / 0.02, Paraboloid(R=0.01)),
         "cone": (lambda r: 0.1 * r, Cone(slope=0.1)),
         "n4": (lambda r: 1e9 * r**4, PowerLaw(c=1e9, n=4))}


def noisy(kind, n, frac, seed):
    f0, prof = CASES[kind]
    r = np.linspace(0.0, R_MAX, n)
    return r, f0(r) + frac * f0(R_MAX) * np.random.default_rng(seed).standard_normal(n), prof


@pytest.mark.parametrize("kind", sorted(CASES))
@pytest.mark.parametrize("n", [200, 2000])
@pytest.mark.parametrize("frac", [1e-3, 2e-2])
def test_auto_smoothing_recovers_the_closed_form_and_its_error_estimate_covers(kind, n, frac):
    covered = []
    for seed in range(5):
        r, f, prof = noisy(kind, n, frac, seed)
        # a measured cone is a real tip: the opt-out of the even axis (issue 26)
        axis = "free" if kind == "cone" else "even"
        c = cl.Contact(Tabulated(r, f, smoothing="auto", axis=axis), materials=(E, E))
        ref = cl.Contact(prof, materials=(E, E))
        d = ref.normal(radius=0.5 * R_MAX).depth
        s, s0 = c.normal(depth=d), ref.normal(depth=d)
        eF, ea = abs(s.force / s0.force - 1), abs(s.radius / s0.radius - 1)
        assert eF < NOISY_TABLE_FORCE and ea < NOISY_TABLE_RADIUS
        est = s.error_estimates
        covered += [eF <= est["force"], ea <= est["radius"]]
    assert np.mean(covered) >= 0.95


def test_report_and_noise_matching():
    r, f, _ = noisy("paraboloid", 400, 2e-3, 3)
    sigma = 2e-3 * R_MAX**2 / 0.02
    tab = Tabulated(r, f, smoothing="auto", noise=sigma)
    rep = tab.smoothing_report
    assert rep.method == "noise" and rep.noise == sigma
    assert rep.rms_change == pytest.approx(sigma, rel=1e-4)    # discrepancy principle
    assert rep.max_change >= rep.rms_change > 0 and 2 < rep.dof < 400
    gcv = Tabulated(r, f, smoothing="auto").smoothing_report
    assert gcv.method == "gcv" and gcv.noise == pytest.approx(sigma, rel=0.2)
    fixed = Tabulated(r, f, smoothing=rep.lam).smoothing_report
    assert fixed.method == "given" and fixed.rms_change == pytest.approx(rep.rms_change, rel=1e-9)
    assert Tabulated(r, f).smoothing_report is None


def test_reinsch_smoother_matches_scipy():
    from scipy.interpolate import make_smoothing_spline
    r, f, _ = noisy("n4", 300, 1e-2, 1)
    x = r / r[-1]
    for lam in (1e-7, 1e-4):
        ours = _Smoother(r, f).apply(f, lam)
        np.testing.assert_allclose(ours, make_smoothing_spline(x, f, lam=lam)(x),
                                   rtol=0, atol=SMOOTHER_SECOND_METHOD * np.max(np.abs(f)))


@pytest.mark.parametrize("start", [0.0, 2e-5])
def test_even_smoother_is_scipys_on_the_mirrored_table(start):
    from scipy.interpolate import make_smoothing_spline
    r, f, _ = noisy("paraboloid", 300, 1e-2, 4)
    r = start + r
    full_r = np.concatenate([-r[::-1][:r.size - (1 if start == 0 else 0)], r])
    full_f = np.concatenate([f[::-1][:r.size - (1 if start == 0 else 0)], f])
    x = full_r / r[-1]
    for lam in (1e-7, 1e-4):
        ours = _Smoother(r, f, even=True).apply(f, lam)
        spline = make_smoothing_spline(x, full_f, lam=lam)
        np.testing.assert_allclose(ours, spline(r / r[-1]), rtol=0,
                                   atol=SMOOTHER_SECOND_METHOD * np.max(np.abs(f)))
        # the even extension's spline is flat on the axis (to rounding of its coefficients)
        assert abs(spline.derivative()(0.0)) <= SMOOTHER_SECOND_METHOD * np.max(np.abs(f))


def test_axis_even_is_the_default_and_free_keeps_the_data_slope():
    r, f, _ = noisy("paraboloid", 200, 2e-2, 0)
    even = Tabulated(r, f, "cubic", smoothing="auto")
    free = Tabulated(r, f, "cubic", smoothing="auto", axis="free")
    assert even.axis == "even" and even.table_axis_slope() == 0.0
    # natural ends leave the noise's slope on the axis: a cone tip of the smoothed data
    assert free.table_axis_slope() != 0.0
    assert even != free
    lin = Tabulated(r, f)
    assert lin.table_axis_slope() == (lin.f[1] - lin.f[0]) / lin.r[1]


@pytest.mark.parametrize("bad", [{"smoothing": "gcv"}, {"smoothing": -1.0},
                                 {"noise": -1e-9}, {"admissible": "closest"},
                                 {"axis": "odd"}])
def test_invalid_options(bad):
    with pytest.raises(ParameterError, match=next(iter(bad))):
        Tabulated(np.linspace(0, 1e-3, 20), np.linspace(0, 1e-3, 20) ** 2, **bad)


def test_non_monotone_table_is_diagnosed_and_nearest_admissible_is_explicit():
    # a cone whose slope halves at r = 0.4 mm (g decreases beyond it), then steepens
    r = np.linspace(0.0, 1e-3, 101)
    f = np.where(r < 4e-4, 0.1 * r, np.where(r < 6e-4, 4e-5 + 0.05 * (r - 4e-4),
                                             5e-5 + 0.4 * (r - 6e-4)))
    c = cl.Contact(Tabulated(r, f), materials=(E, E))
    with pytest.raises(OutsideTheoryError, match=r"decreases at x=0.0004 m \(g=6.28319e-05 m.*admissible='nearest'"):
        c.normal(depth=1.2e-4)
    tab = Tabulated(r, f, admissible="nearest")
    slopes = np.diff(tab.f) / np.diff(tab.r)
    assert np.all(np.diff(slopes) >= -INTEGRATED_SLOPES * np.max(slopes))
    assert tab.smoothing_report.admissible_change > 0
    c2 = cl.Contact(tab, materials=(E, E))
    assert c2.normal(depth=1.2e-4).force > 0


def test_nearest_admissible_against_brute_force():
    from scipy.optimize import minimize
    rng = np.random.default_rng(5)
    r = np.sort(rng.uniform(0, 1, 8))
    r[0] = 0.0
    f = np.cumsum(rng.standard_normal(8)) ** 2 * 0.1
    h = np.diff(r)
    s = np.diff(f) / h
    # brute force: slopes ŝ with ŝ_0 >= 0 and ŝ_k - ŝ_{k-1} >= 0, min Σ h (s - ŝ)²
    cons = [{"type": "ineq", "fun": lambda q: q[0]},
            {"type": "ineq", "fun": lambda q: np.diff(q)}]
    res = minimize(lambda q: np.sum(h * (q - s) ** 2), np.full(s.size, max(s.mean(), 0)),
                   constraints=cons, method="SLSQP", options={"ftol": 1e-14, "maxiter": 500})
    expect = f[0] + np.concatenate([[0.0], np.cumsum(res.x * h)])
    np.testing.assert_allclose(nearest_admissible(r, f), expect, atol=1e-6)
