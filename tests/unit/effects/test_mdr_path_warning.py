"""ValidityWarning of the MDR torsion springs on twisted paths whose normal force changes
(contact.simulate(path, method="mdr"), issue 18), checked against the exact ring solver."""
import warnings

import numpy as np
import pytest

import contactlab as cl
from contactlab.errors import ValidityWarning
from tests.reference import hertz
from tests.tolerances import MDR_PATH_WITHIN_VALIDITY

R, MU, F0 = 0.01, 0.3, 10.0
MAT = (cl.Elastic(E=210e9, nu=0.3), cl.Rigid())
E_STAR = hertz.effective_modulus(210e9, 0.3)


def contact():
    return cl.Contact(cl.profiles.Paraboloid(R=R), materials=MAT, friction=MU)


def path(amp, steps=90):
    """Force 10 N ± 40 % (two cycles), twist ``amp`` μF₀/(G_t a₀²) oscillating (three cycles)."""
    c = contact()
    t = np.arange(1, steps + 1) / steps
    force = F0 * (1 + 0.4 * np.sin(4 * np.pi * t + 0.3))
    a0 = hertz.radius_of_force(F0, R, E_STAR)
    s = MU * F0 / (c.moduli.torsional * a0 * a0)
    twist = amp * s * np.sin(6 * np.pi * t) * np.minimum(1, 2 * t)
    sliding = 3 * np.pi / 16 * MU * force * hertz.radius_of_force(force, R, E_STAR)
    return cl.LoadPath.from_arrays(force=force, twist=twist), float(sliding.max())


def mdr_error(p, M_s, mdr):
    exact = contact().simulate(p, method="exact", n_rings=150)
    return float(np.max(np.abs(mdr.torque - exact.torque))) / M_s


def test_beyond_the_validity_twist_it_warns_and_is_wrong():
    p, M_s = path(0.3)
    with pytest.warns(ValidityWarning, match=r"times .* rad.*Use method='exact'") as rec:
        mdr = contact().simulate(p, method="mdr")
    assert len(rec) == 1
    msg = str(rec[0].message)
    assert "c/a=0.83" in msg and "9-12 % at 5.3-6.4 times it" in msg
    assert mdr_error(p, M_s, mdr) > MDR_PATH_WITHIN_VALIDITY


def test_within_the_validity_twist_it_is_silent_and_close():
    p, M_s = path(0.02)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        mdr = contact().simulate(p, method="mdr")
    assert mdr_error(p, M_s, mdr) < MDR_PATH_WITHIN_VALIDITY


def test_limit_is_the_constant_load_validity_twist_at_the_smallest_radius():
    from contactlab.effects.path import mdr_path_validity
    from contactlab.effects.torsion import mdr_validity_twist
    c = contact()
    p, _ = path(0.3)
    r = c.simulate(p, n_rings=20)
    ratio, big, lim, a = mdr_path_validity(c, r.twist, r.radius, r.depth)
    k = int(np.argmin(r.radius))
    ref = mdr_validity_twist(c, r.radius[k:k + 1], r.depth[k:k + 1],
                             c.profile._g(r.radius[k:k + 1]))[0]
    assert a == r.radius[k] and lim == pytest.approx(ref, rel=1e-12)
    assert big == pytest.approx(np.max(np.abs(r.twist)), rel=1e-15) and ratio == big / lim


def test_error_estimate_warns_once_and_the_exact_method_never():
    p, _ = path(0.3)
    with pytest.warns(ValidityWarning) as rec:
        contact().simulate(p, method="mdr", error_estimate=True, n_springs=400)
    assert len(rec) == 1
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        contact().simulate(p, n_rings=20)
