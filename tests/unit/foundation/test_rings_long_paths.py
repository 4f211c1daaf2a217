"""The exact ring solver on long paths (issue 28): its share of ring-solver steps must not grow
with the number of steps of the same load history.

On a varying-load Hertz path cut into many small steps, the single-slip-annulus step failed its
check inside the stick radius on exceedances of the friction limit of the discretisation's order
(within a ring of the stick radius, while the twist is ramped in): 15 % of 10^4
steps went to the ring solver (3 % of 10^2). The step is now taken when the exceedance lies
within a ring of the stick radius and, weighted by the points' torque, stays within a share of
the ring count's error law (:func:`contactlab.foundation.rings.inside_allowance`). The
reference of the result is the strict solver (no allowance) at twice the rings.
"""
from __future__ import annotations

import numpy as np
import pytest

import contactlab as cl
from contactlab.foundation import rings as _rings
from contactlab.physics import torsion_annulus as _ta
from contactlab.physics.torsion import METHODS
from tests.tolerances import RINGS_LONG_PATH_FALLBACK, RINGS_LONG_PATH_TORQUE

MU = 0.3
C = cl.Contact(cl.profiles.Paraboloid(R=0.01),
               materials=(cl.Elastic(E=210e9, nu=0.3), cl.Rigid()), friction=MU)
N, M = 10_000, 600


def _path():
    """The first ``M`` steps of the benchmark's 10^4-step path (benchmarks/exact_speed.py): force
    10 N +- 40 % at two cycles, twist at 80 % of sliding at three cycles, ramped in."""
    t = np.arange(1, N + 1) / N
    force = 10.0 * (1 + 0.4 * np.sin(2 * np.pi * 2 * t + 0.3))
    a_max = float(np.max(C.normal(force=force)._radius))
    s = MU * 10.0 / (C.moduli.torsional * a_max ** 2)
    phi = 0.8 * s * np.sin(2 * np.pi * 3 * t) * np.minimum(1, 2 * t)
    return cl.LoadPath.from_arrays(force=force[:M], twist=phi[:M]), force[:M]


def _sliding_torque(force: np.ndarray) -> float:
    ns = C.normal(force=force)
    model = METHODS["exact"](C.profile, C.moduli.normal, C.moduli.torsional, MU, C.rtol)
    return float(np.max(model.sliding_torque(np.asarray(ns._radius, float),
                                             np.asarray(ns._depth, float))))


def test_small_steps_stay_on_the_annulus_step():
    path, _ = _path()
    r = C.simulate(path, method="exact")
    assert r.meta["fallback_steps"] <= RINGS_LONG_PATH_FALLBACK * M


def test_accepted_exceedances_within_the_ring_error(monkeypatch):
    path, force = _path()
    out = C.simulate(path, method="exact")
    monkeypatch.setattr(_rings, "INSIDE_ALLOWANCE", 0.0)
    ref = C.simulate(path, method="exact", n_rings=400)
    assert float(np.max(np.abs(out.torque - ref.torque))) <= (
        RINGS_LONG_PATH_TORQUE * _sliding_torque(force))


def test_allowance_follows_the_error_law():
    c, p = _rings.RTOL_LAW
    for n in (16, 142, 200, 400):
        assert _rings.inside_allowance(n) == pytest.approx(_rings.INSIDE_ALLOWANCE * c / n ** p,
                                                           rel=1e-15)


def _state():
    """A density from rest and a step from it whose traction inside the stick radius exceeds
    the friction limit: the limit lowered below the traction at the innermost point."""
    rings = _rings.Rings(C.profile, C.moduli, MU, 1e-4, n_springs=40)
    r, b, G_t = rings.points, rings.boundaries, C.moduli.torsional
    p = 1e9 * np.sqrt(np.maximum(1.0 - (r / b[-1]) ** 2, 0.0))
    bound = MU * p
    slide = _ta.nonnegative_psi(_ta.density(rings.lu, b, rings.jumps, bound, b[-1]))
    first = _ta.step(_ta.empty(), slide, b[-1], G_t, dphi=2e-4, r=r, bound=bound, slip=False,
                     table=rings.table)
    assert first["ok"] and 0 < first["c"] < b[-1]
    return rings, first, slide, bound


