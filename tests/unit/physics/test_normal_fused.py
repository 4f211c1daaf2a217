"""The compiled force-controlled normal solves (issue 29; numba, extra ``fast``) against the
numpy routes they short-cut: on a paraboloid bit-identical radius, depth, force and error
estimate on random batches (and to the scalar route), the declined cases (a force that is not
positive, a quotient beyond the normal range) left to the numpy route; the exact sphere's
Newton rounds bit-identical to the numpy rounds (series, closed form and deep starts), giving up
after as many rounds with the same error. The kernels' logic is also run uncompiled (plain
Python), so it is tested without numba."""
from __future__ import annotations

import functools

import numpy as np
import pytest

import contactlab as cl
from contactlab.errors import ConvergenceError, ParameterError, ValidityWarning
from contactlab.numeric import jit
from contactlab.numeric import normal_kernels as NK
from contactlab.physics import normal as N
from contactlab.physics import normal_fused as NF
from contactlab.profiles import Paraboloid, Sphere
from contactlab.profiles import sphere as sphere_mod

MATERIALS = (cl.Elastic(E=210e9, nu=0.3), cl.Rigid())
needs_numba = pytest.mark.skipif(not jit.available(), reason="numba (extra 'fast') not installed")
# the batches span forces far beyond a paraboloid's half-space range (radii above R/√3 warn): these
# tests compare the routes' bits there, the warning itself is tested in tests/unit/test_defects.py
pytestmark = pytest.mark.filterwarnings("ignore::contactlab.errors.ValidityWarning")


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


@pytest.mark.parametrize("compiled", [False, "numpy", pytest.param(True, marks=needs_numba)])
def test_kernels_match_the_numpy_route(compiled):
    """The passes themselves (plain Python when not compiled, numpy ufuncs into the block) on a
    small batch; forces over 42 decades, so the numpy passes' request check falls back from
    the largest residual against the smallest request to element by element."""
    F = _forces(300, 7)
    prof = Paraboloid(0.004)
    E = cl.Contact(prof, MATERIALS).moduli.normal
    res = NF.paraboloid_force(prof, E, F, compiled)
    assert res is not None
    d0, a0, F0, _ = N.solve(prof, E, "force", F.copy(), 1e-10)
    a, d, Fo = res
    for x, y in ((a0, a), (d0, d), (F0, Fo), (F, Fo)):
        assert x.tobytes() == y.tobytes()


@pytest.mark.parametrize("compiled", [False, "numpy", pytest.param(True, marks=needs_numba)])
@pytest.mark.parametrize("bad", [0.0, -1.0, 1e-290, 1e305, np.nan])
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


@pytest.mark.parametrize("R", [1e-2, 3e-7, 2.5])
def test_numpy_passes_bit_identical_to_the_general_route(backend, R):
    """Without numba (or with the numpy backend forced) a batch of at least FUSED_FROM forces
    on a paraboloid takes the numpy passes into one block: radius, depth, force and error
    estimate bit-identical to the general route (error_estimate=True never takes the passes),
    and to the scalar route; the driver's checks made on the way (pending.checked)."""
    F = _forces(NF.FUSED_FROM + 1001, int(R * 1e7) % 1000)
    prof = Paraboloid(R)
    c = cl.Contact(prof, MATERIALS)
    E = c.moduli.normal
    backend("numpy")
    d, a, Fo, pending = N.solve(prof, E, "force", F, 1e-10, error_estimate="lazy")
    assert pending.checked is True          # (the general route leaves it unset)
    d0, a0, F0, rel0 = N.solve(prof, E, "force", F, 1e-10)
    for x, y in ((d0, d), (a0, a), (F0, Fo), (rel0, pending()), (F, Fo)):
        assert x.tobytes() == y.tobytes()
    state = c.normal(force=F)
    assert _state_arrays(state) == tuple(v.tobytes() for v in (d0, a0, F0, rel0))
    for i in np.random.default_rng(2).integers(0, F.size, 25):
        s = c.normal(force=float(F[i]))
        assert (s.depth, s.radius, s.force) == (d0[i], a0[i], F0[i])


def test_numpy_passes_decline_for_one_bad_request_anywhere():
    """A force the passes must decline (not positive, NaN, a quotient above Q_MAX) anywhere in
    the batch declines the whole batch (the extremes decide)."""
    F = _forces(3 * 1000 + 17, 11)
    prof = Paraboloid(0.003)
    E = cl.Contact(prof, MATERIALS).moduli.normal
    res = NF.paraboloid_force(prof, E, F, "numpy")
    assert res is not None
    d0, a0, F0, _ = N.solve(prof, E, "force", F.copy(), 1e-10)
    for x, y in zip((a0, d0, F0), res):
        assert x.tobytes() == y.tobytes()
    for bad in (0.0, 1e305, np.nan):
        G = F.copy()
        G[-5] = bad
        assert NF.paraboloid_force(prof, E, G, "numpy") is None


