"""Measured error maps of the approximate models: how far the MDR torsion springs are from the
exact (Jäger) solution, and how far the contact law's per-contact springs are from the full
foundation.

Every number here was measured, not derived: the torsion maps by the MDR model and the exact
model evaluated at the same twist on a ladder of exact stick ratios ``c/a`` (one contact of each
mapped profile family: paraboloid, cone, power laws ``n = 4`` and ``n = 20``, flat punch,
truncated paraboloid; steel on steel, mu = 0.3; the method of ``benchmarks/torsion_error_map.py``
and ``benchmarks/fretting_error_map.py``); the spring table by
``benchmarks/law_springs_accuracy.py`` (docs/dem.md). The relative error of the MDR model at a
given exact stick ratio is (nearly) independent of the load, the moduli and the friction
coefficient (self-similarity, docs/theory/11_self_similarity.md), so one contact per family maps
the family.

A result's ``model_error`` is looked up here **conservatively**: the exact stick ratio of a
state is bracketed between two ladder points, and the error taken is the largest magnitude on
the ladder from ``c/a = 1`` down to the lower bracket end (the error grows as the slip annulus
widens; the energy error is not monotone, hence the running maximum). A profile outside the
mapped families takes the largest error of all families (those with a wall included only for a
profile with a wall).
"""
from __future__ import annotations

import math

import numpy as np

from .torsion_validity import twist_at_stick_ratio

__all__ = ["EXACT_STICK_RATIOS", "QUANTITIES", "family", "error_at_index", "ladder_index",
           "mdr_ratio_error", "law_spring_error", "LAW_SPRINGS"]

#: exact stick ratios ``c/a`` of the measured ladder (decreasing)
EXACT_STICK_RATIOS = np.array([
    0.999, 0.995, 0.99, 0.98, 0.95, 0.92, 0.9, 0.88, 0.86, 0.85, 0.84, 0.83, 0.82, 0.81, 0.8, 0.75, 0.7, 0.6, 0.5, 0.4, 0.3, 0.2, 0.1, 0.05, 0.01, 0.001])
#: quantities mapped: torque at a given twist, energy dissipated under monotonic loading to a
#: given twist (hence per Masing cycle, and the worn volume of Archard wear)
QUANTITIES = ("torque", "energy")

