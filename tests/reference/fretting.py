"""Closed forms for fretting loops, derived for docs/fretting.md. Nothing here imports contactlab.

Tangential (Cattaneo–Mindlin), power law f = C rⁿ, constant normal force F:
  virgin curve Q(u) = μF[1 - (1 - u/u_t)^((n+1)/n)] for u <= u_t = μE* d/G* (Mindlin; [PH] §5);
  Masing loop energy W = 8∫_0^{δ*} Q du - 4δ*Q*; at δ* = u_t: ∫_0^1 [1 - (1-s)^((n+1)/n)] ds =
  (n+1)/(2n+1), so W_t = μF u_t (8(n+1)/(2n+1) - 4) = 4μF u_t/(2n+1) and Fouvry's ratio
  A_t = W_t/(4 u_t μF) = 1/(2n+1)  (Hertz: 0.2, cone: 1/3, flat punch n → ∞: 0).
  Gross-slip amplitude: d = κ_n C aⁿ and F = 2E*κ_n C a^(n+1) n/(n+1), so
  u_t(F) = (μE*/G*) κ_n C [(n+1)F/(2nE*κ_n C)]^(n/(n+1)) ∝ F^(n/(n+1)).
Hertz energy per cycle under force amplitude T (Mindlin & Deresiewicz 1953; Johnson 1985 §7.4):
  W = (18/5) μ²F²/(aG*) [1 - (1-t)^(5/3) - (5t/6)(1 + (1-t)^(2/3))], t = T/(μF).
Torsion, Hertz, small amplitude (derived): with dM/dφ = (16/3)G_t c³ and the small-slip expansion
  c²/a² = 1 - φ/φ_1, φ_1 = 3μF/(16 G_t a²), M = K0(φ - 3φ²/(4φ_1)) + O(φ³), K0 = (16/3)G_t a³, so
  W = (4/3) K0 (3/(4φ_1)) φ0³ = 256 G_t² a⁵ φ0³ / (9 μF) = 3 M0³/(16 μF G_t a⁴) (Deresiewicz 1954's
  cube law). Torsional stick-ratio boundary (Lubkin problem): φ(c) = (3μF/(4πG_t a²))[K(k) - E(k)],
  k² = 1 - c²/a².
"""
from __future__ import annotations

import numpy as np
from scipy.special import ellipe, ellipkm1

from tests.reference.kappa import kappa_float

__all__ = ["onset_energy_ratio", "gross_slip_amplitude", "mindlin_energy_of_force_amplitude",
           "hertz_torsion_small_energy", "hertz_twist_of_stick_ratio", "power_virgin_force",
           "hertz_limiting_state", "hertz_gross_slip_scar", "linear_table_volume",
           "hertz_torque_of_stick_ratio", "hertz_torsion_energy_ratio",
           "mindlin_loop_energy_of_displacement"]


def onset_energy_ratio(n: float) -> float:
    """Fouvry's energy ratio at the onset of gross slip, power law of degree n: 1/(2n+1)."""
    return 1.0 / (2.0 * n + 1.0)


def gross_slip_amplitude(F, mu, E_star, G_star, C, n):
    """Tangential gross-slip amplitude u_t(F), power law f = C rⁿ."""
    k = kappa_float(n)
    a = ((n + 1.0) * np.asarray(F, float) / (2.0 * n * E_star * k * C)) ** (1.0 / (n + 1.0))
    return mu * E_star * k * C * a**n / G_star


def power_virgin_force(u, F, mu, u_t, n):
    """Virgin tangential force Q(u), power law (u <= u_t)."""
    return mu * F * (1.0 - (1.0 - np.asarray(u, float) / u_t) ** ((n + 1.0) / n))


def mindlin_energy_of_force_amplitude(T, F, mu, a, G_star):
    """Hertz energy per cycle at tangential force amplitude T (Mindlin–Deresiewicz)."""
    t = T / (mu * F)
    return 18.0 / 5.0 * mu**2 * F**2 / (a * G_star) * (
        1.0 - (1.0 - t) ** (5.0 / 3.0) - 5.0 * t / 6.0 * (1.0 + (1.0 - t) ** (2.0 / 3.0)))


def hertz_torsion_small_energy(phi0, F, mu, a, G_t):
    """Leading-order torsional energy per cycle (Hertz, small amplitude): 256 G_t² a⁵ φ0³/(9μF)."""
    return 256.0 * G_t**2 * a**5 * phi0**3 / (9.0 * mu * F)


def hertz_twist_of_stick_ratio(ratio, F, mu, a, G_t):
    """Twist at stick ratio c/a (Hertz, exact Jäger solution; scipy's elliptic integrals take
    m = k² = 1 - (c/a)²)."""
    s = np.asarray(ratio, float)
    # K(m) through ellipkm1(1 - m) = ellipkm1(s²): accurate for c/a -> 0 (m -> 1)
    return 3.0 * mu * F / (4.0 * np.pi * G_t * a**2) * (ellipkm1(s * s) - ellipe(1.0 - s * s))


