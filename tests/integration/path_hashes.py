"""SHA-256 hashes of every output array of the load-path routes: the guard of refactors that must
keep results bit-identical (tests/integration/test_path_hashes.py compares against
``path_hashes.json`` beside this file).

The cases:

* every example scene (``examples/**/*.toml``): the series and fields of ``Scene.run()``; for a
  scene on the foundation route also ``contact.simulate`` of its load path with each method
  (``"mdr"`` on each backend of the compiled spring kernels, ``"exact"``);
* a generated set of :data:`N_PATHS` load paths (seeded: ramps, holds, sinusoids, tables; force
  or depth control; twist, torque, shift or tangential force; a normal load held or varying;
  several profiles, frictions and discretisation options) through ``contact.simulate`` with
  ``method="mdr"`` on each backend and with ``method="exact"`` (a shifted path records the
  error ``method="exact"`` raises).

Each run records, per key ``case|backend|method|output``: the hash of each series, each snapshot
entry and each array or number in ``meta`` (a failed run: its error type and the hashes of its
partial result), and the ValidityWarning categories it emitted.

The last bits of some outputs depend on the machine: numpy picks its vectorised cube roots,
powers and exponentials by the CPU's instruction set (AVX-512 or AVX2 builds round differently
in the last place), and OpenBLAS its kernels (by CPU model: on AMD Zen 5 its AVX2 kernels beside
numpy's AVX-512 loops, a kind of its own). ``path_hashes.json`` holds the hashes of one kind
of machine (its ``machine`` entry, :func:`machine`); ``path_hashes_<kind>.json`` holds, for each
other kind measured, the keys whose hash differs there. The test compares against the store of
the machine it runs on and is skipped, saying so, on a kind that has none (the command below run
there writes one).

Regenerate (after a change that is meant to alter results; review the diff of the JSON)::

    python tests/integration/path_hashes.py --overwrite              # every case
    python tests/integration/path_hashes.py --overwrite --match 'exact\\|.*dissipated_energy'
    python tests/integration/path_hashes.py --overwrite --match 'viscoelastic_creep' \\
        --cases 'viscoelastic_creep'                                 # compute those cases only

On a machine of the reference kind this rewrites ``path_hashes.json``; on another kind it
writes that kind's ``path_hashes_<kind>.json`` (the keys that differ from the reference), and
the keys a change moved there are listed as ``stale`` in ``path_hashes.json``: their reference
hash predates the change, so the reference kind skips them (saying so) until the command is run
on such a machine, which measures them and clears the list. The other way round, a change
measured on the reference kind lists the keys it moved as ``stale`` in every other kind's store
(their hash there predates the change, so that kind skips them) until the command is run on a
machine of that kind.
``--match REGEX`` recomputes every case but rewrites only the stored keys the regular expression
finds (``re.search``) and adds none; the other stored hashes are kept. ``--paths N`` limits the
generated set to its first ``N`` paths (the default test run uses :data:`DEFAULT_PATHS`).
"""
from __future__ import annotations

import argparse
import glob
import hashlib
import json
import re
import sys
import warnings
from pathlib import Path
from typing import Any

import numpy as np

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[1]
STORE = HERE / "path_hashes.json"
#: generated paths in the store (the slow job checks all of them)
N_PATHS = 200
#: generated paths checked by the default test run (the first ones of the set)
DEFAULT_PATHS = 40
SEED = 20261128


# ---------------------------------------------------------------------------------- machines
def machine() -> str:
    """The kind of machine whose last bits the hashes are: ``"avx512"``, ``"avx2"`` or
    ``"baseline"``, from the instruction sets numpy dispatches its vectorised loops on
    (:func:`contactlab.numeric.simd.machine_kind`)."""
    from contactlab.numeric.simd import machine_kind
    return machine_kind()


def machine_store(kind: str) -> Path:
    """The file of the keys whose hash differs on machines of ``kind`` from the reference."""
    return HERE / f"path_hashes_{kind}.json"


