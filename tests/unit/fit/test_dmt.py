"""DMT fits recover the parameters of curves made from closed forms written here: the MDR force
of the tip less the Derjaguin force of the rigid gap beyond the contact edge, 2πΔγ a/f'(a)
(paraboloid: 2πRΔγ [DMT75]; exact sphere: 2πΔγ sqrt(R² - a²); cone f = s r with Sneddon's
a = 2δ/(π s): 2πΔγ a/s; power law, sum, truncated cone, a measured tip); the derivatives of the
effective radius a/f'(a) match finite differences; the Tabor parameter warns outside the DMT
range; a wall and a flat apex are refused by name."""
from __future__ import annotations

import warnings

import numpy as np
import pytest

from contactlab import Elastic, errors
from contactlab.fit import indentation
from scipy.special import gamma

from contactlab.fit._dmt import DMTModel
from contactlab.fit._tip import TipModel
from contactlab.profiles import (
    Cone,
    FlatPunch,
    Paraboloid,
    PowerLaw,
    Sphere,
    Tabulated,
    TruncatedCone,
)
from tests.tolerances import FIT_CLOSED_FORM_ROUNDING, FIT_JACOBIAN_FD, FIT_RECOVERY

# the synthetic curves use AFM-like soft samples (Tabor parameters far above 0.1): these tests
# are about recovery and derivatives, so the DMT-range warning is tested on its own below
pytestmark = pytest.mark.filterwarnings(
    "ignore:Tabor parameter:contactlab.errors.ValidityWarning")

E, NU, R, Z0, W = 2e6, 0.5, 5e-6, 12e-9, 0.05
ESTAR = E / (1 - NU ** 2)
SAMPLE = Elastic(E=1e6, nu=NU)
Z = np.linspace(-60e-9, 240e-9, 2000)
ALL = ("E", "contact_point", "work_of_adhesion", "force_offset")


def dmt_paraboloid(z, off=0.0):
    d = np.maximum(z - Z0, 0.0)
    return 4 / 3 * ESTAR * np.sqrt(R) * d ** 1.5 - 2 * np.pi * R * W * (z > Z0) + off


@pytest.mark.parametrize("off", [0.0, 2e-9])
def test_paraboloid_recovered(off):
    res = indentation(Z, dmt_paraboloid(Z, off), Paraboloid(R=R), sample=SAMPLE,
                      adhesion="dmt", free=ALL)
    for k, want in {"E": E, "contact_point": Z0, "work_of_adhesion": W}.items():
        assert res.params[k] == pytest.approx(want, rel=FIT_RECOVERY)
    assert res.params["force_offset"] == pytest.approx(off, abs=FIT_RECOVERY * 2 * np.pi * R * W)
    assert res.meta["effective_radius"] == R
    assert res.meta["dmt_route"] == "constant"
    assert res.contact.work_of_adhesion is None          # DMT is not the contact's JKR model


def test_exact_sphere_recovered():
    a = np.linspace(0.0, 1.5e-6, 1500)[1:]
    d = a / 2 * np.log((R + a) / (R - a))
    F = (ESTAR * ((a * a + R * R) / 2 * np.log((R + a) / (R - a)) - a * R)
         - 2 * np.pi * W * np.sqrt(R * R - a * a))
    before = np.linspace(-0.2 * d[-1], 0.0, 200)
    z = np.concatenate([before, d]) + Z0
    force = np.concatenate([np.zeros(200), F])
    res = indentation(z, force, Sphere(R=R), sample=SAMPLE, adhesion="dmt",
                      free=("E", "contact_point", "work_of_adhesion"))
    for k, want in {"E": E, "contact_point": Z0, "work_of_adhesion": W}.items():
        assert res.params[k] == pytest.approx(want, rel=FIT_RECOVERY)
    assert res.meta["effective_radius"] == pytest.approx(np.sqrt(R * R - a[-1] ** 2),
                                                         rel=FIT_CLOSED_FORM_ROUNDING)


