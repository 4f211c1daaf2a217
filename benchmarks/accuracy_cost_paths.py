"""What accuracy costs in time: torsion, the MDR foundation and load paths (issue 7).

Run from the repository root::

    python benchmarks/accuracy_cost_paths.py           # full ladders (~ 1-2 min)
    python benchmarks/accuracy_cost_paths.py --quick   # short ladders

Knobs (``benchmarks/_harness.py``; error against an independent reference, wall time per
evaluation, best of several runs):

1. ``torsion rtol (exact)``: ``Contact(..., rtol=...)`` for the exact (Jäger) partial-slip model:
   torque under stick-radius control, stick radius under twist control, twist under torque
   control (the torque root solve), Hertz at c/a = 0.99, 0.5, 0.01 and flat punch at c/a = 0.5.
   References: mpmath, theory §6.3 (Lubkin closed forms) and §6.2.7 (flat punch).
2. ``foundation springs N``: ``contact.simulate(..., n_springs=N, method="mdr")`` against the MDR torsion
   closed form (§6.4, Masing §6.5) and Cattaneo-Mindlin (§5): torque at +φ1 and after reversal to
   -φ1, tangential force at 0.8 u*.
3. ``time steps (varying normal load)``: oblique loading by force ramp with u = κ(F - F0) (u not
   linear in depth): the only case where the step size matters (held normal load is advanced in
   closed form). Reference: spring picture min(G*(u(d) - u(s(x))), μE*(d - g(x))) integrated by
   scipy.quad (derived below).
4. ``10^3-cycle torsion history``: 0 → φ0 then 1000 cycles ±φ0. Energy dissipated in the 1000
   cycles against 1000 W(φ0) (§6.5, mpmath) and the final torque against M(φ0); exact
   ``twist_history`` (knob rtol), MDR ``twist_history`` (rtol) and ``simulate`` (knob N, MDR
   reference).

Torsion rows report ``TorsionState.error_estimate`` (torque) and ``error_estimates`` (twist,
stick radius; issue 7) in the "honest" column; ``TwistHistory`` and ``PathResult`` carry no
estimate, so the column is n/a for the other rows.

Writes ``benchmarks/results/accuracy_cost_paths.csv`` and Pareto plots
``benchmarks/results/pareto_paths_*.png`` (matplotlib optional).
"""
from __future__ import annotations

import argparse
import math
import sys
import time
import warnings
from pathlib import Path

import mpmath as mp
import numpy as np
from scipy.integrate import quad

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(Path(__file__).resolve().parent))

import contactlab as cl  # noqa: E402
from contactlab import LoadPath  # noqa: E402
from contactlab.errors import ValidityWarning  # noqa: E402
from contactlab.profiles import FlatPunch, Paraboloid  # noqa: E402
from _harness import Knob, machine, measure, pareto_plot, time_to_reach, write_csv  # noqa: E402
from tests.reference import torsion_reference as tr  # noqa: E402

RESULTS = Path(__file__).resolve().parent / "results"
MU = 0.3
R = 0.01
F_N = 10.0
STEEL = cl.Elastic(E=210e9, nu=0.3)
E_STAR = 1 / (2 * (1 - 0.09) / 210e9)                 # identical bodies, theory §1
G_T = 210e9 / 2.6 / 2
G_STAR = 1 / (2 * (2 - 0.3) / (4 * 210e9 / 2.6))
A_H = (3 * F_N * R / (4 * E_STAR)) ** (1 / 3)          # Hertz radius, §3
NAN = float("nan")


def hertz(rtol=None) -> cl.Contact:
    return cl.Contact(Paraboloid(R), materials=(STEEL, STEEL), friction=MU, rtol=rtol)


def hat_scale():
    """(φ scale, M scale): φ = φ̂ μF/(G_t a²), M = M̂ μFa (§6.3)."""
    return MU * F_N / (G_T * A_H**2), MU * F_N * A_H


