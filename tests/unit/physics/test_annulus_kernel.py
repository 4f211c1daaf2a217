"""The compiled annulus step and energy passes of the exact torsion solver (issue 28, 180-step
path row; :mod:`contactlab.numeric.annulus_kernel`).

Must show: :func:`contactlab.physics.torsion_annulus.step` with a twist increment (with and
without check points, with and without a :class:`~contactlab.physics.torsion_annulus.NodeTable`,
with the slip increments wanted or not), ``nonnegative_psi``, ``slip_kernel_integral`` with a
table and the stage energies of :mod:`contactlab.physics.torsion_energy` give the same bits on the
compiled route as on the numpy route (the reference of the stored path hashes), on random
densities and contact radii, increments rising, falling, zero and beyond full sliding; the
kernels' logic run uncompiled too; numpy's pairwise summation order reproduced; the traction
check decided in the pass only outside the rounding of its sums (a bound exactly at the traction
is left to the numpy route); a whole 180-step varying-load path bit-identical with the step's
numpy helpers never called; a nan increment handed to the numpy route.
"""
import numpy as np
import pytest

import contactlab as cl
from contactlab.numeric import annulus_kernel as ak
from contactlab.numeric import jit
from contactlab.numeric import normal_kernels as NK
from contactlab.physics import torsion_annulus as ta
from contactlab.physics import torsion_energy as te
from contactlab.physics import torsion_rings as tr

needs_numba = pytest.mark.skipif(not jit.available(), reason="numba (extra 'fast') not installed")
MAT = (cl.Elastic(E=210e9, nu=0.3), cl.Rigid())
MU = 0.3
ROUTES = [pytest.param(True, marks=needs_numba, id="compiled"),
          pytest.param(False, id="uncompiled-logic")]


def _route(monkeypatch, on, compiled=True):
    monkeypatch.setitem(ta._COMPILED, "on", on)
    monkeypatch.setitem(ta._COMPILED, "compiled", compiled)


def _same(a, b) -> bool:
    if isinstance(a, dict):
        return a.keys() == b.keys() and all(_same(a[k], b[k]) for k in a)
    if isinstance(a, tuple):
        return len(a) == len(b) and all(_same(u, v) for u, v in zip(a, b))
    if isinstance(a, np.ndarray):
        return a.shape == b.shape and a.tobytes() == b.tobytes()
    return np.asarray(a).tobytes() == np.asarray(b).tobytes() and type(a) is type(b)


def _hertz_rings(n):
    """Rings on the unit contact radius, their LU factors and the Hertz sliding density."""
    b = np.linspace(0.0, 1.0, n + 1)
    r = 0.5 * (b[1:] + b[:-1])
    lu = tr.influence(b, r, 1.0)["lu"]
    bound = MU * np.sqrt(np.clip(1.0 - r * r, 0.0, None))
    slide = ta.nonnegative_psi(ta.density(lu, b, np.zeros(0, int), bound, 1.0))
    return b, r, lu, bound, slide


def _cases():
    """(old, slide, radius, dphi, r, bound, table) from a run of steps on 60 rings: growing,
    shrinking and unchanged contact radii, increments of both signs, zero and beyond sliding."""
    b, r, lu, bound, _slide = _hertz_rings(60)
    table = ta.NodeTable(r, b)
    rng = np.random.default_rng(7)
    w = ta.empty()
    out = []
    for _i in range(40):
        k = int(rng.integers(30, 61))
        radius = float(b[k])
        bd = np.where(r < radius, bound * (0.6 + 0.4 * rng.random()), 0.0)
        sl = ta.nonnegative_psi(ta.density(lu, b, np.zeros(0, int), bd, radius))
        dphi = float(rng.choice([0.0, -1.0, 1.0, 3.0]) * rng.random() * 0.3)
        out.append((w, sl, radius, dphi, r, bd, table))
        w = ta.step(w, sl, radius, 1.0, dphi=dphi)["w"]
    return out


