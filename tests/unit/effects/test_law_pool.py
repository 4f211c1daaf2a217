"""Lazy spring state of ContactLaw (issue 29): spring rows exist only for contacts that switch
onto their springs (a pool grown by doubling, rows given back on separation or reset); which row
a contact holds never changes its results, and the state per contact is unchanged."""
from __future__ import annotations

import resource
import sys
import tracemalloc
import warnings

import numpy as np
import pytest

import contactlab as cl
from contactlab.effects.law import law_memory
from contactlab.effects.law_pool import SpringPool, pool_row_bytes
from contactlab.errors import MemoryBudgetError, ValidityWarning
from tests.tolerances import COMPILED_VS_NUMPY_SPRINGS, OLD_SPRING_STATE

HAS_NUMBA = cl.effects.law._kernel.AVAILABLE
BACKENDS = [False, True] if HAS_NUMBA else [False]
FIELDS = ("depth", "radius", "force", "tangential_force", "torque", "stick_radius",
          "torsion_stick_radius", "dissipated_energy", "exact")


def _law(n, fast, **kw):
    return cl.ContactLaw(cl.profiles.Paraboloid, R=np.linspace(2e-3, 9e-3, n), E_star=1.15e11,
                         G_star=4.4e10, G_torsion=4e10, friction=0.3, fast=fast, **kw)


def test_pool_rows_follow_their_contacts():
    """Rows given back are filled from the end; every contact keeps its own row contents."""
    pool = SpringPool(10, 3)
    idx = np.array([7, 2, 5, 9, 0])
    s = pool.assign(idx)
    pool.rows["spr_depth"][s] = idx + 0.5
    pool.rows["spr_tan"][s] = (idx + 0.25)[:, None]
    pool.release(np.array([2, 9, 3]))                # 3 holds no row
    assert pool.used == 3
    on = np.flatnonzero(pool.on())
    np.testing.assert_array_equal(on, [0, 5, 7])
    np.testing.assert_array_equal(pool.owner[pool.slot[on]], on)
    np.testing.assert_array_equal(pool.full("spr_depth")[on], on + 0.5)
    np.testing.assert_array_equal(pool.full("spr_tan")[on], np.repeat((on + 0.25)[:, None], 3, 1))
    assert not pool.full("spr_depth")[[1, 2, 3, 4, 6, 8, 9]].any()


def test_rows_from_the_clean_mark_on_are_zeros():
    """``clean``: the rows from it on were never written (+0 in every element, so a switch
    need not write +0 beyond its edge cell there); rows given back stay below it, and a grown
    pool's rows past those it copied are zeros again."""
    pool = SpringPool(300, 4)
    assert pool.clean == 0
    s = pool.assign(np.arange(10))
    assert pool.clean == 10
    for k in ("spr_tan", "spr_tor"):
        pool.rows[k][s] = -1.5
        assert pool.rows[k][pool.clean:].tobytes() == bytes(pool.rows[k][pool.clean:].nbytes)
    pool.release(np.arange(4))                      # rows 6..9 given back: written, not clean
    assert pool.used == 6 and pool.clean == 10
    pool.take(2)                                    # a compiled switch wrote rows 6, 7
    assert pool.used == 8 and pool.clean == 10
    pool.reserve(pool.capacity)                     # grown: rows 0..7 copied, the rest zeros
    assert pool.clean == 8
    for k in ("spr_tan", "spr_tor"):
        assert pool.rows[k][8:].tobytes() == bytes(pool.rows[k][8:].nbytes)


