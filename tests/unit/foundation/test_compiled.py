"""The compiled foundation kernel (issue 13) against its numpy reference, and whole paths through
simulate() with both backends."""
import contextlib

import numpy as np
import pytest

import contactlab as cl
from contactlab.errors import ParameterError, ValidityWarning
from contactlab.foundation import _compiled
from contactlab.loadpath import LoadPath
from tests.tolerances import BACKENDS_AGREE


def test_jenkins_update_matches_the_numpy_reference(foundation_backend):
    rng = np.random.default_rng(7)
    n = 5000
    K = rng.uniform(0.5, 2.0, n)
    L = rng.uniform(0.0, 1.0, n)
    m0 = np.clip(rng.normal(0, 0.5, n), -L, L)
    for inc in (0.0, 0.3, -1.7, 1e-9):
        m_ref, m = m0.copy(), m0.copy()
        w_ref = _compiled.jenkins_update_numpy(m_ref, K, 1 / K, L, inc)
        w = _compiled.jenkins_update(m, K, 1 / K, L, inc)
        assert np.array_equal(m, m_ref)                         # the clip is exact
        assert abs(w - w_ref) <= BACKENDS_AGREE * max(abs(w_ref), 1e-300)
        # dissipation = Σ L |slip|, slip = (trial - m)/K, over the elements that slid
        trial = m0 + K * inc
        assert abs(w_ref - np.sum(np.abs(trial - m_ref) * L / K)) <= 1e-12 * max(abs(w_ref), 1e-300)


def test_numpy_update_in_chunks_is_bit_identical(monkeypatch):
    """Long vectors run the numpy update a chunk at a time: chunks of 7 elements change no bit
    of the element forces or the dissipated energy (the final sum is over the whole vector)."""
    rng = np.random.default_rng(3)
    n = 1001
    K = rng.uniform(0.5, 2.0, n)
    invK, L = 1 / K, rng.uniform(0.0, 1.0, n)
    out = {}
    for chunk in (10**9, 7):
        monkeypatch.setattr(_compiled, "NUMPY_CHUNK", chunk)
        m, W = np.zeros(n), []
        for inc in (0.3, -0.5, 0.2, 0.0, -0.1):
            W.append(_compiled.jenkins_update_numpy(m, K, invK, L, inc))
        out[chunk] = (m, W)
    assert np.array_equal(out[10**9][0], out[7][0]) and out[10**9][1] == out[7][1]


def test_unknown_backend_is_rejected():
    with pytest.raises(ParameterError, match="backend"):
        _compiled.set_backend("fortran")


def _gait(kind):
    """Gait-like: the normal force and the twist (or shift) change at every step."""
    t = np.linspace(0, 1, 401)
    extra = ({"twist": 2e-4 * np.sin(6 * np.pi * t)} if kind == "twist"
             else {"displacement": 1e-7 * np.sin(4 * np.pi * t)})
    return LoadPath.from_arrays(time=t, force=50 + 40 * np.sin(2 * np.pi * t), **extra)


@pytest.mark.parametrize("kind", ["twist", "shift"])
def test_simulate_agrees_between_backends(foundation_backend, kind):
    if "numba" not in _compiled.available():
        pytest.skip("numba is not installed (extra 'fast')")
    c = cl.Contact(cl.profiles.Paraboloid(R=0.01), (cl.Elastic(E=210e9, nu=0.3),) * 2,
                   friction=0.3)
    out = {}
    for name in ("numpy", "numba"):
        _compiled.set_backend(name)
        out[name] = c.simulate(_gait(kind), method="mdr")
    a, b = out["numpy"], out["numba"]
    keys = ("torque",) if kind == "twist" else ("tangential_force",)
    for key in ("force", "dissipated_energy", "stick_radius") + keys:
        x, y = np.asarray(getattr(a, key)), np.asarray(getattr(b, key))
        assert np.all(np.abs(x - y) <= BACKENDS_AGREE * np.max(np.abs(x))), key


