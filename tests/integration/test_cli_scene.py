"""The command line: every example scene runs, outputs are re-read and checked; exit codes."""
import csv
import json
import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import contactlab
from contactlab import Contact
from contactlab.cli import main
from contactlab.scene import Scene

from tests import tolerances as TOL
from tests.unit.scene.helpers import example_params
from tests.tolerances import CLOSED_FORM, OUTPUT_ROUNDTRIP, TABULATED_SCENE, VISCO_SCENE

ROOT = Path(__file__).parents[2]
EX = ROOT / "examples"


def read_csv(path):
    with open(path) as fh:
        rows = list(csv.reader(fh))
    # headers are "name [unit]" (one style for every CSV contactlab writes)
    return {k.split(" [")[0]: np.array([float(r[i]) for r in rows[1:]])
            for i, k in enumerate(rows[0])}


def run(tmp_path, name, fmt):
    out = tmp_path / "out"
    assert main(["run", str(EX / name), "-o", str(out), "--format", fmt]) == 0
    if fmt == "csv":
        fields = read_csv(out / "fields.csv") if (out / "fields.csv").exists() else {}
        return read_csv(out / "series.csv"), fields
    doc = json.loads((out / "result.json").read_text())
    return ({k: np.array(v, float) for k, v in doc["series"].items()},
            {k: np.array(v, float) for k, v in doc["fields"].items()})


def e_star(*bodies):
    return 1.0 / sum((1 - nu**2) / E for E, nu in bodies)


@pytest.mark.parametrize("fmt", ["csv", "json"])
def test_hertz_steel_ball(tmp_path, fmt):
    s, f = run(tmp_path, "hertz_steel_ball.toml", fmt)
    Es, R, F = e_star((210e9, 0.3), (210e9, 0.3)), 0.01, s["force"]
    a = (3 * F * R / (4 * Es)) ** (1 / 3)                      # Hertz
    np.testing.assert_allclose(s["radius"], a, rtol=CLOSED_FORM)
    np.testing.assert_allclose(s["depth"], a**2 / R, rtol=CLOSED_FORM)
    np.testing.assert_allclose(s["stiffness"], 2 * Es * a, rtol=CLOSED_FORM)
    assert s["peak_pressure"][-1] == pytest.approx(3 * 100 / (2 * np.pi * a[-1] ** 2), rel=TOL.QUADRATURE)
    # headline numbers written in the file's comment
    assert (a[-1], s["depth"][-1]) == (pytest.approx(186.626e-6, rel=TOL.TABLE_6_DIGITS),
                                       pytest.approx(3.48291e-6, rel=TOL.TABLE_6_DIGITS))
    lib = Scene.from_toml(EX / "hertz_steel_ball.toml").contact().normal(force=F)
    np.testing.assert_allclose(s["depth"], lib.depth, rtol=OUTPUT_ROUNDTRIP)
    # at r = a the square-root edge turns the last-ulp difference of r into ~1e-8 p0
    np.testing.assert_allclose(f["pressure"], lib.pressure(f["r"])[-1], rtol=OUTPUT_ROUNDTRIP,
                               atol=TOL.EDGE_PRESSURE * f["pressure"][0])


def test_conical_indenter(tmp_path):
    s, _ = run(tmp_path, "conical_indenter.toml", "csv")
    Es, tb, d = e_star((1141e9, 0.07), (72e9, 0.17)), 1 / math.tan(math.radians(70.3)), s["depth"]
    np.testing.assert_allclose(s["force"], 2 * Es * d**2 / (np.pi * tb), rtol=CLOSED_FORM)   # Sneddon
    np.testing.assert_allclose(s["radius"], 2 * d / (np.pi * tb), rtol=CLOSED_FORM)
    assert s["force"].max() == pytest.approx(30.9550e-3, rel=TOL.PRINTED_6_DIGITS)
    assert d[-1] == 0 and s["force"][-1] == 0        # unloaded again


