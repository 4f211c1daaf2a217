"""Compiled (numba, extra ``fast``) contact-law step, the contacts on their MDR springs: the
switch of contacts from the exact constant-load law onto their springs (:func:`switch_pass`,
once per contact, in the rows of the law's spring pool) and the spring step of contacts on
springs (:func:`spring_pass`, every step). The arithmetic of
:mod:`contactlab.physics.law_springs`, one contact at a time, without temporaries; built,
compiled and cached with the other passes by :func:`contactlab.physics.law_kernel._kernels`
(serial and threaded builds, contacts independent: the same bits).
"""
from __future__ import annotations

import math

import numpy as np

__all__ = ["spring_pass", "switch_pass", "switch_step_pass"]

# ``prange`` in the loops over contacts: ``range`` in plain Python and in the serial build, numba's
# parallel range in the threaded build (set with the builds: ``law_kernel._kernels``)
_prange = range


# the pieces the passes share; numba inlines them into each pass at its IR level
# (``inline="always"``, set with the builds: ``law_kernel._kernels``), the same bits as written
# out (the edge cell's search, zeroing and outputs as inlined helpers measured 10-15 % slower)
_INLINE = ("_radius", "_span", "_edge_terms", "_integrals", "_weight", "_slip", "_sum",
           "_cells", "_first_cells")


def _radius(n, d0, kcc):
    """The radius of a contact of profile family ``n`` (not the flat punch) at depth ``d0``."""
    if n == 2.0:
        return math.sqrt(d0 / kcc)
    return (d0 / kcc) ** (1.0 / n)


def _span(n, kcc, cov):
    """``kc cov^(n+1)``, the factor of a cover's boundary products (paraboloid and cone by
    products, no pow)."""
    if n == 2.0:
        return kcc * cov * cov * cov
    if n == 1.0:
        return kcc * cov * cov
    return kcc * cov ** (n + 1.0)


def _edge_terms(n, kcc, x):
    """``(kc x^(n+1) / (n+1), kc x^(n+2) / (n+2))``: the integrals of the gap up to radius
    ``x``, the edge cell's closed forms."""
    n1 = n + 1.0
    n2 = n + 2.0
    if n == 2.0:
        return kcc * x * x * x / n1, kcc * x * x * x * x / n2
    if n == 1.0:
        return kcc * x * x / n1, kcc * x * x * x / n2
    return kcc * x ** n1 / n1, kcc * x ** n2 / n2


def _integrals(i, k, d, x, w, bl, bl2, br2, gl, gr, hl, hr, Gx, Hx):
    """``(S, T)``, the cell integrals of cell ``i`` at depth ``d`` and radius ``x`` in edge
    cell ``k``: a cell inside the edge cell, the edge cell by its closed forms ``Gx, Hx``
    (:func:`_edge_terms`), nothing beyond (boundary ``bl .. br``, products ``g, h``)."""
    if i < k:
        return d * w - (gr - gl), d * (br2 - bl2) / 2.0 - (hr - hl)
    if i == k and x > bl:
        return (max(d * (x - bl) - (Gx - gl), 0.0),
                max(d * (x * x - bl2) / 2.0 - (Hx - hl), 0.0))
    return 0.0, 0.0


def _weight(dd, S, So, w, x, bl):
    """The share of a cell in contact: the change of its integral over the depth's change
    ``dd`` (the last integral ``So``), or the covered fraction at radius ``x`` where the depth
    holds; clipped to [0, 1]."""
    if dd != 0.0:
        return min(max((S - So) / (dd * w), 0.0), 1.0)
    return min(max((x - bl) / w, 0.0), 1.0)


def _slip(mo, K, L, inc, e, F, free, cs, bl, a):
    """One Jenkins element (stiffness ``K``, limit ``L``) from ``mo`` by the control's
    increment ``inc``: ``(m, e, F, free, cs)``, the element, the dissipation ``e`` and force
    ``F`` summed on, and the stick radius ``cs`` (the first slipping cell's left boundary,
    ``free`` until then). The dissipation ``(trial - m) m / K`` is a zero where the element
    sticks (trial == m): adding it leaves the sum's bits unchanged, so it is skipped there."""
    trial = mo + K * inc
    mn = min(max(trial, -L), L)
    if K > 0.0 and trial != mn:
        e += (trial - mn) * mn / K
    F += mn
    if free and abs(mn) >= L:
        free = False
        cs = min(bl, a)
    return mn, e, F, free, cs


def _sum(m, de, L, e, F, free, cs, bl, a):
    """An element ``m`` after its step (limit ``L``, dissipation ``de``) summed on: ``(e, F,
    free, cs)`` as :func:`_slip` leaves them."""
    e += de
    F += m
    if free and abs(m) >= L:
        free = False
        cs = min(bl, a)
    return e, F, free, cs


