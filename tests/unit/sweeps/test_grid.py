"""Grids, command-line axes, scene key paths and the batch-size rule (no pandas needed)."""
from __future__ import annotations

import itertools
import math

import numpy as np
import pytest

from contactlab.errors import ParameterError
from contactlab.sweeps import (TARGET_OVERHEAD, batch_size, make_grid, parse_axis,
                               parse_key_path, set_key_path)


def test_dict_of_lists_is_the_full_product_last_key_fastest():
    g = make_grid({"a": [1, 2, 3], "b": np.array([0.5, 1.5])})
    assert g.names == ("a", "b")
    assert [tuple(p.values()) for p in g.points] == list(itertools.product([1, 2, 3], [0.5, 1.5]))
    assert g.axes == {"a": [1, 2, 3], "b": [0.5, 1.5]}
    assert all(type(p["b"]) is float for p in g.points)      # numpy scalars become Python ones


def test_rows_keep_their_order_and_have_no_axes():
    rows = [{"x": 3.0, "m": "exact"}, {"x": 1.0, "m": "mdr"}]
    g = make_grid(rows)
    assert g.points == tuple(rows) and g.axes is None


def test_dataframe_rows():
    pd = pytest.importorskip("pandas")
    g = make_grid(pd.DataFrame({"x": [2.0, 1.0], "n": [3, 4]}))
    assert g.points == ({"x": 2.0, "n": 3}, {"x": 1.0, "n": 4})
    assert type(g.points[0]["n"]) is int


@pytest.mark.parametrize("grid, match", [
    ({}, "empty"),
    ({"a": []}, "empty"),
    ({"a": 0.3}, r"grid\['a'\]=0.3 is invalid: give a list"),
    ({"a": "abc"}, "give a list"),
    ({"point": [1]}, "table's own columns"),
    ({"a": [object()]}, "must be numbers or strings"),
    ([], "no rows"),
    ([{"a": 1}, {"b": 2}], "row 1 has keys"),
    ([1, 2], "rows must be dicts"),
    (42, "int is invalid"),
])
def test_bad_grids_raise_naming_the_problem(grid, match):
    with pytest.raises(ParameterError, match=match):
        make_grid(grid)


def test_fingerprint_tells_points_apart_exactly():
    a = make_grid({"x": [0.1, 0.2]}).fingerprint()
    assert a == make_grid({"x": [0.1, 0.2]}).fingerprint()
    assert a != make_grid({"x": [0.1, np.nextafter(0.2, 1)]}).fingerprint()


@pytest.mark.parametrize("spec, key, values", [
    ("interface.friction=0.1:0.5:5", "interface.friction", [0.1, 0.2, 0.3, 0.4, 0.5]),
    ("t=1e-4:1e-2:3:log", "t", [1e-4, 10 ** -3.0, 1e-2]),
    ("outputs.method=exact,mdr", "outputs.method", ["exact", "mdr"]),
    ("load_path[0].ramp.force=10 N,20 N", "load_path[0].ramp.force", ["10 N", "20 N"]),
    ("n=3,4", "n", [3, 4]),
    ("x=2.5", "x", [2.5]),
    ("x=1:1:1", "x", [1.0]),
])
def test_parse_axis(spec, key, values):
    k, v = parse_axis(spec)
    assert k == key
    assert len(v) == len(values)
    for got, want in zip(v, values):
        assert got == pytest.approx(want, rel=1e-15) if isinstance(want, float) else got == want
        assert type(got) is type(want)
    if spec.endswith("log"):          # the end points are exact
        assert v[0] == 1e-4 and v[-1] == 1e-2


@pytest.mark.parametrize("spec, match", [
    ("friction", "expected KEY=A:B:N"), ("=1:2:3", "expected KEY"), ("x=", "expected KEY"),
    ("x=1:2", "A:B:N or A:B:N:log"), ("x=1:2:3:lin", "A:B:N or A:B:N:log"),
    ("x=a:2:3", "must be numbers"), ("x=1:2:0", "N=0 must be >= 1"),
    ("x=0:1:3:log", "log axis needs A > 0"), ("x=1:inf:3", "finite"),
])
def test_parse_axis_errors(spec, match):
    with pytest.raises(ParameterError, match=match):
        parse_axis(spec)


def test_key_paths():
    assert parse_key_path("interface.friction") == ("interface", "friction")
    assert parse_key_path("load_path[1].sinusoid.twist") == ("load_path", 1, "sinusoid", "twist")
    assert parse_key_path("a[0][2].b") == ("a", 0, 2, "b")
    d = {"load_path": [{"ramp": {"force": 1.0}}, {"sinusoid": {"twist": 1e-3, "cycles": 2}}]}
    set_key_path(d, "load_path[1].sinusoid.twist", 2e-3)
    set_key_path(d, "interface.friction", 0.3)                 # a missing table is created
    assert d["load_path"][1]["sinusoid"] == {"twist": 2e-3, "cycles": 2}
    assert d["interface"] == {"friction": 0.3}


@pytest.mark.parametrize("path, match", [
    ("", "expected a key path"), ("a..b", "'' is not a table key"), ("a.1b", "'1b'"),
    ("a[x]", "'a\\[x\\]'"), ("load_path[2].ramp.force", r"load_path has 2 entries \(indices 0..1\)"),
    ("profile[0]", "profile is not a list"), ("profile.R.x", "profile.R is not a table"),
])
def test_bad_key_paths(path, match):
    d = {"profile": {"R": 0.01}, "load_path": [{"ramp": {}}, {"hold": {}}]}
    with pytest.raises(ParameterError, match=match):
        set_key_path(d, path, 1.0)


@pytest.mark.parametrize("point_s, overhead_s", [(1e-6, 1e-3), (1e-4, 2e-3), (3e-3, 1e-2),
                                                 (0.05, 0.01), (2.0, 0.05)])
def test_batches_keep_the_overhead_under_target(point_s, overhead_s):
    b = batch_size(point_s, overhead_s, remaining=10**9, workers=2)
    assert overhead_s <= TARGET_OVERHEAD * b * point_s * (1 + 1e-12)
    assert b == 1 or overhead_s > TARGET_OVERHEAD * (b - 1) * point_s     # and no larger
    need = b
    # a sweep large enough for both: the overhead size, leaving 4 batches per worker
    for remaining in (8 * need, 8 * need + 1, 10**6):
        assert batch_size(point_s, overhead_s, remaining=remaining, workers=2) == need
    # a sweep too small for both: the overhead target wins, but every worker gets a batch
    small = batch_size(point_s, overhead_s, remaining=40, workers=2)
    assert small == min(need, 20)
