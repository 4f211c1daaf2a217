"""Same call, bit-identical result, whatever ran before (issue 11).

A shuffled workload over shared Contact objects is run serially on fresh contacts (the reference),
serially on one warm contact per profile in a shuffled order, in 4 threads sharing the contacts,
and in a process pool; every number must agree bit for bit. The workload covers normal,
tangential and torsion states, spring and exact (ring) simulate, fretting loops, wear and a
ContactLaw history (its family master curve is a shared lazy cache). Lazy caches (profile routes, JKR
branches, table rules, error estimates filled on first access) must never change a result. Also:
results pickle and compare equal to their copies."""
from __future__ import annotations

import pickle
import random
from concurrent.futures import ProcessPoolExecutor, ThreadPoolExecutor

import numpy as np
import pytest

import contactlab as cl
from contactlab import profiles as P

STEEL = cl.Elastic(E=210e9, nu=0.3)
R_TABLE = np.linspace(0.0, 2e-3, 300)


def make_contacts():
    return {
        "paraboloid": cl.Contact(P.Paraboloid(R=0.01), materials=(STEEL, STEEL), friction=0.3),
        "sphere": cl.Contact(P.Sphere(R=0.01), materials=(STEEL, STEEL), friction=0.3),
        "cone+sphere": cl.Contact(P.Cone(slope=0.01) + P.Sphere(R=0.02), materials=(STEEL, STEEL),
                                  friction=0.3),
        "table": cl.Contact(P.Tabulated(r=R_TABLE, f=R_TABLE**2 / 0.02 + 1e3 * R_TABLE**3),
                            materials=(STEEL, STEEL), friction=0.3),
        "adhesive": cl.Contact(P.Paraboloid(R=0.01), materials=(STEEL, STEEL),
                               work_of_adhesion=0.5),
    }


def _numbers(*values):
    return b"".join(np.ascontiguousarray(np.asarray(v, float)).tobytes() for v in values)


def task(contacts, key):
    """One call of the workload -> bytes of every number it returns (estimates included)."""
    name, kind, x = key
    c = contacts[name]
    if kind == "normal":
        s = c.normal(force=x)
        est = s.error_estimates if name != "adhesive" else {}
        return _numbers(s.radius, s.depth, s.force, s.error_estimate, *est.values(),
                        s.pressure([0.0, 0.5 * s.radius]))
    if kind == "depth":
        s = c.normal(depth=x)
        return _numbers(s.radius, s.force, s.error_estimate, s.displacement(3 * s.radius))
    if kind == "torsion":
        s = c.torsion(force=x, twist=[1e-5, 1e-4])
        return _numbers(s.torque, s.stick_radius, s.error_estimate, s.shear([0.0, 1e-5]))
    if kind == "tangential":
        s = c.tangential(force=x, displacement=1e-8)
        return _numbers(s.tangential_force, s.stick_radius, s.shear([0.0, 1e-5]))
    if kind == "pull_off":
        return _numbers(c.pull_off().force, c.adhesion_cycle(depth=[1e-7, -1e-7, 0.0]).force)
    if kind == "simulate":
        path = cl.LoadPath().ramp(force=x, steps=20).sinusoid(displacement=1e-8, cycles=1,
                                                              steps_per_cycle=40)
        r = c.simulate(path, n_springs=200, error_estimate=True)
        return _numbers(*r.data.values(), *r.meta["error_estimates"].values())
    if kind == "exact":
        path = (cl.LoadPath().ramp(force=x, steps=5).ramp(twist=2e-4, steps=6)
                .ramp(force=2 * x, twist=-1e-4, steps=6))
        r = c.simulate(path, method="exact", n_rings=60, error_estimate=True)
        return _numbers(*r.data.values(), *r.meta["error_estimates"].values())
    if kind == "fretting_loop":
        a = c.fretting_loop(force=x, displacement_amplitude=2e-7, n_points=20)
        b = c.fretting_loop(force=x, twist_amplitude=1e-4, n_points=20)
        return _numbers(a.energy, a.peak, a.x, a.y, b.energy, b.peak, b.stick_radius, b.x, b.y)
    if kind == "wear":
        w = c.wear(force=x, twist_amplitude=2e-3, wear_coefficient=1e-14, cycles=1e3,
                   n_grid=100, checkpoints=3)
        return _numbers(w.cycles, w.depth, w.radius, w.volume, w.dissipated_energy,
                        *(p.f for p in w.profiles))
    if kind == "law":
        # (the springs' model-error warning is not what this test is about)
        law = cl.ContactLaw(P.Paraboloid, R=[0.01, 0.005, 0.02], materials=(STEEL, STEEL),
                            friction=0.3, warn_model_error=False)
        out = []
        for k in range(12):           # constant load, then a load change (MDR springs)
            F = x * (1.0 if k < 8 else 1.0 + 0.05 * (k - 7))
            st = law.step(force=F, twist=2e-4 * np.sin(0.7 * k) * np.array([1.0, 0.5, 2.0]))
            st2 = law.step(force=F, displacement=1e-7 * np.cos(0.9 * k) * np.array([1, 2, 0.5]))
            out += [st.torque, st.torsion_stick_radius, st.dissipated_energy,
                    st2.tangential_force, st2.stick_radius, st2.dissipated_energy]
        return _numbers(*out)
    raise AssertionError(kind)