def test_allow_accepts_only_up_to_its_torque():
    rings, first, slide, bound = _state()
    r, b, G_t = rings.points, rings.boundaries, C.moduli.torsional
    inside = r < first["c"]
    tau = np.abs(_ta.traction(first["w"], r, G_t, rings.table))
    low = bound.copy()
    k = int(np.flatnonzero(inside)[-1])
    low[k] = 0.5 * tau[k]               # the limit halved at the last point inside c
    excess = tau[k] - low[k] * (1 + _ta.CHECK_RTOL)
    w = np.abs(rings.g)
    kw = dict(r=r, bound=low, slip=False, table=rings.table)
    strict = _ta.step(_ta.empty(), slide, b[-1], G_t, dphi=2e-4, **kw)
    assert not strict["ok"] and strict["why"].startswith("traction")
    ok = _ta.step(_ta.empty(), slide, b[-1], G_t, dphi=2e-4,
                  allow=(w, 1.01 * w[k] * excess, b[-1]), **kw)
    assert ok["ok"] and ok["c"] == strict["c"]
    short = _ta.step(_ta.empty(), slide, b[-1], G_t, dphi=2e-4,
                     allow=(w, 0.99 * w[k] * excess, b[-1]), **kw)
    assert not short["ok"]
    # the point beyond the limit farther from c than the band: refused whatever the torque
    far = _ta.step(_ta.empty(), slide, b[-1], G_t, dphi=2e-4,
                   allow=(w, 1e3 * w[k] * excess, 0.99 * (strict["c"] - r[k])), **kw)
    assert not far["ok"]
    near = _ta.step(_ta.empty(), slide, b[-1], G_t, dphi=2e-4,
                    allow=(w, 1e3 * w[k] * excess, 1.01 * (strict["c"] - r[k])), **kw)
    assert near["ok"]


def test_allow_carries_no_torque_beyond_sliding():
    """A torque target above the step's sliding torque is gross sliding: an excess inside the
    stick radius (the old traction, full sliding at a higher limit) must not carry it."""
    rings, _, high, bound = _state()
    b, G_t = rings.boundaries, C.moduli.torsional
    low = 0.9 * bound
    slide = _ta.nonnegative_psi(_ta.density(rings.lu, b, rings.jumps, low, b[-1]))
    M_sl = _ta.torque(slide, G_t)
    w = np.abs(rings.g)
    kw = dict(r=rings.points, bound=low, slip=False, table=rings.table)
    for target in (1.001 * M_sl, 1.05 * M_sl):
        huge = _ta.step(high, slide, b[-1], G_t, target_torque=target,
                        allow=(w, 1e3 * M_sl, b[-1]), **kw)
        assert not (huge["ok"] and np.isfinite(huge["gross"]))
    # a target within the sliding torque: the allowance takes the step
    within = _ta.step(high, slide, b[-1], G_t, target_torque=0.999 * M_sl,
                      allow=(w, 1e3 * M_sl, b[-1]), **kw)
    assert within["ok"] and 0 < within["c"] < b[-1]


def test_allowance_gives_the_same_bits_on_the_compiled_route(monkeypatch):
    """The compiled annulus step (numeric.annulus_kernel) decides the check inside the stick
    radius itself only where no allowance is to be weighed; an exceedance goes to the numpy check
    with the allowance, so both routes take the same steps (the compiled route without it sent
    489 of the 600 steps to the ring solver, the numpy route 42)."""
    path, _ = _path()
    runs = []
    for on in (False, True):
        monkeypatch.setitem(_ta._COMPILED, "on", on)
        if on and _ta._annulus_kernels() is None:
            pytest.skip("no compiled route (numba absent or the numpy backend forced)")
        runs.append(C.simulate(path, method="exact"))
    assert runs[0].meta["fallback_steps"] == runs[1].meta["fallback_steps"]
    for key in ("torque", "twist", "dissipated_energy", "stick_radius"):
        assert np.asarray(getattr(runs[0], key)).tobytes() == np.asarray(
            getattr(runs[1], key)).tobytes(), key
