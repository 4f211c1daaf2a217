"""Honesty of simulate(..., error_estimate=True) (issue 7): the half-N difference bounds the
spring-discretisation error against the exact histories (shift_history: Cattaneo-Mindlin with
Masing memory; twist_history(method="mdr"): the MDR torsion springs in closed form)."""
from __future__ import annotations

import warnings

import numpy as np

import contactlab as cl
from contactlab.errors import ValidityWarning

STEEL = cl.Elastic(E=210e9, nu=0.3)
F_N = 50.0
LADDER = (100, 200, 400, 800, 1600)


def _contact():
    return cl.Contact(cl.profiles.Paraboloid(R=0.01), (STEEL, STEEL), friction=0.3)


def test_spring_error_estimate_is_honest():
    c = _contact()
    a = c.normal(force=F_N).radius
    u_star = 0.3 * c.moduli.normal * c.normal(force=F_N).depth / c.moduli.tangential
    phi_ref = 3 * 0.3 * F_N / (16 * c.moduli.torsional * a**2)
    cases = {
        "tangential_force": (cl.LoadPath().ramp(force=F_N, steps=5)
                             .sinusoid(displacement=0.7 * u_star, cycles=2, steps_per_cycle=60),
                             lambda res: c.shift_history(force=F_N,
                                                         displacement=res.displacement[5:]
                                                         ).tangential_force),
        "torque": (cl.LoadPath().ramp(force=F_N, steps=5)
                   .sinusoid(twist=0.8 * phi_ref, cycles=2, steps_per_cycle=60),
                   lambda res: c.twist_history(force=F_N, twist=res.twist[5:],
                                               method="mdr").torque),
    }
    outcomes = []
    for name, (path, exact) in cases.items():
        for n in LADDER:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", ValidityWarning)   # MDR torsion: intended
                res = c.simulate(path, n_springs=n, error_estimate=True, method="mdr")
                ref = exact(res)
            series = getattr(res, name)[5:]
            actual = np.max(np.abs(series - ref)) / np.max(np.abs(series))
            est = res.meta["error_estimates"][name]
            outcomes.append((est >= actual, name, n, est, actual))
            assert est <= 1e3 * max(actual, 1e-12), (name, n, est, actual)
    honest = sum(o[0] for o in outcomes) / len(outcomes)
    assert honest >= 0.95, [o for o in outcomes if not o[0]]


def test_no_estimate_unless_asked():
    c = _contact()
    res = c.simulate(cl.LoadPath().ramp(force=F_N, steps=3), n_springs=50, method="mdr")
    assert "error_estimates" not in res.meta
