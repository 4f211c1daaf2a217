"""MDR springs for many contacts at once: the changing-normal-load regime of the contact law.

Each contact carries ``N`` cells (Jenkins elements) of the Winkler foundation
(:mod:`contactlab.foundation.winkler`) over ``0 <= x <= cover``, edge-refined
(``b_j = cover (1 - (1 - j/N)²)``), for a power-law profile ``g(x) = kc x^n``. The per-step
arithmetic is the foundation's, vectorised over contacts × cells:

* normal cell integrals ``S = ∫_cell (d - g)_+ dx`` and ``T = ∫_cell x (d - g)_+ dx`` exact
  (closed forms of ``∫g`` and ``∫xg``), the edge cell's partial integral included;
* slip limits ``2μE* S`` (tangential) and ``4μE* T`` (torsion); stiffnesses ``2G* w`` and
  ``16 G_t ∫_cell x² dx``, weighted by the part of each cell in contact during the step
  (``ΔS/(w Δd)``; the contact fraction at held depth);
* elements ``m ← clip(m + K_eff Δ, -L, L)``, dissipation ``Σ (trial - m) m / K_eff``.

Pure kernels: plain arrays in, arrays out (state arrays updated in place).
"""
from __future__ import annotations

import numpy as np

__all__ = ["unit_boundaries", "cells", "normal_cells", "weights", "jenkins_rows",
           "stick_radius", "replay", "interp_rows"]


def unit_boundaries(N: int) -> np.ndarray:
    """Edge-refined boundaries on ``[0, 1]`` (the foundation's ``"edge"`` spacing)."""
    s = np.linspace(0.0, 1.0, N + 1)
    b = 1.0 - (1.0 - s) ** 2
    b[-1] = 1.0
    return b


def cells(cover: np.ndarray, kc: np.ndarray, n: float, beta: np.ndarray) -> dict:
    """Cell geometry of contacts with cover radii ``cover`` (m), ``g = kc x^n``: boundaries,
    widths, ``∫g`` and ``∫xg`` at the boundaries and ``∫x`` / ``∫x²`` per cell (rows: contacts)."""
    b = cover[:, None] * beta
    kc = kc[:, None]
    Gb = kc * b ** (n + 1.0) / (n + 1.0)
    Hb = kc * b ** (n + 2.0) / (n + 2.0)
    return {"b": b, "bl": b[:, :-1], "w": np.diff(b, axis=1), "Gb": Gb, "dG": np.diff(Gb, axis=1),
            "Hb": Hb, "dH": np.diff(Hb, axis=1), "X1": np.diff(b * b, axis=1) / 2.0,
            "X2": np.diff(b ** 3, axis=1) / 3.0, "kc": kc, "n": n}


def normal_cells(geo: dict, d: np.ndarray, a: np.ndarray) -> tuple[np.ndarray, ...]:
    """``(S, T, k)``: cell integrals ``∫(d-g)_+`` and ``∫x(d-g)_+`` per cell and the index of
    the edge cell, for depths ``d`` and radii ``a`` (one per row, ``a <= cover``)."""
    b, bl, n, kc = geo["b"], geo["bl"], geo["n"], geo["kc"]
    N = bl.shape[1]
    k = np.minimum(np.sum(b[:, 1:] < a[:, None], axis=1), N - 1)
    rows = np.arange(k.size)
    blk = bl[rows, k]
    ac = a[:, None]
    Ga = (kc * ac ** (n + 1.0) / (n + 1.0))[:, 0]
    Ha = (kc * ac ** (n + 2.0) / (n + 2.0))[:, 0]
    inside = a > blk
    S_e = np.maximum(np.where(inside, d * (a - blk) - (Ga - geo["Gb"][rows, k]), 0.0), 0.0)
    T_e = np.maximum(np.where(inside, d * (a * a - blk * blk) / 2.0 - (Ha - geo["Hb"][rows, k]),
                              0.0), 0.0)
    beyond = np.arange(N)[None, :] > k[:, None]
    S = d[:, None] * geo["w"] - geo["dG"]
    T = d[:, None] * geo["X1"] - geo["dH"]
    S[beyond] = 0.0
    T[beyond] = 0.0
    S[rows, k] = S_e
    T[rows, k] = T_e
    return S, T, k


