"""The contact penalty of a gap: the plane's (solver.cohesive, solver.snap) and the cavity
lid's (solver.lid).  Units of the caller (gaps and onset in R, stiffness in C10 / R)."""
import numpy as np

CONTACT_STIFFNESS = 1e4     # C10 / R: the sharp contact's penalty slope (snap, the lid)
CONTACT_ONSET = 1e-4        # R: the penetration over which its slope rises from 0
#                             (snap.SnapSettings.onset says why this depth)


def penalty(g, k: float, e: float):
    """(energy, stress, slope) of a contact penalty on the gap g (< 0: penetration): slope
    k beyond -e, rising linearly from 0 at g = 0 over -e < g < 0 (a continuous slope:
    Newton does not cycle on points that touch)."""
    h = np.clip(g, -e, 0.0)
    deep = np.minimum(g + e, 0.0)
    energy = -k * h ** 3 / (6 * e) + k * (deep * (deep / 2 - e / 2))
    stress = -k * h ** 2 / (2 * e) + k * deep
    slope = np.where(g < -e, k, -k * h / e)
    return energy, stress, slope
