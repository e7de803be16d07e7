"""Benchmark: two methods, one answer (issue 39 item 3).  The cohesive (Maugis-Dugdale)
pull-off at several lambdas on ONE mesh family with the same number of elements across
the zone at every lambda, extrapolated to zero range, against the energy method's P* for
the same interface.

    python benchmarks/two_methods.py [--shells base,cap] [--interfaces frictionless,no_slip]
        [--lambdas 3,4,5] [--mesh coarse] [--zone-elements 8] [--beta 1] [--history loading]
        [--jsonl FILE]

Shells (R = 20 mm, C10 = 0.3 MPa, gamma = 30 J/m^2, gamma / (C10 R) = 0.005): `base`
t = 3 mm, h = 20 mm; `cap` the solid cap t = h = R (JKR: -1.5 pi gamma R = -2.8274 N).
no_slip runs the mixed-mode law `--beta B` (`solve_cohesive_case`'s; 0: the normal-only
law) with the contact history `--history` (loading, the case's default, or adhesive).  Lambdas above the shipped domain (3) are run by lifting its bound
here (a scratch run: the shipped commands refuse them).  No error bars on the cohesive
runs (their coarse companions would have half the elements across the zone).

The extrapolation: a sphere's Maugis-Dugdale excess of P* over JKR falls about as
lambda^-2 (the closed form: 1.1, 0.65, 0.42 % at lambda 3, 4, 5; the script prints its
lambda^2 x excess, which would be constant under the law), so P*(lambda) = P0 + C /
lambda^2, P0 from the two largest lambdas and by least squares over all.  Applied to the
closed form itself the same rule gives its error (printed: the sphere's P0 against JKR's
-1.5).  Each line is printed as it is computed; `--jsonl FILE` appends one JSON object per
run.  Times are wall seconds on whatever else the machine runs.
"""
import json
import sys
import time

import numpy as np

import shell_adhesion.study.cohesive_case as cc
from shell_adhesion.solver import maugis_dugdale as md
from shell_adhesion.study.case import solve_case

SHELLS = {"base": dict(R_mm=20.0, t_mm=3.0, h_mm=20.0),
          "cap": dict(R_mm=20.0, t_mm=20.0, h_mm=20.0)}
MATERIAL = dict(C10_MPa=0.3, gamma_J_m2=30.0)


def _option(argv, flag, default):
    if flag not in argv:
        return default, argv
    k = argv.index(flag)
    return argv[k + 1], argv[:k] + argv[k + 2:]


def main(argv):
    shells, argv = _option(argv, "--shells", "base,cap")
    interfaces, argv = _option(argv, "--interfaces", "frictionless,no_slip")
    lambdas, argv = _option(argv, "--lambdas", "3,4,5")
    mesh, argv = _option(argv, "--mesh", "coarse")
    elements, argv = _option(argv, "--zone-elements", "8")
    beta, argv = _option(argv, "--beta", "1")
    history, argv = _option(argv, "--history", "loading")
    jsonl, argv = _option(argv, "--jsonl", None)
    if argv:
        sys.exit(f"two_methods: unknown arguments {argv}")
    lambdas = [float(v) for v in lambdas.split(",")]
    beta = float(beta)
    cc.TABOR_RANGE = (cc.TABOR_RANGE[0], max(cc.TABOR_RANGE[1], *lambdas))    # scratch
    md_P = [md.pull_off(lam).P for lam in lambdas]     # units of pi gamma R
    print("Maugis-Dugdale sphere, excess over JKR [%] (x lambda^2): "
          + ", ".join(f"lambda {lam:g}: {100 * (p / -1.5 - 1):.3f} "
                      f"({100 * (p / -1.5 - 1) * lam ** 2:.2f})"
                      for lam, p in zip(lambdas, md_P)), flush=True)
    if len(lambdas) >= 2:
        two, lsq = md.zero_range(lambdas, md_P)
        print(f"  the lambda^-2 rule on the closed form: P0 = {two:.5f} (two largest), "
              f"{lsq:.5f} (least squares) against JKR -1.5: {100 * (two / -1.5 - 1):+.3f} %, "
              f"{100 * (lsq / -1.5 - 1):+.3f} %", flush=True)
    rows = []
    for shell in shells.split(","):
        for interface in interfaces.split(","):
            rows.append(_row(shell, interface, lambdas, mesh, float(elements), beta, jsonl,
                             history))
    print("\n| shell | interface | energy method P* [N] | "
          + " | ".join(f"cohesive lambda {lam:g}" for lam in lambdas)
          + " | zero range (two largest; least squares) | energy / zero range - 1 |")
    print("| --- " * (5 + len(lambdas)) + "|")
    for r in rows:
        print(r)


def _row(shell, interface, lambdas, mesh, elements, beta, jsonl, history):
    geo = SHELLS[shell]
    t0 = time.perf_counter()
    e = solve_case(**geo, **MATERIAL, interface=interface, mesh="default", progress=False)
    po = e.to_dict()["pull_off"][0]["fixed_load"]
    E, E_err = po["P_N"], po["P_N_error"]
    print(f"{shell}, {interface}: energy method (default mesh) P* = {E:.4f} +- {E_err:.2g} N "
          f"({time.perf_counter() - t0:.1f} s)", flush=True)
    b = beta if interface == "no_slip" else None
    own = dict(beta=beta, history=history) if interface == "no_slip" else {}
    P = []
    for lam in lambdas:
        t0 = time.perf_counter()
        r = cc.solve_cohesive_case(**geo, **MATERIAL, tabor=lam, interface=interface,
                                   mesh=mesh, zone_elements=elements, error_bars=False,
                                   **own)
        wall = time.perf_counter() - t0
        prov = r.provenance
        if r.refused:
            P.append(np.nan)
            print(f"  lambda {lam:g}: refused ({r.refused}); {wall:.0f} s", flush=True)
        else:
            P.append(r.to_dict()["pull_off"]["P_star_N"])
            print(f"  lambda {lam:g} ({mesh} mesh x {prov['zone_refinement']:.3g} at the "
                  f"contact, {prov['zone_elements']:g} elements across the zone"
                  + ("" if b is None else f", beta {b:g}")
                  + f"): P* = {P[-1]:.4f} N; {prov['dofs']} dofs, {prov['states']} states, "
                  f"{wall:.0f} s; notes: {list(r.notes)}", flush=True)
        if jsonl:
            with open(jsonl, "a") as f:
                f.write(json.dumps(dict(shell=shell, interface=interface, tabor=lam, mesh=mesh,
                                        zone_elements=elements, beta=b, P_star_N=P[-1],
                                        energy_P_N=E, energy_P_N_error=E_err,
                                        states=prov["states"], dofs=prov["dofs"], wall_s=wall,
                                        refused=r.refused or None)) + "\n")
    ok = [(lam, p) for lam, p in zip(lambdas, P) if np.isfinite(p)]
    if len(ok) >= 2:
        two, lsq = md.zero_range(*zip(*ok))
        zero = f"{two:.4f}; {lsq:.4f}"
        gap = f"{100 * (E / two - 1):+.2f} %; {100 * (E / lsq - 1):+.2f} %"
    else:
        zero = gap = "(too few lambdas answered)"
    cells = " | ".join("refused" if not np.isfinite(p) else f"{p:.4f}" for p in P)
    return (f"| {shell} | {interface}" + ("" if b is None else f" (beta {b:g})")
            + f" | {E:.4f} +- {E_err:.2g} | {cells} | {zero} | {gap} |")


if __name__ == "__main__":
    main(sys.argv[1:])