def test_fixed_work_of_adhesion():
    res = indentation(Z, dmt_paraboloid(Z), Paraboloid(R=R), sample=SAMPLE, adhesion="dmt",
                      work_of_adhesion=W)
    assert res.params["E"] == pytest.approx(E, rel=FIT_RECOVERY)
    assert res.params["work_of_adhesion"] == W


def test_tabor_parameter_warns_outside_dmt():
    with pytest.warns(errors.ValidityWarning, match="outside the DMT limit"):
        res = indentation(Z, dmt_paraboloid(Z), Paraboloid(R=R), sample=SAMPLE, adhesion="dmt",
                          free=("E", "contact_point", "work_of_adhesion"),
                          equilibrium_distance=0.3e-9)
    mu = (R * W * W / (ESTAR ** 2 * 0.3e-9 ** 3)) ** (1 / 3)
    assert res.meta["tabor_parameter"] == pytest.approx(mu, rel=1e-6)
    # a stiff sample and a sharp tip: inside the DMT range, no warning
    Rs, Es, z0 = 10e-9, 100e9, 0.3e-9
    zz = np.linspace(-0.5e-9, 2e-9, 400)
    dd = np.maximum(zz - 0.2e-9, 0.0)
    es = Es / (1 - 0.3 ** 2)
    ff = 4 / 3 * es * np.sqrt(Rs) * dd ** 1.5 - 2 * np.pi * Rs * W * (zz > 0.2e-9)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        res = indentation(zz, ff, Paraboloid(R=Rs), sample=Elastic(E=1e9, nu=0.3),
                          adhesion="dmt", free=("E", "contact_point", "work_of_adhesion"),
                          equilibrium_distance=z0)
    assert res.meta["tabor_parameter"] < 0.1
    assert res.params["E"] == pytest.approx(Es, rel=FIT_RECOVERY)


def test_refusals():
    with pytest.raises(errors.NotSupportedError, match="wall"):
        indentation(Z, dmt_paraboloid(Z), FlatPunch(radius=1e-6), sample=SAMPLE,
                    adhesion="dmt", work_of_adhesion=W)
    with pytest.raises(errors.NotSupportedError, match="flat at the contact's onset"):
        indentation(Z, dmt_paraboloid(Z), PowerLaw(c=1e18, n=4.0), sample=SAMPLE,
                    adhesion="dmt", work_of_adhesion=W)
    with pytest.raises(errors.ParameterError, match="work of adhesion"):
        indentation(Z, dmt_paraboloid(Z), Paraboloid(R=R), sample=SAMPLE, adhesion="dmt")
    with pytest.raises(errors.ParameterError, match="adhesion='vdw'"):
        indentation(Z, dmt_paraboloid(Z), Paraboloid(R=R), sample=SAMPLE, adhesion="vdw")


# ---- any tip: the Derjaguin force of the rigid gap, 2πΔγ a/f'(a) ----
WP = 0.005                          # a smaller Δγ: the cone's force minimum lies inside the data
D = np.maximum(Z - Z0, 0.0)


def kappa(n):
    """MDR factor of c r^n: g = κ_n c a^n, κ_n = √π Γ(n/2 + 1)/Γ(n/2 + 1/2)."""
    return np.sqrt(np.pi) * gamma(n / 2 + 1) / gamma(n / 2 + 0.5)


def power_curve(c, n, d=D, w=WP):
    """F = 2E* n/(n+1) κ c a^(n+1) (the MDR force of c r^n) - 2πΔγ a^(2-n)/(n c)."""
    a = (d / (kappa(n) * c)) ** (1 / n)
    return 2 * ESTAR * n / (n + 1) * kappa(n) * c * a ** (n + 1) - 2 * np.pi * w * a ** (2 - n) / (n * c)


