"""``simulate`` allocates the series it writes at every step without a zero fill (issue 13: the
fill cost ~30 ns per step at N = 100 springs); the others must still start from zeros.

The heap is first filled with NaN arrays of the series' size and freed, so that uninitialised
series would very likely hold NaN: every series must then equal a run on a clean heap bit for
bit, and the series of a spring family the path does not load must be exactly zero.
"""
import warnings

import numpy as np
import pytest

import contactlab as cl
from contactlab.effects.path import SERIES

MAT = (cl.Elastic(E=210e9, nu=0.3), cl.Elastic(E=210e9, nu=0.3))
#: 8 kB series, and blocks of up to 11 of them (88 kB: the returned series are the rows of one
#: block): served from (and returned to) the heap, not fresh mmaps
STEPS = 1000


def contact():
    return cl.Contact(cl.profiles.Paraboloid(R=0.01), materials=MAT, friction=0.3)


def gait(**controls):
    t = np.linspace(0.0, 1.0, STEPS)
    return cl.LoadPath.from_arrays(time=t, force=50 + 40 * np.sin(2 * np.pi * t),
                                   **{k: v * np.sin(6 * np.pi * t) for k, v in controls.items()})


def dirty_heap():
    junk = [np.full(STEPS, np.nan) for _ in range(64)]
    junk += [np.full((rows, STEPS), np.nan) for rows in range(2, len(SERIES) + 1) for _ in range(4)]
    del junk


def run(path, **kw):
    with warnings.catch_warnings():     # the gait's twist leaves the MDR torsion validity
        warnings.simplefilter("ignore", cl.errors.ValidityWarning)
        return contact().simulate(path, n_springs=50, **kw)


@pytest.mark.parametrize("controls, method, zero", [
    ({"twist": 2e-4}, "mdr", ("displacement", "tangential_force")),
    ({"displacement": 1e-7}, None, ("twist", "torque")),
    ({}, None, ("displacement", "tangential_force", "twist", "torque", "dissipated_energy",
                "gross_sliding")),
])
@pytest.mark.parametrize("outputs", [None, ("torque", "tangential_force", "dissipated_energy",
                                            "twist", "displacement", "gross_sliding")])
def test_series_independent_of_heap_contents(controls, method, zero, outputs):
    path = gait(**controls)
    clean = run(path, method=method, outputs=outputs)
    dirty_heap()
    res = run(path, method=method, outputs=outputs)
    assert res.to_dict().keys() == clean.to_dict().keys()
    for name, v in res.to_dict().items():
        assert np.array_equal(v, clean.to_dict()[name]), name
        assert not np.any(np.isnan(v.astype(float))), name
        if name in zero:
            assert not np.any(v), name


def test_a_subset_of_outputs_keeps_only_its_own_series_alive():
    """The returned series share one allocation; series computed but not asked for (the
    normal states the time loop reads) are not in it, so they are freed on return."""
    import gc
    import tracemalloc
    t = np.linspace(0.0, 1.0, 100_000)
    path = cl.LoadPath.from_arrays(time=t, force=50 + 40 * np.sin(2 * np.pi * t),
                                   twist=2e-4 * np.sin(6 * np.pi * t))
    run(gait(twist=2e-4), outputs=("torque",), method="mdr")     # compile, caches: untraced
    tracemalloc.start()
    try:
        torque = run(path, outputs=("torque",), method="mdr").torque
        gc.collect()
        held = tracemalloc.get_traced_memory()[0]
    finally:
        tracemalloc.stop()
    assert torque.shape == t.shape and np.all(np.isfinite(torque))
    # one 800 kB series and small change (caches), not the nine others' 7.2 MB
    assert held <= torque.nbytes + 200_000, held
