"""The edge-cell integrals of a run of steps (foundation.winkler._edge_integrals, issue 13): a
single power term with every radius > 0 skips the masks and error estimates of the general
route, with bit-identical values."""
import numpy as np
import pytest

import contactlab as cl
from contactlab.foundation import winkler as W

PROFILES = [cl.profiles.Paraboloid(0.01), cl.profiles.Cone(0.2), cl.profiles.PowerLaw(1e3, 4.0),
            cl.profiles.PowerLaw(2e-2, 0.7), cl.profiles.Sphere(0.01), cl.profiles.FlatPunch(1e-4)]


@pytest.mark.parametrize("prof", PROFILES, ids=repr)
@pytest.mark.parametrize("first", [0.0, 1e-6])
def test_edge_integrals_bit_identical(prof, first):
    a = np.linspace(first, 9e-5, 1001)
    for tor in (False, True):
        G, H = W._edge_integrals(prof, a, 1e-10, tor)
        assert np.array_equal(G, W._gint(prof, a))
        assert np.array_equal(H, W.xg_integral(prof, a, 1e-10) if tor else G)
