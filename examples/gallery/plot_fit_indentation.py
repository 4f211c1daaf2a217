"""
Fitting an indentation curve: the paraboloid's bias, the exact sphere
=====================================================================

A soft sample (E = 2 MPa, ν = 0.5) indented deeply by a sphere of radius 5 µm: the contact
radius reaches 0.6 R. The curve is made from Sneddon's exact sphere solution with noise, then
fitted twice with ``contactlab.fit.indentation``: with the Hertz paraboloid, whose residuals
show the wrong shape and whose modulus is biased, and with the exact ``Sphere``, whose
residuals are the noise and whose 95 % interval covers the truth.
"""
import matplotlib.pyplot as plt
import numpy as np

import contactlab as cl
from contactlab.profiles import Paraboloid, Sphere

R, E, z0 = 5e-6, 2e6, 40e-9
a = np.linspace(0.0, 0.6 * R, 600)
d = a / 2 * np.log((R + a) / (R - a))
F = E / 0.75 * ((a * a + R * R) / 2 * np.log((R + a) / (R - a)) - a * R)
depth = np.concatenate([np.linspace(-0.2 * d[-1], 0.0, 150, endpoint=False), d]) + z0
force = np.concatenate([np.zeros(150), F])
force += np.random.default_rng(7).normal(0.0, 0.002 * F[-1], force.size)
sample = cl.Elastic(E=1e6, nu=0.5)

fits = {name: cl.fit.indentation(depth, force, prof, sample=sample,
                                 free=("E", "contact_point", "force_offset"))
        for name, prof in (("paraboloid", Paraboloid(R=R)), ("sphere", Sphere(R=R)))}

fig, (ax1, ax2) = plt.subplots(2, 1, sharex=True, figsize=(6, 5), height_ratios=(3, 2),
                               layout="constrained")
ax1.plot(depth * 1e9, force * 1e6, ".", ms=2, color="0.6", label="data")
for name, res in fits.items():
    lo, hi = res.confidence(0.95)["E"]
    ax1.plot(depth * 1e9, res.model * 1e6,
             label=f"{name}: E = {res.params['E'] / 1e6:.4f} MPa [{lo / 1e6:.4f}, {hi / 1e6:.4f}]")
    ax2.plot(depth * 1e9, res.residuals * 1e6, ".", ms=2, label=name)
ax1.set_ylabel("force [µN]")
ax1.legend(fontsize=8)
ax2.set_xlabel("depth [nm]")
ax2.set_ylabel("residual [µN]")
ax2.legend(fontsize=8)
for name, res in fits.items():
    print(f"{name}: E = {res.params['E']:.6g} Pa (truth {E:.6g}), "
          f"contact point {res.params['contact_point'] * 1e9:.3f} nm (truth {z0 * 1e9:.1f})")
