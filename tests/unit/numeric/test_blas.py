"""numeric.blas.serial_blas: one BLAS thread inside the block, the setting restored after the last
block (nested and concurrent blocks included)."""
from __future__ import annotations

import threading

import numpy as np
import pytest

from contactlab.numeric import blas


def _threads() -> list[int]:
    ctl = blas._controller()
    if ctl is None:
        pytest.skip("threadpoolctl is not installed (extra 'fast')")
    return [int(i["num_threads"]) for i in ctl.info() if i["user_api"] == "blas"]


def test_one_thread_inside_and_the_setting_restored_after():
    before = _threads()
    if not before:
        pytest.skip("no BLAS library found by threadpoolctl")
    with blas.serial_blas():
        assert set(_threads()) == {1}
        with blas.serial_blas():             # nested: still one thread
            assert set(_threads()) == {1}
        assert set(_threads()) == {1}        # the inner block does not give the limit back
    assert _threads() == before


def test_concurrent_blocks_hold_the_limit_until_the_last_ends():
    if not _threads():
        pytest.skip("no BLAS library found by threadpoolctl")
    before = _threads()
    inside, leave = threading.Event(), threading.Event()
    seen: list[list[int]] = []

    def worker():
        with blas.serial_blas():
            inside.set()
            leave.wait(10)
            seen.append(_threads())

    t = threading.Thread(target=worker)
    t.start()
    inside.wait(10)
    with blas.serial_blas():
        pass                                 # ends first: must not restore while t is inside
    # the limit is still held, by the holder and in the library
    assert blas._HELD["count"] == 1 and blas._HELD["limiter"] is not None
    assert set(_threads()) == {1}
    leave.set()
    t.join()
    assert len(seen) == 1
    assert blas._HELD["count"] == 0 and blas._HELD["limiter"] is None
    assert _threads() == before


def test_a_block_in_a_worker_thread_runs_on_one_thread_too():
    """After the main thread has held the limit, a block entered first in a worker thread still
    gets one BLAS thread (threadpoolctl >= 3.8 would otherwise ignore the worker's setting and
    the worker's results would follow the process's thread count in their last bits)."""
    before = _threads()
    if not before:
        pytest.skip("no BLAS library found by threadpoolctl")
    with blas.serial_blas():                 # the main thread sets (and gives back) a limit first
        pass
    seen: list[list[int]] = []

    def worker():
        with blas.serial_blas():
            seen.append(_threads())

    for _ in range(2):
        t = threading.Thread(target=worker)
        t.start()
        t.join()
    assert seen == [[1] * len(before)] * 2
    assert _threads() == before              # given back by the worker
    with blas.serial_blas():                 # and the main thread can take it again
        assert set(_threads()) == {1}
    assert _threads() == before


def test_exact_path_in_a_worker_thread_has_the_main_threads_bits():
    """The exact ring solver (small dense solves inside serial_blas) gives the same bits in a
    worker thread as in the main thread, whatever BLAS thread count the process has."""
    import contactlab as cl
    from contactlab import profiles as P

    if not _threads():
        pytest.skip("no BLAS library found by threadpoolctl")
    steel = cl.Elastic(E=210e9, nu=0.3)
    r = np.linspace(0.0, 2e-3, 300)

    def run() -> bytes:
        c = cl.Contact(P.Tabulated(r=r, f=r**2 / 0.02 + 1e3 * r**3), materials=(steel, steel),
                       friction=0.3)
        path = (cl.LoadPath().ramp(force=10.0, steps=5).ramp(twist=2e-4, steps=6)
                .ramp(force=20.0, twist=-1e-4, steps=6))
        res = c.simulate(path, method="exact", n_rings=60)
        return b"".join(np.asarray(v, float).tobytes() for v in res.data.values())

    main = run()
    got: list[bytes] = []
    t = threading.Thread(target=lambda: got.append(run()))
    t.start()
    t.join()
    assert got == [main]


def test_results_inside_are_the_plain_results():
    a = np.arange(9.0).reshape(3, 3) + 3 * np.eye(3)
    with blas.serial_blas():
        x = np.linalg.solve(a, np.ones(3))
    np.testing.assert_allclose(a @ x, np.ones(3), rtol=1e-14)
