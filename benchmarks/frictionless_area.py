"""Benchmark: the frictionless energy method's contact area and adhesive edge force.

    python benchmarks/frictionless_area.py [T_OVER_R] [MESH] [GAMMA_HAT] [WIDTH ...]

While a frictionless shell relaxes at a fixed held set, its held nodes slide on the plane,
so the area it covers, pi r_k(delta)^2 (r_k: the deformed radius of the outermost held
node), is not pi a^2 of the loading state.  The held set's total potential is
Pi_k(delta) = U_E - gamma pi r_k(delta)^2 (DESIGN.md section 10), whose -gamma pi r_k^2
pulls the edge outward (solver.edge).  On the shell t/R, h = R at gamma / (C10 R) =
GAMMA_HAT (default 0.005, the base shell's 30 J/m^2), this prints P* four ways:

- `loading area`: G with pi a^2 of the loading state, P = P_rel (the energy method's
  until the fourth wave; no energy functional produces it);
- `covered, no edge force`: G with the covered areas at the same delta, P = P_rel;
- `first order`: the same G, P = dPi/ddelta = P_rel - gamma dA/ddelta (the edge force to
  first order in gamma on the paths relaxed without it);
- `second order` (the energy method's): also the state's response to the edge force,
  Pi = U_E - gamma A - gamma^2 c / 2 with the covered area's compliance c = dA/dgamma
  each path records (solver.edge), and A + gamma c the area covered;
- `edge force on one node`: every path relaxed with the edge force 2 pi gamma r on the
  edge node (solver.edge), P its rim force: exact for that model, whose line force is
  log-singular, so it depends on the mesh (on the fine mesh it inverts the edge element).

Each WIDTH (arc / R, or `lambda3`: the cohesive zone Maugis expects at lambda 3) adds the
edge force spread evenly over that width inside the edge (solver.edge; every variant then
relaxes the corner family of starts).  Dimensionless P* / (C10 R^2), and in N for the base shell (R = 20 mm, C10 = 0.3 MPa), with
the dofs, the paths and the wall time of each set of relaxations.  The cohesive
(Maugis-Dugdale) pull-off at growing lambda is the referee (docs/adhesion-range.md).
"""
import sys
import time

import numpy as np

from shell_adhesion import energy
from shell_adhesion.errors import ConvergenceError
from shell_adhesion.solver.case import Relaxation, relax_from, relaxation_starts
from shell_adhesion.solver.forms import discretise
from shell_adhesion.solver.geometry import Cap
from shell_adhesion.solver.mesh import cap_mesh, mesh_spec
from shell_adhesion.solver.path import load
from shell_adhesion.solver.request import a_star_estimate, even_arc

N_PER_UNIT = 0.3 * 20.0 ** 2          # C10 R^2 of the base shell, N


class _NoEdgeForce(energy.EnergySurface):
    """The surface with P = P_rel: the covered areas' G without the edge force."""

    def P_pair(self, k, delta, gamma=0.0):
        return super().P_pair(k, delta, 0.0)


def relaxations(d, loading, gamma_hat, gamma_edge=0.0, width=0.0, family=None):
    """The usable relaxation paths of every loaded state (upright part), and the wall time."""
    t0 = time.perf_counter()
    out = []
    for start in relaxation_starts(loading, d.capmesh, family):
        path = relax_from(d, "frictionless", start, gamma_max=gamma_hat, reach=1.5,
                          gamma_edge=gamma_edge, edge_width=width)
        r = Relaxation.of(path, gamma_edge=gamma_edge)
        if r.usable:
            out.append(r.upright())
    return out, time.perf_counter() - t0


