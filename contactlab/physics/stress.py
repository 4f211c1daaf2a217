"""Subsurface stresses of axisymmetric contacts by flat-punch superposition [Sn65; J85 §3.4, §3.8].

Every MDR normal state is a superposition of rigid flat punches (seed eq. 10): a punch of radius
``x`` pressed by ``dd = g'(x) dx`` adds the pressure ``(E*/π) dd / sqrt(x² - r²)``. The
half-space is linear, so its stress field is the same superposition of the flat punch's field::

    σ(r, z) = (E*/π) [ ∫_0^a g'(x) K(r, z; x) dx + (d - g(a)) K(r, z; a) ]

with ``K`` the field of a punch of radius ``x`` whose pressure is ``1/sqrt(x² - r²)``.

The punch field (derived for this module from Boussinesq's potentials, Johnson 1985 §3.2):
with ``ψ = arcsin(x/l2)`` the Newtonian potential of that pressure divided by ``2π`` and ``χ``
the harmonic function with ``∂χ/∂z = ψ``,

* ``σ_zz = ψ_z - z ψ_zz``, ``σ_rz = -z ψ_rz``,
* ``σ_θθ = 2ν ψ_z - z ψ_r/r - (1 - 2ν) χ_r/r``,
* ``σ_rr = ψ_z + z ψ_r/r + z ψ_zz + (1 - 2ν) χ_r/r``,

and, with ``A = r² + z² - x²``, ``Q = sqrt(A² + 4x²z²)``, ``m² = (Q - A)/2 = x² - l1²``,
``n² = (Q + A)/2 = l2² - x²`` (so ``mn = xz``, ``l1 l2 = rx``):
``ψ_z = -m/Q``, ``ψ_r/r = -x n/(l2² Q)``, ``ψ_rz = r m (Q + 2A)/Q³``,
``ψ_zz = -n l1²/(x Q²) + 2 m z (A + 2x²)/Q³``, ``χ_r/r = x²/(l2² (x + m))``.
All are written without cancellation; on the axis they reduce to their limits.

Hertz has Huber's closed form (Johnson eqs. 3.44-3.45 on the axis and the surface; the full field
as given by Huber 1904 and Fischer-Cripps 2007, eq. 6.2.2). Kernels take plain arrays and moduli
and return arrays; they never see a contact or a state.
"""
from __future__ import annotations

import inspect
from collections.abc import Callable

import numpy as np

__all__ = [
    "CHUNK",
    "hertz_field",
    "kronrod_rule",
    "principal_axisymmetric",
    "principal_general",
    "punch_kernel",
    "spheroidal",
    "superposed_field",
    "von_mises",
]

#: grid points evaluated together in the superposition (bounds the (points x nodes) arrays:
#: 4096 points x 96 nodes x 8 bytes x ~12 temporaries ~ 40 MB)
CHUNK = 4096


#: Gauss-Kronrod 7/15 rule on [-1, 1] (QUADPACK qk15): nodes, Kronrod weights, Gauss weights
#: (the Gauss nodes are the odd-indexed Kronrod nodes)
_XK = np.array([0.991455371120812639206854697526329, 0.949107912342758524526189684047851,
                0.864864423359769072789712788640926, 0.741531185599394439863864773280788,
                0.586087235467691130294144838258730, 0.405845151377397166906606412076961,
                0.207784955007898467600689403773245, 0.0])
_WK = np.array([0.022935322010529224963732008058970, 0.063092092629978553290700663189204,
                0.104790010322250183839876322541518, 0.140653259715525918745189590510238,
                0.169004726639267902826583426598550, 0.190350578064785409913256402421014,
                0.204432940075298892414161999234649, 0.209482141084727828012999174891714])
_WG = np.array([0.129484966168869693270611432679082, 0.279705391489276667901467771423780,
                0.381830050505118944950369775488975, 0.417959183673469387755102040816327])


def kronrod_rule() -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """G7/K15 nodes on ``[0, 1]`` with the Kronrod weights and the embedded Gauss weights (0 at
    the Kronrod-only nodes)."""
    x = np.concatenate([-_XK[:-1], _XK[::-1]])
    wk = np.concatenate([_WK[:-1], _WK[::-1]])
    wg = np.zeros(15)
    gauss = np.concatenate([_WG[:-1], _WG[::-1]])
    wg[1::2] = gauss
    return 0.5 * (x + 1.0), 0.5 * wk, 0.5 * wg