def stored_hashes(kind: str | None = None) -> dict[str, str] | None:
    """The stored hashes for machines of ``kind`` (default: this machine), or None where that
    kind has no store."""
    kind = machine() if kind is None else kind
    doc = json.loads(STORE.read_text())
    hashes = dict(doc["hashes"])
    if kind == doc.get("machine", kind):
        for k in doc.get("stale", ()):     # moved by a change measured on another kind only
            hashes.pop(k, None)
        return hashes
    other = machine_store(kind)
    if not other.exists():
        return None
    doc = json.loads(other.read_text())
    hashes.update(doc["hashes"])
    for k in doc.get("stale", ()):         # moved by a change measured on the reference kind only
        hashes.pop(k, None)
    return hashes


# ---------------------------------------------------------------------------------- hashing
def digest(value: Any) -> str:
    """Hash of an array or number (dtype, shape and bytes), or of a string/None."""
    if value is None or isinstance(value, str):
        return hashlib.sha256(repr(value).encode()).hexdigest()[:32]
    arr = np.ascontiguousarray(np.asarray(value))
    h = hashlib.sha256(f"{arr.dtype.str}{arr.shape}".encode())
    h.update(arr.tobytes())
    return h.hexdigest()[:32]


def _flatten(prefix: str, obj: Any, out: dict[str, str]) -> None:
    if isinstance(obj, dict):
        for k in sorted(obj, key=str):
            _flatten(f"{prefix}.{k}", obj[k], out)
    elif isinstance(obj, (list, tuple)) and not all(isinstance(v, (int, float, np.number))
                                                      for v in obj):
        out[prefix] = digest(repr(obj))
    elif isinstance(obj, (np.ndarray, int, float, bool, np.number, np.bool_, list, tuple)):
        out[prefix] = digest(obj)
    elif obj is None or isinstance(obj, str):
        out[prefix] = digest(obj)


def result_hashes(res: Any) -> dict[str, str]:
    """Hashes of a PathResult: series, snapshots, numeric meta (the foundation's repr and the
    citations excluded: text, not results)."""
    out: dict[str, str] = {}
    for k, v in res.data.items():
        out[f"series.{k}"] = digest(v)
    for s, snap in res.snapshots.items():
        _flatten(f"snapshot.{s}", snap, out)
    for k, v in res.meta.items():
        if k in ("foundation", "citations", "error"):
            continue
        _flatten(f"meta.{k}", v, out)
    return out


def _run(fn) -> dict[str, str]:
    """Hashes of ``fn()``'s result, or of its error (type, partial result); warning kinds."""
    from contactlab.errors import ContactlabError
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        try:
            out = result_hashes(fn())
        except ContactlabError as err:
            out = {"error": type(err).__name__}
            part = getattr(err, "partial", None)
            if hasattr(part, "data"):
                out.update({f"partial.{k}": v for k, v in result_hashes(part).items()})
    kinds = sorted({w.category.__name__ for w in caught})
    if kinds:
        out["warnings"] = ",".join(kinds)
    return out


def _backends() -> list[str]:
    from contactlab.foundation import _compiled
    return list(_compiled.available())


def _simulate_all(case: str, contact: Any, path: Any, kw_mdr: dict, kw_exact: dict,
                  out: dict[str, str]) -> None:
    """``contact.simulate`` with method "mdr" per backend and "exact"; hashes into ``out``."""
    from contactlab.foundation import _compiled
    try:
        for b in _backends():
            _compiled.set_backend(b)
            for k, v in _run(lambda: contact.simulate(path, method="mdr", **kw_mdr)).items():
                out[f"{case}|{b}|mdr|{k}"] = v
    finally:
        _compiled.set_backend(None)
    for k, v in _run(lambda: contact.simulate(path, method="exact", **kw_exact)).items():
        out[f"{case}|any|exact|{k}"] = v