def test_rounded_flat_punch(tmp_path):
    s, f = run(tmp_path, "rounded_flat_punch.toml", "json")
    Es, b, R, d = e_star((3e9, 0.35)), 1e-3, 5e-3, s["depth"]
    a = np.sqrt((b * b + np.sqrt(b**4 + 4 * R * R * d * d)) / 2)
    F = 2 * Es * (a * d - (a * a - b * b) ** 1.5 / (3 * R))
    np.testing.assert_allclose(s["radius"][1:], a[1:], rtol=CLOSED_FORM)
    np.testing.assert_allclose(s["force"], F, rtol=CLOSED_FORM, atol=TOL.ABS_FLOOR)
    assert s["force"][-1] == pytest.approx(136.978, rel=TOL.PRINTED_6_DIGITS)
    assert np.all(np.isfinite(f["pressure"][f["r"] < b]))


def test_measured_profile(tmp_path):
    s, _ = run(tmp_path, "measured_profile.toml", "csv")
    Es, R, F = e_star((70e9, 0.22)), 5e-3, s["force"]
    a = (3 * F * R / (4 * Es)) ** (1 / 3)
    np.testing.assert_allclose(s["radius"], a, rtol=TABULATED_SCENE)
    np.testing.assert_allclose(s["depth"], a * a / R, rtol=TABULATED_SCENE)
    assert a[-1] == pytest.approx(100.648e-6, rel=TOL.PRINTED_6_DIGITS)


def test_steel_ball_twist(tmp_path):
    s, _ = run(tmp_path, "steel_ball_twist.toml", "csv")
    assert s["stick_radius"][-1] == pytest.approx(59.0360e-6, rel=TOL.PRINTED_6_DIGITS)   # Lubkin, mpmath
    assert s["torque"][-1] == pytest.approx(2.14505e-3, rel=TOL.PRINTED_6_DIGITS)
    lib = Scene.from_toml(EX / "steel_ball_twist.toml").contact().torsion(
        force=100.0, twist=s["twist"][-1], method="exact")
    assert s["torque"][-1] == pytest.approx(lib.torque, rel=OUTPUT_ROUNDTRIP)


def test_hip_joint_torsion(tmp_path):
    s, _ = run(tmp_path, "hip_joint_torsion.toml", "csv")
    Es, R, mu = e_star((210e9, 0.3), (1e9, 0.46)), 0.1, 0.08
    a = (3 * s["force"] * R / (4 * Es)) ** (1 / 3)
    np.testing.assert_allclose(s["radius"], a, rtol=TOL.FOUNDATION_RADIUS)      # foundation discretisation
    assert np.all(np.abs(s["torque"]) <= 0.75 * mu * s["force"] * a * (1 + 1e-3))
    assert s["dissipated_energy"][-1] > 0


def test_viscoelastic_creep(tmp_path):
    s, _ = run(tmp_path, "viscoelastic_creep.toml", "csv")
    t, a = s["time"][1:] - 1e-3, s["radius"][1:]
    G_inf, G_1, eta_1, R, F0 = 1e6, 2e6, 3e6, 5e-3, 1.0
    tau = eta_1 * (G_inf + G_1) / (G_inf * G_1)
    J = 1 / G_inf - (1 / G_inf - 1 / (G_inf + G_1)) * np.exp(-t / tau)    # SLS creep compliance
    # 1 ms ramp instead of a step (O(1e-3 s / tau)) plus the foundation's discretisation
    np.testing.assert_allclose(a, (3 * R * F0 * J / 16) ** (1 / 3), rtol=VISCO_SCENE)
    assert a[-1] == pytest.approx(0.976156e-3, rel=TOL.PRINTED_6_DIGITS)


def test_every_example_is_tested():
    names = {p.name for p in EX.glob("*.toml")}
    tested = {"hertz_steel_ball.toml", "conical_indenter.toml", "rounded_flat_punch.toml",
              "measured_profile.toml", "steel_ball_twist.toml", "hip_joint_torsion.toml",
              "viscoelastic_creep.toml", "steel_ball_fretting_map.toml", "hip_taper_wear.toml"}
    assert names == tested


