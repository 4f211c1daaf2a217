"""ContactLaw on an array-module backend (issue 29, GPU part): the step written once for any
array module (:mod:`contactlab.physics.law_xp`), run with numpy (``backend="xp-numpy"``)
equals the numpy reference law to the bit on random histories (every family, by force and by
depth, overflowing stacks, separation, a changing load onto the springs, a state saved and
restored in the middle); with CuPy on a GPU it agrees with the numpy law to GPU_VS_NUMPY
(skipped without CuPy or without a device); the errors of a backend that is not there and of
a law too large for the memory budget."""
from __future__ import annotations

import sys
import warnings
from typing import ClassVar

import numpy as np
import pytest

import contactlab as cl
from contactlab.effects import law_device, law_device_springs
from contactlab.numeric import cube_root
from contactlab.physics import law_kernel
from contactlab.errors import MemoryBudgetError, NotSupportedError, ParameterError
from contactlab.errors import UnknownNameError, ValidityWarning
from tests.tolerances import COMPILED_VS_NUMPY_SPRINGS, FUSED_HOST_SPRINGS_VS_NUMPY
from tests.tolerances import FUSED_HOST_VS_NUMPY, GPU_VS_NUMPY
from tests.unit.effects.test_law_compiled import FAMILIES, FIELDS, _changing_run, _history

KW = dict(E_star=1.15e11, G_star=4.4e10, G_torsion=4.0e10)


def _laws(family, gname, lo_hi, extra, seed, n, backend, reference="numpy", **kw):
    rng = np.random.default_rng(seed)
    par = dict({gname: rng.uniform(*lo_hi, n)}, friction=rng.uniform(0.1, 0.5, n), **KW,
               **extra, **kw)
    return (cl.ContactLaw(family, backend=backend, **par),
            cl.ContactLaw(family, backend=reference, **par), rng)


def _host_springs(monkeypatch, springs):
    """The host spring passes of a device law: "numpy" (the reference, forced) or "compiled"
    (skipped without numba); returns the backend of the CPU law with the same springs, whose
    results the device law's equal to the bit (constant load: the numba law's bits are the
    numpy law's for the paraboloid; springs: the same compiled passes)."""
    if springs == "numpy":
        monkeypatch.setattr(law_device_springs, "compiled", lambda xp: False)
        return "numpy"
    if not law_kernel.AVAILABLE:
        pytest.skip("numba is not installed")
    assert law_device_springs.compiled(_FakeCupy())
    return "numba"


