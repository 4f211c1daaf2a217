"""Batched normal solves (issue 29): fewer passes over the arrays, the same numbers.

* The force error estimate of a batched state on an exact route is computed when it is first
  read; it equals, bit for bit, the estimate computed at once (``solve(error_estimate=True)``).
* The single-power-term fast paths (in-place roots, reductions instead of masks) give the same
  bits as the careful branches they short-cut.
* The exact sphere solves its contact radius by Newton from above (no bracket): accurate
  against a 30-digit mpmath reference, a handful of steps, and an element's radius does not
  depend on the batch it is in.
"""
from __future__ import annotations

import mpmath as mp
import numpy as np
import pytest

import contactlab as cl
from contactlab.effects.normal import LazyMeta
from contactlab.errors import OutsideTheoryError
from contactlab.numeric import powers, roots
from contactlab.physics import normal as N
from contactlab.profiles import Cone, Paraboloid, Polynomial, PowerLaw, Sphere
from tests.tolerances import SPHERE_FORCE_START, SPHERE_G_INTEGRAL, SPHERE_NEWTON_RADIUS

MATERIALS = (cl.Elastic(E=210e9, nu=0.3), cl.Rigid())
PROFILES = [Paraboloid(0.01), Cone(0.2), PowerLaw(1e3, 4.0), PowerLaw(2.0, 1.5), Sphere(0.01),
            Polynomial({2: 50.0, 4: 1e6})]


def _values(control: str) -> np.ndarray:
    rng = np.random.default_rng(29)
    if control == "depth":
        return np.r_[rng.uniform(1e-9, 2e-5, 40), 0.0, -1e-6, 3e-7]
    if control == "force":
        return np.r_[rng.uniform(1e-3, 50.0, 40), 0.0, 1e-20, 2.0]
    return np.r_[rng.uniform(1e-7, 1e-3, 40), 0.0, 5e-4]


@pytest.mark.parametrize("prof", PROFILES, ids=repr)
@pytest.mark.parametrize("control", ["depth", "force", "radius"])
@pytest.mark.parametrize("positive", [True, False])
def test_lazy_estimate_bit_identical_to_eager(prof, control, positive):
    v = _values(control)
    if positive:
        v = v[v > 0]
    E = cl.Contact(prof, MATERIALS).moduli.normal
    d0, a0, F0, rel0 = N.solve(prof, E, control, v.copy(), 1e-10)
    d1, a1, F1, pending = N.solve(prof, E, control, v.copy(), 1e-10, error_estimate="lazy")
    assert callable(pending)
    for x, y in ((d0, d1), (a0, a1), (F0, F1), (rel0, pending())):
        assert x.tobytes() == y.tobytes()


@pytest.mark.parametrize("prof", PROFILES, ids=repr)
@pytest.mark.parametrize("control", ["depth", "force"])
def test_batched_state_reads_estimate_lazily(prof, control):
    v = _values(control)
    c = cl.Contact(prof, MATERIALS)
    s = c.normal(**{control: v})
    assert isinstance(s.meta, LazyMeta) and s.meta._pending is not None   # nothing read yet
    assert s.meta.residual is None                  # the request check's residual is dropped
    E = c.moduli.normal
    rel = N.solve(prof, E, control, v, 1e-10)[3]
    assert np.asarray(s.error_estimate).tobytes() == rel.tobytes()
    # a request changed after the call does not change the estimate read later
    s2 = c.normal(**{control: v.copy()})
    if control == "force":
        w = v.copy()
        s3 = c.normal(force=w)
        w[:] = 1.0
        assert np.asarray(s3.error_estimate).tobytes() == np.asarray(s2.error_estimate).tobytes()


def test_root_of_ratio_overwrite_same_bits():
    rng = np.random.default_rng(1)
    for q in (1.0, 2.0, 3.0, 5.0, 1.7):
        num = rng.uniform(1e-30, 1e30, 1000)
        ref = powers.root_of_ratio(num, 3.7, q)
        own = num.copy()
        out = powers.root_of_ratio(own, 3.7, q, overwrite=True)
        assert out.tobytes() == ref.tobytes()
    # a quotient leaving the float range still goes through logarithms
    num = np.array([1e-300, 1.0, 1e300])
    ref = powers.root_of_ratio(num, 1e100, 100.0)
    assert powers.root_of_ratio(num.copy(), 1e100, 100.0, overwrite=True).tobytes() == ref.tobytes()
    assert np.all(ref > 0)