@pytest.mark.parametrize("fast", BACKENDS)
def test_results_do_not_depend_on_the_rows(fast):
    """A law of 40 contacts whose rows are reshuffled by separations and resets gives, for the
    contacts it shares with a law of those contacts alone, the same results to the bit."""
    n, steps = 40, 24
    keep = np.arange(0, n, 3)                       # contacts never separated nor reset
    rng = np.random.default_rng(7)
    F = rng.uniform(1.0, 50.0, n)
    u = np.cumsum(rng.standard_normal((steps, n)), axis=0) * 3e-8
    phi = np.cumsum(rng.standard_normal((steps, n)), axis=0) * 1e-4
    big = _law(n, fast)
    small = cl.ContactLaw(cl.profiles.Paraboloid, R=np.linspace(2e-3, 9e-3, n)[keep],
                          E_star=1.15e11, G_star=4.4e10, G_torsion=4e10, friction=0.3,
                          fast=fast)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ValidityWarning)
        for k in range(steps):
            L = F * (1.0 + 0.05 * np.sin(0.7 * k + np.arange(n))) if k >= 3 else F
            L = L.copy()
            others = np.setdiff1d(np.arange(n), keep)
            if k % 5 == 4:
                L[others[k % 4::4]] = 0.0           # separate: their rows go back to the pool
            if k % 7 == 6:
                big.reset(others[1::3])
            a = big.step(force=L, displacement=u[k], twist=phi[k])
            b = small.step(force=L[keep], displacement=u[k][keep], twist=phi[k][keep])
            for f in FIELDS:
                np.testing.assert_array_equal(getattr(a, f)[keep], getattr(b, f), err_msg=f)
    assert big._pool.used == np.count_nonzero(big.state["spr_on"])
    sb = big.state
    for key, v in small.state.items():
        np.testing.assert_array_equal(sb[key][keep], v, err_msg=key)


@pytest.mark.parametrize("fast", BACKENDS)
def test_spring_rows_only_for_contacts_that_switch(fast):
    """The law holds no spring rows until a load changes, then rows for those contacts only
    (the pool doubles at most): a tenth switching holds far less than every contact's rows
    (they were allocated with the law: 425 B per contact, 903 B per contact in all)."""
    n = 2000
    law = _law(n, fast)
    law.step(force=10.0, displacement=1e-8)
    assert law._pool.capacity == 0
    F = np.full(n, 10.0)
    F[:200] = 11.0                                  # a tenth of the contacts change load
    law.step(force=F, displacement=1e-8)
    assert law._pool.used == 200 and law._pool.capacity <= 400
    assert law_memory(n, 8, 16) == 498 * n
    assert law_memory(n, 8, 16, 200) == 498 * n + 200 * pool_row_bytes(16)


def test_a_fresh_law_holds_its_state_and_no_spring_rows():
    """Measured: tracemalloc's count of a fresh law and a step's results is within
    law_memory (no springs), far below the 903 B per contact when every row was allocated."""
    n = 20_000
    _law(n, None).step(force=1.0, twist=1e-4)       # warm: kernels, tables
    tracemalloc.start()
    try:
        law = _law(n, None)
        law.step(force=1.0, twist=1e-4)
        held = tracemalloc.get_traced_memory()[0]
    finally:
        tracemalloc.stop()
    assert held <= law_memory(n, 8, 16) < 600 * n


@pytest.mark.parametrize("fast", BACKENDS)
def test_spring_rows_are_checked_against_the_budget_when_they_grow(fast):
    """springs=4096 costs nothing until contacts switch; their rows are checked then."""
    previous = cl.set_memory_budget(10e6)
    try:
        law = _law(1000, fast, springs=4096)
        law.step(force=1.0, displacement=1e-8)
        with pytest.raises(MemoryBudgetError, match="1000 contacts on 4096 springs"):
            law.step(force=2.0, displacement=1e-8)
    finally:
        cl.set_memory_budget(previous)


@pytest.mark.skipif(not HAS_NUMBA, reason="numba (extra 'fast') not installed")
def test_threaded_switch_and_springs_are_bit_identical():
    """The threaded kernel assigns the same rows in its switch and gives the serial results to
    the bit under a changing load with separations."""
    n, steps = 500, 12
    rng = np.random.default_rng(3)
    F = rng.uniform(1.0, 50.0, n)
    par, ser = _law(n, True, parallel=True), _law(n, True)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ValidityWarning)
        for k in range(steps):
            L = F * (1.0 + 0.05 * np.sin(0.7 * k + np.arange(n))) if k >= 2 else F.copy()
            if k == 6:
                L[::7] = 0.0
            phi, u = 1e-4 * np.sin(0.5 * k + np.arange(n)), 3e-8 * np.cos(0.4 * k + np.arange(n))
            a = par.step(force=L, twist=phi, displacement=u)
            b = ser.step(force=L, twist=phi, displacement=u)
            for f in FIELDS:
                np.testing.assert_array_equal(getattr(a, f), getattr(b, f), err_msg=f)
    np.testing.assert_array_equal(par._pool.slot, ser._pool.slot)
    sp, ss = par.state, ser.state
    for key, v in ss.items():
        np.testing.assert_array_equal(sp[key], v, err_msg=key)


