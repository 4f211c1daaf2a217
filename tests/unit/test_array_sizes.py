"""The array solves (normal, tangential, torsion), the field methods of their states and
``peak_pressure`` estimate their peak memory before allocating and raise
:class:`MemoryBudgetError` above the budget (docs/robustness.md). Each call of the review that
found them is refused with a message naming the request and its size, while tracemalloc's peak
stays small; the same calls within the budget return the bits they returned without the check,
and their measured peak lies below the estimate."""
from __future__ import annotations

import functools
import math
import re
import tracemalloc

import numpy as np
import pytest

import contactlab as cl
from contactlab.effects import sizes
from contactlab.errors import MemoryBudgetError

STEEL = cl.Elastic(E=210e9, nu=0.3)
RT = np.linspace(0.0, 2e-3, 41)
PROFILES = {
    "paraboloid": cl.profiles.Paraboloid(R=0.01),
    "cone": cl.profiles.Cone(slope=0.1),
    "sphere": cl.profiles.Sphere(R=0.01),
    "table": cl.profiles.Tabulated(RT, RT**2 / 0.02, interpolation="cubic"),
}


def contact(name: str = "paraboloid") -> cl.Contact:
    return cl.Contact(PROFILES[name], materials=(STEEL, STEEL), friction=0.2)


def adhesive(name: str = "paraboloid") -> cl.Contact:
    return cl.Contact(PROFILES[name], materials=(STEEL, STEEL), work_of_adhesion=0.5)


@pytest.fixture
def budget():
    """Set a budget for one test; the previous setting is restored after it."""
    previous = cl.set_memory_budget(None)
    yield cl.set_memory_budget
    cl.set_memory_budget(previous)


def traced_peak(call):
    """``call()``'s result (or the exception it raised) and tracemalloc's peak, bytes."""
    tracemalloc.start()
    try:
        base = tracemalloc.get_traced_memory()[0]
        try:
            out = call()
        except Exception as err:            # noqa: BLE001 - returned for the caller to judge
            out = err
        return out, tracemalloc.get_traced_memory()[1] - base
    finally:
        tracemalloc.stop()


F3 = np.linspace(1.0, 100.0, 10**3)


def _refused_calls():
    c = contact()
    r5 = np.linspace(0.0, 1e-4, 10**5)
    return {
        "pressure": (lambda: c.normal(force=F3), lambda s: s.pressure(r5),
                     r"pressure\(\) would need about 23.8 GiB \(state \(1000,\) x r \(100000,\)"),
        "displacement": (lambda: c.normal(force=F3), lambda s: s.displacement(r5),
                         r"displacement\(\) would need .* GiB \(state \(1000,\) x r \(100000,\)"),
        "tangential shear": (lambda: c.tangential(force=F3, tangential_force=1.0),
                             lambda s: s.shear(r5),
                             r"shear\(\) would need about 23.8 GiB \(state \(1000,\) x r "),
        "torsion": (lambda: None,
                    lambda _: c.torsion(force=np.broadcast_to(1.0, (10**6,)), twist=1e-4),
                    r"torsion\(\) would need about 3.81 GiB \(force x twist broadcast to "
                    r"\(1000000,\), method='exact': 1000000 values x 4096 B"),
        "peak_pressure": (lambda: c.normal(force=np.linspace(1.0, 100.0, 10**4)),
                          lambda s: s.peak_pressure,
                          r"peak_pressure would need .* GiB \(10000 states x 1024 radii"),
        "torsion shear": (lambda: c.torsion(force=F3[:100], twist=1e-4),
                          lambda s: s.shear(np.linspace(0.0, 1e-4, 10**6)),
                          r"shear\(\) would need .* GiB \(state \(100,\) x r \(1000000,\)"),
        "torsion displacement": (lambda: c.torsion(force=F3[:100], twist=1e-4, method="mdr"),
                                 lambda s: s.displacement(np.linspace(0.0, 1e-4, 10**6)),
                                 r"displacement\(\) would need .* GiB \(state \(100,\) x r "),
        "tangential": (lambda: None,
                       lambda _: c.tangential(force=np.ones((10**4, 1)),
                                              tangential_force=np.ones((1, 10**4)) * 0.1),
                       r"tangential\(\) would need about 191 GiB \(force x tangential_force "
                       r"broadcast to \(10000, 10000\)"),
        "normal": (lambda: None, lambda _: c.normal(force=np.linspace(1.0, 100.0, 10**6)),
                   r"normal\(\) would need .* \(force \(1000000,\): 1000000 values x 64 B"),
        "adhesive normal": (lambda: None,
                            lambda _: adhesive().normal(depth=np.linspace(-1e-7, 1e-6, 10**6)),
                            r"normal\(\) would need about 0.954 GiB \(depth \(1000000,\), "
                            r"adhesive: 1000000 values x 1024 B"),
    }


