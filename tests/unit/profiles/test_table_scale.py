"""A table's radii and heights within the range where its transforms hold: a largest radius in
[1e-30, 1e10] m and heights within 1e10 m of 0. Beyond them the cubic spline's solve failed
inside scipy (radii near 1e300 m), the transforms warned of overflow (1e75 m), a cubic table of
1e30 m radii gave a contact radius 4e10 times too small and a linear table of 1e-200 m radii a
zero one for a positive depth, without a word; every physical table lies far inside. At both
ends of the range a table sampled from a paraboloid gives Hertz's closed form."""
from __future__ import annotations

from contextlib import nullcontext

import numpy as np
import pytest

import contactlab as cl
from contactlab.errors import TabulatedDataError, ValidityWarning

MATERIALS = (cl.Elastic(E=1e9, nu=0.3), cl.Rigid())


def _table(scale: float, interpolation: str, n: int = 400) -> tuple[cl.profiles.Tabulated, float]:
    """A paraboloid f = r²/(2R) with R = scale sampled at n radii up to ``scale``; and R."""
    x = np.linspace(0.0, 1.0, n)
    return cl.profiles.Tabulated(x * scale, x**2 * scale / 2, interpolation=interpolation), scale


@pytest.mark.parametrize("interpolation", ["linear", "cubic"])
@pytest.mark.parametrize("scale", [1e-300, 1e-200, 9.9e-31, 1.01e10, 1e20, 1e30, 1e300])
def test_radii_outside_the_range_are_refused_naming_the_largest(interpolation, scale):
    with pytest.raises(TabulatedDataError, match=r"r\[-1\]=.* m is invalid: the largest radius "
                                                 r"of a table must lie between 1e-30 and 1e\+10"):
        _table(scale, interpolation)


def test_heights_beyond_the_range_are_refused_naming_the_value():
    r = np.linspace(0.0, 1e-3, 10)
    f = np.zeros(10)
    f[7] = -2e10
    with pytest.raises(TabulatedDataError, match=r"f\[7\]=-20000000000.0 m is invalid: the "
                                                 r"heights of a table must lie within 1e\+10"):
        cl.profiles.Tabulated(r, f)


@pytest.mark.parametrize("interpolation", ["linear", "cubic"])
@pytest.mark.parametrize("scale", [1e-30, 1e-3, 1e10])
def test_tables_at_the_ends_of_the_range_give_hertz(interpolation, scale):
    """Depth → radius and force, and force → depth, against Hertz's closed forms of the
    sampled paraboloid (a = sqrt(R d), F = 4/3 E* sqrt(R) d^(3/2)), within the table's
    interpolation error: linear, 2 (Δ/a)² with Δ the node spacing (the chords lie above the
    parabola; measured 0.8 (Δ/a)² in the radius at every scale), cubic 1e-8 (measured 1e-15).
    The same relative errors at both ends of the range as at a millimetre."""
    tab, R = _table(scale, interpolation)
    E_star = 1e9 / (1 - 0.3**2)
    c = cl.Contact(tab, MATERIALS)
    d = 0.08 * R                       # a = 0.4 R: 160 table intervals inside the contact
    s = c.normal(depth=d)
    a, F = np.sqrt(R * d), 4.0 / 3.0 * E_star * np.sqrt(R) * d**1.5
    spacing = R / 399
    tol = 2 * (spacing / a) ** 2 if interpolation == "linear" else 1e-8
    assert s.radius == pytest.approx(a, rel=tol)
    assert s.force == pytest.approx(F, rel=tol)
    assert c.normal(force=F).depth == pytest.approx(d, rel=tol)
    with np.errstate(all="raise"):
        with pytest.warns(ValidityWarning) if interpolation == "linear" else nullcontext():
            p = s.peak_pressure                       # a linear table's first chord: a cone tip
    if interpolation == "cubic":
        assert p == pytest.approx(2 * E_star * a / (np.pi * R), rel=1e-6)