def test_power_shortcuts_match_careful_branch():
    x = np.r_[np.geomspace(1e-200, 1e100, 500), 0.0]
    careful = np.array([powers.times_power(3.0, np.array([v]), 2.5)[0] for v in x])
    assert powers.times_power(3.0, x, 2.5).tobytes() == careful.tobytes()
    a = np.geomspace(1e-300, 1e50, 300)
    one = np.array([powers.power_integral(np.array([v]), [(2.0, 2.0)], 1.0)[0] for v in a])
    assert powers.power_integral(a, [(2.0, 2.0)], 1.0).tobytes() == one.tobytes()


# ----------------------------------------------------------------------------- exact sphere
mp.mp.dps = 30
R = 0.01
Q = [1e-8, 1e-4, 1e-3, 0.05, 0.0999, 0.1, 0.3, 0.5, 0.9, 0.999, 1 - 1e-9]


def _depth_ref(q: float) -> float:
    qm = mp.mpf(q)
    return float(R * qm * mp.atanh(qm))


def _reduced_force_ref(q: float) -> float:
    qm = mp.mpf(q)
    return float(mp.mpf(R) ** 2 * ((qm * qm + 1) * mp.atanh(qm) - qm) / 2)


@pytest.mark.filterwarnings("ignore::contactlab.errors.ValidityWarning")
def test_sphere_newton_against_mpmath():
    c = cl.Contact(Sphere(R), MATERIALS)
    E = c.moduli.normal
    a_true = R * np.array(Q)
    a_d = c.normal(depth=np.array([_depth_ref(q) for q in Q])).radius
    a_f = c.normal(force=np.array([2 * E * _reduced_force_ref(q) for q in Q])).radius
    # conditioning: dq/q = dδ/δ / (q δ'/δ), ~1 except next to q = 1 where artanh saturates
    assert np.max(np.abs(a_d / a_true - 1)) <= SPHERE_NEWTON_RADIUS
    assert np.max(np.abs(a_f / a_true - 1)) <= SPHERE_NEWTON_RADIUS


def test_sphere_newton_few_steps_and_batch_independent(monkeypatch):
    calls = []
    real = roots.convex_newton_fused

    def counting(step_of, x0, **kw):
        def counted(q, step, quiet):
            calls.append(q.size)
            return step_of(q, step, quiet)
        return real(counted, x0, **kw)

    import contactlab.profiles.sphere as sphere_mod
    monkeypatch.setattr(sphere_mod, "convex_newton_fused", counting)
    s = Sphere(R)
    d = np.array([_depth_ref(q) for q in Q[:-1]])
    a = s._solve_radius(d, s.max_radius, 1e-10)
    assert len(calls) <= 8              # the bracketed solve took ~20 rounds of g
    alone = np.array([s._solve_radius(d[i:i + 1], s.max_radius, 1e-10)[0] for i in range(d.size)])
    assert a.tobytes() == alone.tobytes()
    F = np.array([_reduced_force_ref(q) for q in Q[:-1]])
    a = s._radius_of_reduced_force(F, 1e-10)
    alone = np.array([s._radius_of_reduced_force(F[i:i + 1], 1e-10)[0] for i in range(F.size)])
    assert a.tobytes() == alone.tobytes()


def test_sphere_force_start_and_rounds(monkeypatch):
    """The force solve starts from the inverted series of the Hertz radius: within
    SPHERE_FORCE_START of 30-digit roots up to q = 0.85, so that Newton stops after at most
    three rounds on a batch of radii from 1e-9 R to 0.85 R (the Hertz radius corrected by its
    first two terms, with the tanh bound above q_H = 0.5, took seven)."""
    from contactlab.numeric import normal_kernels as NK
    import contactlab.profiles.sphere as sphere_mod
    starts, rounds = [], []
    real = roots.convex_newton_fused

    def counting(step_of, x0, **kw):
        starts.append(np.array(x0, copy=True))

        def counted(q, step, quiet):
            rounds.append(q.size)
            return step_of(q, step, quiet)
        return real(counted, x0, **kw)

    monkeypatch.setattr(sphere_mod, "convex_newton_fused", counting)
    monkeypatch.setitem(NK._state, "backend", "numpy")
    q = np.r_[np.geomspace(1e-9, 0.85, 400), np.linspace(0.05, 0.85, 400)]
    F = np.array([_reduced_force_ref(x) for x in q])
    a = Sphere(R)._radius_of_reduced_force(F, 1e-10)
    (x0,) = starts
    assert np.max(np.abs(x0 / q - 1)) <= SPHERE_FORCE_START
    assert len(rounds) <= 3
    assert np.max(np.abs(a / (R * q) - 1)) <= SPHERE_NEWTON_RADIUS


