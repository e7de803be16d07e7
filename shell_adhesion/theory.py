"""Closed-form contact theories, dimensional (mm, N, MPa, J/m^2).

The small-strain solid: shear modulus mu0 = 2 (C10 + C01) (Yeoh and Gent: 2 C10), bulk
modulus K = 2 / D1, Poisson ratio nu = (3 K - 2 mu0) / (2 (3 K + mu0)) (1/2 if incompressible),
E = 2 mu0 (1 + nu) (3 mu0 if incompressible), plane-strain modulus E* = E / (1 - nu^2)
against a rigid flat (8 C10 for the incompressible neo-Hookean solid).  Each function takes
C10 and an optional `material` (solver.material.Material, the ratios to C10; None: the
incompressible neo-Hookean solid).  Signs: P > 0 compression, delta > 0 approach.  Formulas
only: this module imports nothing, so that the analysis of a results cube uses them
without the solver.

- Hertz: P = (4/3) E* sqrt(R) delta^(3/2), a = sqrt(R delta).
- JKR: P = 4 E* a^3 / (3 R) - sqrt(8 pi gamma E* a^3); fixed load pull-off
  P* = -(3/2) pi R gamma at a*^3 = 9 pi gamma R^2 / (8 E*); fixed grips
  P_dagger = -(5/6) pi R gamma; zero load a0^3 = 9 pi gamma R^2 / (2 E*) = 4 a*^3.
- Linear-shell law (the paper's eq. 3): P* = -eta [gamma^4 R^4 (1 - nu^2) / (E t^2)]^(1/3).
"""
import math

NU = 0.5        # the incompressible solid's Poisson ratio
MU0_NEO_HOOKE = 2.0     # the neo-Hookean solid's small-strain shear modulus / C10


def shear_modulus_MPa(C10_MPa, material=None):
    """Small-strain shear modulus mu0 = 2 (C10 + C01)."""
    return (MU0_NEO_HOOKE if material is None else material.mu0) * C10_MPa


def poisson_ratio(material=None):
    """nu = (3 K - 2 mu0) / (2 (3 K + mu0)), K = 2 / D1; 1/2 for an incompressible solid."""
    if material is None or not material.compressible:
        return NU
    K, mu = material.bulk_modulus, material.mu0
    return (3.0 * K - 2.0 * mu) / (2.0 * (3.0 * K + mu))


def youngs_modulus_MPa(C10_MPa, material=None):
    """E = 2 mu0 (1 + nu) (= 3 mu0 = 6 C10 for the incompressible neo-Hookean solid)."""
    return 2.0 * shear_modulus_MPa(C10_MPa, material) * (1.0 + poisson_ratio(material))


def e_star_MPa(C10_MPa, material=None):
    """Plane-strain modulus E* = E / (1 - nu^2) (8 C10 for the incompressible neo-Hookean)."""
    return youngs_modulus_MPa(C10_MPa, material) / (1.0 - poisson_ratio(material) ** 2)


def hertz_P_N(delta_mm, R_mm, C10_MPa, material=None):
    return 4.0 / 3.0 * e_star_MPa(C10_MPa, material) * math.sqrt(R_mm) * delta_mm ** 1.5


def hertz_a_mm(delta_mm, R_mm):
    return math.sqrt(R_mm * delta_mm)


def jkr_P_star_N(R_mm, gamma_J_m2):
    return -1.5 * math.pi * R_mm * gamma_J_m2 * 1e-3


def jkr_P_dagger_N(R_mm, gamma_J_m2):
    return -5.0 / 6.0 * math.pi * R_mm * gamma_J_m2 * 1e-3


def jkr_a_star_mm(R_mm, C10_MPa, gamma_J_m2, material=None):
    return (9.0 * math.pi * gamma_J_m2 * 1e-3 * R_mm ** 2
            / (8.0 * e_star_MPa(C10_MPa, material))) ** (1 / 3)


def jkr_a0_mm(R_mm, C10_MPa, gamma_J_m2, material=None):
    """Contact radius at zero load: a0^3 = 9 pi gamma R^2 / (2 E*)."""
    return (4.5 * math.pi * gamma_J_m2 * 1e-3 * R_mm ** 2
            / e_star_MPa(C10_MPa, material)) ** (1 / 3)


def shell_law_scale_N(R_mm, t_mm, C10_MPa, gamma_J_m2, material=None):
    """[gamma^4 R^4 (1 - nu^2) / (E t^2)]^(1/3) of eq. 3, in N."""
    g = gamma_J_m2 * 1e-3
    nu = poisson_ratio(material)
    E = youngs_modulus_MPa(C10_MPa, material)
    return (g ** 4 * R_mm ** 4 * (1 - nu ** 2) / (E * t_mm ** 2)) ** (1 / 3)


def eta_of(P_star_N, R_mm, t_mm, C10_MPa, gamma_J_m2, material=None):
    """eta of eq. 3 from a pull-off force (abs(P*) / scale)."""
    return abs(P_star_N) / shell_law_scale_N(R_mm, t_mm, C10_MPa, gamma_J_m2, material)
