"""The exact ring solver under torque control after gross sliding (issue 28).

Stored path 64 of tests/integration/path_hashes.py (sphere, torque-controlled, 61 rings): after
the gross sliding of step 98 the torque targets of steps 99-101 fall below the sliding torque.
The ring solver's step kept every point at its limit with no twist increment (its torque stayed
the full-sliding torque, not the target), and step 102, whose target has the other sense, turned
into gross sliding that way with a twist jump of 0.025 rad. Now the step frees the points that
must stop sliding: the twist follows the unloading.

References: the same path at 240 rings (the ring count's convergence) and the spring model
(``method="mdr"``, 2000 springs), a second method whose twist increments under a varying normal
load differ from the exact ones by its model error: the twist turned from step 97 to 102
(0.0022 rad; 0.0267 rad before the fix) differs from the springs' by 13 %.
"""
from __future__ import annotations

import warnings

import numpy as np

from contactlab.foundation import rings as _rings
from tests.integration.path_hashes import make_path
from tests.tolerances import RINGS_RELEASE_FINE, RINGS_RELEASE_MDR

STEPS = slice(99, 103)


def _runs():
    _, contact, path, _, _ = make_path(64)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")     # the path's own validity warnings, not the subject
        return (contact.simulate(path, method="exact", n_rings=61),
                contact.simulate(path, method="exact", n_rings=240),
                contact.simulate(path, method="mdr", n_springs=2000))


def test_unloading_after_gross_sliding_turns_the_twist(monkeypatch):
    monkeypatch.setattr(_rings, "INSIDE_ALLOWANCE", 0.0)      # the strict solver
    coarse, fine, mdr = _runs()
    d = [np.diff(np.asarray(x.twist))[STEPS.start - 1:STEPS.stop - 1] for x in (coarse, fine, mdr)]
    assert not np.any(np.asarray(coarse.gross_sliding)[STEPS])
    assert np.all(np.abs(d[0] - d[1]) <= RINGS_RELEASE_FINE * np.abs(d[1]))
    # the twist turned from step 97 (before the gross sliding) to 102, against the springs
    turn = [float(x.twist[STEPS.stop - 1] - x.twist[STEPS.start - 2]) for x in (coarse, mdr)]
    assert abs(turn[0] - turn[1]) <= RINGS_RELEASE_MDR * abs(turn[1])