def check(res, w=WP, off=None):
    for k, want in {"E": E, "contact_point": Z0, "work_of_adhesion": w}.items():
        assert res.params[k] == pytest.approx(want, rel=FIT_RECOVERY), k
    if off is not None:
        assert res.params["force_offset"] == pytest.approx(off, rel=FIT_RECOVERY)


def test_cone_sneddon():
    s = 0.3
    a = 2 * D / (np.pi * s)                     # Sneddon: δ = (π/2) a s
    F = 2 / np.pi * ESTAR * D * D / s - 2 * np.pi * WP * a / s + 1e-10
    res = indentation(Z, F, Cone(slope=s), sample=SAMPLE, adhesion="dmt", free=ALL)
    check(res, off=1e-10)
    assert res.meta["dmt_route"] == "power"
    # the same tip by its half angle: tan θ = 1/s
    res2 = indentation(Z, F, Cone(half_angle=np.arctan(1 / s)), sample=SAMPLE, adhesion="dmt",
                       free=ALL)
    check(res2, off=1e-10)


def test_power_law_one_and_a_half():
    c, n = 2e2, 1.5
    res = indentation(Z, power_curve(c, n), PowerLaw(c=c, n=n), sample=SAMPLE, adhesion="dmt",
                      free=("E", "contact_point", "work_of_adhesion"))
    check(res)


def test_sum_of_a_paraboloid_and_a_cone():
    """f = r²/(2R) + s r: a/f'(a) = a/(a/R + s); the contact radius from δ = a²/R + (π/2) s a."""
    s = 0.05
    a = np.linspace(0.0, 2.5e-7, 1500)[1:]
    d = a * a / R + np.pi / 2 * s * a
    F = (2 * ESTAR * (a * d - a ** 3 / (3 * R) - np.pi / 4 * s * a * a)
         - 2 * np.pi * WP * a / (a / R + s))
    z = np.concatenate([np.linspace(-0.2 * d[-1], 0.0, 200), d]) + Z0
    force = np.concatenate([np.zeros(200), F])
    res = indentation(z, force, Paraboloid(R=R) + Cone(slope=s), sample=SAMPLE, adhesion="dmt",
                      free=("E", "contact_point", "work_of_adhesion"))
    check(res)


def test_truncated_cone():
    """A flat centre of radius b and a flank of slope s: g = s a arccos(b/a),
    ∫_0^a g = s (a²/2 arccos(b/a) - b/2 sqrt(a² - b²)), a/f'(a) = a/s (a step 2πΔγ b/s at
    the contact point)."""
    b, s = 0.3e-6, 0.3
    a = b * (1 + np.geomspace(1e-6, 1.5, 1500))
    d = s * a * np.arccos(b / a)
    F = (2 * ESTAR * (a * d - s * (a * a / 2 * np.arccos(b / a) - b / 2 * np.sqrt(a * a - b * b)))
         - 2 * np.pi * WP * a / s)
    z = np.concatenate([np.linspace(-0.2 * d[-1], 0.0, 200), d]) + Z0
    force = np.concatenate([np.zeros(200), F])
    res = indentation(z, force, TruncatedCone(radius=b, slope=s), sample=SAMPLE,
                      adhesion="dmt", free=("E", "contact_point", "work_of_adhesion"))
    check(res)


def sphere_dmt(a_max):
    a = np.linspace(0.0, a_max, 1500)[1:]
    d = a / 2 * np.log((R + a) / (R - a))
    F = (ESTAR * ((a * a + R * R) / 2 * np.log((R + a) / (R - a)) - a * R)
         - 2 * np.pi * WP * np.sqrt(R * R - a * a))
    z = np.concatenate([np.linspace(-0.2 * d[-1], 0.0, 200), d]) + Z0
    return z, np.concatenate([np.zeros(200), F])