@pytest.mark.parametrize("name", list(_refused_calls()))
def test_large_calls_are_refused_before_they_allocate(budget, name):
    make, call, match = _refused_calls()[name]
    state = make()                      # (the state itself is small, made before the budget)
    budget("10M")
    err, peak = traced_peak(lambda: call(state))
    assert isinstance(err, MemoryBudgetError), err
    assert re.search(match, str(err)), str(err)
    assert "CONTACTLAB_MEMORY_BUDGET" in str(err)
    assert peak < 12e6                  # the input's own checks at most (10^6 forces: 1 MB)


def _within_calls():
    """(profile, call, estimate in bytes): sizes whose estimate fits a budget of 2x it."""
    F = np.linspace(1.0, 100.0, 100)
    out = []
    for name in PROFILES:
        # (a cubic table's fields take seconds per 10^4 points: fewer radii there)
        r = np.linspace(0.0, 2e-4, 100 if name == "table" else 1000)
        kind = sizes.route_kind(PROFILES[name])
        field = F.size * r.size * sizes.FIELD_BYTES_PER_POINT[kind]
        out += [
            (name, "normal", lambda c: c.normal(force=np.linspace(1.0, 100.0, 10**4)).force,
             10**4 * sizes.NORMAL_BYTES_PER_LOAD[kind]),
            (name, "pressure", lambda c, r=r: c.normal(force=F).pressure(r), field),
            (name, "displacement", lambda c, r=r: c.normal(force=F).displacement(r), field),
            (name, "peak_pressure", lambda c: c.normal(force=F).peak_pressure,
             F.size * sizes.PEAK_RADII * sizes.PEAK_BYTES_PER_RADIUS[kind]),
            (name, "tangential", lambda c: c.tangential(force=F[:, None],
                                                        tangential_force=F[None, :20] / 100
                                                        ).tangential_force,
             F.size * 20 * sizes.TANGENTIAL_BYTES_PER_LOAD),
            (name, "tangential shear",
             lambda c, r=r: c.tangential(force=F, tangential_force=1.0).shear(r), field),
        ]
        for method in ("exact", "mdr"):
            n = 300
            out += [
                (name, f"torsion {method}",
                 lambda c, m=method, n=n: c.torsion(force=F[:, None], twist=np.geomspace(
                     1e-6, 1e-4, n // 100)[None, :], method=m).torque,
                 n * sizes.torsion_bytes_per_load(method, PROFILES[name])),
                (name, f"torsion {method} shear",
                 lambda c, m=method, r=r: c.torsion(force=F[:5], twist=1e-4,
                                                    method=m).shear(r[:200]),
                 5 * r[:200].size * sizes.TORSION_FIELD_BYTES_PER_POINT[method]),
            ]
    for name in PROFILES:
        for key, lo, hi in (("depth", -1e-9, 1e-6), ("force", 0.0, 100.0),
                            ("radius", 0.0, 2e-4)):
            out.append((name, f"adhesive normal by {key}",
                        lambda c, k=key, lo=lo, hi=hi, name=name: adhesive_once(name).normal(
                            **{k: np.linspace(lo, hi, 10**4)}).radius,
                        10**4 * sizes.ADHESIVE_NORMAL_BYTES_PER_LOAD))
    return out


#: the adhesive contact of each profile, built once (its JKR branches cached before a call is
#: measured, as the plain contacts' profile caches are)
adhesive_once = functools.lru_cache(maxsize=None)(adhesive)


@pytest.mark.parametrize("name, what, call, estimate", _within_calls(),
                         ids=[f"{n}-{w}" for n, w, _, _ in _within_calls()])
def test_calls_within_the_budget_give_the_same_bits_within_their_estimate(budget, name, what,
                                                                          call, estimate):
    c = contact(name)
    unchecked = call(c)                 # default budget (2 GiB): what the call gave before
    call(c)                             # (caches of the profile built: not the call's own)
    budget(max(2.0 * estimate, 1e6))
    got, peak = traced_peak(lambda: call(c))
    assert not isinstance(got, Exception), got
    np.testing.assert_array_equal(np.asarray(got), np.asarray(unchecked), strict=True)
    assert peak <= estimate + 1e6, (peak, estimate)     # the estimate covers the measured peak


def test_a_scalar_call_is_not_checked_on_its_fast_route(budget, monkeypatch):
    """The scalar fast route of normal() holds no array: it never reaches the check."""
    import contactlab.effects.normal as normal

    def fail(*args, **kwargs):
        raise AssertionError("checked")

    monkeypatch.setattr(normal, "check_elements", fail)
    budget(1.0)
    assert contact().normal(force=100.0).force == 100.0


def test_the_budget_edge_is_the_estimate(budget):
    """A budget just above a call's estimate passes it, just below refuses it."""
    c = contact()
    s = c.normal(force=F3)
    r = np.linspace(0.0, 1e-4, 1000)
    need = math.prod(s.shape) * r.size * sizes.FIELD_BYTES_PER_POINT["closed"]
    budget(need * 1.001)
    s.pressure(r)
    budget(need * 0.999)
    with pytest.raises(MemoryBudgetError, match=r"pressure\(\)"):
        s.pressure(r)