# ----------------------------------------------------------------------------- 1. torsion rtol
def torsion_knobs(quick: bool) -> list[Knob]:
    ladder = [1e-2, 1e-4, 1e-6, 1e-8, 1e-10, 1e-12] if quick else \
        [1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12, 1e-13]
    ps, ms = hat_scale()
    knobs = []
    for t in (0.99, 0.5, 0.01):
        phi = float(tr.hertz_twist_hat(t)) * ps
        M = float(tr.hertz_torque_hat(t)) * ms
        case = f"Hertz, c/a = {t}"

        def run_M(rtol, t=t):
            s = hertz(rtol).torsion(force=F_N, stick_radius=t * A_H)
            return float(s.torque), float(s.error_estimate)

        def run_Mt(rtol, phi=phi):
            s = hertz(rtol).torsion(force=F_N, twist=phi)
            return float(s.torque), float(s.error_estimate)

        def run_c(rtol, phi=phi):
            s = hertz(rtol).torsion(force=F_N, twist=phi)
            return float(s.stick_radius), float(s.error_estimates["stick_radius"])

        def run_phi(rtol, M=M):
            s = hertz(rtol).torsion(force=F_N, torque=M)
            return float(s.twist), float(s.error_estimates["twist"])

        knobs += [Knob("torsion rtol (exact)", case, "torque", ladder, run_M, M),
                  Knob("torsion rtol (exact)", case, "torque (twist ctl)", ladder, run_Mt, M),
                  Knob("torsion rtol (exact)", case, "stick radius", ladder, run_c, t * A_H),
                  Knob("torque-control root (rtol)", case, "twist", ladder, run_phi, phi)]
    # flat punch (§6.2.7): φ = μE*d/(2πG_t a) K(k_c)
    b, d = 1e-3, 1e-6
    phi_f = float(tr.flat_twist(0.5, E_STAR, d, b, MU, G_T))

    def run_fc(rtol):
        c = cl.Contact(FlatPunch(b), materials=(STEEL, STEEL), friction=MU, rtol=rtol)
        s = c.torsion(depth=d, twist=phi_f)
        return float(s.stick_radius), float(s.error_estimates["stick_radius"])

    def run_fphi(rtol):
        c = cl.Contact(FlatPunch(b), materials=(STEEL, STEEL), friction=MU, rtol=rtol)
        s = c.torsion(depth=d, stick_radius=0.5 * b)
        return float(s.twist), float(s.error_estimates["twist"])

    knobs += [Knob("torsion rtol (exact)", "flat punch, c/a = 0.5", "stick radius", ladder,
                   run_fc, 0.5 * b),
              Knob("torsion rtol (exact)", "flat punch, c/a = 0.5", "twist", ladder, run_fphi,
                   phi_f)]
    return knobs


# ----------------------------------------------------------------------------- 2. foundation N
def mdr_torque(phi):
    """MDR virgin torque, Hertz (§6.4): β = 16G_t a²φ/(3μF), t = sqrt(1+β²/4) - β/2."""
    beta = 16 * G_T * A_H**2 * abs(phi) / (3 * MU * F_N)
    t = math.sqrt(1 + beta**2 / 4) - beta / 2
    return math.copysign(0.75 * MU * F_N * A_H * (1 - t * t) * (1 + t * t / 3), phi)


def foundation_knobs(quick: bool) -> list[Knob]:
    ladder = ([50, 200, 1000, 5000] if quick
              else [50, 100, 200, 500, 1000, 2000, 5000, 10000, 20000, 50000])
    ps, _ = hat_scale()
    phi1 = float(tr.hertz_mdr_hat(0.5)[0]) * ps
    c = hertz()
    tor_path = LoadPath().ramp(force=F_N, steps=2).ramp(twist=phi1, steps=20).ramp(
        twist=-phi1, steps=40)
    d_h = A_H**2 / R
    u_star = MU * E_STAR * d_h / G_STAR                   # §5: full sliding displacement
    tan_path = LoadPath().ramp(force=F_N, steps=2).ramp(displacement=0.8 * u_star, steps=20)
    M1 = mdr_torque(phi1)
    # Masing: M(-φ1) = M1 - 2 M(φ1) = -M1
    Fx = MU * F_N * (1 - (1 - 0.8) ** 1.5)                # CM, n = 2

    def run_tor(N, i):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", ValidityWarning)
            r = c.simulate(tor_path, n_springs=N, method="mdr")
        return float(r.torque[i]), NAN

    def run_tan(N):
        return float(c.simulate(tan_path, n_springs=N, method="mdr").tangential_force[-1]), NAN

    lab = (lambda s: str(s))
    return [Knob("foundation springs N", "Hertz torsion, virgin (c/a = 0.5)", "torque", ladder,
                 lambda N: run_tor(N, 21), M1, setting_label=lab),
            Knob("foundation springs N", "Hertz torsion, after reversal", "torque", ladder,
                 lambda N: run_tor(N, -1), -M1, setting_label=lab),
            Knob("foundation springs N", "Hertz Cattaneo-Mindlin, 0.8 u*", "tangential force",
                 ladder, run_tan, Fx, setting_label=lab)]


