"""Subsurface stresses along load histories at constant normal load and a fretting-fatigue
indicator over a fretting loop: the drivers behind ``ShiftHistory.stress``,
``TwistHistory.stress``, ``FrettingLoop.stress`` and ``FrettingLoop.fatigue``.

Masing's rule holds for the tractions as it does for the forces (Mindlin & Deresiewicz 1953): at
step ``k`` on a branch that left the turning point ``o`` with factor ``f`` (1 on the virgin
curve, 2 after a reversal), ``τ_k = τ_o + sign(u_k - u_o) f τ_v(|u_k - u_o|/f)`` with ``τ_v``
the virgin traction. The half-space is linear, so the field is the same chain of virgin fields
(each the field of a monotonic state, :mod:`contactlab.effects.stress_tangential` or the
torsion field), over the active turning points of :func:`contactlab.physics.masing.masing_program`.
"""
from __future__ import annotations

import warnings
from dataclasses import dataclass, field
from typing import Any, ClassVar

import numpy as np

from ..citations import Cited
from ..errors import NotSupportedError, ParameterError, ValidityWarning
from ..physics import fatigue as _fat
from ..physics.masing import masing_program
from ._protocol import Result
from ..params import check_memory
from ..physics import stress as _st
from .stress import (CHUNK_POINT_BYTES, StressField, body_poisson_ratio, normal_stress,
                     torsion_stress)
from .stress_tangential import (TANGENTIAL_SOURCES, CartesianStressField, _angles, _wrap, _xyz,
                                tangential_stress, to_cartesian)

__all__ = ["FrettingFatigue", "fretting_fatigue", "history_stress", "loop_stress",
           "masing_terms"]

_CART = ("sxx", "syy", "szz", "sxy", "sxz", "syz")


def masing_terms(u: np.ndarray, step: int) -> list[tuple[float, float]]:
    """``[(weight, argument), ...]`` of the virgin states whose sum is the state at ``step``
    (Masing's rule with turning-point memory): ``weight = ±factor``, ``argument >= 0``."""
    origin, factor, arg, _ = masing_program(u)
    out = []
    j = step
    while j >= 0:
        o = int(origin[j])
        uo = float(u[o]) if o >= 0 else 0.0
        s = float(np.sign(u[j] - uo))
        if s != 0.0 and arg[j] > 0:
            out.append((s * float(factor[j]), float(arg[j])))
        j = o
    return out


def _step(step: Any, n: int) -> int:
    if isinstance(step, bool) or not isinstance(step, (int, np.integer)) or not -n <= step < n:
        raise ParameterError(f"step={step!r} is invalid: give an integer step index in "
                             f"[{-n}, {n - 1}] of this history.")
    return int(step) % n


def _quiet(fn, *args, **kwargs):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ValidityWarning)
        return fn(*args, **kwargs)


def _virgin_cart(contact, mode: str, method: str, depth: float, arg: float, x, y, z,
                 body: int) -> tuple[list[np.ndarray], np.ndarray]:
    """Cartesian friction field of the virgin (monotonic, positive) state at ``arg``."""
    if mode == "tangential":
        st = _quiet(contact.tangential, depth=depth, displacement=arg)
        f = tangential_stress(st, x, y, z, body, "friction")
        return [np.asarray(getattr(f, k)) for k in _CART], np.asarray(f.error)
    ts = _quiet(contact.torsion, depth=depth, twist=arg, method=method)
    tf = torsion_stress(ts, np.hypot(x, y), z, body, "friction")
    return list(to_cartesian(tf, x, y)), np.asarray(tf.error)


def _cartesian_sum(contact, mode, method, normal, terms, x, y, z, body, part, meta):
    nu = body_poisson_ratio(contact, body)
    x, y, z = _xyz(x, y, z)
    comps = [np.zeros(x.shape) for _ in _CART]
    err = np.zeros(x.shape)
    depth = float(normal._depth)
    for w, arg in terms:
        c, e = _virgin_cart(contact, mode, method, depth, arg, x, y, z, body)
        comps = [u + w * v for u, v in zip(comps, c)]
        err = err + abs(w) * e
    route = f"{mode}: Masing sum of {len(terms)} virgin field(s)"
    if part == "total":
        rho, _, _ = _angles(x, y)
        nf = normal_stress(normal, rho, z, body)
        comps = [u + v for u, v in zip(to_cartesian(nf, x, y), comps)]
        err = err + nf.error
        route = f"{nf.meta['route']} + {route}"
    src = TANGENTIAL_SOURCES if mode == "tangential" else ("Sn65", "J85", "RS44")
    return _wrap(x, y, z, comps, err, {"route": route, "body": body, "nu": nu, "part": part,
                                       "citations": (*src, "MD53"), **meta})


