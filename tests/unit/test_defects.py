"""Regression tests of the adversarial review (issue 11): every reproduction of the report either
raises its specific contactlab error or returns the correct finite value, checked against an
independent closed form (tests/reference/edge.py)."""
from __future__ import annotations

import math
import warnings

import numpy as np
import pytest

import contactlab as cl
from contactlab import profiles as P
from contactlab.errors import (MemoryBudgetError, NotSupportedError, ParameterError,
                               ValidityWarning)
from contactlab.materials.viscoelastic import StandardLinearSolid
from tests.reference import edge as ref
from tests.reference.kappa import kappa_float
from tests.tolerances import CLOSED_FORM, EDGE_DISPLACEMENT, QUADRATURE

STEEL = cl.Elastic(E=210e9, nu=0.3)
EPS = np.finfo(float).eps


def contact(profile, **kw):
    return cl.Contact(profile, materials=(STEEL, STEEL), **kw)


# ------------------------------------------------------------------ displacement outside
POWER_FAMILY = [P.Paraboloid(R=0.01), P.Cone(slope=0.1), P.PowerLaw(c=1e6, n=4),
                P.PowerLaw(c=2.0, n=0.5), P.Polynomial({2: 50.0, 4: 1e6})]


@pytest.mark.parametrize("prof", POWER_FAMILY, ids=repr)
def test_scalar_displacement_outside_the_contact(prof):
    """Scalar r outside the contact (and at zero load) gave TypeError for the power-law family;
    the scalar must equal the same radius evaluated inside an array."""
    c = contact(prof, friction=0.2)
    s = c.normal(force=100.0)
    r = 2 * s.radius
    u = s.displacement(r)
    assert isinstance(u, float) and math.isfinite(u) and u > 0
    assert u == s.displacement(np.array([r, 3 * r]))[0]
    assert c.normal(force=0.0).displacement(1e-3) == 0.0


@pytest.mark.parametrize("prof, n, coef", [(P.Paraboloid(R=0.01), 2, 50.0),
                                           (P.Cone(slope=0.1), 1, 0.1),
                                           (P.PowerLaw(c=1e6, n=4), 4, 1e6)], ids=["hertz", "cone", "n4"])
def test_displacement_just_outside_the_edge(prof, n, coef):
    """r = a(1 + k eps), k = 1..1000: within 1e-12 of the 40-digit Gauss-series reference (the
    package uses a different route there: the connection formula of the series about z = 1)."""
    s = contact(prof).normal(force=10.0)
    a, d = s.radius, s.depth
    r = a * (1 + np.arange(1, 1001) * EPS)
    u = s.displacement(r)
    want = np.array([float(ref.power_law_displacement(coef, n, a, d, ri)) for ri in r])
    assert np.max(np.abs(u / want - 1)) < EDGE_DISPLACEMENT


def test_sphere_displacement_just_outside_the_edge():
    """Quadrature route (exact sphere, g = x artanh(x/R)) against a 40-digit quadrature."""
    import mpmath as mp
    R = 0.01
    s = contact(P.Sphere(R=R)).normal(force=10.0)
    a, d = s.radius, s.depth
    r = a * (1 + np.array([1, 10, 100, 1000]) * EPS)
    want = [float(ref.displacement_by_quadrature(lambda x: x * mp.atanh(x / R), a, d, ri))
            for ri in r]
    assert np.max(np.abs(s.displacement(r) / want - 1)) < EDGE_DISPLACEMENT


# ------------------------------------------------------------------ shear on the axis
def _cone_like(prof, n, coef, mu=0.3, F=1.0, u=1e-8):
    """State and the closed-form a and stick radius: F = 2E*κ c n/(n+1) a^(n+1);
    g(c) = d - G*u/(μE*) with d = κ c a^n."""
    c = cl.Contact(prof, materials=(STEEL, cl.Rigid()), friction=mu)
    E, G = c.moduli.normal, c.moduli.tangential
    k = kappa_float(n)
    a = (F * (n + 1) / (2 * E * k * coef * n)) ** (1 / (n + 1))
    cs = ((k * coef * a**n - G * u / (mu * E)) / (k * coef)) ** (1 / n)
    return c.tangential(force=F, displacement=u), a, cs, E


@pytest.mark.parametrize("prof, n, coef", [(P.Cone(slope=0.1), 1, 0.1),
                                           (P.PowerLaw(c=1.0, n=0.5), 0.5, 1.0),
                                           (P.PowerLaw(c=1e3, n=1.5), 1.5, 1e3)],
                         ids=["cone", "n0.5", "n1.5"])
def test_shear_on_the_axis_is_the_finite_limit(prof, n, coef):
    """τ(0) = lim μ(p_a - p_c) = μ(E*/π) ∫_c^a g'(x)/x dx (derivation in
    tests/reference/edge.power_law_axis_shear); for the cone μ E* s/2 ln(a/c). p_a(0) and
    p_c(0) are infinite for n <= 1, which gave NaN; 5e-324 overflowed."""
    s, a, cs, E = _cone_like(prof, n, coef)
    assert abs(s.stick_radius / cs - 1) < CLOSED_FORM
    want = float(ref.power_law_axis_shear(0.3, E, coef, n, a, cs))
    got = s.shear(np.array([0.0, 5e-324, 1e-300, 1e-9 * cs]))
    assert np.all(np.isfinite(got))
    assert np.max(np.abs(got / want - 1)) < QUADRATURE
    assert s.shear(0.0) == got[0]


