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


def test_values_of_is_values_restricted_to_the_names():
    """``values_of`` (what simulate's normal solve and time loop each read): the same arrays as
    ``values`` for the quantities asked for, nothing else; no time with ``time=False``."""
    t = np.linspace(0.0, 1.0, 40)
    path = (cl.LoadPath().ramp(force=10.0, twist=2e-4, steps=7).hold(steps=3)
            .sinusoid(force=3.0, twist=1e-4, cycles=2.5, steps_per_cycle=12, mean={"force": 5.0})
            .then(cl.LoadPath.from_arrays(time=t, force=1 + t, twist=1e-4 * t).segments[0]))
    start = {"depth": 0.0, "force": 2.0, "displacement": 0.0, "tangential_force": 0.0,
             "twist": -1e-4, "torque": 0.0}
    for leaf in path.leaves():
        dt, full = leaf.values(start)
        for names in (("depth", "force"), ("twist", "torque"), ("displacement",), ()):
            dt2, part = leaf.values_of(start, names)
            assert np.array_equal(dt2, dt)
            assert sorted(part) == sorted(k for k in full if k in names)
            for k in part:
                assert np.array_equal(part[k], full[k])
            none, part2 = leaf.values_of(start, names, time=False)
            assert none is None and part2.keys() == part.keys()


def test_values_of_default_filters_values():
    """A segment that implements ``values`` only gets ``values_of`` from the base class."""
    from dataclasses import dataclass

    from contactlab.loadpath.base import Segment

    @dataclass(frozen=True)
    class Steps(Segment):
        @property
        def controls(self):
            return frozenset({"force", "twist"})

        @property
        def n_steps(self):
            return 3

        def values(self, start):
            return np.arange(1.0, 4.0), {"force": np.array([1.0, 2.0, 3.0]),
                                         "twist": np.zeros(3)}

    dt, part = Steps().values_of({}, ("force", "depth"))
    assert np.array_equal(dt, [1.0, 2.0, 3.0]) and list(part) == ["force"]
    assert Steps().values_of({}, ("twist",), time=False)[0] is None