def workload():
    keys = []
    for name in ("paraboloid", "sphere", "cone+sphere", "table"):
        keys += [(name, "normal", F) for F in (0.5, 5.0, 50.0)]
        keys += [(name, "depth", 1e-6), (name, "torsion", 10.0), (name, "tangential", 10.0)]
    keys += [("paraboloid", "simulate", 10.0), ("table", "simulate", 10.0)]
    keys += [("adhesive", "normal", 1.0), ("adhesive", "pull_off", 0.0)]
    keys += [("paraboloid", "exact", 10.0), ("table", "exact", 10.0),
             ("paraboloid", "fretting_loop", 10.0), ("cone+sphere", "fretting_loop", 10.0),
             ("paraboloid", "wear", 10.0), ("paraboloid", "law", 10.0)]
    return keys


def run_keys(keys):
    contacts = make_contacts()
    return {k: task(contacts, k) for k in keys}


def test_same_call_same_bits_serial_threads_processes():
    keys = workload()
    fresh = {k: task(make_contacts(), k) for k in keys}          # each call on a new contact
    order = keys * 2
    random.Random(11).shuffle(order)
    warm = make_contacts()
    for k in order:                                               # warm, shuffled, repeated
        assert task(warm, k) == fresh[k], k
    shared = make_contacts()
    with ThreadPoolExecutor(4) as pool:                           # 4 threads, shared contacts
        got = list(pool.map(lambda k: (k, task(shared, k)), order))
    for k, v in got:
        assert v == fresh[k], k
    chunks = [order[i::2] for i in range(2)]
    with ProcessPoolExecutor(2) as pool:                          # processes, own warm contacts
        for part in pool.map(run_keys, chunks):
            for k, v in part.items():
                assert v == fresh[k], k


def _roundtrip(obj):
    copy = pickle.loads(pickle.dumps(obj))
    assert copy == obj and not (copy != obj)
    return copy


def test_results_pickle_and_compare_equal():
    c = make_contacts()["adhesive"]
    cyc = c.adhesion_cycle(depth=[1e-7, -1e-7, 0.0])
    _roundtrip(cyc)
    assert cyc != c.adhesion_cycle(depth=[1e-7, -2e-7, 0.0])
    from contactlab.materials.viscoelastic import StandardLinearSolid
    cv = cl.Contact(P.Paraboloid(R=0.01),
                    materials=(StandardLinearSolid(G_inf=1e6, G_1=1e6, eta_1=1e5), cl.Rigid()))
    t = np.linspace(0.0, 1.0, 20)
    vh = cv.viscoelastic_history(time=t, depth=1e-6 * np.minimum(t, 0.5), n_springs=100)
    _roundtrip(vh)
    from contactlab.scene import Scene
    scene = Scene.loads("""
[profile]
type = "paraboloid"
R = "10 mm"
[materials]
body1 = {type = "elastic", E = "210 GPa", nu = 0.3}
body2 = {type = "rigid"}
[[load_path]]
ramp = {force = "10 N", steps = 5}
""")
    res = scene.run()
    copy = _roundtrip(res)
    assert copy.series["force"].tobytes() == res.series["force"].tobytes()
    with pytest.raises(TypeError):
        hash(res)


def test_fretting_and_wear_results_pickle_and_compare_equal():
    c = cl.Contact(P.Paraboloid(R=0.01), materials=(STEEL, STEEL), friction=0.3)
    fm = c.fretting_map(force=[10.0, 20.0], displacement_amplitude=[1e-7, 1e-6])
    _roundtrip(fm)
    assert fm != c.fretting_map(force=[10.0, 21.0], displacement_amplitude=[1e-7, 1e-6])
    w = c.wear(force=10.0, displacement_amplitude=1e-6, wear_coefficient=1e-15, cycles=10.0,
               n_grid=100, max_radius=2e-4)
    _roundtrip(w)


def test_result_equality_is_one_shared_implementation():
    """Every array-holding result compares through params.FieldsEqual (a dataclass with eq=True
    would write its own tuple __eq__ over it, which raises on arrays)."""
    from contactlab.effects.adhesion import AdhesionCycle
    from contactlab.effects.fretting import FrettingMap
    from contactlab.effects.viscoelastic import ViscoelasticHistory
    from contactlab.effects.wear import WearResult
    from contactlab.params import FieldsEqual
    from contactlab.scene.run import SceneResult
    for cls in (AdhesionCycle, ViscoelasticHistory, FrettingMap, WearResult, SceneResult):
        assert cls.__eq__ is FieldsEqual.__eq__ and cls.__hash__ is None, cls
        assert not cls.__dataclass_params__.eq, cls