@pytest.mark.skipif(not HAS_NUMBA, reason="numba (extra 'fast') not installed")
def test_threaded_switch_and_step_gives_the_serial_bytes():
    """The threaded switch-and-step (contacts spread over the threads) and spring pass give
    the serial build's bytes (signed zeros included): a random history in which
    contacts switch in several steps, some separate and come back, some outgrow their cover
    (regridded), and the state is saved mid-run, stepped on and restored."""
    import numba
    n, steps = 240, 16
    rng = np.random.default_rng(29)
    F = rng.uniform(1.0, 50.0, n)
    par, ser = _law(n, True, parallel=True), _law(n, True)
    threads = numba.get_num_threads()
    numba.set_num_threads(min(2, numba.config.NUMBA_NUM_THREADS))
    saved: list = []
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", ValidityWarning)
            for k in list(range(steps)) + [-1] + list(range(9, steps)):
                if k == -1:                             # back to step 9's state
                    par.state, ser.state = saved
                    continue
                L = F.copy()
                L[: n * min(k, 6) // 6] *= 1.0 + 0.04 * rng.uniform(-1.0, 1.0)
                if k in (7, 12):
                    L[rng.random(n) < 0.1] = 0.0        # separations
                if k == 10:
                    L[::5] *= 8.0                       # radius beyond the cover: regrid
                phi = 1e-4 * rng.uniform(-1.0, 1.0, n)
                u = 3e-8 * rng.uniform(-1.0, 1.0, n)
                a = par.step(force=L, twist=phi, displacement=u)
                b = ser.step(force=L, twist=phi, displacement=u)
                for f in FIELDS:
                    assert getattr(a, f).tobytes() == getattr(b, f).tobytes(), f"step {k}: {f}"
                if k == 9:
                    saved = [par.state, ser.state]
    finally:
        numba.set_num_threads(threads)
    assert ser.state["spr_on"].sum() > n // 2
    for key, v in ser.state.items():
        assert np.asarray(par.state[key]).tobytes() == np.asarray(v).tobytes(), key


@pytest.mark.skipif(not HAS_NUMBA, reason="compiled law needs numba")
def test_outgrown_covers_are_regridded_in_the_compiled_pass_to_the_numpy_bits(monkeypatch):
    """The compiled spring pass finds the contacts whose radius left their cover itself (no
    pass over the covers before it), the law regrids those and steps them: only the grown
    contacts are regridded, covers, depths and edge cells are the numpy law's bits, and forces
    and the spring state agree with it to COMPILED_VS_NUMPY_SPRINGS (the cell integrals are
    formed in another order)."""
    from contactlab.effects import law_springs_numpy
    n = 60
    grown = []
    regrid = law_springs_numpy.regrid
    monkeypatch.setattr(law_springs_numpy, "regrid",
                        lambda law, idx, a: (grown.append(idx.copy()), regrid(law, idx, a)))
    rng = np.random.default_rng(7)
    F = rng.uniform(1.0, 50.0, n)
    fast, ref = _law(n, True), _law(n, False)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ValidityWarning)
        for k in range(10):
            L = F * (1.0 + 0.03 * k)
            if k == 5:
                L[::3] *= 8.0                           # radius x2 > the cover (1.5 x)
            phi, u = 1e-4 * np.sin(0.5 * k + np.arange(n)), 3e-8 * np.cos(0.4 * k + np.arange(n))
            a = fast.step(force=L, twist=phi, displacement=u)
            b = ref.step(force=L, twist=phi, displacement=u)
            for f in FIELDS:
                x, y = getattr(a, f), getattr(b, f)
                np.testing.assert_allclose(x, y, rtol=0, err_msg=f"step {k}: {f}",
                                           atol=COMPILED_VS_NUMPY_SPRINGS * np.max(np.abs(y)))
    sf, sr = fast.state, ref.state
    for key in ("spr_cover", "spr_depth", "spr_a", "spr_k", "spr_x_tan", "spr_x_tor", "spr_on"):
        np.testing.assert_array_equal(sf[key], sr[key], err_msg=key)
    for key in ("spr_tan", "spr_tor"):
        np.testing.assert_allclose(sf[key], sr[key], rtol=0, err_msg=key,
                                   atol=COMPILED_VS_NUMPY_SPRINGS * np.max(np.abs(sr[key])))
    assert len(grown) == 2          # once per law, in step 5
    np.testing.assert_array_equal(grown[0], np.arange(0, n, 3))
    np.testing.assert_array_equal(grown[1], grown[0])


