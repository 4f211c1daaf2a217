"""The compiled ContactLaw step (numba, extra ``fast``) against the numpy reference (issue 29):
bit-identical at constant load on random histories of every family (reversals, loop closures,
overflowing turning-point stacks, separation), by depth and by force; the changing-load run
(the compiled switch onto the springs) within COMPILED_VS_NUMPY_SPRINGS, and bit-identical to itself
across a state saved and restored in the middle; the numpy fallback without numba."""
from __future__ import annotations

import os
import subprocess
import sys
import warnings
from pathlib import Path

import numpy as np
import pytest

import contactlab as cl
from contactlab.errors import ValidityWarning
from tests.tolerances import COMPILED_VS_NUMPY, COMPILED_VS_NUMPY_SPRINGS

ROOT = Path(__file__).resolve().parents[3]
HAS_NUMBA = cl.effects.law._kernel.AVAILABLE
needs_numba = pytest.mark.skipif(not HAS_NUMBA, reason="numba (extra 'fast') not installed")
FIELDS = ("depth", "radius", "force", "tangential_force", "torque", "stick_radius",
          "torsion_stick_radius", "dissipated_energy", "exact")

#: (family, geometry keyword, per-contact geometry range, extra keywords)
FAMILIES = [(cl.profiles.Paraboloid, "R", (1e-3, 1e-2), {}),
            (cl.profiles.Cone, "slope", (0.05, 0.3), {}),
            (cl.profiles.PowerLaw, "c", (1e2, 1e3), {"n": 1.5}),
            (cl.profiles.FlatPunch, "radius", (1e-4, 1e-3), {})]


def _pair(family, gname, lo_hi, extra, seed, n, **kw):
    rng = np.random.default_rng(seed)
    par = dict({gname: rng.uniform(*lo_hi, n)}, E_star=1.15e11, G_star=4.4e10,
               G_torsion=4.0e10, friction=rng.uniform(0.1, 0.5, n), **extra, **kw)
    return (cl.ContactLaw(family, fast=True, **par), cl.ContactLaw(family, fast=False, **par),
            rng)


def _history(rng, steps, n, u_scale, phi_scale):
    """Random walks (reversals at random, loops closing) with a few large excursions."""
    u = np.cumsum(rng.standard_normal((steps, n)), axis=0) * u_scale
    phi = np.cumsum(rng.standard_normal((steps, n)), axis=0) * phi_scale
    return u, phi


def _same(a, b, bits):
    """Every output equal to the bit (``bits``), else to COMPILED_VS_NUMPY of its largest
    value (the per-step dissipation is compared by the caller, against the cumulative one).
    Returns the largest difference of the per-step dissipation."""
    for f in FIELDS[:-2] + FIELDS[-1:]:
        x, y = getattr(a, f), getattr(b, f)
        if bits or f == "exact":
            np.testing.assert_array_equal(x, y, err_msg=f)
        else:
            scale = np.max(np.abs(y))
            np.testing.assert_allclose(x, y, rtol=0, atol=COMPILED_VS_NUMPY * scale, err_msg=f)
    dw = np.max(np.abs(a.dissipated_energy - b.dissipated_energy))
    assert dw == 0 or not bits
    return dw


@needs_numba
@pytest.mark.parametrize("by", ["force", "depth"])
@pytest.mark.parametrize("family, gname, lo_hi, extra", FAMILIES,
                         ids=[f[0].__name__ for f in FAMILIES])
def test_constant_load_bit_identical_on_random_histories(family, gname, lo_hi, extra, by):
    """Every output and every state entry equal to the bit, step by step, memory=3 so that
    stacks overflow; some contacts separate and come back (fresh memory). A general exponent
    (PowerLaw, n = 1.5) to COMPILED_VS_NUMPY: its Cattaneo–Mindlin curve takes ``expm1`` and
    ``log1p``, where numpy's vectorised functions and the kernel's libm differ by an ulp at
    some arguments (seen at 1 of 120 contacts)."""
    n, steps = 120, 60
    fast, slow, rng = _pair(family, gname, lo_hi, extra, 29, n, memory=3)
    bits = family is not cl.profiles.PowerLaw
    F = rng.uniform(1.0, 100.0, n)
    load = F if by == "force" else slow.normal(force=F)[0]
    u, phi = _history(rng, steps, n, 3e-8, 1e-4)
    W = np.zeros(n)
    dw = 0.0
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ValidityWarning)    # overflow; shift + twist together
        for k in range(steps):
            L = load.copy()
            if 20 <= k < 25:
                L[:10] = 0.0                                # separated, then back
            a = fast.step(**{by: L}, displacement=u[k], twist=phi[k])
            b = slow.step(**{by: L}, displacement=u[k], twist=phi[k])
            W += b.dissipated_energy
            dw = max(dw, _same(a, b, bits))
    assert dw <= COMPILED_VS_NUMPY_SPRINGS * W.max()
    assert fast.state["tor_overflow"].any() and fast.state["tan_overflow"].any()
    for key, v in fast.state.items():
        ref = slow.state[key]
        if bits or v.dtype != float:
            np.testing.assert_array_equal(v, ref, err_msg=key)
        else:
            np.testing.assert_allclose(v, ref, rtol=0, err_msg=key,
                                       atol=COMPILED_VS_NUMPY * np.max(np.abs(ref)))