@pytest.mark.parametrize("path", example_params())
def test_every_example_validates_and_plans(path, capsys):
    assert main(["validate", str(path)]) == 0
    assert main(["plan", str(path), "--json"]) == 0
    plan = json.loads(capsys.readouterr().out.split("\n", 1)[1])["plan"]
    assert plan["effects"][0]["effect"] == "normal"


def test_subprocess_run_json_and_version():
    env_cmd = [sys.executable, "-m", "contactlab"]
    p = subprocess.run(env_cmd + ["run", str(EX / "hertz_steel_ball.toml"), "--json"],
                       capture_output=True, text=True, cwd=ROOT)
    assert p.returncode == 0, p.stderr
    doc = json.loads(p.stdout)
    assert doc["ok"] and doc["meta"]["computed"] == ["normal"]
    v = subprocess.run(env_cmd + ["--version"], capture_output=True, text=True, cwd=ROOT)
    assert v.returncode == 0 and v.stdout.strip() == f"contactlab {contactlab.__version__}"


def test_run_plan_flag_does_not_run(capsys, monkeypatch):
    monkeypatch.setattr(Contact, "normal", None)
    assert main(["run", str(EX / "hertz_steel_ball.toml"), "--plan"]) == 0
    assert "closed form route" in capsys.readouterr().out


def test_invalid_scene_exit_2_with_json_issues(tmp_path, capsys):
    bad = tmp_path / "bad.toml"
    bad.write_text('[profile]\ntype = "parabolid"\nR = "10 mmm"\n')
    assert main(["validate", str(bad)]) == 2
    assert "parabolid" in capsys.readouterr().err
    assert main(["validate", str(bad), "--json"]) == 2
    doc = json.loads(capsys.readouterr().out)
    assert doc["ok"] is False and doc["exit"] == 2
    assert {i["path"] for i in doc["issues"]} == {"profile.type", "materials", "load_path"}
    assert main(["run", str(tmp_path / "missing.toml")]) == 2


def test_numerical_failure_exit_1(tmp_path, capsys):
    s = tmp_path / "sphere.toml"    # the exact sphere cannot carry this force: a would reach R
    s.write_text('[profile]\ntype = "sphere"\nR = "1 mm"\n[materials]\n'
                 'body1 = { type = "rigid" }\nbody2 = { type = "elastic", E = "1 MPa", nu = 0.5 }\n'
                 '[[load_path]]\nramp = { force = "1 kN", steps = 2 }\n')
    assert main(["validate", str(s)]) == 0
    assert main(["run", str(s)]) == 1
    assert "run failed (OutsideTheoryError)" in capsys.readouterr().err
    assert main(["run", str(s), "--json"]) == 1
    assert json.loads(capsys.readouterr().out)["exit"] == 1


def test_usage_errors(capsys):
    assert main([]) == 2
    for argv, code in ((["run"], 2), (["run", "x.toml", "--format", "xml"], 2), (["--version"], 0)):
        with pytest.raises(SystemExit) as e:
            main(argv)
        assert e.value.code == code


def test_demo_runs_on_a_fresh_install(tmp_path, capsys):
    assert main(["demo", "-o", str(tmp_path)]) == 0
    out = capsys.readouterr().out
    assert "steel ball on steel flat" in out and "force [N]" in out
    if hasattr(Contact, "twist_history"):
        assert "oscillating twist (exact Masing history)" in out
        assert "twist_history" in out
    try:
        import matplotlib  # noqa: F401
        assert (tmp_path / "contactlab_demo.png").exists()
    except ImportError:
        assert "no plot written" in out
    # a fresh folder: with matplotlib the first run left its plot in tmp_path
    assert main(["demo", "-o", str(tmp_path / "again"), "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    assert doc["ok"] and doc["series"]["force"][-1] == pytest.approx(100.0)


def test_run_with_plot(tmp_path, capsys):
    pytest.importorskip("matplotlib")
    assert main(["run", str(EX / "hertz_steel_ball.toml"), "-o", str(tmp_path), "--plot"]) == 0
    assert (tmp_path / "plot.png").stat().st_size > 0