def _part(part: str) -> None:
    if part not in ("total", "friction"):
        raise ParameterError(f"part={part!r} is invalid: choose 'total' (normal preload "
                             "included) or 'friction' (the frictional part alone).")


def history_stress(history, a: Any, b: Any, c: Any = None, *, step: Any, body: Any = 1,
                   part: str = "total") -> Any:
    """Field at one step of a shift history (``(x, y, z)``: a
    :class:`~contactlab.effects.stress_tangential.CartesianStressField`) or of a twist history
    (``(r, z)``: a :class:`~contactlab.effects.stress.StressField`)."""
    _part(part)
    shift = hasattr(history, "displacement")
    u = np.asarray(history.displacement if shift else history.twist, float)
    k = _step(step, u.size)
    normal = history.normal
    contact = normal.contact
    body_poisson_ratio(contact, body)
    terms = masing_terms(u, k)
    meta = {"step": k}
    if shift:
        if c is None:
            raise ParameterError("ShiftHistory.stress() takes points (x, y, z).")
        return _cartesian_sum(contact, "tangential", "mdr", normal, terms, a, b, c, body, part,
                              meta)
    if c is not None:
        raise ParameterError("TwistHistory.stress() takes points (r, z), as TorsionState.stress.")
    nu = body_poisson_ratio(contact, body)
    base: StressField = normal_stress(normal, a, b, body)
    if part != "total":
        base = StressField(base.r, base.z, *(np.zeros(base.shape),) * 6, np.zeros(base.shape),
                           dict(base.meta))
    stz = np.zeros(base.shape)
    srt = np.zeros(base.shape)
    err = np.array(base.error)
    depth = float(normal._depth)
    for w, arg in terms:
        st = _quiet(contact.torsion, depth=depth, twist=arg, method=history.method)
        f = torsion_stress(st, base.r, base.z, body, "friction")
        stz, srt, err = stz + w * f.stz, srt + w * f.srt, err + abs(w) * f.error
    fin = np.isfinite(stz) & np.isfinite(srt)
    comps = np.abs(np.stack([base.srr, base.stt, base.szz, base.srz, stz, srt]))
    top = np.max(comps[:, fin], initial=0.0)
    rel = float(np.max(err[fin], initial=0.0) / top) if top > 0 else 0.0
    return StressField(base.r, base.z, base.srr, base.stt, base.szz, base.srz, stz, srt,
                       np.where(fin, err, np.inf),
                       {"route": f"torsion: Masing sum of {len(terms)} virgin field(s)",
                        "body": body, "nu": nu, "part": part, "step": k, "error_estimate": rel,
                        "citations": ("Sn65", "J85", "RS44", "MD53")})


def _loop_terms(amp: float, phase: float) -> tuple[float, list[tuple[float, float]]]:
    u = amp * np.cos(2.0 * np.pi * phase)
    if phase <= 0.5:          # from +amp down to -amp
        return u, [(1.0, amp), (-2.0, 0.5 * (amp - u))]
    return u, [(-1.0, amp), (2.0, 0.5 * (u + amp))]


def _phase(phase: Any) -> float:
    try:
        p = float(phase)
    except (TypeError, ValueError) as err:
        raise ParameterError(f"phase={phase!r} is invalid: give a number in [0, 1].") from err
    if not 0.0 <= p <= 1.0 or isinstance(phase, bool):
        raise ParameterError(f"phase={phase!r} is invalid: the phase of the cycle must lie in "
                             "[0, 1] (0 and 1: the tip at +amplitude, 0.5: at -amplitude).")
    return p


def loop_stress(loop, x: Any, y: Any, z: Any, *, phase: Any, body: Any = 1,
                part: str = "total") -> CartesianStressField:
    """Field at ``phase`` of the steady fretting loop (``u = amplitude cos 2π phase``; the
    descending branch for ``phase <= 0.5``), Cartesian at ``(x, y, z)`` for both modes."""
    _part(part)
    p = _phase(phase)
    u, terms = _loop_terms(float(loop.amplitude), p)
    contact = loop.normal.contact
    if not np.isfinite(loop.amplitude):
        raise NotSupportedError("stress() of a loop needs a finite amplitude.")
    return _cartesian_sum(contact, loop.mode, loop.method, loop.normal, terms, x, y, z, body,
                          part, {"phase": p, "control": u})


