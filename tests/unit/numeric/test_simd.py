"""The kind of machine and numpy's SIMD level, read from numpy's CPU table, and the fallbacks
where that private table is not there."""
import pytest

from contactlab.numeric import simd


def test_kind_and_level_agree_with_numpy_s_table():
    from numpy._core._multiarray_umath import __cpu_dispatch__, __cpu_features__
    kind = simd.machine_kind()
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
    assert simd.machine_kind() == kind
    assert simd.simd_level() == level


def test_without_numpy_s_table_one_kind_and_no_level(monkeypatch):
    monkeypatch.setattr(simd, "_tables", lambda: None)
    assert simd.machine_kind() == "baseline"
    assert simd.simd_level() is None