def spheroidal(r: np.ndarray, z: np.ndarray, x: np.ndarray | float,
               offset: np.ndarray | None = None) -> tuple[np.ndarray, ...]:
    """Oblate spheroidal set-up of the point ``(r, z)`` against a disc of radius ``x``.

    Returns ``(r, z, x, x², A, Q, m², n²)`` broadcast to one shape, with ``A = r² + z² - x²``,
    ``Q = sqrt(A² + 4x²z²)``, ``m² = (Q - A)/2 = x² - l1²`` and ``n² = (Q + A)/2 = l2² - x²``,
    each written without cancellation (the smaller of the two is ``2x²z²/(|A| + Q)``). Every
    field kernel of this module and :mod:`contactlab.physics.stress_tangential` starts here.

    ``offset``, when given, is ``x - r`` computed by the caller to full relative precision
    (a quadrature node a hair from ``r``); then ``A = z² - offset (2r + offset)``, which keeps
    its digits where ``r² - x²`` would cancel, and stays nonzero where ``x`` itself rounds to
    ``r`` (the kernel's rim).
    """
    r, z, x = np.broadcast_arrays(np.asarray(r, float), np.asarray(z, float),
                                  np.asarray(x, float))
    x2 = x * x
    if offset is None:
        A = r * r + z * z - x2
    else:
        A = z * z - offset * (2.0 * r + offset)
    Q = np.hypot(A, 2.0 * x * z)
    pos = A >= 0
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        big = np.abs(A) + Q                      # no cancellation
        small = np.where(Q > 0, 2.0 * x2 * z * z / big, 0.0)
        m2 = np.where(pos, small, 0.5 * big)     # x² - l1²
        n2 = np.where(pos, 0.5 * big, small)     # l2² - x²
    return r, z, x, x2, A, Q, m2, n2


