"""Force of a rigid tip on a viscoelastic half-space along an approach-retract history, by
Lee-Radok's and Ting's rules through the MDR, with exact parameter derivatives.

The half-space is incompressible with the shear relaxation function
``G(t) = G_∞ + Σ_k G_k exp(-t/τ_k)``, so ``E*(t) = 4G(t)``; ``Φ(δ)`` is the tip's force at unit
modulus and ``dΦ/dδ = 2a(δ)`` (:mod:`contactlab.fit._tip`). The indenter position ``z(t)`` is
linear between the samples; the indentation is ``δ = z - z0``.

* Approach (``z`` non-decreasing up to the last maximum at ``t_m``; the contact radius grows):
  ``F(t) = 4 ∫ G(t - s) dΦ(δ(s))``.
* Retract (Ting): the contact radius at ``t`` is the approach radius at ``t1 <= t_m`` where the
  edge element's force vanishes, ``D(t1) = ∫_{t1}^{t} G(t - s) ż(s) ds = 0``, and
  ``F(t) = 4 ∫_{t_c}^{t1} G(t - s) dΦ(δ(s))``. With ``C(s') = ∫^{s'} G(t - s) ż(s) ds`` (the
  convolution, increasing over the approach and falling after ``t_m``) ``t1`` is where ``C``
  comes back to its present value ``C(t)``; when ``C(t)`` falls below its value at the contact
  time ``t_c`` the tip has left the surface and ``F = 0``.

Per Prony term the hereditary integral ``H(t) = ∫ exp(-(t - s)/τ) dΦ`` obeys
``H_{j+1} = exp(-Δ_j/τ) H_j + q_j`` with ``q_j = Φ_{j+1} - e^{-Δ'/τ} Φ_lo - (1/τ) ∫ e^{-(s_{j+1}-s)/τ} Φ ds``
(integration by parts over the part of the step in contact; the integral by Gauss-Legendre on
the step, where ``Φ`` is smooth), and the derivatives ``∂H/∂τ`` and ``∂H/∂z0``
(``∂Φ/∂z0 = -2a``) obey the same recursion with their own sources. On the retract ``t1``
depends on the parameters through ``D = 0``; since ``∂F/∂t1 = 4G(t - t1)·2a(t1)·ż(t1)`` and
``∂D/∂t1 = -G(t - t1) ż(t1)``, the total derivative is
``dF/dθ = ∂F/∂θ|_{t1} + 8a(t1) ∂D/∂θ`` (``∂D/∂z0 = 0``: ``t1`` does not depend on the contact
point).

A flat punch (``Φ = 2bδ``, ``a = b`` from the first touch) needs nothing else: with ``Φ``
linear the retract force ``4∫_{t_c}^{t1} G dΦ = 8b(∫_{t_c}^{t} G ż ds - D(t1))`` is the
constant-radius hereditary integral, and leaving the surface is that force reaching zero.

After each call, ``contact`` holds the indentation whose (elastic) contact radius is the
present one, ``δ`` on the approach and ``δ(t1)`` on the retract (0 apart), and its derivatives
by ``G_∞``, ``G_k`` and ``τ_k`` (``dδ(t1)/dθ = (∂D/∂θ)/G(t - t1)``; 0 on the approach): an
adhesive force that depends on the contact radius only (DMT) follows from it.
"""
from __future__ import annotations

from typing import Any

import numpy as np

from ..errors import ParameterError

__all__ = ["TingModel", "GAUSS_NODES"]

#: Gauss-Legendre nodes per time step of the hereditary integrals
GAUSS_NODES = 6
#: largest decay exponent handled in one block of the vectorised recursion (e^600 < 1e261)
_BLOCK = 600.0
_NEWTON = 60
#: decay exponent beyond which a step forgets the past (e^-40 = 4e-18)
_FORGET = 40.0


