"""The tables' index clip (``min(max(k, lo), hi)``) equals ``np.clip`` in values, dtype and
shape on searchsorted output, arrays and scalars alike."""
from __future__ import annotations

import numpy as np

from contactlab.profiles.tabulated._base import _clip_index


def test_clip_index_matches_np_clip():
    rng = np.random.default_rng(3)
    for _ in range(500):
        nodes = np.sort(rng.uniform(0, 1, size=int(rng.integers(2, 30))))
        x = rng.uniform(-0.5, 1.5, size=int(rng.integers(0, 20)))
        hi = int(rng.integers(0, nodes.size))
        for k in (np.searchsorted(nodes, x, side="right") - 1,
                  np.searchsorted(nodes, x, side="left"),
                  np.searchsorted(nodes, float(rng.uniform(-0.5, 1.5))) - 1):
            ref, got = np.clip(k, 0, hi), _clip_index(k, 0, hi)
            assert type(got) is type(ref) and np.shape(got) == np.shape(ref)
            assert np.asarray(got).dtype == np.asarray(ref).dtype
            assert np.array_equal(got, ref)