# ----------------------------------------------------------------------------- 3. time steps
def oblique_reference(F0, F1, kappa):
    """Tangential force after a force ramp F0 → F1 with u = κ(F - F0) (Hertz, monotone).

    Spring picture (§5 with the incremental rule of the foundation): the spring at x enters
    contact at depth s = max(d0, g(x)) with u(s); it carries G*(u(d) - u(s)) per unit length and
    side while that is below μE*(d - g(x)). h(d) = G*(u(d)-u(s)) - μE*(d-g) is convex in d
    (dF/dd = 2E*a grows), ≤ 0 at d = s, so a spring that slipped keeps slipping and
    F_x = 2∫_0^a min(G*(u(d) - u(s)), μE*(d - g(x))) dx.
    """
    def depth(F):
        return (3 * F / (4 * E_STAR * math.sqrt(R))) ** (2 / 3)          # F = (4/3)E*R^½d^{3/2}

    def force(d):
        return 4 / 3 * E_STAR * math.sqrt(R) * d**1.5

    d0, d1 = depth(F0), depth(F1)
    a1 = math.sqrt(R * d1)

    def line(x):
        g = x * x / R
        s = max(d0, g)
        stick = G_STAR * kappa * (F1 - force(s))
        return min(stick, MU * E_STAR * (d1 - g))

    a0 = math.sqrt(R * d0)
    v1, _ = quad(line, 0, a0, epsabs=0, epsrel=1e-13, limit=200)
    v2, _ = quad(line, a0, a1, epsabs=0, epsrel=1e-13, limit=400)
    return 2 * (v1 + v2)


def timestep_knobs(quick: bool) -> list[Knob]:
    ladder = [2, 5, 20, 100, 500] if quick else [2, 5, 10, 20, 50, 100, 200, 500, 1000, 2000]
    F0, F1 = 2.0, 10.0
    a_mid = (3 * 6.0 * R / (4 * E_STAR)) ** (1 / 3)
    kappa = MU / (2 * G_STAR * a_mid)       # slip starts where G*κ dF/dd = μE*: inside the ramp
    ref = oblique_reference(F0, F1, kappa)
    c = hertz()
    N = 5000

    def run(steps):
        F = np.linspace(F0, F1, steps + 1)
        path = LoadPath().ramp(force=F0, steps=2).then(
            cl.loadpath.Table.create(None, {"force": F[1:], "displacement": kappa * (F[1:] - F0)}))
        return float(c.simulate(path, n_springs=N, method="mdr").tangential_force[-1]), NAN

    return [Knob("time steps (varying normal load)", f"Hertz oblique force ramp, N = {N}",
                 "tangential force", ladder, run, ref, setting_label=str)]


# ----------------------------------------------------------------------------- 4. 10^3 cycles
CYCLES = 1000


def cycle_history(phi0, spc):
    th = np.linspace(0.0, 2 * np.pi, spc + 1)[1:]
    one = phi0 * np.cos(th)
    return np.concatenate([[0.0, phi0], np.tile(one, CYCLES)])


def mdr_loop_energy(phi0):
    """W = 8∫_0^{φ0} M dφ - 4φ0M0 (§6.5) with the MDR closed form (mpmath)."""
    integral = mp.quad(lambda p: mdr_torque(float(p)), [0, phi0])
    return float(8 * integral - 4 * phi0 * mdr_torque(phi0))


