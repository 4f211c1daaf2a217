"""Energy of gross sliding on the exact torsion route (``contact.simulate(method="exact")``,
torque control beyond the sliding torque; issue 26 item 1).

A contact sliding as a whole carries ``s μ p`` everywhere; its twist is not fixed by the torque.
The route turns it by the smallest increment at which all of it slides: none while the force
falls (the twist is held: no work, the elastic energy the shrinking sliding traction gives up is
dissipated), the turn of its full-sliding density while the force rises. Checked against
closed forms: the sliding torque ``3π μ F a / 16`` and the elastic energy of the Hertz-shaped
sliding traction, ``k_E (μ p0)² a³ / G_t`` with ``k_E`` from an independent quadrature of the
half-space's torsional displacement (complete elliptic integrals), written here."""
from __future__ import annotations

import functools

import numpy as np
from scipy import integrate, special

import contactlab as cl
from contactlab import LoadPath
from contactlab.profiles import Paraboloid
from tests.tolerances import (
    ENERGY_BALANCE,
    ENERGY_STEP_ROUNDING,
    GROSS_SLIDING_ENERGY,
    GROSS_SLIDING_WORK_STEP,
)

STEEL = cl.Elastic(E=210e9, nu=0.3)
MU = 0.3


def contact():
    return cl.Contact(Paraboloid(0.01), materials=(STEEL, STEEL), friction=MU)


def _ring_kernel(r: float, rho: float) -> float:
    """``∫_0^{2π} cos θ / sqrt(r² + ρ² − 2 r ρ cos θ) dθ`` (complete elliptic integrals)."""
    m1 = ((r - rho) / (r + rho)) ** 2
    m = 1.0 - m1
    return 4.0 / ((r + rho) * m) * ((2.0 - m) * special.ellipkm1(m1) - 2.0 * special.ellipe(m))


@functools.cache
def sliding_energy_constant() -> float:
    """``k_E`` of ``E = k_E q0² a³ / G_t``: the elastic energy of the circumferential traction
    ``q0 sqrt(1 − r²/a²)`` on a half-space pair of torsional modulus ``G_t``.

    A circumferential (divergence-free) traction displaces the surface by
    ``u(x) = (1/(2π G_t)) ∫ τ(y)/|x − y| dA`` (Cerruti's point load; the ``ν`` terms integrate to
    zero), so ``u(r) = (q0 a / G_t) ũ(r/a)``, ``ũ(ρ) = (1/2π) ∫_0^1 sqrt(1 − σ²) σ K(ρ, σ) dσ``,
    and ``E = ½ ∫ τ u dA = π q0² a³/G_t ∫_0^1 sqrt(1 − ρ²) ũ(ρ) ρ dρ``."""
    def u(rho: float) -> float:
        f = lambda s: np.sqrt(1.0 - s * s) * s * _ring_kernel(rho, s)  # noqa: E731
        lo = integrate.quad(f, 0.0, rho, epsabs=0.0, epsrel=1e-10, limit=200)[0]
        hi = integrate.quad(f, rho, 1.0, epsabs=0.0, epsrel=1e-10, limit=200)[0]
        return (lo + hi) / (2.0 * np.pi)
    # (to 1e-9: far below the tolerance it is compared at; tighter, quad reports roundoff)
    val = integrate.quad(lambda r: np.sqrt(1.0 - r * r) * u(r) * r, 0.0, 1.0, epsabs=0.0,
                         epsrel=1e-9, limit=200)[0]
    return float(np.pi * val)


def sliding_torque(F: float) -> float:
    a = float(contact().normal(force=F).radius)
    return 3.0 * np.pi / 16.0 * MU * F * a


def sliding_energy(F: float) -> float:
    c = contact()
    a = float(c.normal(force=F).radius)
    p0 = 3.0 * F / (2.0 * np.pi * a * a)
    return sliding_energy_constant() * (MU * p0) ** 2 * a ** 3 / c.moduli.torsional