# ---------------------------------------------------------------------------------- scenes
def example_scenes() -> list[Path]:
    return sorted(Path(p) for p in glob.glob(str(ROOT / "examples" / "**" / "*.toml"),
                                             recursive=True))


def scene_case(f: Path) -> dict[str, str]:
    """Hashes of the example scene ``f``."""
    from contactlab.scene import Scene
    out: dict[str, str] = {}
    case = scene_name(f)
    sc = Scene.from_toml(f)
    for k, v in _run(lambda: _SceneAsResult(sc.run())).items():
        out[f"{case}|any|run|{k}"] = v
    if sc.plan().route == "foundation":
        kw = ({"n_springs": sc.solver["n_springs"]} if "n_springs" in sc.solver else {})
        _simulate_all(case, sc.contact(), sc.load_path, kw, {}, out)
    return out


def scene_name(f: Path) -> str:
    return "scene:" + f.relative_to(ROOT / "examples").as_posix()


class _SceneAsResult:
    """A SceneResult seen as a PathResult for hashing (series, fields)."""

    def __init__(self, r: Any) -> None:
        self.data = dict(r.series)
        self.snapshots = {"fields": dict(r.fields)} if r.fields else {}
        self.meta = {}
        if r.wear is not None:
            self.meta["wear"] = {k: v for k, v in r.wear.to_dict().items()}
        if r.fretting_map is not None:
            self.meta["fretting_map"] = {k: v for k, v in r.fretting_map.to_dict().items()}


# ---------------------------------------------------------------------------------- paths
def _contacts() -> list[tuple[str, Any]]:
    import contactlab as cl
    from contactlab import profiles as P
    steel = cl.Elastic(E=210e9, nu=0.3)
    poly = cl.Elastic(E=1e9, nu=0.46)
    r = np.linspace(0.0, 2e-3, 200)
    return [
        ("paraboloid", cl.Contact(P.Paraboloid(R=0.01), materials=(steel, steel), friction=0.3)),
        ("paraboloid-nofriction", cl.Contact(P.Paraboloid(R=0.01), materials=(steel, steel))),
        ("cone", cl.Contact(P.Cone(slope=0.02), materials=(steel, poly), friction=0.2)),
        ("sphere", cl.Contact(P.Sphere(R=0.005), materials=(steel, steel), friction=0.1)),
        ("table", cl.Contact(P.Tabulated(r=r, f=r**2 / 0.02 + 1e3 * r**3),
                             materials=(steel, steel), friction=0.3)),
        ("flat-punch", cl.Contact(P.FlatPunch(radius=2e-4), materials=(steel, steel),
                                  friction=0.3)),
        ("truncated-paraboloid", cl.Contact(P.TruncatedParaboloid(radius=1e-4, R=0.01),
                                            materials=(steel, steel), friction=0.3)),
    ]


def _normal_scale(contact: Any, rng: np.random.Generator) -> tuple[float, float, float]:
    """(force, depth, radius) of a moderate normal load of ``contact``."""
    if contact.profile.wall_radius < np.inf:
        d = float(rng.uniform(0.5e-6, 2e-6))
        s = contact.normal(depth=d)
        return float(s.force), d, float(s.radius)
    F = float(rng.uniform(5.0, 60.0))
    s = contact.normal(force=F)
    return F, float(s.depth), float(s.radius)