#: relative error ``MDR/exact - 1`` of the torque at the same twist, per family, on the ladder
_TORQUE: dict[str, tuple[float, ...]] = {
    "paraboloid": (2.501e-07, 6.26e-06, 2.508e-05, 0.0001006, 0.0006345, 0.001638, 0.002574,
        0.003725, 0.005096, 0.005865, 0.006689, 0.007568, 0.008504, 0.009497, 0.01055, 0.01664,
        0.02417, 0.04351, 0.06836, 0.09822, 0.1323, 0.1695, 0.2092, 0.2309, 0.253, 0.2636),
    "cone": (2.5e-07, 6.252e-06, 2.502e-05, 0.0001001, 0.0006272, 0.001609, 0.002519, 0.003634,
        0.004956, 0.005694, 0.006486, 0.007329, 0.008226, 0.009175, 0.01018, 0.01599, 0.02318,
        0.04177, 0.06622, 0.09671, 0.1332, 0.1751, 0.2208, 0.2443, 0.2643, 0.2707),
    "power_law_n4": (2.502e-07, 6.275e-06, 2.52e-05, 0.0001016, 0.0006491, 0.001695, 0.002681,
        0.003904, 0.005367, 0.006189, 0.007072, 0.008016, 0.009021, 0.01009, 0.01121, 0.01773,
        0.02567, 0.04528, 0.06888, 0.0956, 0.1253, 0.1585, 0.1969, 0.2199, 0.2457, 0.2593),
    "power_law_n20": (2.512e-07, 6.4e-06, 2.619e-05, 0.0001094, 0.0007627, 0.002097, 0.003357,
        0.004865, 0.00656, 0.00746, 0.008387, 0.00934, 0.01032, 0.01132, 0.01234, 0.01797,
        0.02474, 0.04248, 0.06532, 0.09232, 0.1229, 0.1569, 0.1952, 0.2179, 0.2438, 0.2579),
    "flat_punch": (3.747e-07, 9.34e-06, 3.722e-05, 0.0001478, 0.0009041, 0.002267, 0.003495,
        0.004968, 0.006676, 0.007615, 0.008611, 0.009662, 0.01077, 0.01192, 0.01313, 0.01994,
        0.02794, 0.04721, 0.07039, 0.09705, 0.1269, 0.1598, 0.1968, 0.2188, 0.2441, 0.258),
    "truncated_paraboloid": (2.501e-07, 6.259e-06, 2.508e-05, 0.0001006, 0.0006342, 0.001637,
        0.002571, 0.003721, 0.00509, 0.005856, 0.006678, 0.007556, 0.00849, 0.00948, 0.01053,
        0.01661, 0.02411, 0.04346, 0.06931, 0.08977, 0.1128, 0.1494, 0.1923, 0.2173, 0.2447,
        0.2589),
}
#: relative error ``MDR/exact - 1`` of the energy dissipated under monotonic loading to the
#: same twist (Jenkins-element form of both models), per family, on the ladder
_ENERGY: dict[str, tuple[float, ...]] = {
    "paraboloid": (-0.0002499, -0.001247, -0.002487, -0.004947, -0.01216, -0.0191, -0.02358,
        -0.02792, -0.03212, -0.03417, -0.03618, -0.03815, -0.04009, -0.04199, -0.04385, -0.05252,
        -0.06008, -0.0715, -0.0772, -0.07602, -0.06627, -0.04488, -0.004037, 0.03241, 0.09308,
        0.1427),
    "cone": (-0.0002497, -0.001244, -0.002474, -0.004898, -0.01186, -0.01836, -0.02245, -0.02632,
        -0.02999, -0.03175, -0.03346, -0.03511, -0.03672, -0.03827, -0.03977, -0.04646, -0.0518,
        -0.05815, -0.05813, -0.05051, -0.0332, -0.002144, 0.05247, 0.09853, 0.168, 0.2149),
    "power_law_n4": (-0.0002501, -0.001253, -0.002512, -0.005046, -0.01277, -0.02064, -0.02594,
        -0.03128, -0.03662, -0.03929, -0.04196, -0.04462, -0.04727, -0.04991, -0.05254, -0.06539,
        -0.07753, -0.09863, -0.114, -0.1222, -0.1212, -0.1069, -0.0687, -0.0295, 0.04087, 0.1015),
    "power_law_n20": (-0.0002521, -0.001304, -0.002718, -0.005895, -0.01843, -0.03554, -0.04906,
        -0.06364, -0.07868, -0.08621, -0.09369, -0.1011, -0.1084, -0.1156, -0.1227, -0.1569,
        -0.189, -0.2398, -0.264, -0.2628, -0.2405, -0.1983, -0.1291, -0.07329, 0.01411, 0.0839),
    "flat_punch": (-0.4998, -0.499, -0.4979, -0.4958, -0.4893, -0.4827, -0.4781, -0.4735,
        -0.4687, -0.4663, -0.4639, -0.4614, -0.4589, -0.4564, -0.4539, -0.4407, -0.4268, -0.3964,
        -0.3618, -0.3217, -0.2742, -0.2154, -0.1354, -0.07571, 0.01436, 0.08479),
    "truncated_paraboloid": (-0.0002499, -0.001247, -0.002486, -0.004945, -0.01215, -0.01907,
        -0.02352, -0.02784, -0.032, -0.03403, -0.03602, -0.03797, -0.03988, -0.04175, -0.04357,
        -0.05202, -0.05925, -0.06929, -0.07009, -0.06004, -0.07339, -0.08576, -0.06377, -0.02909,
        0.03914, 0.09965),
}
#: the MDR model's own stick ratio at the same twist, per family, on the ladder
_MDR_RATIO: dict[str, tuple[float, ...]] = {
    "paraboloid": (0.999, 0.995, 0.99, 0.9801, 0.9506, 0.9216, 0.9026, 0.8837, 0.865, 0.8558,
        0.8466, 0.8375, 0.8284, 0.8194, 0.8104, 0.7663, 0.7236, 0.6421, 0.5653, 0.4923, 0.4217,
        0.3505, 0.2715, 0.2211, 0.1536, 0.1065),
    "cone": (0.999, 0.995, 0.99, 0.9801, 0.9506, 0.9215, 0.9024, 0.8834, 0.8646, 0.8553, 0.846,
        0.8367, 0.8275, 0.8183, 0.8092, 0.764, 0.7197, 0.6335, 0.5496, 0.4672, 0.3851, 0.3007,
        0.2081, 0.1518, 0.08401, 0.0447),
    "power_law_n4": (0.999, 0.995, 0.99, 0.9801, 0.9507, 0.9218, 0.9029, 0.8843, 0.866, 0.857,
        0.8481, 0.8392, 0.8305, 0.8218, 0.8133, 0.7719, 0.733, 0.6624, 0.6001, 0.5428, 0.4861,
        0.4238, 0.3448, 0.2886, 0.2078, 0.1479),
    "power_law_n20": (0.999, 0.995, 0.99, 0.9801, 0.9512, 0.9241, 0.9078, 0.8933, 0.8805, 0.8747,
        0.8693, 0.8642, 0.8594, 0.8549, 0.8505, 0.8301, 0.8094, 0.762, 0.7066, 0.6456, 0.5788,
        0.5032, 0.4096, 0.3445, 0.2513, 0.1811),
    "flat_punch": (0.9995, 0.9975, 0.995, 0.99, 0.9748, 0.9596, 0.9493, 0.939, 0.9287, 0.9235,
        0.9183, 0.913, 0.9078, 0.9025, 0.8972, 0.8705, 0.8433, 0.7872, 0.7284, 0.6658, 0.5978,
        0.5208, 0.425, 0.3583, 0.2622, 0.1894),
    "truncated_paraboloid": (0.999, 0.995, 0.99, 0.9801, 0.9506, 0.9216, 0.9025, 0.8837, 0.865,
        0.8558, 0.8466, 0.8374, 0.8283, 0.8193, 0.8103, 0.7661, 0.7232, 0.6402, 0.5562, 0.4965,
        0.4722, 0.4158, 0.3321, 0.2754, 0.1966, 0.1394),
}

