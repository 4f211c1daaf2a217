"""Subsurface stresses of tangential (Cattaneo–Mindlin) states and of combined states:
:class:`CartesianStressField` and the drivers behind ``TangentialState.stress`` and
:func:`combined_stress`.

The Cattaneo–Mindlin traction ``τ_x = μ[p_a(r) - p_c(r)]`` is, like the pressure, a stack of
punch-type distributions: ``τ_x = μ(E*/π)[∫_c^a g'(x) (x² - r²)^(-1/2) dx + (d - g(a))
(a² - r²)^(-1/2)]`` (only punches wider than the stick radius ``c`` remain in the difference).
Its field is the same integral over the elementary field of a shear traction
``(x² - r²)^(-1/2)`` along ``+x`` (:mod:`contactlab.physics.stress_tangential`), integrated with
the Gauss–Kronrod rule and error estimate of the normal field.

Conventions: Cartesian components at points ``(x, y, z)``, ``x`` the direction of the shift,
``z >= 0`` the depth below the surface of the chosen body, tension positive. Body 1 receives the
traction ``state.shear(r)`` reports (``σ_xz(r, 0) = τ_x(r)``); body 2 receives the opposite one
and its field (in its own frame: same ``x, y``, depth into body 2) is the negative of body 1's
with body 2's Poisson ratio.
"""
from __future__ import annotations

import warnings
from dataclasses import dataclass, field
from typing import Any, ClassVar

import numpy as np

from ..citations import Cited
from ..errors import NotSupportedError, ParameterError, ValidityWarning
from ..params import as_float_array
from ..physics import stress as _st
from ..physics import stress_tangential as _sh
from ._protocol import Result
from .stress import (KINDS, StressDerived, StressMaximum, body_poisson_ratio, check_stress_memory,
                     normal_stress, slope_route)

__all__ = ["CartesianStressField", "TANGENTIAL_SOURCES", "combined_stress", "to_cartesian",
           "tangential_max_stress", "tangential_stress", "tangential_stress_field"]

_CART = ("sxx", "syy", "szz", "sxy", "sxz", "syz")

#: sources: Sneddon's superposition, Johnson (Love's potentials, Boussinesq, Cerruti),
#: Cattaneo and Mindlin (the partial-slip traction)
TANGENTIAL_SOURCES = ("Sn65", "J85", "Cat38", "Min49")

#: units of the CSV columns of a :class:`CartesianStressField`
CART_UNITS = {"x": "m", "y": "m", "z": "m", **{k: "Pa" for k in _CART}, "von_mises": "Pa",
              "max_shear": "Pa", "tresca": "Pa", "error": "Pa"}


@dataclass(frozen=True, eq=False)
class CartesianStressField(StressDerived, Result, Cited):
    """Stress field at points ``(x, y, z)`` in Cartesian components (immutable arrays of the
    broadcast shape of the points).

    Attributes
    ----------
    x, y, z : ndarray
        Position (``x`` along the shift), m; ``z >= 0`` the depth.
    sxx, syy, szz, sxy, sxz, syz : ndarray
        Stress components, Pa (tension positive).
    error : ndarray
        Estimated absolute error of the components, Pa (``inf`` at singular points).
    meta : dict
        ``route``, ``body``, ``nu``, ``error_estimate`` (relative to the largest stress),
        ``part``, ``citations``.

    Notes
    -----
    Derived fields as for :class:`~contactlab.effects.stress.StressField` (the shared
    :class:`~contactlab.effects.stress.StressDerived`): :attr:`principal`, :attr:`von_mises`,
    :attr:`max_shear`, :attr:`tresca`, :attr:`max_principal`, :attr:`min_principal`; ``plot``
    draws the ``x``–``z`` plane.
    """

    x: np.ndarray
    y: np.ndarray
    z: np.ndarray
    sxx: np.ndarray
    syy: np.ndarray
    szz: np.ndarray
    sxy: np.ndarray
    sxz: np.ndarray
    syz: np.ndarray
    error: np.ndarray = field(repr=False)
    meta: dict = field(default_factory=dict, repr=False)

    units: ClassVar[dict[str, str]] = CART_UNITS
    _COORDS: ClassVar[tuple[str, ...]] = ("x", "y", "z")
    _COMPONENTS: ClassVar[tuple[str, ...]] = _CART
    _TENSOR: ClassVar[tuple[str, ...]] = _CART


