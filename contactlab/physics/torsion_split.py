"""Segments of the torsional field quadratures (:mod:`contactlab.physics.torsion_exact`): an
interval per element split at the profile's breakpoints, and the segment sums per element.

The lag ``ψ`` of the exact partial-slip model has a kink or a square-root cusp at every
breakpoint of the profile (the rim of a flat part, a table node); a tanh-sinh rule across one
converges too slowly to certify its tolerance, so the stick-zone traction and the
circumferential displacement integrate segment by segment.
"""
from __future__ import annotations

import numpy as np

__all__ = ["Summed", "split_at_cuts", "per_element"]


class Summed:
    """``(value, error)`` of an integral summed over its segments (for :func:`_check_field`)."""

    def __init__(self, value: np.ndarray, error: np.ndarray) -> None:
        self.value, self.error = value, error


def split_at_cuts(psi, lo: np.ndarray, hi: np.ndarray
                   ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Segments of ``[lo, hi]`` (per element) split at ``psi.cuts`` (the profile's breakpoints,
    where the lag ψ has a kink or a square-root cusp, e.g. the rim of a flat part or a table
    node: tanh-sinh across one converges too slowly to certify its tolerance). Returns
    ``(seg_lo, seg_hi, owner)``: flat segment ends and the element of each segment; elements
    without a cut inside keep one segment, in their own order first."""
    cuts = np.asarray(getattr(psi, "cuts", ()), dtype=float)
    n = lo.size
    if cuts.size == 0:
        return lo, hi, np.arange(n)
    inner = (cuts[None, :] > lo[:, None]) & (cuts[None, :] < hi[:, None])
    if not np.any(inner):
        return lo, hi, np.arange(n)
    el, j = np.nonzero(inner)
    pts = cuts[j]
    # each element's segments: [lo, c1], [c1, c2], ..., [ck, hi]; the first kept at position i
    first_hi = hi.copy()
    k = np.zeros(n, np.int64)
    np.add.at(k, el, 1)
    start = np.concatenate([[0], np.cumsum(k)[:-1]])
    rank = np.arange(el.size) - start[el]
    first_hi[el[rank == 0]] = pts[rank == 0]
    nxt = np.where(rank + 1 < k[el], np.roll(pts, -1), hi[el])
    return (np.concatenate([lo, pts]), np.concatenate([first_hi, nxt]),
            np.concatenate([np.arange(n), el]))


def per_element(values: np.ndarray, owner: np.ndarray, n: int) -> np.ndarray:
    """Sum of the segments' ``values`` per element."""
    if owner.size == n:
        return values
    out = np.zeros(n)
    np.add.at(out, owner, values)
    return out
