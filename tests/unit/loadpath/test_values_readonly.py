"""``Segment.values_readonly`` (issue 13): the same values as ``values``; a table hands out its
own read-only columns (no copy of a long table per call), ``values`` still fresh writeable
copies; other segments default to ``values``."""
import numpy as np

import contactlab as cl


def test_table_values_readonly_are_its_columns():
    t = np.linspace(0.0, 1.0, 50)
    path = cl.LoadPath.from_arrays(time=t, force=1 + t, twist=1e-4 * np.sin(t))
    leaf = next(path.leaves())
    dt, ro = leaf.values_readonly({})
    dt2, rw = leaf.values({})
    assert np.array_equal(dt, dt2) and ro.keys() == rw.keys()
    for k in ro:
        assert np.array_equal(ro[k], rw[k])
        assert not ro[k].flags.writeable            # the table's own data: read only
        assert rw[k].flags.writeable and not np.shares_memory(rw[k], ro[k])
    assert np.array_equal(ro["force"], 1 + t)


def test_other_segments_default_to_values():
    path = cl.LoadPath().ramp(force=10.0, steps=5).sinusoid(twist=1e-4, cycles=1,
                                                             steps_per_cycle=8)
    start = dict.fromkeys(("depth", "force", "displacement", "tangential_force", "twist",
                           "torque"), 0.0)
    for leaf in path.leaves():
        dt, ro = leaf.values_readonly(start)
        dt2, rw = leaf.values(start)
        assert np.array_equal(dt, dt2)
        assert all(np.array_equal(ro[k], rw[k]) for k in rw) and ro.keys() == rw.keys()