def punch_kernel(r: np.ndarray, z: np.ndarray, x: np.ndarray | float, nu: float,
                 offset: np.ndarray | None = None
                 ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Field ``(σ_rr, σ_θθ, σ_zz, σ_rz)`` of a flat punch of radius ``x`` whose surface pressure
    is ``1/sqrt(x² - r²)`` (tension positive, ``z >= 0`` the depth), Pa per unit amplitude.

    Multiply by ``E* d/π`` for a rigid punch pressed to depth ``d``. Finite everywhere except at
    the punch rim ``(r, z) = (x, 0)`` (inverse-square-root singular there); on the surface under
    the punch ``σ_zz = -1/sqrt(x² - r²)``. Arguments broadcast; ``offset`` is ``x - r`` to full
    precision where the caller has it (see :func:`spheroidal`).
    """
    r, z, x, x2, A, Q, m2, n2 = spheroidal(r, z, x, offset)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        m = np.sqrt(m2)
        n = np.sqrt(n2)
        l22 = x2 + n2
        l12 = np.where(l22 > 0, r * r * x2 / l22, 0.0)
        psi_z = -m / Q
        psi_r_r = -x * n / (l22 * Q)
        psi_rz = r * m * (Q + 2.0 * A) / Q**3
        psi_zz = -n * l12 / (x * Q * Q) + 2.0 * m * z * (A + 2.0 * x2) / Q**3
        chi_r_r = x2 / (l22 * (x + m))
    one = 1.0 - 2.0 * nu
    szz = psi_z - z * psi_zz
    srz = -z * psi_rz
    stt = 2.0 * nu * psi_z - z * psi_r_r - one * chi_r_r
    srr = psi_z + z * psi_r_r + z * psi_zz + one * chi_r_r
    # the rim itself (Q = 0): singular; a zero-radius punch carries nothing
    rim = Q == 0
    if np.any(rim):
        val = np.where(x > 0, -np.inf, 0.0)
        szz, srr, stt = (np.where(rim, val, v) for v in (szz, srr, stt))
        srz = np.where(rim, np.where(x > 0, np.nan, 0.0), srz)
    return srr, stt, szz, srz


def twist_kernel(r: np.ndarray, z: np.ndarray, x: np.ndarray | float,
                 offset: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray]:
    """Field ``(σ_θz, σ_rθ)`` of a rigid flat punch of radius ``x`` twisted by a unit angle on a
    half-space of unit shear modulus, divided by ``4/π`` [RS44] (in the twisted body: on the
    surface under the punch ``σ_θz = r/sqrt(x² - r²)``, the traction the punch receives).

    With ``u_θ = (2/π)[r arcsin(x/l2) - r x n/l2²]`` the punch's displacement (it reduces to
    ``r`` under the punch and to the surface formula of theory §6.1 outside), ``σ_θz = -∂u/∂z``
    and ``σ_rθ = -(∂u/∂r - u/r)`` give ``σ_θz = r x² m/(l2² Q)``, ``σ_rθ = r² x³ n/(l2⁴ Q)``
    (notation of :func:`punch_kernel`). Arguments broadcast; ``inf`` at the rim; ``offset`` as in
    :func:`spheroidal`.
    """
    r, z, x, x2, _A, Q, m2, n2 = spheroidal(r, z, x, offset)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        m = np.sqrt(m2)
        n = np.sqrt(n2)
        l22 = x2 + n2
        stz = r * x2 * m / (l22 * Q)
        srt = r * r * x2 * x * n / (l22 * l22 * Q)
    rim = Q == 0
    if np.any(rim):
        val = np.where(x > 0, np.inf, 0.0)
        stz = np.where(rim, val, stz)
        srt = np.where(rim, val, srt)
    return stz, srt


def hertz_field(r: np.ndarray, z: np.ndarray, a: np.ndarray | float, p0: np.ndarray | float,
                nu: float
                ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Huber's closed form of the Hertz field ``(σ_rr, σ_θθ, σ_zz, σ_rz)``, Pa.

    Pressure ``p0 sqrt(1 - r²/a²)``; tension positive; ``z >= 0``. With ``u`` the positive root
    of ``r²/(a² + u) + z²/u = 1`` (``u = n²`` above) and ``s = z/sqrt(u)``::

        σ_zz = -p0 s³ a² u/(u² + a² z²)
        σ_rz = -p0 r z² a² sqrt(u)/((u² + a² z²)(a² + u))
        σ_rr = p0 [(1-2ν)/3 (a²/r²)(1 - s³) + s³ a² u/(u² + a² z²)
                   + s ((1-ν) u/(a² + u) + (1+ν)(sqrt(u)/a) atan(a/sqrt(u)) - 2)]
        σ_θθ = p0 [-(1-2ν)/3 (a²/r²)(1 - s³)
                   - s (2ν + (1-ν) u/(a² + u) - (1+ν)(sqrt(u)/a) atan(a/sqrt(u)))]

    (the sign of the last bracket of σ_θθ follows from the trace ``(1+ν) ψ_z``-form of
    Boussinesq's solution and Johnson's axis and surface values; one printed form has ``+``).

    ``(a²/r²)(1 - s³)`` is evaluated without cancellation near the axis (its axis limit is
    finite); on the surface inside the contact ``s = 1`` (``u → 0``).
    """
    r, z, a, p0 = np.broadcast_arrays(*(np.asarray(v, float) for v in (r, z, a, p0)))
    r, z, a, a2, _A, _Q, m2, u = spheroidal(r, z, a)           # u = n², m² = a² - l1²
    with np.errstate(divide="ignore", invalid="ignore"):
        su = np.sqrt(u)
        # s = z/sqrt(u) = m/a (mn = az); exactly 1 on the contact face
        s = np.sqrt(m2) / a
        s3 = s**3
        den = u * u + a2 * z * z
        zz = np.where(den > 0, s3 * a2 * u / den, s)         # on the face (u = 0) the limit is s
        # (1 - s³) a²/r²: 1 - s² = (a² - m²)/a² = l1²/a², l1² = r² a²/l2², so
        # (1 - s³)/r² = (1 + s + s²)/(1 + s) * (1 - s²)/r² = (1+s+s²)/((1+s) l2²)
        l22 = a2 + u
        edge = a2 * (1.0 + s + s * s) / ((1.0 + s) * l22)
        atn = np.where(su > 0, su / a * np.arctan2(a, su), 0.0)
        ratio = u / l22
        srz = np.where(den > 0, -r * z * z * a2 * su / (den * l22), 0.0)
    one3 = (1.0 - 2.0 * nu) / 3.0
    szz = -zz
    srr = one3 * edge + zz + s * ((1.0 - nu) * ratio + (1.0 + nu) * atn - 2.0)
    stt = -one3 * edge - s * (2.0 * nu + (1.0 - nu) * ratio - (1.0 + nu) * atn)
    return p0 * srr, p0 * stt, p0 * szz, p0 * srz