def _xyz(x: Any, y: Any, z: Any) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    x, y, z = (as_float_array(n, v) for n, v in (("x", x), ("y", y), ("z", z)))
    if np.any(z < 0):
        raise ParameterError(f"z contains {float(z[z < 0].ravel()[0])!r}: depths below the "
                             "surface must be >= 0 m.")
    try:
        out = tuple(np.broadcast_arrays(x, y, z))
    except ValueError as err:
        raise ParameterError(f"x, y and z with shapes {x.shape}, {y.shape}, {z.shape} do not "
                             "broadcast.") from err
    check_stress_memory("stress()", out[0].size)
    return out  # type: ignore[return-value]


def _angles(x: np.ndarray, y: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    rho = np.hypot(x, y)
    on = rho > 0
    safe = np.where(on, rho, 1.0)
    return rho, np.where(on, x / safe, 1.0), np.where(on, y / safe, 0.0)


def to_cartesian(f, x: np.ndarray, y: np.ndarray) -> tuple[np.ndarray, ...]:
    """``(σ_xx, σ_yy, σ_zz, σ_xy, σ_xz, σ_yz)`` of a cylindrical
    :class:`~contactlab.effects.stress.StressField` evaluated at ``r = hypot(x, y)``."""
    _, c, s = _angles(x, y)
    cc, ss, cs = c * c, s * s, c * s
    with np.errstate(invalid="ignore"):
        sxx = f.srr * cc + f.stt * ss - 2.0 * f.srt * cs
        syy = f.srr * ss + f.stt * cc + 2.0 * f.srt * cs
        sxy = (f.srr - f.stt) * cs + f.srt * (cc - ss)
        sxz = f.srz * c - f.stz * s
        syz = f.srz * s + f.stz * c
    return sxx, syy, np.array(f.szz), sxy, sxz, syz


def _single(state, what: str) -> None:
    if np.ndim(state._c) != 0:
        raise NotSupportedError(f"{what} needs a single state, this one has shape "
                                f"{np.shape(state._c)}: index the loads or call tangential() "
                                "per load.")


def _normal_of(state):
    """The normal preload of a single tangential state as a single NormalState."""
    n = state.normal
    if n.shape == ():
        return n
    return type(n)(n.contact, np.float64(np.ravel(n._depth)[0]),
                   np.float64(np.ravel(n._radius)[0]), np.float64(np.ravel(n._force)[0]),
                   {k: v for k, v in n.meta.items() if k != "error_estimate"})


def _friction_part(state, rho: np.ndarray, z: np.ndarray, nu: float, body: int
                   ) -> tuple[tuple[np.ndarray, ...], np.ndarray, str]:
    """Radial functions (flat) of the frictional field of a single tangential state, with the
    body's sign applied, their error and the route."""
    ct = state.contact
    ns = _normal_of(state)
    a, d = float(ns._radius), float(ns._depth)
    c = float(np.ravel(state._c)[0])
    u = float(np.ravel(state._u)[0])
    R, Z = rho.ravel(), z.ravel()
    zero = np.zeros(R.shape)
    if a <= 0 or u == 0:
        return (zero,) * _sh.N_SHEAR_RADIAL, zero, "tangential: none"
    if ct.friction is None:
        # no slip: the rigidly shifted punch, q = Q/(2π a sqrt(a² - r²)): the single
        # punch-type traction of radius a (its kernel's σ_xz is -1/sqrt(a² - r²))
        amp = -float(np.ravel(state.tangential_force)[0]) / (2.0 * np.pi * a)
        amp *= 1.0 if body == 1 else -1.0
        P = tuple(amp * p for p in _sh.shear_kernel(R, Z, a, nu))
        err = 4e-15 * np.maximum.reduce([np.abs(p) for p in P])
        return P, err, "tangential: no-slip shifted punch"
    sign = -np.sign(u) * (1.0 if body == 1 else -1.0)
    k = ct.friction * ct.moduli.normal / np.pi
    prof = ct.profile
    gp, gp_err, g_vals, cuts, table = slope_route(prof, a, ct.rtol)
    c = min(c, a)
    if c > 0:
        gp0, err0, gv0 = gp, gp_err, g_vals
        gp = lambda x: np.where(x >= c, gp0(x), 0.0)      # noqa: E731 - punches wider than c
        if err0 is not None:
            gp_err = lambda x: np.where(x >= c, err0(x), 0.0)  # noqa: E731
        if gv0 is not None:
            g_vals = lambda x: gv0(np.maximum(x, c))        # noqa: E731
        cuts = tuple(sorted({*cuts, c}))

    def kernel(rr, zz, xx, offset=None):
        return _sh.shear_kernel(rr, zz, xx, nu, offset)

    P, err = _st.superposed_field(R, Z, np.full(R.shape, a), zero, gp, 0.0, nu, cuts, gp_err,
                                  g_vals, kernel, k)
    edge = d - float(ns._g_at_radius)
    if edge != 0:
        extra = _sh.shear_kernel(R, Z, a, nu)
        P = tuple(p + k * edge * e for p, e in zip(P, extra))
        err = err + 4e-15 * np.maximum.reduce([np.abs(k * edge * e) for e in extra])
    route = "tangential: superposition" + (" (table)" if table else "")
    return tuple(sign * p for p in P), err, route


def tangential_stress(state, x: Any, y: Any, z: Any, body: Any = 1, part: str = "total"
                      ) -> CartesianStressField:
    """Field of a tangential state (implementation of ``TangentialState.stress``)."""
    if part not in ("total", "friction"):
        raise ParameterError(f"part={part!r} is invalid: choose 'total' (normal preload "
                             "included) or 'friction' (the tangential part alone).")
    nu = body_poisson_ratio(state.contact, body)
    x, y, z = _xyz(x, y, z)
    _single(state, "stress()")
    rho, c, s = _angles(x, y)
    P, err, route = _friction_part(state, rho, z, nu, body)
    comps = _sh.shear_components(tuple(p.reshape(x.shape) for p in P), c, s)
    err = err.reshape(x.shape)
    if part == "total":
        base = normal_stress(_normal_of(state), rho, z, body)
        comps = tuple(a + b for a, b in zip(to_cartesian(base, x, y), comps))
        err = err + base.error
        route = f"{base.meta['route']} + {route}"
    return _wrap(x, y, z, comps, err, {"route": route, "body": body, "nu": nu, "part": part,
                                       "citations": TANGENTIAL_SOURCES})


def _wrap(x, y, z, comps, err, meta: dict) -> CartesianStressField:
    sxx, syy, szz, sxy, sxz, syz = (np.asarray(v, float).reshape(x.shape) for v in comps)
    stack = np.stack([sxx, syy, szz, sxy, sxz, syz])
    fin = np.all(np.isfinite(stack), axis=0)
    err = np.where(fin, err, np.inf)
    top = np.max(np.abs(stack)[:, fin], initial=0.0)
    meta["error_estimate"] = float(np.max(err[fin], initial=0.0) / top) if top > 0 else 0.0
    return CartesianStressField(x, y, z, sxx, syy, szz, sxy, sxz, syz, err, meta)


def _maximise3(evaluate, kind: str, a: float, meta: dict) -> StressMaximum:
    """Grid search over ``|x| <= 2a, 0 <= y <= 2a, 0 <= z <= 2a`` (the field of a shift along
    ``x`` is symmetric in ``y``), then a Nelder–Mead polish; ``r`` of the result is the
    distance from the axis, ``meta["x"], meta["y"]`` the position."""
    from scipy.optimize import minimize
    g = np.linspace(-2.0 * a, 2.0 * a, 33)
    h = np.linspace(0.0, 2.0 * a, 17)
    X, Y, Z = np.meshgrid(g, h, h, indexing="ij")
    vals = evaluate(X, Y, Z).get(kind)
    if not np.all(np.isfinite(vals)):
        i = np.unravel_index(np.argmax(~np.isfinite(vals)), vals.shape)
        return StressMaximum(float("inf"), float(np.hypot(X[i], Y[i])), float(Z[i]), kind,
                             {**meta, "x": float(X[i]), "y": float(Y[i])})
    i = np.unravel_index(np.argmax(vals), vals.shape)
    p0 = np.array([X[i], Y[i], Z[i]]) / a

    def neg(p: np.ndarray) -> float:
        return -float(evaluate(p[0:1] * a, np.abs(p[1:2]) * a, np.abs(p[2:3]) * a).get(kind)[0])

    simplex = p0 + np.vstack([np.zeros(3), 0.02 * np.eye(3)])
    res = minimize(neg, p0, method="Nelder-Mead",
                   options={"xatol": 1e-10, "fatol": 0.0, "maxiter": 6000,
                            "initial_simplex": simplex})
    xx, yy, zz = res.x[0] * a, abs(res.x[1]) * a, abs(res.x[2]) * a
    return StressMaximum(-float(res.fun), float(np.hypot(xx, yy)), float(zz), kind,
                         {**meta, "x": float(xx), "y": float(yy)})


def tangential_max_stress(state, kind: str = "von_mises", body: Any = 1) -> StressMaximum:
    """Implementation of ``TangentialState.max_stress`` (the whole state's field)."""
    if kind not in KINDS:
        raise ParameterError(f"kind={kind!r} is invalid: choose one of "
                             f"{', '.join(repr(k) for k in KINDS)}.")
    body_poisson_ratio(state.contact, body)
    _single(state, "max_stress()")
    a = float(_normal_of(state)._radius)
    meta = {"body": body, "citations": TANGENTIAL_SOURCES}
    if a <= 0:
        return StressMaximum(0.0, 0.0, 0.0, kind, {**meta, "x": 0.0, "y": 0.0})
    return _maximise3(lambda x, y, z: tangential_stress(state, x, y, z, body), kind, a, meta)


def _plane_grid(grid: Any, a: float) -> tuple[np.ndarray, np.ndarray]:
    if grid is None:
        if a <= 0:
            raise ParameterError("stress_field() without grid= needs a contact (radius > 0).")
        xv, zv = np.linspace(-2.0 * a, 2.0 * a, 200), np.linspace(0.0, 1.5 * a, 100)
    else:
        try:
            xv, zv = grid
        except (TypeError, ValueError) as err:
            raise ParameterError(f"grid={grid!r} is invalid: give (x_values, z_values).") from err
        xv, zv = as_float_array("grid x", xv).ravel(), as_float_array("grid z", zv).ravel()
    check_stress_memory("stress_field()", float(xv.size) * float(zv.size), superposed=False)
    X, Z = np.meshgrid(xv, zv, indexing="xy")
    return X, Z


def tangential_stress_field(state, grid: Any = None, body: Any = 1, part: str = "total",
                            y: float = 0.0) -> CartesianStressField:
    """Implementation of ``TangentialState.stress_field``: the field on a grid of the plane
    ``y = const`` (default: 200 ``x`` over ``[-2a, 2a]`` by 100 depths over ``[0, 1.5a]``)."""
    _single(state, "stress_field()")
    X, Z = _plane_grid(grid, float(_normal_of(state)._radius))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ValidityWarning)
        return tangential_stress(state, X, np.full(X.shape, float(y)), Z, body, part)


