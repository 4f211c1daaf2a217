"""One load on a small table takes the node interval's Newton iteration in plain floats
(``_newton_one``, issue 29: the fixed cost of a 7-point table); it must give the batched
route's radius, depth and force bit for bit, on random tables and loads."""
from __future__ import annotations

import numpy as np
import pytest

import contactlab as cl
from contactlab.profiles import Tabulated
from contactlab.profiles.tabulated import _solve

MATERIALS = (cl.Elastic(E=1.0, nu=0.0), cl.Rigid())


def _tables(n: int, seed: int):
    rng = np.random.default_rng(seed)
    for _ in range(n):
        m = int(rng.integers(4, 12))
        r = np.concatenate([[0.0], np.sort(rng.uniform(0, 1, m - 1))])
        r[-1] = 1.0
        # convex gaps (non-decreasing slopes: g rises, no annulus), random slope steps
        slopes = np.cumsum(rng.uniform(0, 1, m - 1) ** rng.uniform(0.3, 3))
        f = np.concatenate([[0.0], np.cumsum(slopes * np.diff(r))])
        yield Tabulated(r, f * 10 ** rng.uniform(-3, 0))


@pytest.mark.parametrize("rtol", [1e-2, 1e-3, 1e-6, 1e-10])
@pytest.mark.parametrize("control", ["depth", "force"])
def test_one_load_is_the_batched_route(rtol, control, monkeypatch):
    calls = {"one": 0, "none": 0}
    real = _solve._newton_one

    def counting(*a, **k):
        out = real(*a, **k)
        calls["one" if out is not None else "none"] += 1
        return out

    monkeypatch.setattr(_solve, "_newton_one", counting)
    rng = np.random.default_rng(int(rtol * 1e12) % 1000 + len(control))
    for tab in _tables(25, seed=int(-np.log10(rtol)) + 7 * len(control)):
        contact = cl.Contact(tab, MATERIALS, rtol=rtol)
        top = contact.normal(radius=0.95)
        hi = top.depth if control == "depth" else top.force
        values = hi * rng.uniform(0.001, 1.0, 8)
        batch = contact.normal(**{control: values})
        for i, v in enumerate(values):
            s = contact.normal(**{control: float(v)})
            for name in ("radius", "depth", "force"):
                assert (np.float64(np.ravel(getattr(s, name))[0]).tobytes()
                        == getattr(batch, name)[i].tobytes()), (tab, v, name)
    assert calls["one"] > 100          # (the float iteration did run)
