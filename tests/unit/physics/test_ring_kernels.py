"""The compiled passes of the exact ring solver's punch densities (issue 28, ring solver row).

Must show: :func:`contactlab.physics.torsion_annulus.psi`, ``_ends`` (through
:func:`~contactlab.physics.torsion_annulus.difference`) and the checks' antiderivatives
(``_antiderivatives``, ``_slip_antiderivatives``: nodes off a table, nan, infinite, zero and
negative radii and nodes) give the same bits with the kernels of
:mod:`contactlab.numeric.ring_kernels` as with the numpy route (the reference, which defines the
stored path hashes), on random densities (abutting, with gaps, zero-width pieces, one piece) at
radii on, between, below and beyond their piece ends; whole exact paths (Hertz, cone, a table;
force rising, falling, constant; a release) bit-identical on both routes; the kernels' logic run
uncompiled too (so it is covered without numba); ``set_backend("numpy")`` keeping numpy.
"""
import numpy as np
import pytest

import contactlab as cl
from contactlab.numeric import jit
from contactlab.numeric import normal_kernels as NK
from contactlab.physics import torsion_annulus as ta

needs_numba = pytest.mark.skipif(not jit.available(), reason="numba (extra 'fast') not installed")
MAT = (cl.Elastic(E=210e9, nu=0.3), cl.Rigid())
MU = 0.3
SERIES = ("torque", "twist", "dissipated_energy", "stick_radius")


def _densities(seed):
    rng = np.random.default_rng(seed)
    b = np.sort(np.r_[0.0, rng.random(40), 1.0]) * 1e-4
    wl, wr = rng.normal(size=(2, b.size - 1))
    yield ta.from_nodes(b, wl, wr)                                    # abutting
    keep = rng.random(b.size - 1) < 0.6                               # gaps between pieces
    yield tuple(a[keep] for a in ta.from_nodes(b, wl, wr))
    z = b.copy()
    z[5] = z[4]                                                       # a zero-width piece
    yield ta.from_nodes(z, wl, wr)
    yield (b[3:4], b[4:5], wl[:1], wr[:1])                            # one piece


def _radii(p, seed):
    rng = np.random.default_rng(seed)
    lo, hi = p[0], p[1]
    return np.concatenate([lo, hi, 0.5 * (lo + hi), [0.0, -1e-5, 2e-4, lo[0], hi[-1]],
                           np.nextafter(hi, 0.0), rng.uniform(0.0, 1.1e-4, 50)])


def _route(monkeypatch, on, compiled=True):
    monkeypatch.setitem(ta._COMPILED, "on", on)
    monkeypatch.setitem(ta._COMPILED, "compiled", compiled)