def make_path(i: int) -> tuple[str, Any, Any, dict, dict]:
    """Generated path ``i``: (contact name, contact, LoadPath, mdr kwargs, exact kwargs)."""
    import contactlab as cl
    rng = np.random.default_rng([SEED, i])
    contacts = _contacts()
    name, contact = contacts[int(rng.integers(len(contacts)))]
    F, d, a = _normal_scale(contact, rng)
    mu = contact.friction if contact.friction is not None else 0.3
    nctrl = "force" if rng.random() < 0.6 else "depth"
    N = F if nctrl == "force" else d
    kind = rng.choice(["twist", "torque", "displacement", "tangential_force", "both", "none"],
                      p=[0.3, 0.2, 0.15, 0.15, 0.05, 0.15])
    tw_scale = 1.5 * mu * d / a                    # about the sliding twist
    sh_scale = 1.5 * mu * d                        # about the sliding shift
    M_scale = 0.6 * mu * F * a                     # about the sliding torque
    T_scale = mu * F                               # the sliding force
    if kind == "twist":
        axes = {"twist": tw_scale}
    elif kind == "torque":
        axes = {"torque": M_scale}
    elif kind == "displacement":
        axes = {"displacement": sh_scale}
    elif kind == "tangential_force":
        axes = {"tangential_force": T_scale}
    elif kind == "both":
        axes = {"twist": tw_scale, "displacement": sh_scale}
    else:
        axes = {}
    force_ctrl = any(k in axes for k in ("torque", "tangential_force"))
    path = cl.LoadPath().ramp(steps=int(rng.integers(3, 40)), **{nctrl: N})
    level = {k: 0.0 for k in axes}
    n_seg = int(rng.integers(1, 5))
    for _ in range(n_seg):
        seg = rng.choice(["ramp", "hold", "sinusoid", "table"], p=[0.35, 0.15, 0.3, 0.2])
        vary = rng.random() < 0.6                 # the normal load changes in this segment
        steps = int(rng.integers(5, 80))
        if seg == "hold":
            path = path.hold(steps=steps)
        elif seg == "ramp":
            tg = {k: float(s * rng.uniform(-1.1 if not force_ctrl else -0.95,
                                           1.1 if not force_ctrl else 0.95))
                  for k, s in axes.items()}
            if vary:
                tg[nctrl] = float(N * rng.uniform(0.4, 1.6))
            if not tg:
                tg[nctrl] = float(N * rng.uniform(0.4, 1.6))
            level.update({k: v for k, v in tg.items() if k in level})
            path = path.ramp(steps=steps, **tg)
        elif seg == "sinusoid":
            amp = {k: float(s * rng.uniform(0.1, 0.8)) for k, s in axes.items()}
            if vary or not amp:
                amp[nctrl] = float(N * rng.uniform(0.05, 0.5))
            path = path.sinusoid(cycles=float(rng.choice([0.5, 1.0, 1.75, 3.0])),
                                 steps_per_cycle=int(rng.integers(8, 60)), **amp)
        else:
            cols = {}
            t = np.cumsum(rng.uniform(0.2, 1.0, steps))
            for k, s in axes.items():
                cols[k] = np.cumsum(rng.normal(0.0, 0.15 * s, steps)).clip(-0.95 * s, 0.95 * s)
            if vary or not cols:
                cols[nctrl] = N * (1.0 + np.cumsum(rng.normal(0.0, 0.05, steps))).clip(0.2, 1.8)
            path = path + cl.LoadPath.from_arrays(time=t, **cols)
    mdr: dict[str, Any] = {}
    exact: dict[str, Any] = {}
    u = rng.random(6)
    mdr["n_springs"] = [None, 64, 301][int(rng.integers(3))]
    exact["n_rings"] = [None, 24, 61][int(rng.integers(3))]
    if u[0] < 0.2:
        mdr["spacing"] = "uniform"
    if u[1] < 0.2:
        mdr["strategy"] = "steps"
    if u[2] < 0.25:
        n = path.n_steps
        mdr["snapshots"] = exact["snapshots"] = [0, n // 2, -1]
    if u[3] < 0.15:
        mdr["error_estimate"] = exact["error_estimate"] = True
    if u[4] < 0.15:
        outs = ["force", "torque", "twist", "stick_radius"] if "twist" in axes or "torque" in axes \
            else ["depth", "tangential_force", "dissipated_energy"]
        mdr["outputs"] = exact["outputs"] = outs
    if kind == "both":
        mdr["approximate"] = True
    return f"{name}:{kind}:{nctrl}", contact, path, mdr, exact


def path_case(i: int) -> dict[str, str]:
    """Hashes of generated path ``i``."""
    out: dict[str, str] = {}
    label, contact, path, kw_mdr, kw_exact = make_path(i)
    _simulate_all(f"path{i:03d}:{label}", contact, path, kw_mdr, kw_exact, out)
    return out


def case_of(key: str) -> str:
    return key.split("|", 1)[0]


def path_index(key: str) -> int | None:
    m = re.match(r"path(\d+):", key)
    return int(m.group(1)) if m else None


def compute(n_paths: int = N_PATHS, cases: str | None = None) -> dict[str, str]:
    """Every hash: the example scenes and the first ``n_paths`` generated paths (``cases``: only
    the cases whose name this regular expression finds, ``re.search``)."""
    pat = None if cases is None else re.compile(cases)
    out: dict[str, str] = {}
    for f in example_scenes():
        if pat is None or pat.search(scene_name(f)):
            out.update(scene_case(f))
    for i in range(n_paths):
        if pat is None or pat.search(f"path{i:03d}:{make_path(i)[0]}"):
            out.update(path_case(i))
    return out


def stale_keys(kind: str | None = None) -> list[str]:
    """The keys whose stored hash for machines of ``kind`` (default: the reference kind)
    predates a change measured on another kind: in the reference store, keys moved on another
    kind (:func:`_write_machine_store`); in another kind's store, keys moved on the reference kind
    (:func:`_mark_other_kinds`). Not compared on that kind until its store is rewritten there."""
    doc = json.loads(STORE.read_text())
    if kind is None or kind == doc.get("machine", kind):
        return list(doc.get("stale", ()))
    other = machine_store(kind)
    return list(json.loads(other.read_text()).get("stale", ())) if other.exists() else []


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--overwrite", action="store_true",
                    help=f"rewrite {STORE.name} (required when it exists)")
    ap.add_argument("--match", default=None,
                    help="rewrite only the stored keys this regular expression finds")
    ap.add_argument("--paths", type=int, default=N_PATHS, help="generated paths (default all)")
    ap.add_argument("--cases", default=None,
                    help="compute only the cases whose name this regular expression finds "
                         "(with --match: the cases that hold its keys)")
    args = ap.parse_args(argv)
    if STORE.exists() and not args.overwrite:
        print(f"{STORE} exists: pass --overwrite to rewrite it", file=sys.stderr)
        return 2
    if args.cases is not None and args.match is None:
        print("--cases needs --match (the other stored hashes are kept)", file=sys.stderr)
        return 2
    new = compute(args.paths, args.cases)
    kind = machine()
    if STORE.exists() and json.loads(STORE.read_text()).get("machine", kind) != kind:
        return _write_machine_store(kind, new, args.match)
    n_paths = args.paths
    stale: list[str] = []
    previous = json.loads(STORE.read_text()) if STORE.exists() else {"hashes": {}}
    if args.match is not None and STORE.exists():
        pat = re.compile(args.match)
        old = previous
        stored, n_paths = dict(old["hashes"]), old["n_paths"]
        changed = 0
        for k in stored:
            if pat.search(k) and k in new and stored[k] != new[k]:
                stored[k] = new[k]
                changed += 1
        new = stored
        # measured here now: no longer stale
        stale = [k for k in old.get("stale", ()) if not (pat.search(k) and k in new)]
        print(f"{changed} stored hashes rewritten")
    _mark_other_kinds(previous, new)
    doc = {"about": "sha256 (first 32 hex) of every output of the load-path routes; "
                    "regenerate with: python tests/integration/path_hashes.py --overwrite",
           "machine": kind, "n_paths": n_paths, "seed": SEED,
           "hashes": dict(sorted(new.items()))}
    if stale:
        doc["stale"] = sorted(stale)
    STORE.write_text(json.dumps(doc, indent=0, sort_keys=False) + "\n")
    print(f"{len(new)} hashes written to {STORE} (machine kind {kind!r}; the stores of other "
          "kinds are not rewritten: regenerate them on such a machine)")
    return 0


