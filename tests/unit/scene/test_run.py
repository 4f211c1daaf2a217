"""Execution: only planned calls are made; series agree with the library and closed forms."""
from types import SimpleNamespace

import numpy as np
import pytest

from contactlab import Contact
from contactlab.errors import ConvergenceError, EffectNotPlannedError, SceneError
from contactlab.scene import Scene

from tests import tolerances as TOL
from tests.tolerances import CLOSED_FORM, QUADRATURE
from tests.unit.scene.helpers import base, twist_scene

UNPLANNED = ("torsion", "twist_history", "simulate", "tangential", "shift_history")


def hertz(F, R, E_star):
    """Hertz (Johnson 1985, eqs. 4.22-4.23): contact radius and depth of force."""
    a = np.cbrt(3.0 * F * R / (4.0 * E_star))   # cube root within 0.53 ulp
    return a, a * a / R


E_STEEL = 1.0 / (2.0 * (1.0 - 0.3**2) / 210e9)


def test_normal_only_never_builds_torsion_or_slip(monkeypatch):
    calls = []

    def forbidden(name):
        def f(*a, **k):
            calls.append(name)
            raise AssertionError(f"{name} computed for a normal-only scene")
        return f
    for name in UNPLANNED:
        monkeypatch.setattr(Contact, name, forbidden(name), raising=False)
    res = Scene(base(interface={"friction": 0.2})).run()
    assert res.meta["computed"] == ["normal"] and calls == []
    assert res.meta["route"] == "closed_form"


def test_normal_only_series_match_hertz_and_the_api():
    res = Scene(base(outputs={"series": ["time", "depth", "force", "radius", "stiffness",
                                         "peak_pressure"]})).run()
    F = np.linspace(0, 100, 11)
    a, d = hertz(F, 0.01, E_STEEL)
    np.testing.assert_allclose(res["force"], F, rtol=CLOSED_FORM)
    np.testing.assert_allclose(res["radius"], a, rtol=CLOSED_FORM)
    np.testing.assert_allclose(res["depth"], d, rtol=CLOSED_FORM)
    np.testing.assert_allclose(res["stiffness"], 2 * E_STEEL * a, rtol=CLOSED_FORM)
    p0 = np.divide(3 * F, 2 * np.pi * a**2, out=np.zeros_like(F), where=a > 0)
    np.testing.assert_allclose(res["peak_pressure"], p0, rtol=QUADRATURE)
    st = Scene(base()).contact().normal(force=F)
    np.testing.assert_array_equal(res["radius"], st.radius)


def test_fields_match_hertz_pressure_and_displacement():
    res = Scene(base(outputs={"fields": ["pressure", "surface_displacement"],
                              "field_points": 31})).run()
    a, d = hertz(100.0, 0.01, E_STEEL)
    r = res.fields["r"]
    assert r[-1] == pytest.approx(1.5 * a, rel=TOL.SHORT_ARITHMETIC)
    inside = r < a
    p = 2 * E_STEEL / (np.pi * 0.01) * np.sqrt(np.clip(a * a - r * r, 0, None))   # Hertz
    # a field point at the contact edge r = a (here point 20 of 30 out to 1.5 a): the pressure
    # p0 sqrt(1 - r²/a²) has an infinite slope in a there, so a rounding of a by k ulp moves it
    # by up to p0 sqrt(2 k eps); both radii are rounded cube roots (k <= 4 allowed)
    edge = np.abs(r - a) <= 4 * np.spacing(a)
    assert edge.sum() == 1
    np.testing.assert_allclose(res["pressure"][~edge], p[~edge], rtol=QUADRATURE,
                               atol=QUADRATURE * p[0])
    assert abs(res["pressure"][edge][0] - p[edge][0]) <= p[0] * np.sqrt(8 * np.finfo(float).eps)
    R = 0.01
    out = ~inside
    uz_out = ((2 * a * a - r[out] ** 2) * np.arcsin(a / r[out])
              + a * np.sqrt(r[out] ** 2 - a * a)) / (np.pi * R)   # Johnson eq. 3.42b
    np.testing.assert_allclose(res["surface_displacement"][inside], d - r[inside] ** 2 / (2 * R),
                               rtol=QUADRATURE)
    np.testing.assert_allclose(res["surface_displacement"][out], uz_out, rtol=QUADRATURE)


def test_unplanned_output_raises_effect_not_planned():
    res = Scene(base()).run()
    with pytest.raises(EffectNotPlannedError, match="add 'torsion'"):
        res["torque"]
    with pytest.raises(KeyError):
        res["nonsense"]


