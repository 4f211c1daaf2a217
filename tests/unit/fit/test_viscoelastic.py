"""Viscoelastic fits (Lee-Radok on the approach, Ting on the retract, through the MDR) recover
the parameters of approach-retract curves made here from Ting's solution for a paraboloid on a
linear ramp, evaluated independently with mpmath quadrature; the model's derivatives are
checked against finite differences; bad input names what is wrong."""
from __future__ import annotations

import mpmath as mp
import numpy as np
import pytest

from contactlab import Elastic, errors
from contactlab.fit import indentation
from contactlab.fit._ting import TingModel
from contactlab.fit._tip import TipModel
from contactlab.materials.viscoelastic import (
    GeneralizedMaxwell,
    KelvinVoigt,
    Maxwell,
    StandardLinearSolid,
)
from contactlab.profiles import Paraboloid
from tests.tolerances import FIT_JACOBIAN_FD, FIT_RECOVERY, FIT_TING_MODEL

R, V, TM, Z0 = 5e-6, 1e-6, 0.5, 20e-9
SLS = dict(G_inf=1e4, G_1=3e4, eta_1=1.2e4)            # tau = 0.4 s


def ting_reference(t, g_inf, arms, v=V, tm=TM):
    """Force of a rigid paraboloid (radius R) on an incompressible half-space with
    G(t) = g_inf + Σ G_k exp(-t/τ_k) (E*(t) = 4G(t)) for the indentation v·s up to tm and
    v·(2tm - s) after (s = 0 at contact): Lee-Radok while the contact grows; Ting's t1 from
    ∫_{t1}^{t} G(t - s) δ'(s) ds = 0 (closed form for the ramp), then
    F = 4∫_0^{t1} G(t - s) dΦ(s) with Φ = (4/3)√R δ^{3/2}; zero once the condition has no
    root in (0, tm). Quadrature by mpmath at 25 digits."""
    mp.mp.dps = 25

    def G(x):
        return g_inf + sum(gk * mp.e ** (-x / tk) for gk, tk in arms)

    def dphi(s):                          # dΦ/ds = 2√(R δ) δ'
        return 2 * mp.sqrt(R * v * s) * v

    def prim(a, b, t):                    # ∫_a^b G(t - s) ds
        return g_inf * (b - a) + sum(gk * tk * (mp.e ** (-(t - b) / tk) - mp.e ** (-(t - a) / tk))
                                     for gk, tk in arms)
    out = []
    for x in t:
        x = mp.mpf(float(x))
        if x <= 0:
            out.append(0.0)
            continue
        if x <= tm:
            out.append(float(4 * mp.quad(lambda s, x=x: G(x - s) * dphi(s), [0, x])))
            continue

        def D(t1, x=x):
            return v * prim(t1, tm, x) - v * prim(tm, x, x)
        if D(mp.mpf(0)) <= 0:
            out.append(0.0)
            continue
        t1 = mp.findroot(D, (mp.mpf(0), mp.mpf(tm)), solver="anderson")
        out.append(float(4 * mp.quad(lambda s, x=x: G(x - s) * dphi(s), [0, t1])))
    return np.array(out)


def ramp(n_app=101, n_ret=101, t_pre=0.1, t_end=2 * TM + 0.05):
    """Sample times (one sample at the turning point) and indenter positions."""
    t = np.concatenate([np.linspace(-t_pre, TM, n_app), np.linspace(TM, t_end, n_ret)[1:]])
    return t, np.where(t <= TM, Z0 + V * t, Z0 + V * TM - V * (t - TM))


@pytest.fixture(scope="module")
def sls_curve():
    t, z = ramp()
    return t, z, ting_reference(t, SLS["G_inf"], [(SLS["G_1"], SLS["eta_1"] / SLS["G_1"])])


@pytest.fixture(scope="module")
def prony_curve():
    t, z = ramp()
    return t, z, ting_reference(t, 1e4, [(3e4, 0.05), (2e4, 0.8)])


def test_model_matches_tings_solution(sls_curve):
    t, z, F = sls_curve
    m = TingModel(t, z, TipModel(Paraboloid(R=R), 1e-6))
    f = m(SLS["G_inf"], np.array([SLS["G_1"]]), np.array([SLS["eta_1"] / SLS["G_1"]]), Z0)[0]
    assert np.max(np.abs(f - F)) < FIT_TING_MODEL * np.max(F)
    assert F[-1] == 0.0 and f[-1] == 0.0            # the tip has left the surface


