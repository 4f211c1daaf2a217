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


#: keys whose stored hash for this kind predates a change measured on another kind (skipped here)
STALE = set(ph.stale_keys(ph.machine()))


def _check(case: str, got: dict[str, str]) -> None:
    assert STORED is not None
    want = {k: v for k, v in STORED.items() if ph.case_of(k) == case}
    stale = sorted(k for k in STALE if ph.case_of(k) == case)
    if not want and stale:
        pytest.skip(f"{case}: every stored hash is stale on this kind (moved by a change "
                    "measured on another kind): rewrite them here with python "
                    f"tests/integration/path_hashes.py --overwrite --match '{case}'")
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
    stale = set(doc.get("stale", ()))
    assert stale <= set(doc["hashes"])
    assert ph.stored_hashes(doc["machine"]) == {k: v for k, v in doc["hashes"].items()
                                                if k not in stale}
    # a stale reference hash was moved on another kind: that kind's store holds its new hash
    others = [json.loads(f.read_text())["hashes"] for f in ph.HERE.glob("path_hashes_*.json")]
    assert all(any(k in o for o in others) for k in stale)
    assert ph.stored_hashes("no-such-kind") is None
    for f in ph.HERE.glob("path_hashes_*.json"):
        kind = json.loads(f.read_text())["machine"]
        assert f == ph.machine_store(kind) and kind != doc["machine"]
        diff = json.loads(f.read_text())["hashes"]
        assert diff and set(diff) <= set(doc["hashes"])
        kind_stale = set(ph.stale_keys(kind))
        assert kind_stale <= set(doc["hashes"]) and not kind_stale & set(diff)
        merged = ph.stored_hashes(kind)
        assert merged is not None and all(merged[k] == v for k, v in diff.items())
        assert all(merged[k] == v for k, v in doc["hashes"].items()
                   if k not in diff and k not in kind_stale)
        assert not kind_stale & set(merged)


def test_a_change_measured_on_another_kind_leaves_the_reference_stale(tmp_path, monkeypatch):
    """Regenerating on a non-reference kind lists the keys the change moved there as stale in
    the reference store (the reference kind skips them); rewriting them on the reference kind
    measures them and clears them from the list."""
    ref = {"a|x": "1", "b|x": "2", "c|x": "3"}
    (tmp_path / "path_hashes.json").write_text(json.dumps(
        {"machine": "avx512", "n_paths": 0, "seed": 0, "hashes": ref}))
    (tmp_path / "path_hashes_avx2.json").write_text(json.dumps(
        {"machine": "avx2", "hashes": {"b|x": "2b"}}))
    monkeypatch.setattr(ph, "STORE", tmp_path / "path_hashes.json")
    monkeypatch.setattr(ph, "HERE", tmp_path)
    # measured on avx2: a unchanged, b and c moved
    assert ph._write_machine_store("avx2", {"a|x": "1", "b|x": "2c", "c|x": "3n"}, None) == 0
    assert ph.stale_keys() == ["b|x", "c|x"]
    assert ph.stored_hashes("avx512") == {"a|x": "1"}
    assert ph.stored_hashes("avx2") == {"a|x": "1", "b|x": "2c", "c|x": "3n"}
    # c measured on the reference kind: rewritten there and no longer stale
    monkeypatch.setattr(ph, "machine", lambda: "avx512")
    monkeypatch.setattr(ph, "compute", lambda n, cases=None: {"a|x": "1", "b|x": "2",
                                                              "c|x": "3r"})
    assert ph.main(["--overwrite", "--match", r"^c\|", "--cases", "c"]) == 0
    assert ph.stale_keys() == ["b|x"]
    assert ph.stored_hashes("avx512") == {"a|x": "1", "c|x": "3r"}


def test_a_change_measured_on_the_reference_kind_leaves_other_kinds_stale(tmp_path, monkeypatch):
    """Rewriting the reference store lists the keys the change moved as stale in every other
    kind's store (that kind skips them; its differing hashes for them are dropped), and a key the
    new reference now equals leaves that kind's differences; regenerating on that kind measures
    them and clears its list. A key stale in the reference (moved on another kind first) marks
    nothing when the reference kind measures it."""
    ref = {"a|x": "1", "b|x": "2", "c|x": "3", "d|x": "4", "e|x": "5"}
    (tmp_path / "path_hashes.json").write_text(json.dumps(
        {"machine": "avx512", "n_paths": 0, "seed": 0, "hashes": ref, "stale": ["e|x"]}))
    (tmp_path / "path_hashes_avx2.json").write_text(json.dumps(
        {"machine": "avx2", "hashes": {"b|x": "2b", "c|x": "3b", "e|x": "5b"}}))
    monkeypatch.setattr(ph, "STORE", tmp_path / "path_hashes.json")
    monkeypatch.setattr(ph, "HERE", tmp_path)
    monkeypatch.setattr(ph, "machine", lambda: "avx512")
    # measured on the reference kind: b and d moved by the change, c now equals avx2's hash,
    # e (stale, measured now) equals the hash avx2 measured after the change
    monkeypatch.setattr(ph, "compute", lambda n, cases=None: {
        "a|x": "1", "b|x": "2r", "c|x": "3b", "d|x": "4r", "e|x": "5b"})
    assert ph.main(["--overwrite", "--match", "x"]) == 0
    assert ph.stale_keys() == []
    assert ph.stale_keys("avx2") == ["b|x", "c|x", "d|x"]
    assert ph.stored_hashes("avx512") == {"a|x": "1", "b|x": "2r", "c|x": "3b", "d|x": "4r",
                                          "e|x": "5b"}
    assert ph.stored_hashes("avx2") == {"a|x": "1", "e|x": "5b"}
    # regenerated on avx2 for b only: measured there, no longer stale; the reference untouched
    monkeypatch.setattr(ph, "machine", lambda: "avx2")
    assert ph._write_machine_store("avx2", {"a|x": "1", "b|x": "2a", "c|x": "3b", "d|x": "4r",
                                            "e|x": "5b"}, r"^b\|") == 0
    assert ph.stale_keys() == [] and ph.stale_keys("avx2") == ["c|x", "d|x"]
    assert ph.stored_hashes("avx2") == {"a|x": "1", "b|x": "2a", "e|x": "5b"}
    # and the rest: c and d measured, nothing stale anywhere
    assert ph._write_machine_store("avx2", {"a|x": "1", "b|x": "2a", "c|x": "3b", "d|x": "4a",
                                            "e|x": "5b"}, None) == 0
    assert ph.stale_keys() == [] and ph.stale_keys("avx2") == []
    assert ph.stored_hashes("avx2") == {"a|x": "1", "b|x": "2a", "c|x": "3b", "d|x": "4a",
                                        "e|x": "5b"}