def test_sphere_g_integral_series_stops_where_its_tail_rounds_away():
    """The ∫g series below a/R = 0.1 stops once the remaining terms are below half an ulp of
    every partial sum (8 terms of 17 just below 0.1, fewer for smaller radii): the same bits
    as all 17 terms, on batches of every scale of q."""
    from contactlab.profiles import sphere as sphere_mod
    assert not sphere_mod._series_tail_vanishes(0.0999999, 8)
    assert sphere_mod._series_tail_vanishes(0.0999999, 9)
    rng = np.random.default_rng(11)
    for Rs in (R, 1e-6, 3.0):
        for q_max in (0.0999999999, 0.03, 1e-3, 1e-8, 1e-60, 1e-110):
            q = np.r_[rng.uniform(0.0, q_max, 2000), np.geomspace(1e-300, q_max, 500), q_max]
            a = q[q > 0] * Rs
            q = a / Rs                      # (the function's own quotient)
            term = q**3
            ser = np.zeros_like(q)
            part = np.empty_like(q)
            for k in range(1, 18):          # all 17 terms, as before the stop
                if k > 1:
                    term *= q
                    term *= q
                np.divide(term, (2 * k - 1) * (2 * k + 1), out=part)
                ser += part
            ser *= Rs**2
            got = Sphere(Rs)._g_integral_closed_form(a)
            assert got.tobytes() == ser.tobytes()


def test_sphere_refuses_radius_beyond_R():
    c = cl.Contact(Sphere(R), MATERIALS)
    with pytest.raises(OutsideTheoryError, match=r"depth=.*max_radius"):
        c.normal(depth=np.array([1e-6, 1.0]))
    with pytest.raises(OutsideTheoryError, match=r"force=1e\+30 N needs .*max_radius"):
        c.normal(force=np.array([1.0, 1e30]))


# ------------------------------------------------- fewer arrays on the force route (issue 29)
def test_force_residual_takes_the_integral_buffer_only_when_unshared():
    """The force residual is written into the buffer of ∫g only when nothing else holds that
    array: a profile caching its ∫g keeps its cache intact, and the estimate is the same."""
    cache: dict = {}

    class Cached(PowerLaw):
        name = "cached_power_law_test"

        def _g_integral_closed_form(self, a):
            key = a.tobytes()
            if key not in cache:
                cache[key] = super()._g_integral_closed_form(a)
            return cache[key]

    plain, cached = PowerLaw(2.0, 1.5), Cached(2.0, 1.5)
    F = np.random.default_rng(3).uniform(1e-3, 50.0, 200)
    E = 1e11
    ref = N.solve(plain, E, "force", F.copy(), 1e-10)
    out = N.solve(cached, E, "force", F.copy(), 1e-10, error_estimate="lazy")
    (stored,) = cache.values()
    kept = stored.copy()
    assert out[3]().tobytes() == ref[3].tobytes()
    assert stored.tobytes() == kept.tobytes()       # the cached ∫g was not overwritten
    assert N._is_own_temporary(np.empty(3), (3,))
    held = np.empty(3)
    assert not N._is_own_temporary(held[:], (3,))   # a view does not own its data


def test_finite_state_short_cut_catches_non_finite_parts():
    from contactlab.effects.normal import _finite_state
    a = np.array([1e-3, 2e-3])
    for d, F in ((np.array([1.0, np.inf]), np.array([1.0, np.inf])),
                 (np.array([1.0, np.nan]), np.array([1.0, np.nan]))):
        assert not _finite_state(F, d, a)
    assert _finite_state(np.array([1.0, 2.0]), np.array([1.0, 2.0]), a)
    # a radius that is not positive leaves the full check: a NaN depth there is still seen
    assert not _finite_state(np.array([0.0, 2.0]), np.array([np.nan, 2.0]), np.array([0.0, 1.0]))