@pytest.mark.parametrize("compiled", ROUTES)
def test_twist_step_is_bit_identical_on_the_compiled_route(monkeypatch, compiled):
    checked = 0
    for old, sl, radius, dphi, r, bound, table in _cases():
        for kw in ({}, {"r": r, "bound": bound, "slip": True},
                   {"r": r, "bound": bound, "slip": False},
                   {"r": r, "bound": bound, "slip": False, "table": table},
                   {"r": r, "bound": bound * 0.3, "slip": False, "table": table}):
            _route(monkeypatch, False)
            ref = ta.step(old, sl, radius, 1.0, dphi=dphi, **kw)
            _route(monkeypatch, True, compiled)
            got = ta.step(old, sl, radius, 1.0, dphi=dphi, **kw)
            assert _same(got, ref), (radius, dphi, kw.keys())
            checked += not ref["ok"]
    assert checked      # failed checks among the cases (the verdicts compared too)


@pytest.mark.parametrize("compiled", ROUTES)
def test_nonnegative_slip_integral_and_energies_are_bit_identical(monkeypatch, compiled):
    b, r, lu, _bound, _slide = _hertz_rings(60)
    table = ta.NodeTable(r, b)
    cases = _cases()
    for old, sl, radius, dphi, _, bd, _ in cases:
        raw = ta.density(lu, b, np.zeros(0, int), bd * np.where(r > 0.8 * radius, -1.0, 1.0),
                         radius)
        new = ta.step(old, sl, radius, 1.0, dphi=dphi)["w"]
        dw = ta.difference(new, old, 0.0)
        # radii all in the table, and one not (the numpy route without a table there)
        radii = (r[r < radius], np.append(r[r < radius], 0.5 * (r[0] + r[1])))
        _route(monkeypatch, False)
        ref = (ta.nonnegative_psi(raw), ta.nonnegative_psi(sl),
               [ta.slip_kernel_integral(dw, x, table) for x in radii],
               te.annulus_energy(old, new, sl, radius, 1.0, 1.0, dphi),
               te.step_energy(old, new, 1.0, gross=None), te.step_energy(old, new, 1.0, 0.1))
        _route(monkeypatch, True, compiled)
        got = (ta.nonnegative_psi(raw), ta.nonnegative_psi(sl),
               [ta.slip_kernel_integral(dw, x, table) for x in radii],
               te.annulus_energy(old, new, sl, radius, 1.0, 1.0, dphi),
               te.step_energy(old, new, 1.0, gross=None), te.step_energy(old, new, 1.0, 0.1))
        assert _same(got[:2], ref[:2])
        assert all(_same(u, v) for u, v in zip(got[2], ref[2]))
        assert all(_same(u, v) for u, v in zip(got[3:], ref[3:]))


def _counting(monkeypatch, passes: dict, name: str) -> list:
    """Replace the pass ``name`` of ``passes`` by one that records its calls in the list
    returned."""
    seen: list = []
    inner = passes[name]

    def counted(*args):
        seen.append(1)
        return inner(*args)
    monkeypatch.setitem(passes, name, counted)
    return seen


@pytest.mark.parametrize("compiled", ROUTES)
def test_shrinking_contact_energy_pass_is_the_loops_bits(monkeypatch, compiled):
    """A shrinking contact's release then family stage (``annulus_energy``'s three-stage
    chain) by one compiled pass, with the release density's step in it or given: the work,
    energies and dissipation of the numpy loop, bit for bit, with and without a gross turn."""
    taken = fused = 0
    for old, sl, radius, dphi, *_ in _cases():
        top = float(old[1][-1]) if old[1].size else 0.0
        if top <= radius:
            continue
        out = ta.step(old, sl, radius, 1.0, dphi=dphi)
        new, sense = out["w"], out["sense"]
        mid = ta.step(old, sl, radius, 1.0, dphi=0.0)["w"]
        chain = [(old, None), (mid, False), (new, True)]
        for gross in (0.0, 0.1, -2.5e-3):
            _route(monkeypatch, False)
            ref = te._stages(chain, 3.0e9, gross)
            ref_step = te.annulus_energy(old, new, sl, radius, sense, 3.0e9, dphi, gross)
            _route(monkeypatch, True, compiled)
            # (the uncompiled logic's passes are copies of ak._PLAIN, made per call)
            passes = ta._annulus_kernels() if compiled else ak._PLAIN
            assert passes is not None
            seen = _counting(monkeypatch, passes, "release_family_energy")
            got = te._stages(chain, 3.0e9, gross)
            assert seen and _same(got, ref), (radius, dphi, gross)
            whole = _counting(monkeypatch, passes, "shrink_energy")
            got_step = te.annulus_energy(old, new, sl, radius, sense, 3.0e9, dphi, gross)
            monkeypatch.undo()
            assert _same(got_step, ref_step), (radius, dphi, gross)
            taken += 1
            fused += bool(whole)
    assert taken >= 15 and fused >= 6


