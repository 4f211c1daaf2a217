"""LoadPath construction, validation, CSV input and PathResult export."""
import sys

import numpy as np
import pytest

import contactlab as cl
from contactlab.errors import ParameterError, TabulatedDataError, UnknownNameError
from contactlab.loadpath import Hold, Ramp, Repeat, Sinusoid, Table
from tests import tolerances as TOL

STEEL = cl.Elastic(E=210e9, nu=0.3)


def contact():
    return cl.Contact(cl.profiles.Paraboloid(R=0.01), materials=(STEEL, STEEL), friction=0.2)


def test_builder_returns_new_immutable_paths():
    p0 = cl.LoadPath()
    p1 = p0.ramp(force=100.0, steps=50)
    p2 = p1.hold(steps=10).sinusoid(twist=8e-4, cycles=10, steps_per_cycle=200)
    assert p0.segments == () and len(p1.segments) == 1 and len(p2.segments) == 3
    assert p2.n_steps == 50 + 10 + 2000
    assert p2.controls == {"force", "twist"}
    assert p2.groups == {"normal", "torsion"}
    with pytest.raises(AttributeError):
        p2.segments = ()
    assert isinstance(p2.segments[0], Ramp) and p2.segments[0].controls == {"force"}
    assert isinstance(p2.segments[1], Hold) and p2.segments[1].controls == frozenset()
    assert isinstance(p2.segments[2], Sinusoid)


def test_repeat_runs_segments_again_from_the_reached_state():
    p = cl.LoadPath().ramp(force=10.0, steps=2).ramp(depth=1e-7, steps=3).ramp(force=20.0, steps=2)
    rp = p.repeat(3, last=2)
    assert isinstance(rp.segments[-1], Repeat) and rp.n_steps == 2 + 3 * 5
    r = contact().simulate(rp)
    assert r.force[-1] == pytest.approx(20.0, rel=TOL.EXACT_ROUTES)
    assert r.depth[4] == pytest.approx(1e-7, rel=TOL.EXACT_ROUTES)
    assert r.depth[9] == pytest.approx(1e-7, rel=TOL.EXACT_ROUTES)


def test_ramp_starts_from_the_current_value_of_a_new_control():
    c = contact()
    r = c.simulate(cl.LoadPath().ramp(depth=1e-6, steps=4).ramp(force=2 * c.normal(
        depth=1e-6).force, steps=2))
    F1 = c.normal(depth=1e-6).force
    assert r.force[4] == pytest.approx(1.5 * F1, rel=TOL.EXACT_ROUTES)


def test_sinusoid_is_bitwise_periodic_and_time_is_ordered():
    p = cl.LoadPath().ramp(force=1.0, steps=3, duration=0.5).sinusoid(
        twist=1e-5, cycles=3, steps_per_cycle=7, period=2.0)
    r = contact().simulate(p, n_springs=10, method="mdr")
    tw = r.twist[3:].reshape(3, 7)
    assert np.array_equal(tw[0], tw[2])
    assert np.all(np.diff(r.time) > 0) and r.time[-1] == pytest.approx(0.5 + 6.0)


# ---- one test per validation rule
def test_rule_unknown_quantity():
    with pytest.raises(UnknownNameError, match="forse"):
        cl.LoadPath().ramp(forse=1.0)


def test_rule_one_control_per_group():
    with pytest.raises(ParameterError, match="normal group"):
        cl.LoadPath().ramp(force=1.0, depth=1e-6)


def test_rule_finite_values():
    with pytest.raises(ParameterError, match="twist"):
        cl.LoadPath().sinusoid(twist=np.inf)
    with pytest.raises(ParameterError, match="force"):
        cl.LoadPath.from_arrays(force=[1.0, np.nan])


def test_rule_steps_at_least_one():
    with pytest.raises(ParameterError, match="steps"):
        cl.LoadPath().ramp(force=1.0, steps=0)
    with pytest.raises(ParameterError, match="steps_per_cycle"):
        cl.LoadPath().sinusoid(twist=1.0, steps_per_cycle=2.5)


def test_rule_positive_duration():
    with pytest.raises(ParameterError, match="duration"):
        cl.LoadPath().hold(steps=2, duration=0.0)


def test_rule_ordered_time():
    with pytest.raises(ParameterError, match="time is not ordered"):
        cl.LoadPath.from_arrays(time=[0.0, 2.0, 1.0], force=[1.0, 2.0, 3.0])


def test_rule_equal_lengths():
    with pytest.raises(ParameterError, match="same length"):
        cl.LoadPath.from_arrays(force=[1.0, 2.0], twist=[0.0])


def test_rule_repeat_count():
    with pytest.raises(ParameterError, match="last"):
        cl.LoadPath().hold().repeat(2, last=3)


def test_rule_force_below_adhesion_limit():
    with pytest.raises(ParameterError, match="adhesion limit"):
        contact().simulate(cl.LoadPath().ramp(force=-1.0))


