"""Units at the edges.  Inside the solver everything is scaled by R and C10 (DESIGN.md 3):

    P / (C10 R^2),  delta / R,  a / R,  U / (C10 R^3),  gamma / (C10 R).

Dimensional units used by the tool: lengths mm, forces N, C10 MPa (N/mm^2), gamma J/m^2
(= 1e-3 N/mm), energies mJ (= N mm).

The two scales have a supported range (R_MM_RANGE, C10_MPA_RANGE): a shell from 1 um to
10 m, a material from 1 Pa to 10 GPa.  Within it every force and energy the tool reports
is a finite double; `check_R` and `check_C10` are the rules, called by every front end with
its own field names.
"""
import math
from numbers import Real

from .geometry import shown
from shell_adhesion.errors import InputError

R_MM_RANGE = (1e-3, 1e4)        # outer radius R [mm]: 1 um to 10 m
C10_MPA_RANGE = (1e-6, 1e4)     # neo-Hookean C10 [MPa]: 1 Pa to 10 GPa


def gamma_hat(gamma_J_m2, C10_MPa, R_mm):
    """gamma / (C10 R), dimensionless."""
    return gamma_J_m2 * 1e-3 / (C10_MPa * R_mm)


def gamma_J_m2(g_hat, C10_MPa, R_mm):
    """gamma [J/m^2] of gamma / (C10 R) (the inverse of gamma_hat)."""
    return g_hat * C10_MPa * R_mm * 1e3


def force_N(P_hat, C10_MPa, R_mm):
    return P_hat * C10_MPa * R_mm ** 2


def length_mm(x_hat, R_mm):
    return x_hat * R_mm


def energy_mJ(U_hat, C10_MPa, R_mm):
    return U_hat * C10_MPa * R_mm ** 3


def _check_scale(value, span, name, unit, what):
    if not value > 0:
        raise InputError(f"{name}: {value:g} must be > 0")
    low, high = span
    if not low <= value <= high:
        raise InputError(f"{name}: {value:g} must be from {low:g} to {high:g} {unit} ({what})")


def check_R(R_mm: float, name: str = "R_mm"):
    """Raise InputError unless the outer radius R [mm] is within R_MM_RANGE."""
    _check_scale(R_mm, R_MM_RANGE, name, "mm", "1 um to 10 m")


def check_C10(C10_MPa: float, name: str = "C10_MPa"):
    """Raise InputError unless the neo-Hookean constant C10 [MPa] is within C10_MPA_RANGE."""
    _check_scale(C10_MPa, C10_MPA_RANGE, name, "MPa", "1 Pa to 10 GPa")


def check_finite(value, name: str, unit: str = "") -> float:
    """`value` as a float; InputError unless it is a finite real number (not a bool)."""
    suffix = f" ({unit})" if unit else ""
    if isinstance(value, bool) or not isinstance(value, Real):
        raise InputError(f"{name}: {shown(value)} must be a number{suffix}")
    if not math.isfinite(value):
        raise InputError(f"{name}: {shown(value)} must be a finite number{suffix}")
    return float(value)
