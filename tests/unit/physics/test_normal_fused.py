"""The compiled force-controlled normal solve of a paraboloid (issue 29; numba, extra ``fast``)
against the numpy route it short-cuts: bit-identical radius, depth, force and error estimate
on random batches (and to the scalar route), the same refusals, and the declined cases (a force
that is not positive, a quotient beyond the normal range) left to the numpy route.
The kernels' logic is also run uncompiled (plain Python), so it is tested without numba."""
from __future__ import annotations

import numpy as np
import pytest

import contactlab as cl
from contactlab.errors import ParameterError
from contactlab.numeric import jit
from contactlab.physics import normal as N
from contactlab.physics import normal_fused as NF
from contactlab.profiles import Paraboloid

MATERIALS = (cl.Elastic(E=210e9, nu=0.3), cl.Rigid())
needs_numba = pytest.mark.skipif(not jit.available(), reason="numba (extra 'fast') not installed")


@pytest.fixture
def backend():
    """Set the backend for one test, restoring the automatic choice after it."""
    yield NF.set_backend
    NF.set_backend(None)


def _forces(size: int, seed: int) -> np.ndarray:
    rng = np.random.default_rng(seed)
    return np.concatenate([rng.lognormal(0.0, 6.0, size - 3), [1e-30, 1.0, 1e12]])


def _state_arrays(s) -> tuple:
    return tuple(np.asarray(v).tobytes() for v in (s.depth, s.radius, s.force,
                                                   s.meta["error_estimate"]))


@needs_numba
@pytest.mark.parametrize("R", [1e-2, 3e-7, 2.5])
def test_compiled_bit_identical_to_numpy_and_scalar(backend, R):
    F = _forces(NF.FUSED_FROM + 1001, int(R * 1e7) % 1000)
    c = cl.Contact(Paraboloid(R), MATERIALS)
    backend("numba")
    fast = c.normal(force=F)
    assert fast.meta.checked is False and fast.meta.residual is None   # (not kept)
    backend("numpy")
    ref = c.normal(force=F)
    assert _state_arrays(fast) == _state_arrays(ref)
    for i in np.random.default_rng(1).integers(0, F.size, 25):
        s = c.normal(force=float(F[i]))
        assert (s.depth, s.radius, s.force) == (fast.depth[i], fast.radius[i], fast.force[i])


@needs_numba
def test_compiled_route_taken_and_shape_kept(backend):
    backend("numba")
    F = _forces(2 * NF.FUSED_FROM, 3).reshape(2, -1)[:, ::2]     # 2-D, not contiguous
    prof = Paraboloid(0.01)
    E = cl.Contact(prof, MATERIALS).moduli.normal
    d, a, Fo, pending = N.solve(prof, E, "force", F, 1e-10, error_estimate="lazy")
    assert pending.checked is True and d.shape == a.shape == Fo.shape == F.shape
    backend("numpy")
    d0, a0, F0, rel0 = N.solve(prof, E, "force", F, 1e-10)
    for x, y in ((d0, d), (a0, a), (F0, Fo), (rel0, pending())):
        assert x.tobytes() == y.tobytes()


@pytest.mark.parametrize("compiled", [False, pytest.param(True, marks=needs_numba)])
def test_kernels_match_the_numpy_route(compiled):
    """The passes themselves (plain Python when not compiled) on a small batch."""
    F = _forces(300, 7)
    prof = Paraboloid(0.004)
    E = cl.Contact(prof, MATERIALS).moduli.normal
    res = NF.paraboloid_force(prof, E, F, compiled)
    assert res is not None
    d0, a0, F0, _ = N.solve(prof, E, "force", F.copy(), 1e-10)
    a, d, Fo, resid = res
    for x, y in ((a0, a), (d0, d), (F0, Fo), (np.abs(F0 - F), resid)):
        assert x.tobytes() == y.tobytes()


@pytest.mark.parametrize("compiled", [False, pytest.param(True, marks=needs_numba)])
@pytest.mark.parametrize("bad", [0.0, -1.0, 1e-290, 1e305])
def test_kernels_decline_outside_their_range(compiled, bad):
    """A force that is not positive or a quotient outside [Q_MIN, Q_MAX] (here 1e-290 N and
    1e305 N on a stiff contact): declined, the numpy route decides."""
    F = _forces(50, 8)
    F[17] = bad
    prof = Paraboloid(0.01)
    assert NF.paraboloid_force(prof, 1e11, F, compiled) is None


@needs_numba
def test_declined_batches_give_the_numpy_results_and_errors(backend):
    prof = Paraboloid(0.01)
    c = cl.Contact(prof, MATERIALS)
    F = _forces(NF.FUSED_FROM + 10, 9)
    F[5] = 0.0                  # the unloaded state: declined, numpy's masked route
    F[6] = 1e-300               # a quotient below Q_MIN: declined, numpy's logarithms
    backend("numba")
    fast = c.normal(force=F)
    backend("numpy")
    assert _state_arrays(fast) == _state_arrays(c.normal(force=F))
    F[5:7] = (3.0, 1e305)       # a quotient above Q_MAX alone: declined too
    backend("numba")
    fast = c.normal(force=F)
    backend("numpy")
    assert _state_arrays(fast) == _state_arrays(c.normal(force=F))


def test_backend_choice(backend, monkeypatch):
    with pytest.raises(ParameterError, match="backend='cuda'"):
        backend("cuda")
    backend("numpy")
    assert NF.backend() == "numpy"
    backend(None)
    monkeypatch.setenv("CONTACTLAB_BACKEND", "numpy")
    assert NF.backend() == "numpy"
    NF.set_backend(None)
    monkeypatch.delenv("CONTACTLAB_BACKEND")
    assert NF.backend() == ("numba" if jit.available() else "numpy")
