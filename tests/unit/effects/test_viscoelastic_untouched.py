"""A force history that is zero (or tensile) on a surface nothing has touched reports depth 0.

The released state's depth is the largest depth at which no element carries force, the depth at
which the indenter touches the surface. On an untouched surface that is the tip, ``g(0) = 0``;
the foundation took it at its first element's centre, ``g(Δx/2) = (Δx/2)²/(2R)`` for a
paraboloid: 7.6 µm into the surface on the fallback foundation of a history without a positive
force, with radius and force 0.
"""
import numpy as np
import pytest

import contactlab as cl
from contactlab.materials.viscoelastic import StandardLinearSolid
from contactlab.profiles import Paraboloid

SLS = StandardLinearSolid(G_inf=1e6, G_1=2e6, eta_1=1e4)


@pytest.mark.parametrize("F", [0.0, -1.0])
def test_untouched_surface_under_no_force_has_zero_depth(F):
    c = cl.Contact(Paraboloid(R=0.01), materials=(SLS, cl.Rigid()))
    h = c.viscoelastic_history(time=np.linspace(0.0, 0.1, 11), force=np.full(11, F))
    assert np.all(h.depth == 0.0)
    assert np.all(h.radius == 0.0) and np.all(h.force == 0.0)


def test_the_first_step_of_a_ramp_from_zero_has_zero_depth():
    c = cl.Contact(Paraboloid(R=0.01), materials=(SLS, cl.Rigid()))
    t = np.linspace(0.0, 0.1, 11)
    h = c.viscoelastic_history(time=t, force=np.linspace(0.0, 1.0, 11))
    assert h.depth[0] == 0.0 and h.radius[0] == 0.0
    assert np.all(np.diff(h.depth) > 0)
