"""The compiled viscoelastic foundation step (issue 13) against its numpy reference: single trial
steps on random element states, and whole depth- and force-controlled histories of the
Kelvin-Voigt, Maxwell, standard-linear-solid and Prony materials."""
import numpy as np
import pytest

import contactlab as cl
from contactlab.foundation import _compiled
from contactlab.foundation.viscoelastic import ViscoelasticElements
from contactlab.materials.viscoelastic import (GeneralizedMaxwell, KelvinVoigt, Maxwell,
                                               StandardLinearSolid)
from contactlab.profiles import Paraboloid
from tests.tolerances import BACKENDS_AGREE

R = 0.01
MATERIALS = {
    "kelvin-voigt": KelvinVoigt(1e6, 1e4),
    "maxwell": Maxwell(1e6, 1e4),
    "sls": StandardLinearSolid(1e6, 2e6, 1e4),
    "prony": GeneralizedMaxwell(1e6, [2e6, 1e6, 5e5, 2e5], [1e-3, 5e-3, 2e-2, 1e-1]),
}


@pytest.fixture(autouse=True)
def _needs_numba():
    if "numba" not in _compiled.available():
        pytest.skip("numba is not installed (extra 'fast')")
    yield
    _compiled.set_backend(None)


def _both(fn):
    out = {}
    for b in ("numpy", "numba"):
        _compiled.set_backend(b)
        out[b] = fn()
    _compiled.set_backend(None)
    return out["numpy"], out["numba"]


def _close(x, y, what):
    x, y = np.asarray(x, float), np.asarray(y, float)
    scale = max(float(np.max(np.abs(x), initial=0.0)), 1e-300)
    assert x.shape == y.shape and np.all(np.abs(x - y) <= BACKENDS_AGREE * scale), what


def _histories():
    t = np.linspace(0.0, 0.04, 161)
    d = 1e-4 * np.where(t <= 0.02, t, 0.04 - t)                 # Ting unloading, lift-off
    F = 0.1 * np.sin(np.pi * t / 0.04) ** 2                      # back to 0: pull-off
    tj = np.concatenate(([0.0, 0.0], np.linspace(1e-3, 0.03, 60)))   # a jump, then a creep
    return {"depth": (t, {"depth": d}), "force": (t, {"force": F}),
            "jump": (tj, {"force": np.full(tj.size, 0.05)})}


@pytest.mark.parametrize("mat", list(MATERIALS))
@pytest.mark.parametrize("hist", ["depth", "force", "jump"])
def test_histories_agree_between_backends(mat, hist):
    if mat == "kelvin-voigt" and hist == "jump":
        pytest.skip("a Kelvin-Voigt dashpot cannot jump (refused, tested elsewhere)")
    c = cl.Contact(Paraboloid(R), materials=(MATERIALS[mat], cl.Rigid()))
    t, load = _histories()[hist]
    a, b = _both(lambda: c.viscoelastic_history(time=t, n_springs=400, **load))
    for key in ("depth", "force", "radius"):
        _close(getattr(a, key), getattr(b, key), (mat, hist, key))
    assert np.any(a.force > 0)


@pytest.mark.parametrize("mat", list(MATERIALS))
def test_trial_steps_agree_between_backends(mat):
    """One step from random element states (some in contact, some free and deformed, some
    virgin) at depths that grow, shrink and hold, with and without a time step: every output
    of the trial."""
    G_inf, Gk, tk, eta = MATERIALS[mat].prony()
    n = 300
    dx = 1e-6
    g = ((np.arange(n) + 0.5) * dx) ** 2 / R
    rng = np.random.default_rng(11)
    for case in range(12):
        fd = ViscoelasticElements(g, dx, G_inf, Gk, tk, eta)
        touched = int(rng.integers(1, n))
        fd.touched = touched
        d_old = float(g[touched - 1]) * rng.uniform(0.5, 1.5)
        fd.u[:touched] = np.maximum(d_old - g[:touched], 0) * rng.uniform(0.5, 1.0, touched)
        fd.s[:touched] = rng.normal(0, 1e-3 * G_inf * d_old, (touched, Gk.size))
        fd.contact[:touched] = rng.random(touched) < 0.7
        fd.ever[:touched] = fd.contact[:touched] | (rng.random(touched) < 0.5)
        d_new = d_old * (1.0 + 0.2 * rng.normal())
        dt = 0.0 if (case % 4 == 3 and eta == 0) else float(rng.uniform(1e-5, 1e-2))
        ref, got = _both(lambda: fd.trial(d_new, d_old, dt))
        assert got.m == ref.m and np.array_equal(got.contact, ref.contact), case
        assert (got.n_contact, got.last) == (ref.n_contact, ref.last), case
        for key in ("q", "u", "s", "stiffness", "radius", "total"):
            _close(getattr(ref, key), getattr(got, key), (mat, case, key))
