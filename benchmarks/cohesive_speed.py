"""Benchmark: the cohesive (Maugis-Dugdale) pull-off of the base shell against the energy
method's, one gamma, frictionless, no error bars, on the same mesh.

    python benchmarks/cohesive_speed.py [MESH] [LAMBDA] [error-bars]

Base shell R = 20 mm, t = 3 mm, h = 20 mm, C10 = 0.3 MPa, gamma = 30 J/m^2 (gamma / (C10 R)
= 0.005).  Prints each method's wall time, dofs, Newton iterations and split (energy
method: loading, relaxation paths, energy surface; cohesive: the traced states, Newton
and chord iterations, factorisations, CPU seconds), P*, and the ratio of the wall times;
`error-bars`: the cohesive case with its coarse companion, as the command runs it.
"""
import sys
import time

from shell_adhesion.study.case import solve_case
from shell_adhesion.study.cohesive_case import solve_cohesive_case

SHELL = dict(R_mm=20.0, t_mm=3.0, h_mm=20.0, C10_MPa=0.3, gamma_J_m2=30.0)


def main(mesh="default", lam="1", bars="no-error-bars"):
    bars = bars == "error-bars"
    t0 = time.perf_counter()
    energy = solve_case(**SHELL, interface="frictionless", mesh=mesh, error_bars=False,
                        progress=False)
    t_energy = time.perf_counter() - t0
    prov = energy.provenance
    po = energy.to_dict()["pull_off"][0]["fixed_load"]
    print(f"energy method, {mesh} mesh: {t_energy:.1f} s wall; {prov.get('dofs')} dofs; "
          f"P* = {po['P_N']:.4f} N")
    print(f"  split: {_split(prov)}")
    t0, c0 = time.perf_counter(), time.process_time()
    coh = solve_cohesive_case(**SHELL, tabor=float(lam), interface="frictionless", mesh=mesh,
                              error_bars=bars)
    t_coh, t_cpu = time.perf_counter() - t0, time.process_time() - c0
    cp = coh.provenance
    P = coh.to_dict()["pull_off"]["P_star_N"] if not coh.refused else float("nan")
    print(f"cohesive, lambda {lam}, {mesh} mesh: {t_coh:.1f} s wall; {cp['dofs']} dofs; "
          f"{cp['states']} states, {cp['newton_iterations']} Newton iterations "
          f"({cp['newton_iterations'] / cp['states']:.1f} per state), "
          f"{cp['chord_iterations']} chord iterations, {cp['factorisations']} "
          f"factorisations; {t_cpu:.1f} s of CPU; P* = {P:.4f} N"
          + (f"; refused: {coh.refused}" if coh.refused else ""))
    print(f"cost ratio cohesive / energy: {t_coh / t_energy:.2f}")


def _split(prov):
    keys = [k for k in prov if k.endswith("_s") or k.endswith("iterations")]
    return ", ".join(f"{k} {prov[k]:.3g}" if isinstance(prov[k], float) else f"{k} {prov[k]}"
                     for k in keys) or "(not recorded)"


if __name__ == "__main__":
    main(*sys.argv[1:])