# ====================================================================== fatigue indicator
@dataclass(frozen=True, eq=False)
class FrettingFatigue(Result, Cited):
    """Fretting-fatigue indicators of a steady fretting loop at the surface of one body.

    Attributes
    ----------
    edge_stress : float
        Largest tensile (maximum principal) stress at the contact edge over the cycle, Pa.
    edge_stress_range : float
        Range over the cycle of the normal stress on the plane of that maximum, Pa.
    edge_normal : ndarray
        That plane's unit normal ``(3,)``.
    swt : float
        Largest Smith–Watson–Topper parameter ``max_t σ_n · Δε_n/2`` over the points and plane
        normals, Pa (see :mod:`contactlab.physics.fatigue`).
    swt_location, swt_normal : ndarray
        Its point ``(x, y, z)`` (m) and critical plane normal.
    findley, findley_location, findley_normal, findley_at_point
        Findley's parameter ``max_n [τ_a + k max_t σ_n]`` (Pa), its point, plane and value per
        point, when ``findley_k`` was given (else ``None`` and empty arrays).
    phase, control : ndarray
        The instants of the cycle (phase in [0, 1)) and the displacement (m) or twist (rad).
    x, y, z, swt_at_point : ndarray
        The surface points searched and the SWT parameter at each, Pa.
    meta : dict
        ``body``, ``E``, ``nu``, ``mode``, ``citations``.
    """

    edge_stress: float
    edge_stress_range: float
    edge_normal: np.ndarray = field(repr=False)
    swt: float = 0.0
    swt_location: np.ndarray = field(default_factory=lambda: np.zeros(3), repr=False)
    swt_normal: np.ndarray = field(default_factory=lambda: np.zeros(3), repr=False)
    phase: np.ndarray = field(default_factory=lambda: np.zeros(0), repr=False)
    control: np.ndarray = field(default_factory=lambda: np.zeros(0), repr=False)
    x: np.ndarray = field(default_factory=lambda: np.zeros(0), repr=False)
    y: np.ndarray = field(default_factory=lambda: np.zeros(0), repr=False)
    z: np.ndarray = field(default_factory=lambda: np.zeros(0), repr=False)
    swt_at_point: np.ndarray = field(default_factory=lambda: np.zeros(0), repr=False)
    meta: dict = field(default_factory=dict, repr=False)
    findley: float | None = None
    findley_location: np.ndarray = field(default_factory=lambda: np.zeros(0), repr=False)
    findley_normal: np.ndarray = field(default_factory=lambda: np.zeros(0), repr=False)
    findley_at_point: np.ndarray = field(default_factory=lambda: np.zeros(0), repr=False)

    units: ClassVar[dict[str, str]] = {"x": "m", "y": "m", "z": "m", "swt": "Pa",
                                       "findley": "Pa"}

    def to_dict(self) -> dict[str, Any]:
        """The indicators (``edge_stress``, ``edge_stress_range`` and ``swt`` in Pa, locations
        in m). The model error is 0.0 (exact fields of the loop's tractions)."""
        out = {"edge_stress": self.edge_stress, "edge_stress_range": self.edge_stress_range,
               "edge_normal": self.edge_normal, "swt": self.swt,
               "swt_location": self.swt_location, "swt_normal": self.swt_normal}
        if self.findley is not None:
            out.update(findley=self.findley, findley_location=self.findley_location,
                       findley_normal=self.findley_normal)
        return out

    def _columns(self) -> dict[str, Any]:
        out = {"x": self.x, "y": self.y, "z": self.z, "swt": self.swt_at_point}
        if self.findley is not None:
            out["findley"] = self.findley_at_point
        return out


#: instants per cycle of :func:`fretting_fatigue` and surface points along the x axis
FATIGUE_PHASES = 24
FATIGUE_POINTS = 49


#: peak bytes per point and phase of :func:`fretting_fatigue` (the normal and shear stresses on
#: every plane normal of :func:`contactlab.physics.fatigue.plane_normals`; tracemalloc with
#: Findley's parameter: 167-171 kB)
FATIGUE_POINT_PHASE_BYTES = 192 * 1024


