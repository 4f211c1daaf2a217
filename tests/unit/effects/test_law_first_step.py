"""The first changing-load step of the compiled ContactLaw (issue 29): the switch onto the
springs and the first spring step fused per contact (``law_kernel_springs._first_pass``) give
the bits of the switch then the step (``_switch_step_pass``, blocks of contacts switched then
stepped): every output, every row entry, the rows' owners, the flags and the counts, for every
family, with and without each channel, contacts whose load rose or fell (edge cells moving
both ways), Masing stacks with turning points, and fresh covers a radius outgrows."""
from __future__ import annotations

import warnings

import numpy as np
import pytest

import contactlab as cl
from contactlab.errors import ValidityWarning

HAS_NUMBA = cl.effects.law._kernel.AVAILABLE
pytestmark = pytest.mark.skipif(not HAS_NUMBA, reason="numba (extra 'fast') not installed")

FAMILIES = [(cl.profiles.Paraboloid, "R", (1e-3, 1e-2), {}),
            (cl.profiles.Cone, "slope", (0.05, 0.3), {}),
            (cl.profiles.PowerLaw, "c", (1e2, 1e3), {"n": 1.5}),
            (cl.profiles.FlatPunch, "radius", (1e-4, 1e-3), {})]
ROWS = ("spr_cover", "spr_a", "spr_k", "spr_depth", "spr_tan", "spr_tor", "spr_x_tan",
        "spr_x_tor")


def _inputs(family, gname, lo_hi, extra, seed):
    """A law after a held-load history with reversals (turning points in both stacks), and the
    next step's depth, radius and controls with every contact's load changed."""
    from contactlab.physics.law_kernel import normal_pass
    rng = np.random.default_rng(seed)
    n = 300
    law = cl.ContactLaw(family, **{gname: rng.uniform(*lo_hi, n)}, E_star=1.15e11,
                        G_star=4.4e10, G_torsion=4e10, friction=rng.uniform(0.1, 0.5, n),
                        memory=5, fast=True, spring_reserve=1.0, **extra)
    F = rng.uniform(1.0, 100.0, n)
    u = np.cumsum(rng.standard_normal((8, n)), axis=0) * 3e-8
    phi = np.cumsum(rng.standard_normal((8, n)), axis=0) * 1e-4
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ValidityWarning)
        for k in range(7):
            law.step(force=F, displacement=u[k], twist=phi[k])
    F2 = F * rng.choice([0.5, 0.97, 1.0, 1.03, 2.0], n)
    d, a, *_ = normal_pass(True, F2, u[7], phi[7], law.kc, law.E_star, law.n, law._flat,
                           law._st["depth_ref"], law.load_rtol, False, None)
    return law, d.copy(), a.copy(), u[7], phi[7]


def _run(kernel, law, d, a, u, phi, cover_factor, block=None, clean=None):
    n = law.size
    pool = law._pool
    pool.slot[:] = -1
    P = pool.rows
    for key in ROWS:                    # garbage: each pass must write what it owns
        P[key][:n] = 7
        if clean is not None:           # rows from ``clean`` on: +0 (as never written)
            P[key][clean:n] = 0
    pool.owner[:n] = -7
    out = tuple(np.full(n, 7.0) for _ in range(5))
    flag = np.zeros(n, np.int8)
    beta = law._beta
    nn = 1.0 if law.n == np.inf else float(law.n)
    bG, bH = beta ** (nn + 1.0) / (nn + 1.0), beta ** (nn + 2.0) / (nn + 2.0)
    chan = law._chan
    empty = np.zeros(1)
    args = (np.arange(n, dtype=np.int64), law._st["depth_ref"], a, law._flat,
            law.n == np.inf, cover_factor, law.kc, nn, beta, bG, bH, law.friction,
            law.E_star, law.G_star, law.G_torsion, chan["X"], chan["depth"], chan["x"],
            pool.slot, pool.owner, 0, d, empty if u is None else u,
            empty if phi is None else phi, u is not None, phi is not None,
            *(P[key] for key in ROWS), *out, flag)
    counts = (kernel(*args) if block is None else kernel(block, *args) if clean is None
              else kernel(*args, clean))
    return (counts, [o.copy() for o in out], flag.copy(), pool.slot.copy(),
            pool.owner[:n].copy(), {key: P[key][:n].copy() for key in ROWS})


CASES = [(fam, channels, parallel) for fam in FAMILIES
         for channels in ("both", "displacement", "twist") for parallel in (False, True)]


@pytest.fixture(params=CASES, ids=[f"{c[0][0].__name__}-{c[1]}-{'threads' if c[2] else 'serial'}"
                                   for c in CASES])
def first_step(request):
    """``make(seed)``: the compiled kernels (serial or threaded), a law after its held-load
    history, the next step's inputs with the case's channels, and covers of which every 7th is
    below 1 (the law refuses that: radii beyond a fresh cover)."""
    (family, gname, lo_hi, extra), channels, parallel = request.param
    from contactlab.physics.law_kernel import _kernels

    def make(seed):
        law, d, a, u, phi = _inputs(family, gname, lo_hi, extra, seed)
        u = u if channels != "twist" else None
        phi = phi if channels != "displacement" else None
        cover = law.spring_cover.copy()
        cover[::7] = 0.93
        return _kernels(parallel), law, d, a, u, phi, cover
    return make


def _assert_same_bits(ref, got):
    """Counts, outputs, flags, slots, owners and every row entry bit for bit."""
    assert ref[0] == got[0]
    for x, y in zip(ref[1], got[1]):
        assert x.tobytes() == y.tobytes()
    for i in (2, 3, 4):
        assert np.array_equal(ref[i], got[i])
    for key in ROWS:
        assert ref[5][key].tobytes() == got[5][key].tobytes(), key


def test_fused_first_step_is_the_switch_then_the_step(first_step):
    kernels, law, d, a, u, phi, cover = first_step(5)
    ref = _run(kernels[4], law, d, a, u, phi, cover, block=13)
    got = _run(kernels[6], law, d, a, u, phi, cover)
    _assert_same_bits(ref, got)
    assert ref[0][1] > 0                               # (non-finite, grown); some grown
    assert not np.any(ref[5]["spr_k"] == 7)           # every row written (garbage 7 before)
    assert np.any(ref[5]["spr_k"] != ref[5]["spr_k"][0])


def test_clean_rows_are_not_written_beyond_the_edge(first_step):
    """Rows from the pool's ``clean`` mark on hold +0 (never written): the fused pass leaves
    their cells beyond both edge cells alone, and every output and row entry is the bits of
    the switch then the step on rows of garbage (rows below the mark are zeroed as before)."""
    kernels, law, d, a, u, phi, cover = first_step(6)
    ref = _run(kernels[4], law, d, a, u, phi, cover, block=13)
    for clean in (0, 117):
        _assert_same_bits(ref, _run(kernels[6], law, d, a, u, phi, cover, clean=clean))
