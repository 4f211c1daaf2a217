"""Fretting loops and running-condition regimes at constant normal load: pure kernels.

A steady fretting loop of amplitude ``δ*`` (shift) or ``φ*`` (twist) follows Masing's rule from
the monotonic loading curve ``y_load`` (force or torque) and its dissipation ``D_load`` [MD53,
D54; docs/fretting.md]:

* loop maximum ``Q* = y_load(δ*)``; branches ``y = ±Q* ∓ 2 y_load((δ* ∓ x)/2)``;
* energy per cycle ``W = 4 D_load(δ*)`` (each half cycle is a Masing branch of excursion
  ``2δ*``, which dissipates ``2 D_load(δ*)``); equivalently ``W = 8∫_0^{δ*} y_load - 4δ*Q*``;
* Fouvry's energy ratio ``A = W / (4 δ* Q*)``;
* minimum stick radius = the virgin-curve stick radius at ``δ*``.

Regimes (Vingsbo & Söderberg 1988): ``0`` stick (``c = a``), ``1`` partial slip, ``2`` gross
slip. Tangential gross slip is physical (``c = 0`` at ``δ* >= δ_t = μE*(d - g(0))/G*``); for
torsion of smooth profiles ``c`` only tends to 0, so gross slip is declared by a criterion
(:data:`CRITERIA`).
"""
from __future__ import annotations

import numpy as np

from .torsion_validity import twist_at_stick_ratio

__all__ = ["STICK", "PARTIAL_SLIP", "GROSS_SLIP", "REGIMES", "CRITERIA", "energy_ratio",
           "loop_branches", "classify", "criterion_value", "torsional_gross_slip",
           "MDR_VALID_STICK_RATIOS", "mdr_validity_twists"]

STICK, PARTIAL_SLIP, GROSS_SLIP = 0, 1, 2
#: Regime names by code.
REGIMES = ("stick", "partial_slip", "gross_slip")

#: Torsional gross-slip criteria and their default thresholds. ``"energy_ratio"``: ``A >= 0.2``
#: (Fouvry's transition value; for tangential Hertz contacts ``A = 1/(2n+1) = 0.2`` exactly at the
#: onset of gross slip, docs/fretting.md); ``"stick_ratio"``: ``c/a <= 0.1``; ``"torque_ratio"``:
#: ``M*/M_slide >= 0.95``.
CRITERIA: dict[str, float] = {"energy_ratio": 0.2, "stick_ratio": 0.1, "torque_ratio": 0.95}


def energy_ratio(W: np.ndarray, amplitude: np.ndarray, peak: np.ndarray) -> np.ndarray:
    """Fouvry's energy ratio ``A = W/(4 x* y*)`` (0 where the loop has no area)."""
    W, amplitude, peak = np.broadcast_arrays(*(np.asarray(v, float) for v in
                                               (W, amplitude, peak)))
    den = 4.0 * np.abs(amplitude) * np.abs(peak)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(den > 0, W / np.where(den > 0, den, 1.0), 0.0)


def loop_branches(amplitude: float, peak: float, load_curve, n: int
                  ) -> tuple[np.ndarray, np.ndarray]:
    """The closed steady loop, ``2n + 1`` points from ``(x*, y*)`` down to ``(-x*, -y*)`` and back.

    ``load_curve(x)`` evaluates the virgin curve (vectorised, ``x >= 0``).
    """
    s = np.linspace(0.0, 2.0 * amplitude, n + 1)              # excursion from the turning point
    y_branch = peak - 2.0 * load_curve(s / 2.0)
    x_down = amplitude - s
    x = np.concatenate([x_down, -x_down[1:]])
    y = np.concatenate([y_branch, -y_branch[1:]])
    return x, y


def criterion_value(criterion: str, A: np.ndarray, c: np.ndarray, a: np.ndarray,
                    peak: np.ndarray, sliding: np.ndarray) -> np.ndarray:
    """The quantity a gross-slip criterion compares with its threshold."""
    with np.errstate(divide="ignore", invalid="ignore"):
        if criterion == "energy_ratio":
            return np.asarray(A, float)
        if criterion == "stick_ratio":
            return np.where(a > 0, c / np.where(a > 0, a, 1.0), 1.0)
        return np.where(sliding > 0, np.abs(peak) / np.where(sliding > 0, sliding, 1.0), 0.0)


def torsional_gross_slip(criterion: str, threshold: float, value: np.ndarray) -> np.ndarray:
    """True where the criterion declares gross slip (``stick_ratio``: at or below the threshold;
    the others: at or above)."""
    if criterion == "stick_ratio":
        return value <= threshold
    return value >= threshold


def classify(c: np.ndarray, a: np.ndarray, amplitude: np.ndarray, gross: np.ndarray
             ) -> np.ndarray:
    """Regime codes: stick where nothing slips (``c >= a`` or zero amplitude), gross slip where
    ``gross``, partial slip otherwise."""
    c, a, amplitude, gross = np.broadcast_arrays(c, a, amplitude, gross)
    out = np.full(c.shape, PARTIAL_SLIP, dtype=np.int8)
    out[(c >= a) | (amplitude == 0)] = STICK
    out[gross & (amplitude != 0)] = GROSS_SLIP
    return out


# ------------------------------------------------------------------ MDR torsion validity
#: Exact stick ratio ``c/a`` below which the MDR torsion model errs by more than 1 % (the
#: torque threshold :data:`~contactlab.physics.torsion.MDR_ERROR_THRESHOLD`) on each fretting
#: quantity at the same twist amplitude. Measured by ``benchmarks/fretting_error_map.py``
#: (docs/fretting.md): torque 0.80-0.823, energy per cycle (and so worn volume) 0.958-0.967,
#: stick radius 0.81-0.895 for paraboloid, cone, n = 4, n = 20 and truncated paraboloid. For
#: profiles with a wall (flat punch) the MDR energy and stick radius err by more than 1 % as soon
#: as anything slips (ratio 1).
MDR_VALID_STICK_RATIOS: dict[str, float] = {"torque": 0.83, "energy": 0.97,
                                            "stick_radius": 0.90, "worn_volume": 0.97}


def mdr_validity_twists(profile, E_star: float, G_t: float, mu: float, a: np.ndarray,
                        d: np.ndarray, g_a: np.ndarray, quantities, rtol: float
                        ) -> dict[str, np.ndarray]:
    """Twist amplitude (rad) beyond which the MDR model errs by more than 1 % on each quantity.

    The exact twist at the stick ratio :data:`MDR_VALID_STICK_RATIOS` ``[q]`` (one evaluation of
    Jäger's slip function per distinct normal state; bounded cost on large tables,
    :mod:`contactlab.physics.torsion_validity`). A profile with a wall gets 0 for
    ``energy``, ``stick_radius`` and ``worn_volume`` (any slip is out of validity).
    """
    out = {}
    wall = np.isfinite(getattr(profile, "wall_radius", np.inf))
    live = a > 0
    for q in quantities:
        ratio = MDR_VALID_STICK_RATIOS[q]
        lim = np.full(a.shape, np.inf)
        if wall and q != "torque":
            lim[live] = 0.0
        elif np.any(live):
            lim = twist_at_stick_ratio(profile, E_star, G_t, mu, ratio, a, d, g_a, rtol)
        out[q] = lim
    return out