def test_sliding_energy_constant_against_the_linear_traction():
    """The quadrature's kernel, checked on a traction whose displacement is known: the rigid
    punch's ``q0 (r/a)/sqrt(1 − r²/a²)`` turns the contact rigidly, ``u = π q0 r / (4 G_t)``."""
    for rho in (0.2, 0.5, 0.8):
        def f(s: float, rho: float = rho) -> float:
            return s / np.sqrt(1.0 - s * s) * s * _ring_kernel(rho, s)
        lo = integrate.quad(f, 0.0, rho, epsrel=1e-12, limit=200)[0]
        hi = integrate.quad(f, rho, 1.0, epsrel=1e-12, limit=200)[0]
        assert abs((lo + hi) / (2.0 * np.pi) - np.pi * rho / 4.0) < 1e-9


def gross_path(n: int, rising: bool) -> tuple:
    """20 N, the torque up to 1.02 times the sliding torque (gross sliding from its last step),
    then the force down to 12 N in ``n`` steps at that torque target (gross throughout: the
    sliding torque falls), and with ``rising`` back up to 20 N in ``n`` steps (still beyond)."""
    T = 1.02 * sliding_torque(20.0)
    path = (LoadPath().ramp(steps=5, force=20.0, torque=0.0).ramp(steps=10, torque=T)
            .ramp(steps=n, force=12.0, torque=T))
    if rising:
        path = path.ramp(steps=n, force=20.0, torque=T)
    return contact().simulate(path, method="exact"), T


def _check_steps(res) -> None:
    e = res.meta["energy"]
    d = e["dissipated_per_step"]
    run = np.maximum.accumulate(np.abs(np.cumsum(d)))
    assert np.all(d >= -ENERGY_STEP_ROUNDING * run)
    scale = max(float(np.max(np.abs(e["work"]))), float(np.max(e["stored"])))
    assert np.max(np.abs(e["work"] - e["stored"] - np.cumsum(d))) <= ENERGY_BALANCE * scale


def test_gross_sliding_with_falling_force_holds_the_twist_and_dissipates_the_sliding_energy():
    """While the force falls the twist is held (no work) and each step dissipates what the
    sliding traction's elastic energy loses: their sum is ``E_slide(20 N) − E_slide(12 N)`` of
    the closed form, the torque is the sliding torque. The old booking turned the contact by the
    turn of its density while reporting the twist held: work at a held twist and negative steps
    (−5e-9 J against a running total of 4.6e-7 J on a generated path)."""
    n = 20
    res, _ = gross_path(n, rising=False)
    g = np.asarray(res.gross_sliding)
    fall = slice(15, 15 + n)
    assert g[14:].all() and not g[:14].any()                   # the premise
    tw, F, M = np.asarray(res.twist), np.asarray(res.force), np.asarray(res.torque)
    e = res.meta["energy"]
    assert np.all(tw[fall] == tw[14])
    assert np.all(np.abs(np.diff(e["work"][14:])) <= ENERGY_BALANCE * np.max(e["stored"]))
    D = float(np.sum(e["dissipated_per_step"][fall]))
    ref = sliding_energy(float(F[14])) - sliding_energy(float(F[-1]))
    assert abs(D - ref) <= GROSS_SLIDING_ENERGY * ref
    Ms = np.array([sliding_torque(float(f)) for f in F[14:]])
    assert np.max(np.abs(M[14:] / Ms - 1.0)) <= GROSS_SLIDING_ENERGY
    _check_steps(res)