def test_measured_sphere_tip_within_its_table_error():
    """A cubic table of the sphere: E, the contact point and Δγ within the table's own
    distance from the sphere (its force and its a/f'(a), over the data) and the fit's reported
    model errors."""
    z, F = sphere_dmt(0.4 * R)
    r = np.linspace(0.0, 0.5 * R, 4001)
    tab = Tabulated(r, R - np.sqrt(R * R - r * r), interpolation="cubic")
    res = indentation(z, F, tab, sample=SAMPLE, adhesion="dmt",
                      free=("E", "contact_point", "work_of_adhesion"))
    assert res.meta["dmt_route"] == "table"
    a = np.linspace(0.05 * R, 0.4 * R, 50)
    d = a / 2 * np.log((R + a) / (R - a))
    at = tab._radius_of_depth(d, 1e-12)
    phi_tab = 2 * (at * d - tab._g_integral(at, 1e-12))
    phi = (a * a + R * R) / 2 * np.log((R + a) / (R - a)) - a * R
    rho_tab = at / tab.derivative(at)
    bound = (np.max(np.abs(phi_tab / phi - 1)) + np.max(np.abs(rho_tab / np.sqrt(R * R - a * a) - 1))
             + sum(res.meta["tip_model_errors"].values()))
    assert 0 < bound < 1e-5
    for k, want in {"E": E, "work_of_adhesion": WP}.items():
        assert res.params[k] == pytest.approx(want, rel=10 * bound), k
    assert res.params["contact_point"] == pytest.approx(Z0, abs=10 * bound * float(z[-1]))


def test_measured_cone_tip():
    """A cubic table of a cone (its slope kept on the axis): a pointed apex, ρ(0) = 0 (no step
    at the contact point), recovered like the closed-form cone within the table's errors."""
    s = 0.3
    a = 2 * D / (np.pi * s)
    F = 2 / np.pi * ESTAR * D * D / s - 2 * np.pi * WP * a / s
    r = np.linspace(0, 2e-6, 401)
    tab = Tabulated(r, s * r, interpolation="cubic", axis="free")
    res = indentation(Z, F, tab, sample=SAMPLE, adhesion="dmt",
                      free=("E", "contact_point", "work_of_adhesion"))
    assert res.meta["dmt_route"] == "table"
    bound = sum(res.meta["tip_model_errors"].values())
    assert bound < 1e-10
    check(res)


def test_linear_table_warns_that_its_effective_radius_is_not_smooth():
    """A linear table's slope is constant on each interval: a/f'(a) is a saw-tooth, and the
    fit says so (the cubic table of the same points does not warn, see above)."""
    z, F = sphere_dmt(0.4 * R)
    r = np.linspace(0.0, 0.5 * R, 4001)
    with pytest.warns(errors.ValidityWarning, match="not smooth"):
        res = indentation(z, F, Tabulated(r, R - np.sqrt(R * R - r * r)), sample=SAMPLE,
                          adhesion="dmt", free=("E", "contact_point", "work_of_adhesion"))
    assert res.meta["tip_model_errors"]["dmt_radius"] > 1e-3


PROFILES = [Cone(slope=0.3), PowerLaw(c=2e2, n=1.5), Sphere(R=R),
            Paraboloid(R=R) + Cone(slope=0.05), TruncatedCone(radius=0.3e-6, slope=0.3),
            Tabulated(np.linspace(0, 2e-6, 301), np.linspace(0, 2e-6, 301) ** 2 / (2 * R),
                      interpolation="cubic")]


