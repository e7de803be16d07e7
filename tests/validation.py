"""The checks behind the README's validation numbers, as functions of a computed result
and a reference, so that a test can show each check fails on a perturbed input
(tests/test_checks_fail.py) as well as hold on the real one.

Every check names what it compared and by how much it missed; relative checks have an
absolute floor (round-off of the compared quantity), never a bare relative bound.
"""
import math

import numpy as np

from shell_adhesion import theory
from shell_adhesion.solver.material import NEO_HOOKE, Material
from shell_adhesion.solver.scaling import force_N, length_mm


def within(name: str, value: float, reference: float, rel: float, floor: float = 0.0):
    """Assert |value - reference| <= rel |reference| + floor, naming the claim."""
    miss = abs(value - reference)
    bound = rel * abs(reference) + floor
    assert math.isfinite(value) and miss <= bound, (
        f"{name}: {value:.6g} against {reference:.6g}: off by {miss:.3g} "
        f"({100 * miss / abs(reference):.3g} %), allowed {bound:.3g}")


def deviations_within(name: str, deviations: dict, stated: dict, factor: float = 2.0):
    """Each relative deviation at most `factor` times the README's stated one (and the
    same sign where the README states a sign): the claim 'within x %' held at 2x."""
    for key, dev in deviations.items():
        s = stated[key]
        assert math.isfinite(dev) and abs(dev) <= factor * abs(s), (
            f"{name} {key}: {100 * dev:+.3f} % from the reference, the README states "
            f"{100 * s:+.2f} % (held to {100 * factor * abs(s):.2f} %)")


def jkr_deviations(po, R_mm: float, C10_MPa: float, gamma_J_m2: float,
                   material: Material = NEO_HOOKE) -> dict:
    """Relative deviations of a pull-off (solver PullOff, dimensionless) from JKR's
    half-space sphere with E* of the material's small-strain limit."""
    return dict(
        P_star=force_N(po.P_star, C10_MPa, R_mm) / theory.jkr_P_star_N(R_mm, gamma_J_m2) - 1,
        a_star=length_mm(po.a_star, R_mm) / theory.jkr_a_star_mm(R_mm, C10_MPa, gamma_J_m2,
                                                                   material) - 1,
        P_dagger=force_N(po.P_dagger, C10_MPa, R_mm) / theory.jkr_P_dagger_N(R_mm, gamma_J_m2) - 1,
        a0=length_mm(po.a0, R_mm) / theory.jkr_a0_mm(R_mm, C10_MPa, gamma_J_m2, material) - 1)


def hertz_ratio(delta_mm, P_N, R_mm: float, C10_MPa: float, material: Material = NEO_HOOKE):
    """P / P_Hertz at each delta."""
    return np.array([P / theory.hertz_P_N(d, R_mm, C10_MPa, material)
                     for d, P in zip(delta_mm, P_N)])


def finite_body_within(ratio, a_over_R, rtol: float):
    """P/P_Hertz against the independent finite-body solution 1 + 0.7 a/R."""
    ref = 1 + 0.7 * np.asarray(a_over_R)
    miss = np.abs(np.asarray(ratio) / ref - 1)
    assert np.all(np.isfinite(miss)) and miss.max() <= rtol, (
        f"P/P_Hertz against 1 + 0.7 a/R: off by {100 * miss.max():.3g} % (allowed "
        f"{100 * rtol:.3g} %)")


def energy_balance_within(work, U, rel: float, floor: float):
    """eq. 1 (the work of P) against the strain-energy integral at every state."""
    work, U = np.asarray(work), np.asarray(U)
    excess = np.abs(work - U) - (rel * np.abs(U) + floor)
    assert np.all(np.isfinite(excess)) and excess.max() <= 0.0, (
        f"work of P against strain energy: worst relative miss "
        f"{np.max(np.abs(work - U) / np.maximum(np.abs(U), floor)):.3g}, allowed {rel:.3g} "
        f"(+ {floor:.3g} absolute)")


def loading_P(states, delta):
    """P at delta on a loading curve (the cubic Hermite of P and its one-sided slopes
    between the two states around delta)."""
    from scipy.interpolate import CubicHermiteSpline
    d = np.array([s.delta for s in states])
    i = int(np.searchsorted(d, delta)) - 1
    s0, s1 = states[i], states[i + 1]
    return float(CubicHermiteSpline([s0.delta, s1.delta], [s0.P, s1.P],
                                    [s0.dP_ddelta, s1.dP_ddelta_left])(delta))
