"""Energy of one step of the exact torsion solver: work in, elastic energy and dissipation.

The state is a punch density ``w`` (:mod:`contactlab.physics.torsion_annulus`) with
``Ψ(x) = ∫_x^∞ w dt``; its elastic energy is ``E = 8 G_t ∫ x² Ψ² dx`` and its torque
``M = 16 G_t ∫ x² Ψ dx`` (integration by parts of ``(16/3) G_t ∫ t³ w dt``). All integrands
below are polynomials on the intervals between the piece ends of the densities involved, so
4-point Gauss–Legendre per interval is exact (gaps between pieces, where ``Ψ`` is constant,
included).

**A step as a process.** The single-slip-annulus step ``w_n = splice(w_o, s W_n, c)`` (``W_n``
the density of the full-sliding traction ``μ p_n``) is the end of the continuous family
``w(c') = splice(w_o, s W_n, c')``, ``c'`` running inwards from the outer end of both densities
to ``c``: every point outside ``c'`` carries ``s μ p_n`` and the points inside ``c'`` turn
rigidly, so ``dM/dφ = (16/3) G_t c'³`` along it. Its work ``∫ M dφ`` and dissipation
``∫ τ ds dA`` are exactly (a *family* stage ``a → b`` with twist increment ``Δφ``)

    W = M_b Δφ − E(Δw),      D = 16 G_t ∫ x² Ψ_b(x) Φ(x) dx,      W = E_b − E_a + D,

``Δw = b − a`` and ``Φ(x) = Δφ − ΔΨ(x)`` the slip of a punch of radius ``x`` (the rigid turn minus
the turn of the punches outside ``x``; the gross turn of a contact sliding as a whole where
``Δφ ≠ ΔΨ(0)``). ``D`` is ``∫ τ_n Δs dA`` (the end traction times the slip of the step) and is
summed from this product, not as ``W − ΔE``: on the annulus ``Ψ_b`` and ``Φ`` both have the sign
of the slip and ``Φ = 0`` inside ``c``, so it has no cancellation and is ``>= 0`` whenever the
slip points the way of the traction (which the step checks).

**A shrinking contact.** Where ``w_o`` reaches beyond the new contact radius ``a_n`` the family
first releases that outer density (traction-free: no dissipation) and turns the contact by
``−G``, ``G = Ψ_o(a_n)``, before the annulus slides the other way (``s G > 0``) or further
(``s G < 0``). Only the latter is a monotone twist; otherwise the step is booked as two stages
that end at the same density:

* ``s Δφ >= 0``: a release at the held twist to ``w_m`` (the step with ``Δφ = 0``), then the
  family ``w_m → w_n``;
* ``s Δφ < 0`` (``|Δφ| < |G|``): the family releases the outer density down to the outermost
  radius ``c₁ >= a_n`` with ``Ψ_o(c₁) = −Δφ`` (``w_q``: the twist reaches ``Δφ``), then a release
  at the held twist ``w_q → w_n``. The release never reaches inside ``a_n`` (``Ψ_o`` need not be
  monotone there: the outer density holds bands of both senses), so the held stage adds only
  the step's own annulus; where the booked ``Δφ`` (a difference of two totals ``Ψ(0)``) rounds
  beyond ``|G|``, ``c₁ = a_n``.

A contact without a friction limit carries rigid punches (point masses of the density,
:func:`contactlab.physics.torsion_annulus.punch_step`): its step is a release at the held twist
(the punches beyond the new contact radius leave, their turn goes to the punch at the radius:
dissipation ``8 G_t ∫_{a_n}^∞ x² Ψ_o² dx``, the energy of the released band) and then a rigid
punch of the radius turned by ``Δφ`` (elastic: work ``½ (M_m + M_n) Δφ``, no dissipation), see
:func:`punch_step_energy`.

A *held* stage ``a → b`` does no work and dissipates ``E_a − E_b = 16 G_t ∫ x² Ψ_b (Ψ_a − Ψ_b)
dx + E(b − a)`` (both ``>= 0`` for the held-twist step). The booking is continuous across
the cases (at ``Δφ = 0`` and at ``Δφ = −G``), and a held twist does no work. The releases of a
shrinking contact end at a density found by a root, whose turn ``ΔΨ(0)`` is rounding rather
than zero: its work ``M_b ΔΨ(0)`` is booked as work and the dissipation taken from the slip
relative to that turn, ``16 G_t ∫ x² Ψ_b (ΔΨ(0) − ΔΨ) dx + E(b − a)`` (else the rounding turn
times the whole torque lands in the dissipation).

All functions are pure: arrays in, arrays out.
"""
from __future__ import annotations

import itertools

import numpy as np