def recur(decay: np.ndarray, u: np.ndarray) -> np.ndarray:
    """``y_0 = 0``, ``y_{j+1} = exp(-decay_j) y_j + u_j`` along the last axis, for ``u`` of
    shape ``(..., K, n)`` sharing the decays ``(K, n)``; vectorised by blocks of total decay
    <= 600 (no exponential overflows); returns ``n + 1`` values along the last axis."""
    K, n = decay.shape
    y = np.zeros((*u.shape[:-1], n + 1))
    # a step that decays by more than e^-40 (4e-18) forgets the past to rounding: clamped, so
    # a block of decay <= 600 always holds 15 steps or more
    decay = np.minimum(decay, _FORGET)
    C = np.zeros((K, n + 1))
    np.cumsum(decay, axis=1, out=C[:, 1:])
    for k in range(K):                      # a few Prony terms
        c = C[k]
        uk, yk = u[..., k, :], y[..., k, :]
        if c[-1] <= _BLOCK:                 # the common case: one block
            ec = np.exp(c[1:])
            yk[..., 1:] = np.cumsum(ec * uk, axis=-1) / ec
            continue
        b = 0
        while b < n:                        # blocks of decay <= 600
            e = int(np.searchsorted(c, c[b] + _BLOCK, side="right")) - 1
            if e <= b + 1:
                yk[..., b + 1] = np.exp(-decay[k, b]) * yk[..., b] + uk[..., b]
                b += 1
                continue
            ec = np.exp(c[b + 1:e + 1] - c[b])
            yk[..., b + 1:e + 1] = (yk[..., b:b + 1] + np.cumsum(ec * uk[..., b:e], axis=-1)) / ec
            b = e
    return y