def _segments(r: np.ndarray, z: np.ndarray, a: np.ndarray, cuts: tuple[float, ...]
              ) -> np.ndarray:
    """Segment ends ``(points, k)`` for each point: 0, the cuts, ``r - w``, ``r``, ``r + w`` and
    ``a`` (``w = 2z``), each clipped to ``[0, a]`` and sorted (empty segments have equal ends).

    Near the surface the punch kernel of radius ``x`` peaks within a few ``z`` of ``x = r``."""
    w = _WIDTH * z
    pts = [np.zeros(r.shape), a, r, r - w, r + w] + [np.full(r.shape, c) for c in cuts]
    ends = np.stack([np.clip(v, 0.0, a) for v in pts], axis=-1)
    return np.sort(ends, axis=-1)


#: half-width of the segment around ``x = r``, in units of the depth
_WIDTH = 2.0
#: a segment whose near end lies closer to ``x = r`` than this fraction of its length is mapped
#: logarithmically in the distance from ``r`` (the kernel there falls like that distance^-1/2)
_LOG_RATIO = 0.05


def _nodes(r: np.ndarray, lo: np.ndarray, hi: np.ndarray, t: np.ndarray,
           z: np.ndarray | None = None, offsets: bool = False) -> tuple[np.ndarray, ...]:
    """Quadrature abscissae and Jacobians ``(x, dx/dt)`` on segments ``[lo, hi]``, ``t`` in [0, 1]
    (with ``offsets``, also ``x - r`` to full relative precision: ``(lo - r) + (hi - lo) s``, no
    rounding of ``x`` in it, so a node of a segment a hair wide next to ``r`` keeps its distance
    to ``r`` and never lands on it).

    Default map: ``x = lo + (hi - lo)(3t² - 2t³)`` (smooth at inverse-square-root ends). A segment
    lying on one side of ``r`` whose gap to ``r`` is a small fraction of its length, and not
    smaller than the depth ``z``, gets the geometric map ``x - r = (lo - r)((hi - r)/(lo - r))^t``
    (or the mirror image), so the ``|x - r|^-1/2`` fall of the near-surface kernel is integrated
    as a smooth function. Within ``z`` of ``r`` the kernel is smooth on the scale ``z`` and the
    geometric map would spend its nodes on decades where nothing happens (a cut a hair from
    ``r``, e.g. a stick radius of 1e-12 m under a point on the axis)."""
    L = hi - lo
    step = L * (t * t * (3.0 - 2.0 * t))
    x = lo + step
    jac = L * (6.0 * t * (1.0 - t))
    d = (lo - r) + step if offsets else None
    gap_r = lo - r                                   # segment right of r
    gap_l = r - hi                                   # segment left of r
    floor = 0.0 if z is None else z
    with np.errstate(divide="ignore", invalid="ignore"):
        right = (gap_r > 0) & (gap_r < _LOG_RATIO * L) & (gap_r >= floor)
        left = (gap_l > 0) & (gap_l < _LOG_RATIO * L) & (gap_l >= floor)
        if np.any(right):
            lr = np.log((hi - r) / np.where(right, gap_r, 1.0))
            dx = np.where(right, gap_r, 1.0) * np.exp(lr * t)
            x = np.where(right, r + dx, x)
            jac = np.where(right, dx * lr, jac)
            if d is not None:
                d = np.where(right, dx, d)
        if np.any(left):
            ll = np.log((r - lo) / np.where(left, gap_l, 1.0))
            dx = np.where(left, gap_l, 1.0) * np.exp(ll * t)
            x = np.where(left, r - dx, x)
            jac = np.where(left, dx * ll, jac)
            if d is not None:
                d = np.where(left, -dx, d)
    jac = np.where(L > 0, jac, 0.0)
    return (x, jac) if d is None else (x, jac, d)