from . import torsion_annulus as _ta

__all__ = ["annulus_energy", "energy", "punch_step_energy", "ring_dissipation", "ring_step_energy",
           "step_energy"]

_GAUSS = np.polynomial.legendre.leggauss(4)
_NONE = (np.zeros(0), np.zeros(0))


def _nodes(*dens: tuple) -> tuple[np.ndarray, np.ndarray]:
    """Gauss points and weights ``x² w`` on the intervals between all piece ends (and 0)."""
    ends = _ta._unique(np.concatenate([np.zeros(1)] + [u for d in dens for u in d[:2]]))
    h = np.diff(ends)
    xg, wg = _GAUSS
    X = (ends[:-1, None] + 0.5 * (xg[None, :] + 1.0) * h[:, None]).ravel()
    W = (0.5 * wg[None, :] * h[:, None]).ravel() * X * X
    return X, W


def energy(w: tuple, G_t: float) -> float:
    """Elastic energy ``8 G_t ∫ x² Ψ² dx`` of a density, J (gaps between its pieces included)."""
    if w[0].size == 0:
        return 0.0
    X, W = _nodes(w)
    P = _ta.psi(w, X)
    return float(8.0 * G_t * (W @ (P * P)))


def _stages(chain: list, G_t: float, gross: float = 0.0) -> dict:
    """Work and dissipation of a chain of stages ``[(w_0, None), (w_1, f_1), (w_2, f_2), ...]``
    (``f``: ``True`` a family stage, ``None`` a held stage, ``False`` a release at the held twist
    whose density's turn ``ΔΨ(0)`` is the rounding of its root: that turn's work is booked),
    plus the elastic energies of its
    ends. A family stage turns by the twist its density increment carries, ``ΔΨ(0)``, plus the
    gross turn ``gross`` of a contact sliding as a whole (on the last family stage)."""
    dens = [c[0] for c in chain]
    k = 8.0 * G_t
    work = diss = 0.0
    ak = _ta._annulus_kernels() if len(dens) <= 3 else None
    if ak is not None and len(chain) == 2 and chain[1][1] is True:
        # one family stage (a step's usual energy): its products in one compiled pass, the
        # dot products below as in the loop (the same bits)
        W, q0, qd, Pb, qbb, qdiss, dphi_ = ak["family_energy"](
            *_ta._arrays(dens[0]), *_ta._arrays(dens[1]), *_GAUSS, float(gross))
        dphi = float(dphi_)
        E_d = k * float(W @ qd)
        work += 2.0 * k * float(W @ Pb) * dphi - E_d
        diss += 2.0 * k * float(W @ qdiss)
        return {"work": work, "stored": k * float(W @ qbb), "stored_old": k * float(W @ q0),
                "dissipated": diss}
    if ak is not None and len(chain) == 3 and chain[1][1] is False and chain[2][1] is True:
        # a shrinking contact's release, then its family stage (annulus_energy): the products
        # of both in one compiled pass, the dot products below as in the loop (the same bits)
        return _release_family_sums(k, ak["release_family_energy"](
            *_ta._arrays(dens[0]), *_ta._arrays(dens[1]), *_ta._arrays(dens[2]), *_GAUSS,
            float(gross)))
    if ak is not None:
        # the compiled passes (numeric.annulus_kernel): the nodes, weights and Ψ of the first
        # density in one pass, each increment's Ψ in one more; the same values
        arr = [_ta._arrays(d) for d in dens]
        third = arr[2] if len(arr) > 2 else _NONE
        X0, W, P0, dP1 = ak["energy_nodes"](*arr[0], *arr[1], third[0], third[1], *_GAUSS)
        Pa = P0
    else:
        X, W = _nodes(*dens)
        # Ψ at the nodes and at 0 in one call (elementwise: the same values)
        X0 = np.append(X, 0.0)
        P0 = Pa = _ta.psi(dens[0], X)
    for i, ((a, _), (b, family)) in enumerate(itertools.pairwise(chain)):
        # the increment's Ψ from the difference density: exactly ΔΨ(0) where the stage leaves
        # the density alone (not a difference of two large Ψ), so Φ vanishes there; Ψ_b as
        # Ψ_a + ΔΨ keeps the balance exact to rounding even on pieces narrower than the
        # spacing of the floats around them
        if ak is not None:
            dP = dP1 if i == 0 else ak["difference_psi"](*arr[i + 1], *arr[i], X0)
        else:
            dP = _ta.psi(_ta.difference(b, a, 0.0), X0)
        d0, dP = float(dP[-1]), dP[:-1]
        Pb = Pa + dP
        E_d = k * float(W @ (dP * dP))
        if family is None:
            diss += -2.0 * k * float(W @ (Pb * dP)) + E_d
        elif family is False:
            # a release at the held twist whose density turns by a rounding ΔΨ(0) (the root of
            # the stage's stick radius): that turn's work M_b ΔΨ(0) is booked as work, the
            # dissipation from the slip relative to it (else the rounding turn times the whole
            # torque lands in the dissipation: −3.9e-20 J against a running total of 4.1e-9 J)
            work += 2.0 * k * float(W @ Pb) * d0
            diss += 2.0 * k * float(W @ (Pb * (d0 - dP))) + E_d
        else:
            dphi = d0 + gross
            work += 2.0 * k * float(W @ Pb) * dphi - E_d
            diss += 2.0 * k * float(W @ (Pb * (dphi - dP)))
        Pa = Pb
    return {"work": work, "stored": k * float(W @ (Pa * Pa)),
            "stored_old": k * float(W @ (P0 * P0)), "dissipated": diss}


