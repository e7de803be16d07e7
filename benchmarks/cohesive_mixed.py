"""Benchmark: the base shell's no_slip cohesive pull-off with the mixed-mode law (`beta`)
beside the normal-only law and the energy method's no_slip P*.

    python benchmarks/cohesive_mixed.py [MESH] [LAMBDA] [BETA ...] [--error-bars]
        [--history adhesive|loading]

Base shell R = h = 20 mm, t = 3 mm, C10 = 0.3 MPa, gamma = 30 J/m^2, no_slip, the
contact formed under adhesion (`--history adhesive`, the default here: the measurements of
docs/adhesion-range.md; `loading` is the case's default).  BETA the mixed-mode law's
delta_c / delta_t (0: the normal-only law, whose path it traces to 1e-12,
tests/test_cohesive_mixed_path.py).  Prints per law the wall time, dofs, states, Newton iterations, P* and
its distance from the energy method's no_slip P* (computed once, same mesh name), and for
a mixed-mode path the largest slip and shear traction in the cohesive zone at P*.  The
same path (mesh, approach, settings) for every beta, so the wall times compare the laws'
cost; then the cost of one linearisation (FE tangent plus interface) at the beta = 0
path's pull-off state, each law on the same state (interleaved, best of several), which
a loaded machine disturbs less.  Default: coarse, lambda 1, betas 0 1; no error bars
unless --error-bars.
"""
import sys
import time

import numpy as np

from shell_adhesion.solver.cohesive import Interface, mixed
from shell_adhesion.solver.forms import tangent
from shell_adhesion.study.case import solve_case
from shell_adhesion.study.cohesive_case import solve_cohesive_case

SHELL = dict(R_mm=20.0, t_mm=3.0, h_mm=20.0, C10_MPa=0.3, gamma_J_m2=30.0)


def main(argv):
    bars = "--error-bars" in argv
    argv = [a for a in argv if a != "--error-bars"]
    history = "adhesive"
    if "--history" in argv:
        k = argv.index("--history")
        history, argv = argv[k + 1], argv[:k] + argv[k + 2:]
    mesh = argv[0] if argv else "coarse"
    lam = float(argv[1]) if len(argv) > 1 else 1.0
    betas = [float(b) for b in argv[2:]] or [0.0, 1.0]
    normal = None
    t0 = time.perf_counter()
    energy = solve_case(**SHELL, interface="no_slip", mesh=mesh, error_bars=False)
    P_energy = energy.to_dict()["pull_off"][0]["fixed_load"]["P_N"]
    print(f"base shell, no_slip, {mesh} mesh: energy method P* = {P_energy:.4f} N "
          f"({time.perf_counter() - t0:.0f} s)", flush=True)
    for beta in betas:
        t0 = time.perf_counter()
        res = _solve(lam, mesh, beta, history, bars)
        wall = time.perf_counter() - t0
        out = res.to_dict()
        prov, law = out["provenance"], f"beta = {beta:g}"
        if res.refused:
            print(f"lambda {lam:g}, {law}: refused ({res.refused}); {wall:.1f} s", flush=True)
            continue
        po = out["pull_off"]
        if beta == 0.0:
            normal = res
        err = "" if po["P_star_N_error"] is None else f" +- {po['P_star_N_error']:.4f}"
        print(f"lambda {lam:g}, {law}: P* = {po['P_star_N']:.4f}{err} N "
              f"({100 * (po['P_star_N'] / P_energy - 1):+.1f} % from the energy method's), "
              f"a* = {po['a_star_mm']:.4f} mm; {prov['dofs']} dofs, {prov['states']} states, "
              f"{prov['newton_iterations']} Newton iterations, path {prov['wall_s']:.1f} s, "
              f"wall {wall:.1f} s", flush=True)
        if beta > 0.0:
            zone_mix(res)

    if normal is not None:
        linearisation_cost(normal)


def zone_mix(result):
    """Print the largest slip / delta_c and shear traction / sigma0 over the outer nodes
    in the cohesive zone (0 < g < reach) at the least-P state of a mixed-mode path."""
    path, law, beta = result.solve.path, result.input.law, result.input.beta
    k = path.turn + int(np.argmin(path.array("P")[path.turn:]))
    state = path.states[k]
    iface = Interface(_discretisation(result), law, beta)
    if iface.d.ndof != result.solve.ndof:
        print("  zone: the rebuilt mesh is not the path's; not measured")
        return
    outer = iface.d.capmesh.outer
    g = iface.d.capmesh.nodes[1, outer] + state.x[iface.d.uz(outer)]
    s = iface.radii(state.x) - state.anchors
    _, Tn, Tt, *_ = mixed(law, beta, g, s)
    zone = (g > 0) & (g < law.reach)
    print(f"  zone at P* ({zone.sum()} outer nodes): |s| <= "
          f"{np.abs(s[zone]).max() / law.delta_c:.3f} delta_c, |T_t| <= "
          f"{np.abs(Tt[zone]).max() / law.sigma0:.3f} sigma0, T_n up to "
          f"{Tn[zone].max() / law.sigma0:.3f} sigma0", flush=True)


def linearisation_cost(result, repeats=30, rounds=5):
    """Seconds per linearisation (FE tangent + interface forces and tangent) at the
    normal-only path's least-P state: normal-only against beta = 1 with the anchors a
    tenth of delta_c from the nodes (best of `rounds` of `repeats`, interleaved)."""
    path = result.solve.path
    iface = Interface(_discretisation(result), result.input.law)
    if iface.d.ndof != result.solve.ndof:
        print("one linearisation: the rebuilt mesh is not the path's; not measured")
        return
    k = path.turn + int(np.argmin(path.array("P")[path.turn:]))
    x = path.states[k].x
    mixed = Interface(iface.d, iface.law, 1.0)
    anchors = mixed.radii(x) + 0.1 * iface.law.delta_c
    best = {"normal-only": np.inf, "beta = 1": np.inf}
    for _ in range(rounds):
        for name, call in (("normal-only", lambda: iface.add(x, *tangent(iface.d, x))),
                           ("beta = 1", lambda: mixed.add(x, *tangent(iface.d, x), anchors))):
            t0 = time.perf_counter()
            for _ in range(repeats):
                call()
            best[name] = min(best[name], (time.perf_counter() - t0) / repeats)
    print(f"one linearisation at P*: normal-only {1e3 * best['normal-only']:.2f} ms, beta = 1 "
          f"{1e3 * best['beta = 1']:.2f} ms ({best['beta = 1'] / best['normal-only']:.2f} x)",
          flush=True)


def _discretisation(result):
    """The discretisation the result's path was traced on (rebuilt from its input and the
    mesh fit its provenance records)."""
    from shell_adhesion.solver.forms import discretise
    from shell_adhesion.solver.geometry import Cap
    from shell_adhesion.solver.mesh import cap_mesh
    from shell_adhesion.study.cohesive_case import fitted_spec
    c, prov = result.input.case, result.provenance
    cap = Cap(c.t_mm / c.R_mm, c.h_mm / c.R_mm)
    fit = dict(uniform=prov["even_arc"], refine=prov["zone_refinement"])
    return discretise(cap_mesh(cap, fitted_spec(c.mesh, fit)))


def _solve(lam, mesh, beta, history, bars):
    return solve_cohesive_case(**SHELL, tabor=lam, interface="no_slip", mesh=mesh,
                               beta=beta, history=history, error_bars=bars)


if __name__ == "__main__":
    main(sys.argv[1:])
