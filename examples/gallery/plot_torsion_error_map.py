"""
MDR versus exact torsion: the error map
=======================================

The MDR narrow-slip model (``method="mdr"``) against Jäger's exact partial-slip solution
(``method="exact"``) for a Hertz contact, at the same twist. The ratios are dimensionless and hold
for every Hertz contact (theory §6.4, §11). The model is excellent while the slip annulus is thin
and overestimates the torque by up to 4/π at full sliding.
"""
import warnings

import matplotlib.pyplot as plt
import numpy as np

import contactlab as cl
from contactlab.errors import ValidityWarning

steel = cl.Elastic(E=210e9, nu=0.3)
contact = cl.Contact(cl.profiles.Paraboloid(R=0.01), materials=(steel, steel), friction=0.3)
a = contact.normal(force=100.0).radius

ratio = np.linspace(0.02, 0.999, 120)                         # exact stick ratio c/a
exact = contact.torsion(force=100.0, stick_radius=ratio * a, method="exact")
with warnings.catch_warnings():
    warnings.simplefilter("ignore", ValidityWarning)          # the model warns above 1 % error
    mdr = contact.torsion(force=100.0, twist=exact.twist, method="mdr")

fig, ax = plt.subplots(figsize=(6, 3.6), layout="constrained")
ax.semilogy(ratio, np.abs(mdr.torque / exact.torque - 1) * 100, label="torque at the same twist")
ax.semilogy(ratio, np.abs(mdr.stick_radius / a - ratio) * 100, "--", label="stick ratio c/a (abs.)")
ax.axhline(1.0, color="0.5", lw=0.8)
ax.text(0.03, 1.15, "1 %: ValidityWarning", color="0.4", fontsize=8)
ax.set_xlabel("exact stick ratio c/a")
ax.set_ylabel("MDR error [%]")
ax.set_title("MDR torsion model vs exact (Hertz)")
ax.legend(loc="lower left")
print(f"at c/a = 0.9: {100 * (np.interp(0.9, ratio, mdr.torque / exact.torque) - 1):.2f} % torque error")
