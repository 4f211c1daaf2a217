"""Cubic tables: the closed-form transform (set up once, node sums) against a second method."""
from __future__ import annotations

import mpmath as mp
import numpy as np
import pytest

import contactlab as cl
from contactlab.profiles import Tabulated

from ...tolerances import (CUBIC_CLOSED_FORM, CUBIC_CLOSED_FORM_CLUSTERED, CUBIC_SLOPE_FD,
                           TABLE_EXACT)


def _table(n: int, kind: str, spacing: str) -> Tabulated:
    if spacing == "uniform":
        r = np.linspace(0.0, 1e-3, n)
    else:
        r = 1e-3 * np.sort(np.r_[0.0, np.random.default_rng(1).random(n - 2), 1.0])
    f = {"sphere": 0.01 - np.sqrt(0.01**2 - r**2),
         "n4": 1e-5 * (r / 1e-3) ** 4,
         "mixed": r**2 / 0.02 + 1e-6 * (r / 1e-3) ** 3}[kind]
    return Tabulated(r, f, "cubic")


def _rel(a: np.ndarray, b: np.ndarray) -> float:
    return float(np.max(np.abs(a - b)) / np.max(np.abs(b)))


@pytest.mark.parametrize("n", [10, 100, 1000, 10_000])
@pytest.mark.parametrize("kind", ["sphere", "n4", "mixed"])
@pytest.mark.parametrize("spacing", ["uniform", "random"])
def test_closed_form_matches_per_interval_gauss(n, kind, spacing):
    tab = _table(n, kind, spacing)
    x = np.linspace(0.0, 1e-3, 57)
    for kind_, p in (("g", 0), ("int", 2)):
        val, est, _ = tab._cubic_value(x, kind_)
        ref, ref_err = tab._spline_theta_sum(x, p)
        ref, ref_err = ref * x ** (p or 1), ref_err * x ** (p or 1)
        tol = CUBIC_CLOSED_FORM_CLUSTERED if (spacing, n) == ("random", 10_000) \
            else CUBIC_CLOSED_FORM
        assert _rel(val, ref) < tol, (kind_, _rel(val, ref))
    assert tab.g_route == "closed_form"


def test_closed_form_against_independent_high_precision_sum():
    """g of the spline's own pieces, integrated piece by piece in 40-digit arithmetic
    (elementary antiderivatives of r^m/sqrt(x²-r²), no node-term rearrangement)."""
    tab = _table(300, "sphere", "uniform")
    c, R = tab._spline.c, tab.r
    with mp.workdps(40):       # local precision: later tests see mpmath unchanged
        for xv in (2.3e-4, 1e-3):
            x = mp.mpf(xv)
            total = mp.mpf(0)
            for j in range(R.size - 1):
                lo, hi = mp.mpf(R[j]), min(mp.mpf(R[j + 1]), x)
                if lo >= x:
                    break
                A0 = lambda u: mp.asin(u / x)                                     # noqa: E731
                A1 = lambda u: -mp.sqrt(x * x - u * u)                            # noqa: E731
                A2 = lambda u: x * x / 2 * mp.asin(u / x) - u / 2 * mp.sqrt(x * x - u * u)  # noqa
                B, C, D = (mp.mpf(float(v)) for v in (c[2, j], c[1, j], c[0, j]))
                p0, p1, p2 = B - 2 * C * lo + 3 * D * lo**2, 2 * C - 6 * D * lo, 3 * D
                total += p0 * (A0(hi) - A0(lo)) + p1 * (A1(hi) - A1(lo)) + p2 * (A2(hi) - A2(lo))
            ref = float(x * total)
            assert abs(float(tab._g_closed_form(np.array(xv))) / ref - 1) < CUBIC_CLOSED_FORM


def test_slope_matches_difference_of_g():
    tab = _table(100, "mixed", "uniform")
    x = np.linspace(1e-5, 9.9e-4, 40)
    _, gp = tab._g_and_slope(x)
    h = 1e-9
    fd = (tab._g_closed_form(x + h) - tab._g_closed_form(x - h)) / (2 * h)
    assert _rel(gp, fd) < CUBIC_SLOPE_FD


def test_cubic_normal_force_route_matches_depth_route():
    """normal(force=) takes the node-search route for cubic tables too; its radius reproduces
    the force through the independent depth route."""
    tab = _table(2000, "sphere", "uniform")
    E = cl.Elastic(E=210e9, nu=0.3)
    c = cl.Contact(tab, (E, E))
    s = c.normal(force=np.array([0.5, 5.0, 50.0]))
    back = c.normal(depth=s.depth)
    assert _rel(back.force, np.array([0.5, 5.0, 50.0])) < 1e-9