def _cells(beta, bG, bH, m_tan, m_tor, r, i0, cnt, cov, cp1, cp2, d, K2, K16, L2, L4, it, ir,
           has_u, has_phi, a, e, Ft, M, free_t, free_m, ct, cm):
    """The cells ``i0 .. i0 + cnt - 1`` of row ``r`` inside the edge cell (weight 1) at depth
    ``d``, cover ``cov`` (the boundary factors ``cp1 = kc cov^(n+1)``, ``cp2 = cp1 cov``),
    both channels' elements stepped (:func:`_slip2`), stored and summed on (a channel only
    where driven): ``(e, Ft, M, free_t, free_m, ct, cm)`` (:func:`_sum`). Compiled,
    :func:`contactlab.physics.law_kernel_lanes.cells4` replaces it for four cells that lie in
    the row (``i0 + 4 <= N``): the same operations, IEEE lane by lane, so the same bits."""
    bl = cov * beta[i0]
    bl2 = bl * bl
    bl3 = bl2 * bl
    gl = cp1 * bG[i0]
    hl = cp2 * bH[i0]
    for i in range(i0, i0 + cnt):
        br = cov * beta[i + 1]
        br2 = br * br
        br3 = br2 * br
        w = br - bl
        gr = cp1 * bG[i + 1]
        hr = cp2 * bH[i + 1]
        # :func:`_integrals`'s first form (a cell inside the edge cell)
        Lt = L2 * (d * w - (gr - gl))
        Lr = L4 * (d * (br2 - bl2) / 2.0 - (hr - hl))
        mt, mr, et, er = _slip2(m_tan[r, i], m_tor[r, i], K2 * w, K16 * ((br3 - bl3) / 3.0), Lt,
                                Lr, it, ir)
        if has_u:
            m_tan[r, i] = mt
            e, Ft, free_t, ct = _sum(mt, et, Lt, e, Ft, free_t, ct, bl, a)
        if has_phi:
            m_tor[r, i] = mr
            e, M, free_m, cm = _sum(mr, er, Lr, e, M, free_m, cm, bl, a)
        bl, bl2, bl3, gl, hl = br, br2, br3, gr, hr
    return e, Ft, M, free_t, free_m, ct, cm


_W = 4                  # cells per vector of the compiled ``_cells4`` and ``_first4``
_CELLS_PY = _cells4 = _cells    # the plain source (compiled: law_kernel_lanes.cells4)


def _first_cells(beta, bG, bH, X, m_tan, m_tor, r, c, i0, cnt, dt, dr, cov, cp1, cp2, d0, d,
                 K2, K16, L2, L4, incs, it, ir, st_u, st_p, a, acc):
    """The cells ``i0 .. i0 + cnt - 1`` of a fresh row ``r`` inside both edge cells (the
    switch's and the step's: contact fraction and weight 1) of contact ``c``: the switch's
    elements at the held depth ``d0`` (the turning points ``X[ch, c, :dt or dr]`` then the
    controls replayed; ``incs``: the increments from 0 and to the control, ``(it0, ir0, itl,
    irl)``), then the step's at depth ``d`` where a channel is driven (``st_u``, ``st_p``),
    stored and summed on: ``acc = (e, Ft, M, free_t, free_m, ct, cm)`` as it leaves them
    (a call of at most 30 arguments: numba inlines no call with more). Compiled,
    :func:`~contactlab.physics.law_kernel_lanes.first4` replaces it for four cells in the
    row: the same operations lane by lane, the same bits (the four past ``cnt``: +0)."""
    it0, ir0, itl, irl = incs
    e, Ft, M, free_t, free_m, ct, cm = acc
    bl = cov * beta[i0]
    bl2 = bl * bl
    bl3 = bl2 * bl
    gl = cp1 * bG[i0]
    hl = cp2 * bH[i0]
    for i in range(i0, i0 + cnt):
        br = cov * beta[i + 1]
        br2 = br * br
        br3 = br2 * br
        w = br - bl
        gr = cp1 * bG[i + 1]
        hr = cp2 * bH[i + 1]
        dg = gr - gl
        dh = hr - hl
        x1 = br2 - bl2
        Kt = K2 * w
        Kr = K16 * ((br3 - bl3) / 3.0)
        # the switch (held depth d0): the elements after 0 -> X[0] -> ... -> x
        L = L2 * (d0 * w - dg)
        m0t = 0.0
        if dt > 0:
            m0t = min(max(m0t + Kt * it0, -L), L)
            for q in range(1, dt):
                m0t = min(max(m0t + Kt * (X[0, c, q] - X[0, c, q - 1]), -L), L)
        m0t = min(max(m0t + Kt * itl, -L), L)
        L = L4 * (d0 * x1 / 2.0 - dh)
        m0r = 0.0
        if dr > 0:
            m0r = min(max(m0r + Kr * ir0, -L), L)
            for q in range(1, dr):
                m0r = min(max(m0r + Kr * (X[1, c, q] - X[1, c, q - 1]), -L), L)
        m0r = min(max(m0r + Kr * irl, -L), L)
        # the step (depth d)
        Lt = L2 * (d * w - dg)
        Lr = L4 * (d * x1 / 2.0 - dh)
        mt, mr, et, er = _slip2(m0t, m0r, Kt, Kr, Lt, Lr, it, ir)
        if st_u:
            m0t = mt
            e, Ft, free_t, ct = _sum(mt, et, Lt, e, Ft, free_t, ct, bl, a)
        if st_p:
            m0r = mr
            e, M, free_m, cm = _sum(mr, er, Lr, e, M, free_m, cm, bl, a)
        m_tan[r, i] = m0t
        m_tor[r, i] = m0r
        bl, bl2, bl3, gl, hl = br, br2, br3, gr, hr
    return e, Ft, M, free_t, free_m, ct, cm