def test_shear_on_the_axis_of_a_linear_table_and_a_sum_with_a_cone():
    """A linear table of a straight line is the cone exactly (g = (π/2) s x); the sum with a
    paraboloid adds the finite n = 2 term ∫_c^a g_2'(x)/x dx = 2κ_2 c_2 (a - c)."""
    slope = 0.1
    r = np.linspace(0, 2e-3, 11)
    s_tab, a, cs, E = _cone_like(P.Tabulated(r=r, f=slope * r), 1, slope)
    want = float(ref.power_law_axis_shear(0.3, E, slope, 1, s_tab.normal.radius, s_tab.stick_radius))
    assert abs(s_tab.shear(0.0) / want - 1) < QUADRATURE
    c = cl.Contact(P.Cone(slope=slope) + P.Paraboloid(R=0.01), materials=(STEEL, cl.Rigid()),
                   friction=0.3)
    s = c.tangential(force=1.0, displacement=1e-8)
    a, cs = s.normal.radius, s.stick_radius
    want = (float(ref.power_law_axis_shear(0.3, E, slope, 1, a, cs))
            + float(ref.power_law_axis_shear(0.3, E, 50.0, 2, a, cs)))
    got = s.shear([0.0, 5e-324])
    assert np.max(np.abs(got / want - 1)) < QUADRATURE


# ------------------------------------------------------------------ formulas, adhesion, inputs
def test_formula_callable_is_zero_below_contact_like_normal():
    c = contact(P.Paraboloid(R=0.01), friction=0.2)
    f = c.formulas(substitute=True).callable("force_of_depth")
    assert f(-1e-6) == 0.0 == c.normal(depth=-1e-6).force
    assert np.array_equal(f([-1.0, 0.0]), [0.0, 0.0])
    R, E = 0.01, c.moduli.normal        # Hertz F = (4/3) E* sqrt(R) d^(3/2)
    assert abs(f(1e-6) / (4 / 3 * E * math.sqrt(R) * 1e-6**1.5) - 1) < CLOSED_FORM
    p = c.formulas(substitute=True).callable("pressure")
    with pytest.raises(ParameterError, match="not defined at r=3e-05"):
        p(3e-5, 2e-5)                   # outside the contact: the formula holds for r < a
    with pytest.raises(ParameterError, match="d=True"):
        f(True)


def test_adhesive_torsion_with_friction_is_not_supported():
    ca = contact(P.Paraboloid(R=0.01), work_of_adhesion=0.05, friction=0.2)
    with pytest.raises(NotSupportedError, match="work_of_adhesion=0.05"):
        ca.torsion(force=1.0, twist=1e-1)
    assert ca.torsion(force=1.0, twist=1e-4, method="no-slip").slip is False


@pytest.mark.parametrize("call, match", [
    (lambda c: c.normal(depth=[]), "depth=\\[\\] is invalid: it is empty"),
    (lambda c: c.normal(force=np.zeros((0, 3))), "empty"),
    (lambda c: c.torsion(force=[], twist=1e-4), "empty"),
    (lambda c: c.tangential(force=1.0, displacement=[]), "empty"),
    (lambda c: c.normal(depth=True), "depth=True"),
    (lambda c: c.normal(depth=[1e-6, False]), "not bool"),
    (lambda c: c.normal(depth="1e-6"), "depth='1e-6'"),
    (lambda c: c.torsion(force=[1., 2., 3.], twist=[1e-4, 2e-4]), "force \\(3,\\), twist \\(2,\\)"),
    (lambda c: c.tangential(force=[1., 2.], displacement=[1e-9, 2e-9, 3e-9]),
     "force \\(2,\\), displacement \\(3,\\)"),
    (lambda c: c.simulate(cl.LoadPath()), "no steps"),
    (lambda c: c.simulate(cl.LoadPath().ramp(force=1.0, steps=3), n_springs=True), "n_springs"),
    (lambda c: c.simulate(cl.LoadPath().ramp(force=1.0, steps=3), n_springs=2.5), "n_springs"),
])
def test_bad_arrays_raise_parameter_error(call, match):
    c = contact(P.Paraboloid(R=0.01), friction=0.2)
    with pytest.raises(ParameterError, match=match):
        call(c)