def _paths():
    """Paths that exercise the fused compiled step: depth up and down while twisted/shifted,
    snapshots inside a run, held stretches between runs, force control mixed in."""
    t = np.linspace(0, 1, 301)
    up_down = LoadPath.from_arrays(time=t, force=60 - 50 * np.abs(np.sin(3 * np.pi * t)),
                                   twist=3e-4 * np.sin(5 * np.pi * t))
    mixed = (LoadPath().ramp(force=50.0, steps=20).ramp(twist=2e-4, steps=30)
             .sinusoid(force=30.0, twist=1e-4, cycles=2, steps_per_cycle=40)
             .hold(steps=10).ramp(force=5.0, steps=25))
    shift = (LoadPath().ramp(force=40.0, steps=10)
             .sinusoid(force=20.0, displacement=1e-7, cycles=3, steps_per_cycle=30))
    torque = (LoadPath().ramp(force=40.0, steps=10).ramp(torque=1e-3, steps=10)
              .sinusoid(force=20.0, cycles=1, steps_per_cycle=30))
    return {"up_down": up_down, "mixed": mixed, "shift": shift, "torque": torque}


@pytest.mark.parametrize("name", ["up_down", "mixed", "shift", "torque"])
@pytest.mark.parametrize("kw", [{}, {"strategy": "steps", "snapshots": [7, 45, -1]},
                                {"spacing": "uniform", "n_springs": 301}])
def test_fused_step_agrees_with_numpy(foundation_backend, name, kw):
    """Every series and snapshot of the numba backend (fused step) within BACKENDS_AGREE of the
    numpy reference, relative to the series' largest value."""
    if "numba" not in _compiled.available():
        pytest.skip("numba is not installed (extra 'fast')")
    c = cl.Contact(cl.profiles.Paraboloid(R=0.01), (cl.Elastic(E=210e9, nu=0.3),) * 2,
                   friction=0.3)
    path = _paths()[name]
    out = {}
    for b in ("numpy", "numba"):
        _compiled.set_backend(b)
        # the torque path twists beyond the MDR springs' validity while the force changes
        with (pytest.warns(ValidityWarning, match="method='exact'") if name == "torque"
              else contextlib.nullcontext()):
            out[b] = c.simulate(path, **kw, method="mdr")
    a, b = out["numpy"], out["numba"]
    for key, x in a.data.items():
        x, y = np.asarray(x, float), np.asarray(b.data[key], float)
        scale = max(float(np.max(np.abs(x))), 1e-300)
        assert np.all(np.abs(x - y) <= BACKENDS_AGREE * scale), (name, key)
    for step, snap in a.snapshots.items():
        for key, x in snap.items():
            if x is None or np.ndim(x) == 0:
                assert b.snapshots[step][key] == x
                continue
            x, y = np.asarray(x, float), np.asarray(b.snapshots[step][key], float)
            scale = max(float(np.max(np.abs(x))), 1e-300)
            assert np.all(np.abs(x - y) <= BACKENDS_AGREE * scale), (name, step, key)


