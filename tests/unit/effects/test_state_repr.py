"""The repr of a state shows its numbers: ``NormalState(depth=... m, radius=... m, ...)``.

The states' dataclass fields are all hidden (they hold the contact and private arrays), so the
dataclass repr was ``NormalState()``: a user at a prompt saw nothing of the result.
"""
import math
import re

import numpy as np
import pytest

import contactlab as cl
from contactlab.profiles import Paraboloid

STEEL = cl.Elastic(E=210e9, nu=0.3)
E_STAR = 210e9 / (2 * (1 - 0.3**2))
R, F = 0.01, 100.0
#: the repr's 6 significant digits
SHOWN = 5e-6


def _items(text: str) -> dict[str, tuple[str, str]]:
    body = re.fullmatch(r"\w+\((.*)\)", text).group(1)
    return {k: (v, u) for k, v, u in re.findall(r"(\w+)=([^ ,<>]+)(?: ([^ ,=<>]+))?", body)}


def test_normal_state_repr_shows_hertz_numbers_with_units():
    s = cl.Contact(Paraboloid(R=R), (STEEL, STEEL)).normal(force=F)
    items = _items(repr(s))
    a = (3 * F * R / (4 * E_STAR)) ** (1 / 3)                      # Hertz
    assert list(items) == ["depth", "radius", "force", "stiffness"]
    assert float(items["radius"][0]) == pytest.approx(a, rel=SHOWN)
    assert float(items["depth"][0]) == pytest.approx(a * a / R, rel=SHOWN)
    assert float(items["force"][0]) == pytest.approx(F, rel=SHOWN)
    assert float(items["stiffness"][0]) == pytest.approx(2 * E_STAR * a, rel=SHOWN)
    assert [items[k][1] for k in items] == ["m", "m", "N", "N/m"]


def test_array_states_show_shape_and_range():
    c = cl.Contact(Paraboloid(R=R), (STEEL, STEEL), friction=0.2)
    text = repr(c.normal(force=[10.0, F]))
    a_lo, a_hi = ((3 * f * R / (4 * E_STAR)) ** (1 / 3) for f in (10.0, F))
    m = re.search(r"radius=<2: (\S+) \.\. (\S+) m>", text)
    assert m is not None
    assert float(m.group(1)) == pytest.approx(a_lo, rel=1e-3)
    assert float(m.group(2)) == pytest.approx(a_hi, rel=1e-3)
    t = repr(c.torsion(force=F, twist=np.full((2, 3), 1e-4)))
    assert t.startswith("TorsionState(method='exact', twist=<2x3: ")


def test_tangential_torsion_and_adhesive_states_show_their_numbers():
    c = cl.Contact(Paraboloid(R=R), (STEEL, STEEL), friction=0.2)
    t = c.tangential(force=F, tangential_force=5.0)
    items = _items(repr(t))
    a = (3 * F * R / (4 * E_STAR)) ** (1 / 3)
    # Cattaneo–Mindlin: c/a = (1 - Fx/(μF))^(1/3)
    assert float(items["stick_radius"][0]) == pytest.approx(a * (1 - 5.0 / (0.2 * F)) ** (1 / 3),
                                                            rel=SHOWN)
    assert items["gross_sliding"] == ("False", "")
    tor = c.torsion(force=F, twist=1e-4)
    assert repr(tor).startswith("TorsionState(method='exact', twist=0.0001 rad, torque=")
    assert float(_items(repr(tor))["torque"][0]) == pytest.approx(tor.torque, rel=SHOWN)
    w, Rs = 0.05, 5e-6
    ca = cl.Contact(Paraboloid(R=Rs), (cl.Rigid(), cl.Elastic(E=2e6, nu=0.5)),
                    work_of_adhesion=w)
    p = _items(repr(ca.pull_off()))
    assert float(p["force"][0]) == pytest.approx(-1.5 * math.pi * w * Rs, rel=SHOWN)   # JKR