def test_fused_newton_same_bits_as_convex_newton(monkeypatch):
    """The sphere's Newton on whole arrays with buffers (convex_newton_fused) repeats the
    iterates and the stopping rule of convex_newton on its residuals as written before, bit for
    bit: depths and reduced forces over the whole range of q, from the sphere's own starts."""
    from contactlab.profiles import sphere as sphere_mod
    from contactlab.profiles.sphere import _NOISE, _reduced_force
    q_true = np.r_[np.geomspace(1e-9, 0.999, 3000), np.linspace(0.01, 0.9, 3000)]
    delta = q_true * np.arctanh(q_true)
    eta = _reduced_force(q_true)

    def depth_residual(q, idx):
        at = np.arctanh(q)
        dl = delta[idx]
        return q * at - dl, at + q / ((1 - q) * (1 + q)), _NOISE * dl

    def force_residual(q, idx):
        at = np.arctanh(q)
        h = _reduced_force(q, at)
        el = eta[idx]
        noise = _NOISE * np.where(q < 0.1, el, 0.5 * ((q * q + 1) * at + q))
        return h - el, q * (at + q / ((1 - q) * (1 + q))), noise

    seen = []
    real = roots.convex_newton_fused

    def capturing(step_of, x0, **kw):
        seen.append((np.array(x0, copy=True), kw["rtol"]))
        return real(step_of, x0, **kw)

    monkeypatch.setattr(sphere_mod, "convex_newton_fused", capturing)
    s = Sphere(1.0)
    a_d = s._solve_radius(delta, s.max_radius, 1e-10)
    a_f = s._radius_of_reduced_force(eta, 1e-10)
    for (x0, tol), residual, out in zip(seen, (depth_residual, force_residual), (a_d, a_f)):
        ref = roots.convex_newton(residual, x0, rtol=tol)
        assert out.tobytes() == (1.0 * ref).tobytes()


def test_sphere_all_positive_forces_same_bits_as_masked_branch():
    """The all-positive force branch (no masks) gives, element by element, the bits of the
    masked branch that a zero force in the batch takes; so do the in-place ∫g and g."""
    s = Sphere(R)
    E = 1e11
    F = np.random.default_rng(7).uniform(1e-3, 2e3, 500)
    a1, d1 = N.radius_depth_of_force(s, E, F, 1e-10)
    a0, d0 = N.radius_depth_of_force(s, E, np.r_[F, 0.0], 1e-10)
    assert a1.tobytes() == a0[:-1].tobytes() and d1.tobytes() == d0[:-1].tobytes()
    q = a1 / R
    ref_gi = np.where(q < 0.1, 0.0, 0.5 * (a1**2 - R**2) * np.arctanh(q) + 0.5 * R * a1)
    gi = s._g_integral_closed_form(a1)
    assert gi[q >= 0.1].tobytes() == ref_gi[q >= 0.1].tobytes()
    assert s._g_closed_form(a1).tobytes() == (a1 * np.arctanh(a1 / R)).tobytes()
    # against 30-digit references: ∫g = (a² - R²)/2 artanh(a/R) + R a/2
    for ai, gv in zip(a1[::50], gi[::50]):
        am = mp.mpf(float(ai))
        ref = (am * am - mp.mpf(R) ** 2) / 2 * mp.atanh(am / R) + mp.mpf(R) * am / 2
        assert abs(gv / float(ref) - 1) <= SPHERE_G_INTEGRAL


@pytest.mark.parametrize("prof", [Paraboloid(1e-3), Sphere(1e-3), PowerLaw(2.0, 1.5)], ids=repr)
def test_zero_dimensional_force_array(prof):
    """A 0-d force array takes the array route: it raised a raw TypeError (the residual of a
    0-d request is a numpy scalar, which np.abs(out=) refuses); now it gives the state of the
    one-element batch, bit for bit, as a 0-d state."""
    c = cl.Contact(prof, MATERIALS)
    s = c.normal(force=np.array(1.0))
    one = c.normal(force=np.array([1.0]))
    assert s.shape == ()
    for q in ("depth", "radius", "force", "error_estimate"):
        assert np.asarray(getattr(s, q)).tobytes() == np.asarray(getattr(one, q))[0].tobytes()
