"""Every plot the API makes renders with the shared style: nothing clipped, loop ticks apart,
engineering units on request (contactlab.plotting)."""
from __future__ import annotations

import numpy as np
import pytest

import contactlab as cl
from contactlab import plotting as pl
from contactlab.errors import ParameterError

matplotlib = pytest.importorskip("matplotlib")
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

#: a label may touch the canvas edge by this much (px) after rounding of the layout engine
EDGE_PX = 1.0

STEEL = cl.Elastic(E=210e9, nu=0.3)


def _contact(friction=0.3):
    return cl.Contact(cl.profiles.Paraboloid(R=0.01), materials=(STEEL, STEEL), friction=friction)


def _check_figure(fig, tmp_path, name):
    """Render to PNG; every text of the figure (titles, labels, tick labels, legends) lies inside
    the canvas, and tick labels on one axis do not overlap."""
    out = tmp_path / f"{name}.png"
    fig.savefig(out)
    assert out.stat().st_size > 0
    renderer = fig.canvas.get_renderer()
    tight = fig.get_tightbbox(renderer)                 # inches: every visible artist drawn
    canvas = fig.bbox_inches
    tol = EDGE_PX / fig.dpi
    assert tight.x0 >= canvas.x0 - tol and tight.y0 >= canvas.y0 - tol, (name, tight, canvas)
    assert tight.x1 <= canvas.x1 + tol and tight.y1 <= canvas.y1 + tol, (name, tight, canvas)
    for ax in fig.axes:
        for axis in (ax.xaxis, ax.yaxis):
            lo, hi = sorted(axis.get_view_interval())
            boxes = [t.label1.get_window_extent(renderer) for t, loc in
                     zip(axis.get_major_ticks(), axis.get_majorticklocs())
                     if lo <= loc <= hi and t.label1.get_visible() and t.label1.get_text()]
            for b1, b2 in zip(boxes, boxes[1:]):
                assert not b1.overlaps(b2), (name, [lab.get_text() for lab in
                                                    axis.get_ticklabels()])
    plt.close(fig)


def _labels(fig):
    return " ".join(ax.get_xlabel() + " " + ax.get_ylabel() for ax in fig.axes)


@pytest.mark.parametrize("units", ["si", "engineering"])
def test_twist_history_plot(tmp_path, units):
    phi = np.concatenate([np.linspace(0, 4e-4, 15), np.linspace(4e-4, -4e-4, 30)[1:],
                          np.linspace(-4e-4, 4e-4, 30)[1:]])
    h = _contact().twist_history(force=100.0, twist=phi)
    ax1, ax2 = h.plot(units=units)
    assert len(ax1.xaxis.get_majorticklocs()) <= pl.MAX_TICKS + 2   # + limits outside the view
    if units == "engineering":
        assert "mrad" in ax1.get_xlabel() and "mN·m" in ax1.get_ylabel()
        assert "µm" in ax2.get_ylabel()
        # the numbers are the SI arrays converted, not a different result
        np.testing.assert_array_equal(ax1.lines[0].get_ydata(), h.torque * 1e3)
    else:
        assert ax1.get_xlabel() == "twist [rad]" and ax1.get_ylabel() == "torque [N·m]"
    _check_figure(ax1.figure, tmp_path, f"twist_{units}")


def test_shift_history_plot(tmp_path):
    u = np.concatenate([np.linspace(0, 1e-6, 10), np.linspace(1e-6, -1e-6, 20)[1:]])
    h = _contact().shift_history(force=100.0, displacement=u)
    ax1, _ = h.plot(units="engineering")
    assert ax1.get_xlabel() == "displacement [µm]"
    _check_figure(ax1.figure, tmp_path, "shift")


def test_fretting_plots(tmp_path):
    c = _contact(0.5)
    ax = c.fretting_loop(force=100.0, displacement_amplitude=1.5e-6).plot(units="engineering")
    assert "µm" in ax.get_xlabel()
    _check_figure(ax.figure, tmp_path, "loop")
    ax = c.fretting_loop(force=100.0, twist_amplitude=1e-3).plot()
    _check_figure(ax.figure, tmp_path, "loop_torsion")
    m = c.fretting_map(force=np.linspace(20.0, 200.0, 5),
                       displacement_amplitude=np.geomspace(1e-7, 2e-5, 6))
    ax = m.plot(units="engineering")
    assert ax.get_xlabel() == "displacement amplitude [µm]"
    _check_figure(ax.figure, tmp_path, "map")


