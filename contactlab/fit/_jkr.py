"""JKR force of a power-law tip at a given indentation, with exact parameter derivatives.

Heß's rule through the MDR: the contact radius ``a`` at indentation ``δ`` solves
``h(a) = g(a) - s(a) - δ = 0`` with the critical elongation ``s = sqrt(2π a Δγ/E*)``, and the
force is the MDR force at that radius, ``F = 2E*(a δ - ∫_0^a g)``. For ``g = K a^n``
(``K = κ_n c``) everything is closed form except ``a(δ)``, found by Newton steps on the stable
branch ``a > a_c`` (``h'(a_c) = 0``), where ``h`` is increasing and convex for ``n >= 1``, from
a start to the right of the root (monotone convergence).

Derivatives at fixed ``δ`` (``a`` implicit, ``h_a = g'(a) - s/(2a) > 0`` on the branch;
``∂F/∂a|_δ = 2E*(δ - g(a)) = -2E* s``):

* ``dF/dδ = 2E* a - 2E* s/h_a``;
* ``dF/dE* = F/E* + s²/h_a``;
* ``dF/dΔγ = -2π a/h_a``.

Below the branch's smallest indentation ``δ_c = δ(a_c)`` (fixed grips: the surfaces have come
apart) the force and its derivatives are zero.
"""
from __future__ import annotations

import numpy as np

__all__ = ["JKRPower", "JKRTable"]

_NEWTON = 60
#: Newton steps after the master table's start (its error ~1e-9: two steps reach rounding)
_MASTER_NEWTON = 2
_MASTERS: dict = {}


