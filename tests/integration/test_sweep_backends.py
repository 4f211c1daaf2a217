"""The same sweep serially, in a local process pool and on a real Dask LocalCluster (2 worker
processes started here): bit-identical tables, failures and warnings included. Not marked slow
(about 15 s together): these are the guarantees the sweep issue must show in every CI run."""
from __future__ import annotations

import numpy as np
import pytest

pd = pytest.importorskip("pandas")

import contactlab
from contactlab.scene import Scene

from tests.unit.scene.helpers import twist_scene

#: torsional loops: preload, then two twist cycles; exact and MDR torsion models
LOOPS = twist_scene({"sinusoid": {"twist": "1 mrad", "cycles": 2, "steps_per_cycle": 40}},
                    outputs={"method": "exact",
                             "series": ["twist", "torque", "stick_radius", "dissipated_energy"]})
GRID = {"interface.friction": [0.1, -0.2, 0.3],                 # -0.2: recorded as an error
        "load_path[1].sinusoid.twist": [2e-4, 3e-3],
        "outputs.method": ["exact", "mdr"]}                   # mdr at 3 mrad: a ValidityWarning


def loop_energy(amplitude, friction):
    """A function study: dissipated energy of one torsional loop per unit friction."""
    contact = contactlab.Contact(contactlab.profiles.Paraboloid(R=0.01),
                                 materials=(contactlab.Elastic(E=210e9, nu=0.3),) * 2,
                                 friction=friction)
    twist = amplitude * np.sin(np.linspace(0.0, 2 * np.pi, 41))
    h = contact.twist_history(twist=twist, force=100.0, method="exact")
    return {"energy_per_mu": h.dissipated_energy[-1] / friction, "torque": h.torque}


FUNCTION_GRID = {"amplitude": [1e-4, 5e-4, 2e-3], "friction": [0.1, 0.25, 0.0]}


def _same(a, b):
    pd.testing.assert_frame_equal(a, b, check_exact=True)
    for col in a.columns:                                      # floats bit for bit (NaN too)
        if a[col].dtype == float:
            assert a[col].to_numpy().tobytes() == b[col].to_numpy().tobytes(), col


@pytest.fixture(scope="module")
def serial():
    return (contactlab.sweep(Scene(LOOPS), GRID, workers=1),
            contactlab.sweep(loop_energy, FUNCTION_GRID, workers=1))


def test_serial_table_has_failures_and_warnings(serial):
    scene, func = serial
    assert (scene["error"] == "SceneError").sum() == 4 and scene["error"].notna().sum() == 4
    warned = scene["warnings"].notna()
    assert warned.any() and scene.loc[warned, "outputs.method"].eq("mdr").all()
    assert all("ValidityWarning" in w for w in scene.loc[warned, "warnings"])
    assert func["error"].tolist().count("ParameterError") == 3          # friction 0: invalid


def _ran_on(table, backend):
    assert table.attrs["sweep"]["stats"]["backend"] == backend
    return table


def test_local_process_pool_is_bit_identical(serial):
    _same(_ran_on(contactlab.sweep(Scene(LOOPS), GRID, workers=2, batch_size=2), "Pool"),
          serial[0])
    _same(_ran_on(contactlab.sweep(loop_energy, FUNCTION_GRID, workers=2, batch_size=1), "Pool"),
          serial[1])


@pytest.fixture(scope="module")
def dask_client():
    """A real LocalCluster of 2 worker processes (one thread each), no dashboard."""
    distributed = pytest.importorskip("distributed")
    import dask
    # bounded, but generous: on a loaded shared 2-core machine two worker processes importing
    # dask and contactlab can take a minute to come up
    with dask.config.set({"distributed.comm.timeouts.connect": "300s"}), \
            distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                     dashboard_address=None, death_timeout=300) as cluster, \
            distributed.Client(cluster, timeout="300s") as client:
        assert len(client.scheduler_info(n_workers=-1)["workers"]) == 2
        yield client


def test_dask_local_cluster_is_bit_identical(serial, dask_client):
    _same(_ran_on(contactlab.sweep(Scene(LOOPS), GRID, client=dask_client, batch_size=3),
                  "DaskClient"), serial[0])
    _same(_ran_on(contactlab.sweep(loop_energy, FUNCTION_GRID, client=dask_client, batch_size=2),
                  "DaskClient"), serial[1])


