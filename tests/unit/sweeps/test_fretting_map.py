"""fretting_map_sweep: the blocks of a fretting map on worker processes give the local map bit
for bit; the block decomposition itself moves results only at rounding level."""
from __future__ import annotations

import numpy as np
import pytest

import contactlab
from contactlab.effects import fretting as fr
from contactlab.errors import ParameterError, ValidityWarning
from contactlab.sweeps import fretting_map_sweep

from tests.tolerances import MAP_BLOCKS

CONTACT = contactlab.Contact(contactlab.profiles.Paraboloid(R=0.01),
                             materials=(contactlab.Elastic(E=210e9, nu=0.3),) * 2, friction=0.3)
TWIST = dict(force=np.geomspace(1.0, 1000.0, 7), twist_amplitude=np.geomspace(1e-5, 1e-2, 11))
SHIFT = dict(force=np.geomspace(1.0, 1000.0, 5), displacement_amplitude=np.geomspace(1e-8, 1e-4, 9))
FIELDS = ("regime", "energy_ratio", "energy", "stick_ratio", "peak", "boundary")


@pytest.fixture
def small_blocks(monkeypatch):
    """Blocks of 10 grid points and 2 boundary searches: every map here has several of each."""
    monkeypatch.setattr(fr, "MAP_BLOCK", 10)
    monkeypatch.setattr(fr, "BOUNDARY_BLOCK", 2)


def _bits(a, b):
    assert a == b
    for f in FIELDS:
        assert getattr(a, f).tobytes() == getattr(b, f).tobytes(), f


def test_blocks_change_the_map_only_at_rounding_level():
    one = CONTACT.fretting_map(**TWIST, method="exact")
    assert len(fr.plan_map(CONTACT, **TWIST, method="exact").blocks()) == 2     # loops, boundary
    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(fr, "MAP_BLOCK", 10)
        mp.setattr(fr, "BOUNDARY_BLOCK", 2)
        plan = fr.plan_map(CONTACT, **TWIST, method="exact")
        assert len(plan.blocks()) == 8 + 4
        many = CONTACT.fretting_map(**TWIST, method="exact")
    assert np.array_equal(one.regime, many.regime)
    for f in FIELDS[1:]:
        np.testing.assert_allclose(getattr(many, f), getattr(one, f), rtol=MAP_BLOCKS, atol=0)


@pytest.mark.parametrize("kw, method", [(TWIST, "exact"), (SHIFT, None)])
def test_serial_and_process_pool_give_the_local_map_bit_for_bit(small_blocks, kw, method):
    local = CONTACT.fretting_map(**kw, method=method)
    _bits(fretting_map_sweep(CONTACT, **kw, method=method, workers=1), local)
    _bits(fretting_map_sweep(CONTACT, **kw, method=method, workers=2), local)


def test_the_mdr_validity_warning_is_raised_here_at_the_callers_line(small_blocks):
    with pytest.warns(ValidityWarning) as local:
        a = CONTACT.fretting_map(**TWIST, method="mdr")
    with pytest.warns(ValidityWarning) as swept:
        b = fretting_map_sweep(CONTACT, **TWIST, method="mdr", workers=1)
    _bits(a, b)
    assert [str(w.message) for w in swept] == [str(w.message) for w in local]
    assert {w.filename for w in swept} == {w.filename for w in local} == {__file__}


def test_bad_input_fails_before_any_work():
    with pytest.raises(ParameterError, match="twist_amplitude"):
        fretting_map_sweep(CONTACT, force=[1.0], twist_amplitude=[-1e-3], workers=2)
    with pytest.raises(ParameterError, match="workers=0"):
        fretting_map_sweep(CONTACT, **TWIST, workers=0)
    assert contactlab.fretting_map_sweep is fretting_map_sweep
