"""No numerical failure on a valid table (issue 12): every finite, admissible table, linear or
cubic, 10 to 10^6 points, uniform or random spacing, runs every route at the default rtol.

The tables sample a convex profile ``f = r²/(2R) + c r⁴`` (admissible: r f' increasing) on
``0..2 mm``; the loads put the contact radius at ~10 % of the table (a 10-point table then holds
the whole contact inside its first segment, a 10^4-point one ~1000 nodes below it). Random
spacing draws the radii uniformly, so the closest nodes of a 10^4-point table lie ~1e-8 of the
radius apart. Each route is also checked against a second route or a bound where one is cheap;
the point of this file is that none of them raises :class:`~contactlab.errors.ConvergenceError`
(or any other error) and none returns a non-finite number.

Cost: 10 and 51 points, and 1000 points except the path simulations, run by default; the rest
is marked ``slow`` (CI's slow job; the exact ring solver on 10^3 and 10^4 points takes 0.5-2.3 s
since its ring pressures come from running sums over the table), except the 10^6-point tables,
which are marked ``exhaustive`` (run them with
``python -m pytest -m exhaustive tests/hard/test_table_audit.py``). The 10^6-point tables run the
routes whose cost stays linear in the table size per evaluation point (normal, tangential, shift
history, no-slip torsion, the spring foundation); the partial-slip torsion kernels (exact and
MDR) integrate over the rule nodes of every table segment below the contact radius (8 per
segment, each g costing O(N)), which is O(N²) and not run there. The spring foundation's
validity check on a twisted path takes a bounded rule on such tables
(``contactlab.physics.torsion_validity``), so ``simulate_mdr`` runs on 10^6 points (~1 min
each for linear and cubic on a loaded 2-core machine, mostly the tables' normal solve and
foundation build).
"""
from __future__ import annotations

import functools
import warnings

import numpy as np
import pytest

import contactlab as cl
from contactlab.errors import ValidityWarning
from contactlab.profiles import Paraboloid, Tabulated
from tests import tolerances as TOL

STEEL = cl.Elastic(E=210e9, nu=0.3)
R_MAX = 2e-3
F = 100.0
MU = 0.3

OPS = ("normal", "inverse_transform", "torsion_noslip", "torsion_exact", "torsion_mdr",
       "tangential", "twist_history_exact", "twist_history_mdr", "shift_history",
       "simulate_exact", "simulate_mdr")
#: routes whose cost per evaluation point stays O(N) (run on 10^6-point tables)
LINEAR_COST = ("normal", "torsion_noslip", "tangential", "shift_history", "simulate_mdr")


@functools.lru_cache(maxsize=4)
def _contact(kind: str, n: int, spacing: str) -> cl.Contact:
    if spacing == "uniform":
        r = np.linspace(0.0, R_MAX, n)
    else:
        r = R_MAX * np.sort(np.r_[0.0, np.random.default_rng(n).random(n - 2), 1.0])
    return cl.Contact(Tabulated(r, r**2 / 0.02 + 2.0 * r**4, kind), (STEEL, STEEL), friction=MU)


def _finite(*values) -> None:
    for v in values:
        assert np.all(np.isfinite(np.asarray(v, float))), v


def _path(c: cl.Contact, twist: bool, steps: int = 60) -> cl.LoadPath:
    a = c.normal(force=F).radius
    k = np.arange(1, steps + 1)
    if twist:
        amp = 3 * MU * F / (16 * c.moduli.torsional * a**2)
        key = "twist"
    else:
        amp = MU * F / (8 * c.moduli.tangential * a)
        key = "displacement"
    return cl.LoadPath().ramp(force=0.75 * F, steps=3).then(cl.loadpath.Table.create(
        None, {"force": F * (0.75 + 0.25 * np.sin(2 * np.pi * k / 37)),
               key: amp * np.sin(2 * np.pi * k / 25)}))


