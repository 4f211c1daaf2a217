"""JKR fits (Heß's rule through the MDR) recover the parameters of retraction curves made from
the JKR closed forms written here (paraboloid, cone), with derivatives checked against finite
differences; the Tabor parameter says when the JKR limit does not hold."""
from __future__ import annotations

import numpy as np
import pytest

from contactlab import Elastic, errors
from contactlab.fit import indentation
from contactlab.fit._jkr import JKRPower
from contactlab.profiles import Cone, Paraboloid, Sphere
from tests.tolerances import FIT_RECOVERY

E, NU, R, Z0, W = 2e6, 0.5, 5e-6, 12e-9, 0.05
ESTAR = E / (1 - NU ** 2)
SAMPLE = Elastic(E=1e6, nu=NU)
#: JKR finite-difference check: central differences with relative step 1e-5 (truncation
#: ~1e-10, rounding ~1e-10 of the force scale), relative to the largest derivative
JKR_FD = 1e-7


def paraboloid_curve(n=2000, detached=300):
    """Fixed-grips retraction branch of a JKR paraboloid [JKR71], parametric in a; the branch
    end a_c = (π Δγ R²/(8E*))^(1/3) is left out by 1 % (the force jumps there)."""
    a_c = (np.pi * W * R * R / (8 * ESTAR)) ** (1 / 3)
    a = np.linspace(1.01 * a_c, 3e-6, n)
    d = a * a / R - np.sqrt(2 * np.pi * a * W / ESTAR)
    F = 4 * ESTAR * a ** 3 / (3 * R) - np.sqrt(8 * np.pi * a ** 3 * ESTAR * W)
    before = np.linspace(d[0] - 0.3 * (d[-1] - d[0]), d[0], detached, endpoint=False)
    return np.concatenate([before, d]) + Z0, np.concatenate([np.zeros(detached), F])


def test_branch_end_is_the_fixed_grips_pull_off():
    m = JKRPower(1.0 / R, 2.0)                  # g = a²/R
    a_c, d_c = m.critical(ESTAR, W)
    assert a_c == pytest.approx((np.pi * W * R * R / (8 * ESTAR)) ** (1 / 3), rel=1e-13)
    F = m.force(np.array([d_c]), ESTAR, W)[0][0]
    assert F == pytest.approx(-5 / 6 * np.pi * W * R, rel=1e-10)


def test_paraboloid_three_parameters():
    z, F = paraboloid_curve()
    res = indentation(z, F, Paraboloid(R=R), sample=SAMPLE, adhesion="jkr",
                      free=("E", "contact_point", "work_of_adhesion"))
    assert abs(res.params["E"] / E - 1) < FIT_RECOVERY
    assert abs(res.params["contact_point"] / Z0 - 1) < FIT_RECOVERY
    assert abs(res.params["work_of_adhesion"] / W - 1) < FIT_RECOVERY
    assert res.contact.work_of_adhesion == res.params["work_of_adhesion"]
    assert "JKR71" in res.citations


def test_paraboloid_with_force_offset():
    z, F = paraboloid_curve()
    res = indentation(z, F + 2e-9, Paraboloid(R=R), sample=SAMPLE, adhesion="jkr",
                      free=("E", "contact_point", "work_of_adhesion", "force_offset"))
    for k, v in {"E": E, "contact_point": Z0, "work_of_adhesion": W,
                 "force_offset": 2e-9}.items():
        assert abs(res.params[k] / v - 1) < FIT_RECOVERY, k


def test_fixed_work_of_adhesion():
    z, F = paraboloid_curve()
    res = indentation(z, F, Paraboloid(R=R), sample=SAMPLE, adhesion="jkr",
                      work_of_adhesion=W)
    assert abs(res.params["E"] / E - 1) < FIT_RECOVERY
    assert res.params["work_of_adhesion"] == W


def test_cone():
    s = 0.5                                     # g = (π/2) s a
    a_c = (np.sqrt(2 * np.pi * W / ESTAR) / (2 * np.pi / 2 * s)) ** 2
    a = np.linspace(1.01 * a_c, 20 * a_c, 1500)
    d = np.pi / 2 * s * a - np.sqrt(2 * np.pi * a * W / ESTAR)
    F = np.pi / 2 * ESTAR * s * a * a - np.sqrt(8 * np.pi * a ** 3 * ESTAR * W)
    before = np.linspace(d[0] - 0.2 * (d[-1] - d[0]), d[0], 200, endpoint=False)
    z, F = np.concatenate([before, d]) + Z0, np.concatenate([np.zeros(200), F])
    res = indentation(z, F, Cone(slope=s), sample=SAMPLE, adhesion="jkr",
                      free=("E", "contact_point", "work_of_adhesion"))
    assert abs(res.params["E"] / E - 1) < FIT_RECOVERY
    assert abs(res.params["work_of_adhesion"] / W - 1) < FIT_RECOVERY


