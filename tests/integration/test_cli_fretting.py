"""Fretting scenes through the command line: the example torsional fretting map and the
hip-taper-like wear run, checked against the Hertz/Lubkin closed forms of tests/reference."""
import csv
import json

import numpy as np
import pytest
from scipy.optimize import brentq, minimize_scalar

from contactlab.cli import main
from contactlab.scene import Scene
from contactlab.scene.run import MANIFEST

from tests import tolerances as TOL
from tests.reference import fretting as ref

from tests.integration.test_cli_scene import EX, e_star


def read_csv(path):
    """Columns by name with the unit suffix dropped, and the units."""
    with open(path) as fh:
        rows = list(csv.reader(fh))
    names = [h.split(" [")[0] for h in rows[0]]
    units = {h.split(" [")[0]: h.split(" [")[1].rstrip("]") for h in rows[0] if " [" in h}
    return {k: np.array([float(r[i]) for r in rows[1:]]) for i, k in enumerate(names)}, units


def run(tmp_path, name, *extra):
    out = tmp_path / "out"
    assert main(["run", str(EX / name), "-o", str(out), *extra]) == 0
    return out


def test_steel_ball_fretting_map(tmp_path):
    out = run(tmp_path, "steel_ball_fretting_map.toml")
    pts, units = read_csv(out / "fretting_map.csv")
    bnd, bunits = read_csv(out / "fretting_boundary.csv")
    assert units["force"] == "N" and units["twist_amplitude"] == "rad" and bunits["force"] == "N"
    Es, Gt, R, mu = e_star((210e9, 0.3), (210e9, 0.3)), 210e9 / (4 * 1.3), 0.01, 0.6
    F = bnd["force"]
    np.testing.assert_allclose(F, np.geomspace(10, 1000, 9), rtol=TOL.CLOSED_FORM)
    a = (3 * F * R / (4 * Es)) ** (1 / 3)
    # the energy-ratio boundary: A = 0.2 on the Lubkin loading curve, independent quadrature
    s_t = brentq(lambda s: ref.hertz_torsion_energy_ratio(s, 100.0, mu, a[4], Gt) - 0.2, 0.05,
                 0.95, xtol=1e-13)
    phi_t = ref.hertz_twist_of_stick_ratio(s_t, F, mu, a, Gt)
    np.testing.assert_allclose(bnd["twist_amplitude"], phi_t, rtol=TOL.TORSION_BOUNDARY_ROOT)
    # headline numbers of the file's comment
    assert s_t == pytest.approx(0.661685, rel=TOL.PRINTED_6_DIGITS)
    np.testing.assert_allclose(phi_t[[0, 4, 8]], [2.79841e-3, 6.02899e-3, 12.9891e-3],
                               rtol=TOL.PRINTED_6_DIGITS)
    np.testing.assert_allclose(phi_t * Gt * a**2 / (mu * F), 0.141336, rtol=TOL.PRINTED_6_DIGITS)
    # every point: its stick ratio lies on the Lubkin curve; gross slip exactly beyond the boundary
    Fp, X = pts["force"], pts["twist_amplitude"]
    ap = (3 * Fp * R / (4 * Es)) ** (1 / 3)
    np.testing.assert_allclose(ref.hertz_twist_of_stick_ratio(pts["stick_ratio"], Fp, mu, ap, Gt),
                               X, rtol=TOL.TORSION_BOUNDARY)
    assert pts["stick_ratio"].min() < 1e-8          # deep gross slip is in the check too
    edge = np.interp(Fp, F, bnd["twist_amplitude"])
    clear = np.abs(X / edge - 1) > 1e-3
    assert np.array_equal((pts["regime"] == 2)[clear], (X >= edge)[clear])
    assert set(np.unique(pts["regime"])) == {1.0, 2.0}
    for i in (0, 30, 100, 200, 278):
        A = ref.hertz_torsion_energy_ratio(pts["stick_ratio"][i], Fp[i], mu, ap[i], Gt)
        assert pts["energy_ratio"][i] == pytest.approx(A, rel=TOL.LUBKIN_ENERGY_REFERENCE)


