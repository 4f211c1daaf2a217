"""
Worn-profile evolution under fretting
=====================================

Archard wear of a steel ball on a flat under a small tangential oscillation at constant normal
load (theory §10): the profile at a few checkpoints, the contact and scar radii, and the worn
volume, as drawn by ``WearResult.plot`` in engineering units.
"""
import contactlab as cl

steel = cl.Elastic(E=210e9, nu=0.3)
contact = cl.Contact(cl.profiles.Paraboloid(R=0.01), materials=(steel, steel), friction=0.5)

wear = contact.wear(force=10.0, displacement_amplitude=0.5e-6, wear_coefficient=1e-15,
                    cycles=1e6, checkpoints=4)
wear.plot(units="engineering")
print(f"worn volume after 1e6 cycles: {wear.volume[-1]:.3g} m^3")
