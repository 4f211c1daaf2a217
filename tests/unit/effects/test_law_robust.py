"""ContactLaw under adversarial use: restored states are checked entry by entry, reset() names
a bad mask, and a turning-point stack that overflows is reported (``exact`` False, one
ValidityWarning per step) instead of passing an approximate response off as exact.

The exact response of a nested history comes from an independent Masing implementation with
unbounded memory over the Cattaneo–Mindlin closed form (tests/reference/masing.py)."""
import re
import warnings

import numpy as np
import pytest

import contactlab as cl
from contactlab.errors import ParameterError, ValidityWarning
from tests.reference.hertz import radius_of_force
from tests.reference.masing import hertz_mindlin_virgin, masing_path
from tests.tolerances import LAW_HISTORY

R, E, G, GT, MU, F = 0.01, 1.15e11, 4.4e10, 4.0e10, 0.3, 100.0
FAST = [False, True] if cl.effects.law._kernel.AVAILABLE else [False]


def _law(**kw):
    return cl.ContactLaw(cl.profiles.Paraboloid, R=R, E_star=E, G_star=G, G_torsion=GT,
                         friction=MU, **kw)


# ---------------------------------------------------------------- restored state
@pytest.mark.parametrize("key,index,value,match", [
    ("depth_ref", 0, np.nan, r"state\['depth_ref'\]\[0\]=nan"),
    ("depth_ref", 1, -1e-6, r"state\['depth_ref'\]\[1\]=-1e-06.*>= 0"),
    ("tor_X", (1, 3), np.inf, r"state\['tor_X'\]\[1, 3\]=inf.*finite"),
    ("tan_y", 0, np.nan, r"state\['tan_y'\]\[0\]=nan"),
    ("tor_depth", 0, 9, r"state\['tor_depth'\]\[0\]=9.*\[0, memory=8\]"),
    ("tan_depth", 1, -1, r"state\['tan_depth'\]\[1\]=-1"),
    ("tan_last", 0, 2, r"state\['tan_last'\]\[0\]=2.*-1, 0 or 1"),
    ("spr_k", 1, 16, r"state\['spr_k'\]\[1\]=16.*springs=16"),
    ("spr_cover", 0, np.nan, r"state\['spr_cover'\]\[0\]=nan"),
])
def test_state_entries_are_checked(key, index, value, match):
    law = _law(size=2)
    law.step(force=F, twist=1e-4, displacement=0.0)
    before = law.state
    s = law.state
    s[key] = s[key].astype(float) if isinstance(value, float) and s[key].dtype != float \
        else s[key]
    s[key][index] = value
    with pytest.raises(ParameterError, match=match):
        law.state = s
    for k, v in law.state.items():                  # refused: nothing was written
        np.testing.assert_array_equal(v, before[k], err_msg=k)


def test_nan_state_cannot_pass_a_load_change_off_as_exact():
    """The campaign's case: a NaN reference depth disabled the constant-load check, and a 4x
    load step was reported exact with the torque of a memory that no longer applies."""
    law = _law(springs=0)
    law.step(force=10.0, twist=1e-4)
    s = law.state
    s["depth_ref"][:] = np.nan
    with pytest.raises(ParameterError, match="depth_ref"):
        law.state = s
    with pytest.raises(cl.errors.OutsideTheoryError, match="load_rtol"):
        law.step(force=40.0, twist=1e-4)                # the memory is still the valid one


@pytest.mark.parametrize("value,match", [
    (None, "state=None is invalid"),
    ([1, 2], r"state=\[1, 2\] is invalid"),
    ("abc", "state='abc' is invalid"),
])
def test_state_must_be_a_mapping(value, match):
    with pytest.raises(ParameterError, match=match):
        _law().state = value


