"""Which vectorised loops numpy runs on this CPU: the last bits of some results depend on it.

numpy dispatches some functions (``cbrt``, ``power``, ``exp`` among them) to SIMD loops chosen by
the instruction sets the CPU has, and OpenBLAS chooses its kernels by CPU. Results that go
through them can therefore differ in their last bits between an AVX-512 machine and an AVX2
one, while every machine is deterministic on its own. The stored result hashes of the tests are
kept per kind of machine, and the benchmarks name the level they ran at; both read it here.

numpy says it only through a private table (``numpy._core._multiarray_umath``); where that moves,
both functions fall back (one kind, no level) instead of failing.
"""
from __future__ import annotations

import importlib

__all__ = ["machine_kind", "simd_level"]


def _tables() -> tuple[tuple[str, ...], dict[str, bool]] | None:
    """numpy's dispatch targets and CPU features, or None where numpy does not expose them."""
    try:
        umath = importlib.import_module("numpy._core._multiarray_umath")
        return tuple(umath.__cpu_dispatch__), dict(umath.__cpu_features__)
    except (ImportError, AttributeError):     # pragma: no cover - other numpy versions
        return None


def machine_kind() -> str:
    """The kind of machine as far as numpy's vectorised loops go: ``"avx512"`` (AVX512F and
    AVX512_SKX), ``"avx2"`` (AVX2 and FMA3) or ``"baseline"`` (anything else, and wherever numpy
    does not expose its CPU table)."""
    got = _tables()
    if got is None:
        return "baseline"
    feats = got[1]
    if feats.get("AVX512F") and feats.get("AVX512_SKX"):
        return "avx512"
    return "avx2" if feats.get("AVX2") and feats.get("FMA3") else "baseline"


def simd_level() -> str | None:
    """numpy's highest dispatch target this CPU has (e.g. ``"X86_V3"``; ``"X86_V4"``: AVX-512),
    ``"baseline only"`` when it has none, None where numpy does not say."""
    got = _tables()
    if got is None:
        return None
    dispatch, feats = got
    found = [f for f in dispatch if feats.get(f)]
    return found[-1] if found else "baseline only"