@pytest.mark.parametrize("seed", range(4))
@pytest.mark.parametrize("shape", ["sphere", "mixed"])
def test_rounding_estimate_covers_error_on_nearly_coincident_nodes(seed, shape):
    """Nodes 1e-9 of the radius apart: the spline's third-derivative jumps are huge and cancel
    between neighbours and inside each node term as r_j -> x. The closed form's rounding estimate
    must cover its actual error (against the per-interval Gauss rule, converged to rounding),
    so that the Gauss fallback fires where the sums are not accurate (the estimate from the
    terms' values alone missed it by up to 5000x on these tables)."""
    rng = np.random.default_rng(seed)
    base = np.linspace(0.0, 1e-3, 200)
    extra = rng.choice(base[5:-5], 20, replace=False) + 1e-12 * rng.integers(1, 5, 20)
    r = np.unique(np.r_[base, extra])
    f = (0.01 - np.sqrt(0.01**2 - r**2) if shape == "sphere"
         else r**2 / 0.02 + 1e-6 * (r / 1e-3) ** 3)
    tab = Tabulated(r, f, "cubic")
    x = np.sort(np.r_[np.linspace(1e-6, 1e-3, 200), extra + 3e-13, extra + 1e-10, extra + 1e-8])
    x = x[x <= 1e-3]
    for kind, weight, p in (("g", 0, 1), ("int", 2, 2), ("xg", "xg", 3)):
        val, est, _ = tab._cubic_sums(x, kind)
        ref, ref_err = tab._spline_theta_sum(x, weight)
        ref, ref_err = ref * x**p, ref_err * x**p
        actual = np.abs(val - ref)
        sharp = ref_err < 0.1 * actual             # where the reference can judge the error
        assert np.all(actual[sharp] <= est[sharp]), (kind, np.max(actual[sharp] / est[sharp]))
        # and the value handed out (closed form or its fallback) is accurate to its estimate
        v2, e2, _ = tab._cubic_value(x, kind)
        assert np.all(np.abs(v2 - ref) <= e2 + ref_err + 4 * np.finfo(float).eps * np.abs(ref))


def test_xg_integral_matches_independent_quadrature():
    """∫_0^a x g dx in closed form (linear and cubic tables) against scipy quad of x g(x)
    split at every node (a second method)."""
    from scipy.integrate import quad
    for kind in ("linear", "cubic"):
        for spacing in ("uniform", "random"):
            n = 60
            r = (np.linspace(0.0, 1e-3, n) if spacing == "uniform" else
                 1e-3 * np.sort(np.r_[0.0, np.random.default_rng(3).random(n - 2), 1.0]))
            tab = Tabulated(r, 0.01 - np.sqrt(0.01**2 - r**2) + 1e-6 * (r / 1e-3) ** 3, kind)
            a = np.array([1e-6, 3.3e-4, 7.77e-4, 1e-3])
            ref = [quad(lambda x: x * float(tab._g_closed_form(np.array(x))), 0.0, aa,
                        points=[b for b in r if 0 < b < aa], limit=500, epsabs=0,
                        epsrel=1e-13)[0] for aa in a]
            tol = CUBIC_CLOSED_FORM if kind == "cubic" else TABLE_EXACT
            assert _rel(tab._xg_integral_closed_form(a), np.array(ref)) < tol


def _random_fine_case(n: int) -> None:
    """A randomly spaced cubic table of f = r²/(2R) + c r⁴ (nearest nodes ~1e-15 of the radius
    apart at 10^6 points): its node sums (clustered pieces kept local) against the profile's
    closed forms g = x²/R + (8/3) c x⁴, ∫g = a³/(3R) + (8/15) c a⁵, ∫x g = a⁴/(4R) + (4/9) c a⁶,
    without falling back to the per-interval Gauss rule (the spline's own interpolation error
    is ~1e-20 here: the difference is the sums' rounding)."""
    from contactlab.profiles.tabulated import CUBIC_SUM_RTOL

    from ...tolerances import CUBIC_RANDOM_FINE
    R, c = 0.01, 2.0
    r = 2e-3 * np.sort(np.r_[0.0, np.random.default_rng(n).random(n - 2), 1.0])
    tab = Tabulated(r, r**2 / (2 * R) + c * r**4, "cubic")
    assert tab._cubic_local_lo.size > 0
    hi = tab._cubic_local_hi
    x = np.r_[np.linspace(1e-5, 1.99e-3, 12), hi[::max(1, hi.size // 5)] + 1e-12]
    closed = {"g": x**2 / R + 8.0 / 3.0 * c * x**4,
              "int": x**3 / (3 * R) + 8.0 / 15.0 * c * x**5,
              "xg": x**4 / (4 * R) + 4.0 / 9.0 * c * x**6}
    for kind, ref in closed.items():
        val, est, _ = tab._cubic_sums(x, kind)
        assert np.all(est <= CUBIC_SUM_RTOL * np.abs(val)), kind      # no Gauss fallback
        rel = np.max(np.abs(val / ref - 1))
        assert rel < CUBIC_RANDOM_FINE, (kind, rel)


def test_random_fine_table_node_sums_match_closed_form():
    _random_fine_case(100_000)


@pytest.mark.slow
def test_random_million_point_table_node_sums_match_closed_form():
    _random_fine_case(1_000_000)