@pytest.mark.parametrize("profile", PROFILES)
def test_effective_radius_slope_is_the_derivative(profile):
    """dρ/dδ (the contact-point column of the Jacobian, with 2E*a and -2π ρ for Δγ) against a
    central difference of the model's own ρ(a(δ)); and da/dδ of the tip model."""
    m = TipModel(profile, 3e-7)
    dm = DMTModel(profile, m)
    d = np.linspace(2e-9, 2.5e-7, 40)
    h = 1e-6 * d
    fd = (dm(d + h)[0] - dm(d - h)[0]) / (2 * h)
    # absolute part: on the scale ρ/δ of the slope (a near-constant ρ has a slope near 0)
    np.testing.assert_allclose(dm(d)[1], fd, rtol=FIT_JACOBIAN_FD,
                               atol=FIT_JACOBIAN_FD * np.max(dm(d)[0]) / d[-1])
    fa = (m.radius(d + h)[0] - m.radius(d - h)[0]) / (2 * h)
    np.testing.assert_allclose(m.radius(d)[1], fa, rtol=FIT_JACOBIAN_FD)


@pytest.mark.parametrize("profile", [PROFILES[0], PROFILES[2], PROFILES[4], PROFILES[5]])
def test_solver_jacobian_against_finite_differences(profile, monkeypatch):
    """The residual and Jacobian handed to the solver (E, contact point, Δγ and offset, an
    elastic tip) agree with central differences at a point away from the solution; samples
    that change sides of the contact point within the step are left out."""
    import contactlab.fit._tip as tipmod
    seen = {}
    real = tipmod.levenberg_marquardt

    def spy(residual, jacobian, x0, **kw):
        seen.setdefault("fn", (residual, jacobian, x0))
        return real(residual, jacobian, x0, **kw)

    monkeypatch.setattr(tipmod, "levenberg_marquardt", spy)
    d = np.linspace(0.0, 2.4e-7, 400)
    z = np.concatenate([np.linspace(-6e-8, 0.0, 100, endpoint=False), d]) + Z0
    m = TipModel(profile, 4e-7)
    phi = m(z - Z0)[0]
    F = ESTAR * phi - 2 * np.pi * WP * DMTModel(profile, m)(z - Z0)[0] + 1e-10
    indentation(z, F, profile, sample=SAMPLE, tip=Elastic(E=1e9, nu=0.3), adhesion="dmt",
                free=ALL)
    residual, jacobian, x0 = seen["fn"]
    x = np.asarray(x0, float) + 0.01
    J = jacobian(x)
    for i in range(x.size):
        h = 1e-6 * max(abs(x[i]), 1.0)
        e = np.zeros_like(x)
        e[i] = h
        rp, r0, rm = residual(x + e), residual(x), residual(x - e)
        fd = (rp - rm) / (2 * h)
        smooth = np.abs((rp - r0) - (r0 - rm)) <= 1e-3 * np.abs(rp - rm) + 1e-30
        np.testing.assert_allclose(J[smooth, i], fd[smooth], rtol=FIT_JACOBIAN_FD,
                                   atol=FIT_JACOBIAN_FD * np.max(np.abs(fd)))


@pytest.mark.parametrize("profile", PROFILES[:4])
def test_effective_radius_closed_forms(profile):
    """ρ(a) = a/f'(a) against the profile's own slope, at its own contact radius."""
    m = TipModel(profile, 3e-7)
    dm = DMTModel(profile, m)
    d = np.linspace(2e-9, 2.5e-7, 20)
    a = profile._radius_of_depth(d, 1e-14)
    np.testing.assert_allclose(dm(d)[0], a / profile.derivative(a),
                               rtol=FIT_CLOSED_FORM_ROUNDING)


def test_tabor_parameter_of_a_cone_uses_the_effective_radius():
    s = 0.3
    a = 2 * D / (np.pi * s)
    F = 2 / np.pi * ESTAR * D * D / s - 2 * np.pi * WP * a / s
    with pytest.warns(errors.ValidityWarning, match="outside the DMT limit"):
        res = indentation(Z, F, Cone(slope=s), sample=SAMPLE, adhesion="dmt",
                          free=("E", "contact_point", "work_of_adhesion"),
                          equilibrium_distance=0.3e-9)
    rho = 2 * (Z[-1] - Z0) / (np.pi * s) / s
    assert res.meta["effective_radius"] == pytest.approx(rho, rel=FIT_RECOVERY)
    mu = (rho * WP * WP / (ESTAR ** 2 * 0.3e-9 ** 3)) ** (1 / 3)
    assert res.meta["tabor_parameter"] == pytest.approx(mu, rel=FIT_RECOVERY)


