"""Speed of contactlab.fit.indentation against scipy's curve_fit (ratios from one run).

* a 2000-point elastic fit of E and the contact point on a paraboloid, against
  ``scipy.optimize.curve_fit`` on the plain closed-form Hertz function with an analytic
  Jacobian (target: within 2x);
* the same curve on a measured (tabulated) sphere tip, table cached (target: <= 10 ms per fit);
* a JKR fit (E, contact point, work of adhesion) of 2000 points (target: <= 5 ms);
* DMT fits (E, contact point, work of adhesion) of 2000 points: a paraboloid and a cone;
* where nanite is installed (optional, never a dependency): its Hertz paraboloid fit (E,
  contact point, baseline) of the same 2000-point curve beside ours with the same parameters;
* a viscoelastic approach-retract fit (standard linear solid: G_inf, G_1, eta_1 and the contact
  point; Lee-Radok and Ting) of 2000 points (target: <= 35 ms), and the same with DMT
  adhesion (the work of adhesion free as well).

Run: ``python benchmarks/fit_speed.py``.
"""
from __future__ import annotations

import time
import warnings

import numpy as np


def _best(f, repeat: int = 5, number: int = 20) -> float:
    out = []
    for _ in range(repeat):
        t = time.perf_counter()
        for _ in range(number):
            f()
        out.append((time.perf_counter() - t) / number)
    return min(out)


def _nanite_line(z: np.ndarray, F: np.ndarray, R: float, nu: float, ours) -> None:
    """nanite's Hertz paraboloid fit (E, contact point and baseline, lmfit) of the same curve,
    beside ours with the same three parameters free; skipped when nanite is not installed
    (it is not a dependency)."""
    try:
        import nanite
        from nanite.fit import IndentationFitter
    except ImportError:
        print("nanite: not installed, comparison skipped (pip install nanite to add it)")
        return
    try:
        # nanite's tip position is negative into the sample; the fit is rebuilt each time
        # (nanite.Indentation.fit_model would return its cached result)
        data = {"force": F, "height (measured)": -z, "tip position": -z,
                "segment": np.zeros(z.size, dtype=bool), "time": np.linspace(0.0, 1.0, z.size)}
        meta = {"spring constant": 0.1, "sensitivity": 1e-8, "imaging mode": "force-distance",
                "duration": 1.0, "path": "synthetic", "enum": 0, "z range": float(np.ptp(z)),
                "speed approach": 1e-6, "speed retract": 1e-6, "point count": z.size,
                "rate approach": 2000.0, "rate retract": 2000.0}
        idnt = nanite.Indentation(data, meta)
        par = idnt.get_initial_fit_parameters(model_key="hertz_para")
        par["R"].set(value=R)
        par["nu"].set(value=nu)

        def nan_fit():
            f = IndentationFitter(idnt, model_key="hertz_para", params_initial=par,
                                  preprocessing=[])
            f.fit()
            return f

        e_nan = nan_fit().fp["params_fitted"]["E"].value
    except BaseException as err:        # an optional tool's API may change: say so, go on
        if isinstance(err, (KeyboardInterrupt, SystemExit)):   # (afmformats' metadata
            raise                                               # errors are BaseExceptions)
        print(f"nanite {getattr(nanite, '__version__', '?')}: comparison failed ({err!r})")
        return
    t_n, t_o = [], []
    for _ in range(3):                  # interleaved, best of each
        t_n.append(_best(nan_fit, repeat=1, number=10))
        t_o.append(_best(ours, repeat=1, number=10))
    print(f"paraboloid, 2000 points, E + contact point + offset: fit.indentation "
          f"{min(t_o) * 1e3:.2f} ms, nanite {nanite.__version__} hertz_para "
          f"{min(t_n) * 1e3:.2f} ms (its E {e_nan:.9g} Pa), ratio {min(t_o) / min(t_n):.2f}")


