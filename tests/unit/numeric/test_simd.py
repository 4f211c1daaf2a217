"""The kind of machine and numpy's SIMD level, read from numpy's CPU table, and the fallbacks
where that private table is not there."""
import pytest

from contactlab.numeric import simd


def test_kind_and_level_agree_with_numpy_s_table():
    from numpy._core._multiarray_umath import __cpu_dispatch__, __cpu_features__
    kind = simd.machine_kind().split("-blas-")[0]
    assert kind in ("avx512", "avx2", "baseline")
    level = simd.simd_level()
    assert level == "baseline only" or (level in __cpu_dispatch__ and __cpu_features__[level])
    if kind == "avx512":
        assert __cpu_features__["AVX512F"] and __cpu_features__["AVX512_SKX"]
    if kind == "avx2":
        assert __cpu_features__["AVX2"] and not __cpu_features__.get("AVX512_SKX")


@pytest.mark.parametrize("feats, dispatch, kind, level", [
    ({"AVX512F": True, "AVX512_SKX": True, "AVX2": True, "FMA3": True, "X86_V3": True,
      "X86_V4": True}, ("X86_V3", "X86_V4"),
     "avx512", "X86_V4"),
    ({"AVX2": True, "FMA3": True, "X86_V3": True}, ("X86_V3", "X86_V4"), "avx2", "X86_V3"),
    ({"AVX2": True, "FMA3": False}, ("X86_V3",), "baseline", "baseline only"),
])
def test_kinds_from_a_table(monkeypatch, feats, dispatch, kind, level):
    monkeypatch.setattr(simd, "_tables", lambda: (dispatch, feats))
    monkeypatch.setattr(simd, "_blas_cores", lambda: None)
    assert simd.machine_kind() == kind
    assert simd.simd_level() == level


def test_without_numpy_s_table_one_kind_and_no_level(monkeypatch):
    monkeypatch.setattr(simd, "_tables", lambda: None)
    monkeypatch.setattr(simd, "_blas_cores", lambda: None)
    assert simd.machine_kind() == "baseline"
    assert simd.simd_level() is None


@pytest.mark.parametrize("cores, numpy_kind, kind", [
    (("skylakex",), "avx512", "avx512"),
    (("cooperlake", "skylakex"), "avx512", "avx512"),
    (("zen",), "avx2", "avx2"),
    (("haswell", "zen"), "avx2", "avx2"),
    (("haswell",), "avx512", "avx512-blas-avx2"),       # AMD Zen 5 with OpenBLAS 0.3.31
    (("skylakex",), "avx2", "avx2-blas-avx512"),
    (("haswell", "skylakex"), "avx512", "avx512-blas-avx2-avx512"),
    (("sandybridge",), "avx2", "avx2-blas-sandybridge"),
    ((), "avx2", "avx2"),                               # no OpenBLAS: numpy's kind alone
    (None, "avx512", "avx512"),                         # no threadpoolctl
])
def test_kind_with_the_blas_kernels(monkeypatch, cores, numpy_kind, kind):
    """numpy's loops and OpenBLAS's kernels both set the last bits: a CPU whose two families
    differ is a kind of its own."""
    feats = ({"AVX512F": True, "AVX512_SKX": True, "AVX2": True, "FMA3": True}
             if numpy_kind == "avx512" else {"AVX2": True, "FMA3": True})
    monkeypatch.setattr(simd, "_tables", lambda: (("X86_V3", "X86_V4"), feats))
    monkeypatch.setattr(simd, "_blas_cores", lambda: cores)
    assert simd.machine_kind() == kind


def test_blas_kind_here_agrees_with_threadpoolctl():
    threadpoolctl = pytest.importorskip("threadpoolctl")
    import scipy.linalg  # noqa: F401
    cores = {i["architecture"].lower() for i in threadpoolctl.threadpool_info()
             if i.get("internal_api") == "openblas" and i.get("architecture")}
    blas = simd.blas_kind()
    if not cores:
        assert blas is None
    else:
        assert blas is not None and set(blas.split("-")) == {simd._BLAS_FAMILIES.get(c, c)
                                                             for c in cores}
