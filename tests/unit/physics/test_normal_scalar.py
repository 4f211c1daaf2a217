"""The scalar fast path of normal() (issue 13) against the array route and the closed forms."""
from __future__ import annotations

import zlib

import numpy as np
import pytest

import contactlab as cl
from contactlab.errors import OutsideTheoryError
from contactlab.physics import normal_scalar
from contactlab.profiles import (Cone, FlatPunch, Paraboloid, Polynomial, PowerLaw, Sphere,
                                 Tabulated, TruncatedParaboloid)
from tests.reference import hertz
from tests.tolerances import CLOSED_FORM, SCALAR_VS_ARRAY

STEEL = cl.Elastic(E=210e9, nu=0.3)
PROFILES = [Paraboloid(0.01), Cone(0.2), PowerLaw(1e3, 4.0), PowerLaw(2e-2, 0.7), Sphere(0.01),
            Polynomial({2: 50.0, 4: 1e6}), TruncatedParaboloid(1e-4, 0.01), FlatPunch(1e-3),
            # sums and scaled profiles: composed from their terms' scalar forms
            Paraboloid(0.01) + Cone(0.1), Sphere(0.01) + PowerLaw(1e3, 4.0),
            TruncatedParaboloid(1e-4, 0.01) + Cone(0.2), 2.0 * Sphere(0.01),
            3.0 * FlatPunch(1e-3), 0.5 * Polynomial({2: 50.0, 4: 1e6})]


@pytest.mark.parametrize("prof", PROFILES, ids=repr)
@pytest.mark.parametrize("key,values", [("depth", [-1e-6, 0.0, 1e-9, 3e-7, 2e-6]),
                                        ("force", [-1.0, 0.0, 1e-3, 10.0, 300.0])])
def test_scalar_path_agrees_with_array_route(prof, key, values):
    c = cl.Contact(prof, (STEEL, STEEL))
    assert normal_scalar.forms_of(prof) is not None          # the fast path is taken
    arr = c.normal(**{key: np.array(values)})
    for i, v in enumerate(values):
        s = c.normal(**{key: v})
        assert type(s.force) is float and s.shape == ()
        for q in ("depth", "radius", "force"):
            ref = getattr(arr, q)[i]
            assert abs(getattr(s, q) - ref) <= SCALAR_VS_ARRAY * abs(ref), (q, v)
        # (the same formula; under force control the residual term differs by a few ulps of F)
        assert s.error_estimate == pytest.approx(arr.error_estimate[i], rel=0.1, abs=1e-300)
        assert type(s.error_estimate) is float
        assert s.meta["control"] == key and s.meta["routes"] == arr.meta["routes"]


def test_hertz_closed_form():
    E = hertz.effective_modulus(210e9, 0.3, 210e9, 0.3)
    c = cl.Contact(Paraboloid(0.01), (STEEL, STEEL))
    for F in (1e-3, 1.0, 1e3):
        s = c.normal(force=F)
        assert abs(s.radius - hertz.radius_of_force(F, 0.01, E)) <= CLOSED_FORM * s.radius
        d = c.normal(depth=s.depth)
        assert abs(d.force - F) <= CLOSED_FORM * F


def test_flat_punch_closed_form():
    """Boussinesq: the contact radius is the punch radius b and F = 2 E* b d."""
    E = hertz.effective_modulus(210e9, 0.3, 210e9, 0.3)
    b = 1e-3
    for prof, k in ((FlatPunch(b), 1.0), (3.0 * FlatPunch(b), 3.0)):
        c = cl.Contact(prof, (STEEL, STEEL))
        for d in (1e-9, 2e-6):
            s = c.normal(depth=d)
            assert s.radius == b and abs(s.force - 2 * E * b * d) <= CLOSED_FORM * s.force
            f = c.normal(force=s.force)
            assert f.radius == b and abs(f.depth - d) <= CLOSED_FORM * d


def test_error_estimate_is_lazy_and_complete():
    c = cl.Contact(Sphere(0.01), (STEEL, STEEL))
    s = c.normal(force=10.0)
    assert dict.get(s.meta, "error_estimate") is None        # not computed yet
    assert "error_estimate" in s.meta and 0 < s.error_estimate < 1e-12
    assert set(s.meta) - {"citations"} == {"routes", "rtol", "control", "error_estimate"}


def test_sphere_too_deep_raises_like_the_array_route():
    c = cl.Contact(Sphere(1e-3), (STEEL, STEEL))
    with pytest.raises(OutsideTheoryError, match="max_radius"):
        c.normal(depth=1.0)
    with pytest.raises(OutsideTheoryError, match="max_radius"):
        c.normal(force=1e12)


def test_profiles_without_scalar_forms_use_the_array_route():
    r = np.linspace(0, 1e-3, 50)
    assert normal_scalar.forms_of(Tabulated(r, r**2 / 0.02)) is None
    assert normal_scalar.forms_of(FlatPunch(1e-3) + Paraboloid(0.01)) is None   # rises at a wall
    assert normal_scalar.forms_of(Paraboloid(0.01) + Tabulated(r, r**2 / 0.02)) is None


def test_same_call_is_bit_identical():
    c = cl.Contact(Polynomial({2: 50.0, 4: 1e6}), (STEEL, STEEL))
    first = c.normal(force=3.0)
    c.normal(depth=np.linspace(0, 1e-6, 7))
    again = c.normal(force=3.0)
    assert (first.force, first.radius, first.depth) == (again.force, again.radius, again.depth)


def test_validity_warning_like_the_array_route():
    from contactlab.errors import ValidityWarning
    c = cl.Contact(Sphere(1e-3), (STEEL, STEEL))
    deep = 0.3e-3          # contact radius beyond R/2
    with pytest.warns(ValidityWarning):
        c.normal(depth=np.array([deep]))
    with pytest.warns(ValidityWarning) as rec:
        c.normal(depth=deep)
    assert rec[0].filename == __file__        # points at the caller


#: profiles whose scalar and array routes perform the same float operations: bit-identical
_SAME_OPERATIONS = {"Paraboloid(R=0.01)", "Cone(slope=0.2)", "FlatPunch(radius=0.001)",
                    "3.0 * FlatPunch(radius=0.001)"}


@pytest.mark.parametrize("prof", PROFILES, ids=repr)
def test_scalar_and_array_routes_random_loads(prof):
    """Random depths and forces over six decades (campaign: 828 of 10⁴ differed in the last
    bits). Where both routes perform the same operations the results are bit-identical; the
    others (a root solve: Newton in floats against Chandrupatla on arrays; a power of a
    non-whole exponent: the C library's pow against numpy's) agree to SCALAR_VS_ARRAY
    (measured <= 2.1e-15, docs/robustness.md)."""
    rng = np.random.default_rng(zlib.crc32(repr(prof).encode()))
    c = cl.Contact(prof, (STEEL, STEEL))
    same = repr(prof) in _SAME_OPERATIONS
    for key, lo, hi in (("depth", -9.0, -5.5), ("force", -3.0, 2.5)):
        values = 10 ** rng.uniform(lo, hi, 60)
        arr = c.normal(**{key: values})
        for i, v in enumerate(values):
            s = c.normal(**{key: float(v)})
            for q in ("depth", "radius", "force"):
                got, ref = getattr(s, q), getattr(arr, q)[i]
                if same:
                    assert got == ref, (q, key, v)
                else:
                    assert abs(got - ref) <= SCALAR_VS_ARRAY * abs(ref), (q, key, v)
