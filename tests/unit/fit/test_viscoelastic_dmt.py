"""DMT on a viscoelastic sample: the force of Ting's rules less the Derjaguin force
2πΔγ a(t)/f'(a(t)) of the contact radius that Ting's rule gives (on the retract the approach's
radius at t1). Curves made here with mpmath (Ting's t1 by root finding, the hereditary integral
by quadrature) for a paraboloid (2πRΔγ while in contact) and a cone (2πΔγ a/s, a = 2δ(t1)/(πs));
the parameters are recovered, the model's derivatives match finite differences, and JKR with a
viscoelastic sample is refused with its reason."""
from __future__ import annotations

import mpmath as mp
import warnings

import numpy as np
import pytest

from contactlab import errors
from contactlab.fit import indentation
from contactlab.materials.viscoelastic import StandardLinearSolid
from contactlab.profiles import Cone, Paraboloid
from tests.tolerances import FIT_JACOBIAN_FD, FIT_RECOVERY

# the synthetic curves use AFM-like soft samples (Tabor parameters far above 0.1): these tests
# are about recovery and derivatives, so the DMT-range warning is tested on its own below
pytestmark = pytest.mark.filterwarnings(
    "ignore:Tabor parameter:contactlab.errors.ValidityWarning")

R, V, TM, Z0, S = 5e-6, 1e-6, 0.5, 20e-9, 0.3
SLS = dict(G_inf=1e4, G_1=3e4, eta_1=1.2e4)            # tau = 0.4 s
ARMS = [(SLS["G_1"], SLS["eta_1"] / SLS["G_1"])]


def ting_dmt_reference(t, tip, w, g_inf=SLS["G_inf"], arms=ARMS, v=V, tm=TM):
    """Force on the ramp δ = v·s up to tm, v·(2tm - s) after (s = 0 at contact):
    4∫_0^{t1} G(t - s) dΦ(s) - 2πw ρ(δ(t1)), with t1 = t on the approach and Ting's root of
    ∫_{t1}^{t} G(t - s) δ'(s) ds = 0 on the retract (no root: apart, 0).
    Paraboloid: dΦ/dδ = 2√(Rδ), ρ = R; cone f = S r: dΦ/dδ = 4δ/(πS), ρ = 2δ/(πS²)."""
    mp.mp.dps = 25

    def G(x):
        return g_inf + sum(gk * mp.e ** (-x / tk) for gk, tk in arms)

    def dphi(s):
        d = v * s
        return (2 * mp.sqrt(R * d) if tip == "paraboloid" else 4 * d / (mp.pi * S)) * v

    def rho(d):
        return mp.mpf(R) if tip == "paraboloid" else 2 * d / (mp.pi * S * S)

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
            t1 = x
        else:
            def D(t1, x=x):
                return v * prim(t1, tm, x) - v * prim(tm, x, x)
            if D(mp.mpf(0)) <= 0:
                out.append(0.0)
                continue
            t1 = mp.findroot(D, (mp.mpf(0), mp.mpf(tm)), solver="anderson")
        F = 4 * mp.quad(lambda s, x=x: G(x - s) * dphi(s), [0, t1])
        out.append(float(F - 2 * mp.pi * w * rho(v * t1)))
    return np.array(out)


def ramp(n_app=101, n_ret=101, t_pre=0.1, t_end=2 * TM + 0.05):
    t = np.concatenate([np.linspace(-t_pre, TM, n_app), np.linspace(TM, t_end, n_ret)[1:]])
    return t, np.where(t <= TM, Z0 + V * t, Z0 + V * TM - V * (t - TM))


CASES = {"paraboloid": (Paraboloid(R=R), 0.002), "cone": (Cone(slope=S), 0.002)}


@pytest.fixture(scope="module", params=sorted(CASES))
def curve(request):
    t, z = ramp()
    prof, w = CASES[request.param]
    return request.param, prof, w, t, z, ting_dmt_reference(t, request.param, w)


def test_recovered(curve):
    name, prof, w, t, z, F = curve
    tmpl = StandardLinearSolid(G_inf=3e3, G_1=1e4, eta_1=1e4)
    res = indentation(z, F, prof, time=t, sample=tmpl, adhesion="dmt",
                      free=("G_inf", "G_1", "eta_1", "contact_point", "work_of_adhesion"))
    want = {**SLS, "contact_point": Z0, "work_of_adhesion": w}
    for k, val in want.items():
        assert res.params[k] == pytest.approx(val, rel=FIT_RECOVERY), (name, k)
    assert res.meta["dmt_route"] == ("constant" if name == "paraboloid" else "power")