def _release_family_sums(k: float, arrays: tuple) -> dict:
    """:func:`_stages` of a release then a family stage from the products of
    :func:`contactlab.numeric.annulus_kernel.release_family_energy` (``k = 8 G_t``): the dot
    products and sums of the loop, in its order (the same bits)."""
    W, qd1, Pb, qdiss1, d01_, qd2, Pc, qdiss2, qcc, q0, dphi_ = arrays
    d0, dphi = float(d01_), float(dphi_)
    work = diss = 0.0
    E_d = k * float(W @ qd1)
    work += 2.0 * k * float(W @ Pb) * d0
    diss += 2.0 * k * float(W @ qdiss1) + E_d
    E_d = k * float(W @ qd2)
    work += 2.0 * k * float(W @ Pc) * dphi - E_d
    diss += 2.0 * k * float(W @ qdiss2)
    return {"work": work, "stored": k * float(W @ qcc), "stored_old": k * float(W @ q0),
            "dissipated": diss}


def step_energy(old: tuple, new: tuple, G_t: float, gross: float | None = 0.0) -> dict:
    """Work, elastic energy and dissipation of the family stage ``old → new``.

    Parameters
    ----------
    old, new : Pieces
        Punch densities before and after the step, rad/m per m.
    G_t : float
        Torsional modulus, Pa.
    gross : float or None
        Turn of the contact sliding as a whole beyond the twist of the density increment, rad
        (0 unless the stick radius is 0); ``None``: a release at the held twist (no work).

    Returns
    -------
    dict
        ``work`` (J), ``stored`` (``E_n``, J), ``stored_old`` (``E_o``, J) and ``dissipated``
        (J); ``work = stored − stored_old + dissipated`` up to rounding. The twist increment of
        the step is ``ΔΨ(0) + gross``.
    """
    if old[0].size == 0 and new[0].size == 0:
        return {"work": 0.0, "stored": 0.0, "stored_old": 0.0, "dissipated": 0.0}
    if gross is None:
        return _stages([(old, None), (new, None)], G_t)
    return _stages([(old, None), (new, True)], G_t, float(gross))


def annulus_energy(old: tuple, new: tuple, slide: tuple, radius: float, sense: float,
                   G_t: float, dphi: float, gross: float = 0.0) -> dict:
    """Energy of a single-slip-annulus step (:func:`contactlab.physics.torsion_annulus.step`
    with sense ``sense`` onto the full-sliding density ``slide`` of the contact radius
    ``radius``, twist increment ``dphi``, gross turn ``gross``): the family, or for a shrinking
    contact the two stages of the module docstring; keys of :func:`step_energy`."""
    top = float(old[1][-1]) if old[1].size else 0.0
    if top > radius:
        G = float(_ta.psi(old, np.array([radius]))[0])
        if sense * G > 0:
            if sense * dphi >= 0:
                # the release density and both stages in one compiled pass where there is one
                arrays = _ta.shrink_energy_arrays(old, slide, radius, G_t, new, _GAUSS, gross)
                if arrays is not None:
                    return _release_family_sums(8.0 * G_t, arrays)
                mid = _ta.step(old, slide, radius, G_t, dphi=0.0)["w"]
                return _stages([(old, None), (mid, False), (new, True)], G_t, gross)
            return _stages([(old, None), (_release(old, radius, top, G_t, float(dphi)), True),
                            (new, False)], G_t)
    return step_energy(old, new, G_t, gross)