def weights(geo: dict, S: np.ndarray, S_old: np.ndarray, k: np.ndarray, k_old: np.ndarray,
            dd: np.ndarray, a: np.ndarray) -> np.ndarray:
    """Contact weight of each cell over the step: ``ΔS/(w Δd)`` clipped to [0, 1] between the
    old and new edge cells, 1 inside, 0 outside; the contact fraction where ``Δd = 0``."""
    N = S.shape[1]
    j = np.arange(N)[None, :]
    lo = np.minimum(k, k_old)[:, None]
    hi = (np.maximum(k, k_old) + 1)[:, None]
    moved = dd != 0.0
    safe = np.where(moved, dd, 1.0)[:, None]
    ws = np.clip((S - S_old) / (safe * geo["w"]), 0.0, 1.0)
    wgt = np.where(j < lo, 1.0, np.where(j >= hi, 0.0, ws))
    frac = np.clip((a[:, None] - geo["bl"]) / geo["w"], 0.0, 1.0)
    return np.where(moved[:, None], wgt, frac)


def jenkins_rows(m: np.ndarray, Keff: np.ndarray, L: np.ndarray, inc: np.ndarray) -> np.ndarray:
    """``m ← clip(m + K_eff inc, -L, L)`` in place (rows: contacts); returns the energy
    dissipated per row, ``Σ (trial - m) m / K_eff``."""
    trial = m + Keff * inc[:, None]
    np.clip(trial, -L, L, out=m)
    with np.errstate(divide="ignore", invalid="ignore"):
        e = np.where(Keff > 0, (trial - m) * m / Keff, 0.0)
    return e.sum(axis=1)


def stick_radius(m: np.ndarray, L: np.ndarray, bl: np.ndarray, a: np.ndarray) -> np.ndarray:
    """Left edge of the first element at its slip limit (cells out of contact count as
    slipping), at most the contact radius ``a``."""
    slip = np.abs(m) >= L
    i = np.argmax(slip, axis=1)
    rows = np.arange(a.size)
    return np.where(slip[rows, i], np.minimum(bl[rows, i], a), a)


def replay(X: np.ndarray, depth: np.ndarray, x: np.ndarray, Keff: np.ndarray,
           L: np.ndarray) -> np.ndarray:
    """Element forces after the history ``0 → X[:, 0] → … → X[:, depth-1] → x`` at fixed
    stiffness and limits (the spring state equivalent to a Masing turning-point stack)."""
    m = np.zeros(Keff.shape)
    prev = np.zeros(x.size)
    for j in range(int(depth.max(initial=0))):       # over stored turning points (<= memory)
        on = depth > j
        tgt = np.where(on, X[:, j], prev)
        m = np.clip(m + Keff * (tgt - prev)[:, None], -L, L)
        prev = tgt
    return np.clip(m + Keff * (x - prev)[:, None], -L, L)


def interp_rows(xq: np.ndarray, xp: np.ndarray, fp: np.ndarray) -> np.ndarray:
    """Row-wise linear interpolation of ``fp(xp)`` at ``xq`` (each row increasing; constant
    beyond the last node)."""
    j = np.sum(xp[:, None, 1:-1] <= xq[:, :, None], axis=2)          # interval per query
    rows = np.arange(xq.shape[0])[:, None]
    x0, x1 = xp[rows, j], xp[rows, j + 1]
    f0, f1 = fp[rows, j], fp[rows, j + 1]
    t = np.clip((xq - x0) / (x1 - x0), 0.0, 1.0)
    return f0 + t * (f1 - f0)