@pytest.mark.parametrize("make, match", [
    (lambda: cl.Elastic(E=True, nu=0.3), "E=True"),
    (lambda: cl.Elastic(E=1e9, nu=False), "nu=False"),
    (lambda: cl.Elastic(E=np.bool_(True), nu=0.3), "E=np.True_|E=True"),
    (lambda: cl.Elastic(E="210e9", nu=0.3), "E='210e9'"),
    (lambda: cl.Elastic(E=np.array([1e9, 2e9]), nu=0.3), "E=array"),
    (lambda: P.Paraboloid(R=True), "R=True"),
    (lambda: StandardLinearSolid(G_inf=1e6, G_1=True, eta_1=1e5), "G_1=True"),
    (lambda: contact(P.Paraboloid(R=0.01), friction=True), "friction=True"),
    (lambda: cl.LoadPath().ramp(force=True, steps=3), "force=True"),
    (lambda: cl.LoadPath().ramp(force=1.0, steps=True), "steps=True"),
])
def test_bools_and_strings_are_not_numbers(make, match):
    with pytest.raises(ParameterError, match=match):
        make()


# ------------------------------------------------------------------ resource guard
def test_memory_guard_simulate_and_viscoelastic():
    c = contact(P.Paraboloid(R=0.01), friction=0.2)
    with pytest.raises(MemoryBudgetError, match="simulate\\(\\) would need about .* GiB"):
        c.simulate(cl.LoadPath().ramp(force=1.0, steps=10**9))
    with pytest.raises(MemoryBudgetError, match="1000000000 springs"):
        c.simulate(cl.LoadPath().ramp(force=1.0, steps=10), n_springs=10**9)
    cv = cl.Contact(P.Paraboloid(R=0.01), materials=(StandardLinearSolid(G_inf=1e6, G_1=1e6, eta_1=1e5),
                                                     cl.Rigid()))
    t = np.linspace(0, 1, 5)
    with pytest.raises(MemoryBudgetError, match="viscoelastic_history"):
        cv.viscoelastic_history(time=t, depth=1e-6 * t, n_springs=10**9)


def test_memory_budget_can_be_raised_and_lowered(monkeypatch):
    c = contact(P.Paraboloid(R=0.01), friction=0.2)
    path = cl.LoadPath().ramp(force=1.0, steps=1000).sinusoid(displacement=1e-8, cycles=1)
    previous = cl.set_memory_budget(100e3)          # 100 kB: a 1100-step run needs ~1.2 MB
    try:
        assert cl.memory_budget() == 100e3
        with pytest.raises(MemoryBudgetError, match="set_memory_budget"):
            c.simulate(path, n_springs=200)
        cl.set_memory_budget("2M")
        assert cl.memory_budget() == 2 * 1024**2
        assert c.simulate(path, n_springs=200).data["force"].size == path.n_steps == 1100
        cl.set_memory_budget(None)
        monkeypatch.setenv("CONTACTLAB_MEMORY_BUDGET", "100K")
        assert cl.memory_budget() == 100 * 1024
        with pytest.raises(MemoryBudgetError):
            c.simulate(path, n_springs=200)
        monkeypatch.setenv("CONTACTLAB_MEMORY_BUDGET", "lots")
        with pytest.raises(ParameterError, match="CONTACTLAB_MEMORY_BUDGET='lots'"):
            cl.memory_budget()
        monkeypatch.delenv("CONTACTLAB_MEMORY_BUDGET")
        assert cl.memory_budget() == 2 * 1024**3
        with pytest.raises(ParameterError, match="n_bytes=-1"):
            cl.set_memory_budget(-1)
    finally:
        cl.set_memory_budget(previous)


# ------------------------------------------------------------------ sphere validity
def test_sphere_warns_beyond_half_the_radius():
    from contactlab.profiles.sphere import VALIDITY_RATIO
    assert VALIDITY_RATIO == 0.5
    c = contact(P.Sphere(R=0.01))
    with pytest.warns(ValidityWarning, match="half-space"):
        s = c.normal(radius=0.0097)
    assert s.radius == 0.0097
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        c.normal(radius=0.005)          # at the threshold: silent
    with pytest.warns(ValidityWarning):
        c.torsion(radius=[1e-3, 0.006], twist=1e-4)


def test_paraboloid_warns_beyond_a_thirty_degree_edge_slope():
    """A paraboloid's edge slope a/R reaches tan 30° (the sphere's limit) at a = R/√3: beyond it
    every route (scalar force and depth, batched forces) warns; an absurd force (1e300 N gave a
    4e95 m radius silently) warns too."""
    from contactlab.profiles.power_law import VALIDITY_SLOPE
    assert VALIDITY_SLOPE == pytest.approx(math.tan(math.radians(30.0)), rel=1e-15)
    R = 0.01
    c = contact(P.Paraboloid(R=R))
    E = c.moduli.normal
    F_limit = 4.0 * E * (R * VALIDITY_SLOPE) ** 3 / (3.0 * R)    # Hertz: F = 4E* a³/(3R)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        c.normal(force=0.99 * F_limit)
        c.normal(force=np.array([1.0, 0.99 * F_limit]))
        c.normal(depth=0.99 * R * VALIDITY_SLOPE ** 2)             # d = a²/R
    for call in (lambda: c.normal(force=1.01 * F_limit),
                 lambda: c.normal(force=np.array([1.0, 1.01 * F_limit])),
                 lambda: c.normal(depth=1.01 * R * VALIDITY_SLOPE ** 2),
                 lambda: c.normal(force=1e300)):
        with pytest.warns(ValidityWarning, match="half-space"):
            s = call()
        assert np.all(np.isfinite(s.radius))