def test_hip_taper_wear(tmp_path):
    out = run(tmp_path, "hip_taper_wear.toml")
    s, _ = read_csv(out / "series.csv")
    w, units = read_csv(out / "wear.csv")
    prof, punits = read_csv(out / "wear_profiles.csv")
    worn, _ = read_csv(out / "worn_profile.csv")
    assert units["volume"] == "m^3" and units["cycles"] == "1" and set(punits.values()) == {"m"}
    Es = e_star((210e9, 0.3), (110e9, 0.34))
    Gt = 1 / (2.6 / 210e9 + 2.68 / 110e9)             # 1/(1/G1 + 1/G2)
    F, R, mu, phi, k = 2000.0, 0.05, 0.3, 2e-3, 1e-14
    a = (3 * F * R / (4 * Es)) ** (1 / 3)
    s0 = brentq(lambda x: ref.hertz_twist_of_stick_ratio(x, F, mu, a, Gt) - phi, 1e-3, 1 - 1e-9,
                xtol=1e-15)
    M = ref.hertz_torque_of_stick_ratio(s0, F, mu, a)
    W = ref.hertz_torsion_energy_ratio(s0, F, mu, a, Gt) * 4 * phi * M
    # headline numbers of the file's comment
    assert (Es, Gt, a, s0, M, W) == (pytest.approx(80.8190e9, rel=TOL.PRINTED_6_DIGITS),
                                     pytest.approx(27.2149e9, rel=TOL.PRINTED_6_DIGITS),
                                     pytest.approx(975.400e-6, rel=TOL.PRINTED_6_DIGITS),
                                     pytest.approx(0.783818, rel=TOL.PRINTED_6_DIGITS),
                                     pytest.approx(0.192412, rel=TOL.PRINTED_6_DIGITS),
                                     pytest.approx(1.85321e-4, rel=TOL.PRINTED_6_DIGITS))
    d0, a0, V0, _ = ref.hertz_limiting_state(s0 * a, F, Es, R)
    assert (d0, a0, V0) == (pytest.approx(20.0809e-6, rel=TOL.PRINTED_6_DIGITS),
                            pytest.approx(1.11637e-3, rel=TOL.PRINTED_6_DIGITS),
                            pytest.approx(2.72428e-12, rel=TOL.PRINTED_6_DIGITS))
    # the path: from the first peak (step 10 + 10) to the last is one steady loop of energy W
    E = s["dissipated_energy"]
    assert s["twist"][20] == pytest.approx(phi, rel=TOL.CLOSED_FORM) and s["twist"][-1] == s["twist"][20]
    assert E[-1] - E[20] == pytest.approx(W, rel=TOL.LUBKIN_ENERGY_REFERENCE)
    assert s["torque"][20] == pytest.approx(M, rel=TOL.LUBKIN_ENERGY_REFERENCE)
    # wear: fresh energy on the grid, wear-energy identity, the limiting state of the final c
    assert w["energy_per_cycle"][0] == pytest.approx(W, rel=TOL.WEAR_GRID_ENERGY)
    assert w["cycles"][-1] == 1e6
    np.testing.assert_allclose(w["volume"], k / mu * w["dissipated_energy"],
                               rtol=TOL.WEAR_ENERGY_IDENTITY, atol=0)
    assert w["energy_per_cycle"][-1] < 1e-2 * w["energy_per_cycle"][0]     # wear has (nearly) stopped
    d_inf, a_inf, V_inf, h = ref.hertz_limiting_state(w["stick_radius"][-1], F, Es, R)
    assert w["depth"][-1] == pytest.approx(d_inf, rel=TOL.WEAR_LIMIT_DEPTH)
    assert w["scar_radius"][-1] == pytest.approx(a_inf, rel=TOL.WEAR_LIMIT_DEPTH)
    assert w["volume"][-1] == pytest.approx(V_inf, rel=TOL.WEAR_LIMIT_VOLUME)
    c = w["stick_radius"][-1]
    h_max = -minimize_scalar(lambda r: -h(r), bounds=(c * (1 + 1e-9), a_inf), method="bounded",
                             options={"xatol": 1e-12}).fun
    assert w["max_wear_depth"][-1] == pytest.approx(h_max, rel=TOL.WEAR_LIMIT_VOLUME)
    # profiles: checkpoints 0, 1e3, 1e4, 1e5, 1e6; the worn profile is the last one
    assert list(prof) == ["r", "profile@0", "profile@1000", "profile@10000", "profile@100000",
                          "profile@1e+06"]
    np.testing.assert_array_equal(worn["f"], prof["profile@1e+06"])
    np.testing.assert_allclose(prof["profile@0"], prof["r"] ** 2 / (2 * R), rtol=TOL.CLOSED_FORM)
    assert np.all(prof["profile@1e+06"] >= prof["profile@0"])       # wear only removes material
    # the worn profile feeds a new scene as a tabulated profile (below the fretting force: in the
    # limiting state g is flat across the slip annulus, so at 2 kN rounding may let it dip and
    # the MDR refuses the annular contact, docs/fretting.md section 5)
    assert Scene.from_dict({"profile": {"type": "tabulated", "file": str(out / "worn_profile.csv")},
                            "materials": {"body1": {"type": "elastic", "E": 210e9, "nu": 0.3},
                                          "body2": {"type": "elastic", "E": 110e9, "nu": 0.34}},
                            "load_path": [{"ramp": {"force": 1000.0, "steps": 2}}]}).run()


def test_run_json_holds_wear_and_map(tmp_path, capsys):
    assert main(["run", str(EX / "hip_taper_wear.toml"), "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    assert doc["wear"]["units"]["volume"] == "m^3"
    assert doc["meta"]["wear"]["cycles"] == 1e6
    assert [r["effect"] for r in doc["plan"]["effects"]][-1] == "wear"
    assert len(doc["wear"]["profiles"]) == 5 == len(doc["wear"]["checkpoints"])
    out = tmp_path / "j"
    assert main(["run", str(EX / "steel_ball_fretting_map.toml"), "-o", str(out), "--format",
                 "json"]) == 0
    doc = json.loads((out / "result.json").read_text())
    assert len(doc["fretting_map"]["points"]["regime"]) == 9 * 31
    assert sorted(p.name for p in out.iterdir()) == [MANIFEST, "result.json"]