def superposed_field(r: np.ndarray, z: np.ndarray, a: np.ndarray, edge: np.ndarray,
                     g_prime: Callable[[np.ndarray], np.ndarray], E_star: float, nu: float,
                     cuts: tuple[float, ...] = (),
                     g_prime_error: Callable[[np.ndarray], np.ndarray] | None = None,
                     g_values: Callable[[np.ndarray], np.ndarray] | None = None,
                     kernel: Callable[..., tuple[np.ndarray, ...]] | None = None,
                     scale: float | None = None
                     ) -> tuple[tuple[np.ndarray, ...], np.ndarray]:
    """``(E*/π)[∫_0^a g'(x) K(r, z; x) dx + edge K(r, z; a)]`` at flat arrays of points.

    Parameters
    ----------
    r, z, a, edge : ndarray
        Radius and depth of each point (m), the contact radius (m) and the edge depth
        ``d - g(a)`` (m) of its state (same shape).
    g_prime : callable
        ``g'(x)`` (dimensionless) at an array of radii.
    E_star, nu : float
        Effective modulus (Pa) and the body's Poisson ratio.
    cuts : tuple of float
        Radii where ``g'`` is singular or jumps (the profile's breakpoints).
    g_prime_error : callable, optional
        An absolute error estimate of ``g'`` (an interpolated ``g'``); its effect on the field,
        ``(E*/π) ∫ |δg'| |K| dx``, is added to the estimate.
    g_values : callable, optional
        ``g(x)`` itself. When given, each node's ``g'(x_j) w_j`` is replaced by the increment of
        ``g`` over the node's cell (the cells tile the segment with the rule's weights), a
        Riemann-Stieltjes sum: second order only, but it carries the exact increments of a
        ``g`` whose slope oscillates faster than the rule resolves (a linear table's ``g'`` has
        an inverse-square-root spike after every node, which point samples alias). The
        estimate is then the difference of the Kronrod and Gauss cell sums.
    kernel, scale : callable and float, optional
        Another elementary field ``kernel(r, z, x) -> components`` and its prefactor in place
        of the pressed punch and ``E*/π`` (the twisted punch: :func:`twist_kernel`, ``4G_t/π``,
        with ``g'`` the twist density ``Φ'``).

    Returns
    -------
    (srr, stt, szz, srz), error
        Stresses (Pa) and an absolute error estimate (Pa): per segment the QUADPACK estimate
        ``min(|K15 - G7|, S (200 |K15 - G7|/S)^1.5)`` (``S`` the integral of the magnitude),
        summed over the segments, the largest over the components, plus a rounding floor.

    Notes
    -----
    The x-range is split at ``x = r`` and ``r ± 2z`` (where the kernel peaks near the surface)
    and at ``cuts``; see :func:`_nodes` for the maps. Points are processed in chunks of
    :data:`CHUNK`; nothing loops over points or nodes in Python.
    """
    t, wk, wg = kronrod_rule()
    bk = np.concatenate([[0.0], np.cumsum(wk)])            # Kronrod cells tiling [0, 1]
    bg = np.concatenate([[0.0], np.cumsum(wg[1::2])])      # Gauss cells
    bk[-1] = bg[-1] = 1.0
    if kernel is None:
        def kernel(rr, zz, xx, offset=None):
            return punch_kernel(rr, zz, xx, nu, offset)
    # a kernel that takes x - r (offset=) gets it: cancellation-free near x = r
    pressed = "offset" in inspect.signature(kernel).parameters
    ncomp = len(kernel(np.zeros(1), np.ones(1), np.ones(1)))
    out = [np.zeros(r.shape) for _ in range(ncomp)]
    err = np.zeros(r.shape)
    k = E_star / np.pi if scale is None else scale
    for lo_i in range(0, r.size, CHUNK):
        sl = slice(lo_i, lo_i + CHUNK)
        rr, zz, aa, ee = r[sl], z[sl], a[sl], edge[sl]
        ends = _segments(rr, zz, aa, cuts)                 # (P, S + 1)
        lo, hi = ends[:, :-1, None], ends[:, 1:, None]     # (P, S, 1)
        z3 = zz[:, None, None]
        # (P, S, 15); with x - r for a kernel that takes it (cancellation-free A)
        nodes = _nodes(rr[:, None, None], lo, hi, t, z3, offsets=pressed)
        x, jac = nodes[0], nodes[1]
        hair = (hi - lo) < 1e-11 * hi                      # (P, S, 1)
        if np.any(hair):
            # a segment a few ulps wide: nodes that round onto its far end step back inside
            # (a density cut off at the contact radius, e.g. the twist's, is 0 on the end)
            x = np.where(hair & (x >= hi), np.nextafter(hi, lo), x)
        if g_values is not None:
            xk, _ = _nodes(rr[:, None, None], lo, hi, bk, z3)
            xg, _ = _nodes(rr[:, None, None], lo, hi, bg, z3)
            seg_k = np.broadcast_to(hi > lo, xk.shape)      # g on the non-empty segments
            seg_g = np.broadcast_to(hi > lo, xg.shape)
            with np.errstate(invalid="ignore"):
                # increments oriented along +x (a mirrored log map runs right to left)
                dgk = (np.diff(_scatter(seg_k, g_values(xk[seg_k])), axis=-1)
                       * np.sign(np.diff(xk, axis=-1)))
                dgg = (np.diff(_scatter(seg_g, g_values(xg[seg_g])), axis=-1)
                       * np.sign(np.diff(xg, axis=-1)))
        live = jac > 0
        xs = np.where(live, x, aa[:, None, None])          # dead nodes: a harmless radius
        # the density and the kernel at the live nodes only (empty segments are common: a
        # point beyond a or deeper than a/4 has some), scattered back with zeros elsewhere;
        # elementwise, so each live value is the one the full arrays gave
        xl = xs[live]
        with np.errstate(invalid="ignore", divide="ignore"):
            gp = _scatter(live, g_prime(xl)) * jac
            dgp = (None if g_prime_error is None else
                   _scatter(live, g_prime_error(xl)) * jac)
        shape3 = xs.shape
        args = (np.broadcast_to(rr[:, None, None], shape3)[live],
                np.broadcast_to(zz[:, None, None], shape3)[live], xl)
        comps = tuple(_scatter(live, c) for c in (
            kernel(*args, offset=nodes[2][live]) if pressed else kernel(*args)))
        has_edge = bool(np.any(ee != 0))
        if has_edge:
            edge_c = kernel(rr, zz, aa)
        e = np.zeros(rr.shape)
        # a point where the kernel over- or underflows (a cone's apex a hair below the surface:
        # Q³ underflows) gets inf or NaN on purpose: flagged singular by the caller, no warning
        with np.errstate(invalid="ignore", over="ignore", divide="ignore"):
            for i, c in enumerate(comps):
                f = c * gp                   # both 0 at the dead nodes
                if g_values is None:
                    kr = f @ wk                                    # (P, S)
                    ga = f @ wg
                    mag = np.abs(f) @ wk
                else:
                    cl = np.where(live, c, 0.0)
                    kr = np.sum(cl * dgk, axis=-1)
                    ga = np.sum(cl[..., 1::2] * dgg, axis=-1)
                    mag = np.sum(np.abs(cl * dgk), axis=-1)
                diff = np.abs(kr - ga)
                qp = np.where(mag > 0, mag * np.minimum(1.0, (200.0 * diff / mag) ** 1.5), 0.0)
                val = np.sum(kr, axis=-1)
                if dgp is not None:
                    diff = diff + np.where(live, np.abs(c * dgp), 0.0) @ wk
                    qp = qp + np.where(live, np.abs(c * dgp), 0.0) @ wk
                if has_edge:
                    val = val + ee * edge_c[i]
                out[i][sl] = k * val
                e = np.maximum(e, k * np.sum(np.minimum(diff, qp), axis=-1))
        err[sl] = e
    scale = np.maximum.reduce([np.abs(o) for o in out])
    return tuple(out), err + 1e-14 * scale