def _run(dev, ref, rng, by, steps, n, host):
    """A random history (reversals, loop closures, separation, from step 40 a changing load
    on half the contacts) through both laws; yields ``(dev step as numpy, ref step)``."""
    F = rng.uniform(1.0, 100.0, n)
    u, phi = _history(rng, steps, n, 3e-8, 1e-4)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ValidityWarning)    # overflow; shift + twist together
        for k in range(steps):
            L = F.copy()
            if 20 <= k < 25:
                L[:10] = 0.0                                # separated, then back
            if k >= 40:
                L[n // 2:] *= 1.0 + 0.03 * np.sin(0.4 * k + np.arange(n - n // 2))
            load = L if by == "force" else ref.normal(force=L)[0]
            a = dev.step(**{by: load}, displacement=u[k], twist=phi[k])
            b = ref.step(**{by: load}, displacement=u[k], twist=phi[k])
            yield {f: host(getattr(a, f)) for f in FIELDS}, b, a


@pytest.mark.parametrize("by", ["force", "depth"])
@pytest.mark.parametrize("family, gname, lo_hi, extra", FAMILIES,
                         ids=[f[0].__name__ for f in FAMILIES])
def test_xp_numpy_equals_the_numpy_law_to_the_bit(family, gname, lo_hi, extra, by):
    """Every output, every model error and every state entry equal to the bit, step by step:
    memory=3 (stacks overflow), contacts separating and coming back, half the contacts onto
    their springs from step 40 (a changing load)."""
    n, steps = 80, 60
    dev, ref, rng = _laws(family, gname, lo_hi, extra, 29, n, "xp-numpy", memory=3)
    assert dev.backend == "xp-numpy" and dev._xp is np and not dev.fast
    for a, b, raw in _run(dev, ref, rng, by, steps, n, np.asarray):
        for f in FIELDS:
            np.testing.assert_array_equal(a[f], getattr(b, f), err_msg=f)
        assert raw.model_errors.keys() == b.model_errors.keys()
        for q, err in b.model_errors.items():
            np.testing.assert_array_equal(raw.model_errors[q], err, err_msg=q)
        assert raw.citations.tags == b.citations.tags
    sd, sr = dev.state, ref.state
    assert sr["tan_overflow"].any() and sr["tor_overflow"].any()
    assert sr["spr_on"][n // 2:].all() and not sr["spr_on"][: n // 2].any()
    assert sd.keys() == sr.keys()
    for key, v in sd.items():
        np.testing.assert_array_equal(v, sr[key], err_msg=key)


def test_xp_numpy_state_saved_and_restored_in_a_changing_load_run(tmp_path):
    """A law restored from law.state (through an .npz file) in the middle of a changing-load
    run continues to the bit as the law that ran through, and as the numpy law."""
    n, steps = 60, 30
    par = dict(R=np.linspace(2e-3, 9e-3, n), friction=0.3, memory=4, **KW)

    def make(backend="xp-numpy"):
        return cl.ContactLaw(cl.profiles.Paraboloid, backend=backend, **par)

    through, a = _changing_run(make(), 3, steps, n)
    restored, b = _changing_run(make(), 3, steps, n, restore_at=17, tmp_path=tmp_path,
                                make=make)
    numpy_law, c = _changing_run(make("numpy"), 3, steps, n)
    assert through.state["spr_on"][: n // 2].all()
    for k in range(steps):
        for f in FIELDS:
            np.testing.assert_array_equal(a[k][f], b[k][f], err_msg=f"step {k}: {f}")
            np.testing.assert_array_equal(a[k][f], c[k][f], err_msg=f"step {k}: {f}")
    for key, v in through.state.items():
        np.testing.assert_array_equal(v, restored.state[key], err_msg=key)
        np.testing.assert_array_equal(v, numpy_law.state[key], err_msg=key)


def test_xp_numpy_out_reset_and_constant_load_refusal(tmp_path):
    """``out=`` is overwritten and returned and writes the numpy law's CSV; ``reset`` clears
    the memory as on the numpy law; without springs a load change is refused with the numpy
    law's error."""
    par = dict(R=[0.01, 0.02, 0.03], friction=0.3, **KW)
    dev = cl.ContactLaw(cl.profiles.Paraboloid, backend="xp-numpy", springs=0, **par)
    ref = cl.ContactLaw(cl.profiles.Paraboloid, backend="numpy", springs=0, **par)
    out = dev.step(force=[1.0, 2.0, 3.0], displacement=1e-8)
    ref.step(force=[1.0, 2.0, 3.0], displacement=1e-8)
    got = dev.step(force=[1.0, 2.0, 3.0], displacement=-2e-8, out=out)
    want = ref.step(force=[1.0, 2.0, 3.0], displacement=-2e-8)
    assert got is out
    got.to_csv(tmp_path / "dev.csv")
    want.to_csv(tmp_path / "ref.csv")
    assert (tmp_path / "dev.csv").read_text() == (tmp_path / "ref.csv").read_text()
    for f in FIELDS:
        np.testing.assert_array_equal(getattr(got, f), getattr(want, f), err_msg=f)
    dev.reset([1])
    ref.reset([1])
    for key, v in dev.state.items():
        np.testing.assert_array_equal(v, ref.state[key], err_msg=key)
    with pytest.raises(cl.errors.OutsideTheoryError, match=r"depth\[0\]="):
        dev.step(force=[2.0, 2.0, 3.0])
    with pytest.raises(ParameterError, match="force"):
        dev.step(force=[1.0, -2.0, 3.0])
    with pytest.raises(NotSupportedError, match="tangent=True"):
        dev.step(force=[1.0, 2.0, 3.0], tangent=True)
    with pytest.raises(ParameterError, match="out="):
        dev.step(force=[1.0, 2.0, 3.0], out="no")


def test_backend_choices_and_contradictions():
    """The backend names and their agreement with ``fast``."""
    kw = dict(R=0.01, friction=0.3, **KW)
    assert cl.ContactLaw(cl.profiles.Paraboloid, backend="numpy", **kw).backend == "numpy"
    assert cl.ContactLaw(cl.profiles.Paraboloid, fast=False, **kw).backend == "numpy"
    with pytest.raises(UnknownNameError, match=r"backend='opencl'.*allowed"):
        cl.ContactLaw(cl.profiles.Paraboloid, backend="opencl", **kw)
    with pytest.raises(ParameterError, match=r"fast=True contradicts backend='numpy'"):
        cl.ContactLaw(cl.profiles.Paraboloid, backend="numpy", fast=True, **kw)


def test_cupy_missing_names_the_backend_and_the_extra(monkeypatch):
    """backend='cupy' without CuPy: NotSupportedError naming the parameter, its value and
    what it needs (the extra ``gpu``, a CUDA device), before anything is allocated."""
    monkeypatch.setitem(sys.modules, "cupy", None)          # import cupy -> ImportError
    with pytest.raises(NotSupportedError) as err:
        cl.ContactLaw(cl.profiles.Paraboloid, R=0.01, friction=0.3, backend="cupy", **KW)
    text = str(err.value)
    assert "backend='cupy'" in text and "contactlab[gpu]" in text and "CUDA" in text


def test_device_memory_checked_against_the_budget_before_allocating():
    """10^7-10^8 contacts: the law's state plus one step's temporaries on the device
    (law_device.device_law_memory) is checked against the memory budget before anything is
    allocated; a budget that holds the numpy law's state but not the device step refuses
    only the array-module backend."""
    from contactlab.effects.law import law_memory
    per = law_device.device_law_memory(1, law_memory(1, 8, 16))
    assert per == law_memory(1, 8, 16) + 56 + law_device.XP_STEP_BYTES
    kw = dict(R=0.01, friction=0.3, **KW)
    for size in (10**7, 10**8):
        with pytest.raises(MemoryBudgetError, match="GiB"):
            cl.ContactLaw(cl.profiles.Paraboloid, size=size, backend="xp-numpy", **kw)
    size = 10**5
    budget = 0.5 * (law_memory(size, 8, 16) + law_device.device_law_memory(
        size, law_memory(size, 8, 16)))
    old = cl.set_memory_budget(budget)
    try:
        cl.ContactLaw(cl.profiles.Paraboloid, size=size, backend="numpy", **kw)
        with pytest.raises(MemoryBudgetError, match="backend 'cupy' or 'xp-numpy'"):
            cl.ContactLaw(cl.profiles.Paraboloid, size=size, backend="xp-numpy", **kw)
    finally:
        cl.set_memory_budget(old)


def test_overflowing_twist_refused_alike_by_numpy_and_xp_numpy():
    """A twist so large that y = φ/φ_s overflows to inf (s = inf/inf, NaN): both backends
    refuse the step with the law's overflow error naming the contact. The numpy law once cast
    that NaN to the panel index -2^63 and failed with an IndexError; the shared master-curve
    evaluation now clips the index into the table, as the device step did."""
    backends = ["numpy", "xp-numpy"] + (["numba"] if law_kernel.AVAILABLE else [])
    for backend in backends:
        law = cl.ContactLaw(cl.profiles.Paraboloid, R=[0.01, 0.02], friction=0.3,
                            backend=backend, **KW)
        # no RuntimeWarning either (filterwarnings=error turns one into a failure here)
        with pytest.raises(ParameterError, match=r"contact 1: .*overflows float64"):
            law.step(force=[1.0, 2.0], twist=[1e-3, 1e307])
        # the refused contact was reset and the law steps on as before
        ok = law.step(force=[1.0, 2.0], twist=[1e-3, 1e-3])
        assert np.all(np.isfinite(ok.torque))


class _DeviceArray(np.ndarray):
    """A numpy array standing in for a device array (its own type, host conversions through
    the module's asnumpy only)."""


def _dev(x):
    if isinstance(x, np.ndarray) and not isinstance(x, _DeviceArray):
        return x.view(_DeviceArray)
    if isinstance(x, tuple):
        return tuple(_dev(v) for v in x)
    return x


class _FakeCupy:
    """numpy dressed as CuPy (a device count, free memory, asnumpy, its own array type): runs
    the code paths that backend="cupy" takes and numpy does not (host views and gathers for
    the springs, device inputs, host copies of the state), with numpy's arithmetic."""
    ndarray = _DeviceArray

    class cuda:                                 # noqa: N801 - CuPy's spelling
        class runtime:                          # noqa: N801
            @staticmethod
            def getDeviceCount():               # noqa: N802
                return 1

            @staticmethod
            def memGetInfo():                   # noqa: N802
                return 2**40, 2**40

    @staticmethod
    def asnumpy(v):
        return np.array(np.asarray(v).view(np.ndarray), order="C")

    class RawModule:
        """CuPy's runtime-compiled module, its kernels run by the host build of its text
        (``host``: a :class:`~contactlab.physics.law_cuda.Kernels`, set by a test that has
        one); each launch is recorded, and its grid must cover every contact."""
        host = None
        launches: ClassVar[list] = []
        _names: ClassVar[dict] = {"law_channel": "channel", "law_normal": "normal",
                                  "law_step": "step"}

        def __init__(self, code, options=()):
            self.options = options

        def get_function(self, name):
            from contactlab.physics import law_cuda
            at = law_cuda.ORDER[name].index("n_contacts")

            def run(grid, block, args):
                size = int(args[at])
                _FakeCupy.RawModule.launches.append(name)
                assert grid[0] * block[0] >= size > (grid[0] - 1) * block[0]
                getattr(_FakeCupy.RawModule.host, _FakeCupy.RawModule._names[name])(args)
            return run

    @staticmethod
    def cbrt(v):
        # a device's cube root comes from its own math library; the stand-in's is the law's
        # own (glibc's bits on every machine), not numpy's, whose AVX-512 loop rounds
        # differently from the reference's in the last place
        return _dev(cube_root.cbrt(np.asarray(v).view(np.ndarray)))

    def __getattr__(self, name):
        f = getattr(np, name)
        if not callable(f) or isinstance(f, type):
            return f
        return lambda *a, **k: _dev(f(*a, **k))


@pytest.mark.parametrize("springs", ["numpy", "compiled"])
@pytest.mark.parametrize("by", ["force", "depth"])
def test_cupy_code_paths_on_a_stand_in_module(monkeypatch, by, springs, tmp_path):
    """backend="cupy" with numpy dressed as CuPy: every output, model error and state entry
    equal to the bit to the CPU law with the same spring passes (the numpy law; the numba law
    where the host springs are compiled) (springs switched through host gathers, results
    scattered back), device arrays accepted as inputs and their bad entries named, and a state
    restored through an .npz continues to the bit."""
    monkeypatch.setitem(sys.modules, "cupy", _FakeCupy())
    reference = _host_springs(monkeypatch, springs)
    n, steps = 60, 50
    dev, ref, rng = _laws(cl.profiles.Paraboloid, "R", (1e-3, 1e-2), {}, 7, n, "cupy",
                          reference, memory=3)
    dev._kernels = None                 # the array path (the fused kernels: the next test)
    assert isinstance(dev._st["tan_X"], _DeviceArray)
    for a, b, raw in _run(dev, ref, rng, by, steps, n, _FakeCupy.asnumpy):
        assert isinstance(raw.torque, _DeviceArray)
        for f in FIELDS:
            np.testing.assert_array_equal(a[f], getattr(b, f), err_msg=f)
        for q, err in b.model_errors.items():
            np.testing.assert_array_equal(raw.model_errors[q], err, err_msg=q)
    sd, sr = dev.state, ref.state
    assert sr["spr_on"][n // 2:].all()
    # the numba law leaves the Masing stacks of contacts on springs as they were (unused);
    # the device law steps them with the others, as the numpy law does
    used = ~sr["spr_on"] if reference == "numba" else slice(None)
    for key, v in sd.items():
        assert type(v) is np.ndarray and v.flags.c_contiguous
        stack = key.startswith(("tan_", "tor_"))
        np.testing.assert_array_equal(v[used] if stack else v, sr[key][used] if stack
                                      else sr[key], err_msg=key)
    np.savez(tmp_path / "s.npz", **sd)
    twin = cl.ContactLaw(cl.profiles.Paraboloid, backend="cupy", memory=3, R=dev.geometry["R"],
                         friction=dev.friction, **KW)
    twin._kernels = None
    with np.load(tmp_path / "s.npz") as f:
        twin.state = dict(f)
    F = ref.normal(depth=ref.state["depth_ref"])[2]
    for law in (dev, twin, ref):
        law.reset([0, 1])
    x = np.linspace(-1e-8, 1e-8, n)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ValidityWarning)    # the twin's model-error warning
        r = [law.step(force=_dev(F), displacement=_dev(x), twist=0.0) for law in (dev, twin)]
        want = ref.step(force=F, displacement=x, twist=0.0)
    for f in FIELDS:
        np.testing.assert_array_equal(np.asarray(getattr(r[0], f)), getattr(want, f), err_msg=f)
        np.testing.assert_array_equal(np.asarray(getattr(r[1], f)), getattr(want, f), err_msg=f)
    bad = F.copy()
    bad[3] = np.nan
    with pytest.raises(ParameterError, match=r"force\[3\]"):
        dev.step(force=_dev(bad))
    with pytest.raises(ParameterError, match="out="):
        dev.step(force=F, out=want)                 # a numpy LawStep is no device result


@pytest.mark.parametrize("springs", ["numpy", "compiled"])
@pytest.mark.parametrize("by", ["force", "depth"])
def test_fused_kernels_launched_on_a_stand_in_module(monkeypatch, host_kernels, by, springs):
    """backend="cupy" with numpy dressed as CuPy and its kernels run by the host build of
    their text: a plain constant-load step is the normal kernel and the step kernel; a step
    with a separated contact or a contact switching onto its springs falls back (after the
    normal kernel, which writes nothing) to the array path with one channel kernel per
    channel; once contacts are on springs (their loads changing every step) the steps are
    plain again, those contacts left to the host's springs. Every grid covers the contacts,
    and the results agree with the CPU law of the same spring passes to
    FUSED_HOST_VS_NUMPY."""
    monkeypatch.setitem(sys.modules, "cupy", _FakeCupy())
    monkeypatch.setattr(_FakeCupy.RawModule, "host", host_kernels)
    monkeypatch.setattr(_FakeCupy.RawModule, "launches", [])
    reference = _host_springs(monkeypatch, springs)
    n, steps = 300, 50                  # two blocks of 256 threads
    dev, ref, rng = _laws(cl.profiles.Paraboloid, "R", (1e-3, 1e-2), {}, 7, n, "cupy",
                          reference, memory=3)
    for a, b, raw in _run(dev, ref, rng, by, steps, n, _FakeCupy.asnumpy):
        assert isinstance(raw.torque, _DeviceArray)
        _assert_close(a, b, dev.friction, FUSED_HOST_VS_NUMPY)
    plain = ["law_normal", "law_step"]
    back = ["law_normal", "law_channel", "law_channel"]
    want = (plain * 20 + back * 5 + plain * 15 + back      # 20-24 separated, 40 switching
            + plain * (steps - 41))         # then on springs: the plain case, their springs
    # on the host
    assert _FakeCupy.RawModule.launches == want


@pytest.mark.parametrize("path", ["array", "fused"])
@pytest.mark.parametrize("family, gname, lo_hi, extra", FAMILIES,
                         ids=[f[0].__name__ for f in FAMILIES])
def test_compiled_host_springs_of_a_device_law_regrid_and_release(monkeypatch, request, family,
                                                                 gname, lo_hi, extra, path):
    """backend="cupy" (numpy dressed as CuPy) with the compiled host spring passes, which run
    on the gathered values of the contacts on springs: loads that grow ninefold (the contacts
    outgrow their spring cover, except a flat punch's: regridded inside the pass, through the
    gathered indices), contacts on springs that separate (their rows given back, then taken
    by the next group's switch) and contacts switching in three groups; every output and the
    spring state equal to the numba law's to the bit (the power law's to
    COMPILED_VS_NUMPY_SPRINGS, the dissipation of each contact's energy scale: its
    constant-load steps on numba differ from numpy's by ulps, and the device law's are
    numpy's), the Masing state of the contacts at constant load too.
    ``path``: the device's array path, or its fused kernels (the host build of their text),
    which step the contacts at constant load while the others are on springs."""
    monkeypatch.setitem(sys.modules, "cupy", _FakeCupy())
    _host_springs(monkeypatch, "compiled")
    if path == "fused":
        monkeypatch.setattr(_FakeCupy.RawModule, "host", request.getfixturevalue("host_kernels"))
        monkeypatch.setattr(_FakeCupy.RawModule, "launches", [])
    n, steps = 48, 40
    dev, ref, rng = _laws(family, gname, lo_hi, extra, 5, n, "cupy", "numba", memory=4)
    if path == "array":
        dev._kernels = None
    same = family is not cl.profiles.PowerLaw

    def check(x, y, what):
        if same:
            np.testing.assert_array_equal(x, y, err_msg=what)
        else:
            np.testing.assert_allclose(x, y, rtol=0, err_msg=what,
                                       atol=COMPILED_VS_NUMPY_SPRINGS * np.max(np.abs(y)))

    F = rng.uniform(1.0, 10.0, n)
    u, phi = _history(rng, steps, n, 3e-8, 1e-4)
    grown = 0
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ValidityWarning)
        for k in range(steps):
            L = F.copy()
            for g in range(3):                  # contacts 16g.. change load from step 6 + 6g
                if k >= 6 + 6 * g:
                    L[16 * g:16 * g + 8] *= 1.0 + 8.0 * min(1.0, (k - 6 - 6 * g) / 8.0)
            if 10 <= k < 12:
                L[2:5] = 0.0                    # contacts on springs separate, come back
                # at a load that still changes and switch again
            cover = ref.state["spr_cover"].copy()
            a = dev.step(force=L, displacement=u[k], twist=phi[k])
            b = ref.step(force=L, displacement=u[k], twist=phi[k])
            got = {f: _FakeCupy.asnumpy(getattr(a, f)) for f in FIELDS}
            if same:
                for f in FIELDS:
                    np.testing.assert_array_equal(got[f], getattr(b, f), f"step {k}: {f}")
            else:           # (the dissipation against each contact's energy scale)
                _assert_close(got, b, dev.friction, COMPILED_VS_NUMPY_SPRINGS, f"step {k}: ")
            on = ref.state["spr_on"]
            grown += int(np.count_nonzero(on & (cover > 0) & (ref.state["spr_cover"] > cover)))
            if k == 10:
                assert not dev.state["spr_on"][2:5].any()      # rows given back
    sd, sr = dev.state, ref.state
    assert (grown > 0) == (family is not cl.profiles.FlatPunch)
    assert sr["spr_on"].sum() == 24
    if path == "fused":         # the last steps (no switch, no separation): the plain case
        assert _FakeCupy.RawModule.launches[-4:] == ["law_normal", "law_step"] * 2
    for key, v in sd.items():
        stack = key.startswith(("tan_", "tor_"))
        used = ~sr["spr_on"] if stack else slice(None)
        check(v[used], sr[key][used], key)


def test_compiled_host_springs_on_threads_give_the_serial_bits(monkeypatch):
    """``parallel=True`` on backend="cupy" (numpy dressed as CuPy) runs the host's compiled
    spring passes on numba's threads: every output and the state equal to the bit to the
    serial numba law's on a history where half the contacts go onto their springs."""
    monkeypatch.setitem(sys.modules, "cupy", _FakeCupy())
    _host_springs(monkeypatch, "compiled")
    n, steps = 60, 50
    dev, ref, rng = _laws(cl.profiles.Paraboloid, "R", (1e-3, 1e-2), {}, 7, n, "cupy", "numba",
                          memory=3, parallel=True)
    dev._kernels = None
    assert dev.parallel
    ref.parallel = False
    for a, b, _ in _run(dev, ref, rng, "force", steps, n, _FakeCupy.asnumpy):
        for f in FIELDS:
            np.testing.assert_array_equal(a[f], getattr(b, f), err_msg=f)
    sd, sr = dev.state, ref.state
    assert sr["spr_on"][n // 2:].all()
    for key in sr:
        if key.startswith("spr_"):
            np.testing.assert_array_equal(sd[key], sr[key], err_msg=key)


def _cupy():
    cupy = pytest.importorskip("cupy")
    try:
        if cupy.cuda.runtime.getDeviceCount() < 1:
            pytest.skip("CuPy finds no CUDA device")
    except Exception as err:                    # no driver
        pytest.skip(f"CuPy finds no CUDA device ({err})")
    return cupy


def _energy_scale(step, friction):
    """Each contact's slip-energy scale, J: ``μF u* + M_full φ_s`` with ``u* = μE*d/G*``,
    ``φ_s = μE*d/(2 G_t a)`` (``M_full <= π/2 μE*d a²``). The per-step dissipation is a
    difference of loading-curve energies of this order (with cancellation at small slip), so
    two roundings of it differ by ulps of this scale, not of the dissipation itself."""
    E, G, Gt = KW["E_star"], KW["G_star"], KW["G_torsion"]
    mEd = friction * E * step.depth
    return (friction * step.force * mEd / G
            + 0.5 * np.pi * mEd * step.radius**2 * mEd / (2.0 * Gt * np.maximum(step.radius,
                                                                               1e-300)))


def _assert_close(a, b, friction, tol, where="", on=None, spring_tol=None):
    """Every field of the step ``a`` (numpy arrays) within ``tol`` of the largest value of the
    field in ``b``; the dissipation within ``tol`` of each contact's energy scale; ``exact``
    equal. ``on``: the contacts on springs (a mask), held to ``spring_tol`` instead."""
    np.testing.assert_array_equal(a["exact"], b.exact)
    lim = np.full(b.exact.shape, float(tol))
    if on is not None:
        lim[on] = spring_tol
    for f in FIELDS[:-2]:
        y = getattr(b, f)
        err = np.abs(a[f] - y)
        bound = lim * np.max(np.abs(y))
        assert np.all(err <= bound), (where + f, float(np.max(err - bound)))
    err = np.abs(a["dissipated_energy"] - b.dissipated_energy)
    bound = lim * _energy_scale(b, friction)
    assert np.all(err <= bound), (where, float(np.max(err - bound)))


def _assert_state_close(sd, sr, tol, spring_tol=None):
    """Every float state entry within ``tol`` of the entry's largest value (the spring rows,
    ``spr_*``, within ``spring_tol`` when given), the integer entries (depths, directions,
    flags) equal; the Masing stacks (``tan_*``, ``tor_*``) of the contacts not on springs
    only (those of contacts on springs are unused: the fused kernels, as the numba law, leave
    them as they were, the array path steps them)."""
    assert sd.keys() == sr.keys()
    free = ~sr["spr_on"]
    for key, v in sd.items():
        if key.startswith(("tan_", "tor_")):
            v, sr = v[free], {**sr, key: sr[key][free]}
        if v.dtype.kind == "f":
            t = spring_tol if spring_tol is not None and key.startswith("spr_") else tol
            np.testing.assert_allclose(v, sr[key], rtol=0, err_msg=key,
                                       atol=t * np.max(np.abs(sr[key])))
        else:
            np.testing.assert_array_equal(v, sr[key], err_msg=key)


@pytest.fixture(scope="module")
def host_kernels():
    """The fused kernels' text built for the host (skipped without a C compiler)."""
    import shutil
    from contactlab.physics import law_cuda
    cc = shutil.which("cc") or shutil.which("gcc")
    if cc is None:
        pytest.skip("no C compiler: the fused kernels' text is tested on the GPU only")
    return law_cuda.host_kernels(cc)


@pytest.mark.parametrize("mode", ["step", "channels"])
@pytest.mark.parametrize("by", ["force", "depth"])
@pytest.mark.parametrize("family, gname, lo_hi, extra", FAMILIES,
                         ids=[f[0].__name__ for f in FAMILIES])
def test_fused_kernel_text_on_the_host_against_the_numpy_law(host_kernels, family, gname,
                                                             lo_hi, extra, by, mode):
    """The GPU's fused kernels (one thread per contact: normal contact, Masing's rule, loop
    closures, loading curves, the step's bookkeeping), their very text compiled for the host
    and run contact by contact inside the array-module step, against the numpy law on the
    random histories of the GPU test (reversals, overflowing stacks, separation, half the
    contacts onto their springs): every output within FUSED_HOST_VS_NUMPY, the integer state
    equal; ``mode`` "step": the whole plain step fused, "channels": the channels only."""
    from contactlab.physics import law_cuda
    n, steps = 80, 60
    dev, ref, rng = _laws(family, gname, lo_hi, extra, 29, n, "xp-numpy", memory=3)
    dev._kernels = (host_kernels if mode == "step" else
                    law_cuda.Kernels(host_kernels.channel))
    for a, b, _ in _run(dev, ref, rng, by, steps, n, np.asarray):
        _assert_close(a, b, dev.friction, FUSED_HOST_VS_NUMPY, on=ref.state["spr_on"],
                      spring_tol=FUSED_HOST_SPRINGS_VS_NUMPY)
    assert ref.state["tan_overflow"].any() and ref.state["tor_overflow"].any()
    _assert_state_close(dev.state, ref.state, FUSED_HOST_VS_NUMPY, FUSED_HOST_SPRINGS_VS_NUMPY)


def test_fused_kernel_refuses_a_master_curve_of_another_degree():
    """The kernels evaluate degree-7 panels only: another table is refused, naming both
    degrees."""
    from dataclasses import replace
    from contactlab.physics import law_cuda
    law = cl.ContactLaw(cl.profiles.Paraboloid, R=0.01, friction=0.3, backend="xp-numpy", **KW)
    master = replace(law._master, coef=law._master.coef[:, :, :6])
    with pytest.raises(NotSupportedError, match="degree 7.*got degree 5"):
        law_cuda.channel_args(law_cuda.TORSION, np.zeros(1), np.ones(1), np.ones(1),
                              np.ones(1), np.ones(1), np.ones(1), np.ones(1), 2.0, master,
                              master.coef, law._chan, 1, (np.empty(1),) * 3)


@pytest.mark.parametrize("by", ["force", "depth"])
@pytest.mark.parametrize("family, gname, lo_hi, extra", FAMILIES,
                         ids=[f[0].__name__ for f in FAMILIES])
def test_cupy_against_the_numpy_law(family, gname, lo_hi, extra, by):
    """On a GPU, with the fused kernels (the default), with the channel kernel only and with
    the array path: every output to GPU_VS_NUMPY of its largest value (the per-step
    dissipation of each contact's energy scale), ``exact`` and the integer state equal;
    results are CuPy arrays."""
    from contactlab.physics import law_cuda
    cupy = _cupy()
    n, steps = 80, 60
    for mode in ("step", "channels", "array"):
        dev, ref, rng = _laws(family, gname, lo_hi, extra, 29, n, "cupy", memory=3)
        assert dev._kernels is not None and dev._kernels.step is not None
        if mode != "step":
            dev._kernels = law_cuda.Kernels(dev._kernels.channel) if mode == "channels" else None
        for a, b, raw in _run(dev, ref, rng, by, steps, n, cupy.asnumpy):
            assert isinstance(raw.torque, cupy.ndarray)
            _assert_close(a, b, dev.friction, GPU_VS_NUMPY, f"{mode}: ")
        _assert_state_close(dev.state, ref.state, GPU_VS_NUMPY)


def test_cupy_state_round_trip_and_device_inputs(tmp_path):
    """On a GPU: device arrays as inputs, the state saved to an .npz and restored into a
    fresh law in the middle of a changing-load run continues to the bit."""
    cupy = _cupy()
    n, steps = 60, 30
    par = dict(R=np.linspace(2e-3, 9e-3, n), friction=0.3, memory=4, **KW)

    def make():
        return cl.ContactLaw(cl.profiles.Paraboloid, backend="cupy", **par)

    through, a = _changing_run(make(), 3, steps, n)
    restored, b = _changing_run(make(), 3, steps, n, restore_at=17, tmp_path=tmp_path,
                                make=make)
    for k in range(steps):
        for f in FIELDS:
            np.testing.assert_array_equal(cupy.asnumpy(a[k][f]), cupy.asnumpy(b[k][f]),
                                          err_msg=f"step {k}: {f}")
    law = make()
    r = law.step(force=cupy.full(n, 5.0), displacement=cupy.zeros(n))
    assert isinstance(r.force, cupy.ndarray)
    with pytest.raises(ParameterError, match=r"force\[3\]"):
        bad = cupy.full(n, 5.0)
        bad[3] = cupy.nan
        law.step(force=bad)