_FIRST_CELLS_PY = _first4 = _first_cells      # (compiled: law_kernel_lanes.first4)


def _slip2(mt, mr, Kt, Kr, Lt, Lr, it, ir):
    """The Jenkins elements of both channels of one cell (tangential ``mt``, torsion ``mr``;
    stiffnesses, limits, increments of the controls): ``(mt, mr, et, er)``, the elements
    after the step and the dissipation of each, ``(trial - m) m / K`` where the element
    slips (``K > 0``, ``trial != m``), else +0 (the sum it is added to is never -0: adding +0
    leaves its bits). Compiled, :func:`contactlab.physics.law_kernel_lanes.slip2` replaces
    it: the same operations on 2-lane vectors, IEEE lane by lane, so the same bits."""
    tt = mt + Kt * it
    tr = mr + Kr * ir
    nt = min(max(tt, -Lt), Lt)
    nr = min(max(tr, -Lr), Lr)
    et = (tt - nt) * nt / Kt if Kt > 0.0 and tt != nt else 0.0
    er = (tr - nr) * nr / Kr if Kr > 0.0 and tr != nr else 0.0
    return nt, nr, et, er


_SLIP2_PY = _slip2      # the plain source (the tests run the kernels uncompiled against it)


def _intrinsics() -> dict:
    """The compiled builds' intrinsics, by name (:mod:`~contactlab.physics.law_kernel_lanes`)."""
    from . import law_kernel_lanes as _lanes
    return {"_slip2": _lanes.slip2(), "_cells4": _lanes.cells4(_W), "_first4": _lanes.first4(_W)}


