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
widens; the energy error is not monotone, hence the running maximum, which also covers a history
whose loops reach every twist up to its largest). A power law between two mapped exponents takes
the larger error of both; a profile outside the mapped families (tables, sums, plugins) the
largest of all families (those with a wall included only for a profile with a wall). Measured
against the exact solution (tests/unit/effects/test_model_error.py) the map is never below the
actual error and within 1.4 times it for paraboloid and cone at 0.35 <= c/a <= 0.98; the
envelope of a table overstates the error up to ~4 times.
"""
from __future__ import annotations

import itertools
import math

import numpy as np

from .torsion_validity import twist_at_stick_ratio

__all__ = ["EXACT_STICK_RATIOS", "QUANTITIES", "family", "error_at_index", "ladder_index",
           "mdr_ratio_error", "law_spring_error", "LAW_SPRINGS"]

#: exact stick ratios ``c/a`` of the measured ladder (decreasing)
EXACT_STICK_RATIOS = np.array([
    0.999, 0.995, 0.99, 0.98, 0.97, 0.96, 0.95, 0.94, 0.92, 0.9, 0.88, 0.86, 0.85, 0.84, 0.83,
    0.82, 0.81, 0.8, 0.78, 0.75, 0.72, 0.7, 0.65, 0.6, 0.55, 0.5, 0.45, 0.4, 0.35, 0.3, 0.25,
    0.2, 0.15, 0.1, 0.07, 0.05, 0.03, 0.02, 0.01, 0.005, 0.001])
#: quantities mapped: torque at a given twist, energy dissipated under monotonic loading to a
#: given twist (hence per Masing cycle, and the worn volume of Archard wear)
QUANTITIES = ("torque", "energy")

#: relative error ``MDR/exact - 1`` of the torque at the same twist, per family, on the ladder
_TORQUE: dict[str, tuple[float, ...]] = {
    "paraboloid": (2.5008e-07, 6.2597e-06, 2.5078e-05, 0.00010062, 0.00022707, 0.00040489,
        0.00063449, 0.00091631, 0.0016382, 0.0025736, 0.0037254, 0.0050963, 0.0058646, 0.0066886,
        0.0075685, 0.0085045, 0.0094968, 0.010546, 0.012814, 0.016644, 0.020989, 0.024173,
        0.033135, 0.043512, 0.055271, 0.068361, 0.08271, 0.098225, 0.11479, 0.13229, 0.15058,
        0.16953, 0.18905, 0.20925, 0.22192, 0.23086, 0.24065, 0.24623, 0.25297, 0.25748, 0.26357),
    "cone": (2.5002e-07, 6.252e-06, 2.5016e-05, 0.00010013, 0.00022545, 0.00040109, 0.00062716,
        0.00090381, 0.0016094, 0.002519, 0.0036339, 0.0049556, 0.0056945, 0.0064856, 0.0073292,
        0.0082255, 0.0091748, 0.010177, 0.012342, 0.015995, 0.020138, 0.023177, 0.031759,
        0.041772, 0.053249, 0.06622, 0.080703, 0.096705, 0.11421, 0.13318, 0.15351, 0.17505,
        0.19758, 0.22076, 0.23484, 0.2443, 0.25391, 0.2589, 0.26426, 0.26735, 0.2707),
    "power_law_n4": (2.502e-07, 6.2753e-06, 2.5201e-05, 0.00010159, 0.00023033, 0.0004125,
        0.00064914, 0.00094122, 0.0016953, 0.002681, 0.0039036, 0.0053666, 0.006189, 0.0070723,
        0.0080164, 0.0090212, 0.010087, 0.011213, 0.013644, 0.017732, 0.022331, 0.025669,
        0.034901, 0.045279, 0.056651, 0.068883, 0.081882, 0.0956, 0.11004, 0.12527, 0.14137,
        0.15849, 0.17686, 0.19689, 0.21015, 0.21989, 0.23097, 0.23753, 0.2457, 0.25136, 0.2593),
    "power_law_n20": (2.512e-07, 6.3999e-06, 2.6194e-05, 0.00010943, 0.0002563, 0.00047255,
        0.00076271, 0.0011298, 0.0020969, 0.0033574, 0.0048654, 0.0065601, 0.0074598, 0.0083874,
        0.00934, 0.010316, 0.011316, 0.012342, 0.014483, 0.01797, 0.021875, 0.024745, 0.032914,
        0.042481, 0.053326, 0.065317, 0.078344, 0.092324, 0.10719, 0.12291, 0.13947, 0.15689,
        0.17532, 0.19518, 0.20825, 0.21787, 0.22889, 0.23547, 0.24377, 0.2496, 0.25793),
    "flat_punch": (3.7472e-07, 9.34e-06, 3.7222e-05, 0.0001478, 0.00033013, 0.00058271,
        0.00090407, 0.0012928, 0.002267, 0.0034951, 0.0049676, 0.0066756, 0.0076154, 0.0086111,
        0.0096617, 0.010766, 0.011924, 0.013134, 0.015708, 0.019941, 0.024603, 0.027941,
        0.037054, 0.047208, 0.058339, 0.070389, 0.083307, 0.097048, 0.11157, 0.12686, 0.14291,
        0.15976, 0.17757, 0.19678, 0.20945, 0.21878, 0.22952, 0.23594, 0.24407, 0.2498, 0.25802),
    "truncated_paraboloid": (2.5008e-07, 6.2595e-06, 2.5075e-05, 0.0001006, 0.00022701,
        0.00040474, 0.00063421, 0.0009158, 0.001637, 0.0025712, 0.0037212, 0.0050895, 0.0058563,
        0.0066785, 0.0075563, 0.0084899, 0.0094797, 0.010526, 0.012787, 0.016606, 0.020938,
        0.024114, 0.03306, 0.043462, 0.055397, 0.069309, 0.083601, 0.089769, 0.099419, 0.11277,
        0.13022, 0.14945, 0.17005, 0.19226, 0.20675, 0.21727, 0.22913, 0.23608, 0.24469, 0.25062,
        0.25888),
}
#: relative error ``MDR/exact - 1`` of the energy dissipated under monotonic loading to the
#: same twist (Jenkins-element form of both models), per family, on the ladder
_ENERGY: dict[str, tuple[float, ...]] = {
    "paraboloid": (-0.00024987, -0.0012467, -0.0024868, -0.0049466, -0.0073789, -0.009783,
        -0.012158, -0.014504, -0.019103, -0.023576, -0.027917, -0.03212, -0.034168, -0.03618,
        -0.038154, -0.04009, -0.041988, -0.043846, -0.04744, -0.052516, -0.057195, -0.060084,
        -0.066449, -0.071503, -0.07513, -0.077199, -0.077557, -0.076021, -0.072362, -0.066274,
        -0.05733, -0.044882, -0.027839, -0.004037, 0.015527, 0.032407, 0.055027, 0.070597,
        0.09308, 0.11137, 0.14267),
    "cone": (-0.00024974, -0.0012436, -0.0024744, -0.0048976, -0.0072697, -0.0095908, -0.011861,
        -0.01408, -0.018365, -0.022446, -0.026322, -0.029994, -0.031752, -0.033459, -0.035114,
        -0.036716, -0.038267, -0.039765, -0.042603, -0.046459, -0.049827, -0.051795, -0.055718,
        -0.058151, -0.058997, -0.058127, -0.055372, -0.050514, -0.043257, -0.0332, -0.019778,
        -0.0021435, 0.02108, 0.052474, 0.077521, 0.098535, 0.12567, 0.14355, 0.16799, 0.18651,
        0.21487),
    "power_law_n4": (-0.00025012, -0.0012529, -0.0025117, -0.0050458, -0.007601, -0.010176,
        -0.012769, -0.015378, -0.020639, -0.025944, -0.031277, -0.036622, -0.039292, -0.041959,
        -0.04462, -0.047272, -0.049912, -0.052539, -0.057743, -0.065386, -0.072776, -0.077532,
        -0.088697, -0.098632, -0.10713, -0.114, -0.11908, -0.12217, -0.12299, -0.12117, -0.11611,
        -0.1069, -0.092046, -0.068702, -0.048052, -0.0295, -0.0038405, 0.014245, 0.040871,
        0.062933, 0.10146),
    "power_law_n20": (-0.00025212, -0.0013037, -0.0027179, -0.0058946, -0.0095599, -0.013736,
        -0.018432, -0.023647, -0.035538, -0.049056, -0.063641, -0.078683, -0.086213, -0.093689,
        -0.10108, -0.10838, -0.11558, -0.12268, -0.13661, -0.15693, -0.17652, -0.18902, -0.2173,
        -0.23976, -0.25533, -0.26399, -0.26626, -0.26279, -0.2541, -0.24051, -0.22204, -0.19827,
        -0.16814, -0.12905, -0.098651, -0.073286, -0.04018, -0.01781, 0.014112, 0.039891,
        0.083899),
    "flat_punch": (-0.49979, -0.49896, -0.49791, -0.49579, -0.49366, -0.4915, -0.48933, -0.48713,
        -0.48267, -0.47811, -0.47347, -0.46872, -0.46631, -0.46388, -0.46142, -0.45893, -0.45642,
        -0.45388, -0.44871, -0.44074, -0.4325, -0.42684, -0.41209, -0.39641, -0.37967, -0.36176,
        -0.34249, -0.32167, -0.29901, -0.27416, -0.24657, -0.21542, -0.17931, -0.13538, -0.10254,
        -0.075706, -0.041239, -0.018214, 0.014363, 0.040485, 0.08479),
    "truncated_paraboloid": (-0.00024986, -0.0012466, -0.0024863, -0.0049448, -0.0073747,
        -0.0097753, -0.012146, -0.014486, -0.01907, -0.023522, -0.027836, -0.032005, -0.034032,
        -0.036021, -0.037971, -0.03988, -0.041747, -0.043572, -0.04709, -0.052024, -0.056519,
        -0.059254, -0.065091, -0.069287, -0.071392, -0.070094, -0.059524, -0.060045, -0.065248,
        -0.073385, -0.082641, -0.085764, -0.080331, -0.063769, -0.046078, -0.029085, -0.0046742,
        0.012909, 0.039137, 0.061072, 0.099647),
}
#: the MDR model's own stick ratio at the same twist, per family, on the ladder
_MDR_RATIO: dict[str, tuple[float, ...]] = {
    "paraboloid": (0.999, 0.99501, 0.99003, 0.9801, 0.97023, 0.9604, 0.95063, 0.94091, 0.92163,
        0.90256, 0.8837, 0.86505, 0.8558, 0.84661, 0.83748, 0.8284, 0.81937, 0.8104, 0.79261,
        0.76634, 0.74055, 0.72362, 0.68221, 0.64207, 0.60312, 0.56527, 0.52839, 0.49233, 0.45685,
        0.42169, 0.38644, 0.35049, 0.31283, 0.27149, 0.24305, 0.22106, 0.1942, 0.17702, 0.15364,
        0.13562, 0.10646),
    "cone": (0.999, 0.99501, 0.99002, 0.9801, 0.97022, 0.96039, 0.95061, 0.94088, 0.92155,
        0.9024, 0.88342, 0.86462, 0.85528, 0.84598, 0.83672, 0.8275, 0.81832, 0.80918, 0.79101,
        0.76403, 0.73736, 0.71975, 0.67625, 0.63345, 0.59126, 0.54958, 0.50829, 0.46724, 0.42625,
        0.38509, 0.34342, 0.30075, 0.25621, 0.2081, 0.17591, 0.15179, 0.12351, 0.10625, 0.084013,
        0.068028, 0.044696),
    "power_law_n4": (0.999, 0.99501, 0.99003, 0.9801, 0.97024, 0.96043, 0.95068, 0.94099,
        0.92181, 0.90291, 0.88431, 0.86603, 0.85701, 0.84808, 0.83924, 0.83048, 0.82182, 0.81326,
        0.79641, 0.77186, 0.74822, 0.73295, 0.69651, 0.66241, 0.63039, 0.6001, 0.57109, 0.54282,
        0.51471, 0.48608, 0.45611, 0.42378, 0.38758, 0.34484, 0.31365, 0.28864, 0.25714, 0.23649,
        0.20781, 0.18527, 0.14792),
    "power_law_n20": (0.999, 0.99501, 0.99003, 0.98013, 0.97033, 0.96065, 0.95115, 0.94187,
        0.92413, 0.90784, 0.89326, 0.88047, 0.8747, 0.8693, 0.86423, 0.85944, 0.85489, 0.85052,
        0.84217, 0.83007, 0.81787, 0.80944, 0.78688, 0.76203, 0.73515, 0.70665, 0.67677, 0.64559,
        0.61301, 0.57878, 0.54244, 0.50324, 0.45987, 0.40955, 0.37334, 0.3445, 0.30824, 0.28445,
        0.25127, 0.22501, 0.18107),
    "flat_punch": (0.9995, 0.9975, 0.99499, 0.98997, 0.98494, 0.9799, 0.97484, 0.96977, 0.95958,
        0.94934, 0.93904, 0.92868, 0.92348, 0.91826, 0.91302, 0.90777, 0.9025, 0.89721, 0.88658,
        0.87051, 0.85425, 0.84332, 0.81559, 0.78725, 0.75822, 0.7284, 0.69765, 0.6658, 0.63262,
        0.59777, 0.56076, 0.5208, 0.47652, 0.42504, 0.38792, 0.35829, 0.32098, 0.29645, 0.26217,
        0.23499, 0.18939),
    "truncated_paraboloid": (0.999, 0.99501, 0.99003, 0.9801, 0.97023, 0.9604, 0.95063, 0.94091,
        0.92163, 0.90255, 0.88368, 0.86502, 0.85577, 0.84657, 0.83743, 0.82834, 0.81929, 0.81031,
        0.79248, 0.76612, 0.7402, 0.72316, 0.68128, 0.6402, 0.59928, 0.55615, 0.50946, 0.49653,
        0.48352, 0.47217, 0.45129, 0.41577, 0.37678, 0.3321, 0.30036, 0.27537, 0.24435, 0.22425,
        0.19657, 0.17496, 0.13938),
}

#: torque error at full sliding (the MDR sliding torque is 4/pi times the exact one)
FULL_SLIDING_TORQUE_ERROR = 4.0 / math.pi - 1.0
_WALL = ("flat_punch",)
#: relative margin on the mapped errors: an extremum of the (non-monotone) energy error between
#: two ladder points, and the five digits kept, stay inside it (the ladder is dense where the
#: energy error turns: 0.05 apart in c/a; at 0.1 spacing a cone's peak at c/a ~ 0.55 exceeded
#: both neighbours by 1.5 %, at 0.05 spacing by less than 0.3 %)
MAP_SAFETY = 1.01
_TABLES = {"torque": _TORQUE, "energy": _ENERGY}


#: exponents of the mapped power-law families
_EXPONENTS = ((1.0, "cone"), (2.0, "paraboloid"), (4.0, "power_law_n4"),
              (20.0, "power_law_n20"))


def family(profile) -> list[str] | None:
    """The mapped families whose errors bound those of ``profile`` (keys of the maps): its own,
    or for a power law between two mapped exponents both neighbours (the errors grow with the
    exponent); None when not mapped (the envelope over all families is used)."""
    name = getattr(profile, "name", "")
    if name == "sphere":
        return ["paraboloid"]
    if name in ("paraboloid", "cone", "flat_punch", "truncated_paraboloid"):
        return [name]
    if name == "power_law":
        n = float(getattr(profile, "n", 0.0))
        if n <= 1.0:
            return ["cone"]
        if n >= 20.0:
            return ["power_law_n20"]
        for (lo, a), (hi, b) in itertools.pairwise(_EXPONENTS):
            if n == lo:
                return [a]
            if lo < n < hi:
                return [a, b]
    return None


def _columns(profile) -> list[str]:
    fam = family(profile)
    if fam is not None:
        return fam
    wall = math.isfinite(getattr(profile, "wall_radius", math.inf))
    return [k for k in _TORQUE if wall or k not in _WALL]


def _running_max(quantity: str, column: str) -> np.ndarray:
    """Largest error magnitude from c/a = 1 down to each ladder point, plus the value beyond the
    ladder (full sliding for the torque; the largest on the ladder for the energy)."""
    e = MAP_SAFETY * np.maximum.accumulate(np.abs(np.asarray(_TABLES[quantity][column], float)))
    tail = max(MAP_SAFETY * FULL_SLIDING_TORQUE_ERROR, e[-1]) if quantity == "torque" else e[-1]
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
        # the number of ladder ratios above each ratio, by one sorted search (a comparison
        # against the whole ladder per value cost a (n, 41) temporary and most of a contact
        # law's changing-load step)
        ladder = np.sort(np.asarray(_MDR_RATIO[c], float))
        k = ladder.size - np.searchsorted(ladder, ratio, side="right")
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