def _check_psi_and_ends(monkeypatch, compiled):
    for seed in range(4):
        dens = list(_densities(seed))
        for p in dens:
            x = _radii(p, seed)
            _route(monkeypatch, False)
            ref = ta.psi(p, x), ta.psi(p, x[:x.size // 2 * 2].reshape(2, -1)), ta.psi(p, np.float64(3e-5))
            diffs = [ta.difference(p, q, s) for q in dens for s in (0.0, float(x[7]))]
            _route(monkeypatch, True, compiled)
            got = ta.psi(p, x), ta.psi(p, x[:x.size // 2 * 2].reshape(2, -1)), ta.psi(p, np.float64(3e-5))
            for u, v in zip(got, ref):
                assert u.shape == v.shape and u.tobytes() == v.tobytes()
            got_d = [ta.difference(p, q, s) for q in dens for s in (0.0, float(x[7]))]
            for d1, d0 in zip(got_d, diffs):
                assert [a.tobytes() for a in d1] == [a.tobytes() for a in d0]


def test_psi_and_ends_uncompiled_logic_is_bit_identical(monkeypatch):
    _check_psi_and_ends(monkeypatch, compiled=False)


@needs_numba
def test_psi_and_ends_compiled_are_bit_identical(monkeypatch):
    _check_psi_and_ends(monkeypatch, compiled=True)


def _antiderivative_cases(seed):
    """Radii (rows) and nodes (columns) of the checks' antiderivatives: zero, negative, nan
    and infinite radii, nodes equal to, just below and beyond radii, a table's band with a
    couple of off-table nodes (the solver's case) and a square block."""
    rng = np.random.default_rng(seed)
    r = np.sort(rng.random(120)) * 1e-4
    t = np.sort(rng.random(9)) * 1.2e-4
    odd = np.array([0.0, -1e-5, np.nan, np.inf, 3e-5])
    yield np.concatenate([odd, r]), np.concatenate([t, r[[3, 50]], np.nextafter(r[7:9], 0.0),
                                                     [0.0, -0.0, 2e-4, np.nan, np.inf]])
    yield r[20:90], r[[33, 71]]
    yield r[:40], np.concatenate([[0.0], r[:40]])
    yield r[:5], np.empty(0)
    yield np.empty(0), t


def _check_antiderivatives(monkeypatch, compiled):
    for seed in range(3):
        for r, t in _antiderivative_cases(seed):
            _route(monkeypatch, False)
            with np.errstate(invalid="ignore"):
                ref = ta._antiderivatives(r, t) + ta._slip_antiderivatives(r, t)
            _route(monkeypatch, True, compiled)
            with np.errstate(invalid="ignore"):
                got = ta._antiderivatives(r, t) + ta._slip_antiderivatives(r, t)
            for u, v in zip(got, ref):
                assert u.shape == v.shape and u.tobytes() == v.tobytes()


def test_check_antiderivatives_uncompiled_logic_is_bit_identical(monkeypatch):
    _check_antiderivatives(monkeypatch, compiled=False)


@needs_numba
def test_check_antiderivatives_compiled_are_bit_identical(monkeypatch):
    _check_antiderivatives(monkeypatch, compiled=True)


@pytest.mark.parametrize("on", [False, True])
def test_traction_with_table_columns_is_bit_identical(monkeypatch, on):
    """The ring-solver step's tractions from a table's columns (``columns=``) are the same bits
    as computed: all rows, a band of rows, radii off the table, densities with nodes on and off
    the table, with gaps (the other formula)."""
    if on and not jit.available():
        pytest.skip("numba (extra 'fast') not installed")
    _route(monkeypatch, on)
    rng = np.random.default_rng(5)
    b = np.sort(np.r_[0.0, rng.random(60), 1.0]) * 1e-4
    r = 0.5 * (b[1:] + b[:-1])
    table = ta.NodeTable(r, b)
    off = np.sort(rng.random(3)) * 1e-4
    nodes = [b, np.unique(np.r_[b[:30], off]), np.unique(np.r_[b[::3], off, b[-1]]), off]
    for t in nodes:
        wl, wr = rng.normal(size=(2, t.size - 1))
        p = ta.from_nodes(t, wl, wr)
        gaps = tuple(a[::2] for a in p)
        for q in (p, gaps):
            for x in (r, r[10:40], np.r_[r[:5], 3.3e-5], np.r_[r[:5], r[3]]):
                ref = ta.traction(q, x, 1e10)
                got = ta.traction(q, x, 1e10, columns=table)
                assert got.tobytes() == ref.tobytes()


def _contacts():
    r = np.linspace(0.0, 4e-4, 200)
    return {"hertz": cl.Contact(cl.profiles.Paraboloid(R=0.01), materials=MAT, friction=MU),
            "cone": cl.Contact(cl.profiles.Cone(slope=0.03), materials=MAT,
                               friction=MU),
            "table": cl.Contact(cl.profiles.Tabulated(r=r, f=r ** 2 / 0.02 + 2e3 * r ** 3),
                                materials=MAT, friction=MU)}


def _path(c, kind, n=60, seed=0):
    rng = np.random.default_rng(seed)
    t = np.arange(1, n + 1) / n
    force = {"rising": 5.0 + 10.0 * t, "falling": 15.0 - 10.0 * t,
             "constant": np.full(n, 10.0),
             "varying": 10.0 * (1 + 0.4 * np.sin(4 * np.pi * t + rng.uniform(0, 1))),
             # unloaded to no contact in the middle, then loaded again
             "release": 10.0 * np.abs(np.cos(np.pi * t)) ** 1.5}[kind]
    a = float(np.max(c.normal(force=np.maximum(force, 1e-3))._radius))
    s = MU * float(np.max(force)) / (c.moduli.torsional * a * a)
    phi = 0.8 * s * np.sin(2 * np.pi * 3 * t + rng.uniform(0, 1)) * np.minimum(1, 2 * t)
    return cl.LoadPath.from_arrays(force=force, twist=phi)


def _runs(monkeypatch, c, path, compiled, **kw):
    _route(monkeypatch, False)
    ref = c.simulate(path, method="exact", **kw)
    _route(monkeypatch, True, compiled)
    got = c.simulate(path, method="exact", **kw)
    return ref, got


def _same(ref, got):
    for k in SERIES:
        assert getattr(got, k).tobytes() == getattr(ref, k).tobytes(), k
    for k in ("work", "stored", "dissipated_per_step"):
        assert got.meta["energy"][k].tobytes() == ref.meta["energy"][k].tobytes(), k
    assert got.meta["fallback_steps"] == ref.meta["fallback_steps"]


@needs_numba
@pytest.mark.parametrize("name", ["hertz", "cone", "table"])
@pytest.mark.parametrize("kind", ["rising", "falling", "constant", "varying", "release"])
def test_exact_paths_are_bit_identical_on_the_compiled_route(monkeypatch, name, kind):
    c = _contacts()[name]
    ref, got = _runs(monkeypatch, c, _path(c, kind), True, n_rings=40)
    _same(ref, got)


def test_exact_path_uncompiled_logic_is_bit_identical(monkeypatch):
    c = _contacts()["hertz"]
    ref, got = _runs(monkeypatch, c, _path(c, "varying", n=40), False, n_rings=24)
    assert ref.meta["annulus"]
    _same(ref, got)


@needs_numba
def test_torque_controlled_path_is_bit_identical_on_the_compiled_route(monkeypatch):
    c = _contacts()["hertz"]
    t = np.arange(1, 61) / 60
    force = 10.0 * (1 + 0.3 * np.sin(4 * np.pi * t))
    a = float(np.min(c.normal(force=force)._radius))
    # up to 0.7 of the smallest sliding torque (Hertz: 3π/16 μ F a)
    M = 0.7 * 3 * np.pi / 16 * MU * 7.0 * a * np.sin(6 * np.pi * t)
    path = cl.LoadPath.from_arrays(force=force, torque=M)
    ref, got = _runs(monkeypatch, c, path, True, n_rings=40)
    _same(ref, got)


def test_numpy_backend_keeps_the_numpy_route(monkeypatch):
    monkeypatch.setitem(ta._COMPILED, "on", None)
    monkeypatch.setitem(NK._state, "backend", "numpy")
    assert ta._kernels() is None
    if jit.available():
        monkeypatch.setitem(NK._state, "backend", "numba")
        assert ta._kernels() is not None


def test_ring_solver_lapack_calls_are_scipys_bits():
    """The box step's positive-definite solves (``torsion_rings._pos_solve``) and the density's
    LU solve (``torsion_annulus.density``) call LAPACK directly: the same bits as
    ``scipy.linalg.solve(assume_a="pos")`` and ``lu_solve`` (one unknown, one and two
    right-hand sides, a matrix symmetric only to rounding; the density's solve is ``lu_solve``'s
    of its values beside zero columns, ``torsion_annulus.coefficients``), and ``LinAlgError``
    where scipy raises it (not positive definite, a zero 1x1)."""
    import scipy.linalg as la
    from contactlab.physics import torsion_rings as tr
    rng = np.random.default_rng(3)
    for n in (1,) * 8 + (2, 7, 120):
        M = rng.random((n, n))
        H = M @ M.T + n * np.eye(n)
        H = H + 1e-12 * rng.random((n, n))          # symmetric to rounding only
        for b in (rng.random(n), rng.random((n, 2))):
            ref = la.solve(H, b, assume_a="pos", check_finite=False)
            got = tr._pos_solve(H, b)
            assert got.shape == ref.shape and got.tobytes() == ref.tobytes()
            assert got.strides == ref.strides     # products of its columns sum in this order
        lu = la.lu_factor(M + n * np.eye(n))
        v = rng.random(n)
        # (the density's solve: beside zero columns up to a whole group of right-hand sides,
        # the multi-vector kernel of its batches)
        coef = la.lu_solve(lu, np.column_stack([v, np.zeros((n, ta.RHS_GROUP - 1))]),
                           check_finite=False)[:, 0]
        b_nodes = np.linspace(0.0, 1e-4, n + 1)
        got = ta.density(lu, b_nodes, np.zeros(0, np.int64), v, 1e-4)
        want = ta.from_coefficients(b_nodes, coef, np.zeros(0, np.int64), 1e-4)
        assert [a.tobytes() for a in got] == [a.tobytes() for a in want]
    for bad in (np.array([[1.0, 2.0], [2.0, 1.0]]), np.zeros((1, 1))):
        with pytest.raises(np.linalg.LinAlgError):
            la.solve(bad, np.ones(2 if bad.size > 1 else 1), assume_a="pos", check_finite=False)
        with pytest.raises(np.linalg.LinAlgError):
            tr._pos_solve(bad, np.ones(2 if bad.size > 1 else 1))


def test_ring_solver_blocks_are_the_fancy_indexed_blocks():
    """``torsion_rings._block`` (two ``compress``) gives ``M[np.ix_(rows, cols)]``: the same
    values in the same (C) layout, for empty, full and mixed masks."""
    from contactlab.physics import torsion_rings as tr
    rng = np.random.default_rng(4)
    M = rng.random((40, 40))
    for rows, cols in ((rng.random(40) < 0.7, rng.random(40) < 0.3), (np.ones(40, bool),) * 2,
                       (np.zeros(40, bool), np.ones(40, bool))):
        ref, got = M[np.ix_(rows, cols)], tr._block(M, rows, cols)
        assert got.shape == ref.shape and got.strides == ref.strides
        assert got.tobytes() == ref.tobytes()