def test_path_result_plot(tmp_path):
    path = cl.LoadPath().ramp(force=10.0, steps=5).ramp(twist=1e-4, steps=5) \
        .ramp(twist=-1e-4, steps=10)
    r = _contact().simulate(path, n_rings=40)
    axes = r.plot(units="engineering")
    assert "mN·m" in _labels(axes[0].figure)
    _check_figure(axes[0].figure, tmp_path, "path")
    ax = r.plot("torque", x="twist")[0]
    _check_figure(ax.figure, tmp_path, "path_loop")


def test_wear_plot(tmp_path):
    w = _contact(0.5).wear(force=10.0, displacement_amplitude=0.5e-6, cycles=1e4,
                           wear_coefficient=1e-15, checkpoints=3)
    axes = w.plot(units="engineering")
    assert "µm³" in _labels(axes[0].figure)
    _check_figure(axes[0].figure, tmp_path, "wear")


def test_scene_and_cost_plots(tmp_path):
    from pathlib import Path

    from contactlab.scene import Scene
    ex = Path(__file__).resolve().parents[2] / "examples"
    res = Scene.from_toml(ex / "steel_ball_twist.toml").run()
    fig_path = res.plot(tmp_path / "scene.png")
    assert fig_path.stat().st_size > 0


def _wear_map_scene(tmp_path):
    """The hip-taper wear example with a small fretting map added (both tables in one scene)."""
    from pathlib import Path

    from contactlab.scene import Scene
    ex = Path(__file__).resolve().parents[2] / "examples"
    data = Scene.from_toml(ex / "hip_taper_wear.toml").to_dict()
    data["wear"]["cycles"] = 1e4
    data["wear"]["checkpoints"] = [1e2, 1e3]
    data["fretting_map"] = {"force": [500.0, 1000.0, 2000.0],
                            "twist_amplitude": [1e-4, 1e-3, 1e-2, 1e-1]}
    return Scene.from_dict(data, tmp_path)


@pytest.mark.parametrize("units", ["si", "engineering"])
def test_scene_plot_draws_wear_and_fretting_map(tmp_path, units):
    res = _wear_map_scene(tmp_path).run()
    assert res.wear is not None and res.fretting_map is not None
    fig = res.figure(units=units)
    titles = [ax.get_title() for ax in fig.axes]
    # the wear row (profile evolution, radii, worn volume against cycles) and the map row
    assert {"profile", "radii", "worn volume"} <= set(titles)
    profile_ax = fig.axes[titles.index("profile")]
    assert len(profile_ax.get_lines()) == res.wear.checkpoints.size
    volume_ax = fig.axes[titles.index("worn volume")]
    np.testing.assert_array_equal(volume_ax.get_lines()[0].get_xdata(), res.wear.cycles[1:])
    map_ax = [ax for ax in fig.axes if ax.collections]
    assert len(map_ax) == 1 and "twist amplitude" in map_ax[0].get_xlabel()
    assert "gross-slip boundary" in [t.get_text() for t in map_ax[0].get_legend().get_texts()]
    _check_figure(fig, tmp_path, f"scene_wear_map_{units}")


def test_cli_run_plot_with_wear(tmp_path):
    from contactlab.cli import main
    scene = _wear_map_scene(tmp_path)
    path = tmp_path / "scene.toml"
    path.write_text(scene.to_toml())
    out = tmp_path / "out"
    assert main(["run", str(path), "-o", str(out), "--plot"]) == 0
    png = out / "plot.png"
    assert png.stat().st_size > 0
    img = plt.imread(png)
    # the same figure as SceneResult.figure(): series rows plus the wear and map rows
    fig = scene.run().figure()
    dpi = pl.STYLE["savefig.dpi"]
    assert img.shape[:2] == (round(fig.get_figheight() * dpi), round(fig.get_figwidth() * dpi))
    assert "worn volume" in [ax.get_title() for ax in fig.axes]
    plt.close(fig)


def test_units_checked():
    with pytest.raises(ParameterError, match="units='imperial'"):
        pl.axis_label("depth", "m", "imperial")
    h = _contact().shift_history(force=1.0, displacement=[0.0, 1e-7])
    with pytest.raises(ParameterError, match="units"):
        h.plot(units="mm")
    assert pl.axis_label("energy ratio", "1") == "energy ratio"