# ------------------------------------------------- the paraboloid's one constant per contact
def _hertz_30_digits(F: np.ndarray, R: float, E: float) -> tuple[np.ndarray, ...]:
    """Radius, depth and force of the Hertz closed form, a = (3RF/(4E*))^(1/3), d = a²/R,
    F = 4E* a³/(3R), in 30 digits (mpmath), rounded to floats."""
    import mpmath
    with mpmath.workdps(30):
        a = [mpmath.cbrt(3 * mpmath.mpf(R) * mpmath.mpf(f) / (4 * mpmath.mpf(E))) for f in F]
        d = [x * x / mpmath.mpf(R) for x in a]
        Fo = [4 * mpmath.mpf(E) * x ** 3 / (3 * mpmath.mpf(R)) for x in a]
        return tuple(np.array([float(v) for v in arr]) for arr in (a, d, Fo))


@pytest.mark.parametrize("R", [1e-2, 3e-7, 2.5])
def test_force_route_is_the_one_constant_closed_form(backend, R):
    """Every force-controlled route of a paraboloid (scalar, the general array route, the numpy
    passes, the compiled passes where numba imports) gives a = cbrt(F/K) and d = (a·a)/R with
    K = 4E*/(3R) bit for bit (before: a chain of four divisions), and the request itself as the
    state's force (before: 2E*(a d - ∫g) from them); radius and depth within
    HERTZ_FORCE_ROUNDING of the 30-digit Hertz closed form, and so is the force of (a, d),
    (a·d)·4E*/3, of the request: the error estimate carries that residual."""
    from tests.tolerances import HERTZ_FORCE_ROUNDING
    F = _forces(NF.FUSED_FROM + 77, int(R * 1e5) % 991)
    prof = Paraboloid(R)
    c = cl.Contact(prof, MATERIALS)
    E = c.moduli.normal
    K, cf = (4.0 * E) / (3.0 * R), (4.0 * E) / 3.0
    a = np.cbrt(F / K)
    d = (a * a) / R
    want = tuple(v.tobytes() for v in (d, a, F))
    resid = np.abs((a * d) * cf - F)
    routes = ["numpy"] + (["numba"] if jit.available() else [])
    for name in routes:
        backend(name)
        s = c.normal(force=F)
        assert tuple(np.asarray(v).tobytes() for v in (s.depth, s.radius, s.force)) == want
        assert np.all(s.meta["error_estimate"] * F >= resid)
    small = c.normal(force=F[:500])                 # below FUSED_FROM: the general route
    assert tuple(np.asarray(v).tobytes() for v in (small.depth, small.radius, small.force)) == \
        tuple(v[:500].tobytes() for v in (d, a, F))
    for i in np.random.default_rng(5).integers(0, F.size, 20):
        s = c.normal(force=float(F[i]))
        assert (s.depth, s.radius, s.force) == (d[i], a[i], F[i])
    idx = np.random.default_rng(6).integers(0, F.size, 200)
    for got, ref in zip((a, d), _hertz_30_digits(F[idx], R, E)):
        assert np.max(np.abs(got[idx] / ref - 1.0)) <= HERTZ_FORCE_ROUNDING
    # the bound the passes' request check rests on (normal_fused._in_range)
    assert np.max(resid / F) <= HERTZ_FORCE_ROUNDING


def test_scalar_state_reads_its_integral_only_for_the_estimate():
    """The scalar force route of a paraboloid skips ∫g (its force is the request): the
    estimate, read later, adds the residual of (a, d), |(a·d)·c - F|, to the rounding terms of
    the scalar route's formula with ∫g at the state's radius."""
    from contactlab.physics import normal_scalar as S
    c = cl.Contact(Paraboloid(0.004), MATERIALS)
    E = c.moduli.normal
    cf = (4.0 * E) / 3.0
    for F in (1e-9, 3.7, 2.5e4):
        s = c.normal(force=F)
        assert s.force == F
        forms = S.forms_of(c.profile)
        resid = abs((s.radius * s.depth) * cf - F)
        rounding = S.force_rel_error(E, s.radius, s.depth, forms.g_integral(s.radius), F, None)
        assert s.meta["error_estimate"] == pytest.approx(rounding + resid / F, rel=1e-15)
        assert s.meta["error_estimate"] >= resid / F


def test_numpy_passes_take_the_callers_extremes(monkeypatch):
    """Given the extremes (the driver's finiteness check reduced them), the numpy passes reduce
    nothing and give the same bits; the driver hands them on (a batch whose extremes are
    swapped for out-of-range ones is declined)."""
    F = _forces(3000, 12)
    prof = Paraboloid(0.01)
    E = cl.Contact(prof, MATERIALS).moduli.normal
    ref = NF.paraboloid_force(prof, E, F, "numpy")
    assert ref is not None
    got = NF.paraboloid_force(prof, E, F, "numpy", (float(F.min()), float(F.max())))
    assert got is not None
    assert all(x.tobytes() == y.tobytes() for x, y in zip(ref, got))
    assert NF.paraboloid_force(prof, E, F, "numpy", (0.0, float(F.max()))) is None
    seen = []
    real = NF.paraboloid_force

    def spy(*args):
        seen.append(args[4])
        return real(*args)
    monkeypatch.setattr(NF, "paraboloid_force", spy)
    NF.set_backend("numpy")
    try:
        cl.Contact(prof, MATERIALS).normal(force=np.resize(F, NF.FUSED_FROM + 1))
    finally:
        NF.set_backend(None)
    assert seen and seen[0] is not None


