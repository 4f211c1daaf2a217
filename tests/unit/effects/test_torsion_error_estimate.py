"""Honesty of the torsion error estimates (issue 7): ``TorsionState.error_estimate`` and
``error_estimates`` against the actual error, over a ladder of ``Contact(rtol=)``, profiles and
stick ratios ``c/a``.

Actual errors come from the independent mpmath reference (tests/reference/torsion_reference.py:
Hertz closed forms of theory §6.3 for the paraboloid, the direct pressure integrals of §6.2
for cone, flat punch and n = 4). The 200-point tabulated paraboloid has no closed form for its
piecewise-linear shape; its reference is the same state at ``rtol = 1e-14`` (a second, converged
run: the estimate is about the numerical error against the given table, not the interpolation).
"""
from __future__ import annotations

import warnings
from functools import lru_cache

import numpy as np
import pytest

import contactlab as cl
from contactlab.errors import ValidityWarning
from tests import tolerances as tol
from tests.reference import torsion_reference as ref

mp = ref.mp

RTOLS = (1e-3, 1e-4, 1e-6, 1e-8, 1e-10, 1e-12)
RATIOS = (0.99, 0.5, 0.01)
MU = 0.3
R = 0.01
A = 2e-4
MAT = cl.Elastic(E=210e9, nu=0.3)


def _profiles() -> dict:
    r = np.linspace(0.0, 1.5 * A, 200)
    return {"paraboloid": cl.profiles.Paraboloid(R=R),
            "cone": cl.profiles.Cone(0.05),
            "flat": cl.profiles.FlatPunch(radius=A),
            "n4": cl.profiles.PowerLaw(2e9, 4),
            "table200": cl.profiles.Tabulated(r, r**2 / (2 * R))}


def _depth(name: str, prof) -> float:
    if name == "flat":
        return 1e-6
    return float(prof._height(np.array([A]))[0]) * (2.0 if name == "cone" else 1.0)


@lru_cache(maxsize=None)
def _reference(name: str, ratio: float) -> tuple[float, float, float, float]:
    """(a, c, φ, M) of the reference for profile ``name`` at ``c/a = ratio``."""
    prof = _profiles()[name]
    d = _depth(name, prof)
    c0 = cl.Contact(prof, (MAT, MAT), friction=MU, rtol=1e-14)
    a = float(c0.normal(depth=d).radius)
    E = c0.moduli.normal
    G = c0.moduli.torsional
    c = ratio * a
    if name == "table200":
        s = c0.torsion(depth=d, stick_radius=c, method="exact")
        return a, c, float(s.twist), float(s.torque)
    if name == "paraboloid":
        F = 4 * E * a**3 / (3 * R)
        phi = ref.hertz_twist_hat(ratio) * MU * F / (G * a * a)
        M = ref.hertz_torque_hat(ratio) * MU * F * a
        return a, c, float(phi), float(M)
    if name == "cone":
        def p(r):
            return ref.pressure_cone(r, a, E, 0.05)
    elif name == "flat":
        def p(r):
            return ref.pressure_flat(r, a, E, d)
    else:
        def p(r):
            return ref.pressure_power(r, a, E, 2e9, 4)
    phi, M = ref.torque_general(c, a, p, MU, G)
    return a, c, float(phi), float(M)


def _cases():
    """(estimate, actual) pairs over the whole ladder (computed once)."""
    out = []
    for name, prof in _profiles().items():
        d = _depth(name, prof)
        for ratio in RATIOS:
            a, c, phi, M = _reference(name, ratio)
            for rtol in RTOLS:
                ct = cl.Contact(prof, (MAT, MAT), friction=MU, rtol=rtol)
                tw = ct.torsion(depth=d, twist=phi, method="exact")
                out.append((name, ratio, rtol, "torque|twist", tw.error_estimate,
                            abs(tw.torque / M - 1)))
                out.append((name, ratio, rtol, "stick|twist", tw.error_estimates["stick_radius"],
                            abs(tw.stick_radius / c - 1)))
                st = ct.torsion(depth=d, stick_radius=c, method="exact")
                out.append((name, ratio, rtol, "torque|stick", st.error_estimate,
                            abs(st.torque / M - 1)))
                out.append((name, ratio, rtol, "twist|stick", st.error_estimates["twist"],
                            abs(st.twist / phi - 1)))
                tq = ct.torsion(depth=d, torque=M, method="exact")
                out.append((name, ratio, rtol, "twist|torque", tq.error_estimates["twist"],
                            abs(tq.twist / phi - 1)))
                out.append((name, ratio, rtol, "stick|torque", tq.error_estimates["stick_radius"],
                            abs(tq.stick_radius / c - 1)))
    return out


@pytest.fixture(scope="module")
def cases():
    return _cases()


def test_estimate_is_honest(cases):
    honest = [est >= act for *_, est, act in cases]
    bad = [cs for cs, ok in zip(cases, honest) if not ok]
    assert np.mean(honest) >= tol.TORSION_ERR_HONEST_FRACTION, bad


def test_estimate_not_absurd(cases):
    ratio = np.array([est / max(act, tol.TORSION_ERR_FLOOR) for *_, est, act in cases])
    worst = cases[int(np.argmax(ratio))]
    assert np.mean(ratio <= tol.TORSION_ERR_MAX_OVER) >= tol.TORSION_ERR_HONEST_FRACTION, worst
    assert ratio.max() <= tol.TORSION_ERR_MAX_OVER_ALL, worst


def test_estimate_in_meta_and_array_shape():
    ct = cl.Contact(cl.profiles.Paraboloid(R=R), (MAT, MAT), friction=MU, rtol=1e-8)
    s = ct.torsion(depth=4e-6, twist=np.array([1e-5, 1e-4, 1e-3]))
    assert s.error_estimate is s.meta["error_estimate"]
    assert np.shape(s.error_estimate) == (3,)
    assert set(s.error_estimates) == {"torque", "twist", "stick_radius"}
    assert np.all(np.isfinite(s.error_estimates["stick_radius"]))


@pytest.mark.parametrize("method", ["no-slip", "mdr"])
def test_closed_form_parts_carry_a_rounding_floor(method):
    """No-slip: ``M = (16/3) G_t a³ φ`` (closed form) — the estimate is a rounding floor, above the
    actual error; MDR against its own closed form for Hertz (theory §6.4)."""
    ct = cl.Contact(cl.profiles.Paraboloid(R=R), (MAT, MAT), friction=MU, rtol=1e-10)
    d = 4e-6
    a = float(ct.normal(depth=d).radius)
    G = ct.moduli.torsional
    F = 4 * ct.moduli.normal * a**3 / (3 * R)
    if method == "no-slip":
        s = ct.torsion(depth=d, twist=1e-4, method=method)
        M = 16 / 3 * G * a**3 * 1e-4
    else:
        t = 0.9
        phi_hat, M_hat = ref.hertz_mdr_hat(t)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", ValidityWarning)
            s = ct.torsion(depth=d, twist=float(phi_hat) * MU * F / (G * a * a), method=method)
        M = float(M_hat) * MU * F * a
    err = abs(s.torque / M - 1)
    assert 0 < s.error_estimate
    assert err <= s.error_estimate <= tol.TORSION_ERR_MAX_OVER * max(err, tol.TORSION_ERR_FLOOR)
