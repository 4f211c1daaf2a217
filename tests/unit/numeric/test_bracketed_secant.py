"""``bracketed_root(secant_start=True)`` (issue 28): the first step at the secant of a bracket
with known end values. Same roots as the classic midpoint start (to the solve's tolerance),
fewer evaluations from a tight bracket, and the classic start stays the default."""
import numpy as np

from contactlab.numeric.roots import bracketed_root


def _solve(secant, lo, hi, target):
    calls = []

    def f(x, idx):
        calls.append(x.size)
        return np.exp(x) + x**3            # increasing, smooth

    out = bracketed_root(f, target, lo, hi, rtol=1e-13, f_lo=f(lo, None), f_hi=f(hi, None),
                         secant_start=secant)
    return out, sum(calls[2:])               # element evaluations of the solve itself


def test_secant_start_same_roots_fewer_passes():
    rng = np.random.default_rng(4)
    root = rng.uniform(-2.0, 2.0, 500)
    target = np.exp(root) + root**3
    lo, hi = root - 1e-5 * rng.random(500), root + 1e-5 * rng.random(500)
    a, n_mid = _solve(False, lo, hi, target)
    b, n_sec = _solve(True, lo, hi, target)
    # both to the solve's tolerance: the exact root is known
    np.testing.assert_allclose(a, root, rtol=0, atol=1e-12)
    np.testing.assert_allclose(b, root, rtol=0, atol=1e-12)
    assert n_sec < n_mid


def test_secant_start_is_off_by_default():
    def f(x, idx):
        return x**3

    seen = []

    def spy(x, idx):
        seen.append(x.copy())
        return f(x, idx)
    bracketed_root(spy, 0.3, 0.0, 1.0, f_lo=0.0, f_hi=1.0)
    assert seen[0][0] == 0.5                  # the classic first step: the midpoint
