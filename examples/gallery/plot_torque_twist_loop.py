"""
Torque–twist loop and stick-radius evolution
============================================

A steel ball (R = 10 mm, 100 N) twisted back and forth at constant normal load: the exact
partial-slip solution with Masing's rule (theory §6.5). ``TwistHistory.plot`` draws the loop and
the radius of the zone that has not slipped since the last reversal, here in engineering units.
"""
import numpy as np

import contactlab as cl

steel = cl.Elastic(E=210e9, nu=0.3)
contact = cl.Contact(cl.profiles.Paraboloid(R=0.01), materials=(steel, steel), friction=0.3)

amp = 2e-3                                                     # twist amplitude, rad
twist = np.concatenate([np.linspace(0.0, amp, 40), np.linspace(amp, -amp, 80)[1:],
                        np.linspace(-amp, amp, 80)[1:]])
history = contact.twist_history(force=100.0, twist=twist, method="exact")
history.plot(units="engineering")
print(f"energy per cycle: {history.dissipated_energy[-1] - history.dissipated_energy[39]:.3g} J")