def test_rule_n_springs_and_spacing():
    p = cl.LoadPath().ramp(force=1.0).ramp(twist=1e-6)
    with pytest.raises(ParameterError, match="n_springs"):
        contact().simulate(p, n_springs=0, method="mdr")
    with pytest.raises(UnknownNameError, match="spacing"):
        contact().simulate(p, spacing="log", method="mdr")


def test_rule_shift_without_contact():
    with pytest.raises(ParameterError, match="never brings the bodies into contact"):
        contact().simulate(cl.LoadPath().ramp(twist=1e-5))


# ---- CSV and exports
def test_csv_round_trip(tmp_path):
    f = tmp_path / "path.csv"
    f.write_text("time [s],force [N],twist [rad]\n0,0,0\n1,50,0\n2,100,1e-5\n3,100,-1e-5\n")
    p = cl.LoadPath.from_csv(f)
    assert isinstance(p.segments[0], Table) and p.n_steps == 4
    r = contact().simulate(p, n_rings=50)
    np.testing.assert_array_equal(r.time, [0, 1, 2, 3])
    np.testing.assert_allclose(r.force, [0, 50, 100, 100], rtol=TOL.EXACT_ROUTES)
    out = tmp_path / "res.csv"
    r.to_csv(out)
    back = cl.loadpath.read_csv  # results are not paths, read as plain numbers
    data = np.genfromtxt(out, delimiter=",", names=True)
    np.testing.assert_allclose(data["torque_Nm"], r.torque, rtol=TOL.ULPS)
    assert callable(back)
    d = r.to_dict()
    assert set(d) >= {"time", "depth", "force", "radius", "displacement", "tangential_force",
                      "twist", "torque", "stick_radius", "dissipated_energy"}


def test_csv_bad_unit_and_bad_data(tmp_path):
    f = tmp_path / "p.csv"
    f.write_text("force [kN]\n1\n")
    seg, = cl.LoadPath.from_csv(f).segments        # units in the header are read (issue 12)
    assert dict(seg.columns)["force"].tolist() == [1000.0]
    f.write_text("force [kNm]\n1\n")
    with pytest.raises(cl.errors.UnitError, match="kNm"):
        cl.LoadPath.from_csv(f)
    f.write_text("force\nabc\n")
    with pytest.raises(TabulatedDataError, match="number"):
        cl.LoadPath.from_csv(f)


def test_to_dataframe_and_plot_optional(monkeypatch):
    r = contact().simulate(cl.LoadPath().ramp(force=10.0, steps=3))
    pd = pytest.importorskip("pandas")
    assert isinstance(r.to_dataframe(), pd.DataFrame)
    monkeypatch.setitem(sys.modules, "matplotlib", None)
    monkeypatch.setitem(sys.modules, "matplotlib.pyplot", None)
    with pytest.raises(ImportError, match="pip install matplotlib"):
        r.plot()


def test_plot_with_matplotlib():
    pytest.importorskip("matplotlib")
    import matplotlib
    matplotlib.use("Agg")
    r = contact().simulate(cl.LoadPath().ramp(force=10.0, steps=3).ramp(twist=1e-5, steps=3),
                           n_rings=20)
    axes = r.plot()
    assert len(axes) == 2


def test_progress_bar_optional_and_quiet_by_default(monkeypatch, capsys):
    p = (cl.LoadPath().ramp(force=10.0, steps=2)
         .sinusoid(twist=1e-5, cycles=200, steps_per_cycle=10))
    contact().simulate(p, n_springs=10, method="mdr")
    assert capsys.readouterr().err == ""
    monkeypatch.setitem(sys.modules, "tqdm", None)
    with pytest.raises(ImportError, match="pip install tqdm"):
        contact().simulate(p, n_springs=10, progress=True, method="mdr")


@pytest.mark.parametrize("method", ["exact", "mdr"])
def test_progress_bar_counts_every_step(method, capsys):
    """Both torsion drivers (the default exact ring solver and the MDR springs) show the bar."""
    pytest.importorskip("tqdm")
    p = (cl.LoadPath().ramp(force=10.0, steps=2)
         .sinusoid(twist=1e-5, cycles=200, steps_per_cycle=10))
    contact().simulate(p, n_rings=20, method=method, progress=True) if method == "exact" else \
        contact().simulate(p, n_springs=10, method=method, progress=True)
    err = capsys.readouterr().err
    assert f"{p.n_steps}/{p.n_steps}" in err


def test_progress_bar_exact_is_the_default_for_twist(monkeypatch):
    p = (cl.LoadPath().ramp(force=10.0, steps=2)
         .sinusoid(twist=1e-5, cycles=200, steps_per_cycle=10))
    monkeypatch.setitem(sys.modules, "tqdm", None)
    with pytest.raises(ImportError, match="pip install tqdm"):
        contact().simulate(p, n_rings=20, progress=True)
