"""A profile or contact that has been used pickles like a fresh one (process pools, distributed
sweeps): its per-object caches (some hold closures) stay behind and are rebuilt on first use."""
from __future__ import annotations

import pickle
import re
from pathlib import Path

import numpy as np
import pytest

import contactlab as cl
from contactlab import profiles as P
from contactlab.params import CACHE_KEYS

ROOT = Path(__file__).resolve().parents[2] / "contactlab"


class _OnlySlope(P.Profile):
    """A profile given only by f and f' (the quadrature route)."""

    def _height(self, r):
        return np.asarray(r, float) ** 2 / 0.02

    def _slope(self, r):
        return np.asarray(r, float) / 0.01


def _profiles():
    r = np.linspace(0.0, 1e-3, 200)
    return [P.Paraboloid(R=0.01), P.Sphere(R=0.01), P.PowerLaw(c=1e3, n=3), P.Cone(slope=0.1),
            P.FlatPunch(1e-4), P.Tabulated(r, r * r / 0.02),
            P.Tabulated(r, r * r / 0.02, interpolation="cubic"), _OnlySlope()]


def _use(contact):
    """The calls that fill the caches: scalar and batched normal solves, both controls."""
    depth = 1e-7 if not isinstance(contact.profile, P.FlatPunch) else 1e-8
    out = [contact.normal(depth=depth), contact.normal(depth=np.array([depth, 2 * depth]))]
    if not isinstance(contact.profile, P.FlatPunch):
        out += [contact.normal(force=0.01), contact.normal(force=np.array([0.01, 0.02]))]
    return [(s.radius, s.force, s.depth) for s in out]


@pytest.mark.parametrize("profile", _profiles(), ids=lambda p: type(p).__name__)
def test_used_contact_round_trips_through_pickle_with_the_same_bits(profile):
    contact = cl.Contact(profile, (cl.Elastic(E=1e9, nu=0.3), cl.Rigid()))
    first = _use(contact)
    clone = pickle.loads(pickle.dumps(contact))          # failed once caches held closures
    again = _use(clone)
    for a, b in zip(first, again):
        for x, y in zip(a, b):
            assert np.array_equal(np.asarray(x), np.asarray(y))
    assert not CACHE_KEYS & set(pickle.loads(pickle.dumps(profile)).__dict__)


def test_every_cache_key_in_the_sources_is_listed():
    """Every ``__dict__["_name"]`` cache the package writes is one :data:`CACHE_KEYS` names
    (otherwise a closure cached under a new name would break pickling again)."""
    pattern = re.compile(r'__dict__(?:\[|\.setdefault\(|\.get\()\s*"(_\w+)"|_\w*KEY\s*=\s*"(_\w+)"')
    found = set()
    for path in ROOT.rglob("*.py"):
        for m in pattern.finditer(path.read_text(encoding="utf-8")):
            found.add(m.group(1) or m.group(2))
    not_caches = {
        "__abstract__", "_cached",                      # class dictionaries, not objects'
        "_contact", "_model_errors_cache", "_model_errors_fn",   # a result's own state
        "_wbuf",            # a foundation's work buffer (a plain array; pickles)
        "_last",            # a fit model's warm start (a plain array; pickles)
    }
    found -= not_caches
    assert found, "the pattern matched nothing: the test reads the wrong files"
    assert found <= CACHE_KEYS, sorted(found - CACHE_KEYS)