def _spring_pass(idx, slot, d, a, u, phi, has_u, has_phi, cover, kc, n, beta, bG, bH, mu, E, G,
                 Gt, a_old, k_old, d_old, m_tan, m_tor, x_tan, x_tor, Ft, ct, M, cm, dW, flag,
                 full_u=False, full_phi=False):
    """One MDR spring step of the contacts ``idx`` (the arithmetic of
    :mod:`contactlab.physics.law_springs`, one contact at a time): cell integrals, contact
    weights, Jenkins elements of both channels, forces, stick radii and dissipation. The
    spring state of contact ``c`` is row ``slot[c]`` of ``cover, a_old, ..., x_tor``. The
    last step's cell integrals (needed only for the weights of the cells between the old and
    new edge cells, where the depth moved) are not stored: they are recomputed from the
    row's depth ``d_old``, radius ``a_old`` and edge cell ``k_old`` by the expressions that
    formed them in the last step or switch, so to the bit (a regridded row: the same
    expressions at the regrid's radius). A contact whose radius exceeds its cover is left
    as it is, ``flag[c] = 4``, and counted (its cells are regridded first:
    :func:`spring_pass`). The elements of the cells beyond the edge cell are +0 after the
    step (a cell out of contact carries nothing; the reference's clip of them to a zero limit
    gave a zero of either sign, the same sums): written in the cells up to the last step's
    edge cell, and in every cell of a channel with ``full_u`` / ``full_phi`` (its cells beyond
    the last edge may not be +0: :attr:`~contactlab.effects.law_pool.SpringPool.stale`);
    beyond that they are +0 already and neither read nor written. Returns (non-finite,
    grown)."""
    N = beta.size - 1
    nonfinite = 0
    grown = 0
    for j in _prange(idx.size):
        c = idx[j]
        r = slot[c]
        cov = cover[r]
        aj = a[c]
        if aj > cov:
            flag[c] = 4
            grown += 1
            continue
        kcc = kc[c]
        dj = d[c]
        cp1 = _span(n, kcc, cov)
        Ga, Ha = _edge_terms(n, kcc, aj)
        cp2 = cp1 * cov
        # the edge cell, searched from the last step's (the boundaries do not decrease: the
        # cell of a search from 0, in a step or two where the radius moved within a cell)
        ko = k_old[r]
        k = min(max(ko, 0), N - 1)
        while k > 0 and not cov * beta[k] < aj:
            k -= 1
        while k < N - 1 and cov * beta[k + 1] < aj:
            k += 1
        lo = min(k, ko)
        hi = max(k, ko) + 1
        # the row's last depth and radius and the contact's controls read once, the sums
        # checked in registers (each read again after the row's stores: the pass measured
        # 110-115 against 102-104 ms CPU at 10^6 contacts)
        do = d_old[r]
        ao = a_old[r]
        dd = dj - do
        mu_E = mu[c] * E[c]
        uc = u[c] if has_u else 0.0
        pc = phi[c] if has_phi else 0.0
        du = uc - x_tan[r] if has_u else 0.0
        dp = pc - x_tor[r] if has_phi else 0.0
        Ft_j, M_j, e, ct_j, cm_j, free_t, free_m = 0.0, 0.0, 0.0, aj, aj, True, True
        # per-contact factors (``2 mu E S`` is ``(2 mu E) S``: the same products, once)
        L2, L4, K2, K16 = 2.0 * mu_E, 4.0 * mu_E, 2.0 * G[c], 16.0 * Gt[c]
        # the cells of weight 1, without a branch per cell: left of both edges when the depth
        # moves, left of the edge cell when it holds (the left boundary is below a by at least
        # the cell width: the clipped ratio is 1); a product with 1 is left out
        inner = lo if dd != 0.0 else k
        # four cells at a time (:func:`_cells4`; the scalar loop where a row ends within the
        # four), then the left boundary's products of the next cell, as the loop leaves them
        for i0 in range(0, inner, _W):
            if i0 + _W <= N:
                e, Ft_j, M_j, free_t, free_m, ct_j, cm_j = _cells4(
                    beta, bG, bH, m_tan, m_tor, r, i0, min(inner - i0, _W), cov, cp1, cp2, dj,
                    K2, K16, L2, L4, du, dp, has_u, has_phi, aj, e, Ft_j, M_j, free_t, free_m,
                    ct_j, cm_j)
            else:
                e, Ft_j, M_j, free_t, free_m, ct_j, cm_j = _cells(
                    beta, bG, bH, m_tan, m_tor, r, i0, inner - i0, cov, cp1, cp2, dj, K2, K16,
                    L2, L4, du, dp, has_u, has_phi, aj, e, Ft_j, M_j, free_t, free_m, ct_j, cm_j)
        bl = cov * beta[inner]
        bl2 = bl * bl
        bl3 = bl2 * bl
        gl = cp1 * bG[inner]
        hl = cp2 * bH[inner]
        # the last step's edge-cell closed form (the old radius; its cell's integral below)
        Gao = _edge_terms(n, kcc, ao)[0] if dd != 0.0 and ko <= k else 0.0
        # the edge cell and those inside it the depth moved over; each cell's left-boundary
        # products are its neighbour's right ones (the same bits)
        for i in range(inner, k + 1):
            br = cov * beta[i + 1]
            br2 = br * br
            br3 = br2 * br
            w = br - bl
            gr = cp1 * bG[i + 1] if i < k else gl
            hr = cp2 * bH[i + 1] if i < k else hl
            S, T = _integrals(i, k, dj, aj, w, bl, bl2, br2, gl, gr, hl, hr, Ga, Ha)
            # the last step's integral of this cell, by the expressions that formed it
            # (inside the old edge cell, the old edge cell, beyond it; its T is not used)
            So = (_integrals(i, ko, do, ao, w, bl, bl2, br2, cp1 * bG[i],
                             cp1 * bG[i + 1], hl, hr, Gao, 0.0)[0] if dd != 0.0 else 0.0)
            wgt = _weight(dd, S, So, w, aj, bl)
            gl, hl = gr, hr
            Lt = L2 * S
            Lr = L4 * T
            mt, mr, et, er = _slip2(m_tan[r, i], m_tor[r, i], K2 * w * wgt,
                                    K16 * ((br3 - bl3) / 3.0) * wgt, Lt, Lr, du, dp)
            if has_u:
                m_tan[r, i] = mt
                e, Ft_j, free_t, ct_j = _sum(mt, et, Lt, e, Ft_j, free_t, ct_j, bl, aj)
            if has_phi:
                m_tor[r, i] = mr
                e, M_j, free_m, cm_j = _sum(mr, er, Lr, e, M_j, free_m, cm_j, bl, aj)
            bl, bl2, bl3 = br, br2, br3
        # beyond the edge cell: S = T = 0, so both limits are +0 and the reference's clip
        # left a zero of either sign there (the sums, dissipation and stick radius the same
        # for either: a sum starting at +0 is never -0, the stiffness is 0 or the element
        # sticks at 0, and the first such cell, at or beyond the radius, counts as slipping
        # at ``min(b, a) = a``, the radius the stick radius holds anyway): written +0 up to
        # the last step's edge cell (all cells of a stale channel); the cells beyond both
        # edges are +0 already (written so when they left the contact) and left untouched
        if has_u:
            for i in range(k + 1, N if full_u else hi):
                m_tan[r, i] = 0.0
        if has_phi:
            for i in range(k + 1, N if full_phi else hi):
                m_tor[r, i] = 0.0
        k_old[r] = k
        d_old[r] = dj
        a_old[r] = aj
        if has_u:
            x_tan[r] = uc
            ct[c] = ct_j
        else:
            ct[c] = aj
        if has_phi:
            x_tor[r] = pc
            cm[c] = cm_j
        else:
            cm[c] = aj
        Ft[c] = Ft_j
        M[c] = M_j
        dW[c] = e
        if not (math.isfinite(e) and math.isfinite(Ft_j) and math.isfinite(M_j)):
            nonfinite += 1
    return nonfinite, grown


