"""Every output of the load-path routes is bit-identical to the stored hashes
(``tests/integration/path_hashes.json``): the example scenes and a seeded set of generated load
paths through ``contact.simulate`` with ``method="mdr"`` on each backend and ``method="exact"``
(the cases: :mod:`tests.integration.path_hashes`).

The default run checks the example scenes and the first ``DEFAULT_PATHS`` (40) generated paths;
the slow job (``python -m pytest -m slow``) the rest of the ``N_PATHS`` (200).

A change meant to alter results regenerates the store with one command (then review its diff)::

    python tests/integration/path_hashes.py --overwrite

or only the keys a regular expression finds, e.g. the exact route's dissipated energy::

    python tests/integration/path_hashes.py --overwrite --match '\\|exact\\|.*(dissipated|energy)'
"""
from __future__ import annotations

import json

import pytest

from tests.integration import path_hashes as ph

STORED = ph.stored_hashes()
#: every case is named in the reference store whatever the machine
CASES = json.loads(ph.STORE.read_text())["hashes"]


#: the hashes hold one kind of machine's last bits: on a kind without a store, nothing to compare
needs_store = pytest.mark.skipif(
    STORED is None, reason=f"no stored hashes for this kind of machine ({ph.machine()!r}: the "
    "last bits follow the instruction set); write them here with: python "
    "tests/integration/path_hashes.py --overwrite")


def _check(case: str, got: dict[str, str]) -> None:
    assert STORED is not None
    want = {k: v for k, v in STORED.items() if ph.case_of(k) == case}
    assert want, f"no stored hashes for {case!r}: regenerate {ph.STORE.name}"
    missing = sorted(set(want) - set(got))
    differ = sorted(k for k in want if k in got and got[k] != want[k])
    assert not missing and not differ, (
        f"{case}: outputs changed: {differ[:20]}; no longer produced: {missing[:20]} "
        f"(meant? regenerate: python tests/integration/path_hashes.py --overwrite)")


@needs_store
@pytest.mark.parametrize("scene", ph.example_scenes(), ids=ph.scene_name)
def test_example_scene_outputs_are_unchanged(scene):
    _check(ph.scene_name(scene), ph.scene_case(scene))


def _label(i: int) -> str:
    return next((ph.case_of(k) for k in CASES if ph.path_index(k) == i), f"path{i:03d}")


@needs_store
@pytest.mark.parametrize("i", range(ph.DEFAULT_PATHS))
def test_generated_path_outputs_are_unchanged(i):
    _check(_label(i), ph.path_case(i))


@pytest.mark.slow
@needs_store
@pytest.mark.parametrize("i", range(ph.DEFAULT_PATHS, ph.N_PATHS))
def test_generated_path_outputs_are_unchanged_slow(i):
    _check(_label(i), ph.path_case(i))


def test_every_example_scene_is_stored():
    stored = {ph.case_of(k) for k in CASES if k.startswith("scene:")}
    assert stored == {ph.scene_name(f) for f in ph.example_scenes()}


def test_machine_stores():
    """The reference kind reads the reference hashes; another kind reads them with its own
    differing keys over them, or nothing without a store of its own."""
    doc = json.loads(ph.STORE.read_text())
    assert doc["machine"] in ("avx512", "avx2", "baseline")
    assert ph.stored_hashes(doc["machine"]) == doc["hashes"]
    assert ph.stored_hashes("no-such-kind") is None
    for f in ph.HERE.glob("path_hashes_*.json"):
        kind = json.loads(f.read_text())["machine"]
        assert f == ph.machine_store(kind) and kind != doc["machine"]
        diff = json.loads(f.read_text())["hashes"]
        assert diff and set(diff) <= set(doc["hashes"])
        merged = ph.stored_hashes(kind)
        assert merged is not None and all(merged[k] == v for k, v in diff.items())
        assert all(merged[k] == v for k, v in doc["hashes"].items() if k not in diff)