@pytest.mark.parametrize("kc, n", [(1.0 / R, 2.0), (np.pi / 2 * 0.5, 1.0), (3e10, 3.0)])
def test_derivatives_against_finite_differences(kc, n):
    m = JKRPower(kc, n)
    _, d_c = m.critical(ESTAR, W)
    d = d_c + np.abs(d_c) * np.linspace(0.2, 30.0, 40) + 1e-9
    _, f_d, f_e, f_w = m.force(d, ESTAR, W)
    h = 1e-5
    for got, fun, x in [(f_d, lambda t: m.force(d + t * np.abs(d_c), ESTAR, W)[0], np.abs(d_c)),
                        (f_e, lambda t: m.force(d, ESTAR * (1 + t), W)[0], ESTAR),
                        (f_w, lambda t: m.force(d, ESTAR, W * (1 + t))[0], W)]:
        fd = (fun(h) - fun(-h)) / (2 * h)
        np.testing.assert_allclose(got * x, fd, rtol=0, atol=JKR_FD * np.max(np.abs(fd)))


def test_tabor_parameter():
    z, F = paraboloid_curve(n=400, detached=60)
    res = indentation(z, F, Paraboloid(R=R), sample=SAMPLE, adhesion="jkr",
                      free=("E", "contact_point", "work_of_adhesion"),
                      equilibrium_distance=0.3e-9)
    mu = (R * W * W / (ESTAR ** 2 * 0.3e-9 ** 3)) ** (1 / 3)
    assert res.meta["tabor_parameter"] == pytest.approx(mu, rel=1e-8)
    assert mu > 5 and not res.notes
    stiff = Elastic(E=1e6, nu=NU)
    with pytest.warns(errors.ValidityWarning, match="Tabor"):
        low = indentation(z * 1.0, F * 1e3, Paraboloid(R=R), sample=stiff, adhesion="jkr",
                    free=("E", "contact_point", "work_of_adhesion"),
                    equilibrium_distance=3e-8)
    assert any("Tabor" in n for n in low.notes)


def sphere_curve(a_max=2.5e-6, n=1700, detached=300):
    """Fixed-grips JKR branch of the exact sphere by Heß's rule, parametric in a:
    g = (a/2) ln((R+a)/(R-a)), ∫_0^a g = ((a²-R²)/2) artanh(a/R) + Ra/2,
    δ = g - sqrt(2πaΔγ/E*), F = 2E*(aδ - ∫g); the branch end (dδ/da = 0) located on a fine
    grid and left out by 1 %."""
    aa = np.linspace(1e-9, a_max, 200001)
    dd = aa / 2 * np.log((R + aa) / (R - aa)) - np.sqrt(2 * np.pi * aa * W / ESTAR)
    a = np.linspace(1.01 * aa[np.argmin(dd)], a_max, n)
    d = a / 2 * np.log((R + a) / (R - a)) - np.sqrt(2 * np.pi * a * W / ESTAR)
    F = 2 * ESTAR * (a * d - ((a * a - R * R) / 2 * np.arctanh(a / R) + R * a / 2))
    before = np.linspace(d[0] - 0.3 * (d[-1] - d[0]), d[0], detached, endpoint=False)
    return np.concatenate([before, d]) + Z0, np.concatenate([np.zeros(detached), F])


def test_exact_sphere_recovered():
    z, F = sphere_curve()
    res = indentation(z, F, Sphere(R=R), sample=SAMPLE, adhesion="jkr",
                      free=("E", "contact_point", "work_of_adhesion"))
    for k, want in {"E": E, "contact_point": Z0, "work_of_adhesion": W}.items():
        assert res.params[k] == pytest.approx(want, rel=FIT_RECOVERY)


