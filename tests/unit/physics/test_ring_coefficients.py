"""The ring solver's coefficients in one LAPACK call per chunk of steps
(:func:`contactlab.physics.torsion_annulus.coefficients`; issue 28, 180-step path row).

Must show: the coefficients solve the traction-per-basis system (against scipy's ``lu_solve``
and the matrix itself); a row's coefficients are the same bits alone, in any batch, at any
position in it, and through :func:`~contactlab.physics.torsion_annulus.density` (so a step's
full-sliding density does not depend on how many steps share the call).
"""
import numpy as np
import scipy.linalg as la

from contactlab.physics import torsion_annulus as ta
from contactlab.physics import torsion_rings as tr
from tests import tolerances as TOL


def _system(n=120):
    b = np.linspace(0.0, 1.0, n + 1)
    r = 0.5 * (b[1:] + b[:-1])
    lu = tr.influence(b, r, 1.0)["lu"]
    rng = np.random.default_rng(3)
    values = 0.3 * np.sqrt(np.clip(1.0 - r * r, 0.0, None)) * (0.5 + rng.random((40, 1)))
    values[::3] *= np.where(r < 0.7, 1.0, 0.0)          # some contact radii smaller
    return b, lu, values


def test_coefficients_solve_the_system():
    _, lu, values = _system()
    coef = ta.coefficients(lu, values)
    ref = la.lu_solve(lu, values.T, check_finite=False).T
    assert coef.shape == values.shape
    assert np.max(np.abs(coef - ref)) <= TOL.CLOSED_FORM * np.max(np.abs(ref))


def test_a_rows_coefficients_do_not_depend_on_the_batch():
    b, lu, values = _system()
    whole = ta.coefficients(lu, values)
    rng = np.random.default_rng(4)
    for rows in ([0], [7], [5, 6], list(range(3, 40)), list(rng.permutation(40)[:17])):
        part = ta.coefficients(lu, values[rows])
        assert part.tobytes() == whole[rows].tobytes(), rows
    for j in (0, 13, 39):
        alone = ta.density(lu, b, np.zeros(0, int), values[j], 0.9)
        batch = ta.from_coefficients(b, whole[j], np.zeros(0, int), 0.9)
        assert all(u.tobytes() == v.tobytes() for u, v in zip(alone, batch))


def test_concurrent_solves_on_shared_factors():
    """Threads solving on one ring set's cached (shared, read-only) factors: the same bits as
    alone and the pivots intact (scipy's getrs wrapper shifts the pivots in place for the call,
    outside the GIL: shared, concurrent calls corrupted them and aborted the process)."""
    import threading

    _, lu, values = _system()
    for a in lu:
        a.flags.writeable = False
    piv = lu[1].copy()
    want = ta.coefficients(lu, values[:8])
    bad = []

    def work():
        for _ in range(300):
            if ta.coefficients(lu, values[:8]).tobytes() != want.tobytes():
                bad.append(1)

    threads = [threading.Thread(target=work) for _ in range(6)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert not bad and np.array_equal(lu[1], piv)