def _run(law, n, steps=12):
    rng = np.random.default_rng(3)
    F = rng.uniform(1.0, 100.0, n)
    outs = []
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ValidityWarning)
        for k in range(steps):
            L = F * np.where(np.arange(n) % 2 == 0, 1.0 + 0.02 * k, 1.0)
            r = law.step(force=L, displacement=1e-8 * np.sin(0.7 * k + np.arange(n)),
                         twist=1e-4 * np.cos(0.5 * k + np.arange(n)))
            outs.append({f: getattr(r, f).copy() for f in FIELDS})
            if k == 6:
                law.reset(np.arange(n) % 5 == 0)        # rows given back, the last moved
    return outs


@pytest.mark.parametrize("fast", BACKENDS)
def test_rows_in_memory_maps_give_the_same_bits(fast, monkeypatch):
    """Pool arrays beyond _MAP_BYTES are anonymous memory maps (base pages: no huge-page
    compaction on the first write, issue 29); mapped or not, a changing-load run with resets
    (rows moved, the pool grown) gives the same bits and the same state, and the mapped rows
    survive a state round trip."""
    import mmap

    from contactlab.effects import law_pool
    n = 70
    plain = _law(n, fast)
    a = _run(plain, n)
    def mapped_(v):
        while isinstance(v, np.ndarray):
            v = v.base
        return isinstance(v.obj if isinstance(v, memoryview) else v, mmap.mmap)

    assert not mapped_(plain._pool.rows["spr_tan"])
    monkeypatch.setattr(law_pool, "_MAP_BYTES", 0)
    mapped = _law(n, fast)
    b = _run(mapped, n)
    for v in (mapped._pool.owner, *mapped._pool.rows.values()):
        assert mapped_(v) and v.flags.writeable
    for x, y in zip(a, b):
        for f in FIELDS:
            np.testing.assert_array_equal(x[f], y[f], err_msg=f)
    for key, v in plain.state.items():
        np.testing.assert_array_equal(v, mapped.state[key], err_msg=key)
    again = _law(n, fast)
    again.state = mapped.state
    for key, v in mapped.state.items():
        np.testing.assert_array_equal(v, again.state[key], err_msg=key)


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="MADV_POPULATE_WRITE: Linux")
@pytest.mark.parametrize("threads", [False, True])
def test_mapped_rows_are_faulted_in_before_the_first_write(threads):
    """The pool's mapped arrays have the rows about to be written faulted in by ``madvise``
    (in one call, or its two halves on two threads): writing them takes (almost) no page
    faults, the rows beyond ``fill`` fault on their first write; contents start at zero."""
    from contactlab.effects import law_pool

    def faults(v):
        f0 = resource.getrusage(resource.RUSAGE_SELF).ru_minflt
        v[...] = 1.0
        return resource.getrusage(resource.RUSAGE_SELF).ru_minflt - f0

    rows, cols = 16384, 64                  # 8 MB (mapped: >= 4 MB), 128 pages per 1024 rows
    probe = law_pool._mapped((rows, cols), np.dtype(np.float64), 2048)
    if faults(probe[:2048]) > 64:
        pytest.skip("madvise(MADV_POPULATE_WRITE) not supported by this kernel")
    arr = law_pool._mapped((rows, cols), np.dtype(np.float64), 8192, threads)
    assert not arr.any()
    assert faults(arr[:8192]) <= 64                 # populated: 1024 pages, no fault each
    assert faults(arr[8192:]) >= 1000               # not populated: a fault per page


def test_a_row_holds_no_cell_integrals_and_its_bytes_are_counted():
    """The spring row stores the last step's radius, not its 16 cell integrals (recomputed
    from depth and radius): 52 + 16 springs bytes per row, counted from the pool's arrays."""
    from contactlab.effects.law_pool import SPRING_FIELDS
    assert "spr_S" not in SPRING_FIELDS and SPRING_FIELDS["spr_a"] == (np.float64, False)
    pool = SpringPool(100, 16)
    pool.reserve(1)
    row = pool.owner[:1].nbytes + sum(v[:1].nbytes for v in pool.rows.values())
    assert row == pool_row_bytes(16) == 308