def test_state_entries_of_the_wrong_kind():
    law = _law(size=2)
    s = law.state
    s["tan_x"] = np.array(["a", "b"])
    with pytest.raises(ParameterError, match=r"state\['tan_x'\] has dtype <U1"):
        law.state = s
    s = law.state
    s["tan_x"] = [[1.0], [2.0, 3.0]]
    with pytest.raises(ParameterError, match=r"state\['tan_x'\]"):
        law.state = s
    s = law.state
    s["tor_depth"] = np.array([0.5, 0.0])               # a turning-point count is whole
    with pytest.raises(ParameterError, match=r"state\['tor_depth'\]\[0\]=0.5"):
        law.state = s
    s = law.state
    s["tor_overflow"] = np.array([2, 0])
    with pytest.raises(ParameterError, match=r"state\['tor_overflow'\]\[0\]=2.*flag"):
        law.state = s
    s = law.state                                       # whole floats and 0/1 ints are fine
    s["tor_depth"] = np.zeros(2)
    s["tor_overflow"] = np.array([0, 1])
    law.state = s
    assert law.state["tor_overflow"].tolist() == [False, True]


@pytest.mark.parametrize("mask,match", [
    ("a", "mask='a' is invalid"),
    ([0.5], r"mask=\[0.5\] is invalid"),
    ([np.nan], r"mask=\[nan\] is invalid"),
    ([[0], [1, 2]], r"mask=\[\[0\], \[1, 2\]\] is invalid"),
    ({"a": 1}, "mask=.* is invalid"),
    ([3], "index 3"),
])
def test_reset_names_a_bad_mask(mask, match):
    law = _law(size=3)
    with pytest.raises(ParameterError, match=match):
        law.reset(mask)


def test_reset_accepts_empty_and_whole_float_indices():
    law = _law(size=3)
    law.step(force=F, twist=[1e-4, 2e-4, 3e-4])
    law.reset([])
    assert np.all(law.state["tor_x"] != 0)
    law.reset([1.0])
    assert law.state["tor_x"].tolist() == [1e-4, 0.0, 3e-4]


# ---------------------------------------------------------------- memory overflow
def _nested_history(u_star):
    """Twelve nested reversals (each excursion inside the previous one), then a sweep to
    -0.95 u* that closes every loop in the exact Masing memory."""
    amps = 0.9 * u_star * np.array([1, -0.9, 0.8, -0.7, 0.6, -0.5, 0.4, -0.3, 0.2, -0.1,
                                    0.05, -0.02])
    hist, prev = [], 0.0
    for A in amps:
        hist.extend(np.linspace(prev, A, 11)[1:])
        prev = A
    hist.extend(np.linspace(prev, -0.95 * u_star, 41)[1:])
    return np.array(hist)


@pytest.mark.parametrize("fast", FAST)
def test_overflow_is_not_reported_exact(fast):
    """Beyond `memory` nested reversals the default law (memory=8) forgets a loop; from that
    step on the response differs from exact Masing (by ~3 % of μF_N here, more in other
    histories) and must say so: out.exact False for that contact, one ValidityWarning in the
    step where its stack overflowed and none in the others. Steps reported exact agree with
    the unbounded-memory reference."""
    a = float(radius_of_force(F, R, E))
    u_star = MU * E * (a * a / R) / G
    hist = _nested_history(u_star)
    ref = np.array(masing_path(hist, lambda x: hertz_mindlin_virgin(x, F, MU, u_star)))
    # contact 0 runs the nested history, contact 1 a single excursion (never overflows)
    law = _law(size=2, fast=fast)
    T, exact, warned = [], [], []
    for x in hist:
        with warnings.catch_warnings(record=True) as w:
            warnings.simplefilter("always")
            out = law.step(force=F, displacement=[x, 0.5 * u_star])
        T.append(out.tangential_force[0])
        exact.append(out.exact.copy())
        warned.append(len([m for m in w if issubclass(m.category, ValidityWarning)]))
    T, exact, warned = np.array(T), np.array(exact), np.array(warned)
    assert exact[:, 1].all()
    first = int(np.argmin(exact[:, 0]))
    assert not exact[first:, 0].any() and exact[:first, 0].all()
    assert first == 9 * 10                  # the ninth reversal finds eight turning points
    assert warned.tolist() == [0] * first + [1] + [0] * (hist.size - first - 1)
    scale = MU * F
    np.testing.assert_allclose(T[:first], ref[:first], rtol=0, atol=LAW_HISTORY * scale)
    assert np.max(np.abs(T - ref)) > 1e-2 * scale   # the forgotten loop shows
    assert law.state["tan_overflow"].tolist() == [True, False]
    law.reset([0])                          # a reset contact is exact again
    out = law.step(force=F, displacement=[0.1 * u_star, 0.5 * u_star])
    assert out.exact.all()