def _mark_other_kinds(previous: dict[str, Any], new: dict[str, str]) -> None:
    """After the reference store is rewritten: in each other kind's store, list as ``stale`` the
    keys whose reference hash this change moved (their hash on that kind predates the change, so
    that kind skips them until its store is rewritten there), and drop the differing hashes the
    new reference now equals. A key that was stale in the reference (moved on another kind
    first) is measured now and marks nothing: that kind's hash already follows the change."""
    was_stale = set(previous.get("stale", ()))
    old = previous["hashes"]
    moved = {k for k, v in new.items() if k in old and old[k] != v and k not in was_stale}
    for path in sorted(HERE.glob("path_hashes_*.json")):
        doc = json.loads(path.read_text())
        diff = {k: v for k, v in doc["hashes"].items() if k not in moved and new.get(k) != v}
        kind_stale = sorted((set(doc.get("stale", ())) | moved) & set(new))
        if diff == doc["hashes"] and kind_stale == sorted(doc.get("stale", ())):
            continue
        doc["hashes"] = dict(sorted(diff.items()))
        if kind_stale:
            doc["stale"] = kind_stale
        else:
            doc.pop("stale", None)
        path.write_text(json.dumps(doc, indent=0, sort_keys=False) + "\n")
        print(f"{len(kind_stale)} hashes marked stale in {path.name} (moved here; rewrite them on "
              f"a machine of kind {doc['machine']!r})")


