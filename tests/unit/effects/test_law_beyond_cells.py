"""ContactLaw on its springs: the elements of the cells beyond a contact's edge cell (issue 29).

A cell out of contact has zero slip limits, so its element is a zero. The spring step writes
+0 there when the cell leaves the contact (or when its channel was not driven since: the pool's
``stale`` flags) and then neither reads nor writes it while it stays beyond both the last and
the present edge cell; both routes (numpy, compiled) the same way. Checked here: every such
element is +0 to the byte in both routes, and skipping them changes no bit of any output or
state entry against zeroing every cell beyond the edge in every step.
"""
from __future__ import annotations

import warnings

import numpy as np
import pytest

import contactlab as cl
from contactlab.errors import ValidityWarning

HAS_NUMBA = cl.effects.law._kernel.AVAILABLE
ROUTES = [False, True] if HAS_NUMBA else [False]
FIELDS = ("force", "tangential_force", "torque", "stick_radius", "torsion_stick_radius",
          "dissipated_energy", "exact")
FAMILIES = [(cl.profiles.Paraboloid, "R", (1e-3, 1e-2), {}),
            (cl.profiles.Cone, "slope", (0.05, 0.3), {}),
            (cl.profiles.PowerLaw, "c", (1e2, 1e3), {"n": 1.5})]


class _Always(dict):
    """Stale flags that are always set: every cell beyond the edge is zeroed in every step
    (the step before the cells beyond both edges were skipped, up to the sign of zeros)."""

    def __getitem__(self, key):
        return True

    def __setitem__(self, key, value):
        pass


def _run(family, gname, lo_hi, extra, fast, zero_all=False, checks=None):
    """A changing-load history: loads rising and falling (edges moving both ways), a few
    contacts growing past their cover (regridded), some separating, steps without the
    displacement or the twist (that channel not driven), a state saved and restored. Returns
    the outputs per step and the final state; ``checks(law, step)`` after each step."""
    rng = np.random.default_rng(11)
    n, steps = 40, 36
    par = dict({gname: rng.uniform(*lo_hi, n)}, E_star=1.15e11, G_star=4.4e10,
               G_torsion=4e10, friction=rng.uniform(0.1, 0.5, n), memory=4, fast=fast,
               springs=12, **extra)
    law = cl.ContactLaw(family, **par)
    F = rng.uniform(1.0, 100.0, n)
    u = np.cumsum(rng.standard_normal((steps, n)), axis=0) * 3e-8
    phi = np.cumsum(rng.standard_normal((steps, n)), axis=0) * 1e-4
    outs = []
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ValidityWarning)
        for k in range(steps):
            L = F.copy()
            if k >= 4:
                L[:30] *= 1.0 + 0.4 * np.sin(0.9 * k + np.arange(30))
            if k >= 24:
                L[:6] *= 2.0 + k / 8.0                  # beyond their covers: regridded
            if 14 <= k < 17:
                L[32:36] = 0.0                          # separated, then back
            if k == 20:
                state = {key: np.array(v) for key, v in law.state.items()}
                law = cl.ContactLaw(family, **par)
                law.state = state
            if zero_all and law._pool is not None:
                law._pool.stale = _Always()
            r = law.step(force=L, displacement=None if k % 7 == 5 else u[k],
                         twist=None if k % 5 == 3 else phi[k])
            outs.append({f: np.array(getattr(r, f)) for f in FIELDS})
            if checks is not None:
                checks(law, k)
    return outs, law.state


@pytest.mark.parametrize("fast", ROUTES)
@pytest.mark.parametrize("family, gname, lo_hi, extra", FAMILIES,
                         ids=[f[0].__name__ for f in FAMILIES])
def test_skipping_the_cells_beyond_both_edges_changes_no_bit(family, gname, lo_hi, extra, fast):
    """Every output and state entry to the byte as with every cell beyond the edge zeroed in
    every step: the cells skipped are +0 already, also after steps that did not drive a
    channel (stale), a restored state and regrids."""
    a, sa = _run(family, gname, lo_hi, extra, fast)
    b, sb = _run(family, gname, lo_hi, extra, fast, zero_all=True)
    for k, (x, y) in enumerate(zip(a, b)):
        for f in FIELDS:
            assert x[f].tobytes() == y[f].tobytes(), f"step {k}: {f}"
    assert sa["spr_on"].any()
    for key, v in sa.items():
        assert np.asarray(v).tobytes() == np.asarray(sb[key]).tobytes(), key


@pytest.mark.parametrize("family, gname, lo_hi, extra", FAMILIES,
                         ids=[f[0].__name__ for f in FAMILIES])
def test_cells_beyond_the_edge_are_plus_zero_in_both_routes(family, gname, lo_hi, extra):
    """After every step that drives a channel, each element beyond its row's edge cell is
    +0.0 (the bytes of +0, not -0) in that channel, in the numpy and in the compiled law, and
    the two routes' elements there agree to the byte (the compiled law before left -0 where a
    cell left the contact with a negative force: numba's min(-0, +0) is -0, numpy's +0)."""
    seen = {}

    def checks(law, k):
        st = law.state
        on = st["spr_on"]
        beyond = np.arange(st["spr_tan"].shape[1])[None, :] > st["spr_k"][:, None]
        beyond &= on[:, None]
        for ch, driven in (("tan", k % 7 != 5), ("tor", k % 5 != 3)):
            if not driven:
                continue
            v = st[f"spr_{ch}"][beyond]
            assert v.size == 0 or (not np.any(v) and not np.any(np.signbit(v))), (k, ch)
            seen.setdefault(law.fast, {})[(k, ch)] = (beyond, v.tobytes())

    for fast in ROUTES:
        _run(family, gname, lo_hi, extra, fast, checks=checks)
    assert seen[False] and sum(len(v) for _, v in seen[False].values()) > 0
    if HAS_NUMBA:       # the same cells beyond the edge, the same bytes there
        for key, (mask, v) in seen[False].items():
            assert np.array_equal(seen[True][key][0], mask), key
            assert seen[True][key][1] == v, key
