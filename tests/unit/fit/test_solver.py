"""The two stops around MINPACK's Levenberg-Marquardt: at the rounding of a noise-free model,
and when the sum of squares stalls (a model with a jump, where MINPACK would creep on to
max_nfev)."""
from __future__ import annotations

import numpy as np

from contactlab.fit._tip import STALL_WINDOW, levenberg_marquardt

X = np.linspace(0.0, 1.0, 50)


def test_floor_stops_a_noise_free_fit_at_rounding():
    y = 2.0 * X + 0.5

    def res(p):
        return p[0] * X + p[1] - y

    def jac(p):
        return np.stack([X, np.ones_like(X)], axis=1)

    _, n_free, ok_free, _ = levenberg_marquardt(res, jac, np.array([1.0, 0.0]))
    x, n, ok, msg = levenberg_marquardt(res, jac, np.array([1.0, 0.0]),
                                        floor=(1e-13 ** 2) * float(y @ y))
    assert ok and ok_free and "rounding" in msg
    assert n < n_free                               # the tail on rounding noise is skipped
    np.testing.assert_allclose(x, [2.0, 0.5], rtol=1e-12)


def test_stall_stops_a_creeping_fit():
    """A jump (a penalty once p0 + p1 > 1.5) holds the least squares on its edge: MINPACK
    creeps along it by rejected and tiny accepted steps; the stall stop ends the creep earlier
    at a sum of squares within the stall's tolerance of MINPACK's own end."""
    def res(p):
        return np.array([p[0] - 1.0, 3.0 * (p[1] - 1.0), 10.0 if p[0] + p[1] > 1.5 else 0.0])

    def jac(p):
        return np.array([[1.0, 0.0], [0.0, 3.0], [0.0, 0.0]])

    x0 = np.array([0.0, 0.2])
    x_m, n_m, ok_m, _ = levenberg_marquardt(res, jac, x0)
    x, n, ok, msg = levenberg_marquardt(res, jac, x0, stall=1e-3)
    assert ok and ok_m and "fell by less than" in msg
    assert STALL_WINDOW < n < n_m
    ss, ss_m = float(res(x) @ res(x)), float(res(x_m) @ res(x_m))
    assert ss_m <= ss <= ss_m * (1.0 + 1e-3)
