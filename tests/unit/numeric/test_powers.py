"""numeric.powers: whole powers by multiplication, cube roots by cbrt, scalar = array element.

Exact references: a double raised to a whole power is an exact rational (``fractions``), and the
cube root is checked through its exact cube (x = r³ brackets), so no reference goes through the
functions under test or through numpy's power.
"""
from __future__ import annotations

import math
from fractions import Fraction

import numpy as np
import pytest

import contactlab as cl
from contactlab.numeric.powers import power, power_float, power_integral, root, root_float
from contactlab.physics import normal as normal_solve

RNG = np.random.default_rng(20261127)
#: radii and forces of everyday contacts and far beyond (1e-30 ... 1e10)
X = RNG.uniform(0.5, 1.0, 4000) * 10.0 ** RNG.integers(-30, 10, 4000)


def ulps_off(value: float, exact: Fraction) -> float:
    """|value - exact| in units of the last place of the double nearest ``exact``."""
    return float(abs(Fraction(value) - exact) / Fraction(np.spacing(float(exact))))


@pytest.mark.parametrize("p, max_ulps", [(1.0, 0.0), (2.0, 0.5), (3.0, 2.0), (4.0, 3.0)])
def test_whole_powers_within_their_roundings(p, max_ulps):
    # relative error u = 2^-53 per rounding: x² correctly rounded; x·x·x at most 2u relative
    # (< 2 ulp of the result); (x·x)² squares x²'s error (2u) and rounds once more (< 3 ulp)
    got = power(X, p)
    worst = max(ulps_off(g, Fraction(x) ** int(p)) for g, x in zip(got.tolist(), X.tolist()))
    assert worst <= max_ulps


def test_other_powers_are_numpys():
    assert np.array_equal(power(X, 2.5), X ** 2.5)
    assert np.array_equal(root(X, 3.5), X ** (1 / 3.5))


def test_cube_root_within_three_ulps_where_the_pow_of_one_third_is_not():
    # x ** (1/3) raises to the double nearest 1/3 (1.85e-17 below it): relative error
    # 1.85e-17 |ln x|, up to ~12 ulp over this range; cbrt stays within 3 ulp (libm) or
    # ~0.5 ulp (numpy's SIMD cbrt)
    def cube_root_ulps(r: float, x: float) -> float:
        lo, hi = Fraction(r) - Fraction(np.spacing(r)) / 2, Fraction(r) + Fraction(np.spacing(r)) / 2
        fx = Fraction(x)
        if lo ** 3 <= fx <= hi ** 3:
            return 0.5
        # distance of the true root to r, through the cube's slope 3 r² (first order)
        return float(abs(fx - Fraction(r) ** 3) / (3 * Fraction(r) ** 2) / Fraction(np.spacing(r)))

    sample = X[:1500]
    ours = max(cube_root_ulps(r, x) for r, x in zip(root(sample, 3.0).tolist(), sample.tolist()))
    pow_third = max(cube_root_ulps(r, x) for r, x in zip((sample ** (1 / 3)).tolist(),
                                                         sample.tolist()))
    assert ours <= 3.0
    assert pow_third > 4.0            # the route replaced: measurably worse on this range


@pytest.mark.parametrize("p", [1.0, 2.0, 3.0, 4.0])
def test_scalar_forms_are_the_array_elements(p):
    assert [power_float(x, p) for x in X.tolist()] == power(X, p).tolist()
    if p <= 3.0:
        assert [root_float(x, p) for x in X.tolist()] == root(X, p).tolist()


@pytest.mark.parametrize("p", [2.5, 0.7, 5.0])
def test_other_exponents_agree_to_about_an_ulp(p):
    # the C library's pow (scalar) against numpy's vector pow: each within ~1 ulp
    for scalar, array in ((power_float, power), (root_float, root)):
        got = np.array([scalar(x, p) for x in X.tolist()])
        ref = array(X, p)
        assert np.all(np.abs(got - ref) <= 2 * np.spacing(ref))


def test_power_integral_is_the_sum_of_its_terms():
    a = X[:500]
    terms = [(2.0, 2.0), (0.5, 1.0)]
    got = power_integral(a, terms, 1.0)
    for g, x in zip(got.tolist(), a.tolist()):
        exact = Fraction(2.0) * Fraction(x) ** 3 / 3 + Fraction(0.5) * Fraction(x) ** 2 / 2
        assert ulps_off(g, exact) <= 4.0
    assert np.array_equal(power_integral(a, [], 1.0), np.zeros(a.shape))


@pytest.mark.parametrize("profile", [cl.profiles.Paraboloid(R=0.01), cl.profiles.Cone(slope=0.1),
                                     cl.profiles.PowerLaw(c=3.0, n=2.0)],
                         ids=["hertz", "cone", "n2"])
def test_scalar_and_batched_force_solves_give_the_same_radius(profile):
    # normal(force=x) on one float and the array solve of a batch use the same operations
    # (the radius is a square or cube root for n = 1, 2)
    c = cl.Contact(profile, (cl.Elastic(E=210e9, nu=0.3),) * 2)
    F = RNG.uniform(1.0, 1000.0, 300)
    _, a, _, _ = normal_solve.solve(profile, c.moduli.normal, "force", F, c.rtol,
                                    error_estimate=False)
    assert [c.normal(force=f).radius for f in F.tolist()] == a.tolist()


def test_hertz_radius_returns_its_force_to_an_ulp_even_far_out():
    # the force recomputed from the solved radius: the old pow(x, 1/3) route lost ~50 ulp of
    # the radius at F = 1e300 N (F came back as 9.999999999999636e299)
    c = cl.Contact(cl.profiles.Paraboloid(R=0.01), (cl.Elastic(E=210e9, nu=0.3),) * 2)
    for F in (1e-6, 1.0, 1e6, 1e300):
        d, a, F_back, _ = normal_solve.solve(c.profile, c.moduli.normal, "force", np.array([F]),
                                             c.rtol, error_estimate=False)
        assert math.isclose(float(F_back[0]), F, rel_tol=16 * np.finfo(float).eps)