def _run(c: cl.Contact, op: str) -> None:
    st = c.normal(force=F)
    a, d = float(st.radius), float(st.depth)
    phi0 = 3 * MU * F / (16 * c.moduli.torsional * a**2)       # ~ full-sliding twist scale
    u0 = MU * F / (8 * c.moduli.tangential * a)
    hist = np.concatenate([np.linspace(0, 1, 12), np.linspace(1, -1, 12), np.linspace(-1, .5, 8)])
    if op == "normal":
        s = c.normal(force=np.array([1.0, F, 300.0]))
        _finite(s.radius, s.depth, s.elastic_energy)
        back = c.normal(depth=np.asarray(s.depth)).force
        np.testing.assert_allclose(back, [1.0, F, 300.0], rtol=TOL.TABLE_ROUND_TRIP)
    elif op == "inverse_transform":
        r = np.linspace(0.0, a, 9)[1:]
        f = c.profile.height(r)
        # a table too fine to split θ at its nodes is integrated to its own resolution (h/r)²,
        # h the largest node spacing below r
        gaps = np.maximum.accumulate(np.diff(c.profile.r))
        h = gaps[np.searchsorted(c.profile.r, r) - 1]
        fine = 0.0 if c.profile.breakpoints else (h / r) ** 2
        assert np.all(np.abs(c.profile.inverse_transform(r) - f)
                      <= (TOL.TABLE_INVERSE + fine) * np.abs(f))
    elif op == "torsion_noslip":
        s = c.torsion(force=F, twist=phi0 * np.array([0.01, 1.0]), method="no-slip")
        np.testing.assert_allclose(s.torque, 16 / 3 * c.moduli.torsional * a**3 * s.twist,
                                   rtol=TOL.CLOSED_FORM)
    elif op in ("torsion_exact", "torsion_mdr"):
        m = op.split("_")[1]
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", ValidityWarning)
            s = c.torsion(force=F, twist=phi0 * np.array([0.01, 0.5, 2.0, 20.0]), method=m)
            full = s.sliding_torque
            assert np.all(np.abs(s.torque) <= full * (1 + TOL.TORSION_EXACT))
            t = c.torsion(force=F, torque=0.5 * full[0], method=m)
            k = c.torsion(force=F, stick_radius=a * np.array([1e-3, 0.5, 0.99]), method=m)
        _finite(s.torque, s.stick_radius, t.twist, k.twist, k.torque)
    elif op == "tangential":
        s = c.tangential(force=F, displacement=u0 * np.array([0.01, 0.5, 2.0]))
        q = c.tangential(force=F, tangential_force=MU * F * np.array([0.01, 0.5, 0.99]))
        _finite(s.tangential_force, s.stick_radius, q.displacement)
        assert np.all(np.abs(s.tangential_force) <= MU * F * (1 + TOL.CLOSED_FORM))
    elif op.startswith("twist_history"):
        m = op.rsplit("_", 1)[1]
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", ValidityWarning)
            h = c.twist_history(force=F, twist=phi0 * hist, method=m)
        _finite(h.torque, h.dissipated_energy)
        assert np.all(np.diff(h.dissipated_energy) >= -1e-12 * np.max(h.dissipated_energy))
    elif op == "shift_history":
        h = c.shift_history(force=F, displacement=u0 * hist)
        _finite(h.tangential_force, h.dissipated_energy)
        assert np.all(np.abs(h.tangential_force) <= MU * F * (1 + TOL.CLOSED_FORM))
    elif op.startswith("simulate"):
        m = op.split("_")[1]
        with warnings.catch_warnings():      # the MDR springs warn beyond their validity twist
            warnings.simplefilter("ignore", ValidityWarning)
            res = c.simulate(_path(c, twist=True), method=m)
        _finite(res.torque, res.force, res.radius)
        if m == "mdr":
            res = c.simulate(_path(c, twist=False), method=m)
            _finite(res.tangential_force, res.force)
    else:                                                                  # pragma: no cover
        raise AssertionError(op)
    assert d > 0


def _cases():
    for kind in ("linear", "cubic"):
        for n in (10, 51, 1000, 10_000, 1_000_000):
            for spacing in ("uniform", "random"):
                for op in OPS:
                    if n == 1_000_000 and op not in LINEAR_COST:
                        continue
                    slow = n >= 10_000 or (n == 1000 and op.startswith("simulate"))
                    # 10^6 points: the exhaustive job, not CI
                    huge = n == 1_000_000
                    marks = ([pytest.mark.exhaustive] if huge else
                             [pytest.mark.slow] if slow else [])
                    yield pytest.param(kind, n, spacing, op, marks=marks,
                                       id=f"{kind}-{n}-{spacing}-{op}")


@pytest.mark.parametrize("kind, n, spacing, op", list(_cases()))
def test_valid_table_runs_every_route(kind, n, spacing, op):
    _run(_contact(kind, n, spacing), op)


def test_table_of_paraboloid_matches_paraboloid_on_every_route():
    """A second method for the routes above: a 1000-point linear table of a paraboloid against
    the paraboloid's closed forms (agreement to the table's resolution)."""
    r = np.linspace(0.0, R_MAX, 1000)
    tab = cl.Contact(Tabulated(r, r**2 / 0.02), (STEEL, STEEL), friction=MU)
    ana = cl.Contact(Paraboloid(R=0.01), (STEEL, STEEL), friction=MU)
    a = float(ana.normal(force=F).radius)
    phi = 3 * MU * F / (16 * ana.moduli.torsional * a**2) * np.array([0.05, 0.5, 2.0])
    for m in ("exact", "mdr"):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", ValidityWarning)
            st, sa = (x.torsion(force=F, twist=phi, method=m) for x in (tab, ana))
        np.testing.assert_allclose(st.torque, sa.torque, rtol=TOL.TORSION_TABLE_1000)
        np.testing.assert_allclose(st.sliding_torque, sa.sliding_torque,
                                   rtol=TOL.TORSION_TABLE_1000)
    u = MU * F / (8 * ana.moduli.tangential * a) * np.array([0.0, 1.0, -1.0, 0.3])
    ht, ha = (x.shift_history(force=F, displacement=u) for x in (tab, ana))
    np.testing.assert_allclose(ht.dissipated_energy[-1], ha.dissipated_energy[-1],
                               rtol=TOL.TABLE_1000_DISSIPATION)
    np.testing.assert_allclose(tab.normal(force=F).elastic_energy,
                               ana.normal(force=F).elastic_energy, rtol=TOL.TORSION_TABLE_1000)
