"""
Hertz contact: force, radius and pressure
=========================================

A steel ball (R = 10 mm) pressed on a steel flat. The MDR gives the exact Hertz solution; the
pressure field comes from the same state object.
"""
import matplotlib.pyplot as plt
import numpy as np

import contactlab as cl

steel = cl.Elastic(E=210e9, nu=0.3)
contact = cl.Contact(cl.profiles.Paraboloid(R=0.01), materials=(steel, steel))
s = contact.normal(force=np.linspace(0.0, 100.0, 101))

fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(8, 3.2), layout="constrained")
ax1.plot(s.depth * 1e6, s.force)
ax1.set_xlabel("depth [µm]")
ax1.set_ylabel("force [N]")
last = contact.normal(force=100.0)
r = np.linspace(0, 1.5 * last.radius, 200)
ax2.plot(r * 1e6, last.pressure(r) / 1e9)
ax2.set_xlabel("radius [µm]")
ax2.set_ylabel("pressure [GPa]")
print(f"a = {last.radius * 1e6:.2f} µm, p0 = {last.pressure(0.0) / 1e9:.3f} GPa")