#: torque error at full sliding (the MDR sliding torque is 4/pi times the exact one)
FULL_SLIDING_TORQUE_ERROR = 4.0 / math.pi - 1.0
_WALL = ("flat_punch",)
_TABLES = {"torque": _TORQUE, "energy": _ENERGY}


def family(profile) -> str | None:
    """The mapped family of ``profile`` (a key of the maps) or None (not mapped: the envelope
    over all families is used)."""
    name = getattr(profile, "name", "")
    if name in ("paraboloid", "sphere"):
        return "paraboloid"
    if name in ("cone", "flat_punch", "truncated_paraboloid"):
        return name
    if name == "power_law":
        n = float(getattr(profile, "n", 0.0))
        return ("cone" if n <= 1.5 else "paraboloid" if n <= 3.0 else
                "power_law_n4" if n <= 10.0 else "power_law_n20")
    return None


def _columns(profile) -> list[str]:
    fam = family(profile)
    if fam is not None:
        return [fam]
    wall = math.isfinite(getattr(profile, "wall_radius", math.inf))
    return [k for k in _TORQUE if wall or k not in _WALL]


def _running_max(quantity: str, column: str) -> np.ndarray:
    """Largest error magnitude from c/a = 1 down to each ladder point, plus the value beyond the
    ladder (full sliding for the torque; the largest on the ladder for the energy)."""
    e = np.maximum.accumulate(np.abs(np.asarray(_TABLES[quantity][column], float)))
    tail = max(FULL_SLIDING_TORQUE_ERROR, e[-1]) if quantity == "torque" else e[-1]
    return np.append(e, tail)


def error_at_index(profile, quantity: str, k: np.ndarray) -> np.ndarray:
    """Conservative relative error of ``quantity`` for states whose exact stick ratio lies above
    ladder point ``k`` (:func:`ladder_index`; ``k = len(EXACT_STICK_RATIOS)``: below the ladder)."""
    k = np.asarray(k, np.intp)
    return np.max([_running_max(quantity, c)[k] for c in _columns(profile)], axis=0)


def ladder_index(profile, E_star: float, G_t: float, mu: float, twist: np.ndarray,
                 a: np.ndarray, d: np.ndarray, g_a: np.ndarray, rtol: float) -> np.ndarray:
    """Index of the first ladder ratio at or below the exact stick ratio of each state (flat
    arrays: twist magnitude, rad, and normal state), i.e. the number of ladder twists below
    ``|twist|``: one slip function per ladder ratio and distinct normal state."""
    twist = np.abs(np.asarray(twist, float))
    lim = np.stack([twist_at_stick_ratio(profile, E_star, G_t, mu, r, a, d, g_a, rtol)
                    for r in EXACT_STICK_RATIOS])
    return np.sum(lim < twist[None, :], axis=0)


def mdr_ratio_error(profile, quantity: str, ratio: np.ndarray) -> np.ndarray:
    """Conservative relative error of ``quantity`` at the MDR model's own stick ratio
    ``ratio`` (c/a of the MDR springs, as a spring foundation reports it)."""
    ratio = np.asarray(ratio, float)
    out = np.zeros(ratio.shape)
    for c in _columns(profile):
        ladder = np.asarray(_MDR_RATIO[c], float)
        k = np.sum(ladder > ratio[..., None], axis=-1)
        out = np.maximum(out, _running_max(quantity, c)[k])
    return np.where(ratio >= 1.0, 0.0, out)


#: springs per contact of the contact law's spring table and the largest relative error measured
#: there against the 2000-spring foundation (torque, its dissipation, tangential force, its
#: dissipation: the largest of the four; docs/dem.md)
LAW_SPRINGS = np.array([8.0, 16.0, 32.0, 64.0])
_LAW_SPRING_ERROR = np.array([5.2e-2, 1.0e-2, 3.8e-3, 1.1e-3])


def law_spring_error(springs: int) -> float:
    """Measured spring-discretisation error of the contact law at ``springs`` springs per
    contact (log-log interpolation in the table; beyond it the measured ``1/N²`` fall-off)."""
    n = float(springs)
    if n <= 0:
        return 0.0
    if n < LAW_SPRINGS[0]:
        return float(_LAW_SPRING_ERROR[0] * (LAW_SPRINGS[0] / n) ** 2)
    if n > LAW_SPRINGS[-1]:
        return float(_LAW_SPRING_ERROR[-1] * (LAW_SPRINGS[-1] / n) ** 2)
    return float(np.exp(np.interp(np.log(n), np.log(LAW_SPRINGS), np.log(_LAW_SPRING_ERROR))))