def pull_offs(t_over_R=0.15, mesh="default", gamma_hat=0.005, one_node=True, widths=(),
              family=None, h_over_R=1.0):
    """{variant: PullOff (dimensionless)} of the shell t/R, h/R (default 1), frictionless, and
    {"dofs", "paths", "seconds", "slide"}: the held edge's slide / R over each path of the
    paths relaxed without the edge force (its end minus its start).  `widths` (arc / R):
    also the edge force spread over each width ("spread over W"; needs `family` "corner")."""
    cap = Cap(float(t_over_R), float(h_over_R))
    a_need = a_star_estimate(cap, gamma_hat)
    d = discretise(cap_mesh(cap, mesh_spec(mesh, even_arc(cap, a_need))))
    loading = load(d, "frictionless", 0.3, a_stop=1.6 * a_need, stop_at_limit=True)
    paths, seconds = relaxations(d, loading, gamma_hat, family=family)
    covered = energy.energy_surface([r.energy_path()[:8] for r in paths])
    loaded = energy.energy_surface([r.energy_path()[:5] for r in paths])
    fields = {f: getattr(covered, f) for f in covered.__dataclass_fields__}
    out = {"loading area": loaded,
           "covered, no edge force": _NoEdgeForce(**fields),
           "first order": covered,
           "second order": energy.energy_surface([r.energy_path() for r in paths])}
    out = {k: energy.pull_off(energy.equilibrium(s, gamma_hat)) for k, s in out.items()}
    info = {"dofs": d.ndof, "paths": len(paths), "seconds": {"gamma-free paths": seconds},
            "slide": np.array([r.a_edge[-1] - r.a_edge[0] for r in paths])}
    for width in widths:
        name = f"spread over {width:.5g}"
        try:
            edged, seconds = relaxations(d, loading, gamma_hat, gamma_hat, width, family)
        except ConvergenceError as e:
            info[name + " fails"] = str(e)
            continue
        surface = energy.energy_surface([r.energy_path() for r in edged])
        out[name] = energy.pull_off(energy.equilibrium(surface, gamma_hat))
        info["seconds"][name] = seconds
    if one_node:
        try:
            edged, seconds = relaxations(d, loading, gamma_hat, gamma_hat, family=family)
        except ConvergenceError as e:   # the line force inverts the edge element
            info["one node fails"] = str(e)
            return out, info
        surface = energy.energy_surface([r.energy_path() for r in edged])
        out["edge force on one node"] = energy.pull_off(energy.equilibrium(surface, gamma_hat))
        info["seconds"]["edge-force paths"] = seconds
    return out, info


def main(t_over_R="0.15", mesh="default", gamma_hat="0.005", *widths):
    t0 = time.perf_counter()
    widths = [_width(w, float(gamma_hat)) for w in widths]
    got, info = pull_offs(float(t_over_R), mesh, float(gamma_hat), widths=widths,
                          family="corner" if widths else None)
    print(f"t/R {float(t_over_R):g}, h/R 1, gamma/(C10 R) {float(gamma_hat):g}, {mesh} mesh, "
          f"{info['dofs']} dofs, {info['paths']} relaxation paths, "
          f"{time.perf_counter() - t0:.1f} s in all; relaxations: "
          + ", ".join(f"{k} {v:.1f} s" for k, v in info["seconds"].items()))
    for name, po in got.items():
        print(f"  {name:24s} P*/(C10 R^2) {po.P_star:.6f} ({po.P_star * N_PER_UNIT:.4f} N on the "
              f"base shell), a*/R {po.a_star:.5f}, delta*/R {po.delta_star:.5f}")
    for name, why in info.items():
        if name.endswith(" fails"):
            print(f"  {name[:-6]:24s} fails: {why}")
    slide = info["slide"]
    print(f"  the held edge slides by {np.median(slide):.3g} R over a path (median; from "
          f"{slide.min():.3g} to {slide.max():.3g} R)")


def _width(text, gamma_hat):
    """A width of arc / R, or "lambdaL": the cohesive zone Maugis expects at lambda L."""
    if text.startswith("lambda"):
        from shell_adhesion.study.cohesive_case import zone_estimate
        return zone_estimate(gamma_hat, float(text[6:]))
    return float(text)


if __name__ == "__main__":
    main(*sys.argv[1:])
