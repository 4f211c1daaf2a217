"""A truncated cone at tiny forces (issue 26, item 6): flat punch part + cone, in closed form.

Below ~1e-3 N (b = 0.1 mm, s = 0.1, steel) the contact radius rounds onto the rim b while the
depth is the flat punch's ``F/(2E* b)``; a root solve in the radius returned depth 0 (scalar
route) or reported an overflow (array route). The reference is the closed form written in
θ = arccos(b/a) (mpmath, 40 digits): ``F/(2E*) = s b² (θ + sin θ cos θ)/(2 cos² θ)``,
``a = b/cos θ``, ``d = s a θ``.
"""
from __future__ import annotations

import mpmath as mp
import numpy as np
import pytest

import contactlab as cl
from contactlab.errors import OutsideTheoryError
from contactlab.profiles import TruncatedCone
from tests.tolerances import TRUNCATED_CONE_SUBNORMAL, TRUNCATED_CONE_TINY

B, S = 1e-4, 0.1
STEEL = cl.Elastic(E=210e9, nu=0.3)


def _reference(F: float, E_star: float) -> tuple[float, float]:
    """Contact radius and depth (m) of force F (N), 40 digits."""
    with mp.workdps(40):
        fr = mp.mpf(F) / (2 * mp.mpf(E_star))
        b, s = mp.mpf(B), mp.mpf(S)

        def h(th):
            return s * b**2 * (th + mp.sin(th) * mp.cos(th)) / (2 * mp.cos(th) ** 2) - fr

        th0 = fr / (s * b**2)
        th = mp.findroot(h, th0 if th0 < 0.5 else mp.mpf(1.0), tol=mp.mpf(10) ** -36 * th0)
        a = b / mp.cos(th)
        return float(a), float(s * a * th)


@pytest.mark.parametrize("F", [1e3, 1.0, 1e-3, 1e-10, 1e-30, 1e-100, 1e-200, 1e-290, 1e-300])
def test_tiny_forces_match_closed_form(F):
    c = cl.Contact(TruncatedCone(radius=B, slope=S), materials=(STEEL, STEEL))
    a_ref, d_ref = _reference(F, c.moduli.normal)
    tol = TRUNCATED_CONE_SUBNORMAL if F < 1e-295 else TRUNCATED_CONE_TINY
    scalar = c.normal(force=F)
    array = c.normal(force=np.array([F, F]))
    for st in (scalar, array):
        d = np.asarray(st.depth).ravel()[0]
        a = np.asarray(st.radius).ravel()[0]
        f = np.asarray(st.force).ravel()[0]
        assert d > 0
        assert abs(d - d_ref) <= tol * 4 * d_ref
        assert abs(a - a_ref) <= 2 * np.finfo(float).eps * a_ref
        assert abs(f - F) <= tol * 4 * F
    # the two routes perform the same operations
    assert float(scalar.depth) == float(array.depth[0])
    assert float(scalar.radius) == float(array.radius[0])


def test_tiny_flat_punch_limit():
    """Below ~1e-10 N the state is the flat punch's: d = F/(2E* b) to rounding."""
    c = cl.Contact(TruncatedCone(radius=B, slope=S), materials=(STEEL, STEEL))
    for F in (1e-12, 1e-30, 1e-150):
        assert float(c.normal(force=F).depth) == pytest.approx(F / (2 * c.moduli.normal * B),
                                                               rel=TRUNCATED_CONE_TINY * 4)


def test_force_below_double_precision_raises():
    """A force whose state underflows (5e-324 N) is refused, never returned as 0 N."""
    c = cl.Contact(TruncatedCone(radius=B, slope=S), materials=(STEEL, STEEL))
    for arg in (5e-324, np.array([5e-324])):
        with pytest.raises(OutsideTheoryError):
            c.normal(force=arg)