def _old_format(state, law):
    """``state`` as a law saved it before ``spr_a`` replaced ``spr_S`` (the cell integrals of
    the last step per spring; their values are not read back)."""
    old = {k: v for k, v in state.items() if k != "spr_a"}
    old["spr_S"] = np.full((law.size, law.springs), np.nan)
    return old


@pytest.mark.parametrize("fast", BACKENDS)
def test_a_state_saved_before_spr_a_still_loads_and_continues(fast, tmp_path):
    """A state of the earlier format (``spr_S`` per spring, no ``spr_a``) restores: the radius
    is recomputed from the stored depth, so a depth-controlled Paraboloid run continues to the
    bit (its radius is the same closed form of the depth), and a state holding both keys is
    refused naming the extra one."""
    n, steps, at = 40, 16, 9
    rng = np.random.default_rng(11)
    d = cl.ContactLaw(cl.profiles.Paraboloid, R=np.linspace(2e-3, 9e-3, n), E_star=1.15e11,
                      G_star=4.4e10, G_torsion=4e10, friction=0.3).normal(
                          force=rng.uniform(1.0, 100.0, n))[0]

    def run(law, restore=False):
        outs = []
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", ValidityWarning)
            for k in range(steps):
                if restore and k == at:
                    np.savez(tmp_path / "old.npz", **_old_format(law.state, law))
                    law = _law(n, fast)
                    with np.load(tmp_path / "old.npz") as f:
                        law.state = dict(f)
                D = d * np.where(np.arange(n) % 2 == 0, 1.0 + 0.02 * np.sin(0.6 * k), 1.0)
                r = law.step(depth=D, displacement=1e-8 * np.sin(0.7 * k + np.arange(n)),
                             twist=1e-4 * np.cos(0.5 * k + np.arange(n)))
                outs.append({f: getattr(r, f).copy() for f in FIELDS})
        return law, outs

    through, a = run(_law(n, fast))
    restored, b = run(_law(n, fast), restore=True)
    assert through.state["spr_on"].sum() == n // 2
    for k, (x, y) in enumerate(zip(a, b)):
        for f in FIELDS:
            assert x[f].tobytes() == y[f].tobytes(), f"step {k}: {f}"
    for key, v in through.state.items():
        np.testing.assert_array_equal(v, restored.state[key], err_msg=key)
    both = dict(through.state, spr_S=np.zeros((n, 16)))
    with pytest.raises(cl.errors.ParameterError, match="unknown keys \\['spr_S'\\]"):
        restored.state = both


@pytest.mark.parametrize("fast", BACKENDS)
def test_a_state_saved_before_spr_a_continues_a_force_driven_power_law(fast, tmp_path):
    """By force, on a PowerLaw (n = 1.5), the radius recomputed from the stored depth may differ
    from the force's by an ulp: the run continues within OLD_SPRING_STATE of the largest value
    (the contacts at constant load to the bit)."""
    n, steps, at = 40, 16, 9
    F0 = np.random.default_rng(11).uniform(1.0, 100.0, n)

    def make():
        return cl.ContactLaw(cl.profiles.PowerLaw, n=1.5, c=np.linspace(1e2, 1e3, n),
                             E_star=1.15e11, G_star=4.4e10, G_torsion=4e10, friction=0.3,
                             fast=fast)

    def run(restore):
        law, outs = make(), []
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", ValidityWarning)
            for k in range(steps):
                if restore and k == at:
                    np.savez(tmp_path / "old.npz", **_old_format(law.state, law))
                    law = make()
                    with np.load(tmp_path / "old.npz") as f:
                        law.state = dict(f)
                L = F0 * np.where(np.arange(n) % 2 == 0, 1.0 + 0.02 * np.sin(0.6 * k), 1.0)
                r = law.step(force=L, displacement=1e-8 * np.sin(0.7 * k + np.arange(n)),
                             twist=1e-4 * np.cos(0.5 * k + np.arange(n)))
                outs.append({f: getattr(r, f).copy() for f in FIELDS})
        return outs

    a, b = run(False), run(True)
    held = np.arange(n) % 2 == 1
    for k, (x, y) in enumerate(zip(a, b)):
        for f in FIELDS:
            assert x[f][held].tobytes() == y[f][held].tobytes(), f"step {k}: {f}"
            if f == "exact":
                np.testing.assert_array_equal(x[f], y[f])
                continue
            np.testing.assert_allclose(y[f], x[f], rtol=0, err_msg=f"step {k}: {f}",
                                       atol=OLD_SPRING_STATE * np.max(np.abs(x[f])))