def test_tabulated_sphere_within_the_tables_bound():
    """A measured sphere (2001 heights, 2 nm apart): the recovered parameters lie within the
    JKR table's stated error of g."""
    from contactlab.profiles import Tabulated
    z, F = sphere_curve()
    r = np.linspace(0.0, 4e-6, 2001)
    res = indentation(z, F, Tabulated(r, R - np.sqrt(R * R - r * r)), sample=SAMPLE,
                      adhesion="jkr", free=("E", "contact_point", "work_of_adhesion"))
    bound = res.meta["tip_model_errors"]["g"]
    assert 0 < bound < 0.05
    for k, want in {"E": E, "contact_point": Z0, "work_of_adhesion": W}.items():
        assert res.params[k] == pytest.approx(want, rel=bound), k


def test_table_route_matches_the_power_law_route():
    from contactlab.fit._jkr import JKRTable
    tab, pw = JKRTable(Paraboloid(R=R), 3e-6), JKRPower(1.0 / R, 2.0)
    _, d_c = pw.critical(ESTAR, W)
    d = d_c + np.abs(d_c) * np.linspace(0.01, 6.0, 200)          # a <= 2.8 µm (table 3 µm)
    for x, y in zip(tab.force(d, ESTAR, W), pw.force(d, ESTAR, W)):
        np.testing.assert_allclose(x, y, rtol=JKR_FD, atol=JKR_FD * np.max(np.abs(y)))


def test_table_derivatives_against_finite_differences():
    from contactlab.fit._jkr import JKRTable
    m = JKRTable(Sphere(R=R), 3e-6)
    _, d_c = m.critical(ESTAR, W)
    d = d_c + np.abs(d_c) * np.linspace(0.2, 8.0, 40) + 1e-9       # a <= 2.6 µm (table 3 µm)
    _, f_d, f_e, f_w = m.force(d, ESTAR, W)
    h = 1e-5
    for got, fun, x in [(f_d, lambda t: m.force(d + t * np.abs(d_c), ESTAR, W)[0], np.abs(d_c)),
                        (f_e, lambda t: m.force(d, ESTAR * (1 + t), W)[0], ESTAR),
                        (f_w, lambda t: m.force(d, ESTAR, W * (1 + t))[0], W)]:
        fd = (fun(h) - fun(-h)) / (2 * h)
        np.testing.assert_allclose(got * x, fd, rtol=0, atol=JKR_FD * np.max(np.abs(fd)))


def test_unsupported_tips():
    from contactlab.profiles import FlatPunch
    z, F = paraboloid_curve(n=200, detached=30)
    # a flat centre inside a wall (the flat punch alone is Kendall's, test_kendall.py; a
    # rounded end inside a wall, test_jkr_flat.py)
    from contactlab.profiles import TruncatedCone
    with pytest.raises(errors.NotSupportedError, match="wall"):
        indentation(z, F, FlatPunch(radius=1e-6) + TruncatedCone(radius=0.5e-6, slope=0.3),
                    sample=SAMPLE, adhesion="jkr", work_of_adhesion=W)
    with pytest.raises(errors.ParameterError, match="work_of_adhesion=-1"):
        indentation(z, F, Paraboloid(R=R), sample=SAMPLE, adhesion="jkr", work_of_adhesion=-1.0)


@pytest.mark.parametrize("adhesive", [False, True])
def test_solver_jacobian_against_finite_differences(monkeypatch, adhesive):
    """The residual and Jacobian handed to the solver (all four parameters, an elastic tip)
    agree with central finite differences at a point away from the solution."""
    import contactlab.fit._tip as tipmod
    seen = {}
    real = tipmod.levenberg_marquardt

    def spy(residual, jacobian, x0, **kw):
        seen.setdefault("fun", (residual, jacobian, np.array(x0, float)))
        return real(residual, jacobian, x0, **kw)

    monkeypatch.setattr(tipmod, "levenberg_marquardt", spy)
    z, F = paraboloid_curve(n=300, detached=40)
    kw = ({"adhesion": "jkr", "free": ("E", "contact_point", "work_of_adhesion")} if adhesive
          else {"free": ("E", "contact_point", "force_offset")})
    indentation(z, F + 1e-9, Paraboloid(R=R), sample=SAMPLE, tip=Elastic(E=5e6, nu=0.3), **kw)
    residual, jacobian, x0 = seen["fun"]
    x = x0 + np.array([0.05, 0.01, 0.02])[:x0.size]
    J = jacobian(x)
    h = 1e-7        # the branch end's curvature makes the truncation error large at 1e-6
    for i in range(x.size):
        e = np.zeros(x.size)
        e[i] = h
        fd = (residual(x + e) - residual(x - e)) / (2 * h)
        # the first attached point can sit where the branch's curvature is unbounded: there
        # the truncation error (~h²) of step h is large; Richardson's extrapolation of steps h
        # and h/10 removes it (its rounding error is larger elsewhere): each point must agree
        # with one of the two
        fd10 = (residual(x + e / 10) - residual(x - e / 10)) / (2 * h / 10)
        fd10 = (100.0 * fd10 - fd) / 99.0
        # points next to the branch end switch between attached and detached: compare where
        # the step does not move the branch end across a data point
        smooth = np.abs(residual(x + e) - residual(x - e)) < 1e3 * np.abs(J[:, i]).max() * h
        err = np.minimum(np.abs(J[:, i] - fd), np.abs(J[:, i] - fd10))
        assert np.max(err[smooth]) <= JKR_FD * np.max(np.abs(fd[smooth]))


