"""Benchmark: which contact area the frictionless energy method should count.

    python benchmarks/frictionless_area.py [T_OVER_R] [MESH]

While a frictionless shell relaxes, its held nodes slide outward on the plane, so the
area it covers grows beyond pi a^2 of the loading state.  The energy method (shell_adhesion.
energy) takes G = dU_E/dA with A the loading state's area; this script takes the same
relaxation paths (h = R, gamma / (C10 R) = 0.005, frictionless) and prints P* both ways:
with A = pi a^2 of the loading state, and with the area each path actually covers at each
delta (the deformed radius of its outermost held node, linear in delta between states).
Dimensionless P* / (C10 R^2) and, for the base shell (R = 20 mm, C10 = 0.3 MPa), in N.
The cohesive (Maugis-Dugdale) pull-off at growing lambda is the referee
(docs/adhesion-range.md).
"""
import dataclasses
import sys
import time

import numpy as np

from shell_adhesion import energy
from shell_adhesion.solver.case import relax_from, relaxation_starts
from shell_adhesion.solver.forms import discretise
from shell_adhesion.solver.geometry import Cap
from shell_adhesion.solver.mesh import cap_mesh, mesh_spec
from shell_adhesion.solver.path import load
from shell_adhesion.solver.request import a_star_estimate, even_arc

GAMMA_HAT = 0.005
N_PER_UNIT = 0.3 * 20.0 ** 2          # C10 R^2 of the base shell, N


def pull_offs(t_over_R=0.15, mesh="default"):
    """(loading-area PullOff, covered-area PullOff, held-edge slides / R, dofs, paths) of
    the shell t/R, h = R at GAMMA_HAT, frictionless (dimensionless, shell_adhesion.energy)."""
    cap = Cap(float(t_over_R), 1.0)
    a_need = a_star_estimate(cap, GAMMA_HAT)
    d = discretise(cap_mesh(cap, mesh_spec(mesh, even_arc(cap, a_need))))
    loading = load(d, "frictionless", 0.3, a_stop=1.6 * a_need, stop_at_limit=True)
    paths = []
    for start in relaxation_starts(loading, d.capmesh):
        rp = relax_from(d, "frictionless", start, gamma_max=GAMMA_HAT, reach=1.5)
        if not (rp.penetration or rp.centre_lifts):
            paths.append((start.a, rp.array("delta"), rp.array("P"), rp.array("U"),
                          rp.array("dP_ddelta"), rp.array("a")))
    surface = energy.energy_surface([p[:5] for p in paths])
    loading_area = energy.pull_off(energy.equilibrium(surface, GAMMA_HAT))
    covered = dataclasses.replace(surface, G=_covered_G(surface, paths))
    covered_area = energy.pull_off(energy.equilibrium(covered, GAMMA_HAT))
    slide = np.array([p[5][-1] - p[0] for p in paths])
    return loading_area, covered_area, slide, d.ndof, len(paths)


def main(t_over_R="0.15", mesh="default"):
    t0 = time.perf_counter()
    loading_area, covered_area, slide, ndof, n = pull_offs(float(t_over_R), mesh)
    print(f"t/R {float(t_over_R):g}, {mesh} mesh, {ndof} dofs, {n} relaxation "
          f"paths, {time.perf_counter() - t0:.1f} s")
    for name, po in (("loading area", loading_area), ("covered area", covered_area)):
        print(f"  {name}: P*/(C10 R^2) {po.P_star:.6f} ({po.P_star * N_PER_UNIT:.4f} N on the "
              f"base shell), delta*/R {po.delta_star:.5f}")
    print(f"  ratio covered / loading: {covered_area.P_star / loading_area.P_star:.4f}; the held "
          f"edge slides by {np.median(slide):.3g} R (median over the paths, max {slide.max():.3g})")


def _covered_G(surface, paths):
    """dU_E/dA between neighbouring paths at each delta of the surface's grid, A the area
    each path covers there (NaN where a pair does not overlap)."""
    grid = surface.grid
    U = np.full((len(paths), len(grid)), np.nan)
    A = np.full_like(U, np.nan)
    for k, (_, delta, _, _, _, a) in enumerate(paths):
        inside = (grid >= delta.min()) & (grid <= delta[0])
        order = np.argsort(delta)
        A[k, inside] = np.pi * np.interp(grid[inside], delta[order], a[order]) ** 2
        U[k, inside] = surface.splines[k](grid[inside])
    return (U[1:] - U[:-1]) / (A[1:] - A[:-1])


if __name__ == "__main__":
    main(*sys.argv[1:])
