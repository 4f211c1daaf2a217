"""ContactLaw warns when a step's model error exceeds 1 % (issue 26 item 4), once per law and
quantity, never for an overflowed memory (it has its own warning), and not when silenced."""
from __future__ import annotations

import warnings

import numpy as np
import pytest

import contactlab as cl
from contactlab.effects.law import MODEL_ERROR_WARN
from contactlab.errors import ValidityWarning


def _law(**kw):
    return cl.ContactLaw(cl.profiles.Paraboloid, R=[0.01, 0.02], E_star=1.15e11, G_star=4.4e10,
                         G_torsion=4.0e10, friction=0.3, **kw)


def _run(law, steps=6):
    """Contact 0's force changes every step (springs), contact 1's stays (exact)."""
    outs, rec = [], []
    with warnings.catch_warnings(record=True) as w:
        warnings.simplefilter("always")
        law.step(force=[10.0, 20.0], twist=[1e-4, 1e-4], displacement=[0.0, 0.0])
        for k in range(steps):
            outs.append(law.step(force=[12.0 + k, 20.0], twist=[2e-4, 1e-4],
                                 displacement=[1e-7, 0.0]))
        rec = [str(x.message) for x in w if issubclass(x.category, ValidityWarning)
               and "model error" in str(x.message)]
    return outs, rec


@pytest.mark.parametrize("fast", [False, True])
def test_warns_once_per_quantity_above_one_percent(fast):
    if fast:
        pytest.importorskip("numba")
    outs, rec = _run(_law(springs=8, fast=fast))
    # 8 springs: the measured spring error 5.2 % (> 1 %) for both quantities
    assert max(float(np.max(o.model_errors["tangential_force"])) for o in outs) > MODEL_ERROR_WARN
    assert len(rec) == 2
    assert any("tangential force reached" in t for t in rec)
    assert any("torque reached" in t for t in rec)
    assert all("warn_model_error=False" in t for t in rec)
    # the text lands in the step's notes (the step that warned)
    assert any(o.notes for o in outs)


def test_no_warning_at_or_below_one_percent():
    """64 springs (1.1e-3) without twist: nothing to say."""
    law = _law(springs=64)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        law.step(force=[10.0, 20.0], displacement=[1e-7, 1e-7])
        out = law.step(force=[12.0, 20.0], displacement=[2e-7, 1e-7])
    assert not out.exact[0] and 0 < float(np.max(out.model_error)) <= MODEL_ERROR_WARN


def test_silenced_by_flag_and_attribute():
    outs, rec = _run(_law(springs=8, warn_model_error=False))
    assert rec == [] and float(np.max(outs[-1].model_error)) > MODEL_ERROR_WARN
    law = _law(springs=8)
    law.warn_model_error = False
    assert _run(law)[1] == []


def test_a_fresh_law_warns_again():
    assert len(_run(_law(springs=8))[1]) == 2
    assert len(_run(_law(springs=8))[1]) == 2