def test_table_and_dict():
    res = Scene(base()).run()
    assert "force [N]" in res.table()
    d = res.to_dict()
    assert d["units"]["force"] == "N" and d["meta"]["computed"] == ["normal"]


# ---- routes with stand-ins for the parallel APIs (checks the plumbing, not the physics) --------
class Recorder:
    def __init__(self, result_factory):
        self.calls = []
        self.factory = result_factory

    def __call__(self, contact, *args, **kw):
        self.calls.append((args, kw))
        return self.factory(*args, **kw)


def fake_history(**kw):
    tw = np.asarray(kw["twist"], float)
    return SimpleNamespace(twist=tw, torque=3.0 * tw, stick_radius=np.full(tw.shape, 1e-5),
                           dissipated_energy=np.abs(tw))


def test_oscillating_twist_calls_history_once_at_constant_load(monkeypatch):
    rec = Recorder(fake_history)
    monkeypatch.setattr(Contact, "twist_history", lambda self, **kw: rec(self, **kw), raising=False)
    monkeypatch.setattr(Contact, "torsion", None, raising=False)
    monkeypatch.setattr(Contact, "simulate", None, raising=False)
    s = Scene(twist_scene())
    res = s.run()
    assert res.meta["computed"] == ["normal", "twist_history"]
    (args, kw), = rec.calls
    assert kw["force"] == 100.0 and kw["method"] == "exact"
    np.testing.assert_array_equal(kw["twist"], s.history().values("torsion")[10:])
    assert np.all(res["torque"][:10] == 0)
    np.testing.assert_array_equal(res["stick_radius"][:10], res["radius"][:10])
    np.testing.assert_array_equal(res["torque"][10:], 3.0 * kw["twist"])


def test_monotone_twist_calls_torsion(monkeypatch):
    rec = Recorder(fake_history)
    monkeypatch.setattr(Contact, "torsion", lambda self, **kw: rec(self, **kw), raising=False)
    res = Scene(twist_scene({"ramp": {"twist": "1 mrad", "steps": 5}}, friction=None)).run()
    assert res.meta["computed"] == ["normal", "torsion"]
    assert rec.calls[0][1]["method"] == "no-slip"


def test_foundation_route_passes_the_typed_path(monkeypatch):
    seen = {}

    def simulate(self, path, **kw):
        seen.update(path=path, kw=kw)
        smp = path.sample()
        n = smp.n_steps
        return SimpleNamespace(depth=np.ones(n), force=smp.values["force"], radius=np.ones(n),
                               twist=smp.values["twist"], torque=np.zeros(n),
                               stick_radius=np.ones(n), dissipated_energy=np.zeros(n))
    monkeypatch.setattr(Contact, "simulate", simulate, raising=False)
    seg = {"sinusoid": {"twist": 1e-3, "force": 50.0, "cycles": 1}}
    # the default (exact) torsion method routes a changing load to the exact ring solver
    Scene(twist_scene(seg, solver={"n_springs": 64})).run()
    assert seen["kw"] == {"method": "exact"}
    # the ring solver reads solver.n_rings (issue 26: the cost report laddered n_springs)
    Scene(twist_scene(seg, solver={"n_springs": 64, "n_rings": 90})).run()
    assert seen["kw"] == {"method": "exact", "n_rings": 90}
    with pytest.raises(SceneError, match="n_rings"):
        Scene(twist_scene(seg, solver={"n_rings": 1}))
    d = twist_scene(seg, solver={"n_springs": 64}, outputs={"method": "mdr"})
    s = Scene(d)
    res = s.run()
    assert res.meta["computed"] == ["simulate"]
    # outputs.method = 'mdr' asks for the spring foundation by name (simulate's default for a
    # twisted path is the exact ring solver)
    assert seen["path"] is s.load_path and seen["kw"] == {"n_springs": 64, "method": "mdr"}
    kinds = [type(seg).__name__ for seg in seen["path"].segments]
    assert kinds == ["Table", "Ramp", "Sinusoid"]      # the unloaded start, then the scene's
    np.testing.assert_array_equal(res["twist"], s.history().values("torsion"))


def test_nan_from_a_solver_is_a_convergence_error(monkeypatch):
    def bad(self, **kw):
        r = fake_history(**kw)
        r.torque[-1] = np.nan
        return r
    monkeypatch.setattr(Contact, "twist_history", bad, raising=False)
    with pytest.raises(ConvergenceError, match=r"torque\[\d+\] is NaN"):
        Scene(twist_scene()).run()