def _master(n: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Nodes ``σ_i``, ``x_i`` and slopes ``dx/dσ`` of the branch's master curve (cached)."""
    if n not in _MASTERS:
        q = np.concatenate([[0.0], np.geomspace(1e-8, 1e8, 2000)])
        x = 1.0 + q
        psi = x ** n - 2.0 * n * np.sqrt(x)
        sig = np.sqrt(np.maximum(psi - (1.0 - 2.0 * n), 0.0))
        dpsi = n * x ** (n - 1.0) - n / np.sqrt(x)
        m = np.empty_like(x)
        m[1:] = 2.0 * sig[1:] / dpsi[1:]
        m[0] = np.sqrt(2.0 / (n * (n - 0.5)))          # ψ''(1) = n(n - 1/2)
        _MASTERS[n] = (sig, x, m)
    return _MASTERS[n]


def _paraboloid_x(y: np.ndarray) -> np.ndarray:
    """The paraboloid's master curve in closed form: ``x = u²`` with ``u >= 1`` the largest
    root of the quartic ``u⁴ - 4u - y = 0`` (``y >= -3``), by Ferrari's resolvent cubic
    ``m³ + y m - 2 = 0``, whose real root is written ``m = 2/(A² + AB + B²)`` (no
    cancellation; ``A³ = 1 + √(1 + y³/27)``, ``B = y/(3A)``), and ``u² - √(2m) u + m - 2/√(2m)
    = 0``. Near the branch end (``y → -3``, a double root) the last square root loses
    digits; one Newton step in ``σ`` restores them."""
    y = np.maximum(y, -3.0)
    A = np.cbrt(1.0 + np.sqrt(np.maximum(1.0 + y * y * y / 27.0, 0.0)))
    B = y / (3.0 * A)
    m = 2.0 / (A * A + A * B + B * B)
    s = np.sqrt(2.0 * m)
    u = 0.5 * (s + np.sqrt(np.maximum(8.0 / s - 2.0 * m, 0.0)))
    return np.maximum(u * u, 1.0)


def _hermite_x(s: np.ndarray, sn: np.ndarray, xn: np.ndarray, mn: np.ndarray) -> np.ndarray:
    k = np.clip(np.searchsorted(sn, s, side="right") - 1, 0, sn.size - 2)
    h = sn[k + 1] - sn[k]
    t = (s - sn[k]) / h
    t2 = t * t
    t3 = t2 * t
    return ((2 * t3 - 3 * t2 + 1) * xn[k] + (t3 - 2 * t2 + t) * h * mn[k]
            + (3 * t2 - 2 * t3) * xn[k + 1] + (t3 - t2) * h * mn[k + 1])


class JKRPower:
    """JKR through the MDR for ``f = c r^n`` (``n >= 1``).

    Parameters
    ----------
    kc : float
        ``K = κ_n c`` of the transform ``g = K a^n``.
    n : float
        Exponent (>= 1).
    """

    def __init__(self, kc: float, n: float) -> None:
        self.K, self.n = float(kc), float(n)

    def critical(self, E_star: float, w: float) -> tuple[float, float]:
        """Contact radius ``a_c`` (m) and indentation ``δ_c`` (m) where the branch ends."""
        K, n = self.K, self.n
        beta = np.sqrt(2.0 * np.pi * w / E_star)
        if beta == 0.0:
            return 0.0, 0.0
        a_c = (beta / (2.0 * n * K)) ** (1.0 / (n - 0.5))
        return a_c, K * a_c ** n - beta * np.sqrt(a_c)

    def radius(self, delta: np.ndarray, E_star: float, w: float) -> np.ndarray:
        """Contact radius on the stable branch (m); ``nan`` below ``δ_c``.

        With ``x = a/a_c`` the branch is one master curve for every ``E*`` and ``Δγ``:
        ``δ = δ_s ψ(x)``, ``ψ(x) = x^n - 2n√x``, ``δ_s = K a_c^n`` (since
        ``β √a_c = 2nK a_c^n`` at the branch end). In ``σ = √(ψ(x) - ψ(1))``, which grows
        linearly from the branch end (where ``ψ' = 0``), ``x(σ)`` is a cubic Hermite table built
        once per exponent; two Newton steps on ``σ(x) = σ`` then reach rounding. The paraboloid
        (``n = 2``) takes the closed form of :func:`_paraboloid_x` and one Newton step."""
        K, n = self.K, self.n
        a_c, d_c = self.critical(E_star, w)
        if a_c == 0.0:                          # no adhesion: Hertz-like
            return (np.maximum(delta, 0.0) / K) ** (1.0 / n)
        out = np.full(np.shape(delta), np.nan)
        on = delta >= d_c
        out[on] = a_c * self._master_x(delta[on] / (K * a_c ** n))
        return out

    def _master_x(self, y: np.ndarray) -> np.ndarray:
        """``x = a/a_c >= 1`` on the master curve at ``y = δ/δ_s >= ψ(1)``."""
        n = self.n
        sig = np.sqrt(np.maximum(y - (1.0 - 2.0 * n), 0.0))
        if n == 2.0:
            x = _paraboloid_x(y)
            steps = 1
        else:
            sn, xn, mn = _master(n)
            x = _hermite_x(np.minimum(sig, sn[-1]), sn, xn, mn)
            beyond = sig > sn[-1]
            if np.any(beyond):                  # beyond the table: x^n = y + 2n√x
                yb = np.maximum(y[beyond], 1.0)
                far = yb ** (1.0 / n)
                x[beyond] = (yb + 2.0 * n * np.sqrt(far)) ** (1.0 / n)
            steps = _MASTER_NEWTON
        for _ in range(steps):
            sx = np.sqrt(x)
            xn_ = x * x if n == 2.0 else x ** n
            psi = xn_ - 2.0 * n * sx
            dpsi = n * xn_ / x - n / sx
            s_x = np.sqrt(np.maximum(psi - (1.0 - 2.0 * n), 0.0))
            ok = dpsi > 0
            # Newton on σ(x) = σ: σ' = ψ'/(2σ)
            x = np.maximum(x - np.where(ok, (s_x - sig) * 2.0 * s_x / np.where(ok, dpsi, 1.0),
                                        0.0), 1.0)
        return x

    def branch_end(self, E_star: float, w: float) -> tuple[float, float]:
        """Force (N) and indentation (m) at the end of the branch."""
        a_c, d_c = self.critical(E_star, w)
        return 2.0 * E_star * (a_c * d_c - self.K * a_c ** (self.n + 1.0) / (self.n + 1.0)), d_c

    def forces(self, delta: np.ndarray, E_star: np.ndarray, w: np.ndarray) -> np.ndarray:
        """Forces (N) of several parameter sets at once (a start search): ``delta`` of shape
        ``(m, k)``, ``E_star`` and ``w`` of shape ``(m,)`` (``w > 0``); zeros where apart."""
        K, n = self.K, self.n
        beta = np.sqrt(2.0 * np.pi * w / E_star)
        a_c = (beta / (2.0 * n * K)) ** (1.0 / (n - 0.5))
        d_c = K * a_c ** n - beta * np.sqrt(a_c)
        out = np.zeros(delta.shape)
        on = delta >= d_c[:, None]
        rows = on.nonzero()[0]
        d = delta[on]
        a = a_c[rows] * self._master_x(d / (K * a_c[rows] ** n))
        out[on] = 2.0 * E_star[rows] * (a * d - K * a ** (n + 1.0) / (n + 1.0))
        return out

    def force(self, delta: np.ndarray, E_star: float, w: float
              ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """Force (N) and its derivatives ``dF/dδ``, ``dF/dE*``, ``dF/dΔγ`` at indentations
        ``δ``; zeros where the surfaces are apart."""
        K, n = self.K, self.n
        a_c, d_c = self.critical(E_star, w)
        if a_c > 0.0:                           # only the attached points are computed
            out = np.zeros((4, np.size(delta)))
            on = (delta >= d_c).nonzero()[0]
            d = delta[on]
            a = a_c * self._master_x(d / (K * a_c ** n))
            if n == 2.0:                        # the paraboloid without general powers
                F = 2.0 * E_star * (a * d - K * (a * a * a) / 3.0)
                s = np.sqrt((2.0 * np.pi * w / E_star) * a)
                ha = 2.0 * K * a - s / (2.0 * a)
            else:
                F = 2.0 * E_star * (a * d - K * a ** (n + 1.0) / (n + 1.0))
                s = np.sqrt(2.0 * np.pi * w * a / E_star)
                ha = n * K * a ** (n - 1.0) - s / (2.0 * a)
            # ha > 0 on the branch (a > a_c); 0 at its end
            inv = np.where(ha > 0, 1.0 / np.where(ha > 0, ha, 1.0), 0.0)
            out[0, on] = F
            out[1, on] = 2.0 * E_star * (a - s * inv)
            out[2, on] = F / E_star + s * s * inv
            out[3, on] = -2.0 * np.pi * a * inv
            return out[0], out[1], out[2], out[3]
        a = self.radius(delta, E_star, w)
        on = np.isfinite(a)
        a = np.where(on, a, 0.0)
        G = K * a ** (n + 1.0) / (n + 1.0)
        F = 2.0 * E_star * (a * delta - G)
        s = np.sqrt(2.0 * np.pi * w * a / E_star)
        with np.errstate(divide="ignore", invalid="ignore"):
            ha = n * K * a ** (n - 1.0) - s / (2.0 * a)
            inv = np.where(on & (ha > 0), 1.0 / ha, 0.0)
        dF_dd = 2.0 * E_star * (a - s * inv)
        dF_dE = F / E_star + s * s * inv
        dF_dw = -2.0 * np.pi * a * inv
        z = np.zeros_like(F)
        return (np.where(on, F, z), np.where(on, dF_dd, z), np.where(on, dF_dE, z),
                np.where(on, dF_dw, z))


class JKRTable:
    """JKR through the MDR for any tip without a wall (the exact sphere, measured tables, sums):
    the transform ``g`` is a cubic Hermite interpolant in the contact radius through nodes
    ``g(a_i)`` with the slopes ``g'(a_i)`` (closed form where the profile has one, else
    differences of a finer evaluation), so ``g``, ``g'``, ``g''`` and ``∫g`` of the model are
    exact piecewise polynomials; ``a(δ)`` follows from a start by interpolation of ``h`` at the
    nodes and Newton steps on ``h(a) = g(a) - β√a - δ``; the derivatives are those of
    :class:`JKRPower` with the model's ``g'``.

    Parameters
    ----------
    profile : Profile
        The tip.
    a_max : float
        Largest contact radius the fit may need, m.
    rtol : float
        Tolerance of the profile's routes.
    """

    def __init__(self, profile, a_max: float, rtol: float = 1e-12, nodes: int = 1025) -> None:
        key = ("jkr", nodes, a_max, rtol)
        cache = profile.__dict__.setdefault("_fit_tip_tables", {})
        if key not in cache:
            a = a_max * np.linspace(0.0, 1.0, nodes) ** 1.5      # graded towards the apex
            g = profile._g(a, rtol)
            g[0] = 0.0
            gp = self._slopes(profile, a, rtol)
            # exact integral of each cubic piece: h (y0 + y1)/2 + h² (m0 - m1)/12
            h = np.diff(a)
            G = np.concatenate([[0.0], np.cumsum(h * (g[:-1] + g[1:]) / 2
                                                  + h * h * (gp[:-1] - gp[1:]) / 12)])
            am = 0.5 * (a[1:] + a[:-1])                           # the table's measured error
            gm = profile._g(am, rtol)
            val = 0.5 * (g[:-1] + g[1:]) + h * (gp[:-1] - gp[1:]) / 8
            inner = gm > 1e-6 * g[-1]
            err = float(np.max(np.abs(val - gm)[inner] / gm[inner], initial=0.0))
            cache[key] = (a, g, gp, G, err)
        self.a, self.g, self.gp, self.G, self.error = cache[key]
        self.a_max = a_max
        #: a punch wall at the table's end (its radius, m; ``inf`` without)
        self.wall = float(profile.wall_radius) if a_max >= profile.wall_radius else np.inf

    @staticmethod
    def _slopes(profile, a: np.ndarray, rtol: float) -> np.ndarray:
        fn = getattr(profile, "_g_prime_closed_form", None)
        if fn is not None and profile.g_route == "closed_form":
            with np.errstate(all="ignore"):
                gp = np.asarray(fn(a), float)
            if np.all(np.isfinite(gp)):
                return gp
        # fourth-order central differences on a finer step (inside a wall: the last node's
        # stencil ends at the wall)
        eps = 1e-3 * np.diff(a).min()
        x = np.clip(a, 2 * eps, profile.wall_radius - 2 * eps)
        f = [profile._g(x + k * eps, rtol) for k in (-2, -1, 1, 2)]
        return (f[0] - 8 * f[1] + 8 * f[2] - f[3]) / (12 * eps)

    # ------------------------------------------------------------------ the interpolant
    def _piece(self, a: np.ndarray, full: bool = True) -> tuple[np.ndarray, ...]:
        """``g``, ``g'`` and (``full``) ``g''`` and ``∫_0^a g`` of the model at radii ``a``."""
        an, gn, mn, Gn = self.a, self.g, self.gp, self.G
        k = np.clip(np.searchsorted(an, a, side="right") - 1, 0, an.size - 2)
        x0 = an[k]
        h = an[k + 1] - x0
        t = (a - x0) / h
        y0, y1, m0, m1 = gn[k], gn[k + 1], mn[k], mn[k + 1]
        t2, t3 = t * t, t * t * t
        g = ((2 * t3 - 3 * t2 + 1) * y0 + (t3 - 2 * t2 + t) * h * m0 + (3 * t2 - 2 * t3) * y1
             + (t3 - t2) * h * m1)
        gp = ((6 * t2 - 6 * t) / h * (y0 - y1) + (3 * t2 - 4 * t + 1) * m0 + (3 * t2 - 2 * t) * m1)
        if not full:
            return g, gp
        gpp = ((12 * t - 6) / (h * h) * (y0 - y1) + (6 * t - 4) / h * m0 + (6 * t - 2) / h * m1)
        t4 = t2 * t2
        Gi = h * ((t4 / 2 - t3 + t) * y0 + (t4 / 4 - 2 * t3 / 3 + t2 / 2) * h * m0
                  + (t3 - t4 / 2) * y1 + (t4 / 4 - t3 / 3) * h * m1)
        return g, gp, gpp, Gn[k] + Gi

    def critical(self, E_star: float, w: float) -> tuple[float, float]:
        """Contact radius ``a_c`` (m) where ``h'(a_c) = 0`` and the indentation ``δ_c = h(a_c)``
        (the end of the stable branch)."""
        key = (E_star, w)
        memo = self.__dict__.setdefault("_critical_memo", {})
        if key not in memo:
            if len(memo) > 64:
                memo.clear()
            memo[key] = self._critical(E_star, w)
        return memo[key]

    def _critical(self, E_star: float, w: float) -> tuple[float, float]:
        beta = np.sqrt(2.0 * np.pi * w / E_star)
        if beta == 0.0:
            return 0.0, 0.0
        an = self.a[1:]
        ha = self.gp[1:] - beta / (2.0 * np.sqrt(an))
        if np.isfinite(self.wall) and not ha[-1] > 0:
            # the branch would end beyond the wall (a start's trial Δγ far too high): it ends
            # at the wall, where the contact radius stops
            return float(an[-1]), float(self.g[-1] - beta * np.sqrt(an[-1]))
        i = int(np.argmax(ha > 0))
        a = np.array([an[i]])
        for _ in range(12):                       # Newton on h'(a) = 0 from the right
            _, gp, gpp, _ = self._piece(a)
            f = gp - beta / (2.0 * np.sqrt(a))
            d = gpp + beta / (4.0 * a ** 1.5)
            step = f / d if d[0] > 0 else np.zeros(1)
            a = np.clip(a - step, an[max(i - 1, 0)] if i > 0 else 1e-300, an[i])
            if abs(step[0]) <= 1e-12 * a[0]:   # quadratic: the next step is at rounding
                break
        g, *_ = self._piece(a)
        return float(a[0]), float(g[0] - beta * np.sqrt(a[0]))

    def radius(self, delta: np.ndarray, E_star: float, w: float) -> np.ndarray:
        """Contact radius on the stable branch (m); ``nan`` below ``δ_c``."""
        beta = np.sqrt(2.0 * np.pi * w / E_star)
        a_c, d_c = self.critical(E_star, w)
        on = delta >= d_c
        an = self.a
        hn = self.g - beta * np.sqrt(an)
        j0 = int(np.searchsorted(an, a_c))
        br_a, br_h = np.concatenate([[a_c], an[j0:]]), np.concatenate([[d_c], hn[j0:]])
        a = np.interp(delta, br_h, br_a)             # start: h is increasing on the branch
        last_a = self.__dict__.get("_last")
        if last_a is not None and last_a.shape == a.shape:
            # the previous call's radii: a fit moves its parameters little between calls
            a = np.where(np.isfinite(last_a) & (last_a >= a_c), last_a, a)
        last = False
        move = on & (delta < hn[-1]) if np.isfinite(self.wall) else on
        for _ in range(_NEWTON):
            g, gp = self._piece(a, full=False)
            sa = np.sqrt(a)
            hval = g - beta * sa - delta
            ha = gp - beta / (2.0 * np.where(sa > 0, sa, 1.0))
            step = np.where(move & (ha > 0), hval / np.where(ha > 0, ha, 1.0), 0.0)
            a = np.clip(a - step, a_c, an[-1])
            if last:
                break
            last = not np.any(np.abs(step) > 1e-10 * np.maximum(a, 1e-300))
        if np.isfinite(self.wall):          # beyond the wall's depth the radius stays at it
            a = np.where(on & (delta >= hn[-1]), an[-1], a)
        out = np.where(on, a, np.nan)
        self._last = out
        return out

    def force(self, delta: np.ndarray, E_star: float, w: float
              ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """Force (N) and ``dF/dδ``, ``dF/dE*``, ``dF/dΔγ`` (zeros where apart)."""
        a = self.radius(delta, E_star, w)
        on = np.isfinite(a)
        a = np.where(on, a, 0.0)
        _, gp, _, G = self._piece(a)
        F = 2.0 * E_star * (a * delta - G)
        s = np.sqrt(2.0 * np.pi * w * a / E_star)
        with np.errstate(divide="ignore", invalid="ignore"):
            ha = gp - s / (2.0 * a)
            inv = np.where(on & (ha > 0), 1.0 / ha, 0.0)
        if np.isfinite(self.wall):          # at the wall a does not move: F = 2E*(bδ - ∫g)
            at_wall = on & (delta >= self.g[-1] - np.sqrt(2.0 * np.pi * w / E_star * self.a[-1]))
            inv = np.where(at_wall, 0.0, inv)
        z = np.zeros_like(F)
        return (np.where(on, F, z), np.where(on, 2.0 * E_star * (a - s * inv), z),
                np.where(on, F / E_star + s * s * inv, z), np.where(on, -2.0 * np.pi * a * inv, z))

    def branch_end(self, E_star: float, w: float) -> tuple[float, float]:
        """Force (N) and indentation (m) at the end of the branch."""
        a_c, d_c = self.critical(E_star, w)
        G = self._piece(np.array([a_c]))[3][0]
        return 2.0 * E_star * (a_c * d_c - G), d_c
