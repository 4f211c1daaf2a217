"""Which vectorised loops numpy runs on this CPU: the last bits of some results depend on it.

numpy dispatches some functions (``cbrt``, ``power``, ``exp`` among them) to SIMD loops chosen by
the instruction sets the CPU has, and OpenBLAS chooses its kernels by CPU. Results that go
through them can therefore differ in their last bits between an AVX-512 machine and an AVX2
one, while every machine is deterministic on its own. The stored result hashes of the tests are
kept per kind of machine, and the benchmarks name the level they ran at; both read it here.

numpy says it only through a private table (``numpy._core._multiarray_umath``); where that moves,
both functions fall back (one kind, no level) instead of failing. OpenBLAS says which kernels it
chose (its core name, read through threadpoolctl, extra ``fast``); a CPU whose numpy loops and
BLAS kernels belong to different families (an AVX-512 CPU on which OpenBLAS runs its AVX2
kernels, as on AMD Zen 5 with OpenBLAS 0.3.31) is a kind of its own.
"""
from __future__ import annotations

import importlib

__all__ = ["machine_kind", "simd_level", "blas_kind"]

#: OpenBLAS core names (lower case) by the family of kernels they run
_BLAS_FAMILIES = {"skylakex": "avx512", "cooperlake": "avx512", "sapphirerapids": "avx512",
                  "haswell": "avx2", "zen": "avx2"}


def _tables() -> tuple[tuple[str, ...], dict[str, bool]] | None:
    """numpy's dispatch targets and CPU features, or None where numpy does not expose them."""
    try:
        umath = importlib.import_module("numpy._core._multiarray_umath")
        return tuple(umath.__cpu_dispatch__), dict(umath.__cpu_features__)
    except (ImportError, AttributeError):     # pragma: no cover - other numpy versions
        return None


def _numpy_kind() -> str:
    got = _tables()
    if got is None:
        return "baseline"
    feats = got[1]
    if feats.get("AVX512F") and feats.get("AVX512_SKX"):
        return "avx512"
    return "avx2" if feats.get("AVX2") and feats.get("FMA3") else "baseline"


def _blas_cores() -> tuple[str, ...] | None:
    """The core names of the OpenBLAS libraries loaded with scipy's linear algebra (lower case),
    or None without threadpoolctl."""
    import scipy.linalg  # noqa: F401  (loads scipy's own BLAS before the look-up)
    try:
        from threadpoolctl import threadpool_info
    except ImportError:
        return None
    return tuple(sorted({str(i.get("architecture", "")).lower() for i in threadpool_info()
                         if i.get("internal_api") == "openblas" and i.get("architecture")}))


def blas_kind() -> str | None:
    """The family of the kernels OpenBLAS runs on this CPU: ``"avx512"`` (SkylakeX, Cooperlake,
    SapphireRapids), ``"avx2"`` (Haswell, Zen), another core's name in lower case, several
    joined by ``"-"`` where the loaded libraries differ; None where it is not known (no
    threadpoolctl, or no OpenBLAS)."""
    cores = _blas_cores()
    if not cores:
        return None
    return "-".join(sorted({_BLAS_FAMILIES.get(c, c) for c in cores}))


def machine_kind() -> str:
    """The kind of machine as far as the last bits of results go: numpy's vectorised loops,
    ``"avx512"`` (AVX512F and AVX512_SKX), ``"avx2"`` (AVX2 and FMA3) or ``"baseline"``
    (anything else, and wherever numpy does not expose its CPU table); followed by
    ``"-blas-"`` and the BLAS kernels' family (:func:`blas_kind`) where that family is known
    and differs (e.g. ``"avx512-blas-avx2"``)."""
    kind = _numpy_kind()
    blas = blas_kind()
    return kind if blas is None or blas == kind else f"{kind}-blas-{blas}"


def simd_level() -> str | None:
    """numpy's highest dispatch target this CPU has (e.g. ``"X86_V3"``; ``"X86_V4"``: AVX-512),
    ``"baseline only"`` when it has none, None where numpy does not say."""
    got = _tables()
    if got is None:
        return None
    dispatch, feats = got
    found = [f for f in dispatch if feats.get(f)]
    return found[-1] if found else "baseline only"
