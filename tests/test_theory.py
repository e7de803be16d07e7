"""Closed-form theories from the small-strain constants of each material (dimensional
inputs: mm, MPa, J/m^2, N)."""
import math

import pytest

from shell_adhesion import theory
from shell_adhesion.solver.material import Material

R, C10, GAMMA = 20.0, 0.3, 30.0


def test_neo_hooke_defaults_are_the_papers():
    assert theory.shear_modulus_MPa(C10) == pytest.approx(0.6)
    assert theory.youngs_modulus_MPa(C10) == pytest.approx(1.8)
    assert theory.e_star_MPa(C10) == pytest.approx(2.4)           # 8 C10
    assert theory.hertz_P_N(0.5, R, C10) == pytest.approx(4 / 3 * 2.4 * math.sqrt(20) * 0.5 ** 1.5)
    # eq. 3 scale: [gamma^4 R^4 (3/4) / (6 C10 t^2)]^(1/3) with gamma in N/mm
    assert theory.shell_law_scale_N(R, 3.0, C10, GAMMA) == pytest.approx(
        (0.03 ** 4 * 20 ** 4 * 0.75 / (1.8 * 9)) ** (1 / 3))


def test_mooney_rivlin_uses_mu0():
    m = Material.from_MPa("mooney_rivlin", C10_MPa=C10, C01_MPa=0.1)
    assert theory.shear_modulus_MPa(C10, m) == pytest.approx(0.8)   # 2 (C10 + C01)
    assert theory.e_star_MPa(C10, m) == pytest.approx(3.2)          # 8 (C10 + C01)
    ratio = theory.hertz_P_N(0.5, R, C10, m) / theory.hertz_P_N(0.5, R, C10)
    assert ratio == pytest.approx(4 / 3)
    # a* ~ E*^(-1/3); the JKR pull-off force does not depend on the modulus
    assert theory.jkr_a_star_mm(R, C10, GAMMA, m) == pytest.approx(
        theory.jkr_a_star_mm(R, C10, GAMMA) * (3 / 4) ** (1 / 3))
    assert theory.jkr_a0_mm(R, C10, GAMMA, m) == pytest.approx(
        4 ** (1 / 3) * theory.jkr_a_star_mm(R, C10, GAMMA, m))
    assert theory.eta_of(-1.0, R, 3.0, C10, GAMMA, m) == pytest.approx(
        theory.eta_of(-1.0, R, 3.0, C10, GAMMA) * (4 / 3) ** (1 / 3))
    # Yeoh and Gent: mu0 = 2 C10
    assert theory.e_star_MPa(C10, Material("yeoh", C20_over_C10=-0.02, C30_over_C10=0.004)) == pytest.approx(2.4)
    assert theory.e_star_MPa(C10, Material("gent", Jm=20.0)) == pytest.approx(2.4)


def test_compressible_poisson_ratio_from_D1():
    # K = 2 / D1 = 1 MPa and mu0 = 0.6 MPa: nu = (3 - 1.2) / (2 (3 + 0.6)) = 1/4
    m = Material.from_MPa("neo_hooke", C10_MPa=C10, D1_per_MPa=2.0)
    assert theory.poisson_ratio(m) == pytest.approx(0.25)
    assert theory.youngs_modulus_MPa(C10, m) == pytest.approx(9 * 1.0 * 0.6 / (3 * 1.0 + 0.6))
    assert theory.e_star_MPa(C10, m) == pytest.approx(1.5 / (1 - 0.0625))
    assert theory.shell_law_scale_N(R, 3.0, C10, GAMMA, m) == pytest.approx(
        (0.03 ** 4 * 20 ** 4 * (1 - 0.0625) / (1.5 * 9)) ** (1 / 3))
    # a rubber's D1 leaves nu within 2e-6 of 1/2
    rubber = Material.from_MPa("neo_hooke", C10_MPa=C10, D1_per_MPa=1e-5)
    assert 0.5 - 2e-6 < theory.poisson_ratio(rubber) < 0.5
