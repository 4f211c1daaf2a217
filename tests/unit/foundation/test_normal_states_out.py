"""``iter_path_normal_states(..., out=)`` (issue 13: ``simulate`` solves the normal states straight
into its series, no per-leaf arrays and copies) gives the states of the default route bit for
bit, on force, depth and hold leaves, chunked or not, and they are Hertz's."""
import numpy as np
import pytest

import contactlab as cl
from contactlab.foundation.base import iter_path_normal_states
from tests.reference import hertz
from tests.tolerances import CLOSED_FORM

R = 0.01
E_STAR = hertz.effective_modulus(210e9, 0.3, 210e9, 0.3)
PATH = (cl.LoadPath().ramp(force=100.0, steps=37).hold(steps=11)
        .sinusoid(force=30.0, cycles=2, steps_per_cycle=25)
        .ramp(depth=2e-6, steps=19).hold(steps=5))


@pytest.mark.parametrize("chunk", [None, 7, 1000])
def test_out_route_equals_default_route(chunk):
    prof = cl.profiles.Paraboloid(R=R)
    ref = list(iter_path_normal_states(prof, E_STAR, PATH, 1e-10, chunk=chunk))
    n = PATH.n_steps
    out = {k: np.full(n, np.nan) for k in ("depth", "radius", "force")}
    got = list(iter_path_normal_states(prof, E_STAR, PATH, 1e-10, chunk=chunk, out=out))
    assert len(got) == len(ref)
    i0 = 0
    for g, r in zip(got, ref):
        m = r["depth"].size
        for k in ("depth", "radius", "force"):
            assert np.array_equal(g[k], r[k]), k
            assert np.shares_memory(g[k], out[k])
            assert np.array_equal(out[k][i0:i0 + m], r[k]), k
        assert np.array_equal(g["dt"], r["dt"])
        i0 += m
    assert i0 == n
    a = hertz.radius_of_force(out["force"], R, E_STAR)
    assert np.allclose(out["radius"], a, rtol=CLOSED_FORM, atol=0.0)
