"""
Fretting loop and regime map
============================

A steel ball on a steel flat under an oscillating tangential displacement at constant normal load:
one steady loop (Masing's rule, exact) and the running-condition map over normal force and
amplitude, both drawn by the library's own ``plot()`` methods (theory §10).
"""
import matplotlib.pyplot as plt
import numpy as np

import contactlab as cl

steel = cl.Elastic(E=210e9, nu=0.3)
contact = cl.Contact(cl.profiles.Paraboloid(R=0.01), materials=(steel, steel), friction=0.5)

loop = contact.fretting_loop(force=100.0, displacement_amplitude=1.5e-6)
fretting_map = contact.fretting_map(force=np.linspace(20.0, 200.0, 12),
                                    displacement_amplitude=np.geomspace(1e-7, 2e-5, 16))

fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(9, 3.6), layout="constrained")
loop.plot(ax=ax1)
fretting_map.plot(ax=ax2)
print(loop.regime, f"A = {loop.energy_ratio:.3f}", loop.citations.tags)