@pytest.mark.parametrize("fast", BACKENDS)
def test_reserved_spring_rows_change_no_result(fast):
    """``spring_reserve`` allocates the rows of that fraction of the contacts with the law (and
    again after ``reset()``); a changing-load run with resets (rows moved, the pool grown past
    the reservation) gives the bits and the state of a law without it."""
    n = 400                                         # a half switches: past the reservation
    lazy, kept = _law(n, fast), _law(n, fast, spring_reserve=0.25)
    assert lazy._pool.capacity == 0 and kept._pool.capacity == 100 and kept._pool.used == 0
    for x, y in zip(_run(lazy, n), _run(kept, n)):
        for f in FIELDS:
            assert x[f].tobytes() == y[f].tobytes(), f
    for key, v in lazy.state.items():
        np.testing.assert_array_equal(v, kept.state[key], err_msg=key)
    kept.reset()
    assert kept._pool.capacity == 100 and kept._pool.used == 0


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="MADV_POPULATE_WRITE: Linux")
@pytest.mark.skipif(not HAS_NUMBA, reason="numba (extra 'fast') not installed")
def test_reserved_rows_take_no_page_faults_in_the_first_changing_step():
    """The reserved rows are faulted in when the law is built: the first changing-load step of
    a reserved law allocates no rows (the pool's arrays are the ones built with the law) and
    takes fewer minor page faults than the same step of a lazy law, which faults the pool's
    per-spring pages (2 x 128 B per row, 2500 pages) in then: by at least half of them (the
    step's result arrays fault a varying number of pages of their own, as malloc reuses memory;
    the compiled step: the numpy step's temporaries vary more)."""
    fast = True
    from contactlab.effects import law_pool
    n = 40000                        # per-spring arrays 5.1 MB: memory maps (>= 4 MB)
    probe = law_pool._mapped((1024, 1024), np.dtype(np.float64), 512)
    f0 = resource.getrusage(resource.RUSAGE_SELF).ru_minflt
    probe[:512] = 1.0
    if resource.getrusage(resource.RUSAGE_SELF).ru_minflt - f0 > 64:
        pytest.skip("madvise(MADV_POPULATE_WRITE) not supported by this kernel")
    F = np.random.default_rng(2).uniform(1.0, 100.0, n)
    faults = []
    for reserve in (0.0, 1.0):
        law = _law(n, fast, spring_reserve=reserve)
        law.step(force=F, displacement=1e-8)
        built = [law._pool.owner, *law._pool.rows.values()]
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", ValidityWarning)
            f0 = resource.getrusage(resource.RUSAGE_SELF).ru_minflt
            law.step(force=1.01 * F, displacement=2e-8)
            faults.append(resource.getrusage(resource.RUSAGE_SELF).ru_minflt - f0)
        assert law._pool.used == n
        same = all(a is b for a, b in zip(built, [law._pool.owner, *law._pool.rows.values()]))
        assert same == (reserve == 1.0)                 # no rows allocated in the step
    assert faults[0] - faults[1] >= 2 * n * 128 // 4096 // 2, faults


@pytest.mark.parametrize("bad", [-0.1, 1.5, float("nan"), True, "half", [0.5]])
def test_spring_reserve_must_be_a_fraction(bad):
    with pytest.raises(cl.errors.ParameterError, match="spring_reserve"):
        _law(10, False, spring_reserve=bad)


def test_reserved_rows_are_checked_against_the_budget_with_the_law():
    """The reservation is counted with the law (law_memory with its rows): refused at
    construction when it does not fit, while the lazy law fits."""
    previous = cl.set_memory_budget(10e6)
    try:
        _law(1000, False, springs=4096)
        with pytest.raises(MemoryBudgetError, match="spring_reserve=1"):
            _law(1000, False, springs=4096, spring_reserve=1.0)
    finally:
        cl.set_memory_budget(previous)
