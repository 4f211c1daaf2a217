"""The linearly implicit wear step (issue 28): the wear rate's Jacobian against finite differences
of the rate kernels, and the Rosenbrock-W step's order and stability against closed-form ODE
solutions."""
from __future__ import annotations

import numpy as np
import pytest

import contactlab as cl
from contactlab.physics import wear as W
from contactlab.physics import wear_rosenbrock as ros
from tests.tolerances import WEAR_JACOBIAN_FD, WEAR_STEP_ORDER

STEEL = cl.Elastic(E=210e9, nu=0.3)
MU, F = 0.5, 100.0


def _setup(n=60, R_grid=4e-4):
    c = cl.Contact(cl.profiles.Paraboloid(R=0.01), materials=(STEEL, STEEL), friction=MU)
    E = c.moduli.normal
    ops = W.operators(R_grid, n)
    r = ops["r"]
    f0 = np.asarray(c.profile.height(r), float)
    rng = np.random.default_rng(0)
    h = 1e-8 * np.exp(-(r / 1.5e-4) ** 2) * (1 + 0.1 * rng.random(r.size))   # a worn state
    return c, E, ops, r, f0, h


CASES = [("tangential", 1e-6, "mdr"), ("tangential", 2e-5, "mdr"), ("torsion", 3e-3, "exact"),
         ("torsion", 0.133, "exact"), ("torsion", 3e-3, "mdr")]


@pytest.mark.parametrize("mode,amp,method", CASES, ids=[f"{m}-{a}-{x}" for m, a, x in CASES])
def test_rate_jacobian_matches_finite_differences(mode, amp, method):
    c, E, ops, r, f0, h = _setup()
    Gm = c.moduli.tangential if mode == "tangential" else c.moduli.torsional
    jops = ros.jacobian_operators(ops, E)

    def q(y):
        g = W.transform(ops, f0 + y)
        d = W.normal_depth(g, ops["w1"], E, F)
        if mode == "tangential":
            return W.tangential_rate(ops, g, d, E, Gm, MU, amp)[0]
        return W.torsion_rate(ops, g, d, E, Gm, MU, amp, method)[0]

    g = W.transform(ops, f0 + h)
    d = W.normal_depth(g, ops["w1"], E, F)
    J = ros.rate_jacobian(ops, jops, g, d, E, Gm, MU, amp, mode, method)
    eps = 1e-13                                   # 1e-5 of the wear depth: no kink is crossed
    fd = np.array([(q(h + eps * e) - q(h - eps * e)) / (2 * eps) for e in np.eye(r.size)]).T
    assert np.max(np.abs(J - fd)) <= WEAR_JACOBIAN_FD * np.max(np.abs(fd))
    # the padded matrix adds a damping self-coupling on the diagonal of the two nodes beyond the
    # edge and changes nothing else
    Jp = ros.rate_jacobian(ops, jops, g, d, E, Gm, MU, amp, mode, method, edge=2)
    last = int(np.flatnonzero(d - g > 0)[-1])
    pad = [last + 1, last + 2]
    diff = Jp - J
    assert np.all(diff[pad, pad] <= 0) and np.any(diff[pad, pad] < 0)
    diff[pad, pad] = 0.0
    assert not np.any(diff)


LAM = 1.0


def _f(y):
    """y0' = -y0², y1' = -λ(y1 - y0) - y0²: y0 = 1/(1+t), y1 = y0 + (y1(0) - 1) e^{-λt}."""
    return np.array([-y[0] ** 2, -LAM * (y[1] - y[0]) - y[0] ** 2])


def _exact(t, y10):
    return np.array([1 / (1 + t), 1 / (1 + t) + (y10 - 1) * np.exp(-LAM * t)])


