"""MDR torsion of a flat punch with the stick radius next to the punch radius (issue 26).

The annulus integral ``∫_c^a x (d - g) dx`` of a flat punch is ``d (a² - c²)/2``; its quadrature
in ``ln x`` lost the width of the annulus to the rounding of ``ln a`` and raised
ConvergenceError from ``1 - c/a ~ 1e-8`` on (fretting loops and ``torsion(..., method="mdr")``
at such amplitudes). Closed forms of the MDR model [S eqs. 47-52] for the punch (g = 0 inside,
``d = F/(2E* a)``): ``φ = μE* d/(4 G_t c)``, ``M = (4/3) μE* d c² + 2μE* d (a² - c²)``.
"""
from __future__ import annotations

import warnings

import mpmath as mp
import numpy as np
import pytest

import contactlab as cl
from contactlab.physics import torsion_mdr as tm
from contactlab.profiles import FlatPunch
from tests.tolerances import MDR_NEAR_ANNULUS, MDR_NEAR_LOOP_ENERGY

B, F, MU = 1e-3, 100.0, 0.3
C = cl.Contact(FlatPunch(radius=B), materials=(cl.Elastic(E=210e9, nu=0.3), cl.Rigid()),
               friction=MU)
GAPS = [1e-3, 1e-4, 1e-6, 1e-8, 1e-10, 1e-12]


def _closed(c: float) -> tuple[float, float]:
    """Twist (rad) and torque (N·m) of the MDR punch at stick radius c (mpmath, 30 digits)."""
    with mp.workdps(30):
        E, G = mp.mpf(C.moduli.normal), mp.mpf(C.moduli.torsional)
        a, cc, mu = mp.mpf(B), mp.mpf(c), mp.mpf(MU)
        d = mp.mpf(F) / (2 * E * a)
        phi = mu * E * d / (4 * G * cc)
        M = mp.mpf(4) / 3 * mu * E * d * cc**2 + 2 * mu * E * d * (a - cc) * (a + cc)
        return float(phi), float(M)


@pytest.mark.parametrize("gap", GAPS)
def test_annulus_integral_of_punch(gap):
    c = B * (1 - gap)
    d = 1e-6
    val, err = tm.annulus_integral(FlatPunch(radius=B), np.array([c]), np.array([B]),
                                   np.array([d]), 1e-10, return_error=True)
    with mp.workdps(30):
        ref = float(mp.mpf(d) * (mp.mpf(B) - mp.mpf(c)) * (mp.mpf(B) + mp.mpf(c)) / 2)
    assert abs(val[0] - ref) <= MDR_NEAR_ANNULUS * ref
    assert err[0] <= MDR_NEAR_ANNULUS * ref


@pytest.mark.parametrize("gap", GAPS)
def test_torsion_near_the_punch_radius(gap):
    c = B * (1 - gap)
    phi, M = _closed(c)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")     # the model's own validity note (not under test)
        by_c = C.torsion(force=F, stick_radius=c, method="mdr")
        by_phi = C.torsion(force=F, twist=phi, method="mdr")
        by_M = C.torsion(force=F, torque=M, method="mdr")
    assert float(by_c.twist) == pytest.approx(phi, rel=MDR_NEAR_ANNULUS)
    assert float(by_c.torque) == pytest.approx(M, rel=MDR_NEAR_ANNULUS)
    assert float(by_phi.torque) == pytest.approx(M, rel=MDR_NEAR_ANNULUS)
    # the stick radius of a torque is fixed only to dM/dc = (4/3) μE* d c, i.e. to
    # rounding of M over that slope: compare the gap a - c, not c
    assert abs(float(by_phi.stick_radius) - c) <= MDR_NEAR_ANNULUS * B
    assert abs(float(by_M.stick_radius) - c) <= 1e-4 * B * gap + 64 * np.finfo(float).eps * B


@pytest.mark.parametrize("gap", [1e-3, 1e-6, 1e-9, 1e-12])
def test_fretting_loop_energy_near_punch_radius(gap):
    """The loop energy of the MDR springs (Masing: 4 x slip limit x slip per spring) in closed
    form, ``W = 32 G_t φ0² c (a - c)²`` with the amplitude's stick radius ``c``: it raised
    ConvergenceError from gap ~1e-8 on."""
    c = B * (1 - gap)
    phi, _ = _closed(c)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        loop = C.fretting_loop(force=F, twist_amplitude=phi, method="mdr")
    with mp.workdps(30):
        G = mp.mpf(C.moduli.torsional)
        ref = float(32 * G * mp.mpf(phi) ** 2 * mp.mpf(c) * (mp.mpf(B) - mp.mpf(c)) ** 2)
    assert float(loop.energy) == pytest.approx(
        ref, rel=1e-12 + MDR_NEAR_LOOP_ENERGY * np.finfo(float).eps / gap)