# ---- real physics once the torsion helper's API is merged ----------------------------------------
def test_monotone_twist_against_lubkin():
    import mpmath as mp
    res = Scene(twist_scene({"ramp": {"twist": "5 mrad", "steps": 5}})).run()
    G_t = 210e9 / (4 * 1.3)
    a, _ = hertz(100.0, 0.01, E_STEEL)
    mu, F = 0.2, 100.0

    def phi_of_t(t):   # theory §6.3
        m = 1 - t * t
        return 3 * mu * F / (4 * mp.pi * G_t * a * a) * (mp.ellipk(m) - mp.ellipe(m))
    for phi, M, c in zip(res["twist"][-3:], res["torque"][-3:], res["stick_radius"][-3:]):
        t = mp.findroot(lambda t: phi_of_t(t) - phi, 0.5)
        M_ref = mu * F * a * (3 * mp.pi / 16 - 4 / mp.pi * mp.quad(
            lambda s: s * s * mp.ellipe(1 - s * s), [0, t]))
        assert M == pytest.approx(float(M_ref), rel=TOL.SCENE_VS_MPMATH)
        assert c == pytest.approx(float(t) * a, rel=TOL.SCENE_VS_MPMATH)


def test_oscillating_twist_masing_symmetry():
    res = Scene(twist_scene()).run()
    # Masing: the loop is symmetric, M(-phi_max) = -M(phi_max)
    i_max, i_min = int(np.argmax(res["twist"])), int(np.argmin(res["twist"]))
    assert res["torque"][i_min] == pytest.approx(-res["torque"][i_max], rel=TOL.SCENE_VS_MPMATH)


def test_adhesive_scene_against_jkr():
    # JKR (Johnson-Kendall-Roberts 1971): F = 4E*a^3/(3R) - sqrt(8 pi a^3 E* w)
    res = Scene(base(interface={"work_of_adhesion": "0.05 J/m^2"})).run()
    a, E, w, R = res["radius"][-1], E_STEEL, 0.05, 0.01
    assert res["force"][-1] == pytest.approx(4 * E * a**3 / (3 * R)
                                             - np.sqrt(8 * np.pi * a**3 * E * w), rel=TOL.QUADRATURE)


def test_monotone_shift_against_cattaneo_mindlin():
    res = Scene(twist_scene({"ramp": {"displacement": "0.3 um", "steps": 4}})).run()
    assert res.meta["computed"] == ["normal", "tangential"]
    mu, F = 0.2, 100.0
    G = 210e9 / 2.6
    G_star = 2 * G / (2 - 0.3)                       # 1/G* = 2 (2-nu)/(4G), identical bodies
    a, _ = hertz(F, 0.01, E_STEEL)
    u_star = 3 * mu * F / (4 * a * G_star)            # Mindlin 1949
    u = res["displacement"][-4:]
    np.testing.assert_allclose(res["tangential_force"][-4:],
                               mu * F * (1 - (1 - u / u_star) ** 1.5), rtol=TOL.CM_CLOSED)
    np.testing.assert_allclose(res["stick_radius"][-4:], a * np.sqrt(1 - u / u_star), rtol=TOL.CM_CLOSED)


def test_oscillating_shift_masing_energy():
    amp = 0.2e-6
    res = Scene(twist_scene({"sinusoid": {"displacement": amp, "cycles": 1,
                                          "steps_per_cycle": 400}},
                            {"sinusoid": {"displacement": amp, "cycles": 1,
                                          "steps_per_cycle": 400}})).run()
    assert res.meta["computed"] == ["normal", "shift_history"]
    mu, F = 0.2, 100.0
    G_star = 2 * (210e9 / 2.6) / 1.7
    a, _ = hertz(F, 0.01, E_STEEL)
    u_star = 3 * mu * F / (4 * a * G_star)
    T = mu * F * (1 - (1 - amp / u_star) ** 1.5)      # force amplitude on the virgin curve
    t = T / (mu * F)                                  # Mindlin-Deresiewicz loop energy
    bracket = 1 - (1 - t) ** (5 / 3) - 5 * t / 6 * (1 + (1 - t) ** (2 / 3))
    W = 18 / 5 * mu**2 * F**2 / (a * G_star) * bracket
    E = res["dissipated_energy"]
    n = 400
    assert E[-1] - E[-1 - n] == pytest.approx(W, rel=TOL.SCENE_VS_MPMATH)   # second (steady) cycle
