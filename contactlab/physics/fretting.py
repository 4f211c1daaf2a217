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

from ..errors import ConvergenceError
from .torsion_exact import C_MIN_REL
from .torsion_validity import twist_at_stick_ratio

__all__ = ["STICK", "PARTIAL_SLIP", "GROSS_SLIP", "REGIMES", "CRITERIA", "energy_ratio",
           "loop_branches", "classify", "criterion_value", "torsional_gross_slip",
           "MDR_VALID_STICK_RATIOS", "mdr_validity_twists", "torsional_boundary",
           "BOUNDARY_RTOL", "BOUNDARY_GRID", "BOUNDARY_STAGES"]

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


def criterion_value(criterion: str, A: np.ndarray | None, c: np.ndarray, a: np.ndarray,
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


# ------------------------------------------------------------------ torsional gross-slip boundary
#: Relative width of the certified twist bracket of :func:`torsional_boundary` (a tighter
#: ``rtol`` of the contact tightens it further).
BOUNDARY_RTOL = 1e-10

#: ``y = ln(c/a)`` nodes that bracket the boundary before the root solve: ``y = 0`` (no slip), then
#: ``|y|`` log-spaced from 1e-5 to ``|ln C_MIN_REL|`` (full sliding to double precision), three
#: nodes per decade. (A criterion met between ``y = -1e-5`` and 0 is still bracketed, by the
#: first two nodes; the MDR annulus quadrature of a flat punch fails closer to ``c = a``.)
BOUNDARY_GRID = np.concatenate([[0.0], -np.logspace(-5.0, np.log10(-np.log(C_MIN_REL)), 23)])

#: ``|y|`` up to which the scan for the bracket goes in its first and second stage (c/a >= 6e-6,
#: >= 2e-22); only states not met by then go on to the next stage.
BOUNDARY_STAGES = (12.0, 50.0)

#: Iteration cap of the bracketed solve (Chandrupatla: at worst about bisection, so 200 steps
#: cover any float bracket).
_BOUNDARY_MAXITER = 200


def torsional_boundary(model, a: np.ndarray, d: np.ndarray, g_a: np.ndarray, criterion: str,
                       threshold: float, rtol: float = BOUNDARY_RTOL) -> np.ndarray:
    """Twist amplitude (rad) at which a torsional gross-slip criterion is first met, per state.

    The criterion value (:func:`criterion_value` of the steady loop) is monotone along the loading
    curve, which is parametrised by ``y = ln(c/a)``: at each ``y`` the model gives the twist, the
    torque and the dissipation directly (no inner root solve). The crossing is bracketed on
    :data:`BOUNDARY_GRID` (all states in one batched evaluation) and solved by a vectorised
    bracketing iteration (Chandrupatla's inverse quadratic interpolation with bisection
    safeguard) over all states at once. The bracket is certified: the criterion is met at
    one end and not at the other at every step, and the iteration stops when the twists of its
    ends differ by at most ``rtol`` relative. The twist of the end where the criterion is met is
    returned, so a loop at the returned amplitude is classified gross slip.

    Parameters
    ----------
    model : TorsionModel
        The torsion model (:mod:`contactlab.physics.torsion`); ``"no-slip"`` never slips.
    a, d, g_a : ndarray
        Contact radius (m), depth (m) and ``g(a)`` (m) of the normal states, flat, equal size.
    criterion : {"energy_ratio", "stick_ratio", "torque_ratio"}
    threshold : float
        In (0, 1).
    rtol : float
        Relative width of the certified twist bracket.

    Returns
    -------
    ndarray
        Twist amplitudes, rad; ``inf`` where the criterion is not met for any stick radius down
        to ``C_MIN_REL a`` (or without contact, or without slip).

    Raises
    ------
    ConvergenceError
        The bracket did not reach ``rtol`` within the iteration cap.
    """
    n = a.size
    out = np.full(n, np.inf)
    live = np.flatnonzero(a > 0)
    if model.name == "no-slip" or live.size == 0:
        return out
    a, d, g_a = a[live], d[live], g_a[live]
    sliding = model.sliding_torque(a, d)

    def at(y: np.ndarray, idx: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Twist and criterion value minus threshold (>= 0: met) at ``c = a e^y``."""
        A_, D_, G_ = a[idx], d[idx], g_a[idx]
        sol = model.of_stick_radius(A_ * np.exp(y), A_, D_, G_)
        phi = sol.twist
        A_ratio = None
        if criterion == "energy_ratio":             # the dissipation costs most: only here
            W = 4.0 * model.dissipation(phi, sol.stick_radius, A_, D_, G_)
            A_ratio = energy_ratio(W, phi, sol.torque)
        v = criterion_value(criterion, A_ratio, sol.stick_radius, A_, sol.torque, sliding[idx])
        return phi, (threshold - v if criterion == "stick_ratio" else v - threshold)

    if criterion == "stick_ratio":                  # met exactly from c = threshold a on
        out[live] = at(np.full(a.size, np.log(threshold)), np.arange(a.size))[0]
        return out
    grid = BOUNDARY_GRID
    m = grid.size
    phi_g, f_g = np.full((a.size, m), np.nan), np.full((a.size, m), np.nan)
    # the scan goes deeper (smaller c) only for states not met yet: the dissipation quadrature of
    # one state costs in proportion to ln(a/c), and c/a of every threshold up to 0.9 (Hertz)
    # lies above 1e-5
    rows, start = np.arange(a.size), 0
    for stop in (*np.searchsorted(-grid, BOUNDARY_STAGES, side="right"), m):
        if rows.size == 0 or stop <= start:
            continue
        k = stop - start
        p_, f_ = at(np.tile(grid[start:stop], rows.size), np.repeat(rows, k))
        phi_g[rows, start:stop] = p_.reshape(rows.size, k)
        f_g[rows, start:stop] = f_.reshape(rows.size, k)
        rows = rows[~np.any(f_g[rows, start:stop] >= 0, axis=1)]
        start = stop
    res = np.full(a.size, np.inf)
    # met already without slip (c = a): only the torque ratio of a profile with a wall, whose
    # torque is the no-slip (16/3) G_t a³ φ up to the first slip; the criterion is linear there
    at_top = f_g[:, 0] >= 0
    if np.any(at_top):
        K0 = 16.0 / 3.0 * model.G * a[at_top] ** 3
        res[at_top] = threshold * sliding[at_top] / K0
    hit = f_g >= 0
    first = np.argmax(hit, axis=1)                  # first node (from c = a down) where met
    solve = np.flatnonzero(~at_top & hit.any(axis=1))
    if solve.size:
        j = first[solve]
        j3 = np.minimum(j + 1, m - 1)               # a third node for the first interpolation
        f3 = f_g[solve, j3]
        j3 = np.where(np.isfinite(f3), j3, j - 1)
        res[solve] = _solve_boundary(at, solve, grid[j], grid[j - 1], f_g[solve, j],
                                     f_g[solve, j - 1], phi_g[solve, j], phi_g[solve, j - 1],
                                     grid[j3], f_g[solve, j3], rtol)
    out[live] = res
    return out


def _chandrupatla_step(x1, x2, x3, f1, f2, f3, tol):
    """Next point as a fraction of the way from ``x1`` to ``x2`` (Chandrupatla 1997): inverse
    quadratic interpolation through the three points where it is safe, bisection otherwise, at
    least half a tolerance inside the bracket."""
    width = np.abs(x2 - x1)
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        xi = (x1 - x2) / (x3 - x2)
        ph = (f1 - f2) / (f3 - f2)
        iqi = ((1 - np.sqrt(np.maximum(1 - xi, 0.0))) < ph) & (ph < np.sqrt(np.maximum(xi, 0.0)))
        alpha = (x3 - x1) / (x2 - x1)
        tq = f1 / (f1 - f2) * f3 / (f3 - f2) - alpha * f1 / (f3 - f1) * f2 / (f2 - f3)
        tl = 0.5 * tol / np.where(width > 0, width, 1.0)
    tn = np.where(iqi & np.isfinite(tq), tq, 0.5)
    tl = np.clip(tl, 4 * np.finfo(float).eps, 0.5)
    return np.clip(tn, tl, 1 - tl)


def _solve_boundary(at, idx: np.ndarray, y_lo: np.ndarray, y_hi: np.ndarray, f_lo: np.ndarray,
                    f_hi: np.ndarray, p_lo: np.ndarray, p_hi: np.ndarray, y_3: np.ndarray,
                    f_3: np.ndarray, rtol: float) -> np.ndarray:
    """Vectorised bracketed solve of ``f(y) = 0`` with ``f(y_lo) >= 0 > f(y_hi)``, until the twists
    ``p`` at the two ends of the bracket agree to ``rtol``; returns the twist of the end where
    ``f >= 0`` (the criterion is met).

    Chandrupatla's steps (T. R. Chandrupatla, Adv. Eng. Softw. 28 (1997) 145): inverse quadratic
    interpolation where it is safe, bisection otherwise, every step at least half a tolerance
    inside the bracket, so the last steps straddle the root and both ends close in. The step
    tolerance in ``y`` is ``rtol |y| / 4`` (``|d ln φ/d ln|y|| <= 1.3`` along the loading curves
    measured, so this is finer than ``rtol`` in the twist); the stop is on the twists themselves.
    """
    # x1 newest point, x2 the end of opposite sign, x3 the point dropped last
    x1, x2 = np.array(y_lo, float), np.array(y_hi, float)
    f1, f2 = np.array(f_lo, float), np.array(f_hi, float)
    p1, p2 = np.array(p_lo, float), np.array(p_hi, float)
    x3, f3 = np.array(y_3, float), np.array(f_3, float)

    def tol_of(x1, x2, f1, f2):
        return 0.25 * rtol * np.maximum(np.abs(np.where(np.abs(f1) <= np.abs(f2), x1, x2)), 1e-300)
    step = _chandrupatla_step(x1, x2, x3, f1, f2, f3, tol_of(x1, x2, f1, f2))
    act = np.arange(x1.size)
    for _ in range(_BOUNDARY_MAXITER):
        a1, a2 = x1[act], x2[act]
        met1 = f1[act] >= 0
        p_met, p_not = np.where(met1, p1[act], p2[act]), np.where(met1, p2[act], p1[act])
        done = ((np.abs(p_met - p_not) <= rtol * np.minimum(p_met, p_not))
                | (np.where(met1, f1[act], f2[act]) == 0))
        mid = 0.5 * (a1 + a2)
        done |= (mid == a1) | (mid == a2)                       # no float left inside
        act = act[~done]
        if act.size == 0:
            break
        a1, a2, st = x1[act], x2[act], step[act]
        xn = np.where(st <= 0.5, a1 + st * (a2 - a1), a2 + (1.0 - st) * (a1 - a2))
        pn, fn = at(xn, idx[act])
        g1, g2 = f1[act], f2[act]
        same = (fn >= 0) == (g1 >= 0)
        x3[act] = np.where(same, a1, a2)
        f3[act] = np.where(same, g1, g2)
        x2[act] = np.where(same, a2, a1)
        f2[act] = np.where(same, g2, g1)
        p2[act] = np.where(same, p2[act], p1[act])
        x1[act], f1[act], p1[act] = xn, fn, pn
        step[act] = _chandrupatla_step(x1[act], x2[act], x3[act], f1[act], f2[act], f3[act],
                                       tol_of(x1[act], x2[act], f1[act], f2[act]))
    else:
        raise ConvergenceError(f"torsional gross-slip boundary: the twist bracket did not "
                               f"shrink to rtol={rtol:g} in {_BOUNDARY_MAXITER} steps.")
    return np.where(f1 >= 0, p1, p2)