def _scatter(mask: np.ndarray, values: np.ndarray) -> np.ndarray:
    """``values`` at the ``True`` places of ``mask``, 0 elsewhere."""
    out = np.zeros(mask.shape)
    out[mask] = values
    return out


def principal_axisymmetric(srr: np.ndarray, stt: np.ndarray, szz: np.ndarray, srz: np.ndarray
                           ) -> np.ndarray:
    """Principal stresses (descending, last axis of length 3) when ``σ_rθ = σ_θz = 0`` (NaN at a
    singular point whose components are infinite)."""
    with np.errstate(invalid="ignore"):
        mean = 0.5 * (srr + szz)
        rad = np.hypot(0.5 * (srr - szz), srz)
    p = np.stack([mean + rad, mean - rad, stt], axis=-1)
    return -np.sort(-p, axis=-1)


def principal_general(sxx, syy, szz, sxy, sxz, syz) -> np.ndarray:
    """Principal stresses (descending, last axis of length 3) of symmetric tensors."""
    T = np.stack([np.stack([sxx, sxy, sxz], -1), np.stack([sxy, syy, syz], -1),
                  np.stack([sxz, syz, szz], -1)], -2)
    finite = np.all(np.isfinite(T), axis=(-1, -2))
    ev = np.full(T.shape[:-1], np.nan)
    if np.any(finite):
        ev[finite] = np.linalg.eigvalsh(T[finite])[..., ::-1]
    return ev


def von_mises(s11, s22, s33, s12, s13, s23) -> np.ndarray:
    """Von Mises equivalent stress, Pa."""
    with np.errstate(invalid="ignore"):
        return np.sqrt(0.5 * ((s11 - s22)**2 + (s22 - s33)**2 + (s33 - s11)**2)
                       + 3.0 * (s12 * s12 + s13 * s13 + s23 * s23))