def _switch_pass(idx, ref, a, flat, is_flat, cover_factor, kc, n, beta, bG, bH, mu, E, G, Gt,
                 X, depth, x, slot, owner, base, cover, a_old, k_old, d_old, m_tan, m_tor,
                 x_tan, x_tor):
    """Switch the contacts ``idx`` from the exact constant-load law to their MDR springs (the
    arithmetic of ``ContactLaw._to_springs`` with the cell integrals of :func:`_spring_pass`,
    one contact at a time, no temporaries): cover, normal cells at the held depth ``ref`` the
    contact leaves, and each channel's Masing turning points ``X[ch, c, :depth]`` then its
    current control ``x[ch, c]`` replayed through the elements at that load (channel 0
    tangential, 1 torsion). Contact ``idx[j]`` gets row ``base + j`` of the spring pool
    (``slot``: row per contact, ``owner``: contact per row)."""
    N = beta.size - 1
    for j in _prange(idx.size):
        c = idx[j]
        r = base + j
        slot[c] = r
        owner[r] = c
        d0 = ref[c]
        kcc = kc[c]
        if is_flat:
            a0 = flat[c] if d0 > 0.0 else 0.0
        else:
            a0 = _radius(n, d0, kcc)
        cov = cover_factor[c] * max(a0, a[c])
        cover[r] = cov
        cp1 = _span(n, kcc, cov)
        Ga, Ha = _edge_terms(n, kcc, a0)
        cp2 = cp1 * cov
        k = 0
        while k < N - 1 and cov * beta[k + 1] < a0:
            k += 1
        mu_E = mu[c] * E[c]
        # the elements at the held load: the history 0 -> X[0] -> ... -> X[depth-1] -> x,
        # element by element (each element's path is independent of the others); the products
        # of a cell's left boundary are its left neighbour's right ones, carried (the same
        # expressions, the same bits)
        bl = cov * beta[0]
        bl2 = bl * bl
        bl3 = bl2 * bl
        gl = cp1 * bG[0]
        hl = cp2 * bH[0]
        for i in range(k + 1):
            br = cov * beta[i + 1]
            br2 = br * br
            br3 = br2 * br
            w = br - bl
            gr = cp1 * bG[i + 1] if i < k else gl
            hr = cp2 * bH[i + 1] if i < k else hl
            S, T = _integrals(i, k, d0, a0, w, bl, bl2, br2, gl, gr, hl, hr, Ga, Ha)
            gl, hl = gr, hr
            # inside the edge cell the clipped ratio is 1 (a0 > br, so a0 - bl >= w): no
            # division, the same bits
            frac = 1.0 if i < k else _weight(0.0, 0.0, 0.0, w, a0, bl)
            for ch in range(2):
                if ch == 0:
                    Kc = 2.0 * G[c] * w * frac
                    L = 2.0 * mu_E * S
                else:
                    Kc = 16.0 * Gt[c] * ((br3 - bl3) / 3.0) * frac
                    L = 4.0 * mu_E * T
                m = 0.0
                prev = 0.0
                for p in range(depth[ch, c]):
                    tgt = X[ch, c, p]
                    m = min(max(m + Kc * (tgt - prev), -L), L)
                    prev = tgt
                m = min(max(m + Kc * (x[ch, c] - prev), -L), L)
                if ch == 0:
                    m_tan[r, i] = m
                else:
                    m_tor[r, i] = m
            bl, bl2, bl3 = br, br2, br3
        # the cells beyond the contact: S = T = 0 and contact fraction 0 (their left edge is
        # at or beyond a0), so both stiffnesses and limits are +0 and the reference's replay
        # through them gives +0 (from +0, m + 0 dx is +0 and its clip to [-0, +0] keeps it;
        # finite turning points): written, without the replay
        for i in range(k + 1, N):
            m_tan[r, i] = 0.0
            m_tor[r, i] = 0.0
        x_tan[r] = x[0, c]
        x_tor[r] = x[1, c]
        k_old[r] = k
        d_old[r] = d0
        a_old[r] = a0


def _switch_step_pass(block, idx, ref, a, flat, is_flat, cover_factor, kc, n, beta, bG, bH, mu,
                      E, G, Gt, X, depth, x, slot, owner, base, d, u, phi, has_u, has_phi,
                      cover, a_old, k_old, d_old, m_tan, m_tor, x_tan, x_tor, Ft, ct, M, cm, dW,
                      flag):
    """Switch the contacts ``idx`` onto their springs and step them there, in blocks of
    ``block`` contacts: each block switched (:func:`_switch_pass`, rows ``base + j``) and
    stepped (:func:`_spring_pass`) while its fresh rows are still in cache, the blocks spread
    over the threads by one parallel loop (one launch per step, not two per block). Contacts
    are independent and rows assigned in the same order: the bits of one switch and one step.
    Returns (non-finite, grown) of the spring steps."""
    nb = (idx.size + block - 1) // block
    nonfinite = 0
    grown = 0
    for b in _prange(nb):
        lo = b * block
        part = idx[lo:min(lo + block, idx.size)]
        _switch_one(part, ref, a, flat, is_flat, cover_factor, kc, n, beta, bG, bH, mu, E, G,
                    Gt, X, depth, x, slot, owner, base + lo, cover, a_old, k_old, d_old, m_tan,
                    m_tor, x_tan, x_tor)
        nf, gr = _spring_one(part, slot, d, a, u, phi, has_u, has_phi, cover, kc, n, beta, bG,
                             bH, mu, E, G, Gt, a_old, k_old, d_old, m_tan, m_tor, x_tan, x_tor,
                             Ft, ct, M, cm, dW, flag, False, False)
        nonfinite += nf
        grown += gr
    return nonfinite, grown