@pytest.mark.parametrize("fast", FAST)
def test_overflow_warns_once_per_step_for_many_contacts(fast):
    n = 50
    law = _law(size=n, memory=2, fast=fast)
    hist = 1e-4 * np.array([1.0, -0.8, 0.6, -0.4, 0.2])
    counts = []
    for k, p in enumerate(hist):
        with warnings.catch_warnings(record=True) as w:
            warnings.simplefilter("always")
            out = law.step(force=F, twist=np.where(np.arange(n) < 30, p, 1e-5 * k))
        counts.append([str(m.message) for m in w])
    assert [len(c) for c in counts] == [0, 0, 0, 1, 0]
    assert "of 30 contact(s)" in counts[3][0]
    np.testing.assert_array_equal(out.exact, np.arange(n) >= 30)


# ---------------------------------------------------------------- fixed parameters
@pytest.mark.parametrize("name", ["friction", "E_star", "G_star", "G_torsion", "kc",
                                  "spring_cover"])
def test_parameters_are_fixed_when_the_law_is_built(name):
    """The law holds products of its parameters (mu E*, the force factor) for the compiled
    passes: a parameter written in place would leave them behind, and the compiled and numpy
    paths would then disagree silently. Writing in place and assigning are both refused."""
    law = _law(size=3)
    value = getattr(law, name)
    assert value.shape == (3,)
    with pytest.raises(ValueError, match="read-only"):
        value[0] = 0.5
    with pytest.raises(ParameterError, match=rf"ContactLaw\.{name} is fixed.*0\.5"):
        setattr(law, name, 0.5)
    assert law.geometry["R"].flags.writeable is False


@pytest.mark.parametrize("fast", FAST)
def test_fixed_parameters_leave_the_results_unchanged(fast):
    """Reading the parameters (views) does not change a step: the same bits as a law never read,
    and the compiled path equals the numpy path."""
    ref = _law(size=3, fast=False).step(force=[50.0, 100.0, 150.0], twist=1e-4)
    law = _law(size=3, fast=fast)
    _ = (law.friction, law.E_star, law.kc, law.geometry)
    out = law.step(force=[50.0, 100.0, 150.0], twist=1e-4)
    assert out.torque.tobytes() == ref.torque.tobytes()
    assert out.radius.tobytes() == ref.radius.tobytes()


def test_geometry_is_fixed_when_the_law_is_built():
    """The geometry mapping refuses an entry replaced, as the parameters refuse assignment."""
    law = _law(size=2)
    with pytest.raises(ParameterError, match=r"ContactLaw\.geometry\['R'\] is fixed.*0\.5"):
        law.geometry["R"] = 0.5
    assert list(law.geometry) == ["R"] and len(law.geometry) == 1
    np.testing.assert_array_equal(law.geometry["R"], [R, R])


# ---------------------------------------------------------------- the paraboloid's validity
def _force_at(a_over_R, radii):
    """Hertz force at contact radius ``a`` (closed form F = 4 E* a^3 / (3 R))."""
    a = a_over_R * np.asarray(radii)
    return 4.0 * E * a**3 / (3.0 * np.asarray(radii))


BACKENDS = [dict(fast=f) for f in FAST] + [dict(backend="xp-numpy")]


@pytest.mark.parametrize("kw", BACKENDS, ids=lambda k: str(k))
def test_radius_beyond_r_over_root3_warns_once_naming_the_contact(kw):
    """A paraboloid contact whose radius exceeds R/√3 (surface slope tan 30°, where a single
    Paraboloid's state warns) leaves the half-space theory: the law says so once, naming the
    first such contact, in the warning and in the step's notes; within the range it is silent."""
    radii = np.array([0.01, 0.02, 0.005])
    law = cl.ContactLaw(cl.profiles.Paraboloid, R=radii, E_star=E, G_star=G, G_torsion=GT,
                        friction=MU, **kw)
    inside = _force_at(np.array([0.3, 0.57, 0.1]), radii)     # 1/√3 = 0.5774
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        out = law.step(force=inside, twist=1e-6)
    assert "notes" not in out.meta
    beyond = _force_at(np.array([0.3, 0.6, 0.7]), radii)
    with pytest.warns(ValidityWarning, match=r"contact 1's radius 0\.012\d* m exceeds R/√3 = "
                                             r"0\.011547\d* m \(R = 0\.02 m\)") as rec:
        out = law.step(force=beyond, twist=1e-6)
    assert len(rec) == 1 and "tan 30°" in out.meta["notes"][0]
    assert rec[0].filename == __file__                # attributed to the caller's step
    np.testing.assert_allclose(out.radius, [0.003, 0.012, 0.0035], rtol=1e-14)
    with warnings.catch_warnings():
        warnings.simplefilter("error")                 # said once per law
        law.step(force=beyond, twist=1e-6)


