"""Closed-form contact theories, dimensional (mm, N, MPa, J/m^2).

Incompressible solid: nu = 1/2, E = 6 C10, plane-strain modulus E* = E / (1 - nu^2) = 8 C10
against a rigid flat.  Signs: P > 0 compression, delta > 0 approach.

- Hertz: P = (4/3) E* sqrt(R) delta^(3/2), a = sqrt(R delta).
- JKR: P = 4 E* a^3 / (3 R) - sqrt(8 pi gamma E* a^3); fixed load pull-off
  P* = -(3/2) pi R gamma at a*^3 = 9 pi gamma R^2 / (8 E*); fixed grips
  P_dagger = -(5/6) pi R gamma; zero load a0^3 = 9 pi gamma R^2 / (2 E*) = 4 a*^3.
- Linear-shell law (the paper's eq. 3): P* = -eta [gamma^4 R^4 (1 - nu^2) / (E t^2)]^(1/3).
"""
import math

NU = 0.5


def e_star_MPa(C10_MPa):
    """Plane-strain modulus of the incompressible neo-Hookean solid, 8 C10."""
    return 6.0 * C10_MPa / (1.0 - NU ** 2)


def hertz_P_N(delta_mm, R_mm, C10_MPa):
    return 4.0 / 3.0 * e_star_MPa(C10_MPa) * math.sqrt(R_mm) * delta_mm ** 1.5


def hertz_a_mm(delta_mm, R_mm):
    return math.sqrt(R_mm * delta_mm)


def jkr_P_star_N(R_mm, gamma_J_m2):
    return -1.5 * math.pi * R_mm * gamma_J_m2 * 1e-3


def jkr_P_dagger_N(R_mm, gamma_J_m2):
    return -5.0 / 6.0 * math.pi * R_mm * gamma_J_m2 * 1e-3


def jkr_a_star_mm(R_mm, C10_MPa, gamma_J_m2):
    return (9.0 * math.pi * gamma_J_m2 * 1e-3 * R_mm ** 2 / (8.0 * e_star_MPa(C10_MPa))) ** (1 / 3)


def jkr_a0_mm(R_mm, C10_MPa, gamma_J_m2):
    """Contact radius at zero load: a0^3 = 9 pi gamma R^2 / (2 E*)."""
    return (4.5 * math.pi * gamma_J_m2 * 1e-3 * R_mm ** 2 / e_star_MPa(C10_MPa)) ** (1 / 3)


def shell_law_scale_N(R_mm, t_mm, C10_MPa, gamma_J_m2):
    """[gamma^4 R^4 (1 - nu^2) / (E t^2)]^(1/3) of eq. 3, in N."""
    g = gamma_J_m2 * 1e-3
    return (g ** 4 * R_mm ** 4 * (1 - NU ** 2) / (6.0 * C10_MPa * t_mm ** 2)) ** (1 / 3)


def eta_of(P_star_N, R_mm, t_mm, C10_MPa, gamma_J_m2):
    """eta of eq. 3 from a pull-off force (|P*| / scale)."""
    return abs(P_star_N) / shell_law_scale_N(R_mm, t_mm, C10_MPa, gamma_J_m2)
