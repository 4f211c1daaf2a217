"""Brackets of the contact radius from f alone (contactlab.profiles.radius_bounds, issue 29).

Where f does not decrease, left Riemann-Stieltjes sums over f are lower bounds of g and of the
force, so the first ladder radius whose bound reaches a depth or force lies at or above the
root. Checked against the closed forms of random polynomial gaps; the quadrature route's solves
at a loose rtol use these brackets and first points and must still give the same bits for one
load and a batch, and take fewer quadratures than the old growing bracket.
"""
from __future__ import annotations

import math
from typing import ClassVar

import numpy as np
import pytest

import contactlab as cl
from contactlab.numeric.roots import _chandrupatla, bracketed_root
from contactlab.profiles import Cone, Paraboloid, Polynomial, PowerLaw, Profile
from contactlab.profiles.radius_bounds import (_bounds, _ladder, first_step_from_f,
                                               first_step_one, upper_radius_from_f,
                                               upper_radius_one)
from tests.tolerances import RADIUS_BOUND_ROUNDING

MATERIALS = (cl.Elastic(E=1.0, nu=0.0), cl.Rigid())          # E* = 1 Pa


class FOnly(Profile):
    """Only f and f' of another profile: g, ∫g and the radius go by quadrature."""

    name: ClassVar[str] = "f_only_radius_bounds"
    params: ClassVar[tuple] = ()

    def __init__(self, base: Profile) -> None:
        self.base = base

    def _param_values(self):
        return (self.base,)

    def __repr__(self) -> str:
        return f"FOnly({self.base!r})"

    def _length_scale(self):
        return self.base._length_scale()

    def _height(self, r):
        return self.base._height(r)

    def _slope(self, r):
        return self.base._slope_any(r)


class Wavy(Profile):
    """``r²/2 + 0.15 r sin(8 r)``: f' = r + 0.15 sin(8r) + 1.2 r cos(8r) < 0 near r = π/8, where
    f dips: bounds there do not hold and are not used."""

    name: ClassVar[str] = "wavy_radius_bounds"
    params: ClassVar[tuple] = ()

    def _param_values(self):
        return ()

    def __repr__(self) -> str:
        return "Wavy()"

    def _length_scale(self):
        return 1.0

    def _height(self, r):
        return 0.5 * r * r + 0.15 * r * np.sin(8 * r)

    def _slope(self, r):
        return r + 0.15 * np.sin(8 * r) + 1.2 * r * np.cos(8 * r)


def _random_polynomials(n: int, seed: int = 7):
    rng = np.random.default_rng(seed)
    out = [Paraboloid(1.0), Cone(0.5), PowerLaw(10.0, 4.0), PowerLaw(1.0, 0.5),
           PowerLaw(3.0, 8.0)]
    for _ in range(n):
        k = int(rng.integers(1, 4))
        terms = {float(rng.uniform(0.5, 6.0)): float(10 ** rng.uniform(-2, 2)) for _ in range(k)}
        out.append(Polynomial(terms))
    return out


