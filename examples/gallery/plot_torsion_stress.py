"""
Subsurface stress under torsional partial slip
==============================================

The steel ball of the Hertz example, pressed with 100 N and twisted (μ = 0.3) until the stick
zone has shrunk to about half the contact radius (Jäger's exact partial-slip solution). The
torsional shear ``σ_θz`` (left) vanishes on the axis and peaks at the surface inside the slip
annulus. Added to the normal field (right) it raises the von Mises stress near the surface;
at this twist the maximum (``+``) is still the Hertz one on the axis, where σ_θz is zero.
"""
import matplotlib.pyplot as plt
import numpy as np

import contactlab as cl

steel = cl.Elastic(E=210e9, nu=0.3)
contact = cl.Contact(cl.profiles.Paraboloid(R=0.01), materials=(steel, steel), friction=0.3)
a = contact.normal(force=100.0).radius
state = contact.torsion(force=100.0, stick_radius=0.5 * a)
grid = (np.linspace(0.0, 2 * a, 120), np.linspace(0.0, 1.2 * a, 60))
friction = state.stress_field(grid, part="friction")
total = state.stress_field(grid)
peak = state.max_stress("von_mises")

fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(10, 3.4), layout="constrained")
friction.plot("stz", ax=ax1)
ax1.set_title("torsional shear σ_θz")
total.plot("von_mises", ax=ax2)
ax2.plot(peak.r, -peak.z, "w+", markersize=12)
ax2.set_title("von Mises, normal load + twist")
print(f"c/a = {state.stick_radius / a:.2f}; max von Mises {peak.value / 1e9:.3f} GPa at "
      f"r = {peak.r / a:.3f} a, z = {peak.z / a:.3f} a")