def _unchecked_paraboloid(R: float) -> Paraboloid:
    """A paraboloid of radius ``R`` outside the lengths its constructor accepts
    (``contactlab.params.LENGTH_BOUNDS``): the passes' own range check is what is tested."""
    prof = Paraboloid(1.0)
    prof.R, prof.c = R, 1.0 / (2.0 * R)
    return prof


def test_passes_decline_where_a_value_leaves_their_range():
    """Requests whose quotient F/K (a radius of curvature of 1e-300 m) or whose depth (the same
    with a soft modulus and large forces: d up to 1e293 m) leaves [1e-290, 1e290], the range
    in which the passes prove their request check, are declined by both passes; the general
    route answers, with the operations of the passes where they are finite."""
    F = np.geomspace(1e-20, 1e20, 300)
    prof = _unchecked_paraboloid(1e-300)
    for compiled in ("numpy", False):
        assert NF.paraboloid_force(prof, 1e11, F, compiled) is None
    F = np.geomspace(1.0, 1e280, 300)
    E = 1e-10
    K = prof._hertz_force_constants(E)[0]
    assert not NF._in_range(1.0, 1e280, 1e-300, K)
    for compiled in ("numpy", False):
        assert NF.paraboloid_force(prof, E, F, compiled) is None
    d0, a0, F0, _ = N.solve(prof, E, "force", F, 1e-10)
    a = np.cbrt(F / K)
    assert a0.tobytes() == a.tobytes() and d0.tobytes() == ((a * a) / 1e-300).tobytes()
    assert F0.tobytes() == F.tobytes()


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


# ------------------------------------------------------------------ the exact sphere's Newton
def _sphere_forces(R: float, size: int, seed: int) -> np.ndarray:
    """Forces of contact radii from 1e-9 R to 0.999 R (the series below a/R = 0.1, the closed
    form above it, the deep start above a/R ~ 0.5)."""
    rng = np.random.default_rng(seed)
    q = np.concatenate([rng.uniform(0.0, 0.999, size - 3), [1e-9, 0.0999999, 0.1]])
    c = cl.Contact(Sphere(R), MATERIALS)
    with pytest.warns(ValidityWarning):
        return np.asarray(c.normal(radius=q * R).force)


@needs_numba
@pytest.mark.parametrize("R", [1e-2, 1e-6, 3.0])
def test_sphere_compiled_newton_bit_identical_to_numpy(backend, R):
    F = _sphere_forces(R, NF.FUSED_FROM + 500, int(R * 1e6) % 997)
    c = cl.Contact(Sphere(R), MATERIALS)
    backend("numba")
    with pytest.warns(ValidityWarning):
        fast = c.normal(force=F)
    backend("numpy")
    with pytest.warns(ValidityWarning):
        ref = c.normal(force=F)
    assert _state_arrays(fast) == _state_arrays(ref)


@pytest.mark.parametrize("compiled", [False, pytest.param(True, marks=needs_numba)])
def test_sphere_newton_kernel_matches_numpy_rounds(monkeypatch, compiled):
    """The Newton round itself (plain Python when not compiled) against the numpy rounds."""
    prof = Sphere(0.01)
    F = _sphere_forces(0.01, 400, 5)
    E = cl.Contact(prof, MATERIALS).moduli.normal
    NK._state["backend"] = "numpy"
    try:
        ref = prof._radius_of_reduced_force(F / (2 * E), 1e-10)
        monkeypatch.setattr(NK, "FUSED_FROM", 1)
        monkeypatch.setattr(NK, "sphere_force_newton",
                            functools.partial(NK.sphere_force_newton, compiled=compiled))
        NK._state["backend"] = "numba"        # (the route; the kernels as the test chose)
        got = prof._radius_of_reduced_force(F / (2 * E), 1e-10)
    finally:
        NK.set_backend(None)
    assert ref.tobytes() == got.tobytes()


@pytest.mark.parametrize("compiled", [False, pytest.param(True, marks=needs_numba)])
def test_sphere_newton_kernel_gives_up_as_numpy_does(monkeypatch, compiled):
    prof = Sphere(0.01)
    F = _sphere_forces(0.01, 300, 6)
    E = cl.Contact(prof, MATERIALS).moduli.normal
    monkeypatch.setattr(sphere_mod, "_MAXITER", 1)
    monkeypatch.setattr(NK, "FUSED_FROM", 1)
    monkeypatch.setattr(NK, "sphere_force_newton",
                        functools.partial(NK.sphere_force_newton, compiled=compiled))
    for route in ("numpy", "numba"):
        NK._state["backend"] = route
        try:
            with pytest.raises(ConvergenceError, match=r"did not converge in 1 steps \(at "):
                prof._radius_of_reduced_force(F / (2 * E), 1e-10)
        finally:
            NK.set_backend(None)