@pytest.mark.parametrize("compiled", ROUTES)
def test_pairwise_sum_is_numpys_order(compiled):
    if compiled:
        ak.kernels()                    # the helpers compiled
    f = ak.pairwise_sum if compiled else getattr(ak.pairwise_sum, "py_func", ak.pairwise_sum)
    rng = np.random.default_rng(1)
    for n in [*range(0, 140), 255, 256, 257, 1000, 4099]:
        a = rng.standard_normal(n) * 10.0 ** rng.integers(-8, 8, n)
        assert (0.0 + f(a, 0, n)) == np.sum(a), n
    assert not np.signbit(0.0 + f(np.full(9, -0.0), 0, 9))      # np.sum's identity 0.0


def test_traction_check_is_left_open_within_rounding():
    """The pass decides the traction check inside the stick radius only where its margin
    exceeds a bound on the rounding of its sums: a bound at the traction itself is left to the
    numpy route, well above or below it is decided."""
    b, r, _lu, _bound, slide = _hertz_rings(40)
    table = ta.NodeTable(r, b)
    w = ta.step(ta.empty(), slide, 1.0, 1.0, dphi=0.2)["w"]
    c = 0.6
    inside = r < c
    tau = np.abs(ta.traction(w, r[inside], 1.0, table))
    F0, F1 = table.arrays["traction"]
    arrays = [np.ascontiguousarray(a, float) for a in w]

    def verdict(bd):
        full = np.where(inside, 0.0, 1.0)
        full[inside] = bd
        return ak._inside(*arrays, r, full, c, 1.0, ta.CHECK_RTOL, F0, F1, table.r, table.nodes)

    assert verdict(tau * 2.0) == ak.INSIDE_OK
    assert verdict(tau * 0.5) == ak.INSIDE_FAIL
    assert verdict(tau / (1 + ta.CHECK_RTOL)) == ak.INSIDE_OPEN
    # no table: always the numpy route's
    assert ak._inside(*arrays, r, np.ones(r.size), c, 1.0, ta.CHECK_RTOL, np.zeros((0, 0)),
                      np.zeros((0, 0)), np.zeros(0), np.zeros(0)) == ak.INSIDE_OPEN


@needs_numba
def test_nan_increment_goes_to_the_numpy_route(monkeypatch):
    _b, _r, _lu, _bound, slide = _hertz_rings(30)
    _route(monkeypatch, False)
    ref = ta.step(ta.empty(), slide, 1.0, 1.0, dphi=float("nan"))
    _route(monkeypatch, True)
    got = ta.step(ta.empty(), slide, 1.0, 1.0, dphi=float("nan"))
    assert _same(got, ref)


def _varying(c, n=180):
    t = np.arange(1, n + 1) / n
    force = 10.0 * (1 + 0.4 * np.sin(2 * np.pi * 2 * t + 0.3))
    a = float(np.max(c.normal(force=force)._radius))
    s = MU * 10.0 / (c.moduli.torsional * a * a)
    phi = 0.8 * s * np.sin(2 * np.pi * 3 * t) * np.minimum(1, 2 * t)
    return cl.LoadPath.from_arrays(force=force, twist=phi)


@needs_numba
@pytest.mark.parametrize("kw", [{"torque_rtol": 1e-3}, {"n_rings": 60}])
def test_varying_path_is_bit_identical_and_takes_the_pass(monkeypatch, kw):
    """The benchmark's 180-step path (ring-solver steps among its steps): the same bits on both
    routes; on the compiled route the numpy step's root, splice and totals are not called."""
    c = cl.Contact(cl.profiles.Paraboloid(R=0.01), materials=MAT, friction=MU)
    path = _varying(c)
    _route(monkeypatch, False)
    ref = c.simulate(path, method="exact", **kw)
    _route(monkeypatch, True)

    def unused(*a, **k):
        raise AssertionError("the numpy step was taken")

    monkeypatch.setattr(ta, "_root", unused)
    monkeypatch.setattr(ta, "splice", unused)
    got = c.simulate(path, method="exact", **kw)
    assert got.meta["fallback_steps"] > 0          # ring-solver steps included
    for k in ("torque", "twist", "dissipated_energy", "stick_radius", "slip"):
        if k in got.data:
            assert getattr(got, k).tobytes() == getattr(ref, k).tobytes(), k
    for k in ("work", "stored", "dissipated_per_step"):
        assert got.meta["energy"][k].tobytes() == ref.meta["energy"][k].tobytes(), k


