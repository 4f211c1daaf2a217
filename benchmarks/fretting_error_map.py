"""MDR torsion model against the exact solution on every fretting quantity (issue 15).

For each profile, the exact stick ratio c/a at which the MDR torque, energy per cycle and stick
radius (same twist amplitude) first err by more than 1 %. Run: python benchmarks/fretting_error_map.py
"""
import numpy as np, contactlab as cl, warnings
from contactlab.effects.torsion import torsion_model
from contactlab.errors import ValidityWarning
warnings.simplefilter("ignore", ValidityWarning)
steel = cl.Elastic(E=210e9, nu=0.3)
P = cl.profiles
profs = {"paraboloid": P.Paraboloid(R=0.01), "cone": P.Cone(slope=0.05), "n4": P.PowerLaw(c=1e8, n=4),
         "n20": P.PowerLaw(c=1e40, n=20), "flat": P.FlatPunch(radius=1e-4),
         "trpar": P.TruncatedParaboloid(radius=5e-5, R=0.01)}
for name, pr in profs.items():
    c = cl.Contact(pr, materials=(steel, steel), friction=0.3)
    n = c.normal(depth=1e-6) if name != "flat" else c.normal(depth=1e-7)
    a, d = float(n._radius), float(n._depth)
    ga = min(float(pr._g(np.array(a))), d)
    ex, md = torsion_model(c, "exact"), torsion_model(c, "mdr")
    ratio = np.linspace(0.995, 0.3, 300)
    A = np.full(ratio.size, a); D = np.full(ratio.size, d); GA = np.full(ratio.size, ga)
    se = ex.of_stick_radius(ratio*a, A, D, GA)
    phi = se.twist
    Wex = ex.dissipation(phi, se.stick_radius, A, D, GA)
    sm = md.of_twist(phi, A, D, GA)
    Wm = md.dissipation(phi, sm.stick_radius, A, D, GA)
    eW = Wm/Wex - 1; eM = sm.torque/se.torque - 1; ec = sm.stick_radius/se.stick_radius - 1
    def cross(e):
        i = np.argmax(np.abs(e) > 0.01); return ratio[i]
    print(name, "torque", cross(eM), "energy", cross(eW), "stick", cross(ec), "eW@0.9", np.interp(0.9, ratio[::-1], eW[::-1]))