def test_validity_check_runs_in_blocks_and_finds_a_contact_past_the_first():
    """The host check runs over blocks of contacts: a contact past the first block is found
    and named; depth-driven steps are checked as force-driven ones (a = √(R d))."""
    from contactlab.effects.law_checks import _SLOPE_BLOCK
    n = _SLOPE_BLOCK + 10
    i = _SLOPE_BLOCK + 5
    law = _law(size=n, fast=False)
    d = np.full(n, (0.5 * R) ** 2 / R)
    d[i] = (0.58 * R) ** 2 / R
    with pytest.warns(ValidityWarning, match=rf"contact {i}'s radius 0\.0058\d* m"):
        law.step(depth=d)


def test_other_families_have_no_validity_radius():
    """Cones and power laws carry no R/√3 limit (their profiles' validity radius is inf)."""
    law = cl.ContactLaw(cl.profiles.Cone, slope=0.2, E_star=E, G_star=G, G_torsion=GT,
                        friction=MU, size=2)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        law.step(force=[1.0, 1e9])
    assert cl.profiles.Cone(slope=0.2).validity_radius == np.inf


@pytest.mark.parametrize("family, name, value, where", [
    (cl.profiles.Paraboloid, "R", [0.01, 1e-40], "R[1]=1e-40"),
    (cl.profiles.Paraboloid, "R", 1e20, "R=1e+20"),
    (cl.profiles.FlatPunch, "radius", [2e-3, 3e-3, 1e12], "radius[2]=1000000000000.0"),
    (cl.profiles.Paraboloid, "E_star", [1e11, 1e25], "E_star[1]=1e+25"),
    (cl.profiles.Paraboloid, "G_star", 1e-20, "G_star=1e-20"),
    (cl.profiles.Paraboloid, "G_torsion", [1e10, 1e10, 1e30], "G_torsion[2]=1e+30"),
])
def test_lengths_and_moduli_outside_the_bounds_are_refused(family, name, value, where):
    """A radius outside [1e-30, 1e10] m (the profiles' LENGTH_BOUNDS) or a modulus outside
    [1e-10, 1e20] Pa (the materials' MODULUS_BOUNDS) is refused with their message, naming the
    contact: a paraboloid of R = 1e200 m answered a contact radius of 9e62 m, one of 1e-200 m
    only a slope warning."""
    kw = dict(E_star=E, G_star=G, G_torsion=GT, friction=MU)
    if family is cl.profiles.Paraboloid:
        kw["R"] = 0.01
    kw[name] = value
    unit = "Pa" if name.endswith(("star", "torsion")) else "m"
    lo, hi = ("1e-10", r"1e\+20") if unit == "Pa" else ("1e-30", r"1e\+10")
    with pytest.raises(ParameterError, match=re.escape(where) + rf" is invalid: it must "
                       rf"lie between {lo} and {hi} {unit} \(check the units\)"):
        cl.ContactLaw(family, **kw)


def test_lengths_at_the_bounds_follow_hertz():
    """At both ends of the bounds the law is still Hertz's contact (radius (3FR/4E*)^(1/3))."""
    R = np.array([1e-30, 1e10])
    law = cl.ContactLaw(cl.profiles.Paraboloid, R=R, E_star=E, G_star=G, G_torsion=GT,
                        friction=MU)
    F = np.array([1e-60, 1.0])          # a stays below R/√3 at the small end
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        out = law.step(force=F)
    np.testing.assert_allclose(out.radius, radius_of_force(F, R, E), rtol=4e-16)