def history_knobs(quick: bool) -> list[Knob]:
    spc = 20
    ps, ms = hat_scale()
    t0 = 0.9
    phi0 = float(tr.hertz_twist_hat(t0)) * ps
    tw = cycle_history(phi0, spc)
    W_ex = float(tr.hertz_loop_energy_hat(t0)) * (MU * F_N) ** 2 / (G_T * A_H)
    M_ex = float(tr.hertz_torque_hat(t0)) * ms
    W_md = mdr_loop_energy(phi0)
    M_md = mdr_torque(phi0)
    ladder = [1e-3, 1e-6, 1e-8, 1e-10, 1e-12] if quick else \
        [1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12, 1e-13]

    def run_hist(rtol, method, what):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", ValidityWarning)
            h = hertz(rtol).twist_history(force=F_N, twist=tw, method=method)
            if what == "energy":
                return float(h.dissipated_energy[-1] - h.dissipated_energy[1]), NAN
        return float(h.torque[-1]), NAN

    n_ladder = ([50, 200, 1000, 5000] if quick
                else [50, 100, 200, 500, 1000, 2000, 5000, 10000, 20000])
    path = LoadPath().ramp(force=F_N, steps=2).then(
        cl.loadpath.Table.create(None, {"twist": tw[1:]}))

    def run_sim(N, what):
        r = hertz().simulate(path, n_springs=N, method="mdr")
        if what == "energy":
            return float(r.dissipated_energy[-1] - r.dissipated_energy[2]), NAN
        return float(r.torque[-1]), NAN

    lab = "10^3-cycle torsion history"
    case = f"Hertz ±φ0 (exact c0/a = {t0}), {spc} steps/cycle"
    return [
        Knob(lab + ": twist_history exact, rtol", case, "cycle energy", ladder,
             lambda s: run_hist(s, "exact", "energy"), CYCLES * W_ex),
        Knob(lab + ": twist_history exact, rtol", case, "final torque", ladder,
             lambda s: run_hist(s, "exact", "torque"), M_ex),
        Knob(lab + ": twist_history mdr, rtol", case, "cycle energy", ladder,
             lambda s: run_hist(s, "mdr", "energy"), CYCLES * W_md),
        Knob(lab + ": simulate (MDR), N", case, "cycle energy", n_ladder,
             lambda N: run_sim(N, "energy"), CYCLES * W_md, setting_label=str),
        Knob(lab + ": simulate (MDR), N", case, "final torque", n_ladder,
             lambda N: run_sim(N, "torque"), M_md, setting_label=str),
    ]


# ----------------------------------------------------------------------------- main
def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="short ladders")
    args = ap.parse_args(argv)
    t_start = time.perf_counter()
    print("Machine:", machine())
    min_total = 0.02 if args.quick else 0.05
    rows = measure(torsion_knobs(args.quick) + foundation_knobs(args.quick)
                   + timestep_knobs(args.quick) + history_knobs(args.quick), min_total=min_total)
    RESULTS.mkdir(parents=True, exist_ok=True)
    suffix = "_quick" if args.quick else ""
    print("\nwrote", write_csv(rows, RESULTS / f"accuracy_cost_paths{suffix}.csv"))
    for p in pareto_plot(rows, RESULTS, prefix=f"pareto_paths{suffix}"):
        print("wrote", p)
    print("\nTime to reach a relative error (s per evaluation; '-' = not reached on the ladder)")
    print(f"{'knob':52s} {'case':44s} {'quantity':16s} {'1e-3':>9s} {'1e-6':>9s} {'1e-9':>9s}")
    for (knob, case, q), tt in time_to_reach(rows).items():
        cells = " ".join(f"{v:9.3g}" if math.isfinite(v) else f"{'-':>9s}" for v in tt.values())
        print(f"{knob:52s} {case:44s} {q:16s} {cells}")
    print(f"\ntotal benchmark time {time.perf_counter() - t_start:.1f} s")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