def fretting_fatigue(loop, body: Any = 1, n_phases: int = FATIGUE_PHASES,
                     points: Any = None, findley_k: Any = None) -> FrettingFatigue:
    """Implementation of ``FrettingLoop.fatigue``: edge tensile stress, its range, the SWT
    parameter and (with ``findley_k``) Findley's over ``n_phases`` instants of the steady loop,
    at surface points along the ``x`` axis (``FATIGUE_POINTS`` over ``[-1.2a, 1.2a]`` plus the
    edges) or at ``points=(x, y, z)``."""
    if findley_k is not None:
        try:
            fk = float(findley_k)
        except (TypeError, ValueError) as err:
            raise ParameterError(f"findley_k={findley_k!r} is invalid: give a number >= 0.") \
                from err
        if isinstance(findley_k, bool) or not np.isfinite(fk) or fk < 0:
            raise ParameterError(f"findley_k={findley_k!r} is invalid: Findley's normal-stress "
                                 "sensitivity k must be a finite number >= 0.")
    nu = body_poisson_ratio(loop.normal.contact, body)
    E = getattr(loop.normal.contact.materials[body - 1], "E", None)
    if E is None:
        raise NotSupportedError(f"body={body} has no Young's modulus: SWT needs an elastic body.")
    if isinstance(n_phases, bool) or not isinstance(n_phases, (int, np.integer)) or n_phases < 2:
        raise ParameterError(f"n_phases={n_phases!r} is invalid: give an integer >= 2.")
    a = float(loop.radius)
    if a <= 0:
        raise ParameterError("fatigue() needs a contact (radius > 0).")
    edges = np.array([a, -a])
    if points is None:
        px: Any = np.linspace(-1.2 * a, 1.2 * a, FATIGUE_POINTS)
        py: Any = 0.0
        pz: Any = 0.0
    else:
        try:
            px, py, pz = points
        except (TypeError, ValueError) as err:
            raise ParameterError("points= must be (x, y, z) arrays.") from err
    gx, gy, gz = (np.ravel(v) for v in _xyz(px, py, pz))
    n_pts = float(gx.size + 2)
    check_memory("fatigue()", FATIGUE_POINT_PHASE_BYTES * n_pts * float(n_phases)
                 + CHUNK_POINT_BYTES * min(n_pts, float(_st.CHUNK)),
                 f"n_phases={n_phases} x {n_pts:.0f} points x {FATIGUE_POINT_PHASE_BYTES} bytes"
                 " (stresses on every plane normal)")
    X = np.concatenate([edges, gx])
    Y = np.concatenate([[0.0, 0.0], gy])
    Z = np.concatenate([[0.0, 0.0], gz])
    phases = np.arange(n_phases) / n_phases
    S = np.empty((n_phases, X.size, 6))
    ctrl = np.empty(n_phases)
    for i, p in enumerate(phases):
        f = loop_stress(loop, X, Y, Z, phase=p, body=body)
        S[i] = np.stack([np.asarray(getattr(f, k)) for k in _CART], axis=-1)
        ctrl[i] = f.meta["control"]
    # the edge: largest principal stress over the cycle at (±a, 0, 0)
    T = np.stack([np.stack([S[:, :2, 0], S[:, :2, 3], S[:, :2, 4]], -1),
                  np.stack([S[:, :2, 3], S[:, :2, 1], S[:, :2, 5]], -1),
                  np.stack([S[:, :2, 4], S[:, :2, 5], S[:, :2, 2]], -1)], -2)
    w, v = np.linalg.eigh(T)                                   # ascending
    t, e = np.unravel_index(np.argmax(w[..., -1]), w.shape[:2])
    n = v[t, e, :, -1]
    sn = _fat.normal_stress_on_planes(S[:, e, :], n[None, :])[:, 0]
    val, normals = _fat.swt(S, E, nu)
    j = int(np.argmax(val))
    extra: dict[str, Any] = {}
    meta = {"body": body, "E": float(E), "nu": nu, "mode": loop.mode,
            "citations": ("J85", "MD53")}
    if findley_k is not None:
        fv, fn = _fat.findley(S, fk)
        i = int(np.argmax(fv))
        extra = {"findley": float(fv[i]), "findley_location": np.array([X[i], Y[i], Z[i]]),
                 "findley_normal": fn[i], "findley_at_point": fv}
        meta["findley_k"] = fk
    return FrettingFatigue(float(w[t, e, -1]), float(np.max(sn) - np.min(sn)), n,
                           float(val[j]), np.array([X[j], Y[j], Z[j]]), normals[j], phases,
                           ctrl, X, Y, Z, val, meta, **extra)
