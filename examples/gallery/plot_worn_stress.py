"""
Subsurface stress in a worn profile
===================================

The steel ball of the wear example after 10⁶ fretting cycles (10 N, ±0.5 µm shift, Archard
wear): the worn profile is a measured-like table, and its stress field comes from the same
superposition of flat punches as any other profile. The von Mises stress at the tip of the
fretting cycle (normal load plus the Cattaneo–Mindlin shear), in the plane of the shift, for the
fresh ball (left) and the worn one (right). Partial-slip wear removes material in the slip
annulus and leaves the stick zone standing: the worn contact is wider, but its load gathers in
the centre, and the largest von Mises stress moves from the surface at the slip edge to the
surface near the axis (where the table's linear interpolation leaves a slight cone tip, whose
pressure is logarithmically singular on the axis).
"""
import matplotlib.pyplot as plt
import numpy as np

import contactlab as cl

steel = cl.Elastic(E=210e9, nu=0.3)
contact = cl.Contact(cl.profiles.Paraboloid(R=0.01), materials=(steel, steel), friction=0.5)
wear = contact.wear(force=10.0, displacement_amplitude=0.5e-6, wear_coefficient=1e-15,
                    cycles=1e6, checkpoints=2)
worn = cl.Contact(wear.profiles[-1], materials=(steel, steel), friction=0.5)

a0 = contact.normal(force=10.0).radius
a1 = worn.normal(force=10.0).radius
grid = (np.linspace(-1.5 * a1, 1.5 * a1, 121), np.linspace(0.0, 1.2 * a1, 50))
fresh = contact.tangential(force=10.0, displacement=0.5e-6).stress_field(grid)
shifted = worn.tangential(force=10.0, displacement=0.5e-6).stress_field(grid)

levels = np.linspace(0.0, max(np.nanmax(fresh.von_mises), np.nanmax(shifted.von_mises)), 31)
fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(10, 3.2), layout="constrained")
ax1.contourf(fresh.x, -fresh.z, fresh.von_mises, levels)
ax1.set_title(f"fresh, fretting tip (a = {a0 * 1e6:.0f} µm)")
cs = ax2.contourf(shifted.x, -shifted.z, shifted.von_mises, levels)
ax2.set_title(f"worn 10⁶ cycles, fretting tip (a = {a1 * 1e6:.0f} µm)")
fig.colorbar(cs, ax=(ax1, ax2), label="von Mises (Pa)")
for ax in (ax1, ax2):
    ax.set_xlabel("x (m)")
    ax.set_ylabel("-z (m)")
    ax.set_aspect("equal")
print(f"max von Mises at the fretting tip: fresh {np.nanmax(fresh.von_mises) / 1e6:.0f} MPa, "
      f"worn {np.nanmax(shifted.von_mises) / 1e6:.0f} MPa")