@pytest.mark.slow
def test_coverage_of_the_95_percent_interval():
    """With noise, the 95 % intervals of E, the contact point and Δγ cover the truth in 90-99 %
    of 200 repetitions."""
    rng = np.random.default_rng(31)
    free = ("E", "contact_point", "work_of_adhesion")
    hits = dict.fromkeys(free, 0)
    n = 200
    clean = dmt_paraboloid(Z)
    truth = {"E": E, "contact_point": Z0, "work_of_adhesion": W}
    for _ in range(n):
        res = indentation(Z, clean + rng.normal(0.0, 3e-10, Z.size), Paraboloid(R=R),
                          sample=SAMPLE, adhesion="dmt", free=free)
        ci = res.confidence(0.95)
        for k in free:
            hits[k] += ci[k][0] <= truth[k] <= ci[k][1]
    for k, v in hits.items():
        assert 0.90 * n <= v <= 0.99 * n, (k, v)


@pytest.mark.slow
def test_coverage_of_the_95_percent_interval_on_a_cone():
    """The pointed tip's start (a search over contact points with the linear parameters
    projected out) and fit: the 95 % intervals of E, the contact point and Δγ cover the truth
    in 90-99 % of 200 repetitions."""
    rng = np.random.default_rng(17)
    s = 0.3
    clean = 2 / np.pi * ESTAR * D * D / s - 2 * np.pi * WP * (2 * D / (np.pi * s)) / s
    truth = {"E": E, "contact_point": Z0, "work_of_adhesion": WP}
    hits = dict.fromkeys(truth, 0)
    n = 200
    for _ in range(n):
        res = indentation(Z, clean + rng.normal(0.0, 2e-10, Z.size), Cone(slope=s),
                          sample=SAMPLE, adhesion="dmt", free=ALL)
        ci = res.confidence(0.95)
        for k in truth:
            hits[k] += ci[k][0] <= truth[k] <= ci[k][1]
    for k, v in hits.items():
        assert 0.90 * n <= v <= 0.99 * n, (k, v)


def test_tabor_warning_without_an_equilibrium_distance_only_when_the_range_is_outside():
    """Without z0 the DMT warning is raised only when the Tabor parameter exceeds 0.1 for every
    z0 in 0.2-0.5 nm; a stiff sample and a sharp tip stay silent and report the value."""
    with warnings.catch_warnings():
        warnings.simplefilter("default")
        with pytest.warns(errors.ValidityWarning, match="for every equilibrium distance"):
            indentation(Z, dmt_paraboloid(Z), Paraboloid(R=R), sample=SAMPLE, adhesion="dmt",
                        free=("E", "contact_point", "work_of_adhesion"))
    Rs, Es = 10e-9, 100e9
    zz = np.linspace(-0.5e-9, 2e-9, 400)
    dd = np.maximum(zz - 0.2e-9, 0.0)
    es = Es / (1 - 0.3 ** 2)
    ff = 4 / 3 * es * np.sqrt(Rs) * dd ** 1.5 - 2 * np.pi * Rs * W * (zz > 0.2e-9)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        res = indentation(zz, ff, Paraboloid(R=Rs), sample=Elastic(E=1e9, nu=0.3),
                          adhesion="dmt", free=("E", "contact_point", "work_of_adhesion"))
    lo, hi = res.meta["tabor_parameter_range"]
    assert lo < res.meta["tabor_parameter"] < hi < 0.1
    assert res.meta["tabor_parameter"] == pytest.approx(
        (Rs * W * W / (es ** 2 * 0.3e-9 ** 3)) ** (1 / 3), rel=1e-6)