def _first_pass(idx, ref, a, flat, is_flat, cover_factor, kc, n, beta, bG, bH, mu, E, G, Gt,
                X, depth, x, slot, owner, base, d, u, phi, has_u, has_phi, cover, a_old, k_old,
                d_old, m_tan, m_tor, x_tan, x_tor, Ft, ct, M, cm, dW, flag, clean=1 << 62):
    """Switch the contacts ``idx`` onto their springs and step them there, one contact at a
    time: the arithmetic of :func:`_switch_pass` then :func:`_spring_pass` (the bits of the
    two), with the row in registers between them. A cell's boundary products serve both; the
    switch's cell integrals at the held depth are the step's last ones (the spring pass
    recomputes them from the row); the cells beyond the step's edge cell are not replayed
    where the step writes them +0 (a channel not driven keeps the switch's elements), nor
    written beyond both edge cells in rows from ``clean`` on (+0 already: the pool's
    :attr:`~contactlab.effects.law_pool.SpringPool.clean`). A contact whose radius exceeds
    its fresh cover gets the switch's row only, ``flag[c] = 4``, counted (stepped after its
    regrid: :func:`switch_step_pass`). Contact ``idx[j]`` gets row ``base + j``. Returns
    (non-finite, grown)."""
    N = beta.size - 1
    nonfinite = 0
    grown = 0
    for j in _prange(idx.size):
        c = idx[j]
        r = base + j
        slot[c] = r
        owner[r] = c
        # the switch's scalars (:func:`_switch_pass`)
        d0 = ref[c]
        kcc = kc[c]
        if is_flat:
            a0 = flat[c] if d0 > 0.0 else 0.0
        else:
            a0 = _radius(n, d0, kcc)
        aj = a[c]
        cov = cover_factor[c] * max(a0, aj)
        cover[r] = cov
        cp1 = _span(n, kcc, cov)
        Ga0, Ha0 = _edge_terms(n, kcc, a0)
        Ga, Ha = _edge_terms(n, kcc, aj)
        cp2 = cp1 * cov
        k0 = 0
        while k0 < N - 1 and cov * beta[k0 + 1] < a0:
            k0 += 1
        mu_E = mu[c] * E[c]
        x0t = x[0, c]
        x0r = x[1, c]
        # the step's scalars (:func:`_spring_pass`; the row's old values are the switch's)
        step = not aj > cov
        if not step:
            flag[c] = 4
            grown += 1
        dj = d[c]
        # the step's edge cell, searched from the switch's (:func:`_spring_pass`)
        k = k0
        while k > 0 and not cov * beta[k] < aj:
            k -= 1
        while k < N - 1 and cov * beta[k + 1] < aj:
            k += 1
        if not step:
            k = k0
        hi = max(k, k0) + 1
        dd = dj - d0
        st_u = step and has_u
        st_p = step and has_phi
        # the controls read once (read again after the row's stores, for the row's controls:
        # the pass measured 4-6 % slower)
        uc = u[c] if has_u else 0.0
        pc = phi[c] if has_phi else 0.0
        du = uc - x0t if st_u else 0.0
        dp = pc - x0r if st_p else 0.0
        inner = min(k, k0) if dd != 0.0 else k
        Ft_j, M_j, e, ct_j, cm_j, free_t, free_m = 0.0, 0.0, 0.0, aj, aj, True, True
        L2, L4, K2, K16 = 2.0 * mu_E, 4.0 * mu_E, 2.0 * G[c], 16.0 * Gt[c]
        # the replay's increments of the control, per contact (the same subtractions as per
        # cell): the first from 0 (a stack of turning points), the last to the control now
        dt = depth[0, c]
        dr = depth[1, c]
        pt = X[0, c, dt - 1] if dt > 0 else 0.0
        pr = X[1, c, dr - 1] if dr > 0 else 0.0
        it0 = X[0, c, 0] - 0.0 if dt > 0 else 0.0
        ir0 = X[1, c, 0] - 0.0 if dr > 0 else 0.0
        itl = x0t - pt
        irl = x0r - pr
        # the cells inside both edge cells (their contact fraction and weight 1, boundary
        # products of the cell's own right boundary): no branch per cell on the cell's place;
        # the switch's stiffness is the step's (``K w 1``: the same bits)
        n1 = min(k, k0)
        incs = (it0, ir0, itl, irl)
        for i0 in range(0, n1, _W):
            acc = (e, Ft_j, M_j, free_t, free_m, ct_j, cm_j)
            if i0 + _W <= N:
                e, Ft_j, M_j, free_t, free_m, ct_j, cm_j = _first4(
                    beta, bG, bH, X, m_tan, m_tor, r, c, i0, min(n1 - i0, _W), dt, dr, cov, cp1,
                    cp2, d0, dj, K2, K16, L2, L4, incs, du, dp, st_u, st_p, aj, acc)
            else:
                e, Ft_j, M_j, free_t, free_m, ct_j, cm_j = _first_cells(
                    beta, bG, bH, X, m_tan, m_tor, r, c, i0, n1 - i0, dt, dr, cov, cp1, cp2, d0,
                    dj, K2, K16, L2, L4, incs, du, dp, st_u, st_p, aj, acc)
        bl = cov * beta[n1]
        bl2 = bl * bl
        bl3 = bl2 * bl
        gl = cp1 * bG[n1]
        hl = cp2 * bH[n1]
        # each cell up to both edge cells: the switch's elements (to the switch's edge cell,
        # +0 beyond it), then the step's (to its edge cell, +0 beyond it) where it drives
        last = hi if (not st_u or not st_p) else k + 1
        for i in range(n1, last):
            br = cov * beta[i + 1]
            br2 = br * br
            br3 = br2 * br
            w = br - bl
            if i < k0 or i < k:
                gr = cp1 * bG[i + 1]
                hr = cp2 * bH[i + 1]
            else:
                gr = gl
                hr = hl
            # the switch (held depth d0, radius a0)
            S0, T0 = _integrals(i, k0, d0, a0, w, bl, bl2, br2, gl, gr, hl, hr, Ga0, Ha0)
            m0t = 0.0
            m0r = 0.0
            if i <= k0 and (i <= k or not st_u or not st_p):
                frac = 1.0 if i < k0 else _weight(0.0, 0.0, 0.0, w, a0, bl)
                Kc = K2 * w * frac
                L = L2 * S0
                if dt > 0:
                    m0t = min(max(m0t + Kc * it0, -L), L)
                    for q in range(1, dt):
                        m0t = min(max(m0t + Kc * (X[0, c, q] - X[0, c, q - 1]), -L), L)
                m0t = min(max(m0t + Kc * itl, -L), L)
                Kc = K16 * ((br3 - bl3) / 3.0) * frac
                L = L4 * T0
                if dr > 0:
                    m0r = min(max(m0r + Kc * ir0, -L), L)
                    for q in range(1, dr):
                        m0r = min(max(m0r + Kc * (X[1, c, q] - X[1, c, q - 1]), -L), L)
                m0r = min(max(m0r + Kc * irl, -L), L)
            # the step (depth dj, radius aj), cells up to its edge cell
            if i <= k and (st_u or st_p):
                S, T = _integrals(i, k, dj, aj, w, bl, bl2, br2, gl, gr, hl, hr, Ga, Ha)
                wgt = 1.0 if i < inner else _weight(dd, S, S0, w, aj, bl)
                if st_u:
                    m0t, e, Ft_j, free_t, ct_j = _slip(
                        m0t, K2 * w if i < inner else K2 * w * wgt, L2 * S, du, e, Ft_j,
                        free_t, ct_j, bl, aj)
                if st_p:
                    m0r, e, M_j, free_m, cm_j = _slip(
                        m0r, (K16 * ((br3 - bl3) / 3.0) if i < inner
                              else K16 * ((br3 - bl3) / 3.0) * wgt),
                        L4 * T, dp, e, M_j, free_m, cm_j, bl, aj)
            elif i > k:
                if st_u:
                    m0t = 0.0
                if st_p:
                    m0r = 0.0
            m_tan[r, i] = m0t
            m_tor[r, i] = m0r
            gl, hl = gr, hr
            bl, bl2, bl3 = br, br2, br3
        for i in range(last, N if r < clean else last):
            m_tan[r, i] = 0.0
            m_tor[r, i] = 0.0
        if not step:
            k_old[r] = k0
            d_old[r] = d0
            a_old[r] = a0
            x_tan[r] = x0t
            x_tor[r] = x0r
            continue
        k_old[r] = k
        d_old[r] = dj
        a_old[r] = aj
        if has_u:
            x_tan[r] = uc
            ct[c] = ct_j
        else:
            x_tan[r] = x0t
            Ft_j = 0.0
            ct[c] = aj
        if has_phi:
            x_tor[r] = pc
            cm[c] = cm_j
        else:
            x_tor[r] = x0r
            M_j = 0.0
            cm[c] = aj
        Ft[c] = Ft_j
        M[c] = M_j
        dW[c] = e
        # checked in registers (read back from the outputs: the pass measured 5-7 %
        # slower at 10^6 contacts)
        if not (math.isfinite(e) and math.isfinite(Ft_j) and math.isfinite(M_j)):
            nonfinite += 1
    return nonfinite, grown