def test_standard_linear_solid_recovered(sls_curve):
    t, z, F = sls_curve
    tmpl = StandardLinearSolid(G_inf=3e4, G_1=1e4, eta_1=1e4)
    res = indentation(z, F, Paraboloid(R=R), time=t, sample=tmpl,
                      free=("G_inf", "G_1", "eta_1", "contact_point"))
    for k, want in {**SLS, "contact_point": Z0}.items():
        assert res.params[k] == pytest.approx(want, rel=FIT_RECOVERY)
    assert isinstance(res.contact.materials[1], StandardLinearSolid)
    assert res.meta["x_name"] == "time"


def test_standard_linear_solid_with_offset(sls_curve):
    t, z, F = sls_curve
    tmpl = StandardLinearSolid(G_inf=2e4, G_1=2e4, eta_1=2e4)
    res = indentation(z, F + 2e-9, Paraboloid(R=R), time=t, sample=tmpl,
                      free=("G_inf", "G_1", "eta_1", "contact_point", "force_offset"))
    for k, want in {**SLS, "contact_point": Z0, "force_offset": 2e-9}.items():
        assert res.params[k] == pytest.approx(want, rel=FIT_RECOVERY)


def test_prony_series_recovered(prony_curve):
    t, z, F = prony_curve
    tmpl = GeneralizedMaxwell(2e4, moduli=[2e4, 1e4], relaxation_times=[0.1, 0.5])
    res = indentation(z, F, Paraboloid(R=R), time=t, sample=tmpl,
                      free=("G_inf", "moduli", "relaxation_times", "contact_point"))
    want = {"G_inf": 1e4, "moduli[0]": 3e4, "relaxation_times[0]": 0.05, "moduli[1]": 2e4,
            "relaxation_times[1]": 0.8, "contact_point": Z0}
    for k, w in want.items():
        assert res.params[k] == pytest.approx(w, rel=FIT_RECOVERY)


@pytest.mark.parametrize("material", [
    StandardLinearSolid(G_inf=1e4, G_1=3e4, eta_1=1.2e4),
    GeneralizedMaxwell(1e4, moduli=[3e4, 2e4], relaxation_times=[0.05, 0.8]),
    Maxwell(G=3e4, eta=3e4),                  # loses contact early in the retract
])
def test_jacobian_against_finite_differences(material):
    from contactlab.fit.viscoelastic import _chain, _prony, _values
    t, z = ramp(n_app=301, n_ret=301)
    m = TingModel(t, z, TipModel(Paraboloid(R=R), 2e-6))
    cls = type(material)
    z0 = Z0 + 0.3 * V * (t[1] - t[0])         # between samples: F ~ δ^(3/2) has a kink at 0
    v0 = {**_values(material), "contact_point": z0}

    def force(v):
        return m(*_prony(cls, v), v["contact_point"])[0]
    _, dGi, dGk, dtk, dz0 = m(*_prony(cls, v0), z0)
    jac = {**_chain(cls, v0, dGi, dGk, dtk), "contact_point": dz0}
    for name, col in jac.items():
        h = 1e-6 * v0[name]
        fd = (force({**v0, name: v0[name] + h}) - force({**v0, name: v0[name] - h})) / (2 * h)
        assert np.max(np.abs(col - fd)) < FIT_JACOBIAN_FD * np.max(np.abs(fd)), name


def test_retract_loses_contact_for_a_fluid():
    t, z = ramp()
    m = TingModel(t, z, TipModel(Paraboloid(R=R), 1e-6))
    f = m(0.0, np.array([3e4]), np.array([1.0]), Z0)[0]
    ref = ting_reference(t[::10], 0.0, [(3e4, 1.0)])
    assert np.max(np.abs(f[::10] - ref)) < FIT_TING_MODEL * np.max(ref)


