"""Independent high-precision (mpmath) reference for torsion, written from theory §6 only.

Nothing here imports contactlab. Pressures come from the closed forms of theory §3; the slip
function ``P(x) = ∫_x^a p(s)/sqrt(s²-x²) ds`` is integrated directly from the pressure (substitution
``s = x cosh u``), the torque from the *swapped single integral* of §6.2 item 3 (a different route
from contactlab's universal-kernel form), full sliding from ``2πμ∫ p r² dr``. Hertz uses the
Lubkin-problem closed forms of §6.3 (complete elliptic integrals).

Sources: theory §3 (pressures), §6.1-6.5 (torsion), [J95], [L51], [D54], [RS44].
"""
from __future__ import annotations

import mpmath as mp

from .kappa import kappa  # noqa: F401 (re-exported: ref.kappa)

mp.mp.dps = 30



def K(m):
    """Complete elliptic integral of the first kind, parameter m = k² (mpmath convention)."""
    return mp.ellipk(m)


def E(m):
    return mp.ellipe(m)


def K_of_comp(u):
    """K with complementary modulus u (k² = 1 - u²) via the AGM: π/(2 agm(1, u))."""
    return mp.pi / (2 * mp.agm(1, u))


# ------------------------------------------------------------------ pressures (theory §3)
def pressure_power(r, a, E_star, c, n):
    """Power law f = c r^n, non-adhesive: (E* n κ_n c a^{n-1}/π) sqrt(1-ρ²) ₂F₁(1-n/2,1;3/2;1-ρ²)."""
    r, a, c, n = (mp.mpf(v) for v in (r, a, c, n))
    rho2 = (r / a) ** 2
    return (E_star * n * kappa(n) * c * a ** (n - 1) / mp.pi * mp.sqrt(1 - rho2)
            * mp.hyp2f1(1 - n / 2, 1, mp.mpf(3) / 2, 1 - rho2))


def pressure_cone(r, a, E_star, slope):
    return E_star * mp.mpf(slope) / 2 * mp.acosh(mp.mpf(a) / r)


def pressure_flat(r, a, E_star, d):
    return E_star * mp.mpf(d) / (mp.pi * mp.sqrt(mp.mpf(a) ** 2 - mp.mpf(r) ** 2))


# ------------------------------------------------------------------ general exact torsion (§6.2)
def slip_P(x, a, p):
    """P(x) = ∫_x^a p(s)/sqrt(s²-x²) ds with s² = x² + (a²-x²) sin²θ (both ends regular):
    P = ∫_0^{π/2} p(s) sqrt(a²-x²) cosθ / s dθ."""
    x, a = mp.mpf(x), mp.mpf(a)
    w = mp.sqrt(a**2 - x**2)

    def f(th):
        s = mp.sqrt(x**2 + (w * mp.sin(th)) ** 2)
        return p(min(s, a * (1 - mp.mpf(10) ** -28))) * w * mp.cos(th) / s

    return mp.quad(f, mp.linspace(0, mp.pi / 2, 5))


def torque_general(c, a, p, mu, G):
    """(twist, torque) at stick radius c: φ = μP(c)/(2G);
    M = (8/3) μ c³ P(c) + 4μ ∫_c^a p(r) [r² acos(c/r) + c sqrt(r² - c²)] dr."""
    c, a = mp.mpf(c), mp.mpf(a)
    Pc = slip_P(c, a, p)
    ring = mp.quad(lambda r: p(r) * (r**2 * mp.acos(c / r) + c * mp.sqrt(r**2 - c**2)), [c, a])
    return mu * Pc / (2 * G), mp.mpf(8) / 3 * mu * c**3 * Pc + 4 * mu * ring


def sliding_torque_general(a, p, mu, singular_edge=False):
    """M_full = 2πμ ∫_0^a p r² dr."""
    return 2 * mp.pi * mu * mp.quad(lambda r: p(r) * r**2, [0, a])


# ------------------------------------------------------------------ Hertz (§6.3)
def hertz_twist_hat(t):
    """φ̂ = φ G a²/(μF) = (3/(4π)) [K(k) - E(k)], k² = 1 - t²."""
    m = 1 - mp.mpf(t) ** 2
    return 3 / (4 * mp.pi) * (K(m) - E(m))


def hertz_torque_hat(t):
    """M̂ = M/(μFa) = 3π/16 - (4/π) ∫_0^t s² E(sqrt(1-s²)) ds."""
    t = mp.mpf(t)
    return 3 * mp.pi / 16 - 4 / mp.pi * mp.quad(lambda s: s**2 * E(1 - s**2), [0, t])


def hertz_stick_shear_hat(rho, t):
    """τ/(μ p0) in the stick zone r/a = rho < c/a = t: (2ρ/π) ∫_t^1 E(k_s)/(s sqrt(s²-ρ²)) ds."""
    rho, t = mp.mpf(rho), mp.mpf(t)
    return 2 * rho / mp.pi * mp.quad(lambda s: E(1 - s**2) / (s * mp.sqrt(s**2 - rho**2)), [t, 1])


def hertz_mdr_hat(t):
    """MDR (§6.4): φ̂ = 3(1-t²)/(16t), M̂ = (3/4)(1-t²)(1+t²/3)."""
    t = mp.mpf(t)
    return 3 * (1 - t**2) / (16 * t), mp.mpf(3) / 4 * (1 - t**2) * (1 + t**2 / 3)


def hertz_loop_energy_hat(t0):
    """Energy per cycle ±φ0 (§6.5), W/(μ²F²/(G a)) with c0/a = t0:
    W = 8∫_0^{φ0} M dφ - 4 φ0 M0, ∫_0^{φ0} M dφ = ∫_{t0}^1 M̂(t) |dφ̂/dt| dt,
    |dφ̂/dt| = (3/(4π)) E(1-t²)/t."""
    t0 = mp.mpf(t0)
    integral = mp.quad(lambda t: hertz_torque_hat(t) * 3 / (4 * mp.pi) * E(1 - t**2) / t, [t0, 1])
    return 8 * integral - 4 * hertz_twist_hat(t0) * hertz_torque_hat(t0)


# ------------------------------------------------------------------ flat punch (§6.2 item 7)
def flat_twist(t, E_star, d, a, mu, G):
    """φ = μE*d/(2πG a) K(k_c), k_c² = 1 - t² (t = c/a)."""
    return mu * E_star * mp.mpf(d) / (2 * mp.pi * G * a) * K(1 - mp.mpf(t) ** 2)


def flat_onset(E_star, d, a, mu, G):
    """φ_0 = μE*d/(4G a) and M_0 = (4/3) μ E* d a²."""
    return mu * E_star * d / (4 * G * a), mp.mpf(4) / 3 * mu * E_star * d * a**2
