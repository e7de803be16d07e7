"""Benchmark: the base shell's cohesive pull-off with frictionless and no_slip contact,
beside the energy method's, for several lambdas.

    python benchmarks/cohesive_interfaces.py [MESH] [LAMBDA ...] [--only no_slip]
        [--zone-elements N] [--no-error-bars]

Base shell R = h = 20 mm, t = 3 mm, C10 = 0.3 MPa, gamma = 30 J/m^2.  Prints, per
interface, the energy method's P* and, per lambda, the cohesive P*, delta*, a* with their
error bars (next coarser mesh; none with --no-error-bars), the states, Newton iterations
and wall time; --zone-elements: the elements across the cohesive zone (default 4).  The
cohesive law is normal only and the contact forms under adhesion (`beta=0,
history="adhesive"`, the no_slip choices before the fourth wave, whose numbers
docs/adhesion-range.md states): with no_slip the nodes below the plane keep their radius
(solver.arclength), the zone beyond them slides.  `--defaults`: the case's no_slip
defaults instead (mixed-mode beta 1, the loading history).
"""
import sys
import time

from shell_adhesion.study.case import solve_case
from shell_adhesion.study.cohesive_case import ZONE_ELEMENTS, solve_cohesive_case

SHELL = dict(R_mm=20.0, t_mm=3.0, h_mm=20.0, C10_MPa=0.3, gamma_J_m2=30.0)


def _option(argv, flag):
    """(the value after `flag` or None, argv without both)."""
    if flag not in argv:
        return None, argv
    k = argv.index(flag)
    return argv[k + 1], argv[:k] + argv[k + 2:]


def main(argv):
    only, argv = _option(argv, "--only")
    elements, argv = _option(argv, "--zone-elements")
    bars = "--no-error-bars" not in argv
    own = {} if "--defaults" in argv else dict(beta=0.0, history="adhesive")
    argv = [a for a in argv if a not in ("--no-error-bars", "--defaults")]
    mesh = argv[0] if argv else "default"
    lambdas = [float(v) for v in argv[1:]] or [1.0, 2.0]
    for interface in ("frictionless", "no_slip"):
        if only and interface != only:
            continue
        t0 = time.perf_counter()
        po = solve_case(**SHELL, interface=interface, mesh=mesh,
                        progress=False).to_dict()["pull_off"][0]["fixed_load"]
        print(f"{interface}, {mesh} mesh: energy method P* = {po['P_N']:.4f} +- "
              f"{po['P_N_error']:.2g} N, a* = {po['a_mm']:.3f} mm "
              f"({time.perf_counter() - t0:.1f} s)", flush=True)
        for lam in lambdas:
            t0 = time.perf_counter()
            r = solve_cohesive_case(**SHELL, tabor=lam, interface=interface, mesh=mesh,
                                    zone_elements=float(elements or ZONE_ELEMENTS),
                                    error_bars=bars,
                                    **(own if interface == "no_slip" else {}))
            out, prov = r.to_dict(), r.provenance
            if r.refused:
                print(f"  lambda {lam:g}: refused: {r.refused}", flush=True)
                continue
            p = out["pull_off"]
            print(f"  lambda {lam:g}: P* = {p['P_star_N']:.4f} +- {_bar(p['P_star_N_error'])} "
                  f"N, "
                  f"delta* = {p['delta_star_mm']:.4f} +- {_bar(p['delta_star_mm_error'])} mm, "
                  f"a* = {p['a_star_mm']:.3f} +- {_bar(p['a_star_mm_error'])} mm; "
                  f"{prov['dofs']} dofs, {prov['states']} states, "
                  f"{prov['newton_iterations']} Newton iterations, "
                  f"{time.perf_counter() - t0:.1f} s in all; notes: {list(r.notes)}", flush=True)


def _bar(value):
    return "(none)" if value is None else f"{value:.2g}"


if __name__ == "__main__":
    main(sys.argv[1:])