def _release(old: tuple, radius: float, top: float, G_t: float, dphi: float) -> tuple:
    """The outer density of ``old`` released from its end ``top`` down to the outermost
    ``c₁ >= radius`` with ``Ψ_o(c₁) = −Δφ`` (a step onto no density: the first stage of a
    shrinking contact whose twist goes back, module docstring).

    The release never reaches inside the new contact radius: the held stage that follows adds
    the annulus ``(c, radius)`` only, so its slip is the step's own (checked) slip. ``Ψ_o`` need
    not be monotone beyond ``radius`` (the density there carries the bands of earlier steps of
    both senses, or a ring step's remainder), so the first crossing from ``top`` may sit in the
    piece that holds ``radius``, with a second root below it; the search is then repeated with a
    piece end at ``radius``. Where ``|Δφ| > |Ψ_o(radius)|`` (the twist of the step is ``Δφ``
    but the booked turn is a difference of two totals ``Ψ(0)``, and its rounding can exceed a
    ``Ψ_o(radius)`` of ~1e-25 rad) no root lies beyond ``radius`` and the whole band beyond it
    is released (``c₁ = radius``, the twist of the step to rounding).
    """
    q = _ta.step(old, _ta.empty(), top, G_t, dphi=dphi)
    if q["c"] >= radius:
        return q["w"]
    q = _ta.step(_ta.splice(old, old, radius), _ta.empty(), top, G_t, dphi=dphi)
    if q["c"] >= radius:
        return q["w"]
    return _ta.splice(old, _ta.empty(), radius)


def ring_dissipation(H: np.ndarray, z_old: np.ndarray, z: np.ndarray, lam: np.ndarray,
                     held: bool) -> float:
    """Dissipation of a box-constrained ring step
    (:func:`contactlab.physics.torsion_rings.box_step`) in its own energy measure, J.

    ``z·λ``, the end traction times the area-weighted slip of the step (the rule of the family
    stage; ``>= 0`` term by term: a point slides only at its limit and in the sense of its
    traction), plus, at a held twist, the energy of the increment ``½ Δzᵀ H Δz`` (the rule of a
    held stage: the step releases ``−ΔE`` and does no work).
    """
    D = float(z @ lam)
    if held:
        dz = z - z_old
        D += 0.5 * float(dz @ (H @ dz))
    return D


def ring_step_energy(old: tuple, new: tuple, G_t: float, ring: float,
                     stored_old: float | None = None) -> dict:
    """Energy of a step taken by the ring solver (two slip zones): its dissipation in its own
    measure (:func:`ring_dissipation`), the elastic energies of the densities, and the work that
    balances them (``E_n − E_o + D``; it differs from ``∫ M dφ`` by the ring discretisation:
    the ring step's energy measure is not the density's); keys of :func:`step_energy`.
    ``stored_old``: :func:`energy` of ``old`` when known (the last ring step's ``stored``)."""
    E_o = energy(old, G_t) if stored_old is None else float(stored_old)
    E_n = energy(new, G_t)
    D = float(ring)
    return {"work": E_n - E_o + D, "stored": E_n, "stored_old": E_o, "dissipated": D}


def punch_step_energy(t: np.ndarray, m: np.ndarray, t_new: np.ndarray, m_new: np.ndarray,
                      radius: float, G_t: float, dphi: float) -> dict:
    """Energy of a step of a contact without a friction limit (rigid punches of radii ``t``,
    turns ``m`` to ``t_new``, ``m_new``; :func:`contactlab.physics.torsion_annulus.punch_step`
    with the contact radius ``radius`` and the twist increment ``dphi``).

    The release at the held twist dissipates the energy of the band beyond ``radius``,
    ``8 G_t ∫_radius^∞ x² Ψ_o² dx`` (``Ψ_o`` the turn of the punches beyond ``x``: a step
    function), summed from its non-negative terms; the rigid punch of the radius then does the
    elastic work ``½ (M_m + M_n) Δφ``; keys of :func:`step_energy`.
    """
    t, m = np.asarray(t, float), np.asarray(m, float)
    out = t >= radius
    order = np.argsort(t[out], kind="stable")
    tb, mb = t[out][order], m[out][order]
    tail = np.cumsum(mb[::-1])[::-1]                        # Ψ_o on (t_{k-1}, t_k) beyond
    lo = np.concatenate([[radius], tb[:-1]])
    D = float(8.0 * G_t * np.sum(tail ** 2 * (tb ** 3 - lo ** 3)) / 3.0)
    k = 16.0 / 3.0 * G_t
    M_m = float(k * (np.sum(t[~out] ** 3 * m[~out]) + radius ** 3 * np.sum(mb)))
    M_n = _ta.punch_torque(t_new, m_new, G_t)
    return {"work": 0.5 * (M_m + M_n) * float(dphi), "stored": _ta.punch_energy(t_new, m_new, G_t),
            "stored_old": _ta.punch_energy(t, m, G_t), "dissipated": D}