def test_jacobian_against_finite_differences(curve, monkeypatch):
    """The residual and Jacobian handed to the solver agree with central differences at a
    point away from the solution (all five parameters, the retract's t1 moving with them)."""
    import contactlab.fit._tip as tipmod
    _, prof, _, t, z, F = curve
    seen = {}
    real = tipmod.levenberg_marquardt

    def spy(residual, jacobian, x0, **kw):
        seen["fn"] = (residual, jacobian, x0)   # the last: the whole curve, five parameters
        return real(residual, jacobian, x0, **kw)

    monkeypatch.setattr(tipmod, "levenberg_marquardt", spy)
    tmpl = StandardLinearSolid(G_inf=3e3, G_1=1e4, eta_1=1e4)
    indentation(z, F, prof, time=t, sample=tmpl, adhesion="dmt",
                free=("G_inf", "G_1", "eta_1", "contact_point", "work_of_adhesion"))
    residual, jacobian, x0 = seen["fn"]
    assert len(x0) == 5
    x = np.asarray(x0, float) + 0.03
    J = jacobian(x)
    for i in range(x.size):
        h = 1e-6 * max(abs(x[i]), 1.0)
        e = np.zeros_like(x)
        e[i] = h
        fd = (residual(x + e) - residual(x - e)) / (2 * h)
        # points whose contact state changes inside the step are excluded (a jump of ρ)
        same = (residual(x + e) - residual(x)) * (residual(x) - residual(x - e)) >= 0
        scale = np.max(np.abs(fd))
        np.testing.assert_allclose(J[same, i], fd[same], rtol=FIT_JACOBIAN_FD,
                                   atol=FIT_JACOBIAN_FD * scale)


@pytest.mark.parametrize("curve", ["paraboloid"], indirect=True)
def test_tabor_parameter_at_the_instantaneous_and_relaxed_moduli(curve):
    _, prof, w, t, z, F = curve
    tmpl = StandardLinearSolid(G_inf=3e3, G_1=1e4, eta_1=1e4)
    with pytest.warns(errors.ValidityWarning, match="outside the DMT limit"):
        res = indentation(z, F, prof, time=t, sample=tmpl, adhesion="dmt",
                          free=("G_inf", "G_1", "eta_1", "contact_point", "work_of_adhesion"),
                          equilibrium_distance=0.3e-9)
    e_inst, e_rel = 4 * (SLS["G_inf"] + SLS["G_1"]), 4 * SLS["G_inf"]
    for key, e in (("tabor_parameter", e_inst), ("tabor_parameter_relaxed", e_rel)):
        assert res.meta[key] == pytest.approx((R * w * w / (e * e * 0.3e-9 ** 3)) ** (1 / 3),
                                              rel=FIT_RECOVERY)


def test_jkr_with_a_viscoelastic_sample_is_refused():
    t, z = ramp()
    with pytest.raises(errors.NotSupportedError, match="rate"):
        indentation(z, np.zeros_like(z), Paraboloid(R=R), time=t,
                    sample=StandardLinearSolid(**SLS), adhesion="jkr", work_of_adhesion=0.01)


@pytest.mark.parametrize("curve", ["paraboloid"], indirect=True)
def test_one_tabor_warning_from_the_fit_not_from_its_elastic_start(curve):
    """The elastic fit that starts a viscoelastic one (at a unit modulus) keeps its validity
    notes to itself: the user sees the fit's own Tabor warning, once."""
    _, prof, w, t, z, F = curve
    tmpl = StandardLinearSolid(G_inf=3e3, G_1=1e4, eta_1=1e4)
    with warnings.catch_warnings(record=True) as seen:
        warnings.simplefilter("always")
        indentation(z, F, prof, time=t, sample=tmpl, adhesion="dmt",
                    free=("G_inf", "G_1", "eta_1", "contact_point", "work_of_adhesion"))
    tabor = [str(x.message) for x in seen if "Tabor" in str(x.message)]
    assert len(tabor) == 1 and "for every equilibrium distance" in tabor[0]