def _write_machine_store(kind: str, new: dict[str, str], match: str | None) -> int:
    """Write ``path_hashes_<kind>.json``: the keys whose hash on this machine differs from the
    reference store's (with ``match``, only the keys it finds are rewritten).

    A key whose hash here moved from the one this kind had (a change meant to alter results,
    measured on this kind only) has a reference hash that predates the change: it is listed in
    the reference store's ``stale`` keys, which the reference kind does not compare until its
    own store is rewritten there (:func:`stale_keys`)."""
    ref_doc = json.loads(STORE.read_text())
    ref = ref_doc["hashes"]
    path = machine_store(kind)
    old_doc = json.loads(path.read_text()) if path.exists() else {"hashes": {}}
    old = old_doc["hashes"]
    kind_stale = set(old_doc.get("stale", ()))   # moved on the reference kind: measured now
    pat = None if match is None else re.compile(match)
    diff = dict(old)
    moved = set(ref_doc.get("stale", ()))
    for k, v in new.items():
        if k in ref and (pat is None or pat.search(k)):
            if path.exists() and k not in kind_stale and v != old.get(k, ref[k]):
                moved.add(k)
            kind_stale.discard(k)
            if v != ref[k]:
                diff[k] = v
            else:
                diff.pop(k, None)
    if moved != set(ref_doc.get("stale", ())):
        ref_doc["stale"] = sorted(moved)
        STORE.write_text(json.dumps(ref_doc, indent=0, sort_keys=False) + "\n")
        print(f"{len(moved)} reference hashes marked stale in {STORE.name} (moved here; "
              "rewrite them on a machine of the reference kind)")
    doc = {"about": f"the hashes that differ on machines of kind {kind!r} from path_hashes.json "
                    "(numpy's vectorised loops and OpenBLAS's kernels by instruction set); "
                    "regenerate on such a machine with: python tests/integration/path_hashes.py "
                    "--overwrite",
           "machine": kind, "hashes": dict(sorted(diff.items()))}
    if kind_stale:
        doc["stale"] = sorted(kind_stale)
    path.write_text(json.dumps(doc, indent=0, sort_keys=False) + "\n")
    print(f"{len(diff)} of {len(ref)} hashes differ on this {kind!r} machine: written to {path}")
    return 0


if __name__ == "__main__":
    sys.path.insert(0, str(ROOT))
    sys.exit(main())