def _changing_run(law, rng_seed, steps, n, restore_at=None, tmp_path=None, make=None):
    """A history where contacts 0..n/2 change their load from step 8 on (onto the springs);
    ``restore_at``: the state is saved to an .npz there and restored into a fresh law."""
    rng = np.random.default_rng(rng_seed)
    F = rng.uniform(1.0, 100.0, n)
    u, phi = _history(rng, steps, n, 3e-8, 1e-4)
    outs = []
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ValidityWarning)
        for k in range(steps):
            if k == restore_at:
                np.savez(tmp_path / "law.npz", **law.state)
                law = make()
                with np.load(tmp_path / "law.npz") as f:
                    law.state = dict(f)
            L = F.copy()
            if k >= 8:
                L[: n // 2] *= 1.0 + 0.03 * np.sin(0.4 * k + np.arange(n // 2))
            r = law.step(force=L, displacement=u[k], twist=phi[k])
            outs.append({f: getattr(r, f).copy() for f in FIELDS})
    return law, outs


@pytest.mark.parametrize("fast", [False, True] if HAS_NUMBA else [False])
def test_state_saved_and_restored_in_a_changing_load_run(fast, tmp_path):
    """A law restored from law.state (through an .npz file) in the middle of a changing-load
    run continues to the bit as the law that ran through."""
    n, steps = 60, 30
    par = dict(R=np.linspace(2e-3, 9e-3, n), E_star=1.15e11, G_star=4.4e10, G_torsion=4e10,
               friction=0.3, memory=4, fast=fast)

    def make():
        return cl.ContactLaw(cl.profiles.Paraboloid, **par)

    through, a = _changing_run(make(), 3, steps, n)
    restored, b = _changing_run(make(), 3, steps, n, restore_at=17, tmp_path=tmp_path,
                                make=make)
    assert through.state["spr_on"][: n // 2].all()
    for k in range(steps):
        for f in FIELDS:
            np.testing.assert_array_equal(a[k][f], b[k][f], err_msg=f"step {k}: {f}")
    for key, v in through.state.items():
        np.testing.assert_array_equal(v, restored.state[key], err_msg=key)


@needs_numba
@pytest.mark.parametrize("family, gname, lo_hi, extra", FAMILIES,
                         ids=[f[0].__name__ for f in FAMILIES])
def test_changing_load_compiled_switch_against_numpy(family, gname, lo_hi, extra):
    """The compiled switch onto the springs (turning points replayed in the kernel) and the
    spring steps after it against the numpy law: contacts at constant load bit-identical,
    contacts on springs to COMPILED_VS_NUMPY_SPRINGS of the largest value (the cell integrals
    are formed in another order); the spring state likewise."""
    n, steps = 60, 30
    par = dict({gname: np.linspace(*lo_hi, n)}, E_star=1.15e11, G_star=4.4e10, G_torsion=4e10,
               friction=0.3, memory=6, **extra)
    fast, a = _changing_run(cl.ContactLaw(family, fast=True, **par), 4, steps, n)
    slow, b = _changing_run(cl.ContactLaw(family, fast=False, **par), 4, steps, n)
    assert fast.state["spr_on"][: n // 2].all() and not fast.state["spr_on"][n // 2:].any()
    W = np.cumsum([o["dissipated_energy"] for o in b], axis=0)
    for k in range(steps):
        np.testing.assert_array_equal(a[k]["exact"], b[k]["exact"])
        ex = b[k]["exact"]
        for f in FIELDS[:-1]:
            if family is not cl.profiles.PowerLaw:     # see the constant-load test
                np.testing.assert_array_equal(a[k][f][ex], b[k][f][ex],
                                              err_msg=f"step {k}: {f}")
            scale = W[-1].max() if f == "dissipated_energy" else np.max(np.abs(b[k][f]))
            np.testing.assert_allclose(a[k][f], b[k][f], rtol=0, err_msg=f"step {k}: {f}",
                                       atol=COMPILED_VS_NUMPY_SPRINGS * scale)
    sf, ss = fast.state, slow.state
    for key in ("spr_cover", "spr_depth", "spr_a", "spr_k", "spr_x_tan", "spr_x_tor", "spr_on"):
        np.testing.assert_array_equal(sf[key], ss[key], err_msg=key)
    for key in ("spr_tan", "spr_tor"):
        np.testing.assert_allclose(sf[key], ss[key], rtol=0,
                                   atol=COMPILED_VS_NUMPY_SPRINGS * np.max(np.abs(ss[key])),
                                   err_msg=key)


def test_backend_numpy_forces_the_numpy_law():
    """CONTACTLAB_BACKEND=numpy / set_backend("numpy") chooses the numpy law by default, as
    it does for the foundations; an explicit fast= wins."""
    from contactlab.foundation import _compiled
    kw = dict(R=0.01, E_star=1e11, G_star=4e10, G_torsion=4e10, friction=0.3)
    _compiled.set_backend("numpy")
    try:
        assert cl.ContactLaw(cl.profiles.Paraboloid, **kw).fast is False
    finally:
        _compiled.set_backend(None)
    assert cl.ContactLaw(cl.profiles.Paraboloid, **kw).fast is HAS_NUMBA
    assert cl.ContactLaw(cl.profiles.Paraboloid, fast=False, **kw).fast is False


def test_numpy_fallback_without_numba(tmp_path):
    """numba absent (here: a numba that refuses to import): the law runs its numpy path, and
    a changing-load history there equals the numpy law of this process to the bit."""
    (tmp_path / "numba").mkdir()
    (tmp_path / "numba" / "__init__.py").write_text("raise ImportError('no numba here')\n")
    code = ("import sys, numpy as np, contactlab as cl\n"
            "from tests.unit.effects.test_law_compiled import _changing_run, FIELDS\n"
            "law = cl.ContactLaw(cl.profiles.Paraboloid, R=np.linspace(2e-3, 9e-3, 40),\n"
            "                    E_star=1.15e11, G_star=4.4e10, G_torsion=4e10, friction=0.3)\n"
            "assert law.fast is False and not cl.effects.law._kernel.AVAILABLE\n"
            "law, outs = _changing_run(law, 5, 20, 40)\n"
            "assert 'numba' not in sys.modules or not hasattr(sys.modules['numba'], 'njit')\n"
            "np.savez(sys.argv[1], **{f'{k}_{f}': o[f] for k, o in enumerate(outs)\n"
            "                         for f in FIELDS})\n")
    env = {k: v for k, v in os.environ.items() if not k.startswith(("NUMBA_", "CONTACTLAB_"))}
    env["PYTHONPATH"] = os.pathsep.join([str(tmp_path), str(ROOT)])
    res = subprocess.run([sys.executable, "-W", "error", "-c", code, str(tmp_path / "o.npz")],
                         capture_output=True, text=True, env=env, cwd=ROOT)
    assert res.returncode == 0, res.stderr
    law = cl.ContactLaw(cl.profiles.Paraboloid, R=np.linspace(2e-3, 9e-3, 40), E_star=1.15e11,
                        G_star=4.4e10, G_torsion=4e10, friction=0.3, fast=False)
    _, outs = _changing_run(law, 5, 20, 40)
    with np.load(tmp_path / "o.npz") as got:
        for k, o in enumerate(outs):
            for f in FIELDS:
                np.testing.assert_array_equal(got[f"{k}_{f}"], o[f], err_msg=f"{k} {f}")


def test_level_major_stacks_give_contact_major_state():
    """The turning points live level-major for the fused pass (issue 29: a step reads the top
    levels only); ``law.state`` still gives each channel's stack per contact, (n, memory),
    C-contiguous, and a restored state lands in the arrays the kernel reads."""
    pytest.importorskip("numba")
    law = cl.ContactLaw(cl.profiles.Paraboloid, R=[0.01, 0.02, 0.03], E_star=1.15e11,
                        G_star=4.4e10, G_torsion=4.0e10, friction=0.3, memory=4, fast=True)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ValidityWarning)    # shift + twist together
        for k in range(6):          # reversals: turning points on the stacks
            law.step(force=[10.0, 20.0, 30.0],
                     twist=2e-5 * np.array([1, -1, 1]) * (-1) ** k * (6 - k),
                     displacement=1e-8 * (-1) ** k * (6 - k))
    st = law.state
    for ch in ("tan", "tor"):
        for f in ("X", "Y"):
            v = st[f"{ch}_{f}"]
            assert v.shape == (3, 4) and v.flags.c_contiguous
            c = 0 if ch == "tan" else 1
            assert np.array_equal(v, law._chan[f + "_levels"][c].T)
    assert np.any(st["tor_depth"] > 0)
    saved = {k: v.copy() for k, v in st.items()}
    law.reset()
    law.state = saved
    for c, ch in enumerate(("tan", "tor")):
        assert np.array_equal(law._chan["X_levels"][c].T, saved[f"{ch}_X"])
        assert np.array_equal(law._chan["Y_levels"][c].T, saved[f"{ch}_Y"])


@needs_numba
@pytest.mark.parametrize("family, gname, lo_hi, extra", FAMILIES[:2],
                         ids=[f[0].__name__ for f in FAMILIES[:2]])
def test_uncompiled_kernels_give_the_compiled_bits(family, gname, lo_hi, extra, monkeypatch):
    """The kernels' Python source run uncompiled (numba's ``py_func``, plain loops) gives the
    compiled law's outputs and state to the bit on a random changing-load history (reversals,
    loop closures, the switch onto the springs): what numba compiles is what the source says
    (a rewrite such as ``x / 2`` -> ``x * 0.5`` in a kernel must not move a bit)."""
    from contactlab.physics import law_kernel as K
    n, steps = 16, 14
    par = dict({gname: np.linspace(*lo_hi, n)}, E_star=1.15e11, G_star=4.4e10, G_torsion=4e10,
               friction=0.3, memory=4, springs=8, **extra)
    compiled, a = _changing_run(cl.ContactLaw(family, fast=True, **par), 5, steps, n)
    built = K._kernels(False)
    monkeypatch.setitem(K._KERNELS, False, tuple(f.py_func for f in built))
    monkeypatch.setattr(K, "_load", K._KERNELS["load"].py_func)
    monkeypatch.setattr(K, "_poly3", K._POLY3_PY)   # the three curves' scalar source
    for name in ("_switch_one", "_spring_one"):     # the passes of a switch-and-step block
        monkeypatch.setattr(K._springs, name, getattr(K._springs, name).py_func)
    # the spring passes' lane pieces: their scalar source
    monkeypatch.setattr(K._springs, "_slip2", K._springs._SLIP2_PY)
    monkeypatch.setattr(K._springs, "_cells4", K._springs._CELLS_PY)
    monkeypatch.setattr(K._springs, "_cells", K._springs._CELLS_PY)
    monkeypatch.setattr(K._springs, "_first4", K._springs._FIRST_CELLS_PY)
    monkeypatch.setattr(K._springs, "_first_cells", K._springs._FIRST_CELLS_PY)
    assert not any(hasattr(f, "py_func") for f in K._kernels(False))     # plain Python now
    plain, b = _changing_run(cl.ContactLaw(family, fast=True, **par), 5, steps, n)
    assert compiled.state["spr_on"].any()
    for k in range(steps):
        for f in FIELDS:
            np.testing.assert_array_equal(a[k][f], b[k][f], err_msg=f"step {k}: {f}")
    for key, v in compiled.state.items():
        np.testing.assert_array_equal(v, plain.state[key], err_msg=key)


@needs_numba
@pytest.mark.parametrize("reuse", [False, True], ids=["fresh", "out"])
def test_every_contact_on_springs_skips_the_fused_pass_to_the_bit(reuse, monkeypatch):
    """With every contact on springs, or switching onto them in the step, the compiled step
    gives its outputs without the fused pass (issue 29): the same bits as for those contacts in a law with one more contact held
    at constant load (which runs the fused pass over all contacts), fresh outputs and ``out=``
    (whose ``exact`` was True in the constant-load steps before)."""
    n, steps = 40, 12
    par = dict(E_star=1.15e11, G_star=4.4e10, G_torsion=4e10, friction=0.3, memory=4,
               fast=True)
    R = np.linspace(2e-3, 9e-3, n + 1)
    rng = np.random.default_rng(11)
    F = rng.uniform(1.0, 100.0, n + 1)
    u, phi = _history(rng, steps, n + 1, 3e-8, 1e-4)
    alone = cl.ContactLaw(cl.profiles.Paraboloid, R=R[:n], **par)
    mixed = cl.ContactLaw(cl.profiles.Paraboloid, R=R, **par)
    oa = om = None
    skipped = []
    law_mod = cl.effects.law
    real = law_mod.springs_only_outputs
    monkeypatch.setattr(law_mod, "springs_only_outputs",
                        lambda size, out: skipped.append(size) or real(size, out))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ValidityWarning)
        for k in range(steps):
            L = F.copy()
            if k >= 3:
                L[:n] *= 1.0 + 0.03 * np.sin(0.4 * k + np.arange(n))
            ra = alone.step(force=L[:n], displacement=u[k, :n], twist=phi[k, :n], out=oa)
            rm = mixed.step(force=L, displacement=u[k], twist=phi[k], out=om)
            if reuse:
                oa, om = ra, rm
            for f in FIELDS:
                np.testing.assert_array_equal(getattr(ra, f), getattr(rm, f)[:n],
                                              err_msg=f"step {k}: {f}")
    assert alone.state["spr_on"].all() and not mixed.state["spr_on"][n]
    # the step in which every contact switches and those after it; the mixed law never
    assert skipped == [n] * (steps - 3)
    for key, v in alone.state.items():
        np.testing.assert_array_equal(v, mixed.state[key][:n], err_msg=key)


@needs_numba
def test_fused_pass_refuses_a_master_curve_of_another_degree():
    """The compiled pass evaluates degree-7 master curves only (Estrin's scheme, no fallback
    loop): a curve of another degree is refused with NotSupportedError naming the degree,
    never read with the wrong number of coefficients."""
    from contactlab.errors import NotSupportedError
    from contactlab.physics.master import MasterCurve
    law = cl.ContactLaw(cl.profiles.Paraboloid, R=np.full(3, 5e-3), E_star=1.15e11,
                        G_star=4.4e10, G_torsion=4e10, friction=0.3, fast=True)
    mc = law._master
    law._master = MasterCurve(mc.n, mc.y_scale, mc.coef[:, :, :6].copy(), mc.certified_error)
    with pytest.raises(NotSupportedError, match="degree 5"):
        law.step(force=np.full(3, 10.0), twist=np.full(3, 1e-4))


@needs_numba
def test_fused_pass_counts_a_sum_of_finite_outputs_that_overflows():
    """The pass tests the sum of a contact's five outputs for finiteness (one test instead of
    five): outputs that are each finite but whose sum overflows are counted (the law then runs
    its exact check of every array, which finds nothing and refuses nothing), a NaN output
    is counted, ordinary outputs are not."""
    from contactlab.physics import law_kernel
    law = cl.ContactLaw(cl.profiles.Paraboloid, R=np.full(3, 5e-3), E_star=1.0, G_star=1.0,
                        G_torsion=1.0, friction=1.0, fast=True)
    one = np.ones(3)
    d = one.copy()
    F = np.array([1.5e308, 1.0, 1.0])
    u = np.full(3, 0.5)
    rounds = []
    for a, counted in ((np.array([8e307, 1e-3, 2e-3]), 1), (np.array([8e307, 1e-3, np.nan]), 2)):
        Ft, ct, M, cm, dW, exact, nf, n_over = law_kernel.fused_pass(
            u, None, d, a, F, np.zeros(3, np.int8), np.zeros(3), one, one, one, one, 2.0,
            law._master, law._chan)
        assert nf == counted and n_over == 0
        rounds.append((a, Ft, M, ct, cm, dW))
        assert np.all(np.isfinite(np.stack([Ft, ct, M, cm, dW])[:, :2]))
        with np.errstate(over="ignore"):
            assert not np.isfinite(Ft[0] + ct[0] + M[0] + cm[0] + dW[0])
        law._chan["x"][...] = 0.0                   # the next round starts virgin again
        law._chan["y"][...] = 0.0
        law._chan["w"][...] = 0.0
        law._chan["last"][...] = 0
    assert np.isnan(ct[2])
    law._check_finite(np.ones(3, bool), d, *rounds[0][:1], F, *rounds[0][1:])  # finite: passes


@needs_numba
@pytest.mark.parametrize("n", [2.0, 1.0, 0.5, np.inf])
def test_master_curve_lanes_give_the_scalar_bits(n):
    """The compiled three-curve evaluation of the torsion pass (the panel's coefficients of each
    power of ``u`` for t, m, q in one 4-lane vector, LLVM IR written by the kernel module) gives
    the scalar Estrin scheme's bits (the plain source, which the law's numpy reference
    evaluates in the same order) on every panel, at ``u`` = ±1, 0 and random points of [-1, 1]."""
    import numba
    from contactlab.physics import law_kernel as K
    from contactlab.physics import master
    K._kernels(False)
    poly = K._poly3
    assert poly is not K._POLY3_PY                  # the intrinsic

    @numba.njit
    def run(tab, js, us, out):
        for i in range(js.size):
            u = us[i]
            u2 = u * u
            u4 = u2 * u2
            out[i, 0], out[i, 1], out[i, 2] = poly(tab, js[i], u, u2, u4)

    tab = K.lane_table(master.torsion_master(n))
    N = tab.shape[0]
    rng = np.random.default_rng(3)
    js = np.concatenate([np.repeat(np.arange(N), 3), rng.integers(0, N, 400)])
    us = np.concatenate([np.tile([-1.0, 0.0, 1.0], N), rng.uniform(-1.0, 1.0, 400)])
    got = np.empty((js.size, 3))
    run(tab, js, us, got)
    want = np.array([K._POLY3_PY(tab, int(j), u, u * u, (u * u) ** 2) for j, u in zip(js, us)])
    np.testing.assert_array_equal(got, want)
    # the table holds the curve's coefficients: master.evaluate's scheme on its (3, N, 8)
    # table, vectorised over the same panels and points, gives the same bits
    coef = master.torsion_master(n).coef
    u2 = us * us
    u4 = u2 * u2
    for k in range(3):
        c = coef[k][js]
        ref = (((c[:, 0] + c[:, 1] * us) + (c[:, 2] + c[:, 3] * us) * u2)
               + ((c[:, 4] + c[:, 5] * us) + (c[:, 6] + c[:, 7] * us) * u2) * u4)
        np.testing.assert_array_equal(want[:, k], ref)


# forces over twelve decades: some radii pass R/√3 (a ValidityWarning; the numbers are the point)
@pytest.mark.filterwarnings("ignore::contactlab.errors.ValidityWarning")
@pytest.mark.parametrize("fast", [False, pytest.param(True, marks=needs_numba)])
def test_hertz_radius_from_force_two_cube_roots(fast):
    """A paraboloid law's radius from a force is cbrt(F)·cbrt(3/(4 E* kc)) (the factor's root a
    per-contact constant of the law: no product F·factor per step; both cube roots
    contactlab.numeric.cube_root's, glibc's algorithm on every machine), the same bits in the
    step, the law's normal() and the array-module step (the exported source: test_law_source),
    and within LAW_HERTZ_RADIUS of the 40-digit cube root of F·3/(4 E* kc)."""
    import mpmath as mp
    from contactlab.numeric.cube_root import cbrt
    from contactlab.physics import law_xp
    from tests.tolerances import LAW_HERTZ_RADIUS
    rng = np.random.default_rng(29)
    n = 300
    R, E = rng.uniform(1e-4, 1e-1, n), rng.uniform(1e8, 1e12, n)
    F = rng.uniform(1e-6, 1e3, n) * 10.0 ** rng.integers(-6, 3, n)
    law = cl.ContactLaw(cl.profiles.Paraboloid, R=R, E_star=E, G_star=4.4e10,
                        G_torsion=4.0e10, friction=0.3, fast=fast)
    a = law.step(force=F).radius
    c = 3.0 / (4.0 * E * law.kc)
    assert a.tobytes() == (cbrt(F) * cbrt(c)).tobytes()
    assert law.normal(force=F)[1].tobytes() == a.tobytes()
    assert law_xp.normal(np, True, F, law.kc, law.E_star, 2.0, None)[1].tobytes() == a.tobytes()
    with mp.workdps(40):
        ref = np.array([float(mp.cbrt(mp.mpf(f) * 3 / (4 * mp.mpf(e) * mp.mpf(k))))
                        for f, e, k in zip(F, law.E_star, law.kc)])
    assert np.all(np.abs(a - ref) <= LAW_HERTZ_RADIUS * ref)
