"""
Subsurface stress: von Mises below a Hertz contact
==================================================

A steel ball (R = 10 mm) pressed on a steel flat with 100 N. ``state.stress_field()`` evaluates
the subsurface field on a grid (Huber's closed form for a paraboloid; the flat-punch
superposition for any other profile) and ``state.max_stress()`` finds the largest value: the
von Mises stress peaks on the axis about half a contact radius below the surface, not at it.
"""
import matplotlib.pyplot as plt

import contactlab as cl

steel = cl.Elastic(E=210e9, nu=0.3)
contact = cl.Contact(cl.profiles.Paraboloid(R=0.01), materials=(steel, steel))
state = contact.normal(force=100.0)
field = state.stress_field()
peak = state.max_stress("von_mises")

fig, ax = plt.subplots(figsize=(7, 3.6), layout="constrained")
field.plot("von_mises", ax=ax)
ax.plot(peak.r, -peak.z, "w+", markersize=12)
ax.set_title("von Mises stress below a Hertz contact (+: maximum)")
p0 = state.pressure(0.0)
print(f"max von Mises = {peak.value / p0:.4f} p0 at z = {peak.z / state.radius:.4f} a")