# the torque path goes beyond the MDR springs' validity twist (ValidityWarning): not the subject
@pytest.mark.filterwarnings("ignore::contactlab.errors.ValidityWarning")
@pytest.mark.parametrize("name", ["up_down", "mixed", "shift", "torque"])
def test_fused_step_in_small_blocks(monkeypatch, name):
    """The fused step runs the springs in blocks (each block through every step of a run):
    blocks of 7 springs (a remainder and a partial unrolled group per block) against one pass
    give bit-identical element forces (snapshots) and stick radius, sums within BACKENDS_AGREE."""
    if "numba" not in _compiled.available():
        pytest.skip("numba is not installed (extra 'fast')")
    c = cl.Contact(cl.profiles.Paraboloid(R=0.01), (cl.Elastic(E=210e9, nu=0.3),) * 2,
                   friction=0.3)
    path = _paths()[name]
    out = {}
    try:
        _compiled.set_backend("numba")
        for block in (10**6, 7):
            monkeypatch.setattr(_compiled, "FUSED_BLOCK", block)
            monkeypatch.setattr(_compiled, "FUSED_BLOCK_FROM", min(block, 10**6))
            out[block] = c.simulate(path, n_springs=301, snapshots=[7, 45, -1], method="mdr")
    finally:
        _compiled.set_backend(None)
    a, b = out[10**6], out[7]
    for key, x in a.data.items():
        x, y = np.asarray(x, float), np.asarray(b.data[key], float)
        if key in ("stick_radius", "twist", "displacement", "depth", "force", "radius", "time"):
            assert np.array_equal(x, y), (name, key)
        scale = max(float(np.max(np.abs(x))), 1e-300)
        assert np.all(np.abs(x - y) <= BACKENDS_AGREE * scale), (name, key)
    for step, snap in a.snapshots.items():
        for key, x in snap.items():
            assert np.array_equal(np.asarray(x), np.asarray(b.snapshots[step][key])), (step, key)


def test_fused_step_is_deterministic(foundation_backend):
    c = cl.Contact(cl.profiles.Paraboloid(R=0.01), (cl.Elastic(E=210e9, nu=0.3),) * 2,
                   friction=0.3)
    path = _paths()["up_down"]
    r1, r2 = c.simulate(path, method="mdr"), c.simulate(path, method="mdr")
    for key in r1.data:
        assert np.array_equal(r1.data[key], r2.data[key]), key


@pytest.mark.parametrize("needs", [("torsion",), ("tangential",)])
@pytest.mark.parametrize("spacing", ["edge", "uniform"])
@pytest.mark.parametrize("profile", [
    cl.profiles.Paraboloid(R=0.01),           # one power term, whole n+1, n+2: in the pass
    cl.profiles.Cone(slope=0.01),             # n = 1: powers 2 and 3 in the pass
    cl.profiles.PowerLaw(c=50.0, n=2.5),      # non-whole powers: integrals passed in
    cl.profiles.Sphere(R=0.01),               # no power terms: integrals passed in
], ids=["hertz", "cone", "n2.5", "sphere"])
def test_compiled_edge_data_is_bit_identical(needs, spacing, profile):
    """Winkler.edge_data with the numba backend (edge cell search and partial integrals in one
    compiled pass; one power term's integrals computed there) gives the numpy reference's cells
    and integrals bit for bit, for radii in random order, on cell boundaries, at 0 and beyond
    the foundation's radius."""
    if "numba" not in _compiled.available():
        pytest.skip("numba is not installed (extra 'fast')")
    from contactlab.foundation import Winkler
    c = cl.Contact(profile, (cl.Elastic(E=210e9, nu=0.3),) * 2, friction=0.3)
    fnd = Winkler(c.profile, c.moduli, c.friction, 1e-4, n_springs=37, spacing=spacing,
                  needs=needs, rtol=c.rtol)
    rng = np.random.default_rng(5)
    a = np.concatenate((rng.uniform(0, 1.2e-4, 300), np.sort(rng.uniform(0, 1e-4, 300)),
                        fnd.boundaries, [0.0, 1e-4, 2e-4]))
    d = c.profile._g(np.minimum(a, 1e-4)) * rng.uniform(0.9, 1.1, a.size)
    out = {}
    try:
        for b in ("numpy", "numba"):
            _compiled.set_backend(b)
            out[b] = fnd.edge_data(d, a)
    finally:
        _compiled.set_backend(None)
    assert out["numpy"].keys() == out["numba"].keys()
    for key, x in out["numpy"].items():
        assert x.dtype == out["numba"][key].dtype and np.array_equal(x, out["numba"][key]), key