# the passes a block of :func:`_switch_step_pass` calls: the plain functions, or their serial
# compiled builds (set with the builds: ``law_kernel._kernels``)
_switch_one = _switch_pass
_spring_one = _spring_pass


def spring_pass(idx, d, a, u, phi, kc, n: float, beta, mu, E, G, Gt, pool,
                out: tuple, parallel: bool = False, flag=None, regrid=None,
                stale: tuple | None = None) -> int:
    """Compiled MDR spring step of the contacts ``idx`` (``d``, ``a``, ``u``, ``phi``: depth,
    radius and controls of all contacts, or None; ``kc``, moduli: per contact; ``beta``: unit
    cell boundaries). The spring state (``pool``: the law's
    :class:`~contactlab.effects.law_pool.SpringPool`, rows ``pool.slot[idx]``) is updated in
    place; ``out = (Ft, ct, M, cm, dW)`` (the law's full arrays) are written at ``idx``.
    Contacts whose radius exceeds their cover are found in the pass (``flag``: int8 per
    contact, set to 4 there; scratch by default), given to ``regrid(contacts)`` (it grows
    their cover, at least to the radius) and then stepped: contacts are independent, so this
    is the step of regridding them first, without a pass over the covers before the kernel.
    ``stale``: per channel (tangential, torsion), zero every cell beyond the edge cell, not
    only those up to the last edge cell; None: the pool's
    :attr:`~contactlab.effects.law_pool.SpringPool.stale`, updated after the step (these
    are all the rows in use). Returns the number of contacts whose outputs are not finite.
    Flat punch (``n = inf``): ``kc = 0`` with any finite exponent."""
    nn = float(n) if n != np.inf else 1.0
    bG = beta ** (nn + 1.0) / (nn + 1.0)
    bH = beta ** (nn + 2.0) / (nn + 2.0)
    from .law_kernel import _EMPTY, _kernels
    P = pool.rows
    if flag is None:
        flag = np.zeros(pool.size, np.int8)
    kernel = _kernels(parallel)[2]
    update = stale is None
    if stale is None:
        stale = (pool.stale["tan"], pool.stale["tor"])

    def run(ix):
        return kernel(ix, pool.slot, d, a, _EMPTY if u is None else u,
                      _EMPTY if phi is None else phi, u is not None, phi is not None,
                      P["spr_cover"], kc, nn, beta, bG, bH, mu, E, G, Gt, P["spr_a"],
                      P["spr_k"], P["spr_depth"], P["spr_tan"], P["spr_tor"],
                      P["spr_x_tan"], P["spr_x_tor"], *out, flag, stale[0], stale[1])

    nf, grown = run(idx)
    if grown:
        g = idx[flag[idx] == 4]
        if regrid is None:
            raise ValueError(f"spring_pass: {g.size} contact(s) outgrew their cover and no "
                             "regrid was given")
        regrid(g)
        nf2, again = run(g)
        assert again == 0, "regrid left a contact's radius beyond its cover"
        nf += nf2
    if update:                      # every row stepped: a channel driven is clean, else stale
        pool.stale["tan"], pool.stale["tor"] = u is None, phi is None
    return int(nf)


