"""The exact ring solver at tiny scales (issue 26 item 6: a raw LinAlgError at 2.5e-188 N).

The ring solver's torque integrals carry fifth powers of the contact radius: below ~1e-58 m they
fall into the subnormal range (and its influence matrices underflow further down). Such paths
raise OutsideTheoryError naming the radius and the force; down to there the solver keeps every
digit. Expected values come from dimensional analysis: a Hertz path scaled by s (force
s F, torque s^(4/3) M) has contact radii s^(1/3) a, twists s^(1/3) φ and the same torque ratios
and stick-radius ratios.
"""
from __future__ import annotations

import numpy as np
import pytest

import contactlab as cl
from contactlab.errors import OutsideTheoryError
from tests.tolerances import RINGS_SCALE_INVARIANCE

MU = 0.3
C = cl.Contact(cl.profiles.Paraboloid(R=0.01),
               materials=(cl.Elastic(E=210e9, nu=0.3), cl.Rigid()), friction=MU)


def _run(s: float):
    F = 10.0 * s
    a = float(C.normal(force=F).radius)
    M_slide = 3 * np.pi / 16 * MU * F * a
    M = M_slide * np.array([0.0, 0.3, 0.6, -0.2, 0.5, 0.9, 0.1])
    path = (cl.LoadPath().ramp(force=F, steps=3)
            + cl.LoadPath.from_arrays(torque=M, force=np.full(M.size, F)))
    return C.simulate(path, method="exact"), M_slide, a


@pytest.mark.parametrize("s", [1e-120, 1e-160])
def test_scaled_path_obeys_scaling_laws(s):
    ref, M1, a1 = _run(1.0)
    out, Ms, a = _run(s)
    G = C.moduli.torsional
    twist_ref = ref.twist * G * a1**3 / M1
    assert np.max(np.abs(out.twist * G * a**3 / Ms - twist_ref)) <= (
        RINGS_SCALE_INVARIANCE * np.max(np.abs(twist_ref)))
    assert np.allclose(out.torque / Ms, ref.torque / M1, rtol=0, atol=RINGS_SCALE_INVARIANCE)
    assert np.allclose(out.stick_radius / a, ref.stick_radius / a1, rtol=0,
                       atol=RINGS_SCALE_INVARIANCE, equal_nan=True)


@pytest.mark.parametrize("s", [1e-170, 2.5e-188, 1e-250])
def test_scales_beyond_double_precision_raise(s):
    """Force = torque = 2.5e-188 (the fuzz case): a contactlab error naming the contact radius
    and the force, never a raw LinAlgError or a silently wrong twist."""
    path = (cl.LoadPath().ramp(force=s, steps=3)
            + cl.LoadPath.from_arrays(torque=s * np.array([0.0, 1e-3, 2e-3]), force=np.full(3, s)))
    with pytest.raises(OutsideTheoryError, match=r"contact radius .*normal force"):
        C.simulate(path, method="exact")