def test_numpy_backend_has_no_passes(monkeypatch):
    monkeypatch.setitem(ta._COMPILED, "on", None)
    monkeypatch.setitem(NK._state, "backend", "numpy")
    assert ta._annulus_kernels() is None
    if jit.available():
        monkeypatch.setitem(NK._state, "backend", "numba")
        assert ta._annulus_kernels() is not None


@pytest.mark.parametrize("compiled", ROUTES)
def test_coefficient_pieces_are_bit_identical(monkeypatch, compiled):
    """``from_coefficients`` (the ring solver's hats and half-hats, cut at a radius) on both
    routes: no cut, a cut inside a ring, at a node, beyond the rings; repeated jump nodes
    (numpy's ``left[jumps] +=`` writes the last); an out-of-range jump raises on both."""
    rng = np.random.default_rng(5)
    b = np.sort(np.r_[0.0, rng.random(30), 1.0])
    for jumps in (np.zeros(0, int), np.array([3, 10, 17]), np.array([4, 4, 9])):
        coef = rng.normal(size=b.size - 1 + jumps.size)
        for radius in (None, 0.5 * (b[7] + b[8]), float(b[12]), 2.0, 0.0):
            _route(monkeypatch, False)
            ref = ta.from_coefficients(b, coef, jumps, radius)
            _route(monkeypatch, True, compiled)
            got = ta.from_coefficients(b, coef, jumps, radius)
            assert _same(got, ref), (jumps, radius)
    for on in (False, True):
        _route(monkeypatch, on, compiled)
        with pytest.raises(IndexError):
            ta.from_coefficients(b, rng.normal(size=b.size + 1), np.array([40, 41]), 0.5)


def _banded_densities():
    """Densities whose Ψ dips below zero (inside and at the outer end, with a gap, a piece of
    zero width, a double root), densities without a band, and random ones on 5-200 pieces."""
    q = (np.array([0.1, 0.3, 0.45, 0.6, 0.85]), np.array([0.3, 0.45, 0.6, 0.85, 1.0]),
         np.array([1.0, -2.0, -6.0, 4.0, 2.0]), np.array([-1.0, -6.0, 8.0, 3.0, -9.0]))
    yield q
    yield tuple(a.copy() for a in (q[0], q[1], np.abs(q[2]), np.abs(q[3])))     # no band
    yield (np.array([0.0, 0.5, 0.5]), np.array([0.5, 0.5, 1.0]), np.array([1.0, 3.0, 1.0]),
           np.array([1.0, 3.0, -3.0]))                                        # zero width
    yield (np.array([0.0, 0.5]), np.array([0.5, 1.0]), np.array([0.0, 1.0]),
           np.array([1.0, -1.0]))                                             # Ψ touches 0
    rng = np.random.default_rng(28)
    for n in (5, 17, 60, 200):
        for _ in range(6):
            b = np.sort(rng.uniform(0.0, 1.0, n + 1))
            wl, wr = rng.normal(0.3, 1.0, n), rng.normal(0.2, 1.0, n)
            yield b[:-1].copy(), b[1:].copy(), wl, wr


@pytest.mark.parametrize("compiled", ROUTES)
def test_band_removal_is_bit_identical(monkeypatch, compiled):
    """``nonnegative_psi``'s band removal in one compiled pass gives the numpy route's bits, on
    densities with a band and without (then the density itself, the same arrays); a nan is left
    to the numpy route."""
    banded = 0
    for p in _banded_densities():
        _route(monkeypatch, False)
        ref = ta.nonnegative_psi(p)
        _route(monkeypatch, True, compiled)
        got = ta.nonnegative_psi(p)
        assert _same(got, ref)
        assert (got is p) == (ref is p)
        banded += ref is not p
        # the pass itself decided it (not handed to the numpy route)
        status, _ = ak.kernels(compiled)["nonnegative_band"](*p)
        assert status == (ak.BAND_NONE if ref is p else ak.BAND_CUT)
    assert banded >= 10
    nan = (np.array([0.0, 0.5]), np.array([0.5, 1.0]), np.array([1.0, np.nan]), np.ones(2))
    status, _ = ak.kernels(compiled)["nonnegative_band"](*nan)
    assert status == ak.BAND_REFERENCE