# ---------------------------------------------------------------- fretting wear (derived)
def hertz_limiting_state(c, F, E_star, R):
    """Limiting worn state of partial-slip fretting, Hertz, permanent stick radius c.

    MDR picture (Popov 2014; Dmitriev et al. 2016): wear stops when the slip annulus carries no
    load, i.e. the 1D profile is g0 inside c and flat at d∞ across the annulus. The stick zone
    carries the force, F = 2E* ∫_0^c (d∞ - g0) dx, so d∞ = (F/(2E*) + c³/(3R))/c. The 3D profile
    inside the scar is the inverse transform of that g; the wear depth is
    h∞(r) = (2/π)[d∞ acos(c/r) - ((r²/2) acos(c/r) + (c/2) sqrt(r²-c²))/R], c < r < a∞, and the scar
    ends where it meets the unworn surface, h∞(a∞) = 0. Returns (d∞, a∞, V∞, h∞).
    """
    from scipy.integrate import quad
    from scipy.optimize import brentq
    d_inf = (F / (2.0 * E_star) + c**3 / (3.0 * R)) / c

    def h(r):
        ac = np.arccos(c / r)
        return 2.0 / np.pi * (d_inf * ac - (0.5 * r * r * ac + 0.5 * c * np.sqrt(r * r - c * c)) / R)
    a_inf = brentq(h, c * (1 + 1e-12), 20 * c, xtol=1e-16, rtol=1e-14)
    V = quad(lambda r: 2 * np.pi * r * h(r), c, a_inf, epsabs=0, epsrel=1e-12)[0]
    return d_inf, a_inf, V, h


def hertz_gross_slip_scar(k, R, F, delta, N):
    """Tangential gross slip at large amplitude (every point slides 4δ per cycle): worn volume
    V = 4kFδN, worn flat cap πa⁴/(4R) ⇒ a = (16 k R F δ N / π)^(1/4)."""
    return (16.0 * k * R * F * delta * np.asarray(N, float) / np.pi) ** 0.25


def linear_table_volume(r, h):
    """∫ 2πr h dr of the piecewise-linear h on the nodes r (exact, per interval)."""
    r0, r1, h0, h1 = r[:-1], r[1:], h[:-1], h[1:]
    dr = r1 - r0
    return float(np.sum(2 * np.pi * dr * (h0 * (r0 / 2 + dr / 6) + h1 * (r0 / 2 + dr / 3))))


# ---------------------------------------------------------------- torsion, Hertz (Lubkin)
def hertz_torque_of_stick_ratio(ratio, F, mu, a):
    """Torque at stick ratio s = c/a (Hertz, exact; Lubkin 1951 / Jäger 1995):
    M = μFa [3π/16 - (4/π) ∫_0^s t² E(sqrt(1 - t²)) dt]  (scipy's ellipe takes m = k²)."""
    from scipy.integrate import quad
    s = float(ratio)
    inner = quad(lambda t: t * t * ellipe(1.0 - t * t), 0.0, s, epsabs=0, epsrel=1e-13)[0]
    return mu * F * a * (3.0 * np.pi / 16.0 - 4.0 / np.pi * inner)


def hertz_torsion_energy_ratio(ratio, F, mu, a, G_t):
    """Fouvry's energy ratio A = W/(4φ*M*) of the steady torsional loop whose amplitude has
    stick ratio s = c/a (Hertz). Masing: W = 8 ∫_0^φ* M dφ - 4φ*M*, the integral taken along the
    loading curve in the stick ratio: with φ(s) = C [K(m) - E(m)], m = 1 - s², C = 3μF/(4πG_t a²),
    and d(K - E)/dm = E(m)/(2(1 - m)), the derivative is φ'(s) = -C E(m)/s, so
    ∫_0^φ* M dφ = C ∫_s^1 M(t) E(1 - t²)/t dt."""
    from scipy.integrate import quad
    s0 = float(ratio)
    C = 3.0 * mu * F / (4.0 * np.pi * G_t * a**2)
    I = C * quad(lambda t: hertz_torque_of_stick_ratio(t, F, mu, a) * ellipe(1.0 - t * t) / t,
                 s0, 1.0, epsabs=0, epsrel=1e-13, limit=200)[0]
    M0 = hertz_torque_of_stick_ratio(s0, F, mu, a)
    p0 = float(hertz_twist_of_stick_ratio(s0, F, mu, a, G_t))
    return (8.0 * I - 4.0 * p0 * M0) / (4.0 * p0 * M0)


def mindlin_loop_energy_of_displacement(u0, F, mu, E_star, G_star, R, digits=50):
    """Hertz energy per cycle at displacement amplitude ``u0`` (Mindlin & Deresiewicz), in
    ``digits``-digit arithmetic (mpmath): the closed form cancels as ``t³`` for small
    amplitudes, which double precision cannot follow (Johnson 1985 §7.4; small-amplitude law
    ``W ≈ T³/(9μFaG*)``). Returns (W, T) as floats, J and N.

    a = (3FR/(4E*))^(1/3), d = a²/R, u_t = μE*d/G*, T = μF[1 - (1 - u0/u_t)^(3/2)].
    """
    import mpmath as mp
    with mp.workdps(digits):
        F_, mu_, E_, G_, R_, u_ = (mp.mpf(v) for v in (F, mu, E_star, G_star, R, u0))
        a = (3 * F_ * R_ / (4 * E_)) ** (mp.mpf(1) / 3)
        u_t = mu_ * E_ * a * a / R_ / G_
        T = mu_ * F_ * (1 - (1 - u_ / u_t) ** mp.mpf(1.5))
        t = T / (mu_ * F_)
        W = (mp.mpf(18) / 5 * mu_**2 * F_**2 / (a * G_)
             * (1 - (1 - t) ** (mp.mpf(5) / 3) - 5 * t / 6 * (1 + (1 - t) ** (mp.mpf(2) / 3))))
        return float(W), float(T)


