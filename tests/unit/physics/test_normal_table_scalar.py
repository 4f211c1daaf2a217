"""One depth on a small linear table takes the plain-float route (issue 29) and gives the array
route's bits; everything else keeps the array route."""
from __future__ import annotations

import numpy as np
import pytest

import contactlab as cl
from contactlab.errors import OutsideTheoryError
from contactlab.physics import normal_table_scalar as T
from contactlab.profiles import Tabulated

MATERIALS = (cl.Elastic(E=1.0, nu=0.0), cl.Rigid())          # E* = 1 Pa


def _tables(seed: int, count: int):
    rng = np.random.default_rng(seed)
    for i in range(count):
        n = int(rng.integers(2, T.MAX_NODES + 1))
        r = np.unique(np.concatenate([[0.0], rng.uniform(0.0, 1.0, n - 1)]))
        # a paraboloid, a cone plus r^4, and random slopes rising from node to node
        slopes = np.sort(rng.uniform(0.0, 1.0, r.size - 1))
        f = r**2 if i % 3 == 0 else (0.3 * r + r**4 if i % 3 == 1 else
                                     np.concatenate([[0.0], np.cumsum(slopes * np.diff(r))]))
        yield Tabulated(r, f)


@pytest.mark.parametrize("rtol", [1e-2, 1e-3, 1e-10])
def test_one_depth_is_the_batched_route(rtol):
    """Radius, depth, force and error estimate of one depth, bit for bit those of the same depth
    in a batch, on random small tables (paraboloids, cone plus r^4, random convex tables) and
    depths from 1e-9 of the table's reach to its end."""
    taken = total = 0
    for tab in _tables(7, 24):
        contact = cl.Contact(tab, MATERIALS, rtol=rtol)
        g_end = float(tab._g(np.array([tab.r[-1] * 0.999]))[0])
        depths = g_end * np.array([1e-9, 1e-4, 0.01, 0.3, 0.77, 0.999])
        batch = contact.normal(depth=depths)
        for i, d in enumerate(depths):
            s = contact.normal(depth=float(d))
            total += 1
            taken += type(s._radius) is np.float64         # (the float route's state)
            for name in ("radius", "depth", "force"):
                assert np.float64(getattr(s, name)).tobytes() == getattr(batch, name)[i].tobytes()
            assert (np.float64(s.error_estimate).tobytes()
                    == np.float64(batch.error_estimate[i]).tobytes())
    assert taken >= 0.9 * total


def test_the_route_answers_the_closed_form():
    """A table sampled from a cone is a cone: its radius of a depth is the cone's, 2d/(π m)."""
    r = np.linspace(0.0, 0.2, 7)
    s = cl.Contact(Tabulated(r, 0.5 * r), MATERIALS, rtol=1e-2).normal(depth=0.05)
    assert type(s._radius) is np.float64
    assert s.radius == pytest.approx(2 * 0.05 / (np.pi * 0.5), rel=1e-12)


def test_where_the_route_is_not_taken():
    r = np.linspace(0.0, 0.2, 7)
    assert T.table_scalar_ok(Tabulated(r, r**2))
    assert not T.table_scalar_ok(Tabulated(r, r**2, interpolation="cubic"))
    big = np.linspace(0.0, 0.2, T.MAX_NODES + 1)
    assert not T.table_scalar_ok(Tabulated(big, big**2))
    # beyond the table: the array route's error
    tab = Tabulated(r, r**2)
    with pytest.raises(OutsideTheoryError):
        cl.Contact(tab, MATERIALS, rtol=1e-2).normal(depth=1.0)
    # zero and negative depths: the array route (no contact)
    s = cl.Contact(tab, MATERIALS, rtol=1e-2).normal(depth=0.0)
    assert s.radius == 0.0 and s.force == 0.0