def _run(n, J, T=1.0, y10=2.0):
    y = np.array([1.0, y10])
    tau = T / n
    lu = ros.factor(J, tau)
    est = 0.0
    for _ in range(n):
        y, e, _ = ros.rosenbrock_step(_f, y, _f(y), tau, J, lu, tau)
        est = max(est, float(np.max(np.abs(e))))
    return float(np.max(np.abs(y - _exact(T, y10)))), est


@pytest.mark.parametrize("J", [np.array([[-2.0, 0.0], [-1.0, -1.0]]),      # the exact one at t=0
                               np.zeros((2, 2)),                             # none (explicit)
                               np.array([[0.3, -1.0], [0.2, 0.7]])],         # a wrong one
                         ids=["jacobian", "zero", "wrong"])
def test_w_method_is_third_order_with_any_matrix(J):
    """ROS34PW2 is a W-method: order 3 whatever matrix stands in for the Jacobian; its embedded
    estimate (the order-2 solution's local error) falls as the step cubed."""
    ns = np.array([16, 32, 64, 128])
    errs, ests = np.array([_run(n, J) for n in ns]).T
    order = -np.polyfit(np.log(ns), np.log(errs), 1)[0]
    est_order = -np.polyfit(np.log(ns), np.log(ests), 1)[0]
    assert abs(order - 3) < WEAR_STEP_ORDER
    assert abs(est_order - 3) < WEAR_STEP_ORDER


def test_stiff_mode_is_damped_at_long_steps():
    """λ = 1e8 with steps of 0.05: far beyond any explicit limit (2/λ), the step stays stable and
    the fast mode is gone after one step (L-stable, stiffly accurate)."""
    global LAM
    LAM, old = 1e8, LAM
    try:
        J = np.array([[-2.0, 0.0], [LAM - 2.0, -LAM]])
        err, _ = _run(20, J)
    finally:
        LAM = old
    assert err < 1e-5


def test_block_factor_solves_as_the_dense_matrix():
    """factor() factors only the leading block that holds the off-diagonal entries (the wear
    Jacobian beyond the contact edge is a padded diagonal or zero): its solves equal those of the
    dense ``I - γ dN J`` to rounding, and a full matrix is factored whole."""
    import scipy.linalg
    rng = np.random.default_rng(1)
    n, lead = 40, 13
    J = np.zeros((n, n))
    J[:lead, :lead] = rng.normal(size=(lead, lead))
    J[np.arange(lead, lead + 3), np.arange(lead, lead + 3)] = -5.0       # padded diagonal
    for M in (J, rng.normal(size=(n, n))):
        lu = ros.factor(M, 0.3)
        rhs = rng.normal(size=n)
        dense = scipy.linalg.solve(np.eye(n) - ros.GAMMA * 0.3 * M, rhs)
        assert np.allclose(ros._solve(lu, rhs), dense, rtol=1e-12, atol=1e-12)
    assert ros.factor(J, 0.3)[1] == lead


@pytest.mark.parametrize("mode,amp,method", CASES, ids=[f"{m}-{a}-{x}" for m, a, x in CASES])
def test_windowed_rates_equal_the_full_grid(mode, amp, method):
    """The implicit route evaluates the rates on the nodes the contact covers (``window=True``):
    every rate beyond is zero, so the same values to rounding, and the same stick and contact
    radii."""
    c, E, ops, _, f0, h = _setup(n=120, R_grid=8e-4)
    Gm = c.moduli.tangential if mode == "tangential" else c.moduli.torsional
    g = W.transform(ops, f0 + h)
    d = W.normal_depth(g, ops["w1"], E, F)
    assert d - g[-1] < 0                            # the window is a real cut
    if mode == "tangential":
        full, win = (W.tangential_rate(ops, g, d, E, Gm, MU, amp, w) for w in (False, True))
    else:
        full, win = (W.torsion_rate(ops, g, d, E, Gm, MU, amp, method, w) for w in (False, True))
    assert np.allclose(win[0], full[0], rtol=1e-12, atol=1e-12 * np.max(full[0]))
    assert win[1:] == pytest.approx(full[1:], rel=1e-12)