def _g_and_force(p: Profile, a: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """g(a) and F/2E* = a g(a) - ∫g in closed form."""
    g = p._g(a, 1e-12)
    return g, a * g - p._g_integral(a, 1e-12)


@pytest.mark.parametrize("p", _random_polynomials(12), ids=repr)
def test_bounds_are_lower_bounds(p):
    q = FOnly(p)
    radii = _ladder(1e-6, math.inf, 0)
    g, f2e = _g_and_force(p, radii)
    for kind, exact in (("depth", g), ("force", f2e)):
        b = _bounds(q, radii, kind)
        fin = np.isfinite(exact) & (exact > 0)
        assert fin.sum() > 50
        assert np.all(b[fin] <= exact[fin] * (1 + RADIUS_BOUND_ROUNDING)), kind
        # and a useful bound: within a factor 2 of the value (the bracket's first use)
        assert np.all(b[fin] >= 0.5 * exact[fin]), kind


@pytest.mark.parametrize("p", _random_polynomials(12, seed=11), ids=repr)
def test_bracket_contains_the_root(p):
    """Random depths and forces over twelve decades: g (the force) at the bracket is at or above
    the request, and the bracket is within 1.19 × (the bound's looseness) of the root."""
    q = FOnly(p)
    rng = np.random.default_rng(3)
    a_true = 10 ** rng.uniform(-5, 3, 200)
    g, f2e = _g_and_force(p, a_true)
    for kind, target in (("depth", g), ("force", f2e)):
        ok = np.isfinite(target) & (target > 0)
        hb = upper_radius_from_f(q, target[ok], 1e-6, math.inf, kind)
        assert np.all(np.isfinite(hb))
        gh, fh = _g_and_force(p, hb)
        reached = gh if kind == "depth" else fh
        assert np.all(reached >= target[ok]), kind
        assert np.all(hb <= 2.0 * a_true[ok]), kind


def test_bracket_edge_cases():
    q = FOnly(Paraboloid(1.0))
    # below the first candidate: the start itself (the solve's shrinking takes over there)
    assert upper_radius_from_f(q, np.array([1e-300]), 1e-6, math.inf, "depth")[0] == 1e-6
    # beyond the ladder (2^64 above the start) or above the cap: none (NaN, the growing bracket)
    assert np.isnan(upper_radius_from_f(q, np.array([1e300]), 1e-6, math.inf, "depth")[0])
    assert np.isnan(upper_radius_from_f(q, np.array([1.0]), 1e-6, 0.1, "force")[0])
    # no start: none
    assert np.isnan(upper_radius_from_f(q, np.array([1.0]), 0.0, math.inf, "depth")[0])
    # where f decreases between grid points the bound is -inf (never used)
    w = Wavy()
    radii = _ladder(1e-6, math.inf, 0)
    b = _bounds(w, radii, "depth")
    s = np.sin(np.arange(17) * (0.5 * np.pi / 16))
    dips = np.array([np.any(np.diff(w._height(r * s)) < 0) for r in radii])
    assert dips.any() and np.all(b[dips] == -np.inf) and np.all(b[~dips] > -np.inf)
    # a first step without a usable ladder (a non-monotone f's bounds) is a bisection
    st = first_step_from_f(w, np.array([0.1]), np.array([0.0]), np.array([1.0]),
                           np.array([0.5]), 1e-6, math.inf, "depth")
    assert st[0] == 0.5


@pytest.mark.parametrize("p", [*_random_polynomials(6, seed=5)[3:], Wavy()], ids=repr)
@pytest.mark.parametrize("rtol", [1e-2, 1e-3])
@pytest.mark.parametrize("control", ["depth", "force"])
def test_loose_solves_scalar_equals_batched(p, rtol, control):
    """At a loose rtol (the new brackets and first points) one load on the plain-float route
    and the same load in a batch give the same bits; the answer reaches its rtol."""
    q = FOnly(p)
    rng = np.random.default_rng(19)
    a_true = 10 ** rng.uniform(-3, 0.5, 6)
    g, f2e = _g_and_force(p if not isinstance(p, Wavy) else q, a_true)
    values = g if control == "depth" else 2.0 * f2e
    contact = cl.Contact(q, MATERIALS, rtol=rtol)
    batch = contact.normal(**{control: values})
    for i, v in enumerate(values):
        s = contact.normal(**{control: float(v)})
        for name in ("radius", "depth", "force"):
            assert np.float64(getattr(s, name)).tobytes() == getattr(batch, name)[i].tobytes()
        if not isinstance(p, Wavy):         # (g of the wavy gap may fall: any root will do)
            assert abs(s.radius / a_true[i] - 1) <= rtol


def test_first_step_and_ftol_same_bits_in_both_root_finders():
    """bracketed_root with first_step and ftol and the scalar Chandrupatla: the same iterates
    (on increasing functions of plain arithmetic, the same bits in arrays and floats)."""
    rng = np.random.default_rng(23)
    c = 10 ** rng.uniform(-3, 3, 300)
    k = 10 ** rng.uniform(-3, 3, 300)
    hi = 10 ** rng.uniform(-2, 2, 300)

    def fn(x, i):
        return c[i] * x * (1.0 + k[i] * x * x)

    t = fn(hi * rng.uniform(0.05, 0.99, 300), np.arange(300))
    step = rng.uniform(1 / 64, 63 / 64, 300)
    for ftol in (0.0, 1e-5):
        arr = bracketed_root(fn, t, 0.0, hi, rtol=1e-5, ftol=ftol, first_step=step)
        for i in range(300):
            one = _chandrupatla(lambda x, i=i: float(fn(np.float64(x), i)), float(t[i]), 0.0,
                                float(hi[i]), -float(t[i]), float(fn(hi[i], i) - t[i]), 1e-5,
                                200, "x", float(step[i]), ftol)
            assert np.float64(one).tobytes() == arr[i].tobytes(), i


@pytest.mark.parametrize("p, a", [(Paraboloid(1.0), 0.1), (PowerLaw(10.0, 4.0), 0.1),
                                  (Cone(0.5), 0.1), (PowerLaw(2.0, 1.5), 3.0)], ids=repr)
@pytest.mark.parametrize("rtol", [1e-2, 1e-3])
def test_power_law_force_takes_two_passes(monkeypatch, p, a, rtol):
    """Regression (issue 29): one force on a quadrature power law took 6-7 passes of g and ∫g
    (the bracket's check, four to five Chandrupatla steps from a linearly interpolated first
    point, ∫g once more for the state). The first point from the power of the bounds is now
    the root itself (both the force and its bound scale as a^(n+1)), the residual stop ends
    there, and the state takes ∫g from the root's own pass: two passes."""
    from contactlab.physics import normal_scalar as ns
    calls = {"n": 0}
    real = ns._g_and_integral_one, ns.g_one, ns.g_integral_one

    def counted(fn):
        def call(*args, **kw):
            calls["n"] += 1
            return fn(*args, **kw)
        return call

    for name, fn in zip(("_g_and_integral_one", "g_one", "g_integral_one"), real):
        monkeypatch.setattr(ns, name, counted(fn))
    q = FOnly(p)
    _, f2e = _g_and_force(p, np.array([a]))
    s = cl.Contact(q, MATERIALS, rtol=rtol).normal(force=2.0 * float(f2e[0]))
    assert calls["n"] == 2
    assert abs(s.radius / a - 1) <= rtol
    # the residual stop keeps the force within the driver's check of its request
    assert abs(s.force / (2.0 * float(f2e[0])) - 1) <= 1e-7


def test_loose_rtol_takes_fewer_quadratures(monkeypatch):
    """Regression (issue 29): at rtol 1e-2 one force on a quadrature paraboloid took 18 passes of
    g and ∫g (a bracket grown ×4 from 1 µm on the force) and one depth 10 g; then at most 7 and
    6; now 2 and 3 (one of them g(0) = 0, no quadrature)."""
    from contactlab.physics import normal_scalar as ns
    calls = {"g": 0, "gi": 0}
    real_g, real_gi = ns.g_one, ns._g_and_integral_one

    def g_one(*a, **k):
        calls["g"] += 1
        return real_g(*a, **k)

    def g_and_integral_one(*a, **k):
        calls["gi"] += 1
        return real_gi(*a, **k)

    monkeypatch.setattr(ns, "g_one", g_one)
    monkeypatch.setattr(ns, "_g_and_integral_one", g_and_integral_one)
    contact = cl.Contact(FOnly(Paraboloid(1.0)), MATERIALS, rtol=1e-2)
    s = contact.normal(force=4 / 3 * 0.1**3)
    assert calls["g"] + calls["gi"] <= 2 and abs(s.radius / 0.1 - 1) <= 1e-2
    calls.update(g=0, gi=0)
    s = contact.normal(depth=0.01)
    assert calls["g"] + calls["gi"] <= 3 and abs(s.radius / 0.1 - 1) <= 1e-2


@pytest.mark.parametrize("p", [*_random_polynomials(4, seed=29), Wavy()], ids=repr)
@pytest.mark.parametrize("kind", ["depth", "force"])
def test_one_load_functions_are_the_array_functions(p, kind):
    """The float versions the one-load solves use give the array versions' bits, on random
    targets, brackets and values (including degenerate ones: zero width, zero value, NaN)."""
    q = p if isinstance(p, Wavy) else FOnly(p)
    rng = np.random.default_rng(31)
    n = 400
    t = 10 ** rng.uniform(-12, 6, n)
    hi = 10 ** rng.uniform(-7, 4, n)
    lo = hi * rng.choice([0.0, 0.3, 1.0], n)
    v = t * 10 ** rng.uniform(-0.5, 1.5, n)
    v[::37] = 0.0
    t[::53] = np.nan
    for cap in (math.inf, 0.5):
        arr = upper_radius_from_f(q, t, 1e-6, cap, kind)
        steps = first_step_from_f(q, t, lo, hi, v, 1e-6, cap, kind)
        if not isinstance(p, Wavy):
            assert np.sum(steps != 0.5) > n // 10 and np.sum(np.isfinite(arr)) > n // 4
        for i in range(n):
            one = upper_radius_one(q, float(t[i]), 1e-6, cap, kind)
            assert np.float64(one).tobytes() == arr[i].tobytes(), i
            st = first_step_one(q, float(t[i]), float(lo[i]), float(hi[i]), float(v[i]), 1e-6,
                                cap, kind)
            assert np.float64(st).tobytes() == steps[i].tobytes(), i
