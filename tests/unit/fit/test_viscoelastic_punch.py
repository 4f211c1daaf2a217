"""Viscoelastic fits with a flat punch: its contact radius is the punch radius ``b`` from the
first touch, so the force is the hereditary integral ``F(t) = 8b ∫ G(t - s) δ'(s) ds`` (E* = 4G)
on the approach and — Ting's rule at a constant radius — on the retract until it reaches zero
(the punch then leaves the surface). References evaluated here by mpmath quadrature of that
integral; the parameters recovered from noise-free curves, the model's derivatives against
finite differences."""
from __future__ import annotations

import mpmath as mp
import numpy as np
import pytest

from contactlab import errors
from contactlab.fit import indentation
from contactlab.fit._ting import TingModel
from contactlab.fit._tip import TipModel
from contactlab.materials.viscoelastic import GeneralizedMaxwell, StandardLinearSolid
from contactlab.profiles import FlatPunch, Paraboloid
from tests.tolerances import FIT_JACOBIAN_FD, FIT_RECOVERY, FIT_TING_MODEL

B, V, TM, Z0 = 2e-6, 1e-6, 0.5, 20e-9
SLS = dict(G_inf=1e4, G_1=3e4, eta_1=1.2e4)            # tau = 0.4 s
PRONY = (1e4, [(3e4, 0.05), (2e4, 0.8)])


def punch_reference(t, g_inf, arms, v=V, tm=TM):
    """Force of a rigid flat punch (radius B) on an incompressible half-space with
    G(t) = g_inf + Σ G_k exp(-t/τ_k) for the indentation v·s up to tm and v·(2tm - s) after
    (s = 0 at contact): 8B ∫_0^t G(t - s) δ'(s) ds while positive, zero from its first zero
    on. mpmath quadrature at 25 digits."""
    mp.mp.dps = 25

    def G(x):
        return g_inf + sum(gk * mp.e ** (-x / tk) for gk, tk in arms)

    out, left = [], False
    for x in t:
        x = mp.mpf(float(x))
        if x <= 0 or left:
            out.append(0.0)
            continue
        f = 8 * B * v * mp.quad(lambda s, x=x: G(x - s), [0, min(x, tm)])
        if x > tm:
            f -= 8 * B * v * mp.quad(lambda s, x=x: G(x - s), [tm, x])
        if f <= 0:
            left = True
            f = mp.mpf(0)
        out.append(float(f))
    return np.array(out)


def ramp(n_app=101, n_ret=101, t_pre=0.1, t_end=2 * TM + 0.05):
    t = np.concatenate([np.linspace(-t_pre, TM, n_app), np.linspace(TM, t_end, n_ret)[1:]])
    return t, np.where(t <= TM, Z0 + V * t, Z0 + V * TM - V * (t - TM))


@pytest.fixture(scope="module")
def sls_curve():
    t, z = ramp()
    return t, z, punch_reference(t, SLS["G_inf"], [(SLS["G_1"], SLS["eta_1"] / SLS["G_1"])])


@pytest.fixture(scope="module")
def prony_curve():
    t, z = ramp()
    return t, z, punch_reference(t, *PRONY)


def test_model_matches_the_hereditary_integral(sls_curve, prony_curve):
    t, z, F = sls_curve
    m = TingModel(t, z, TipModel(FlatPunch(radius=B), 1e-6, allow_wall=True))
    f = m(SLS["G_inf"], np.array([SLS["G_1"]]), np.array([SLS["eta_1"] / SLS["G_1"]]), Z0)[0]
    assert np.max(np.abs(f - F)) < FIT_TING_MODEL * np.max(F)
    assert F[-1] == 0.0 and f[-1] == 0.0 and np.count_nonzero(F[t > TM] == 0) > 5
    t, z, F = prony_curve
    g = m(PRONY[0], np.array([3e4, 2e4]), np.array([0.05, 0.8]), Z0)[0]
    assert np.max(np.abs(g - F)) < FIT_TING_MODEL * np.max(F)


def test_standard_linear_solid_recovered(sls_curve):
    t, z, F = sls_curve
    tmpl = StandardLinearSolid(G_inf=3e4, G_1=1e4, eta_1=1e4)
    res = indentation(z, F, FlatPunch(radius=B), time=t, sample=tmpl,
                      free=("G_inf", "G_1", "eta_1", "contact_point"))
    for k, want in {**SLS, "contact_point": Z0}.items():
        assert res.params[k] == pytest.approx(want, rel=FIT_RECOVERY)


def test_prony_series_recovered(prony_curve):
    t, z, F = prony_curve
    tmpl = GeneralizedMaxwell(2e4, moduli=[2e4, 1e4], relaxation_times=[0.1, 0.5])
    res = indentation(z, F, FlatPunch(radius=B), time=t, sample=tmpl,
                      free=("G_inf", "moduli", "relaxation_times", "contact_point"))
    want = {"G_inf": 1e4, "moduli[0]": 3e4, "relaxation_times[0]": 0.05, "moduli[1]": 2e4,
            "relaxation_times[1]": 0.8, "contact_point": Z0}
    for k, w in want.items():
        assert res.params[k] == pytest.approx(w, rel=FIT_RECOVERY)


@pytest.mark.parametrize("material", [
    StandardLinearSolid(G_inf=1e4, G_1=3e4, eta_1=1.2e4),
    GeneralizedMaxwell(1e4, moduli=[3e4, 2e4], relaxation_times=[0.05, 0.8]),
])
def test_jacobian_against_finite_differences(material):
    from contactlab.fit.viscoelastic import _chain, _prony, _values
    t, z = ramp(n_app=301, n_ret=301)
    m = TingModel(t, z, TipModel(FlatPunch(radius=B), 2e-6, allow_wall=True))
    cls = type(material)
    z0 = Z0 + 0.3 * V * (t[1] - t[0])         # between samples: the force has a kink at touch
    v0 = {**_values(material), "contact_point": z0}

    def force(v):
        return m(*_prony(cls, v), v["contact_point"])[0]
    _, dGi, dGk, dtk, dz0 = m(*_prony(cls, v0), z0)
    jac = {**_chain(cls, v0, dGi, dGk, dtk), "contact_point": dz0}
    for name, col in jac.items():
        h = 1e-6 * v0[name]
        fd = (force({**v0, name: v0[name] + h}) - force({**v0, name: v0[name] - h})) / (2 * h)
        assert np.max(np.abs(col - fd)) < FIT_JACOBIAN_FD * np.max(np.abs(fd)), name


def test_other_walls_refused(sls_curve):
    t, z, F = sls_curve
    with pytest.raises(errors.NotSupportedError, match="wall"):
        indentation(z, F, Paraboloid(R=1e-5) + FlatPunch(radius=B), time=t,
                    sample=StandardLinearSolid(**SLS))