class TingModel:
    """Viscoelastic force of an approach-retract history and its derivatives.

    Parameters
    ----------
    time, depth : ndarray
        Sample times (s, strictly increasing) and indenter positions (m): non-decreasing up to
        the last maximum, non-increasing after it.
    tip : TipModel
        ``Φ`` and ``2a`` of the profile.
    """

    def __init__(self, time: np.ndarray, depth: np.ndarray, tip: Any,
                 nodes: int = GAUSS_NODES) -> None:
        t, z = time, depth
        if np.any(np.diff(t) <= 0):
            i = int(np.argmax(np.diff(t) <= 0)) + 1
            raise ParameterError(f"time[{i}]={float(t[i])!r} s is invalid: time must increase "
                                 "strictly (give the samples in the order they were taken).")
        im = int(z.size - 1 - np.argmax(z[::-1]))       # the last maximum
        dz = np.diff(z)
        bad = np.flatnonzero(dz[:im] < 0)
        if bad.size:
            raise ParameterError(
                f"depth[{int(bad[0]) + 1}]={float(z[bad[0] + 1])!r} m is invalid: the approach "
                "(up to the largest depth) must not move back (Lee-Radok's rule needs a growing "
                "contact); smooth or drop the points.")
        bad = np.flatnonzero(dz[im:] > 0)
        if bad.size:
            raise ParameterError(
                f"depth[{int(bad[0]) + im + 1}]={float(z[bad[0] + im + 1])!r} m is invalid: "
                "the retract (after the largest depth) must not move forward again (Ting's rule "
                "covers one approach and one retract).")
        self.t, self.z, self.tip, self.im = t, z, tip, im
        self.dt = np.diff(t)
        self.v = dz / self.dt
        x, w = np.polynomial.legendre.leggauss(nodes)
        self._gx, self._gw = 0.5 * (x + 1.0), 0.5 * w

    # ------------------------------------------------------------------ helpers
    def _segment_nodes(self, lo: np.ndarray, hi: np.ndarray, j: np.ndarray, z0: float
                       ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """Gauss nodes on ``[lo, hi]`` inside step ``j``: times, weights, ``Φ`` and ``2a``.

        Within one step of the contact point (``δ(s_j) < δ(s_{j+1}) - δ(s_j)``, the step where
        contact begins included) the nodes follow ``s = lo + L u²``: ``a ~ sqrt(δ)`` of a
        rounded tip becomes smooth in ``u``, and the rule does not jump when the contact point
        crosses a sample."""
        first = (self.z[j] - z0 < self.z[j + 1] - self.z[j])[:, None]
        u, gw = self._gx, self._gw
        L = (hi - lo)[:, None]
        s = lo[:, None] + L * np.where(first, u * u, u)
        w = L * np.where(first, 2.0 * u * gw, gw)
        d = self.z[j][:, None] + self.v[j][:, None] * (s - self.t[j][:, None]) - z0
        phi, a2 = self.tip(d.ravel())
        return s, w, phi.reshape(s.shape), a2.reshape(s.shape)

    def _contact_start(self, j: np.ndarray, z0: float) -> tuple[np.ndarray, np.ndarray]:
        """Start of contact inside step ``j`` (the step's start once in contact) and whether
        the step's start is in contact."""
        zj = self.z[j]
        inside = zj >= z0
        with np.errstate(divide="ignore", invalid="ignore"):
            tc = self.t[j] + np.where(self.v[j] > 0, (z0 - zj) / self.v[j], 0.0)
        return np.where(inside, self.t[j], np.minimum(tc, self.t[j + 1])), inside

    # ------------------------------------------------------------------ evaluation
    def __call__(self, G_inf: float, Gk: np.ndarray, tk: np.ndarray, z0: float
                 ) -> tuple[np.ndarray, ...]:
        """Force (N) and ``∂F/∂G_∞``, ``∂F/∂G_k`` (K, n), ``∂F/∂τ_k`` (K, n), ``∂F/∂z0``."""
        t, z, im = self.t, self.z, self.im
        n = t.size
        K = Gk.size
        tau = tk[:, None]
        phi_n, a2_n = self.tip(z - z0)
        # ---- approach: the hereditary integrals H, ∂H/∂τ, ∂H/∂z0 at nodes 0..im
        F = np.zeros(n)
        dGi = np.zeros(n)
        dGk = np.zeros((K, n))
        dtk = np.zeros((K, n))
        dz0 = np.zeros(n)
        js = np.arange(im)
        if im > 0:
            lo, inside = self._contact_start(js, z0)
            hi = t[1:im + 1]
            s, w, ph, a2 = self._segment_nodes(lo, hi, js, z0)
            live = (z[1:im + 1] > z0)[:, None]
            w = np.where(live, w, 0.0)
            back = hi[:, None] - s                      # (nseg, m)
            E = np.exp(-back[None] / tau[..., None])    # (K, nseg, m)
            wE = w[None] * E
            I0 = np.einsum("ksm,sm->ks", wE, ph)
            I1 = np.einsum("ksm,sm->ks", wE, ph * back)
            Ia = np.einsum("ksm,sm->ks", wE, a2)
            phi_lo = np.where(inside, phi_n[js], 0.0)
            a2_lo = np.where(inside, a2_n[js], 0.0)
            blo = hi - lo
            rlo = np.exp(-blo / tau)
            dec = self.dt[None, :im] / tau
            r = np.exp(-dec)
            q = phi_n[1:im + 1] - rlo * phi_lo - I0 / tau
            q_t = -rlo * blo / tau ** 2 * phi_lo + I0 / tau ** 2 - I1 / tau ** 3
            q_z = -a2_n[1:im + 1] + rlo * a2_lo + Ia / tau
            H, H_z = recur(dec, np.stack([q, q_z]))
            H_t = recur(dec, r * self.dt[:im] / tau ** 2 * H[:, :-1] + q_t)
        else:
            H = H_t = H_z = np.zeros((K, 1))
        a = slice(0, im + 1)
        F[a] = 4.0 * (G_inf * phi_n[a] + Gk @ H)
        dGi[a] = 4.0 * phi_n[a]
        dGk[:, a] = 4.0 * H
        dtk[:, a] = 4.0 * Gk[:, None] * H_t
        dz0[a] = 4.0 * (-G_inf * a2_n[a] + Gk @ H_z)
        # the indentation whose contact radius is the present one (0 apart) and its
        # derivatives by G_∞, G_k, τ_k (the retract's t1 moves with them; ∂/∂z0 is -1)
        c_d = np.zeros(n)
        c_Gi = np.zeros(n)
        c_Gk = np.zeros((K, n))
        c_tk = np.zeros((K, n))
        c_d[a] = np.maximum(z[a] - z0, 0.0)
        self.contact = (c_d, c_Gi, c_Gk, c_tk)
        if im == n - 1:
            return F, dGi, dGk, dtk, dz0
        # ---- retract: t1 from Ting's condition, then the force up to t1
        dec_all = self.dt[None, :] / tau
        r_all = np.exp(-dec_all)
        omr = -np.expm1(-dec_all)
        vt = self.v[None, :] * tau
        h = recur(dec_all, vt * omr)            # ∫ e^{-(t-s)/τ} ż ds from the first sample
        h_t = recur(dec_all, r_all * self.dt / tau ** 2 * (h[:, :-1] - vt) + self.v * omr)
        # C(t_i, s_j) = G_∞(z_j - z_0) + Σ_k e^{-(t_i - t_m)/τ} A_kj at approach nodes j
        A = np.exp(-(t[im] - t[:im + 1]) / tau) * h[:, :im + 1]
        zrel = z[:im + 1] - z[0]
        ri = np.arange(im + 1, n)
        ti = t[ri]
        target = G_inf * (z[ri] - z[0]) + Gk @ h[:, ri]

        GW = Gk[:, None] * np.exp(-(ti - t[im])[None] / tau)     # (K, n_retract)

        def conv(j: np.ndarray) -> np.ndarray:         # C(t_i, s_j) at approach nodes j
            return G_inf * zrel[j] + np.einsum("ki,ki->i", GW, A[:, j])

        below = conv(np.zeros(ri.size, dtype=int)) <= target
        lo_i = np.zeros(ri.size, dtype=int)
        hi_i = np.full(ri.size, im)             # C(t_i, t_m) > target (the retract moved)
        for _ in range(int(np.ceil(np.log2(max(im, 1)))) + 1):     # bisection, vectorised
            mid = (lo_i + hi_i) // 2
            ok = conv(mid) <= target
            lo_i = np.where(ok, mid, lo_i)
            hi_i = np.where(ok, hi_i, mid)
            if np.all(hi_i - lo_i <= 1):
                break
        j = np.minimum(lo_i, im - 1)
        sj, vj, zj = t[j], self.v[j], z[j]
        ej = np.exp(-(ti - sj)[None] / tau)
        base = G_inf * (zj - z[0]) + Gk @ (ej * h[:, j])
        s1 = t[j + 1].copy()                    # Newton from the right: C is convex, increasing
        act = np.flatnonzero(below)             # the points still in contact
        last = False
        for _ in range(_NEWTON):
            sa, ea, ta = s1[act], ej[:, act], ti[act]
            e1 = np.exp(-(ta - sa)[None] / tau)
            va = vj[act]
            val = (base[act] + G_inf * va * (sa - sj[act]) + Gk @ (va * tk[:, None] * (e1 - ea))
                   - target[act])
            der = va * (G_inf + Gk @ e1)
            new = np.minimum(np.maximum(sa - val / np.where(der > 0, der, np.inf), sj[act]),
                             t[j[act] + 1])
            moved = np.abs(new - sa) > 1e-13 * (t[-1] - t[0])
            s1[act] = new
            if last:
                break
            act = act[moved]
            last = act.size == 0
        d1 = zj + vj * (s1 - sj) - z0
        on = below & (d1 > 0)
        phi1, a21 = self.tip(np.where(on, d1, 0.0))
        lo, inside = self._contact_start(j, z0)
        lo = np.minimum(np.where(on, lo, s1), s1)
        s, w, ph, a2 = self._segment_nodes(lo, s1, j, z0)
        back = ti[:, None] - s
        E = np.exp(-back[None] / tau[..., None])
        wE = w[None] * E
        J0 = np.einsum("kim,im->ki", wE, ph)
        J1 = np.einsum("kim,im->ki", wE, ph * back)
        Ja = np.einsum("kim,im->ki", wE, a2)
        phi_lo = np.where(inside, phi_n[j], 0.0)
        a2_lo = np.where(inside, a2_n[j], 0.0)
        e1 = np.exp(-(ti - s1)[None] / tau)
        elo = np.exp(-(ti - lo)[None] / tau)
        P = e1 * phi1 - elo * phi_lo - J0 / tau
        P_t = ((ti - s1) * e1 * phi1 - (ti - lo) * elo * phi_lo) / tau ** 2 + J0 / tau ** 2 \
            - J1 / tau ** 3
        P_z = -e1 * a21 + elo * a2_lo + Ja / tau
        X = ej * H[:, j] + P
        X_t = (ti - sj) / tau ** 2 * ej * H[:, j] + ej * H_t[:, j] + P_t
        X_z = ej * H_z[:, j] + P_z
        # ∂D/∂θ (Ting's condition): D = ∫_{t1}^{t} G(t - s) ż ds
        Y = h[:, ri] - ej * h[:, j] - vj * tk[:, None] * (e1 - ej)
        Y_t = h_t[:, ri] - ((ti - sj) / tau ** 2 * ej * h[:, j] + ej * h_t[:, j]
                            + vj * (e1 - ej) + vj / tau * ((ti - s1) * e1 - (ti - sj) * ej))
        corr = 4.0 * a21                                  # 8a(t1)
        m = np.where(on, 1.0, 0.0)
        F[ri] = m * 4.0 * (G_inf * phi1 + Gk @ X)
        dGi[ri] = m * (4.0 * phi1 + corr * (z[ri] - (zj + vj * (s1 - sj))))
        dGk[:, ri] = m * (4.0 * X + corr * Y)
        dtk[:, ri] = m * Gk[:, None] * (4.0 * X_t + corr * Y_t)
        dz0[ri] = m * 4.0 * (-G_inf * a21 + Gk @ X_z)
        # δ(t1) = z(t1) - z0: dδ1/dθ = ż(t1) dt1/dθ = (∂D/∂θ)/G(t - t1)
        g_t1 = G_inf + Gk @ e1
        c_d[ri] = np.where(on, d1, 0.0)
        c_Gi[ri] = m * (z[ri] - (zj + vj * (s1 - sj))) / g_t1
        c_Gk[:, ri] = m * Y / g_t1
        c_tk[:, ri] = m * Gk[:, None] * Y_t / g_t1
        return F, dGi, dGk, dtk, dz0
