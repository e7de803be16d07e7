r"""Design on the pull-off map
==========================

Design a suction-cup-like shell: the (t, h) that sticks best, from the pull-off map.

A silicone of C10 = 0.3 MPa sticking with gamma = 30 J/m^2, on shells of radius of
curvature R = 20 mm, thickness 1 to 6 mm and depth 10 to 20 mm.  `shell_adhesion.design`
searches the shipped pull-off map (a dense grid of the interpolant, then Nelder-Mead) for
the largest ``|P*|``, then ``|P*|`` per preload and per unit volume of rubber, says whether
each optimum lies on a bound, and confirms the first with one FE case on the map's mesh.

    python examples/ex05_design.py [MAP]     (MAP: coarse, the shipped map, or a map file)

The map is dimensionless (P / (C10 R^2), lengths / R, gamma / (C10 R)): the same search
serves any rubber and size inside it (t/R 0.05-0.4, h/R 0.5-1, gamma/(C10 R) up to 0.03).
"""
import sys

import shell_adhesion as sa

C10_MPA, GAMMA_J_M2, R_MM = 0.3, 30.0, 20.0
T_BOUNDS_MM, H_BOUNDS_MM = (1.0, 6.0), (10.0, 20.0)


def designs(map_name="coarse", confirm=True):
    """objective -> sa.design result (only the first objective is confirmed by FE)."""
    out = {}
    for i, objective in enumerate(("pull_off", "per_preload", "per_volume")):
        out[objective] = sa.design(C10_MPA, GAMMA_J_M2, objective, R_mm=R_MM,
                                   t_mm=T_BOUNDS_MM, h_mm=H_BOUNDS_MM, map=map_name,
                                   confirm=confirm and i == 0)
    return out


if __name__ == "__main__":
    for objective, result in designs(sys.argv[1] if len(sys.argv) > 1 else "coarse").items():
        print(result.to_text(), end="\n\n")