def hertz_torsion_gross_slip_scar(k, R, F, phi, N):
    """Torsional gross slip at large twist, uniform wear of the slipping scar: slip 4φr per
    cycle, so p ∝ 1/r (the wear rate k p 4φr is the same everywhere), sliding torque μFa/2,
    dV/dN = 2kFφa, worn flat cap V = πa⁴/(4R) ⇒ a = (6 k R F φ N / π)^(1/3)."""
    return (6.0 * k * R * F * phi * np.asarray(N, float) / np.pi) ** (1.0 / 3.0)


def pillar_load_share(b, a, a0, E_star, R, F):
    """Load share of the unworn central pillar of radius b (the stick zone never slips, so never
    wears): it protrudes by the growth of the cap depth, (a² - a0²)/(2R), and as a flat punch of
    radius b carries 2E*b times that: ψ = E*b(a² - a0²)/(RF)."""
    return E_star * b * (np.asarray(a, float) ** 2 - a0**2) / (R * F)


def hertz_stick_radius_of_twist(phi, F, mu, a, G_t):
    """Stick radius of a fresh Hertz contact twisted to φ (root of the Lubkin closed form)."""
    from scipy.optimize import brentq
    return a * brentq(lambda s: hertz_twist_of_stick_ratio(s, F, mu, a, G_t) - phi, 1e-12,
                      1 - 1e-12, xtol=1e-15)


# ---------------------------------------------------------------- torsional gross-slip boundary
def hertz_torsion_boundary(criterion, threshold, digits=20):
    """Dimensionless torsional gross-slip amplitude ``φ̂ = φ_t G_t a²/(μF)`` of a Hertz contact
    (exact Jäger / Lubkin solution), in ``digits``-digit arithmetic (mpmath), and the stick ratio
    ``s = c/a`` there. Returns ``(φ̂, s)`` as floats.

    With ``m = 1 - s²`` (mpmath's K and E take the parameter m = k²):
      φ̂(s) = (3/(4π)) [K(m) - E(m)]                                   (physics §6.3)
      M̂(s) = M/(μFa) = 3π/16 - (4/π) ∫_0^s t² E(1 - t²) dt, so dM̂ = -(4/π) s² E(1 - s²) ds
      sliding torque M̂_full = 3π/16
    The Masing energy per cycle (§6.5) W = 4φ*M* - 8∫_0^{M*} φ dM, taken along the loading curve
    in s: ∫_0^{M*} φ̂ dM̂ = (4/π) ∫_{s0}^1 φ̂(t) t² E(1 - t²) dt (one quadrature of closed forms,
    no nested integral), and Fouvry's ratio A = W/(4φ*M*) = 1 - 2∫φ̂dM̂/(φ̂0 M̂0).
    Criteria: ``energy_ratio`` A = threshold; ``torque_ratio`` M̂/M̂_full = threshold;
    ``stick_ratio`` s = threshold. The root in ``y = ln s`` is found by mpmath's Anderson–Björck
    solver from a bracket (every criterion is monotone in s).
    """
    import mpmath as mp
    with mp.workdps(digits):
        thr = mp.mpf(threshold)

        def phi_hat(s):
            m = 1 - s * s
            return 3 / (4 * mp.pi) * (mp.ellipk(m) - mp.ellipe(m))

        def torque_hat(s):
            return 3 * mp.pi / 16 - 4 / mp.pi * mp.quad(lambda t: t * t * mp.ellipe(1 - t * t),
                                                          [0, s])

        def energy_ratio(s):
            inner = 4 / mp.pi * mp.quad(lambda t: phi_hat(t) * t * t * mp.ellipe(1 - t * t),
                                        [s, (1 + s) / 2, 1])
            return 1 - 2 * inner / (phi_hat(s) * torque_hat(s))

        if criterion == "stick_ratio":
            s = thr
        else:
            f = {"energy_ratio": energy_ratio,
                 "torque_ratio": lambda s: torque_hat(s) / (3 * mp.pi / 16)}[criterion]
            g = lambda y: f(mp.exp(y)) - thr             # decreasing in y = ln s
            lo, hi = mp.mpf(-1), mp.mpf(-1e-6)
            while g(lo) < 0:                              # widen until the bracket holds the root
                lo *= 2
            y = mp.findroot(g, (lo, hi), solver="anderson", tol=mp.mpf(10) ** (4 - digits))
            s = mp.exp(y)
        return float(phi_hat(s)), float(s)