def tiny(x):
    return {"y": 2.0 * x}


def test_a_sweep_smaller_than_a_round_trip_stays_here(dask_client, monkeypatch):
    """Less work left after the timing points than one round trip to the cluster: the cheapest
    plan is to finish here (the table is the same wherever points run). The cluster's round trip
    is measured (positive); the plan is then made against a round trip of a minute, so that a
    pause of this process while it times the points cannot decide it (late in a long test run a
    pause, likely a garbage collection, once made the microseconds of work look longer than
    the measured round trip)."""
    from contactlab.sweeps import backends
    assert backends.DaskClient(tiny, dask_client).roundtrip() > 0
    monkeypatch.setattr(backends.DaskClient, "roundtrip", lambda self: 60.0)
    table = contactlab.sweep(tiny, {"x": [float(i) for i in range(40)]}, client=dask_client)
    stats = table.attrs["sweep"]["stats"]
    assert stats["backend"] == "Serial" and stats["roundtrip_seconds"] == 60.0
    assert table["y"].tolist() == [2.0 * i for i in range(40)]


def test_progress_bar_on_a_dask_cluster(serial, dask_client, capsys, monkeypatch):
    pytest.importorskip("tqdm")
    monkeypatch.setattr("contactlab.sweeps.run.PROGRESS_SECONDS", 0.0)   # always show the bar
    table = contactlab.sweep(loop_energy, FUNCTION_GRID, client=dask_client, batch_size=2,
                             progress=True)
    _same(table, serial[1])
    err = capsys.readouterr().err
    assert "sweep" in err and "9/9" in err           # fed by the tasks as they completed


def test_fretting_map_on_a_dask_cluster_is_the_local_map(dask_client, monkeypatch, capsys):
    from contactlab.effects import fretting as fr
    monkeypatch.setattr(fr, "MAP_BLOCK", 10)              # several blocks of each kind
    monkeypatch.setattr(fr, "BOUNDARY_BLOCK", 2)
    monkeypatch.setattr("contactlab.sweeps.run.PROGRESS_SECONDS", 0.0)
    contact = contactlab.Contact(contactlab.profiles.Paraboloid(R=0.01),
                                 materials=(contactlab.Elastic(E=210e9, nu=0.3),) * 2,
                                 friction=0.3)
    kw = dict(force=np.geomspace(1.0, 1000.0, 7), twist_amplitude=np.geomspace(1e-5, 1e-2, 11),
              method="exact")
    local = contact.fretting_map(**kw)
    swept = contactlab.fretting_map_sweep(contact, **kw, client=dask_client, progress=True)
    assert swept == local
    for f in ("regime", "energy_ratio", "energy", "stick_ratio", "peak", "boundary"):
        assert getattr(swept, f).tobytes() == getattr(local, f).tobytes(), f
    assert "12/12" in capsys.readouterr().err           # 8 map blocks + 4 boundary blocks


def test_a_sweep_on_a_client_that_is_not_dasks_default(serial, dask_client, monkeypatch):
    """With two clients in one process, Dask's as_completed follows the *default* (latest)
    client's event loop unless told otherwise; the sweep tracks its futures on its own client's
    loop (a second thread driving this client's connections broke tornado's write buffers and
    hung the benchmark)."""
    import distributed
    from contactlab.sweeps import backends
    loops = []

    def spy(futures, **kw):
        loops.append(kw.get("loop"))
        return distributed.as_completed(futures, **kw)

    with distributed.Client(n_workers=1, threads_per_worker=1, processes=False,
                            dashboard_address=":0"):
        assert distributed.client.default_client() is not dask_client
        real_init = backends.DaskClient.__init__

        def init(self, *a, **k):
            real_init(self, *a, **k)
            self._as_completed = spy

        monkeypatch.setattr(backends.DaskClient, "__init__", init)
        table = contactlab.sweep(loop_energy, FUNCTION_GRID, client=dask_client, batch_size=2)
    _same(_ran_on(table, "DaskClient"), serial[1])
    assert loops == [dask_client.loop]
