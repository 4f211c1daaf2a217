"""Optional compiled kernels of the MDR foundation (extra ``fast``: numba), numpy as reference.

Plain-array signatures, no object state, so other drivers (a DEM contact law, a viscoelastic
foundation) can call them directly:

``jenkins_update(m, K, invK, L, inc) -> float``
    Advance Jenkins elements (springs of stiffness ``K`` in series with Coulomb sliders of limit
    ``L >= 0``) in place by the displacement increment ``inc``: ``m ← clip(m + K inc, -L, L)``;
    returns the energy dissipated, ``Σ (trial - m) m / K`` (``invK = 1/K``; any finite value
    where ``K = 0``). Float64 arrays of one length, ``m`` writable.

The numba version is used automatically when numba imports (``backend() == "numba"``); numpy is
the reference and the fallback (``CONTACTLAB_BACKEND=numpy`` or :func:`set_backend` forces it).
The element updates are bit-identical between the two; the dissipated energy is a sum in another
order (sequential against numpy's pairwise), equal to ~``N`` ulps, far below 1e-12 relative for
the spring counts in use. numba compiles the kernel on its first call in a process (~1 s).
"""
from __future__ import annotations

import os

import numpy as np

__all__ = ["jenkins_update", "jenkins_update_numpy", "backend", "set_backend", "available"]

_state: dict = {"backend": None, "kernel": None}


def jenkins_update_numpy(m: np.ndarray, K: np.ndarray, invK: np.ndarray, L: np.ndarray,
                         inc: float, tmp: np.ndarray | None = None,
                         nL: np.ndarray | None = None) -> float:
    """Reference numpy implementation of :func:`jenkins_update` (``tmp``: optional scratch,
    ``nL``: ``-L`` if the caller keeps it)."""
    tmp = np.empty_like(m) if tmp is None else tmp
    nL = -L if nL is None else nL
    np.multiply(K, inc, out=tmp)
    tmp += m
    np.minimum(tmp, L, out=m)
    np.maximum(m, nL, out=m)
    tmp -= m
    tmp *= m
    tmp *= invK
    # a plain (pairwise) sum, not np.dot: a BLAS dot runs multithreaded on long vectors and
    # costs 50x more at N = 10^5 on a loaded machine (and its result follows the thread count)
    return float(tmp.sum())


def _numba_kernel():
    import numba

    @numba.njit(cache=False, fastmath=False, nogil=True)
    def jenkins_numba(m, K, invK, L, inc):     # pragma: no cover - compiled
        w = 0.0
        for i in range(m.size):
            t = K[i] * inc + m[i]
            v = min(t, L[i])
            v = max(v, -L[i])
            m[i] = v
            w += (t - v) * v * invK[i]
        return w

    return jenkins_numba


def available() -> tuple[str, ...]:
    """Backends usable in this environment (``"numpy"`` always)."""
    try:
        import numba  # noqa: F401
    except ImportError:
        return ("numpy",)
    return ("numpy", "numba")


def set_backend(name: str | None) -> None:
    """Force ``"numpy"`` or ``"numba"``; ``None`` returns to the automatic choice."""
    from ..errors import ParameterError
    if name is not None and name not in available():
        raise ParameterError(f"backend={name!r} is invalid: available here: "
                             f"{', '.join(available())} (numba comes with the extra 'fast').")
    _state["backend"], _state["kernel"] = name, None


def backend() -> str:
    """The backend :func:`jenkins_update` uses (chosen on first use)."""
    name = _state["backend"]
    if name is None:
        forced = os.environ.get("CONTACTLAB_BACKEND", "").strip().lower()
        name = forced if forced in available() else available()[-1]
        _state["backend"] = name
    return name


def jenkins_update(m: np.ndarray, K: np.ndarray, invK: np.ndarray, L: np.ndarray,
                   inc: float, tmp: np.ndarray | None = None,
                   nL: np.ndarray | None = None) -> float:
    """Advance Jenkins elements in place by ``inc``; return the dissipated energy, J (see module)."""
    kernel = _state["kernel"]
    if kernel is None:
        kernel = _numba_kernel() if backend() == "numba" else jenkins_update_numpy
        _state["kernel"] = kernel
    if kernel is jenkins_update_numpy:
        return jenkins_update_numpy(m, K, invK, L, inc, tmp, nL)
    return float(kernel(m, K, invK, L, float(inc)))
