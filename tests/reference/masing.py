"""Masing's rule with unbounded memory for one contact, and the Cattaneo–Mindlin loading curve of
a Hertzian (paraboloid) contact in closed form.

Sources: G. Masing, Eigenspannungen und Verfestigung beim Messing, Proc. 2nd Int. Congr. Appl.
Mech., Zürich 1926, 332-335 (a branch from a turning point (x_o, y_o) follows y_o ± 2 y_v(|x - x_o|/2)
with the virgin curve y_v; a branch that passes the turning point where its enclosing loop
began rejoins the older branch: the inner loop is erased). R. D. Mindlin, H. Deresiewicz,
Elastic spheres in contact under varying oblique forces, J. Appl. Mech. 20 (1953) 327-344:
virgin curve F = μF_N [1 - (1 - u/u*)^(3/2)] for u < u* = μE* d / G* (E*, G* the effective
normal and tangential moduli, d = a²/R the depth), and μF_N beyond.

A plain Python list holds every turning point (no bound); nothing here imports contactlab.
"""
from __future__ import annotations

import math

__all__ = ["hertz_mindlin_virgin", "masing_path"]


def hertz_mindlin_virgin(u: float, F_N: float, mu: float, u_star: float) -> float:
    """Cattaneo–Mindlin virgin curve of a paraboloid, N, at displacement ``u >= 0``."""
    if u >= u_star:
        return mu * F_N
    return mu * F_N * (1.0 - (1.0 - u / u_star) ** 1.5)


def masing_path(xs, virgin) -> list[float]:
    """Response of Masing's rule with unbounded turning-point memory along the controls ``xs``
    (starting from the virgin state at x = 0); ``virgin(x >= 0)`` is the loading curve (odd
    extension for x < 0). Each control is reached by one monotonic move from the previous one.
    """
    turning = []                    # (x, y) of every open reversal, oldest first
    x_prev, y_prev, direction = 0.0, 0.0, 0
    out = []
    for x in xs:
        x = float(x)
        if x != x_prev:
            s = 1 if x > x_prev else -1
            if direction != 0 and s != direction:       # reversal at the previous point
                turning.append((x_prev, y_prev))
            direction = s
            # the active branch closes when it passes the start of the branch it reversed
            # from (or, from the first reversal, the virgin curve's mirror point): its loop
            # is erased and the older branch continues
            while turning:
                lim = turning[-2][0] if len(turning) >= 2 else -turning[0][0]
                if (x - lim) * direction <= 0:
                    break
                del turning[-2:]
        if turning:
            xo, yo = turning[-1]
            y = yo + math.copysign(2.0 * virgin(abs(x - xo) / 2.0), x - xo)
        else:
            y = math.copysign(virgin(abs(x)), x)
        out.append(y)
        x_prev, y_prev = x, y
    return out