def main() -> None:
    # the synthetic adhesive curves are soft AFM samples: their Tabor warnings (outside the
    # DMT range) would repeat at every timed call; the fits' results are what is timed
    from contactlab.errors import ValidityWarning
    warnings.simplefilter("ignore", ValidityWarning)
    import os
    import platform

    from scipy.optimize import curve_fit
    print(f"machine: {platform.machine()}, {os.cpu_count()} CPUs, load average "
          f"{os.getloadavg()[0]:.1f}")

    from contactlab import Elastic, fit
    from contactlab.profiles import Paraboloid, Tabulated
    E, nu, R, z0 = 2e6, 0.5, 5e-6, 10e-9
    k = 1.0 - nu * nu
    z = np.linspace(-50e-9, 200e-9, 2000)
    d = np.maximum(z - z0, 0.0)
    F = 4.0 / 3.0 * E / k * np.sqrt(R) * d ** 1.5
    sample = Elastic(E=1e6, nu=nu)
    prof = Paraboloid(R=R)

    def hertz(x, e, c):
        dd = np.maximum(x - c, 0.0)
        return 4.0 / 3.0 * e / k * np.sqrt(R) * dd ** 1.5

    def hertz_jac(x, e, c):
        dd = np.maximum(x - c, 0.0)
        return np.stack([4.0 / 3.0 / k * np.sqrt(R) * dd ** 1.5, -2.0 * e / k * np.sqrt(R * dd)], 1)

    t_ours = _best(lambda: fit.indentation(z, F, prof, sample=sample))
    t_cf = _best(lambda: curve_fit(hertz, z, F, p0=(1e6, 0.0), jac=hertz_jac))
    print(f"paraboloid, 2000 points: fit.indentation {t_ours * 1e3:.2f} ms, curve_fit "
          f"{t_cf * 1e3:.2f} ms, ratio {t_ours / t_cf:.2f} (target <= 2)")
    _nanite_line(z, F, R, nu, lambda: fit.indentation(
        z, F, prof, sample=sample, free=("E", "contact_point", "force_offset")))
    r = np.linspace(0.0, 4e-6, 2001)
    tab = Tabulated(r, R - np.sqrt(R * R - r * r))
    t0 = time.perf_counter()
    fit.indentation(z, F, tab, sample=sample)
    print(f"tabulated sphere tip, first fit (builds the table): {(time.perf_counter() - t0) * 1e3:.0f} ms")
    t_tab = _best(lambda: fit.indentation(z, F, tab, sample=sample), repeat=3, number=5)
    print(f"tabulated sphere tip, later fits: {t_tab * 1e3:.2f} ms (target <= 10 ms)")
    w = 0.05                                    # JKR paraboloid, fixed grips, 2000 points
    es = E / k
    a_c = (np.pi * w * R * R / (8 * es)) ** (1 / 3)
    a = np.linspace(1.01 * a_c, 3e-6, 1700)
    dj = a * a / R - np.sqrt(2 * np.pi * a * w / es)
    Fj = 4 * es * a ** 3 / (3 * R) - np.sqrt(8 * np.pi * a ** 3 * es * w)
    before = np.linspace(dj[0] - 0.3 * (dj[-1] - dj[0]), dj[0], 300, endpoint=False)
    zj, Fj = np.concatenate([before, dj]) + z0, np.concatenate([np.zeros(300), Fj])
    t_jkr = _best(lambda: fit.indentation(zj, Fj, prof, sample=sample, adhesion="jkr",
                                          free=("E", "contact_point", "work_of_adhesion")),
                  repeat=3, number=5)
    print(f"JKR paraboloid, 2000 points: {t_jkr * 1e3:.2f} ms (target <= 5 ms)")
    Fd = F - 2.0 * np.pi * R * w * (z > z0)
    t_dmt = _best(lambda: fit.indentation(z, Fd, prof, sample=sample, adhesion="dmt",
                                          free=("E", "contact_point", "work_of_adhesion")),
                  repeat=3, number=5)
    print(f"DMT paraboloid, 2000 points: {t_dmt * 1e3:.2f} ms")
    from contactlab.profiles import Cone
    sl, wc = 0.3, 0.005                         # DMT cone: 2πΔγ a/s with a = 2δ/(π s)
    Fc = 2 / np.pi * E / k * d * d / sl - 2 * np.pi * wc * (2 * d / (np.pi * sl)) / sl
    t_dc = _best(lambda: fit.indentation(z, Fc, Cone(slope=sl), sample=sample, adhesion="dmt",
                                         free=("E", "contact_point", "work_of_adhesion")),
                 repeat=3, number=5)
    print(f"DMT cone (no step: candidate search for the start), 2000 points: "
          f"{t_dc * 1e3:.2f} ms")
    from contactlab.fit._ting import TingModel
    from contactlab.fit._tip import TipModel
    from contactlab.materials.viscoelastic import StandardLinearSolid
    v, tm = 1e-6, 0.5                           # a linear ramp in and out, 2000 samples
    t = np.concatenate([np.linspace(-0.1, tm, 1001), np.linspace(tm, 2 * tm, 1000)[1:]])
    zv = np.where(t <= tm, z0 + v * t, z0 + v * tm - v * (t - tm))
    Fv = TingModel(t, zv, TipModel(prof, 1e-6))(1e4, np.array([3e4]), np.array([0.4]), z0)[0]
    tmpl = StandardLinearSolid(G_inf=3e4, G_1=1e4, eta_1=1e4)
    t_ve = _best(lambda: fit.indentation(zv, Fv, prof, time=t, sample=tmpl), repeat=3, number=3)
    print(f"viscoelastic approach-retract (SLS), 2000 points: {t_ve * 1e3:.2f} ms "
          "(target <= 35 ms)")
    from contactlab.fit._dmt import DMTModel
    tipm = TipModel(prof, 1e-6)
    ting = TingModel(t, zv, tipm)
    Fa = ting(1e4, np.array([3e4]), np.array([0.4]), z0)[0]
    Fa = Fa - 2 * np.pi * 0.002 * DMTModel(prof, tipm)(ting.contact[0])[0]
    t_vd = _best(lambda: fit.indentation(zv, Fa, prof, time=t, sample=tmpl, adhesion="dmt",
                                         free=("G_inf", "G_1", "eta_1", "contact_point",
                                               "work_of_adhesion")), repeat=2, number=2)
    print(f"viscoelastic DMT approach-retract (SLS, paraboloid), 2000 points: "
          f"{t_vd * 1e3:.2f} ms")


if __name__ == "__main__":
    main()