def test_bad_input_named(sls_curve):
    t, z, F = sls_curve
    prof, tmpl = Paraboloid(R=R), StandardLinearSolid(**SLS)
    with pytest.raises(errors.NotSupportedError, match="Kelvin-Voigt"):
        indentation(z, F, prof, time=t, sample=KelvinVoigt(G=1e4, eta=1e3))
    with pytest.raises(errors.ParameterError, match="time has"):
        indentation(z, F, prof, time=t[:-1], sample=tmpl)
    with pytest.raises(errors.ParameterError, match="time"):
        indentation(z, F, prof, time=t[::-1], sample=tmpl)
    bumpy = z.copy()
    bumpy[20] -= 1e-8
    with pytest.raises(errors.ParameterError, match=r"depth\[20\]"):
        indentation(bumpy, F, prof, time=t, sample=tmpl)
    with pytest.raises(errors.UnknownNameError, match="E"):
        indentation(z, F, prof, time=t, sample=tmpl, free=("E",))
    with pytest.raises(errors.NotSupportedError, match="rigid tip"):
        indentation(z, F, prof, time=t, sample=tmpl, tip=Elastic(E=1e9, nu=0.3))
    with pytest.raises(errors.ParameterError, match=r"time=\.\.\."):
        indentation(z, F, prof, sample=tmpl)
    tt = t.copy()
    tt[3] = np.nan
    with pytest.raises(errors.ParameterError, match=r"time\[3\]"):
        indentation(z, F, prof, time=tt, sample=tmpl)


@pytest.mark.parametrize("kw, err, text", [
    ({"start": {"G_inf": 0.0}}, errors.ParameterError, r"start\['G_inf'\]=0.0 is invalid"),
    ({"start": {"eta_1": -1.0}}, errors.ParameterError, r"start\['eta_1'\]=-1.0 is invalid"),
    ({"start": {"G_1": "x"}}, errors.ParameterError, r"start\['G_1'\]='x' is invalid"),
    ({"start": {"contact_point": np.inf}}, errors.ParameterError,
     r"start\['contact_point'\]=inf is invalid"),
    ({"start": (1, 2)}, errors.ParameterError, r"start=\(1, 2\) is invalid"),
    ({"start": {"tau": 1.0}}, errors.UnknownNameError, "'tau', which is not fitted"),
    ({"free": 3}, errors.ParameterError, "free=3 is invalid"),
    ({"work_of_adhesion": 0.05}, errors.ParameterError, "given but adhesion=None"),
])
def test_bad_arguments_named(sls_curve, kw, err, text):
    """Each was a bare Python or numpy error, or silently ignored."""
    t, z, F = sls_curve
    with pytest.raises(err, match=text):
        indentation(z, F, Paraboloid(R=R), time=t, sample=StandardLinearSolid(**SLS), **kw)


@pytest.mark.slow
def test_coverage_of_the_95_percent_interval(sls_curve):
    """With noise, the 95 % intervals of the standard linear solid's parameters and the contact
    point cover the truth in 90-99 % of 200 repetitions (Ting's solution, approach and
    retract)."""
    t, z, clean = sls_curve
    rng = np.random.default_rng(33)
    free = ("G_inf", "G_1", "eta_1", "contact_point")
    hits = dict.fromkeys(free, 0)
    n = 200
    truth = {**SLS, "contact_point": Z0}
    noise = 1e-3 * float(np.max(clean))
    tmpl = StandardLinearSolid(G_inf=3e4, G_1=1e4, eta_1=1e4)
    for _ in range(n):
        res = indentation(z, clean + rng.normal(0.0, noise, z.size), Paraboloid(R=R), time=t,
                          sample=tmpl, free=free)
        ci = res.confidence(0.95)
        for k in free:
            hits[k] += ci[k][0] <= truth[k] <= ci[k][1]
    for k, v in hits.items():
        assert 0.90 * n <= v <= 0.99 * n, (k, v)


def test_long_curve_first_pass_on_a_subsample():
    """A curve of 1500 samples (fitted first on a subsample, then on every sample) is recovered
    as well: Lee-Radok's approach on a ramp in closed form (Dawson's integral D:
    ∫_0^t e^(-(t-s)/τ) √s ds = τ√t - τ^(3/2) D(√(t/τ)))."""
    from scipy.special import dawsn
    g_inf, g_1, tau = SLS["G_inf"], SLS["G_1"], SLS["eta_1"] / SLS["G_1"]
    t = np.linspace(-0.1, TM, 1500)
    s = np.maximum(t, 0.0)
    F = 8 * np.sqrt(R) * V ** 1.5 * (g_inf * 2 / 3 * s ** 1.5 + g_1 * (
        tau * np.sqrt(s) - tau ** 1.5 * dawsn(np.sqrt(s / tau))))
    res = indentation(Z0 + V * t, F, Paraboloid(R=R), time=t,
                      sample=StandardLinearSolid(G_inf=3e4, G_1=1e4, eta_1=1e4))
    for k, want in {**SLS, "contact_point": Z0}.items():
        assert res.params[k] == pytest.approx(want, rel=FIT_RECOVERY)