# ====================================================================== combined states
#: relative excess of the combined surface traction over μp tolerated before a warning
TRACTION_EXCESS = 1e-9


def combined_stress(x: Any, y: Any, z: Any, *, normal: Any = None, tangential: Any = None,
                    torsion: Any = None, body: Any = 1) -> CartesianStressField:
    """Field of a normal load with a shift and a twist at one instant, by superposition.

    The normal preload (of whichever states are given; they must share it) plus the frictional
    part of the tangential state plus that of the torsion state, in Cartesian components at
    ``(x, y, z)``. See docs/stress.md for the decoupling assumption: each frictional traction is
    the library's solution for its load alone; the sum is the field of the summed tractions
    (linear elasticity: exact), and those are the combined contact's tractions only while their
    vector sum stays within ``μ p`` (checked on the surface: a ``ValidityWarning`` otherwise) and
    the normal–tangential decoupling holds (elastically similar bodies: a warning otherwise).

    Raises
    ------
    ParameterError
        No state, or states with different contacts or normal loads.
    """
    given: list[tuple[Any, Any, float, float]] = []     # (state, its normal state, d, a)
    if normal is not None:
        if normal.shape != ():
            raise NotSupportedError("combined_stress() needs single states.")
        given.append((normal, normal, float(normal._depth), float(normal._radius)))
    if tangential is not None:
        _single(tangential, "combined_stress()")
        tn = _normal_of(tangential)
        given.append((tangential, tn, float(tn._depth), float(tn._radius)))
    if torsion is not None:
        if torsion.shape != ():
            raise NotSupportedError("combined_stress() needs single states.")
        from .stress import _one_normal
        on = torsion.normal if torsion.normal.shape == () else _one_normal(torsion)
        given.append((torsion, on, float(torsion._d), float(torsion._a)))
    if not given:
        raise ParameterError("combined_stress() needs at least one of normal=, tangential=, "
                             "torsion=.")
    base = given[0][1]
    ct = base.contact
    for st, _, d, a in given:
        if st.contact is not ct or (d, a) != (given[0][2], given[0][3]):
            raise ParameterError("combined_stress() needs states of one contact at one normal "
                                 f"load: got depth/radius {d!r}/{a!r} m against "
                                 f"{given[0][2]!r}/{given[0][3]!r} m (build them with the same "
                                 "force= or depth=).")
    nu = body_poisson_ratio(ct, body)
    x, y, z = _xyz(x, y, z)
    rho, c, s = _angles(x, y)
    nf = normal_stress(base, rho, z, body)
    comps = list(to_cartesian(nf, x, y))
    err = np.asarray(nf.error, float)
    routes = [nf.meta["route"]]
    if tangential is not None:
        P, e, route = _friction_part(tangential, rho, z, nu, body)
        tc = _sh.shear_components(tuple(p.reshape(x.shape) for p in P), c, s)
        comps = [u + v for u, v in zip(comps, tc)]
        err = err + e.reshape(x.shape)
        routes.append(route)
    if torsion is not None:
        from .stress import torsion_stress
        tf = torsion_stress(torsion, rho, z, body, "friction")
        comps = [u + v for u, v in zip(comps, to_cartesian(tf, x, y))]
        err = err + tf.error
        routes.append(tf.meta["route"])
    notes = _decoupling_notes(ct, tangential, torsion, float(base._radius))
    for n in notes:
        warnings.warn(n, ValidityWarning, stacklevel=2)
    return _wrap(x, y, z, comps, err, {"route": " + ".join(routes), "body": body, "nu": nu,
                                       "part": "combined", "notes": tuple(notes),
                                       "citations": (*TANGENTIAL_SOURCES, "RS44")})


def _decoupling_notes(ct, tangential: Any, torsion: Any, a: float) -> list[str]:
    notes = []
    if tangential is not None and not ct.moduli.elastically_similar:
        notes.append("combined_stress(): the bodies are not elastically similar, so the normal "
                     "and tangential problems couple; the Cattaneo-Mindlin traction the field "
                     "superposes neglects that coupling.")
    if tangential is not None and torsion is not None and ct.friction is not None and a > 0:
        r = np.linspace(0.0, a, 257)[1:-1]
        tx = np.abs(np.asarray(tangential.shear(r), float))
        tt = np.abs(np.asarray(torsion.shear(r), float))
        p = np.asarray(_normal_of(tangential).pressure(r), float)
        over = tx + tt > ct.friction * p * (1.0 + TRACTION_EXCESS)
        if np.any(over):
            notes.append("combined_stress(): the summed shift and twist tractions exceed the "
                         f"friction limit mu*p at r = {float(r[over][0]):.6g} m (the two "
                         "solutions each assume the other load is absent); the field is that of "
                         "the summed tractions, not of the combined partial-slip contact.")
    return notes
