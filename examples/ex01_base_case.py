r"""The paper's base shell, one pull-off
====================================

The paper's base shell (R = h = 20 mm, t = 3 mm, C10 = 0.3 MPa) with gamma = 30 J/m^2.

Loads the shell without adhesion, relaxes every contact radius at fixed contact, and
applies Maugis' energy method: the fixed-load pull-off (P*, delta*, a*) is the minimum of
P along the equilibrium curve G = gamma, the fixed-grips one the minimum of delta.

    python examples/ex01_base_case.py [coarse|default|fine]
"""
import sys

from shell_adhesion.solver import solve_paths
from shell_adhesion.solver.scaling import force_N, gamma_hat, length_mm

R_MM, C10_MPA, GAMMA_J_M2 = 20.0, 0.3, 30.0


def pull_off(mesh="coarse"):
    paths, _, _ = solve_paths(t=3.0 / R_MM, h=1.0, mesh=mesh, delta_max=0.25, gamma_max=0.006)
    _, po = paths.pull_off(gamma_hat(GAMMA_J_M2, C10_MPA, R_MM))
    return po


if __name__ == "__main__":
    po = pull_off(sys.argv[1] if len(sys.argv) > 1 else "coarse")
    print(f"P* = {force_N(po.P_star, C10_MPA, R_MM):.3f} N, "
          f"delta* = {length_mm(po.delta_star, R_MM):.3f} mm, a* = {length_mm(po.a_star, R_MM):.3f} mm")
    print(f"fixed grips: P = {force_N(po.P_dagger, C10_MPA, R_MM):.3f} N, "
          f"delta = {length_mm(po.delta_dagger, R_MM):.3f} mm, a = {length_mm(po.a_dagger, R_MM):.3f} mm")
