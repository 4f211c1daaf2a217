"""Recipe of the hip-cup study's data files (run: python examples/hip_cup/make_data.py).

hip_cup_profile.csv: the gap between a femoral head and a worn cup as a profilometer would give
it: 200 radii 0..10 mm, height f(r) = r²/(2R) + c r⁴ with R = 100 mm (the conformal pair's
effective radius) and c = 2 m⁻³ (wear), plus 50 nm of Gaussian measurement noise (seed 2024);
columns r [mm], f [um].

gait.csv: one gait cycle of 1 s in 50 steps: force 0.3-3 kN (double hump of a walking cycle),
internal/external rotation ±0.02 deg; columns time [ms], force [kN], twist [deg]. The first row
is at t = 0, the step after the previous segment.
"""
from pathlib import Path

import numpy as np

HERE = Path(__file__).parent


def profile() -> tuple[np.ndarray, np.ndarray]:
    r = np.linspace(0.0, 10e-3, 200)
    f = r**2 / (2 * 0.1) + 2.0 * r**4
    return r, f + 50e-9 * np.random.default_rng(2024).standard_normal(r.size)


def gait() -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    t = np.arange(50) / 50
    force = 300.0 + 2700.0 * np.clip(np.sin(2 * np.pi * t) ** 2 * (t < 0.6)
                                     , 0.0, 1.0)
    twist = np.radians(0.02) * np.sin(2 * np.pi * t)
    return t, force, twist


if __name__ == "__main__":
    r, f = profile()
    with open(HERE / "hip_cup_profile.csv", "w") as fh:
        fh.write("# worn hip cup, 50 nm noise; recipe: make_data.py\nr [mm],f [um]\n")
        fh.writelines(f"{float(a) * 1e3!r},{float(b) * 1e6!r}\n" for a, b in zip(r, f))
    t, force, twist = gait()
    with open(HERE / "gait.csv", "w") as fh:
        fh.write("# one gait cycle; recipe: make_data.py\ntime [ms],force [kN],twist [deg]\n")
        fh.writelines(f"{float(a) * 1e3!r},{float(b) / 1e3!r},{float(np.degrees(c))!r}\n"
                      for a, b, c in zip(t, force, twist))
