"""Units at the edges.  Inside the solver everything is scaled by R and C10 (DESIGN.md 3):

    P / (C10 R^2),  delta / R,  a / R,  U / (C10 R^3),  gamma / (C10 R).

Dimensional units used by the tool: lengths mm, forces N, C10 MPa (N/mm^2), gamma J/m^2
(= 1e-3 N/mm), energies mJ (= N mm).
"""


def gamma_hat(gamma_J_m2, C10_MPa, R_mm):
    """gamma / (C10 R), dimensionless."""
    return gamma_J_m2 * 1e-3 / (C10_MPa * R_mm)


def gamma_J_m2(gamma_hat_, C10_MPa, R_mm):
    return gamma_hat_ * C10_MPa * R_mm * 1e3


def force_N(P_hat, C10_MPa, R_mm):
    return P_hat * C10_MPa * R_mm ** 2


def length_mm(x_hat, R_mm):
    return x_hat * R_mm


def energy_mJ(U_hat, C10_MPa, R_mm):
    return U_hat * C10_MPa * R_mm ** 3