@pytest.mark.slow
def test_coverage_of_the_95_percent_interval():
    """With noise, the 95 % intervals of E, the contact point and Δγ cover the truth in 90-99 %
    of 200 repetitions (fixed-grips branch of a paraboloid)."""
    rng = np.random.default_rng(32)
    free = ("E", "contact_point", "work_of_adhesion")
    hits = dict.fromkeys(free, 0)
    n = 200
    z, clean = paraboloid_curve()
    truth = {"E": E, "contact_point": Z0, "work_of_adhesion": W}
    noise = 1e-3 * float(np.max(np.abs(clean)))
    for _ in range(n):
        res = indentation(z, clean + rng.normal(0.0, noise, z.size), Paraboloid(R=R),
                          sample=SAMPLE, adhesion="jkr", free=free)
        ci = res.confidence(0.95)
        for k in free:
            hits[k] += ci[k][0] <= truth[k] <= ci[k][1]
    for k, v in hits.items():
        assert 0.90 * n <= v <= 0.99 * n, (k, v)


def test_tabor_parameter_reported_without_an_equilibrium_distance():
    """Every adhesive fit reports the Tabor parameter (closed form here): at z0 = 0.3 nm with
    its range over 0.2-0.5 nm; no warning when the whole range is inside the JKR limit."""
    z, F = paraboloid_curve(n=400, detached=60)
    res = indentation(z, F, Paraboloid(R=R), sample=SAMPLE, adhesion="jkr",
                      free=("E", "contact_point", "work_of_adhesion"))
    def mu(z0):
        return (R * W * W / (ESTAR ** 2 * z0 ** 3)) ** (1 / 3)
    assert res.meta["tabor_parameter"] == pytest.approx(mu(0.3e-9), rel=1e-8)
    lo, hi = res.meta["tabor_parameter_range"]
    assert (lo, hi) == (pytest.approx(mu(0.5e-9), rel=1e-8), pytest.approx(mu(0.2e-9), rel=1e-8))
    assert res.meta["equilibrium_distance"] == 0.3e-9 and "assumed" in res.meta["tabor_note"]
    assert not res.notes


def test_tabor_parameter_of_a_jkr_cone_uses_the_effective_radius():
    """A cone has no apex radius: the Tabor length is a/f'(a) at the deepest point, with
    Sneddon's a = 2δ/(π s) (independent of the fit's tip model)."""
    s = 0.5
    a = np.linspace(0.2e-6, 2e-6, 600)
    # JKR cone by Heß's rule: g = (π/2) s a, δ = g - sqrt(2πaΔγ/E*), F = 2E*(aδ - π s a²/4)
    d = np.pi / 2 * s * a - np.sqrt(2 * np.pi * a * W / ESTAR)
    F = 2 * ESTAR * (a * d - np.pi * s * a * a / 4)
    res = indentation(d + Z0, F, Cone(slope=s), sample=SAMPLE, adhesion="jkr",
                      free=("E", "contact_point", "work_of_adhesion"),
                      start={"contact_point": Z0})
    a_deep = 2 * d[-1] / (np.pi * s)            # the generating curve's deepest indentation
    rho = a_deep / s
    assert res.meta["tabor_parameter"] == pytest.approx(
        (rho * W * W / (ESTAR ** 2 * 0.3e-9 ** 3)) ** (1 / 3), rel=1e-6)