def switch_pass(idx, a, flat, cover_factor, kc, n: float, beta, mu, E, G, Gt, chan: dict,
                st: dict, pool, parallel: bool = False) -> None:
    """Compiled switch of the contacts ``idx`` (int64, not on springs) from their Masing
    stacks (``chan``: the fields of :func:`~contactlab.physics.masing_stack.new_stack` over a
    leading channel axis) to their MDR springs: rows ``pool.used ...`` of the law's
    :class:`~contactlab.effects.law_pool.SpringPool` (room reserved by the caller), assigned and
    written in the kernel; ``st``: the law's state (``depth_ref``); ``a``: the contacts' radii
    in this step (the cover spans the larger of it and the held radius), ``cover_factor``:
    ``spring_cover`` per contact. No temporaries per contact."""
    is_flat = n == np.inf
    nn = float(n) if not is_flat else 1.0
    bG = beta ** (nn + 1.0) / (nn + 1.0)
    bH = beta ** (nn + 2.0) / (nn + 2.0)
    from .law_kernel import _kernels
    P = pool.rows
    _kernels(parallel)[3](idx, st["depth_ref"], a, flat, is_flat, cover_factor, kc, nn, beta,
                          bG, bH, mu, E, G, Gt, chan["X"], chan["depth"], chan["x"],
                          pool.slot, pool.owner, pool.used, P["spr_cover"], P["spr_a"],
                          P["spr_k"], P["spr_depth"], P["spr_tan"], P["spr_tor"],
                          P["spr_x_tan"], P["spr_x_tor"])
    pool.take(idx.size)


def switch_step_pass(idx, d, a, u, phi, flat, cover_factor, kc, n: float, beta, mu,
                     E, G, Gt, chan: dict, st: dict, pool, out: tuple, parallel: bool = False,
                     flag=None, regrid=None) -> int:
    """:func:`switch_pass` then :func:`spring_pass` of the contacts ``idx`` (int64, not on
    springs; rows ``pool.used ...`` reserved by the caller), one contact at a time in one
    (threaded) loop, the row in registers between the two (:func:`_first_pass`; the bits of
    the two passes, measured ~10 % faster than switching and stepping blocks of contacts,
    :func:`_switch_step_pass`, kept as the reference its tests compare with). Contacts whose
    radius exceeds their fresh cover are regridded and stepped after the loop
    (:func:`spring_pass`). Returns the number of contacts whose outputs are not finite."""
    from .law_kernel import _EMPTY, _kernels
    is_flat = n == np.inf
    nn = float(n) if not is_flat else 1.0
    bG = beta ** (nn + 1.0) / (nn + 1.0)
    bH = beta ** (nn + 2.0) / (nn + 2.0)
    P = pool.rows
    if flag is None:
        flag = np.zeros(pool.size, np.int8)
    nf, grown = _kernels(parallel)[6](
        idx, st["depth_ref"], a, flat, is_flat, cover_factor, kc, nn, beta, bG, bH,
        mu, E, G, Gt, chan["X"], chan["depth"], chan["x"], pool.slot, pool.owner, pool.used, d,
        _EMPTY if u is None else u, _EMPTY if phi is None else phi, u is not None,
        phi is not None, P["spr_cover"], P["spr_a"], P["spr_k"], P["spr_depth"], P["spr_tan"],
        P["spr_tor"], P["spr_x_tan"], P["spr_x_tor"], *out, flag, pool.clean)
    pool.take(idx.size)
    if grown:                       # stepped again: found (flag 4), regridded, stepped
        nf += spring_pass(idx[flag[idx] == 4], d, a, u, phi, kc, n, beta, mu, E, G, Gt, pool,
                          out, parallel, flag, regrid, (False, False))
    # the fresh rows are +0 beyond the switch's edge cell (no stale cells to zero); a channel
    # not driven keeps its elements beyond the new edge, so it is stale after the step (the
    # rows that were in use before are the spring pass's, which follows)
    if u is None:
        pool.stale["tan"] = True
    if phi is None:
        pool.stale["tor"] = True
    return int(nf)