def test_gross_sliding_with_rising_force_books_the_work_of_the_sliding_torque():
    """While the force rises the contact must turn on (a held twist would make points slide
    against their traction): the twist advances monotonically, every step dissipates ``>= 0``
    and the booked work is ``∫ M_slide(F) dφ`` along the reported twist (closed-form torque,
    trapezoid), to the first-order error of a step whose family takes the end pressure."""
    n = 80
    res, _ = gross_path(n, rising=True)
    g = np.asarray(res.gross_sliding)
    rise = np.arange(15 + n, 15 + 2 * n)
    assert g[rise].all()                                        # the premise
    tw, F = np.asarray(res.twist), np.asarray(res.force)
    assert np.all(np.diff(tw[rise[0] - 1:]) >= 0.0) and tw[-1] > tw[rise[0] - 1]
    Ms = np.array([sliding_torque(float(f)) for f in F])
    trap = float(np.sum(0.5 * (Ms[rise - 1] + Ms[rise]) * (tw[rise] - tw[rise - 1])))
    e = res.meta["energy"]
    W = float(e["work"][rise[-1]] - e["work"][rise[0] - 1])
    assert abs(W - trap) <= GROSS_SLIDING_WORK_STEP * trap
    _check_steps(res)


def test_flat_punch_gross_sliding_turns_while_the_force_rises_and_holds_while_it_falls():
    """A flat punch runs on the ring solver alone: its gross step (torque target beyond the
    sliding torque ``π μ F a/4``) held the twist and booked ``E_n − E_o + ½ΔzᵀHΔz`` as work at
    that held twist. Now, with the target held at 0.9 of the sliding torque at F0: while the
    force falls below 0.9 F0 the twist is held after the step that turns the stuck centre into
    sliding, no work is booked and each step dissipates ``>= 0``; while it rises again (still
    beyond the target) the twist advances and each step's work lies between ``M_slide(F_o) Δφ``
    and ``M_slide(F_n) Δφ`` (the closed-form sliding torque at the ends of the step, ``∫ M dφ``
    with ``M`` rising with the force); the torque is the sliding torque."""
    from contactlab.profiles import FlatPunch
    from tests.tolerances import RINGS_FLAT_PUNCH
    a, F0 = 2e-4, 50.0
    c = cl.Contact(FlatPunch(radius=a), materials=(STEEL, STEEL), friction=MU)

    def slide(f):
        return np.pi * MU * f * a / 4.0

    n = 12
    force = np.concatenate([np.linspace(F0 / 5, F0, 5), np.full(5, F0),
                            np.linspace(F0, 0.5 * F0, n + 1)[1:],
                            np.linspace(0.5 * F0, 0.85 * F0, n + 1)[1:]])
    torque = np.concatenate([np.zeros(5), np.linspace(0.18, 0.9, 5) * slide(F0),
                             np.full(2 * n, 0.9 * slide(F0))])
    res = c.simulate(LoadPath.from_arrays(force=force, torque=torque), method="exact")
    g = np.asarray(res.gross_sliding)
    tw, M = np.asarray(res.twist), np.asarray(res.torque)
    fall = np.flatnonzero(g & (np.arange(g.size) < 10 + n))
    rise = np.arange(10 + n, 10 + 2 * n)
    assert fall.size >= 6 and g[rise].all() and not g[:10].any()     # the premise
    assert np.max(np.abs(M[g] / slide(force[g]) - 1.0)) <= RINGS_FLAT_PUNCH
    e = res.meta["energy"]
    scale = float(np.max(e["stored"]))
    # falling: the first gross step turns the stuck centre on into sliding; then the twist is
    # held and no work is booked
    held = fall[1:]
    assert tw[fall[0]] > tw[fall[0] - 1] and np.all(tw[held] == tw[fall[0]])
    assert np.all(np.abs(e["work"][held] - e["work"][held - 1]) <= ENERGY_BALANCE * scale)
    # rising: the twist turns on, the work of each step within the sliding torque's bracket
    dphi = tw[rise] - tw[rise - 1]
    assert np.all(dphi > 0.0)
    W = e["work"][rise] - e["work"][rise - 1]
    lo, hi = slide(force[rise - 1]) * dphi, slide(force[rise]) * dphi
    assert np.all(W >= lo * (1 - RINGS_FLAT_PUNCH)) and np.all(W <= hi * (1 + RINGS_FLAT_PUNCH))
    _check_steps(res)
