"""Dimensional report of one shell (the `shell-adhesion case` command's content).

Takes a dimensionless PathSet and returns plain dicts in mm, N, mJ, MPa, J/m^2.
"""
import numpy as np

from shell_adhesion.solver import theory
from shell_adhesion.solver.case import PathSet
from shell_adhesion.solver.scaling import energy_mJ, force_N, gamma_hat, length_mm


def _num(v, digits=10):
    """A JSON-safe number: None where the value is undefined (NaN)."""
    v = float(v)
    return None if not np.isfinite(v) else float(f"{v:.{digits}g}")


def _list(x, digits=10):
    return [_num(v, digits) for v in np.asarray(x, dtype=float)]


def loading_dict(ps: PathSet, R_mm, C10_MPa):
    return {"delta_mm": _list(length_mm(ps.loading_delta, R_mm)),
            "P_N": _list(force_N(ps.loading_P, C10_MPa, R_mm)),
            "a_mm": _list(length_mm(ps.loading_a, R_mm)),
            "U_E_mJ": _list(energy_mJ(ps.loading_U, C10_MPa, R_mm))}


def relaxation_list(ps: PathSet, R_mm, C10_MPa):
    out = []
    for r in ps.relaxations:
        out.append({"a_mm": float(length_mm(r.a, R_mm)),
                    "delta1_mm": float(length_mm(r.delta[0], R_mm)),
                    "P1_N": float(force_N(r.P[0], C10_MPa, R_mm)),
                    "delta_mm": _list(length_mm(r.delta, R_mm)),
                    "P_N": _list(force_N(r.P, C10_MPa, R_mm)),
                    "U_E_mJ": _list(energy_mJ(r.U, C10_MPa, R_mm)),
                    "ended_by": r.ended_by,
                    "centre_lifts": bool(r.centre_lifts),
                    "penetration": bool(r.penetration)})
    return out


def adhesion_dicts(ps: PathSet, R_mm, t_mm, C10_MPa, gammas_J_m2):
    """Equilibrium curves and pull-off points, one entry per gamma."""
    surface = ps.surface()
    equilibria, pull_offs = [], []
    for g in gammas_J_m2:
        eq, po = ps.pull_off(gamma_hat(g, C10_MPa, R_mm), surface)
        L = lambda v: _num(length_mm(v, R_mm))
        F = lambda v: _num(force_N(v, C10_MPa, R_mm))
        equilibria.append({"gamma_J_m2": g, "a_mm": _list(length_mm(eq.a, R_mm)),
                           "P_N": _list(force_N(eq.P, C10_MPa, R_mm)),
                           "delta_mm": _list(length_mm(eq.delta, R_mm)),
                           "stable_fixed_load": [bool(v) for v in eq.stable_fixed_load],
                           "stable_fixed_grips": [bool(v) for v in eq.stable_fixed_grips]})
        P_star = F(po.P_star)
        pull_offs.append({"gamma_J_m2": g,
                          "fixed_load": {"P_N": P_star, "delta_mm": L(po.delta_star),
                                         "a_mm": L(po.a_star)},
                          "fixed_grips": {"P_N": F(po.P_dagger), "delta_mm": L(po.delta_dagger),
                                          "a_mm": L(po.a_dagger)},
                          "a0_mm": L(po.a0),
                          "eta": theory.eta_of(P_star, R_mm, t_mm, C10_MPa, g),
                          "jkr_P_star_N": theory.jkr_P_star_N(R_mm, g)})
    return equilibria, pull_offs
