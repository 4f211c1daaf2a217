"""Closed-form tangential contact (Cattaneo–Mindlin through the MDR) and shift histories.

:func:`tangential` gives the state for one monotonic shift at constant normal load;
:func:`shift_history` follows an arbitrary displacement history at constant normal load with the
Masing rule and turning-point memory (exact for the MDR Jenkins elements and for the 3D theory).
Both are used through :meth:`Contact.tangential` and :meth:`Contact.shift_history`.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

from .errors import NotSupportedError, ParameterError
from .numeric.roots import bracketed_root
from .params import as_float_array
from .physics import tangential as _tan

__all__ = ["TangentialState", "ShiftHistory", "tangential", "shift_history"]


def _out(v: np.ndarray) -> Any:
    v = np.asarray(v, float)
    return float(v) if v.ndim == 0 else v


def _one(name_values: dict[str, Any], what: str) -> tuple[str, Any]:
    given = {k: v for k, v in name_values.items() if v is not None}
    if len(given) != 1:
        raise ParameterError(f"{what} needs exactly one of {', '.join(k + '=' for k in name_values)}"
                             f" got {sorted(given) or 'none'}.")
    return next(iter(given.items()))


@dataclass(frozen=True, eq=False)
class TangentialState:
    """Cattaneo–Mindlin state (one load or an array of loads) at constant normal load.

    Attributes
    ----------
    normal : NormalState
        The normal state the shift acts on.
    displacement : float or ndarray
        Tangential displacement of the indenter ``u``, m (signed).
    tangential_force : float or ndarray
        Tangential force ``F_x``, N (same sign as ``u``).
    stick_radius : float or ndarray
        Radius ``c`` of the stick zone, m (``a`` without slip, 0 at full sliding).
    gross_sliding : bool or ndarray
        True where the force reached ``μF_N`` (the displacement reported is the smallest one
        that reaches it).
    """

    contact: Any = field(repr=False)
    normal: Any = field(repr=False)
    _u: np.ndarray = field(repr=False)
    _F: np.ndarray = field(repr=False)
    _c: np.ndarray = field(repr=False)
    _sliding: np.ndarray = field(repr=False)
    meta: dict = field(default_factory=dict, repr=False)

    @property
    def displacement(self) -> Any:
        return _out(self._u)

    @property
    def tangential_force(self) -> Any:
        return _out(self._F)

    @property
    def stick_radius(self) -> Any:
        return _out(self._c)

    @property
    def gross_sliding(self) -> Any:
        s = np.asarray(self._sliding, bool)
        return bool(s) if s.ndim == 0 else s

    @property
    def stiffness(self) -> Any:
        """Incremental tangential stiffness ``dF_x/du = 2G*c``, N/m."""
        return _out(2.0 * self.contact.moduli.tangential * self._c)

    def shear(self, r: Any) -> Any:
        """Tangential traction ``τ_x(r)``, Pa (sign of the displacement), shape ``state + r``."""
        r = as_float_array("r", r)
        if np.any(r < 0):
            raise ParameterError(f"r contains {r[r < 0].ravel()[0]!r}: radii must be >= 0 m.")
        sh = np.shape(self._c)
        ex = (1,) * r.ndim
        a = np.asarray(self.normal._radius, float).reshape(sh + ex)
        d = np.asarray(self.normal._depth, float).reshape(sh + ex)
        c = np.asarray(self._c, float).reshape(sh + ex)
        sign = np.sign(np.asarray(self._u, float)).reshape(sh + ex)
        c_ = self.contact
        mu = np.inf if c_.friction is None else c_.friction
        if not np.isfinite(mu):
            raise NotSupportedError("shear() needs a friction coefficient: without friction the "
                                    "no-slip traction is that of a rigidly shifted punch.")
        tau = _tan.shear(c_.profile, c_.moduli.normal, mu, r, a, d, c, c_.rtol)
        return _out(sign * tau)


def tangential(contact, *, depth: Any = None, force: Any = None, radius: Any = None,
               displacement: Any = None, tangential_force: Any = None,
               stick_radius: Any = None) -> TangentialState:
    """Cattaneo–Mindlin state; see :meth:`contactlab.Contact.tangential`."""
    if contact.is_adhesive:
        raise NotSupportedError("tangential() is implemented for non-adhesive contacts only "
                                "(work_of_adhesion=None).")
    nkey, nval = _one({"depth": depth, "force": force, "radius": radius}, "tangential()")
    tkey, tval = _one({"displacement": displacement, "tangential_force": tangential_force,
                       "stick_radius": stick_radius}, "tangential()")
    ns = contact.normal(**{nkey: nval})
    tv = as_float_array(tkey, tval)
    a0, d0, F0 = (np.asarray(v, float) for v in (ns._radius, ns._depth, ns._force))
    a, d, FN, t = np.broadcast_arrays(a0, d0, F0, tv)
    if ns.shape != a.shape:
        ns = contact.normal(depth=d.copy())
    prof = contact.profile
    E, Gs = contact.moduli.normal, contact.moduli.tangential
    mu = contact.friction
    sign = np.sign(t)
    if mu is None:  # no slip (μ → ∞): rigid shift of the whole contact
        if tkey == "stick_radius":
            raise NotSupportedError("stick_radius= needs friction: without friction the stick "
                                    "radius is always the contact radius.")
        k = 2.0 * Gs * a
        if tkey == "displacement":
            u = t.copy()
        else:
            u = np.where(k > 0, t / np.where(k > 0, k, 1.0), 0.0)
            if np.any((k == 0) & (t != 0)):
                raise ParameterError("tangential_force != 0 is invalid without contact (force 0).")
        return TangentialState(contact, ns, u, k * u, a.copy(), np.zeros(a.shape, bool),
                               {"control": tkey, "method": "no-slip"})
    sliding = np.zeros(a.shape, bool)
    if tkey == "displacement":
        ustar = _tan.full_slip_displacement(E, Gs, mu, d)
        sliding = np.abs(t) >= ustar
        c = _tan.stick_radius_of_displacement(prof, E, Gs, mu, a, d, t)
        u = t.copy()
    elif tkey == "stick_radius":
        if np.any((t < 0) | (t > a)):
            bad = t[(t < 0) | (t > a)].ravel()[0]
            raise ParameterError(f"stick_radius={bad!r} m is invalid: it must satisfy "
                                 "0 <= stick_radius <= contact radius.")
        c = t.copy()
        u = _tan.displacement_of_stick_radius(prof, E, Gs, mu, d, c)
        sign = np.ones(a.shape)
        sliding = c == 0
    else:
        T = np.abs(t)
        sliding = T >= mu * FN
        ustar = _tan.full_slip_displacement(E, Gs, mu, d)
        u = np.where(sliding, ustar, 0.0)
        inner = ~sliding & (T > 0)
        if np.any(inner):
            ai, di = a[inner], d[inner]
            u[inner] = bracketed_root(
                lambda x, idx: _tan.force_of_displacement(prof, E, Gs, mu, ai[idx], di[idx], x)[0],
                T[inner], 0.0, ustar[inner], rtol=1e-14, what="tangential displacement")
        u = sign * u
    if tkey == "stick_radius":
        F = sign * _tan.force_of_stick_radius(prof, E, mu, a, d, c)
    else:
        Fm, c = _tan.force_of_displacement(prof, E, Gs, mu, a, d, u)
        F = np.sign(u) * Fm
    F = np.where(a > 0, F, 0.0)
    if tkey == "tangential_force":
        F = np.where(sliding, sign * mu * FN, F)
    return TangentialState(contact, ns, u, F, c, sliding,
                           {"control": tkey, "method": "cattaneo-mindlin", "rtol": contact.rtol})


@dataclass(frozen=True, eq=False)
class ShiftHistory:
    """Result of :meth:`Contact.shift_history`: per-step arrays at constant normal load.

    Attributes
    ----------
    displacement, tangential_force, stick_radius, dissipated_energy : ndarray
        Displacement (m), tangential force (N), stick radius of the active branch (m) and
        cumulative dissipated energy (J) per step.
    normal : NormalState
    """

    normal: Any = field(repr=False)
    displacement: np.ndarray
    tangential_force: np.ndarray
    stick_radius: np.ndarray
    dissipated_energy: np.ndarray
    meta: dict = field(default_factory=dict, repr=False)


def _masing_program(u: np.ndarray):
    """Walk a displacement history with turning-point memory (Masing rule, Iwan erasure).

    Returns ``branch`` (per step: index into ``branches`` or -1 for the virgin curve),
    ``branches`` (list of ``(origin_u, direction, created_at_step)``) and the dissipation pieces
    ``(step, branch, delta_from, delta_to)``.
    """
    stack: list[int] = []  # branch ids, innermost last
    branches: list[tuple[float, float, int]] = []
    branch = np.full(u.size, -1, dtype=int)
    pieces: list[tuple[int, int, float, float]] = []
    cur = 0.0
    for i, un in enumerate(u):
        du = un - cur
        if du != 0:
            step_dir = 1.0 if du > 0 else -1.0
            s = branches[stack[-1]][1] if stack else (np.sign(cur) if cur != 0 else step_dir)
            if step_dir != s:  # reversal at the current point
                branches.append((cur, step_dir, i))
                stack.append(len(branches) - 1)
                s = step_dir
            pos = cur
            while stack:
                o = branches[stack[-1]][0]
                target = branches[stack[-2]][0] if len(stack) >= 2 else -branches[stack[0]][0]
                if (un - target) * s > 0:  # loop closes at target: erase its memory
                    pieces.append((i, stack[-1], abs(pos - o), abs(target - o)))
                    pos = target
                    del stack[-2 if len(stack) >= 2 else -1:]
                    continue
                pieces.append((i, stack[-1], abs(pos - o), abs(un - o)))
                break
            else:
                pieces.append((i, -1, abs(pos), abs(un)))
            cur = un
        branch[i] = stack[-1] if stack else -1
    return branch, branches, pieces


def shift_history(contact, *, displacement: Any, depth: Any = None,
                  force: Any = None) -> ShiftHistory:
    """Exact tangential response to a displacement history at constant normal load.

    See :meth:`contactlab.Contact.shift_history`.
    """
    if contact.friction is None:
        raise NotSupportedError("shift_history() needs friction: without it the response is "
                                "linear, F_x = 2G*a u (use tangential()).")
    nkey, nval = _one({"depth": depth, "force": force}, "shift_history()")
    ns = contact.normal(**{nkey: nval})
    if ns.shape != ():
        raise ParameterError(f"{nkey} must be a scalar for shift_history() (constant normal load).")
    u = as_float_array("displacement", displacement).ravel()
    prof, E, Gs, mu = (contact.profile, contact.moduli.normal, contact.moduli.tangential,
                       contact.friction)
    a, d = float(ns._radius), float(ns._depth)
    branch, branches, pieces = _masing_program(u)

    def F_load(delta):
        return _tan.force_of_displacement(prof, E, Gs, mu, a, d, np.asarray(delta, float))

    n = u.size
    origin = np.array([b[0] for b in branches] + [0.0])[branch]
    virgin = branch < 0
    delta = np.where(virgin, np.abs(u), np.abs(u - origin) / 2.0)
    Fl, c_out = F_load(delta)
    F = np.where(virgin, np.sign(u) * Fl, 0.0)
    # a branch starts at the force of the step before its creation; resolve in step order
    F_origin = np.zeros(len(branches))
    done = np.zeros(len(branches), bool)
    for i in np.flatnonzero(~virgin):
        b = branch[i]
        if not done[b]:
            k = branches[b][2]
            F_origin[b] = F[k - 1] if k > 0 else 0.0
            done[b] = True
        F[i] = F_origin[b] + branches[b][1] * 2.0 * Fl[i]
    W = np.zeros(n)
    if pieces:
        st, br, d0, d1 = (np.array(v) for v in zip(*pieces))
        vir = br < 0

        def D(x: np.ndarray) -> np.ndarray:
            return _tan.virgin_dissipation(prof, E, Gs, mu, a, d, x, contact.rtol)

        inc = np.where(vir, D(d1) - D(d0), 2.0 * (D(d1 / 2) - D(d0 / 2)))
        np.add.at(W, st, inc)
    return ShiftHistory(ns, u.copy(), F, c_out, np.cumsum(W),
                        {"method": "masing", "rtol": contact.rtol})
